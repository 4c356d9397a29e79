"""Size a machine: every axis at the master speed, the slowest axis setting it (sec. 5.3).

With a given master speed (or cycle time) each axis is sized as a design with its move
and dwell durations taken from the master angles. With ``master_speed: minimize`` each
axis's smallest machine cycle time is found first (:func:`machine_cycle_time`), the
machine runs at the largest of them, and every axis is then sized at that speed (the
slowest axis's best candidate is then at its limit: margin zero). Each axis's first-ranked
feasible candidate is its choice; the shared DC bus is computed for these choices
(:func:`bus_result`). The machine is feasible when every axis has a feasible
candidate and the bus's braking resistor, where a limit is given, copes.

What do the axes of a machine ask of the DC bus they share (issue 16, :func:`bus_result`)?

For each axis's chosen candidate (its first-ranked feasible one) the motor torque and
speed over one machine cycle (sizer.sizing.samples.motor_trace) give its bus power
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

How fast can the master turn (:func:`machine_cycle_time`)? The slowest axis sets the
master speed (book sec. 5.3): v_c = min over the axes of the speed each axis's limits
allow. Here an axis's limit is its best candidate (motor x law x transmission): at the
machine cycle time T_c the axis moves in f T_c and rests g T_c (f, g its move and dwell
shares of the master's cycle), so each candidate's smallest T_c is the smallest scale s
of the axis's cycle with move f s and dwell g s at which every check passes: one
minimize sizing of that cycle gives them all (:func:`scaled_cycle_time`). Laws chosen
per duration (`auto` shapes, shaped laws without f_T: the task shorthand only) and
axes without a dwell take the root of phi(T_c) = T_c - H(T_c), H(T_c) = min over the
candidates of T_min(g T_c) / f (:func:`searched_cycle_time`; sizer.numerics.roots.
bracketed_root on a bracket from H itself: a dwell that relieves the RMS torque makes H fall,
then [H(H(0)), H(0)] brackets the root; one that costs makes it rise, then T_c doubles
until phi >= 0). The machine's cycle time is the largest of the axes', Theta / v_c.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from sizer.energy import axis_power, braking, capacitor_energy
from sizer.energy.bus import BusAxis, shared_bus
from sizer.energy.power import integral, interval_parts
from sizer.model.domain import Design, ServoDrive
from sizer.model.machine import Bus, Machine, MachineAxis
from sizer.numerics.roots import bracketed_root
from sizer.sizing.energy_check import without_power_figures
from sizer.sizing.engine import size_design
from sizer.sizing.results import CandidateResult, SizingResult
from sizer.sizing.samples import motor_trace

SAMPLES = 1001
"""Samples per move of each axis's torque and speed (as sizer.sizing.samples)."""


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
    if motor.torque_constant is None or motor.winding_resistance is None:
        return None, 0.0
    return float(motor.torque_constant), float(motor.winding_resistance)


def _axis_bus_power(axis: AxisOnBus) -> tuple[np.ndarray, np.ndarray]:
    """(time, bus power) of one axis over its machine cycle, from t = 0."""
    c = axis.candidate
    assert c.duration is not None  # an axis on the bus is a feasible result
    time, torque, speed = motor_trace(axis.design, c.motor_object, c.law_object, c.duration,
                                      c.transmission, samples=SAMPLES)
    k_t, R = _copper(c)
    power = axis_power(time, torque, speed, torque_constant=k_t, winding_resistance=R)
    return time - time[0], power.bus[0]


def _lowest(values: Sequence[float | None]) -> float | None:
    return min((v for v in values if v is not None), default=None)


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


RELATIVE_TOLERANCE = 1e-12
"""Of the machine cycle time found for an axis."""

DOUBLINGS = 40
"""At most this many doublings of T_c when a held load makes the dwell costly."""


def shortest(design: Design, workers: int | None = 1) -> float:
    """The shortest feasible duration (the design's reported one) over its candidates
    in minimize mode; inf when none is feasible at any (sized in ``workers`` processes)."""
    with without_power_figures():  # only the durations count here
        table = size_design(design, workers=workers).table
    assert table is not None
    durations = np.asarray(table.figures["duration"], dtype=float)[table.feasible]
    durations = durations[np.isfinite(durations)]
    return float(durations.min()) if durations.size else math.inf


def axis_cycle_time(axis: MachineAxis, cycle_angle: float,
                    workers: int | None = 1) -> float | None:
    """The smallest machine cycle time at which ``axis`` has a feasible candidate."""
    if axis.dwell > 0.0 and all(spec.is_fixed for spec in axis.design.laws):
        return scaled_cycle_time(axis, cycle_angle, workers)
    return searched_cycle_time(axis, cycle_angle, workers)


def scaled_cycle_time(axis: MachineAxis, cycle_angle: float,
                      workers: int | None = 1) -> float | None:
    """T_c of a resting axis with fixed laws: its scaled cycle (MachineAxis.scaled)
    minimized over s, which reports its cycle time sum(w_i) s."""
    design = axis.scaled(cycle_angle)
    top = shortest(design, workers) / math.fsum(design.machine_cycle.weights())
    return top if math.isfinite(top) else None


