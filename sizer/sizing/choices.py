"""Which ratio and which shape each candidate takes: the choices of a design's axes.

Which ratio of the free transmission stage suits each motor and law best
(:func:`choose_ratio`)? The options are a list of ratios, catalog gearboxes (each ratio with
its own efficiency, inertia and limits), or a continuous range searched on a logarithmic
lattice refined around each motor's best point down to 0.25 % steps. All options of a round
are one flat candidate axis (motors x options, sizer.sizing.candidates) evaluated together.
Per motor the best option is the feasible one with the shortest T_min (minimize mode) or the
smallest RMS torque (duration given); when none is feasible, the one closest to feasible
(the largest worst slack). Ties keep the first option (gearboxes, then the listed ratios,
then the lattice).

In minimize mode the listed options (gearboxes and ratios) are evaluated in rounds, each
motor's options in the order of their duration floors
(sizer.sizing.shortest_duration.duration_floor): an option whose floor lies above the
motor's best feasible T_min so far cannot beat it and is not evaluated; after the first
round, an option whose RMS check fails at every duration up to that T_min
(sizer.sizing.engine.rms_fails_up_to: one evaluation at it) neither. The choice is the one
of evaluating every option.

Shape parameters written ``auto`` are chosen per motor by the solver (:func:`choose_shape`).
In minimize mode the parameters minimize T_min; with a given duration they maximize the
smallest margin (ties broken by the next smallest). The trapezoid and the double S in the
book's case (rectangular regions, purely inertial load, ideal transmission) have their time-
optimal shape computed exactly (sizer.sizing.optimal_shapes, sec. 3.2-3.4 and 6.2); every
other case is searched
to tolerance (below). The chosen parameters are kept at full precision: the duration and
margins reported are those of the law with exactly these parameters.

A parameter is searched over its admissible range. The exact optimum approaches an open
end to within OPEN_INSET of the range (the infimum is not attained there: T_min at the
inset point is within about 1e-10 of it, e.g. beta -> 0 of a double S without a jerk
limit); the search keeps SEARCH_INSET away. A parameter without a finite range cannot
be searched.

Searched to tolerance, for the cases without a closed form (:func:`search_shape`): Friction,
damping, efficiency, curved envelopes, stage limits, a given duration (the largest smallest
margin) or other families: the score of a shape (-T_min in minimize mode, else the slacks of
all checks smallest first, compared lexicographically) is computed by the engine's own
checks for each motor; the T_min of a trapezoid or a double S in minimize mode, where
nothing depends on the speed (no damping, rectangular regions), by closed forms through any
efficiencies (sizer.sizing.optimal_shapes.trusted_phase_model: for the motors where they
agree with the engine's T_min of one such law). One parameter (:func:`search_1d`): a
coarse grid brackets each motor's best point (T_min and the margins are max/min of
quasi-convex/quasi-concave bounds, unimodal on the bracket), then each step tries where
the two bounds cross (read
from the lines through the points either side: the optimum is mostly such a crossing)
or the vertex of a parabola (a smooth optimum of one bound), whichever foretold the
other points better, a golden-section-like point where neither lies inside or the
bracket did not halve in two steps, until the bracket is narrower than TOLERANCE[1] or
the scores across it agree to FLAT. Two parameters: the same, nested (the inner search
for each outer point), to TOLERANCE[2] per parameter (coarser: the cost is the product of
the two searches). Three or more (:func:`search_box`): a grid shared by all motors, then a pattern
search on the 3^N - 1 neighbours of each motor's best point to TOLERANCE[3]. Integer
parameters are enumerated. Motors at equal points are evaluated together (vectorized). In
minimize mode each T_min is the engine's (sizer.sizing.shortest_duration).

A law shaped for the load's mode at each candidate's own duration (book sec. 7.4.2,
:func:`evaluate_shaped`). ``{kind: shaped, law: L, shaper: zv}`` without ``f_T`` in a design
with ``load.natural_frequency``: the shaper's impulses are set by the mode (their times are
multiples of its damped period), so the normalized shaped law depends on the move's duration
T through f_T = f_n T (sizer.vibration.shaped_law). The shaped move keeps the whole duration
T, its base law taking T - t_n.

- A given duration: one law, f_T = f_n T, sized like any other.
- ``minimize``: the shortest T at which the law shaped for T is feasible, per candidate:
  T = T_min(L(f_n T)), solved by a secant iteration from T_0 = T_min(base) + t_n (the
  base move at its own T_min convolved with the shaper: its peaks are convex
  combinations of the base's, sec. 7.4.2). Each step sizes every candidate with the law
  shaped for its own T (one law per distinct T, as for ``auto`` shapes); the result is
  the law shaped for the last T, sized in minimize mode, so its verdict and figures are
  the engine's own.

What the laws of one sizing share is built once, for every law (:class:`SharedByLaws`:
sizer.sizing.engine, and each of its worker processes).
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from collections.abc import Callable
from contextlib import nullcontext
from dataclasses import dataclass, replace
from fractions import Fraction
from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np

from sizer.errors import UserError
from sizer.laws import AUTO, LawChoice, MotionLaw, make_law
from sizer.laws.base import Parameter
from sizer.laws.data_spec import data_spec_text, read_data_spec
from sizer.model.domain import Design, Task, Transmission
from sizer.numerics.bracket_search import Scores, agree, beats, from_grid
from sizer.sizing.candidates import Candidates, MotorArrays
from sizer.sizing.checks import evaluate_checks
from sizer.sizing.cycle import single_task
from sizer.sizing.energy_check import has_braking_check, has_heat_check, without_power_figures
from sizer.sizing.move import CycleCalculator, candidates_per_chunk, grid_samples
from sizer.sizing.results import CandidateTable, Mode, concatenate, in_groups
from sizer.sizing.shortest_duration import laws_model, minimum_duration
from sizer.vibration.elastic_load import ElasticLoad

if TYPE_CHECKING:
    from sizer.sizing.evaluation import CycleModel
    from sizer.sizing.shortest_duration import PeakScales


GRID = {1: 13, 2: 7, 3: 4}
TOLERANCE = {1: 1e-12, 2: 1e-4, 3: 1e-3}
"""Bracket width at which the bracket search stops, per parameter. Two parameters cost
the product of the two searches, each point a full T_min search in minimize mode (about
0.1 s per motor with friction), so 1e-12 there would take hours; 1e-4 takes minutes.
Three or more: the step of the pattern search (:func:`search_box`), at most BOX_ROUNDS
rounds; where two bounds cross along a ridge oblique to the axes it can stop short of the
optimum by about the step (1e-4 relative in T_min): never worse than its grid."""
BOX_ROUNDS = 60


def search_shape(family: type[MotionLaw], fixed: dict[str, float],
                 ranges: dict[str, tuple[float, float]], design: Design,
                 motors: Candidates) -> dict[str, np.ndarray]:
    """The best value of each auto parameter per motor (arrays over the motors)."""
    names = list(ranges)
    params = {p.name: p for p in family.parameters}
    n = len(motors)
    dims = len(names)
    from sizer.sizing.optimal_shapes import trusted_phase_model  # lazy: start-up (issue 34)

    phases = trusted_phase_model(family, fixed, names, ranges, design, motors)

    def score_rows(points: list[np.ndarray], rows: np.ndarray) -> Scores:
        """The scores of the motors ``rows`` at ``points`` (an array per parameter, a
        value per row; nan: none): the law's closed forms where they hold and
        agree with the engine (sizer.sizing.optimal_shapes), else the engine's."""
        if phases is None:
            return evaluate_points(family, fixed, names, points, design, motors.take(rows))
        out = np.empty((len(rows), 1))
        mine = phases.trusted[rows]
        if mine.any():
            T = phases.durations([p[mine] for p in points], rows[mine])
            out[mine, 0] = np.where(np.isfinite(T), -T, -np.inf)
        if not mine.all():
            out[~mine] = evaluate_points(family, fixed, names, [p[~mine] for p in points],
                                         design, motors.take(rows[~mine]))
        return out

    bounds = [ranges[name] for name in names]
    best = search_box(score_rows, bounds, n) if dims >= 3 else \
        _nested(score_rows, [params[name] for name in names], bounds, np.arange(n), dims,
                ())[0]
    return dict(zip(names, best, strict=True))


