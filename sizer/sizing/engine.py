"""Input -> calculator -> result: size a design for every motor x law (book ch. 6).

``size_design`` evaluates every candidate (motor x transmission option, one flat axis:
sizer.sizing.candidates) for each law: with a given duration, the requirements and
margins of each; with ``minimize``, T_min of each. Results stay arrays
(sizer.sizing.results); rows are built for what a report reads. ``check_design`` verifies
the one motor and law a design names. Laws with ``auto`` shape parameters have them
chosen per candidate (sizer.sizing.choices).

Which process sizes which law: each law sizes every candidate on its own
(:func:`evaluate_spec`), so the laws of a large design are tasks, one law per task,
handed to ``workers`` processes as they come free (:func:`tables_in_processes`); the
tables come back in the laws' order and the result is the one a single process gives, bit
for bit. The one thing a law takes from another is the option its ratio search tries
first (the choice of the last law finished, sizer.sizing.choices.listed_choice),
which changes the search's cost, never its answer. The workers are started clean
(``forkserver``, or ``spawn`` where there is none), so no lock held by another thread of
the caller is inherited; like every such pool they import the caller's main module
again, which must keep its work under ``if __name__ == "__main__":``. That is why the
library sizes in one process unless asked (``workers``), and the ``sizer`` command, whose
entry points are guarded, asks.

Is a candidate infeasible at every duration up to a given one, by its RMS check
(:func:`rms_fails_up_to`)? The ratio search asks it of a motor's other options at the
best T_min found: one evaluation without peaks, and for options that share the stretches
between power-flow reversals one evaluation per motor; for a cycle of segments one
evaluation of the cycle at the scale of that cycle time.
"""

from __future__ import annotations

import dataclasses
import math
import os
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING

import numpy as np

from sizer.envelope import envelope_note
from sizer.errors import UserError
from sizer.laws import LawChoice, MotionLaw, law_choice
from sizer.laws.per_move import LawsPerMove, PerMoveChoice, RankedLaw, per_move
from sizer.laws.row_laws import RowLaws
from sizer.model.cycle import Cycle, Dwell
from sizer.model.domain import Design, Motor
from sizer.numerics.arrays import sorted_unique
from sizer.sizing.candidates import Builds, Candidates, MotorArrays
from sizer.sizing.checks import TOLERANCE, CheckArrays, CheckName, shaft_notes
from sizer.sizing.checks import feasible as all_pass
from sizer.sizing.choices import (
    SharedByLaws,
    choose_ratio,
    choose_shape,
    evaluate_shaped,
    listed_choice,
    listed_pairs,
)
from sizer.sizing.cycle import (
    SegmentCycle,
    left_out_laws,
    ranked_laws,
    shorthand_task,
    single_task,
)
from sizer.sizing.energy_check import energy_limit, energy_notes, without_power_figures
from sizer.sizing.evaluation import CycleMetrics, CycleModel
from sizer.sizing.move import (
    CycleCalculator,
    MoveScales,
    RmsModel,
    candidates_per_chunk,
    grid_samples,
)
from sizer.sizing.ranking import rank_order
from sizer.sizing.results import (
    FIGURES,
    CandidateResult,
    CandidateTable,
    Mode,
    Rows,
    SizingResult,
    concatenate,
    in_groups,
)
from sizer.sizing.shortest_duration import (
    answer,
    duration_floor,
    is_purely_inertial,
    laws_model,
)
from sizer.sizing.stage_life import gearbox_life_limits, screw_limits
from sizer.sizing.vibration_check import ResidualRows, residual_limit

if TYPE_CHECKING:
    from concurrent.futures import Future


Progress = Callable[[int, int], None]
"""Called as ``progress(done, total)``: laws sized so far, of all the laws."""


def mode_of(design: Design) -> Mode:
    return Mode.MINIMIZE if design.machine_cycle.minimize else Mode.DURATION


