"""One machine cycle sampled in time, for every candidate at once, and its slices.

The design's cycle (the task shorthand: move, dwell and with ``return_move`` the move back
and a dwell, book sec. 6.1.1; a cycle of segments; either through a linkage) is sampled
piece after piece, each candidate in its own duration. A law move is sampled on its
normalized grid (both ends of every piece, so a step of the acceleration is a repeated
time: a jump), scaled by its duration T: time = t0 + T u, speed h v_N(u) / T, acceleration
h a_N(u) / T^2; a move with boundary speeds on its own polynomial per candidate
(sizer.laws.boundary_speeds); a run at its constant speed; a dwell holds its constant load.
A move through a linkage is read on its profile's uniform grid (sizer.sizing.linkage_move).
The motor torque is the engine's (the rotor, damping, the transmission with its
efficiencies in the direction of power flow, the load).

Its slices: :func:`cycle_samples` (every candidate's torque and speed, the inputs of
sizer.energy and sizer.thermal); :func:`task_curve` (one candidate's curves, the
speed-torque plane of Fig. 6.2 with the RMS point of Fig. 6.3, for plots and reports);
:func:`linkage_curve_of` (the ratio-and-torque plot). :func:`segment_breakdown` gives the
cycle segment by segment from the engine's per-segment figures (issue 12).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from sizer.envelope import continuous_region, intermittent_region
from sizer.errors import UserError
from sizer.laws import MotionLaw, make_law
from sizer.mechanics import Drive
from sizer.model.cycle import Dwell, Move, Run, from_task, shorthand_task
from sizer.model.domain import Curve, Design, Motor, Transmission
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.cycle import JOIN_TOLERANCE, SegmentCycle, normalized_move
from sizer.sizing.evaluation import CycleMetrics
from sizer.sizing.linkage_move import (
    HeldDwell,
    LinkageCalculator,
    LinkageCycle,
    LinkageProfile,
    dead_points,
    linkage_figures,
    linkage_parts,
    result_calculator,
)
from sizer.sizing.move import CycleCalculator, MoveScales

SAMPLES = 1001
"""Samples of the normalized law per move for energy and heat (spread over its pieces by
their lengths)."""
CURVE_SAMPLES = 401
"""The same for one candidate's curves."""
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


@dataclass(frozen=True)
class _Piece:
    """One segment of the sampled cycle: (candidates, samples) arrays, or (samples,) where
    the same for every candidate (the load's position); ``theta`` and ``ratio`` through a
    linkage only."""

    name: str
    time: np.ndarray
    position: np.ndarray
    load_speed: np.ndarray
    load_acceleration: np.ndarray
    motor_speed: np.ndarray
    motor_acceleration: np.ndarray
    torque: np.ndarray
    theta: np.ndarray | None = None
    ratio: np.ndarray | None = None


def law_samples(law: MotionLaw, samples: int = SAMPLES) -> tuple[np.ndarray, ...]:
    """u, q_N, v_N, a_N on [0, 1], piece by piece with both ends of each piece (book ch.
    2-3: the law's normalized form)."""
    parts: list[list[np.ndarray]] = [[], [], [], []]
    for index, piece in enumerate(law.pieces):
        u = np.linspace(piece.start, piece.end, max(2, round(samples * (piece.end -
                                                                         piece.start))))
        parts[0].append(u)
        for order in range(3):
            parts[order + 1].append(law.piece_derivative(index, u, order))
    return tuple(np.concatenate(p) for p in parts)


def signed_torque(drive: Drive, motors: MotorArrays, a: np.ndarray, v: np.ndarray,
                  rest_sign: float) -> np.ndarray:
    """The motor torque (signed like the motion) at the load's acceleration ``a`` and speed
    ``v`` (candidates, samples): s (J_m K a_l + B_m K v_l + shaft(a_l, v_l)) with
    (a_l, v_l) = s (a, v), s the sign of v (``rest_sign`` where v is 0) and shaft() the
    drive's chain with the efficiencies in the direction of power flow."""
    n = a.shape[0]
    K = np.broadcast_to(np.asarray(drive.ratio, dtype=float), (n,))[:, None]
    J = np.asarray(motors.inertia, dtype=float)[:, None]
    B = np.asarray(motors.damping, dtype=float)[:, None]
    sign = np.where(v > 0.0, 1.0, np.where(v < 0.0, -1.0, rest_sign))
    out = np.zeros_like(a)
    for s in (1.0, -1.0):
        if not (sign == s).any():
            continue
        shaft, _ = drive.chain(s * a, s * v, s)
        along = J * K * s * a + B * K * s * v + shaft
        out = np.where(sign == s, s * along, out)
    return out


