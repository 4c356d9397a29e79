"""A lower bound on T_min from the checks that only grow stricter as the move gets faster.

The speed check, the load's speed, acceleration and jerk limits and the peak torque
checks (motor against its intermittent region, stage outputs against their peak ratings)
each hold for every duration from a threshold on (book sec. 6.1.1, eq. 6.2 in the
rectangular case). Their largest threshold is a lower bound on T_min: where the cycle is
feasible there, it is T_min, found without a search (sizer.sizing.minimum_duration).

The peak check in u = 1/T. Every torque is a maximum of linear functions of the load's
(a, v) (sizer.mechanics.drive.Drive.linear_pieces), a = h u^2 a_N, v = h u v_N, so one of
its functions under one line of the region, alpha + sigma * omega with omega = K v, reads

    F(u) = max over tau of (P a_N u^2 + Q v_N u)  <=  D,
    P = A h,  Q = (B - c sigma K) h,  D = c alpha - C,

with c = 1 - torque margin. For a rest-to-rest law (v_N >= 0) F(u) = u g(u) with g a
maximum of linear functions of u, nondecreasing from u = 0: F is convex and increasing,
so the condition holds on [0, u*]. From a point x where F(x) > D each step takes the
quadratic of the maximizer there, q(u) = P a_N u^2 + Q v_N u at its tau (the law's exact
linear peak, sizer.laws.linear_peaks): q <= F everywhere and q(x) = F(x), so the
positive root of q = D lies in [u*, x); the iterates fall monotonically to u*, as
Newton's method would, but faster, the step's quadratic being exact for a fixed tau
(F - q is of second order in u - x, with the maximizer's drift as its only cause;
Newton's step where rounding leaves q no root). Stopped anywhere, the iterate is
>= u*, so 1/u is a valid bound. The condition is necessary where the line lies on or
above the region at every speed the move may reach: true of every segment's line of a
concave region (a flat part, then falling segments that fall faster and faster), and of
the flat line at the region's largest torque for any region. Only the motoring side
(torque >= 0) is bounded: -tau is a minimum of the functions, for which a single
function gives no necessary condition.
"""

from __future__ import annotations

import numpy as np

from sizer.laws.linear_peaks import piece_values
from sizer.model.domain import Limits
from sizer.sizing.cycle import CycleCalculator

NEWTON_STEPS = 40
"""Steps at most (quadratic convergence: about 3 from the start used here)."""

SETTLED = 1e-8
"""A relative step of :func:`_largest_u` that ends its row: the step after it would be
of about its square times the maximizer's drift, below rounding."""


def peak_duration(calculator: CycleCalculator, limits: Limits,
                  prune: bool = True) -> np.ndarray | None:
    """A lower bound on T_min per candidate (inf where no duration passes a peak or speed
    check; None where the law may move backwards, v_N < 0, and the bound does not hold).
    ``prune=False`` solves every query (the reference the pruned result equals)."""
    law = calculator.law
    peaks = law.linear_peaks
    if float(peaks.minimum(0.0, 1.0).value) < -1e-12:
        return None
    c = law.coefficients
    n, h = len(calculator.motors), calculator.h
    if h == 0.0:  # no move: nothing bounds the duration
        return np.zeros(n)
    bounds = [speed_bounds(calculator, limits)]
    queries = peak_queries(calculator, limits)
    if queries is not None:
        who, P, Q, D = queries
        bounds.append(_largest_duration(peaks, law, n, who, P, Q, D, c.C_a, c.C_v, prune))
    return np.max(np.stack(bounds), axis=0)


