"""A design diff (``sizer diff``, sizer.sizing.design_diff) in every format.

- Terminal table and plain text: a summary (how many pairs regressed, improved, changed,
  were removed or added), the design fields that differ, then one row per changed field
  of each pair: its value before and after and the change (margins in %, their change in
  percentage points; other numbers SI, with the relative change).
- Markdown (a pull-request comment): the same summary first, the regressions and newly
  feasible pairs listed with their limiting check, then the details table in a
  collapsible block.
- JSON: ``{"format", "a", "b", "summary", "regression", "design_changes", "fields",
  "units", "pairs"}``, every pair with its status, the fields that changed and its whole
  row in A and B (sizer.sizing.results.flat_record: SI, margins as fractions).
- CSV: the records of :meth:`DesignDiff.to_records`, one line per pair and changed field.

Nothing is decided here: the statuses and the changes are the diff's.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from sizer.laws.data_spec import law_label
from sizer.report.candidate_row import percent
from sizer.report.csv_text import render_csv
from sizer.report.formats import Format, Rendered
from sizer.report.json_text import render_json
from sizer.report.markdown_table import render_markdown_table
from sizer.report.numbers import NOISE, full, short
from sizer.report.output import emit, stdout_is_terminal
from sizer.report.printable import printable
from sizer.report.table import Column, Table, make_table
from sizer.report.text_table import render_text_table
from sizer.sizing.design_diff import PairDiff, PairStatus
from sizer.sizing.results import RECORD_UNITS

if TYPE_CHECKING:
    from sizer.sizing.design_diff import DesignDiff, FieldChange

FORMAT = "sizer.diff/1"
"""The ``format`` of the JSON document: its name and version."""

CSV_HEADERS = ("motor", "drive", "law", "status", "field", "before", "after", "change")

STATUS_WORDS = {
    PairStatus.REGRESSED: "regressed (feasible before, fails now)",
    PairStatus.IMPROVED: "improved (fails before, feasible now)",
    PairStatus.CHANGED: "changed",
    PairStatus.REMOVED: "removed (only before)",
    PairStatus.ADDED: "added (only after)",
    PairStatus.UNCHANGED: "unchanged",
}

NONE = "-"
"""A value a pair does not have (absent on that side, or no such figure)."""


@dataclass(frozen=True)
class DiffDocument(Rendered):
    """A design diff with the names of its two sides (file paths or ``REV:path``)."""

    diff: DesignDiff
    label_a: str
    label_b: str

    # ------------------------------------------------------------- texts
    @property
    def title(self) -> str:
        return f"sizer diff: {self.label_a} -> {self.label_b}"

    def summary(self) -> str:
        """One line: the count of each status (zeros left out), or that nothing changed."""
        counts = self.diff.counts()
        shown = [f"{n} {status}" for status, n in counts.items() if n]
        if self.diff.empty:
            return f"no change: {len(self.diff.pairs)} motor/law pairs, every field equal"
        return f"{len(self.diff.pairs)} motor/law pairs: " + ", ".join(shown)

    def mode_line(self) -> str | None:
        if self.diff.mode_a == self.diff.mode_b:
            return None
        return (f"mode changed: {self.diff.mode_a} -> {self.diff.mode_b} (the duration is "
                f"T_min with minimize)")

    def design_lines(self) -> list[str]:
        return [f"{c.field}: {_brief(c.before)} -> {_brief(c.after)}"
                for c in self.diff.design]

    def verdict_lines(self) -> list[str]:
        """A line per regressed or improved pair: its limiting check and margin, A -> B."""
        lines = []
        for p in self.diff.pairs:
            if p.status in (PairStatus.REGRESSED, PairStatus.IMPROVED):
                lines.append(f"{p.status}: {_label(p)}: {_limiting(p)}")
        return lines

    def rows(self) -> list[tuple[str, ...]]:
        """One row per changed field; a pair's cells on its first row only."""
        out: list[tuple[str, ...]] = []
        for p in self.diff.pairs:
            if p.status is PairStatus.UNCHANGED:
                continue
            first = True
            for c in _shown_changes(p):
                pair = (_label(p), str(p.status)) if first else ("", "")
                out.append((*pair, c.field, _cell(c.field, c.before), _cell(c.field, c.after),
                            _change_cell(c)))
                first = False
        return out

    def table(self) -> Table:
        columns = (Column("pair", "left"), Column("status", "left"), Column("field", "left"),
                   Column("before"), Column("after"), Column("change"))
        return make_table(columns, self.rows(), title=self.title)

    def notes(self) -> list[str]:
        return ["margins in % of the limit left unused (change in percentage points); other "
                "numbers SI (s, N*m, rad/s; the units of sizer size --format json), change "
                "after - before with the relative change",
                "a pair only before or after lists its own row: feasible, limiting and "
                "duration"]

    # ------------------------------------------------------------- formats
    def head_lines(self) -> list[str]:
        """The lines above the table: title, summary, design changes, verdicts."""
        lines = [self.title, "", self.summary()]
        lines += [x for x in (self.mode_line(),) if x]
        if self.diff.design:
            lines += ["", "design changes:", *(f"  {x}" for x in self.design_lines())]
        if self.verdict_lines():
            lines += ["", *self.verdict_lines()]
        return lines

    def plain_text(self) -> str:
        text = "\n".join(self.head_lines()) + "\n"
        if self.rows():
            text += "\n" + render_text_table(self.table()) + "\n" + \
                "\n".join(f"note: {n}" for n in self.notes()) + "\n"
        return text

    def markdown(self) -> str:
        regressions = len(self.diff.regressions)
        head = (f"**{regressions} regression{'s' if regressions != 1 else ''}**: "
                if regressions else "")
        lines = [f"### {_md(self.title)}", "", head + _md(self.summary())]
        lines += [_md(x) for x in (self.mode_line(),) if x]
        if self.diff.design:
            lines += ["", "Design changes:", ""]
            lines += [f"- `{c.field}`: {_code(_brief(c.before))} → {_code(_brief(c.after))}"
                      for c in self.diff.design]
        if self.verdict_lines():
            lines += [""] + [f"- {_md(x)}" for x in self.verdict_lines()]
        text = "\n".join(lines) + "\n"
        rows = self.rows()
        if rows:
            table = Table(self.table().columns, self.table().rows)
            text += (f"\n<details><summary>{len(rows)} changed fields</summary>\n\n"
                     + render_markdown_table(table) + "\n"
                     + "\n".join(f"_{_md(n)}_" for n in self.notes())
                     + "\n\n</details>\n")
        return text

    def json(self) -> str:
        diff = self.diff
        units = {**RECORD_UNITS, **{f: "1" for f in diff.fields if f.startswith("margin_")}}
        return render_json({
            "format": FORMAT,
            "a": {"file": self.label_a, "design": diff.name_a, "mode": diff.mode_a},
            "b": {"file": self.label_b, "design": diff.name_b, "mode": diff.mode_b},
            "summary": diff.counts(),
            "regression": bool(diff.regressions),
            "design_changes": [{"field": c.field, "before": c.before, "after": c.after}
                               for c in diff.design],
            "fields": list(diff.compared),
            "units": {f: units.get(f, "") for f in diff.fields},
            "pairs": [_pair_json(p) for p in diff.pairs],
        })

    def csv(self) -> str:
        rows = [tuple(_csv_cell(r[h]) for h in CSV_HEADERS) for r in self.diff.to_records()]
        return render_csv(CSV_HEADERS, rows)


