"""The residual vibration of each law against the duration (``sizer vibration --plot``):
the figure a designer reads to pick T (book sec. 7.2), the limit as a line."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from sizer.laws.data_spec import law_label
from sizer.report.plots.figure_files import new_figure
from sizer.report.vibration_table import display_unit

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from sizer.sizing.vibration_check import VibrationSweep


def vibration_figure(sweep: VibrationSweep, linear: bool, cycle: bool,
                     size: tuple[float, float] = (8.0, 4.5)) -> Figure:
    """Residual amplitude (um or arcsec, log scale) against T (ms) or the cycle's scale."""
    unit, factor = display_unit(linear)
    figure = new_figure(size)
    ax = figure.add_subplot()
    x = sweep.scales if cycle else sweep.scales * 1000.0
    floor = np.inf
    for law, values in zip(sweep.laws, sweep.residual, strict=True):
        y = values * factor
        positive = y[y > 0]
        floor = min(floor, float(positive.min()) if positive.size else np.inf)
        ax.plot(x, np.maximum(y, 1e-300), label=law_label(law.spec), linewidth=1.2)
    if sweep.limit is not None:
        ax.axhline(sweep.limit * factor, color="black", linestyle="--", linewidth=1.0,
                   label="limit")
    ax.set_yscale("log")
    if np.isfinite(floor):
        top = max(float(np.max(v)) for v in sweep.residual) * factor
        ax.set_ylim(max(floor, top * 1e-8), top * 2.0)
    ax.set_xlabel("scale of the free durations" if cycle else "T [ms]")
    ax.set_ylabel(f"residual vibration [{unit}]")
    ax.grid(True, which="both", linewidth=0.3)
    ax.legend(fontsize="small")
    return figure