def peak_queries(calculator: CycleCalculator, limits: Limits):
    """The peak conditions F(u) <= D of the module docs, one per candidate x torque
    function x region line (or stage rating) x direction: (candidate, P, Q, D) arrays,
    or None where there are none."""
    motors, drive, h = calculator.motors, calculator.drive, calculator.h
    n = len(motors)
    K = np.broadcast_to(drive.ratio, (n,))
    grip = 1.0 - limits.torque_margin
    alpha, sigma, _ = motors.intermittent.lines()
    rows, cols = np.nonzero(np.isfinite(alpha))
    queries: list[tuple[np.ndarray, ...]] = []
    for direction in calculator.directions:
        shaft, outputs = drive.linear_pieces(direction)
        for A, B, C in shaft:
            A = np.broadcast_to(A + motors.inertia * K, (n,))
            B = np.broadcast_to(B + motors.damping * K, (n,))
            C = np.broadcast_to(C, (n,))
            queries.append((rows, A[rows] * h, (B[rows] - grip * sigma[rows, cols] * K[rows]) * h,
                            grip * alpha[rows, cols] - C[rows]))
        for stage, pieces in zip(drive.stages, outputs, strict=True):
            if stage.peak_output_torque is None:
                continue
            rated = np.flatnonzero(np.broadcast_to(stage.rated["peak_output_torque"], (n,)))
            rating = np.broadcast_to(stage.peak_output_torque, (n,))[rated]
            for A, B, C in pieces:
                queries.append((rated, np.broadcast_to(A, (n,))[rated] * h,
                                np.broadcast_to(B, (n,))[rated] * h,
                                grip * rating - np.broadcast_to(C, (n,))[rated]))
    if not queries:
        return None
    who = np.concatenate([q[0] for q in queries])
    P, Q, D = (np.concatenate([q[i] for q in queries]) for i in (1, 2, 3))
    return who, P, Q, D


PRUNE_MARGIN = 1e-9
"""Relative gap by which a query's upper bracket must lie below another query's lower
bracket to be left out (far above the rounding of either)."""


def _largest_duration(peaks, law, n: int, who: np.ndarray, P: np.ndarray, Q: np.ndarray,
                      D: np.ndarray, C_a: float, C_v: float, prune: bool) -> np.ndarray:
    """Per candidate the largest of its queries' bounds 1/u (:func:`_largest_u`).

    Only the largest counts, so a query is solved only where it may be the largest: each
    query's bound lies in a bracket from closed forms (:func:`_brackets`), and a query
    whose upper end is below the largest lower end of its candidate's queries is left
    out. Where the solved queries do not reach that lower end after all (a Newton run
    that never got to the right of u*), the candidate's other queries are solved too, so
    the result is the largest over all queries, as without pruning."""
    keep = np.ones(len(who), dtype=bool)
    if prune:
        low, high = _brackets(P, Q, D, C_a, C_v)
        floor = np.zeros(n)
        np.maximum.at(floor, who, low)
        keep = ~(high * (1.0 + PRUNE_MARGIN) < floor[who] * (1.0 - PRUNE_MARGIN))
    worst = np.zeros(n)
    solved = np.zeros(len(who), dtype=bool)
    for _ in range(2):
        todo = keep & ~solved
        if todo.any():
            u = _largest_u(peaks, law, P[todo], Q[todo], D[todo], C_a, C_v)
            with np.errstate(divide="ignore"):
                np.maximum.at(worst, who[todo], np.where(u > 0.0, 1.0 / u, np.inf))
            solved |= todo
        if keep.all():
            break
        short = worst < floor * (1.0 - PRUNE_MARGIN)
        keep |= short[who]
    return worst