def _label(p: PairDiff) -> str:
    """The pair as tables name it: 'motor / law' (a data law by its short label)."""
    drive = f" + {p.key.drive}" if p.key.drive else ""
    return f"{p.key.motor}{drive} / {law_label(p.key.law)}"


def _pair_json(p: PairDiff) -> dict[str, Any]:
    return {"motor": p.key.motor, "drive": p.key.drive or None, "law": p.key.law,
            "status": str(p.status),
            "changes": [{"field": c.field, "before": c.before, "after": c.after,
                         "change": c.change} for c in p.changes],
            "before": None if p.before is None else dict(p.before),
            "after": None if p.after is None else dict(p.after)}


SHOWN_ALONE = ("feasible", "spec", "limiting", "limiting_margin", "duration")
"""The fields a table shows of a pair only before or after (the JSON and CSV keep all)."""


def _shown_changes(p: PairDiff) -> Sequence[FieldChange]:
    if p.status in (PairStatus.ADDED, PairStatus.REMOVED):
        return [c for c in p.changes if c.field in SHOWN_ALONE]
    return p.changes


def _limiting(p: PairDiff) -> str:
    before, after = p.before or {}, p.after or {}

    def side(row: Any) -> str:
        margin = row.get("limiting_margin")
        shown = "n/a" if margin is None else f"{percent(margin)} %"
        return f"{row.get('limiting') or NONE} {shown}"
    return f"limiting check and margin {side(before)} -> {side(after)}"


