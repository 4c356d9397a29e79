"""Which shape of a family is time-optimal, in closed form: the trapezoid and the double S in
the book's case, exactly (sec. 3.2-3.4, 5.2, 6.2), for all motors at once
(:func:`exact_time_optimal`, used by sizer.sizing.choices.choose_shape); and how short
each shape of theirs can be through lossy drives, the score of the search elsewhere
(:func:`trusted_phase_model`, last section).

With rectangular regions, an ideal transmission of plain stages and no damping, T_min of a
shape is the largest of the bounds of eq. (6.2), each a closed form in one coefficient:

    speed   T_V = C_v S_V            S_V = max(K h / v_lim, h / v_load)
    torque  T_A = sqrt(C_a S_A)      S_A = max(K h J_t / (tau_p - max|c|), h / a_max)
    RMS     T_R: T^3 (T + dwell') = (C_a_rms S_R)^2,  S_R = K h J_t / sqrt(tau_c^2 - mean c^2)
    jerk    T_J = cbrt(C_j S_J)      S_J = h / j_max

(margins applied to the limits as in sizer.sizing.shortest_duration). c are the load's
constant torques at the motor, one per move (Coulomb friction against the motion, a
constant external load), and dwell' = dwell (tau_c^2 - H^2) / (tau_c^2 - mean c^2) with H
the torque held in the dwells: sizer.sizing.shortest_duration derives them (sec. 6.1.1,
eq. 6.2); for a purely inertial load c = H = 0, S_A = K h J_t / tau_p, S_R = K h J_t /
tau_c and dwell' = dwell, the book's case. The families' shapes are symmetric (max q_N''
= -min q_N'' = C_a), so the peak bound keeps the form sqrt(C_a S_A) and every bound is
still monotone in one coefficient: what follows holds unchanged with these scales.
Motors the closed forms do not decide (an ill-conditioned crossing, a possible window of
the RMS: DurationBounds.undecided) are left to the search (:func:`exact_time_optimal`).

The trapezoid's coefficients are C_v = 1/(1-a), C_a = 1/(a(1-a)), C_a_rms = sqrt(2/a)/(1-a)
(a = alpha, sec. 6.2.1); each bound is monotone or unimodal in a (T_V increasing, T_A
decreasing, T_R smallest at a = 1/3) and the sign of every difference of two bounds changes
at most once on (0, 1/2]. The optimum is therefore among: the ends, a = 1/3, and the
crossings of two bounds: T_V = T_A at a = S_A/(S_A + S_V^2), T_V = T_R at the root of a
quadratic (dwell' >= 0), T_A = T_R (and T_V = T_R with a negative dwell') found to machine
precision by a bracketed root; all candidates are evaluated and the best kept, for all
motors at once.

The double S (a = alpha, b = beta) has C_a = 1/(a(1-a)(1-b)), C_j = 1/(a^2 b (1-a)(1-b)),
C_a_rms = sqrt((6-8b)/(3a))/((1-a)(1-b)): in b, T_A and T_R increase and T_J decreases,
so for a given a the best b is where max(T_A, T_R) meets T_J (a 1-D root), or an end of
the range. What remains is a function of a alone, the largest of smooth pieces; its
minimum (a minimum of one piece or a crossing of two) is bracketed on a dense sample
that contains the special points and located to 1e-13 in a by the bracket search of
sizer.numerics.bracket_search (steps where two pieces cross or to a parabola's vertex,
safeguarded like golden section). Where T_R does not bind and the optimum lies in the
ranges, it is the book's closed form (sec. 3.4.3).

The T_min of a trapezoid or a double S at any shape where nothing depends on the speed,
through any efficiencies (:func:`trusted_phase_model`, the shape search's score where it
holds: sizer.sizing.choices.search_shape). With no damping anywhere (motor, stages, load),
plain stages and rectangular regions read at the peak speed, the motor torque of a move is
the largest of the drive's linear functions P a_l + C of the load's acceleration alone
(the engine's, CycleCalculator.channel_terms: one per choice of power-flow direction in
each stage, P with the rotor's inertia): a function of the acceleration, whose square
integrates over the move from how long the law spends at each acceleration. The
trapezoid's normalized acceleration is C_a, 0 and -C_a (sec. 3.2): plateaus alpha each,
the cruise 1 - 2 alpha;
the double S's (sec. 3.4) plateaus alpha (1 - 2 beta) each, the cruise, and four ramps of
alpha beta each sweeping [0, +-C_a] uniformly. With x = C_a h / T^2 (the load's
acceleration on the plateaus) the checks of T_min (sec. 6.1.1) are closed forms of T per
motor:

    speed, thermal speed, load speed   T >= C_v S, S the largest of K h / v' (each region's
                                       top speed with its margin) and h / v_load
    peak    |torque| <= tau_p' at every acceleration of every move and in the dwells (the
            torque is convex in it: its extremes at +-x),
            x <= min_k (tau_p' - C_k) / P_k, x <= max_k (tau_p' + C_k) / P_k,
            |max_k C_k| <= tau_p' (cruise)
    load acceleration and jerk   x <= a_max, T >= cbrt(C_j h / j_max)
    RMS     T sum_moves [plateaus (t_+^2 + t_-^2) + cruise t_0^2 + ramps (S_+ + S_-)]
                + n d H^2 <= n tau_c'^2 (T + d)

(t_+, t_0, t_- a move's torques at x, 0, -x, S_+- their mean squares over the ramps'
sweeps, exact on the polyline of the largest function; n moves, d the dwell after each,
H the torque held there: sizer.sizing.move.CycleCalculator.evaluate's sums): T_min is
the largest of the first bounds, or past them the smallest T where the RMS holds
(Newton's method from the other bounds, safeguarded by the bracket of the durations
tried). For the motors where one law's T_min sized by the engine
(sizer.sizing.shortest_duration.minimum_duration) is the model's to AGREEMENT, with no
check the model does not know (a drive's currents, a stage's ratings...), the search
scores by the model; the others by the engine.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from sizer.laws import MotionLaw
from sizer.laws.piecewise_polynomial import DoubleS, Trapezoidal
from sizer.model.domain import Design
from sizer.numerics.arrays import sorted_unique
from sizer.numerics.bracket_search import from_grid
from sizer.sizing.candidates import Candidates
from sizer.sizing.checks import CheckName
from sizer.sizing.cycle import single_task
from sizer.sizing.move import CycleCalculator, MoveScales
from sizer.sizing.shortest_duration import (
    DurationBounds,
    beyond_flat_part,
    duration_bounds,
    has_constant_torques,
    minimum_duration,
    plain_stages,
    rms_duration,
)

SAMPLES = 65
SEARCH_WIDTH = 1e-13
"""The width in alpha to which the double S with an RMS bound is searched."""
HALF = 0.5


@dataclass(frozen=True)
class BoundScales:
    """Per-motor scales of the bounds of eq. (6.2) (see the module docstring), SI.

    A zero scale means no such limit; ``feasible`` is False where no shape can work
    (e.g. a zero torque); checks that no shape changes (the inertia ratio) are left to
    the verdict. ``dwell`` is the RMS bound's dwell', one for all motors or one per
    motor (with constant torques; negative where the hold exceeds the rating).
    """

    speed: np.ndarray
    torque: np.ndarray
    rms: np.ndarray
    jerk: np.ndarray
    dwell: float | np.ndarray
    feasible: np.ndarray

    def take(self, rows: np.ndarray) -> BoundScales:
        """The scales of the motors ``rows``."""
        dwell = np.asarray(self.dwell)[rows] if np.ndim(self.dwell) else self.dwell
        return BoundScales(self.speed[rows], self.torque[rows], self.rms[rows],
                           self.jerk[rows], dwell, self.feasible[rows])

    @property
    def dwells(self) -> np.ndarray:
        """``dwell`` per motor (one number broadcast)."""
        return np.broadcast_to(np.asarray(self.dwell, dtype=float), np.shape(self.speed))


@dataclass(frozen=True)
class OptimalShape:
    """The best parameters per motor and T_min there (inf where nothing is feasible)."""

    params: dict[str, np.ndarray]
    duration: np.ndarray


# --------------------------------------------------------------------- coefficients
def trapezoid_coefficients(a):
    """C_v, C_a, C_a_rms of the trapezoid with alpha = a (sec. 3.2, 6.2.1), vectorized."""
    return 1.0 / (1.0 - a), 1.0 / (a * (1.0 - a)), np.sqrt(2.0 / a) / (1.0 - a)


def double_s_coefficients(a, b):
    """C_v, C_a, C_a_rms, C_j of the double S (sec. 3.4, 6.2.1), vectorized."""
    c_a = 1.0 / (a * (1.0 - a) * (1.0 - b))
    c_a_rms = np.sqrt((6.0 - 8.0 * b) / (3.0 * a)) / ((1.0 - a) * (1.0 - b))
    return 1.0 / (1.0 - a), c_a, c_a_rms, c_a / (a * b)


# --------------------------------------------------------------------------- bounds
def rms_time(x: np.ndarray, dwell: float | np.ndarray) -> np.ndarray:
    """The smallest T with T^3 (T + dwell) >= x^2 (x = C_a_rms S_R), vectorized.

    Newton's method from an upper bound (the quartic is convex and increasing for T > 0,
    so the iterates decrease monotonically to the root). A dwell per element (broadcast
    with x) or a negative one: sizer.sizing.shortest_duration.rms_duration.
    """
    x = np.asarray(x, dtype=float)
    if np.ndim(dwell) or dwell < 0.0:
        return np.where(np.isnan(x), np.nan, rms_duration(x, dwell))
    target = x * x
    if dwell == 0.0:
        return np.sqrt(x)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        T = np.sqrt(x)
        if dwell > 0.0:
            T = np.minimum(T, np.cbrt(target / dwell))
        for _ in range(60):
            f = T**3 * (T + dwell) - target
            step = f / (T * T * (4.0 * T + 3.0 * dwell))
            step = np.where(np.isfinite(step) & (T > 0.0) & (step > 0.0), step, 0.0)
            T = T - step
            if not np.any(step > 1e-15 * T):  # quadratic convergence: one more is exact
                f = T**3 * (T + dwell) - target
                T = T - np.where(T > 0.0, f / (T * T * (4.0 * T + 3.0 * dwell)), 0.0)
                break
    return np.where(x > 0.0, T, np.where(np.isnan(x), np.nan, 0.0))


def _scales_like(scales: BoundScales, shape: tuple[int, ...], rows=None):
    """The four scales broadcast to ``shape`` (motor-major), or taken at flat ``rows``."""
    out = []
    for s in (scales.speed, scales.torque, scales.rms, scales.jerk):
        full = np.broadcast_to(s.reshape((-1,) + (1,) * (len(shape) - 1)), shape)
        out.append(full if rows is None else full.reshape(-1)[rows])
    return out


def _dwell_like(scales: BoundScales, shape: tuple[int, ...], rows=None) -> float | np.ndarray:
    """The dwell' of :func:`_scales_like`'s scales (one number where it is one)."""
    if not np.ndim(scales.dwell):
        return scales.dwell
    d = np.asarray(scales.dwell)
    full = np.broadcast_to(d.reshape((-1,) + (1,) * (len(shape) - 1)), shape)
    return full if rows is None else full.reshape(-1)[rows]


def _bounds(S, dwell: float | np.ndarray, c_v, c_a, c_a_rms, c_j=None) -> list[np.ndarray]:
    """T_V, T_A, T_R (and T_J) from coefficient arrays and scales S of the same shape."""
    coefficients = (c_v, c_a, c_a_rms) if c_j is None else (c_v, c_a, c_a_rms, c_j)
    return [_bound(k, S, dwell, coefficients) for k in range(len(coefficients))]


def _bound(k: int, S, dwell: float | np.ndarray, coefficients) -> np.ndarray:
    """Bound k of :func:`_bounds` alone (T_V, T_A, T_R, T_J: 0, 1, 2, 3)."""
    c = coefficients[k]
    if k == 0:
        return c * S[0]
    if k == 1:
        return np.sqrt(c * S[1])
    if k == 2:
        return rms_time(c * S[2], dwell)
    return np.cbrt(c * S[3])


def trapezoid_bounds(scales: BoundScales, a: np.ndarray) -> list[np.ndarray]:
    """T_V, T_A, T_R of the trapezoid at alpha = a (array (motors, k))."""
    shape = np.shape(a)
    return _bounds(_scales_like(scales, shape), _dwell_like(scales, shape),
                   *trapezoid_coefficients(a))


def double_s_bounds(scales: BoundScales, a: np.ndarray, b: np.ndarray,
                    rows=None) -> list[np.ndarray]:
    """T_V, T_A, T_R, T_J of the double S at (a, b) (arrays (motors, k), or flat arrays
    at the positions ``rows`` of such an array)."""
    shape = np.shape(a) if rows is None else rows[1]
    at = None if rows is None else rows[0]
    S = _scales_like(scales, shape, at)
    return _bounds(S, _dwell_like(scales, shape, at), *double_s_coefficients(a, b))


def trapezoid_duration(scales: BoundScales, a: np.ndarray) -> np.ndarray:
    """T_min of the trapezoid at alpha = a (array (motors, k)): the largest bound."""
    return np.max(np.stack(trapezoid_bounds(scales, a)), axis=0)


def double_s_duration(scales: BoundScales, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """T_min of the double S at (a, b) (arrays (motors, k)): the largest bound."""
    return np.max(np.stack(double_s_bounds(scales, a, b)), axis=0)


# -------------------------------------------------------------------------- optima
def optimal_trapezoid(scales: BoundScales, low: float, high: float = HALF) -> OptimalShape:
    """alpha in [low, high] minimizing T_min, per motor: the candidates enumerated."""
    n = len(scales.speed)
    special = np.array([low, min(max(1.0 / 3.0, low), high), high])
    candidates = [np.broadcast_to(special, (n, 3))]
    candidates.append(_inside(speed_torque_alpha(scales), low, high)[:, None])
    candidates.append(_speed_rms_crossing(scales, low, high)[:, None])
    candidates.append(_torque_rms_crossing(scales, low, high)[:, None])
    a = np.concatenate(candidates, axis=1)
    T = trapezoid_duration(scales, a)
    best = np.argmin(np.where(np.isnan(T), np.inf, T), axis=1)
    rows = np.arange(n)
    return _finish(scales, {"alpha": a[rows, best]}, T[rows, best], {"alpha": 1.0 / 3.0})


def _log_gap_crossing(scales: BoundScales, rows: np.ndarray, i: int, j: int, low: float,
                      high: float) -> np.ndarray:
    """Where the trapezoid's bounds T_i and T_j meet for the motors ``rows``
    (:func:`_crossing` on log T_i - log T_j, the two bounds alone: T_R costs a root)."""
    part = scales.take(rows)

    def gap(a: np.ndarray) -> np.ndarray:
        shape = np.shape(a)
        S, dwell = _scales_like(part, shape), _dwell_like(part, shape)
        c = trapezoid_coefficients(a)
        return _log_ratio(_bound(i, S, dwell, c), _bound(j, S, dwell, c))
    return _crossing(gap, len(rows), low, high)


def speed_torque_alpha(scales: BoundScales) -> np.ndarray:
    """The alpha at which the trapezoid's T_V = S_V/(1-a) meets T_A = sqrt(S_A/(a(1-a))):
    S_V^2 a = S_A (1 - a), a = S_A/(S_A + S_V^2) (nan where both scales are zero)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return scales.torque / (scales.torque + scales.speed * scales.speed)


