"""The motor torque and speed over a machine cycle of segments, sampled, for all candidates.

The counterpart of sizer.sizing.cycle_samples for a cycle of segments (sizer.model.cycle:
moves, runs, dwells, each with its own load): each segment in its own duration at the
candidates' scales s (sizer.sizing.segment_cycle.SegmentCycle.durations), one after the
other. A rest-to-rest move is sampled on its law's normalized grid (both ends of every
piece), a move with boundary speeds on its own piecewise polynomial per candidate
(sizer.laws.boundary_speeds, as the engine evaluates it), a run at its constant speed and
a dwell holding its constant load. The torque is the engine's, pointwise:

    tau = s (J_m K a_l + B_m K v_l + shaft(a_l, v_l)),   (a_l, v_l) = s (a, v)

with s the sign of the load's speed (the move's direction where it is zero) and shaft()
the drive's chain with the efficiencies in the direction of power flow
(sizer.mechanics.drive). These are the inputs of sizer.energy and sizer.thermal.
"""

from __future__ import annotations

import numpy as np

from sizer.laws import MotionLaw
from sizer.mechanics import Drive
from sizer.model.cycle import Dwell, Move, Run
from sizer.sizing.cycle_samples import SAMPLES, CycleSamples, law_samples
from sizer.sizing.motors import MotorArrays
from sizer.sizing.segment_cycle import SegmentCycle, normalized_move


def signed_torque(drive: Drive, motors: MotorArrays, a: np.ndarray, v: np.ndarray,
                  rest_sign: float) -> np.ndarray:
    """The motor torque (signed like the motion) at the load's acceleration ``a`` and speed
    ``v`` (candidates, samples); where v is 0 the motion's sign is ``rest_sign``."""
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


def _rest_move(move: Move, law: MotionLaw, T: np.ndarray, samples: int):
    """u (samples,), the load's speed and acceleration (n, samples) of a rest-to-rest move."""
    u, v_n, a_n = law_samples(law, samples)
    h, Tc = move.displacement, T[:, None]
    return u, h * v_n[None] / Tc, h * a_n[None] / (Tc * Tc)


def _boundary_move(move: Move, law: MotionLaw, T: np.ndarray, samples: int):
    """The same for a move with boundary speeds: each candidate's own polynomial."""
    from sizer.laws.boundary_speeds import boundary_form

    basis = boundary_form(law.spec)
    assert basis is not None
    c = normalized_move(basis, move, T)  # (n, P, d+1), ascending powers of u - break
    powers = np.arange(c.shape[2])
    us, vs, accs = [], [], []
    for p in range(len(basis.breaks) - 1):
        lo, hi = float(basis.breaks[p]), float(basis.breaks[p + 1])
        u = np.linspace(lo, hi, max(2, round(samples * (hi - lo))))
        x = (u - lo)[:, None]
        dx = np.where(powers >= 1, powers * x ** np.maximum(powers - 1, 0), 0.0)
        ddx = np.where(powers >= 2, powers * (powers - 1) * x ** np.maximum(powers - 2, 0), 0.0)
        us.append(u)
        vs.append(c[:, p, :] @ dx.T)
        accs.append(c[:, p, :] @ ddx.T)
    h, Tc = move.displacement, T[:, None]
    return (np.concatenate(us), h * np.concatenate(vs, axis=1) / Tc,
            h * np.concatenate(accs, axis=1) / (Tc * Tc))


def segment_samples(calculator: SegmentCycle, scale: np.ndarray,
                    samples: int = SAMPLES) -> CycleSamples:
    """The motor torque and speed of every candidate of ``calculator`` over one machine
    cycle at its scale s of the free durations (module docstring)."""
    n = len(calculator.motors)
    s = np.broadcast_to(np.asarray(scale, dtype=float), (n,))
    motors = calculator.motors
    times, torques, speeds = [], [], []
    start = np.zeros((n, 1))
    for segment, law, drive, T in zip(calculator.cycle.segments, calculator.laws,
                                      calculator.drives, calculator.durations(s), strict=True):
        K = np.broadcast_to(np.asarray(drive.ratio, dtype=float), (n,))[:, None]
        Tc = np.asarray(T, dtype=float)[:, None]
        if isinstance(segment, Move):
            assert law is not None
            sample = _rest_move if segment.rest_to_rest else _boundary_move
            u, v, a = sample(segment, law, np.asarray(T, dtype=float), samples)
            rest = 1.0 if segment.displacement >= 0.0 else -1.0
            times.append(start + Tc * u[None])
            torques.append(signed_torque(drive, motors, a, v, rest))
            speeds.append(K * v)
        elif isinstance(segment, Run):
            v = np.full((n, 2), segment.speed)
            times.append(np.concatenate([start, start + Tc], axis=1))
            torques.append(signed_torque(drive, motors, np.zeros((n, 2)), v, 1.0))
            speeds.append(K * v)
        else:
            assert isinstance(segment, Dwell)
            hold = np.broadcast_to(np.asarray(drive.holding_torque, dtype=float), (n,))
            times.append(np.concatenate([start, start + Tc], axis=1))
            torques.append(np.repeat((hold * np.sign(drive.load.torque))[:, None], 2, axis=1))
            speeds.append(np.zeros((n, 2)))
        start = start + Tc
    return CycleSamples(np.concatenate(times, axis=1), np.concatenate(torques, axis=1),
                        np.concatenate(speeds, axis=1), start[:, 0])
