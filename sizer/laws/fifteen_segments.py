"""The fifteen-segment law: a double S with a trapezoidal jerk (book sec. 3.5).

Rest to rest with T = 1, h = 1 and symmetric phases (v0 = v1 = 0, T_d = T_a), the
durations of eq. (3.43) are given as shares: T_a = alpha, T_j = beta*T_a and
T_s = gamma*T_j. The snap q^(4) is piecewise constant (+-s_max, 0) over the fifteen
segments of Fig. 3.30; each piece of the first half starts from the closed-form state
of eq. (3.48) at its start (:func:`ramp_states`), and the half is mirrored.
Validity (3.44)-(3.47) is the ranges beta, gamma <= 1/2 and alpha <= 1/2.
"""

from __future__ import annotations

from sizer.laws.base import MotionLaw, Parameter
from sizer.laws.pieces import mirrored, trig_poly_piece
from sizer.laws.piecewise_polynomial import MIN_FRACTION

MIN_SHARE = 1e-3
"""Smallest beta and gamma: the jerk varies linearly over T_s = alpha beta gamma, and a
piece end is placed to an ulp of its position (~alpha 1e-16), so the jerk at the piece
ends is exact to about 1e-16/(beta gamma): 1e-10 at beta = gamma = 1e-3."""


def ramp_states(alpha: float, beta: float, gamma: float
                ) -> list[tuple[float, tuple[float, float, float, float], float]]:
    """(start, (q, v, a, j) at the start, snap) of each segment of the acceleration phase.

    The states are the book's closed forms (3.48a)-(3.48d) at the segment ends, and for the
    second half of the phase the symmetry of the velocity ramp: v(T_a - u) = v_max - v(u),
    q(T_a - u) = v_max (T_a/2 - u) + q(u), a and -j equal. Each piece starts from exact
    values, so narrow segments with a large snap do not accumulate integration drift.
    """
    v_max, a_max, j_max, s = peaks(alpha, beta, gamma)
    t_a, t_j = alpha, alpha * beta
    t_s = gamma * t_j
    t2 = t_j - t_s
    first = [
        (0.0, (0.0, 0.0, 0.0, 0.0), s),
        (t_s, (j_max * t_s**3 / 24.0, j_max * t_s**2 / 6.0, j_max * t_s / 2.0, j_max), 0.0),
        (t2, (j_max / 24.0 * (2.0 * t2 - t_s) * (2.0 * t2 * (t2 - t_s) + t_s**2),
              j_max * t_s**2 / 6.0 + j_max / 2.0 * t2 * (t2 - t_s),
              j_max * (t2 - t_s / 2.0), j_max), -s),
        (t_j, (a_max / 12.0 * (2.0 * t_j**2 - t_j * t_s + t_s**2), a_max * t_j / 2.0, a_max,
               0.0), 0.0),
    ]
    snaps_after = {t_j: -s, t2: 0.0, t_s: s}  # the snap after the reflected boundary
    second = [(t_a - u, (v_max * (t_a / 2.0 - u) + q, v_max - v, a, -j), snaps_after[u])
              for u, (q, v, a, j), _ in reversed(first[1:])]
    return [*first, *second, (t_a, (v_max * t_a / 2.0, v_max, 0.0, 0.0), 0.0)]


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
        Parameter("beta", 1 / 4, MIN_SHARE, 0.5,
                  description="jerk time over acceleration time, T_j/T_a; at least 1e-3"),
        Parameter("gamma", 1 / 4, MIN_SHARE, 0.5,
                  description="snap time over jerk time, T_s/T_j; at least 1e-3 (toward "
                              "0 the double S)"),
    )

    def _build(self):
        states = ramp_states(*(self.params[k] for k in ("alpha", "beta", "gamma")))
        ends = [start for start, _, _ in states[1:]] + [0.5]
        half = [trig_poly_piece(start, end, (q, v, a / 2.0, j / 6.0, s / 24.0), origin=start)
                for (start, (q, v, a, j), s), end in zip(states, ends, strict=True)
                if end > start]
        return mirrored(half), 3

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
