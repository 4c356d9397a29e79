"""Which ratio of the free transmission stage suits each motor and law best.

The options are a list of ratios, catalog gearboxes (each ratio with its own efficiency,
inertia and limits), or a continuous range searched on a logarithmic lattice refined
around each motor's best point down to 0.25 % steps. All options of a round are one flat
candidate axis (motors x options, sizer.sizing.candidates) evaluated together. Per motor
the best option is the feasible one with the shortest T_min (minimize mode) or the
smallest RMS torque (duration given); when none is feasible, the one closest to feasible
(the largest worst slack). Ties keep the first option (gearboxes, then the listed ratios,
then the lattice).

In minimize mode the listed options (gearboxes and ratios) are evaluated in rounds, each
motor's options in the order of their duration floors (sizer.sizing.duration_floor): an
option whose floor lies above the motor's best feasible T_min so far cannot beat it and
is not evaluated; after the first round, an option whose RMS check fails at every
duration up to that T_min (sizer.sizing.rms_fails_up_to: one evaluation
at it) neither. The choice is the one of evaluating every option.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from contextlib import nullcontext
from dataclasses import dataclass

import numpy as np

from sizer.model.domain import Design, Transmission
from sizer.sizing.candidates import Candidates
from sizer.sizing.energy_check import has_braking_check, has_heat_check, without_power_figures
from sizer.sizing.motors import MotorArrays
from sizer.sizing.table import CandidateTable, Mode, concatenate

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
    place: dict[tuple[str | None, float], int] = {}
    for k, key in enumerate(keys):
        place.setdefault(key, k)
    names = np.array(table.gearboxes, dtype=object)[table.option]
    return np.array([place.get((name, float(ratio)), -1) for name, ratio in
                     zip(names, table.stage_ratio, strict=True)], dtype=np.intp)


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
    point once, for all the motors whose neighbourhood contains it.
    """
    lo, hi = math.log(bounds[0]), math.log(bounds[1])
    step = (hi - lo) / (COARSE - 1)
    points = [with_ratio(math.exp(x)) for x in np.linspace(lo, hi, COARSE)]
    consider(points, [None] * COARSE, np.repeat(np.arange(motors), COARSE),
             np.tile(np.arange(COARSE), motors))
    last = COARSE - 1
    offsets = np.array([-2, -1, 1, 2])
    while step > LOG_STEP:
        step /= 2.0
        last *= 2
        centre = np.rint((np.log(best.stage_ratio) - lo) / step).astype(np.intp)
        keys = centre[:, None] + offsets[None, :]
        valid = (keys >= 0) & (keys <= last)
        motor = np.broadcast_to(np.arange(motors)[:, None], keys.shape)[valid]
        unique, option = np.unique(keys[valid], return_inverse=True)
        points = [with_ratio(math.exp(lo + int(k) * step)) for k in unique]
        consider(points, [None] * len(points), motor, option.reshape(-1))
