"""Laws made of constant-jerk segments: constant acceleration, trapezoid, double S.

Book sec. 2.1.2, 3.2, 3.4 and 6.2.1. Each is symmetric; the first half is integrated
exactly from its jerk (or acceleration steps) and mirrored.
"""

from __future__ import annotations

import math

from sizer.laws.base import MotionLaw, Parameter, mirrored
from sizer.laws.pieces import constant_jerk_pieces

MIN_FRACTION = 1e-6
"""Smallest alpha and beta: C_a = 1/(alpha (1 - alpha)(1 - beta)) and
C_j ~ 1/(alpha^2 beta) stay finite and the pieces (widths down to 1e-12) exact in double
precision; alpha = 1e-6 is a trapezoid with C_v = 1 + 1e-6."""


class Trapezoidal(MotionLaw):
    """Trapezoidal velocity with T_a = alpha*T (sec. 3.2, 6.2.1)."""

    law_id = "trapezoidal"
    title = "Trapezoidal velocity"
    parameters = (
        Parameter("alpha", 1 / 3, MIN_FRACTION, 0.5,
                  description="acceleration time over duration, T_a/T; at least 1e-6"),
    )

    def _build(self):
        alpha = self.params["alpha"]
        a_max = 1.0 / (alpha * (1.0 - alpha))
        half = [(alpha, a_max, 0.0), (0.5 - alpha, 0.0, 0.0)]
        return mirrored(constant_jerk_pieces(half, end=0.5)), 1

    def closed_form_coefficients(self) -> dict[str, float]:
        a = self.params["alpha"]
        return {
            "C_v": 1.0 / (1.0 - a),
            "C_a": 1.0 / (a * (1.0 - a)),
            "C_v_rms": math.sqrt(1.0 - 4.0 * a / 3.0) / (1.0 - a),
            "C_a_rms": math.sqrt(2.0 * a) / (a * (1.0 - a)),
        }


class ConstantAcceleration(MotionLaw):
    """Constant acceleration (triangular velocity, bang-bang), sec. 2.1.2: alpha = 1/2."""

    law_id = "constant_acceleration"
    title = "Constant acceleration"

    def _build(self):
        half = [(0.5, 4.0, 0.0)]
        return mirrored(constant_jerk_pieces(half, end=0.5)), 1

    def closed_form_coefficients(self) -> dict[str, float]:
        return {"C_v": 2.0, "C_a": 4.0, "C_v_rms": 2.0 / math.sqrt(3.0), "C_a_rms": 4.0}


class DoubleS(MotionLaw):
    """Double S velocity with T_a = alpha*T and T_j = beta*T_a (sec. 3.4, 6.2.1)."""

    law_id = "double_s"
    title = "Double S"
    parameters = (
        Parameter("alpha", 1 / 3, MIN_FRACTION, 0.5,
                  description="acceleration time over duration, T_a/T; at least 1e-6"),
        Parameter("beta", 1 / 4, MIN_FRACTION, 0.5,
                  description="jerk time over acceleration time, T_j/T_a; at least 1e-6"),
    )

    def _build(self):
        alpha, beta = self.params["alpha"], self.params["beta"]
        a_max = 1.0 / (alpha * (1.0 - alpha) * (1.0 - beta))
        t_j = alpha * beta
        jerk = a_max / t_j
        half = [
            (t_j, None, jerk),
            (alpha - 2.0 * t_j, None, 0.0),
            (t_j, None, -jerk),
            (0.5 - alpha, 0.0, 0.0),
        ]
        return mirrored(constant_jerk_pieces(half, end=0.5)), 2

    def closed_form_coefficients(self) -> dict[str, float]:
        a, b = self.params["alpha"], self.params["beta"]
        return {
            "C_v": 1.0 / (1.0 - a),
            "C_a": 1.0 / (a * (1.0 - a) * (1.0 - b)),
            "C_j": 1.0 / (a * a * b * (1.0 - a) * (1.0 - b)),
            "C_a_rms": math.sqrt((6.0 - 8.0 * b) / (3.0 * a)) / ((1.0 - a) * (1.0 - b)),
            # int v^2 over the seven segments (beta = 0 gives the trapezoid's value)
            "C_v_rms": math.sqrt(
                (30.0 * (1.0 - b) ** 2 - a * (40.0 - 90.0 * b + 65.0 * b * b - 16.0 * b**3))
                / 30.0) / ((1.0 - a) * (1.0 - b)),
        }