def _held(name: str, start: np.ndarray, T: np.ndarray, position: float,
          torque: np.ndarray) -> _Piece:
    """A dwell of T (candidates, 1) from ``start`` holding ``torque`` (candidates,)."""
    zeros = np.zeros((len(start), 2))
    return _Piece(name, np.concatenate([start, start + T], axis=1), np.full(2, position),
                  zeros, zeros, zeros, zeros, np.repeat(np.asarray(torque)[:, None], 2, axis=1))


def _task_pieces(calc: CycleCalculator, T: np.ndarray, samples: int) -> list[_Piece]:
    """The task shorthand (sizer.sizing.move.CycleCalculator) at move durations T."""
    n = len(calc.motors)
    u, q_n, v_n, a_n = law_samples(calc.law, samples)
    h, Tc = calc.h, T[:, None]
    K = np.broadcast_to(np.asarray(calc.drive.ratio, dtype=float), (n,))[:, None]
    hold = np.broadcast_to(np.asarray(calc.drive.holding_torque, dtype=float), (n,))
    hold = hold * np.sign(calc.drive.load.torque)
    directions = iter(calc.directions)
    out, start, position = [], np.zeros((n, 1)), 0.0
    for segment in from_task(calc.task).segments:  # named move, dwell, return, dwell 2
        name = segment.name or ""
        if isinstance(segment, Dwell):
            out.append(_held(name, start, np.full((n, 1), calc.task.dwell), position, hold))
            start = start + calc.task.dwell
            continue
        direction = next(directions)
        torque, _ = calc.channels(a_n[None], v_n[None], MoveScales(h / T / T, h / T, direction))
        speed = direction * h * v_n[None] / Tc
        acceleration = direction * h * a_n[None] / Tc / Tc
        out.append(_Piece(name, start + Tc * u[None], position + direction * h * q_n, speed,
                          acceleration, K * speed, K * acceleration,
                          direction * np.broadcast_to(torque, (n, u.size))))
        start, position = start + Tc, position + direction * h
    return out


def _move_samples(move: Move, law: MotionLaw, T: np.ndarray, samples: int):
    """u (samples,), the load's position from the move's start (samples,) or (n, samples),
    speed and acceleration (n, samples) of a move in durations T: a move from rest on its
    law's grid, a move with boundary speeds on each candidate's own polynomial."""
    h, Tc = move.displacement, T[:, None]
    if move.rest_to_rest:
        u, q_n, v_n, a_n = law_samples(law, samples)
        return u, h * q_n, h * v_n[None] / Tc, h * a_n[None] / (Tc * Tc)
    from sizer.laws.boundary_speeds import boundary_form

    basis = boundary_form(law.spec)
    assert basis is not None, "sizer.io.cycle accepts only laws with a boundary form"
    c = normalized_move(basis, move, T)  # (n, P, d+1), ascending powers of u - break
    p = np.arange(c.shape[2])
    parts: list[list[np.ndarray]] = [[], [], [], []]
    for k in range(len(basis.breaks) - 1):
        lo, hi = float(basis.breaks[k]), float(basis.breaks[k + 1])
        u = np.linspace(lo, hi, max(2, round(samples * (hi - lo))))
        x = (u - lo)[:, None]
        dx = np.where(p >= 1, p * x ** np.maximum(p - 1, 0), 0.0)
        ddx = np.where(p >= 2, p * (p - 1) * x ** np.maximum(p - 2, 0), 0.0)
        for out, values in zip(parts, (u, c[:, k, :] @ (x ** p).T, c[:, k, :] @ dx.T,
                                       c[:, k, :] @ ddx.T), strict=True):
            out.append(values)
    u, q, v, a = (np.concatenate(x, axis=-1) for x in parts)
    return u, h * q, h * v / Tc, h * a / (Tc * Tc)


