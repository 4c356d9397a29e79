"""The motor torque and speed over one machine cycle as sampled arrays, for all candidates.

The task shorthand's cycle (move, dwell, and with ``return_move`` the move back and a
dwell: book sec. 6.1.1) is sampled on one normalized grid of the law (both ends of every
piece, so a step of the acceleration is a repeated time: a jump), scaled per candidate by
its own duration T: time = t0 + T u, load acceleration h a_N(u) / T^2, speed h v_N(u) / T.
The motor torque comes from the same calculator the engine uses
(:meth:`sizer.sizing.cycle.CycleCalculator.channels`: rotor inertia, damping, the
transmission with its efficiencies in the direction of power flow, the load), as
:func:`sizer.sizing.profile.task_curve` does for one candidate; a dwell holds the constant
load. These are the inputs of sizer.energy and sizer.thermal (samples, piecewise linear in
between). A cycle of segments is sampled by sizer.sizing.segment_samples; a linkage is
refused (not sampled yet).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from sizer.errors import UserError
from sizer.laws import MotionLaw
from sizer.model.domain import Design
from sizer.sizing.cycle import CycleCalculator, MoveScales

SAMPLES = 1001
"""Samples of the normalized law per move (spread over its pieces by their lengths)."""


@dataclass(frozen=True)
class CycleSamples:
    """(candidates, samples) arrays over one machine cycle: times (s, non-decreasing, a
    repeated time is a jump), motor torque (N*m, signed like the motion) and motor speed
    (rad/s); ``cycle_time`` (s) per candidate."""

    time: np.ndarray
    torque: np.ndarray
    speed: np.ndarray
    cycle_time: np.ndarray


def law_samples(law: MotionLaw, samples: int = SAMPLES) -> tuple[np.ndarray, ...]:
    """u, v_N, a_N on [0, 1], piece by piece with both ends of each piece (book ch. 2-3:
    the law's normalized form)."""
    parts: list[list[np.ndarray]] = [[], [], []]
    for index, piece in enumerate(law.pieces):
        count = max(2, round(samples * (piece.end - piece.start)))
        u = np.linspace(piece.start, piece.end, count)
        parts[0].append(u)
        parts[1].append(law.piece_derivative(index, u, 1))
        parts[2].append(law.piece_derivative(index, u, 2))
    return tuple(np.concatenate(p) for p in parts)


def refuse_unsupported(design: Design) -> None:
    """A UserError for what is not sampled here: a cycle of segments (its own sampler,
    sizer.sizing.segment_samples), a linkage (not yet)."""
    if design.cycle is not None:
        raise UserError("a cycle of segments is sampled by sizer.sizing.segment_samples",
                        field="cycle")
    if design.transmission.linkage is not None:
        raise UserError("energy and heat through a linkage are not computed yet",
                        field="transmission")


def cycle_samples(design: Design, calculator: CycleCalculator, duration: np.ndarray,
                  samples: int = SAMPLES) -> CycleSamples:
    """The motor torque and speed of every candidate of ``calculator`` over one machine
    cycle of the task shorthand, each candidate moving in its own ``duration`` T (s)."""
    refuse_unsupported(design)
    n = len(calculator.motors)
    T = np.broadcast_to(np.asarray(duration, dtype=float), (n,))
    if not np.all(np.isfinite(T) & (T > 0.0)):
        raise UserError("the cycle is sampled only at finite positive durations",
                        field="task.duration")
    u, v_n, a_n = law_samples(calculator.law, samples)
    h = calculator.h
    K = np.broadcast_to(np.asarray(calculator.drive.ratio, dtype=float), (n,))[:, None]
    hold = np.broadcast_to(np.asarray(calculator.drive.holding_torque, dtype=float), (n,))
    hold = (hold * np.sign(design.load.torque))[:, None]
    dwell = design.task.dwell
    times, torques, speeds = [], [], []
    start = np.zeros((n, 1))
    Tc = T[:, None]
    for direction in calculator.directions:
        torque, _ = calculator.channels(a_n[None], v_n[None],
                                        MoveScales(h / T / T, h / T, direction))
        times.append(start + Tc * u[None])
        torques.append(direction * np.broadcast_to(torque, (n, u.size)))
        speeds.append(K * (direction * h * v_n[None] / Tc))
        start = start + Tc
        if dwell > 0.0:
            times.append(np.concatenate([start, start + dwell], axis=1))
            torques.append(np.repeat(hold, 2, axis=1))
            speeds.append(np.zeros((n, 2)))
            start = start + dwell
    return CycleSamples(np.concatenate(times, axis=1), np.concatenate(torques, axis=1),
                        np.concatenate(speeds, axis=1), start[:, 0])
