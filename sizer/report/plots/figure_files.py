"""A new figure on the Agg canvas, and saving it as PNG or SVG (chosen by the file suffix).

Files are written atomically (a temporary file beside the target, then renamed), and the
bytes are deterministic: no date in the SVG metadata and a fixed hash salt for its ids.
"""

from __future__ import annotations

import io
from pathlib import Path
from typing import TYPE_CHECKING

from sizer.errors import UserError
from sizer.report.output import write_bytes_atomically

if TYPE_CHECKING:
    from matplotlib.figure import Figure

FIGURE_FORMATS = ("png", "svg")
"""File formats by suffix."""

MAX_PIXELS = 100_000_000
"""Largest figure, in pixels (width x height x dpi^2), to keep memory bounded."""

SVG_HASH_SALT = "sizer"


def figure_format(path: Path | str, field: str = "--output") -> str:
    """'png' or 'svg' from the file's suffix; any other suffix is a UserError."""
    suffix = Path(path).suffix.lower().lstrip(".")
    if suffix not in FIGURE_FORMATS:
        shown = f"'.{suffix}'" if suffix else "no suffix"
        raise UserError(f"cannot tell the figure format from {shown}: name the file "
                        f"*.png or *.svg", file=str(path), field=field)
    return suffix


def check_figure_size(size: tuple[float, float], dpi: float) -> None:
    """Positive width, height and dpi, and not an absurd number of pixels."""
    width, height = size
    if not (width > 0 and height > 0):
        raise UserError(f"width and height must be positive, got {width:g}x{height:g}",
                        field="--size")
    if not dpi > 0:
        raise UserError(f"must be positive, got {dpi:g}", field="--dpi")
    if width * height * dpi * dpi > MAX_PIXELS:
        raise UserError(f"{width:g}x{height:g} in at {dpi:g} dpi is more than "
                        f"{MAX_PIXELS:,} pixels", field="--size")


def new_figure(size: tuple[float, float], dpi: float = 100.0) -> Figure:
    """A blank figure of ``size`` inches on the non-interactive Agg canvas (no pyplot)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    check_figure_size(size, dpi)
    figure = Figure(figsize=size, dpi=dpi, layout="constrained")
    FigureCanvasAgg(figure)
    return figure


def figure_bytes(figure: Figure, fmt: str, dpi: float | None = None) -> bytes:
    """The figure encoded as PNG or SVG, at its own size (no tight bounding box)."""
    import matplotlib

    if fmt not in FIGURE_FORMATS:
        raise ValueError(f"unknown figure format {fmt!r}")
    buffer = io.BytesIO()
    metadata = {"Date": None} if fmt == "svg" else {}
    with matplotlib.rc_context({"svg.hashsalt": SVG_HASH_SALT}):
        figure.savefig(buffer, format=fmt, dpi=dpi or figure.dpi, metadata=metadata)
    return buffer.getvalue()


def save_figure(figure: Figure, path: Path | str, dpi: float | None = None) -> Path:
    """Write the figure to ``path`` (PNG or SVG by suffix), atomically; returns the path."""
    path = Path(path)
    data = figure_bytes(figure, figure_format(path), dpi)
    write_bytes_atomically(path, data)  # a UserError naming the file when it cannot
    return path


