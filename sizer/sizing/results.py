"""What the sizing found: plain data that reports format (no computation there).

:class:`SizingResult` holds the ranked candidates; a :class:`CandidateTable` holds, per
candidate, the motor, law and transmission it was evaluated with (indices into tuples of
the objects themselves, never names looked up again), the verdict, the figures and the
checks, all decided in the core (sizer.sizing.checks). :meth:`CandidateTable.row`
formats nothing: it only gathers one candidate's numbers into a
:class:`CandidateResult`. :func:`record` is a result row as plain data
(``SizingResult.to_records``): numbers in SI, None where a figure does not exist (no NaN
or inf), so that it serializes as JSON as it stands.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from enum import StrEnum
from functools import cached_property
from typing import Any, overload

import numpy as np

from sizer.laws.per_move import RankedLaw
from sizer.model.domain import Design, Motor, ServoDrive, Transmission
from sizer.sizing.checks import TOLERANCE, CheckArrays, limiting_index
from sizer.sizing.energy_check import ENERGY_FIGURES

NOT_AVAILABLE = "n/a"
"""The text of a figure that does not exist (an unbounded requirement, no feasible
duration); the reason goes with it (Check.undefined_reason, CandidateResult.reason)."""

UNBOUNDED_WHY = {"jerk": "the law has jerk impulses",
                 "inertia_ratio": "the motor's inertia is 0",
                 "peak": "the move needs torque at a speed where the intermittent region "
                         "gives none"}
"""Why a check's value can be infinite, by check name."""

RATIO_MEANING = {"peak": "torque over the intermittent torque at its speed",
                 "inertia_ratio": "inertia driven over the rotor's"}
"""What the unitless value of a check is a ratio of (its unit in a reason)."""


def margin_percent(margin: float, decimals: int = 2, *, failed: bool = False,
                   required: float = 0.0) -> str:
    """A margin in % with ``decimals`` decimals ('12.50').

    A failing margin gets as many more decimals as it takes to show it below the required
    one (visibly negative for required 0: '-0.0001', never '-0.00'); a passing margin never
    shows a minus sign on zero.
    """
    if not math.isfinite(margin):
        return NOT_AVAILABLE
    value = 100.0 * margin
    text = f"{value:.{decimals}f}"
    if failed:
        while float(text) >= 100.0 * required and decimals < 20:
            decimals += 1
            text = f"{value:.{decimals}f}"
    elif float(text) == 0.0:
        text = text.lstrip("-")
    return text


@dataclass(frozen=True, slots=True)
class Check:
    """One limit checked for a candidate. margin = 1 - value/limit (capability left unused).

    The check passes when margin >= required - TOLERANCE (sizer.sizing.checks: the one
    tolerance of every verdict, so that a requirement equal to its rating passes).
    """

    name: str
    value: float
    limit: float
    unit: str
    margin: float
    required: float = 0.0
    note: str = ""
    """Why it fails when the numbers do not say it (sizer.sizing.checks.CheckArrays)."""

    @property
    def slack(self) -> float:
        return self.margin - self.required

    @property
    def passed(self) -> bool:
        return self.slack >= -TOLERANCE

    @property
    def undefined_reason(self) -> str | None:
        """Why the value or margin is no finite number (None when both are finite)."""
        if math.isfinite(self.value) and math.isfinite(self.margin):
            return None
        if math.isnan(self.value) or math.isnan(self.margin):
            return f"{self.name}: not computable for this candidate"
        if math.isfinite(self.value) and self.limit == 0.0:
            unit = f" {self.unit}" if self.unit else ""
            return (f"{self.name}: {self.value:.6g}{unit} needed where the motor gives none "
                    f"(margin unbounded)")
        why = UNBOUNDED_WHY.get(self.name, "beyond the range of a float")
        return f"{self.name}: unbounded ({why})"

    def describe(self) -> str:
        """One line: which limit, the value and the limit with their unit, the margin, and
        whether it passes; a failing check's note (how its value was found) after the
        verdict. Only where the value is no number (an unbounded requirement, a broken
        dead-point rule) does the note stand in for the numbers."""
        unit = f" {self.unit}" if self.unit else ""
        undefined = self.undefined_reason
        if self.note and not self.passed and undefined is not None:
            return f"{self.name}: {self.note} (FAILS)"
        verdict = "ok" if self.passed else "FAILS"
        if undefined is not None:
            return f"{undefined} against {self.limit:.6g}{unit} ({verdict})"
        need = f", {self.required:.0%} required" if self.required else ""
        margin = margin_percent(self.margin, failed=not self.passed, required=self.required)
        ratio = f" ({RATIO_MEANING[self.name]})" if self.name in RATIO_MEANING else ""
        note = f"; {self.note}" if self.note and not self.passed else ""
        return (f"{self.name}: {self.value:.6g}{unit} against {self.limit:.6g}{unit}{ratio}, "
                f"margin {margin}%{need} ({verdict}{note})")


