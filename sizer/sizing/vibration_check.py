"""The residual vibration of a design's moves (book sec. 7.2), as a check.

A design with ``load.natural_frequency`` has each move's residual vibration computed: the
amplitude of the load's free vibration (sec. 7.1.1, eq. 7.2) at the end of the move, in
the machine's steady state, where the cycle repeats and what one move leaves is carried
through the dwells into the next (sizer.vibration.modal_state; exact). An undamped mode
has no steady state: its cycle is then run once from rest. The check's value is the
largest over the moves; ``limits.residual_vibration`` bounds it.

The residual depends on the law and the durations only, not on the motor, so in minimize
mode the admissible scales are found on one grid for every candidate
(:func:`admissible_scale`); as a later limit of the search for the shortest duration
(:class:`ResidualLimit`, sizer.sizing.shortest_duration.settle) it moves each candidate's
T_min up to the first scale where the limit holds.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Protocol, runtime_checkable

import numpy as np

from sizer.errors import UserError
from sizer.laws.base import MotionLaw
from sizer.laws.per_move import RankedLaw
from sizer.model.cycle import from_task
from sizer.model.domain import Design
from sizer.numerics.roots import bracketed_root
from sizer.sizing.checks import RESIDUAL_VIBRATION
from sizer.sizing.cycle import cycle_laws
from sizer.sizing.evaluation import CycleMetrics, CycleModel
from sizer.sizing.results import RESIDUAL
from sizer.sizing.shortest_duration import LaterChecks
from sizer.vibration.elastic_load import ElasticLoad

if TYPE_CHECKING:
    from sizer.vibration.cycle_residual import CycleVibration

GRID_PER_PERIOD = 16
"""Samples per damped period of the search for the admissible durations."""

WINDOW_PERIODS = 8
"""Periods of the mode past the largest T_min that the first search window covers; each
next window is four times the last."""

SEARCH_PERIODS = 2000
"""How far past the largest T_min (in periods) the search looks before it gives up."""


def refusal(design: Design) -> str | None:
    """Why the design's residual vibration is not computed, or None."""
    if design.transmission.linkage is not None:
        return "a linkage's output does not follow the law (the ratio varies)"
    return None


def cycle_vibration(design: Design, law: RankedLaw, sweep: bool = False
                    ) -> CycleVibration | None:
    """The residual vibration of the design's cycle with this law, or None without a mode.

    With ``sweep`` the task shorthand's moves take the scale as their duration even where
    the design fixes it (``sizer vibration`` varies it). UserError where the design asks
    for it and it is not computed (:func:`refusal`)."""
    elastic = design.load.elastic
    if elastic is None:
        return None
    why = refusal(design)
    if why is not None:
        raise UserError(f"the residual vibration is not computed for {why}; remove "
                        "load.natural_frequency", field="load.natural_frequency")
    cycle, task = design.machine_cycle, design.machine_cycle.shorthand
    if sweep and task is not None:  # written as a task: its moves take the scale
        cycle = from_task(replace(task, duration=None))
    elif sweep and not cycle.free:
        raise UserError("no segment of the cycle has a free duration to sweep",
                        field="cycle")
    from sizer.vibration.cycle_residual import CycleVibration  # lazy: a mode's only

    return CycleVibration(elastic, cycle, cycle_laws(cycle, law))


