"""The rich table of ``sizer size`` on a terminal: it fits the width, keeps the margins and
the limiting check, and names every column it leaves out (rich Console(width=...))."""

from __future__ import annotations

import io
from pathlib import Path

import pytest
from rich.console import Console

from sizer.report.abbreviations import HEADERS, short_check
from sizer.report.candidate_row import percent, summary_margin
from sizer.report.rich_table import fit_table, minimum_width
from sizer.report.sizing_table import SizingDocument, print_terminal_table
from sizer.report.table import Column, make_table

ROOT = Path(__file__).resolve().parent.parent
NOT_SHOWN = "not shown at this terminal width: "


@pytest.fixture(scope="module")
def sized() -> dict:
    from sizer.io import load_design
    from sizer.sizing import size_design

    out = {}
    for name in ("indexing-table", "indexing-table-gearboxes"):
        design = load_design(ROOT / "examples" / f"{name}.yaml")
        out[name] = (design, size_design(design))
    return out


def terminal(document: SizingDocument, width: int) -> str:
    buffer = io.StringIO()
    console = Console(width=width, file=buffer, color_system=None, highlight=False)
    print_terminal_table(document, console)
    return buffer.getvalue()


@pytest.mark.parametrize("name", ["indexing-table", "indexing-table-gearboxes"])
@pytest.mark.parametrize("show_all", [False, True])
def test_80_columns_keep_the_margins_and_name_what_is_left_out(sized: dict, name: str,
                                                              show_all: bool) -> None:
    design, sizing = sized[name]
    document = SizingDocument(sizing, design, top=8, include_infeasible=show_all)
    text = terminal(document, 80)
    lines = text.splitlines()
    assert max(map(len, lines)) <= 80
    rule = next(i for i, line in enumerate(lines) if set(line.strip()) == {"─"})
    header = " ".join(lines[rule - 3:rule])
    short = "mrg" in header  # abbreviated to fit (sizer.report.abbreviations)
    assert header.count("mrg" if short else "margin") == 3
    assert ("limit" if short else "limiting") in header
    for rank, result in document.rows:  # each row: its rank, margins and limiting check
        line = next(x for x in lines[rule + 1:] if x.startswith(f"{rank} "))
        cells = line.split()
        for check in ("peak", "rms", "speed"):
            assert percent(summary_margin(result, check)) in cells
        assert (short_check(result.limiting) if short else result.limiting) in cells
    footer = " ".join(lines[lines.index("", rule):])
    dropped = footer[footer.index(NOT_SHOWN):].split("(a wider")[0]
    full = document.table(compact=True).headers
    for column in full:  # every column is shown or named as not shown
        words = (HEADERS.get(column, column) if short else column).split()
        assert all(w in header for w in words) or column in dropped, column
    assert not any(m in dropped for m in ("margin", "limiting", "motor", "law"))


def test_a_wide_terminal_shows_every_column(sized: dict) -> None:
    design, sizing = sized["indexing-table"]
    document = SizingDocument(sizing, design, top=5, include_infeasible=True)
    text = terminal(document, 200)
    assert NOT_SHOWN not in text
    for word in ("speed", "[rpm]", "[N*m]", "ok", "limiting"):
        assert word in text
    assert max(map(len, text.splitlines())) <= 200


def test_fit_table_drops_only_the_droppable_in_order() -> None:
    table = make_table([Column("a", "left"), Column("bbbbbbbbbb"), Column("cccccccccc"),
                        Column("d")], [("x", "1", "2", "3")])
    assert minimum_width(table) == 1 + 10 + 10 + 1 + 3 * 2
    same, dropped = fit_table(table, 28, ["cccccccccc", "bbbbbbbbbb"])
    assert dropped == [] and same == table
    fitted, dropped = fit_table(table, 20, ["cccccccccc", "bbbbbbbbbb"])
    assert dropped == ["cccccccccc"] and fitted.headers == ("a", "bbbbbbbbbb", "d")
    fitted, dropped = fit_table(table, 5, ["cccccccccc"])  # never more than allowed
    assert dropped == ["cccccccccc"] and fitted.rows == (("x", "1", "3"),)