def size_design(design: Design, rank_by: str | None = None,
                motors: Sequence[Motor] | None = None,
                progress: Progress | None = None, workers: int | None = 1,
                builds: Builds | None = None) -> SizingResult:
    """Every motor x law (x transmission option) of the design, ranked (feasible first).

    ``progress``, if given, is called with (0, n) and then after each of the n laws, or
    once with (n, n) where they are sized together (:func:`evaluate_law_axis`).
    ``workers``: processes sizing the laws (:func:`tables_in_processes`; None: every CPU
    for a large design); the result is the same whatever their number. ``builds``: per
    motor (typically a copy) its build of the machine, its load's figures and transmission
    (sizer.robust), for a design whose engine reads them (:func:`reads_builds`) and
    without a ratio choice where they change the transmission.
    """
    motors = tuple(motors if motors is not None else design.motors)
    if not motors:
        from sizer.sizing.planning import LoadLimits

        planned = LoadLimits.of(design.limits).given  # docs/planning.md
        raise UserError("no motors to size: give a catalog in the design or with --catalog"
                        + ("; with the load's limits and no motors the design is a plan, "
                           "which `sizer size` gives" if planned else ""), field="motors")
    if builds is not None and not reads_builds(design, bool(builds.modes)):
        raise ValueError("builds per motor are sized for a cycle without a linkage or "
                         "loads of the position (and builds of the mode without a law "
                         "or split made for the design's mode)")
    specs = ranked_laws(design)
    arrays = MotorArrays.of(motors, design.limits.envelope, design.drives, builds)
    if progress is not None:
        progress(0, len(specs))
    count = worker_count(workers, len(arrays) * _options(design), len(specs))
    if count > 1:

        tables = tables_in_processes(design, specs, arrays, count, None if progress is None
                                     else lambda done: progress(done, len(specs)))
    elif (axis := law_axis(design, specs, len(arrays))) is not None:
        tables = [evaluate_law_axis(design, axis, arrays)]
        if progress is not None:
            progress(len(specs), len(specs))
    else:
        tables = []
        first = None  # the options one law chose: the others try them first
        shared = SharedByLaws(design, arrays)
        for done, spec in enumerate(specs, start=1):
            tables.append(evaluate_spec(design, spec, arrays, first, shared))
            if design.ratio_choice is not None:
                first = listed_choice(design, tables[-1])
            if progress is not None:
                progress(done, len(specs))
    table = concatenate(tables)
    order = rank_order(table, rank_by)
    return SizingResult(table.mode, Rows(table, order), design.name,
                        notes=assumptions(design), table=table)


def reads_builds(design: Design, modes: bool = False) -> bool:
    """Whether the engine of ``design`` reads each candidate's build of the machine
    (sizer.sizing.candidates.Builds: the drive's load figures and transmissions): the law
    move and the cycle of segments; a linkage's engine and the one for loads of the
    position read the design's load. With ``modes``, builds of the load's mode too (the
    residual vibration's): not where a law is shaped for the mode at each duration or the
    split minimizes the residual (both made for the design's mode)."""
    if design.transmission.linkage is not None or design.load.position_dependent:
        return False
    return not modes or (not any(c.open_shaped for c in design.laws)
                         and design.machine_cycle.share.goal != "vibration")


def _options(design: Design) -> int:
    """Transmission options per motor: the listed ratios and gearboxes of a free stage (a
    continuous range counts as one), else one."""
    choice = design.ratio_choice
    if choice is None:
        return 1
    return max(1, len(choice.ratios) + len(choice.gearboxes))


def evaluate_spec(design: Design, spec: LawChoice | PerMoveChoice | str, motors: MotorArrays,
                  first: np.ndarray | None = None,
                  shared: SharedByLaws | None = None) -> CandidateTable:
    """One law choice for all motors (one row per motor), the free ratio chosen if any
    (``first``: per motor the listed option to try first, sizer.sizing.choices;
    ``shared``: what the laws of the sizing share, built once for them all)."""
    if isinstance(spec, PerMoveChoice):  # a law per move, chosen with the split
        choice = spec

        def sized(candidates: Candidates) -> CandidateTable:
            return evaluate_per_move(design, choice, candidates)

        if design.ratio_choice is None:
            return sized(Candidates.single(motors, design.load, design.transmission))
        return choose_ratio(design, motors, sized, first=first,
                            pairs=(SharedByLaws(design, motors) if shared is None
                                   else shared).pairs)
    spec = law_choice(spec)
    if design.ratio_choice is None:
        candidates = Candidates.single(motors, design.load, design.transmission)
        return evaluate_law(design, spec, candidates)
    common = SharedByLaws(design, motors) if shared is None else shared

    def without_peaks(candidates: Candidates) -> CandidateTable:
        return evaluate_fixed_law(design, spec.law, candidates, peaks=False)

    def floor(candidates: Candidates) -> np.ndarray | None:
        scales = common.scales if candidates is common.pairs.candidates \
            and shorthand_task(design.machine_cycle) else None
        return duration_floor(design, spec, candidates, scales)

    return choose_ratio(design, motors, lambda c: evaluate_law(design, spec, c),
                        floor=floor,
                        fails_up_to=lambda c, T, g: rms_fails_up_to(design, spec, c, T, g),
                        without_peaks=without_peaks if _plain_given_duration(design, spec)
                        else None, first=first, pairs=common.pairs)


AXIS_ROWS = 2**14
"""Most candidates (motors x transmission options x laws) sized as one law axis
(:func:`evaluate_law_axis`); a larger design sizes its laws one after another: each law's
overhead is then small against its work, and one law's arrays stay within the CPU's
caches (measured, book problem with 15 laws and 12 ratios: the axis 3x faster at 20
motors, even at about 150 motors, 15 % slower at 200)."""


