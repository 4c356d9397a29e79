"""The shortest duration at which every check passes: T_min per candidate (book eq. 6.2).

With the book's rectangular regions, an ideal transmission of plain stages and no damping
T_min is a closed form (:func:`closed_form_duration`): eq. (6.2) for a purely inertial load,
extended to a cycle with dwell and to the load's constant torques (Coulomb friction, a
constant external load), derived below. Otherwise T_min starts from a lower bound, the
largest duration below which a peak or speed check fails (the model's peak_bound): where the
cycle is feasible there it is T_min; where the RMS check fails there, T_min is where the RMS
reaches its limit, by rounds on the cycle's RMS model (:func:`rms_crossing`). What these
leave (and the designs whose laws move backwards, where the bound does not hold) is found by
a search on the worst slack, vectorized over candidates: a walk in log T up the slack until
a feasible duration (or Brent's search for the slack's maximum where it stops
rising), then Chandrupatla's method down to where the binding check reaches its limit, to a
relative width of 1e-13; each step evaluates only the candidates still open.

The checks this search does not see, the later limits (residual vibration, braking
resistor, winding temperature: :class:`LaterLimit`), are settled in the same search
(:func:`settle`): from the mechanical T_min each gives its smallest passing scale, the
candidate moves there and the mechanical checks are evaluated again; the limits take
turns until none moves.

Feasible means what it means everywhere (sizer.sizing.checks.feasible: every slack
>= -TOLERANCE). T_min is where the binding check is exactly at its limit; only where no
duration reaches slack 0 but some are within the tolerance, it is the shortest of those.

The closed form with constant torques (book sec. 6.1.1, eq. 6.1 and 6.2). With an ideal
drive (Drive.is_ideal: efficiencies 1, or on the steady load only), plain stages and no
damping (load and motors), the motor torque along move i of a rest-to-rest cycle is

    tau_i(t) = J_t K h q_N''(t/T) / T^2 + c_i,

J_t = J_m + J_stages + J_l/K^2, and c_i the constant the drive reflects to the motor for
that direction: the friction opposing the motion plus the constant external load, both
from Drive.linear_chain (e.g. forward c = (F + G)/K, return c = (F - G)/K through an
ideal gearbox, the torques along each move's own motion: the return's torque in the
forward sense is -(J a) - F + G). In the dwells the motor holds H (Drive.holding_torques:
the external load alone; zero for friction alone), and the peak check reads it too.

Peak. max_t |tau_i| = max(P a_max + c_i, P |a_min| - c_i), P = J_t K h / T^2 and a_max,
a_min the law's extreme q_N'' (both C_a for a symmetric law). So the peak check,
|tau| <= tau_p' = (1 - margin) tau_p, holds iff T^2 >= a_max J_t K h / (tau_p' - c_i) and
T^2 >= |a_min| J_t K h / (tau_p' + c_i) for every move: with up = max_i c_i and down =
max_i (-c_i) the torque scale of a symmetric law is S_A = J_t K h / (tau_p' - max(up, down))
= J_t K h / (tau_p' - max_i |c_i|), T_A = sqrt(C_a S_A) as in eq. (6.2), no duration where
the denominator is <= 0. The load's acceleration limit adds T^2 >= C_a h / a_max as before.

RMS. Over a rest-to-rest move int q_N'' = 0, so the cross term of tau_i^2 integrates to 0
and int tau_i^2 dt = (J_t K h C_a_rms)^2 / T^3 + c_i^2 T. With n moves each followed by a
dwell t_d holding H, RMS^2 = (sum_i int tau_i^2 dt + n t_d H^2) / (n (T + t_d))
(sizer.sizing.move.CycleCalculator.evaluate), and the check RMS <= tau_c' = (1 - margin)
tau_c (the continuous region's flat torque at the thermal speed, whatever the thermal
rule, as long as the move stays on the flat part) reads, with m2 = mean_i c_i^2,

    (J_t K h C_a_rms)^2 / T^3 <= T (tau_c'^2 - m2) + t_d (tau_c'^2 - H^2),

i.e. where A = tau_c'^2 - m2 > 0: T^3 (T + t_d') >= (C_a_rms S_R')^2 with
S_R' = J_t K h / sqrt(A) and t_d' = t_d (tau_c'^2 - H^2) / A (the book's S_R = J_t K h /
tau_c' and t_d where c = H = 0). The left side rises for T > -t_d' (t_d' < 0 where the
hold exceeds the rating: then T > -t_d' and the RMS still falls to sqrt(m2) as T grows),
so the crossing is unique (:func:`rms_duration`). Where A <= 0 the RMS tends to sqrt(m2)
>= tau_c': no duration if it also exceeds it in the dwell (or there is none), B = t_d
(tau_c'^2 - H^2) <= 0; else a window of durations may pass where max_T T^3 (A T + B) =
(27/256) B^4 / |A|^3 (at T = 3B / (4|A|)) reaches (J_t K h C_a_rms)^2, which needs at
least (J_t K h)^2 12 (LEAST_SQUARE: no rest-to-rest law has C_a_rms^2 below the cubic's
12): below that no law passes at any duration, otherwise the search looks.

Where a denominator is within EDGE of 0 (the crossing ill-conditioned) or an RMS window
may exist the closed form does not decide: those candidates are searched
(DurationBounds.undecided); where a constant alone fails a check by more than the
tolerance at every duration there is no duration (inf). Everything else the closed form
gives is verified like any duration (:func:`minimum_duration`).

Below which duration can no candidate be feasible (:func:`duration_floor`)? The peak and
speed bound of sizer.sizing.move.peak_duration (book sec. 6.1.1, eq. 6.2 in the
rectangular case) holds for the checks as they are decided, tolerance included, when
every limit it reads is relaxed by the checks' tolerance: a check passes where value <=
(1 - required + TOLERANCE) * limit (sizer.sizing.checks), so a torque margin m reads as
m - TOLERANCE, a speed margin likewise, a load limit as (1 + TOLERANCE) times itself.
Every duration a candidate reports as feasible passes those checks, so it is at least
the floor; the later limits only move T_min up, which keeps it so. The ratio search
(sizer.sizing.choices) leaves out an option whose floor lies above a motor's best T_min:
it cannot beat it.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np

from sizer.laws import LawChoice, MotionLaw, law_choice
from sizer.laws.row_laws import RowLaws
from sizer.model.cycle import shorthand_task
from sizer.model.domain import Design, Limits, Task, ThermalSpeedRule
from sizer.numerics.golden import BrentMax, interior_points
from sizer.numerics.roots import bracketed_root
from sizer.sizing.candidates import Candidates, MotorArrays
from sizer.sizing.checks import (
    TOLERANCE,
    CheckArrays,
    dead_point_check,
    evaluate_checks,
    feasible,
    unbounded_checks,
    worst_slack,
)
from sizer.sizing.cycle import single_task
from sizer.sizing.evaluation import (
    CycleMetrics,
    CycleModel,
    RmsCurve,
    combined_metrics,
    singular_metrics,
)
from sizer.sizing.move import (
    CycleCalculator,
    acceleration_range,
    peak_queries,
    speed_bounds,
)

if TYPE_CHECKING:
    from sizer.mechanics import Drive

EXPANSIONS = 80
PEAK_STEPS = 80
PEAK_WIDTH = 1e-7
STEP = math.log(2.0)


@dataclass(frozen=True)
class DurationSolution:
    """T_min per candidate (nan where no duration is feasible) and the state there."""

    duration: np.ndarray
    feasible: np.ndarray
    metrics: CycleMetrics
    checks: list[CheckArrays]
    method: str


def evaluate(calculator: CycleModel, limits: Limits, T: np.ndarray, peaks: bool = True,
             model: bool = False, rms: np.ndarray | None = None):
    """The metrics and checks at T (CycleModel.evaluate; ``rms`` known there)."""
    metrics = calculator.evaluate(T, peaks, model=True) if model else \
        calculator.evaluate(T, peaks, rms=rms)
    checks = evaluate_checks(metrics, calculator.motors, calculator.drive, limits,
                             calculator.task.linear)
    return metrics, checks


def has_constant_torques(calculator: CycleModel) -> bool:
    """The case of the closed forms (module docs): ideal transmission, plain stages, no
    damping; the load may have Coulomb friction and a constant torque, so the motor torque
    along each move is its inertial part plus a constant.

    The motors' regions are read as their flat part (MotorArrays.flat_speed): exact for
    the book's rectangles, and for extended regions wherever the move's peak speed stays
    below the end of the flat part (:func:`minimum_duration` searches the others).
    """
    drive, motors = calculator.drive, calculator.motors
    return (drive.figures.none("damping") and drive.is_ideal and plain_stages(drive)
            and bool(np.all(motors.damping == 0.0)))


def plain_stages(drive: Drive) -> bool:
    """Whether no stage has a preload torque or a rating of its own (speed, torques): the
    motor's checks are the stages' too."""
    return all(bool(np.all(s.preload_torque == 0.0)) and s.max_input_speed is None
               and s.rated_output_torque is None and s.peak_output_torque is None
               for s in drive.stages)


def is_purely_inertial(calculator: CycleModel) -> bool:
    """The case of eq. (6.2) as the book has it: :func:`has_constant_torques` without
    friction or a constant load (no constant torque at all)."""
    return calculator.drive.figures.none("friction", "torque") \
        and has_constant_torques(calculator)


def laws_model(laws: Sequence[MotionLaw], part: np.ndarray, task: Task, drive: Drive,
               motors: MotorArrays, thermal_speed: ThermalSpeedRule) -> CycleCalculator | None:
    """Several law moves of ``task`` as the rows of one model (sizer.laws.row_laws.RowLaws
    in CycleCalculator), row i with laws[part[i]]: the closed forms and the search for
    T_min once over all the rows, each row's numbers its law's alone; None where a law may
    move backwards (no peak bound: its search is another, law by law)."""
    law = RowLaws(laws, part)
    return None if law.moves_backwards() else CycleCalculator(None, task, drive, motors,
                                                               thermal_speed, law=law)


def minimum_duration(calculator: CycleModel, limits: Limits) -> DurationSolution:
    """Shortest feasible duration of the calculator's law for each candidate.

    The closed form is checked like any duration; where it misses (a check it does not
    model, or rounding beyond the tolerance) the search starts from it.
    """
    move = calculator.law_move()
    if move is not None and has_constant_torques(move):
        # a law move rest-to-rest: its closed form (only its law has the coefficients);
        # where it does not decide (DurationBounds.undecided) the search
        bounds = duration_bounds(move, limits)
        T = closed_form_duration(move, limits, bounds)
        method = "closed form (eq. 6.2)"
        finite = np.isfinite(T)
        probe = np.where(finite, T, _largest_tried(calculator))
        metrics, checks = evaluate(calculator, limits, probe)
        missed = finite & ~feasible(checks)
        beyond = beyond_flat_part(move, limits, T) | bounds.undecided
        if not (missed | beyond).any():  # the closed form is the answer: no search
            ok = finite & feasible(checks)
            return DurationSolution(np.where(ok, probe, np.nan), ok, metrics, checks, method)
        start = np.where(missed & (T > 0.0), T, calculator.initial_guess())
        searched = bisect_duration(calculator, limits, guess=start, active=missed | beyond)
        T = np.where(missed | beyond, searched, T)
    else:
        bound = calculator.peak_bound(limits)
        if bound is not None:
            return _from_bound(calculator, limits, bound)
        T = bisect_duration(calculator, limits)
        method = "search on the scale of the free durations" if calculator.segmented \
            else "bisection"
    finite = np.isfinite(T)
    probe = np.where(finite, T, _largest_tried(calculator))
    metrics, checks = evaluate(calculator, limits, probe)
    ok = finite & feasible(checks)
    return DurationSolution(np.where(ok, probe, np.nan), ok, metrics, checks, method)


def _from_bound(calculator: CycleModel, limits: Limits,
                bound: np.ndarray) -> DurationSolution:
    """T_min from a lower bound (sizer.sizing.move): the bound itself where the
    cycle is feasible there. Elsewhere, in turn, each step for the candidates the last
    one left infeasible: where the motor's RMS check reaches its limit above the bound
    (:func:`rms_crossing`); a search from the bound on the checks other than the peaks
    (which pass from the bound on: the cheap part of an evaluation); a search on all the
    checks from there. inf bounds: no duration."""
    usable = np.isfinite(bound) & (bound > 0.0)
    probe = np.where(usable, bound, _largest_tried(calculator))
    # the RMS model at the bound too: the first round of the RMS crossing starts there;
    # the peaks only where every other check passes (elsewhere the candidate is searched
    # on and evaluated again where it ends)
    metrics, checks = evaluate(calculator, limits, probe, peaks=False, model=True)
    at_bound = metrics.rms_model
    at = probe.copy()  # where each candidate's row of ``metrics`` was evaluated in full
    others = feasible(checks)
    at[~others] = np.nan
    if others.any():
        index = np.flatnonzero(others)
        metrics = merge_metrics(metrics, index,
                                evaluate(calculator.take(index), limits, probe[index])[0])
        checks = evaluate_checks(metrics, calculator.motors, calculator.drive, limits,
                                 calculator.task.linear)
    ok = usable & feasible(checks)
    method = "peak and speed bounds"
    rest = ~ok & np.isfinite(bound)
    if not rest.any() and not np.isnan(at).any():
        return DurationSolution(np.where(ok, probe, np.nan), ok, metrics, checks, method)
    method += " and searches"
    floor = calculator.search_start(limits)
    rest &= ~rms_unreachable(calculator, limits)  # no duration meets the RMS check
    if floor is not None:  # below it a check fails: inf, at every duration
        rest &= np.isfinite(floor)
    guess = calculator.initial_guess()
    if floor is not None:  # from it on the peaks pass (the linkage's peak floor)
        guess = np.where(np.isfinite(floor) & (floor > 0.0), floor, guess)
    start = np.where(usable, bound, guess)
    T = np.where(ok, bound, np.inf)

    known = np.full(len(T), np.nan)  # the RMS at the crossings found, from their models
    # where the RMS crossing starts: the bound, else (where the model gives one) a
    # duration below which a check fails; the crossing above it is then the shortest
    # duration the RMS check allows, verified below with every check
    above = bound if floor is None else np.where(usable, bound, floor)
    startable = np.isfinite(above) & (above > 0.0)

    def from_rms(left: np.ndarray) -> np.ndarray:
        out = np.full(len(T), np.nan)
        index = np.flatnonzero(left & startable)
        if len(index):
            # the model at the bound is built where the crossing starts only where usable
            first = (at_bound, index) if at_bound is not None and usable[index].all() \
                else None
            found, rms = rms_crossing_with_rms(calculator.take(index), limits, above[index],
                                               first)
            keep = found >= above[index] * (1.0 - 1e-12)
            out[index] = np.where(keep, found, np.nan)
            known[index] = np.where(keep, rms, np.nan)
        return out

    steps = (from_rms,
             lambda left: bisect_duration(calculator, limits, guess=start, active=left,
                                          peaks=False),
             lambda left: bisect_duration(calculator, limits, guess=T, active=left))
    passed = ok.copy()
    for number, step in enumerate(steps):
        left = rest & ~passed
        if number == 2:  # no duration passes the other checks: none passes them all
            left &= np.isfinite(T)
        if not left.any():
            break
        found = step(left)
        T[left] = np.where(np.isnan(found[left]), T[left], found[left])
        index = np.flatnonzero(left & np.isfinite(T))  # verified where they changed
        if len(index):
            rms = known[index] if number == 0 else None
            if rms is not None and not np.all(np.isfinite(rms)):
                rms = None
            part, part_checks = evaluate(calculator.take(index), limits, T[index], rms=rms)
            passed[index] = feasible(part_checks)
            metrics = merge_metrics(metrics, index, part)
            at[index] = T[index]
    probe = np.where(np.isfinite(T), T, _largest_tried(calculator))
    again = np.flatnonzero(probe != at)  # rows not yet evaluated where they end
    if len(again):
        metrics = merge_metrics(metrics, again,
                                evaluate(calculator.take(again), limits, probe[again])[0])
    checks = evaluate_checks(metrics, calculator.motors, calculator.drive, limits,
                             calculator.task.linear)
    passed &= feasible(checks)
    return DurationSolution(np.where(passed, probe, np.nan), passed, metrics, checks, method)


def merge_metrics(metrics: CycleMetrics, index: np.ndarray, part: CycleMetrics) -> CycleMetrics:
    """``metrics`` with the rows at ``index`` replaced by those of ``part`` (an evaluation
    of the candidates at ``index``); the RMS model is dropped. Every evaluation is
    elementwise over candidates, so the merge equals one evaluation of all of them."""
    n = len(metrics.duration)

    def put(pair: list[np.ndarray]) -> np.ndarray:
        whole, rows = pair
        out = np.array(np.broadcast_to(whole, (n,)), dtype=np.result_type(whole, rows))
        out[index] = np.broadcast_to(rows, (len(index),))
        return out

    return CycleMetrics(**combined_metrics((metrics, part), put))


def mechanical_answer(calculator: CycleModel, limits: Limits, minimize: bool,
                      peaks: bool = True
                      ) -> tuple[np.ndarray, CycleMetrics, list[CheckArrays], np.ndarray]:
    """(scale, metrics, checks, verdicts) of the mechanical checks: in minimize mode at the
    shortest scale (:func:`minimum_duration`; NaN where infeasible), else at the model's
    given scale (without ``peaks`` the peak checks left passing). Through a linkage the
    dead-point check comes first; a law that breaks its rule is infeasible at any
    duration, shown at the model's first guess with its torques unbounded."""
    issues = calculator.dead_point_issues()
    n = len(calculator.motors)
    point = [] if issues is None else [dead_point_check(issues, n)]
    if minimize and not issues:
        solution = minimum_duration(calculator, limits)
        return solution.duration, solution.metrics, [*point, *solution.checks], \
            solution.feasible
    s = calculator.initial_guess() if minimize else np.full(n, calculator.given_scale())
    metrics = calculator.evaluate(s, peaks)
    if issues:  # the crank's motion is singular: no torque to report
        metrics = singular_metrics(metrics)
    checks = evaluate_checks(metrics, calculator.motors, calculator.drive, limits,
                             calculator.task.linear)
    if issues:
        checks = unbounded_checks(checks)
    checks = [*point, *checks]
    passed = feasible(checks)
    return (np.where(passed, s, np.nan) if minimize else s), metrics, checks, passed


