"""The fifteen-segment law: a double S with a trapezoidal jerk (book sec. 3.5).

Rest to rest with T = 1, h = 1 and symmetric phases (v0 = v1 = 0, T_d = T_a), the
durations of eq. (3.43) are given as shares: T_a = alpha, T_j = beta*T_a and
T_s = gamma*T_j. The snap q^(4) is piecewise constant (+-s_max, 0) over the fifteen
segments of Fig. 3.30; the first half is integrated exactly from rest and mirrored.
Validity (3.44)-(3.47) is the ranges beta, gamma <= 1/2 and alpha <= 1/2.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

from sizer.laws.base import MotionLaw, Parameter, Piece, mirrored
from sizer.laws.pieces import trig_poly_piece
from sizer.laws.piecewise_polynomial import MIN_FRACTION


def constant_snap_pieces(segments: Sequence[tuple[float, float]], end: float) -> list[Piece]:
    """Quartic pieces from (duration, snap) segments, integrated exactly from rest at 0.

    Zero-length segments are skipped; the last piece ends exactly at ``end``.
    """
    pieces = []
    t = q = v = a = j = 0.0
    for d, s in segments:
        if d <= 0.0:
            continue
        pieces.append(trig_poly_piece(t, t + d, (q, v, a / 2.0, j / 6.0, s / 24.0), origin=t))
        q, v, a, j = (q + v * d + a * d**2 / 2.0 + j * d**3 / 6.0 + s * d**4 / 24.0,
                      v + a * d + j * d**2 / 2.0 + s * d**3 / 6.0,
                      a + j * d + s * d**2 / 2.0,
                      j + s * d)
        t += d
    pieces[-1] = replace(pieces[-1], end=end)
    return pieces


def peaks(alpha: float, beta: float, gamma: float) -> tuple[float, float, float, float]:
    """(v_max, a_max, j_max, s_max) of the normalized law: the inverse of eq. (3.43)
    with q1 - q0 = 1, T = 1 and T_v = 1 - 2 T_a."""
    t_a, t_j = alpha, alpha * beta
    t_s = gamma * t_j
    v = 1.0 / (1.0 - alpha)
    a = v / (t_a - t_j)
    j = a / (t_j - t_s)
    return v, a, j, j / t_s


class FifteenSegments(MotionLaw):
    """Fifteen-segment trajectory: piecewise constant snap, continuous jerk (sec. 3.5)."""

    law_id = "fifteen_segments"
    title = "Fifteen segments"
    parameters = (
        Parameter("alpha", 1 / 3, MIN_FRACTION, 0.5,
                  description="acceleration time over duration, T_a/T; at least 1e-6"),
        Parameter("beta", 1 / 4, MIN_FRACTION, 0.5,
                  description="jerk time over acceleration time, T_j/T_a; at least 1e-6"),
        Parameter("gamma", 1 / 4, MIN_FRACTION, 0.5,
                  description="snap time over jerk time, T_s/T_j; at least 1e-6 (toward "
                              "0 the double S)"),
    )

    def _build(self):
        alpha, beta, gamma = (self.params[k] for k in ("alpha", "beta", "gamma"))
        t_a, t_j = alpha, alpha * beta
        t_s = gamma * t_j
        s = peaks(alpha, beta, gamma)[3]
        half = [
            (t_s, s), (t_j - 2.0 * t_s, 0.0), (t_s, -s),     # jerk up and down: a to a_max
            (t_a - 2.0 * t_j, 0.0),                         # constant acceleration
            (t_s, -s), (t_j - 2.0 * t_s, 0.0), (t_s, s),     # a back to 0
            (0.5 - t_a, 0.0),                               # half the constant velocity
        ]
        return mirrored(constant_snap_pieces(half, end=0.5)), 3

    def closed_form_coefficients(self) -> dict[str, float]:
        """Peaks from eq. (3.43); the RMS values by integrating the segments (sympy):
        int a^2 = 2 a_max^2 T_a (1 - 2 beta + 2 beta R(gamma)) with R the double S
        ramp's share, and int v^2 = v_max^2 (1 - 2 alpha + 2 alpha r(beta, gamma))."""
        a_, b, g = (self.params[k] for k in ("alpha", "beta", "gamma"))
        v, acc, jerk, _ = peaks(a_, b, g)
        ramp = (20.0 - 30.0 * g - 5.0 * g * g + 16.0 * g**3) / (60.0 * (1.0 - g) ** 2)
        h = (1.0 - g) ** 2
        r = (420.0 * h - 630.0 * b * h
             - b * b * (210.0 * g**4 - 630.0 * g**3 + 735.0 * g * g - 420.0 * g + 105.0)
             - b**3 * (64.0 * g**5 - 427.0 * g**4 + 945.0 * g**3 - 1190.0 * g * g
                       + 945.0 * g - 336.0)) / (1260.0 * (1.0 - b) ** 2 * h)
        return {
            "C_v": v,
            "C_a": acc,
            "C_j": jerk,
            "C_v_rms": v * (1.0 - 2.0 * a_ + 2.0 * a_ * r) ** 0.5,
            "C_a_rms": acc * (2.0 * a_ * (1.0 - 2.0 * b + 2.0 * b * ramp)) ** 0.5,
        }
