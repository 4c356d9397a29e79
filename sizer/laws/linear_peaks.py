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
checked against a graded brute force. A polynomial piece (degree <= 7: g has at most 4
stationary points, and the cubic Hermite model is exact up to degree 5) takes 64 uniform
intervals and 4 points a decade toward its ends (checked against the same brute force:
the double S's maxima within 1e-4 of a piece end need the grading).

Restricted to a speed band. A move that leaves the speed-torque region needs the peaks
over the part of the move below its top speed (v_N <= u) and the part above it
(v_N >= u) (:meth:`LinearPeaks.band`, :meth:`LinearPeaks.maximum_within`,
:meth:`LinearPeaks.ratio_maximum_within`). The maximum over such a part is at a
stationary point inside it or at one of its ends, where v_N = u. The samples (with the
exact extrema of v_N added, so that v_N is monotone between samples) ordered by v_N
(or -v_N) make each part's samples a prefix of that order; the hull of every prefix is
held at once by the monotone chain's persistent lower and upper chains (each point's
predecessor when it was added), and a support query walks the chain from the prefix's
last point by binary lifting. The vertex is refined as above (a stationary point
outside the part does not count), and the part's ends, the roots of v_N = u in each
monotone run of v_N (cubic Hermite model, then a Newton step on the law), are compared
with it.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from sizer.laws.coefficients import scan_grid
from sizer.laws.piece_forms import PieceForms
from sizer.laws.pieces import LawShape
from sizer.numerics.hermite import hermite_root

SAMPLES_PER_PIECE = 1024
"""Uniform sample intervals per piece (plus the graded points of ``scan_grid``)."""

SAMPLES_PER_POLYNOMIAL = 64
"""Uniform sample intervals of a polynomial piece (``Piece.degree``, up to
POLYNOMIAL_DEGREE), without grading: its curve has no steep end, and g = p*j_N + q*a_N is
a polynomial of degree <= degree - 2 with at most degree - 3 stationary points, so 64
intervals separate its roots, and the cubic Hermite model of g between two samples is
exact up to degree 5 (a Newton step on the law polishes the rest)."""
POLYNOMIAL_DEGREE = 7
GRADED_POLYNOMIAL = 4
"""Samples per decade toward a polynomial piece's ends (a maximum may lie within 1e-4 of
an end, where the curve returns to rest: the double S's)."""

GRADED_PER_DECADE = 16
"""Samples per decade of the geometric grading toward piece ends and fine points."""

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


@dataclass(frozen=True)
class SpeedBand:
    """Per row, the part of a move where v_N <= bound (``side`` +1: below a top speed) or
    v_N >= bound (``side`` -1: above it), for :meth:`LinearPeaks.maximum_within`; made by
    :meth:`LinearPeaks.band`. ``last``: the position, in the law's samples ordered by
    side*v_N, of the last sample inside (-1: none); ``cross_*``: the points where v_N
    crosses the bound between two samples (rows x monotone runs of v_N, ``cross_ok``
    where there is one), the band's ends."""

    side: float
    bound: np.ndarray
    last: np.ndarray
    cross_tau: np.ndarray
    cross_piece: np.ndarray
    cross_v: np.ndarray
    cross_a: np.ndarray
    cross_ok: np.ndarray

    def take(self, index: np.ndarray) -> SpeedBand:
        """The rows at ``index`` (repeats allowed)."""
        return SpeedBand(self.side, self.bound[index], self.last[index],
                         self.cross_tau[index], self.cross_piece[index],
                         self.cross_v[index], self.cross_a[index], self.cross_ok[index])


@dataclass(frozen=True)
class _Table:
    """Samples of a law's (v_N, a_N) curve in tau order, piece by piece (one-sided values
    at the piece ends), with j_N and q_N^(4) for the refinement."""

    tau: np.ndarray
    piece: np.ndarray
    v: np.ndarray
    a: np.ndarray
    j: np.ndarray
    snap: np.ndarray
    first: np.ndarray
    last: np.ndarray


def piece_values(law: LawShape, tau: np.ndarray, piece: np.ndarray,
                 order: int | Sequence[int]) -> np.ndarray | tuple[np.ndarray, ...]:
    """q_N^(order) at each (tau, piece index) pair: each piece evaluated once, on its
    points (one-sided values at its ends); tau and piece broadcast together. With a
    sequence of orders, a tuple of arrays (the points grouped by piece once)."""
    orders = (order,) if isinstance(order, int) else tuple(order)
    tau, piece = np.broadcast_arrays(np.asarray(tau, dtype=float), np.asarray(piece))
    flat_tau, flat_piece = tau.ravel(), piece.ravel()
    if len(law.pieces) == 1:  # one piece: no grouping
        shaped = tuple(law.piece_derivative(0, flat_tau, k).reshape(tau.shape) for k in orders)
        return shaped[0] if isinstance(order, int) else shaped
    forms = law.piece_forms()
    if forms is not None:  # every piece at once, the same values
        shaped = tuple(v.reshape(tau.shape) for v in forms.values(
            flat_piece.astype(np.intp, copy=False), flat_tau, orders))
        return shaped[0] if isinstance(order, int) else shaped
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


