"""Auto shape parameters searched to tolerance, for the cases without a closed form.

Friction, damping, efficiency, curved envelopes, stage limits, a given duration (the
largest smallest margin) or other families: the score of a shape (-T_min in minimize
mode, else the slacks of all checks smallest first, compared lexicographically) is
computed by the engine's own checks for each motor. One parameter: a coarse grid brackets
each motor's best point, then golden section narrows the bracket to TOLERANCE[1] (T_min
and the margins are max/min of quasi-convex/quasi-concave bounds, unimodal on the
bracket), or until the scores across the bracket agree to FLAT. Two parameters: the
same, nested (the inner search for each outer point), to TOLERANCE[2] per parameter
(coarser: the cost is the product of the two searches). Integer parameters are
enumerated. Motors at equal points are evaluated together (vectorized). In minimize
mode each T_min starts from the motor's previous one (warm_duration), falling back to
the full search of sizer.sizing.minimum_duration.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from sizer.laws import MotionLaw
from sizer.model.domain import Design
from sizer.sizing.candidates import Candidates
from sizer.sizing.checks import evaluate_checks, worst_slack
from sizer.sizing.cycle import CycleCalculator
from sizer.sizing.minimum_duration import evaluate, minimum_duration
from sizer.sizing.roots import illinois

GRID = {1: 13, 2: 7}
TOLERANCE = {1: 1e-12, 2: 1e-4}
"""Bracket width at which the golden section stops, per parameter. Two parameters cost
the product of the two searches, each point a full T_min search in minimize mode (about
0.1 s per motor with friction), so 1e-12 there would take hours; 1e-4 takes minutes."""
FLAT = 1e-13
TIE = 1e-14
WARM = 1e-2
INV_PHI = (math.sqrt(5.0) - 1.0) / 2.0

Scores = np.ndarray
"""(motors, m) rows compared lexicographically, higher is better."""


def search_shape(family: type[MotionLaw], fixed: dict[str, float],
                 ranges: dict[str, tuple[float, float]], design: Design,
                 motors: Candidates) -> dict[str, np.ndarray]:
    """The best value of each auto parameter per motor (arrays over the motors)."""
    names = list(ranges)
    params = {p.name: p for p in family.parameters}
    n = len(motors)
    dims = len(names)

    guess = np.full(n, np.nan)  # the last T_min of each motor, to start the next one

    def score(points: list[np.ndarray]) -> Scores:
        scores = evaluate_points(family, fixed, names, points, design, motors, guess)
        if design.task.minimize:
            found = np.isfinite(scores[:, 0])
            guess[found] = -scores[found, 0]
        return scores

    if dims == 1:
        best, _ = search_1d(lambda x: score([x]), params[names[0]], ranges[names[0]], n, dims)
        return {names[0]: best}
    outer, inner = names
    # the inner optimum of every outer point tried, to return the best pair at the end
    tried: list[tuple[np.ndarray, np.ndarray, Scores]] = []

    def outer_score(x: np.ndarray) -> Scores:
        y, scores = search_1d(lambda y: score([x, y]), params[inner], ranges[inner], n, dims)
        tried.append((x.copy(), y, scores))
        return scores

    search_1d(outer_score, params[outer], ranges[outer], n, dims)
    best_x, best_y, best_s = tried[0]
    for x, y, s in tried[1:]:
        take = beats(s, best_s)
        best_x, best_y = np.where(take, x, best_x), np.where(take, y, best_y)
        best_s = np.where(take[:, None], s, best_s)
    return {outer: best_x, inner: best_y}


def search_1d(score: Callable[[np.ndarray], Scores], parameter, bounds: tuple[float, float],
              n: int, dims: int) -> tuple[np.ndarray, Scores]:
    """Best point per motor of a 1-D score, and its score (grid, then golden section).

    A motor is settled when its bracket is narrower than TOLERANCE[dims] or when the
    scores at the bracket's ends and inner points agree to FLAT (the optimum's value is
    then known to that precision); settled motors are not evaluated again (their point
    is passed as nan).
    """
    lo, hi = bounds
    if parameter.integer:
        grid = np.arange(math.ceil(lo), math.floor(hi) + 1, dtype=float)
        if parameter.odd:
            grid = grid[grid % 2 == 1]
        best, best_s, _, _ = _best_on_grid(score, grid, n)
        return best, best_s
    grid = np.linspace(lo, hi, GRID[dims])
    best, best_s, index, on_grid = _best_on_grid(score, grid, n)
    rows = np.arange(n)
    left_i, right_i = np.maximum(index - 1, 0), np.minimum(index + 1, len(grid) - 1)
    a, b = grid[left_i], grid[right_i]
    fa, fb = on_grid[left_i, rows], on_grid[right_i, rows]
    x1, x2 = b - INV_PHI * (b - a), a + INV_PHI * (b - a)
    f1, f2 = score(x1), score(x2)
    active = np.ones(n, dtype=bool)
    while True:
        active &= (b - a > TOLERANCE[dims]) & ~_flat(fa, f1, f2, fb)
        if not active.any():
            break
        left = ~beats(f2, f1)  # the best lies in [a, x2]
        move_b, move_a = active & left, active & ~left
        fb = np.where(move_b[:, None], f2, fb)
        fa = np.where(move_a[:, None], f1, fa)
        b, a = np.where(move_b, x2, b), np.where(move_a, x1, a)
        new1 = np.where(left, b - INV_PHI * (b - a), x2)
        new2 = np.where(left, x1, a + INV_PHI * (b - a))
        f_new = score(np.where(active, np.where(left, new1, new2), np.nan))
        f1, f2 = (np.where(move_b[:, None], f_new, np.where(move_a[:, None], f2, f1)),
                  np.where(move_b[:, None], f1, np.where(move_a[:, None], f_new, f2)))
        x1, x2 = np.where(active, new1, x1), np.where(active, new2, x2)
    for x, s in ((x1, f1), (x2, f2)):
        take = beats(s, best_s)
        best, best_s = np.where(take, x, best), np.where(take[:, None], s, best_s)
    return best, best_s


def _flat(*scores: Scores) -> np.ndarray:
    """Per row: all the score rows agree to FLAT (relative, or absolute near zero)."""
    first = scores[0]
    with np.errstate(invalid="ignore"):
        same = [np.isclose(s, first, rtol=FLAT, atol=FLAT) | (s == first) for s in scores[1:]]
    return np.all(np.stack(same), axis=(0, 2))


def _best_on_grid(score, grid: np.ndarray,
                  n: int) -> tuple[np.ndarray, Scores, np.ndarray, np.ndarray]:
    """Best grid point per motor (first of equals), its score, its index, all scores."""
    every = np.stack([score(np.full(n, x)) for x in grid])
    index = np.zeros(n, dtype=int)
    best_s = every[0]
    for i in range(1, len(grid)):
        take = beats(every[i], best_s)
        index, best_s = np.where(take, i, index), np.where(take[:, None], every[i], best_s)
    return grid[index], best_s, index, every


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


def evaluate_points(family: type[MotionLaw], fixed: dict[str, float], names: list[str],
                    points: list[np.ndarray], design: Design,
                    motors: Candidates, guess: np.ndarray | None = None) -> Scores:
    """The score of each motor at its own point (motors at equal points evaluated together)."""
    n = len(motors)
    stacked = np.column_stack(points)
    wanted = np.nonzero(~np.isnan(stacked).any(axis=1))[0]
    if not len(wanted):
        return np.full((n, 1), -np.inf)
    keys, inverse = np.unique(stacked[wanted], axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    out: Scores | None = None
    for k, key in enumerate(keys):
        members = wanted[np.nonzero(inverse == k)[0]]
        law = family(**fixed, **{name: float(v) for name, v in zip(names, key, strict=True)})
        subset = motors if len(members) == n else motors.take(members)
        rows = score_law(law, design, subset,
                         None if guess is None else guess[members])
        if out is None:
            out = np.full((n, rows.shape[1]), -np.inf)
        out[members] = rows
    assert out is not None
    return out


def score_law(law: MotionLaw, design: Design, candidates: Candidates,
              guess: np.ndarray | None = None) -> Scores:
    """(-T_min,) in minimize mode (-inf if infeasible), else the sorted slacks."""
    motors, drive = candidates.motors, candidates.drive
    if design.transmission.linkage is not None:  # through the linkage (issue 14)
        from sizer.sizing.linkage_sizing import evaluate_linkage

        duration, _, checks, feasible = evaluate_linkage(design, law, motors, drive)
        if design.task.minimize:
            return -np.where(feasible, duration, np.inf)[:, None]
        return np.sort(np.stack([c.slack for c in checks], axis=1), axis=1)
    calculator = CycleCalculator(None, design.task, drive, motors,
                                 design.limits.thermal_speed, law=law)
    if design.task.minimize:
        T = warm_duration(calculator, design, guess) if guess is not None else None
        if T is None:
            solution = minimum_duration(calculator, design.limits)
            T = np.where(solution.feasible, solution.duration, np.inf)
        return -T[:, None]
    metrics = calculator.evaluate(np.full(len(motors), design.task.duration))
    checks = evaluate_checks(metrics, motors, drive, design.limits, design.task.linear)
    return np.sort(np.stack([c.slack for c in checks], axis=1), axis=1)


def warm_duration(calculator: CycleCalculator, design: Design,
                  guess: np.ndarray) -> np.ndarray | None:
    """T_min near a previous one (a neighbouring shape's): the worst slack bracketed in
    [guess (1 - WARM), guess (1 + WARM)], then the Illinois method on log T to 1e-14
    (the feasible end returned). None when a motor has no guess or no bracket there:
    the caller then uses the full search of sizer.sizing.minimum_duration."""
    if not np.all(np.isfinite(guess)):
        return None

    def slack(T: np.ndarray) -> np.ndarray:
        return worst_slack(evaluate(calculator, design.limits, T)[1])

    lo, hi = guess * (1.0 - WARM), guess * (1.0 + WARM)
    f_lo, f_hi = slack(lo), slack(hi)
    if not (np.all(f_lo < 0.0) and np.all(f_hi >= 0.0)):
        return None
    root = illinois(lambda x: slack(np.exp(x)), np.log(lo), np.log(hi), f_lo, f_hi,
                    xtol=1e-14)
    T = np.exp(root)
    for _ in range(8):  # the feasible side, as minimum_duration reports it
        short = slack(T) < 0.0
        if not short.any():
            return T
        T = np.where(short, T * (1.0 + 1e-14), T)
    return None
