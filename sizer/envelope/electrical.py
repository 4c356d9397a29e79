"""The speed-torque limit that follows from a motor's winding and its supply (issue 35).

A permanent-magnet motor's torque is k_t I; at speed the drive must also push that current
against the back-EMF, the winding's resistance and its inductance with the voltage the DC
link allows. The largest current at each speed, clipped by the motor's peak current and
peak torque, is the intermittent region a datasheet draws for that supply.

Conventions (the inputs as datasheets print them, converted where the motor is read):
k_t in N*m per A rms; k_e the RMS line-to-line back-EMF per rad/s; R and L phase to phase
(line to line: a star winding's per-phase figures doubled); the DC link V_dc.

- ``sinusoidal`` (an AC servo, field-oriented with i_d = 0: no field weakening): per phase
  of the equivalent star, RMS phasors, the current in phase with the back-EMF E,

      V^2 >= (E + R_ph I)^2 + (omega_e L_ph I)^2,   E = k_e omega / sqrt(3),

  with R_ph = R/2, L_ph = L/2, omega_e = p omega (p pole pairs) and V = V_dc / sqrt(6),
  the largest RMS phase voltage of space-vector modulation (peak V_dc / sqrt(3)). Its
  larger root gives I(omega), zero at the no-load speed E = V. Power balance ties the
  constants: k_t = 3 k_e / sqrt(3) = sqrt(3) k_e (k_e from k_t where only k_t is printed).
  Without the pole count the inductive drop is left out (stated in the notes).
- ``block`` (a brushless DC motor in six steps, maxon's EC data): two phases in series
  carry the DC current at the terminals, U = R I + k_e omega with U = V_dc and k_e = k_t
  (SI): the straight line from the stall torque k_t V_dc / R to the no-load speed
  V_dc / k_e that maxon prints.

What the model leaves out, each on the optimistic side unless said: the drive's voltage
drops and dead time, overmodulation (more voltage, on the other side), the winding's
resistance rising with its temperature (R as printed, usually at 20 degC), iron losses and
friction, and the inductance's saturation. Past the corner where the voltage starts to
limit, the region is straight lines between exact points of the voltage-limited torque,
within TOLERANCE of it at the middle of each.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from sizer.model.domain import Curve, Motor
from sizer.numerics.arrays import sorted_unique

TOLERANCE = 1e-3
"""How far (a share of the peak torque) the region's straight lines may stray from the
voltage-limited torque at the middle of each: segments are halved until they do not."""
START = 8
"""Segments from the corner to the end before the halving."""


@dataclass(frozen=True)
class Winding:
    """What the voltage limit needs of a motor (SI; R and L phase to phase)."""

    torque_constant: float
    back_emf_constant: float
    resistance: float
    inductance: float
    pole_pairs: int | None
    bus_voltage: float
    block: bool

    @classmethod
    def of(cls, motor: Motor) -> Winding | None:
        """The motor's winding, or None without k_t (or k_e), R or the bus voltage."""
        k_t, k_e = motor.torque_constant, motor.back_emf_constant
        if (k_t is None and k_e is None) or motor.winding_resistance is None \
                or motor.dc_bus_voltage is None:
            return None
        block = motor.commutation == "block"
        factor = 1.0 if block else math.sqrt(3.0)  # k_t = factor * k_e
        k_t = k_t if k_t is not None else factor * k_e  # type: ignore[operator]
        k_e = k_e if k_e is not None else k_t / factor
        return cls(k_t, k_e, motor.winding_resistance, motor.winding_inductance or 0.0,
                   None if motor.poles is None else motor.poles // 2, motor.dc_bus_voltage,
                   block)

    @property
    def inductive(self) -> bool:
        """The inductive drop is counted (a sinusoidal winding with L and its poles)."""
        return not self.block and self.inductance > 0.0 and self.pole_pairs is not None

    def _terms(self) -> tuple[float, float, float, float]:
        """(V, a, R, b): supply voltage, E = a omega, the resistance and X = b omega of the
        circuit the current flows through (a phase of the star, or the terminals)."""
        if self.block:
            return self.bus_voltage, self.back_emf_constant, self.resistance, 0.0
        b = self.pole_pairs * self.inductance / 2.0 if self.inductive else 0.0  # type: ignore[operator]
        return (self.bus_voltage / math.sqrt(6.0), self.back_emf_constant / math.sqrt(3.0),
                self.resistance / 2.0, b)

    def current(self, speed: np.ndarray) -> np.ndarray:
        """The largest current (A rms; block: DC) the supply drives at ``speed`` (rad/s):
        the larger root of (E + R I)^2 + (X I)^2 = V^2, 0 at and past the no-load speed."""
        V, a, R, b = self._terms()
        w = np.abs(np.asarray(speed, dtype=float))
        E, X = a * w, b * w
        Z2 = R * R + X * X
        root = np.sqrt(np.maximum(V * V * Z2 - E * E * X * X, 0.0))
        with np.errstate(divide="ignore", invalid="ignore"):
            current = np.where(Z2 > 0.0, (root - E * R) / Z2, np.inf)
        return np.where(w >= V / a, 0.0, np.maximum(current, 0.0))

    def no_load_speed(self) -> float:
        """rad/s at which the back-EMF takes the whole supply voltage."""
        V, a, _, _ = self._terms()
        return V / a

    def corner_speed(self, current: float) -> float:
        """The speed up to which ``current`` (A) is available, 0 if not even at standstill:
        the root of (a w + R I)^2 + (b w I)^2 = V^2."""
        V, a, R, b = self._terms()
        A = a * a + (b * current) ** 2
        half_B = a * R * current
        C = (R * current) ** 2 - V * V
        if C >= 0.0:
            return 0.0
        return float(-C / (half_B + math.sqrt(half_B * half_B - A * C)))  # stable form


