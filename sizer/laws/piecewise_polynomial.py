"""Laws made of constant-jerk segments: constant acceleration, trapezoid, double S.

Book sec. 2.1.2, 3.2, 3.4 and 6.2.1. The symmetric laws integrate their first half
exactly from its jerk (or acceleration steps) and mirror it. The trapezoid and the
double S also take a deceleration phase of its own (``alpha_d``, ``beta_d``: sec. 3.2.7
and 3.4 with v0 = v1 = 0): the whole move is then integrated from rest. Left out, or
equal to ``alpha`` and ``beta``, they give the symmetric law and its spec.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

from sizer.laws.base import MotionLaw, Parameter
from sizer.laws.pieces import Piece, constant_jerk_pieces, mirrored

MIN_FRACTION = 1e-6
"""Smallest alpha and beta: C_a = 1/(alpha (1 - alpha)(1 - beta)) and
C_j ~ 1/(alpha^2 beta) stay finite and the pieces (widths down to 1e-12) exact in double
precision; alpha = 1e-6 is a trapezoid with C_v = 1 + 1e-6."""


NO_AUTO_SHARE = ("the deceleration phase is given, not searched: write a number, or leave "
                 "it out for the symmetric law")


def _deceleration_share(name: str, default: float, of: str, what: str) -> Parameter:
    """An optional share of the deceleration phase, by default the acceleration's ``of``."""
    return Parameter(name, default, MIN_FRACTION, 0.5,
                     description=f"{what}; left out, it equals {of} (the symmetric law)",
                     no_auto=NO_AUTO_SHARE)


def _drop_symmetric(values: dict[str, float], given: Mapping[str, float],
                    pairs: tuple[tuple[str, str], ...]) -> dict[str, float]:
    """The canonical values without the deceleration shares equal to their acceleration
    shares (or not given): the symmetric law keeps its parameters and its spec."""
    for dependent, source in pairs:
        if dependent not in given or values[dependent] == values[source]:
            del values[dependent]
    return values


def _shares(params: Mapping[str, float], pairs: tuple[tuple[str, str], ...]) -> list[float]:
    """Every share, the deceleration ones defaulting to their acceleration shares."""
    return [params.get(dependent, params[source]) for dependent, source in pairs]


class Trapezoidal(MotionLaw):
    """Trapezoidal velocity with T_a = alpha*T and T_d = alpha_d*T (sec. 3.2, 3.2.7, 6.2.1).

    ``alpha_d`` defaults to ``alpha`` (the symmetric law, whose spec it leaves out)."""

    law_id = "trapezoidal"
    title = "Trapezoidal velocity"
    parameters = (
        Parameter("alpha", 1 / 3, MIN_FRACTION, 0.5,
                  description="acceleration time over duration, T_a/T; at least 1e-6"),
        _deceleration_share("alpha_d", 1 / 3, "alpha", "deceleration time over duration, T_d/T"),
    )
    _symmetric_pairs = (("alpha_d", "alpha"),)

    @classmethod
    def canonical_params(cls, params: Mapping[str, float]) -> dict[str, float]:
        return _drop_symmetric(super().canonical_params(params), params, cls._symmetric_pairs)

    @property
    def decelerations(self) -> tuple[float]:
        """(alpha_d,): the deceleration share, alpha for the symmetric law."""
        return tuple(_shares(self.params, self._symmetric_pairs))  # type: ignore[return-value]

    def _build(self):
        alpha = self.params["alpha"]
        if "alpha_d" in self.params:  # asymmetric: the book's eq. (3.13) with v0 = v1 = 0
            alpha_d = self.params["alpha_d"]
            v_v = 2.0 / (2.0 - alpha - alpha_d)
            return _joined([(alpha, v_v / alpha, 0.0), (1.0 - alpha - alpha_d, 0.0, 0.0)],
                           [(alpha_d, v_v / alpha_d, 0.0)], alpha_d), 1
        a_max = 1.0 / (alpha * (1.0 - alpha))
        half = [(alpha, a_max, 0.0), (0.5 - alpha, 0.0, 0.0)]
        return mirrored(constant_jerk_pieces(half, end=0.5)), 1

    def closed_form_coefficients(self) -> dict[str, float]:
        a = self.params["alpha"]
        if "alpha_d" in self.params:
            d = self.params["alpha_d"]
            v_v = 2.0 / (2.0 - a - d)  # cruise speed: the area under the trapezoid is 1
            return {
                "C_v": v_v,
                "C_a": v_v / min(a, d),
                "C_v_rms": v_v * math.sqrt(1.0 - 2.0 * (a + d) / 3.0),
                "C_a_rms": v_v * math.sqrt(1.0 / a + 1.0 / d),
            }
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
    """Double S velocity with T_a = alpha*T and T_j = beta*T_a (sec. 3.4, 6.2.1).

    The deceleration phase has T_d = alpha_d*T and T_j2 = beta_d*T_d (sec. 3.4 with
    v0 = v1 = 0); alpha_d and beta_d default to alpha and beta (the symmetric law, whose
    spec leaves them out)."""

    law_id = "double_s"
    title = "Double S"
    parameters = (
        Parameter("alpha", 1 / 3, MIN_FRACTION, 0.5,
                  description="acceleration time over duration, T_a/T; at least 1e-6"),
        Parameter("beta", 1 / 4, MIN_FRACTION, 0.5,
                  description="jerk time over acceleration time, T_j/T_a; at least 1e-6"),
        _deceleration_share("alpha_d", 1 / 3, "alpha", "deceleration time over duration, T_d/T"),
        _deceleration_share("beta_d", 1 / 4, "beta",
                            "jerk time over deceleration time, T_j2/T_d"),
    )
    _symmetric_pairs = (("alpha_d", "alpha"), ("beta_d", "beta"))

    @classmethod
    def canonical_params(cls, params: Mapping[str, float]) -> dict[str, float]:
        return _drop_symmetric(super().canonical_params(params), params, cls._symmetric_pairs)

    @property
    def decelerations(self) -> tuple[float, float]:
        """(alpha_d, beta_d): the deceleration shares, alpha and beta when symmetric."""
        return tuple(_shares(self.params, self._symmetric_pairs))  # type: ignore[return-value]

    @property
    def symmetric(self) -> bool:
        return "alpha_d" not in self.params and "beta_d" not in self.params

    def _build(self):
        alpha, beta = self.params["alpha"], self.params["beta"]
        if not self.symmetric:
            alpha_d, beta_d = self.decelerations
            v_v = 2.0 / (2.0 - alpha - alpha_d)
            return _joined([*_double_s_ramp(alpha, beta, v_v),
                            (1.0 - alpha - alpha_d, 0.0, 0.0)],
                           _double_s_ramp(alpha_d, beta_d, v_v), alpha_d), 2
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
        if not self.symmetric:
            return _asymmetric_double_s_coefficients(a, b, *self.decelerations)
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


