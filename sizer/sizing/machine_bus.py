"""What do the axes of a machine ask of the DC bus they share? (issue 16)

For each axis's chosen candidate (its first-ranked feasible one) the motor torque and
speed over one machine cycle (sizer.sizing.profile.task_curve) give its bus power
(sizer.energy.axis_power: shaft power plus copper loss where the motor gives k_t and R);
the axes' powers add with their phases in the machine cycle (sizer.energy.shared_bus).
From the sum: the peak power drawn and returned, the energy per cycle, and the braking
(sizer.energy.braking): per stop the bus capacitance absorbs C (U_top^2 - U_nom^2) / 2,
the resistor takes the rest. The same braking figures for each axis on a bus of its own
(its drive's capacitance) show what sharing saves: one axis's braking feeds another's
motoring.

The bus data come from the machine's ``bus:`` where given, else from the chosen drives:
the capacitances add (modules on one DC link), the nominal voltage and the braking
threshold (or the trip level) are the lowest of the drives'.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from sizer.energy import axis_power, braking, capacitor_energy
from sizer.energy.bus import BusAxis, shared_bus
from sizer.energy.power import integral, interval_parts
from sizer.model.domain import Design, ServoDrive
from sizer.model.machine import Bus
from sizer.sizing.profile import task_curve
from sizer.sizing.results import CandidateResult

SAMPLES = 1001
"""Samples per move of each axis's torque and speed (as sizer.sizing.cycle_samples)."""


@dataclass(frozen=True)
class AxisOnBus:
    """One axis's chosen candidate in its design at the machine speed, and its phase
    (s) in the machine cycle."""

    name: str
    design: Design
    candidate: CandidateResult
    phase: float


@dataclass(frozen=True)
class BusResult:
    """The shared bus over one machine cycle (SI: s, W, J; None where unknown).

    ``resistor_power`` / ``separate_resistor_power``: the braking resistor's continuous
    power on the shared bus / summed over the axes each on a bus of its own;
    ``resistor_limit`` the bus's ``braking_resistor_power`` (None: not checked).
    """

    axes: tuple[str, ...]
    cycle_time: float
    peak_power: float
    peak_regenerative_power: float
    mean_power: float
    motoring_energy: float
    regenerated_energy: float
    net_energy: float
    capacitance: float | None
    absorbable_energy: float
    worst_stop_energy: float
    resistor_energy: float
    resistor_peak_power: float
    resistor_power: float
    separate_resistor_power: float
    resistor_limit: float | None
    time: np.ndarray
    power: np.ndarray

    @property
    def passed(self) -> bool:
        """The resistor's continuous power within the limit (1e-9 relative), if any."""
        if self.resistor_limit is None:
            return True
        return self.resistor_power <= self.resistor_limit * (1.0 + 1e-9)


def _copper(candidate: CandidateResult) -> tuple[float | None, float]:
    motor = candidate.motor_object
    if motor is None or motor.torque_constant is None or motor.winding_resistance is None:
        return None, 0.0
    return float(motor.torque_constant), float(motor.winding_resistance)


def _axis_bus_power(axis: AxisOnBus) -> tuple[np.ndarray, np.ndarray]:
    """(time, bus power) of one axis over its machine cycle, from t = 0."""
    c = axis.candidate
    assert c.motor_object is not None and c.law_object is not None and c.duration is not None
    curve = task_curve(axis.design, c.motor_object, c.law_object, c.duration,
                       c.transmission, samples=SAMPLES)
    k_t, R = _copper(c)
    power = axis_power(curve.time, curve.motor_torque, curve.motor_speed,
                       torque_constant=k_t, winding_resistance=R)
    return curve.time - curve.time[0], power.bus[0]


def _lowest(values: Sequence[float | None]) -> float | None:
    known = [v for v in values if v is not None]
    return min(known) if known else None


def _bus_levels(bus: Bus | None, drives: Sequence[ServoDrive | None]
                ) -> tuple[float | None, float | None, float | None]:
    """(capacitance, nominal voltage, braking threshold) of the shared bus."""
    given = bus or Bus()
    capacitance = given.capacitance
    known = [d.bus_capacitance for d in drives if d is not None]
    if capacitance is None and drives and len(known) == len(drives) and None not in known:
        capacitance = float(sum(c for c in known if c is not None))
    voltage = given.voltage
    if voltage is None:
        voltage = _lowest([d.dc_bus_voltage for d in drives if d is not None])
    top = given.braking_threshold
    if top is None:
        top = _lowest([d.braking_threshold if d.braking_threshold is not None
                       else d.max_bus_voltage for d in drives if d is not None])
    return capacitance, voltage, top


def _absorbable(capacitance: float | None, voltage: float | None, top: float | None) -> float:
    if capacitance is None or voltage is None or top is None or top <= voltage:
        return 0.0
    return float(capacitor_energy(capacitance, top, voltage))


def bus_result(axes: Sequence[AxisOnBus], cycle_time: float, bus: Bus | None) -> BusResult:
    """The shared bus of ``axes`` (each with a chosen candidate) over one machine cycle."""
    sampled = [_axis_bus_power(a) for a in axes]
    parts = [BusAxis(t[None], p[None], a.phase) for a, (t, p) in zip(axes, sampled, strict=True)]
    time, total = shared_bus(parts, cycle_time)
    drives = [a.candidate.drive_object for a in axes]
    capacitance, voltage, top = _bus_levels(bus, drives)
    stored = _absorbable(capacitance, voltage, top)
    shared = braking(time, total, stored)
    separate = 0.0
    for a, (t, p) in zip(axes, sampled, strict=True):
        own = _absorbable(*_bus_levels(None, [a.candidate.drive_object]))
        separate += float(braking(t[None], p[None], own).resistor_continuous_power[0])
    up, down = interval_parts(time, total)
    motoring, regenerated = float(up.sum()), float(down.sum())
    return BusResult(
        axes=tuple(a.name for a in axes), cycle_time=cycle_time,
        peak_power=max(float(total.max()), 0.0),
        peak_regenerative_power=max(-float(total.min()), 0.0),
        mean_power=float(integral(time, total)[0]) / cycle_time,
        motoring_energy=motoring, regenerated_energy=regenerated,
        net_energy=motoring - regenerated, capacitance=capacitance,
        absorbable_energy=stored, worst_stop_energy=float(shared.worst_stop_energy[0]),
        resistor_energy=float(shared.resistor_cycle_energy[0]),
        resistor_peak_power=float(shared.resistor_peak_power[0]),
        resistor_power=float(shared.resistor_continuous_power[0]),
        separate_resistor_power=separate,
        resistor_limit=None if bus is None else bus.braking_resistor_power,
        time=time[0], power=total[0])