def law_axis(design: Design, specs: Sequence[LawChoice | PerMoveChoice],
             motors: int) -> list[LawChoice] | None:
    """The design's laws where they are sized as one axis (:func:`evaluate_law_axis`):
    two or more fixed laws of the task shorthand or of a cycle of rest-to-rest moves
    (:func:`rows_cycle`; no linkage, no loads of the position), at most AXIS_ROWS
    candidates in all; else None (law by law)."""
    cycle = design.machine_cycle
    if len(specs) < 2 or (shorthand_task(cycle) is None and not rows_cycle(cycle)) \
            or design.transmission.linkage is not None or design.load.position_dependent:
        return None
    laws = [spec for spec in specs if isinstance(spec, LawChoice) and spec.is_fixed
            and not spec.open_shaped]
    if len(laws) < len(specs) or motors * _options(design) * len(laws) > AXIS_ROWS:
        return None
    return laws


def evaluate_law_axis(design: Design, specs: Sequence[LawChoice],
                      motors: MotorArrays) -> CandidateTable:
    """Every fixed law for all motors as one axis: the motors laid out once per law (law
    k's rows the k-th copy, MotorArrays.axis), each row sized with its own law as the rows
    of one model (:func:`evaluate_laws`), the free ratio chosen for every row at once
    (sizer.sizing.choices.choose_ratio: each row's choice its own, the floors and the RMS
    test law by law). The table's rows are law-major, as the laws' tables one after
    another, each row's numbers those of its law sized alone."""
    laws = [spec.law for spec in specs]
    n = len(motors)
    which = np.repeat(np.arange(len(laws)), n)
    rows = dataclasses.replace(motors.subset(np.tile(np.arange(n), len(laws))), axis=which)

    def law_of(candidates: Candidates) -> np.ndarray:
        axis = candidates.motors.axis
        assert axis is not None
        return axis

    def sized(candidates: Candidates) -> CandidateTable:
        return evaluate_laws(design, laws, law_of(candidates), candidates)

    if design.ratio_choice is None:
        return sized(Candidates.single(rows, design.load, design.transmission))

    def each_law(candidates: Candidates, each: Callable[[int, Candidates, np.ndarray],
                                                          np.ndarray | None]
                 ) -> np.ndarray | None:
        """``each(k, law k's candidates, their positions)`` joined; None if one is."""
        which = law_of(candidates)
        out: np.ndarray | None = None
        for k in sorted_unique(which):
            at = np.flatnonzero(which == k)
            found = each(int(k), candidates.take(at), at)
            if found is None:
                return None
            if out is None:
                out = np.empty(len(candidates), dtype=found.dtype)
            out[at] = found
        return out

    def floor(candidates: Candidates) -> np.ndarray | None:
        return each_law(candidates, lambda k, part, at: duration_floor(design, specs[k], part))

    def fails_up_to(candidates: Candidates, T: np.ndarray, group: np.ndarray) -> np.ndarray:
        found = each_law(candidates, lambda k, part, at: rms_fails_up_to(
            design, specs[k], part, T[at], group[at]))
        assert found is not None
        return found

    def without_peaks(candidates: Candidates) -> CandidateTable:
        present = sorted_unique(law_of(candidates))
        return in_groups(np.searchsorted(present, law_of(candidates)),
                         lambda j, index: evaluate_fixed_law(
                             design, laws[int(present[j])], candidates.take(index),
                             peaks=False), len(present))

    plain = all(_plain_given_duration(design, spec) for spec in specs)
    return choose_ratio(design, rows, sized, floor=floor, fails_up_to=fails_up_to,
                        without_peaks=without_peaks if plain else None,
                        pairs=listed_pairs(design, rows))


def _plain_given_duration(design: Design, spec: LawChoice) -> bool:
    """A given duration, the task shorthand, a fixed law: every check but the peaks is
    known from an evaluation without them, and leaving them out only passes them (the
    ratio search evaluates the peaks of the options that can still win: sizer.sizing.
    ratio_choice)."""
    if design.machine_cycle.minimize or shorthand_task(design.machine_cycle) is None or \
            design.transmission.linkage is not None:
        return False
    return spec.is_fixed


def evaluate_law(design: Design, spec: LawChoice | str,
                 candidates: Candidates) -> CandidateTable:
    """One law choice (fixed or with auto parameters) for all candidates, in their order."""
    spec = law_choice(spec)
    if spec.open_shaped:  # shaped for the load's mode at each candidate's duration
        return evaluate_shaped(design, spec, candidates, evaluate_fixed_law, evaluate_laws)
    if spec.auto:
        single_task(design)  # chosen for the task shorthand only (sizer.io refuses others)
        with without_power_figures():  # verdicts only; the chosen laws get them below
            laws = choose_shape(spec.family, dict(spec.values), design, candidates)
    else:
        return evaluate_fixed_law(design, spec.law, candidates)
    distinct = list(dict.fromkeys(laws))
    which = {law: k for k, law in enumerate(distinct)}
    group = np.array([which[law] for law in laws])
    return evaluate_laws(design, distinct, group, candidates)


