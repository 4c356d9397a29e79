"""How fast can the master turn? The slowest axis sets the master speed (book sec. 5.3).

The book takes v_c = min over the axes of the speed each axis's limits allow (velocity,
acceleration, jerk: v_max,k / |q_k'(theta)|max, ...). Here an axis's limit is its best
candidate: the machine cycle time T_c at which at least one of its motor x law (x
transmission) candidates passes every check. At T_c the axis moves in T = f T_c and rests
d = g T_c (f, g its move and dwell shares of the master's cycle), so T_c is feasible for
the axis when f T_c >= T_min(g T_c), the engine's minimum duration (eq. 6.2 and its
extensions) of the best candidate with that dwell. The smallest such T_c is the root of

    phi(T_c) = T_c - H(T_c),   H(T_c) = min over candidates of T_min(g T_c) / f,

found by the project's root finder (sizer.numerics.roots.illinois) on a bracket built from
H itself: a dwell that only relieves the RMS torque makes H fall with T_c (then
[H(H(0)), H(0)] brackets the root), a held load that heats the motor while it rests makes
H rise (then T_c is doubled until phi >= 0). The machine's cycle time is the largest of
the axes' (the slowest axis), its master speed Theta / T_c.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from sizer.model.machine import Machine, MachineAxis
from sizer.numerics.roots import illinois
from sizer.sizing.energy_check import without_power_figures
from sizer.sizing.engine import size_design

RELATIVE_TOLERANCE = 1e-12
"""Of the machine cycle time found for an axis."""

DOUBLINGS = 40
"""At most this many doublings of T_c when a held load makes the dwell costly."""


@dataclass(frozen=True)
class AxisSpeed:
    """An axis's smallest machine cycle time (s; None: no candidate is feasible at any
    master speed) and how many sizings it took."""

    cycle_time: float | None
    sizings: int


def best_duration(axis: MachineAxis, dwell_time: float, workers: int | None = 1) -> float:
    """min over the axis's candidates of T_min with each dwell ``dwell_time`` (s); inf
    when none is feasible at any duration (sized in ``workers`` processes: size_design)."""
    with without_power_figures():  # only the durations count here
        table = size_design(axis.minimizing(dwell_time), workers=workers).table
    assert table is not None
    durations = np.asarray(table.figures["duration"], dtype=float)[table.feasible]
    durations = durations[np.isfinite(durations)]
    return float(durations.min()) if durations.size else math.inf


def axis_cycle_time(axis: MachineAxis, cycle_angle: float,
                    workers: int | None = 1) -> AxisSpeed:
    """The smallest machine cycle time at which ``axis`` has a feasible candidate."""
    f, g = axis.move / cycle_angle, axis.dwell / cycle_angle
    calls = 0

    def H(cycle_time: float) -> float:
        nonlocal calls
        calls += 1
        return best_duration(axis, g * cycle_time, workers) / f

    first = H(0.0)
    if not math.isfinite(first):
        return AxisSpeed(None, calls)
    if g == 0.0:
        return AxisSpeed(first, calls)
    value = H(first)
    if value <= first:  # the dwell relieves: [H(first), first] brackets the root
        lo, hi = value, first
        phi_lo = lo - H(lo) if lo < hi else 0.0
        if phi_lo >= 0.0:
            return AxisSpeed(lo, calls)
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
            return AxisSpeed(None, calls)
    if phi_hi == 0.0:
        return AxisSpeed(hi, calls)

    def phi(x: np.ndarray) -> np.ndarray:
        return np.array([float(x[0]) - H(float(x[0]))])

    _, top = illinois(phi, np.array([lo]), np.array([hi]), np.array([phi_lo]),
                      np.array([phi_hi]), xtol=RELATIVE_TOLERANCE * min(1.0, hi), bracket=True)
    return AxisSpeed(float(top[0]), calls)


def machine_cycle_time(machine: Machine, workers: int | None = 1,
                       on_axis: Callable[[], None] | None = None
                       ) -> tuple[list[AxisSpeed], int | None]:
    """Each axis's smallest cycle time and the index of the slowest axis (None when an
    axis is feasible at no master speed); each sizing in ``workers`` processes;
    ``on_axis()`` called after each axis (for progress)."""
    speeds = []
    for axis in machine.axes:
        speeds.append(axis_cycle_time(axis, machine.cycle_angle, workers))
        if on_axis is not None:
            on_axis()
    times = [s.cycle_time for s in speeds]
    if any(t is None for t in times):
        return speeds, None
    return speeds, int(np.argmax(np.array(times, dtype=float)))