@dataclass(frozen=True)
class ResidualLimit:
    """The residual vibration as a later limit of the search for the shortest duration
    (sizer.sizing.shortest_duration.LaterLimit): its figure always, its check where the
    design gives a limit. The residual depends on the law and the scale only."""

    vibration: CycleVibration
    limit: float | None
    linear: bool
    modes: tuple[CycleVibration, ...] = ()
    """Each build's where the candidates' builds change the mode (their ``mode`` indexes
    it: sizer.sizing.candidates.Builds); else the design's :attr:`vibration` for all."""

    def _groups(self, calculator: CycleModel, rows: np.ndarray | None = None
                ) -> list[tuple[CycleVibration, np.ndarray | None]]:
        """(vibration, the candidates of ``rows`` (default: all) it holds for; None: all)."""
        builds = calculator.motors.builds
        if not self.modes or builds is None or builds.mode is None:
            return [(self.vibration, None)]
        mode = builds.mode if rows is None else builds.mode[rows]
        return [(v, np.flatnonzero(mode == k)) for k, v in enumerate(self.modes)]

    def at(self, calculator: CycleModel, s: np.ndarray, metrics: CycleMetrics,
           known: np.ndarray) -> LaterChecks:
        return self.checks(self.worst(calculator, np.where(known, s, 1.0)), known)

    def worst(self, calculator: CycleModel, at: np.ndarray) -> np.ndarray:
        """The largest residual over the moves of each candidate at scales ``at``."""
        own = own_durations(calculator, at)
        worst = np.empty(np.shape(at))
        for vibration, index in self._groups(calculator):
            if index is None:
                worst = vibration.worst(at, own)
            elif index.size:
                worst[index] = vibration.worst(at[index], None if own is None
                                               else [d[index] for d in own])
        return worst

    def checks(self, worst: np.ndarray, known: np.ndarray) -> LaterChecks:
        """The figure, and the check against the limit, of the residuals ``worst`` where
        ``known`` (elsewhere the figure is NaN and the check passes)."""
        figures = {RESIDUAL: np.where(known, worst, np.nan)}
        if self.limit is None:
            return LaterChecks([], np.ones(len(known), dtype=bool), figures)
        check = RESIDUAL_VIBRATION.arrays(np.where(known, worst, 0.0),
                                          np.full(np.shape(worst), self.limit), 0.0,
                                          linear=self.linear)
        return LaterChecks([check], check.passed, figures)

    def passing_scale(self, calculator: CycleModel, rows: np.ndarray, s: np.ndarray,
                      found: LaterChecks) -> np.ndarray:
        assert self.limit is not None, "a check fails only against a limit"
        out = np.empty(np.shape(s))
        for vibration, index in self._groups(calculator, rows):
            if index is None:
                return admissible_scale(vibration, s, self.limit)
            if index.size:
                out[index] = admissible_scale(vibration, s[index], self.limit)
        return out


@runtime_checkable
class RowsByLaw(Protocol):
    """A model whose rows may each move with their own law (sizer.laws.row_laws.RowLaws:
    sizer.sizing.move.CycleCalculator, sizer.sizing.cycle.SegmentCycle): its rows split
    law by law, each part the model of those rows with that law alone."""

    def by_law(self, rows: np.ndarray) -> Sequence[tuple[int, np.ndarray, CycleModel]]: ...


def _by_law(calculator: CycleModel) -> RowsByLaw:
    """``calculator`` as a model of rows by law (:class:`RowsByLaw`)."""
    if not isinstance(calculator, RowsByLaw):
        raise TypeError(f"{type(calculator).__name__} has no rows by law")
    return calculator


@dataclass(frozen=True)
class ResidualRows:
    """The residual limits of several laws as one later limit over the rows of a model
    of their laws (:class:`RowsByLaw`): the rows of law k read ``limits[k]`` (its law's
    residual at their scales, with the model of those rows and that law: ``by_law``), so
    every row's figure, check and passing scale are those its law gives alone. The limits
    share the design's limit."""

    limits: tuple[ResidualLimit, ...]

    def at(self, calculator: CycleModel, s: np.ndarray, metrics: CycleMetrics,
           known: np.ndarray) -> LaterChecks:
        at = np.where(known, s, 1.0)
        worst = np.empty(np.shape(at))
        for k, rows, part in _by_law(calculator).by_law(np.arange(len(at))):
            worst[rows] = self.limits[k].worst(part, at[rows])
        return self.limits[0].checks(worst, known)

    def passing_scale(self, calculator: CycleModel, rows: np.ndarray, s: np.ndarray,
                      found: LaterChecks) -> np.ndarray:
        out = np.empty(np.shape(s))
        for k, at, part in _by_law(calculator).by_law(np.asarray(rows, dtype=np.intp)):
            out[at] = self.limits[k].passing_scale(part, np.arange(len(at)), s[at], found)
        return out


