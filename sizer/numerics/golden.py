"""Vectorized golden-section search: the step shared by every bracketed extremum search.

Each caller keeps its own stopping rule (a fixed count, a width, a feasible point found)
and decides per element which side holds the extremum; the step then shrinks the
brackets and evaluates the objective once, at one new point per element.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

INV_PHI = (math.sqrt(5.0) - 1.0) / 2.0

Bracket = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]
"""(lo, hi, x1, x2, f1, f2) with lo < x1 < x2 < hi and f1 = f(x1), f2 = f(x2)."""


def interior_points(lo: np.ndarray, hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The two golden points x1 < x2 of [lo, hi]."""
    return hi - INV_PHI * (hi - lo), lo + INV_PHI * (hi - lo)


def golden_step(f: Callable[[np.ndarray], np.ndarray], bracket: Bracket,
                left: np.ndarray) -> Bracket:
    """One step: where ``left`` the extremum lies in [lo, x2], elsewhere in [x1, hi]."""
    lo, hi, x1, x2, f1, f2 = bracket
    hi, lo = np.where(left, x2, hi), np.where(left, lo, x1)
    new_x1 = np.where(left, hi - INV_PHI * (hi - lo), x2)
    new_x2 = np.where(left, x1, lo + INV_PHI * (hi - lo))
    f_new = f(np.where(left, new_x1, new_x2))
    return (lo, hi, new_x1, new_x2,
            np.where(left, f_new, f2), np.where(left, f1, f_new))


CGOLD = 1.0 - INV_PHI
"""The golden share of the larger part of a bracket (0.381966...)."""


class BrentMax:
    """Brent's method for a maximum (parabolic interpolation safeguarded by golden
    section; Brent 1973, ch. 5), one new point per element a step: each caller evaluates
    :meth:`point` and hands the values to :meth:`update`, and stops an element by its own
    rule (a width, a value found), dropping it with :meth:`take`.

    State per element: the bracket [a, b] (its lower end's value fa, for a caller that
    looks below a point), the best point x, the second best w and the one before v
    (values fx, fw, fv), the last step d
    and the one before e. Where f is smooth near its maximum the parabola through x, w, v
    converges superlinearly; golden-section steps keep the bracket shrinking elsewhere
    (a kink, a flat stretch). ``tol``: the absolute spacing below which no two points are
    read; an element is settled once its bracket is about 4 tol wide (:attr:`settled`).
    """

    def __init__(self, a, b, fa, x, fx, w, fw, tol: float) -> None:
        self.a, self.b, self.fa = a, b, fa
        self.x, self.fx, self.w, self.fw, self.v, self.fv = x, fx, w, fw, w.copy(), fw.copy()
        self.d, self.e = np.zeros_like(a), np.zeros_like(a)
        self.tol = tol

    def take(self, keep: np.ndarray) -> BrentMax:
        out = object.__new__(BrentMax)
        for name in ("a", "b", "fa", "x", "fx", "w", "fw", "v", "fv", "d", "e"):
            setattr(out, name, getattr(self, name)[keep])
        out.tol = self.tol
        return out

    @property
    def settled(self) -> np.ndarray:
        """The elements whose best point is known to about the tolerance."""
        middle = 0.5 * (self.a + self.b)
        return np.abs(self.x - middle) <= 2.0 * self.tol - 0.5 * (self.b - self.a)

    def point(self) -> np.ndarray:
        """The next point of each element (its steps d and e updated)."""
        a, b, x, w, v = self.a, self.b, self.x, self.w, self.v
        tol1, tol2 = self.tol, 2.0 * self.tol
        middle = 0.5 * (a + b)
        golden_e = np.where(x >= middle, a - x, b - x)
        # the parabola through (x, fx), (w, fw), (v, fv): its vertex x + p/q
        r = (x - w) * (self.fx - self.fv)
        q = (x - v) * (self.fx - self.fw)
        p = (x - v) * q - (x - w) * r
        q = 2.0 * (q - r)
        p = np.where(q > 0.0, -p, p)
        q = np.abs(q)
        tried = np.abs(self.e) > tol1
        with np.errstate(divide="ignore", invalid="ignore"):
            step = p / q
        usable = tried & (np.abs(p) < np.abs(0.5 * q * self.e)) & (p > q * (a - x)) \
            & (p < q * (b - x)) & np.isfinite(step)
        u = x + step
        near_end = (u - a < tol2) | (b - u < tol2)
        step = np.where(near_end, np.copysign(tol1, middle - x), step)
        e = np.where(usable, self.d, golden_e)
        d = np.where(usable, step, CGOLD * golden_e)
        self.e, self.d = e, d
        return np.where(np.abs(d) >= tol1, x + d, x + np.copysign(tol1, d))

    def update(self, u: np.ndarray, fu: np.ndarray) -> None:
        """Take f(u) = fu in: the bracket, the best three points."""
        x, w, v, fx, fw, fv = self.x, self.w, self.v, self.fx, self.fw, self.fv
        better = fu >= fx  # u is the new best: x becomes an end
        x_end_low = better & (u >= x)  # a = x
        x_end_high = better & (u < x)  # b = x
        u_end_low = ~better & (u < x)  # a = u
        u_end_high = ~better & (u >= x)  # b = u
        self.a = np.where(x_end_low, x, np.where(u_end_low, u, self.a))
        self.fa = np.where(x_end_low, fx, np.where(u_end_low, fu, self.fa))
        self.b = np.where(x_end_high, x, np.where(u_end_high, u, self.b))
        second = ~better & ((fu >= fw) | (w == x))
        third = ~better & ~second & ((fu >= fv) | (v == x) | (v == w))
        self.v = np.where(better | second, w, np.where(third, u, v))
        self.fv = np.where(better | second, fw, np.where(third, fu, fv))
        self.w = np.where(better, x, np.where(second, u, w))
        self.fw = np.where(better, fx, np.where(second, fu, fw))
        self.x = np.where(better, u, x)
        self.fx = np.where(better, fu, fx)
