"""The largest value of p*a_N(tau) + q*v_N(tau) over a move, exactly, for arrays of (p, q).

The motor torque of a move is J*h/T^2*a_N + B*h/T*v_N plus terms that do not depend on
tau (book sec. 6.2, eq. 6.4), so its peak is max over tau of p*a_N + q*v_N for one (p, q)
per candidate: this module answers it for millions of candidates at once, with the tau
and the piece where it is reached (book sec. 6.2; the peak points of Fig. 6.3).

Why it is exact. The maximum of a linear functional (q, p).(v, a) over the curve
tau -> (v_N(tau), a_N(tau)) equals its maximum over the curve's convex hull, and is
reached at a point of the curve on the hull (a linear function takes its maximum over a
convex set at an extreme point). Per law, once: each smooth piece is sampled densely
(uniform, graded toward the piece ends and the law's fine points; its one-sided values
at both ends included, for a_N jumps at breakpoints and at tau = 0, 1) and the convex
hull of the samples is built (monotone chain). A query is then the hull's support
function: the hull vertex whose normal cone holds the direction (q, p), found by a
binary search on the sorted edge-normal angles (O(log n) per query, no candidates x
samples array). The sampled vertex is within a sample of the true maximizer on its piece:
where the derivative g = p*j_N + q*a_N changes sign between the vertex and a neighbouring
sample, the stationary point is the root of the cubic Hermite interpolant of g on that
interval (g and g' = p*q_N^(4) + q*j_N are tabulated at the samples), found for all
queries at once by safeguarded Newton steps on the cubic, then polished by one Newton
step on the law itself: the interpolant is within h^4/384 max|g^(4)| of g (h the sample
spacing), the Newton step squares that error, and p*a_N + q*v_N is evaluated from the
law at the point, below the maximum by half the curvature times the squared error:
rounding. The best of the sample, the root and the polished root is kept, so the result
is always a value the law reaches. A vertex at a piece end whose derivative points out
of the piece is a one-sided maximum, its own value. When two distant arcs of the curve
nearly tie (within the sampling error of the samples), the hull neighbours of the vertex
are refined as well, so the maximum of the refined arcs is the maximum over the curve.

The samples must resolve the curve (at most one stationary point of g between two
samples near a maximum): 1024 uniform intervals per piece and 16 points a decade graded
toward the piece ends and the fine points do so at the ends of the parameter ranges too
(elliptic n = 1000, modified cycloidal kappa = +-0.99, exponential sigma = 1, lam = 0.15),
checked against a graded brute force.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from sizer.laws.base import MotionLaw
from sizer.laws.coefficients import scan_grid

SAMPLES_PER_PIECE = 1024
"""Uniform sample intervals per piece (plus the graded points of ``scan_grid``)."""

GRADED_PER_DECADE = 16
"""Samples per decade of the geometric grading toward piece ends and fine points."""

NEWTON_STEPS = 6
"""Safeguarded Newton steps on the cubic model of the derivative (from the secant
estimate three reach rounding; the rest are margin)."""

DINKELBACH_STEPS = 20
"""Dinkelbach iterations at most for a peak ratio (superlinear: 3 to 5 reach rounding)."""

NEAR_TIE_SAFETY = 4.0
"""Factor on the second-order bound of the sampling error that flags near ties."""


@dataclass(frozen=True)
class LinearPeak:
    """Where p*a_N + q*v_N is largest (or smallest): its value, tau and piece index."""

    value: np.ndarray
    tau: np.ndarray
    piece: np.ndarray


def piece_values(law: MotionLaw, tau: np.ndarray, piece: np.ndarray,
                 order: int | Sequence[int]) -> np.ndarray | tuple[np.ndarray, ...]:
    """q_N^(order) at each (tau, piece index) pair: each piece evaluated once, on its
    points (one-sided values at its ends); tau and piece broadcast together. With a
    sequence of orders, a tuple of arrays (the points grouped by piece once)."""
    orders = (order,) if isinstance(order, int) else tuple(order)
    tau, piece = np.broadcast_arrays(np.asarray(tau, dtype=float), np.asarray(piece))
    flat_tau, flat_piece = tau.ravel(), piece.ravel()
    out = [np.empty(flat_tau.shape) for _ in orders]
    by_piece = np.argsort(flat_piece, kind="stable")
    bounds = np.searchsorted(flat_piece[by_piece], np.arange(len(law.pieces) + 1))
    for index in range(len(law.pieces)):
        rows = by_piece[bounds[index]:bounds[index + 1]]
        if len(rows):
            at = flat_tau[rows]
            for values, k in zip(out, orders, strict=True):
                values[rows] = law.piece_derivative(index, at, k)
    shaped = tuple(values.reshape(tau.shape) for values in out)
    return shaped[0] if isinstance(order, int) else shaped


def _convex_hull(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Indices of the hull vertices of the points (x, y), counterclockwise (monotone
    chain; collinear and repeated points dropped)."""
    order = np.lexsort((y, x))
    xs, ys = x[order].tolist(), y[order].tolist()

    def chain(indices: range) -> list[int]:
        hull: list[int] = []
        for i in indices:
            while len(hull) >= 2:
                a, b = hull[-2], hull[-1]
                cross = (xs[b] - xs[a]) * (ys[i] - ys[a]) - (ys[b] - ys[a]) * (xs[i] - xs[a])
                if cross > 0.0:
                    break
                hull.pop()
            hull.append(i)
        return hull

    lower = chain(range(len(xs)))
    upper = chain(range(len(xs) - 1, -1, -1))
    return order[np.array(lower[:-1] + upper[:-1])]