@dataclass(frozen=True)
class LinearAcceleration:
    """The extremes of a law whose acceleration is linear on every piece (each piece a
    polynomial of degree <= 3: the trapezoid, the double S), from its piece ends
    (:func:`linear_acceleration`)."""

    lowest: float
    """min a_N over the move."""
    highest: float
    """max a_N over the move."""
    slowest: float
    """min v_N over the move (at a piece end or where a_N crosses zero inside one)."""


def linear_acceleration(law: LawShape) -> LinearAcceleration | None:
    """:class:`LinearAcceleration` of a law whose every piece is a polynomial of degree
    <= 3, else None. a_N is linear on each piece, so its extremes are among the pieces'
    one-sided end values: the very values :class:`LinearPeaks` samples there (its samples
    hold every piece's ends, evaluated by the same arithmetic, and a query (p, 0) finds no
    stationary point inside a piece of constant jerk), so p*a_N + c peaks at p times one
    of them, plus c, with the same floats and no samples or hull. v_N is quadratic on a
    piece: its least value is at an end or where a_N is zero inside."""
    if not all(piece.degree is not None and piece.degree <= 3 for piece in law.pieces):
        return None
    count = len(law.pieces)
    starts = np.array([piece.start for piece in law.pieces])
    ends = np.array([piece.end for piece in law.pieces])
    index = np.arange(count)
    tau = np.concatenate((starts, ends))
    piece = np.concatenate((index, index))
    v, a = piece_values(law, tau, piece, (1, 2))
    a0, a1 = a[:count], a[count:]
    inside = np.flatnonzero(a0 * a1 < 0.0)
    slowest = float(np.min(v))
    if len(inside):  # a linear a_N's zero, where v_N is at its vertex
        share = a0[inside] / (a0[inside] - a1[inside])
        zero = starts[inside] + (ends[inside] - starts[inside]) * share
        slowest = min(slowest, float(np.min(piece_values(law, zero, inside, 1))))
    return LinearAcceleration(float(np.min(a)), float(np.max(a)), slowest)


def _piece_grid(law: LawShape, index: int) -> np.ndarray:
    """The samples of one piece: its scan grid (finer where its law varies fast)."""
    piece = law.pieces[index]
    polynomial = piece.degree is not None and piece.degree <= POLYNOMIAL_DEGREE
    return scan_grid(piece, uniform=SAMPLES_PER_POLYNOMIAL if polynomial else SAMPLES_PER_PIECE,
                     toward=law.fine_points(),
                     per_decade=GRADED_POLYNOMIAL if polynomial else GRADED_PER_DECADE)


def _piece_samples(law: LawShape, index: int) -> tuple[np.ndarray, ...]:
    """tau, piece index, v_N, a_N, j_N and q_N^(4) at the samples of one piece (its scan
    grid). A piece of constant acceleration (zero jerk at every sample: the trapezoid's)
    is a straight segment of the curve, whose hull is its two ends: only they are kept
    (the jerk is read first, the other orders only where needed)."""
    tau = _piece_grid(law, index)
    j = law.piece_derivative(index, tau, 3)
    if not j.any():
        tau, j = tau[[0, -1]], j[[0, -1]]
    v, a, snap = (law.piece_derivative(index, tau, order) for order in (1, 2, 4))
    return tau, np.full(len(tau), index), v, a, j, snap


def _law_samples(law: LawShape) -> tuple[np.ndarray, ...]:
    """:func:`_piece_samples` of every piece, concatenated; for a law with pieces as data
    (sizer.laws.piece_forms) every piece in one pass, the same samples and values."""
    forms = law.piece_forms()
    if forms is None:
        columns = [_piece_samples(law, index) for index in range(len(law.pieces))]
        return tuple(np.concatenate(parts) for parts in zip(*columns, strict=True))
    return _samples_on(forms, [_piece_grid(law, index) for index in range(len(law.pieces))])


def _samples_on(forms: PieceForms, grids: Sequence[np.ndarray]) -> tuple[np.ndarray, ...]:
    """tau, piece, v_N, a_N, j_N and q_N^(4) of the pieces of ``forms`` at their scan
    grids (``grids[i]``: piece i's), in one pass: :func:`_piece_samples` of each piece
    (a piece of constant acceleration keeps its two ends)."""
    sizes = np.array([len(g) for g in grids])
    tau = np.concatenate(grids)
    piece = np.repeat(np.arange(len(grids)), sizes)
    (j,) = forms.values(piece, tau, (3,))
    starts = np.concatenate(([0], np.cumsum(sizes)[:-1]))
    moving = np.logical_or.reduceat(j != 0.0, starts)
    ends = np.zeros(len(tau), dtype=bool)
    ends[starts], ends[starts + sizes - 1] = True, True
    keep = np.repeat(moving, sizes) | ends
    tau, piece, j = tau[keep], piece[keep], j[keep]
    v, a, snap = forms.values(piece, tau, (1, 2, 4))
    return tau, piece, v, a, j, snap


