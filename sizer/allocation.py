"""Cycle-time allocation (issue 39): each candidate's own split of a given cycle time
among the free moves of a cycle, the one that minimizes a goal (docs/allocation.md).

With the cycle time T_c given and the fixed segments (dwells, runs, fixed moves) at their
durations, the free moves share F = T_c - (fixed time): T_1 + ... + T_m = F. The goals
are sums of one term per segment (a separable resource allocation):

- the RMS motor torque: RMS^2 T_c = sum of each segment's integral of tau^2 (the fixed
  segments' terms are constants), so the least RMS is the least sum of the free moves'
  integrals E_j(T_j);
- the electrical energy per cycle: each segment's shaft work plus its copper loss
  f R/k_t^2 times its integral of tau^2.

The caller (sizer.sizing.cycle.SegmentCycle) gives each term from the engine, for any
candidates at any durations (``cost``); this module only searches, over arrays of
candidates (no loop over motors).

Method, per round for every candidate still open: the slope g_j and curvature H_j of each
E_j at the current T_j (central differences of the engine's values); the KKT condition
of the least sum under the sum constraint is equal marginal costs, E_j'(T_j) = -lambda for
every free move. Each E_j' is modelled locally (a power law -p T^-q where E_j falls and
is convex, exact for a purely inertial move, whose integral is c/T^3; else its tangent
line g + H (T - T_j)), so that T_j(lambda) is explicit and decreasing; the lambda at which
they sum to F is found by the project's vectorized root finder
(sizer.numerics.roots.bracketed_root) for all candidates at once. The step towards that split
is halved until the goal does not rise (the engine's values, not the model's), each
T_j kept within a factor TRUST of its value. The rounds stop per candidate when no T_j
moves by more than TOLERANCE of itself.

A law per free move (:func:`allocate_laws`): every combination of the laws offered a row
of that search where they are few, each candidate's best row taken; else laws and split
chosen in turn. The largest residual vibration (:func:`minimax_split`): not a sum and not
smooth, one split for all candidates, a coarse grid of the simplex then a pattern search.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from sizer.numerics.arrays import sorted_unique
from sizer.numerics.roots import bracketed_root

Cost = Callable[[int, np.ndarray, np.ndarray], np.ndarray]
"""``cost(j, T, rows)``: free move j's term of the goal at durations T (k,) for the
candidates ``rows`` (k,), repeats allowed: an array (k,)."""

SLOPE_STEP = 1e-5
"""The relative step of the central difference for the slope E'(T)."""
CURVATURE_STEP = 1e-3
"""The relative step of the second difference for the curvature E''(T)."""
TRUST = 4.0
"""A round moves no duration by more than this factor."""
TOLERANCE = 1e-11
"""A candidate is done when no duration moves by more than this share of itself."""
ROUNDS = 40
HALVINGS = 30


@dataclass(frozen=True)
class Split:
    """Per candidate the free moves' durations (candidates, moves), summing to F, and
    whether its rounds converged (else the best split found: the goal never rose)."""

    durations: np.ndarray
    converged: np.ndarray


def allocate(cost: Cost, free_time: np.ndarray, start: np.ndarray) -> Split:
    """The split of ``free_time`` (candidates,) among the free moves that minimizes the
    sum of ``cost`` over them, from ``start`` (candidates, moves; scaled to sum to F).
    A candidate whose goal is not finite at its start keeps its start."""
    F = np.asarray(free_time, dtype=float)
    D = np.array(start, dtype=float)
    D *= (F / D.sum(axis=1))[:, None]
    n, m = D.shape
    converged = np.zeros(n, dtype=bool)
    if m < 2:
        return Split(D, np.ones(n, dtype=bool))
    open_ = np.arange(n)
    for _ in range(ROUNDS):
        if not len(open_):
            break
        T = D[open_]
        value, slope, curve = _derivatives(cost, T, open_)
        total = value.sum(axis=1)
        good = np.isfinite(total) & np.isfinite(slope).all(axis=1) \
            & np.isfinite(curve).all(axis=1)
        converged[open_[~good]] = False
        open_, T, value, slope, curve, total = (
            x[good] for x in (open_, T, value, slope, curve, total))
        if not len(open_):
            break
        target = _model_split(T, slope, curve, F[open_])
        step = target - T
        alpha = np.ones(len(open_))
        todo = np.arange(len(open_))
        for _ in range(HALVINGS):  # halve where the goal rose
            trial = T[todo] + alpha[todo, None] * step[todo]
            new = _total(cost, trial, open_[todo])
            rose = ~(new <= total[todo] + 1e-14 * np.abs(total[todo]))
            todo = todo[rose]
            if not len(todo):
                break
            alpha[todo] *= 0.5
        alpha[todo] = 0.0  # no descent found: keep the split (the best one)
        moved = alpha[:, None] * step
        D[open_] = T + moved
        D[open_] *= (F[open_] / D[open_].sum(axis=1))[:, None]
        done = np.max(np.abs(moved) / T, axis=1) <= TOLERANCE
        converged[open_[done]] = True
        open_ = open_[~done & (alpha > 0.0)]
    return Split(D, converged)