RowScore = Callable[[np.ndarray, np.ndarray], Scores]
"""``score(x, which)``: the scores of the rows ``which`` (repeats allowed) at the values
``x`` of a parameter (nan: none), one row of scores each."""
PointScore = Callable[[list[np.ndarray], np.ndarray], Scores]
"""``score(points, motors)``: the scores of the motors (repeats allowed) at the points
(an array per parameter, a value per row; nan: none)."""


def _nested(score_rows: PointScore, parameters: list[Parameter],
            bounds: list[tuple[float, float]], rows: np.ndarray, dims: int,
            prefix: tuple[np.ndarray, ...]) -> tuple[list[np.ndarray], Scores]:
    """Best values per row (``rows``: each row's motor) of the parameters after ``prefix``
    (their values fixed, an array over the rows each), and the score there: a 1-D search
    of the first whose score is the best over the rest for that value (nested; the rows
    of an outer step's inner search are its motors x values, one search); the best of
    all the points tried is returned."""
    def fixed(which: np.ndarray) -> list[np.ndarray]:
        return [p[which] for p in prefix]

    if len(parameters) == 1:
        value, scores = search_1d(lambda x, which: score_rows([*fixed(which), x],
                                                              rows[which]),
                                  parameters[0], bounds[0], len(rows), dims)
        return [value], scores
    tried: list[tuple[np.ndarray, list[np.ndarray], Scores]] = []

    def outer(x: np.ndarray, which: np.ndarray) -> Scores:
        out = np.full((len(x), 1), -np.inf)
        live = np.flatnonzero(~np.isnan(x))  # settled rows: no inner search
        if len(live):
            rest, scores = _nested(score_rows, parameters[1:], bounds[1:],
                                   rows[which[live]], dims,
                                   (*fixed(which[live]), x[live]))
            tried.append((which[live], [x[live], *rest], scores))
            out = np.full((len(x), scores.shape[1]), -np.inf)
            out[live] = scores
        return out

    search_1d(outer, parameters[0], bounds[0], len(rows), dims)
    n = len(rows)
    best = [np.full(n, np.nan) for _ in parameters]
    best_s = np.full((n, tried[0][2].shape[1]), -np.inf)
    has = np.zeros(n, dtype=bool)
    for which, point, s in tried:  # in the order tried; within a call, its order
        turn = _occurrence(which)
        for k in range(int(turn.max()) + 1 if len(turn) else 0):
            at = np.flatnonzero(turn == k)
            row = which[at]
            take = ~has[row] | beats(s[at], best_s[row])
            sel, row = at[take], row[take]
            for b, p in zip(best, point, strict=True):
                b[row] = p[sel]
            best_s[row] = s[sel]
            has[row] = True
    return best, best_s


def _occurrence(which: np.ndarray) -> np.ndarray:
    """Per element, how many equal elements come before it."""
    order = np.argsort(which, kind="stable")
    ranked = which[order]
    start = np.flatnonzero(np.concatenate(([True], ranked[1:] != ranked[:-1])))
    counts = np.diff(np.concatenate((start, [len(which)])))
    out = np.empty(len(which), dtype=np.intp)
    out[order] = np.arange(len(which)) - np.repeat(start, counts)
    return out


