"""Figures of results: speed-torque diagrams (book Figs. 6.1-6.3, 6.7) and law profiles
(Figs. 6.4-6.6), motor torque and speed over a machine cycle with its segments marked,
drawn with matplotlib.

matplotlib is imported lazily, inside the functions that draw, so importing this package
(or running ``sizer size``) does not load it. Each figure is built by a function that returns
a ``matplotlib.figure.Figure`` (drawn on the non-interactive Agg canvas, no pyplot state);
``save_figure`` writes it as PNG or SVG. The numbers come from the core (``task_curve``,
the laws); nothing here computes physics, it only converts units for display.
"""

from sizer.report.plots.figure_files import (
    FIGURE_FORMATS,
    figure_format,
    new_figure,
    save_figure,
)
from sizer.report.plots.law_profiles import law_profiles_figure
from sizer.report.plots.linkage_curves import linkage_figure
from sizer.report.plots.speed_torque import speed_torque_figure
from sizer.report.plots.task_curves import curve_for, transmission_for
from sizer.report.plots.time_curves import time_figure

__all__ = [
    "FIGURE_FORMATS",
    "curve_for",
    "figure_format",
    "law_profiles_figure",
    "linkage_figure",
    "new_figure",
    "save_figure",
    "speed_torque_figure",
    "time_figure",
    "transmission_for",
]
