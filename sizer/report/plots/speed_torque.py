"""The speed-torque diagram of a motor with the mechanical tasks of one or more laws.

The motor's intermittent and continuous regions (Fig. 6.1) filled, mirrored to negative
torque (braking) and, when the cycle moves back, to negative speed; each law's task
curve (speed(t), torque(t)) over the machine cycle (Fig. 6.2) and its RMS point (thermal
speed, RMS torque) of Fig. 6.3. With ``acceleration`` a second panel shows the same in the
speed-acceleration plane (Fig. 6.7 b): the regions divided by J_t, the task's motor
acceleration, and the RMS point at tau_rms/J_t.

Everything drawn comes from the core's TaskCurve; only the speed unit is converted.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from sizer.laws.data_spec import law_label
from sizer.report.candidate_row import MARGINS, RPM_PER_RAD_S, percent
from sizer.report.numbers import short
from sizer.report.plots.figure_files import new_figure

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from sizer.model.domain import Curve
    from sizer.sizing import CandidateResult
    from sizer.sizing.samples import TaskCurve

SPEED_UNITS = {"rpm": RPM_PER_RAD_S, "rad/s": 1.0}
"""Display unit of speed -> factor from rad/s."""

INTERMITTENT_STYLE = {"facecolor": "#fdd0a2", "edgecolor": "#e6550d"}
CONTINUOUS_STYLE = {"facecolor": "#c7e9c0", "edgecolor": "#31a354"}
CURVE_COLORS = ("#08519c", "#a50f15", "#54278f", "#252525", "#8c510a", "#01665e",
                "#c51b7d", "#4d4d4d")

DEFAULT_SIZE = (8.0, 6.0)
DEFAULT_SIZE_WITH_ACCELERATION = (13.0, 6.0)

GID_INTERMITTENT = "intermittent-region"
GID_CONTINUOUS = "continuous-region"
GID_TASK = "task-curve"
GID_RMS = "rms-point"
GID_SEGMENT_START = "segment-start"
"""Artist ids (``get_gid()``), so a reader of the figure (a test) finds what is what."""


def region_outline(curve: Curve, both_directions: bool) -> np.ndarray:
    """Closed outline (N x 2, speed rad/s and torque) of a region: |torque| <= limit(|speed|).

    The corner points from 0 speed to the last, then the same with negative torque back
    to 0 speed; with ``both_directions`` also mirrored to negative speed.
    """
    upper = np.array(curve, dtype=float)
    lower = upper[::-1] * (1.0, -1.0)
    parts = [upper, lower]
    if both_directions:
        parts += [upper * (-1.0, -1.0), lower * (-1.0, -1.0)]
    return np.concatenate(parts)


def speed_torque_figure(curves: Sequence[TaskCurve],
                        results: Sequence[CandidateResult] | None = None, *,
                        acceleration: bool = False, speed_unit: str = "rpm",
                        size: tuple[float, float] | None = None, dpi: float = 100.0,
                        title: str = "", duration_name: str = "T",
                        mark_segments: bool = False) -> Figure:
    """The speed-torque diagram of one motor with the task curves of its laws.

    ``curves`` are TaskCurves of the same motor (one per law); ``results`` the matching
    sizing results (same order) whose margins go in the title. ``title`` is a first
    title line (e.g. the design's name); ``duration_name`` labels the durations ('T_min'
    in minimize mode). With ``mark_segments`` (a cycle of segments) the point where each
    segment starts is marked on the first curve with the segment's name. Returns the
    Figure.
    """
    check_one_motor(curves)
    if results is not None and len(results) != len(curves):
        raise ValueError("one result per curve")
    scale = SPEED_UNITS[speed_unit]
    figure = new_figure(size or (DEFAULT_SIZE_WITH_ACCELERATION if acceleration
                                 else DEFAULT_SIZE), dpi)
    axes = figure.subplots(1, 2 if acceleration else 1, squeeze=False)[0]
    both = any(float(np.min(c.motor_speed)) < 0.0 for c in curves)
    first = curves[0]

    torque_axes = axes[0]
    _draw_regions(torque_axes, first.continuous_region, first.intermittent_region, both, scale)
    for index, curve in enumerate(curves):
        color = CURVE_COLORS[index % len(CURVE_COLORS)]
        label = _curve_label(curve, duration_name)
        torque_axes.plot(curve.motor_speed * scale, curve.motor_torque, color=color, lw=1.6,
                         label=label, gid=GID_TASK, zorder=4)
        torque_axes.plot([curve.thermal_speed * scale], [curve.rms_torque], ls="none",
                         marker="o", ms=7, mfc="white", mec=color, mew=2.0, gid=GID_RMS,
                         label=f"RMS point: {short(curve.rms_torque)} N*m", zorder=5)
    if mark_segments:
        _mark_segment_starts(torque_axes, first, scale)
    _finish(torque_axes, f"motor speed [{speed_unit}]", "motor torque [N*m]",
            "speed-torque plane (Figs. 6.1-6.3)")

    if acceleration:
        _draw_acceleration_panel(axes[1], curves, both, scale, speed_unit, duration_name)

    figure.suptitle("\n".join(_title_lines(first.motor, curves, results, title)),
                    fontsize="medium")
    return figure


def check_one_motor(curves: Sequence[TaskCurve]) -> None:
    """A ValueError unless ``curves`` are one or more task curves of one motor."""
    if not curves:
        raise ValueError("no task curve to draw")
    motors = {c.motor for c in curves}
    if len(motors) > 1:
        raise ValueError(f"curves of several motors: {', '.join(sorted(motors))}")

def _draw_acceleration_panel(ax: Axes, curves: Sequence[TaskCurve], both: bool,
                             scale: float, speed_unit: str, duration_name: str) -> None:
    first = curves[0]
    continuous, intermittent = first.acceleration_regions
    _draw_regions(ax, continuous, intermittent, both, scale)
    for index, curve in enumerate(curves):
        color = CURVE_COLORS[index % len(CURVE_COLORS)]
        if index and not math.isclose(curve.total_inertia, first.total_inertia, rel_tol=1e-12):
            # another ratio, another J_t: its own region outlines, dashed in its colour
            for region in curve.acceleration_regions:
                outline = region_outline(region, both)
                ax.fill(outline[:, 0] * scale, outline[:, 1], fill=False, ls="--",
                        edgecolor=color, lw=1.0, gid="acceleration-region-outline")
        ax.plot(curve.motor_speed * scale, curve.motor_acceleration, color=color, lw=1.6,
                label=_curve_label(curve, duration_name), gid=GID_TASK, zorder=4)
        rms_acceleration = curve.rms_torque / curve.total_inertia
        ax.plot([curve.thermal_speed * scale], [rms_acceleration], ls="none", marker="o",
                ms=7, mfc="white", mec=color, mew=2.0, gid=GID_RMS, zorder=5,
                label=f"RMS point: tau_rms/J_t = {short(rms_acceleration)} rad/s^2")
    inertias = dict.fromkeys(short(c.total_inertia) for c in curves)
    _finish(ax, f"motor speed [{speed_unit}]", "motor acceleration [rad/s^2]",
            f"speed-acceleration plane (Fig. 6.7 b), J_t = {', '.join(inertias)} kg*m^2")


def _mark_segment_starts(ax: Axes, curve: TaskCurve, scale: float) -> None:
    """A small square where each segment of the cycle starts, with its name."""
    points = segment_points(curve)
    if not points:
        return
    ax.plot([p[1] * scale for p in points], [p[2] for p in points], ls="none", marker="s",
            ms=4, color="0.2", gid=GID_SEGMENT_START, zorder=6, label="segment starts")
    for name, speed, torque in points:
        ax.annotate(name, (speed * scale, torque), xytext=(4, 4),
                    textcoords="offset points", fontsize="x-small", color="0.2", zorder=6)


def segment_points(curve: TaskCurve) -> list[tuple[str, float, float]]:
    """(names, motor speed, motor torque) where segments start: the segment's first
    sample (the last one at its start time: the previous segment ends at that time too).
    Segments starting at the same point (at rest, say) share one, their names joined."""
    points: dict[tuple[float, float], list[str]] = {}
    for name, start, _ in curve.segments:
        index = max(int(np.searchsorted(curve.time, start, side="right")) - 1, 0)
        key = (float(curve.motor_speed[index]), float(curve.motor_torque[index]))
        points.setdefault(key, []).append(name)
    return [(", ".join(names), speed, torque) for (speed, torque), names in points.items()]


def _draw_regions(ax: Axes, continuous: Curve, intermittent: Curve, both: bool,
                  scale: float) -> None:
    for region, style, gid, label, z in (
        (intermittent, INTERMITTENT_STYLE, GID_INTERMITTENT, "intermittent region", 1),
        (continuous, CONTINUOUS_STYLE, GID_CONTINUOUS, "continuous region", 2),
    ):
        outline = region_outline(region, both)
        (polygon,) = ax.fill(outline[:, 0] * scale, outline[:, 1], label=label, lw=1.2,
                             zorder=z, facecolor=style["facecolor"],
                             edgecolor=style["edgecolor"])
        polygon.set_gid(gid)


def _finish(ax: Axes, xlabel: str, ylabel: str, title: str) -> None:
    ax.axhline(0.0, color="0.5", lw=0.6, zorder=3)
    ax.axvline(0.0, color="0.5", lw=0.6, zorder=3)
    ax.grid(True, color="0.85", lw=0.5)
    ax.set_axisbelow(True)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize="small")
    ax.legend(loc="best", fontsize="x-small", framealpha=0.85)


def _curve_label(curve: TaskCurve, duration_name: str) -> str:
    return f"{curve.law}, {duration_name} = {short(curve.duration * 1000.0)} ms"


def _title_lines(motor: str, curves: Sequence[TaskCurve],
                 results: Sequence[CandidateResult] | None, title: str) -> list[str]:
    lines = [f"{title}: motor {motor}" if title else f"motor {motor}"]
    if results is None:
        return lines
    for curve, result in zip(curves, results, strict=True):
        margins = ", ".join(f"{name} {percent(result.margin(name))} %"
                            for name in MARGINS
                            if result.margin(name) is not None)
        ratio = f", K = {short(curve.ratio)}" if curve.ratio != 1.0 else ""
        verdict = "" if result.feasible else f" - FAILS ({result.limiting})"
        lines.append(f"{law_label(result.spec)}{ratio}: margins {margins}{verdict}")
    return lines