def _derivatives(cost: Cost, T: np.ndarray, rows: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Each term's value, slope and curvature at T (k, m): one call of ``cost`` per free
    move with the five points of both differences."""
    k, m = T.shape
    factors = np.array([1.0, 1.0 - SLOPE_STEP, 1.0 + SLOPE_STEP, 1.0 - CURVATURE_STEP,
                        1.0 + CURVATURE_STEP])
    value, slope, curve = (np.empty((k, m)) for _ in range(3))
    every = np.tile(rows, len(factors))
    for j in range(m):
        points = (factors[:, None] * T[None, :, j]).ravel()
        E = np.asarray(cost(j, points, every), dtype=float).reshape(len(factors), k)
        with np.errstate(invalid="ignore", over="ignore"):
            value[:, j] = E[0]
            slope[:, j] = (E[2] - E[1]) / (2.0 * SLOPE_STEP * T[:, j])
            curve[:, j] = (E[4] - 2.0 * E[0] + E[3]) / np.square(CURVATURE_STEP * T[:, j])
    return value, slope, curve


def _total(cost: Cost, T: np.ndarray, rows: np.ndarray) -> np.ndarray:
    return np.sum([np.asarray(cost(j, T[:, j], rows), dtype=float)
                   for j in range(T.shape[1])], axis=0)


def _model_split(T: np.ndarray, g: np.ndarray, H: np.ndarray, F: np.ndarray) -> np.ndarray:
    """The split (k, m) at which the local models of the marginal costs are equal and the
    durations sum to F, each within a factor TRUST of T (the KKT condition on the models:
    one lambda per candidate, by the root finder over all candidates at once)."""
    power = (g < 0.0) & (H > 0.0)  # E' = -p T^-q: q = H T / |g|
    with np.errstate(divide="ignore", invalid="ignore"):
        q = np.where(power, H * T / np.abs(g), 1.0)
        # the tangent line where E' is not a falling power: a curvature > 0 to move on
        H_line = np.where(H > 0.0, H, (np.abs(g) + 1e-300) / T)
    scale = np.maximum(np.mean(np.abs(g), axis=1), 1e-300)  # lambda in units of |g|
    lo_T, hi_T = T / TRUST, T * TRUST

    def lam_at(D: np.ndarray) -> np.ndarray:  # the (scaled) lambda of each model at D
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            along = np.where(power, np.abs(g) * (T / D) ** q, -(g + H_line * (D - T)))
        return along / scale[:, None]

    def split(lam: np.ndarray, T, g, q, H_line, power, scale) -> np.ndarray:
        x = lam[:, None] * scale[:, None]
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            D = np.where(power, T * (np.abs(g) / np.where(x > 0.0, x, np.nan)) ** (1.0 / q),
                         T - (g + x) / H_line)
        D = np.where(power & ~(x > 0.0), np.inf, D)
        return np.clip(D, T / TRUST, T * TRUST)

    def gap(lam, T, g, q, H_line, power, scale, F):
        return F - split(lam, T, g, q, H_line, power, scale).sum(axis=1)

    low = np.min(lam_at(hi_T), axis=1) - 1.0  # every duration at its longest
    high = np.max(lam_at(lo_T), axis=1) + 1.0  # every duration at its shortest
    args = (T, g, q, H_line, power, scale, F)
    lam = bracketed_root(gap, low, high, gap(low, *args), gap(high, *args), xtol=1e-15,
                         args=args)
    return split(lam, T, g, q, H_line, power, scale)


# ------------------------------------------------------------------ minimax (vibration)
GRID_POINTS = 4096
"""At most this many splits on the coarse grid of the simplex (its compositions)."""
KEEP = 8
"""The refinement starts from this many of the grid's best splits."""
REFINE_ROUNDS = 400
"""At most this many steps (or halvings) of the refinement."""
REFINE_TOLERANCE = 1e-12
"""The refinement stops when its step is below this share of F."""


def minimax_split(worst: Callable[[np.ndarray], np.ndarray], free_time: float,
                  moves: int) -> np.ndarray:
    """The split (moves,) of ``free_time`` that minimizes ``worst`` (the largest of some
    figures over the cycle: ``worst(D)`` for splits D (k, moves), an array (k,)), one
    split for every candidate (the goal does not depend on the motor).

    A goal such as the largest residual vibration over the moves is not smooth (a max)
    and has many local minima (it oscillates with each duration at the mode's period),
    so the search is direct: every split of a coarse grid of the simplex (all
    compositions of N steps into ``moves`` positive parts, N as large as GRID_POINTS
    allows) in one call, then a pattern search from the KEEP best: each round every
    transfer of a step h from one move to another, for all starts at once, the best that
    lowers the goal taken, h halved where none does, until h < REFINE_TOLERANCE F. The
    result is never worse than the grid's best split."""
    F = float(free_time)
    if moves < 2:
        return np.full(moves, F)
    N = _grid_steps(moves)
    grid = _compositions(N, moves) * (F / N)
    values = _finite(worst(grid))
    order = np.argsort(values, kind="stable")[:KEEP]
    D, best = grid[order], values[order]
    pairs = np.array([(i, j) for i in range(moves) for j in range(moves) if i != j])
    shift = np.zeros((len(pairs), moves))
    shift[np.arange(len(pairs)), pairs[:, 0]] = 1.0
    shift[np.arange(len(pairs)), pairs[:, 1]] = -1.0
    h = np.full(len(D), F / N)
    for _ in range(REFINE_ROUNDS):
        open_ = np.flatnonzero(h > REFINE_TOLERANCE * F)
        if not len(open_):
            break
        trial = (D[open_, None, :] + h[open_, None, None] * shift[None, :, :]).reshape(
            -1, moves)
        inside = (trial > 0.0).all(axis=1)
        flat = np.full(len(trial), np.inf)
        if inside.any():
            flat[inside] = _finite(worst(trial[inside]))
        got = flat.reshape(len(open_), len(pairs))
        pick = np.argmin(got, axis=1)
        better = got[np.arange(len(open_)), pick] < best[open_]
        rows = open_[better]
        D[rows] = D[rows] + h[rows, None] * shift[pick[better]]
        D[rows] *= F / D[rows].sum(axis=1)[:, None]  # against the rounding's drift
        best[rows] = got[better, pick[better]]
        h[open_[~better]] *= 0.5
    return D[int(np.argmin(best))]


def _finite(x: np.ndarray) -> np.ndarray:
    x = np.asarray(x, dtype=float)
    return np.where(np.isnan(x), np.inf, x)


def _grid_steps(moves: int) -> int:
    """The largest N whose compositions into ``moves`` positive parts, C(N-1, moves-1),
    are at most GRID_POINTS (at least ``moves``)."""
    from math import comb

    N = moves
    while comb(N, moves - 1) <= GRID_POINTS:
        N += 1
    return N


def _compositions(N: int, moves: int) -> np.ndarray:
    """Every split of N into ``moves`` positive integers (k, moves)."""
    from itertools import combinations

    cuts = np.array(list(combinations(range(1, N), moves - 1)), dtype=float).reshape(
        -1, moves - 1)
    edges = np.hstack([np.zeros((len(cuts), 1)), cuts, np.full((len(cuts), 1), N)])
    return np.diff(edges, axis=1)


# ------------------------------------------------------------------ a law per move
COMBINATIONS = 64
"""At most this many law combinations are each given their own split (rows of one
search); above it the laws and the split are chosen in turn."""
LAW_ROUNDS = 10


@dataclass(frozen=True)
class LawSplit:
    """Per candidate the free moves' durations (candidates, moves), the law of each free
    move (candidates, moves; indices into the laws offered), the goal there
    (candidates,) and whether the split converged."""

    durations: np.ndarray
    laws: np.ndarray
    goal: np.ndarray
    converged: np.ndarray


LawCost = Callable[[int, int, np.ndarray, np.ndarray], np.ndarray]
"""``cost(j, law, T, rows)``: free move j's term by law number ``law`` at durations T (k,)
for the candidates ``rows`` (k,): an array (k,), inf where the law cannot move it."""


def allocate_laws(cost: LawCost, laws: int, free_time: np.ndarray, start: np.ndarray
                  ) -> LawSplit:
    """The split of ``free_time`` (candidates,) and a law per free move (of ``laws``
    offered) that minimize the sum of ``cost`` over the free moves, per candidate.

    Where the combinations (laws ** moves) are at most COMBINATIONS, each combination is
    its own row of one search (candidates x combinations rows, :func:`allocate`), and each
    candidate takes its best row: the least over every combination of its optimal split.
    Else the laws and the split are chosen in turn from each law for all moves (the best
    of those rows): every free move the law of least cost at the current split, then the
    split for those laws, until no law changes (at most LAW_ROUNDS), the goal never
    rising (a local optimum, not the least over every combination)."""
    F = np.asarray(free_time, dtype=float)
    start = np.asarray(start, dtype=float)
    n, m = start.shape
    if laws ** m <= COMBINATIONS:
        combos = np.array(np.meshgrid(*[np.arange(laws)] * m, indexing="ij")).reshape(m, -1).T
        return _best_rows(cost, combos, F, start)
    found = _best_rows(cost, np.repeat(np.arange(laws)[:, None], m, axis=1), F, start)
    for _ in range(LAW_ROUNDS):
        every = np.stack([np.stack([_finite(cost(j, law, found.durations[:, j], np.arange(n)))
                                    for law in range(laws)], axis=1)
                          for j in range(m)], axis=1)  # (candidates, moves, laws)
        chosen = np.argmin(every, axis=2)
        better = chosen != found.laws
        kept = np.take_along_axis(every, found.laws[:, :, None], axis=2)[:, :, 0]
        least = np.take_along_axis(every, chosen[:, :, None], axis=2)[:, :, 0]
        chosen = np.where(better & (least < kept), chosen, found.laws)
        if (chosen == found.laws).all():
            break
        rows = np.flatnonzero((chosen != found.laws).any(axis=1))
        split = allocate(_by_law(cost, chosen[rows], rows), F[rows], found.durations[rows])
        goal = _total(_by_law(cost, chosen[rows], rows), split.durations,
                      np.arange(len(rows)))
        durations, law_index = found.durations.copy(), found.laws.copy()
        total, converged = found.goal.copy(), found.converged.copy()
        durations[rows], law_index[rows] = split.durations, chosen[rows]
        total[rows], converged[rows] = goal, split.converged
        found = LawSplit(durations, law_index, total, converged)
    return found


def _best_rows(cost: LawCost, combos: np.ndarray, F: np.ndarray, start: np.ndarray
               ) -> LawSplit:
    """Each candidate's best of the law combinations ``combos`` (C, moves), each
    combination's own split found for all (candidate, combination) rows at once."""
    n, C = len(F), len(combos)
    candidate = np.repeat(np.arange(n), C)
    laws = np.tile(combos, (n, 1))
    rows_cost = _by_law(cost, laws, candidate)
    split = allocate(rows_cost, F[candidate], start[candidate])
    goal = _finite(_total(rows_cost, split.durations, np.arange(n * C))).reshape(n, C)
    best = np.argmin(goal, axis=1)
    pick = np.arange(n) * C + best
    return LawSplit(split.durations[pick], laws[pick], goal[np.arange(n), best],
                    split.converged[pick])


def _by_law(cost: LawCost, laws: np.ndarray, candidate: np.ndarray) -> Cost:
    """The cost of rows whose move j goes by law ``laws[row, j]``, row r the candidate
    ``candidate[r]``: one call of ``cost`` per law present."""
    def rows_cost(j: int, T: np.ndarray, rows: np.ndarray) -> np.ndarray:
        out = np.empty(len(rows))
        law = laws[rows, j]
        for value in sorted_unique(law):
            where = law == value
            out[where] = cost(j, int(value), T[where], candidate[rows[where]])
        return out

    return rows_cost
