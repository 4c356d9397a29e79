"""Motors as arrays, so that every check runs for all of them at once."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from sizer.envelope import RegionTable, continuous_region, intermittent_region
from sizer.model.domain import EnvelopeRule, Motor


@dataclass(frozen=True)
class MotorArrays:
    """Rotor inertia, damping and speed-torque regions of the candidates' motors.

    ``catalog`` are the distinct motors, ``index`` the motor of each candidate (a motor
    repeats once per transmission option); the arrays are per candidate.

    ``envelope`` is the rule that completed the regions without curves
    (sizer.envelope.completion); ``book`` keeps the book's rectangles.
    """

    catalog: tuple[Motor, ...]
    index: np.ndarray
    inertia: np.ndarray
    damping: np.ndarray
    intermittent: RegionTable
    continuous: RegionTable
    envelope: EnvelopeRule = "book"

    @classmethod
    def of(cls, motors: Sequence[Motor], envelope: EnvelopeRule = "book") -> MotorArrays:
        motors = tuple(motors)
        return cls(
            motors,
            np.arange(len(motors)),
            np.array([m.inertia for m in motors], dtype=float),
            np.array([m.damping for m in motors], dtype=float),
            RegionTable([intermittent_region(m, envelope) for m in motors]),
            RegionTable([continuous_region(m, envelope) for m in motors]),
            envelope,
        )

    def __len__(self) -> int:
        return len(self.index)

    @property
    def motors(self) -> tuple[Motor, ...]:
        """The motor of each candidate."""
        return tuple(self.catalog[int(i)] for i in self.index)


    @property
    def speed_limit(self) -> np.ndarray:
        """Highest speed of the intermittent region (rated speed for the book's rectangles)."""
        return self.intermittent.max_speed

    @cached_property
    def is_rectangular(self) -> np.ndarray:
        """True where both regions are flat up to one common speed (the book's case).

        Read from the regions as completed, so a motor whose regions were extended past
        the rated speed by a falling line is not rectangular (eq. 6.2 does not apply).
        """
        flat_i = np.all(self.intermittent.torques == self.intermittent.torques[:, :1], axis=1)
        flat_c = np.all(self.continuous.torques == self.continuous.torques[:, :1], axis=1)
        return flat_i & flat_c & (self.intermittent.max_speed == self.continuous.max_speed)

    @cached_property
    def flat_speed(self) -> np.ndarray:
        """Speed up to which both regions keep their standstill torque: the rectangle that
        eq. (6.2) sees (the rated speed for a motor whose regions the envelope rule
        extended, the whole region for the book's rectangles)."""
        return np.minimum(_flat_end(self.intermittent), _flat_end(self.continuous))

    @cached_property
    def all_rectangular(self) -> bool:
        return bool(np.all(self.is_rectangular))

    def subset(self, index: np.ndarray) -> MotorArrays:
        """The candidates at the given positions, in that order (repeats allowed)."""
        index = np.asarray(index, dtype=np.intp)
        return MotorArrays(self.catalog, self.index[index], self.inertia[index],
                           self.damping[index], self.intermittent.take(index),
                           self.continuous.take(index), self.envelope)


def _flat_end(table: RegionTable) -> np.ndarray:
    """Per motor, the speed where the region's torque first leaves its value at rest."""
    same = table.torques == table.torques[:, :1]
    first_change = np.argmin(same, axis=1)  # 0 only where every point is the same
    end = table.speeds[np.arange(len(table)), np.maximum(first_change - 1, 0)]
    return np.where(same.all(axis=1), table.max_speed, np.minimum(end, table.max_speed))
