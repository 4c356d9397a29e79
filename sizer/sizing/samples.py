"""One machine cycle sampled in time, for every candidate at once, and its slices.

The design's cycle (the task shorthand: move, dwell and with ``return_move`` the move back
and a dwell, book sec. 6.1.1; a cycle of segments; either through a linkage) is sampled by
its cycle model piece after piece (sizer.sizing.evaluation.CycleModel.pieces), each
candidate in its own duration: a law move on its normalized grid (both ends of every
piece, so a step of the acceleration is a repeated time: a jump) scaled by its duration,
a move through a linkage on its profile's uniform grid, a dwell holding its load. The
motor torque is the engine's (the rotor, damping, the transmission with its efficiencies
in the direction of power flow, the load).

Its slices: :func:`sampled` (every candidate's torque and speed, the inputs of
sizer.energy and sizer.thermal); :func:`task_curve` (one candidate's curves, the
speed-torque plane of Fig. 6.2 with the RMS point of Fig. 6.3, for plots and reports);
:func:`linkage_curve_of` (the ratio-and-torque plot). :func:`segment_breakdown` gives the
cycle segment by segment from the model's per-segment figures (issue 12). None of them
asks which model it holds.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from sizer.envelope import continuous_region, intermittent_region
from sizer.errors import UserError
from sizer.laws import MotionLaw, make_law
from sizer.laws.per_move import RankedLaw, one_law
from sizer.mechanics import Drive
from sizer.model.cycle import shorthand_task
from sizer.model.domain import Curve, Design, Motor, Transmission
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.cycle import JOIN_TOLERANCE, SegmentCycle
from sizer.sizing.evaluation import (
    SAMPLES,
    CycleMetrics,
    CycleModel,
    CyclePiece,
    SegmentedModel,
)
from sizer.sizing.move import CycleCalculator

if TYPE_CHECKING:
    from sizer.sizing.linkage_move import PositionCalculator, PositionCycle

CURVE_SAMPLES = 401
"""Samples per move of one candidate's curves (SAMPLES: for energy and heat)."""
FIGURES = ("duration", "peak_torque", "square", "max_speed", "energy", "start_acceleration",
           "end_acceleration")
"""The per-segment figures a breakdown row is made of."""


@dataclass(frozen=True)
class CycleSamples:
    """(candidates, samples) arrays over one machine cycle: times (s, non-decreasing, a
    repeated time is a jump), motor torque (N*m, signed like the motion) and motor speed
    (rad/s); ``cycle_time`` (s) per candidate."""

    time: np.ndarray
    torque: np.ndarray
    speed: np.ndarray
    cycle_time: np.ndarray


def _joined(pieces: list[CyclePiece], key: str, row: int | None = None) -> np.ndarray:
    """One series of the cycle, all candidates or one ``row``."""
    values = [getattr(p, key) for p in pieces]
    if row is None:
        return np.concatenate(values, axis=1)
    return np.concatenate([x if x.ndim == 1 else x[row] for x in values])


def refuse_unsupported(design: Design) -> None:
    """A UserError for what :func:`cycle_samples` does not sample: a cycle of segments, a
    linkage (both: :func:`sampled` with their calculator)."""
    if design.machine_cycle.shorthand is None:
        raise UserError("a cycle of segments is sampled by sizer.sizing.samples.sampled",
                        field="cycle")
    if design.transmission.linkage is not None:
        raise UserError("a linkage is sampled by sizer.sizing.samples.sampled",
                        field="transmission")


def cycle_samples(design: Design, calculator: CycleCalculator, duration: np.ndarray,
                  samples: int = SAMPLES) -> CycleSamples:
    """The motor torque and speed of every candidate of ``calculator`` over one machine
    cycle of the task shorthand, each candidate moving in its own ``duration`` T (s)."""
    refuse_unsupported(design)
    T = np.broadcast_to(np.asarray(duration, dtype=float), (len(calculator.motors),))
    if not np.all(np.isfinite(T) & (T > 0.0)):
        raise UserError("the cycle is sampled only at finite positive durations",
                        field="task.duration")
    return sampled(calculator, T, samples)