def own_durations(calculator: CycleModel, s: np.ndarray) -> list[np.ndarray] | None:
    """Each segment's durations at the scales s where the candidates split the cycle time
    each their own way (``share: {optimize: ...}``: SegmentCycle.split), else None (the
    cycle's rule, the same for all: CycleVibration.durations)."""
    if getattr(calculator, "split", None) is None:
        return None
    durations: list[np.ndarray] = calculator.durations(s)  # type: ignore[attr-defined]
    return durations


def residual_limit(design: Design, law: RankedLaw,
                   modes: tuple[ElasticLoad | None, ...] = ()) -> ResidualLimit | None:
    """The design's residual vibration with this law as a later limit, or None without a
    mode of the load (UserError where the design limits it all the same: a limit is never
    skipped; sizer.io refuses it at its line). ``modes``: the modes of the candidates'
    builds (sizer.sizing.candidates.Builds), each candidate's residual by its own."""
    vibration = cycle_vibration(design, law)
    if vibration is None:
        if design.limits.residual_vibration is not None:
            raise UserError("a residual_vibration limit needs the load's mode: give "
                            "load.natural_frequency (and damping_ratio)",
                            field="limits.residual_vibration")
        return None
    per_mode = tuple(cycle_vibration(replace(design, load=replace(design.load, elastic=m)),
                                     law) for m in modes)
    if any(v is None for v in per_mode):
        raise ValueError("every build of a load with a mode has one")
    return ResidualLimit(vibration, design.limits.residual_vibration,
                         design.machine_cycle.linear,
                         tuple(v for v in per_mode if v is not None))


def admissible_scale(vibration: CycleVibration, s: np.ndarray, limit: float) -> np.ndarray:
    """Per candidate, the smallest scale >= s at which every move's residual is within the
    limit (to the checks' tolerance); inf where none is found within SEARCH_PERIODS
    periods. Found on one grid for all candidates (the residual does not depend on the
    motor), each crossing refined by bisection."""
    s = np.asarray(s, dtype=float)
    out = np.full(s.shape, np.inf)
    finite = np.isfinite(s)
    if not finite.any():
        return out
    ok_now = vibration.worst(np.where(finite, s, 1.0)) <= limit * (1.0 + 1e-9)
    out[finite & ok_now] = s[finite & ok_now]
    todo = finite & ~ok_now
    if not todo.any():
        return out
    # the scale's period: the moves' durations grow with s at the rate of their weights
    rate = max(max(vibration.cycle.weights()), 1e-300)
    period = vibration.load.damped_period / rate
    step = period / GRID_PER_PERIOD
    index = np.flatnonzero(todo)
    begin, reach = float(s[index].min()), float(s[index].max()) + WINDOW_PERIODS * period
    while index.size and reach <= float(s[todo].max()) + SEARCH_PERIODS * period:
        grid = np.arange(begin, reach + step, step)
        start = np.searchsorted(grid, s[index], side="left")
        good = _good_points(vibration, grid, start, limit)
        # the first good grid point at or after each candidate's s, the crossing before it
        pick = np.searchsorted(good, start)
        found = pick < good.size
        if found.any():
            j = good[pick[found]]
            left = np.maximum(grid[np.maximum(j - 1, 0)], s[index[found]])
            out[index[found]] = _crossing(vibration, left, grid[j], limit)
        index = index[~found]
        begin, reach = reach, reach + 4.0 * (reach - begin)
    return out