def speed_rms_alpha(scales: BoundScales) -> np.ndarray:
    """The alpha in (0, 1) at which the trapezoid's T_V = S_V/(1-a) meets T_R (the root of
    T^3 (T + d) = 2 S_R^2/(a (1-a)^2), d = dwell' >= 0): with T = T_V, a quadratic
    A a^2 - B a + C = 0 (over S_V^4: A = 2r + e, B = 1 + e + 4r, C = 2r, r =
    S_R^2/S_V^4, e = d/S_V), positive at 0, -1 at 1: its smaller root C/q, q = (B +
    sqrt(B^2 - 4AC))/2, B^2 - 4AC = (1 + e)^2 + 8r (no cancellation). T_V < T_R below it,
    T_V > T_R above. nan where d < 0 or a scale is zero (no such crossing: the caller
    decides)."""
    d = scales.dwells
    S_V, S_R = scales.speed, scales.rms
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        r = S_R * S_R / (S_V * S_V * S_V * S_V)
        e = d / S_V
        q = 0.5 * (1.0 + e + 4.0 * r + np.sqrt((1.0 + e) * (1.0 + e) + 8.0 * r))
        root = 2.0 * r / q
    ok = (d >= 0.0) & (S_V > 0.0) & (S_R > 0.0) & np.isfinite(root)
    return np.where(ok, root, np.nan)


