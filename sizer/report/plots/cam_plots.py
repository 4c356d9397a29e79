"""A disc cam's figure (issue 38, ``sizer plot --cam``): the follower's motion over the cam
angle and the cam's profile.

Left, four panels sharing the cam angle (deg, one turn): the follower's lift, velocity,
acceleration and jerk at the cam's constant speed (mm and m/s^k for a translating follower,
deg and rad/s^k for an oscillating one's swing), the segments of the cycle shaded and named.
Right, the cam in its own frame (mm, equal axes): the pitch curve (the roller's centre),
the actual profile, the base circle and the roller at the start of each segment. Several
laws are drawn over each other, each its own cam (an ``auto`` base radius is each law's).

The numbers come from the core (sizer.mechanics.disc_cam.follower_motion and
profile_points of the cam the sizing resolved, its ``figures``); here radians become
degrees and metres millimetres, nothing else.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from sizer.report.numbers import short
from sizer.report.plots.figure_files import new_figure
from sizer.report.plots.speed_torque import CURVE_COLORS
from sizer.report.plots.time_curves import JOIN_COLOR, SPAN_COLOR, finish_axes

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from sizer.mechanics.disc_cam import CamPoints, CamStage, FollowerMotion

DEFAULT_SIZE = (14.0, 8.0)
RPM_PER_RAD_S = 60.0 / (2.0 * math.pi)

GID_MOTION = ("cam-lift", "cam-velocity", "cam-acceleration", "cam-jerk")
GID_PITCH = "cam-pitch-curve"
GID_PROFILE = "cam-profile"
GID_BASE_CIRCLE = "cam-base-circle"
GID_ROLLER = "cam-roller"
GID_SPAN = "cam-segment-span"
"""Artist ids (``get_gid()``), so a reader of the figure (a test) finds what is what."""


@dataclass(frozen=True)
class CamView:
    """One law's cam to draw: its label (the motor, the law), the resolved stage (its
    base radius, roller, offset or arm and ``figures``), the follower's motion over a turn
    and the profile's points, both from sizer.mechanics.disc_cam."""

    label: str
    stage: CamStage
    motion: FollowerMotion
    points: CamPoints


def motion_units(linear: bool) -> tuple[float, tuple[str, ...]]:
    """(the lift's display scale, the four panels' axis labels): mm and m/s^k for a
    translating follower, deg and rad/s^k for an oscillating one."""
    if linear:
        return 1000.0, ("lift [mm]", "velocity [m/s]", "acceleration [m/s²]", "jerk [m/s³]")
    return math.degrees(1.0), ("swing [deg]", "angular velocity [rad/s]",
                               "angular acceleration [rad/s²]", "angular jerk [rad/s³]")


def cam_figure(views: Sequence[CamView], segments: Sequence[tuple[str, float, float]] = (),
               *, size: tuple[float, float] | None = None, dpi: float = 100.0,
               title: str = "") -> Figure:
    """The figure of the cams ``views`` (module docstring); ``segments`` are the cycle's
    (name, start, end) in cam angle (rad)."""
    if not views:
        raise ValueError("no cam to draw")
    linear = views[0].stage.output_linear
    if any(v.stage.output_linear != linear for v in views):
        raise ValueError("the cams' followers differ: all translating or all oscillating")
    figure = new_figure(size or DEFAULT_SIZE, dpi)
    grid = figure.add_gridspec(4, 2, width_ratios=(1.35, 1.0))
    motion_axes: list[Axes] = []
    for row in range(4):
        share = motion_axes[0] if motion_axes else None
        motion_axes.append(figure.add_subplot(grid[row, 0], sharex=share))
    profile_axes = figure.add_subplot(grid[:, 1])

    scale, labels = motion_units(linear)
    for index, view in enumerate(views):
        color = CURVE_COLORS[index % len(CURVE_COLORS)]
        m = view.motion
        degrees = np.degrees(m.theta)
        series = (m.position * scale, m.velocity, m.acceleration, m.jerk)
        for ax, values, gid in zip(motion_axes, series, GID_MOTION, strict=True):
            ax.plot(degrees, values, color=color, lw=1.4, label=view.label, gid=gid,
                    zorder=4)
        _draw_cam(profile_axes, view, color, segments)
    for row, (ax, label) in enumerate(zip(motion_axes, labels, strict=True)):
        _shade_segments(ax, segments, named=row == 0)
        finish_axes(ax, "cam angle [deg]" if row == 3 else "", label,
                    zero_color=JOIN_COLOR, legend=row == 0 and len(views) > 1)
        if row < 3:
            ax.tick_params(labelbottom=False)
    motion_axes[0].set_xlim(0.0, 360.0)
    motion_axes[0].set_xticks(np.arange(0.0, 361.0, 45.0))

    profile_axes.plot([0.0], [0.0], marker="+", color="0.2", ms=10, ls="none")
    profile_axes.set_aspect("equal", adjustable="datalim")
    profile_axes.grid(True, color="0.85", lw=0.5)
    profile_axes.set_axisbelow(True)
    profile_axes.set_xlabel("x [mm] (cam frame, turning counterclockwise)")
    profile_axes.set_ylabel("y [mm]")
    profile_axes.legend(loc="upper right", fontsize="x-small", framealpha=0.85)
    profile_axes.set_title("\n".join(cam_caption(v) for v in views), fontsize="small")

    speed = views[0].motion.speed * RPM_PER_RAD_S
    heading = f"{title}: " if title else ""
    figure.suptitle(f"{heading}the follower over the cam angle at {short(speed)} rpm of "
                    f"the cam, and the cam's profile", fontsize="medium")
    return figure


