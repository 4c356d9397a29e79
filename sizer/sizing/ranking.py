"""Order candidates the way engineers choose: feasible first, then the smallest drive that
passes with the required margins.

A ranking is a chain of criteria, each "smaller first": the key the user chose, then the
next meaningful ones (size, margin, rotor inertia), and finally a total order that no
input order reaches (:data:`TIES`): the motor id, then the canonical law spec, then the
ratio, then the catalog gearbox. So the same pairs rank the same whatever the order of the
catalogs, of the motors in them or of the laws in the design (a tie of two pairs that
differ in nothing the user can see is then harmless).

- ``size`` (the default with a given duration; alias ``power``): the motor's rated power
  tau_c*v_n, then its continuous torque, then the margin, then the rotor inertia.
- ``duration`` (the default with ``duration: minimize``): T_min, then size, then margin.
- ``margin``: the largest smallest slack (margin beyond the required one) first, then the
  next smallest..., then size.
- ``rms``, ``peak``: the smallest motor torque the task needs; ``price``, ``mass``: the
  cheapest or lightest motor (unknown values last); each then size and margin.
- ``worst_margin`` (alias ``robust``): only with the design's tolerances (``sizer size
  --robust``, sizer.robust): the largest worst-case margin over the builds first; the
  nominal sizing it reorders ranks by ``margin``.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from enum import StrEnum
from typing import TYPE_CHECKING

import numpy as np

from sizer.errors import UserError
from sizer.sizing.results import RESIDUAL, CandidateResult, Mode

if TYPE_CHECKING:
    from sizer.sizing.results import CandidateTable


class RankKey(StrEnum):
    """The keys of ``--rank-by``."""

    SIZE = "size"
    DURATION = "duration"
    MARGIN = "margin"
    RMS = "rms"
    PEAK = "peak"
    PRICE = "price"
    MASS = "mass"
    VIBRATION = "vibration"
    WORST_MARGIN = "worst_margin"


ROBUST_KEYS: frozenset[RankKey] = frozenset({RankKey.WORST_MARGIN})
"""Keys only a robust sizing orders by (``sizer size --robust``, sizer.robust): its
nominal sizing (and every build's) ranks by :func:`nominal_rank_by` of the key."""


RANK_ALIASES: dict[str, RankKey] = {"power": RankKey.SIZE, "robust": RankKey.WORST_MARGIN}
"""Other names accepted for a key (``power`` is the rated power, the ``size`` key)."""

RANK_KEYS: tuple[str, ...] = tuple(k.value for k in RankKey)


def _number(value: float | None) -> float:
    """A value to sort by, smaller first; unknown (None, NaN) last."""
    return math.inf if value is None or math.isnan(value) else float(value)


def _column(values: np.ndarray) -> np.ndarray:
    """``_number`` over an array: NaN last."""
    return np.where(np.isnan(values), np.inf, values)


@dataclass(frozen=True)
class Criterion:
    """One "smaller first" criterion, for a result row and for a whole table.

    ``row`` gives the sort key of one result; ``columns`` the same order as lexsort keys
    over a table (most significant first), one or several arrays.
    """

    name: str
    row: Callable[[CandidateResult], float | tuple]
    columns: Callable[[CandidateTable], list[np.ndarray]]


def _figure(name: str) -> Criterion:
    def columns(t: CandidateTable) -> list[np.ndarray]:
        known = t.feasible | (t.mode is not Mode.MINIMIZE)
        return [np.where(known, _column(t.figures[name]), np.inf)]
    return Criterion(name, lambda r: _number(getattr(r, name)), columns)


def _motor(name: str, attribute: str) -> Criterion:
    return Criterion(name, lambda r: _number(getattr(r, name)),
                     lambda t: [_column(t.motor_column(attribute))])


def _margin_row(r: CandidateResult) -> tuple[float, ...]:
    # the largest smallest slack first, then the next; an undefined slack (NaN) last
    return tuple(math.inf if math.isnan(s) else -s for s in r.slacks)


def margin_columns(t: CandidateTable) -> list[np.ndarray]:
    slacks = np.sort(np.where(np.isnan(t.slacks), -np.inf, t.slacks), axis=1)
    return list(-slacks.T)  # a check that does not apply (slack inf) sorts like an absent one


def rated_power_column(t: CandidateTable) -> list[np.ndarray]:
    return [_column(t.motor_column("continuous_torque") * t.motor_column("rated_speed"))]


_POWER = Criterion("rated_power", lambda r: _number(r.rated_power), rated_power_column)
_CONTINUOUS = _motor("continuous_torque", "continuous_torque")
_MARGIN = Criterion("margin", _margin_row, margin_columns)
_INERTIA = _motor("rotor_inertia", "inertia")


def _ranks(values: Sequence[str]) -> np.ndarray:
    """The rank of each text in sorted order (equal texts, equal ranks)."""
    return np.unique(np.array(values, dtype=object), return_inverse=True)[1].reshape(-1)


def _identity_columns(t: CandidateTable) -> list[np.ndarray]:
    motor = _ranks([m.id for m in t.motors])[t.motor]
    spec = _ranks([law.spec for law in t.laws])[t.law]
    ratio = _column(np.array([tr.ratio for tr in t.transmissions]))[t.option]
    gearbox = _ranks([g or "" for g in t.gearboxes])[t.option]
    return [motor, spec, ratio, gearbox]


_IDENTITY = Criterion(
    "identity", lambda r: (r.motor, r.spec, _number(r.ratio), r.gearbox or ""),
    _identity_columns)

_SIZE: tuple[Criterion, ...] = (_POWER, _CONTINUOUS)
_THEN: tuple[Criterion, ...] = (*_SIZE, _MARGIN, _INERTIA)
_THEN_TEXT = ", then the smallest motor (rated power tau_c*v_n), then the largest margin"
"""The ties of every key but size and margin, in words (the criteria of _THEN)."""

TIES: tuple[Criterion, ...] = (_IDENTITY,)
"""The last criterion of every rule, a total order: motor id, canonical law spec, ratio,
catalog gearbox name (each ascending)."""
TIES_TEXT = "motor id, law spec, ratio"
"""The final tie-break of every rule, in words."""


@dataclass(frozen=True)
class RankRule:
    """A key, the criteria it sorts by (each smaller first) and the rule in words."""

    key: RankKey
    criteria: tuple[Criterion, ...]
    text: str


RULES: dict[RankKey, RankRule] = {rule.key: rule for rule in (
    RankRule(RankKey.SIZE, (*_SIZE, _MARGIN, _INERTIA),
             "smallest motor first (rated power tau_c*v_n, then continuous torque), then the "
             "largest margin, then the smallest rotor inertia"),
    RankRule(RankKey.DURATION, (_figure("duration"), *_THEN),
             "shortest duration first" + _THEN_TEXT),
    RankRule(RankKey.MARGIN, (_MARGIN, *_SIZE, _INERTIA),
             "most room left at the tightest limit first, then the smallest motor (rated "
             "power tau_c*v_n)"),
    RankRule(RankKey.RMS, (_figure("rms_torque"), *_THEN),
             "smallest RMS torque first" + _THEN_TEXT),
    RankRule(RankKey.PEAK, (_figure("peak_torque"), *_THEN),
             "smallest peak torque first" + _THEN_TEXT),
    RankRule(RankKey.PRICE, (_motor("price", "price"), *_THEN),
             "cheapest motor first (unknown prices last)" + _THEN_TEXT),
    RankRule(RankKey.MASS, (_motor("mass", "mass"), *_THEN),
             "lightest motor first (unknown masses last)" + _THEN_TEXT),
    RankRule(RankKey.VIBRATION, (_figure(RESIDUAL), *_THEN),
             "smallest residual vibration first" + _THEN_TEXT),
    RankRule(RankKey.WORST_MARGIN, (_MARGIN, *_SIZE, _INERTIA),
             "largest worst-case margin over the design's tolerances first (sizer size "
             "--robust, which orders by it; a sizing of one machine has only its nominal "
             "margin, and orders by that), then the smallest motor (rated power tau_c*v_n)"),
)}


def default_rank_key(mode: Mode | str) -> RankKey:
    """Duration in minimize mode, size (the smallest motor that passes) otherwise (the
    mode's text accepted: a report reads it from a document)."""
    return RankKey.DURATION if mode == Mode.MINIMIZE else RankKey.SIZE


def rank_key(rank_by: str) -> RankKey | None:
    """The key a ``--rank-by`` text names (or an alias of it); None: no key."""
    name = rank_by.strip().lower()
    return RANK_ALIASES.get(name, next((k for k in RankKey if k == name), None))


RANK_CHOICES = ", ".join((*RANK_KEYS, *RANK_ALIASES))
"""The keys and aliases, in words (the message of an unknown key)."""


def is_robust_key(rank_by: str) -> bool:
    """Whether ``rank_by`` names a key of :data:`ROBUST_KEYS` (or an alias of one)."""
    return rank_key(rank_by) in ROBUST_KEYS


def nominal_rank_by(rank_by: str | None) -> str | None:
    """The key a robust sizing's nominal sizing ranks by: ``margin`` for worst_margin (the
    worst case's nominal counterpart, ordering its ties), else ``rank_by`` itself."""
    return RankKey.MARGIN.value if rank_by is not None and is_robust_key(rank_by) else rank_by


def rank_rule(rank_by: str | None, mode: Mode) -> RankRule:
    """The rule of a ``--rank-by`` key (None: the default of the mode); UserError if unknown."""
    key = default_rank_key(mode) if rank_by is None else rank_key(rank_by)
    if key is None:
        raise UserError(f"cannot rank by {rank_by!r}; choose one of {RANK_CHOICES}")
    return RULES[key]


def rank(results: Iterable[CandidateResult], rank_by: str | None,
         mode: Mode) -> list[CandidateResult]:
    """Feasible pairs first, then by the rule of ``rank_by`` (see the module docstring).

    What the rule's criteria leave tied is ordered by :data:`TIES` (motor id, law spec,
    ratio, gearbox), never by the order of the input.
    """
    rule = rank_rule(rank_by, mode)
    return sorted(results, key=lambda r: (not r.feasible, *(c.row(r) for c in rule.criteria),
                                          *(c.row(r) for c in TIES)))


def rank_order(table: CandidateTable, rank_by: str | None) -> np.ndarray:
    """The order of :func:`rank` for a whole table, by one lexsort over its arrays."""
    rule = rank_rule(rank_by, table.mode)
    if rule.key is RankKey.VIBRATION and RESIDUAL not in table.figures:
        raise UserError("ranking by vibration needs the load's mode: give "
                        "load.natural_frequency (and damping_ratio)", field="load")
    keys: list[np.ndarray] = [~table.feasible]
    for criterion in (*rule.criteria, *TIES):
        keys.extend(criterion.columns(table))
    keys = [np.broadcast_to(k, (len(table),)) for k in keys]
    return np.lexsort(keys[::-1])
