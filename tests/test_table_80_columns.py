"""``sizer size`` on an 80-column terminal (issue 36): motor, law, T, the peak, RMS and
speed margins and the limiting check are all shown, none cut; where the full words do not
fit they are abbreviated (sizer.report.abbreviations), a line under the table says so,
and the abbreviations are the documented ones."""

from __future__ import annotations

import io
from pathlib import Path

import pytest
from rich.console import Console

from sizer.report.abbreviations import (
    CAPTION,
    HEADERS,
    LEGEND,
    abbreviated,
    short_check,
    short_law,
)
from sizer.report.candidate_row import percent, summary_margin
from sizer.report.rich_table import fit_table
from sizer.report.sizing_table import SizingDocument, print_terminal_table
from sizer.report.table import Column, make_table

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ["indexing-table", "indexing-table-vibration",
            "vendor-ballscrew", "flying-saw", "indexing-duty-cycle", "vertical-pick-and-place"]


@pytest.fixture(scope="module", params=EXAMPLES)
def document(request: pytest.FixtureRequest) -> SizingDocument:
    from sizer.io import load_design
    from sizer.sizing import size_design

    design = load_design(ROOT / "examples" / f"{request.param}.yaml", default_motors=True)
    return SizingDocument(size_design(design), design, top=6, include_infeasible=True)


def shown(document: SizingDocument, console: Console) -> str:
    print_terminal_table(document, console)
    return console.file.getvalue()  # type: ignore[attr-defined]


def check_80(document: SizingDocument, text: str) -> None:
    lines = text.splitlines()
    assert max(map(len, lines)) <= 80
    rule = next(i for i, line in enumerate(lines) if set(line.strip()) == {"─"})
    header = " ".join(lines[:rule])
    short = CAPTION in text
    assert "motor" in header and "law" in header and "[ms]" in header
    assert header.count("mrg" if short else "margin") == 3
    assert ("limit" if short else "limiting") in header.split()
    body = lines[rule + 1:lines.index("", rule)]
    full = document.table(compact=True)
    laws = dict(zip((r[0] for r in full.rows), (r[full.headers.index("law")] for r in full.rows),
                    strict=True))
    for rank, result in document.rows:
        at = next(i for i, x in enumerate(body) if x.startswith(f"{rank} "))
        cells = body[at].split()
        assert result.motor in cells
        law = short_law(laws[str(rank)]) if short else laws[str(rank)]
        assert law.split()[0] in cells  # its first word whole (a space may wrap it)
        for check in ("peak", "rms", "speed"):
            assert percent(summary_margin(result, check)) in cells
        assert (short_check(result.limiting) if short else result.limiting) in cells


def test_a_rich_console_of_80_columns(document: SizingDocument) -> None:
    console = Console(width=80, file=io.StringIO(), color_system=None, highlight=False)
    check_80(document, shown(document, console))


def test_columns_80_in_the_environment(document: SizingDocument,
                                       monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("COLUMNS", "80")
    console = Console(file=io.StringIO(), force_terminal=True, color_system=None,
                      highlight=False)
    assert console.width == 80
    check_80(document, shown(document, console))


def test_a_wide_terminal_is_not_abbreviated(document: SizingDocument) -> None:
    console = Console(width=250, file=io.StringIO(), color_system=None, highlight=False)
    text = shown(document, console)
    assert CAPTION not in text and "margin" in text and "limiting" in text


def test_the_short_forms() -> None:
    assert short_law("trapezoidal(alpha=1/3)") == "trap(1/3)"
    assert short_law("polynomial(degree=5)") == "poly(5)"
    assert short_law("double_s(alpha=1/3, beta=1/4)") == "double_s(1/3, 1/4)"
    assert short_law("zv(cycloidal)") == "zv(cycl)"
    assert short_law("modified_sinusoidal") == "mod_sine"
    assert short_law("cams/trapezoidal.csv") == "cams/trapezoidal.csv"  # a file: as written
    assert short_check("inertia_ratio") == "J_ratio"
    assert short_check("winding_temperature_rise") == "winding_dT"
    assert short_check("ball_screw_speed") == "ball_screw_spd"
    assert short_check("rms") == "rms"


def test_the_legend_names_every_short_form_it_uses() -> None:
    for word in ("mrg = margin", "pk = peak", "spd = speed", "trap(1/3)", "poly(5)",
                 "mod_sine", "cycl", "J_ratio", "winding_dT", "limit"):
        assert word in LEGEND
    assert set(HEADERS.values()) >= {"pk mrg [%]", "rms mrg [%]", "spd mrg [%]", "limit"}


def test_the_dropped_are_named_by_their_full_headers() -> None:
    table = make_table([Column("law", "left"), Column("speed [rpm]"),
                        Column("peak margin [%]")],
                       [("modified_sinusoidal", "1234567890", "12.5")])
    fitted, dropped = fit_table(table, 24, ["speed [rpm]"], wrap_headers=True)
    assert dropped == ["speed [rpm]"]
    assert fitted == abbreviated(make_table([Column("law", "left"),
                                             Column("peak margin [%]")],
                                            [("modified_sinusoidal", "12.5")]))
    same, none = fit_table(table, 80, ["speed [rpm]"], wrap_headers=True)
    assert same is table and none == []
