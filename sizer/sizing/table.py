"""Results of many candidates as arrays; result rows are built only for what is shown.

A :class:`CandidateTable` holds, per candidate, the motor, law and transmission it was
evaluated with (indices into tuples of the objects themselves, never names looked up
again), the verdict, the figures and the checks, all decided in the core
(sizer.sizing.checks). :meth:`CandidateTable.row` formats nothing: it only gathers one
candidate's numbers into a :class:`~sizer.sizing.results.CandidateResult`.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from enum import StrEnum
from functools import cached_property
from typing import overload

import numpy as np

from sizer.laws import MotionLaw
from sizer.model.domain import Motor, ServoDrive, Transmission
from sizer.sizing.checks import CheckArrays, limiting_index
from sizer.sizing.energy_check import ENERGY_FIGURES
from sizer.sizing.results import CandidateResult, Check


class Mode(StrEnum):
    """What a sizing computes: the checks at a given duration, or T_min."""

    DURATION = "duration"
    MINIMIZE = "minimize"


FIGURES = ("duration", "peak_torque", "rms_torque", "max_speed", "load_speed", "load_torque")
"""The per-candidate figures of a table (NaN where unknown: no feasible duration)."""

RESIDUAL = "residual_vibration"
"""The optional figure of designs with a mode of the load: the largest residual vibration
of the moves at the load (m or rad; sizer.sizing.vibration_check)."""


@dataclass(frozen=True, eq=False)
class CandidateTable:
    """Per candidate (arrays of equal length): indices into ``laws``, ``motors`` and
    ``transmissions``, the verdict, the figures (SI, NaN where unknown) and the checks.

    ``gearboxes`` names the catalog gearbox of each transmission option (None: none);
    ``stage_ratio`` is the free stage's ratio per candidate when the ratio was chosen.
    """

    mode: Mode
    laws: tuple[MotionLaw, ...]
    law: np.ndarray
    motors: tuple[Motor, ...]
    motor: np.ndarray
    transmissions: tuple[Transmission, ...]
    gearboxes: tuple[str | None, ...]
    option: np.ndarray
    feasible: np.ndarray
    figures: dict[str, np.ndarray]
    checks: tuple[CheckArrays, ...]
    stage_ratio: np.ndarray | None = None
    drives: tuple[ServoDrive, ...] = ()
    drive: np.ndarray | None = None
    """Per candidate, its drive (an index into ``drives``); None: motors alone."""

    def __len__(self) -> int:
        return len(self.motor)

    def take(self, index: np.ndarray) -> CandidateTable:
        """The candidates at ``index``, in that order."""
        index = np.asarray(index, dtype=np.intp)
        return CandidateTable(
            self.mode, self.laws, self.law[index], self.motors, self.motor[index],
            self.transmissions, self.gearboxes, self.option[index], self.feasible[index],
            {k: v[index] for k, v in self.figures.items()},
            tuple(c.take(index) for c in self.checks),
            None if self.stage_ratio is None else self.stage_ratio[index], self.drives,
            None if self.drive is None else self.drive[index])

    @cached_property
    def binding(self) -> np.ndarray:
        """Index of each candidate's binding check (smallest slack)."""
        return limiting_index(list(self.checks))

    @property
    def slacks(self) -> np.ndarray:
        """(candidates, checks): each check's margin beyond the required one."""
        return np.stack([np.broadcast_to(c.slack, (len(self),)) for c in self.checks], axis=1)

    def motor_column(self, name: str) -> np.ndarray:
        """A motor figure per candidate (NaN where the catalog gives none)."""
        values = np.array([_number(getattr(m, name)) for m in self.motors], dtype=float)
        return values[self.motor]

    def row(self, i: int) -> CandidateResult:
        """Candidate ``i`` as a result row."""
        motor = self.motors[int(self.motor[i])]
        law = self.laws[int(self.law[i])]
        option = int(self.option[i])
        rows = []
        binding_name = None
        binding = int(self.binding[i])
        for k, c in enumerate(self.checks):
            if c.applies is not None and not c.applies[i]:
                continue
            check = Check(c.name, float(_at(c.value, i)), float(_at(c.limit, i)), c.unit,
                          float(_at(c.margin, i)), c.required,
                          "" if c.notes is None else str(_at(c.notes, i)))
            rows.append(check)
            if k == binding:
                binding_name = check
        ok = bool(self.feasible[i])
        minimize = self.mode is Mode.MINIMIZE
        assert binding_name is not None
        if ok:
            reason = ""
        elif minimize:
            reason = f"no duration is feasible: {binding_name.describe()}"
        else:
            reason = "; ".join(r.describe() for r in rows if not r.passed)
        known = ok or not minimize

        def figure(name: str) -> float | None:
            value = float(self.figures[name][i])
            return value if known and np.isfinite(value) else None  # never inf in a result

        extra = {} if self.stage_ratio is None else {"stage_ratio": float(self.stage_ratio[i])}
        transmission = self.transmissions[option]
        drive = None if self.drive is None else self.drives[int(self.drive[i])]
        return CandidateResult(
            motor=motor.id, law=law.law_id, spec=law.spec, params=dict(law.params),
            feasible=ok, duration=figure("duration"), peak_torque=figure("peak_torque"),
            rms_torque=figure("rms_torque"), max_speed=figure("max_speed"),
            checks=tuple(rows), limiting=binding_name.name, reason=reason,
            price=motor.price, mass=motor.mass, ratio=transmission.ratio,
            gearbox=self.gearboxes[option], transmission=transmission,
            load_speed=figure("load_speed"), load_torque=figure("load_torque"),
            residual_vibration=figure(RESIDUAL) if RESIDUAL in self.figures else None,
            **{k: figure(k) for k in ENERGY_FIGURES if k in self.figures},
            rated_power=motor.continuous_torque * motor.rated_speed,
            continuous_torque=motor.continuous_torque, rotor_inertia=motor.inertia,
            extra=extra, motor_object=motor, law_object=law,
            drive=None if drive is None else drive.id, drive_object=drive)