class CheckFigure:
    """A figure of a design's checks, read from ``CandidateResult.figures`` by its name
    (None where the design has no such check or the figure is unknown)."""

    def __set_name__(self, owner: type, name: str) -> None:
        self.name = name

    def __get__(self, result: CandidateResult, owner: type | None = None) -> float | None:
        return result.figures.get(self.name)


@dataclass(frozen=True, slots=True)
class CandidateResult:
    """A motor with a law: its duration, requirements at the motor shaft and checks.

    The motor, the law (parsed once: its ``spec`` is the canonical text) and the drive
    (where the design has drives) are the catalog's objects, so that no report looks one up
    by id; their ids and the motor's figures are read from them. ``transmission`` is the
    one the result was computed with (the design's, or with the chosen ratio or catalog
    gearbox in place; ``ratio`` its total ratio K: rad/rad, or rad/m on a linear axis),
    ``gearbox`` the catalog gearbox chosen if any; ``load_speed`` and ``load_torque`` are
    the peak speed and peak torque (force on a linear axis) at the load. ``figures`` holds
    the figures the design's checks add (:data:`OPTIONAL_FIGURES`) and the chosen free
    stage's ``stage_ratio``.
    """

    motor_object: Motor
    law_object: RankedLaw
    feasible: bool
    duration: float | None
    peak_torque: float | None
    rms_torque: float | None
    max_speed: float | None
    checks: tuple[Check, ...]
    limiting: str | None
    reason: str = ""
    transmission: Transmission = field(default_factory=Transmission)
    gearbox: str | None = None
    load_speed: float | None = None
    load_torque: float | None = None
    figures: dict[str, float] = field(default_factory=dict)
    drive_object: ServoDrive | None = None

    # the figures of the design's checks (sizer.sizing.energy_check, vibration_check)
    residual_vibration = CheckFigure()  # m or rad: the moves' largest, at the load
    regenerated_energy = CheckFigure()  # J per machine cycle returned to the DC bus
    braking_power = CheckFigure()  # W: the braking resistor's continuous power
    winding_rise = CheckFigure()  # K: the winding temperature rise of the heat check
    peak_power = CheckFigure()  # W: the largest motoring power at the shaft (tau*omega > 0)
    mean_power = CheckFigure()  # W: the motoring shaft power's mean over the machine cycle
    copper_loss = CheckFigure()  # W: the mean copper loss, 3/2 R (tau/k_t)^2
    cycle_energy = CheckFigure()  # J per machine cycle drawn from the DC bus (net)
    stop_energy = CheckFigure()  # J: what the largest stop returns to the bus
    braking_peak_power = CheckFigure()  # W: the braking resistor's peak power

    @property
    def motor(self) -> str:
        return self.motor_object.id

    @property
    def law(self) -> str:
        return self.law_object.law_id

    @property
    def spec(self) -> str:
        return self.law_object.spec

    @property
    def params(self) -> Mapping[str, float]:
        return self.law_object.params

    @property
    def ratio(self) -> float:
        """The total transmission ratio K (motor speed over load speed)."""
        return self.transmission.ratio

    def fixed_in(self, design: Design) -> Design:
        """``design`` with this pair's motor (and drive) alone and the transmission the
        sizing chose in place of a ratio choice; its laws and durations as it has them."""
        fixed = replace(design, motors=(self.motor_object,), chosen_motor=None,
                        chosen_law=None)
        if design.ratio_choice is not None:
            fixed = replace(fixed, ratio_choice=None, transmission=self.transmission)
        if self.drive_object is not None:
            fixed = replace(fixed, drives=(self.drive_object,))
        return fixed

    @property
    def drive(self) -> str | None:
        """The drive's id (amplifier), where the design has drives."""
        return None if self.drive_object is None else self.drive_object.id

    @property
    def price(self) -> float | None:
        return self.motor_object.price

    @property
    def mass(self) -> float | None:
        return self.motor_object.mass

    @property
    def rated_power(self) -> float:
        """tau_c*v_n (W): the motor's size, for ranking."""
        return self.motor_object.continuous_torque * self.motor_object.rated_speed

    @property
    def continuous_torque(self) -> float:
        return self.motor_object.continuous_torque

    @property
    def rotor_inertia(self) -> float:
        return self.motor_object.inertia

    def check(self, name: str) -> Check | None:
        return next((c for c in self.checks if c.name == name), None)

    def margin(self, name: str) -> float | None:
        found = self.check(name)
        return None if found is None else found.margin

    @property
    def worst_slack(self) -> float:
        """The smallest margin beyond the required one, over all checks (ranking key)."""
        return min((c.slack for c in self.checks), default=math.inf)

    @property
    def slacks(self) -> tuple[float, ...]:
        """All slacks, smallest first: ties on the worst are broken by the next ones."""
        return tuple(sorted(c.slack for c in self.checks))

    def record(self) -> dict[str, object]:
        """This candidate as one flat record (:func:`flat_record`; units:
        :data:`RECORD_UNITS`)."""
        return flat_record(self)

    def _repr_html_(self) -> str:
        """Jupyter's display: the verdict and every check as an HTML table."""
        from sizer.notebook import candidate_html  # formatting: loaded when displayed

        return candidate_html(self)


