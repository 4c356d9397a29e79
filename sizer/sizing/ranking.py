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
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from enum import StrEnum

from sizer.errors import UserError
from sizer.sizing.results import CandidateResult


class RankKey(StrEnum):
    """The keys of ``--rank-by``."""

    SIZE = "size"
    DURATION = "duration"
    MARGIN = "margin"
    RMS = "rms"
    PEAK = "peak"
    PRICE = "price"
    MASS = "mass"


RANK_ALIASES: dict[str, RankKey] = {"power": RankKey.SIZE}
"""Other names accepted for a key (``power`` is the rated power, the ``size`` key)."""

RANK_KEYS: tuple[str, ...] = tuple(k.value for k in RankKey)


def _number(value: float | None) -> float:
    """A value to sort by, smaller first; unknown (None, NaN) last."""
    return math.inf if value is None or math.isnan(value) else float(value)


Criterion = Callable[[CandidateResult], float | tuple[float, ...]]


def _power(r: CandidateResult) -> float:
    return _number(r.rated_power)


def _continuous_torque(r: CandidateResult) -> float:
    return _number(r.continuous_torque)


def _margin(r: CandidateResult) -> tuple[float, ...]:
    # the largest smallest slack first, then the next; an undefined slack (NaN) last
    return tuple(math.inf if math.isnan(s) else -s for s in r.slacks)


def _inertia(r: CandidateResult) -> float:
    return _number(r.rotor_inertia)


_SIZE: tuple[Criterion, ...] = (_power, _continuous_torque)
_THEN: tuple[Criterion, ...] = (*_SIZE, _margin, _inertia)
_THEN_TEXT = ", then the smallest motor (rated power tau_c*v_n), then the largest margin"
"""The ties of every key but size and margin, in words (the criteria of _THEN)."""


def _identity(r: CandidateResult) -> tuple[str, str, float, str]:
    return (r.motor, r.spec, _number(r.ratio), r.gearbox or "")


TIES: tuple[Criterion, ...] = (_identity,)
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
    RankRule(RankKey.SIZE, (*_SIZE, _margin, _inertia),
             "smallest motor first (rated power tau_c*v_n, then continuous torque), then the "
             "largest margin, then the smallest rotor inertia"),
    RankRule(RankKey.DURATION, (lambda r: _number(r.duration), *_THEN),
             "shortest duration first" + _THEN_TEXT),
    RankRule(RankKey.MARGIN, (_margin, *_SIZE, _inertia),
             "most room left at the tightest limit first, then the smallest motor (rated "
             "power tau_c*v_n)"),
    RankRule(RankKey.RMS, (lambda r: _number(r.rms_torque), *_THEN),
             "smallest RMS torque first" + _THEN_TEXT),
    RankRule(RankKey.PEAK, (lambda r: _number(r.peak_torque), *_THEN),
             "smallest peak torque first" + _THEN_TEXT),
    RankRule(RankKey.PRICE, (lambda r: _number(r.price), *_THEN),
             "cheapest motor first (unknown prices last)" + _THEN_TEXT),
    RankRule(RankKey.MASS, (lambda r: _number(r.mass), *_THEN),
             "lightest motor first (unknown masses last)" + _THEN_TEXT),
)}


def default_rank_key(mode: str) -> RankKey:
    """Duration in minimize mode, size (the smallest motor that passes) otherwise."""
    return RankKey.DURATION if mode == "minimize" else RankKey.SIZE


def rank_rule(rank_by: str | None, mode: str) -> RankRule:
    """The rule of a ``--rank-by`` key (None: the default of the mode); UserError if unknown."""
    if rank_by is None:
        return RULES[default_rank_key(mode)]
    name = rank_by.strip().lower()
    key = RANK_ALIASES.get(name)
    if key is None:
        try:
            key = RankKey(name)
        except ValueError:
            known = ", ".join((*RANK_KEYS, *RANK_ALIASES))
            raise UserError(f"cannot rank by {rank_by!r}; choose one of {known}") from None
    return RULES[key]


def rank(results: Iterable[CandidateResult], rank_by: str | None,
         mode: str) -> list[CandidateResult]:
    """Feasible pairs first, then by the rule of ``rank_by`` (see the module docstring).

    What the rule's criteria leave tied is ordered by :data:`TIES` (motor id, law spec,
    ratio, gearbox), never by the order of the input.
    """
    rule = rank_rule(rank_by, mode)
    return sorted(results, key=lambda r: (not r.feasible, *(c(r) for c in rule.criteria),
                                          *(c(r) for c in TIES)))
