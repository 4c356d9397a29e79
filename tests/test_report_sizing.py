"""The sizing and check reports (sizer.report) on hand-made results: no sizing runs here."""

from __future__ import annotations

import csv
import io
import json
import math

import pytest

from sizer.laws import make_law
from sizer.model.domain import Design, Limits, Load, Motor, Stage, Task, Transmission
from sizer.report.candidate_row import (
    CSV_HEADERS,
    check_line,
    check_passed,
    percent,
    result_csv_cells,
    result_display_cells,
    result_json,
)
from sizer.report.check_report import CheckDocument
from sizer.report.design_summary import design_summary
from sizer.report.formats import Format
from sizer.report.numbers import finite_or_none
from sizer.report.sizing_table import NO_FEASIBLE, SizingDocument, publish_sizing
from sizer.sizing import CandidateResult, Check, SizingResult

DESIGN = Design(Task(1.0, 0.5), Load(1.0), laws=("cycloidal",), name="demo",
                limits=Limits(torque_margin=0.1, max_jerk=100.0))


def candidate(motor: str, feasible: bool, *, duration: float | None = 0.5,
              rms_margin: float = 0.5, jerk: bool = False) -> CandidateResult:
    checks = [
        Check("speed", 4.0, 10.0, "rad/s", 0.6),
        Check("peak", 0.5, 1.0, "", 0.5, 0.1),
        Check("rms", 4.0 * (1 - rms_margin) / 0.5, 8.0, "N*m", rms_margin, 0.1),
    ]
    if jerk:
        checks.append(Check("jerk", math.inf, 100.0, "rad/s^3", -math.inf))
    known = duration is not None
    return CandidateResult(
        motor_object=Motor(motor, 1e-4, 1.0, 3.0, 300.0, mass=1.5),
        law_object=make_law("cycloidal"), feasible=feasible,
        duration=duration, peak_torque=12.5 if known else None,
        rms_torque=7.25 if known else None, max_speed=10.0 if known else None,
        checks=tuple(checks), limiting="rms", reason="" if feasible else "rms: too much")


def test_a_ratio_column_when_the_ratio_varies() -> None:
    from dataclasses import replace

    same = SizingDocument(sizing(candidate("a", True), candidate("b", True)), DESIGN)
    assert "ratio" not in same.table().headers
    free = SizingDocument(sizing(candidate("a", True),
                                 replace(candidate("b", True), gearbox="GB-7",
                                         transmission=Transmission((Stage(ratio=7.0),)))),
                          DESIGN)
    table = free.table()
    assert table.headers[:5] == ("#", "motor", "law", "ratio", "feasible")
    assert [row[3] for row in table.rows] == ["1", "7 (GB-7)"]
    assert json.loads(free.json())["results"][1]["gearbox"] == "GB-7"


def sizing(*results: CandidateResult) -> SizingResult:
    return SizingResult("duration", results, "demo", notes=("a note",))


def test_percent_and_finite_or_none() -> None:
    assert percent(0.1234) == "12.3"
    assert percent(-1e-17) == "0.0"  # never '-0.0'
    assert percent(-math.inf) == "n/a" and percent(None) == "n/a"
    assert finite_or_none(math.inf) is None and finite_or_none(None) is None
    assert finite_or_none(2) == 2.0


def test_result_json_keys_and_nulls() -> None:
    data = result_json(candidate("m1", False, jerk=True))
    assert list(data)[:5] == ["motor", "law", "spec", "params", "feasible"]
    assert data["margin_rms"] == 0.5 and data["price"] is None and data["mass"] == 1.5
    jerk = data["checks"][-1]
    assert jerk == {"name": "jerk", "value": None, "limit": 100.0, "unit": "rad/s^3",
                    "margin": None, "required": 0.0, "passed": False,
                    "reason": "jerk: unbounded (the law has jerk impulses)"}
    json.dumps(data, allow_nan=False)  # never NaN or Infinity


def test_no_feasible_duration_leaves_the_summary_margins_empty() -> None:
    result = candidate("m1", False, duration=None)
    data = result_json(result)
    assert data["duration"] is None and data["margin_peak"] is None
    assert data["checks"][1]["margin"] == 0.5  # the engine's checks are kept
    cells = result_display_cells(3, result)
    assert cells[4:11] == ("n/a",) * 7  # with the reason in the note below the table
    assert result_csv_cells(3, result)[5:12] == ("",) * 7


def test_csv_cells_are_exact() -> None:
    cells = result_csv_cells(1, candidate("m1", True))
    assert len(cells) == len(CSV_HEADERS)
    row = dict(zip(CSV_HEADERS, cells, strict=True))
    assert row["duration [s]"] == "0.5" and row["feasible"] == "true"
    assert row["price"] == "" and row["mass [kg]"] == "1.5"


def test_display_cells_in_ms_rpm_and_percent() -> None:
    cells = result_display_cells(1, candidate("m1", True))
    assert cells[:5] == ("1", "m1", "cycloidal", "yes", "500")
    assert cells[7] == "95.493"  # 10 rad/s
    assert cells[8:11] == ("50.0", "50.0", "60.0")