def _inside(root: np.ndarray, low: float, high: float) -> np.ndarray:
    """The roots strictly inside (low, high), else low (as :func:`_crossing` gives where
    the sign does not change)."""
    with np.errstate(invalid="ignore"):
        return np.where((root > low) & (root < high), root, low)


def _speed_rms_crossing(scales: BoundScales, low: float, high: float) -> np.ndarray:
    """Where T_V meets T_R in (low, high), else low: the closed form
    (:func:`speed_rms_alpha`; T_V - T_R changes sign once on (0, 1)), by the bracketed
    root where it does not apply (a negative dwell', or no such limit)."""
    root = speed_rms_alpha(scales)
    out = _inside(root, low, high)
    rest = np.flatnonzero(np.isnan(root) & (scales.speed > 0.0) & (scales.rms > 0.0))
    if len(rest):
        out[rest] = _log_gap_crossing(scales, rest, 0, 2, low, high)
    return out


def _torque_rms_crossing(scales: BoundScales, low: float, high: float) -> np.ndarray:
    """Where T_A meets T_R in (low, high), else low, by the bracketed root: with dwell'
    >= 0 on the sign of 3 log T_A + log(T_A + d) - 2 log(C_a_rms S_R), that of
    T_A - T_R (T^3 (T + d) rises in T), which needs no root for T_R; with a negative
    dwell' on log T_A - log T_R itself."""
    d = scales.dwells
    out = np.full(len(d), low)
    plain, held = np.flatnonzero(d >= 0.0), np.flatnonzero(d < 0.0)
    if len(plain):
        out[plain] = _crossing(_torque_rms_excess(scales.take(plain)), len(plain), low, high)
    if len(held):
        out[held] = _log_gap_crossing(scales, held, 1, 2, low, high)
    return out


def _torque_rms_excess(scales: BoundScales):
    """3 log T_A + log(T_A + d) - 2 log(C_a_rms S_R) of the trapezoid as a function of
    alpha (arrays (n, 1)), dwell' d >= 0: the sign of T_A - T_R."""
    S_A, S_R = scales.torque[:, None], scales.rms[:, None]
    d = scales.dwells[:, None]

    def excess(a: np.ndarray) -> np.ndarray:
        _, c_a, c_a_rms = trapezoid_coefficients(a)
        with np.errstate(divide="ignore", invalid="ignore"):
            T_A = np.sqrt(c_a * S_A)
            return 3.0 * np.log(T_A) + np.log(T_A + d) - 2.0 * np.log(c_a_rms * S_R)
    return excess


