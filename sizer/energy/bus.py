"""Several axes on one DC bus (issue 16): their bus powers add with their phase in the
machine cycle (Lust CDA3000 engineering guide, DC network operation: the braking powers
of the axes on one DC link add).

Each axis gives its bus power sampled over one machine cycle (its times span exactly the
cycle time; an axis with a shorter cycle pads a dwell) and its phase: the machine time at
which its own time t[0] falls. The sum is taken on the union of all the axes' shifted
breakpoints (each time twice: the left and the right limit, so jumps stay jumps; row by
row, each candidate with its own grid of the same length; times closer than 1e-9 of the
cycle are one time, as shifting by a phase rounds), where
each axis's piecewise-linear power is evaluated exactly: the sum is the exact sum of the
interpolants, and sizer.energy.braking / AxisPower.figures apply to it unchanged.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from sizer.energy.inputs import finite, positive, samples, times
from sizer.errors import UserError

SPAN_TOLERANCE = 1e-9
"""Relative tolerance on an axis's time span against the machine cycle time."""


@dataclass(frozen=True)
class BusAxis:
    """One axis on the bus: sample times ((candidates or 1,) samples), bus power
    ((candidates or 1,) samples) in W, and its phase (s) in the machine cycle (scalar or
    per candidate)."""

    time: np.ndarray
    power: np.ndarray
    phase: float | np.ndarray = 0.0


SNAP = 1e-9
"""Times closer than this share of the cycle are one time (shifting by a phase rounds)."""

Side = Literal["left", "right"]
"""Which limit where the samples jump, as numpy's searchsorted names it."""


def _merge_close(grid: np.ndarray, tolerance: np.ndarray) -> np.ndarray:
    """Sorted rows with each run of times closer than ``tolerance`` set to its first."""
    close = np.zeros(grid.shape, dtype=bool)
    close[:, 1:] = np.diff(grid, axis=1) < tolerance
    first = np.where(close, 0, np.arange(grid.shape[1]))
    return np.take_along_axis(grid, np.maximum.accumulate(first, axis=1), axis=1)


def _snap(t: np.ndarray, x: np.ndarray, tolerance: np.ndarray) -> np.ndarray:
    """x moved onto the nearest sample time of its row where closer than ``tolerance``."""
    i = np.clip(_count_before(t, x, "left"), 1, t.shape[1] - 1)
    below, above = np.take_along_axis(t, i - 1, axis=1), np.take_along_axis(t, i, axis=1)
    x = np.where(np.abs(x - above) < tolerance, above, x)
    return np.where(np.abs(x - below) < tolerance, below, x)


def _count_before(t: np.ndarray, x: np.ndarray, side: Side) -> np.ndarray:
    """Row by row, how many of the sorted t (rows, p) are < x ("left") or <= x ("right"),
    x (rows, k): numpy's searchsorted for each row, by one stable merge sort (one row:
    searchsorted itself, the same counts)."""
    if t.shape[0] == 1 and x.shape[0] == 1:  # a machine's own cycle: one candidate
        return np.searchsorted(t[0], x[0], side=side)[None, :]
    p = t.shape[1]
    k = x.shape[1]
    order = np.argsort(x, axis=1, kind="stable")
    xs = np.take_along_axis(x, order, axis=1)
    merged = np.concatenate([xs, t] if side == "left" else [t, xs], axis=1)
    perm = np.argsort(merged, axis=1, kind="stable")
    rank = np.empty_like(perm)
    np.put_along_axis(rank, perm, np.broadcast_to(np.arange(p + k), perm.shape), axis=1)
    first = 0 if side == "left" else p
    counts = rank[:, first:first + k] - np.arange(k)
    out = np.empty_like(counts)
    np.put_along_axis(out, order, counts, axis=1)
    return out