def search_box(score_rows: PointScore, bounds: list[tuple[float, float]],
               n: int) -> list[np.ndarray]:
    """Best point per motor of N >= 3 continuous parameters (nested 1-D searches would
    cost the product of N searches): a grid of GRID[3] points per parameter shared by all
    motors, then per motor the 3^N - 1 neighbours at +-step around its best point, the
    step halved where none is better, until it is below TOLERANCE[3] or the neighbours'
    scores agree with the best to FLAT (at most BOX_ROUNDS rounds). The grid, and each
    round's neighbours, are scored in one call (``score_rows(points, motors)``: a row per
    motor and point; motors at equal points evaluated together), a point of a motor once;
    the neighbours are then taken in turn, the best of all the points tried returned."""
    low, high = (np.array(ends, dtype=float) for ends in zip(*bounds, strict=True))
    points = np.array(list(itertools.product(*(np.linspace(a, b, GRID[3]) for a, b in bounds))))
    motor = np.arange(n)
    every = score_rows(list(np.repeat(points, n, axis=0).T),
                       np.tile(motor, len(points))).reshape(len(points), n, -1)
    index, best_s = np.zeros(n, dtype=int), every[0]
    for i in range(1, len(points)):  # the first of equals (grid order)
        take = beats(every[i], best_s)
        index, best_s = np.where(take, i, index), np.where(take[:, None], every[i], best_s)
    best = points[index]
    step = np.broadcast_to((high - low) / (GRID[3] - 1), best.shape).copy()
    offsets = np.array([o for o in itertools.product((-1, 0, 1), repeat=len(bounds)) if any(o)])
    active = np.ones(n, dtype=bool)
    seen: list[dict[bytes, Scores]] = [{} for _ in range(n)]  # per motor: point -> score

    def once(point: np.ndarray) -> Scores:
        """The scores at per-motor points (k, motors, N) (nan: none), each motor's point
        scored once in the search (a clipped neighbour or the neighbour of a moved centre
        repeats one): the points not seen before in one call of ``score_rows``."""
        k = len(point)
        out = np.full((k, n, best_s.shape[1]), -np.inf)
        wanted = [(j, i) for j in range(k) for i in np.flatnonzero(~np.isnan(point[j, :, 0]))]
        fresh = [(j, i) for j, i in wanted if point[j, i].tobytes() not in seen[i]]
        if fresh:
            at = np.array(fresh)
            out[at[:, 0], at[:, 1]] = score_rows(list(point[at[:, 0], at[:, 1]].T), at[:, 1])
        for j, i in wanted:  # in the order the neighbours are taken: the first one kept
            out[j, i] = seen[i].setdefault(point[j, i].tobytes(), out[j, i].copy())
        return out

    for _ in range(BOX_ROUNDS):
        if not active.any():
            break
        step[active] *= 0.5
        center, center_s, flat = best.copy(), best_s, np.ones(n, dtype=bool)
        around = np.where(active[None, :, None],
                          np.clip(center[None] + offsets[:, None] * step[None], low, high),
                          np.nan)
        scored = once(around)
        for point, scores in zip(around, scored, strict=True):
            flat &= agree(center_s, scores)
            take = active & beats(scores, best_s)
            best[take], best_s = point[take], np.where(take[:, None], scores, best_s)
        moved = np.any(best != center, axis=1)
        step[moved] *= 2.0  # a better neighbour: the same step around it
        active &= moved | ((step.max(axis=1) > TOLERANCE[3]) & ~flat)
    return list(best.T)


def search_1d(score: RowScore, parameter, bounds: tuple[float, float], n: int,
              dims: int) -> tuple[np.ndarray, Scores]:
    """Best point per row of a 1-D score, and its score: a grid of GRID[dims] points
    (scored in one call), then from each row's best grid point the bracket search of
    sizer.numerics.bracket_search (steps where two bounds cross, or to a parabola's
    vertex, safeguarded) to TOLERANCE[dims], or until the deciding entry of the scores
    agrees to FLAT across the bracket. Settled rows are not evaluated again (their point
    is passed as nan). Integer parameters are enumerated.
    """
    lo, hi = bounds
    if parameter.integer:
        grid = np.arange(math.ceil(lo), math.floor(hi) + 1, dtype=float)
        if parameter.odd:
            grid = grid[grid % 2 == 1]
        best, best_s, _, _ = _best_on_grid(score, grid, n)
        return best, best_s
    tol = TOLERANCE[dims]
    grid = np.linspace(lo, hi, GRID[dims])
    _, _, index, on_grid = _best_on_grid(score, grid, n)
    every = np.arange(n)
    return from_grid(lambda x: score(x, every), grid, on_grid, index, tol)


def _best_on_grid(score: RowScore, grid: np.ndarray,
                  n: int) -> tuple[np.ndarray, Scores, np.ndarray, np.ndarray]:
    """Best grid point per row (first of equals), its score, its index, all scores (the
    grid scored in one call)."""
    every = score(np.repeat(grid, n), np.tile(np.arange(n), len(grid))).reshape(len(grid), n,
                                                                                 -1)
    index = np.zeros(n, dtype=int)
    best_s = every[0]
    for i in range(1, len(grid)):
        take = beats(every[i], best_s)
        index, best_s = np.where(take, i, index), np.where(take[:, None], every[i], best_s)
    return grid[index], best_s, index, every


