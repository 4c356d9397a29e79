"""Where a unimodal score is best, per row, in few steps: a bracket search that steps to
where two bounds cross, safeguarded by golden-section-like steps.

The scores are (rows, m) arrays compared lexicographically, higher is better
(:func:`beats`). A shortest duration is the largest of smooth per-check bounds, a
largest smallest margin the smallest of smooth margins: their optimum over a shape
parameter is mostly where two of them cross (a kink), else a smooth optimum of one.
From a grid's best point and its neighbours (:func:`from_grid`), each step tries one
point per row: where the lines through the points either side of the bracket meet, or
the vertex of the parabola through it, whichever model foretold a point it was not
fitted to better (and within TRUST of the score's rise across the bracket); else, and
where the bracket did not halve in two steps, a point on its wider side. The crossing
converges like a secant at a kink, the parabola at a smooth optimum, the safeguard like
golden section (book-independent numerics; sizer.sizing.choices and
sizer.sizing.optimal_shapes search shape parameters with it). Every row's steps depend
on its own values only.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from sizer.numerics.golden import INV_PHI

Scores = np.ndarray
"""(rows, m) arrays compared lexicographically, higher is better."""

FLAT = 1e-13
"""Scores agreeing to FLAT (relative, or absolute near zero) across a bracket whose best
point lies well inside it settle the row: the optimum's value is known to rounding."""
TIE = 1e-14
"""Entries within TIE (relative) of each other tie: the next entry decides (:func:`beats`)."""
TRUST = 0.3
"""A step goes where a model of the score (two crossing lines, or a parabola) puts the
optimum only where that model foretold a point it was not fitted to within TRUST times
the rise of the score across the bracket (:func:`_v_step`)."""