def _evaluate(t: np.ndarray, p: np.ndarray, x: np.ndarray, side: Side) -> np.ndarray:
    """The piecewise-linear interpolant of p (rows, samples) at t (rows, samples), read at
    x (rows, k): the left or right limit where the samples jump."""
    i = np.clip(_count_before(t, x, side), 1, t.shape[1] - 1)
    t0, t1 = np.take_along_axis(t, i - 1, axis=1), np.take_along_axis(t, i, axis=1)
    p0, p1 = np.take_along_axis(p, i - 1, axis=1), np.take_along_axis(p, i, axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        w = np.where(t1 > t0, (x - t0) / (t1 - t0), 1.0 if side == "left" else 0.0)
    w = np.clip(w, 0.0, 1.0)
    return p0 * (1.0 - w) + p1 * w


def shared_bus(axes: Sequence[BusAxis],
               cycle_time: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """The machine cycle's sample times (candidates, samples; from 0 to ``cycle_time``,
    a scalar or one per candidate) and the summed bus power (candidates, samples) of
    ``axes``, each shifted by its phase (periodic)."""
    T = np.atleast_1d(positive(cycle_time, "cycle_time"))
    if T.ndim != 1:
        raise UserError("must be one number or one per candidate", field="cycle_time")
    if not axes:
        raise UserError("needs at least one axis", field="axes")
    prepared = []
    for k, axis in enumerate(axes):
        field = f"axes[{k}]"
        t = times(axis.time, f"{field}.time")
        p = samples(axis.power, t, f"{field}.power")
        phase = np.atleast_1d(finite(axis.phase, f"{field}.phase"))
        prepared.append((t, p, phase, field))
    n = max([T.size] + [max(t.shape[0], p.shape[0], phase.size) for t, p, phase, _ in prepared])
    if T.size not in (1, n):
        raise UserError(f"must be one number or one per candidate ({n})", field="cycle_time")
    T = np.broadcast_to(T, (n,))[:, None]
    breaks = [np.zeros((n, 1)), T]
    for i, (t, p, phase, field) in enumerate(prepared):
        for name, size in (("time", t.shape[0]), ("power", p.shape[0]),
                           ("phase", phase.size)):
            if size not in (1, n):
                raise UserError(f"has {size} candidates, the others {n}",
                                field=f"{field}.{name}")
        t = np.broadcast_to(t, (n, t.shape[1]))
        spans = t[:, -1:] - t[:, :1]
        if bool(np.any(np.abs(spans - T) > SPAN_TOLERANCE * T)):
            worst = float(np.max(np.abs(spans - T)))
            raise UserError(f"the samples do not span the machine cycle (off by {worst:g} s)",
                            field=f"{field}.time")
        phase = np.broadcast_to(phase, (n,))[:, None]
        prepared[i] = (t, np.broadcast_to(p, (n, p.shape[1])), phase, field)
        breaks.append(np.mod(t - t[:, :1] + phase, T))
    grid = _merge_close(np.sort(np.minimum(np.concatenate(breaks, axis=1), T), axis=1),
                        SNAP * T)
    right, left = grid[:, :-1], grid[:, 1:]  # where each interval starts and ends
    time = np.repeat(grid, 2, axis=1)[:, 1:-1]
    total = np.zeros((n, time.shape[1]))
    for t, p, phase, _ in prepared:
        start, end = t[:, :1], t[:, -1:]
        local_right = _snap(t, np.mod(right - phase, T) + start, SNAP * T)
        local_right = np.where(local_right >= end, start, local_right)  # the next cycle
        local_left = _snap(t, np.mod(left - phase, T) + start, SNAP * T)
        local_left = np.where(local_left <= start, end, local_left)  # the cycle's end
        value = _evaluate(t, p, local_right, "right")
        total[:, 0::2] += value
        # a zero-width interval (a time in several axes' breakpoints) keeps the value after
        # the jump: one jump, no back-and-forth
        total[:, 1::2] += np.where(left > right, _evaluate(t, p, local_left, "left"), value)
    return time, total