def _segment_pieces(calc: SegmentCycle, s: np.ndarray, samples: int) -> list[_Piece]:
    """A cycle of segments (sizer.sizing.segment_cycle.SegmentCycle) at scales s."""
    n = len(calc.motors)
    out, start, position = [], np.zeros((n, 1)), 0.0
    for segment, law, drive, T in zip(calc.cycle.segments, calc.laws, calc.drives,
                                      calc.durations(s), strict=True):
        K = np.broadcast_to(np.asarray(drive.ratio, dtype=float), (n,))[:, None]
        Tc = np.asarray(T, dtype=float)[:, None]
        name = segment.name or type(segment).__name__.lower()
        if isinstance(segment, Dwell):
            hold = np.broadcast_to(np.asarray(drive.holding_torque, dtype=float), (n,))
            out.append(_held(name, start, Tc, position, hold * np.sign(drive.load.torque)))
        else:
            if isinstance(segment, Move):
                assert law is not None, "sizer.sizing.segment_cycle.cycle_laws gives one"
                u, q, v, a = _move_samples(segment, law, np.asarray(T, dtype=float), samples)
                rest = 1.0 if segment.displacement >= 0.0 else -1.0
            else:
                assert isinstance(segment, Run)
                u, rest = np.array([0.0, 1.0]), 1.0
                v, a = np.full((n, 2), segment.speed), np.zeros((n, 2))
                q = segment.speed * (Tc * u[None])
            out.append(_Piece(name, start + Tc * u[None], position + q, v, a, K * v, K * a,
                              signed_torque(drive, calc.motors, a, v, rest)))
        start, position = start + Tc, position + segment.displacement
    return out


def _linkage_pieces(calc: LinkageCalculator | LinkageCycle, s: np.ndarray,
                    samples: int | None) -> list[_Piece]:
    """Through a linkage at durations (one move) or scales s: each move on ``samples`` of
    its profile's uniform grid (all of them with None), each dwell holding the output."""
    n = len(calc.motors)
    N = np.broadcast_to(np.asarray(calc.drive.ratio, dtype=float), (n,))[:, None]
    eta = np.broadcast_to(np.asarray(calc.drive.efficiency, dtype=float), (n,))[:, None]
    out, start, position = [], np.zeros((n, 1)), 0.0
    names = [name for name, _, _ in _linkage_segments(calc, calc.law)]
    for name, (part, T, move) in zip(names, linkage_parts(calc, s), strict=True):
        Tc = np.asarray(T, dtype=float)[:, None]
        if isinstance(part, HeldDwell):
            out.append(_held(name, start, Tc, position, abs(part.hold) / (N * eta)[:, 0]))
        else:
            assert move is not None
            speed, torque, _ = move.motor_samples(np.asarray(T, dtype=float))
            pick = np.flatnonzero(part.weights == 0.0)  # the uniform grid, in order
            if samples is not None:
                pick = pick[np.linspace(0, len(pick) - 1, samples).round().astype(int)]
            out.append(_Piece(name, start + Tc * part.u[pick][None], part.s[pick],
                              part.s1[pick][None] / Tc, part.s2[pick][None] / Tc**2,
                              speed[:, pick], N * part.theta2[pick][None] / Tc**2,
                              torque[:, pick], part.theta[pick], part.ratio[pick]))
            position = float(part.s[-1])
        start = start + Tc
    return out


def _linkage_segments(calc: LinkageCalculator | LinkageCycle, law: MotionLaw | None
                      ) -> list[tuple[str, str, MotionLaw | None]]:
    """(name, kind, law) of each part of the cycle through a linkage."""
    if isinstance(calc, LinkageCalculator):
        return [("move", "move", law), ("dwell", "dwell", None)][:1 + (calc.task.dwell > 0)]
    return [(seg.name or type(seg).__name__.lower(), type(seg).__name__.lower(), own)
            for seg, own in zip(calc.cycle.segments, calc.laws, strict=True)]