@dataclass(frozen=True)
class LaterChecks:
    """A later limit's checks at the candidates' scales, its verdict per candidate and the
    figures it reports (the residual vibration; the braking and heat figures)."""

    checks: list[CheckArrays]
    passed: np.ndarray
    figures: dict[str, np.ndarray]


class LaterLimit(Protocol):
    """A check the mechanical search does not see and a longer duration may meet (residual
    vibration, braking resistor, winding temperature): its checks at given scales, and the
    smallest scale at or past a given one at which they pass."""

    def at(self, calculator: CycleModel, s: np.ndarray, metrics: CycleMetrics,
           known: np.ndarray) -> LaterChecks:
        """The checks at scales ``s`` where ``known`` (elsewhere they pass, value 0)."""

    def passing_scale(self, calculator: CycleModel, rows: np.ndarray, s: np.ndarray,
                      found: LaterChecks) -> np.ndarray:
        """For the candidates at ``rows`` (failing at their scales ``s``, ``found`` the
        checks there), the smallest scale >= s at which they pass; inf where none is."""


@dataclass(frozen=True)
class Settled:
    """The scales, metrics and checks once every limit is in (mechanical ones first, then
    the later ones), the verdicts and the later limits' figures."""

    scale: np.ndarray
    metrics: CycleMetrics
    checks: list[CheckArrays]
    feasible: np.ndarray
    figures: dict[str, np.ndarray]