def evaluate_points(family: type[MotionLaw], fixed: dict[str, float], names: list[str],
                    points: list[np.ndarray], design: Design, motors: Candidates) -> Scores:
    """The score of each motor at its own point (motors at equal points evaluated together)."""
    n = len(motors)
    stacked = np.column_stack(points)
    wanted = np.nonzero(~np.isnan(stacked).any(axis=1))[0]
    if not len(wanted):
        return np.full((n, 1), -np.inf)
    keys, inverse = np.unique(stacked[wanted], axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    laws = [family(**fixed, **{name: float(v) for name, v in zip(names, key, strict=True)})
            for key in keys]
    together = _law_rows(laws, inverse, design, motors.take(wanted))
    if together is not None:
        every = np.full((n, together.shape[1]), -np.inf)
        every[wanted] = together
        return every
    out: Scores | None = None
    for k, law in enumerate(laws):
        members = wanted[np.nonzero(inverse == k)[0]]
        subset = motors if len(members) == n else motors.take(members)
        rows = score_law(law, design, subset)
        if out is None:
            out = np.full((n, rows.shape[1]), -np.inf)
        out[members] = rows
    assert out is not None
    return out


def _law_rows(laws: list[MotionLaw], part: np.ndarray, design: Design,
              candidates: Candidates) -> Scores | None:
    """The scores of several laws' candidates (row i of laws[part[i]]) sized as the rows
    of one model (sizer.sizing.shortest_duration.laws_model: each row's figures its law's
    alone, bit for bit): a move rest-to-rest without a linkage or a load of the position,
    no law that moves backwards; T_min in minimize mode, the checks at the given duration
    otherwise. None elsewhere (each law scored alone)."""
    if len(laws) < 2 or design.transmission.linkage is not None \
            or design.load.position_dependent:
        return None
    task = single_task(design)
    n = len(candidates)
    size = candidates_per_chunk(max(grid_samples(law) for law in laws) * task.moves_per_cycle)
    out: Scores | None = None
    for start in range(0, n, size):  # in chunks, as the engine sizes: bounded memory
        at = np.arange(start, min(start + size, n))
        chunk = candidates if len(at) == n else candidates.take(at)
        rows = laws_model(laws, part[at], task, chunk.drive, chunk.motors,
                          design.limits.thermal_speed)
        if rows is None:
            return None
        scores = _model_scores(rows, task, design, chunk)
        if out is None:
            out = np.empty((n, scores.shape[1]))
        out[at] = scores
    return out


def _model_scores(calculator: CycleModel, task: Task, design: Design,
                  candidates: Candidates) -> Scores:
    """(-T_min,) in minimize mode (-inf if infeasible), else the sorted slacks of the
    checks at the task's duration, of the candidates of ``calculator``."""
    if task.minimize:
        solution = minimum_duration(calculator, design.limits)
        return -np.where(solution.feasible, solution.duration, np.inf)[:, None]
    metrics = calculator.evaluate(np.full(len(candidates), task.duration))
    checks = evaluate_checks(metrics, candidates.motors, candidates.drive, design.limits,
                             task.linear)
    return np.sort(np.stack([c.slack for c in checks], axis=1), axis=1)


def score_law(law: MotionLaw, design: Design, candidates: Candidates) -> Scores:
    """(-T_min,) in minimize mode (-inf if infeasible), else the sorted slacks. T_min is
    the engine's own (sizer.sizing.shortest_duration.minimum_duration: from its bounds,
    cheaper than a bracket around a neighbouring shape's T_min)."""
    motors, drive = candidates.motors, candidates.drive
    if design.transmission.linkage is not None:  # through the linkage (issue 14)
        from sizer.sizing.linkage_move import evaluate_linkage

        duration, _, checks, feasible = evaluate_linkage(design, law, motors, drive)
        if design.machine_cycle.minimize:
            return -np.where(feasible, duration, np.inf)[:, None]
        return np.sort(np.stack([c.slack for c in checks], axis=1), axis=1)
    task = single_task(design)
    calculator: CycleModel
    if design.load.position_dependent:  # gravity, a spring, a table: the position engine
        from sizer.sizing.linkage_move import position_model  # lazy: start-up

        calculator = position_model(design.machine_cycle, law, design.load, drive, motors,
                                    design.limits.thermal_speed)
    else:
        calculator = CycleCalculator(None, task, drive, motors, design.limits.thermal_speed,
                                     law=law)
    return _model_scores(calculator, task, design, candidates)


OPEN_INSET = 1e-10
SEARCH_INSET = 1e-3
"""The searched laws are built and sampled at each point; next to an open end their
shapes get steep (e.g. kappa -> -1 of the modified cycloidal) and their numerics are
not reliable there, so the search keeps 1e-3 of the range away from open ends."""


def choose_shape(family: type[MotionLaw], values: dict[str, Fraction | str], design: Design,
                 candidates: Candidates) -> list[MotionLaw]:
    """The best law of the family for each candidate, its auto parameters optimized."""
    motors = candidates.motors
    free = [p for p in family.parameters if values.get(p.name) == AUTO]
    fixed = {k: float(v) for k, v in values.items() if v != AUTO}
    ranges = {p.name: search_range(family.law_id, p, OPEN_INSET) for p in free}
    from sizer.sizing.optimal_shapes import exact_time_optimal  # lazy: start-up (issue 34)

    exact = exact_time_optimal(family, fixed, ranges, design, candidates)
    params, search = (None, np.ones(len(motors), dtype=bool)) if exact is None else exact
    if search.any():
        ranges = {p.name: search_range(family.law_id, p, SEARCH_INSET) for p in free}
        index = np.flatnonzero(search)
        found = search_shape(family, fixed, ranges, design, candidates.take(index))
        if params is None:
            params = found
        else:
            for name, chosen in found.items():
                params[name] = params[name].astype(float).copy()
                params[name][index] = chosen
    if params is None:  # no candidates: neither the exact shapes nor a search
        return []
    names = list(params)  # the auto parameters (at least one)
    points, inverse = np.unique(np.column_stack([params[name] for name in names]), axis=0,
                                return_inverse=True)  # one law per distinct point
    laws = [family(**fixed, **{name: float(v) for name, v in zip(names, point, strict=True)})
            for point in points]
    return [laws[k] for k in inverse.reshape(-1)]


def search_range(law_id: str, p: Parameter, inset: float) -> tuple[float, float]:
    """The closed interval searched for an auto parameter: its ``auto_range`` (sizer.laws),
    open ends inset by ``inset`` times the range."""
    refusal = p.auto_refusal(law_id)
    if refusal is not None:
        raise UserError(refusal)
    low, high = p.auto_range  # type: ignore[misc]
    span = high - low
    return (low + (inset * span if p.low_open and low == p.low else 0.0),
            high - (inset * span if p.high_open and high == p.high else 0.0))


FixedLawSizing = Callable[[Design, MotionLaw, Candidates], CandidateTable]
"""Sizes one fixed law for every candidate (sizer.sizing.engine.evaluate_fixed_law)."""
LawsSizing = Callable[[Design, list[MotionLaw], np.ndarray, Candidates], CandidateTable]
"""Sizes each candidate with its own law, laws[group[i]], as the rows of one model where
it can (sizer.sizing.engine.evaluate_laws)."""

ROUNDS = 12
"""Most secant steps of the minimize iteration."""

RTOL = 1e-9
"""Relative change of T at which the iteration stops."""


def _mode(design: Design, fields: dict[str, Any]) -> ElasticLoad:
    elastic = design.load.elastic
    if elastic is None:
        raise UserError("a shaped law without f_T is shaped for the load's mode: give "
                        "load.natural_frequency (or f_T)", field="laws")
    return ElasticLoad(elastic.natural_frequency,
                       float(fields.get("damping_ratio", elastic.damping_ratio)))


def _shaped(fields: dict[str, Any], mode: ElasticLoad, T: float) -> MotionLaw:
    return make_law(data_spec_text({**fields, "f_T": mode.natural_frequency * T,
                                    "damping_ratio": mode.damping_ratio}))


def evaluate_shaped(design: Design, choice: LawChoice, candidates: Candidates,
                    evaluate_fixed_law: FixedLawSizing,
                    evaluate_laws: LawsSizing) -> CandidateTable:
    """The open shaped law ``choice`` for every candidate, in their order, each law shaped
    for it: one law by ``evaluate_fixed_law``, the laws of each round's durations by
    ``evaluate_laws`` (sizer.sizing.engine's)."""
    from sizer.vibration.shapers import shaper_length

    fields = dict(read_data_spec(choice.text))
    mode = _mode(design, fields)
    task = single_task(design)
    if task.duration is not None:
        return evaluate_fixed_law(design, _shaped(fields, mode, task.duration), candidates)
    # the rounds size the torques alone: the law shaped for T leaves no residual at T, a
    # residual limit is checked once T is found (moving T inside the rounds would break the
    # shaping's timing)
    limit = design.limits.residual_vibration
    plain = replace(design, limits=replace(design.limits, residual_vibration=None))
    base = fields["law"] if isinstance(fields["law"], str) else data_spec_text(fields["law"])
    start = evaluate_fixed_law(plain, make_law(base), candidates).figures["duration"]
    t_n = shaper_length(fields["shaper"], mode, fields.get("vibration_limit"))
    known = np.isfinite(start)
    fallback = float(np.nanmax(start)) if known.any() else 4.0 * t_n
    T = np.where(known, start, fallback) + t_n
    table, h = _round(plain, fields, mode, T, candidates, evaluate_laws)
    previous_T, previous_h = T, h
    for _ in range(ROUNDS):
        moving = np.isfinite(h) & (np.abs(h) > RTOL * T)
        if not moving.any():
            break
        slope = np.where(np.isfinite(previous_h) & (previous_T != T),
                         (h - previous_h) / np.where(previous_T != T, T - previous_T, 1.0),
                         0.0)
        # the secant of h(T) = T_min(L(f_n T)) - T, whose slope is about -1 (a plain
        # fixed-point step T + h where there is no slope yet or it is unusable)
        usable = (slope < -0.05) & (slope > -20.0)
        step = np.where(usable, -h / np.where(usable, slope, -1.0), h)
        nxt = np.where(moving, np.maximum(T + step, t_n * (1.0 + 1e-6)), T)
        previous_T, previous_h = T, h
        T = nxt
        table, h = _round(plain, fields, mode, T, candidates, evaluate_laws,
                          (table, previous_T))
    if limit is None:
        return table
    return _round(design, fields, mode, T, candidates, evaluate_laws)[0]


def _round(design: Design, fields: dict[str, Any], mode: ElasticLoad, T: np.ndarray,
           candidates: Candidates, evaluate_laws: LawsSizing,
           previous: tuple[CandidateTable, np.ndarray] | None = None,
           ) -> tuple[CandidateTable, np.ndarray]:
    """Every candidate sized (minimize) with the law shaped for its own T (the candidates
    of one T, to 15 digits, share the law shaped for the first one's), the laws as the
    rows of one model where the engine can; the table in the candidates' order and
    h = T_min - T (nan where infeasible). ``previous``: an earlier round's table and T,
    its rows kept where T is the same (the same row)."""
    kept = np.zeros(len(T), dtype=bool) if previous is None else previous[1] == T
    new = np.flatnonzero(~kept)
    _, first, group = np.unique(np.round(T[new], 15), return_index=True,
                                return_inverse=True)
    laws = [_shaped(fields, mode, float(T[new[i]])) for i in first]

    def size(k: int, index: np.ndarray) -> CandidateTable:
        if k == 0 or not len(index):  # the rows kept from the previous round
            assert previous is not None
            return previous[0].take(index)
        return evaluate_laws(design, laws, np.ravel(group), candidates.take(index))

    table = in_groups((~kept).astype(np.intp), size, 2) if kept.any() else size(1, new)
    return table, table.figures["duration"] - T


COARSE = 9
LOG_STEP = 2.5e-3
"""Final spacing of the search in log(ratio): the chosen ratio is within ~0.25 %."""

Evaluate = Callable[[Candidates], CandidateTable]
"""Evaluates one law (spec) for candidates; the table has one row per candidate."""
Floor = Callable[[Candidates], "np.ndarray | None"]
"""Per candidate a duration below which it is infeasible, or None (no floor known)."""
FailsUpTo = Callable[[Candidates, np.ndarray, np.ndarray], np.ndarray]
"""``fails_up_to(candidates, T, group)``: per candidate, is it infeasible at every duration
up to its T? (``group``: the candidates sharing a T, each motor's options.)"""


def _score(table: CandidateTable) -> tuple[np.ndarray, np.ndarray]:
    """(infeasible, value) per candidate, both smaller better."""
    infeasible = ~table.feasible
    name = "duration" if table.mode is Mode.MINIMIZE else "rms_torque"
    value = table.figures[name]
    worst = np.min(table.slacks, axis=1)
    key = np.where(infeasible, -worst, value)
    return infeasible, np.where(np.isnan(key), np.inf, key)


class _Best:
    """The best candidate so far per motor, over the tables of the rounds."""

    def __init__(self, motors: int) -> None:
        self.tables: list[CandidateTable] = []
        self.where = np.full((motors, 2), -1, dtype=np.intp)  # (table, row)
        self.infeasible = np.ones(motors, dtype=bool)
        self.value = np.full(motors, np.inf)
        self.found = np.zeros(motors, dtype=bool)
        self.stage_ratio = np.full(motors, np.nan)
        self.rank = np.zeros(motors, dtype=np.intp)
        self.seen = 0  # ranks given so far

    def update(self, table: CandidateTable, motor: np.ndarray, stage_ratio: np.ndarray,
               rank: np.ndarray | None = None) -> None:
        """Keep, per motor, the best candidate of ``table`` (rows for motors ``motor``) if
        it beats the one kept: smaller (infeasible, value), then smaller ``rank`` (the
        option's place in the order options are listed; default: after every option
        seen so far, in the table's order)."""
        if rank is None:
            rank = self.seen + np.arange(len(table))
        self.seen = max(self.seen, int(np.max(rank, initial=-1)) + 1)
        infeasible, value = _score(table)
        order = np.lexsort((rank, value, infeasible, motor))
        first = np.ones(len(order), dtype=bool)
        first[1:] = motor[order][1:] != motor[order][:-1]
        rows = order[first]
        m = motor[rows]
        same = (infeasible[rows] == self.infeasible[m]) & (value[rows] == self.value[m])
        better = ~self.found[m] | (infeasible[rows] < self.infeasible[m]) | \
            ((infeasible[rows] == self.infeasible[m]) & (value[rows] < self.value[m])) | \
            (same & (rank[rows] < self.rank[m]))
        rows, m = rows[better], m[better]
        self.tables.append(table)
        self.where[m] = np.column_stack((np.full(len(m), len(self.tables) - 1), rows))
        self.infeasible[m], self.value[m] = infeasible[rows], value[rows]
        self.rank[m] = rank[rows]
        self.found[m] = True
        self.stage_ratio[m] = stage_ratio[rows]

    def table(self) -> CandidateTable:
        joined = concatenate(self.tables)
        offsets = np.cumsum([0] + [len(t) for t in self.tables])
        chosen = offsets[self.where[:, 0]] + self.where[:, 1]
        best = joined.take(chosen)
        return dataclasses.replace(best, stage_ratio=self.stage_ratio.copy())


@dataclass(frozen=True)
class ListedPairs:
    """Every motor with every listed option of the free stage (gearboxes, then ratios),
    motor-major: the same for every law, so built once per sizing (:func:`listed_pairs`);
    ``candidates`` None where nothing is listed (a continuous range only)."""

    transmissions: list[Transmission]
    names: list[str | None]
    motor: np.ndarray
    option: np.ndarray
    candidates: Candidates | None


def with_ratio(design: Design, ratio: float) -> Transmission:
    """The design's transmission with its free stage at ``ratio``."""
    choice = design.ratio_choice
    assert choice is not None
    base = design.transmission.stages[choice.stage]
    return design.transmission.with_stage(choice.stage, dataclasses.replace(base, ratio=ratio))


def listed_pairs(design: Design, motors: MotorArrays) -> ListedPairs:
    """The :class:`ListedPairs` of a design with a free stage, for these motors."""
    choice = design.ratio_choice
    assert choice is not None
    listed = [design.transmission.with_stage(choice.stage, g.stage) for g in choice.gearboxes]
    names: list[str | None] = [g.gearbox for g in choice.gearboxes]
    listed += [with_ratio(design, r) for r in choice.ratios]
    names += [None] * len(choice.ratios)
    n, m = len(motors), len(listed)
    motor, option = np.repeat(np.arange(n), m), np.tile(np.arange(m), n)
    every = Candidates.pairs(motors, design.load, listed, motor, option,
                             gearboxes=tuple(names)) if listed else None
    return ListedPairs(listed, names, motor, option, every)


def choose_ratio(design: Design, motors: MotorArrays, evaluate: Evaluate,
                 floor: Floor | None = None,
                 fails_up_to: FailsUpTo | None = None,
                 without_peaks: Evaluate | None = None,
                 first: np.ndarray | None = None,
                 pairs: ListedPairs | None = None) -> CandidateTable:
    """The best option for each motor (one row per motor, carrying ratio and gearbox).
    In minimize mode ``floor`` bounds the options' T_min from below and ``fails_up_to``
    tells the candidates infeasible at every duration up to a given one, and ``first``
    (per motor a listed option, or -1) is the option to try first (the choice of another
    law: :func:`listed_choice`); with a given duration ``without_peaks`` evaluates all
    but the peaks (module docs). None of these changes the choice, only its cost.
    ``pairs``: the design's :func:`listed_pairs` for these motors, where built already."""
    choice = design.ratio_choice
    assert choice is not None
    best = _Best(len(motors))
    energy = has_heat_check(motors.catalog) or has_braking_check(design, motors.drives)
    # with energy checks every option is evaluated in full at once: the peaks in rounds
    # (_peaks_in_order) keep the choice (the heat and braking checks do not read the
    # peaks) but cost more calls than the rows they save (pick-and-place, measured:
    # 0.43 s at once, 0.65 s in rounds)
    lazy = without_peaks if not energy else None

    def consider(transmissions: list[Transmission], gearboxes: list[str | None],
                 motor: np.ndarray, option: np.ndarray, rank: np.ndarray | None = None,
                 candidates: Candidates | None = None) -> None:
        """Evaluate the pairs (motor, option) and keep the best (``candidates``: those
        pairs, when built already)."""
        if candidates is None:
            candidates = Candidates.pairs(motors, design.load, transmissions, motor, option,
                                          gearboxes=tuple(gearboxes))
        ratios = np.array([t.stages[choice.stage].ratio for t in transmissions])[option]
        if rank is None:
            rank = best.seen + np.arange(len(candidates))
        if lazy is None:
            best.update(evaluate(candidates), motor, ratios, rank)
            return
        rows, table = _peaks_in_order(candidates, motor, rank, evaluate, lazy)
        best.update(table, motor[rows], ratios[rows], rank[rows])

    if pairs is None:
        pairs = listed_pairs(design, motors)
    listed, names = pairs.transmissions, pairs.names
    with without_power_figures() if energy else nullcontext():
        if listed:
            n, m = len(motors), len(listed)
            motor, option, every = pairs.motor, pairs.option, pairs.candidates
            assert every is not None
            bounds = floor(every) if floor is not None and m > 1 else None
            if bounds is None:
                consider(listed, names, motor, option, option, every)
            else:
                def rule_out(mo: np.ndarray, op: np.ndarray, T: np.ndarray) -> np.ndarray:
                    assert fails_up_to is not None
                    return fails_up_to(every.take(mo * m + op), T, mo)

                def round_of(mo: np.ndarray, op: np.ndarray) -> None:
                    consider(listed, names, mo, op, op, every.take(mo * m + op))

                _by_floor(bounds.reshape(n, m), round_of, best,
                          None if fails_up_to is None else rule_out, first)
        if choice.bounds is not None:
            _continuous(choice.bounds, lambda ratio: with_ratio(design, ratio), consider, best,
                        len(motors))
    chosen = best.table()
    if not energy:
        return chosen
    # the chosen candidates once more, with the power figures the search left out
    again = evaluate(Candidates.pairs(motors, design.load, list(chosen.transmissions),
                                      np.arange(len(motors)), chosen.option,
                                      gearboxes=chosen.gearboxes))
    return dataclasses.replace(again, stage_ratio=chosen.stage_ratio)


def listed_choice(design: Design, table: CandidateTable) -> np.ndarray | None:
    """Per motor (row of a :func:`choose_ratio` table) the listed option it holds
    (gearboxes, then ratios: the order of the search), by gearbox name and ratio; -1 for
    another ratio (a lattice point); None without listed options."""
    choice = design.ratio_choice
    if choice is None or not (choice.gearboxes or choice.ratios):
        return None
    keys: list[tuple[str | None, float]] = [(g.gearbox, g.stage.ratio)
                                            for g in choice.gearboxes]
    keys += [(None, r) for r in choice.ratios]
    assert table.stage_ratio is not None  # a table of the ratio search
    # per row its option's gearbox (a name, or None) as the place of that name among the
    # table's names, then each listed key in turn: the first that matches (name, ratio)
    names = list(dict.fromkeys(table.gearboxes))
    name_of = np.array([names.index(g) for g in table.gearboxes], dtype=np.intp)[table.option]
    out = np.full(len(table.option), -1, dtype=np.intp)
    for k, (name, ratio) in enumerate(keys):
        if name in names:
            out[(out < 0) & (name_of == names.index(name))
                & (table.stage_ratio == float(ratio))] = k
    return out


def _peaks_in_order(candidates: Candidates, motor: np.ndarray, rank: np.ndarray,
                    evaluate: Evaluate, without_peaks: Evaluate
                    ) -> tuple[np.ndarray, CandidateTable]:
    """A given duration: the candidates whose peaks can decide the choice, evaluated in
    full (rows of ``candidates`` and their table). All are evaluated without the peaks
    first (the RMS torque and every other check; left out, the peak checks pass, so a
    candidate infeasible there is infeasible); then, per motor, in rounds, its candidate
    with the next smallest (RMS torque, rank) among those feasible so far, until one is
    feasible with its peaks: no candidate after it can beat it. Where none is, every
    candidate of the motor is evaluated (the closest to feasible is chosen)."""
    rough = without_peaks(candidates)
    infeasible, value = _score(rough)
    order = np.lexsort((rank, value, infeasible, motor))
    by_motor = motor[order]
    start = np.flatnonzero(np.r_[True, by_motor[1:] != by_motor[:-1]])
    place = np.arange(len(order)) - np.repeat(start, np.diff(np.r_[start, len(order)]))
    motors = int(motor.max(initial=-1)) + 1
    found = np.zeros(motors, dtype=bool)
    evaluated = np.zeros(len(order), dtype=bool)
    picked: list[np.ndarray] = []
    tables: list[CandidateTable] = []

    def full(rows: np.ndarray) -> None:
        table = evaluate(candidates.take(rows))
        found[motor[rows][table.feasible]] = True
        evaluated[rows] = True
        picked.append(rows)
        tables.append(table)

    for k in range(int(place.max(initial=-1)) + 1):
        rows = order[(place == k) & ~infeasible[order] & ~found[by_motor]]
        if len(rows) == 0:
            break
        full(rows)
    rest = np.flatnonzero(~found[motor] & ~evaluated)
    if len(rest):
        full(rest)
    return np.concatenate(picked), concatenate(tables)


FLOOR_MARGIN = 1e-12
"""Relative gap by which an option's floor must exceed the best T_min to be left out
(the floor and T_min are each exact to a few ulps)."""


RuleOut = Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray]
"""``rule_out(motor, option, T)``: per pair, is it infeasible at every duration up to T?"""


