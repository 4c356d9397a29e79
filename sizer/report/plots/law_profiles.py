"""Position, velocity, acceleration and jerk of motion laws, in four stacked panels
(book Figs. 6.4-6.6): normalized (h = T = 1) or scaled to a move of h in T.

Each law is sampled piece by piece, so a derivative that jumps at a breakpoint is drawn
as a vertical step rather than a slanted line; the rest before and after the move is
drawn too (at the law's own end position: a cam that returns rests at its start). A
periodic law (a cam whose ends move and join, sec. 4.4.2) is drawn over ``PERIODS``
periods, its position unwrapped (each period starts where the last ended, one stroke
higher for a knife that turns once per cycle), so the curve never jumps between periods.
Where the acceleration jumps the jerk is an impulse: an arrow in the jerk
panel, up or down with the sign of the jump, labelled with the jump's size (its area).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from sizer.laws.data_spec import law_label
from sizer.report.numbers import short
from sizer.report.plots.figure_files import new_figure
from sizer.report.plots.speed_torque import CURVE_COLORS

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from sizer.laws import MotionLaw

DEFAULT_SIZE = (8.0, 9.0)
REST_PAD = 0.05
"""Rest shown before and after the move, as a fraction of T."""

PERIODS = 3
"""Periods drawn of a periodic law."""

ORDERS = (0, 1, 2, 3)
NAMES = ("position", "velocity", "acceleration", "jerk")

GID_PROFILE = "law-profile"
GID_IMPULSE = "jerk-impulse"
GID_IMPULSE_LABEL = "jerk-impulse-label"


@dataclass(frozen=True)
class Move:
    """The scaling of the plot: None for normalized (h = T = 1)."""

    displacement: float | None = None
    duration: float | None = None
    linear: bool = False

    @property
    def normalized(self) -> bool:
        return self.displacement is None

    @property
    def h(self) -> float:
        return 1.0 if self.displacement is None else self.displacement

    @property
    def T(self) -> float:
        return 1.0 if self.duration is None else self.duration

    def scale(self, order: int) -> float:
        """The k-th derivative of q(t) = h q_N(t/T) is h/T^k times q_N's."""
        return self.h / self.T**order

    def label(self, order: int) -> str:
        if self.normalized:
            return f"{NAMES[order]} q_N{chr(39) * order} [-]"
        unit = "m" if self.linear else "rad"
        suffix = "" if order == 0 else "/s" if order == 1 else f"/s^{order}"
        return f"{NAMES[order]} [{unit}{suffix}]"

    def jump_text(self, jump: float) -> str:
        unit = "" if self.normalized else (" m/s^2" if self.linear else " rad/s^2")
        return f"\u0394a = {'+' if jump > 0 else ''}{short(jump)}{unit}"


def periods_of(law: MotionLaw) -> int:
    """Periods drawn of ``law``: PERIODS for a periodic law, else 1 (one move)."""
    return PERIODS if getattr(law, "periodic", False) else 1


def law_samples(law: MotionLaw, order: int, samples: int,
                end: float = 1.0 + REST_PAD) -> tuple[np.ndarray, np.ndarray]:
    """(tau, value) of the order-th derivative of q_N, piece by piece; a breakpoint
    appears twice (the values on its left and right).

    A move rests before 0 and after 1 (until ``end``) at its outside values; a periodic
    law is drawn over ``periods_of(law)`` periods from 0, the position unwrapped."""
    periods = periods_of(law)
    taus: list[np.ndarray] = []
    values: list[np.ndarray] = []
    before, after = law.outside(order)
    if periods == 1:
        taus.append(np.array([-REST_PAD, 0.0]))
        values.append(np.full(2, before))
    stroke = (float(law.piece_derivative(len(law.pieces) - 1, 1.0, 0))
              - float(law.piece_derivative(0, 0.0, 0))) if order == 0 else 0.0
    for period in range(periods):
        for index, piece in enumerate(law.pieces):
            width = piece.end - piece.start
            count = max(3, math.ceil(samples * width))
            u = np.linspace(0.0, 1.0, count)
            if law.steep_ends:
                u = 0.5 - 0.5 * np.cos(np.pi * u)  # denser toward the piece's ends
            tau = piece.start + width * u
            taus.append(tau + period)
            values.append(np.asarray(law.piece_derivative(index, tau, order), dtype=float)
                          + period * stroke)
    if periods == 1:
        taus.append(np.array([1.0, max(end, 1.0 + REST_PAD)]))
        values.append(np.full(2, after))
    return np.concatenate(taus), np.concatenate(values)


