"""Minimum duration T_min of one law for each candidate motor (book eq. 6.2).

With the book's rectangular regions and a purely inertial load (no damping, friction or
constant load, efficiency 1) T_min is the closed form of eq. (6.2), extended to a cycle
with dwell: the RMS bound T^3 (T + t_dwell) >= (J_t k h C_a_rms / tau_c)^2 is solved
exactly. Otherwise T_min is found by bisection on the feasibility of every check,
vectorized over candidates, to a relative width of 1e-12.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import optimize

from sizer.model.domain import Limits
from sizer.sizing.checks import CheckArrays, evaluate_checks, worst_slack
from sizer.sizing.cycle import CycleCalculator, CycleMetrics

EXPANSIONS = 80
BISECTIONS = 200


@dataclass(frozen=True)
class DurationSolution:
    """T_min per candidate (nan where no duration is feasible) and the state there."""

    duration: np.ndarray
    feasible: np.ndarray
    metrics: CycleMetrics
    checks: list[CheckArrays]
    method: str


def evaluate(calculator: CycleCalculator, limits: Limits, T: np.ndarray):
    metrics = calculator.evaluate(T)
    checks = evaluate_checks(metrics, calculator.motors, calculator.drive, limits,
                             calculator.task.linear)
    return metrics, checks


def is_purely_inertial(calculator: CycleCalculator) -> bool:
    """The case of eq. (6.2): rectangles, inertial load, ideal transmission."""
    load, drive, motors = calculator.drive.load, calculator.drive, calculator.motors
    stages_plain = all(s.preload_torque == 0.0 and s.max_input_speed is None
                       and s.rated_output_torque is None and s.peak_output_torque is None
                       for s in drive.stages)
    return (load.damping == 0.0 and load.friction == 0.0 and load.torque == 0.0
            and drive.is_ideal and stages_plain and bool(np.all(motors.damping == 0.0))
            and bool(np.all(motors.is_rectangular)))


def minimum_duration(calculator: CycleCalculator, limits: Limits) -> DurationSolution:
    """Shortest feasible duration of the calculator's law for each candidate."""
    if is_purely_inertial(calculator):
        T = closed_form_duration(calculator, limits)
        method = "closed form (eq. 6.2)"
    else:
        T = bisect_duration(calculator, limits)
        method = "bisection"
    finite = np.isfinite(T)
    probe = np.where(finite, T, _largest_tried(calculator))
    metrics, checks = evaluate(calculator, limits, probe)
    # a closed form can land a rounding error (1e-16) short of its bound: step onto
    # the feasible side by a few ulps so that every check of T_min passes
    for _ in range(8):
        short = finite & (worst_slack(checks) < 0.0) & (worst_slack(checks) > -1e-9)
        if not short.any():
            break
        probe = np.where(short, probe * (1.0 + 4.0 * np.finfo(float).eps), probe)
        metrics, checks = evaluate(calculator, limits, probe)
    feasible = finite & (worst_slack(checks) >= 0.0)
    return DurationSolution(np.where(feasible, probe, np.nan), feasible, metrics, checks, method)


def _largest_tried(calculator: CycleCalculator) -> np.ndarray:
    return _initial_guess(calculator) * 2.0**EXPANSIONS


def closed_form_duration(calculator: CycleCalculator, limits: Limits) -> np.ndarray:
    """Eq. (6.2) per candidate, with the dwell in the RMS; inf where nothing is feasible."""
    c = calculator.law.coefficients
    drive, motors, task = calculator.drive, calculator.motors, calculator.task
    k, h = drive.ratio, calculator.h
    J_t = motors.inertia + drive.transmission_inertia + drive.reflected_load_inertia
    speed = motors.speed_limit * (1.0 - limits.speed_margin)
    tau_p = motors.intermittent.torques[:, 0] * (1.0 - limits.torque_margin)
    tau_c = motors.continuous.torques[:, 0] * (1.0 - limits.torque_margin)
    with np.errstate(divide="ignore"):
        bounds = [c.C_v * k * h / speed, np.sqrt(c.C_a * k * h * J_t / tau_p)]
        rms_scale = J_t * k * h * c.C_a_rms / tau_c
    bounds.append(np.array([_rms_duration(s, task.dwell) for s in rms_scale]))
    if limits.max_acceleration is not None:
        bounds.append(np.full(len(motors), math.sqrt(c.C_a * h / limits.max_acceleration)))
    if limits.max_jerk is not None:
        jerk_bound = (c.C_j * h / limits.max_jerk) ** (1 / 3) if c.jerk_bounded else math.inf
        bounds.append(np.full(len(motors), jerk_bound))
    T = np.max(np.stack(bounds), axis=0)
    if limits.inertia_ratio is not None:
        with np.errstate(divide="ignore"):
            too_light = drive.reflected_load_inertia / motors.inertia > limits.inertia_ratio
        T = np.where(too_light, np.inf, T)
    return T


