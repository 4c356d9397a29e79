"""The transmission ratio of a linkage and the motor torque over the crank angle (issue 14).

Two panels sharing the crank angle (deg): the ratio ds/dtheta of the linkage (m/rad for a
slider, rad/rad for a rocker), zero at the dead points, and the motor torque of each
candidate (N*m). Each dead point is a vertical line on both panels, at every angle of
the plotted range congruent to it (a motion over several turns meets it once per turn),
named at the top of the ratio panel. The numbers come from the core (the linkage's
``output(theta, 1)`` and sizer.mechanics.linkages.dynamics); only radians become degrees.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

import numpy as np

from sizer.report.numbers import short
from sizer.report.plots.figure_files import new_figure
from sizer.report.plots.speed_torque import CURVE_COLORS
from sizer.report.plots.time_curves import JOIN_COLOR, finish_axes

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

DEFAULT_SIZE = (10.0, 6.0)
DEAD_POINT_COLOR = "#a50f15"

GID_RATIO = "linkage-ratio"
GID_TORQUE = "linkage-torque"
GID_DEAD_POINT = "dead-point"
GID_DEAD_POINT_LABEL = "dead-point-label"
"""Artist ids (``get_gid()``), so a reader of the figure (a test) finds what is what."""


def linkage_figure(theta: np.ndarray, ratio: np.ndarray,
                   torque_by_candidate: Mapping[str, np.ndarray],
                   dead_points: Sequence[float] | Mapping[str, float], *, linear: bool,
                   size: tuple[float, float] | None = None, dpi: float = 100.0,
                   title: str = "") -> Figure:
    """The ratio ds/dtheta and the motor torque of each candidate (its label: the motor,
    the law...) over the crank angle ``theta`` (rad, drawn in deg). ``dead_points`` are
    crank angles (rad), or names (e.g. "top dead centre") to angles; ``linear``: the
    output is a slider (ratio in m/rad), else a rocker (rad/rad)."""
    theta = np.asarray(theta, dtype=float)
    ratio = np.asarray(ratio, dtype=float)
    if theta.ndim != 1 or theta.size < 2:
        raise ValueError("theta must be a 1-D array of at least two angles")
    if ratio.shape != theta.shape:
        raise ValueError(f"ratio has shape {ratio.shape}, theta {theta.shape}")
    if not torque_by_candidate:
        raise ValueError("no motor torque to draw")
    torques = {name: np.asarray(t, dtype=float) for name, t in torque_by_candidate.items()}
    for name, torque in torques.items():
        if torque.shape != theta.shape:
            raise ValueError(f"the torque of {name!r} has shape {torque.shape}, theta "
                             f"{theta.shape}")
    if isinstance(dead_points, Mapping):
        named = {str(name): float(angle) for name, angle in dead_points.items()}
    else:
        named = {f"dead point {i + 1}": float(angle) for i, angle in enumerate(dead_points)}

    figure = new_figure(size or DEFAULT_SIZE, dpi)
    ratio_axes, torque_axes = figure.subplots(2, 1, sharex=True, squeeze=True)
    degrees = np.degrees(theta)
    ratio_axes.plot(degrees, ratio, color=CURVE_COLORS[0], lw=1.5, gid=GID_RATIO, zorder=4)
    for index, (name, torque) in enumerate(torques.items()):
        torque_axes.plot(degrees, torque, color=CURVE_COLORS[index % len(CURVE_COLORS)],
                         lw=1.5, label=name, gid=GID_TORQUE, zorder=4)
    low, high = float(np.min(degrees)), float(np.max(degrees))
    for name, angle in named.items():
        for at in dead_point_angles(math.degrees(angle), low, high):
            for ax in (ratio_axes, torque_axes):
                ax.axvline(at, color=DEAD_POINT_COLOR, lw=0.9, ls="--", zorder=3,
                           gid=GID_DEAD_POINT)
            _label(ratio_axes, at, f"{name} {short(round(at, 1))}°")
    unit = "m/rad" if linear else "rad/rad"
    finish_axes(ratio_axes, "", f"transmission ratio ds/dθ [{unit}]", zero_color=JOIN_COLOR,
                legend=False)
    finish_axes(torque_axes, "crank angle [deg]", "motor torque [N*m]", zero_color=JOIN_COLOR)
    torque_axes.set_xlim(low, high)
    heading = f"{title}: " if title else ""
    figure.suptitle(f"{heading}transmission ratio and motor torque over the crank angle",
                    fontsize="medium")
    return figure


def dead_point_angles(angle: float, low: float, high: float) -> list[float]:
    """The angles angle + k 360 (deg) in [low, high]."""
    first = math.ceil((low - angle) / 360.0 - 1e-12)
    last = math.floor((high - angle) / 360.0 + 1e-12)
    return [angle + 360.0 * k for k in range(first, last + 1)]


def _label(ax: Axes, at: float, text: str) -> None:
    from matplotlib.transforms import blended_transform_factory

    transform = blended_transform_factory(ax.transData, ax.transAxes)
    ax.text(at, 0.98, text, transform=transform, ha="center", va="top", fontsize="x-small",
            color=DEAD_POINT_COLOR, clip_on=True, gid=GID_DEAD_POINT_LABEL,
            bbox={"facecolor": "white", "edgecolor": "none", "alpha": 0.8, "pad": 1.0})
