"""Input -> calculator -> result: size a design for every motor x law (book ch. 6).

``size_design`` evaluates every candidate (motor x transmission option, one flat axis:
sizer.sizing.candidates) for each law: with a given duration, the requirements and
margins of each; with ``minimize``, T_min of each. Results stay arrays
(sizer.sizing.table); rows are built for what a report reads. ``check_design`` verifies
the one motor and law a design names. Laws with ``auto`` shape parameters have them
chosen per candidate (sizer.sizing.auto_shape).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Sequence

import numpy as np

from sizer.envelope import envelope_note
from sizer.errors import UserError
from sizer.laws import AUTO, MotionLaw, make_law, resolve
from sizer.laws.open_shaped import is_open_shaped
from sizer.model.cycle import Dwell
from sizer.model.domain import Design, Motor
from sizer.sizing.auto_shape import choose_shape
from sizer.sizing.candidates import Candidates
from sizer.sizing.checks import TOLERANCE, evaluate_checks
from sizer.sizing.checks import feasible as all_pass
from sizer.sizing.cycle import CycleCalculator
from sizer.sizing.cycle_shape import given_scale, left_out_laws, plain_design, ranked_laws
from sizer.sizing.energy_check import (
    HEAT_CHECK,
    EnergyChecks,
    energy_checks,
    energy_notes,
    has_braking_check,
    has_heat_check,
    without_power_figures,
)
from sizer.sizing.grid import law_grid
from sizer.sizing.law_processes import worker_count
from sizer.sizing.minimum_duration import is_purely_inertial, merge_metrics, minimum_duration
from sizer.sizing.motors import MotorArrays
from sizer.sizing.ranking import rank_order
from sizer.sizing.results import CandidateResult, SizingResult
from sizer.sizing.shared_by_laws import SharedByLaws
from sizer.sizing.table import FIGURES, RESIDUAL, CandidateTable, Mode, Rows, concatenate

Progress = Callable[[int, int], None]
"""Called as ``progress(done, total)``: laws sized so far, of all the laws."""


def mode_of(design: Design) -> Mode:
    minimize = design.cycle.minimize if design.cycle is not None else design.task.minimize
    return Mode.MINIMIZE if minimize else Mode.DURATION


def size_design(design: Design, rank_by: str | None = None,
                motors: Sequence[Motor] | None = None,
                progress: Progress | None = None, workers: int | None = 1) -> SizingResult:
    """Every motor x law (x transmission option) of the design, ranked (feasible first).

    ``progress``, if given, is called with (0, n) and then after each of the n laws.
    ``workers``: processes sizing the laws (sizer.sizing.law_processes; None: every CPU
    for a large design); the result is the same whatever their number.
    """
    design = plain_design(design)
    motors = tuple(motors if motors is not None else design.motors)
    if not motors:
        raise UserError("no motors to size: give a catalog in the design or with --catalog",
                        field="motors")
    specs = ranked_laws(design)
    arrays = MotorArrays.of(motors, design.limits.envelope, design.drives)
    if progress is not None:
        progress(0, len(specs))
    count = worker_count(workers, len(arrays) * _options(design), len(specs))
    if count > 1:
        from sizer.sizing.law_processes import tables_in_processes

        tables = tables_in_processes(design, specs, arrays, count, None if progress is None
                                     else lambda done: progress(done, len(specs)))
    else:
        tables = []
        first = None  # the options one law chose: the others try them first
        shared = SharedByLaws(design, arrays)
        for done, spec in enumerate(specs, start=1):
            tables.append(evaluate_spec(design, spec, arrays, first, shared))
            if design.ratio_choice is not None:
                from sizer.sizing.ratio_choice import listed_choice

                first = listed_choice(design, tables[-1])
            if progress is not None:
                progress(done, len(specs))
    table = concatenate(tables)
    order = rank_order(table, rank_by)
    return SizingResult(table.mode, Rows(table, order), design.name,
                        notes=assumptions(design), table=table)


def _options(design: Design) -> int:
    """Transmission options per motor: the listed ratios and gearboxes of a free stage (a
    continuous range counts as one), else one."""
    choice = design.ratio_choice
    if choice is None:
        return 1
    return max(1, len(choice.ratios) + len(choice.gearboxes))


def evaluate_spec(design: Design, spec: str, motors: MotorArrays,
                  first: np.ndarray | None = None,
                  shared: SharedByLaws | None = None) -> CandidateTable:
    """One law spec for all motors (one row per motor), the free ratio chosen if any
    (``first``: per motor the listed option to try first, sizer.sizing.ratio_choice;
    ``shared``: what the laws of the sizing share, built once for them all)."""
    if design.ratio_choice is None:
        candidates = Candidates.single(motors, design.load, design.transmission)
        return evaluate_law(design, spec, candidates)
    from sizer.sizing.duration_floor import duration_floor
    from sizer.sizing.ratio_choice import choose_ratio
    from sizer.sizing.rms_fails_up_to import rms_fails_up_to

    common = SharedByLaws(design, motors) if shared is None else shared

    def without_peaks(candidates: Candidates) -> CandidateTable:
        return evaluate_fixed_law(design, make_law(spec), candidates, peaks=False)

    def floor(candidates: Candidates) -> np.ndarray | None:
        scales = common.scales if candidates is common.pairs.candidates else None
        return duration_floor(design, spec, candidates, scales)

    return choose_ratio(design, motors, lambda c: evaluate_law(design, spec, c),
                        floor=floor,
                        fails_up_to=lambda c, T, g: rms_fails_up_to(design, spec, c, T, g),
                        without_peaks=without_peaks if _plain_given_duration(design, spec)
                        else None, first=first, pairs=common.pairs)


def _plain_given_duration(design: Design, spec: str) -> bool:
    """A given duration, the task shorthand, a fixed law: every check but the peaks is
    known from an evaluation without them, and leaving them out only passes them (the
    ratio search evaluates the peaks of the options that can still win: sizer.sizing.
    ratio_choice)."""
    if design.task.minimize or design.cycle is not None or \
            design.transmission.linkage is not None or is_open_shaped(spec):
        return False
    return not any(v == AUTO for v in resolve(spec)[1].values())


def evaluate_law(design: Design, spec: str, candidates: Candidates) -> CandidateTable:
    """One law spec (fixed or with auto parameters) for all candidates, in their order."""
    if is_open_shaped(spec):  # shaped for the load's mode at each candidate's duration
        from sizer.sizing.shaped_sizing import evaluate_shaped

        return evaluate_shaped(design, spec, candidates)
    family, values = resolve(spec)
    if any(v == AUTO for v in values.values()):
        if design.cycle is not None:
            raise UserError(f"{spec}: `auto` shape parameters are chosen for the task "
                            "shorthand only, not yet for a cycle of segments; give the "
                            "shape", field="laws")
        with without_power_figures():  # verdicts only; the chosen laws get them below
            laws = choose_shape(family, values, design, candidates)
    else:
        return evaluate_fixed_law(design, make_law(spec), candidates)
    distinct = list(dict.fromkeys(laws))
    which = {law: k for k, law in enumerate(distinct)}
    group = np.array([which[law] for law in laws])
    parts, positions = [], []
    for k, law in enumerate(distinct):
        index = np.flatnonzero(group == k)
        parts.append(evaluate_fixed_law(design, law, candidates.take(index)))
        positions.append(index)
    joined = concatenate(parts)
    inverse = np.empty(len(candidates), dtype=np.intp)
    inverse[np.concatenate(positions)] = np.arange(len(candidates))
    return joined.take(inverse)


CHUNK_SAMPLES = 2**21
"""Candidates x law samples evaluated at once (each array of that size is 16 MiB): larger
candidate sets are evaluated in chunks, so memory stays bounded whatever the catalog."""
MIN_CHUNK = 64
"""The smallest chunk (the per-evaluation overhead stays small against the work) while
its samples stay within MAX_CHUNK_SAMPLES."""
MAX_CHUNK_SAMPLES = 8 * CHUNK_SAMPLES
"""Candidates x samples never exceeded by a chunk: a cycle of many moves (each candidate
already holds millions of samples) is evaluated a few candidates, or one, at a time."""


def candidates_per_chunk(samples: int) -> int:
    """How many candidates of ``samples`` samples each one evaluation takes: CHUNK_SAMPLES
    worth, at least MIN_CHUNK, at most MAX_CHUNK_SAMPLES worth, at least one."""
    samples = max(samples, 1)
    return max(1, min(max(MIN_CHUNK, CHUNK_SAMPLES // samples), MAX_CHUNK_SAMPLES // samples))


def chunk_size(law: MotionLaw, moves: int = 1) -> int:
    """How many candidates one evaluation of ``law`` takes (its grid's samples each, for
    each of ``moves`` moves evaluated together)."""
    grid = law_grid(law)
    return candidates_per_chunk((grid.nodes.size + 2 * grid.size) * max(moves, 1))


def evaluate_fixed_law(design: Design, law: MotionLaw, candidates: Candidates,
                       peaks: bool = True) -> CandidateTable:
    """The requirements, checks and verdicts of one law for every candidate, in chunks
    of :func:`chunk_size` candidates. Without ``peaks`` (a given duration only) the peak
    torques and ratios are left at zero: their checks pass."""
    if design.transmission.linkage is not None:
        moves = len(design.cycle.moves) if design.cycle is not None else 1
        size = candidates_per_chunk(LINKAGE_SAMPLES * moves)
    elif design.cycle is not None:
        size = chunk_size(law, len(design.cycle.moves))
    else:
        calculator = CycleCalculator(None, design.task, candidates.drive, candidates.motors,
                                     design.limits.thermal_speed, law=law)
        if is_purely_inertial(calculator):  # closed forms: memory per candidate, no grid
            return _evaluate_chunk(design, law, candidates, peaks)
        size = chunk_size(law)
    if len(candidates) <= size:
        return _evaluate_chunk(design, law, candidates, peaks)
    starts = range(0, len(candidates), size)
    return concatenate([_evaluate_chunk(design, law, candidates.take(
        np.arange(start, min(start + size, len(candidates)))), peaks) for start in starts])


def _evaluate_chunk(design: Design, law: MotionLaw, candidates: Candidates,
                    peaks: bool = True) -> CandidateTable:
    if design.transmission.linkage is not None:
        return _evaluate_linkage_chunk(design, law, candidates)
    if design.cycle is not None:
        return _evaluate_cycle_chunk(design, law, candidates)
    motors, drive = candidates.motors, candidates.drive
    calculator = CycleCalculator(None, design.task, drive, motors,
                                 design.limits.thermal_speed, law=law)
    if design.task.minimize:
        solution = minimum_duration(calculator, design.limits)
        metrics, checks, feasible = solution.metrics, solution.checks, solution.feasible
        duration = solution.duration
    else:
        T = np.full(len(motors), design.task.duration)
        metrics = calculator.evaluate(T, peaks)
        checks = evaluate_checks(metrics, motors, drive, design.limits, design.task.linear)
        feasible = all_pass(checks)
        duration = T
    vibration = _vibration(design, law, calculator, duration, metrics, checks, feasible,
                           design.task.minimize, design.task.linear)
    residual = None
    if vibration is not None:
        duration, metrics, checks, feasible, residual = vibration
    duration, metrics, checks, feasible, figures = _with_energy(
        design, calculator, duration, metrics, checks, feasible, design.task.minimize,
        residual is not None, design.task.linear)
    return _table(design, law, candidates, duration, metrics, checks, feasible, residual,
                  figures)


def _with_energy(design: Design, calculator, duration: np.ndarray, metrics, checks, feasible,
                 minimize: bool, vibrating: bool, linear: bool):
    """The braking and heat checks added (sizer.sizing.energy_check), and in minimize mode
    the candidates that fail only those moved to the first duration that passes them
    (not with a load mode: ``vibrating``). ``duration`` is the move's T, or a cycle's scale
    s. Returns (duration, metrics, checks, feasible, figures); unchanged, without figures,
    for a design with neither check."""
    energy = energy_checks(design, calculator, duration, metrics, feasible, minimize)
    if energy is not None and minimize and not vibrating:
        moved = _energy_moved(design, calculator, duration, feasible, energy)
        if moved is not None:
            rows, T = moved
            metrics = merge_metrics(metrics, rows, calculator.take(rows).evaluate(T))
            checks = _replaced(checks, evaluate_checks(metrics, calculator.motors,
                                                       calculator.drive, design.limits,
                                                       linear))
            # only the moved rows change: their verdicts and durations from the new checks
            feasible = np.array(feasible, dtype=bool)
            feasible[rows] = all_pass(checks)[rows]
            duration = np.array(duration, dtype=float)
            duration[rows] = np.where(feasible[rows], T, np.nan)
            energy = energy_checks(design, calculator, duration, metrics, feasible, True)
    if energy is None:
        return duration, metrics, checks, feasible, None
    verdict = energy.feasible
    if design.limits.thermal_duty == "once":  # a one-off run: the winding model decides
        checks, verdict = _once(checks, energy)
    return energy.duration, metrics, [*checks, *energy.checks], verdict, energy.figures


def _once(checks, energy: EnergyChecks):
    """A one-off run (``thermal_duty: once``): where the winding model checks the motor,
    the RMS check is no criterion (it does not apply there); the verdicts again."""
    heat = next((c for c in energy.checks if c.name == HEAT_CHECK), None)
    if heat is None:
        return checks, energy.feasible
    modelled = np.ones(len(heat.value), dtype=bool) if heat.applies is None else heat.applies
    out = [dataclasses.replace(c, applies=~modelled if c.applies is None
                               else c.applies & ~modelled) if c.name == "rms" else c
           for c in checks]
    return out, all_pass([*out, *energy.checks])


def _replaced(checks, new) -> list:
    """``checks`` with those ``new`` evaluates again in their place (by name; the others,
    such as a linkage's dead_point, kept)."""
    by_name = {c.name: c for c in new}
    out = [by_name.pop(c.name, c) for c in checks]
    return [*out, *by_name.values()]


def _energy_moved(design: Design, calculator, duration: np.ndarray, feasible: np.ndarray,
                  energy: EnergyChecks) -> tuple[np.ndarray, np.ndarray] | None:
    """Minimize mode: the candidates that pass every check but the energy and heat ones
    at T_min, and the first durations at which those pass too
    (sizer.sizing.energy_duration); where none does, the candidate stays at T_min (its
    energy check fails there and names the limit). None when no candidate moves."""
    late = np.asarray(feasible, dtype=bool) & ~energy.feasible & np.isfinite(duration)
    if not late.any():
        return None
    from sizer.sizing.energy_duration import energy_duration

    rows = np.flatnonzero(late)
    slack = np.min([check.slack[rows] for check in energy.checks], axis=0) + TOLERANCE
    moved = energy_duration(design, calculator.take(rows), duration[rows], slack)
    found = np.isfinite(moved)
    if not found.any():
        return None
    return rows[found], moved[found]


def _vibration(design: Design, law: MotionLaw, calculator, scale: np.ndarray, metrics,
               checks, feasible, minimize: bool, linear: bool):
    """The residual vibration of the moves (sizer.sizing.vibration_check), or None when
    the design gives no mode of the load: with a limit, in minimize mode each scale moved
    up to the first one that meets it (the other checks then evaluated there), and the
    check added; the scale, metrics, checks, verdicts and the residual per candidate."""
    from sizer.sizing.vibration_check import admissible_scale, cycle_vibration, residual_check

    vibration = cycle_vibration(design, law)
    if vibration is None:
        return None
    limit = design.limits.residual_vibration
    known = np.isfinite(scale) & (np.asarray(feasible, dtype=bool) | (not minimize))
    if minimize and limit is not None and known.any():
        moved = np.where(known, admissible_scale(vibration, np.where(known, scale, np.nan),
                                                 limit), scale)
        late = known & (moved > scale)
        if late.any():
            metrics = calculator.evaluate(np.where(np.isfinite(moved), moved, scale))
            checks = evaluate_checks(metrics, calculator.motors, calculator.drive,
                                     design.limits, linear)
            feasible = np.asarray(feasible, dtype=bool) & np.isfinite(moved) & all_pass(checks)
            # where no duration within the search meets the limit, the check at T_min
            # fails and names the limit (the pair is infeasible)
            scale = np.where(np.isfinite(moved), moved, scale)
    residual = np.where(known, vibration.worst(np.where(known, scale, 1.0)), np.nan)
    if limit is not None:
        check = residual_check(vibration, np.where(known, scale, 1.0), limit, linear)
        check = type(check)(check.name, np.where(known, check.value, 0.0), check.limit,
                            check.unit, check.required)
        checks = [*checks, check]
        feasible = np.asarray(feasible, dtype=bool) & check.passed
    if minimize:
        scale = np.where(feasible, scale, np.nan)
    return scale, metrics, checks, feasible, residual


def _evaluate_cycle_chunk(design: Design, law: MotionLaw,
                          candidates: Candidates) -> CandidateTable:
    """A cycle of segments (sizer.sizing.segment_cycle): minimize is the smallest scale
    of the free durations (time scaling, book sec. 5.2), searched per candidate; the
    duration reported is the cycle time."""
    from sizer.sizing.segment_cycle import SegmentCycle  # only designs with a cycle need it

    cycle = design.cycle
    assert cycle is not None
    motors = candidates.motors
    calculator = SegmentCycle(cycle, law, candidates.drive, motors,
                              design.limits.thermal_speed)
    if cycle.minimize:
        solution = minimum_duration(calculator, design.limits)
        metrics, checks, feasible = solution.metrics, solution.checks, solution.feasible
    else:
        metrics = calculator.evaluate(np.full(len(motors), given_scale(cycle)))
        checks = evaluate_checks(metrics, motors, calculator.drive, design.limits, cycle.linear)
        feasible = all_pass(checks)
    scale = solution.duration if cycle.minimize else np.full(len(motors), given_scale(cycle))
    vibration = _vibration(design, law, calculator, scale, metrics, checks, feasible,
                           cycle.minimize, cycle.linear)
    residual = None
    if vibration is not None:
        scale, metrics, checks, feasible, residual = vibration
    _, metrics, checks, feasible, figures = _with_energy(
        design, calculator, scale, metrics, checks, feasible, cycle.minimize,
        residual is not None, cycle.linear)
    duration = np.where(feasible, metrics.duration, np.nan) if cycle.minimize \
        else metrics.duration
    return _table(design, law, candidates, duration, metrics, checks, feasible, residual,
                  figures)


LINKAGE_SAMPLES = 8192
"""Samples of a move through a linkage per candidate (sizer.sizing.linkage_sizing)."""


def _evaluate_linkage_chunk(design: Design, law: MotionLaw,
                            candidates: Candidates) -> CandidateTable:
    """Through a linkage at the load (sizer.sizing.linkage_sizing): the profile of the
    law computed once, the candidates at its samples; minimize by time scaling."""
    from sizer.sizing.linkage_sizing import evaluate_linkage  # only linkage designs

    if design.cycle is not None:
        from sizer.sizing.linkage_cycle import evaluate_linkage_cycle

        evaluate = evaluate_linkage_cycle
    else:
        evaluate = evaluate_linkage
    duration, metrics, checks, feasible = evaluate(design, law, candidates.motors,
                                                   candidates.drive)
    if not (has_heat_check(candidates.motors.catalog)
            or has_braking_check(design, candidates.motors.drives)):
        return _table(design, law, candidates, duration, metrics, checks, feasible)
    from sizer.sizing.linkage_samples import linkage_calculator, scale_of_durations

    calculator = linkage_calculator(design, law, candidates.motors, candidates.drive)
    cycle = design.cycle is not None or design.task.return_move
    scale = scale_of_durations(calculator, metrics.duration if cycle else duration)
    scale = np.where(np.isfinite(duration), scale, np.nan)
    minimize = design.cycle.minimize if design.cycle is not None else design.task.minimize
    moved, metrics, checks, feasible, figures = _with_energy(
        design, calculator, scale, metrics, checks, feasible, minimize, False,
        design.cycle.linear if design.cycle is not None else design.task.linear)
    if cycle:  # the cycle time, or for a task with a return each move's T
        duration = metrics.duration if design.cycle is not None else \
            (metrics.duration - 2.0 * design.task.dwell) / 2.0
        duration = np.where(feasible, duration, np.nan) if minimize else duration
    else:
        duration = moved
    return _table(design, law, candidates, duration, metrics, checks, feasible,
                  extra=figures)


def _table(design: Design, law: MotionLaw, candidates: Candidates, duration: np.ndarray,
           metrics, checks, feasible, residual: np.ndarray | None = None,
           extra: dict[str, np.ndarray] | None = None) -> CandidateTable:
    motors, drive = candidates.motors, candidates.drive
    n = len(motors)
    figures = {"duration": duration, "peak_torque": metrics.peak_torque,
               "rms_torque": metrics.rms_torque, "max_speed": metrics.max_speed,
               "load_speed": metrics.load_speed, "load_torque": metrics.load_torque}
    assert set(figures) == set(FIGURES)
    if residual is not None:
        figures[RESIDUAL] = residual
    figures.update(extra or {})  # energy and heat (sizer.sizing.energy_check)
    return CandidateTable(
        mode_of(design), (law,), np.zeros(n, dtype=np.intp), motors.catalog, motors.index,
        drive.transmissions, candidates.gearbox_names, candidates.option,
        np.asarray(feasible, dtype=bool),
        {k: np.broadcast_to(np.asarray(v, dtype=float), (n,)).copy()
         for k, v in figures.items()},
        tuple(checks), drives=motors.drives, drive=motors.drive)


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
    table = evaluate_spec(plain_design(design), design.chosen_law,
                          MotorArrays.of([motor], design.limits.envelope, design.drives))
    return table.row(0)


def cycle_notes(design: Design) -> list[str]:
    """What sizing a cycle of segments assumed, for reports."""
    cycle = design.cycle
    assert cycle is not None
    notes = [f"a cycle of {len(cycle.segments)} segments; durations are cycle times"]
    if cycle.minimize_segment is not None:
        notes.append(f"minimize: segment {cycle.minimize_segment!r}, the others fixed")
    elif cycle.minimize:
        notes.append("minimize: every free duration scaled by one factor (time scaling, book "
                     f"sec. 5.2), shared by the rule {cycle.share.value!r}")
    elif cycle.cycle_time is not None:
        notes.append(f"free durations fill the cycle time, shared by the rule "
                     f"{cycle.share.value!r}")
    left = left_out_laws(design)
    if left:
        notes.append("left out, no form with boundary speeds: " + ", ".join(left))
    return notes


def assumptions(design: Design) -> tuple[str, ...]:
    """What the computation assumed, for reports."""
    notes = []
    if any(m.continuous_curve is None or m.intermittent_curve is None for m in design.motors):
        notes.append(envelope_note(design.limits.envelope))
    cycle = plain_design(design).cycle
    if cycle is not None:
        notes.extend(cycle_notes(design))
        holds = any(isinstance(s, Dwell) and (design.load.torque + s.load.torque) != 0.0
                    for s in cycle.segments)
    else:
        holds = bool(design.load.torque and design.task.dwell)
    if holds:
        notes.append("holding the constant load at rest counts as driving (torque / efficiency)")
    if not math.isclose(design.transmission.efficiency, 1.0):
        if design.transmission.efficiency_applies_to == "steady_load":
            notes.append("efficiency applied to the load's steady torque only (friction, "
                         "constant load); inertial torque without loss (Yaskawa's convention)")
        else:
            notes.append("efficiency applied in the direction of power flow")
    notes.extend(energy_notes(plain_design(design)))
    if design.limits.inertia_ratio is not None:
        if design.limits.inertia_ratio_of == "load":
            notes.append("inertia ratio: the load alone reflected to the motor, over the "
                         "rotor inertia")
        else:
            notes.append("inertia ratio: everything the motor drives (load, screws, gears, "
                         "couplings) reflected to the motor, over the rotor inertia")
    return tuple(notes)