def evaluate_laws(design: Design, laws: Sequence[MotionLaw], group: np.ndarray,
                  candidates: Candidates) -> CandidateTable:
    """Each candidate with its own law (laws[group[i]]), in the candidates' order: as the
    rows of one model (sizer.laws.row_laws.RowLaws in the task shorthand's
    sizer.sizing.move.CycleCalculator or a cycle of rest-to-rest moves' SegmentCycle: the
    closed forms, the search for T_min and the checks once over every row) where no law
    moves backwards, no later limit but the residual vibration applies and one chunk holds
    them (:func:`_law_rows`); else law by law (:func:`evaluate_fixed_law`), which gives
    the same numbers."""
    present = sorted_unique(group)
    if len(present) < len(laws):  # the laws some candidate has, in their order
        laws, group = [laws[k] for k in present], np.searchsorted(present, group)
    found = _law_rows(design, laws, group, candidates)
    if found is None:
        return in_groups(group, lambda k, index: evaluate_fixed_law(
            design, laws[k], candidates.take(index)), len(laws))
    rows, later = found
    cycle, limits = design.machine_cycle, design.limits
    settled = answer(rows, limits, later, cycle.minimize)
    checks, verdict = settled.checks, settled.feasible
    if limits.thermal_duty == "once":
        checks, verdict = _once(checks, verdict)
    duration = rows.reported(settled.metrics)
    if cycle.minimize:
        duration = np.where(settled.feasible, duration, np.nan)
    return _table(design, tuple(laws), candidates, duration, settled.metrics, checks,
                  verdict, settled.figures, law_index=group)


def _law_rows(design: Design, laws: Sequence[MotionLaw], group: np.ndarray,
              candidates: Candidates) -> tuple[CycleModel, list[ResidualRows]] | None:
    """The candidates as the rows of one model of their laws (sizer.laws.row_laws.RowLaws)
    where :func:`evaluate_laws` may size them so, with its later limit (the laws' residual
    vibration, where the load has a mode), else None: the task
    shorthand's law move (sizer.sizing.move.CycleCalculator) or a cycle of segments whose
    moves are rest to rest, its split the rule's (:func:`rows_cycle`: SegmentCycle)."""
    cycle = design.machine_cycle
    task = shorthand_task(cycle)
    if (len(laws) < 2 or design.transmission.linkage is not None
            or design.load.position_dependent or (task is None and not rows_cycle(cycle))):
        return None
    drive, motors = candidates.drive, candidates.motors
    rows: CycleModel | None
    if task is not None:
        rows = laws_model(laws, group, task, drive, motors, design.limits.thermal_speed)
    else:
        law = RowLaws(laws, group)
        rows = None if law.moves_backwards() else SegmentCycle(
            cycle, law, drive, motors, design.limits.thermal_speed)
    if rows is None:
        return None
    builds = motors.builds
    modes = () if builds is None else builds.modes
    moves = 1 if task is not None else len(cycle.moves)
    if (energy_limit(design, motors) is not None or screw_limits(drive)
            or (cycle_sampled(design) and gearbox_life_limits(drive))
            or (len(candidates) > min(chunk_size(law, moves) for law in laws)
                and not (task is not None and is_purely_inertial(rows)))):
        return None  # (the closed forms of a law move need no grid)
    residuals = [limit for law in laws if (limit := residual_limit(design, law, modes))
                 is not None]
    if not residuals:  # the load has no mode
        return rows, []
    if len(residuals) < len(laws):
        return None
    return rows, [ResidualRows(tuple(residuals))]


def rows_cycle(cycle: Cycle) -> bool:
    """Whether a cycle of segments takes several laws as the rows of one model: every move
    rest to rest (each on the law move's engine) and the split of its time the rule's (no
    share optimized per candidate)."""
    return cycle.share.goal is None and all(move.rest_to_rest for move in cycle.moves)


def evaluate_per_move(design: Design, choice: PerMoveChoice,
                      candidates: Candidates) -> CandidateTable:
    """``share: {optimize: GOAL, laws: per_move}``: each candidate's law for each move that
    names none (of ``choice.laws``) chosen with its split of the cycle time to minimize
    the goal (SegmentCycle.move_laws: sizer.allocation.allocate_laws, every combination a
    row of one search where they are few); the candidates grouped by the combination
    chosen, each group sized with it (its split found again by the engine for those laws:
    the same search, the same optimum), as the shapes of ``auto`` laws are."""
    if design.transmission.linkage is not None or design.load.position_dependent:
        raise UserError("`laws: per_move` chooses a law for each move of a cycle of "
                        "segments; through a linkage or against loads of the position the "
                        "cycle takes one law for its moves", field="cycle.share")
    laws = tuple(spec.law for spec in choice.laws)
    cycle = design.machine_cycle
    weights = np.array(cycle.weights())

    def choose(part: Candidates) -> np.ndarray:
        return SegmentCycle(cycle, None, part.drive, part.motors, design.limits.thermal_speed,
                            weights=weights).move_laws(laws)

    size = max(1, chunk_size(LawsPerMove(laws), len(cycle.moves)) // _rows_per_candidate(
        cycle, len(laws)))
    chosen = np.concatenate([choose(candidates.take(np.arange(start, min(
        start + size, len(candidates))))) for start in range(0, len(candidates), size)])
    combinations, group = np.unique(chosen, axis=0, return_inverse=True)
    return in_groups(np.ravel(group), lambda k, index: evaluate_fixed_law(
        design, per_move(tuple(laws[j] for j in combinations[k])), candidates.take(index)),
        len(combinations))


