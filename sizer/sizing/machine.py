"""Size a machine: every axis at the master speed, the slowest axis setting it (sec. 5.3).

With a given master speed (or cycle time) each axis is sized as a design with its move
and dwell durations taken from the master angles. With ``master_speed: minimize`` each
axis's smallest machine cycle time is found first (sizer.sizing.machine_speed), the
machine runs at the largest of them, and every axis is then sized at that speed (the
slowest axis's best candidate is then at its limit: margin zero). Each axis's first-ranked
feasible candidate is its choice; the shared DC bus is computed for these choices
(sizer.sizing.machine_bus). The machine is feasible when every axis has a feasible
candidate and the bus's braking resistor, where a limit is given, copes.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from sizer.model.domain import Design
from sizer.model.machine import Machine
from sizer.sizing.engine import size_design
from sizer.sizing.machine_bus import AxisOnBus, BusResult, bus_result
from sizer.sizing.machine_speed import machine_cycle_time
from sizer.sizing.results import CandidateResult, SizingResult

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
        speeds, slowest = machine_cycle_time(machine, workers, on_axis=step)
        fastest = [s.cycle_time for s in speeds]
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
