"""Segment by segment: what each part of a machine cycle asks of one motor (issue 12).

For a sizing result (a motor, a law, a transmission, a duration) the cycle's segments
(sizer.model.cycle; the task shorthand expanded) with their start and end times, peak
torque, RMS torque over the segment and share of the cycle's squared RMS, peak motor
speed and work at the motor shaft; and where the acceleration steps at the join with
the previous segment (a jerk impulse). Plain data for the reports.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from sizer.laws import MotionLaw, make_law
from sizer.mechanics import Drive
from sizer.model.cycle import Cycle, Dwell, Move, Run, from_task
from sizer.model.domain import Design, Motor, Transmission
from sizer.sizing.cycle_shape import plain_design
from sizer.sizing.motors import MotorArrays
from sizer.sizing.segment_cycle import JOIN_TOLERANCE, SegmentCycle, normalized_move


@dataclass(frozen=True)
class SegmentRow:
    """One segment of the cycle for one motor (SI: s, N*m, rad/s, J)."""

    name: str
    kind: str
    law: str | None
    start: float
    end: float
    peak_torque: float
    rms_torque: float
    rms_share: float
    """This segment's part of the cycle's integral of tau^2 (the shares sum to 1)."""
    peak_speed: float
    energy: float
    """Work at the motor shaft, the integral of tau*omega: > 0 driving, < 0 braking."""
    acceleration_step: float
    """The load's acceleration just after the join with the previous segment minus just
    before it (rad/s^2 or m/s^2): nonzero is a jerk impulse."""


@dataclass(frozen=True)
class SegmentBreakdown:
    motor: str
    law: str
    cycle_time: float
    rms_torque: float
    rows: tuple[SegmentRow, ...]


def design_cycle(design: Design) -> Cycle:
    """The design's cycle, the task shorthand expanded."""
    return design.cycle if design.cycle is not None else from_task(design.task)


def scale_of(design: Design, duration: float) -> float:
    """The scale s of the free durations of a result's ``duration`` (the move duration T
    for the task shorthand, the cycle time for a cycle)."""
    cycle = design_cycle(design)
    if plain_design(design).cycle is None:  # sized as the task: the duration is T
        return duration
    weights = math.fsum(cycle.weights())
    return 1.0 if weights == 0.0 else (duration - cycle.fixed_time) / weights


def result_cycle(design: Design, motor: Motor, law: MotionLaw, duration: float,
                 transmission: Transmission | None = None) -> tuple[SegmentCycle, np.ndarray]:
    """The segment calculator of a sizing result's motor, law and transmission, and the
    scale s of its ``duration``."""
    motors = MotorArrays.of([motor], design.limits.envelope)
    drive = Drive(design.load, transmission or design.transmission)
    calc = SegmentCycle(design_cycle(design), law, drive, motors, design.limits.thermal_speed)
    return calc, np.array([scale_of(design, duration)])


def segment_breakdown(design: Design, motor: Motor, law: MotionLaw | str, duration: float,
                      transmission: Transmission | None = None) -> SegmentBreakdown:
    """The segments of ``design``'s cycle for ``motor`` with ``law`` (the ranked law of
    the moves that name none) at a result's ``duration``."""
    if isinstance(law, str):
        law = make_law(law)
    if design.transmission.linkage is not None:
        from sizer.sizing.linkage_sizing import linkage_breakdown

        return linkage_breakdown(design, motor, law, duration, transmission)
    calc, s = result_cycle(design, motor, law, duration, transmission)
    cycle = calc.cycle
    parts = calc.figures(s)
    metrics = calc.evaluate(s)
    total = math.fsum(float(p.torque_square[0]) for p in parts)
    reference = max((abs(seg.displacement) / float(p.duration[0]) ** 2
                     for seg, p in zip(cycle.segments, parts, strict=True)
                     if isinstance(seg, Move)), default=0.0)
    rows, start, before = [], 0.0, 0.0
    for segment, own, figures in zip(cycle.segments, calc.laws, parts, strict=True):
        T = float(figures.duration[0])
        first, last = end_accelerations(segment, own, T)
        step = first - before
        rows.append(SegmentRow(
            name=segment.name or _kind(segment), kind=_kind(segment),
            law=own.spec if own is not None else None, start=start, end=start + T,
            peak_torque=float(figures.peak_torque[0]),
            rms_torque=math.sqrt(float(figures.torque_square[0]) / T) if T > 0 else 0.0,
            rms_share=float(figures.torque_square[0]) / total if total > 0 else 0.0,
            peak_speed=float(figures.max_speed[0]), energy=float(figures.energy[0]),
            acceleration_step=step if abs(step) > JOIN_TOLERANCE * reference else 0.0))
        start += T
        before = last
    return SegmentBreakdown(motor.id, law.spec, float(metrics.duration[0]),
                            float(metrics.rms_torque[0]), tuple(rows))


def end_accelerations(segment, law: MotionLaw | None, T: float) -> tuple[float, float]:
    """The load's acceleration at the start and at the end of a segment."""
    if not isinstance(segment, Move) or law is None:
        return 0.0, 0.0
    h = segment.displacement
    if segment.rest_to_rest:
        a0 = float(law.piece_derivative(0, 0.0, 2))
        a1 = float(law.piece_derivative(len(law.pieces) - 1, 1.0, 2))
        return h * a0 / T / T, h * a1 / T / T
    from sizer.laws.boundary_speeds import boundary_form

    basis = boundary_form(law.spec)
    assert basis is not None
    c = normalized_move(basis, segment, np.array([T]))[0]
    width = basis.breaks[-1] - basis.breaks[-2]
    powers = np.arange(c.shape[1])
    end = float(np.sum(c[-1, 2:] * powers[2:] * (powers[2:] - 1) * width ** (powers[2:] - 2)))
    return h * 2.0 * float(c[0, 2]) / T / T, h * end / T / T


def _kind(segment) -> str:
    return "move" if isinstance(segment, Move) else "run" if isinstance(segment, Run) \
        else "dwell" if isinstance(segment, Dwell) else type(segment).__name__.lower()
