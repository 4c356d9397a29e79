"""The residual vibration of each law against the duration (``sizer vibration --plot``):
the figure a designer reads to pick T (book sec. 7.2), the limit as a line.

The y-range (log scale) always holds the limit, with a decade below it: the region where
a duration passes (residual under the limit) is shaded, so the durations to pick are
visible even where every sampled residual is above the limit.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from sizer.laws.data_spec import law_label
from sizer.report.numbers import short
from sizer.report.plots.figure_files import new_figure
from sizer.report.vibration_table import display_unit

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from sizer.sizing.vibration_check import VibrationSweep

GID_LIMIT = "vibration-limit"
GID_PASSING = "vibration-passing"
GID_RESIDUAL = "vibration-residual"
"""Artist ids (``get_gid()``), so a reader of the figure (a test) finds what is what."""

DECADES_BELOW_LIMIT = 1.0
"""The y-range reaches at least this many decades below the limit (the passing region)."""
DYNAMIC_RANGE = 1e-8
"""Without a limit, the y-range spans at most this ratio below the largest residual."""


def y_range(residual: np.ndarray, limit: float | None) -> tuple[float, float] | None:
    """(bottom, top) of the log y-axis: the residuals, and the limit with a decade of the
    passing region below it; None when there is nothing positive to show."""
    values = np.asarray(residual, dtype=float)
    positive = values[np.isfinite(values) & (values > 0)]
    if positive.size == 0 and limit is None:
        return None
    top = float(positive.max()) if positive.size else 0.0
    bottom = float(positive.min()) if positive.size else np.inf
    bottom = max(bottom, top * DYNAMIC_RANGE)
    if limit is not None and limit > 0:
        top = max(top, limit)
        bottom = min(bottom, limit * 10.0 ** -DECADES_BELOW_LIMIT)
    return bottom, top * 2.0


def vibration_figure(sweep: VibrationSweep, linear: bool, cycle: bool,
                     size: tuple[float, float] = (8.0, 4.5)) -> Figure:
    """Residual amplitude (um or arcsec, log scale) against T (ms) or the cycle's scale,
    the limit as a dashed line over the shaded passing region."""
    unit, factor = display_unit(linear)
    figure = new_figure(size)
    ax = figure.add_subplot()
    x = sweep.scales if cycle else sweep.scales * 1000.0
    residual = np.asarray(sweep.residual, dtype=float) * factor
    limit = None if sweep.limit is None else float(sweep.limit) * factor
    span = y_range(residual, limit)
    floor = span[0] * 0.5 if span is not None else 1e-300
    for law, y in zip(sweep.laws, residual, strict=True):
        ax.plot(x, np.maximum(y, floor), label=law_label(law.spec), linewidth=1.2,
                gid=GID_RESIDUAL)
    ax.set_yscale("log")
    if span is not None:
        ax.set_ylim(*span)
    if limit is not None and span is not None:
        ax.axhspan(span[0], limit, color="tab:green", alpha=0.10, linewidth=0,
                   gid=GID_PASSING, label="passing (below the limit)", zorder=0)
        ax.axhline(limit, color="black", linestyle="--", linewidth=1.2, gid=GID_LIMIT,
                   label=f"limit {short(limit)} {unit}", zorder=3)
    ax.set_xlim(float(x[0]), float(x[-1]))
    ax.set_xlabel("scale of the free durations" if cycle else "T [ms]")
    ax.set_ylabel(f"residual vibration [{unit}]")
    ax.grid(True, which="both", linewidth=0.3)
    ax.legend(fontsize="small")
    return figure
