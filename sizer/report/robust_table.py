"""``sizer size --robust``: the sizing table with each pair's worst case over the corners
of the design's tolerances (sizer.robust, docs/robust.md)."""

from __future__ import annotations

import json
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from sizer.report.candidate_row import percent
from sizer.report.json_text import render_json
from sizer.report.numbers import finite_or_none
from sizer.report.sizing_table import SizingDocument
from sizer.report.table import Column, Table, make_table

if TYPE_CHECKING:
    from sizer.model.domain import Design
    from sizer.robust import Corner, RobustResult, RobustSizing

RANKING = ("the pairs feasible at every corner first, then as usual (the nominal "
           "ranking within each group)")


def corner_text(corner: Corner) -> str:
    """'load.inertia +20 %, motor.peak_torque -10 %'."""
    return ", ".join(f"{name} {change * 100.0:+g} %" for name, change in corner)


def _corner_json(corner: Corner) -> dict[str, float]:
    return {name: change for name, change in corner}


class RobustDocument(SizingDocument):
    """The robust sizing's ranked results (sizer.report.sizing_table.SizingDocument) with
    a worst-case margin column and, in JSON, a ``robust`` object per result."""

    def __init__(self, robust: RobustSizing, design: Design, **options: Any) -> None:
        super().__init__(robust.sizing, design, **options)
        self.robust = robust
        self._of = {id(r.nominal): r for r in robust.results}

    def table(self, compact: bool = False) -> Table:
        base = super().table(compact)
        columns = (*base.columns, Column("worst margin [%]"), Column("robust", "left"))
        rows = [(*row, percent(finite_or_none(self._of[id(r)].margin)),
                 _verdict(self._of[id(r)]))
                for row, (_, r) in zip(base.rows, self.rows, strict=True)]
        return make_table(columns, rows, title=base.title)

    def footer(self, dropped: Sequence[str] = ()) -> list[str]:
        count = self.robust.results[0].corners if self.robust.results else 0
        tolerances = ", ".join(f"{n} +-{t * 100.0:g} %" for n, t in self.robust.tolerances)
        lines = [f"robust: every pair at the {count} corners of {tolerances}; 'worst "
                 f"margin' is the least margin over them (exact where the margins are "
                 f"monotone in the inputs; --format json names each check's corner)",
                 f"ranked robustly: {RANKING}"]
        for rank, r in self.rows:
            worst = self._of[id(r)]
            if worst.limiting is not None and not worst.feasible:
                lines.append(f"  #{rank} {r.motor}: worst {worst.limiting} at "
                             f"{corner_text(worst.corner[worst.limiting])}")
        return [*super().footer(dropped), *lines]

    def json(self) -> str:
        data = json.loads(super().json())
        data["tolerances"] = {n: t for n, t in self.robust.tolerances}
        data["robust_ranking"] = RANKING
        for item, (_, r) in zip(data["results"], self.rows, strict=True):
            item["robust"] = robust_json(self._of[id(r)])
        return render_json(data)


def _verdict(result: RobustResult) -> str:
    if result.feasible:
        return "ok"
    return f"FAILS at {result.failing}/{result.corners}"


def robust_json(result: RobustResult) -> dict[str, Any]:
    """A pair's ``robust`` object: the verdict, the least worst-case margin, its check and
    corner, and each check's worst-case margin and corner."""
    limiting = result.limiting
    return {
        "feasible": result.feasible,
        "failing_corners": result.failing,
        "corners": result.corners,
        "margin": finite_or_none(result.margin),
        "limiting": limiting,
        "corner": _corner_json(result.corner[limiting]) if limiting is not None else None,
        "checks": {name: {"margin": finite_or_none(margin),
                          "corner": _corner_json(result.corner[name])}
                   for name, margin in result.worst.items()},
    }
