"""A machine: several axes on one master, synchronized over its cycle (book sec. 5.3).

The master turns at a constant speed v_c through its cycle angle Theta (360 deg by
default), so one machine cycle lasts T_c = Theta / v_c. Each axis moves while the master
turns its ``move`` angle and rests for its ``dwell`` angle (twice with a return), starting
at its ``start`` angle: at T_c its move lasts T = T_c move / Theta and its dwell
T_c dwell / Theta, and its phase in the machine cycle is T_c start / Theta. All angles in
rad, times in s.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

from sizer.model.cycle import Dwell, Move, ShareRule, from_task
from sizer.model.domain import Design


@dataclass(frozen=True)
class MachineAxis:
    """One axis: its design (task without a duration) and its timing on the master."""

    name: str
    design: Design
    move: float
    dwell: float
    start: float = 0.0

    def at(self, cycle_time: float, cycle_angle: float) -> Design:
        """The axis's design when one machine cycle lasts ``cycle_time`` (s)."""
        share = cycle_time / cycle_angle
        task = replace(self.design.task, duration=self.move * share,
                       dwell=self.dwell * share)
        return replace(self.design, machine_cycle=from_task(task))

    def scaled(self, cycle_angle: float) -> Design:
        """The axis's design with its moves and dwells free, lasting f s and g s (f, g
        their shares of ``cycle_angle``): minimizing the scale s gives the axis's T_c."""
        f, g = self.move / cycle_angle, self.dwell / cycle_angle
        cycle = from_task(replace(self.design.task, duration=None, dwell=g))
        segments = tuple(replace(s, weight=f) if isinstance(s, Move) else
                         Dwell(None, weight=g, name=s.name) for s in cycle.segments)
        return replace(self.design, machine_cycle=replace(
            cycle, segments=segments, share=ShareRule.WEIGHTS, shorthand=None))

    def minimizing(self, dwell_time: float) -> Design:
        """The axis's design with ``duration: minimize`` and a dwell of ``dwell_time`` s."""
        task = replace(self.design.task, duration=None, dwell=dwell_time)
        return replace(self.design, machine_cycle=from_task(task))


@dataclass(frozen=True)
class Bus:
    """The DC bus the axes share (SI; None: taken from the chosen drives)."""

    capacitance: float | None = None
    voltage: float | None = None
    braking_threshold: float | None = None
    braking_resistor_power: float | None = None


def bus_level_fault(voltage: float | None, braking_threshold: float | None,
                    max_voltage: float | None = None, *,
                    voltage_name: str = "voltage") -> tuple[str, str] | None:
    """The first inconsistent DC-link level, as (field, message), or None: the braking
    chopper switches on above the nominal bus voltage, and the overvoltage trip level
    (``max_voltage``) is above both (a drive's or a machine's bus; volts)."""
    if voltage is not None and max_voltage is not None and max_voltage <= voltage:
        return "max_bus_voltage", (f"max_bus_voltage {max_voltage:g} V must be above the bus "
                                   f"voltage {voltage_name} {voltage:g} V")
    if voltage is not None and braking_threshold is not None and braking_threshold <= voltage:
        return "braking_threshold", (f"braking_threshold {braking_threshold:g} V must be above "
                                     f"the bus voltage {voltage_name} {voltage:g} V")
    if (braking_threshold is not None and max_voltage is not None
            and braking_threshold > max_voltage):
        return "braking_threshold", (f"braking_threshold {braking_threshold:g} V is above "
                                     f"the maximum bus voltage {max_voltage:g} V")
    return None


@dataclass(frozen=True)
class Machine:
    """Axes on one master: ``master_speed`` rad/s (None: as fast as the slowest axis
    allows, sec. 5.3), ``cycle_angle`` Theta rad."""

    axes: tuple[MachineAxis, ...]
    cycle_angle: float
    master_speed: float | None = None
    bus: Bus | None = None
    name: str = ""
    warnings: tuple[str, ...] = ()
    files: tuple[Path, ...] = ()

    @property
    def minimize(self) -> bool:
        return self.master_speed is None

    def cycle_time(self, master_speed: float) -> float:
        """T_c = Theta / v_c."""
        return self.cycle_angle / master_speed