def sampled(calculator: CycleModel, T: np.ndarray, samples: int | None = None
            ) -> CycleSamples:
    """One machine cycle per candidate of any cycle model at its durations or scales T
    (its pieces: sizer.sizing.evaluation.CycleModel.pieces), ``samples`` per move (None:
    the model's own for energy and heat)."""
    s = np.broadcast_to(np.asarray(T, dtype=float), (len(calculator.motors),))
    pieces = calculator.pieces(s, samples)
    time = _joined(pieces, "time")
    return CycleSamples(time, _joined(pieces, "torque"), _joined(pieces, "motor_speed"),
                        time[:, -1])


def segment_samples(calculator: SegmentCycle, scale: np.ndarray,
                    samples: int = SAMPLES) -> CycleSamples:
    """The same for a cycle of segments at the candidates' scales s."""
    return sampled(calculator, scale, samples)


@dataclass(frozen=True)
class TaskCurve:
    """One machine cycle sampled in time (SI), with the RMS point and the motor's regions."""

    motor: str
    law: str
    duration: float
    ratio: float
    time: np.ndarray
    position: np.ndarray
    load_speed: np.ndarray
    load_acceleration: np.ndarray
    motor_speed: np.ndarray
    motor_acceleration: np.ndarray
    motor_torque: np.ndarray
    rms_torque: float
    thermal_speed: float
    peak_torque: float
    max_speed: float
    continuous_region: Curve
    intermittent_region: Curve
    total_inertia: float
    """J_t at the motor shaft (rotor + transmission + load/K^2), for the speed-acceleration
    plane of Fig. 6.7, where each region's torque becomes an acceleration tau/J_t."""
    segments: tuple[tuple[str, float, float], ...] = ()
    """(name, start, end) of each segment of the cycle, s: the plots mark them."""

    @property
    def acceleration_regions(self) -> tuple[Curve, Curve]:
        """(continuous, intermittent) regions divided by J_t: Fig. 6.7 (b)."""
        def scaled(curve: Curve) -> Curve:
            return tuple((speed, torque / self.total_inertia) for speed, torque in curve)
        return scaled(self.continuous_region), scaled(self.intermittent_region)


def scale_of(design: Design, duration: float) -> float:
    """The scale s of the free durations of a result's ``duration`` (the move duration T
    for the task shorthand, the cycle time for a cycle)."""
    cycle = design.machine_cycle
    if shorthand_task(cycle) is not None:  # sized as the task: the duration is T
        return duration
    weights = math.fsum(cycle.weights())
    return 1.0 if weights == 0.0 else (duration - cycle.fixed_time) / weights


def _result(design: Design, motor: Motor, law: RankedLaw,
            transmission: Transmission | None) -> CycleModel:
    """The cycle model of a sizing result's motor, law and transmission."""
    task = shorthand_task(design.machine_cycle)
    if task is None or design.transmission.linkage is not None:
        return _segmented(design, motor, law, transmission)
    if design.load.position_dependent:  # a load of the position
        return _position(design, motor, one_law(law), transmission)
    return CycleCalculator(None, task, Drive(design.load, transmission or design.transmission),
                           MotorArrays.of([motor], design.limits.envelope),
                           design.limits.thermal_speed, law=one_law(law))


def _segmented(design: Design, motor: Motor, law: RankedLaw,
               transmission: Transmission | None) -> SegmentedModel:
    """The same as a cycle of segments (the task shorthand as the cycle it means)."""
    if design.transmission.linkage is not None:
        from sizer.sizing.linkage_move import result_calculator  # lazy: start-up

        return result_calculator(design, motor, one_law(law), transmission)
    if design.load.position_dependent:  # a load of the position
        return _position(design, motor, one_law(law), transmission)
    return SegmentCycle(design.machine_cycle, law,
                        Drive(design.load, transmission or design.transmission),
                        MotorArrays.of([motor], design.limits.envelope),
                        design.limits.thermal_speed)