def _joined(first: list[tuple[float, float | None, float]],
            last: list[tuple[float, float | None, float]], share: float) -> list[Piece]:
    """A rest-to-rest law from its acceleration and cruise segments on [0, 1 - share] and
    its deceleration phase given as an acceleration from rest over ``share``, reflected
    as q_N(u) = 1 - g(1 - u) (sec. 5.1): short phases next to u = 1 keep their widths
    exact, as the symmetric laws' mirrored halves do."""
    ramp = constant_jerk_pieces(last, end=share)
    return [*constant_jerk_pieces(first, end=1.0 - share), *mirrored(ramp)[len(ramp):]]


def _double_s_ramp(alpha: float, beta: float, v_v: float
                   ) -> list[tuple[float, float | None, float]]:
    """The three constant-jerk segments from rest to speed v_v in time alpha, jerk time
    beta*alpha (sec. 3.4, eqs. 3.30a-c with v0 = 0)."""
    t_j = alpha * beta
    jerk = v_v / (alpha * t_j * (1.0 - beta))
    return [(t_j, None, jerk), (alpha - 2.0 * t_j, None, 0.0), (t_j, None, -jerk)]


def _double_s_ramp_v2(beta: float) -> float:
    """int v^2 over an acceleration phase from rest to speed 1 in time 1, jerk time beta
    (beta = 0: 1/3, the trapezoid's ramp; the symmetric law's C_v_rms gives it)."""
    b = beta
    return 1.0 - (40.0 - 90.0 * b + 65.0 * b * b - 16.0 * b**3) / (60.0 * (1.0 - b) ** 2)


def _asymmetric_double_s_coefficients(a: float, b: float, d: float, e: float
                                      ) -> dict[str, float]:
    """C_v, C_a, C_j and the RMS values of the rest-to-rest double S of shares
    (alpha, beta) = (a, b) accelerating and (alpha_d, beta_d) = (d, e) decelerating."""
    v_v = 2.0 / (2.0 - a - d)
    acc_a, acc_d = v_v / (a * (1.0 - b)), v_v / (d * (1.0 - e))
    v2 = 1.0 - a - d + a * _double_s_ramp_v2(b) + d * _double_s_ramp_v2(e)
    a2 = acc_a**2 * a * (1.0 - 4.0 * b / 3.0) + acc_d**2 * d * (1.0 - 4.0 * e / 3.0)
    return {
        "C_v": v_v,
        "C_a": max(acc_a, acc_d),
        "C_j": max(acc_a / (a * b), acc_d / (d * e)),
        "C_v_rms": v_v * math.sqrt(v2),
        "C_a_rms": math.sqrt(a2),
    }