def on_supply(motor: Motor, bus: float | None) -> Motor:
    """The motor fed from a DC link of ``bus`` volts (None: its own figures). A printed
    intermittent curve stated for another supply (the motor's ``dc_bus_voltage``: maxon's
    line at its nominal voltage) no longer holds there: the winding's model replaces it."""
    if bus is None or bus == motor.dc_bus_voltage:
        return motor
    drawn_elsewhere = motor.intermittent_curve is not None and motor.dc_bus_voltage is not None
    return replace(motor, dc_bus_voltage=bus,
                   intermittent_curve=None if drawn_elsewhere else motor.intermittent_curve)


def disagreement(winding: Winding, speed: float, torque: float) -> float:
    """How far the model is from a printed point (speed rad/s, torque N*m) of the voltage
    limit, relative: in torque (k_t I(speed) against ``torque``), or in speed for a point
    at zero torque (the no-load speed against ``speed``); the current is not capped."""
    if torque == 0.0:
        return winding.no_load_speed() / speed - 1.0
    return float(winding.torque_constant * winding.current(np.array([speed]))[0]) / torque - 1.0


def electrical_intermittent(motor: Motor, winding: Winding) -> Curve:
    """The intermittent region of ``motor`` from its winding: its peak torque (and k_t
    times its peak current) up to the corner where the supply starts to limit, then the
    voltage-limited torque k_t I(omega) down to the no-load speed or to max_speed."""
    k_t = winding.torque_constant
    cap = motor.peak_torque
    if motor.peak_current is not None:
        cap = min(cap, k_t * motor.peak_current)
    end = winding.no_load_speed()
    if motor.max_speed is not None:
        end = min(end, motor.max_speed)
    corner = winding.corner_speed(cap / k_t)
    if corner >= end:  # the supply never limits below the end
        return ((0.0, cap), (end, cap))

    def torque(speed: np.ndarray) -> np.ndarray:
        return np.minimum(cap, k_t * winding.current(speed))

    speeds = np.linspace(corner, end, START + 1)
    torques = torque(speeds)
    for _ in range(30):  # each round halves the segments still too far from the curve
        middle = 0.5 * (speeds[:-1] + speeds[1:])
        exact = torque(middle)
        far = np.abs(exact - 0.5 * (torques[:-1] + torques[1:])) > TOLERANCE * cap
        if not far.any():
            break
        speeds = np.insert(speeds, np.flatnonzero(far) + 1, middle[far])
        torques = np.insert(torques, np.flatnonzero(far) + 1, exact[far])
    points = [(0.0, cap)] if corner > 0.0 else []
    points += [(float(w), float(t)) for w, t in zip(speeds, torques, strict=True)]
    return tuple(points)


def clipped(curve: Curve, limit: Curve) -> Curve:
    """The region min(curve, limit) as points: both curves' corners and their crossings,
    up to the shorter one's end (a region is zero past its last point)."""
    (cs, ct), (ls, lt) = np.array(curve, dtype=float).T, np.array(limit, dtype=float).T
    end = min(cs[-1], ls[-1])
    speeds = sorted_unique(np.concatenate((cs, ls)))
    speeds = speeds[speeds <= end]
    d = np.interp(speeds, cs, ct) - np.interp(speeds, ls, lt)
    if speeds[-1] == cs[-1] and np.all(d <= 0.0):  # the limit never binds
        return curve
    cross = np.flatnonzero(d[:-1] * d[1:] < 0.0)
    step = speeds[cross + 1] - speeds[cross]
    speeds = np.union1d(speeds, speeds[cross] + step * d[cross] / (d[cross] - d[cross + 1]))
    low = np.minimum(np.interp(speeds, cs, ct), np.interp(speeds, ls, lt))
    # corners on the straight line through their neighbours add nothing
    line = low[:-2] + (low[2:] - low[:-2]) * (speeds[1:-1] - speeds[:-2]) / (
        speeds[2:] - speeds[:-2])
    keep = np.ones(len(speeds), dtype=bool)
    keep[1:-1] = np.abs(low[1:-1] - line) > 1e-12 * np.max(np.abs(low))
    return tuple((float(s), float(t)) for s, t in zip(speeds[keep], low[keep], strict=True))