def _rows_per_candidate(cycle: Cycle, laws: int) -> int:
    """The rows one candidate becomes in the search of its laws and split
    (sizer.allocation.allocate_laws: a row per law combination of the free moves, at most
    COMBINATIONS, else per law; five durations each for the slope and curvature), so that
    its chunks stay within the engine's samples per evaluation."""
    from sizer.allocation import COMBINATIONS

    free = sum(1 for i in cycle.free if not getattr(cycle.segments[i], "law", None))
    combinations = laws ** free
    return 5 * (combinations if combinations <= COMBINATIONS else laws)


def chunk_size(law: RankedLaw, moves: int = 1) -> int:
    """How many candidates one evaluation of ``law`` takes (its grid's samples each, for
    each of ``moves`` moves evaluated together; a law per move: its largest grid's)."""
    if isinstance(law, LawsPerMove):
        return min(chunk_size(one, moves) for one in law.laws)
    return candidates_per_chunk(grid_samples(law) * max(moves, 1))


def evaluate_fixed_law(design: Design, law: RankedLaw, candidates: Candidates,
                       peaks: bool = True) -> CandidateTable:
    """The requirements, checks and verdicts of one law for every candidate, in chunks
    of :func:`chunk_size` candidates. Without ``peaks`` (a given duration only) the peak
    torques and ratios are left at zero: their checks pass."""
    task = shorthand_task(design.machine_cycle)
    if design.transmission.linkage is not None or design.load.position_dependent:
        moves = len(design.machine_cycle.moves) if task is None else task.moves_per_cycle
        size = candidates_per_chunk(LINKAGE_SAMPLES * moves)
    elif task is None:
        size = chunk_size(law, len(design.machine_cycle.moves))
    else:
        calculator = CycleCalculator(None, task, candidates.drive, candidates.motors,
                                     design.limits.thermal_speed, law=law)
        if is_purely_inertial(calculator):  # closed forms: memory per candidate, no grid
            return _evaluate_chunk(design, law, candidates, peaks)
        size = chunk_size(law)
    if len(candidates) <= size:
        return _evaluate_chunk(design, law, candidates, peaks)
    starts = range(0, len(candidates), size)
    return concatenate([_evaluate_chunk(design, law, candidates.take(
        np.arange(start, min(start + size, len(candidates)))), peaks) for start in starts])


def _evaluate_chunk(design: Design, law: RankedLaw, candidates: Candidates,
                    peaks: bool = True) -> CandidateTable:
    """One law for a chunk of candidates on the design's cycle model (:func:`cycle_model`):
    every check at the given scale, or in minimize mode at the shortest scale at which
    every slack passes, the later limits (residual vibration, braking, heat) included
    (sizer.sizing.shortest_duration.answer); the duration the model reports."""
    cycle, limits = design.machine_cycle, design.limits
    calculator = cycle_model(design, law, candidates)
    builds = candidates.motors.builds
    later = [kind for kind in (residual_limit(design, law,
                                              () if builds is None else builds.modes),
                               energy_limit(design, candidates.motors),
                               *screw_limits(candidates.drive),
                               *(gearbox_life_limits(candidates.drive)
                                 if cycle_sampled(design) else ())) if kind is not None]
    settled = answer(calculator, limits, later, cycle.minimize, peaks)
    checks, verdict = settled.checks, settled.feasible
    if limits.thermal_duty == "once":  # a one-off run: the winding model decides
        checks, verdict = _once(checks, verdict)
    duration = calculator.reported(settled.metrics)
    if cycle.minimize:
        duration = np.where(settled.feasible, duration, np.nan)
    return _table(design, law, candidates, duration, settled.metrics, checks, verdict,
                  settled.figures)


def cycle_sampled(design: Design) -> bool:
    """Whether the stages' forces over the cycle are read from the drive at the load's
    samples (sizer.sizing.stage_life): not through a linkage (its samples are the
    output's); position-dependent loads included (their terms added at each sample's
    position, speed and acceleration: sizer.sizing.stage_life.mean_cubic_load). The
    gearbox output bearing life checks are made there only (a note says so)."""
    return design.transmission.linkage is None