@dataclass(frozen=True)
class SizingResult:
    """All candidates of a design, ranked, with what the run assumed."""

    mode: Mode
    """What was computed: the checks at a given duration, or T_min."""
    results: Sequence[CandidateResult]
    """Ranked, best first (rows built when read: :class:`Rows`)."""
    design_name: str = ""
    notes: tuple[str, ...] = ()
    table: CandidateTable | None = field(default=None, compare=False, repr=False)
    """The same candidates as arrays, in table order (None for hand-made results)."""

    def __post_init__(self) -> None:
        object.__setattr__(self, "mode", Mode(self.mode))  # its text accepted too

    @property
    def feasible(self) -> tuple[CandidateResult, ...]:
        if self.table is not None:  # ranked feasible first: a prefix of the rows
            return tuple(self.results[: int(np.count_nonzero(self.table.feasible))])
        return tuple(r for r in self.results if r.feasible)

    def to_records(self) -> list[dict[str, object]]:
        """One plain dict per candidate, ranked (JSON-ready numbers; None where unknown)."""

        return [record(r) for r in self.results]

    def to_dict(self) -> dict[str, object]:
        """The whole result as plain data: mode, design name, notes and the records."""
        return {"design": self.design_name, "mode": str(self.mode),
                "notes": list(self.notes), "candidates": self.to_records()}

    def records(self) -> list[dict[str, object]]:
        """One flat record per candidate, ranked (:func:`flat_record`): the figures, a
        ``margin_<check>`` per check of the design (None where a check does not apply) and
        the limiting check; SI numbers, units in :data:`RECORD_UNITS` (:meth:`units`)."""
        names = self.check_names()
        return [flat_record(r, rank, names) for rank, r in enumerate(self.results, 1)]

    def check_names(self) -> tuple[str, ...]:
        """The names of the design's checks, in the order the rows give them."""
        if self.table is not None:
            return tuple(str(c.name) for c in self.table.checks)
        return tuple(dict.fromkeys(str(c.name) for r in self.results for c in r.checks))

    def units(self) -> dict[str, str]:
        """The unit of each key of :meth:`records` (``RECORD_UNITS``, margins ``1``)."""
        return {**RECORD_UNITS, **{f"margin_{n}": "1" for n in self.check_names()}}

    def to_pandas(self) -> Any:
        """:meth:`records` as a pandas DataFrame, ranked (index ``rank``), the units in
        ``frame.attrs["units"]``. Needs pandas (the ``pandas`` extra: ``pip install
        'sizer-motion[pandas]'``); an ImportError saying so without it."""
        from sizer.notebook import to_pandas  # pandas is imported only here

        return to_pandas(self.records(), self.units(), self.design_name, str(self.mode))

    def _repr_html_(self) -> str:
        """Jupyter's display: the ranked candidates as a compact HTML table."""
        from sizer.notebook import sizing_html

        return sizing_html(self)