def samples_together(laws: Sequence[LawShape]) -> list[tuple[np.ndarray, ...]]:
    """:func:`_law_samples` of several laws with their pieces as data, every law's pieces
    evaluated in one pass (sizer.laws.piece_forms.PieceForms.stacked: each piece with its
    own arithmetic, numbered across the laws): the same samples and values, law by law."""
    tables = [law.piece_forms() for law in laws]
    assert all(table is not None for table in tables), "laws with their pieces as data"
    forms = PieceForms.stacked([table for table in tables if table is not None])
    counts = np.array([len(law.pieces) for law in laws])
    grids = [_piece_grid(law, index) for law in laws for index in range(len(law.pieces))]
    tau, piece, v, a, j, snap = _samples_on(forms, grids)
    first = np.concatenate(([0], np.cumsum(counts)[:-1]))  # each law's first piece
    bounds = np.searchsorted(piece, np.append(first, len(grids)))
    return [(tau[lo:hi].copy(), piece[lo:hi] - first[k], v[lo:hi].copy(), a[lo:hi].copy(),
             j[lo:hi].copy(), snap[lo:hi].copy())
            for k, (lo, hi) in enumerate(itertools.pairwise(bounds))]


def _next(x: np.ndarray) -> np.ndarray:
    """x[i + 1] at i, cyclically (np.roll(x, -1) without its overhead)."""
    return np.concatenate((x[1:], x[:1]))