def optimal_double_s(scales: BoundScales, low_a: float, low_b: float,
                     high_a: float = HALF, high_b: float = HALF) -> OptimalShape:
    """(alpha, beta) in [low_a, high_a] x [low_b, high_b] minimizing T_min per motor: the
    book's closed form (:func:`time_optimal_double_s`) where it is the optimum, else
    :func:`searched_double_s`.

    The closed form is the minimum-time move under the speed, acceleration and jerk limits
    (sec. 3.4; Ruckig's, tests/test_double_s_closed_form.py): it minimizes max(T_V, T_A,
    T_J) over every double S, (a, b) in (0, 1/2]^2 (b = low_b without a jerk limit). It is
    the optimum here where (a) T_R <= T at it: adding the bound T_R cannot lower the
    minimum, and this point meets it; and (b) (alpha, beta) lies in the box: a minimum
    over a set, attained in a subset, is the subset's minimum. Infeasible motors are left
    to _finish, the others to the search.
    """
    alpha, beta, T = time_optimal_double_s(scales, low_b)
    with np.errstate(invalid="ignore"):
        exact = (scales.feasible & np.isfinite(T) & (T > 0.0) & (alpha >= low_a)
                 & (alpha <= high_a) & (beta >= low_b) & (beta <= high_b))
    if scales.rms.any() and exact.any():
        _, _, c_a_rms, _ = double_s_coefficients(alpha[exact], beta[exact])
        dwell = np.asarray(scales.dwell)[exact] if np.ndim(scales.dwell) else scales.dwell
        exact[exact] = rms_time(c_a_rms * scales.rms[exact], dwell) <= T[exact]
    params = {"alpha": alpha, "beta": beta}
    rest = np.flatnonzero(scales.feasible & ~exact)
    if len(rest):
        found, T[rest] = searched_double_s(scales.take(rest), low_a, low_b, high_a, high_b)
        for name, value in found.items():
            params[name][rest] = value
    return _finish(scales, params, T, {"alpha": 1.0 / 3.0, "beta": 0.25})


