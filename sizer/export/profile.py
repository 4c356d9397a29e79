"""The motion a cam exports: a normalized law scaled to a stroke over a master span, or a
machine cycle of such moves and dwells.

A move is y(x) = y0 + H * q_N((x - x0) / X) for x in [x0, x0 + X]: X is its duration
(a table over time, x in s) or its share of a master range (x in deg of the master), H
its stroke in the file's unit (deg for a rotary axis, mm for a linear one). Its k-th
derivative with respect to x is H / X^k * q_N^(k), evaluated exactly piece by piece. A
dwell holds y0. The profile's pieces are the moves' law pieces and the dwells, in order.
A design's ``cycle:`` of segments is built by sizer.export.cycle_profile: its moves between
boundary speeds are frozen shapes (not at rest at their ends), its runs linear segments.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np

from sizer.laws.base import MotionLaw
from sizer.laws.per_move import RankedLaw, one_law
from sizer.numerics.arrays import sorted_unique


@dataclass(frozen=True)
class CamSegment:
    """A move of ``stroke`` by ``law`` from ``origin``, or a dwell at ``origin`` (law None),
    over [start, start + span] of the master."""

    start: float
    span: float
    origin: float = 0.0
    stroke: float = 0.0
    law: MotionLaw | None = None
    name: str = "move"
    end_speeds: tuple[float, float] | None = None
    """dy/dx at both ends as the design gives them (a cycle's boundary speeds in file
    units, sizer.export.cycle_profile); None: from the law (at rest)."""


@dataclass(frozen=True)
class CamProfile:
    """``law`` scaled to ``stroke`` (in ``slave_unit``) over ``span`` (in
    ``master_unit``); with ``segments``, the machine cycle they make (moves by ``law`` of
    ``stroke`` each way, and dwells) over ``span`` in all."""

    law: RankedLaw
    stroke: float
    span: float
    slave_unit: str = "deg"
    master_unit: str = "s"
    segments: tuple[CamSegment, ...] = ()

    def __post_init__(self) -> None:
        if not (math.isfinite(self.stroke) and self.stroke != 0.0):
            raise ValueError(f"the stroke must be finite and non-zero, got {self.stroke!r}")
        if not (math.isfinite(self.span) and self.span > 0.0):
            raise ValueError(f"the master span must be positive, got {self.span!r}")
        if not self.segments:
            object.__setattr__(self, "segments",
                               (CamSegment(0.0, self.span, 0.0, self.stroke,
                                           one_law(self.law)),))

    @property
    def over_time(self) -> bool:
        return self.master_unit == "s"

    @property
    def is_cycle(self) -> bool:
        return len(self.segments) > 1

    @cached_property
    def _pieces(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(breakpoints in master units, segment of each piece, law piece of each piece)."""
        starts, segment, local = [], [], []
        for i, s in enumerate(self.segments):
            if s.law is None:
                starts.append(s.start)
                segment.append(i)
                local.append(-1)
                continue
            for j, piece in enumerate(s.law.pieces):
                starts.append(s.start + piece.start * s.span)
                segment.append(i)
                local.append(j)
        last = self.segments[-1]
        return (np.append(np.array(starts), last.start + last.span), np.array(segment),
                np.array(local))

    @property
    def breakpoints(self) -> np.ndarray:
        """Where the pieces meet, in master units (0 and the span included)."""
        return self._pieces[0]

    @property
    def peak_acceleration(self) -> float:
        """max |d^2y/dx^2| over the profile (inf when a law's is unbounded)."""
        return max((abs(s.stroke) / s.span ** 2 * s.law.coefficients.C_a
                    for s in self.segments if s.law is not None), default=0.0)

    @property
    def peak_velocity(self) -> float:
        """max |dy/dx| over the profile."""
        return max((abs(s.stroke) / s.span * s.law.coefficients.C_v
                    for s in self.segments if s.law is not None), default=0.0)

    def piece_of(self, x: np.ndarray) -> np.ndarray:
        """The index of the piece that holds each x (the right one at a breakpoint)."""
        starts = self.breakpoints[:-1]
        index = np.searchsorted(starts, np.asarray(x, dtype=float), side="right") - 1
        return np.clip(index, 0, len(starts) - 1)

    def derivative(self, x: np.ndarray, order: int = 0,
                   piece: np.ndarray | None = None) -> np.ndarray:
        """d^order y / dx^order at x; on the given pieces (one-sided at their ends), else
        on the piece that holds each x."""
        x = np.asarray(x, dtype=float)
        index = self.piece_of(x) if piece is None else np.asarray(piece).astype(int)
        index = np.broadcast_to(index, x.shape)
        _, segment, local = self._pieces
        out = np.zeros(x.shape)
        for k in sorted_unique(index):
            mask = index == k
            s = self.segments[segment[k]]
            if order == 0:
                out[mask] = s.origin
            if s.law is not None:
                tau = (x[mask] - s.start) / s.span
                out[mask] += (s.stroke / s.span ** order
                              * s.law.piece_derivative(int(local[k]), tau, order))
        return out

    def position(self, x: np.ndarray) -> np.ndarray:
        return self.derivative(x, 0)


def task_cycle(law: MotionLaw, stroke: float, duration: float, dwell: float,
               return_move: bool, scale: float = 1.0, **units: str) -> CamProfile:
    """The task shorthand's machine cycle: move, dwell (and move back, dwell), each
    duration times ``scale`` (master units per second: 1 over time)."""
    T, D = duration * scale, dwell * scale
    segments, x, y = [], 0.0, 0.0
    plan = [("move", stroke, T), ("dwell", 0.0, D)]
    if return_move:
        plan += [("return", -stroke, T), ("dwell 2", 0.0, D)]
    for name, h, span in plan:
        if span <= 0.0:
            continue
        segments.append(CamSegment(x, span, y, h, None if h == 0.0 else law, name))
        x, y = x + span, y + h
    return CamProfile(law, stroke, x, segments=tuple(segments), **units)


def move_profile(law: RankedLaw, h: float, duration: float, linear: bool,
                 master_range: float | None, task: Any = None) -> CamProfile:
    """The profile ``sizer cam`` exports: a move of h (m or rad, SI) in ``duration`` s,
    the slave in mm or deg; over time, or over a master range (deg) spanning the move (or,
    with ``task``: its dwell, return and second dwell, the machine cycle)."""
    stroke, unit = (h * 1000.0, "mm") if linear else (math.degrees(h), "deg")
    master_unit = "s" if master_range is None else "deg"
    if task is None:
        span = duration if master_range is None else master_range
        return CamProfile(one_law(law), stroke, span, unit, master_unit)
    cycle_time = (duration + task.dwell) * (2 if task.return_move else 1)
    scale = 1.0 if master_range is None else master_range / cycle_time
    return task_cycle(one_law(law), stroke, duration, task.dwell, task.return_move, scale,
                      slave_unit=unit, master_unit=master_unit)
