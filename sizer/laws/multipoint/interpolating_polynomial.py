"""The polynomial through n + 1 points (book sec. 4.1), with optional end conditions.

Kind ``interpolating_polynomial``. Given the points (t_k, q_k), k = 0..n, there is one
polynomial of degree n through them (eq. 4.1); conditions on the velocity, acceleration
or jerk at the first and last point (``start: {velocity: 0, acceleration: 0}``) raise the
degree by one each, as in the book's system with v_0, a_0, v_n, a_n (degree n + 4).

The book solves for the monomial coefficients with the Vandermonde matrix (eq. 4.2),
whose condition number grows so fast (Example 4.1: 1.2e8 for n = 10, 9.1e16 for n = 20)
that the coefficients lose every digit by n = 20. Here the unknowns are the coefficients
of a Chebyshev series on [t_0, t_n] (numpy.polynomial.Chebyshev): the same polynomial,
computed from a system whose columns are bounded by 1 on the interval, and evaluated, with
its derivatives, in that basis. The polynomial is still the unique one through the
points, so it keeps the book's drawback that no basis removes: the *oscillations*
between the points (Runge's phenomenon) grow with n, most for evenly spaced points. The
law's report gives ``lebesgue_constant`` (max over the interval of sum |l_k(t)|, the
factor by which an error in the positions may grow between the points: about 30 for 11
evenly spaced points, 1.1e4 for 21) and ``overshoot`` (how far the curve leaves the
range of the positions, a share of that range).

Errors: fewer than two points, times that do not increase, a degree above MAX_DEGREE
(the book's table of condition numbers stops at 20, where the monomial system is
singular in double precision; a cubic spline or a B-spline is the book's answer), and a
system too ill-conditioned to be solved (points crowded against each other).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from sizer.errors import UserError
from sizer.laws.multipoint import Curve, FittedCurve
from sizer.laws.multipoint.fields import conditions, points, refuse_unknown

if TYPE_CHECKING:
    from numpy.polynomial import Chebyshev

KIND = "interpolating_polynomial"
FIELDS = ("points", "times", "positions", "start", "end")

MAX_DEGREE = 20
"""Highest degree of a polynomial law of sec. 4.1 and 4.2 (the book's table of the
Vandermonde condition numbers ends at n = 20)."""

MAX_CONDITION = 1e12
"""Condition number (of the row-scaled Chebyshev system) beyond which the polynomial is
refused: fewer than 4 of the 16 digits of the data would survive."""

MAX_PIECES = 32
"""Most pieces a law of these kinds is cut into: the data's times, or for more points
MAX_PIECES equal parts (the curve is one function; the cuts only bound the scans for its
peaks: sizer.laws.coefficients scans each piece on its own grid)."""

_SCAN = 2_049
"""Points at which the Lebesgue function and the overshoot are sampled."""


@dataclass(eq=False)
class ChebyshevCurve:
    """One polynomial over [x[0], x[-1]] as a Chebyshev series on that interval, with
    every derivative exact (the series differentiated in its own basis); ``x`` are the
    data's times, the breakpoints the law's pieces end at (the polynomial is the same on
    both sides of each)."""

    x: np.ndarray
    series: Chebyshev
    _derivatives: dict[int, Chebyshev] = field(default_factory=dict, repr=False)

    def __call__(self, t: np.ndarray, nu: int = 0) -> np.ndarray:
        derivative = self._derivatives.get(nu)
        if derivative is None:
            derivative = self.series.deriv(nu) if nu else self.series
            self._derivatives[nu] = derivative
        return np.asarray(derivative(np.asarray(t, dtype=float)), dtype=float)


def breakpoints(t: np.ndarray) -> np.ndarray:
    """The ends of the law's pieces: the times ``t``, or MAX_PIECES equal parts of
    [t_0, t_n] when there are more."""
    if len(t) <= MAX_PIECES + 1:
        return np.asarray(t, dtype=float)
    cuts = np.linspace(t[0], t[-1], MAX_PIECES + 1)
    cuts[0], cuts[-1] = t[0], t[-1]
    return cuts


def build_interpolating_polynomial(fields: Mapping[str, Any]) -> FittedCurve:
    """The YAML mapping of an ``interpolating_polynomial`` law (module docstring)."""
    refuse_unknown(fields, FIELDS, KIND)
    t, q = points(fields, minimum=2)
    ends = [_end_conditions(fields, key) for key in ("start", "end")]
    degree = len(t) - 1 + sum(len(e) for e in ends)
    if degree > MAX_DEGREE:
        raise UserError(f"a polynomial through {len(t)} points"
                        f"{_with_conditions(ends)} has degree {degree}: the limit is "
                        f"{MAX_DEGREE} (book sec. 4.1: the oscillations and the errors grow "
                        f"with the degree); use a cubic_spline or a bspline",
                        field="points" if "points" in fields else "positions")
    series = interpolating_series(t, q, ends[0], ends[1])
    curve = ChebyshevCurve(breakpoints(t), series)
    report = {"degree": float(degree), "lebesgue_constant": lebesgue_constant(t, ends),
              "overshoot": overshoot(curve, q)}
    return FittedCurve(curve, report)


def _end_conditions(fields: Mapping[str, Any], key: str) -> dict[int, float]:
    found = conditions(fields, key, highest=3)
    if 0 in found:
        raise UserError(f"the {key} position is the {'first' if key == 'start' else 'last'} "
                        f"point's; give velocity, acceleration or jerk",
                        field=f"{key}.position")
    return found


def _with_conditions(ends: list[dict[int, float]]) -> str:
    count = sum(len(e) for e in ends)
    return f" and {count} end condition{'s' if count > 1 else ''}" if count else ""


def interpolating_series(t: np.ndarray, q: np.ndarray, start: Mapping[int, float],
                         end: Mapping[int, float]) -> Chebyshev:
    """The polynomial through (t_k, q_k) with the derivative conditions {order: value} at
    t_0 and t_n, as a Chebyshev series on [t_0, t_n]; UserError when the system is too
    ill-conditioned."""
    from numpy.polynomial import Chebyshev
    from numpy.polynomial import chebyshev as cheb

    t = np.asarray(t, dtype=float)
    q = np.asarray(q, dtype=float)
    degree = len(t) - 1 + len(start) + len(end)
    half = 0.5 * (t[-1] - t[0])
    x = np.clip((t - t[0]) / half - 1.0, -1.0, 1.0)
    rows = [cheb.chebvander(x, degree)]
    rhs = [q]
    # d^r/dt^r T_j(x(t)) = T_j^(r)(x) / half^r: the row of T_j^(r)(+-1) for value * half^r
    unit = np.eye(degree + 1)
    for side, given in ((-1.0, start), (1.0, end)):
        for order, value in sorted(given.items()):
            rows.append(np.array([[cheb.chebval(side, cheb.chebder(unit[j], order))
                                   for j in range(degree + 1)]]))
            rhs.append(np.array([value * half ** order]))
    matrix, vector = np.vstack(rows), np.concatenate(rhs)
    scale = np.max(np.abs(matrix), axis=1)
    matrix, vector = matrix / scale[:, None], vector / scale
    condition = float(np.linalg.cond(matrix))
    if not condition < MAX_CONDITION:
        raise UserError(f"the points make an ill-conditioned system (condition number "
                        f"{condition:.3g}): times too close together for a polynomial of "
                        f"degree {degree}; use a cubic_spline", field="points")
    coefficients = np.linalg.solve(matrix, vector)
    return Chebyshev(coefficients, domain=[float(t[0]), float(t[-1])])


def lebesgue_constant(t: np.ndarray, ends: list[dict[int, float]] | None = None) -> float:
    """max over [t_0, t_n] of sum_k |l_k(t)|, l_k the polynomial of the law's degree that
    is 1 at t_k, 0 at the other points and whose end conditions are all 0: the most an
    error of 1 in the positions moves the curve between the points."""
    start, end = (ends or [{}, {}])
    zeros = ({k: 0.0 for k in start}, {k: 0.0 for k in end})
    grid = np.linspace(t[0], t[-1], _SCAN)
    total = np.zeros_like(grid)
    for k in range(len(t)):
        unit = np.zeros(len(t))
        unit[k] = 1.0
        total += np.abs(interpolating_series(t, unit, *zeros)(grid))
    return float(np.max(total))


def overshoot(curve: Curve, q: np.ndarray) -> float:
    """How far the curve leaves [min q_k, max q_k], as a share of that range (0 inside;
    the points' spread, or 1 when they are all equal)."""
    grid = np.linspace(curve.x[0], curve.x[-1], _SCAN)
    values = curve(grid)
    low, high = float(np.min(q)), float(np.max(q))
    span = high - low or 1.0
    return float(max(0.0, low - float(np.min(values)), float(np.max(values)) - high) / span)



RUNGE_OVERSHOOT = 0.1
"""``overshoot`` (a share of the positions' range) above which :func:`oscillation_warning`
speaks."""

RUNGE_LEBESGUE = 100.0
"""``lebesgue_constant`` above which :func:`oscillation_warning` speaks: an error in the
positions may grow a hundredfold between the points."""


def oscillation_warning(report: Mapping[str, float]) -> str | None:
    """The warning a law of these kinds deserves from its report (the book's Runge
    phenomenon, sec. 4.1 and Fig. 4.5), or None: for the design loader to show at the
    law's line (the core never prints)."""
    swing = report.get("overshoot", 0.0)
    amplification = report.get("lebesgue_constant", 0.0)
    if swing <= RUNGE_OVERSHOOT and amplification <= RUNGE_LEBESGUE:
        return None
    parts = []
    if swing > RUNGE_OVERSHOOT:
        parts.append(f"swings {100 * swing:.3g} % of the points' range beyond them")
    if amplification > RUNGE_LEBESGUE:
        parts.append(f"amplifies an error in the positions up to {amplification:.3g} "
                     f"times between them (Lebesgue constant)")
    return (f"the curve {' and '.join(parts)}: it oscillates between the points (Runge's "
            f"phenomenon, book sec. 4.1 and Fig. 4.5); a cubic_spline or bspline through "
            f"the same points oscillates less")