def cam_caption(view: CamView) -> str:
    """One line of a cam's figures: its base radius, largest pressure angle and smallest
    convex radius of the pitch curve (the sizing's, ``stage.figures``)."""
    stage = view.stage
    assert stage.base_radius is not None, "the cam resolved"
    parts = [f"R_b {short(stage.base_radius * 1000.0)} mm"]
    figures = stage.figures
    if figures is not None:
        parts.append(f"largest pressure angle "
                     f"{short(math.degrees(figures.max_pressure_angle))}°")
        if math.isfinite(figures.min_convex_radius):
            parts.append(f"pitch curve's smallest convex radius "
                         f"{short(figures.min_convex_radius * 1000.0)} mm")
    return f"{view.label}:\n" + ", ".join(parts)


def _draw_cam(ax: Axes, view: CamView, color: str,
              segments: Sequence[tuple[str, float, float]]) -> None:
    """The pitch curve, the profile, the base circle and the roller at each segment's
    start (at the nearest of the points' angles) of one cam, in mm."""
    from matplotlib.patches import Circle

    p, stage = view.points, view.stage
    assert stage.base_radius is not None, "the cam resolved"
    name = view.label
    ax.plot(p.profile_x * 1000.0, p.profile_y * 1000.0, color=color, lw=1.6,
            label=f"profile, {name}", gid=GID_PROFILE, zorder=4)
    ax.plot(p.pitch_x * 1000.0, p.pitch_y * 1000.0, color=color, lw=0.9, ls="--",
            label=f"pitch curve, {name}", gid=GID_PITCH, zorder=3)
    ax.add_patch(Circle((0.0, 0.0), stage.base_radius * 1000.0, fill=False, color=color,
                        lw=0.7, ls=":", gid=GID_BASE_CIRCLE, zorder=2,
                        label=f"base circle R_b = {short(stage.base_radius * 1000.0)} mm"))
    starts = [start for _, start, _ in segments] or [0.0]
    for start in starts:
        i = int(np.argmin(np.abs(np.mod(p.theta - start + math.pi, 2.0 * math.pi)
                                 - math.pi)))
        ax.add_patch(Circle((float(p.pitch_x[i]) * 1000.0, float(p.pitch_y[i]) * 1000.0),
                            stage.roller_radius * 1000.0, fill=False, color=color, lw=0.8,
                            gid=GID_ROLLER, zorder=5))


def _shade_segments(ax: Axes, segments: Sequence[tuple[str, float, float]], *,
                    named: bool) -> None:
    """Every other segment shaded, a line at each join, the names on top (``named``)."""
    from matplotlib.transforms import blended_transform_factory

    transform = blended_transform_factory(ax.transData, ax.transAxes)
    for index, (name, start, end) in enumerate(segments):
        lo, hi = math.degrees(start), math.degrees(end)
        if index % 2 == 0:
            ax.axvspan(lo, hi, color=SPAN_COLOR, lw=0, zorder=0, gid=GID_SPAN)
        if index:
            ax.axvline(lo, color=JOIN_COLOR, lw=0.7, ls=":", zorder=1)
        if named and name and hi > lo:
            ax.text(0.5 * (lo + hi), 0.98, name, transform=transform, ha="center",
                    va="top", fontsize="x-small", color="0.25", clip_on=True)