def _convex_hull(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Indices of the hull vertices of the points (x, y), counterclockwise: the vertices
    of the monotone chain (collinear and repeated points dropped; of repeated points the
    one the chain keeps), each chain found by :func:`_chain_vertices`, vectorized."""
    order = np.lexsort((y, x))
    xs, ys = x[order], y[order]
    count = len(xs)
    # runs of repeated points (adjacent once sorted): the chains work on their first
    new = np.ones(count, dtype=bool)
    new[1:] = (xs[1:] != xs[:-1]) | (ys[1:] != ys[:-1])
    starts = np.flatnonzero(new)
    ends = np.append(starts[1:], count) - 1
    if len(starts) == 1:  # one point, maybe repeated: the chain keeps the first and last
        return order[[0, count - 1]] if count > 1 else order[:0]
    ux, uy = xs[starts], ys[starts]
    lower = _chain_vertices(ux, uy)
    upper = _chain_vertices(ux[::-1], uy[::-1])
    last = len(starts) - 1
    # the monotone chain keeps the first of a repeated start and the last of the others
    lower_sorted = np.where(lower == 0, starts[0], ends[lower])[:-1]
    upper_runs = last - upper
    upper_sorted = np.where(upper == 0, ends[last], starts[upper_runs])[:-1]
    return order[np.concatenate((lower_sorted, upper_sorted))]


THINNING_PASSES = 32
"""Vectorized passes of :func:`_chain_vertices` before the point-by-point chain takes
the rest (a smooth law's curve needs a few, a cam table's sampled one a few dozen)."""


def _chain_vertices(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Positions of the vertices of one monotone chain of distinct points, in the chain's
    order (x, y sorted along it), first and last included.

    Thinning: every point that does not turn the chain strictly left from its current
    neighbours (cross product <= 0) lies inside the triangle of its neighbours' chord or
    on it, so it is no vertex (the points are distinct: no vertex hides behind a copy of
    itself); all are dropped at once, pass after pass, until every turn is strictly left:
    the monotone chain of the points. Once a pass drops few points, the next passes test
    only the points next to a dropped one (the others keep their neighbours, hence their
    turn), on a linked list (:func:`_thin_links`). After THINNING_PASSES, the monotone
    chain runs on what is left (:func:`_chain_on`)."""
    kept = np.arange(len(x), dtype=np.intp)
    for passes in range(1, THINNING_PASSES + 1):
        if len(kept) < 3:
            return kept
        flat = _turns(x, y, kept[:-2], kept[1:-1], kept[2:]) <= 0.0
        drop = np.flatnonzero(flat) + 1
        if len(drop) == 0:
            return kept
        alive = np.ones(len(kept), dtype=bool)
        alive[drop] = False
        kept = kept[alive]
        if len(drop) <= FEW_DROPPED and passes < THINNING_PASSES:
            # the points next to a dropped one, by their positions in what is left
            near = np.zeros(len(alive), dtype=bool)
            near[drop - 1] = near[drop + 1] = True
            return _thin_links(x, y, kept, np.flatnonzero(near[alive]).tolist(),
                               THINNING_PASSES - passes)
    return kept[_chain_on(x[kept], y[kept])]


FEW_DROPPED = 64
"""A thinning pass dropping at most this many points hands over to :func:`_thin_links`."""


def _turns(x: np.ndarray, y: np.ndarray, a: np.ndarray, b: np.ndarray,
           c: np.ndarray) -> np.ndarray:
    """The cross products of (b - a, c - a): > 0 where a, b, c turn strictly left."""
    return (x[b] - x[a]) * (y[c] - y[a]) - (y[b] - y[a]) * (x[c] - x[a])


def _thin_links(x: np.ndarray, y: np.ndarray, kept: np.ndarray, near: list[int],
                passes: int) -> np.ndarray:
    """:func:`_chain_vertices`'s last ``passes`` thinning passes on the points ``kept``
    (a doubly linked list), each testing the points ``near`` a point the pass before
    dropped (positions in ``kept``; the same cross products, the same floats), then the
    monotone chain on what is left."""
    xs, ys = x[kept].tolist(), y[kept].tolist()
    count = len(xs)
    before = list(range(-1, count - 1))
    after = list(range(1, count + 1))
    dropped: list[int] = []
    for _ in range(passes):
        flat: list[int] = []
        for b in near:
            a, c = before[b], after[b]
            if a >= 0 and c < count and (xs[b] - xs[a]) * (ys[c] - ys[a]) - \
                    (ys[b] - ys[a]) * (xs[c] - xs[a]) <= 0.0:
                flat.append(b)
        if not flat or count - len(dropped) < 3:
            break
        touched: list[int] = []
        for b in flat:
            a, c = before[b], after[b]
            if a >= 0:
                after[a] = c
            if c < count:
                before[c] = a
            before[b] = after[b] = -2  # dropped
            touched += (a, c)
        dropped += flat
        near = [p for p in set(touched) if 0 <= p < count and after[p] != -2]
    else:  # THINNING_PASSES done: the monotone chain on what is left
        left = np.delete(kept, dropped)
        return left[_chain_on(x[left], y[left])]
    return np.delete(kept, dropped)


def _chain_on(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """The monotone chain of the points (x, y) in their order, point by point (Andrew's
    stack: pop while the last two and the new point do not turn strictly left), the
    positions it keeps. Its tests of three consecutive points are read from one array
    computation: while the stack's top two are the new point's two predecessors, the
    points up to the next turn that is not strictly left are pushed at once (the same
    cross products, the same floats; the thinned chain has few such turns)."""
    count = len(x)
    if count < 3:
        return np.arange(count, dtype=np.intp)
    position = np.arange(count, dtype=np.intp)
    turn = _turns(x, y, position[:-2], position[1:-1], position[2:])
    bad = (np.flatnonzero(~(turn > 0.0)) + 1).tolist()  # their middle points, ascending
    xs, ys = x.tolist(), y.tolist()
    hull: list[int] = [0, 1]
    i, k = 2, 0  # the next point; the next such turn's middle is bad[k] (>= i - 1)
    while i < count:
        if hull[-1] == i - 1 and hull[-2] == i - 2:
            while k < len(bad) and bad[k] < i - 1:
                k += 1
            stop = bad[k] if k < len(bad) else count - 1
            if stop > i - 1:  # every turn up to the one at stop is left: push to stop
                hull.extend(range(i, stop + 1))
                i = stop + 1
                continue
        xi, yi = xs[i], ys[i]
        while len(hull) >= 2:
            a, b = hull[-2], hull[-1]
            if (xs[b] - xs[a]) * (yi - ys[a]) - (ys[b] - ys[a]) * (xi - xs[a]) > 0.0:
                break
            hull.pop()
        hull.append(i)
        i += 1
    return np.array(hull, dtype=np.intp)


def _with_speed_extrema(peaks: LinearPeaks) -> _Table:
    """The law's samples with the exact extrema of v_N inside sample intervals added (the
    roots of a_N where it changes sign between two samples of a piece: the model root of
    :meth:`LinearPeaks._stationary_points`, polished by a Newton step on the law), so that
    v_N is monotone between neighbouring samples and its top is a sample."""
    law, base = peaks.law, peaks._table
    inner = ~base.last[:-1]
    lo = np.flatnonzero(inner & (((base.a[:-1] > 0.0) & (base.a[1:] < 0.0))
                                 | ((base.a[:-1] < 0.0) & (base.a[1:] > 0.0))))
    if len(lo) == 0:
        return base
    piece = base.piece[lo]
    root = peaks._stationary_points(lo, np.zeros(len(lo)), np.ones(len(lo)), base)
    a, j = piece_values(law, root, piece, (2, 3))
    with np.errstate(divide="ignore", invalid="ignore"):
        newton = root - a / j
    newton = np.clip(np.where(np.isfinite(newton), newton, root), base.tau[lo], base.tau[lo + 1])
    a1 = piece_values(law, newton, piece, 2)
    tau = np.where(np.abs(a1) < np.abs(a), newton, root)
    v, a, j, snap = piece_values(law, tau, piece, (1, 2, 3, 4))
    merged = [np.concatenate((x, y)) for x, y in ((base.tau, tau), (base.piece, piece),
                                                  (base.v, v), (base.a, a), (base.j, j),
                                                  (base.snap, snap))]
    order = np.lexsort((merged[0], merged[1]))
    tau, piece, v, a, j, snap = (x[order] for x in merged)
    first = np.concatenate(([True], piece[1:] != piece[:-1]))
    last = np.concatenate((piece[1:] != piece[:-1], [True]))
    return _Table(tau, piece, v, a, j, snap, first, last)


@dataclass(frozen=True)
class _Chain:
    """One persistent hull chain (lower or upper) of points sorted by (x, y): parent[i] is
    the chain's vertex before point i when i was added, so the chain of the first m + 1
    points is the path from m to the root (position 0); up[k] is the 2^k-th ancestor."""

    parent: np.ndarray
    up: np.ndarray


def _persistent_chain(x: list[float], y: list[float], upper: bool) -> _Chain:
    """The monotone chain's lower (or upper) hull built point by point, each point's parent
    kept (collinear and repeated points dropped), with its jump table."""
    count = len(x)
    parent = np.zeros(count, dtype=np.intp)
    hull: list[int] = []
    sign = -1.0 if upper else 1.0
    for i in range(count):
        while len(hull) >= 2:
            a, b = hull[-2], hull[-1]
            cross = (x[b] - x[a]) * (y[i] - y[a]) - (y[b] - y[a]) * (x[i] - x[a])
            if sign * cross > 0.0:
                break
            hull.pop()
        parent[i] = hull[-1] if hull else i
        hull.append(i)
    levels = max(1, int(count - 1).bit_length())
    # 32-bit positions: the table is levels x points (a cam table's 10^5 points: 7 MB)
    up = np.empty((levels, count), dtype=np.int32 if count < 2**31 else np.intp)
    up[0] = parent
    for k in range(1, levels):
        up[k] = up[k - 1][up[k - 1]]
    return _Chain(parent, up)


class _SpeedOrder:
    """A law's samples (with the extrema of v_N) ordered by (side*v_N, a_N): the samples
    with side*v_N <= side*bound are a prefix, and the hull of a prefix is the path from its
    last point in the lower and in the upper persistent chain. Also the monotone runs of
    v_N in tau order, for the points where v_N crosses a bound."""

    def __init__(self, table: _Table, side: float) -> None:
        self.table = table
        x_all = side * table.v
        self.order = np.lexsort((table.a, x_all))
        self.x = x_all[self.order]
        self.y = table.a[self.order]
        xs, ys = self.x.tolist(), self.y.tolist()
        self.lower = _persistent_chain(xs, ys, upper=False)
        self.upper = _persistent_chain(xs, ys, upper=True)
        # monotone runs of v_N along the move (zero steps join the run they are in)
        step = np.sign(np.diff(table.v))
        moving = np.flatnonzero(step)
        self.runs: list[tuple[int, int, float]] = []
        if len(moving):
            fill = np.zeros(len(step), dtype=np.intp)
            fill[moving] = moving
            fill = np.maximum.accumulate(fill)
            fill[:moving[0]] = moving[0]
            filled = step[fill]
            breaks = np.flatnonzero(filled[1:] != filled[:-1]) + 1
            starts = np.concatenate(([0], breaks))
            ends = np.concatenate((breaks, [len(table.v) - 1]))
            self.runs = [(int(a), int(b), float(filled[a])) for a, b in zip(starts, ends,
                                                                            strict=True)]

    def support(self, chain: _Chain, other: _Chain, m: np.ndarray, qx: np.ndarray,
                py: np.ndarray) -> tuple[np.ndarray, list[np.ndarray]]:
        """The vertex maximizing qx*x + py*y over the first m + 1 points (positions in the
        order), on ``chain`` (the upper one for py >= 0, the lower one for py < 0), and its
        neighbours on the prefix's hull (-1 where none): along the chain's path from m the
        value rises to the maximum and falls after it (a convex chain), so the last point
        before the rise stops is found by binary lifting."""
        x, y = self.x, self.y
        parent, up = chain.parent, chain.up

        def rises(node):
            above = parent[node]
            return qx * x[above] + py * y[above] > qx * x[node] + py * y[node]

        node = m.copy()
        climbing = rises(node)
        for k in range(len(up) - 1, -1, -1):
            ahead = up[k][node]
            node = np.where(climbing & rises(ahead), ahead, node)
        best = np.where(climbing, parent[node], m)
        child = np.where(climbing, node, -1)
        root = best == 0
        before = np.where(root, -1, parent[best])
        # at the prefix's last point the other neighbour is on the other chain
        after = np.where(climbing, child, np.where(m > 0, other.parent[m], -1))
        # at the root, the other chain's vertex next to it
        beside = np.full(len(m), -1, dtype=np.intp)
        at_root = np.flatnonzero(root & (m > 0))
        if len(at_root):
            tail = m[at_root]
            for k in range(len(other.up) - 1, -1, -1):
                ahead = other.up[k][tail]
                tail = np.where(ahead != 0, ahead, tail)
            beside[at_root] = tail
        return best, [before, after, beside]

    def crossings(self, law: LawShape, bound: np.ndarray):
        """Per bound and monotone run of v_N, the point where v_N crosses the bound between
        two samples of a piece: (tau, piece, v_N, a_N, ok) arrays (bounds x runs). The root
        of the cubic Hermite model of v_N - bound, polished by a Newton step on the law."""
        t = self.table
        count, runs = len(bound), len(self.runs)
        tau = np.zeros((count, runs))
        piece = np.zeros((count, runs), dtype=np.intp)
        v = np.zeros((count, runs))
        a = np.zeros((count, runs))
        ok = np.zeros((count, runs), dtype=bool)
        los, cols, rows = [], [], []
        for run, (start, end, direction) in enumerate(self.runs):
            key = direction * t.v[start:end + 1]
            k = np.searchsorted(key, direction * bound, side="left")
            inside = (k >= 1) & (k <= end - start)
            first = start + np.clip(k - 1, 0, max(end - start - 1, 0))
            inside &= (direction * (t.v[first] - bound) < 0.0)
            inside &= (direction * (t.v[first + 1] - bound) > 0.0)
            inside &= t.piece[first] == t.piece[first + 1]
            sel = np.flatnonzero(inside)
            los.append(first[sel])
            rows.append(sel)
            cols.append(np.full(len(sel), run))
        if not runs or not sum(len(r) for r in rows):
            return tau, piece, v, a, ok
        lo, row, col = np.concatenate(los), np.concatenate(rows), np.concatenate(cols)
        u = bound[row]
        width = t.tau[lo + 1] - t.tau[lo]
        root = t.tau[lo] + hermite_root(t.v[lo] - u, t.v[lo + 1] - u, t.a[lo] * width,
                                         t.a[lo + 1] * width) * width
        at = t.piece[lo]
        v0, a0 = piece_values(law, root, at, (1, 2))
        with np.errstate(divide="ignore", invalid="ignore"):
            newton = root - (v0 - u) / a0
        newton = np.clip(np.where(np.isfinite(newton), newton, root), t.tau[lo], t.tau[lo + 1])
        v1, a1 = piece_values(law, newton, at, (1, 2))
        closer = np.abs(v1 - u) < np.abs(v0 - u)
        tau[row, col] = np.where(closer, newton, root)
        piece[row, col] = at
        v[row, col] = np.where(closer, v1, v0)
        a[row, col] = np.where(closer, a1, a0)
        ok[row, col] = True
        return tau, piece, v, a, ok


class LinearPeaks:
    """A law's sampled (v_N, a_N) curve and its convex hull (built once per law: use
    ``law.linear_peaks``), answering max and min of p*a_N + q*v_N over tau in [0, 1]."""

    def __init__(self, law: LawShape, samples: tuple[np.ndarray, ...] | None = None) -> None:
        """``samples``: the law's :func:`_law_samples` where computed with other laws'
        (:func:`samples_together`)."""
        self.law = law
        self.tau, self.piece, self.v, self.a, self.j, self.snap = (
            _law_samples(law) if samples is None else samples)
        self.first = np.concatenate(([True], self.piece[1:] != self.piece[:-1]))
        self.last = np.concatenate((self.piece[1:] != self.piece[:-1], [True]))
        self._table = _Table(self.tau, self.piece, self.v, self.a, self.j, self.snap,
                             self.first, self.last)
        self._speed_orders: dict[float, _SpeedOrder] = {}
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
        ex, ey = _next(hx) - hx, _next(hy) - hy
        angles = np.arctan2(-ex, ey)  # outward normal of edge i (vertex i to i + 1)
        self._shift = shift = int(np.argmin(angles))
        self._angles = np.maximum.accumulate(np.concatenate((angles[shift:], angles[:shift])))

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
                      rate: np.ndarray, floor: np.ndarray | None = None) -> LinearPeak:
        """max over tau of (p a_N + q v_N + c) / (alpha + rate v_N), elementwise, where the
        denominator is positive along the whole move (a torque over a speed-dependent
        limit, book sec. 6.1.1).

        Dinkelbach's method: r_{k+1} = N/D at the maximizer of N - r_k D, a linear peak
        (:meth:`maximum`). Each r_k is a value the law reaches; the sequence rises to the
        maximum superlinearly and stops when N - r_k D <= 0 everywhere (to rounding).
        With ``floor`` (per row, a value known to be reached elsewhere; -inf for none)
        the sequence starts there instead of at the maximizer of N: where no point of the
        move exceeds it the row stops after one step with the floor as its value (tau
        and piece then mean nothing).
        """
        return self._dinkelbach(p, q, c, alpha, rate, floor,
                                lambda rows, P, Q: self.maximum(P, Q))

    # ------------------------------------------------- restricted to a speed band
    @property
    def speeds_nonnegative(self) -> bool:
        """Whether v_N >= 0 along the whole move (to rounding, the exact minima of v_N
        included): where it holds, |v_N| = v_N and the bands of :meth:`band` are the
        parts of the move below and above a top speed."""
        order = self._speed_order(1.0)
        return bool(order.table.v.min() >= -1e-12 * self._scale_v)

    def band(self, bound: np.ndarray, side: float) -> SpeedBand:
        """The part of the move where v_N <= bound (side +1) or >= bound (side -1), per
        element of ``bound``: the samples inside and the points where v_N crosses it."""
        order = self._speed_order(side)
        bound = np.asarray(bound, dtype=float).ravel()
        last = np.searchsorted(order.x, side * bound, side="right") - 1
        return SpeedBand(side, bound, last, *order.crossings(self.law, bound))

    def bands(self, bound: np.ndarray) -> tuple[SpeedBand, SpeedBand]:
        """The parts below and above ``bound`` (:meth:`band` with side +1 and -1), their
        common ends (the crossings of v_N = bound) found once."""
        below, above = self._speed_order(1.0), self._speed_order(-1.0)
        bound = np.asarray(bound, dtype=float).ravel()
        ends = below.crossings(self.law, bound)
        return (SpeedBand(1.0, bound, np.searchsorted(below.x, bound, side="right") - 1, *ends),
                SpeedBand(-1.0, bound, np.searchsorted(above.x, -bound, side="right") - 1,
                          *ends))

    def maximum_within(self, p: np.ndarray | float, q: np.ndarray | float,
                       band: SpeedBand) -> LinearPeak:
        """max of p*a_N + q*v_N over the part of the move in ``band`` (one row of it per
        element of p, q), with its tau and piece; -inf where the part is empty.

        The maximum over a part of the curve is at a stationary point inside it or at one
        of its ends (where v_N crosses the bound). The samples inside are a prefix of the
        samples ordered by side*v_N, whose convex hulls the persistent chains of
        :class:`_SpeedOrder` hold: the support vertex is found on them by binary lifting
        (O(log n) per query), refined between its neighbouring samples as in
        :meth:`maximum` (a stationary point outside the band does not count), near ties
        with its neighbours on the hull likewise; the crossings are compared with it.
        """
        p, q = np.broadcast_arrays(np.asarray(p, dtype=float), np.asarray(q, dtype=float))
        P, Q = p.ravel(), q.ravel()
        n = len(P)
        order = self._speed_order(band.side)
        t = order.table
        value = np.full(n, -np.inf)
        tau = np.zeros(n)
        piece = np.zeros(n, dtype=np.intp)
        rows = np.flatnonzero(band.last >= 0)
        if len(rows):
            m, Pr, Qr = band.last[rows], P[rows], Q[rows]
            bound = band.bound[rows]
            found = np.empty(len(rows), dtype=np.intp)
            nearby = [np.full(len(rows), -1, dtype=np.intp) for _ in range(3)]
            for use_upper in (True, False):
                sel = np.flatnonzero((Pr >= 0.0) == use_upper)
                if len(sel):
                    chain, opposite = ((order.upper, order.lower) if use_upper
                                       else (order.lower, order.upper))
                    pos, near = order.support(chain, opposite, m[sel], band.side * Qr[sel],
                                              Pr[sel])
                    found[sel] = pos
                    for mine, theirs in zip(nearby, near, strict=True):
                        mine[sel] = theirs
            sample = order.order[found]
            val, tv, pv = self._refine(sample, Pr, Qr, t, bound, band.side)
            # near ties: the hull neighbours (on other arcs) within the sampling error
            margin = (np.abs(Pr) * self._miss_j + np.abs(Qr) * self._miss_snap
                      + 1e-13 * (np.abs(Pr) * self._scale_a + np.abs(Qr) * self._scale_v))
            for pos in nearby:
                ok = pos >= 0
                other = order.order[np.where(ok, pos, 0)]
                ok &= (np.abs(other - sample) > 1) | (t.piece[other] != t.piece[sample])
                ok &= Pr * t.a[other] + Qr * t.v[other] >= val - margin
                if ok.any():
                    sub = np.flatnonzero(ok)
                    v2, t2, i2 = self._refine(other[sub], Pr[sub], Qr[sub], t, bound[sub],
                                              band.side)
                    better = v2 > val[sub]
                    sub = sub[better]
                    val[sub], tv[sub], pv[sub] = v2[better], t2[better], i2[better]
            value[rows], tau[rows], piece[rows] = val, tv, pv
        if band.cross_ok.shape[1]:
            at = np.where(band.cross_ok, P[:, None] * band.cross_a + Q[:, None] * band.cross_v,
                          -np.inf)
            k = np.argmax(at, axis=1)
            best = at[np.arange(n), k]
            better = best > value
            value = np.where(better, best, value)
            tau = np.where(better, band.cross_tau[np.arange(n), k], tau)
            piece = np.where(better, band.cross_piece[np.arange(n), k], piece)
        shape = p.shape
        return LinearPeak(value.reshape(shape), tau.reshape(shape), piece.reshape(shape))

    def ratio_maximum_within(self, p: np.ndarray, q: np.ndarray, c: np.ndarray,
                             alpha: np.ndarray, rate: np.ndarray, band: SpeedBand,
                             floor: np.ndarray | None = None) -> LinearPeak:
        """max of (p a_N + q v_N + c) / (alpha + rate v_N) over the part of the move in
        ``band`` (the denominator positive there), elementwise: Dinkelbach's method as in
        :meth:`ratio_maximum`, each step a :meth:`maximum_within`. -inf where the part is
        empty.

        With ``floor`` (per row, a value known to be reached elsewhere) the iteration
        starts at r = floor: where max (N - floor D) <= 0 no point of the part exceeds
        it, the row stops after one step and its value is the floor itself (its tau and
        piece then mean nothing); elsewhere the result is the part's maximum."""
        return self._dinkelbach(p, q, c, alpha, rate, floor,
                                lambda rows, P, Q: self.maximum_within(P, Q, band.take(rows)))

    def _dinkelbach(self, p, q, c, alpha, rate, floor: np.ndarray | None,
                    maximize: Callable[[np.ndarray, np.ndarray, np.ndarray], LinearPeak]
                    ) -> LinearPeak:
        """Dinkelbach's iteration for :meth:`ratio_maximum` and
        :meth:`ratio_maximum_within`: ``maximize(rows, P, Q)`` is the linear peak of
        P a_N + Q v_N over the part of the move of those rows (-inf where it is empty)."""
        p, q, c, alpha, rate = (np.asarray(x, dtype=float).ravel()
                                for x in np.broadcast_arrays(p, q, c, alpha, rate))
        n = len(p)
        low = np.full(n, -np.inf) if floor is None else np.asarray(floor, dtype=float).ravel()
        tau, piece = np.zeros(n), np.zeros(n, dtype=np.intp)
        r = low.copy()
        fresh = np.flatnonzero(~np.isfinite(low))
        if len(fresh):
            start = maximize(fresh, p[fresh], q[fresh])
            tau[fresh], piece[fresh] = start.tau, start.piece
            v, a = piece_values(self.law, start.tau, start.piece, (1, 2))
            with np.errstate(divide="ignore", invalid="ignore"):
                r[fresh] = np.where(np.isfinite(start.value),
                                    (p[fresh] * a + q[fresh] * v + c[fresh])
                                    / (alpha[fresh] + rate[fresh] * v), -np.inf)
        index = np.flatnonzero(np.isfinite(r))
        for _ in range(DINKELBACH_STEPS):
            if len(index) == 0:
                break
            peak = maximize(index, p[index], q[index] - r[index] * rate[index])
            v, a = piece_values(self.law, peak.tau, peak.piece, (1, 2))
            new = (p[index] * a + q[index] * v + c[index]) / (alpha[index] + rate[index] * v)
            better = (new > r[index]) & np.isfinite(peak.value)  # (an empty part: no point)
            rows = index[better]
            gain = new[better] - r[rows]
            r[rows], tau[rows], piece[rows] = new[better], peak.tau[better], peak.piece[better]
            index = rows[gain > 1e-15 * np.abs(r[rows])]
        return LinearPeak(r, tau, piece)

    def _speed_order(self, side: float) -> _SpeedOrder:
        """The samples ordered by side*v_N with their persistent hull chains (per side,
        built on first use)."""
        if side not in self._speed_orders:
            if -side in self._speed_orders:
                table = self._speed_orders[-side].table
            else:
                table = _with_speed_extrema(self)
            self._speed_orders[side] = _SpeedOrder(table, side)
        return self._speed_orders[side]

    # ------------------------------------------------------------------ steps
    def _stationary_points(self, lo: np.ndarray, P: np.ndarray, Q: np.ndarray,
                           table: _Table | None = None) -> np.ndarray:
        """tau where the cubic Hermite model of g = p*j + q*a between the samples lo and
        lo + 1 (one piece, g changing sign) vanishes: safeguarded Newton on the model."""
        t = self._table if table is None else table
        hi = lo + 1
        width = t.tau[hi] - t.tau[lo]
        g0 = P * t.j[lo] + Q * t.a[lo]
        g1 = P * t.j[hi] + Q * t.a[hi]
        d0 = (P * t.snap[lo] + Q * t.j[lo]) * width
        d1 = (P * t.snap[hi] + Q * t.j[hi]) * width
        return t.tau[lo] + hermite_root(g0, g1, d0, d1) * width

    def _support_vertex(self, P: np.ndarray, Q: np.ndarray) -> np.ndarray:
        """Position in the hull of the vertex maximizing (Q, P).(v, a) (the support point)."""
        theta = np.arctan2(P, Q)
        start = self._angles[0]
        theta = np.where(theta < start, theta + 2.0 * math.pi, theta)
        k = np.searchsorted(self._angles, theta, side="left")
        return (self._shift + k) % len(self.hull)

    def _refine(self, sample: np.ndarray, P: np.ndarray, Q: np.ndarray,
                table: _Table | None = None, bound: np.ndarray | None = None,
                side: float = 1.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The maximum on the sample's piece between its neighbouring samples: the
        stationary point of p*a + q*v where its derivative changes sign, else the sample.
        With ``bound`` (per row) a stationary point counts only where side*(v_N - bound)
        <= 0 (the part of the move a :class:`SpeedBand` keeps; the sample is in it)."""
        t = self._table if table is None else table
        value = P * t.a[sample] + Q * t.v[sample]
        tau = t.tau[sample].copy()
        piece = t.piece[sample].copy()
        slope = P * t.j[sample] + Q * t.a[sample]
        right = np.minimum(sample + 1, len(t.tau) - 1)
        left = np.maximum(sample - 1, 0)
        go_right = (slope > 0.0) & ~t.last[sample]
        go_right &= P * t.j[right] + Q * t.a[right] < 0.0
        go_left = (slope < 0.0) & ~t.first[sample]
        go_left &= P * t.j[left] + Q * t.a[left] > 0.0
        rows = np.nonzero(go_right | go_left)[0]
        if len(rows) == 0:
            return value, tau, piece
        lo = np.where(go_right[rows], sample[rows], left[rows])
        P, Q, at = P[rows], Q[rows], piece[rows]
        root = self._stationary_points(lo, P, Q, t)
        # one Newton step on the law itself: the model's error (h^4) squared
        v, a, j, snap = piece_values(self.law, root, at, (1, 2, 3, 4))
        with np.errstate(divide="ignore", invalid="ignore"):
            newton = root - (P * j + Q * a) / (P * snap + Q * j)
        newton = np.clip(np.where(np.isfinite(newton), newton, root),
                         t.tau[lo], t.tau[lo + 1])
        v1, a1 = piece_values(self.law, newton, at, (1, 2))
        found, polished = P * a + Q * v, P * a1 + Q * v1
        if bound is not None:
            limit = bound[rows]
            found = np.where(side * (v - limit) <= 0.0, found, -np.inf)
            polished = np.where(side * (v1 - limit) <= 0.0, polished, -np.inf)
        where = np.where(polished > found, newton, root)
        found = np.maximum(found, polished)
        better = found > value[rows]
        chosen = rows[better]
        value[chosen], tau[chosen] = found[better], where[better]
        return value, tau, piece


class PeakedLaw(Protocol):
    """A law that holds its :class:`LinearPeaks` (sizer.laws.base.MotionLaw)."""

    @property
    def linear_peaks(self) -> LinearPeaks: ...


def maximum(law: PeakedLaw, p: np.ndarray | float, q: np.ndarray | float) -> LinearPeak:
    """max over tau in [0, 1] of p*a_N + q*v_N for arrays p, q (see the module docs)."""
    return law.linear_peaks.maximum(p, q)


def minimum(law: PeakedLaw, p: np.ndarray | float, q: np.ndarray | float) -> LinearPeak:
    """min over tau in [0, 1] of p*a_N + q*v_N for arrays p, q (see the module docs)."""
    return law.linear_peaks.minimum(p, q)