LATER_ROUNDS = 16
"""Rounds of the search past the mechanical T_min: each round moves every candidate to the
smallest scale at which each later limit passes; with one later limit one round settles
it, with several they take turns until none moves."""


def answer(calculator: CycleModel, limits: Limits, later: Sequence[LaterLimit],
           minimize: bool, peaks: bool = True) -> Settled:
    """Every check of the model's law for each candidate: in minimize mode at the shortest
    scale at which every slack passes (:func:`mechanical_answer`, then the later limits
    settled by :func:`settle`), else at the given scale."""
    scale, metrics, checks, passed = mechanical_answer(calculator, limits, minimize, peaks)
    return settle(calculator, limits, later, scale, metrics, checks, passed, minimize)


def settle(calculator: CycleModel, limits: Limits, later: Sequence[LaterLimit],
           scale: np.ndarray, metrics: CycleMetrics, checks: list[CheckArrays],
           passed: np.ndarray, minimize: bool) -> Settled:
    """The one search for the shortest duration, continued past the mechanical slacks.

    ``scale``, ``metrics``, ``checks`` and ``passed`` are the mechanical answer (T_min of
    :func:`minimum_duration`, or the given scale). With a given scale the later limits are
    only checked there. In minimize mode each later limit moves the candidates that pass
    every mechanical check and fail it to its smallest passing scale (the mechanical
    checks evaluated again there); the limits take turns until no candidate moves, so the
    scale found is the smallest at which every slack passes, given that the mechanical
    ones still pass there (else the candidate is infeasible: the moved-to scale names the
    failing check). Where a later limit finds no passing scale the candidate stays: its
    check fails there and names the limit.
    """
    scale = np.array(scale, dtype=float)
    ok = np.array(passed, dtype=bool)
    known = np.isfinite(scale) & (ok | (not minimize))
    stuck = np.zeros(len(scale), dtype=bool)
    found = [kind.at(calculator, scale, metrics, known) for kind in later]
    for _ in range(LATER_ROUNDS if minimize else 0):
        target = scale.copy()
        for kind, there in zip(later, found, strict=True):
            rows = np.flatnonzero(ok & known & ~stuck & ~there.passed)
            if rows.size:
                target[rows] = np.maximum(target[rows], kind.passing_scale(
                    calculator, rows, scale[rows], there))
        stuck |= ~np.isfinite(target)
        moved = np.flatnonzero(np.isfinite(target) & (target != scale))
        if not moved.size:
            break
        metrics = merge_metrics(metrics, moved,
                                calculator.take(moved).evaluate(target[moved]))
        checks = replaced_checks(checks, evaluate_checks(
            metrics, calculator.motors, calculator.drive, limits, calculator.task.linear))
        scale[moved] = target[moved]
        ok[moved] = feasible(checks)[moved]
        found = [kind.at(calculator, scale, metrics, known) for kind in later]
    figures: dict[str, np.ndarray] = {}
    for there in found:
        checks = [*checks, *there.checks]
        ok &= there.passed
        figures.update(there.figures)
    if minimize:
        scale = np.where(ok, scale, np.nan)
    return Settled(scale, metrics, checks, ok, figures)


def replaced_checks(checks: list[CheckArrays], new: list[CheckArrays]) -> list[CheckArrays]:
    """``checks`` with those ``new`` evaluates again in their place (by name; the others,
    such as a linkage's dead_point, kept)."""
    by_name = {c.name: c for c in new}
    out = [by_name.pop(c.name, c) for c in checks]
    return [*out, *by_name.values()]