def _by_floor(floors: np.ndarray, consider: Callable[[np.ndarray, np.ndarray], None],
              best: _Best, rule_out: RuleOut | None = None,
              first: np.ndarray | None = None) -> None:
    """The listed options in rounds (minimize mode): per motor, its options in the order
    of their floors (motors x options), one per round while the motor has a feasible
    option, whose T_min the options with a higher floor cannot beat; every option left at
    once where the motor has none yet after its first (the closest to feasible is chosen
    from all of them). After the first round, ``rule_out`` rules out the options that
    cannot beat the T_min found (a cheap test at that duration). ``first``: per motor the
    option of the first round instead of the one with the lowest floor (-1: that one)."""
    n, m = floors.shape
    key = floors
    if first is not None:
        key = np.where(np.arange(m)[None, :] == np.asarray(first)[:, None], -np.inf, floors)
    order = np.argsort(key, axis=1, kind="stable")
    done = np.zeros((n, m), dtype=bool)
    rows = np.arange(n)
    for number in range(m + 1):
        feasible = best.found & ~best.infeasible
        with np.errstate(invalid="ignore"):
            beaten = feasible[:, None] & (floors > best.value[:, None] * (1.0 + FLOOR_MARGIN))
        if number == 1 and rule_out is not None:  # ``done``: evaluated or ruled out
            motor, option = np.nonzero(feasible[:, None] & ~done & ~beaten)
            if len(motor):
                done[motor, option] |= rule_out(motor, option, best.value[motor])
        open_ = ~done & ~beaten
        # the next option per motor in floor order, or all those left (no feasible one yet)
        ordered = np.take_along_axis(open_, order, axis=1)
        has = ordered.any(axis=1)
        if not has.any():
            return
        nxt = order[rows, np.argmax(ordered, axis=1)]
        pick = np.zeros((n, m), dtype=bool)
        one = has & (feasible | ~done.any(axis=1))
        pick[rows[one], nxt[one]] = True
        pick |= open_ & (has & ~one)[:, None]
        motor, option = np.nonzero(pick)
        done |= pick
        consider(motor, option)