class Mode(StrEnum):
    """What a sizing computes: the checks at a given duration, or T_min."""

    DURATION = "duration"
    MINIMIZE = "minimize"


FIGURES = ("duration", "peak_torque", "rms_torque", "max_speed", "load_speed", "load_torque")
"""The per-candidate figures of a table (NaN where unknown: no feasible duration)."""

RESIDUAL = "residual_vibration"
"""The optional figure of designs with a mode of the load: the largest residual vibration
of the moves at the load (m or rad; sizer.sizing.vibration_check)."""

OPTIONAL_FIGURES = (RESIDUAL, *ENERGY_FIGURES)
"""The figures a design's checks add (NaN in a table where unknown, absent from a result's
``figures``), each read as a :class:`CandidateResult` attribute."""


@dataclass(frozen=True, eq=False)
class CandidateTable:
    """Per candidate (arrays of equal length): indices into ``laws``, ``motors`` and
    ``transmissions``, the verdict, the figures (SI, NaN where unknown) and the checks.

    ``gearboxes`` names the catalog gearbox of each transmission option (None: none);
    ``stage_ratio`` is the free stage's ratio per candidate when the ratio was chosen.
    """

    mode: Mode
    laws: tuple[RankedLaw, ...]
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
        return CandidateResult(
            motor_object=self.motors[int(self.motor[i])],
            law_object=self.laws[int(self.law[i])], feasible=ok,
            duration=figure("duration"), peak_torque=figure("peak_torque"),
            rms_torque=figure("rms_torque"), max_speed=figure("max_speed"),
            checks=tuple(rows), limiting=binding_name.name, reason=reason,
            transmission=self.transmissions[option], gearbox=self.gearboxes[option],
            load_speed=figure("load_speed"), load_torque=figure("load_torque"),
            figures={**{k: v for k in OPTIONAL_FIGURES if k in self.figures
                        and (v := figure(k)) is not None}, **extra},
            drive_object=None if self.drive is None else self.drives[int(self.drive[i])])


def in_groups(group: np.ndarray, size: Callable[[int, np.ndarray], CandidateTable],
              groups: int) -> CandidateTable:
    """One table of candidates sized in groups (``group``: per candidate its group, 0 to
    ``groups`` - 1; ``size(k, index)``: the table of group k's candidates at ``index``),
    its rows in the candidates' order."""
    parts, positions = [], []
    for k in range(groups):
        index = np.flatnonzero(group == k)
        parts.append(size(k, index))
        positions.append(index)
    joined = concatenate(parts)
    inverse = np.empty(len(group), dtype=np.intp)
    inverse[np.concatenate(positions)] = np.arange(len(group))
    return joined.take(inverse)


def concatenate(tables: Sequence[CandidateTable]) -> CandidateTable:
    """One table of the candidates of several (same mode, motors and checks)."""
    first = tables[0]
    if len(tables) == 1:
        return first
    laws: list[RankedLaw] = []
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


FIELDS = ("motor", "law", "spec", "feasible", "duration", "peak_torque", "rms_torque",
          "max_speed", "load_speed", "load_torque", "ratio", "gearbox", "limiting", "reason",
          "price", "mass", "rated_power")
