"""A law for each move of a cycle: ``share: {optimize: GOAL, laws: per_move}`` (issue 39,
docs/allocation.md).

The combination of the design's laws that one candidate's sizing chose for the moves
that name no law of their own, in the cycle's order. It is not a motion law (it has no
one normalized profile): a cycle's engine reads it in place of the ranked law, spread over
those moves (sizer.sizing.cycle.cycle_laws), and a result reports it in the law's place,
its spec listing the laws.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar, TypeAlias

from sizer.laws.base import MotionLaw
from sizer.laws.choice import LawChoice


@dataclass(frozen=True)
class LawsPerMove:
    """``laws``: the law of each move that names none, in the cycle's order (at least two
    distinct: one law for every move is that law itself)."""

    laws: tuple[MotionLaw, ...]
    law_id: ClassVar[str] = "per_move"

    @property
    def spec(self) -> str:
        """``per_move(LAW; LAW; ...)``: each move's law by its spec, in the cycle's order."""
        return f"{self.law_id}({'; '.join(law.spec for law in self.laws)})"

    @property
    def params(self) -> dict[str, float]:
        """No parameters of its own (each law has its own in the spec)."""
        return {}

    def __str__(self) -> str:
        return self.spec


RankedLaw: TypeAlias = MotionLaw | LawsPerMove
"""What a cycle is sized with for the moves that name no law: one law, or one each."""


def per_move(laws: tuple[MotionLaw, ...]) -> RankedLaw:
    """The combination of ``laws`` (one per move that names none), or the law itself where
    every move takes the same one."""
    if len(set(laws)) == 1:
        return laws[0]
    return LawsPerMove(laws)


@dataclass(frozen=True)
class PerMoveChoice:
    """The one law choice a sizing ranks with ``laws: per_move``: every candidate its own
    law of ``laws`` (fixed laws, the design's that meet the moves' boundary speeds) for
    each move that names none, chosen with the split (sizer.sizing.engine)."""

    laws: tuple[LawChoice, ...]
    text: ClassVar[str] = "per_move"

    def __str__(self) -> str:
        return self.text


def one_law(law: RankedLaw) -> MotionLaw:
    """``law`` where one law is meant (a move alone, its profile): a law per move is a
    cycle's only (ValueError)."""
    if isinstance(law, LawsPerMove):
        raise ValueError(f"{law.spec} is a cycle's: each move has its own law")
    return law
