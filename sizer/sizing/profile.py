"""The mechanical task of one motor and law over a machine cycle, sampled in time.

The curve (motor speed(t), motor torque(t)) is what the book draws in the speed-torque
plane (Fig. 6.2); with the RMS point (thermal speed, RMS torque) of Fig. 6.3 and the
motor's regions it makes the speed-torque diagram. Signs follow the motion: the return
move has negative speed.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from sizer.envelope import continuous_region, intermittent_region
from sizer.laws import MotionLaw, make_law
from sizer.mechanics import Drive
from sizer.model.cycle import Cycle, Dwell, Move, Run
from sizer.model.domain import Curve, Design, Motor, Transmission
from sizer.sizing.cycle import CycleCalculator, MoveScales
from sizer.sizing.cycle_shape import plain_design
from sizer.sizing.motors import MotorArrays
from sizer.sizing.segment_breakdown import design_cycle, result_cycle, scale_of
from sizer.sizing.segment_cycle import normalized_move


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


def task_curve(design: Design, motor: Motor, law: MotionLaw | str, duration: float,
               transmission: Transmission | None = None, samples: int = 401) -> TaskCurve:
    """Sample the cycle of ``law`` in ``duration`` for ``motor`` (samples per move).

    Pass the law and duration of a sizing result (its ``spec`` and ``duration``) and,
    when the ratio was chosen by the solver, the transmission with that ratio.
    """
    if isinstance(law, str):
        law = make_law(law)
    if design.transmission.linkage is not None:
        from sizer.sizing.linkage_sizing import linkage_curve

        return linkage_curve(design, motor, law, duration, transmission, samples)
    if plain_design(design).cycle is not None:
        return _cycle_curve(design, motor, law, duration, transmission, samples)
    drive = Drive(design.load, transmission or design.transmission)
    motors = MotorArrays.of([motor], design.limits.envelope)
    calc = CycleCalculator(None, design.task, drive, motors, design.limits.thermal_speed,
                           law=law)
    T = np.array([duration])
    metrics = calc.evaluate(T)
    h, K = calc.h, float(drive.ratio[0])
    tau, q_n, v_n, a_n = _sample_pieces(law, samples)
    times, positions, speeds, accelerations, torques = [], [], [], [], []
    t0, start = 0.0, 0.0
    hold = float(drive.holding_torque[0])
    for direction in calc.directions:
        torque, _ = calc.channels(a_n[None], v_n[None], MoveScales(h / T / T, h / T, direction))
        times.append(t0 + duration * tau)
        positions.append(start + direction * h * q_n)
        speeds.append(direction * h * v_n / duration)
        accelerations.append(direction * h * a_n / duration / duration)
        torques.append(direction * torque[0])
        t0 += duration
        start += direction * h
        if design.task.dwell > 0.0:
            times.append(np.array([t0, t0 + design.task.dwell]))
            positions.append(np.full(2, start))
            speeds.append(np.zeros(2))
            accelerations.append(np.zeros(2))
            torques.append(np.full(2, hold * np.sign(design.load.torque)))
            t0 += design.task.dwell
    return _curve(design, motor, law, duration, K, (times, positions, speeds, accelerations,
                                                     torques), metrics,
                  motor.inertia + float(drive.driven_inertia[0]),
                  _segment_times(design_cycle(design), scale_of(design, duration)))


def _curve(design: Design, motor: Motor, law: MotionLaw, duration: float, K: float,
           samples: tuple[list[np.ndarray], ...], metrics, total_inertia: float,
           segments: tuple[tuple[str, float, float], ...]) -> TaskCurve:
    """The TaskCurve of the sampled (times, positions, speeds, accelerations, torques)."""
    times, positions, speeds, accelerations, torques = (np.concatenate(x) for x in samples)
    return TaskCurve(
        motor=motor.id, law=law.spec, duration=duration, ratio=K, time=times,
        position=positions, load_speed=speeds, load_acceleration=accelerations,
        motor_speed=K * speeds, motor_acceleration=K * accelerations, motor_torque=torques,
        rms_torque=float(metrics.rms_torque[0]), thermal_speed=float(metrics.thermal_speed[0]),
        peak_torque=float(metrics.peak_torque[0]), max_speed=float(metrics.max_speed[0]),
        continuous_region=continuous_region(motor, design.limits.envelope),
        intermittent_region=intermittent_region(motor, design.limits.envelope),
        total_inertia=total_inertia, segments=segments)


def _segment_times(cycle: Cycle, s: float) -> tuple[tuple[str, float, float], ...]:
    out, start = [], 0.0
    for i, (segment, w) in enumerate(zip(cycle.segments, cycle.weights(), strict=True)):
        T = w * s if i in cycle.free else segment.duration
        out.append((segment.name or type(segment).__name__.lower(), start, start + T))
        start += T
    return tuple(out)


def _cycle_curve(design: Design, motor: Motor, law: MotionLaw, duration: float,
                 transmission: Transmission | None, samples: int) -> TaskCurve:
    """The task curve of a cycle of segments: each segment sampled in its own time (a
    move by its law, its boundary speeds met), each with its own load."""
    calc, s = result_cycle(design, motor, law, duration, transmission)
    cycle, motors = calc.cycle, calc.motors
    metrics = calc.evaluate(s)
    K = float(calc.drives[0].ratio[0])
    times, positions, speeds, accelerations, torques = [], [], [], [], []
    t0, q0 = 0.0, 0.0
    for segment, own, drive, T in zip(cycle.segments, calc.laws, calc.drives,
                                      calc.durations(s), strict=True):
        T = float(T[0])
        if isinstance(segment, Move):
            u, q, v, a = _move_samples(segment, own, T, samples)
            time = t0 + T * u
        else:
            speed = segment.speed if isinstance(segment, Run) else 0.0
            time = np.array([t0, t0 + T])
            q, v, a = speed * (time - t0), np.full(2, speed), np.zeros(2)
        direction = np.where(v > 0, 1.0, np.where(v < 0, -1.0, np.sign(segment.displacement)
                                                   or 1.0))
        torque = _signed_torque(drive, motors, a, v, direction)
        if isinstance(segment, Dwell):
            hold = float(drive.holding_torque[0])
            torque = np.full(2, hold * np.sign(drive.load.torque))
        times.append(time)
        positions.append(q0 + q)
        speeds.append(v)
        accelerations.append(a)
        torques.append(torque)
        t0 += T
        q0 += segment.displacement
    return _curve(design, motor, law, duration, K, (times, positions, speeds, accelerations,
                                                     torques), metrics,
                  motor.inertia + float(calc.drive.driven_inertia[0]),
                  _segment_times(cycle, float(s[0])))


def _move_samples(move: Move, law: MotionLaw | None, T: float, samples: int):
    """u, q, v, a of a move (SI, q from the move's start), both ends of every piece."""
    h = move.displacement
    if move.rest_to_rest:
        assert law is not None
        u, q_n, v_n, a_n = _sample_pieces(law, samples)
        return u, h * q_n, h * v_n / T, h * a_n / T / T
    from sizer.laws.boundary_speeds import boundary_form

    assert law is not None
    basis = boundary_form(law.spec)
    assert basis is not None
    c = normalized_move(basis, move, np.array([T]))[0]
    parts: list[list[np.ndarray]] = [[], [], [], []]
    for p in range(len(basis.breaks) - 1):
        lo, hi = basis.breaks[p], basis.breaks[p + 1]
        u = np.linspace(lo, hi, max(2, round(samples * (hi - lo))))
        poly = np.polynomial.Polynomial(c[p])
        x = u - lo
        for k, values in enumerate((u, poly(x), poly.deriv(1)(x), poly.deriv(2)(x))):
            parts[k].append(values)
    u, q_n, v_n, a_n = (np.concatenate(x) for x in parts)
    return u, h * q_n, h * v_n / T, h * a_n / T / T


def _signed_torque(drive: Drive, motors: MotorArrays, a: np.ndarray, v: np.ndarray,
                   direction: np.ndarray) -> np.ndarray:
    """The motor torque (signed like the motion) at the load's a, v: the torque along the
    motion of the direction of each sample (Coulomb friction and the power flow follow it)."""
    K = float(drive.ratio[0])
    out = np.empty_like(a)
    for sign in (1.0, -1.0):
        where = direction == sign
        if not where.any():
            continue
        shaft, _ = drive.chain(sign * a[where][None], sign * v[where][None], sign)
        along = (float(motors.inertia[0]) * K * sign * a[where]
                 + float(motors.damping[0]) * K * sign * v[where] + shaft[0])
        out[where] = sign * along
    return out


def _sample_pieces(law: MotionLaw, samples: int) -> tuple[np.ndarray, ...]:
    """tau, q_N, v_N, a_N sampled piece by piece, both ends of each piece included, so
    that a step of the acceleration (a jerk impulse) shows as a vertical step."""
    parts: list[list[np.ndarray]] = [[], [], [], []]
    for index, piece in enumerate(law.pieces):
        count = max(2, round(samples * (piece.end - piece.start)))
        tau = np.linspace(piece.start, piece.end, count)
        parts[0].append(tau)
        for order in range(3):
            parts[order + 1].append(law.piece_derivative(index, tau, order))
    return tuple(np.concatenate(p) for p in parts)
