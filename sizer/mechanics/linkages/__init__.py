"""1-DOF linkages between the motor and the load: position-dependent transmissions.

Seed 003 (Lores García, Veciana, Jordi: feasibility of motion laws at dead points). A
linkage maps its input angle theta (the crank, driven by the motor) to its output s (a
slider position, m, or a rocker angle, rad): s = f(theta). Its ratio ds/dtheta varies
with theta and vanishes at the dead points, where the inverse kinematics is 0/0. Every
linkage gives f and its exact derivatives; the modules around it invert the motion
(:mod:`inverse_motion`), apply the paper's rules at the dead points and compute the
torque at the crank by virtual work (:mod:`dynamics`).
"""

from __future__ import annotations

from typing import Protocol

import numpy as np

MAX_ORDER = 4
"""Highest derivative d^k s / d theta^k every linkage gives exactly."""


class Linkage(Protocol):
    """The geometry of a 1-DOF linkage from its input angle to its output."""

    @property
    def output_linear(self) -> bool:
        """True when the output is a length (a slider, m); False for an angle (rad)."""
        ...

    def output(self, theta: np.ndarray, order: int = 0) -> np.ndarray:
        """d^order s / d theta^order at the input angles theta (order 0..MAX_ORDER)."""
        ...

    def input_of(self, s: np.ndarray, half: int) -> np.ndarray:
        """The input angle giving output s on one half of the input's turn: ``half``
        +1 or -1 picks one of the two assemblies of the crank between the dead points
        (the half-turn where ds/dtheta has that sign). UserError if s is out of range."""
        ...

    def dead_points(self) -> np.ndarray:
        """The input angles in [-pi, pi) where ds/dtheta = 0 (the output's extremes)."""
        ...

    def output_range(self) -> tuple[float, float]:
        """The least and largest output over a turn of the input (the dead points')."""
        ...


def outside_range(s: np.ndarray, low: float, high: float) -> float | None:
    """The first output of ``s`` outside [low, high] by more than rounding (1e-12 of the
    span), NaN included, or None when all are inside."""
    span = high - low
    bad = ~((s >= low - 1e-12 * span) & (s <= high + 1e-12 * span))
    return float(s[bad].flat[0]) if np.any(bad) else None