def _continuous(bounds, with_ratio, consider, best: _Best, motors: int) -> None:
    """Log-spaced lattice over the bounds, then halving steps around each motor's best.

    All points lie on one lattice in log(ratio), so each round evaluates every needed
    point once, for all the motors whose neighbourhood contains it. A point a motor had
    evaluated in an earlier round (its best's neighbours one old step away are the new
    round's outer offsets: the same ratio to the bit, lo + k step) is not evaluated
    again: it gives the same figures, and with its earlier, smaller rank it could not
    replace the best kept on a tie either.
    """
    lo, hi = math.log(bounds[0]), math.log(bounds[1])
    coarse_step = (hi - lo) / (COARSE - 1)
    xs = np.linspace(lo, hi, COARSE)
    points = [with_ratio(math.exp(x)) for x in xs]
    consider(points, [None] * COARSE, np.repeat(np.arange(motors), COARSE),
             np.tile(np.arange(COARSE), motors))
    steps, step = [], coarse_step  # the halving rounds' spacings, each half the one before
    while step > LOG_STEP:
        step /= 2.0
        steps.append(step)
    finest = (COARSE - 1) << len(steps)  # the last index on the finest lattice
    # every (motor, point) evaluated, as motor * (finest + 1) + index on the finest
    # lattice; a coarse point counts only where linspace put it at lo + k step exactly
    coarse = np.flatnonzero(xs == lo + np.arange(COARSE) * coarse_step)
    seen = (np.arange(motors)[:, None] * (finest + 1)
            + (coarse << len(steps))[None, :]).ravel()
    offsets = np.array([-2, -1, 1, 2])
    for done, step in enumerate(steps, start=1):
        last, finer = (COARSE - 1) << done, len(steps) - done  # halvings still to come
        centre = np.rint((np.log(best.stage_ratio) - lo) / step).astype(np.intp)
        keys = centre[:, None] + offsets[None, :]
        every = np.broadcast_to(np.arange(motors)[:, None], keys.shape)
        at = every * (finest + 1) + (keys << finer)
        valid = (keys >= 0) & (keys <= last) & ~np.isin(at, seen)
        if not valid.any():  # every neighbour evaluated already
            continue
        seen = np.union1d(seen, at[valid])
        unique, option = np.unique(keys[valid], return_inverse=True)
        points = [with_ratio(math.exp(lo + int(k) * step)) for k in unique]
        consider(points, [None] * len(points), every[valid], option.reshape(-1))


class SharedByLaws:
    """What every law of one sizing of a free stage shares, each part built on first use:
    every motor with every listed option (sizer.sizing.choices.listed_pairs) and
    their peak scales (sizer.sizing.shortest_duration.peak_scales)."""

    def __init__(self, design: Design, motors: MotorArrays) -> None:
        self.design, self.motors = design, motors

    @cached_property
    def pairs(self) -> ListedPairs:

        return listed_pairs(self.design, self.motors)

    @cached_property
    def scales(self) -> PeakScales:
        from sizer.sizing.shortest_duration import peak_scales

        assert self.pairs.candidates is not None  # asked for the listed pairs' floors only
        return peak_scales(self.design, self.pairs.candidates)
