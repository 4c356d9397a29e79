"""The cheaper per-law analysis gives the old floats bit for bit (issue 34): the convex
hull of a law's (v_N, a_N) samples (thinning passes on a linked list, the monotone chain
pushing runs of left turns at once) against the plain thinning and point-by-point chain
it replaced, kept here; a shaped law's pieces (terms on one base piece evaluated in one
call) and the trigonometric pieces (constants per order) against their plain formulas."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sizer.laws import make_law
from sizer.laws.linear_peaks import (
    LinearPeaks,
    _chain_on,
    _chain_vertices,
    _convex_hull,
    piece_values,
)
from sizer.laws.pieces import trig_poly_piece


def plain_chain_vertices(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """The replaced _chain_vertices: 32 vectorized thinning passes, then the chain."""
    kept = np.arange(len(x), dtype=np.intp)
    for _ in range(32):
        if len(kept) < 3:
            return kept
        a, b, c = kept[:-2], kept[1:-1], kept[2:]
        flat = (x[b] - x[a]) * (y[c] - y[a]) - (y[b] - y[a]) * (x[c] - x[a]) <= 0.0
        if not flat.any():
            return kept
        kept = kept[~np.concatenate(([False], flat, [False]))]
    return plain_chain(x, y, kept.tolist())


def plain_chain(x: np.ndarray, y: np.ndarray, kept: list[int]) -> np.ndarray:
    """Andrew's monotone chain, point by point, on the points ``kept`` in their order."""
    xs, ys = x.tolist(), y.tolist()
    hull: list[int] = []
    for i in kept:
        while len(hull) >= 2:
            a0, b0 = hull[-2], hull[-1]
            if (xs[b0] - xs[a0]) * (ys[i] - ys[a0]) - (ys[b0] - ys[a0]) * (xs[i] - xs[a0]) > 0.0:
                break
            hull.pop()
        hull.append(i)
    return np.array(hull, dtype=np.intp)


