"""What a change of a design did to its sizing: two sizings compared pair by pair.

:func:`diff_sizings` takes the :class:`SizingResult` of a design before (A) and after (B)
a change and returns a :class:`DesignDiff` of plain records: no printing, no files.

- A pair is a motor (with its drive, where the design has drives) and a law as the design
  lists it (:class:`PairKey`): a law with ``auto`` parameters keeps its key when the solver
  chooses other values, and the chosen transmission option (ratio, catalog gearbox) is a
  compared field, so a change of the chosen gearbox reads as a change of that pair.
- Each pair's fields are those of the result rows (:func:`sizer.sizing.results.
  flat_record`): duration (T_min with ``duration: minimize``), peak and RMS torque,
  speeds, ratio, gearbox, ``margin_<check>`` of every check of either design, the limiting
  check and its margin, the motor's price, mass and rated power. ``rank`` and the
  ``reason`` text are kept in the records but not compared (the ranking and the words
  follow from the compared numbers).
- A pair in both is ``regressed`` (feasible in A, not in B), ``improved`` (the other way),
  ``changed`` (a compared field differs) or ``unchanged``; a pair only in A is
  ``removed``, only in B ``added``.
- Numbers are compared exactly: the sizing is deterministic, so identical inputs give an
  empty diff and any difference, however small, is reported.

:func:`design_changes` compares the two design documents (the mappings of their files)
field by field: what the change was, next to what it did.
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from enum import StrEnum
from typing import Any

from sizer.laws.per_move import PerMoveChoice
from sizer.model.domain import Design
from sizer.sizing.results import CandidateResult, SizingResult, flat_record

NOT_COMPARED = ("rank", "motor", "drive", "law", "reason")
"""Keys of a result row that are no compared field: the pair's key (motor, drive; the law
is keyed by its listed choice, the resolved ``spec`` is compared), the rank and the reason
text."""


class PairStatus(StrEnum):
    """What the change did to a pair, in the order a report lists them."""

    REGRESSED = "regressed"
    """Feasible in A, infeasible in B."""
    IMPROVED = "improved"
    """Infeasible in A, feasible in B."""
    CHANGED = "changed"
    """In both, same verdict, some compared field differs."""
    REMOVED = "removed"
    """Only in A (a motor or a law no longer sized)."""
    ADDED = "added"
    """Only in B."""
    UNCHANGED = "unchanged"
    """In both, every compared field equal."""


STATUS_ORDER = tuple(PairStatus)


@dataclass(frozen=True, order=True)
class PairKey:
    """A pair across two sizings: motor id, drive id ('' without drives) and the law as
    the design lists it (its ``auto`` parameters unresolved)."""

    motor: str
    drive: str
    law: str

    def label(self) -> str:
        """'motor / law' or 'motor + drive / law'."""
        drive = f" + {self.drive}" if self.drive else ""
        return f"{self.motor}{drive} / {self.law}"


@dataclass(frozen=True)
class FieldChange:
    """One compared field of a pair: its value in A and in B (None where it has none)."""

    field: str
    before: object
    after: object

    @property
    def change(self) -> float | None:
        """after - before, where both are numbers (not booleans); else None."""
        if _number(self.before) and _number(self.after):
            return float(self.after) - float(self.before)  # type: ignore[arg-type]
        return None


@dataclass(frozen=True)
class PairDiff:
    """One pair: its status, its row in A and in B (None where absent) and the compared
    fields that differ, in the rows' field order."""

    key: PairKey
    status: PairStatus
    before: Mapping[str, object] | None
    after: Mapping[str, object] | None
    changes: tuple[FieldChange, ...] = ()

    def change(self, name: str) -> FieldChange | None:
        return next((c for c in self.changes if c.field == name), None)


@dataclass(frozen=True)
class DesignChange:
    """A field of the design documents that differs: its dotted path and its value in A and
    B as compact text (None where absent)."""

    field: str
    before: str | None
    after: str | None


