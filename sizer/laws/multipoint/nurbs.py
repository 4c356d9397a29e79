"""NURBS trajectories (slides "NURBS"): a B-spline with one weight per control point,

    S(t) = sum_j R_j(t) A_j,   R_j(t) = N_j(t) W_j / sum_i N_i(t) W_i,

with the B-spline's basis functions N_j of order k. scipy has no rational splines, so the
curve is a small class here: numerator a(t) = sum W_j A_j N_j(t) and denominator
w(t) = sum W_j N_j(t) are scipy BSplines, and the derivatives follow exactly from
a = S w by Leibniz: S^(m) = (a^(m) - sum_{i=1..m} C(m, i) w^(i) S^(m-i)) / w. The curve is
rational, not piecewise polynomial, so it is a Curve but not a PPoly.

For fixed weights every condition S^(m)(t) = v is linear in the control points (the rows
are R_j^(m)(t), by the same recursion on the basis), so via-points and kinematic
conditions are solved as for the B-spline (slides: "si sceglie il vettore dei pesi ...,
si imposta il sistema").
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from sizer.errors import UserError
from sizer.laws.multipoint import fields as F
from sizer.laws.multipoint.bsplines import (
    BSPLINE_FIELDS,
    Basis,
    basis_matrix,
    check_knots,
    default_knots,
    direct_counts,
    read_direct,
    read_knots,
    solve_control_points,
)
from sizer.laws.multipoint.poly_splines import Condition, end_conditions
from sizer.numerics.arrays import sorted_unique


def _leibniz_quotient(num: list[np.ndarray], den: list[np.ndarray]) -> list[np.ndarray]:
    """Derivatives 0..m of num/den from those of num and den (den[0] > 0); num[i] may be
    a matrix with one column per basis function, den[i] a vector (broadcast by row)."""
    out: list[np.ndarray] = []
    w = den[0]
    for m in range(len(num)):
        acc = num[m].copy()
        for i in range(1, m + 1):
            acc -= math.comb(m, i) * _rows(den[i], acc) * out[m - i]
        out.append(acc / _rows(w, acc))
    return out


def _rows(v: np.ndarray, like: np.ndarray) -> np.ndarray:
    return v[:, None] if like.ndim == 2 else v


class NURBS:
    """S(t) = sum W_j A_j N_j(t) / sum W_j N_j(t) over the base interval of the knots,
    with exact derivatives of any order (``__call__(t, nu)``), vectorized over t."""

    def __init__(self, knots: np.ndarray, control_points: np.ndarray, weights: np.ndarray,
                 degree: int) -> None:
        from scipy.interpolate import BSpline

        self.knots = np.asarray(knots, dtype=float)
        self.control_points = np.asarray(control_points, dtype=float)
        self.weights = np.asarray(weights, dtype=float)
        self.degree = int(degree)
        self._num = BSpline(self.knots, self.weights * self.control_points, self.degree)
        self._den = BSpline(self.knots, self.weights, self.degree)
        lo, hi = self.knots[self.degree], self.knots[-self.degree - 1]
        inner = self.knots[(self.knots > lo) & (self.knots < hi)]
        self.x = sorted_unique(np.concatenate([[lo], inner, [hi]]))

    def _derivs(self, spline: Any, t: np.ndarray, nu: int) -> list[np.ndarray]:
        return [spline(t, i) if i <= self.degree else np.zeros_like(t)
                for i in range(nu + 1)]

    def __call__(self, t: np.ndarray | float, nu: int = 0) -> np.ndarray:
        """The nu-th derivative at t (exact: Leibniz on numerator and denominator)."""
        t = np.asarray(t, dtype=float)
        flat = t.ravel()
        out = _leibniz_quotient(self._derivs(self._num, flat, nu),
                                self._derivs(self._den, flat, nu))[nu]
        return out.reshape(t.shape)


def rational_basis(knots: np.ndarray, degree: int, weights: np.ndarray, x: np.ndarray,
                   nu: int = 0) -> np.ndarray:
    """R_j^(nu)(x) (columns j): the rows of a NURBS condition S^(nu)(x) = v."""
    x = np.atleast_1d(np.asarray(x, dtype=float))
    N = [basis_matrix(knots, degree, x, i) for i in range(nu + 1)]
    return _leibniz_quotient([n * weights for n in N], [n @ weights for n in N])[nu]


def interpolating_nurbs(t: np.ndarray, q: np.ndarray, degree: int, weights: np.ndarray,
                        knots: np.ndarray | str | None = None,
                        start: Mapping[int, float] | None = None,
                        end: Mapping[int, float] | None = None,
                        conditions: Sequence[Condition] = (),
                        periodic: Sequence[int] = ()) -> NURBS:
    """The NURBS of degree p with the given weights through (t_k, q_k) meeting the
    conditions (knots as for :func:`~sizer.laws.multipoint.bsplines.interpolating_bspline`)."""
    t = np.asarray(t, dtype=float)
    if knots is None or isinstance(knots, str):
        u = default_knots(t, degree, knots)
    else:
        u = check_knots(np.asarray(knots, dtype=float), degree)
    weights = check_weights(np.asarray(weights, dtype=float), u, degree)
    every = end_conditions(float(t[0]), float(t[-1]), start, end) + list(conditions)
    what = f"order {degree + 1} (degree {degree}) through {len(t)} points"

    def basis_of(knots_u: np.ndarray) -> Basis:
        return lambda x, nu: rational_basis(knots_u, degree, weights, x, nu)

    P = solve_control_points(t, q, degree, u, every, periodic, basis_of, what)
    return NURBS(u, P, weights, degree)


def check_weights(weights: np.ndarray, knots: np.ndarray, degree: int,
                  field: str = "weights") -> np.ndarray:
    """One positive weight per control point."""
    direct_counts(knots, degree, len(weights), field)
    bad = np.flatnonzero(weights <= 0.0)
    if bad.size:
        i = int(bad[0])
        raise UserError(f"must be positive: {field}[{i}] = {weights[i]:g}", field=field)
    return weights


NURBS_FIELDS = (*BSPLINE_FIELDS, "weights")


def build_nurbs(fields: Mapping[str, Any]) -> NURBS:
    """kind ``nurbs``: the bspline's fields plus ``weights`` (one per control point)."""
    F.refuse_unknown(fields, NURBS_FIELDS, "nurbs")
    if "control_points" in fields:
        degree, given, P = read_direct(fields, "nurbs")
        weights = check_weights(F.numbers(fields, "weights"), given, degree)
        return NURBS(given, P, weights, degree)
    degree = F.order_of(fields) - 1
    knots = read_knots(fields, degree)
    t, q = F.points(fields, minimum=2)
    u = default_knots(t, degree, knots) if knots is None or isinstance(knots, str) else knots
    weights = check_weights(F.numbers(fields, "weights"), u, degree)
    return interpolating_nurbs(t, q, degree, weights, u, F.conditions(fields, "start"),
                               F.conditions(fields, "end"), F.timed_conditions(fields),
                               F.periodic(fields))