def cycle_model(design: Design, law: RankedLaw, candidates: Candidates) -> CycleModel:
    """The model the design's cycle is sized on, for these candidates: the law move of the
    task shorthand (its closed forms), the cycle of segments, or either through a
    linkage (sizer.sizing.linkage_move)."""
    if isinstance(law, LawsPerMove):  # a cycle of segments (evaluate_per_move)
        return SegmentCycle(design.machine_cycle, law, candidates.drive, candidates.motors,
                            design.limits.thermal_speed)
    if design.transmission.linkage is not None:
        from sizer.sizing.linkage_move import linkage_calculator  # lazy: start-up

        return linkage_calculator(design, law, candidates.motors, candidates.drive)
    cycle, motors, rule = design.machine_cycle, candidates.motors, design.limits.thermal_speed
    task = shorthand_task(cycle)
    if design.load.position_dependent:  # one move, a return or a cycle of segments
        from sizer.sizing.linkage_move import position_model  # lazy: start-up

        return position_model(cycle, law, design.load, candidates.drive, motors, rule)
    if task is None:
        return SegmentCycle(cycle, law, candidates.drive, motors, rule)
    return CycleCalculator(None, task, candidates.drive, motors, rule, law=law)


def _once(checks: list[CheckArrays], verdict: np.ndarray
          ) -> tuple[list[CheckArrays], np.ndarray]:
    """A one-off run (``thermal_duty: once``): where the winding model checks the motor,
    the RMS check is no criterion (it does not apply there); the verdicts again."""
    heat = next((c for c in checks if c.name == CheckName.WINDING_TEMPERATURE_RISE), None)
    if heat is None:
        return checks, verdict
    modelled = np.ones(len(heat.value), dtype=bool) if heat.applies is None else heat.applies
    out = [dataclasses.replace(c, applies=~modelled if c.applies is None
                               else c.applies & ~modelled) if c.name == "rms" else c
           for c in checks]
    return out, all_pass(out)


LINKAGE_SAMPLES = 8192
"""Samples of a move through a linkage per candidate (sizer.sizing.linkage_move)."""