def concatenate(tables: Sequence[CandidateTable]) -> CandidateTable:
    """One table of the candidates of several (same mode, motors and checks)."""
    first = tables[0]
    if len(tables) == 1:
        return first
    laws: list[MotionLaw] = []
    transmissions: list[Transmission] = []
    gearboxes: list[str | None] = []
    law_index, option_index = [], []
    for t in tables:
        law_index.append(t.law + len(laws))
        option_index.append(t.option + len(transmissions))
        laws.extend(t.laws)
        transmissions.extend(t.transmissions)
        gearboxes.extend(t.gearboxes)
    names = [c.name for c in first.checks]
    if any([c.name for c in t.checks] != names for t in tables):
        raise ValueError("tables with different checks")
    checks = []
    for k, c in enumerate(first.checks):
        parts = [t.checks[k] for t in tables]
        n = [len(t) for t in tables]

        def joined(attr, parts=parts, n=n):
            return np.concatenate([np.broadcast_to(getattr(p, attr), (m,))
                                   for p, m in zip(parts, n, strict=True)])
        applies = None
        if any(p.applies is not None for p in parts):
            applies = np.concatenate([np.ones(m, bool) if p.applies is None else p.applies
                                      for p, m in zip(parts, n, strict=True)])
        notes = None
        if any(p.notes is not None for p in parts):
            notes = np.concatenate([np.full(m, "", dtype=object) if p.notes is None
                                    else np.broadcast_to(p.notes, (m,))
                                    for p, m in zip(parts, n, strict=True)])
        checks.append(CheckArrays(c.name, joined("value"), joined("limit"), c.unit,
                                  c.required, applies, notes))
    ratios = None
    if any(t.stage_ratio is not None for t in tables):
        ratios = np.concatenate([np.full(len(t), np.nan) if t.stage_ratio is None
                                 else t.stage_ratio for t in tables])
    return CandidateTable(
        first.mode, tuple(laws), np.concatenate(law_index), first.motors,
        np.concatenate([t.motor for t in tables]), tuple(transmissions), tuple(gearboxes),
        np.concatenate(option_index), np.concatenate([t.feasible for t in tables]),
        {k: np.concatenate([t.figures[k] for t in tables]) for k in first.figures},
        tuple(checks), ratios, first.drives,
        None if first.drive is None else np.concatenate([t.drive for t in tables]))


class Rows(Sequence[CandidateResult]):
    """The rows of a table in a given order, each built when first read."""

    def __init__(self, table: CandidateTable, order: np.ndarray) -> None:
        self.table = table
        self.order = np.asarray(order, dtype=np.intp)
        self._built: dict[int, CandidateResult] = {}

    def __len__(self) -> int:
        return len(self.order)

    @overload
    def __getitem__(self, i: int) -> CandidateResult: ...
    @overload
    def __getitem__(self, i: slice) -> tuple[CandidateResult, ...]: ...

    def __getitem__(self, i):
        if isinstance(i, slice):
            return tuple(self[k] for k in range(*i.indices(len(self))))
        if i < 0:
            i += len(self)
        if not 0 <= i < len(self):
            raise IndexError(i)
        if i not in self._built:
            self._built[i] = self.table.row(int(self.order[i]))
        return self._built[i]

    def __eq__(self, other: object) -> bool:
        if isinstance(other, Sequence):
            return tuple(self) == tuple(other)
        return NotImplemented

    def __repr__(self) -> str:
        return f"Rows({len(self)} candidates)"


def _at(x, i: int):
    return x if np.ndim(x) == 0 else (x[0] if len(x) == 1 else x[i])


def _number(value) -> float:
    return np.nan if value is None else float(value)
