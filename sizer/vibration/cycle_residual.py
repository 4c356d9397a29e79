"""The residual vibration of a cycle as a function of its durations (book sec. 7.2):
each move's residual amplitude at the load in the machine's steady state, for arrays of
scales or of each row's own durations. It depends on the laws and the durations only,
not on the motor (sizer.sizing.vibration_check makes it a check; sizer.allocation's
vibration goal minimizes its largest value over the moves)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from sizer.laws.base import MotionLaw
from sizer.model.cycle import Cycle, Move
from sizer.vibration.elastic_load import ElasticLoad
from sizer.vibration.modal_state import (
    amplitude,
    free_turn,
    move_increment,
    polynomial_increment,
)


@dataclass(frozen=True)
class CycleVibration:
    """The residual vibration of one law's cycle as a function of the scale s of its free
    durations (the move duration T for the task shorthand)."""

    load: ElasticLoad
    cycle: Cycle
    laws: tuple[MotionLaw | None, ...]

    @cached_property
    def _fixed(self) -> list[float]:
        free = self.cycle.free
        return [math.nan if s.duration is None or i in free else float(s.duration)
                for i, s in enumerate(self.cycle.segments)]

    def durations(self, s: np.ndarray) -> list[np.ndarray]:
        weights = self.cycle.weights()
        return [np.full_like(s, fixed) if math.isfinite(fixed) else w * s
                for fixed, w in zip(self._fixed, weights, strict=True)]

    def residuals(self, s: np.ndarray, durations: list[np.ndarray] | None = None
                  ) -> np.ndarray:
        """(moves, candidates): each move's residual amplitude at the load (m or rad), at
        the scales s or at each candidate's own ``durations`` (a split per motor:
        sizer.sizing.cycle.SegmentCycle.split)."""
        s = np.asarray(s, dtype=float)
        durations = self.durations(s) if durations is None else durations
        state = np.zeros(s.shape, dtype=complex)
        ends: list[np.ndarray] = []
        for segment, law, T in zip(self.cycle.segments, self.laws, durations, strict=True):
            state = state * free_turn(T, self.load)  # a dwell or a run: no acceleration
            if isinstance(segment, Move):
                assert law is not None
                state = state + segment.displacement * self._increment(segment, law, T)
                ends.append(state)
        if self.load.damping_ratio > 0.0:  # the steady state of the repeated cycle
            turn = free_turn(sum(durations, np.zeros_like(s)), self.load)
            start = state / (1.0 - turn)
            k = 0
            elapsed = np.zeros_like(s)
            for segment, T in zip(self.cycle.segments, durations, strict=True):
                elapsed = elapsed + T
                if isinstance(segment, Move):
                    ends[k] = ends[k] + start * free_turn(elapsed, self.load)
                    k += 1
        if not ends:
            return np.zeros((0, s.size))
        return amplitude(np.stack(ends), self.load)

    def _increment(self, move: Move, law: MotionLaw, T: np.ndarray) -> np.ndarray:
        """The H a move of unit displacement adds: the law's own shape, or for a move
        between boundary speeds its polynomial shape at each duration."""
        if move.rest_to_rest:
            return move_increment(law, T, self.load)
        from sizer.laws.boundary_speeds import boundary_form

        basis = boundary_form(law)
        assert basis is not None  # a cycle's laws meet its moves' boundary speeds
        T = np.asarray(T, dtype=float)
        flat = T.ravel()
        h = move.displacement
        r = (None if move.start_acceleration == 0.0 and move.end_acceleration == 0.0 else
             (move.start_acceleration * flat**2 / h, move.end_acceleration * flat**2 / h))

        def acceleration(u: np.ndarray, rows: np.ndarray) -> np.ndarray:
            s0, s1 = move.start_speed * flat[rows] / h, move.end_speed * flat[rows] / h
            if r is None:
                return basis.derivative(u, 2, s0, s1)
            return basis.derivative(u, 2, s0, s1, r0=r[0][rows], r1=r[1][rows])

        return polynomial_increment(acceleration, basis.breaks, flat, self.load).reshape(
            T.shape)

    def worst(self, s: np.ndarray, durations: list[np.ndarray] | None = None) -> np.ndarray:
        """The largest residual over the moves, per scale (or at ``durations``)."""
        residuals = self.residuals(s, durations)
        return residuals.max(axis=0) if len(residuals) else np.zeros(np.shape(s))
