"""Motor torque and motor speed over time for a machine cycle, its segments marked
(issue 12; the time view of the book's Fig. 6.2 task).

Two panels sharing the time axis: the motor torque tau(t) with the RMS torque as a dashed
line, and the motor speed omega(t). Each segment of the cycle is a shaded span (light and
white in turn) named at the top, with a vertical line at each join. Everything drawn comes
from the core's TaskCurve (its samples and its ``segments``); only units are converted.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from sizer.report.numbers import short
from sizer.report.plots.figure_files import new_figure
from sizer.report.plots.speed_torque import CURVE_COLORS, SPEED_UNITS, check_one_motor

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from sizer.sizing.samples import TaskCurve

DEFAULT_SIZE = (10.0, 6.0)
SPAN_COLOR = "#deebf7"
JOIN_COLOR = "0.55"

GID_TORQUE = "torque-time"
GID_SPEED = "speed-time"
GID_SPAN = "segment-span"
GID_JOIN = "segment-join"
GID_RMS_LINE = "rms-torque-line"
"""Artist ids (``get_gid()``), so a reader of the figure (a test) finds what is what."""


def time_figure(curves: Sequence[TaskCurve], *, speed_unit: str = "rpm",
                size: tuple[float, float] | None = None, dpi: float = 100.0,
                title: str = "", duration_name: str = "T") -> Figure:
    """Motor torque and speed over one machine cycle for each law's task curve (one
    motor), with the segments of the first curve shaded and named."""
    check_one_motor(curves)
    scale = SPEED_UNITS[speed_unit]
    figure = new_figure(size or DEFAULT_SIZE, dpi)
    torque_axes, speed_axes = figure.subplots(2, 1, sharex=True, squeeze=True)
    first = curves[0]
    for ax, named in ((torque_axes, True), (speed_axes, False)):
        mark_segments(ax, first.segments, named=named)
    for index, curve in enumerate(curves):
        color = CURVE_COLORS[index % len(CURVE_COLORS)]
        label = f"{curve.law}, {duration_name} = {short(curve.duration * 1000.0)} ms"
        torque_axes.plot(curve.time * 1000.0, curve.motor_torque, color=color, lw=1.5,
                         label=label, gid=GID_TORQUE, zorder=4)
        torque_axes.axhline(curve.rms_torque, color=color, lw=1.0, ls="--", zorder=3,
                            gid=GID_RMS_LINE, label=f"RMS torque {short(curve.rms_torque)} N*m")
        speed_axes.plot(curve.time * 1000.0, curve.motor_speed * scale, color=color, lw=1.5,
                        label=label, gid=GID_SPEED, zorder=4)
    finish_axes(torque_axes, "", "motor torque [N*m]")
    finish_axes(speed_axes, "time [ms]", f"motor speed [{speed_unit}]")
    end = max(float(c.time[-1]) for c in curves) * 1000.0
    speed_axes.set_xlim(0.0, end)
    heading = f"{title}: motor {first.motor}" if title else f"motor {first.motor}"
    figure.suptitle(f"{heading}\nmotor torque and speed over the cycle, by segment",
                    fontsize="medium")
    return figure


def mark_segments(ax: Axes, segments: Sequence[tuple[str, float, float]], *,
                  named: bool = True) -> None:
    """Shade every other segment, draw a line at each join and (``named``) write each
    segment's name at the top of its span (times in s, drawn in ms)."""
    from matplotlib.transforms import blended_transform_factory

    transform = blended_transform_factory(ax.transData, ax.transAxes)
    for index, (name, start, end) in enumerate(segments):
        lo, hi = start * 1000.0, end * 1000.0
        if index % 2 == 0:
            ax.axvspan(lo, hi, color=SPAN_COLOR, lw=0, zorder=0, gid=GID_SPAN)
        if index:
            ax.axvline(lo, color=JOIN_COLOR, lw=0.7, ls=":", zorder=1, gid=GID_JOIN)
        if named and hi > lo:
            ax.text(0.5 * (lo + hi), 0.98, name, transform=transform, ha="center",
                    va="top", fontsize="x-small", color="0.25", clip_on=True)


def finish_axes(ax: Axes, xlabel: str, ylabel: str, *, zero_color: str = "0.5",
                legend: bool = True) -> None:
    """The zero line, the grid, the labels (no x label when empty) and the legend."""
    ax.axhline(0.0, color=zero_color, lw=0.6, zorder=2)
    ax.grid(True, color="0.85", lw=0.5)
    ax.set_axisbelow(True)
    if xlabel:
        ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if legend:
        ax.legend(loc="lower right", fontsize="x-small", framealpha=0.85)
    ax.margins(y=0.15)

