"""The sensitivities of a pair (sizer.sensitivity) as a table, Markdown, CSV or JSON.

One row per input, most influential first; one column per margin (and T_min in minimize
mode): d margin / d ln x, the margin's change per relative change of the input. Where a
quantity has a kink at the input's value the cell shows both one-sided values,
``-a|+b`` (left, right), and the row is marked. The records (JSON, CSV) are plain: input,
value, unit, and per quantity ``d_<name>/d_ln_x`` (with ``_minus`` and ``_plus`` where
kinked); nothing here re-decides a verdict.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from sizer.report.formats import Format, Rendered

if TYPE_CHECKING:
    from pathlib import Path

    from sizer.sensitivity import InputSensitivity, Sensitivity, Slope


SHOWN_ZERO = 1e-8
"""Slopes smaller than this show as 0 in the tables: the sizing's round-off divided by the
step (~1e-10), not an influence (the records keep the computed value)."""


def _number(value: float) -> str:
    return f"{value:+.4g}" if abs(value) >= SHOWN_ZERO else "0"


def _cell(slope: Slope | None) -> str:
    if slope is None:
        return "-"
    if slope.kink:
        return f"{_number(slope.minus)}|{_number(slope.plus)}"
    return _number(slope.central)


def _key(quantity: str) -> str:
    return f"d_{quantity}/d_ln_x"


def record(row: InputSensitivity, quantities: tuple[str, ...]) -> dict[str, Any]:
    """One input as a plain record."""
    out: dict[str, Any] = {"input": row.name, "value": row.value, "unit": row.unit,
                           "kink": row.kinked}
    for quantity in quantities:
        slope = row.slopes.get(quantity)
        out[_key(quantity)] = None if slope is None else slope.central
        if slope is not None and slope.kink:
            out[_key(quantity) + "_minus"] = slope.minus
            out[_key(quantity) + "_plus"] = slope.plus
    if row.limiting is not None:
        out["limiting_minus"], out["limiting_plus"] = row.limiting
    return out


class SensitivityDocument(Rendered):
    """The sensitivities of one pair, in every format."""

    def __init__(self, sensitivity: Sensitivity, name: str = "") -> None:
        self.sensitivity = sensitivity
        self.name = name

    @property
    def title(self) -> str:
        result = self.sensitivity.result
        where = f"{self.name}: " if self.name else ""
        return (f"{where}sensitivities of {result.motor} with {result.spec} "
                f"(d margin / d ln x; h = {self.sensitivity.step:g})")

    def table(self) -> Any:
        from sizer.report.table import Column, make_table

        s = self.sensitivity
        quantities = s.quantities
        headers = [Column("input", "left"), Column("value"), Column("unit", "left"),
                   *(Column(q + (" [s]" if q == "T_min" else "")) for q in quantities),
                   Column("kink", "left")]
        rows = []
        for row in s.inputs:
            kink = ""
            if row.limiting is not None:
                kink = f"limiting {row.limiting[0]} | {row.limiting[1]}"
            elif row.kinked:
                kink = "yes"
            rows.append([row.name, f"{row.value:.6g}", row.unit,
                         *(_cell(row.slopes.get(q)) for q in quantities), kink])
        return make_table(headers, rows, title=self.title)

    def records(self) -> list[dict[str, Any]]:
        quantities = self.sensitivity.quantities
        return [record(row, quantities) for row in self.sensitivity.inputs]

    def note(self) -> str:
        """The legend, after the inputs not perturbed (with the reason)."""
        lines = [f"not perturbed: {name}: {reason}"
                 for name, reason in self.sensitivity.skipped]
        lines.append("a|b: a kink at the input's value, the left and right one-sided "
                     "slopes; a margin's slope per 100 % of the input (+0.5: 1 % more of "
                     "x gives 0.005 more margin)")
        return "\n".join(lines)

    def plain_text(self) -> str:
        from sizer.report.text_table import render_text_table

        return self.title + "\n" + render_text_table(self.table()) + self.note() + "\n"

    def markdown(self) -> str:
        from sizer.report.markdown_table import render_markdown_table

        return (f"### {self.title}\n\n" + render_markdown_table(self.table())
                + "\n" + self.note() + "\n")

    def json(self) -> str:
        from sizer.report.json_text import render_json

        result = self.sensitivity.result
        return render_json({"design": self.name, "motor": result.motor, "law": result.spec,
                            "minimize": self.sensitivity.minimize,
                            "step": self.sensitivity.step, "inputs": self.records(),
                            "skipped": [{"input": n, "reason": r}
                                        for n, r in self.sensitivity.skipped]})

    def csv(self) -> str:
        from sizer.report.csv_text import render_csv

        records = self.records()
        headers = list(dict.fromkeys(k for r in records for k in r)) or ["input"]
        return render_csv(headers, [["" if r.get(h) is None else str(r.get(h))
                                     for h in headers] for r in records])


def publish(document: SensitivityDocument, fmt: Format, output: Path | None) -> None:
    """Print (rich on a terminal) or write ``document`` in ``fmt``."""
    from sizer.report.output import emit, stdout_is_terminal

    if fmt is Format.TABLE and output is None and stdout_is_terminal():
        from sizer.report.rich_table import print_rich_table

        print_rich_table(document.table(), title_above=True)
        emit(document.note() + "\n", None, escape=True)
        return
    text = document.render(fmt)
    emit(text, output, escape=fmt in (Format.TABLE, Format.MD))
