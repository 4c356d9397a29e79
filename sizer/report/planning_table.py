"""The plan of a design without a motor (sizer.sizing.planning): table, CSV, JSON, Markdown.

One row per law, in the result's order (feasible first, by T_min or by lambda). The
figures are the result's: this module formats them and decides nothing.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

from sizer.report.csv_text import render_csv
from sizer.report.formats import Format
from sizer.report.json_text import render_json
from sizer.report.numbers import finite_or_none, full_or_empty, short_or_na
from sizer.report.table import Column, Table, make_table
from sizer.sizing.planning import LawPlan, PlanningResult, SegmentPlan

NO_FEASIBLE_LAW = "no feasible law"
"""The line on stderr when no law is feasible and the output is not shown to a person."""

CSV_HEADERS = ("rank", "law", "feasible", "T_min", "duration", "lambda", "scale", "binding",
               "segment", "T_vel", "T_acc", "T_jerk", "reason")
"""CSV columns (s; T_vel, T_acc, T_jerk of the deciding move; empty where none)."""


def _terms(result: PlanningResult,
           seg: SegmentPlan | None) -> tuple[float | None, float | None, float | None]:
    """T_vel, T_acc, T_jerk of a move; None where its limit is not given (or no move)."""
    if seg is None:
        return (None, None, None)
    v, a, j = result.limits.values
    return (None if v is None else seg.T_vel, None if a is None else seg.T_acc,
            None if j is None else seg.T_jerk)


def _deciding_terms(result: PlanningResult,
                    plan: LawPlan) -> tuple[float | None, float | None, float | None]:
    """T_vel, T_acc, T_jerk of the move that decides."""
    return _terms(result, next((s for s in plan.segments if s.name == plan.segment), None))


def _limits_text(result: PlanningResult) -> str:
    length = "m" if result.linear else "rad"
    names = ("v_max", "a_max", "j_max")
    return ", ".join(f"{name} {short_or_na(value)} {length}/s{power}"
                     for name, value, power in zip(names, result.limits.values,
                                                   ("", "^2", "^3"), strict=True)
                     if value is not None)


class PlanningDocument:
    """A planning result in every format."""

    def __init__(self, result: PlanningResult, *, top: int | None = None) -> None:
        self.result = result
        self.plans = result.plans[:top] if top is not None else result.plans
        ranks, n = [], 0
        for plan in self.plans:
            n += plan.feasible
            ranks.append(str(n) if plan.feasible else "-")
        self.ranks = ranks

    @property
    def any_feasible(self) -> bool:
        return self.result.any_feasible

    @property
    def title(self) -> str:
        r = self.result
        what = ("shortest durations" if r.minimize else "scaling factors lambda (eq. 5.4)")
        return f"{r.name}: {what} without a motor, limits at the load: {_limits_text(r)}"

    def table(self) -> Table:
        r = self.result
        time = "T" if r.task else "cycle"
        cycle = [] if r.task else [Column("segment", "left")]
        if r.minimize:
            columns = [Column("#"), Column("law", "left"), Column(f"{time}_min s"),
                       Column("binding", "left"), *cycle, Column("T_vel s"),
                       Column("T_acc s"), Column("T_jerk s"), Column("note", "left")]
        else:
            columns = [Column("#"), Column("law", "left"), Column(f"{time} s"),
                       Column("lambda"), Column("binding", "left"), *cycle,
                       Column(f"{time}/lambda s"), Column("note", "left")]
        rows = []
        for rank, plan in zip(self.ranks, self.plans, strict=True):
            where = [] if r.task else [plan.segment or ""]
            if r.minimize:
                rows.append([rank, plan.law, short_or_na(plan.T_min), plan.binding or "",
                             *where, *(short_or_na(x) for x in _deciding_terms(self.result, plan)),
                             plan.reason])
            else:
                rows.append([rank, plan.law, short_or_na(plan.duration),
                             short_or_na(plan.lam), plan.binding or "", *where,
                             short_or_na(plan.T_min), plan.reason])
        return make_table(columns, rows, title=self.title)

    def csv(self) -> str:
        rows = []
        for rank, plan in zip(self.ranks, self.plans, strict=True):
            rows.append((
                rank if plan.feasible else "", plan.law, "true" if plan.feasible else "false",
                full_or_empty(plan.T_min), full_or_empty(plan.duration),
                full_or_empty(plan.lam), full_or_empty(plan.scale), plan.binding or "",
                plan.segment or "",
                *(full_or_empty(x) for x in _deciding_terms(self.result, plan)),
                plan.reason))
        return render_csv(CSV_HEADERS, rows)

    def json(self) -> str:
        r = self.result
        length = "m" if r.linear else "rad"
        return render_json({
            "design": r.name,
            "plan": "without a motor",
            "mode": "minimize" if r.minimize else "given duration",
            "axis": "linear" if r.linear else "rotary",
            "units": {"time": "s", "displacement": length, "max_speed": f"{length}/s",
                      "max_acceleration": f"{length}/s^2", "max_jerk": f"{length}/s^3"},
            "limits": dict(zip(("max_speed", "max_acceleration", "max_jerk"),
                               r.limits.values, strict=True)),
            "any_feasible": r.any_feasible,
            "laws": [_plan_json(r, rank, plan)
                     for rank, plan in zip(self.ranks, self.plans, strict=True)],
        })

    def render(self, fmt: Format) -> str:
        from sizer.report.document import render_text

        return render_text(self, fmt)


def _plan_json(result: PlanningResult, rank: str, plan: LawPlan) -> dict[str, Any]:
    return {
        "rank": int(rank) if plan.feasible else None,
        "law": plan.law,
        "feasible": plan.feasible,
        "reason": plan.reason,
        "T_min": finite_or_none(plan.T_min),  # null: no duration is feasible
        "duration": finite_or_none(plan.duration),
        "lambda": finite_or_none(plan.lam),
        "scale": finite_or_none(plan.scale),
        "binding": plan.binding,
        "segment": plan.segment,
        "segments": [{
            "name": s.name, "law": s.law, "displacement": s.displacement,
            "duration": finite_or_none(s.duration), "free": s.free,
            **{key: finite_or_none(value) for key, value in zip(
                ("T_vel", "T_acc", "T_jerk"), _terms(result, s), strict=True)},
            "T_min": finite_or_none(s.T_min),
            "lambda": finite_or_none(s.lam), "binding": s.binding,
        } for s in plan.segments],
    }


def publish_planning(document: PlanningDocument, fmt: Format, output: Path | None) -> None:
    """Write the plan to ``output`` or stdout (a rich table on a terminal); the line 'no
    feasible law' on stderr when none is and the output is not shown to a person."""
    from sizer.report.output import emit, stdout_is_terminal

    if fmt is Format.TABLE and output is None and stdout_is_terminal():
        _print_terminal(document)
        return
    emit(document.render(fmt), output, escape=fmt in (Format.TABLE, Format.MD))
    shown_to_user = output is None and fmt in (Format.TABLE, Format.MD)
    if not document.any_feasible and not shown_to_user:
        sys.stderr.write(NO_FEASIBLE_LAW + "\n")
        sys.stderr.flush()


def _print_terminal(document: PlanningDocument) -> None:
    """The rich table without its note column, each infeasible law's reason under it
    (a long reason would squeeze the numbers on an 80-column terminal)."""
    from rich.console import Console
    from rich.text import Text

    from sizer.report.printable import printable
    from sizer.report.rich_table import print_rich_table, without_columns

    console = Console(highlight=False)
    print_rich_table(without_columns(document.table(), ["note"]), wrap_headers=True,
                     title_above=True, console=console)
    for plan in document.plans:
        if plan.reason:
            console.print(Text(printable(f"{plan.law}: {plan.reason}")))
    if not document.any_feasible:
        console.print(Text(NO_FEASIBLE_LAW))