def _is_margin(name: str) -> bool:
    return name.startswith("margin_") or name == "limiting_margin"


def _cell(name: str, value: object) -> str:
    if value is None:
        return NONE
    if isinstance(value, bool):
        return "yes" if value else "no"
    if name == "spec":
        return law_label(str(value))
    if isinstance(value, int | float):
        if not math.isfinite(float(value)):
            return "n/a"
        return f"{percent(float(value))} %" if _is_margin(name) else short(float(value))
    return str(value)


def _change_cell(c: FieldChange) -> str:
    change = c.change
    if change is None:
        return ""
    scale = max(abs(float(c.before)), abs(float(c.after)))  # type: ignore[arg-type]
    if abs(change) <= NOISE * scale:
        return "0 (rounding)"
    if _is_margin(c.field):
        return f"{100.0 * change:+.1f} pts"
    before = float(c.before)  # type: ignore[arg-type]
    relative = f" ({100.0 * change / abs(before):+.1f} %)" if before != 0.0 else ""
    return f"{'+' if change >= 0 else ''}{short(change)}{relative}"


def _csv_cell(value: object) -> str:
    if value is None:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return full(value) if math.isfinite(value) else ""
    return str(value)


def _md(text: str) -> str:
    """Text for Markdown outside a table: characters Markdown reads as markup escaped."""
    for char in "\\`*_[]<|":
        text = text.replace(char, "\\" + char)
    return text.replace(" -> ", " → ")


BRIEF = 72
"""Characters of a design field's value the tables and Markdown show (JSON: all)."""


def _brief(text: str | None) -> str:
    """A design field's value for people: '(absent)', or its text cut to BRIEF."""
    if text is None:
        return "(absent)"
    text = " ".join(text.split())
    return text if len(text) <= BRIEF else text[:BRIEF - 3] + "..."


def _code(text: str) -> str:
    if text == "(absent)":
        return text
    text = " ".join(text.split())
    fence = "``" if "`" in text else "`"
    return f"{fence} {text} {fence}" if "`" in text else f"`{text}`"


def print_terminal(document: DiffDocument, console: Any = None) -> None:
    """The summary lines, then the rich table, then the notes (``console``: a rich
    Console, default stdout)."""
    from rich.console import Console
    from rich.text import Text

    from sizer.report.rich_table import print_rich_table

    console = console or Console(highlight=False)
    for line in document.head_lines():
        console.print(Text(printable(line)))
    if document.rows():
        console.print()
        print_rich_table(Table(document.table().columns, document.table().rows),
                         console=console)
        for note in document.notes():
            console.print(Text(f"note: {note}"))


def publish_diff(document: DiffDocument, fmt: Format, output: Path | None) -> None:
    """Write the document to ``output`` or stdout (a rich table on a terminal)."""
    if fmt is Format.TABLE and output is None and stdout_is_terminal():
        print_terminal(document)
        return
    emit(document.render(fmt), output, escape=fmt in (Format.TABLE, Format.MD))
