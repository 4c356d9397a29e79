"""The trade-off front as a figure (``sizer plot DESIGN --front``): every feasible pair as
a point of motor size against time, the front as a line through its points (smallest
motor first), the straight line through the front's two ends dashed and the knee marked
(sizer.sizing.front: the front point farthest from that line, both axes scaled to [0, 1]).

matplotlib is imported inside the drawing (sizer.report.plots.figure_files.new_figure);
the front and its knee come from the core, nothing here decides which point is which.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from sizer.laws.data_spec import law_label
from sizer.report.numbers import short
from sizer.report.plots.figure_files import new_figure
from sizer.sizing.front import SIZE_OBJECTIVES

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from sizer.sizing import SizingResult
    from sizer.sizing.front import Front

DEFAULT_SIZE = (8.0, 6.0)
LABELLED = 12
"""Front points named beside their marker when the front has at most this many."""

GID_CANDIDATES = "candidates"
GID_FRONT = "front"
GID_CHORD = "chord"
GID_KNEE = "knee"


def front_axes_labels(front: Front, duration_name: str) -> tuple[str, str, float]:
    """(x label, y label, y factor from SI): the size objective as in tables (its SI
    value), the time in ms (or the smallest margin in %)."""
    size = SIZE_OBJECTIVES[front.by]
    x_label = f"{size.name} [{size.unit}]" if size.unit else size.name
    if front.time_name == "duration":
        return x_label, f"{duration_name} [ms]", 1000.0
    return x_label, "smallest margin beyond the required [%] (larger better)", 100.0


def front_figure(sizing: SizingResult, front: Front, *, duration_name: str = "T_min",
                 title: str = "", size: tuple[float, float] | None = None,
                 dpi: float = 100.0) -> Figure:
    """The front of ``sizing`` (its ranked results, as ``front`` indexes them)."""
    figure = new_figure(size or DEFAULT_SIZE, dpi)
    ax = figure.subplots()
    x_label, y_label, fy = front_axes_labels(front, duration_name)
    x = np.asarray(front.size, dtype=float)
    y = np.asarray(front.time, dtype=float) * fy
    known = np.isfinite(x) & np.isfinite(y)
    ax.scatter(x[known], y[known], s=18, color="0.6", zorder=2, gid=GID_CANDIDATES,
               label=f"feasible pairs ({int(np.count_nonzero(known))})")
    members = np.asarray(front.members, dtype=np.intp)
    if members.size:
        ax.plot(x[members], y[members], "-o", color="C0", ms=5, lw=1.5, zorder=3,
                gid=GID_FRONT, label=f"front ({members.size})")
        ends = members[[0, -1]]
        if members.size > 1:
            ax.plot(x[ends], y[ends], "--", color="0.4", lw=0.9, zorder=1, gid=GID_CHORD,
                    label="line through the front's ends")
        points: dict[tuple[float, float], list[str]] = {}
        for i in members:  # pairs at one point (laws of a motor that tie) named once
            names = points.setdefault((float(x[i]), float(y[i])), [])
            if sizing.results[int(i)].motor not in names:
                names.append(sizing.results[int(i)].motor)
        if len(points) <= LABELLED:
            for (px, py), names in points.items():
                ax.annotate(", ".join(names), (px, py), textcoords="offset points",
                            xytext=(5, 4), fontsize=7, color="C0")
    if front.knee is not None:
        k = front.knee
        r = sizing.results[k]
        ax.plot([x[k]], [y[k]], "*", color="C3", ms=16, zorder=4, gid=GID_KNEE,
                label=(f"knee: {r.motor}, {law_label(r.spec)} ({short(x[k])}, "
                       f"{short(y[k])})"))
    ax.set_xlabel(x_label)
    ax.set_ylabel(y_label)
    ax.grid(True, lw=0.4, alpha=0.6)
    ax.legend(loc="best", fontsize=8)
    heading = f"{title}: " if title else ""
    what = "time" if front.time_name == "duration" else "margin"
    ax.set_title(f"{heading}trade-off front of {what} against {x_label.split(' [')[0]}",
                 fontsize=10)
    if front.left_out:
        figure.text(0.01, 0.005, f"{front.left_out} feasible pairs without "
                    f"{SIZE_OBJECTIVES[front.by].name} not drawn", fontsize=7, color="0.35")
    _pad(ax, x[known], y[known])
    return figure


def _pad(ax, x: np.ndarray, y: np.ndarray) -> None:
    """Room around the points (a single point or equal values get a visible span)."""
    for values, setter in ((x, ax.set_xlim), (y, ax.set_ylim)):
        if values.size == 0:
            continue
        low, high = float(values.min()), float(values.max())
        span = high - low if high > low else max(abs(high), 1.0) * 0.1
        if math.isfinite(span):
            setter(low - 0.08 * span, high + 0.12 * span)