def from_grid(score: Callable[[np.ndarray], Scores], grid: np.ndarray, on_grid: Scores,
              index: np.ndarray, tol: float) -> tuple[np.ndarray, Scores]:
    """Best point per row, and its score, from the grid's scores (``on_grid``: (points,
    rows, m)) and each row's best grid point ``index``: its neighbours bracket the best
    (the score unimodal there), and each step tries one point in the bracket until it is
    narrower than ``tol`` or the deciding entry (:func:`deciding`) agrees to FLAT across
    it with its best point well inside. A best point at an end of the grid is first
    compared with the point tol/2 beside it: where the end is better (beyond TIE) the
    optimum is the end, settled in one step; else the search goes on from that point.
    ``score(x)`` scores each row at its own point, nan for a settled row (its score is
    then not read). The best of all the points tried is returned."""
    n = len(index)
    rows, last = np.arange(n), len(grid) - 1
    best, best_s = grid[index], on_grid[index, rows]

    def at(i: np.ndarray) -> tuple[np.ndarray, Scores]:
        """The grid's points and scores at indices i (nan beyond the grid)."""
        inside = (i >= 0) & (i <= last)
        k = np.clip(i, 0, last)
        return (np.where(inside, grid[k], np.nan),
                np.where(inside[:, None], on_grid[k, rows], np.nan))

    (lo_x, f_lo), (a, fa) = at(index - 2), at(np.maximum(index - 1, 0))
    (b, fb), (r, fr) = at(np.minimum(index + 1, last)), at(index + 2)
    m, fm = grid[index], best_s
    active = np.ones(n, dtype=bool)
    edge = (index == 0) | (index == last)
    if edge.any():  # the point beside the end: the end stays best, or the bracket is
        low = index == 0  # (end, beside, next)
        z = np.where(edge, m + np.where(low, 0.5, -0.5) * tol, np.nan)
        f_z = score(z)
        best, best_s = keep_best(best, best_s, z, f_z, edge)
        # settled where the end is better beyond TIE; a tie (a slope too small to show
        # over tol/2) says nothing: the search goes on in (end, beside, next)
        moved = edge & ~beats(fm, f_z)
        active &= ~edge | moved
        a, fa = np.where(moved & low, m, a), np.where((moved & low)[:, None], fm, fa)
        b, fb = np.where(moved & ~low, m, b), np.where((moved & ~low)[:, None], fm, fb)
        m, fm = np.where(moved, z, m), np.where(moved[:, None], f_z, fm)
    before = [np.full(n, np.inf), np.full(n, np.inf)]  # the widths of the last two steps
    while True:
        # the entry that depends on the shape known to FLAT across the bracket: its
        # optimum is found (the next entries would only break ties within rounding)
        column = deciding(fa, fm, fb)
        decides = [f[rows, column][:, None] for f in (fa, fm, fb)]
        active &= (b - a > tol) & ~(agree(*decides) & (np.minimum(m - a, b - m)
                                                        >= 0.2 * (b - a)))
        if not active.any():
            break
        values = np.stack([f_lo, fa, fm, fb, fr])
        z = _v_step(np.stack([lo_x, a, m, b, r]), -values[:, rows, column])
        # else a point on the wider side: at the golden section, or at three times the
        # narrow side's width where that is nearer (m is then likely within it: the
        # bracket closes around m, else the next such step goes three times as far)
        wide_right = b - m > m - a
        wide, narrow = np.maximum(b - m, m - a), np.minimum(b - m, m - a)
        step = np.minimum((1 - INV_PHI) * wide, 3.0 * narrow)
        z = np.where(np.isnan(z) | (b - a > 0.5 * before[0]),
                     np.where(wide_right, m + step, m - step), z)
        z = _apart(z, a, m, b, 0.25 * tol)
        f_z = score(np.where(active, z, np.nan))
        best, best_s = keep_best(best, best_s, z, f_z, active)
        before = [before[1], b - a]
        # the inner points u < w: the bracket keeps the better one inside, the point it
        # leaves out is the next beyond it on that side
        z_left = z < m
        u, w = np.where(z_left, z, m), np.where(z_left, m, z)
        f_u, f_w = (np.where(z_left[:, None], f_z, fm), np.where(z_left[:, None], fm, f_z))
        to_left = active & ~beats(f_w, f_u)  # the best lies in [a, w]
        to_right = active & ~to_left  # in [u, b]
        r, fr = np.where(to_left, b, r), np.where(to_left[:, None], fb, fr)
        lo_x, f_lo = np.where(to_right, a, lo_x), np.where(to_right[:, None], fa, f_lo)
        b, fb = np.where(to_left, w, b), np.where(to_left[:, None], f_w, fb)
        a, fa = np.where(to_right, u, a), np.where(to_right[:, None], f_u, fa)
        m = np.where(to_left, u, np.where(to_right, w, m))
        fm = np.where(to_left[:, None], f_u, np.where(to_right[:, None], f_w, fm))
    return best, best_s


def deciding(*scores: Scores) -> np.ndarray:
    """Per row the first entry of the scores that is not the same at every point (the
    first that depends on the shape; the first where none does): a given duration's
    smallest margin may not depend on the shape (the inertia ratio), and the next one
    decides."""
    first = scores[0]
    varies = np.zeros(first.shape, dtype=bool)
    for s in scores[1:]:
        varies |= s != first
    return np.argmax(varies, axis=1)


def keep_best(best: np.ndarray, best_s: Scores, x: np.ndarray, s: Scores,
              where: np.ndarray) -> tuple[np.ndarray, Scores]:
    """The best point so far per row: x where ``where`` and its score s beats it."""
    take = where & beats(s, best_s)
    return np.where(take, x, best), np.where(take[:, None], s, best_s)


