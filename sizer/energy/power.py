"""Power and energy at the motor shaft and at the DC bus for sampled moves (issue 16).

Inputs are samples: the motor torque tau (the electromagnetic torque, rotor inertia and
friction included, efficiencies applied by power flow as sizer.mechanics.drive does) and
speed omega at the times ``time`` (non-decreasing; (samples,) shared by all candidates or
(candidates, samples), each candidate with its own durations), arrays (candidates,
samples). A repeated time is a jump (a torque step). Between samples every
power is taken as linear in time (the piecewise-linear interpolant of its samples), and
every integral is exact for that interpolant, split exactly where a power changes sign.
This is exact where tau or omega is constant on each interval (trapezoidal speed,
constant-torque pieces) and O(dt^2) otherwise: sample at the law's grid and piece ends.

- shaft power p = tau * omega (> 0 motoring, < 0 braking);
- copper loss P_cu = f R (tau / k_t)^2, k_t in N*m/A_rms; f = 3/2 with R measured between
  two terminals (line to line, the default), 3 with R per phase (star), 1 for a DC motor;
- bus power P_bus = P_e + d |P_e| with P_e = p + P_cu the motor's electrical power and d
  the drive's loss share (0 by default): the bus delivers P_e (1 + d) while motoring and
  receives |P_e| (1 - d) while braking.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from sizer.energy.inputs import (
    fraction,
    nonnegative,
    per_candidate,
    positive,
    samples,
    span,
    times,
)
from sizer.errors import UserError

WINDING_FACTORS = {"line-to-line": 1.5, "phase": 3.0, "dc": 1.0}
"""f in P_cu = f R I^2 by what the resistance R is measured across."""


def copper_loss(torque: ArrayLike, torque_constant: ArrayLike, winding_resistance: ArrayLike,
                winding: str = "line-to-line") -> np.ndarray:
    """P_cu = f R (tau/k_t)^2 (W), f by ``winding`` (:data:`WINDING_FACTORS`); k_t and R
    scalars or broadcasting against ``torque``."""
    if winding not in WINDING_FACTORS:
        raise UserError(f"must be one of {', '.join(WINDING_FACTORS)}, got {winding!r}",
                        field="winding")
    k_t = positive(torque_constant, "torque_constant")
    R = nonnegative(winding_resistance, "winding_resistance")
    current = np.asarray(torque, dtype=float) / k_t
    return WINDING_FACTORS[winding] * R * current * current


def interval_parts(time: np.ndarray, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per interval the integrals of the positive and of the negative part (as >= 0) of
    the piecewise-linear interpolant of ``values`` (candidates, samples) at ``time``
    (1 or candidates, samples): two arrays (candidates, samples - 1), exact, split at the
    sign change."""
    h = np.diff(time, axis=1)
    p0, p1 = values[:, :-1], values[:, 1:]
    same = p0 * p1 >= 0.0
    mean = 0.5 * (p0 + p1) * h
    positive_part, negative_part = np.maximum(mean, 0.0), np.maximum(-mean, 0.0)
    # where the sign changes (a few intervals), each part is the triangle on its side
    rows, cols = np.nonzero(~same)
    if len(rows):
        a, b = p0[rows, cols], p1[rows, cols]
        width = np.broadcast_to(h, p0.shape)[rows, cols]
        with np.errstate(divide="ignore", invalid="ignore"):
            span = np.abs(a) + np.abs(b)
            up = 0.5 * width * (np.maximum(a, 0.0) ** 2 + np.maximum(b, 0.0) ** 2) / span
            down = 0.5 * width * (np.minimum(a, 0.0) ** 2 + np.minimum(b, 0.0) ** 2) / span
        positive_part[rows, cols] = np.where(span > 0.0, up, 0.0)
        negative_part[rows, cols] = np.where(span > 0.0, down, 0.0)
    return positive_part, negative_part


def integral(time: np.ndarray, values: np.ndarray) -> np.ndarray:
    """The exact integral of the piecewise-linear interpolant, per candidate."""
    return np.sum(0.5 * (values[:, :-1] + values[:, 1:]) * np.diff(time, axis=1), axis=1)