def _brackets(P: np.ndarray, Q: np.ndarray, D: np.ndarray, C_a: float,
              C_v: float) -> tuple[np.ndarray, np.ndarray]:
    """Per query a lower and an upper end of its bound 1/u* (module docs: F(u) <= D).

    Lower: 1/u at the start of :func:`_largest_u` (the Newton iterates stay at or below
    it, so the bound computed is at least this). Upper: where P, Q >= 0, F(u) <= P C_a u^2
    + Q C_v u (a_N <= C_a, 0 <= v_N <= C_v), so u* is at least that quadratic's root and
    1/u* at most (Q C_v + sqrt((Q C_v)^2 + 4 P C_a D)) / (2 D); inf elsewhere (and where
    D <= 0: no duration passes)."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        start = np.minimum(np.sqrt(D / (P * C_a)), D / (Q * C_v))
        low = np.where((D > 0.0) & np.isfinite(start) & (start > 0.0), 1.0 / start, 0.0)
        a, b = P * C_a, Q * C_v
        high = (b + np.sqrt(b * b + 4.0 * a * D)) / (2.0 * D)
    high = np.where((D > 0.0) & (P >= 0.0) & (Q >= 0.0) & np.isfinite(high), high, np.inf)
    low = np.where(D > 0.0, low, np.inf)
    return low, high


def speed_bounds(calculator: CycleCalculator, limits: Limits) -> np.ndarray:
    """The durations below which the speed check or a load limit fails (closed forms)."""
    c = calculator.law.coefficients
    h, motors = calculator.h, calculator.motors
    K = np.broadcast_to(calculator.drive.ratio, (len(motors),))
    with np.errstate(divide="ignore", invalid="ignore"):
        T = c.C_v * K * h / (motors.speed_limit * (1.0 - limits.speed_margin))
        T = np.where(np.isnan(T), np.inf, T)
    if calculator.thermal_rule == "max":  # the thermal speed is the peak speed
        with np.errstate(divide="ignore", invalid="ignore"):
            thermal = c.C_v * K * h / (motors.continuous.max_speed * (1.0 - limits.speed_margin))
        T = np.maximum(T, np.where(np.isnan(thermal), np.inf, thermal))
    if limits.max_speed is not None:
        T = np.maximum(T, c.C_v * h / limits.max_speed)
    if limits.max_acceleration is not None:
        T = np.maximum(T, np.sqrt(c.C_a * h / limits.max_acceleration))
    if limits.max_jerk is not None:
        T = np.maximum(T, np.cbrt(c.C_j * h / limits.max_jerk) if c.jerk_bounded else np.inf)
    for k, stage in zip(calculator.drive.input_ratios, calculator.drive.stages, strict=True):
        if stage.max_input_speed is not None:
            rated = np.broadcast_to(stage.rated["max_input_speed"], T.shape)
            with np.errstate(divide="ignore", invalid="ignore"):
                bound = c.C_v * k * h / (stage.max_input_speed * (1.0 - limits.speed_margin))
            T = np.where(rated, np.maximum(T, bound), T)
    return T


def _largest_u(peaks, law, P: np.ndarray, Q: np.ndarray, D: np.ndarray,
               C_a: float, C_v: float) -> np.ndarray:
    """Per query the largest u with max_tau (P a_N u^2 + Q v_N u) <= D (0 where D <= 0,
    inf where nothing limits u): the maximizer's quadratic from the right (module docs)."""
    u = np.full(P.shape, np.inf)
    u[D <= 0.0] = 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        # F(u) >= max(P C_a u^2, Q C_v u) (v_N >= 0, a_N >= 0 at the peaks), so the smaller
        # of these two roots has F >= D: a start on the right of u*
        start = np.minimum(np.sqrt(D / (P * C_a)), D / (Q * C_v))
    open_ = (D > 0.0) & np.isfinite(start)
    index = np.flatnonzero(open_)
    x = start[index]
    P, Q, D = P[index], Q[index], D[index]
    for _ in range(NEWTON_STEPS):
        if len(index) == 0:
            break
        peak = peaks.maximum(P * x * x, Q * x)
        v, a = piece_values(law, peak.tau, peak.piece, (1, 2))
        excess = peak.value - D
        # the maximizer's quadratic A u^2 + b u <= F(u), equal at x with the same slope:
        # its positive root, in the stable form, lies in (u*, x) where F(x) > D
        A, b = P * a, Q * v
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            root = 2.0 * D / (b + np.sqrt(b * b + 4.0 * A * D))
            newton = x - excess / (2.0 * A * x + b)  # where rounding leaves no root
        root = np.where((root > 0.0) & (root < x), root, newton)
        nxt = np.where((excess > 0.0) & (root < x) & (root > 0.0), root, x)
        # a point where F >= D is on the right of u* (to rounding: F is exact to a few ulps)
        right = excess >= -1e-14 * np.abs(D)
        u[index] = np.minimum(u[index], np.where(right, x, u[index]))
        # a step this small leaves the next of about its square: the step's end, right of
        # u* by construction, is the answer without evaluating F there
        settled = (nxt < x) & (x - nxt <= SETTLED * x)
        u[index] = np.where(settled, np.minimum(u[index], nxt), u[index])
        moving = (nxt < x) & (x - nxt > 1e-15 * x) & ~settled
        x = nxt
        index, x, P, Q, D = (z[moving] for z in (index, x, P, Q, D))
    return u