def plain_convex_hull(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """The replaced _convex_hull (its run handling unchanged), on the plain chains."""
    order = np.lexsort((y, x))
    xs, ys = x[order], y[order]
    count = len(xs)
    new = np.ones(count, dtype=bool)
    new[1:] = (xs[1:] != xs[:-1]) | (ys[1:] != ys[:-1])
    starts = np.flatnonzero(new)
    ends = np.append(starts[1:], count) - 1
    if len(starts) == 1:
        return order[[0, count - 1]] if count > 1 else order[:0]
    ux, uy = xs[starts], ys[starts]
    lower = plain_chain_vertices(ux, uy)
    upper = plain_chain_vertices(ux[::-1], uy[::-1])
    last = len(starts) - 1
    lower_sorted = np.where(lower == 0, starts[0], ends[lower])[:-1]
    upper_sorted = np.where(upper == 0, ends[last], starts[last - upper])[:-1]
    return order[np.concatenate((lower_sorted, upper_sorted))]


LAWS = ["cycloidal", "harmonic", "modified_trapezoidal", "modified_sinusoidal",
        "modified_cycloidal(kappa=-0.9)", "trapezoidal(alpha=0.07)",
        "double_s(alpha=0.2, beta=0.3)",
        "elliptic(n=400)", "exponential(sigma=90, lam=0.2)", "polynomial(degree=17)",
        "fifteen_segments", "cycloidal_blends(alpha=0.3)", "circular_blends(ratio=20)",
        "{kind: shaped, law: cycloidal, shaper: zv, f_T: 3.7}",
        "{kind: shaped, law: cycloidal, shaper: ei3, f_T: 11}",
        "{kind: shaped, law: double_s, shaper: zvd, f_T: 6.5, damping_ratio: 0.05}",
        "{kind: shaped, law: 'elliptic(n=50)', shaper: zvdd, f_T: 21}",
        "{kind: cubic_spline, points: [[0, 0], [0.3, 0.15], [0.55, 0.8], [1, 1]]}",
        "{kind: bspline, order: 6, points: [[0, 0], [0.3, 0.15], [0.55, 0.8], [1, 1]], "
        "start: {velocity: 0, acceleration: 0}, end: {velocity: 0, jerk: 0}}",
        "{kind: shaped, law: {kind: cubic_spline, points: [[0, 0], [0.4, 0.3], [1, 1]]}, "
        "shaper: zv, f_T: 9.5}"]


@pytest.mark.parametrize("spec", LAWS)
def test_the_hull_of_a_law_is_the_plain_one(spec):
    peaks = LinearPeaks(make_law(spec))
    np.testing.assert_array_equal(peaks.hull, plain_convex_hull(peaks.v, peaks.a))


@pytest.mark.parametrize("seed", range(6))
def test_the_hull_of_noisy_and_wavy_curves_is_the_plain_one(seed):
    """Dense loops with noise (many short pop cascades) and a slow wave (a concave run
    the thinning eats two points a pass, past its 32 passes)."""
    rng = np.random.default_rng(seed)
    t = np.sort(rng.uniform(0.0, 2.0 * np.pi, 3000))
    r = 1.0 + 10.0 ** rng.uniform(-12, -2) * rng.standard_normal(len(t))
    x, y = r * np.cos(t), r * np.sin(2.0 * t + seed)
    np.testing.assert_array_equal(_convex_hull(x, y), plain_convex_hull(x, y))
    u = np.linspace(0.0, 1.0, 400 + 50 * seed)  # a convex arc, then a point far below:
    x = np.append(u, 1.0 + 10.0 ** -seed)  # (the thinning drops one a pass)
    y = np.append(u**2 * (1.0 + seed), -10.0)
    np.testing.assert_array_equal(_convex_hull(x, y), plain_convex_hull(x, y))


@pytest.mark.parametrize("seed", range(4))
def test_the_chain_is_the_plain_chain(seed):
    """Random points (a wrong turn at every other point), noisy convex arcs (a few) and
    arcs with points far below (long pop cascades), pushed at once between them."""
    rng = np.random.default_rng(seed)
    for count in (0, 1, 2, 3, 4, 7, 60, 500):
        x = np.sort(rng.uniform(0.0, 1.0, count))
        for y in (rng.uniform(0.0, 1.0, count), x**2 + 1e-4 * rng.standard_normal(count),
                  np.where(rng.uniform(size=count) < 0.02, -1.0, x**2)):
            np.testing.assert_array_equal(_chain_on(x, y), plain_chain(x, y, list(range(count))))


@pytest.mark.parametrize("seed", range(4))
def test_the_thinned_chain_is_the_plain_one(seed):
    """Convex arcs with points far below (the thinning drops one a pass on each, past its
    32 passes, some with noise): the linked-list passes and the chain after them."""
    rng = np.random.default_rng(seed)
    for count in (40, 300, 2000):
        x = np.sort(rng.uniform(0.0, 1.0, count))
        y = x**2 + 10.0 ** rng.uniform(-14, -3) * rng.standard_normal(count)
        y[rng.choice(count, 1 + seed, replace=False)] = -1.0
        np.testing.assert_array_equal(_chain_vertices(x, y), plain_chain_vertices(x, y))


def test_the_hull_of_lattice_points_is_the_plain_one():
    rng = np.random.default_rng(7)
    for size in (1, 2, 3, 5, 40, 300):
        x, y = (rng.integers(-3, 4, size).astype(float) for _ in range(2))
        np.testing.assert_array_equal(_convex_hull(x, y), plain_convex_hull(x, y))


def plain_shaped(law, tau: np.ndarray, order: int) -> np.ndarray:
    """q_s^(k) = sum A_i r^-k q_N^(k)((tau - tau_i) / r), piece by piece as the law did
    before: every term through the base law's piece_derivative, in the shaper's order."""
    base, r = law.base, law.base_fraction
    starts = np.asarray(base.breakpoints[:-1])
    out = np.empty(len(tau))
    index = np.clip(np.searchsorted(law.breakpoints, tau, side="right") - 1, 0,
                    len(law.pieces) - 1)
    for k, piece in enumerate(law.pieces):
        at = tau[index == k]
        middle = 0.5 * (piece.start + piece.end)
        value = np.full(at.shape, 0.0)
        offset = 0.0
        terms = []
        for a, t in zip(law.shaper.amplitudes, law.shaper.times, strict=True):
            u = (middle - t) / r
            if u >= 1.0:
                offset += float(a)
            elif u > 0.0:
                terms.append((float(a), float(t),
                              int(np.searchsorted(starts, u, side="right")) - 1))
        value = np.full(at.shape, offset if order == 0 else 0.0)
        for a, t, i in terms:
            value += (a * r**-order) * base.piece_derivative(i, (at - t) / r, order)
        out[index == k] = value
    return out


@pytest.mark.parametrize("spec", [s for s in LAWS if "shaped" in s])
def test_shaped_pieces_are_the_plain_sum(spec):
    law = make_law(spec)
    tau = np.random.default_rng(3).uniform(0.0, 1.0, 2000)
    for order in range(5):
        np.testing.assert_array_equal(
            np.concatenate([p.evaluate(p.clamp(tau[(tau >= p.start) & (tau < p.end)]), order)
                            for p in law.pieces]),
            np.concatenate([plain_shaped(law, tau[(tau >= p.start) & (tau < p.end)], order)
                            for p in law.pieces]))


def test_trigonometric_pieces_are_the_plain_formula():
    sines = [(-1 / (2 * math.pi), 2 * math.pi, 0.0), (0.3, 5.0, 0.25)]
    piece = trig_poly_piece(0.1, 0.9, (0.5, -1.0, 2.0, 0.25), sines, origin=0.1)
    tau = np.linspace(0.1, 0.9, 501)
    for order in range(6):
        coef = np.polynomial.polynomial.polyder([0.5, -1.0, 2.0, 0.25], order) \
            if order < 4 else np.zeros(1)
        x = tau - 0.1
        plain = coef[-1] + x * 0.0
        for c in coef[-2::-1]:
            plain = c + plain * x
        plain = plain + 0.0
        for amplitude, omega, phase in sines:
            plain = plain + amplitude * omega**order * np.sin(omega * tau + phase
                                                              + order * math.pi / 2)
        np.testing.assert_array_equal(piece.evaluate(tau, order), plain)


def test_piece_values_broadcasts_as_before():
    law = make_law("{kind: shaped, law: cycloidal, shaper: zv, f_T: 3.7}")
    tau = np.linspace(0.0, 1.0, 12).reshape(3, 4)
    piece = np.clip(np.searchsorted(law.breakpoints, tau, side="right") - 1, 0,
                    len(law.pieces) - 1)
    v, a = piece_values(law, tau, piece, (1, 2))
    np.testing.assert_array_equal(v, law.derivative(tau, 1))
    np.testing.assert_array_equal(a, law.derivative(tau, 2))
    row = piece_values(law, tau[0], np.array([1]), 2)  # broadcast against one piece
    assert row.shape == (4,)
    np.testing.assert_array_equal(row, np.array([law.piece_derivative(1, t, 2) for t in tau[0]]))
