"""The motor torque and speed over a machine cycle through a linkage, sampled, for all
candidates (issue 16: energy and heat through a linkage).

A move through the linkage is its law's profile over normalized time
(sizer.sizing.linkage_sizing.LinkageProfile, computed once per law and start), so every
candidate's motor speed N theta'(u)/T and torque (J_m + J_stages) N theta''(u)/T^2 +
tau_c/(N eta^(+-1)) are read on the profile's uniform grid at its own duration
(LinkageCalculator.motor_samples); a dwell holds the output's static load,
|tau_hold| / (N eta). A single move with its dwell (LinkageCalculator) and a cycle of
segments (sizer.sizing.linkage_cycle.LinkageCycle, a task with a return included) are
sampled segment after segment. These are the inputs of sizer.energy and sizer.thermal.
"""

from __future__ import annotations

import math

import numpy as np

from sizer.laws import MotionLaw
from sizer.mechanics.drive import Drive
from sizer.model.domain import Design
from sizer.sizing.cycle_samples import CycleSamples
from sizer.sizing.linkage_cycle import HeldDwell, LinkageCycle
from sizer.sizing.linkage_sizing import (
    LinkageCalculator,
    LinkageProfile,
    crank_drive,
    linkage_profile,
    shorthand_cycle,
)
from sizer.sizing.motors import MotorArrays


def linkage_calculator(design: Design, law: MotionLaw, motors: MotorArrays, drive: Drive
                       ) -> LinkageCalculator | LinkageCycle:
    """The calculator the engine sizes a linkage design with: one move and its dwell, or
    the cycle (a task with a return is the cycle it means)."""
    if design.cycle is not None or design.task.return_move:
        cyc = design if design.cycle is not None else shorthand_cycle(design)
        return LinkageCycle(cyc, law, drive, motors, design.limits.thermal_speed)
    profile = linkage_profile(design, law)
    return LinkageCalculator(profile, design.task, crank_drive(design, drive, profile),
                             motors, design.limits.thermal_speed, law)


def scale_of_durations(calculator: LinkageCalculator | LinkageCycle,
                       duration: np.ndarray) -> np.ndarray:
    """The calculator's scale at the engine's reported durations: T itself for one move;
    for a cycle s = (cycle time - fixed time) / sum of the free weights (1 with none)."""
    if isinstance(calculator, LinkageCalculator):
        return np.asarray(duration, dtype=float)
    fixed = float(np.nansum(calculator.fixed))
    weights = math.fsum(w for w, f in zip(calculator.weights, calculator.fixed, strict=True)
                        if not np.isfinite(f))
    if weights == 0.0:
        return np.ones_like(np.asarray(duration, dtype=float))
    return (np.asarray(duration, dtype=float) - fixed) / weights


def _move(calc: LinkageCalculator, T: np.ndarray):
    """(u on the uniform grid, motor speed, motor torque) of one move at durations T."""
    speed, torque, _ = calc.motor_samples(T)
    pick = np.flatnonzero(calc.profile.weights == 0.0)  # the uniform grid, in order
    return calc.profile.u[pick], speed[:, pick], torque[:, pick]


def _move_calculator(calculator: LinkageCalculator | LinkageCycle,
                     profile: LinkageProfile) -> LinkageCalculator:
    """The calculator of one move: the single move's own, or the cycle's for ``profile``."""
    if isinstance(calculator, LinkageCalculator):
        return calculator
    return calculator._move(profile)


def cycle_time(calculator: LinkageCalculator | LinkageCycle, scale: np.ndarray) -> np.ndarray:
    """The machine cycle's time at durations (one move: T + dwell) or scales s."""
    s = np.asarray(scale, dtype=float)
    if isinstance(calculator, LinkageCalculator):
        return s + calculator.task.dwell
    return sum(calculator.durations(s), np.zeros_like(s))


def linkage_samples(calculator: LinkageCalculator | LinkageCycle,
                    scale: np.ndarray) -> CycleSamples:
    """The motor torque and speed of every candidate over one machine cycle at its
    duration (one move) or scale s (a cycle)."""
    n = len(calculator.motors)
    s = np.broadcast_to(np.asarray(scale, dtype=float), (n,))
    drive = calculator.drive
    holding = 1.0 / (np.asarray(drive.ratio, dtype=float) * np.asarray(drive.efficiency,
                                                                        dtype=float))
    holding = np.broadcast_to(holding, (n,))[:, None]
    if isinstance(calculator, LinkageCalculator):
        parts: list[tuple[LinkageProfile | HeldDwell, np.ndarray]] = [(calculator.profile, s)]
        if calculator.task.dwell > 0.0:
            hold = HeldDwell(calculator.profile.hold, 0.0)
            parts.append((hold, np.full(n, calculator.task.dwell)))
    else:
        parts = list(zip(calculator.parts, calculator.durations(s), strict=True))
    times, torques, speeds = [], [], []
    start = np.zeros((n, 1))
    for part, T in parts:
        Tc = np.asarray(T, dtype=float)[:, None]
        if isinstance(part, HeldDwell):
            times.append(np.concatenate([start, start + Tc], axis=1))
            torques.append(np.repeat(abs(part.hold) * holding, 2, axis=1))
            speeds.append(np.zeros((n, 2)))
        else:
            u, speed, torque = _move(_move_calculator(calculator, part),
                                     np.asarray(T, dtype=float))
            times.append(start + Tc * u[None])
            torques.append(torque)
            speeds.append(speed)
        start = start + Tc
    return CycleSamples(np.concatenate(times, axis=1), np.concatenate(torques, axis=1),
                        np.concatenate(speeds, axis=1), start[:, 0])
