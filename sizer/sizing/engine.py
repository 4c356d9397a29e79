"""Input -> calculator -> result: size a design for every motor x law (book ch. 6).

``size_design`` evaluates every candidate pair: with a given duration, the requirements
and margins of each; with ``minimize``, T_min of each. ``check_design`` verifies the one
motor and law a design names. Laws with ``auto`` shape parameters have them chosen per
motor (sizer.sizing.shape).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np

from sizer.envelope import envelope_note
from sizer.errors import UserError
from sizer.laws import AUTO, MotionLaw, make_law, resolve
from sizer.mechanics import Drive
from sizer.model.domain import Design, Motor, Transmission
from sizer.sizing.checks import CheckArrays, evaluate_checks, limiting_index
from sizer.sizing.checks import feasible as all_pass
from sizer.sizing.cycle import CycleCalculator, CycleMetrics
from sizer.sizing.duration import minimum_duration
from sizer.sizing.motors import MotorArrays
from sizer.sizing.ranking import rank
from sizer.sizing.results import CandidateResult, Check, SizingResult
from sizer.sizing.shape import choose_shape

Progress = Callable[[int, int], None]
"""Called as ``progress(done, total)``: laws sized so far, of all the laws."""


def size_design(design: Design, rank_by: str | None = None,
                motors: Sequence[Motor] | None = None,
                progress: Progress | None = None) -> SizingResult:
    """Every motor x law of the design, ranked (feasible first).

    ``progress``, if given, is called with (0, n) and then after each of the n laws.
    """
    motors = tuple(motors if motors is not None else design.motors)
    if not motors:
        raise UserError("no motors to size: give a catalog in the design or with --catalog",
                        field="motors")
    if not design.laws:
        raise UserError("no motion laws to consider", field="laws")
    arrays = MotorArrays.of(motors, design.limits.envelope)
    results: list[CandidateResult] = []
    if progress is not None:
        progress(0, len(design.laws))
    for done, spec in enumerate(design.laws, start=1):
        results.extend(evaluate_candidates(design, spec, arrays))
        if progress is not None:
            progress(done, len(design.laws))
    mode = "minimize" if design.task.minimize else "duration"
    return SizingResult(mode, tuple(rank(results, rank_by, mode)), design.name,
                        notes=assumptions(design))


def evaluate_candidates(design: Design, spec: str,
                        motors: MotorArrays) -> list[CandidateResult]:
    """Results of one law spec for all motors, the free ratio chosen if there is one."""
    if design.ratio_choice is None:
        return evaluate_law(design, spec, motors)
    from sizer.sizing.ratio import choose_ratio

    return choose_ratio(design, spec, motors, evaluate_law)


def evaluate_law(design: Design, spec: str, motors: MotorArrays) -> list[CandidateResult]:
    """Results of one law spec (fixed or with auto parameters) for all motors."""
    family, values = resolve(spec)
    drive = Drive(design.load, design.transmission)
    if any(v == AUTO for v in values.values()):
        laws = choose_shape(family, values, design, drive, motors)
    else:
        law = make_law(spec)
        laws = [law] * len(motors)
    results: list[CandidateResult | None] = [None] * len(motors)
    for law in dict.fromkeys(laws):
        index = np.array([i for i, chosen in enumerate(laws) if chosen == law])
        subset = motors.subset(index)
        for i, result in zip(index, evaluate_fixed_law(design, law, drive, subset), strict=True):
            results[i] = result
    return [r for r in results if r is not None]


def evaluate_fixed_law(design: Design, law: MotionLaw, drive: Drive,
                       motors: MotorArrays) -> list[CandidateResult]:
    calculator = CycleCalculator(None, design.task, drive, motors,
                                 design.limits.thermal_speed, law=law)
    if design.task.minimize:
        solution = minimum_duration(calculator, design.limits)
        metrics, checks, feasible = solution.metrics, solution.checks, solution.feasible
        duration = solution.duration
    else:
        T = np.full(len(motors), design.task.duration)
        metrics = calculator.evaluate(T)
        checks = evaluate_checks(metrics, motors, drive, design.limits, design.task.linear)
        feasible = all_pass(checks)
        duration = T
    return to_results(law, motors, metrics, checks, feasible, duration,
                      minimize=design.task.minimize, transmission=drive.transmission)


def to_results(law: MotionLaw, motors: MotorArrays, metrics: CycleMetrics,
               checks: list[CheckArrays], feasible: np.ndarray, duration: np.ndarray,
               minimize: bool, transmission: Transmission) -> list[CandidateResult]:
    binding = limiting_index(checks)
    out = []
    for i, motor in enumerate(motors.motors):
        rows = tuple(
            Check(c.name, float(c.value[i]), float(c.limit[i]), c.unit, float(c.margin[i]),
                  c.required)
            for c in checks
        )
        ok = bool(feasible[i])
        limiting = rows[int(binding[i])]
        if ok:
            reason = ""
        elif minimize:
            reason = f"no duration is feasible: {limiting.describe()}"
        else:
            failed = [r.describe() for r in rows if not r.passed]
            reason = "; ".join(failed)
        known = ok or not minimize
        out.append(CandidateResult(
            motor=motor.id,
            law=law.law_id,
            spec=law.spec,
            params=dict(law.params),
            feasible=ok,
            duration=float(duration[i]) if ok or not minimize else None,
            peak_torque=float(metrics.peak_torque[i]) if known else None,
            rms_torque=float(metrics.rms_torque[i]) if known else None,
            max_speed=float(metrics.max_speed[i]) if known else None,
            checks=rows,
            limiting=limiting.name,
            reason=reason,
            price=motor.price,
            mass=motor.mass,
            ratio=transmission.ratio,
            transmission=transmission,
            load_speed=float(metrics.load_speed[i]) if known else None,
            load_torque=float(metrics.load_torque[i]) if known else None,
            rated_power=motor.continuous_torque * motor.rated_speed,
            continuous_torque=motor.continuous_torque,
            rotor_inertia=motor.inertia,
        ))
    return out


def check_design(design: Design) -> CandidateResult:
    """The result of the motor and law the design names (for ``sizer check``)."""
    if not design.chosen_motor or not design.chosen_law:
        raise UserError("the design names no motor and law to check "
                        "(add `check: {motor: ID, law: SPEC}`)", field="check")
    motor = next((m for m in design.motors if m.id == design.chosen_motor), None)
    if motor is None:
        known = ", ".join(m.id for m in design.motors) or "none"
        raise UserError(f"unknown motor {design.chosen_motor!r}; loaded motors: {known}",
                        field="check.motor")
    results = evaluate_candidates(design, design.chosen_law,
                                  MotorArrays.of([motor], design.limits.envelope))
    return results[0]


def assumptions(design: Design) -> tuple[str, ...]:
    """What the computation assumed, for reports."""
    notes = []
    if any(m.continuous_curve is None or m.intermittent_curve is None for m in design.motors):
        notes.append(envelope_note(design.limits.envelope))
    if design.load.torque and design.task.dwell:
        notes.append("holding the constant load at rest counts as driving (torque / efficiency)")
    if not math.isclose(design.transmission.efficiency, 1.0):
        if design.transmission.efficiency_applies_to == "steady_load":
            notes.append("efficiency applied to the load's steady torque only (friction, "
                         "constant load); inertial torque without loss (Yaskawa's convention)")
        else:
            notes.append("efficiency applied in the direction of power flow")
    if design.limits.inertia_ratio is not None:
        if design.limits.inertia_ratio_of == "load":
            notes.append("inertia ratio: the load alone reflected to the motor, over the "
                         "rotor inertia")
        else:
            notes.append("inertia ratio: everything the motor drives (load, screws, gears, "
                         "couplings) reflected to the motor, over the rotor inertia")
    return tuple(notes)