@dataclass(frozen=True)
class DesignDiff:
    """Two sizings compared: every pair of either (:class:`PairDiff`, in
    :data:`STATUS_ORDER`, then by rank in B, or in A for a removed pair), the fields of
    their rows (``fields``) and the design changes."""

    name_a: str
    name_b: str
    mode_a: str
    mode_b: str
    pairs: tuple[PairDiff, ...]
    fields: tuple[str, ...]
    design: tuple[DesignChange, ...] = field(default=())

    @property
    def regressions(self) -> tuple[PairDiff, ...]:
        """Pairs feasible in A and infeasible in B (the exit code 1 of ``sizer diff``)."""
        return tuple(p for p in self.pairs if p.status is PairStatus.REGRESSED)

    @property
    def compared(self) -> tuple[str, ...]:
        """The fields compared (``fields`` without :data:`NOT_COMPARED`)."""
        return tuple(f for f in self.fields if f not in NOT_COMPARED)

    def counts(self) -> dict[str, int]:
        """How many pairs have each status (every status, zeros too)."""
        return {str(s): sum(p.status is s for p in self.pairs) for s in STATUS_ORDER}

    @property
    def empty(self) -> bool:
        """No pair changed and the design documents are equal."""
        return not self.design and all(p.status is PairStatus.UNCHANGED for p in self.pairs)

    def pair(self, key: PairKey) -> PairDiff | None:
        return next((p for p in self.pairs if p.key == key), None)

    def to_records(self) -> list[dict[str, object]]:
        """The diff as flat records, one per pair and compared field that differs (a pair
        only in A or B: one per field of its row, the missing side None): ``motor``,
        ``drive``, ``law``, ``status``, ``field``, ``before``, ``after``, ``change``
        (after - before for numbers, else None). Unchanged pairs give none."""
        out: list[dict[str, object]] = []
        for p in self.pairs:
            if p.status is PairStatus.UNCHANGED:
                continue
            for c in p.changes:
                out.append({"motor": p.key.motor, "drive": p.key.drive or None,
                            "law": p.key.law, "status": str(p.status), "field": c.field,
                            "before": c.before, "after": c.after, "change": c.change})
        return out


def _number(value: object) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool) \
        and math.isfinite(float(value))


def ranked_choices(design: Design) -> tuple[object, ...]:
    """The law choices a sizing of ``design`` keys its rows by (:func:`keyed_rows`): its
    laws, and with ``laws: per_move`` that one choice."""
    if design.machine_cycle.share.per_move:
        return (*design.laws, PerMoveChoice(tuple(design.laws)))
    return tuple(design.laws)


def _law_key(result: CandidateResult, choices: Sequence[object]) -> str:
    """The law as the design lists it: the first choice ``result``'s law comes from (same
    family, its fixed values equal), else the law's own spec; with a law per move
    (``laws: per_move``, every motor one row) the choice itself, whatever laws it took."""
    spec = result.spec
    if any(isinstance(choice, PerMoveChoice) for choice in choices):
        return PerMoveChoice.text
    for choice in choices:
        if str(choice) == spec:
            return spec
    for choice in choices:
        family = getattr(choice, "family", None)
        fixed = getattr(choice, "fixed", None)
        if family is None or fixed is None or getattr(choice, "is_fixed", True):
            continue
        if not isinstance(result.law_object, family):
            continue
        params = result.params
        if all(name in params and float(params[name]) == float(value)
               for name, value in fixed.items()):
            return str(choice)
    return spec


def keyed_rows(sizing: SizingResult, check_names: Sequence[str],
               choices: Sequence[object] = ()) -> dict[PairKey, dict[str, object]]:
    """Each result row of ``sizing`` (:func:`flat_record` with the ``check_names``
    margins, its rank) by its :class:`PairKey`, in rank order. ``choices``: the design's
    law choices (``Design.laws``), to key a law with ``auto`` parameters by its listed text.
    A key met twice (one pair with several transmission options) gets the option's ratio
    and gearbox added to its law text."""
    rows: dict[PairKey, dict[str, object]] = {}
    for rank, result in enumerate(sizing.results, 1):
        row = flat_record(result, rank, check_names)
        key = PairKey(result.motor, result.drive or "", _law_key(result, choices))
        if key in rows:
            gearbox = f", gearbox {result.gearbox}" if result.gearbox else ""
            key = PairKey(key.motor, key.drive, f"{key.law} [ratio {result.ratio!r}{gearbox}]")
        rows[key] = row
    return rows


