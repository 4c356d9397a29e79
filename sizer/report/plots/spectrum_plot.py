"""Amplitude spectra of laws over the (normalized) frequency, as in the book's Figs.
7.19-7.28; the harmonics of a repeated move as stems (Figs. 7.29-7.31), with the
continuous spectrum they sample drawn faintly where it is given.

matplotlib is imported inside the drawing (sizer.report.plots.figure_files.new_figure);
the numbers come from sizer.vibration through a SpectrumDocument.
"""

from __future__ import annotations

import textwrap
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from sizer.report.plots.figure_files import new_figure
from sizer.report.plots.speed_torque import CURVE_COLORS

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from sizer.report.spectrum_table import SpectrumDocument

DEFAULT_SIZE = (8.0, 5.0)
TITLE_WIDTH = 90
MARKERS = ("o", "s", "^", "D", "v", "P", "X", "*")

GID_SPECTRUM = "spectrum"
GID_HARMONIC = "harmonic"
GID_ENVELOPE = "envelope"


def spectrum_figure(document: SpectrumDocument, *,
                    envelopes: Sequence[tuple[np.ndarray, np.ndarray]] = (),
                    size: tuple[float, float] | None = None, dpi: float = 100.0) -> Figure:
    """The document's spectra as curves, or its harmonics as stems (one marker per law);
    ``envelopes`` (x, y), one per law, drawn as thin lines."""
    figure = new_figure(size or DEFAULT_SIZE, dpi)
    ax = figure.subplots()
    unit = f" [{document.value_unit}]" if document.value_unit else ""
    count = len(document.series)
    x = np.asarray(document.frequency, dtype=float)
    step = float(np.min(np.diff(x))) if x.size > 1 else 1.0
    for index, series in enumerate(document.series):
        color = CURVE_COLORS[index % len(CURVE_COLORS)]
        if document.k is None:
            ax.plot(x, series.values, color=color, lw=1.3, label=series.label,
                    gid=GID_SPECTRUM)
            continue
        # at the harmonics' own frequencies (on their envelopes): later laws drawn
        # thinner, each with its own marker, so coinciding stems stay visible
        width = 1.0 + 1.6 * (count - 1 - index) / max(count - 1, 1)
        stems = ax.vlines(x, 0.0, series.values, color=color, lw=width,
                          label=series.label)
        stems.set_gid(GID_HARMONIC)
        ax.plot(x, series.values, MARKERS[index % len(MARKERS)], color=color, ms=4.0)
        if index < len(envelopes):
            ex, ey = envelopes[index]
            ax.plot(ex, ey, color=color, lw=0.7, alpha=0.45, gid=GID_ENVELOPE)
    ax.axhline(0.0, color="0.5", lw=0.6)
    ax.grid(True, color="0.85", lw=0.5)
    right = float(x.max()) if x.size else 1.0
    ax.set_xlim(0.0, right + (0.5 * step if document.k is not None else 0.0))
    ax.set_ylim(bottom=0.0)
    ax.set_xlabel(document.frequency_name)
    ax.set_ylabel(f"{document.value_name}{unit}")
    ax.legend(loc="upper right", fontsize="x-small")
    ax.set_title("\n".join(textwrap.wrap(document.title, TITLE_WIDTH)), fontsize="small")
    return figure
