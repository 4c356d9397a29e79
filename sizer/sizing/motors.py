"""Motors as arrays, so that every check runs for all of them at once."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from sizer.envelope import RegionTable, continuous_region, intermittent_region
from sizer.model.domain import EnvelopeRule, Motor, ServoDrive
from sizer.sizing.catalog_facts import catalog_facts
from sizer.sizing.drives import CurrentCurves, clip_region, pairs


@dataclass(frozen=True)
class MotorArrays:
    """Rotor inertia, damping and speed-torque regions of the candidates' motors.

    ``catalog`` are the distinct motors, ``index`` the motor of each candidate (a motor
    repeats once per transmission option); the arrays are per candidate.

    ``envelope`` is the rule that completed the regions without curves
    (sizer.envelope.completion); ``book`` keeps the book's rectangles.

    With ``drives`` a candidate is a motor with one drive (sizer.sizing.drives): ``drive``
    indexes ``drives`` per candidate, ``currents`` is each candidate's torque-current
    curve, and the regions are clipped at the drive's torques.
    """

    catalog: tuple[Motor, ...]
    index: np.ndarray
    inertia: np.ndarray
    damping: np.ndarray
    intermittent: RegionTable
    continuous: RegionTable
    envelope: EnvelopeRule = "book"
    drives: tuple[ServoDrive, ...] = ()
    drive: np.ndarray | None = None
    currents: CurrentCurves | None = None

    @classmethod
    def of(cls, motors: Sequence[Motor], envelope: EnvelopeRule = "book",
           drives: Sequence[ServoDrive] = ()) -> MotorArrays:
        """The motors' arrays; with ``drives``, one candidate per compatible motor-drive
        pair, the regions clipped at the drive's torques."""
        alone = cls._alone(tuple(motors), envelope)
        if not drives:
            return alone
        return alone.with_drives(tuple(drives))

    @classmethod
    def _alone(cls, motors: tuple[Motor, ...], envelope: EnvelopeRule) -> MotorArrays:
        return cls(
            motors,
            np.arange(len(motors)),
            np.array([m.inertia + m.brake_inertia for m in motors], dtype=float),
            np.array([m.damping for m in motors], dtype=float),
            RegionTable([intermittent_region(m, envelope) for m in motors]),
            RegionTable([continuous_region(m, envelope) for m in motors]),
            envelope,
        )

    def with_drives(self, drives: tuple[ServoDrive, ...]) -> MotorArrays:
        """Every compatible (motor, drive) pair of these motors (one per motor: the
        catalog) as candidates, the regions clipped at T(I_peak) and T(I_cont)."""
        motor, drive = pairs(self.catalog, drives)
        paired = self.subset(motor)
        distinct = np.unique(motor)  # the curves once per paired motor, then per pair
        currents = CurrentCurves.of([self.catalog[int(m)] for m in distinct]).take(
            np.searchsorted(distinct, motor))
        peak = np.array([d.peak_current for d in drives])[drive]
        continuous = np.array([d.continuous_current for d in drives])[drive]
        return MotorArrays(self.catalog, paired.index, paired.inertia, paired.damping,
                           clip_region(paired.intermittent, currents.torque(peak)),
                           clip_region(paired.continuous, currents.torque(continuous)),
                           self.envelope, drives, drive, currents)

    @property
    def peak_current(self) -> np.ndarray:
        """Each candidate's drive peak current (A rms)."""
        assert self.drive is not None
        return np.array([d.peak_current for d in self.drives])[self.drive]

    @property
    def continuous_current(self) -> np.ndarray:
        """Each candidate's drive continuous current (A rms)."""
        assert self.drive is not None
        return np.array([d.continuous_current for d in self.drives])[self.drive]

    def __len__(self) -> int:
        return len(self.index)

    @property
    def brake_torque(self) -> np.ndarray:
        """Each candidate's holding-brake torque (N*m; NaN: the motor has no brake)."""
        return catalog_facts(self.catalog).column("brake_holding_torque")[self.index]

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
                           self.continuous.take(index), self.envelope, self.drives,
                           None if self.drive is None else self.drive[index],
                           None if self.currents is None else self.currents.take(index))


def _flat_end(table: RegionTable) -> np.ndarray:
    """Per motor, the speed where the region's torque first leaves its value at rest."""
    same = table.torques == table.torques[:, :1]
    first_change = np.argmin(same, axis=1)  # 0 only where every point is the same
    end = table.speeds[np.arange(len(table)), np.maximum(first_change - 1, 0)]
    return np.where(same.all(axis=1), table.max_speed, np.minimum(end, table.max_speed))