def searched_cycle_time(axis: MachineAxis, cycle_angle: float,
                        workers: int | None = 1) -> float | None:
    """T_c by the search on phi (module docstring): one sizing of the task, its dwell
    fixed, per step."""
    f, g = axis.move / cycle_angle, axis.dwell / cycle_angle

    def H(cycle_time: float) -> float:
        return shortest(axis.minimizing(g * cycle_time), workers) / f

    first = H(0.0)
    if not math.isfinite(first):
        return None
    if g == 0.0:
        return first
    value = H(first)
    if value <= first:  # the dwell relieves: [H(first), first] brackets the root
        lo, hi = value, first
        phi_lo = lo - H(lo) if lo < hi else 0.0
        if phi_lo >= 0.0:
            return lo
        phi_hi = hi - value
    else:  # the dwell costs: lengthen until the axis keeps up
        lo, phi_lo = first, first - value
        hi = max(value, 2.0 * first)
        for _ in range(DOUBLINGS):
            phi_hi = hi - H(hi)
            if phi_hi >= 0.0:
                break
            lo, phi_lo, hi = hi, phi_hi, 2.0 * hi
        else:
            return None
    if phi_hi == 0.0:
        return hi

    def phi(x: np.ndarray) -> np.ndarray:
        return np.array([float(x[0]) - H(float(x[0]))])

    _, top = bracketed_root(phi, np.array([lo]), np.array([hi]), np.array([phi_lo]),
                            np.array([phi_hi]), xtol=RELATIVE_TOLERANCE * min(1.0, hi),
                            bracket=True)
    return float(top[0])


def machine_cycle_time(machine: Machine, workers: int | None = 1,
                       on_axis: Callable[[], None] | None = None
                       ) -> tuple[list[float | None], int | None]:
    """Each axis's smallest cycle time and the index of the slowest axis (None when an
    axis is feasible at no master speed); each sizing in ``workers`` processes;
    ``on_axis()`` called after each axis (for progress)."""
    times = []
    for axis in machine.axes:
        times.append(axis_cycle_time(axis, machine.cycle_angle, workers))
        if on_axis is not None:
            on_axis()
    if any(t is None for t in times):
        return times, None
    return times, int(np.argmax(np.array(times, dtype=float)))


Progress = Callable[[int, int], None]


@dataclass(frozen=True)
class AxisResult:
    """One axis at the machine speed: its sizing, its choice (None: nothing feasible),
    its own smallest machine cycle time (s; minimize mode only, None otherwise or when
    no master speed suits it) and its timing (move, dwell, phase in s)."""

    name: str
    design: Design
    sizing: SizingResult
    chosen: CandidateResult | None
    fastest_cycle_time: float | None
    move_time: float | None
    dwell_time: float | None
    phase: float | None
    """The times at the machine's speed (None when no master speed suits any axis: the
    axis is then sized alone in minimize mode, without dwell, to show what fails)."""


@dataclass(frozen=True)
class MachineResult:
    """The machine's speed, each axis's result and the shared bus."""

    name: str
    minimize: bool
    cycle_angle: float
    cycle_time: float | None
    limiting_axis: str | None
    axes: tuple[AxisResult, ...]
    bus: BusResult | None
    reason: str = ""

    @property
    def master_speed(self) -> float | None:
        """v_c = Theta / T_c, rad/s."""
        return None if self.cycle_time is None else self.cycle_angle / self.cycle_time

    @property
    def feasible(self) -> bool:
        return not self.reason


def size_machine(machine: Machine, rank_by: str | None = None,
                 progress: Progress | None = None, workers: int | None = 1) -> MachineResult:
    """Every axis of ``machine`` at its master speed (module docstring); ``rank_by`` ranks
    each axis's candidates (sizer.sizing.ranking), its first feasible one is its choice.
    ``workers``: the processes of each axis's sizings (size_design; None: every CPU for a
    large axis)."""
    steps = len(machine.axes) * (2 if machine.minimize else 1)
    done = 0

    def step() -> None:
        nonlocal done
        done += 1
        if progress is not None:
            progress(done, steps)

    if progress is not None:
        progress(0, steps)
    fastest: list[float | None] = [None] * len(machine.axes)
    limiting: str | None = None
    reason = ""
    if machine.minimize:
        fastest, slowest = machine_cycle_time(machine, workers, on_axis=step)
        known = [t for t in fastest if t is not None]
        blocked = [a.name for a, t in zip(machine.axes, fastest, strict=True) if t is None]
        if blocked:
            reason = (f"axis {blocked[0]!r}: no candidate is feasible at any master speed")
        if slowest is not None:
            limiting = machine.axes[slowest].name
        cycle_time = max(known) if known else None
    else:
        assert machine.master_speed is not None
        cycle_time = machine.cycle_time(machine.master_speed)
    results = []
    for axis, own in zip(machine.axes, fastest, strict=True):
        if cycle_time is None:  # no axis suits any speed: each shows why, minimized alone
            design, share = axis.minimizing(0.0), None
        else:
            design, share = axis.at(cycle_time, machine.cycle_angle), \
                cycle_time / machine.cycle_angle
        sizing = size_design(design, rank_by, workers=workers)
        step()
        chosen = sizing.feasible[0] if sizing.feasible else None
        if chosen is None and not reason:
            reason = f"axis {axis.name!r}: no candidate is feasible at this master speed"
        times = (None, None, None) if share is None else \
            (axis.move * share, axis.dwell * share, axis.start * share)
        results.append(AxisResult(axis.name, design, sizing, chosen, own, *times))
    bus = None
    if cycle_time is not None and all(r.chosen is not None for r in results):
        on_bus = [AxisOnBus(r.name, r.design, r.chosen, r.phase)
                  for r in results if r.chosen is not None and r.phase is not None]
        bus = bus_result(on_bus, cycle_time, machine.bus)
        if not bus.passed and not reason:
            reason = (f"bus: the braking resistor needs {bus.resistor_power:.6g} W, the "
                      f"limit is {bus.resistor_limit:.6g} W")
    return MachineResult(machine.name, machine.minimize, machine.cycle_angle, cycle_time,
                         limiting, tuple(results), bus, reason)