def _v_step(x: np.ndarray, f: np.ndarray) -> np.ndarray:
    """The next point to try per row (nan where none is found), from the points
    x = (p, a, m, b, r) (p, r beyond the bracket a < m < b, nan where there are none) and
    the values f to minimize there: where the two bounds cross, or the vertex of the
    parabola through a, m, b, whichever model foretells the points it was not fitted to
    better, if within TRUST of the rise across the bracket. Crossing: if m lies on the
    falling bound, the lines through (a, m) and (b, r) meet at the optimum when the bounds
    are straight (told p); if on the rising one, those through (p, a) and (m, b) (told r).
    A line joining points on either bound lies above them where they are convex, so of
    the two crossings found the lower one is taken. The parabola converges where the
    optimum is a smooth minimum of one bound."""
    p, a, m, b, r = x
    fp, fa, fm, fb, fr = f
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        x1, y1, miss1 = _crossing_of(a, fa, m, fm, b, fb, r, fr, p, fp)
        x2, y2, miss2 = _crossing_of(p, fp, a, fa, m, fm, b, fb, r, fr)
        ok1 = (x1 > m) & (x1 < b)
        ok2 = (x2 > a) & (x2 < m)
        take1 = ok1 & ~(ok2 & (y2 < y1))
        cross = np.where(take1, x1, np.where(ok2, x2, np.nan))
        miss = np.where(take1, miss1, miss2)
        slope = (fm - fa) / (m - a)
        curve = ((fb - fm) / (b - m) - slope) / (b - a)
        vertex = np.where(curve > 0.0, 0.5 * (a + m) - slope / (2.0 * curve), np.nan)
        vertex = np.where((vertex > a) & (vertex < b), vertex, np.nan)

        def parabola(t: np.ndarray) -> np.ndarray:
            return fa + slope * (t - a) + curve * (t - a) * (t - m)

        told = np.fmax(np.abs(parabola(p) - fp), np.abs(parabola(r) - fr))
        # a model is trusted where it foretold its held-out point within TRUST of the
        # rise across the bracket (a wall, such as T_min as beta -> 0, fits neither)
        trust = TRUST * (np.maximum(fa, fb) - fm)
        cross = np.where(miss <= trust, cross, np.nan)
        vertex = np.where(told <= trust, vertex, np.nan)
        use_vertex = ~np.isnan(vertex) & (np.isnan(cross) | (told < miss))
        return np.where(use_vertex, vertex, cross)


def _crossing_of(x0: np.ndarray, f0: np.ndarray, x1: np.ndarray, f1: np.ndarray,
                 x2: np.ndarray, f2: np.ndarray, x3: np.ndarray, f3: np.ndarray,
                 xt: np.ndarray, ft: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Where the falling line through (x0, f0), (x1, f1) meets the rising one through
    (x2, f2), (x3, f3), its value there (nan where the slopes do not fall and rise), and
    how far the line on the side of (xt, ft) misses it (nan where there is no such point)."""
    falling = (f1 - f0) / (x1 - x0)
    rising = (f3 - f2) / (x3 - x2)
    good = (falling < 0.0) & (rising > 0.0) & np.isfinite(falling) & np.isfinite(rising)
    x = (f2 - f1 + falling * x1 - rising * x2) / (falling - rising)
    told = np.where(xt < x0, f1 + falling * (xt - x1), f2 + rising * (xt - x2))
    return (np.where(good, x, np.nan), np.where(good, f1 + falling * (x - x1), np.nan),
            np.abs(told - ft))


def _apart(z: np.ndarray, a: np.ndarray, m: np.ndarray, b: np.ndarray,
           gap: float) -> np.ndarray:
    """z moved to at least ``gap`` from m and inside [a + gap, b - gap]."""
    z = np.clip(z, a + gap, b - gap)
    side = np.where(z == m, np.where(b - m > m - a, 1.0, -1.0), np.sign(z - m))
    side = np.where(np.where(side > 0, b - m, m - a) < 2.0 * gap, -side, side)
    return np.where(np.abs(z - m) < gap, m + side * gap, z)


def agree(*scores: Scores) -> np.ndarray:
    """Per row: all the score rows agree to FLAT (relative, or absolute near zero)."""
    first = scores[0]
    with np.errstate(invalid="ignore"):
        same = [np.isclose(s, first, rtol=FLAT, atol=FLAT) | (s == first) for s in scores[1:]]
    return np.all(np.stack(same), axis=(0, 2))


def beats(new: Scores, old: Scores) -> np.ndarray:
    """Per row: new is better than old at the first entry where they differ beyond
    rounding (TIE relative: a check that does not depend on the shape ties,
    and the next one decides); nan counts as worst."""
    new = np.where(np.isnan(new), -np.inf, new)
    old = np.where(np.isnan(old), -np.inf, old)
    with np.errstate(invalid="ignore"):
        differs = ~np.isclose(new, old, rtol=TIE, atol=1e-300) & (new != old)
    first = np.argmax(differs, axis=1)
    rows = np.arange(len(new))
    return differs.any(axis=1) & (new[rows, first] > old[rows, first])