class LinearPeaks:
    """A law's sampled (v_N, a_N) curve and its convex hull (built once per law: use
    ``law.linear_peaks``), answering max and min of p*a_N + q*v_N over tau in [0, 1]."""

    def __init__(self, law: MotionLaw) -> None:
        self.law = law
        grids = [scan_grid(piece, uniform=SAMPLES_PER_PIECE, toward=law.fine_points(),
                           per_decade=GRADED_PER_DECADE)
                 for piece in law.pieces]
        self.tau = np.concatenate(grids)
        self.piece = np.repeat(np.arange(len(grids)), [len(g) for g in grids])
        self.v, self.a, self.j, self.snap = (piece_values(law, self.tau, self.piece, order)
                                             for order in (1, 2, 3, 4))
        self.first = np.concatenate(([True], self.piece[1:] != self.piece[:-1]))
        self.last = np.concatenate((self.piece[1:] != self.piece[:-1], [True]))
        # a piece of constant acceleration (zero jerk: the trapezoid's) is a straight
        # segment of the curve, whose hull is its two ends: the samples between go
        jerkless = np.ones(len(grids), dtype=bool)
        np.logical_and.at(jerkless, self.piece, self.j == 0.0)
        keep = ~jerkless[self.piece] | self.first | self.last
        if not keep.all():
            self.tau, self.piece, self.v, self.a, self.j, self.snap, self.first, self.last = (
                x[keep] for x in (self.tau, self.piece, self.v, self.a, self.j, self.snap,
                                  self.first, self.last))
        snap = self.snap
        # second-order bound of what the samples miss of a maximum inside an interval
        inner = ~self.last[:-1]
        width2 = np.diff(self.tau)[inner] ** 2 / 8.0
        self._miss_j = NEAR_TIE_SAFETY * float(np.max(
            width2 * np.maximum(np.abs(self.j[:-1]), np.abs(self.j[1:]))[inner], initial=0.0))
        self._miss_snap = NEAR_TIE_SAFETY * float(np.max(
            width2 * np.maximum(np.abs(snap[:-1]), np.abs(snap[1:]))[inner], initial=0.0))
        self._scale_a = float(np.max(np.abs(self.a)))
        self._scale_v = float(np.max(np.abs(self.v)))
        self.hull = _convex_hull(self.v, self.a)
        hx, hy = self.v[self.hull], self.a[self.hull]
        ex, ey = np.roll(hx, -1) - hx, np.roll(hy, -1) - hy
        angles = np.arctan2(-ex, ey)  # outward normal of edge i (vertex i to i + 1)
        self._shift = int(np.argmin(angles))
        self._angles = np.maximum.accumulate(np.roll(angles, -self._shift))

    # ------------------------------------------------------------------ queries
    def maximum(self, p: np.ndarray | float, q: np.ndarray | float) -> LinearPeak:
        """max over tau in [0, 1] of p*a_N(tau) + q*v_N(tau), elementwise over the
        broadcast of p and q, with the tau and piece index where it is reached."""
        p, q = np.broadcast_arrays(np.asarray(p, dtype=float), np.asarray(q, dtype=float))
        shape = p.shape
        P, Q = p.ravel(), q.ravel()
        vertex = self._support_vertex(P, Q)
        sample = self.hull[vertex]
        value, tau, piece = self._refine(sample, P, Q)
        # near ties: refine the vertex's hull neighbours that are not its own neighbours
        # on the piece (their arcs' maxima may exceed this one by less than the sampling)
        margin = (np.abs(P) * self._miss_j + np.abs(Q) * self._miss_snap
                  + 1e-13 * (np.abs(P) * self._scale_a + np.abs(Q) * self._scale_v))
        m = len(self.hull)
        for step in (-1, 1):
            other = self.hull[(vertex + step) % m]
            candidate = (np.abs(other - sample) > 1) | (self.piece[other] != self.piece[sample])
            candidate &= P * self.a[other] + Q * self.v[other] >= value - margin
            if candidate.any():
                rows = np.nonzero(candidate)[0]
                v2, t2, i2 = self._refine(other[rows], P[rows], Q[rows])
                better = v2 > value[rows]
                rows = rows[better]
                value[rows], tau[rows], piece[rows] = v2[better], t2[better], i2[better]
        return LinearPeak(value.reshape(shape), tau.reshape(shape), piece.reshape(shape))

    def minimum(self, p: np.ndarray | float, q: np.ndarray | float) -> LinearPeak:
        """min over tau in [0, 1] of p*a_N(tau) + q*v_N(tau) (the maximum of the negated
        combination), with the tau and piece index where it is reached."""
        peak = self.maximum(-np.asarray(p, dtype=float), -np.asarray(q, dtype=float))
        return LinearPeak(-peak.value, peak.tau, peak.piece)

    def ratio_maximum(self, p: np.ndarray, q: np.ndarray, c: np.ndarray, alpha: np.ndarray,
                      rate: np.ndarray) -> LinearPeak:
        """max over tau of (p a_N + q v_N + c) / (alpha + rate v_N), elementwise, where the
        denominator is positive along the whole move (a torque over a speed-dependent
        limit, book sec. 6.1.1).

        Dinkelbach's method: r_{k+1} = N/D at the maximizer of N - r_k D, a linear peak
        (:meth:`maximum`). Each r_k is a value the law reaches; the sequence rises to the
        maximum superlinearly and stops when N - r_k D <= 0 everywhere (to rounding).
        """
        p, q, c, alpha, rate = (np.asarray(x, dtype=float).ravel()
                                for x in np.broadcast_arrays(p, q, c, alpha, rate))
        start = self.maximum(p, q)
        tau, piece = start.tau.copy(), start.piece.copy()
        v, a = piece_values(self.law, tau, piece, (1, 2))
        r = (p * a + q * v + c) / (alpha + rate * v)
        index = np.arange(len(p))
        for _ in range(DINKELBACH_STEPS):
            if len(index) == 0:
                break
            peak = self.maximum(p[index], q[index] - r[index] * rate[index])
            v, a = piece_values(self.law, peak.tau, peak.piece, (1, 2))
            new = (p[index] * a + q[index] * v + c[index]) / (alpha[index] + rate[index] * v)
            better = new > r[index]
            rows = index[better]
            gain = new[better] - r[rows]
            r[rows], tau[rows], piece[rows] = new[better], peak.tau[better], peak.piece[better]
            index = rows[gain > 1e-15 * np.abs(r[rows])]
        return LinearPeak(r, tau, piece)

    # ------------------------------------------------------------------ steps
    def _stationary_points(self, lo: np.ndarray, P: np.ndarray, Q: np.ndarray) -> np.ndarray:
        """tau where the cubic Hermite model of g = p*j + q*a between the samples lo and
        lo + 1 (one piece, g changing sign) vanishes: safeguarded Newton on the model."""
        hi = lo + 1
        width = self.tau[hi] - self.tau[lo]
        g0 = P * self.j[lo] + Q * self.a[lo]
        g1 = P * self.j[hi] + Q * self.a[hi]
        d0 = (P * self.snap[lo] + Q * self.j[lo]) * width
        d1 = (P * self.snap[hi] + Q * self.j[hi]) * width
        # H(s) = g0 + d0 s + c2 s^2 + c3 s^3 on [0, 1]: H(0) = g0, H(1) = g1, slopes d0, d1
        c2 = 3.0 * (g1 - g0) - 2.0 * d0 - d1
        c3 = 2.0 * (g0 - g1) + d0 + d1
        low, high = np.zeros_like(g0), np.ones_like(g0)
        rising = g0 < 0.0
        s = g0 / (g0 - g1)
        for _ in range(NEWTON_STEPS):
            h = g0 + s * (d0 + s * (c2 + s * c3))
            before = (h < 0.0) == rising  # the root lies above s
            low, high = np.where(before, s, low), np.where(before, high, s)
            with np.errstate(divide="ignore", invalid="ignore"):
                step = s - h / (d0 + s * (2.0 * c2 + 3.0 * s * c3))
            # a step inside the bracket, or one at rounding level (converged), is taken;
            # a zero of the model is kept; else bisect
            take = ((step >= low) & (step <= high)) | (np.abs(step - s) <= 1e-15)
            s = np.where(h == 0.0, s, np.where(take, step, 0.5 * (low + high)))
        return self.tau[lo] + np.clip(s, 0.0, 1.0) * width

    def _support_vertex(self, P: np.ndarray, Q: np.ndarray) -> np.ndarray:
        """Position in the hull of the vertex maximizing (Q, P).(v, a) (the support point)."""
        theta = np.arctan2(P, Q)
        start = self._angles[0]
        theta = np.where(theta < start, theta + 2.0 * math.pi, theta)
        k = np.searchsorted(self._angles, theta, side="left")
        return (self._shift + k) % len(self.hull)

    def _refine(self, sample: np.ndarray, P: np.ndarray,
                Q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The maximum on the sample's piece between its neighbouring samples: the
        stationary point of p*a + q*v where its derivative changes sign, else the sample."""
        value = P * self.a[sample] + Q * self.v[sample]
        tau = self.tau[sample].copy()
        piece = self.piece[sample].copy()
        slope = P * self.j[sample] + Q * self.a[sample]
        right = np.minimum(sample + 1, len(self.tau) - 1)
        left = np.maximum(sample - 1, 0)
        go_right = (slope > 0.0) & ~self.last[sample]
        go_right &= P * self.j[right] + Q * self.a[right] < 0.0
        go_left = (slope < 0.0) & ~self.first[sample]
        go_left &= P * self.j[left] + Q * self.a[left] > 0.0
        rows = np.nonzero(go_right | go_left)[0]
        if len(rows) == 0:
            return value, tau, piece
        lo = np.where(go_right[rows], sample[rows], left[rows])
        P, Q, at = P[rows], Q[rows], piece[rows]
        root = self._stationary_points(lo, P, Q)
        # one Newton step on the law itself: the model's error (h^4) squared
        v, a, j, snap = piece_values(self.law, root, at, (1, 2, 3, 4))
        with np.errstate(divide="ignore", invalid="ignore"):
            newton = root - (P * j + Q * a) / (P * snap + Q * j)
        newton = np.clip(np.where(np.isfinite(newton), newton, root),
                         self.tau[lo], self.tau[lo + 1])
        v1, a1 = piece_values(self.law, newton, at, (1, 2))
        found, where = P * a + Q * v, root
        polished = P * a1 + Q * v1
        found, where = np.maximum(found, polished), np.where(polished > found, newton, root)
        better = found > value[rows]
        chosen = rows[better]
        value[chosen], tau[chosen] = found[better], where[better]
        return value, tau, piece


def maximum(law: MotionLaw, p: np.ndarray | float, q: np.ndarray | float) -> LinearPeak:
    """max over tau in [0, 1] of p*a_N + q*v_N for arrays p, q (see the module docs)."""
    return law.linear_peaks.maximum(p, q)


def minimum(law: MotionLaw, p: np.ndarray | float, q: np.ndarray | float) -> LinearPeak:
    """min over tau in [0, 1] of p*a_N + q*v_N for arrays p, q (see the module docs)."""
    return law.linear_peaks.minimum(p, q)