def law_profiles_figure(laws: Sequence[MotionLaw], *, displacement: float | None = None,
                        duration: float | None = None, linear: bool = False,
                        samples: int = 401, size: tuple[float, float] | None = None,
                        dpi: float = 100.0) -> Figure:
    """Four stacked panels (q, v, a, j) of the laws; normalized unless h and T are given."""
    if not laws:
        raise ValueError("no law to draw")
    if (displacement is None) != (duration is None):
        raise ValueError("give both the displacement and the duration, or neither")
    move = Move(displacement, duration, linear)
    figure = new_figure(size or DEFAULT_SIZE, dpi)
    axes = figure.subplots(4, 1, sharex=True)
    periods = max(periods_of(law) for law in laws)
    end = periods + REST_PAD
    jerk_extent = 0.0
    for index, law in enumerate(laws):
        color = CURVE_COLORS[index % len(CURVE_COLORS)]
        for ax, order in zip(axes, ORDERS, strict=True):
            tau, value = law_samples(law, order, samples, end)
            y = move.scale(order) * value
            ax.plot(move.T * tau, y, color=color, lw=1.4, gid=GID_PROFILE,
                    label=law_label(law.spec) if order == 0 else None)
            if order == 3:
                jerk_extent = max(jerk_extent, float(np.max(np.abs(y))))
    impulses, left_out = drawn_impulses(laws)
    _draw_impulses(axes[3], impulses, move, jerk_extent)

    for ax, order in zip(axes, ORDERS, strict=True):
        ax.axhline(0.0, color="0.5", lw=0.6)
        ax.grid(True, color="0.85", lw=0.5)
        ax.set_ylabel(move.label(order), fontsize="small")
    axes[0].legend(loc="upper left", fontsize="x-small")
    axes[3].set_xlabel("tau = t/T [-]" if move.normalized else "time t [s]")
    axes[3].set_xlim(-REST_PAD * move.T, end * move.T)
    if impulses:
        more = (f"; the {MAX_DRAWN_IMPULSES} largest of each law, {left_out} smaller not "
                f"drawn" if left_out else "")
        axes[3].set_title("arrows: jerk impulses where the acceleration jumps "
                          f"(not to scale; labelled with the jump{more})", fontsize="x-small")
    if move.normalized:
        heading = "Motion laws, normalized (h = 1, T = 1)"
    else:
        unit = "m" if linear else "rad"
        heading = f"Motion laws, h = {short(move.h)} {unit}, T = {short(move.T * 1000.0)} ms"
    if periods > 1:
        heading += f"; periodic laws over {periods} periods"
    figure.suptitle(heading, fontsize="medium")
    return figure


MAX_DRAWN_IMPULSES = 12
"""Jerk impulses drawn (and labelled) per law: a cam table or a spline of many knots jumps
at each of thousands of them, which a figure cannot show (and matplotlib takes minutes to
lay out); the largest are drawn and the title counts the others."""


def drawn_impulses(laws: Sequence[MotionLaw]) -> tuple[list[tuple[int, MotionLaw, Any]], int]:
    """(law index, law, jump) of the impulses to draw, at most MAX_DRAWN_IMPULSES per law
    (the largest |jump|, in the order of tau), and how many were left out."""
    impulses: list[tuple[int, MotionLaw, Any]] = []
    left_out = 0
    for index, law in enumerate(laws):
        jumps = list(law.coefficients.acceleration_jumps)
        if len(jumps) > MAX_DRAWN_IMPULSES:
            left_out += len(jumps) - MAX_DRAWN_IMPULSES
            largest = sorted(jumps, key=lambda jump: abs(jump.jump), reverse=True)
            jumps = sorted(largest[:MAX_DRAWN_IMPULSES], key=lambda jump: jump.tau)
        impulses += [(index, law, jump) for jump in jumps]
    return impulses, left_out


def _draw_impulses(ax, impulses, move: Move, jerk_extent: float) -> None:
    """An arrow from 0 at each jump, its height a share of the jerk axis (not to scale)."""
    if not impulses:
        return
    reach = jerk_extent if jerk_extent > 0.0 else 1.0
    tips = []
    repeated = [(i, jump, k) for i, law, jump in impulses for k in range(periods_of(law))]
    for index, jump, period in repeated:
        color = CURVE_COLORS[index % len(CURVE_COLORS)]
        x = move.T * (jump.tau + period)
        size = move.scale(2) * jump.jump
        tip = math.copysign(reach * (0.9 - 0.2 * (index % 4)), size)
        tips.append(tip)
        arrow = ax.annotate("", xy=(x, tip), xytext=(x, 0.0),
                            arrowprops={"arrowstyle": "-|>", "color": color, "lw": 1.4,
                                        "shrinkA": 0.0, "shrinkB": 0.0})
        arrow.set_gid(GID_IMPULSE)
        side = "left" if jump.tau < 0.5 else "right"
        text = ax.text(x, tip, " " + move.jump_text(size) + " ", color=color,
                       fontsize="x-small", ha=side, va="bottom" if tip > 0 else "top")
        text.set_gid(GID_IMPULSE_LABEL)
    low, high = ax.get_ylim()
    ax.set_ylim(min(low, min(tips) * 1.25), max(high, max(tips) * 1.25))