def pair_durations(design: Design, motor: Motor, law: RankedLaw, duration: float,
                   transmission: Transmission | None = None) -> list[float]:
    """Each segment's duration (s) of a cycle of segments as the sizing gave it to this
    motor, law and transmission at its reported cycle time ``duration``: its own split
    where the cycle's share is chosen per motor (SegmentCycle.split)."""
    model = _segmented(design, motor, law, transmission)
    assert isinstance(model, SegmentCycle), "a cycle of segments without a linkage"
    return [float(T[0]) for T in model.durations(np.array([scale_of(design, duration)]))]


def _position(design: Design, motor: Motor, law: MotionLaw,
              transmission: Transmission | None) -> PositionCalculator | PositionCycle:
    """The cycle against loads of the position: one move and its dwell, a task with its
    return, a cycle of segments (sizer.sizing.linkage_move.position_model)."""
    from sizer.sizing.linkage_move import position_model  # lazy: start-up

    return position_model(design.machine_cycle, law, design.load,
                          Drive(design.load, transmission or design.transmission),
                          MotorArrays.of([motor], design.limits.envelope),
                          design.limits.thermal_speed)


def _one_linkage_move(design: Design) -> bool:
    """A move through a linkage with its dwell (no return): drawn as one move, its
    curves unmarked, its ratio-and-torque plot on the profile's whole grid."""
    task = shorthand_task(design.machine_cycle)
    return design.transmission.linkage is not None and task is not None \
        and not task.return_move


def task_curve(design: Design, motor: Motor, law: RankedLaw | str, duration: float,
               transmission: Transmission | None = None,
               samples: int = CURVE_SAMPLES) -> TaskCurve:
    """Sample the cycle of ``law`` in ``duration`` for ``motor`` (samples per move).

    Pass the law and duration of a sizing result (its ``spec`` and ``duration``) and,
    when the ratio was chosen by the solver, the transmission with that ratio.
    """
    law = make_law(law) if isinstance(law, str) else law
    calc, s, pieces = _curve_pieces(design, motor, law, duration, transmission, samples)
    segments = () if _one_linkage_move(design) else tuple(
        (p.name, float(p.time[0, 0]), float(p.time[0, -1])) for p in pieces)
    metrics: CycleMetrics = calc.evaluate(s)
    return TaskCurve(
        motor=motor.id, law=law.spec, duration=duration, ratio=float(calc.drive.ratio[0]),
        time=_joined(pieces, "time", 0), position=_joined(pieces, "position", 0),
        load_speed=_joined(pieces, "load_speed", 0),
        load_acceleration=_joined(pieces, "load_acceleration", 0),
        motor_speed=_joined(pieces, "motor_speed", 0),
        motor_acceleration=_joined(pieces, "motor_acceleration", 0),
        motor_torque=_joined(pieces, "torque", 0), rms_torque=float(metrics.rms_torque[0]),
        thermal_speed=float(metrics.thermal_speed[0]),
        peak_torque=float(metrics.peak_torque[0]), max_speed=float(metrics.max_speed[0]),
        continuous_region=continuous_region(motor, design.limits.envelope),
        intermittent_region=intermittent_region(motor, design.limits.envelope),
        total_inertia=motor.inertia + float(calc.drive.driven_inertia[0]), segments=segments)