def test_reports_show_the_engines_verdict_and_never_a_failing_minus_zero() -> None:
    at_limit = Check("rms", 14.000000000000002, 14.0, "N*m", -2.2e-16)
    feasible = candidate("m1", True)
    assert at_limit.passed and check_passed(feasible, at_limit)
    assert check_line(feasible, at_limit).endswith("margin 0.00% (ok)")
    just_over = Check("rms", 14.000014, 14.0, "N*m", -1e-6)
    assert not check_passed(feasible, just_over)  # never re-decided from feasibility
    assert check_line(feasible, just_over).endswith("margin -0.0001% (FAILS)")
    assert percent(-1e-6) == "-0.0001" and percent(-2.2e-16) == "0.0"
    clearly_over = Check("rms", 15.0, 14.0, "N*m", -1 / 14)
    assert not check_passed(feasible, clearly_over)


def test_sizing_document_filters_and_keeps_ranks() -> None:
    results = sizing(candidate("a", True), candidate("b", True), candidate("c", False))
    shown = SizingDocument(results, DESIGN)
    assert [rank for rank, _ in shown.rows] == [1, 2]
    assert shown.footer()[0] == "1 infeasible pairs not shown (--all shows them)"
    everything = SizingDocument(results, DESIGN, include_infeasible=True, top=3)
    assert [r.motor for _, r in everything.rows] == ["a", "b", "c"]
    assert "  #3 c, cycloidal: rms: too much" in everything.footer()
    top = SizingDocument(results, DESIGN, include_infeasible=True, top=1)
    assert "2 more pairs not shown (--top)" in top.footer()
    assert top.title == ("demo: h = 1 rad in T = 500 ms; 2 of 3 motor/law pairs feasible, "
                         "ranked by size")


def test_sizing_document_formats() -> None:
    document = SizingDocument(sizing(candidate("a", True)), DESIGN, rank_by="rms")
    data = json.loads(document.json())
    assert data["ranked_by"] == "rms" and data["design"]["notes"] == ["a note"]
    assert data["design"]["limits"]["max_jerk"] == 100.0
    rows = list(csv.reader(io.StringIO(document.csv())))
    assert rows[0] == list(CSV_HEADERS) and rows[1][1] == "a"
    md = document.markdown()
    assert md.startswith("**demo:") and "- note: a note\n" in md
    assert document.render(Format.TABLE) == document.plain_text()


def test_publish_tells_stderr_when_nothing_is_feasible(capsys: pytest.CaptureFixture) -> None:
    document = SizingDocument(sizing(candidate("c", False)), DESIGN)
    publish_sizing(document, Format.JSON, None)
    out, err = capsys.readouterr()
    assert json.loads(out)["results"] == [] and err == NO_FEASIBLE + "\n"
    publish_sizing(document, Format.TABLE, None)
    out, err = capsys.readouterr()
    assert NO_FEASIBLE in out and err == ""


def test_design_summary_of_a_linear_axis() -> None:
    design = Design(Task(0.2, None, dwell=0.1, return_move=True, linear=True),
                    Load(12.0, damping=5.0, friction=10.0, torque=3.0),
                    transmission=Transmission())
    summary = design_summary(design)
    assert summary["mode"] == "minimize" and summary["task"]["duration"] is None
    assert summary["task"]["units"]["displacement"] == "m" and summary["task"]["return"]
    assert list(summary["load"])[:4] == ["mass", "damping", "friction", "force"]
    assert summary["load"]["units"]["damping"] == "N*s/m"
    assert summary["transmission"]["stages"] == [] and summary["check"] is None


def test_check_document_text_and_json() -> None:
    passed = CheckDocument(candidate("m1", True), DESIGN, ("n",))
    text = passed.text().splitlines()
    assert text[0] == "check demo: motor m1, law cycloidal"
    assert text[1].startswith("  T = 500 ms, peak torque 12.5 N*m")
    assert text[-1] == "PASS: m1 with cycloidal meets every limit with the required " \
                       "margins (limiting: rms)"
    failed = CheckDocument(candidate("m1", False, rms_margin=-0.25), DESIGN)
    assert failed.text().splitlines()[-1] == (
        "FAIL: m1 with cycloidal: rms: 10 N*m against 8 N*m, margin -25.00%, "
        "10% required (FAILS)")
    assert json.loads(failed.json())["passed"] is False


def test_terminal_gets_a_rich_table_with_the_footer(monkeypatch: pytest.MonkeyPatch,
                                                    capsys: pytest.CaptureFixture) -> None:
    import sizer.report.sizing_table as sizing_table

    monkeypatch.setattr(sizing_table, "stdout_is_terminal", lambda: True)
    monkeypatch.setenv("COLUMNS", "120")
    document = SizingDocument(sizing(candidate("a", True), candidate("c", False)), DESIGN,
                              include_infeasible=True)
    publish_sizing(document, Format.TABLE, None)
    out = capsys.readouterr().out
    assert "─" in out and "95.493" in out  # box drawing; every numeric column shown
    assert out.rstrip().endswith("note: a note")
    assert "  #2 c, cycloidal: rms: too much" in out


def test_check_document_without_a_feasible_duration_gives_the_reason() -> None:
    result = candidate("m1", False, duration=None)
    text = CheckDocument(result, DESIGN).text().splitlines()
    assert text[1] == "  no feasible duration" and len(text) == 3
    assert text[-1] == "FAIL: m1 with cycloidal: rms: too much"