def rms_lower_bound(calculator: CycleModel) -> np.ndarray | None:
    """Per candidate a torque the motor's RMS over the cycle exceeds at every duration
    (book sec. 6.1.1), None where none holds: the model's own (CycleCalculator.
    rms_lower_bound for a move rest-to-rest, SegmentCycle.rms_lower_bound for a cycle)."""
    return calculator.rms_lower_bound()


def rms_unreachable(calculator: CycleModel, limits: Limits) -> np.ndarray:
    """Per candidate: does the RMS check fail at every duration? True only where
    :func:`rms_lower_bound` exceeds the largest torque of the continuous region (the
    limit at any speed) with the margin, by more than rounding: no search can find a
    duration there."""
    bound = rms_lower_bound(calculator)
    if bound is None:
        return np.zeros(len(calculator.motors), dtype=bool)
    top = calculator.motors.continuous.torques.max(axis=1)
    return bound > (1.0 - limits.torque_margin + TOLERANCE) * top * (1.0 + 1e-9)


RMS_ROUNDS = 8
"""Rounds of the RMS crossing at most (each an evaluation and the model's root: the
model's error is of second order, so three or four reach rounding)."""
NEAR = 4.0
"""After the first round, the first step of the bracket search is NEAR times the last
move (in log T): the crossing moves by far less than that from one model to the next."""
CONVERGED = 1e-6
"""A round that moves the duration by less than this (relative) gives the answer: the
model it came from is exact to rounding that close to where it was built."""
FLAT_BAND = 1e-6
"""A crossing is flat where the checks' tolerance spans more than this (relative) in T:
|d log(RMS / limit) / d log T| < TOLERANCE / FLAT_BAND."""
FLAT_STEP = 1e-4
"""Step in log T of the slope's central difference on the model (exact to O(step^2))."""


def rms_crossing(calculator: CycleModel, limits: Limits, start: np.ndarray,
                 first: tuple[RmsCurve, np.ndarray] | None = None) -> np.ndarray:
    """The durations of :func:`rms_crossing_with_rms`."""
    return rms_crossing_with_rms(calculator, limits, start, first)[0]