"""The keys of a record, in order (then the energy figures where the design has those
checks, ``params``, ``stage_ratio`` and ``checks``)."""


def _plain(value: object) -> object:
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def check_record(check: Check) -> dict[str, object]:
    return {"name": check.name, "value": _plain(check.value), "limit": _plain(check.limit),
            "unit": check.unit, "margin": _plain(check.margin), "required": check.required,
            "passed": check.passed}


def record(result: CandidateResult) -> dict[str, object]:
    """One candidate: its fields, shape parameters and checks."""
    # designs with drives (issue 16): the pair's drive after its motor
    names = FIELDS if result.drive is None else (FIELDS[0], "drive", *FIELDS[1:])
    out = {name: _plain(getattr(result, name)) for name in names}
    # designs with braking or heat checks: their figures
    out.update({k: result.figures[k] for k in ENERGY_FIGURES if k in result.figures})
    out["params"] = {k: float(v) for k, v in result.params.items()}
    if "stage_ratio" in result.figures:
        out["stage_ratio"] = _plain(result.figures["stage_ratio"])
    out["checks"] = [check_record(c) for c in result.checks]
    return out


RECORD_UNITS: Mapping[str, str] = {
    "rank": "", "motor": "", "drive": "", "law": "", "spec": "", "feasible": "",
    "duration": "s", "peak_torque": "N*m", "rms_torque": "N*m", "max_speed": "rad/s",
    "load_speed": "rad/s (m/s on a linear axis)",
    "load_torque": "N*m (N on a linear axis)",
    "ratio": "rad/rad (rad/m on a linear axis)", "gearbox": "", "limiting": "",
    "limiting_margin": "1", "reason": "", "price": "catalog currency", "mass": "kg",
    "rated_power": "W",
}
"""The unit of each key of a flat record (:func:`flat_record`): SI, the shaft figures at
the motor; every ``margin_<check>`` is a fraction (unit ``1``: 0.25 is 25 % of the limit
left unused, negative where the check fails)."""


def flat_record(result: CandidateResult, rank: int | None = None,
                check_names: Sequence[str] | None = None) -> dict[str, object]:
    """One candidate as a flat record for a table or a DataFrame: ``rank`` (where given),
    motor (and drive), law, spec, feasible, duration, peak and RMS torque, max speed, the
    load's speed and torque, ratio, gearbox, ``margin_<check>`` for every check (those of
    ``check_names``, None where a check does not apply to this candidate), the limiting
    check and its margin, the reason it fails, price, mass and rated power.

    Numbers in SI (:data:`RECORD_UNITS`), None for a figure that does not exist (never
    NaN or inf). As in the JSON, a candidate with no feasible duration (``minimize``) has
    no margins: its checks describe the longest duration tried, no operating point (its
    ``checks`` keep them: :meth:`SizingResult.to_records`).
    """
    out: dict[str, object] = {} if rank is None else {"rank": rank}
    out["motor"] = result.motor
    if result.drive is not None:
        out["drive"] = result.drive
    out.update({"law": result.law, "spec": result.spec, "feasible": bool(result.feasible)})
    for name in ("duration", "peak_torque", "rms_torque", "max_speed", "load_speed",
                 "load_torque", "ratio"):
        out[name] = _plain(getattr(result, name))
    out["gearbox"] = result.gearbox
    known = result.duration is not None
    names = check_names if check_names is not None else [c.name for c in result.checks]
    for name in names:
        margin = result.margin(name)
        out[f"margin_{name}"] = _plain(margin) if known and margin is not None else None
    out["limiting"] = None if result.limiting is None else str(result.limiting)
    limiting = result.margin(result.limiting) if result.limiting else None
    out["limiting_margin"] = _plain(limiting) if known and limiting is not None else None
    out["reason"] = result.reason
    out.update({"price": _plain(result.price), "mass": _plain(result.mass),
                "rated_power": _plain(result.rated_power)})
    return out
