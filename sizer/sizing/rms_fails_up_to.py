"""Is a candidate infeasible at every duration up to a given one, by its RMS check?

The ratio search (sizer.sizing.ratio_choice) asks it of a motor's other options at the
best T_min found: one evaluation without peaks, and for options that share the stretches
between power-flow reversals one evaluation per motor; for a cycle of segments one
evaluation of the cycle at the scale of that cycle time.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from sizer.laws import make_law
from sizer.model.domain import Design
from sizer.sizing.candidates import Candidates
from sizer.sizing.checks import TOLERANCE
from sizer.sizing.cycle import CycleCalculator, MoveScales, RmsModel

if TYPE_CHECKING:
    from sizer.sizing.segment_cycle import SegmentCycle

STEP = 1e-3
"""Relative step in T at which the RMS model tells which way the RMS check moves."""
FALL = 1e-5
"""Relative fall of RMS / limit over STEP that counts as falling: far above the model's
error there (second order: about 1e-3 STEP^2 on the laws tried) and rounding."""


def rms_fails_up_to(design: Design, spec: str, candidates: Candidates,
                    T: np.ndarray, group: np.ndarray | None = None) -> np.ndarray:
    """Per candidate: does the RMS check of ``spec`` fail at every duration up to its T?

    True where it fails at T beyond the tolerance and RMS / limit (the continuous limit at
    the thermal speed) falls as T grows there, by the cycle's RMS model (exact at T, its
    slope too: sizer.sizing.cycle.RmsModel). That ratio falls with T and may rise again
    past its minimum (friction and a constant load over a cycle with dwell), never the
    other way (the search for T_min rests on the same: sizer.sizing.minimum_duration), so
    it is higher still at every shorter duration.

    ``group`` (per candidate, e.g. its motor): candidates of a group share their T; where
    the transmission options differ only upstream of every power-flow reversal (each
    stage's output torque the same function for all: one stage, or the free ratio
    nearest the motor), they share the stretches between reversals too, and one
    evaluation per group gives every member's RMS model (:func:`_shared_models`)."""
    from sizer.sizing.engine import chunk_size  # the engine imports this module lazily

    law = make_law(spec)
    if design.cycle is not None:
        return _cycle_fails_up_to(design, law, candidates, T)
    size = chunk_size(law, 2 if design.task.return_move else 1)
    out = np.zeros(len(candidates), dtype=bool)
    if group is not None and len(candidates):
        groups = np.unique(group)
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
        calculator = CycleCalculator(None, design.task, part.drive, part.motors,
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
    from sizer.sizing.engine import chunk_size
    from sizer.sizing.segment_cycle import SegmentCycle  # only designs with a cycle need it

    cycle = design.cycle
    assert cycle is not None
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
    """Every candidate's RMS model at its T (sizer.sizing.cycle.RmsModel) from one
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
    n = len(candidates)
    calculator = CycleCalculator(None, design.task, drive, candidates.motors,
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
    return calculator, RmsModel(T.copy(), moves, design.task.dwell, hold)