def _table(design: Design, law: RankedLaw | tuple[MotionLaw, ...], candidates: Candidates,
           duration: np.ndarray, metrics: CycleMetrics, checks: list[CheckArrays],
           feasible: np.ndarray, extra: dict[str, np.ndarray],
           law_index: np.ndarray | None = None) -> CandidateTable:
    """The table of one law (or of several: ``law`` their tuple, ``law_index`` each
    candidate's)."""
    motors, drive = candidates.motors, candidates.drive
    n = len(motors)
    laws = law if isinstance(law, tuple) else (law,)
    index = np.zeros(n, dtype=np.intp) if law_index is None else np.asarray(law_index,
                                                                             dtype=np.intp)
    figures = {"duration": duration, "peak_torque": metrics.peak_torque,
               "rms_torque": metrics.rms_torque, "max_speed": metrics.max_speed,
               "load_speed": metrics.load_speed, "load_torque": metrics.load_torque}
    assert set(figures) == set(FIGURES)
    figures.update(extra)  # the later limits': residual vibration, energy and heat
    return CandidateTable(
        mode_of(design), laws, index, motors.catalog, motors.index,
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
    table = evaluate_spec(design, design.chosen_law,
                          MotorArrays.of([motor], design.limits.envelope, design.drives))
    return table.row(0)


def cycle_notes(design: Design) -> list[str]:
    """What sizing a cycle of segments assumed, for reports."""
    cycle = design.machine_cycle
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
    task = shorthand_task(design.machine_cycle)
    if task is None:
        notes.extend(cycle_notes(design))
        holds = any(isinstance(s, Dwell) and (design.load.torque + s.load.torque) != 0.0
                    for s in design.machine_cycle.segments)
    else:
        holds = bool(design.load.torque and task.dwell)
    if holds:
        notes.append("holding the constant load at rest counts as driving (torque / efficiency)")
    if not math.isclose(design.transmission.efficiency, 1.0):
        if design.transmission.efficiency_applies_to == "steady_load":
            notes.append("efficiency applied to the load's steady torque only (friction, "
                         "constant load); inertial torque without loss (Yaskawa's convention)")
        else:
            notes.append("efficiency applied in the direction of power flow")
    notes.extend(energy_notes(design))
    notes.extend(shaft_notes(design.motors, design.transmission, design.ratio_choice,
                             cycle_sampled(design)))
    if design.limits.inertia_ratio is not None:
        if design.limits.inertia_ratio_of == "load":
            notes.append("inertia ratio: the load alone reflected to the motor, over the "
                         "rotor inertia")
        else:
            notes.append("inertia ratio: everything the motor drives (load, screws, gears, "
                         "couplings) reflected to the motor, over the rotor inertia")
    return tuple(notes)


AUTO_WORK = 500_000
"""Candidate x law evaluations from which ``workers=None`` (auto) uses every CPU: about
five seconds of work in one process, against about half a second to start a worker."""


def usable_cpus() -> int:
    """The CPUs this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


def worker_count(workers: int | None, candidates: int, laws: int) -> int:
    """How many processes size ``laws`` laws of ``candidates`` candidates each: ``workers``
    as given (1: this process), or with None every usable CPU where the work is at least
    AUTO_WORK evaluations; never more than the laws."""
    if workers is None:
        workers = usable_cpus() if candidates * laws >= AUTO_WORK else 1
    return max(1, min(int(workers), laws))


_STATE: dict[str, object] = {}
"""A worker's design and motor arrays, sent once when it starts, and what its laws share."""


def _start(design: Design, motors: MotorArrays) -> None:
    _STATE["design"], _STATE["motors"] = design, motors
    _STATE["shared"] = SharedByLaws(design, motors)


def _size_law(spec: LawChoice | PerMoveChoice, first: np.ndarray | None) -> CandidateTable:
    """One law in a worker; the table goes back without its motors (the caller's own
    objects go in again: one copy of the catalog, shared by every table)."""

    design, motors, shared = _STATE["design"], _STATE["motors"], _STATE["shared"]
    assert isinstance(design, Design) and isinstance(motors, MotorArrays)
    assert isinstance(shared, SharedByLaws)
    table = evaluate_spec(design, spec, motors, first, shared)
    return dataclasses.replace(table, motors=())


def tables_in_processes(design: Design, specs: Sequence[LawChoice | PerMoveChoice | str],
                        motors: MotorArrays, workers: int,
                        done: Callable[[int], None] | None = None) -> list[CandidateTable]:
    """The table of each law choice (sizer.sizing.engine.evaluate_spec), sized in
    ``workers`` processes; ``done(count)`` after each law with the count so far."""
    choices = [spec if isinstance(spec, PerMoveChoice) else law_choice(spec)
               for spec in specs]
    import multiprocessing  # here: the start-up of a command sized in one process
    from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait

    methods = multiprocessing.get_all_start_methods()
    context = multiprocessing.get_context("forkserver" if "forkserver" in methods else "spawn")
    tables: list[CandidateTable | None] = [None] * len(specs)
    hint: np.ndarray | None = None
    with ProcessPoolExecutor(workers, mp_context=context, initializer=_start,
                             initargs=(design, motors)) as pool:
        pending: dict[Future[CandidateTable], int] = {}
        queued = iter(range(len(specs)))

        def submit() -> None:
            k = next(queued, None)
            if k is not None:
                pending[pool.submit(_size_law, choices[k], hint)] = k

        for _ in range(workers):
            submit()
        finished = 0
        try:
            while pending:
                ready, _ = wait(pending, return_when=FIRST_COMPLETED)
                for future in sorted(ready, key=pending.__getitem__):
                    k = pending.pop(future)
                    table = dataclasses.replace(future.result(), motors=motors.catalog)
                    tables[k] = table
                    if design.ratio_choice is not None:
                        hint = listed_choice(design, table)
                    finished += 1
                    if done is not None:
                        done(finished)
                    submit()
        except BaseException:  # a law's error (a UserError) is the sizing's: stop the rest
            for future in pending:
                future.cancel()
            raise
    assert all(t is not None for t in tables)
    return [t for t in tables if t is not None]


STEP = 1e-3
"""Relative step in T at which the RMS model tells which way the RMS check moves."""
FALL = 1e-5
"""Relative fall of RMS / limit over STEP that counts as falling: far above the model's
error there (second order: about 1e-3 STEP^2 on the laws tried) and rounding."""


def rms_fails_up_to(design: Design, spec: LawChoice | str, candidates: Candidates,
                    T: np.ndarray, group: np.ndarray | None = None) -> np.ndarray:
    """Per candidate: does the RMS check of ``spec`` fail at every duration up to its T?

    True where it fails at T beyond the tolerance and RMS / limit (the continuous limit at
    the thermal speed) falls as T grows there, by the cycle's RMS model (exact at T, its
    slope too: sizer.sizing.move.RmsModel). That ratio falls with T and may rise again
    past its minimum (friction and a constant load over a cycle with dwell), never the
    other way (the search for T_min rests on the same: sizer.sizing.shortest_duration), so
    it is higher still at every shorter duration.

    ``group`` (per candidate, e.g. its motor): candidates of a group share their T; where
    the transmission options differ only upstream of every power-flow reversal (each
    stage's output torque the same function for all: one stage, or the free ratio
    nearest the motor), they share the stretches between reversals too, and one
    evaluation per group gives every member's RMS model (:func:`_shared_models`)."""

    law = law_choice(spec).law
    task = shorthand_task(design.machine_cycle)
    if task is None:
        return _cycle_fails_up_to(design, law, candidates, T)
    size = chunk_size(law, task.moves_per_cycle)
    out = np.zeros(len(candidates), dtype=bool)
    if group is not None and len(candidates):
        groups = sorted_unique(group)
        done = True
        for start in range(0, len(groups), size):  # the groups' evaluations in chunks
            rows = np.flatnonzero(np.isin(group, groups[start:start + size]))
            part = candidates.take(rows)
            shared = _shared_models(design, law, part, T[rows], group[rows])
            if shared is None:
                done = False
                break
            calculator, model = shared
            out[rows] = _falls_failing(design, part, calculator, model, T[rows],
                                       model.rms(T[rows]))
        if done:
            return out
    for start in range(0, len(candidates), size):
        rows = np.arange(start, min(start + size, len(candidates)))
        part = candidates.take(rows)
        calculator = CycleCalculator(None, task, part.drive, part.motors,
                                     design.limits.thermal_speed, law=law)
        here = T[rows]
        metrics = calculator.evaluate(here, peaks=False, model=True)
        if metrics.rms_model is None:
            continue
        out[rows] = _falls_failing(design, part, calculator, metrics.rms_model, here,
                                   metrics.rms_torque)
    return out


def _cycle_fails_up_to(design: Design, law, candidates: Candidates,
                       T: np.ndarray) -> np.ndarray:
    """The test for a cycle of segments: on the cycle's RMS model (SegmentCycle, with the
    free moves' models) at the scale of the free durations whose cycle time is T. The
    cycle's RMS has the single law's form in that scale (each free move's integral a
    Laurent polynomial in it, the fixed segments constant), so the same reading holds.
    False where the cycle has no model (a free move with boundary speeds)."""
    cycle = design.machine_cycle
    size = chunk_size(law, max(len(cycle.moves), 1))
    out = np.zeros(len(candidates), dtype=bool)
    for start in range(0, len(candidates), size):
        rows = np.arange(start, min(start + size, len(candidates)))
        part = candidates.take(rows)
        calculator = SegmentCycle(cycle, law, part.drive, part.motors,
                                  design.limits.thermal_speed)
        scale = calculator.scale_of(T[rows])
        metrics = calculator.evaluate(scale, peaks=False, model=True)
        if metrics.rms_model is None:
            return out
        out[rows] = _falls_failing(design, part, calculator, metrics.rms_model, scale,
                                   metrics.rms_torque)
    return out


def _falls_failing(design: Design, candidates: Candidates,
                   calculator: CycleCalculator | SegmentCycle, model, T: np.ndarray,
                   rms: np.ndarray) -> np.ndarray:
    """The test of :func:`rms_fails_up_to` from the RMS at T and the model built there."""
    level = 1.0 - design.limits.torque_margin + TOLERANCE
    later = T * (1.0 + STEP)

    def ratio(value: np.ndarray, at: np.ndarray) -> np.ndarray:
        limit = candidates.motors.continuous.limit_clipped(calculator.thermal_speed(at))
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(limit > 0.0, value / limit, np.inf)

    now = ratio(rms, T)
    after = ratio(model.rms(later), later)
    return np.isfinite(now) & (now > level * (1.0 + 1e-9)) & (after < now * (1.0 - FALL))


def _shared_models(design: Design, law, candidates: Candidates, T: np.ndarray,
                   group: np.ndarray):
    """Every candidate's RMS model at its T (sizer.sizing.move.RmsModel) from one
    evaluation per group, or None where the stretches may differ within a group.

    Between two power-flow reversals the motor torque is one of its linear functions,
    the same one for every option (the reflections switch with the sign of a stage's
    output torque; the rotor adds to all of them alike), so a candidate's RMS is the
    quadratic form of its own functions with the law's moments summed over those
    stretches: the moments of the group's first member, the functions of each. That
    holds where every stage's output torque is one function for all candidates (the
    options differ upstream of the reversals) and no stage is ideal (an ideal drive has
    closed forms, no stretches)."""
    drive = candidates.drive
    if drive.is_ideal:
        return None
    n, task = len(candidates), single_task(design)
    calculator = CycleCalculator(None, task, drive, candidates.motors,
                                 design.limits.thermal_speed, law=law)
    for direction in calculator.directions:
        _, outputs = drive.linear_pieces(direction)
        for pieces in outputs:
            for part in pieces:
                for x in part:
                    x = np.broadcast_to(np.asarray(x, dtype=float), (n,))
                    if not np.all(x == x[0]):
                        return None
    _, first, inverse = np.unique(group, return_index=True, return_inverse=True)
    same = bool(np.all(T[first][inverse] == T))
    if not same:
        return None
    model = calculator.take(first).evaluate(T[first], peaks=False, model=True).rms_model
    if not isinstance(model, RmsModel):  # a law's model (a cycle's has other parts)
        return None
    moves = []
    for direction, reference in zip(calculator.directions, model.moves, strict=True):
        scales = MoveScales(calculator.h / T / T, calculator.h / T, direction)
        functions = calculator.channel_terms(scales)[0]
        if len(functions) != len(reference):
            return None
        moves.append([(P, Q, C, M[:, inverse]) for (P, Q, C), (*_, M)
                      in zip(functions, reference, strict=True)])
    hold = np.broadcast_to(drive.holding_torques()[0], (n,))
    return calculator, RmsModel(T.copy(), moves, task.dwell, hold)
