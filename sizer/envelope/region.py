"""Torque limit as a function of speed: piecewise linear, zero past the last point.

A region is given by (speed, torque) points with strictly increasing speed from 0.
Scalar ratings alone give the book's rectangles (sec. 6.1.1): the continuous region is
tau_c and the intermittent region tau_p, both up to the rated speed v_n; a completion rule
(sizer.envelope.completion) may extend a region without a curve up to ``max_speed``.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from sizer.envelope.completion import completed_continuous, completed_intermittent, from_zero
from sizer.model.domain import Curve, EnvelopeRule, Motor


def continuous_region(motor: Motor, rule: EnvelopeRule = "book") -> Curve:
    """The continuous (S1) region's corner points: the catalog's curve, else by ``rule``."""
    if motor.continuous_curve:
        return from_zero(motor.continuous_curve)
    return completed_continuous(motor, rule)


def intermittent_region(motor: Motor, rule: EnvelopeRule = "book") -> Curve:
    """The intermittent (peak) region's corner points: the catalog's curve, else by ``rule``."""
    if motor.intermittent_curve:
        return from_zero(motor.intermittent_curve)
    return completed_intermittent(motor, rule)


_COUNTED_CORNERS = 16
"""Up to this many interior corners a region's segments are counted, one pass over the
speeds per corner (memory: the index alone); beyond, searched."""


_CONCAVE_TOLERANCE = 1e-12
"""Relative rise of a segment's slope still read as concave (rounding of the corners)."""