def diff_sizings(a: SizingResult, b: SizingResult, *, laws_a: Sequence[object] = (),
                 laws_b: Sequence[object] = (),
                 design: Sequence[DesignChange] = ()) -> DesignDiff:
    """The pairs of ``a`` (before) and ``b`` (after) compared field by field
    (module docstring). ``laws_a`` and ``laws_b``: the designs' law choices
    (``Design.laws``), so that a law with ``auto`` parameters is one pair in both;
    ``design``: the design changes to carry (:func:`design_changes`)."""
    checks = tuple(dict.fromkeys((*a.check_names(), *b.check_names())))
    rows_a = keyed_rows(a, checks, laws_a)
    rows_b = keyed_rows(b, checks, laws_b)
    first = next(iter(rows_a.values()), None) or next(iter(rows_b.values()), None)
    fields = tuple(first) if first is not None else ()
    if any(tuple(r) != fields for r in (*rows_a.values(), *rows_b.values())):
        # drives in one design only: the union of the keys, in order
        fields = tuple(dict.fromkeys(k for r in (*rows_a.values(), *rows_b.values())
                                     for k in r))
    compared = [f for f in fields if f not in NOT_COMPARED]
    pairs: list[tuple[tuple[int, int], PairDiff]] = []
    for key in (*rows_a, *(k for k in rows_b if k not in rows_a)):
        before, after = rows_a.get(key), rows_b.get(key)
        changes = tuple(
            FieldChange(name, None if before is None else before.get(name),
                        None if after is None else after.get(name))
            for name in compared
            if before is None or after is None or not _same(before.get(name),
                                                            after.get(name)))
        status = _status(before, after, bool(changes))
        rank = (after or before or {}).get("rank", 0)
        order = (STATUS_ORDER.index(status), int(rank))  # type: ignore[call-overload]
        pairs.append((order, PairDiff(key, status, before, after, changes)))
    pairs.sort(key=lambda item: (item[0], item[1].key))
    return DesignDiff(a.design_name, b.design_name, str(a.mode), str(b.mode),
                      tuple(p for _, p in pairs), fields, tuple(design))


def _same(x: object, y: object) -> bool:
    if isinstance(x, float) and isinstance(y, float) and math.isnan(x) and math.isnan(y):
        return True
    return x == y


def _status(before: Mapping[str, object] | None, after: Mapping[str, object] | None,
            changed: bool) -> PairStatus:
    if before is None:
        return PairStatus.ADDED
    if after is None:
        return PairStatus.REMOVED
    if before["feasible"] and not after["feasible"]:
        return PairStatus.REGRESSED
    if after["feasible"] and not before["feasible"]:
        return PairStatus.IMPROVED
    return PairStatus.CHANGED if changed else PairStatus.UNCHANGED


def design_changes(a: Mapping[str, Any], b: Mapping[str, Any],
                   depth: int = 3) -> tuple[DesignChange, ...]:
    """The fields of two design documents (their files' mappings) that differ, as dotted
    paths down to ``depth`` levels of mappings (a list, or anything deeper, compared
    whole), in the order of A's keys then B's new ones; values as compact JSON-like text
    (a string as it is written)."""
    out: list[DesignChange] = []
    _walk(a, b, (), depth, out)
    return tuple(out)


_MISSING = object()


def _walk(a: object, b: object, path: tuple[str, ...], depth: int,
          out: list[DesignChange]) -> None:
    if isinstance(a, Mapping) and isinstance(b, Mapping) and len(path) < depth:
        for name in (*a, *(k for k in b if k not in a)):
            _walk(a.get(name, _MISSING), b.get(name, _MISSING), (*path, str(name)), depth,
                  out)
        return
    if a is _MISSING and b is _MISSING:
        return
    if a is not _MISSING and b is not _MISSING and _text(a) == _text(b):
        return
    out.append(DesignChange(".".join(path),
                            None if a is _MISSING else _text(a),
                            None if b is _MISSING else _text(b)))


def _text(value: object) -> str:
    if isinstance(value, str):
        return value
    return json.dumps(value, sort_keys=False, default=str, ensure_ascii=False)
