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
(sizer.numerics.roots.illinois) for all candidates at once. The step towards that split
is halved until the goal does not rise (the engine's values, not the model's), each
T_j kept within a factor TRUST of its value. The rounds stop per candidate when no T_j
moves by more than TOLERANCE of itself.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from sizer.numerics.roots import illinois

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
    lam = illinois(gap, low, high, gap(low, *args), gap(high, *args), xtol=1e-15,
                   args=args)
    return split(lam, T, g, q, H_line, power, scale)
