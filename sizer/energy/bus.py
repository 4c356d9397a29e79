"""Several axes on one DC bus (issue 16): their bus powers add with their phase in the
machine cycle (Lust CDA3000 engineering guide, DC network operation: the braking powers
of the axes on one DC link add).

Each axis gives its bus power sampled over one machine cycle (its times span exactly the
cycle time; an axis with a shorter cycle pads a dwell) and its phase: the machine time at
which its own time t[0] falls. The sum is taken on the union of all the axes' shifted
breakpoints (each time twice: the left and the right limit, so jumps stay jumps), where
each axis's piecewise-linear power is evaluated exactly: the sum is the exact sum of the
interpolants, and sizer.energy.braking / AxisPower.figures apply to it unchanged.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from sizer.energy.inputs import finite, positive, samples, times
from sizer.errors import UserError

SPAN_TOLERANCE = 1e-9
"""Relative tolerance on an axis's time span against the machine cycle time."""


@dataclass(frozen=True)
class BusAxis:
    """One axis on the bus: sample times (samples,), bus power (candidates or 1, samples)
    in W, and its phase (s) in the machine cycle."""

    time: np.ndarray
    power: np.ndarray
    phase: float = 0.0


def _evaluate(t: np.ndarray, p: np.ndarray, x: np.ndarray, side: str) -> np.ndarray:
    """The piecewise-linear interpolant of p (candidates, samples) at x, the left or
    right limit where the samples jump."""
    i = np.clip(np.searchsorted(t, x, side=side), 1, t.size - 1)  # type: ignore[call-overload]
    t0, t1 = t[i - 1], t[i]
    with np.errstate(divide="ignore", invalid="ignore"):
        w = np.where(t1 > t0, (x - t0) / (t1 - t0), 1.0 if side == "left" else 0.0)
    w = np.clip(w, 0.0, 1.0)
    return p[:, i - 1] * (1.0 - w) + p[:, i] * w


def shared_bus(axes: Sequence[BusAxis], cycle_time: float) -> tuple[np.ndarray, np.ndarray]:
    """The machine cycle's time grid (from 0 to ``cycle_time``) and the summed bus power
    (candidates, samples) of ``axes``, each shifted by its phase (periodic)."""
    T = float(positive(cycle_time, "cycle_time"))
    if not axes:
        raise UserError("needs at least one axis", field="axes")
    prepared = []
    counts = set()
    for k, axis in enumerate(axes):
        field = f"axes[{k}]"
        t = times(axis.time, f"{field}.time")
        p = samples(axis.power, t, f"{field}.power")
        phase = float(finite(axis.phase, f"{field}.phase"))
        if abs((t[-1] - t[0]) - T) > SPAN_TOLERANCE * T:
            raise UserError(f"the samples span {t[-1] - t[0]:g} s, not the machine cycle "
                            f"{T:g} s", field=f"{field}.time")
        prepared.append((t, p, phase))
        counts.add(p.shape[0])
    if len(counts - {1}) > 1:
        raise UserError("the axes must have the same number of candidates", field="axes")
    n = max(counts)
    breaks = [np.array([0.0, T])]
    for t, _, phase in prepared:
        breaks.append(np.mod(t - t[0] + phase, T))
    grid = np.unique(np.concatenate(breaks))
    grid = grid[(grid >= 0.0) & (grid <= T)]
    left, right = grid[1:], grid[:-1]  # the left limit where an interval ends, right starts
    time = np.repeat(grid, 2)[1:-1]
    total = np.zeros((n, time.size))
    for t, p, phase in prepared:
        local_right = np.mod(right - phase, T) + t[0]
        local_left = np.mod(left - phase, T)
        local_left = np.where(local_left == 0.0, T, local_left) + t[0]
        values = np.empty((p.shape[0], time.size))
        values[:, 0::2] = _evaluate(t, p, local_right, "right")
        values[:, 1::2] = _evaluate(t, p, local_left, "left")
        total = total + values
    return time, total