def _rms_duration(scale: float, dwell: float) -> float:
    """Smallest T with T^3 (T + dwell) >= scale^2 (scale = J_t k h C_a_rms / tau_c)."""
    if not math.isfinite(scale):
        return math.inf
    if scale == 0.0:
        return 0.0
    if dwell == 0.0:
        return math.sqrt(scale)
    target = scale * scale
    hi = math.sqrt(scale)  # T^4 = target is the dwell-free bound, always above the root

    def excess(T: float) -> float:
        return T**3 * (T + dwell) - target

    return optimize.brentq(excess, 0.0, hi, xtol=1e-300, rtol=4 * np.finfo(float).eps)


def _initial_guess(calculator: CycleCalculator) -> np.ndarray:
    """A duration scale from the speed and inertial bounds (never zero)."""
    c = calculator.law.coefficients
    drive, motors = calculator.drive, calculator.motors
    k, h = drive.ratio, calculator.h
    J_t = motors.inertia + drive.transmission_inertia + drive.reflected_load_inertia
    tau_p = np.maximum(motors.intermittent.torques.max(axis=1), 1e-300)
    guess = np.maximum(c.C_v * k * h / motors.speed_limit, np.sqrt(c.C_a * k * h * J_t / tau_p))
    return np.where(np.isfinite(guess) & (guess > 0.0), guess, 1.0)


def bisect_duration(calculator: CycleCalculator, limits: Limits) -> np.ndarray:
    """T_min by bracketing, then the Illinois method on the worst slack; inf if none works.

    The worst slack (smallest margin beyond the required one, over all checks) is
    continuous in T and >= 0 exactly where the candidate is feasible. The bracket
    [lo, hi] keeps lo infeasible and hi feasible, so the answer is always feasible; it
    stops when the bracket is narrower than 1e-13 (relative) or hi has slack < 1e-14.
    """

    def slack(T: np.ndarray) -> np.ndarray:
        _, checks = evaluate(calculator, limits, T)
        return worst_slack(checks)

    hi = _initial_guess(calculator)
    f_hi = slack(hi)
    for _ in range(EXPANSIONS):
        if (f_hi >= 0.0).all():
            break
        hi = np.where(f_hi >= 0.0, hi, 2.0 * hi)
        f_hi = slack(hi)
    ok = f_hi >= 0.0
    lo = hi / 2.0
    f_lo = slack(lo)
    for _ in range(EXPANSIONS):
        low_ok = ok & (f_lo >= 0.0)
        if not low_ok.any():
            break
        hi, f_hi = np.where(low_ok, lo, hi), np.where(low_ok, f_lo, f_hi)
        lo = np.where(low_ok, lo / 2.0, lo)
        f_lo = np.where(low_ok, slack(lo), f_lo)
    x_lo, x_hi = np.log(lo), np.log(hi)
    side = np.zeros(len(hi))  # which end moved last: -1 lo, +1 hi (Illinois weighting)
    for step in range(BISECTIONS):
        open_ = ok & (x_hi - x_lo > 1e-13) & (f_hi > 1e-14)
        if not open_.any():
            break
        finite = np.isfinite(f_lo) & np.isfinite(f_hi) & (f_hi > f_lo)
        with np.errstate(invalid="ignore", divide="ignore"):
            secant = x_hi - f_hi * (x_hi - x_lo) / (f_hi - f_lo)
        inside = finite & (secant > x_lo) & (secant < x_hi) & (step % 4 != 3)
        x = np.where(inside, secant, 0.5 * (x_lo + x_hi))
        f = slack(np.exp(x))
        good = f >= 0.0
        move_hi, move_lo = open_ & good, open_ & ~good
        f_lo = np.where(move_hi & (side == 1), 0.5 * f_lo, f_lo)
        f_hi = np.where(move_lo & (side == -1), 0.5 * f_hi, f_hi)
        x_hi, f_hi = np.where(move_hi, x, x_hi), np.where(move_hi, f, f_hi)
        x_lo, f_lo = np.where(move_lo, x, x_lo), np.where(move_lo, f, f_lo)
        side = np.where(move_hi, 1, np.where(move_lo, -1, side))
    return np.where(ok, np.exp(x_hi), np.inf)