def _joined(pieces: list[_Piece], key: str, row: int | None = None) -> np.ndarray:
    """One series of the cycle, all candidates or one ``row``."""
    values = [getattr(p, key) for p in pieces]
    if row is None:
        return np.concatenate(values, axis=1)
    return np.concatenate([x if x.ndim == 1 else x[row] for x in values])


def _samples(pieces: list[_Piece]) -> CycleSamples:
    time = _joined(pieces, "time")
    return CycleSamples(time, _joined(pieces, "torque"), _joined(pieces, "motor_speed"),
                        time[:, -1])


def refuse_unsupported(design: Design) -> None:
    """A UserError for what :func:`cycle_samples` does not sample: a cycle of segments
    (:func:`segment_samples`), a linkage (:func:`linkage_samples`)."""
    if design.machine_cycle.shorthand is None:
        raise UserError("a cycle of segments is sampled by sizer.sizing.samples."
                        "segment_samples", field="cycle")
    if design.transmission.linkage is not None:
        raise UserError("a linkage is sampled by sizer.sizing.samples.linkage_samples",
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


def sampled(calculator: CycleCalculator | SegmentCycle | LinkageCalculator | LinkageCycle,
            T: np.ndarray, samples: int = SAMPLES) -> CycleSamples:
    """One machine cycle per candidate of any calculator: a law move's task at move
    durations T, a cycle of segments at scales T, a linkage at its durations or scales."""
    if isinstance(calculator, SegmentCycle):
        return segment_samples(calculator, T, samples)
    if isinstance(calculator, LinkageCalculator | LinkageCycle):
        return linkage_samples(calculator, T)
    return _samples(_task_pieces(calculator, T, samples))


def segment_samples(calculator: SegmentCycle, scale: np.ndarray,
                    samples: int = SAMPLES) -> CycleSamples:
    """The same for a cycle of segments at the candidates' scales s."""
    s = np.broadcast_to(np.asarray(scale, dtype=float), (len(calculator.motors),))
    return _samples(_segment_pieces(calculator, s, samples))


def linkage_samples(calculator: LinkageCalculator | LinkageCycle,
                    scale: np.ndarray) -> CycleSamples:
    """The same through a linkage at durations (one move) or scales s (a cycle), each
    move on its profile's whole uniform grid."""
    s = np.broadcast_to(np.asarray(scale, dtype=float), (len(calculator.motors),))
    return _samples(_linkage_pieces(calculator, s, None))


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


def _result(design: Design, motor: Motor, law: MotionLaw,
            transmission: Transmission | None, segments: bool = False
            ) -> CycleCalculator | SegmentCycle | LinkageCalculator | LinkageCycle:
    """The calculator of a sizing result's motor, law and transmission: the task
    shorthand's as a cycle of segments too with ``segments``."""
    if design.transmission.linkage is not None:
        return result_calculator(design, motor, law, transmission)
    motors = MotorArrays.of([motor], design.limits.envelope)
    drive = Drive(design.load, transmission or design.transmission)
    task = shorthand_task(design.machine_cycle)
    if task is not None and not segments:
        return CycleCalculator(None, task, drive, motors, design.limits.thermal_speed, law=law)
    return SegmentCycle(design.machine_cycle, law, drive, motors, design.limits.thermal_speed)


def task_curve(design: Design, motor: Motor, law: MotionLaw | str, duration: float,
               transmission: Transmission | None = None,
               samples: int = CURVE_SAMPLES) -> TaskCurve:
    """Sample the cycle of ``law`` in ``duration`` for ``motor`` (samples per move).

    Pass the law and duration of a sizing result (its ``spec`` and ``duration``) and,
    when the ratio was chosen by the solver, the transmission with that ratio.
    """
    law = make_law(law) if isinstance(law, str) else law
    calc = _result(design, motor, law, transmission)
    s = np.array([scale_of(design, duration)])
    if isinstance(calc, LinkageCalculator | LinkageCycle):
        pieces = _linkage_pieces(calc, s, samples)
        if isinstance(calc, LinkageCalculator):  # its dwell holds the static torque's sign
            pieces[1:] = [_Piece(**{**vars(p), "torque": p.torque * np.sign(
                calc.profile.hold)}) for p in pieces[1:]]
    elif isinstance(calc, CycleCalculator):
        pieces = _task_pieces(calc, s, samples)
    else:
        pieces = _segment_pieces(calc, s, samples)
    segments = () if isinstance(calc, LinkageCalculator) else tuple(
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


def linkage_curve_of(design: Design, motor, law: MotionLaw, duration: float,
                     transmission=None) -> LinkageCurve:
    """The data of the ratio-and-torque plot of one result (sizer plot --linkage): the
    moves, one move on its profile's whole uniform grid, a cycle's on CURVE_SAMPLES."""
    stage = design.transmission.linkage
    assert stage is not None, "sizer plot --linkage asks for a linkage"
    calc = result_calculator(design, motor, law, transmission)
    one = isinstance(calc, LinkageCalculator)
    pieces = [p for p in _linkage_pieces(calc, np.array([scale_of(design, duration)]),
                                         None if one else CURVE_SAMPLES)
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


def segment_breakdown(design: Design, motor: Motor, law: MotionLaw | str, duration: float,
                      transmission: Transmission | None = None) -> SegmentBreakdown:
    """What each segment of ``design``'s cycle asks of ``motor`` with ``law`` (the ranked
    law of the moves that name none) at a result's ``duration`` (issue 12): its start and
    end, peak torque, RMS torque and share of the cycle's squared RMS, peak motor speed,
    work at the motor shaft and the step of the acceleration at its join with the one
    before (a jerk impulse), from the engine's per-segment figures."""
    law = make_law(law) if isinstance(law, str) else law
    calc = _result(design, motor, law, transmission, segments=True)
    s = np.array([scale_of(design, duration)])
    figures: list[dict[str, float]] = []
    if isinstance(calc, LinkageCalculator | LinkageCycle):
        figures = [{k: float(f[k][0]) for k in FIGURES} for f in linkage_figures(calc, s)]
        reference = max((float(np.max(np.abs(part.s2))) / float(T[0]) ** 2
                         for part, T, _ in linkage_parts(calc, s)
                         if isinstance(part, LinkageProfile)), default=0.0)
        segments = _linkage_segments(calc, law)
    else:
        assert isinstance(calc, SegmentCycle)
        for g in calc.figures(s):
            ends = g.end_accelerations or (np.zeros(1), np.zeros(1))
            figures.append({"duration": float(g.duration[0]),
                            "peak_torque": float(g.peak_torque[0]),
                            "square": float(g.torque_square[0]),
                            "max_speed": float(g.max_speed[0]), "energy": float(g.energy[0]),
                            "start_acceleration": float(ends[0][0]),
                            "end_acceleration": float(ends[1][0])})
        reference = max((abs(seg.displacement) / f["duration"] ** 2
                         for seg, f in zip(calc.cycle.segments, figures, strict=True)
                         if isinstance(seg, Move)), default=0.0)
        segments = [(seg.name or type(seg).__name__.lower(), type(seg).__name__.lower(), own)
                    for seg, own in zip(calc.cycle.segments, calc.laws, strict=True)]
    metrics = calc.evaluate(s)
    total = math.fsum(f["square"] for f in figures)
    rows, start, before = [], 0.0, 0.0
    for (name, kind, own), f in zip(segments, figures, strict=True):
        T, square = f["duration"], f["square"]
        step = f["start_acceleration"] - before
        rows.append(SegmentRow(
            name=name, kind=kind, law=own.spec if own is not None else None,
            start=start, end=start + T, peak_torque=f["peak_torque"],
            rms_torque=math.sqrt(square / T) if T > 0 else 0.0,
            rms_share=square / total if total > 0 else 0.0, peak_speed=f["max_speed"],
            energy=f["energy"],
            acceleration_step=step if abs(step) > JOIN_TOLERANCE * reference else 0.0))
        start += T
        before = f["end_acceleration"]
    cycle_time = calc.cycle_time(s) if isinstance(calc, LinkageCalculator) \
        else metrics.duration
    return SegmentBreakdown(motor.id, law.spec, float(cycle_time[0]),
                            float(metrics.rms_torque[0]), tuple(rows))