def rms_crossing_with_rms(calculator: CycleModel, limits: Limits, start: np.ndarray,
                          first: tuple[RmsCurve, np.ndarray] | None = None
                          ) -> tuple[np.ndarray, np.ndarray]:
    """Per candidate the duration above ``start`` where the motor's RMS torque reaches the
    continuous limit at the thermal speed (margin applied); nan where none was found.

    Each round evaluates the cycle at the current durations with its RMS model
    (sizer.sizing.move.RmsModel: exact there, second-order near) and moves to the
    model's crossing: from the current point up (or down) by factors of 2 to a change of
    sign, then the project's root finder. The rounds converge like Newton's method; a
    candidate is done when a round moves it by less than CONVERGED. ``first``: the model
    already built at ``start`` (an evaluation of more candidates, and the rows of these
    in it), which the first round uses instead of evaluating again. With the durations,
    the RMS torque there by the model of the last round (built within CONVERGED of it:
    exact to rounding, the square of that move times the model's second-order error).
    """
    grip = 1.0 - limits.torque_margin
    n = len(start)
    out = np.full(n, np.nan)
    out_rms = np.full(n, np.nan)
    T = np.asarray(start, dtype=float).copy()
    index = np.arange(n)
    moved: np.ndarray | None = None  # per candidate the last round's move in log T
    for number in range(RMS_ROUNDS):
        sub = calculator if len(index) == n else calculator.take(index)
        rows = None
        model: RmsCurve | None
        if number == 0 and first is not None:
            model, rows = first
        else:
            model = sub.evaluate(T, peaks=False, model=True).rms_model
        if model is None:  # a cycle with a free move that has boundary speeds: no model
            break
        model_rows = rows  # this round's candidates in the model (None: the same)

        held = sub.motors.continuous.held_at(sub.thermal_speed(T))

        def excess_of(x: np.ndarray, where: np.ndarray, sub=sub, model=model, rows=rows,
                      template=T, held=held) -> np.ndarray:
            """log(RMS / limit) of the model at log durations x of the candidates at
            ``where`` (the root finder works on the ones still open; each value is the
            same as in a call for all of them)."""
            at = np.exp(x)
            full = template.copy()
            full[where] = at
            speed = sub.thermal_speed(full)[where]
            limit = held.limit_clipped(speed, where)
            with np.errstate(divide="ignore"):
                return (np.log(model.rms(at, where if rows is None else rows[where]))
                        - np.log(grip * limit))

        every = np.arange(len(index))

        def excess(x: np.ndarray, every=every, of=excess_of) -> np.ndarray:
            return of(x, every)

        x0 = np.log(T)
        g0 = excess(x0)
        step = np.where(g0 > 0.0, STEP, -STEP)
        # after the first round the crossing lies within a small multiple of the last
        # move (the model's error is of second order in it): the first step is that
        first_step = step if moved is None else np.copysign(np.minimum(STEP, NEAR * moved), step)
        x_a, g_a, x_b = x0, g0, x0 + first_step
        g_b = excess(x_b)
        for _ in range(EXPANSIONS // 2):
            same = (np.sign(g_b) == np.sign(g_a)) & np.isfinite(g_b)
            if not same.any():
                break
            x_a, g_a = np.where(same, x_b, x_a), np.where(same, g_b, g_a)
            x_b = np.where(same, x_b + step, x_b)
            g_b = np.where(same, excess(x_b), g_b)
        found = (np.sign(g_b) != np.sign(g_a)) & np.isfinite(g_a) & np.isfinite(g_b)
        lo, hi = np.minimum(x_a, x_b), np.maximum(x_a, x_b)
        g_lo, g_hi = np.where(x_a < x_b, g_a, g_b), np.where(x_a < x_b, g_b, g_a)
        x = np.where(found, 0.5 * (lo + hi), x0)
        if found.any():
            x[found] = bracketed_root(excess_of, lo[found], hi[found], g_lo[found], g_hi[found],
                                      xtol=1e-15, args=(np.flatnonzero(found),))
        new = np.exp(x)
        # the model's error grows with the square of the distance from where it was built
        # (about 1e-3 d^2 relative on the laws tried): a move below 1e-6 leaves 1e-15
        done = found & ((np.abs(new - T) <= CONVERGED * T) | (g0 == 0.0))
        # a crossing where the RMS barely moves with T (it approaches its limit from
        # above as T grows, or touches it at its minimum) is no T_min: durations far
        # shorter are within the checks' tolerance; those are left to the search on the
        # worst slack, which finds the shortest of them
        rows = np.flatnonzero(done)
        if len(rows):
            slope = (excess_of(x[rows] + FLAT_STEP, rows)
                     - excess_of(x[rows] - FLAT_STEP, rows)) / (2.0 * FLAT_STEP)
            flat = ~(np.abs(slope) >= TOLERANCE / FLAT_BAND)
            done[rows[flat]] = False
            found[rows[flat]] = False
        out[index[done]] = new[done]
        rows = np.flatnonzero(done)
        if len(rows):
            out_rms[index[rows]] = model.rms(new[rows], rows if model_rows is None
                                             else model_rows[rows])
        keep = found & ~done
        moved = np.maximum(np.abs(x[keep] - x0[keep]), 1e-13 * np.maximum(1.0, np.abs(x0[keep])))
        index, T = index[keep], new[keep]
        if len(index) == 0:
            break
    return out, out_rms


def beyond_flat_part(calculator: CycleCalculator, limits: Limits, T: np.ndarray,
                     C_v: np.ndarray | float | None = None) -> np.ndarray:
    """Where a duration T from eq. (6.2) may not be the shortest: the motor's region goes
    on past its flat part and the move reaches the end of it (or T is infinite), so a
    shorter, faster move might still fit the falling part."""
    motors = calculator.motors
    c_v = calculator.law.coefficients.C_v if C_v is None else C_v
    with np.errstate(divide="ignore", invalid="ignore"):
        at_flat_end = (c_v * calculator.drive.ratio * calculator.h
                       / (motors.flat_speed * (1.0 - limits.speed_margin)))
    return (motors.flat_speed < motors.speed_limit) & ~(at_flat_end * (1.0 + 1e-9) < T)


def _largest_tried(calculator: CycleModel) -> np.ndarray:
    return calculator.initial_guess() * 2.0**EXPANSIONS


LEAST_SQUARE = 12.0
"""The least int_0^1 q_N''^2 of a rest-to-rest law (the cubic's, q_N'' = 6 - 12 tau: the
Euler-Lagrange equation of the integral makes q_N'' linear), so C_a_rms^2 >= 12."""

EDGE = 1e-3
"""Where a denominator of the closed forms with constant torques, tau_p' - c or tau_c'^2 -
mean c^2, is at most EDGE times its first term the crossing is ill-conditioned (a check
that barely moves with T, a relative error of about 1e-16/EDGE in T): the closed form
leaves those candidates to the search (module docs)."""


@dataclass(frozen=True)
class ConstantTorques:
    """The constant parts of the motor torque with :func:`has_constant_torques` (module
    docs), per candidate: ``up`` = max_i c_i and ``down`` = max_i (-c_i) over the moves,
    ``mean_square`` = mean_i c_i^2, ``hold`` the torque held in the dwells (0 without a
    dwell)."""

    up: np.ndarray
    down: np.ndarray
    mean_square: np.ndarray
    hold: np.ndarray

    @property
    def none(self) -> np.ndarray:
        """Where there is no constant torque at all: eq. (6.2) as the book has it."""
        return (self.mean_square == 0.0) & (self.hold == 0.0)


def constant_torques(calculator: CycleCalculator) -> ConstantTorques | None:
    """The c_i of the task's moves, from the drive's own reflection of the load
    (Drive.linear_chain for each move's direction: friction against the motion, the
    external load with its sign) and the torque the dwells hold (Drive.holding_torques);
    None where nothing constant is there to reflect (the book's case)."""
    drive, n = calculator.drive, len(calculator.motors)
    if drive.figures.none("friction", "torque") \
            and all(bool(np.all(s.preload_torque == 0.0)) for s in drive.stages):
        return None
    c = np.stack([np.broadcast_to(np.asarray(drive.linear_chain(d)[2], dtype=float), (n,))
                  for d in calculator.directions])
    hold = np.broadcast_to(np.asarray(drive.holding_torques()[0], dtype=float), (n,)) \
        if calculator.task.dwell > 0.0 else np.zeros(n)
    return ConstantTorques(c.max(axis=0), (-c).max(axis=0),
                           np.square(c).sum(axis=0) / len(c), hold)


@dataclass(frozen=True)
class DurationBounds:
    """Per-candidate scales of the bounds of eq. (6.2), margins applied, SI.

    For a law with coefficients C_v, C_a, C_a_rms, C_j the bounds on T are C_v*speed,
    sqrt(C_a*torque), the RMS bound of scale C_a_rms*rms with the dwell, and
    cbrt(C_j*jerk). The load's own limits merge into the motor's: a load speed limit
    into ``speed`` (both multiply C_v), a load acceleration limit into ``torque``. 0 means
    no such limit; inf that no duration meets it.

    With constant torques (module docs) ``torque`` is S_A = J_t K h / (tau_p' - max|c|)
    (a symmetric law: max q_N'' = -min q_N'' = C_a), ``rise`` and ``fall`` its parts for
    the accelerating and the braking stretches (J_t K h / (tau_p' - up), J_t K h /
    (tau_p' - down)), which a law with max q_N'' = a and min q_N'' = -b bounds by
    T^2 >= max(a rise, b fall, C_a acceleration), ``acceleration`` the load's limit's
    scale h / a_max (0: none); ``rms`` is S_R' and ``dwell`` t_d' (per candidate where
    a constant is not 0). ``undecided``: where the closed forms do not decide (module
    docs): searched.
    """

    speed: np.ndarray
    torque: np.ndarray
    rms: np.ndarray
    jerk: np.ndarray
    dwell: float | np.ndarray
    rise: np.ndarray
    fall: np.ndarray
    acceleration: np.ndarray
    undecided: np.ndarray
    constant: bool
    """Some candidate has a constant torque (else eq. 6.2 as the book has it)."""


def duration_bounds(calculator: CycleCalculator, limits: Limits) -> DurationBounds:
    """The scales of eq. (6.2) for the candidates of a calculator (its law unused), with
    :func:`has_constant_torques` (module docs)."""
    drive, motors, task = calculator.drive, calculator.motors, calculator.task
    k, h, n = drive.ratio, calculator.h, len(motors)
    J_t = motors.inertia + drive.transmission_inertia + drive.reflected_load_inertia
    speed = motors.flat_speed * (1.0 - limits.speed_margin)
    tau_p = motors.intermittent.torques[:, 0] * (1.0 - limits.torque_margin)
    tau_c = motors.continuous.torques[:, 0] * (1.0 - limits.torque_margin)
    const = constant_torques(calculator)
    with np.errstate(divide="ignore", invalid="ignore"):
        s_v = k * h / speed
        s_r = J_t * k * h / tau_c
        if const is None:  # eq. (6.2) as the book has it
            rise = fall = k * h * J_t / tau_p
        else:  # tau_p - 0 = tau_p where c = 0: the same numbers
            rise = k * h * J_t / (tau_p - const.up)
            fall = k * h * J_t / (tau_p - const.down)
    undecided = np.zeros(n, dtype=bool)
    dwell: float | np.ndarray = task.dwell
    constant = const is not None and not bool(const.none.all())
    if constant:
        assert const is not None
        plain = const.none
        # the checks pass at value <= (1 - margin + TOLERANCE) limit: a constant above
        # that (with a hair for rounding) fails them at every duration
        relax = (1.0 - limits.torque_margin + TOLERANCE) * (1.0 + 1e-9)
        top_p = motors.intermittent.torques[:, 0] * relax
        top_c = motors.continuous.torques[:, 0] * relax
        held = const.hold > motors.intermittent.limit(np.zeros(n)) * relax
        sides, stopped = [], held.copy()  # stopped: no duration passes the peaks
        for side, c in ((rise, const.up), (fall, const.down)):
            blocked = (c > top_p) | held
            undecided |= (c != 0.0) & ~blocked & ~(tau_p - c > EDGE * tau_p)
            sides.append(np.where(blocked, np.inf, side))
            stopped |= blocked
        rise, fall = sides
        room = tau_c * tau_c - const.mean_square  # A of the module docs
        with np.errstate(divide="ignore", invalid="ignore"):
            s_r = np.where(plain, s_r, J_t * k * h / np.sqrt(room))
            dwell = np.where(plain, task.dwell,
                             task.dwell * (tau_c * tau_c - const.hold**2) / room)
        least = const.mean_square if task.dwell == 0.0 else \
            np.minimum(const.mean_square, const.hold**2)
        blocked = ~plain & (least > top_c * top_c)
        # a window needs max_T T^3 (A T + B) = (27/256) B^4 / |A|^3 >= X (A < 0 < B, the
        # limit relaxed), X at least (J_t K h)^2 12 for any law (module docs)
        wide = top_c * top_c - const.mean_square
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            reach = 27.0 / 256.0 * (task.dwell * (top_c * top_c - const.hold**2)) ** 4 \
                / np.abs(wide) ** 3
        blocked |= ~plain & (wide < 0.0) & (reach < LEAST_SQUARE * (J_t * k * h) ** 2
                                             * (1.0 - 1e-9))
        undecided |= ~plain & ~blocked & ~(room > EDGE * tau_c * tau_c)
        s_r = np.where(blocked, np.inf, s_r)
        undecided &= ~(blocked | stopped)  # no duration at all: decided
        dwell = np.where(blocked | undecided, 0.0, dwell)
    s_a = np.maximum(rise, fall) if constant else rise
    s_acc = np.zeros(n)
    if limits.max_speed is not None:
        s_v = np.maximum(s_v, h / limits.max_speed)
    if limits.max_acceleration is not None:
        s_acc = np.full(n, h / limits.max_acceleration)
        s_a = np.maximum(s_a, h / limits.max_acceleration)
    s_j = np.full(n, h / limits.max_jerk if limits.max_jerk is not None else 0.0)
    return DurationBounds(s_v, s_a, s_r, s_j, dwell, rise, fall, s_acc, undecided, constant)


def closed_form_duration(calculator: CycleCalculator, limits: Limits,
                         bounds: DurationBounds | None = None) -> np.ndarray:
    """Eq. (6.2) per candidate, with the dwell in the RMS, the user's load limits and
    the constant torques (module docs); nan where it does not decide
    (DurationBounds.undecided). ``bounds``: :func:`duration_bounds` where known.

    The bounds are those of the checks that depend on T (speed, peak, RMS, load speed,
    acceleration and jerk); a check no duration changes (the inertia ratio) is left to
    the verdict at the bound. With a constant torque the peak bound reads the law's
    largest and smallest q_N'' (its linear peaks, as the evaluation does).
    """
    c = calculator.law.coefficients
    s = duration_bounds(calculator, limits) if bounds is None else bounds
    rms = rms_duration(c.C_a_rms * s.rms, s.dwell)
    if limits.max_jerk is None:
        jerk = np.zeros_like(s.jerk)
    else:  # inf where the law's (each row's law's) acceleration jumps
        with np.errstate(invalid="ignore"):
            jerk = np.where(c.jerk_bounded, np.cbrt(c.C_j * s.jerk), np.inf)
    if s.constant:
        most, least = _acceleration_extremes(calculator.law)  # max q_N'', -min q_N''
        torque = np.sqrt(np.maximum(np.maximum(most * s.rise, least * s.fall),
                                    c.C_a * s.acceleration))
    else:
        torque = np.sqrt(c.C_a * s.torque)
    T = np.max(np.stack([c.C_v * s.speed, torque, rms, jerk]), axis=0)
    return np.where(s.undecided, np.nan, T)


def _acceleration_extremes(law: MotionLaw | RowLaws) -> tuple[Any, Any]:
    """max q_N'' and -min q_N'' of the law, from its linear peaks (as the evaluation reads
    them), or from its pieces where its acceleration is linear on each (the same values:
    MotionLaw.linear_acceleration); of each row's law for RowLaws (arrays over the
    rows)."""
    linear = acceleration_range(law)
    if linear is not None:
        lowest, highest = linear
        return highest, -lowest
    laws = law.laws if isinstance(law, RowLaws) else (law,)
    found = np.array([one.linear_peaks.maximum(np.array([1.0, -1.0]), np.zeros(2)).value
                      for one in laws])
    if isinstance(law, RowLaws):
        return found[law.index, 0], found[law.index, 1]
    return float(found[0, 0]), float(found[0, 1])


def rms_duration(scale: np.ndarray, dwell: float | np.ndarray) -> np.ndarray:
    """Smallest T with T^3 (T + dwell) >= scale^2 per candidate (scale = J_t k h C_a_rms /
    tau_c), vectorized; ``dwell`` one number or one per candidate (t_d' of the module
    docs, negative where the hold exceeds the rating: then T > -dwell).

    Solved on logarithms, so that no power leaves the float range (scale up to 1e308):
    in x = log T the excess f = 3x + log(e^x + dwell) - 2 log(scale) rises (slope
    3 + e^x/(e^x + dwell), between 3 and 4) and is convex (f'' = dwell e^x/(e^x +
    dwell)^2 > 0), so Newton's method started where f >= 0 (the smaller of the dwell-free
    bound sqrt(scale) and the dwell-dominated one cbrt(scale^2/dwell)) falls monotonically
    to the root, quadratically: five or six steps from within a factor of two. It stops
    where a step no longer lowers x (rounding), a few ulps above the root at most. A
    negative dwell -D is solved in y = log(T - D): g = y + 3 log(e^y + D) - 2 log(scale)
    rises (slope between 1 and 4) and is convex the same way, from y with e^y >=
    max(D, 2^(1/4) sqrt(scale)) (there T^3 (T - D) >= (T - D)^4 >= scale^2).
    """
    scale = np.asarray(scale, dtype=float)
    if np.ndim(dwell) > 0:
        return _rms_durations(scale, np.asarray(dwell, dtype=float))
    dwell = float(dwell)
    if dwell < 0.0:
        return _rms_durations(scale, np.full(scale.shape, dwell))
    out = np.where(np.isfinite(scale), 0.0, np.inf)
    if dwell == 0.0:
        with np.errstate(invalid="ignore"):
            return np.where(np.isfinite(scale), np.sqrt(scale), np.inf)
    solve = np.isfinite(scale) & (scale > 0.0)
    if not solve.any():
        return out
    log_scale = np.log(scale[solve])
    log_target = 2.0 * log_scale
    x = np.minimum(0.5 * log_scale, (log_target - math.log(dwell)) / 3.0) + 1e-9
    for _ in range(MAX_NEWTON):
        e = np.exp(x)
        new = x - (3.0 * x + np.log(e + dwell) - log_target) / (3.0 + e / (e + dwell))
        lower = new < x
        if not lower.any():
            break
        x = np.where(lower, new, x)
    out[solve] = np.exp(x)
    return out


def _rms_durations(scale: np.ndarray, dwell: np.ndarray) -> np.ndarray:
    """:func:`rms_duration` with a dwell per element (broadcast with ``scale``)."""
    shape = np.broadcast_shapes(np.shape(scale), np.shape(dwell))
    scale, dwell = (np.broadcast_to(x, shape).reshape(-1) for x in (scale, dwell))
    out = np.where(np.isfinite(scale), np.maximum(-dwell, 0.0), np.inf)  # scale 0: T >= -dwell
    solve = np.isfinite(scale) & (scale > 0.0) & np.isfinite(dwell)
    with np.errstate(invalid="ignore"):
        out[solve & (dwell == 0.0)] = np.sqrt(scale[solve & (dwell == 0.0)])
    for positive in (True, False):
        pick = solve & ((dwell > 0.0) if positive else (dwell < 0.0))
        if not pick.any():
            continue
        d = dwell[pick]
        log_target = 2.0 * np.log(scale[pick])
        if positive:  # x = log T (rms_duration)
            x = np.minimum(0.25 * log_target, (log_target - np.log(d)) / 3.0) + 1e-9
        else:  # y = log(T - D), D = -d
            x = np.maximum(np.log(-d), 0.25 * math.log(2.0) + 0.25 * log_target) + 1e-9
        for _ in range(MAX_NEWTON):
            e = np.exp(x)
            if positive:
                new = x - (3.0 * x + np.log(e + d) - log_target) / (3.0 + e / (e + d))
            else:
                new = x - (x + 3.0 * np.log(e - d) - log_target) / (1.0 + 3.0 * e / (e - d))
            lower = new < x
            if not lower.any():
                break
            x = np.where(lower, new, x)
        out[pick] = np.exp(x) if positive else np.exp(x) - d
    return out.reshape(shape)


MAX_NEWTON = 60
"""Newton steps of :func:`rms_duration` at most (it takes five or six)."""


def bisect_duration(calculator: CycleModel, limits: Limits,
                    guess: np.ndarray | None = None,
                    active: np.ndarray | None = None, peaks: bool = True) -> np.ndarray:
    """T_min per candidate by search on the worst slack; inf where no duration is feasible.

    First a bracket (:func:`_bracket`): a feasible log T and an infeasible one below it,
    then the crossing between them (:func:`_crossing`). ``guess`` is where the search
    starts (default: the speed and inertial bounds), ``active`` which candidates to solve
    (the others get inf); without ``peaks`` the peak checks are left out (they are
    known to pass).
    """
    x0 = np.log(calculator.initial_guess() if guess is None else np.asarray(guess, float))
    active = np.ones(len(x0), dtype=bool) if active is None else np.asarray(active, bool)
    if not active.all():  # the search works on the active candidates only
        out = np.full(len(x0), np.inf)
        index = np.flatnonzero(active)
        if len(index):
            out[index] = bisect_duration(calculator.take(index), limits,
                                         guess=np.exp(x0[index]), peaks=peaks)
        return out

    slack = _Slack(calculator, limits, peaks)
    found, x_bad, x_ok, f_bad, f_ok = _bracket(slack, x0, active)
    x = _crossing(slack, x_bad, x_ok, f_bad, f_ok, found & np.isfinite(x_bad))
    return np.where(found, np.exp(x), np.inf)


@dataclass(frozen=True)
class _Slack:
    """The worst slack at log durations x, for all candidates or those at ``index`` (each
    step of a search evaluates only the candidates still searching)."""

    calculator: CycleModel
    limits: Limits
    peaks: bool

    def checks(self, x: np.ndarray, index: np.ndarray | None = None) -> list[CheckArrays]:
        calculator = self.calculator if index is None else self.calculator.take(index)
        return evaluate(calculator, self.limits, np.exp(x), self.peaks)[1]

    def __call__(self, x: np.ndarray, index: np.ndarray | None = None) -> np.ndarray:
        if index is not None and len(index) == 0:
            return np.empty(0)
        return worst_slack(self.checks(x, index))


def _unfixable(*samples: list[CheckArrays]) -> np.ndarray:
    """A check that fails with the same value and limit at every duration sampled (the
    inertia ratio, a holding torque, a jerk impulse): no duration fixes it."""
    first = samples[0]
    out = np.zeros(len(first[0].value), dtype=bool)
    for i, check in enumerate(first):
        same = ~check.passed
        for other in samples[1:]:
            same &= ~other[i].passed & (other[i].value == check.value) & \
                (other[i].limit == check.limit)
        out |= same
    return out


def _bracket(slack: _Slack, x0: np.ndarray, active: np.ndarray):
    """Per candidate a feasible x_ok = log T and an infeasible x_bad < x_ok.

    The worst slack f is a minimum of checks that each fall or rise with T, or rise and
    then fall (an RMS with friction over a cycle with dwell): the feasible durations form
    an interval. From x0 the walk goes up the slack by factors of 2 until f >= -TOLERANCE;
    where f stops rising before, its maximum lies in the last three points and a
    search for it (Brent's method) looks there. From a feasible x0 the walk goes down to an
    infeasible point. Returns (found, x_bad, x_ok, f_bad, f_ok); x_bad is nan where every
    point down to 2^-EXPANSIONS x0 was feasible.
    """
    n = len(x0)
    nan = np.full(n, np.nan)
    first = slack.checks(x0)
    f0 = worst_slack(first)
    x1 = x0 + STEP
    second = slack.checks(x1)
    f1 = worst_slack(second)
    ok0, ok1 = f0 >= -TOLERANCE, f1 >= -TOLERANCE
    stuck = _unfixable(first, second, slack.checks(x0 + EXPANSIONS / 2 * STEP))
    found = active & (ok0 | ok1)
    x_ok, f_ok = np.where(ok0, x0, np.where(ok1, x1, nan)), np.where(ok0, f0, f1)
    x_bad, f_bad = np.where(ok0, nan, x0), np.where(ok0, nan, f0)
    # climb: per candidate a direction d, the previous point and the current one
    climbing = active & ~found & ~stuck
    up = f1 > f0
    d = np.where(up, STEP, -STEP)
    x_prev, f_prev = np.where(up, x0, x1), np.where(up, f0, f1)
    x_cur, f_cur = np.where(up, x1, x0), np.where(up, f1, f0)
    descending = active & ok0  # from a feasible point down to an infeasible one
    peaked = np.zeros(n, dtype=bool)  # the slack stopped rising: its peak searched
    x_lo, x_hi = nan.copy(), nan.copy()
    for _ in range(EXPANSIONS):
        if not (climbing.any() or descending.any()):
            break
        x_next = np.where(descending, x_ok - STEP, x_cur + d)
        moving = np.flatnonzero(climbing | descending)
        f_next = np.full(n, np.nan)  # read only where climbing or descending
        f_next[moving] = slack(x_next[moving], moving)
        good = f_next >= -TOLERANCE
        # descending: a feasible point moves x_ok down, an infeasible one ends the walk
        down_ok = descending & good
        down_end = descending & ~good
        x_ok, f_ok = np.where(down_ok, x_next, x_ok), np.where(down_ok, f_next, f_ok)
        x_bad, f_bad = np.where(down_end, x_next, x_bad), np.where(down_end, f_next, f_bad)
        descending = down_ok
        # climbing: feasible ends the climb (going down: then descend from it)
        hit = climbing & good
        x_ok, f_ok = np.where(hit, x_next, x_ok), np.where(hit, f_next, f_ok)
        hit_up = hit & (d > 0)
        x_bad, f_bad = np.where(hit_up, x_cur, x_bad), np.where(hit_up, f_cur, f_bad)
        found |= hit
        descending |= hit & (d < 0)
        top = climbing & ~good & (f_next <= f_cur)
        peaked |= top
        x_lo = np.where(top, np.minimum(x_prev, x_next), x_lo)
        x_hi = np.where(top, np.maximum(x_prev, x_next), x_hi)
        rising = climbing & ~good & ~top
        x_prev, f_prev = np.where(rising, x_cur, x_prev), np.where(rising, f_cur, f_prev)
        x_cur, f_cur = np.where(rising, x_next, x_cur), np.where(rising, f_next, f_cur)
        climbing = rising
    if peaked.any():
        hit, x_top, f_top, x_below, f_below = _peak_search(slack, x_lo, x_hi, peaked)
        found |= hit
        x_ok, f_ok = np.where(hit, x_top, x_ok), np.where(hit, f_top, f_ok)
        x_bad, f_bad = np.where(hit, x_below, x_bad), np.where(hit, f_below, f_bad)
    return found, x_bad, x_ok, f_bad, f_ok


def _peak_search(slack: _Slack, lo: np.ndarray, hi: np.ndarray, active: np.ndarray):
    """A feasible point where the slack peaks in [lo, hi], by Brent's method for a maximum
    (sizer.numerics.golden.BrentMax: parabolic steps where the slack is smooth there,
    golden-section ones elsewhere), from the bracket's two golden points.

    Stops for a candidate at its first feasible point; every point evaluated before it
    was infeasible, so the nearest of them below it brackets the crossing. Also stops
    where the best point is known to about PEAK_WIDTH: the slack's maximum is then known
    to about PEAK_WIDTH^2 times its curvature, far below the tolerance (golden section
    alone took 33 steps from a bracket of 1.4 to that width; a smooth peak takes about
    ten). Returns (hit, x_ok, f_ok, x_bad, f_bad).
    """
    n = len(lo)
    hit = np.zeros(n, dtype=bool)
    x_ok, f_ok = np.full(n, np.nan), np.full(n, np.nan)
    x_bad, f_bad = lo.copy(), np.full(n, np.nan)
    index = np.flatnonzero(active)
    lo, hi = lo[index], hi[index]
    f_lo = slack(lo, index)
    f_bad[index] = f_lo
    x1, x2 = interior_points(lo, hi)
    f1, f2 = slack(x1, index), slack(x2, index)
    # the first two points in order: x1 (the point below it: lo), then x2 (below: x1)
    open_ = np.ones(len(index), dtype=bool)
    for x, f, below, f_below in ((x1, f1, lo, f_lo), (x2, f2, x1, f1)):
        new = open_ & (f >= -TOLERANCE)
        where = index[new]
        hit[where] = True
        x_ok[where], f_ok[where] = x[new], f[new]
        x_bad[where], f_bad[where] = below[new], f_below[new]
        open_ &= ~new
    best = f1 >= f2
    search = BrentMax(lo, hi, f_lo, np.where(best, x1, x2), np.where(best, f1, f2),
                      np.where(best, x2, x1), np.where(best, f2, f1), 0.25 * PEAK_WIDTH)
    for _ in range(PEAK_STEPS):
        open_ &= ~search.settled
        index, search = index[open_], search.take(open_)
        if len(index) == 0:
            break
        # the points read so far below each new point: all infeasible (else it stopped)
        known = np.stack((search.a, search.x, search.w, search.v))
        values = np.stack((search.fa, search.fx, search.fw, search.fv))
        u = search.point()
        fu = slack(u, index)
        new = fu >= -TOLERANCE
        if new.any():
            rows = np.flatnonzero(new)
            under = np.where(known[:, rows] < u[rows], known[:, rows], -np.inf)
            k = np.argmax(under, axis=0)
            where = index[rows]
            hit[where] = True
            x_ok[where], f_ok[where] = u[rows], fu[rows]
            x_bad[where] = known[k, rows]
            f_bad[where] = values[k, rows]
        search.update(u, fu)
        open_ = ~new
    return hit, x_ok, f_ok, x_bad, f_bad


def _crossing(slack: _Slack, x_lo, x_hi, f_lo, f_hi, active) -> np.ndarray:
    """log T where the worst slack reaches 0 between an infeasible x_lo and a feasible x_hi.

    The project's root finder (sizer.numerics.roots) on g = f (or on f + TOLERANCE where
    x_hi reaches only the tolerance), to a relative width of 1e-13, each step on the
    candidates still open; the feasible end of the bracket is returned, so the answer is
    feasible.
    """
    out = np.array(x_hi, dtype=float)
    index = np.flatnonzero(active)
    if len(index) == 0:
        return out
    offset = np.where(f_hi[index] >= 0.0, 0.0, TOLERANCE)
    _, hi = bracketed_root(lambda x, where, shift: slack(x, where) + shift, x_lo[index],
                           x_hi[index], f_lo[index] + offset, f_hi[index] + offset,
                           xtol=1e-13, args=(index, offset), bracket=True)
    out[index] = hi
    return out


CHUNK = 1 << 14
"""Candidates bounded at once (the peak queries of each are a few dozen numbers)."""


def relaxed(limits: Limits) -> Limits:
    """The limits as the checks apply them at the edge of their tolerance."""
    def wider(limit: float | None) -> float | None:
        return None if limit is None else limit * (1.0 + TOLERANCE)

    return dataclasses.replace(
        limits, torque_margin=limits.torque_margin - TOLERANCE,
        speed_margin=limits.speed_margin - TOLERANCE, max_speed=wider(limits.max_speed),
        max_acceleration=wider(limits.max_acceleration), max_jerk=wider(limits.max_jerk))


@dataclass(frozen=True)
class PeakScales:
    """What the floor's peak part takes from the candidates, for every law at once.

    Each peak query F(u) <= D of sizer.sizing.move has its lower bracket 1/u =
    max(sqrt(C_a P / D), C_v Q / D) where D > 0 and P, Q >= 0 (0 where P or Q < 0, no
    duration where D <= 0): the law enters by C_a and C_v only, so a candidate's largest
    bracket is max(sqrt(C_a) root, C_v ratio) with ``root`` its largest sqrt(P / D) and
    ``ratio`` its largest Q / D, and ``blocked`` where some D <= 0."""

    root: np.ndarray
    ratio: np.ndarray
    blocked: np.ndarray


def peak_scales(design: Design, candidates: Candidates) -> PeakScales:
    """The :class:`PeakScales` of the candidates, limits relaxed (module docs)."""
    limits, n = relaxed(design.limits), len(candidates)
    root, ratio, blocked = np.zeros(n), np.zeros(n), np.zeros(n, dtype=bool)
    for start in range(0, n, CHUNK):
        rows = np.arange(start, min(start + CHUNK, n))
        part = candidates if n <= CHUNK else candidates.take(rows)
        calculator = CycleCalculator(None, single_task(design), part.drive, part.motors,
                                     design.limits.thermal_speed)
        queries = peak_queries(calculator, limits)
        if queries is None:
            continue
        who, P, Q, D = queries
        usable = (D > 0.0) & (P >= 0.0) & (Q >= 0.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            np.maximum.at(root, rows[who[usable]], np.sqrt(P[usable] / D[usable]))
            np.maximum.at(ratio, rows[who[usable]], Q[usable] / D[usable])
        blocked[rows[who[D <= 0.0]]] = True
    return PeakScales(root, ratio, blocked)


def duration_floor(design: Design, spec: LawChoice | str, candidates: Candidates,
                   scales: PeakScales | None = None) -> np.ndarray | None:
    """Per candidate a duration below which the law ``spec`` is infeasible, in minimize
    mode for the task shorthand (a move, its dwell and return) with a fixed law; None
    where there is no such floor (a given duration, a linkage, a law shaped per
    candidate, a law that moves backwards) or no need of one (the closed form of eq. 6.2
    sizes every option at the cost of one evaluation). ``scales``: the candidates'
    :func:`peak_scales` where known (the same for every law). A cycle of segments has
    its own floor: :func:`_cycle_floor`."""
    choice = law_choice(spec)
    if not design.machine_cycle.minimize or design.transmission.linkage is not None \
            or not choice.is_fixed:
        return None
    law, limits = choice.law, relaxed(design.limits)
    task = shorthand_task(design.machine_cycle)
    if task is None:
        return _cycle_floor(design, law, candidates, limits)
    calculator = CycleCalculator(None, task, candidates.drive, candidates.motors,
                                 design.limits.thermal_speed, law=law)
    if is_purely_inertial(calculator):  # eq. (6.2): every option is cheap as it is
        return None
    if law.moves_backwards():
        return None  # it moves backwards: no peak bound (sizer.sizing.move)
    if calculator.h == 0.0:
        return np.zeros(len(candidates))
    scales = peak_scales(design, candidates) if scales is None else scales
    c = law.coefficients
    peak = np.where(scales.blocked, np.inf,
                    np.maximum(math.sqrt(c.C_a) * scales.root, c.C_v * scales.ratio))
    return np.maximum(speed_bounds(calculator, limits), peak)


def _cycle_floor(design: Design, law, candidates: Candidates,
                 limits: Limits) -> np.ndarray | None:
    """The floor of a cycle of segments in minimize mode: its time at the lower bound on
    the scale of its free durations from the free moves' peak checks (SegmentCycle.
    peak_bound, the limits relaxed), below which no scale passes them; the cycle time
    grows with the scale. None where a law moves backwards (no bound)."""
    from sizer.sizing.cycle import SegmentCycle  # only designs with a cycle need it

    cycle = design.machine_cycle
    n = len(candidates)
    out = np.zeros(n)
    for start in range(0, n, CHUNK):
        rows = np.arange(start, min(start + CHUNK, n))
        part = candidates if n <= CHUNK else candidates.take(rows)
        calculator = SegmentCycle(cycle, law, part.drive, part.motors,
                                  design.limits.thermal_speed)
        bound = calculator.peak_bound(limits)
        if bound is None:
            return None
        out[rows] = calculator.cycle_time(bound)
    return out