class RegionTable:
    """The regions of many motors as padded arrays, evaluated for all of them at once."""

    def __init__(self, curves: Sequence[Curve]) -> None:
        lengths = np.array([len(c) for c in curves], dtype=np.intp)
        width = int(lengths.max())
        # every curve's points laid end to end, each row read from its own stretch
        points = np.array([(p[0], p[1]) for c in curves for p in c], dtype=float)
        first = np.cumsum(lengths) - lengths
        column = np.arange(width)[None, :]
        past = column - lengths[:, None]  # >= 0 past a curve's last point
        source = first[:, None] + np.minimum(column, lengths[:, None] - 1)
        self.max_speed = points[first + lengths - 1, 0]
        # strictly increasing padding past the end keeps every segment well defined
        self.speeds = np.where(past >= 0, self.max_speed[:, None] * (2.0 + past),
                               points[source, 0])
        self.torques = points[source, 1]

    def __len__(self) -> int:
        return len(self.max_speed)

    def take(self, index: np.ndarray) -> RegionTable:
        """The rows at ``index`` (repeats allowed), without rebuilding from the curves."""
        table = object.__new__(RegionTable)
        table.speeds = self.speeds[index]
        table.torques = self.torques[index]
        table.max_speed = self.max_speed[index]
        return table

    def limit(self, speed: np.ndarray) -> np.ndarray:
        """Torque limit at |speed|; speed has shape (motors, ...). Past the end: 0."""
        speed = np.abs(np.asarray(speed, dtype=float))
        shape = speed.shape
        flat = speed.reshape(shape[0], -1)
        # each sample's segment as a place in the tables laid end to end: one gather
        # each, not a two-index lookup
        at = self._segment(flat) + (np.arange(shape[0]) * self.speeds.shape[1])[:, None]
        speeds, torques = self.speeds.ravel(), self.torques.ravel()
        s0, s1 = speeds.take(at), speeds.take(at + 1)
        t0, t1 = torques.take(at), torques.take(at + 1)
        value = t0 + (t1 - t0) * (flat - s0) / (s1 - s0)
        value[flat > self.max_speed[:, None] * (1.0 + 1e-12)] = 0.0
        return value.reshape(shape)

    def _segment(self, flat: np.ndarray) -> np.ndarray:
        """Per motor row, the segment of each speed: the count of interior corner speeds
        <= it (0 .. width-2). Tables of few corners count directly; others by one searchsorted
        over all rows laid end to end (memory motors x samples, not x curve points); the
        offsets cost a few ulps, so the index is then corrected by one step against the
        row's own corner speeds (exact)."""
        count, width = self.speeds.shape
        if width - 2 <= _COUNTED_CORNERS:  # few corners: counted one corner at a time
            index = np.zeros(flat.shape, dtype=np.intp)
            for k in range(1, width - 1):
                index += flat >= self.speeds[:, k, None]
            return index
        span = self.speeds[:, -1] - self.speeds[:, 0] + 1.0
        base = np.concatenate(([0.0], np.cumsum(span)[:-1]))[:, None]
        laid = (self.speeds - self.speeds[:, :1] + base).ravel()
        query = np.clip(flat, self.speeds[:, :1], self.speeds[:, -1:]) - self.speeds[:, :1]
        found = np.searchsorted(laid, query + base, side="right")
        rows = np.arange(count)[:, None]
        index = np.minimum(np.maximum(found - rows * width - 1, 0), width - 2)  # ints: no clip
        index -= (index > 0) & (flat < self.speeds[rows, index])
        index += (index < width - 2) & (flat >= self.speeds[rows, index + 1])
        return index

    def lines(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(alpha, sigma, concave): per candidate and segment lines alpha + sigma * speed that
        lie on or above the region at every speed up to its end (alpha inf where a segment is
        no such line), and whether the region is the minimum of them (concave).

        A concave region is the minimum of its segments' lines; any other region keeps one
        line, flat at its largest torque.
        """
        s, t = self.speeds, self.torques
        with np.errstate(divide="ignore", invalid="ignore"):
            sigma = np.diff(t, axis=1) / np.diff(s, axis=1)
        alpha = t[:, :-1] - sigma * s[:, :-1]
        inside = s[:, :-1] < self.max_speed[:, None]
        inside[:, 0] = True
        with np.errstate(invalid="ignore"):  # -inf - -inf past the ends of padded curves
            rise = np.diff(np.where(inside, sigma, -np.inf), axis=1)
        scale = np.abs(t).max(axis=1, keepdims=True) / np.maximum(self.max_speed[:, None], 1e-300)
        concave = np.all((rise <= _CONCAVE_TOLERANCE * scale) | ~inside[:, 1:], axis=1)
        alpha = np.where(inside & concave[:, None], alpha, np.inf)
        sigma = np.where(inside & concave[:, None], sigma, 0.0)
        alpha[~concave, 0] = t[~concave].max(axis=1)
        return alpha, sigma, concave

    def held_at(self, speed: np.ndarray) -> HeldSegments:
        """Each row's segment at one speed per row (clipped into the region), held for
        :meth:`HeldSegments.limit_clipped` at nearby speeds."""
        flat = np.minimum(np.abs(np.asarray(speed, dtype=float)), self.max_speed)
        index = self._segment(flat[:, None])[:, 0]
        rows = np.arange(len(index))
        last = self.speeds.shape[1] - 2
        s0, s1 = self.speeds[rows, index], self.speeds[rows, index + 1]
        return HeldSegments(self, np.where(index > 0, s0, -np.inf),
                            np.where(index < last, s1, np.inf), s0, s1,
                            self.torques[rows, index], self.torques[rows, index + 1])

    def limit_clipped(self, speed: np.ndarray) -> np.ndarray:
        """Torque limit with the speed clipped into the region (speed is checked apart)."""
        speed = np.minimum(np.abs(np.asarray(speed, dtype=float)),
                           self.max_speed.reshape((-1,) + (1,) * (np.ndim(speed) - 1)))
        return self.limit(speed)


@dataclass(frozen=True)
class HeldSegments:
    """A region's segment per row, found at one speed each (:meth:`RegionTable.held_at`):
    speeds in [low, high) lie on it (the segment :meth:`RegionTable.limit` would pick),
    so the limit there is its interpolation with no search; a root finder's iterates
    near that speed stay on it."""

    table: RegionTable
    low: np.ndarray
    high: np.ndarray
    s0: np.ndarray
    s1: np.ndarray
    t0: np.ndarray
    t1: np.ndarray

    def limit_clipped(self, speed: np.ndarray, rows: np.ndarray) -> np.ndarray:
        """RegionTable.limit_clipped of the rows at ``rows`` at ``speed`` (one per row),
        the same to the bit: the held segment's interpolation where the speed is on it,
        the table's search elsewhere."""
        flat = np.minimum(np.abs(np.asarray(speed, dtype=float)), self.table.max_speed[rows])
        s0, s1, t0, t1 = self.s0[rows], self.s1[rows], self.t0[rows], self.t1[rows]
        value = t0 + (t1 - t0) * (flat - s0) / (s1 - s0)
        off = np.flatnonzero(~((flat >= self.low[rows]) & (flat < self.high[rows])))
        if len(off):
            value[off] = self.table.take(rows[off]).limit(flat[off])
        return value