def _good_points(vibration: CycleVibration, grid: np.ndarray, start: np.ndarray,
                 limit: float) -> np.ndarray:
    """The indices of the grid's points whose worst residual is within the limit, in
    order, from its first point up to the first good point at or after each index of
    ``start`` (or all of them): the grid evaluated in runs from WINDOW_PERIODS periods'
    points up, each twice the last, that stop once every start has its good point (each
    point's residual is its own, so the first good points are those of the whole grid;
    the far points of a window, whose residuals cost the most, are mostly not needed)."""
    size = WINDOW_PERIODS * GRID_PER_PERIOD
    found: list[np.ndarray] = []
    done = 0
    while done < grid.size:
        stop = min(grid.size, done + size)
        found.append(done + np.flatnonzero(vibration.worst(grid[done:stop])
                                           <= limit * (1.0 - 1e-12)))
        done, size = stop, 2 * size
        good = np.concatenate(found)
        if np.all(np.searchsorted(good, start) < good.size):
            break
    return np.concatenate(found)


def _crossing(vibration: CycleVibration, left: np.ndarray, right: np.ndarray,
              limit: float) -> np.ndarray:
    """The first scale in (left, right] where the worst residual meets the limit, right
    meeting it: the project's root finder on residual - limit to an ulp or so (the
    residual is smooth within a grid step), the end that meets the limit returned; left
    itself where it meets it already."""
    def excess(x: np.ndarray) -> np.ndarray:
        return vibration.worst(x) - limit

    f_left, f_right = excess(left), excess(right)
    out = np.where(f_left <= 0.0, left, right)
    open_ = (f_left > 0.0) & (f_right < 0.0)
    if open_.any():
        index = np.flatnonzero(open_)
        _, hi = bracketed_root(lambda x, where: excess(x), left[index], right[index],
                               f_left[index], f_right[index], xtol=4e-16,
                               args=(index,), bracket=True)
        out[index] = hi
    return out


@dataclass(frozen=True)
class VibrationSweep:
    """Each law's worst residual vibration over a range of scales (``sizer vibration``):
    the move duration T for the task shorthand, the scale of the free durations for a
    cycle. ``residual[k]`` is law k's, in m or rad at the load."""

    scales: np.ndarray
    laws: tuple[MotionLaw, ...]
    residual: tuple[np.ndarray, ...]
    limit: float | None
    tracking: tuple[np.ndarray, ...] | None = None
    """The task's peak tracking error |x - y| during its move, started at rest (sec. 7.2),
    per law (m or rad); None for a cycle."""


def vibration_sweep(design: Design, laws: tuple[MotionLaw, ...], scales: np.ndarray,
                    progress: Callable[[int, int], None] | None = None,
                    steps: int = 1) -> VibrationSweep:
    """The residual vibration of each law at every scale (UserError without a mode).

    With ``steps`` > 1 each law's scales are evaluated in that many runs, ``progress(done,
    total)`` called with (0, total) and after each (a progress bar with an estimate): the
    residual at a scale depends on that scale only, so the numbers are the one run's."""
    from sizer.vibration.response import tracking_error

    scales = np.asarray(scales, dtype=float)
    pieces = [p for p in np.array_split(scales, max(1, min(steps, scales.size))) if p.size]
    pieces = pieces or [scales]
    total = len(laws) * len(pieces)
    if progress is not None:
        progress(0, total)
    out, tracking, task = [], [], design.machine_cycle.shorthand
    for k, law in enumerate(laws):
        vibration = cycle_vibration(design, law, sweep=True)
        if vibration is None:
            raise UserError("the design gives no mode of the load: add "
                            "load.natural_frequency (and damping_ratio)",
                            field="load.natural_frequency")
        worst, track = [], []
        for j, piece in enumerate(pieces, start=1):
            worst.append(vibration.worst(piece))
            if task is not None:
                mode = vibration.load
                track.append(abs(task.displacement) * tracking_error(
                    law, mode.natural_frequency * piece, mode.damping_ratio))
            if progress is not None:
                progress(k * len(pieces) + j, total)
        out.append(np.concatenate(worst))
        if task is not None:
            tracking.append(np.concatenate(track))
    return VibrationSweep(scales, laws, tuple(out), design.limits.residual_vibration,
                          tuple(tracking) if task is not None else None)
