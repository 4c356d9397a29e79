"""The candidates of a design as one flat axis: motors x transmission options.

A candidate is a motor with one transmission (the design's, or it with a listed ratio, a
catalog gearbox or a lattice point of a continuous ratio in place). Its figures are the
rows of ``motors`` (sizer.sizing.motors) and ``drive`` (sizer.mechanics.drive), so that
every check runs for all candidates at once, whatever mixes motors and options.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from sizer.mechanics import Drive
from sizer.model.domain import Load, Transmission
from sizer.sizing.motors import MotorArrays


@dataclass(frozen=True)
class Candidates:
    """Per candidate: its motor's figures and its drive's (arrays over candidates)."""

    motors: MotorArrays
    drive: Drive
    gearboxes: tuple[str | None, ...] | None = None
    """The catalog gearbox of each transmission option (None: no names)."""

    def __len__(self) -> int:
        return len(self.motors)

    @classmethod
    def single(cls, motors: MotorArrays, load: Load, transmission: Transmission) -> Candidates:
        """Every motor with the same transmission."""
        return cls(motors, Drive(load, transmission))

    @classmethod
    def pairs(cls, motors: MotorArrays, load: Load, transmissions: Sequence[Transmission],
              motor: np.ndarray, option: np.ndarray,
              gearboxes: tuple[str | None, ...] | None = None) -> Candidates:
        """The candidates (motor[i], transmissions[option[i]]): ``motor`` indexes the
        rows of ``motors``."""
        return cls(motors.subset(motor), Drive(load, transmissions, option), gearboxes)

    def take(self, index: np.ndarray) -> Candidates:
        """The candidates at ``index`` (repeats allowed), in that order."""
        index = np.asarray(index, dtype=np.intp)
        return Candidates(self.motors.subset(index), self.drive.take(index), self.gearboxes)

    @property
    def gearbox_names(self) -> tuple[str | None, ...]:
        return self.gearboxes or (None,) * len(self.drive.transmissions)

    @property
    def option(self) -> np.ndarray:
        """The transmission option of each candidate."""
        if self.drive.option is None:
            return np.zeros(len(self), dtype=np.intp)
        return self.drive.option