def time_optimal_double_s(scales: BoundScales,
                          low_b: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """alpha = T_a/T, beta = T_j/T_a and T of the time-optimal rest-to-rest double S under
    the speed, acceleration and jerk scales (T_R left out), vectorized: book sec. 3.4.3 with
    h = 1, v_max = 1/S_V, a_max = 1/S_A, j_max = 1/S_J (a zero scale: no such limit), its
    cases whether v_max and a_max are reached. Without a jerk limit beta = low_b (T_A
    increases with beta, T_J = 0): the trapezoid with S_A/(1 - low_b) (sec. 3.2), the same
    formulas with T_j = 0. nan where no limit bounds the move.
    """
    S_V, S_J = scales.speed, scales.jerk
    S_A = np.where(S_J > 0.0, scales.torque, scales.torque / (1.0 - low_b))
    with np.errstate(divide="ignore", invalid="ignore"):
        # case 1, v_max reached (T_v >= 0): a_max reached iff v_max j_max >= a_max^2
        reached = S_A * S_A >= S_V * S_J
        T_j = np.where(reached, S_J / S_A, np.sqrt(S_J / S_V))
        T_a = np.where(reached, T_j + S_A / S_V, 2.0 * T_j)
        slow = ~(T_a <= S_V)
        # case 2, v_max not reached: a_max reached iff h >= 2 a_max^3 / j_max^2
        reached = S_A**3 >= 2.0 * S_J * S_J
        T_j2 = np.where(reached, S_J / S_A, np.cbrt(0.5 * S_J))
        T_a2 = np.where(reached, 0.5 * T_j2 + np.sqrt(0.25 * T_j2 * T_j2 + S_A), 2.0 * T_j2)
        T_j, T_a = np.where(slow, T_j2, T_j), np.where(slow, T_a2, T_a)
        T = np.where(slow, 2.0 * T_a, T_a + S_V)
        return T_a / T, np.where(S_J > 0.0, T_j / T_a, low_b), T


def searched_double_s(scales: BoundScales, low_a: float, low_b: float, high_a: float,
                      high_b: float) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """(alpha, beta) minimizing T_min per motor and T_min there, searched: beta exact for
    each alpha, alpha by a dense sample, then the bracket search around each motor's best
    sample (sizer.numerics.bracket_search: T_min(alpha) is the largest of the bounds, its
    optimum mostly where two cross) to SEARCH_WIDTH; each motor's steps depend on its own
    values only."""
    n = len(scales.speed)

    def reduced(a: np.ndarray, part: BoundScales = scales) -> tuple[np.ndarray, np.ndarray]:
        b = best_beta(part, a, low_b, high_b)
        return double_s_duration(part, a, b), b

    grid = sorted_unique(np.concatenate((np.linspace(low_a, high_a, SAMPLES),
                                     [min(max(1.0 / 3.0, low_a), high_a)])))
    T_grid, _ = reduced(np.broadcast_to(grid, (n, len(grid))).copy())
    best = np.argmin(np.where(np.isnan(T_grid), np.inf, T_grid), axis=1)

    def score(x: np.ndarray) -> np.ndarray:
        """-T_min at each motor's own alpha (nan: a settled motor, not evaluated)."""
        out = np.full((n, 1), np.nan)
        rows = np.flatnonzero(~np.isnan(x))
        if len(rows):
            out[rows, 0] = -reduced(x[rows, None], scales.take(rows))[0][:, 0]
        return out

    a, _ = from_grid(score, grid, -T_grid.T[:, :, None], best, SEARCH_WIDTH)
    candidates = np.column_stack((a, grid[best]))
    T, b = reduced(candidates)
    pick = np.argmin(np.where(np.isnan(T), np.inf, T), axis=1)
    rows = np.arange(n)
    return {"alpha": candidates[rows, pick], "beta": b[rows, pick]}, T[rows, pick]


def best_beta(scales: BoundScales, a: np.ndarray, low: float, high: float = HALF) -> np.ndarray:
    """For each alpha (array (motors, k)), the beta minimizing max(T_A, T_R, T_J).

    T_A and T_R increase with beta, T_J decreases: the best beta is where the larger of
    the first two meets T_J (the smaller of the two crossings), or an end of [low, high].
    T_A = T_J is the quadratic b^2/(1-b) = S_J^2 P_j^2/(S_A^3 P^3) (P = 1/(a(1-a)),
    P_j = P/a); T_R = T_J, i.e. T_J^3 (T_J + dwell) = (C_a_rms S_R)^2, is a 1-D root.
    """
    a = np.asarray(a, dtype=float)
    _, S_A, S_R, S_J = _scales_like(scales, a.shape)
    P = 1.0 / (a * (1.0 - a))
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        c = S_J**2 * (P / a) ** 2 / (S_A**3 * P**3)
        b_aj = np.where(np.isinf(c), 1.0, 2.0 * c / (c + np.sqrt(c * c + 4.0 * c)))
    beta = np.clip(b_aj, low, high)
    if scales.rms.any():
        dwell = np.broadcast_to(_dwell_like(scales, a.shape), a.shape).reshape(-1)

        def gap(b: np.ndarray, where: np.ndarray) -> np.ndarray:
            aa, bb = a.reshape(-1)[where], b
            _, _, c_a_rms, c_j = double_s_coefficients(aa, bb)
            T_j = np.cbrt(c_j * S_J.reshape(-1)[where])
            # T_R > T_J exactly where T_J^3 (T_J + dwell) < (C_a_rms S_R)^2 (always where
            # T_J <= -dwell: T_R lies above -dwell)
            inner = T_j**3 * (T_j + dwell[where])
            with np.errstate(divide="ignore", invalid="ignore"):
                return np.where(inner > 0.0, 2.0 * np.log(c_a_rms * S_R.reshape(-1)[where])
                                - np.log(inner), np.inf)

        every = np.arange(a.size)
        f_low = gap(np.full(a.size, low), every)
        f_top = gap(beta.reshape(-1), every)
        cross = (f_low < 0.0) & (f_top > 0.0)
        flat = beta.reshape(-1).copy()
        flat[f_low >= 0.0] = low
        if cross.any():
            where = np.flatnonzero(cross)
            # in log(beta), where T_J ~ beta^(-1/3) makes the gap nearly linear
            flat[where] = np.exp(log_gap_root(lambda u, i: gap(np.exp(u), where[i]),
                                              np.full(len(where), math.log(low)),
                                              np.log(flat[where]), f_low[where],
                                              f_top[where]))
        beta = flat.reshape(a.shape)
    return np.where(S_J > 0.0, beta, low)


# ------------------------------------------------------------------------- helpers
def _log_ratio(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """log x - log y (inf or nan where a bound is zero or missing)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.log(x) - np.log(y)


def _crossing(gap, n: int, low: float, high: float) -> np.ndarray:
    """Where gap(a) (arrays (n, 1) -> (n, 1)) changes sign in [low, high], else low."""
    lo, hi = np.full(n, low), np.full(n, high)
    f_lo, f_hi = gap(lo[:, None])[:, 0], gap(hi[:, None])[:, 0]
    root = np.full(n, low)
    sign_change = np.isfinite(f_lo) & np.isfinite(f_hi) & (np.sign(f_lo) * np.sign(f_hi) < 0)
    if sign_change.any():
        idx = np.nonzero(sign_change)[0]

        def restricted(x: np.ndarray, i: np.ndarray) -> np.ndarray:
            full = np.full(n, low)
            full[idx[i]] = x
            return gap(full[:, None])[idx[i], 0]

        root[idx] = log_gap_root(restricted, lo[idx], hi[idx], f_lo[idx], f_hi[idx])
    return root


def log_gap_root(f, lo: np.ndarray, hi: np.ndarray, f_lo: np.ndarray, f_hi: np.ndarray,
                 ftol: float = 1e-15) -> np.ndarray:
    """Roots of a log-ratio of two bounds, f(x, i) for the elements i, bracketed by
    [lo, hi] with f_lo, f_hi of opposite signs: Illinois steps on the unsettled elements
    until |f| <= ftol (the bounds equal to 1e-15 relative) or the bracket is one ulp."""
    lo, hi, f_lo, f_hi = (np.array(x, dtype=float) for x in (lo, hi, f_lo, f_hi))
    root = 0.5 * (lo + hi)
    side = np.zeros(lo.shape)
    active = np.arange(len(lo))
    for step in range(200):
        if not len(active):
            break
        a, b, fa, fb = lo[active], hi[active], f_lo[active], f_hi[active]
        with np.errstate(invalid="ignore", divide="ignore"):
            x = (a * fb - b * fa) / (fb - fa)
        bad = ~np.isfinite(x) | (x <= a) | (x >= b) | (step % 8 == 7)
        x = np.where(bad, 0.5 * (a + b), x)
        fx = f(x, active)
        done = (np.abs(fx) <= ftol) | (b - a <= 4e-16 * np.maximum(np.abs(a), np.abs(b)))
        root[active] = x
        same = np.sign(fx) == np.sign(fa)  # root in [x, b]: move lo
        s = side[active]
        fb = np.where(same & (s == -1), 0.5 * fb, fb)
        fa = np.where(~same & (s == 1), 0.5 * fa, fa)
        lo[active], f_lo[active] = np.where(same, x, a), np.where(same, fx, fa)
        hi[active], f_hi[active] = np.where(same, b, x), np.where(same, fb, fx)
        side[active] = np.where(same, -1, 1)
        active = active[~done]
    return root


def _finish(scales: BoundScales, params: dict[str, np.ndarray], duration: np.ndarray,
            default: dict[str, float]) -> OptimalShape:
    """Infeasible motors keep the default shape (for reporting) and T = inf."""
    ok = scales.feasible & np.isfinite(duration)
    params = {k: np.where(ok, v, default[k]) for k, v in params.items()}
    return OptimalShape(params, np.where(ok, duration, np.inf))


# --------------------------------------------------------------------------- entry
def bound_scales(calculator, limits, raw: DurationBounds | None = None) -> BoundScales:
    """The scales of the bounds for the candidates of a CycleCalculator (law unused):
    those of eq. (6.2) in sizer.sizing.shortest_duration (``raw`` where known), zeroed
    where one is infinite (no shape can meet it: ``feasible`` False) and where the closed
    forms do not decide (DurationBounds.undecided: ``feasible`` False too, the caller
    searches those)."""
    raw = duration_bounds(calculator, limits) if raw is None else raw
    scales = (raw.speed, raw.torque, raw.rms, raw.jerk)
    feasible = np.all(np.isfinite(np.stack(scales)), axis=0) & ~raw.undecided
    speed, torque, rms, jerk = (np.where(feasible, s, 0.0) for s in scales)
    dwell = np.where(feasible, raw.dwell, 0.0) if np.ndim(raw.dwell) else raw.dwell
    return BoundScales(speed, torque, rms, jerk, dwell=dwell, feasible=feasible)


def exact_time_optimal(family: type[MotionLaw], fixed: dict[str, float],
                       ranges: dict[str, tuple[float, float]], design: Design,
                       candidates: Candidates) -> tuple[dict[str, np.ndarray], np.ndarray] | None:
    """The exact optimum where it is known (minimize mode, the book's case with constant
    torques: sizer.sizing.shortest_duration.has_constant_torques), else None.

    With it, the mask of the motors left to the search: those whose region goes on past
    the flat part the exact optimum sees, where the optimum reaches the end of it
    (sizer.sizing.shortest_duration.beyond_flat_part), and those the closed forms with
    constant torques do not decide (DurationBounds.undecided).
    """
    if not design.machine_cycle.minimize or family not in (Trapezoidal, DoubleS) \
            or design.transmission.linkage is not None or design.load.position_dependent:
        return None  # the book's case has no linkage and no load of the position
    if "alpha_d" in fixed or "beta_d" in fixed:  # the closed form is the symmetric law's
        return None
    motors = candidates.motors
    calculator = CycleCalculator(None, single_task(design), candidates.drive, motors,
                                 design.limits.thermal_speed)
    if not has_constant_torques(calculator):
        return None
    raw = duration_bounds(calculator, design.limits)
    scales = bound_scales(calculator, design.limits, raw)
    if family is Trapezoidal:
        if design.limits.max_jerk is not None:  # infinite jerk: no alpha is feasible
            return {"alpha": np.full(len(motors), 1.0 / 3.0)}, np.zeros(len(motors), bool)
        solution = optimal_trapezoid(scales, *ranges["alpha"])
    else:
        given = {p.name: float(p.default) for p in family.parameters
                 if p.default is not None} | fixed
        a = ranges.get("alpha", (given["alpha"],) * 2)
        b = ranges.get("beta", (given["beta"],) * 2)
        solution = optimal_double_s(scales, a[0], b[0], a[1], b[1])
    alpha = solution.params.get("alpha", np.full(len(motors), fixed.get("alpha", 0.0)))
    # C_v = 1/(1 - alpha) for both families (sec. 3.2, 3.4)
    beyond = beyond_flat_part(calculator, design.limits, solution.duration, 1.0 / (1.0 - alpha))
    beyond |= raw.undecided
    return {name: solution.params[name] for name in ranges}, beyond


# ------------------------------------------------- the trapezoid with constant phases
AGREEMENT = 1e-9
"""Relative difference of the model's T_min from the engine's at which a motor is scored
by the model."""

MODELLED = frozenset({CheckName.SPEED, CheckName.PEAK, CheckName.RMS,
                      CheckName.THERMAL_SPEED, CheckName.INERTIA_RATIO,
                      CheckName.LOAD_SPEED, CheckName.ACCELERATION, CheckName.JERK})
"""The checks the model knows (the inertia ratio does not depend on the shape: where it
fails the engine's T_min is inf at every shape, and the model does not agree)."""

DOUBLINGS = 64
"""Doublings of T past the other bounds looking for a duration the RMS allows."""
NEWTON_STEPS = 200
"""Most steps of the search for the RMS crossing (Newton's in log T: about three)."""


@dataclass(frozen=True)
class PhaseTorques:
    """Per motor (arrays (n,)) the figures of the model (module docs) for a trapezoid or a
    double S of stroke h, ``moves`` moves each followed by ``dwell``."""

    h: float
    moves: int
    dwell: float
    speed: np.ndarray
    """S of T >= C_v S."""
    acceleration: np.ndarray
    """The largest load acceleration in the outer phases the peaks and the load's limit
    allow (x of the module docs); <= 0 where none."""
    jerk: float
    """S_J = h / j_max of T >= cbrt(C_j S_J); 0 without a jerk limit."""
    slopes: np.ndarray
    """P_k (moves, pieces, n): the motor torque per unit load acceleration."""
    offsets: np.ndarray
    """C_k (moves, pieces, n): the motor torque at rest in the motion's direction."""
    held: np.ndarray
    """n d H^2: the dwells' share of the integral of the squared torque."""
    rating: np.ndarray
    """tau_c'^2, the squared continuous torque with its margin."""
    feasible: np.ndarray
    """False where no shape passes (the cruise or the hold above the peak limit)."""

    def durations(self, alpha: np.ndarray, rows: np.ndarray,
                  beta: np.ndarray | None = None) -> np.ndarray:
        """T_min of the trapezoid at ``alpha`` (the double S at ``alpha``, ``beta``) for the
        motors ``rows`` (arrays of one shape; inf where nothing passes, nan where a
        parameter is nan)."""
        a = np.asarray(alpha, dtype=float)
        b = np.zeros(a.shape) if beta is None else np.asarray(beta, dtype=float)
        c_v, c_a = 1.0 / (1.0 - a), 1.0 / (a * (1.0 - a) * (1.0 - b))
        top = self.acceleration[rows]
        with np.errstate(divide="ignore", invalid="ignore"):
            T = np.maximum(c_v * self.speed[rows], np.sqrt(c_a * self.h / top))
            if self.jerk > 0.0:
                T = np.maximum(T, np.cbrt(c_a / (a * b) * self.jerk))
        T = np.where(self.feasible[rows] & (top > 0.0), T, np.inf)
        ramps = beta is not None
        fails = np.isfinite(T) & (self._rms_excess(T, a, b, rows, ramps) > 0.0)
        if fails.any():
            where = np.flatnonzero(fails)
            every = np.broadcast_to(rows, a.shape)
            T.flat[where] = self._rms_crossing(T.flat[where], a.flat[where], b.flat[where],
                                               every.flat[where], ramps)
        return np.where(np.isnan(a) | np.isnan(b), np.nan, T)

    def _rms_excess(self, T: np.ndarray, a: np.ndarray, b: np.ndarray, rows: np.ndarray,
                    ramps: bool = False) -> np.ndarray:
        """The squared RMS torque over its limit, less one (> 0: the RMS check fails).
        Per move: the plateaus at +-x (alpha (1 - 2 beta) each), the cruise (1 - 2 alpha)
        and with ``ramps`` the double S's four ramps (alpha beta each, the torque's mean
        square over a uniform sweep of the acceleration: :func:`_sweep_mean_square`)."""
        return self._excess_and_slope(T, a, b, rows, ramps, False)[0]

    def _excess_and_slope(self, T: np.ndarray, a: np.ndarray, b: np.ndarray,
                          rows: np.ndarray, ramps: bool, slope: bool = True
                          ) -> tuple[np.ndarray, np.ndarray | None]:
        """:meth:`_rms_excess` and, with ``slope``, its derivative in T: with N = T M +
        n d H^2 and D = n tau_c'^2 (T + d), dN/dT = M - 2 x dM/dx (x = C_a h / T^2), a
        plateau's d(t^2)/dx = 2 t dt/dx (the slope of the line that is the torque), a
        ramp's mean square S' = (t(x)^2 - S) / x."""
        with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
            x = self.h / (a * (1.0 - a) * (1.0 - b)) / T / T
            plateau = a * (1.0 - 2.0 * b)
            p, c = self.slopes[:, :, rows], self.offsets[:, :, rows]
            rising, falling = p * x + c, c - p * x  # each move's lines at +-x
            rise, fall = np.max(rising, axis=1), np.max(falling, axis=1)
            cruise = np.max(c, axis=1)
            terms = plateau * (rise * rise + fall * fall) + (1.0 - 2.0 * a) * cruise**2
            swept = None
            if ramps:  # the four ramps of every move in one sweep: (sign, move, ...)
                lines = p.shape[1]
                swept = _sweep_mean_square(
                    np.concatenate([p, -p]).swapaxes(0, 1).reshape(lines, -1),
                    np.concatenate([c, c]).swapaxes(0, 1).reshape(lines, -1),
                    np.broadcast_to(x, (2, *p.shape[:1], *np.shape(x))).reshape(-1))
                swept = swept.reshape(2, *terms.shape)
                terms = terms + 2.0 * a * b * (swept[0] + swept[1])
            total = np.sum(terms, axis=0)
            scale = self.moves * self.rating[rows]
            excess = (T * total + self.held[rows]) / (scale * (T + self.dwell)) - 1.0
            if not slope:
                return excess, None
            up = np.take_along_axis(p, np.argmax(rising, axis=1)[:, None], axis=1)[:, 0]
            down = np.take_along_axis(p, np.argmax(falling, axis=1)[:, None], axis=1)[:, 0]
            d_terms = 2.0 * plateau * (rise * up - fall * down)
            if swept is not None:
                d_terms = d_terms + 2.0 * a * b * (rise * rise - swept[0]
                                                   + fall * fall - swept[1]) / x
            d_numerator = total - 2.0 * x * np.sum(d_terms, axis=0)
            return excess, (d_numerator - (excess + 1.0) * scale) / (scale * (T + self.dwell))

    def _rms_crossing(self, low: np.ndarray, a: np.ndarray, b: np.ndarray, rows: np.ndarray,
                      ramps: bool) -> np.ndarray:
        """The smallest T > low (where the RMS fails) at which it holds, to rounding:
        Newton's method on log(excess + 1) = log N - log D in log T from ``low``, kept
        inside the bracket of the durations tried (doubling until one holds where a step
        would leave it), stepping at least an ulp up from a failing duration; inf where
        no duration up to 2^DOUBLINGS times ``low`` holds. In those variables an inertial
        torque's N ~ T^-3 against D ~ T is a line (one step; the excess itself, ~ T^-4,
        gains a quarter of T per step from far below)."""
        T, lo = low.copy(), low.copy()
        hi = np.full(len(low), np.inf)
        out = np.full(len(low), np.inf)
        index = np.arange(len(low))
        ceiling = low * 2.0**DOUBLINGS
        for _ in range(NEWTON_STEPS):
            if not len(index):
                break
            f, df = self._excess_and_slope(T, a[index], b[index], rows[index], ramps)
            assert df is not None
            holds = f <= 0.0
            hi[index] = np.where(holds, T, hi[index])
            lo[index] = np.where(holds, lo[index], T)
            with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
                ratio = 1.0 + f  # N / D; d log(N / D) / d log T = T df / (1 + f)
                step = T * np.exp(-np.log(ratio) * ratio / (T * df))
            below, h = lo[index], hi[index]
            # from a failing duration at least an ulp up (its step may round to it)
            step = np.where(holds, step, np.maximum(step, np.nextafter(T, np.inf)))
            inside = np.isfinite(step) & (step > below) & (step < h)
            nxt = np.where(inside, step, np.where(np.isfinite(h), 0.5 * (below + h), 2.0 * T))
            done = (h - below <= 4.0 * np.spacing(h)) | (holds & (np.abs(step - T)
                                                                  <= 4.0 * np.spacing(T)))
            out[index[done]] = h[done]
            lost = ~done & (nxt > ceiling[index])
            keep = ~(done | lost)
            index, T = index[keep], nxt[keep]
        out[index] = hi[index]  # (steps spent: the shortest duration found to hold)
        return out


def _sweep_mean_square(p: np.ndarray, c: np.ndarray, x: np.ndarray) -> np.ndarray:
    """(1/x) int_0^x (max_k p_k s + c_k)^2 ds per element (p, c: (lines, m), x: (m,)):
    the mean square of the torque while the acceleration sweeps [0, x] uniformly (a ramp
    of the double S). The largest of the lines is a convex polyline whose corners are
    among the lines' crossings: on each stretch between the sorted crossings inside
    (0, x) one line, whose square integrates exactly ((y0^2 + y0 y1 + y1^2) w / 3)."""
    shape, lines = np.shape(x), p.shape[0]
    p, c, x = p.reshape(lines, -1), c.reshape(lines, -1), np.ravel(x)
    if lines == 1:  # one line: no corner
        y0, y1 = c[0], p[0] * x + c[0]
        return ((y0 * y0 + y0 * y1 + y1 * y1) / 3.0).reshape(shape)
    ends = [np.zeros(x.shape), x]
    for i in range(lines):
        for j in range(i + 1, lines):
            with np.errstate(divide="ignore", invalid="ignore"):
                s = (c[j] - c[i]) / (p[i] - p[j])
            ends.append(np.where((s > 0.0) & (s < x), s, 0.0))
    cuts = np.sort(np.stack(ends), axis=0)
    lo, hi = cuts[:-1], cuts[1:]
    pick = np.argmax(p[:, None] * (0.5 * (lo + hi)) + c[:, None], axis=0)
    column = np.arange(x.size)
    slope, level = p[pick, column], c[pick, column]
    y0, y1 = slope * lo + level, slope * hi + level
    return (np.sum((hi - lo) * (y0 * y0 + y0 * y1 + y1 * y1), axis=0) / (3.0 * x)).reshape(shape)


def phase_model(design: Design, candidates: Candidates,
                family: type[MotionLaw] = Trapezoidal) -> PhaseTorques | None:
    """The model of the module docs for these candidates, or None where its case does not
    hold (damping, stage ratings, another thermal rule, a jerk limit for the
    trapezoid...). The motors' regions are taken as flat: :func:`trusted_phase_model`
    keeps the motors where they are."""
    limits, motors, drive = design.limits, candidates.motors, candidates.drive
    cycle = design.machine_cycle
    if family not in (Trapezoidal, DoubleS) or not cycle.minimize \
            or design.transmission.linkage is not None or design.load.position_dependent \
            or (family is Trapezoidal and limits.max_jerk is not None) \
            or limits.thermal_speed != "max" or not plain_stages(drive):
        return None
    task = single_task(design)
    calculator = CycleCalculator(None, task, drive, motors, limits.thermal_speed)
    n = len(motors)

    def per_motor(x) -> np.ndarray:
        return np.broadcast_to(np.asarray(x, dtype=float), (n,)).copy()

    K, h = per_motor(drive.ratio), calculator.h
    speed_part = 1.0 - limits.speed_margin
    grip = 1.0 - limits.torque_margin
    peak = motors.intermittent.torques[:, 0] * grip
    with np.errstate(divide="ignore", invalid="ignore"):
        speed = K * h / (np.minimum(motors.speed_limit, motors.continuous.max_speed)
                         * speed_part)
        if limits.max_speed is not None:
            speed = np.maximum(speed, h / limits.max_speed)
    top = np.full(n, np.inf) if limits.max_acceleration is None \
        else np.full(n, limits.max_acceleration)
    slopes, offsets = [], []
    feasible = np.ones(n, dtype=bool)
    unit = np.ones(n)
    for direction in calculator.directions:
        # the motor's functions per unit load acceleration and speed (the engine's own)
        motor = calculator.channel_terms(MoveScales(unit, unit, float(direction)))[0]
        if any(bool(np.any(Q != 0.0)) for _, Q, _ in motor):
            return None  # damping: a torque of the speed, not of the acceleration alone
        P = np.stack([P for P, _, _ in motor])
        C = np.stack([C for _, _, C in motor])
        with np.errstate(divide="ignore", invalid="ignore"):
            top = np.minimum(top, np.minimum(np.min((peak - C) / P, axis=0),
                                             np.max((peak + C) / P, axis=0)))
        feasible &= np.abs(np.max(C, axis=0)) <= peak
        slopes.append(P)
        offsets.append(C)
    if len({len(P) for P in slopes}) > 1:
        return None  # (the directions' functions are as many: Drive.linear_pieces)
    moves = len(calculator.directions)
    hold = per_motor(drive.holding_torques()[0])
    if task.dwell > 0.0:
        feasible &= hold <= motors.intermittent.limit(np.zeros(n)) * grip
    rating = np.square(motors.continuous.torques[:, 0] * grip)
    jerk = 0.0 if limits.max_jerk is None else h / limits.max_jerk
    return PhaseTorques(h, moves, task.dwell, speed, top, jerk, np.stack(slopes),
                        np.stack(offsets), moves * task.dwell * hold * hold, rating, feasible)


@dataclass(frozen=True)
class TrustedModel:
    """The model, per motor whether it scores it, and the law's parameters: ``names`` the
    searched ones in the search's order, ``fixed`` the others (:func:`trusted_phase_model`)."""

    model: PhaseTorques
    trusted: np.ndarray
    names: tuple[str, ...]
    fixed: dict[str, float]

    def durations(self, points: list[np.ndarray], rows: np.ndarray) -> np.ndarray:
        """T_min of the motors ``rows`` at ``points`` (an array per searched parameter):
        the double S where the parameters have a beta, else the trapezoid."""
        values = dict(self.fixed) | dict(zip(self.names, points, strict=True))
        shape = np.shape(points[0])
        alpha = np.broadcast_to(np.asarray(values["alpha"], dtype=float), shape)
        if "beta" not in values:
            return self.model.durations(alpha, rows)
        beta = np.broadcast_to(np.asarray(values["beta"], dtype=float), shape)
        return self.model.durations(alpha, rows, beta)


def trusted_phase_model(family: type[MotionLaw], fixed: dict[str, float], names: list[str],
                        ranges: dict[str, tuple[float, float]], design: Design,
                        candidates: Candidates) -> TrustedModel | None:
    """The model for the search of a symmetric trapezoid's alpha or a symmetric double S's
    alpha and beta over these candidates, with the motors it scores: those with
    rectangular regions whose T_min of the law at the middle of the ranges, sized by the
    engine, is the model's to AGREEMENT with no check the model does not know (both inf
    counts as agreeing). None where the case does not hold or no motor agrees."""
    shape = {"alpha"} if family is Trapezoidal else {"alpha", "beta"}
    if family not in (Trapezoidal, DoubleS) or not set(names) | set(fixed) <= shape:
        return None  # (alpha_d, beta_d: an asymmetric law)
    model = phase_model(design, candidates, family)
    if model is None:
        return None
    given = {p.name: float(p.default) for p in family.parameters
             if p.name in shape and p.default is not None} | fixed
    middle = given | {name: 0.5 * sum(ranges[name]) for name in names}
    n = len(candidates)
    law = family(**middle)
    calculator = CycleCalculator(None, single_task(design), candidates.drive,
                                 candidates.motors, design.limits.thermal_speed, law=law)
    solution = minimum_duration(calculator, design.limits)
    if not {check.name for check in solution.checks} <= MODELLED:
        return None
    engine = np.where(solution.feasible, solution.duration, np.inf)
    trusted = TrustedModel(model, np.ones(n, dtype=bool), tuple(names),
                           {k: v for k, v in given.items() if k not in names})
    mine = trusted.durations([np.full(n, middle[name]) for name in names], np.arange(n))
    with np.errstate(invalid="ignore"):
        agree = np.where(np.isinf(engine), np.isinf(mine),
                         np.abs(mine - engine) <= AGREEMENT * engine)
    agree &= candidates.motors.is_rectangular
    return replace(trusted, trusted=agree) if agree.any() else None
