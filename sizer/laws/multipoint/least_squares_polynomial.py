"""Orthogonal polynomials fitted by least squares to n + 1 points (book sec. 4.2).

Kind ``least_squares_polynomial``. The curve q(t) = sum_{j=0..m} a_j p_j (eq. 4.3) of
degree m (``degree``, at most the number of points less one) minimizes the total square
error E^2 = sum_k w_k (q_k - q(t_k))^2 (``weights`` w_k > 0, default all 1; the book's
case). The p_j are orthogonal on the points (eq. 4.4), built as the book builds them,
by Forsythe's recurrence

    p_j = (tau - alpha_j) p_{j-1} - beta_{j-1} p_{j-2},
    alpha_j = sum w tau_k p_{j-1}(tau_k)^2 / sum w p_{j-1}(tau_k)^2,
    beta_j = sum w p_j(tau_k)^2 / sum w p_{j-1}(tau_k)^2,

so that each a_j = sum w q_k p_j(tau_k) / sum w p_j(tau_k)^2 needs no system. The
recurrence runs in the normalized time tau = (t - t_0) / (t_n - t_0) (the book's
variable for Examples 4.3-4.5; Example 4.2 writes it in t, which spans the same
polynomials: the fitted curve is the same) and every p_j is kept as a Chebyshev series in
tau (numpy.polynomial), so the curve and all its derivatives are evaluated in that basis.

Ends (the book's method of Clenshaw and Hayes, Examples 4.3-4.5). By default the ends
are free (Example 4.2): the curve passes near the first and last points, not through
them, and its end velocities are what the fit gives. With ``through_ends: true`` the
curve passes through the first and last points (Example 4.3): q~ = q - q_a (1 - tau) -
q_b tau is fitted with p_0 = tau (1 - tau). ``start: {velocity: 0}`` adds a null velocity
at the first point (Example 4.4: q~ = q - q_a (1 - tau^2) - q_b tau^2, p_0 = tau^2 (1 -
tau)), ``start: {velocity: 0, acceleration: 0}`` a null acceleration as well (Example
4.5: tau^3); ``end`` does the same at the last point, with the factor (1 - tau)^2 or
(1 - tau)^3 in p_0. With r_a = 1, 2, 3 conditions at the start and r_b at the end,
p_0 = tau^r_a (1 - tau)^r_b and the part taken out is q_a + (q_b - q_a) H(tau), H the
polynomial of least degree with H(0) = 0, H(1) = 1 and the null derivatives (tau^r_a
when r_b = 1, as in the book; 3 tau^2 - 2 tau^3 for a rest-to-rest law). Any end
condition makes the curve pass through both end points. Only null velocities and
accelerations are the book's; a null acceleration comes with a null velocity.

A law for a rest-to-rest move is ``start: {velocity: 0}, end: {velocity: 0}``.

Degree. With free ends the n + 1 points fix a polynomial of degree up to n (degree n:
the interpolating polynomial of sec. 4.1). With fixed ends p_0 vanishes at both end
points, so only the n - 1 inner points determine the a_j: degree at most n - 2 (the
book's Examples 4.3-4.5 find a_4 = 0 with 4 inner points, "the most appropriate degree
... is three"); a higher degree is refused. The report gives the residuals at the points
(``max_residual``, ``rms_residual``) and the coefficients a_j.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from math import comb
from typing import TYPE_CHECKING, Any

import numpy as np

from sizer.errors import UserError
from sizer.laws.multipoint import FittedCurve
from sizer.laws.multipoint.fields import (
    boolean,
    conditions,
    integer,
    numbers,
    points,
    refuse_unknown,
)
from sizer.laws.multipoint.interpolating_polynomial import (
    MAX_DEGREE,
    ChebyshevCurve,
    breakpoints,
    overshoot,
)

if TYPE_CHECKING:
    from numpy.polynomial import Chebyshev

KIND = "least_squares_polynomial"
FIELDS = ("points", "times", "positions", "degree", "weights", "through_ends", "start",
          "end")


@dataclass(frozen=True)
class OrthogonalFit:
    """The book's quantities of a fit: the orthogonal polynomials p_j (Chebyshev series
    over the variable's domain), the recurrence's alpha_j (j = 1..m) and beta_j (j =
    1..m-1), the coefficients a_j (0 where p_j vanishes at every point, as the book
    writes a_4 = 0) and the fitted sum sum a_j p_j."""

    polynomials: tuple[Chebyshev, ...]
    alphas: tuple[float, ...]
    betas: tuple[float, ...]
    coefficients: tuple[float, ...]
    fitted: Chebyshev


def orthogonal_fit(s: np.ndarray, values: np.ndarray, degree: int, first: Chebyshev,
                   weights: np.ndarray | None = None) -> OrthogonalFit:
    """Forsythe's orthogonal polynomials p_0 = ``first``, ..., p_degree on the abscissas
    ``s`` (in the variable of ``first``'s domain) and the least-squares coefficients of
    ``values`` (book sec. 4.2)."""
    w = np.ones(len(s)) if weights is None else np.asarray(weights, dtype=float)
    variable = first.identity(domain=first.domain, window=first.window)
    polys = [first]
    at = [first(s)]
    norms = [float(np.sum(w * at[0] ** 2))]
    alphas: list[float] = []
    betas: list[float] = []
    for j in range(1, degree + 1):
        alpha = float(np.sum(w * s * at[-1] ** 2)) / norms[-1]
        nxt = (variable - alpha) * polys[-1]
        if j >= 2:
            beta = norms[-1] / norms[-2]
            betas.append(beta)
            nxt = nxt - beta * polys[-2]
        alphas.append(alpha)
        polys.append(nxt)
        at.append(nxt(s))
        norms.append(float(np.sum(w * at[-1] ** 2)))
    # a p_j that vanishes at every point (its values there rounding next to its size on
    # the interval) has no coefficient: the book's a_4 = 0 of Examples 4.3-4.5
    total = float(np.sum(w))
    coefficients = [float(np.sum(w * values * a)) / g
                    if np.sqrt(g / total) > 1e-10 * float(np.max(np.abs(p.coef))) else 0.0
                    for a, g, p in zip(at, norms, polys, strict=True)]
    fitted = sum((c * p for c, p in zip(coefficients, polys, strict=True)),
                 start=0.0 * first)
    return OrthogonalFit(tuple(polys), tuple(alphas), tuple(betas), tuple(coefficients),
                         fitted)


def smoothstep(start: int, end: int) -> Chebyshev:
    """H(tau) on [0, 1]: the polynomial of least degree with H(0) = 0, H(1) = 1 and its
    first ``start`` - 1 derivatives null at 0, ``end`` - 1 at 1:
    tau^start sum_{i < end} C(start - 1 + i, i) (1 - tau)^i."""
    tau, one = _tau(), _tau() * 0.0 + 1.0
    total = sum((comb(start - 1 + i, i) * (one - tau) ** i for i in range(end)),
                start=0.0 * one)
    return tau ** start * total


def _tau() -> Chebyshev:
    from numpy.polynomial import Chebyshev

    return Chebyshev.identity(domain=[0.0, 1.0])


def build_least_squares_polynomial(fields: Mapping[str, Any]) -> FittedCurve:
    """The YAML mapping of a ``least_squares_polynomial`` law (module docstring)."""
    from numpy.polynomial import Chebyshev

    refuse_unknown(fields, FIELDS, KIND)
    t, q = points(fields, minimum=2)
    degree = integer(fields, "degree", low=0, high=MAX_DEGREE)
    weights = _weights(fields, len(t))
    start, end = (_null_conditions(fields, key) for key in ("start", "end"))
    through = boolean(fields, "through_ends", bool(start or end))
    if not through and (start or end):
        raise UserError("an end condition makes the curve pass through both end points: "
                        "through_ends cannot be false with start or end",
                        field="through_ends")
    tau = (t - t[0]) / (t[-1] - t[0])
    tau[-1] = 1.0
    where = "points" if "points" in fields else "positions"
    if through:
        inner = len(t) - 2
        if inner < 1:
            raise UserError("with the ends held the fit needs an inner point: at least 3 "
                            "points, got 2", field=where)
        if degree > inner - 1:
            raise UserError(_too_high(degree, inner, len(t), inner - 1, "inner points "
                                      "(the curve is held at both end points)"),
                            field="degree")
        r_a, r_b = 1 + len(start), 1 + len(end)
        held = q[0] + (q[-1] - q[0]) * smoothstep(r_a, r_b)
        first = _tau() ** r_a * (1.0 - _tau()) ** r_b
    else:
        if degree > len(t) - 1:
            raise UserError(_too_high(degree, len(t), len(t), len(t) - 1, "points"),
                            field="degree")
        held = 0.0 * _tau()
        first = _tau() * 0.0 + 1.0
    fit = orthogonal_fit(tau, q - held(tau), degree, first, weights)
    total = fit.fitted + held
    series = Chebyshev(total.coef, domain=[float(t[0]), float(t[-1])])
    curve = ChebyshevCurve(breakpoints(t), series)
    residual = curve(t) - q
    if not np.all(np.isfinite(residual)):
        raise UserError("the law these data make is not finite in double precision (the "
                        "fit overflows): the values are too large", field=where)
    report = {"degree": float(degree), "samples": float(len(t)),
              "max_residual": float(np.max(np.abs(residual))),
              "rms_residual": float(np.sqrt(np.mean(residual ** 2))),
              "overshoot": overshoot(curve, q)}
    report.update({f"a_{j}": a for j, a in enumerate(fit.coefficients)})
    return FittedCurve(curve, report)


def _too_high(degree: int, count: int, total: int, highest: int, what: str) -> str:
    return (f"degree {degree} is too high for {total} points: {count} {what} determine a "
            f"polynomial of degree at most {highest} (book sec. 4.2: a higher p_j "
            f"vanishes at every point)")


def _weights(fields: Mapping[str, Any], count: int) -> np.ndarray | None:
    if "weights" not in fields or fields["weights"] is None:
        return None
    w = numbers(fields, "weights", length=count)
    for i, value in enumerate(w):
        if not value > 0.0:
            raise UserError(f"must be positive, got {value:g}", field=f"weights[{i}]")
    return w / np.max(w)


def _null_conditions(fields: Mapping[str, Any], key: str) -> Sequence[int]:
    """The null derivatives at one end: () or (1,) or (1, 2); UserError for a value that
    is not 0 or an acceleration without the velocity."""
    found = conditions(fields, key, highest=2)
    names = {1: "velocity", 2: "acceleration"}
    if 0 in found:
        raise UserError("the end positions are the points' (give through_ends: true)",
                        field=f"{key}.position")
    for order, value in found.items():
        if value != 0.0:
            raise UserError(f"the book's orthogonal polynomials impose null end "
                            f"conditions only, got {value:g}; for a given value use an "
                            f"interpolating_polynomial", field=f"{key}.{names[order]}")
    if 2 in found and 1 not in found:
        raise UserError("a null acceleration comes with a null velocity (book sec. 4.2: "
                        "p_0 = tau^3 (1 - tau)): write {velocity: 0, acceleration: 0}",
                        field=f"{key}.acceleration")
    return tuple(sorted(found))