@dataclass(frozen=True)
class PowerFigures:
    """Energy figures of one cycle (or sequence) per candidate (SI: s, W, J).

    Shaft: peak_motoring_power (largest tau*omega > 0), mean_motoring_power (the integral
    of its positive part over the cycle time), mean_shaft_power (net). Bus: peak_bus_power,
    peak_regenerative_power (largest |P_bus| with P_bus < 0), mean_bus_power (net),
    motoring_energy and regenerated_energy (integrals of the positive and negative parts,
    both >= 0), net_energy = motoring - regenerated (the energy per cycle when the bus
    keeps what is regenerated), copper_energy and mean_copper_loss.
    """

    cycle_time: np.ndarray
    peak_motoring_power: np.ndarray
    mean_motoring_power: np.ndarray
    mean_shaft_power: np.ndarray
    peak_bus_power: np.ndarray
    peak_regenerative_power: np.ndarray
    mean_bus_power: np.ndarray
    motoring_energy: np.ndarray
    regenerated_energy: np.ndarray
    net_energy: np.ndarray
    copper_energy: np.ndarray
    mean_copper_loss: np.ndarray


@dataclass(frozen=True)
class AxisPower:
    """Sampled powers of one axis: time (1 or candidates, samples), shaft, copper and bus
    power (candidates, samples) in W."""

    time: np.ndarray
    shaft: np.ndarray
    copper: np.ndarray
    bus: np.ndarray

    def figures(self) -> PowerFigures:
        """The cycle's energy figures (the samples span one cycle or one sequence)."""
        t = self.time
        cycle = np.broadcast_to(span(t), self.bus.shape[:1])
        shaft_up, _ = interval_parts(t, self.shaft)
        bus_up, bus_down = interval_parts(t, self.bus)
        motoring, regenerated = bus_up.sum(axis=1), bus_down.sum(axis=1)
        copper = integral(t, self.copper)
        return PowerFigures(
            cycle_time=cycle,
            peak_motoring_power=np.maximum(self.shaft.max(axis=1), 0.0),
            mean_motoring_power=shaft_up.sum(axis=1) / cycle,
            mean_shaft_power=integral(t, self.shaft) / cycle,
            peak_bus_power=np.maximum(self.bus.max(axis=1), 0.0),
            peak_regenerative_power=np.maximum(-self.bus.min(axis=1), 0.0),
            mean_bus_power=integral(t, self.bus) / cycle,
            motoring_energy=motoring, regenerated_energy=regenerated,
            net_energy=motoring - regenerated, copper_energy=copper,
            mean_copper_loss=copper / cycle)


def axis_power(time: ArrayLike, torque: ArrayLike, speed: ArrayLike, *,
               torque_constant: ArrayLike | None = None,
               winding_resistance: ArrayLike = 0.0, winding: str = "line-to-line",
               drive_loss: ArrayLike = 0.0) -> AxisPower:
    """Shaft, copper and bus power of sampled moves (module docstring for conventions).

    ``torque`` (N*m) and ``speed`` (rad/s) are (samples,) or (candidates, samples);
    ``torque_constant`` (N*m/A_rms), ``winding_resistance`` (ohm) and ``drive_loss`` are
    scalars or one per candidate. Without a torque constant the copper loss is zero (then
    the resistance must be zero too).
    """
    t = times(time)
    tau = samples(torque, t, "torque")
    omega = samples(speed, t, "speed")
    sizes = [np.size(v) for v in (torque_constant, winding_resistance, drive_loss)
             if v is not None]
    n = max([t.shape[0], tau.shape[0], omega.shape[0], *sizes])
    for name, rows in (("time", t.shape[0]), ("torque", tau.shape[0]),
                       ("speed", omega.shape[0])):
        if rows not in (1, n):
            raise UserError(f"has {rows} candidates (rows), the other inputs {n}", field=name)
    R = per_candidate(nonnegative(winding_resistance, "winding_resistance"), n,
                      "winding_resistance")
    if torque_constant is None:
        if bool(np.any(R > 0.0)):
            raise UserError("a winding resistance needs the torque constant",
                            field="torque_constant")
        copper = np.zeros((n, t.shape[1]))
    else:
        k_t = per_candidate(positive(torque_constant, "torque_constant"), n,
                            "torque_constant")
        copper = np.broadcast_to(copper_loss(tau, k_t, R, winding), (n, t.shape[1]))
    d = per_candidate(fraction(drive_loss, "drive_loss"), n, "drive_loss")
    shaft = np.broadcast_to(tau * omega, (n, t.shape[1]))
    electrical = shaft + copper
    return AxisPower(t, shaft, np.asarray(copper), electrical + d * np.abs(electrical))