def motor_trace(design: Design, motor: Motor, law: RankedLaw, duration: float,
                transmission: Transmission | None = None,
                samples: int = CURVE_SAMPLES) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(time, motor torque, motor speed) of :func:`task_curve`'s samples, without the
    figures it reports besides (the shared DC bus reads only these: sizer.sizing.machine)."""
    _, _, pieces = _curve_pieces(design, motor, law, duration, transmission, samples)
    return (_joined(pieces, "time", 0), _joined(pieces, "torque", 0),
            _joined(pieces, "motor_speed", 0))


def _curve_pieces(design: Design, motor: Motor, law: RankedLaw, duration: float,
                  transmission: Transmission | None, samples: int
                  ) -> tuple[CycleModel, np.ndarray, list[CyclePiece]]:
    """The cycle model of one result, its scale at ``duration`` and its sampled pieces."""
    calc = _result(design, motor, law, transmission)
    s = np.array([scale_of(design, duration)])
    return calc, s, calc.pieces(s, samples)


@dataclass(frozen=True)
class LinkageCurve:
    """One candidate through the linkage over the crank angle: the crank angle (rad,
    increasing or decreasing as the crank turns), the ratio ds/dtheta and the motor
    torque at the result's duration, and the linkage's dead points (name: angle)."""

    theta: np.ndarray
    ratio: np.ndarray
    motor_torque: np.ndarray
    dead_points: dict[str, float]
    linear: bool


def linkage_curve_of(design: Design, motor, law: RankedLaw, duration: float,
                     transmission=None) -> LinkageCurve:
    """The data of the ratio-and-torque plot of one result (sizer plot --linkage): the
    moves, one move on its profile's whole uniform grid, a cycle's on CURVE_SAMPLES."""
    stage = design.transmission.linkage
    assert stage is not None, "sizer plot --linkage asks for a linkage"
    from sizer.sizing.linkage_move import dead_points, result_calculator  # lazy: start-up

    calc = result_calculator(design, motor, one_law(law), transmission)
    s = np.array([scale_of(design, duration)])
    pieces = [p for p in calc.pieces(s, None if _one_linkage_move(design) else CURVE_SAMPLES)
              if p.ratio is not None]  # the moves
    return LinkageCurve(_joined(pieces, "theta", 0), _joined(pieces, "ratio", 0),
                        _joined(pieces, "torque", 0), dead_points(stage), stage.output_linear)


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


def segment_breakdown(design: Design, motor: Motor, law: RankedLaw | str,
                      duration: float,
                      transmission: Transmission | None = None) -> SegmentBreakdown:
    """What each segment of ``design``'s cycle asks of ``motor`` with ``law`` (the ranked
    law of the moves that name none) at a result's ``duration`` (issue 12): its start and
    end, peak torque, RMS torque and share of the cycle's squared RMS, peak motor speed,
    work at the motor shaft and the step of the acceleration at its join with the one
    before (a jerk impulse), from the engine's per-segment figures."""
    law = make_law(law) if isinstance(law, str) else law
    calc = _segmented(design, motor, law, transmission)
    s = np.array([scale_of(design, duration)])
    parts = calc.breakdown(s)
    figures = [{k: float(getattr(p, k)[0]) for k in FIGURES} for p in parts]
    reference = max((float(p.acceleration_scale[0]) for p in parts
                     if p.acceleration_scale is not None), default=0.0)
    metrics = calc.evaluate(s)
    total = math.fsum(f["square"] for f in figures)
    rows, start, before = [], 0.0, 0.0
    for p, f in zip(parts, figures, strict=True):
        T, square = f["duration"], f["square"]
        step = f["start_acceleration"] - before
        rows.append(SegmentRow(
            name=p.name, kind=p.kind, law=p.law.spec if p.law is not None else None,
            start=start, end=start + T, peak_torque=f["peak_torque"],
            rms_torque=math.sqrt(square / T) if T > 0 else 0.0,
            rms_share=square / total if total > 0 else 0.0, peak_speed=f["max_speed"],
            energy=f["energy"],
            acceleration_step=step if abs(step) > JOIN_TOLERANCE * reference else 0.0))
        start += T
        before = f["end_acceleration"]
    cycle_time = calc.cycle_time(s)
    return SegmentBreakdown(motor.id, law.spec, float(cycle_time[0]),
                            float(metrics.rms_torque[0]), tuple(rows))
