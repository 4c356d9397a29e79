"""The outputs of a machine cycle of segments (issue 12): ``sizer segments`` in every format,
the segment table of ``sizer check`` and ``sizer report``, the cycle in the design summary,
and the plots over time with the segments marked.

The table's numbers are the core's breakdown (sizer.sizing.segment_breakdown), compared
exactly; a few closed forms of the test cycle pin what the columns mean.
"""

from __future__ import annotations

import csv
import io
import json
import math
from dataclasses import replace
from pathlib import Path

import pytest
from cli_run import assert_user_error
from cli_run import run_cli as run

from sizer import api
from sizer.model.cycle import Cycle, Dwell, Move, SegmentLoad
from sizer.model.domain import Design, Load, Motor, Stage, Task, Transmission
from sizer.report.check_report import CheckDocument
from sizer.report.design_report import TIME_FIGURE, DesignReport, md
from sizer.report.design_summary import design_summary
from sizer.report.markdown_table import render_markdown_table
from sizer.report.segment_table import (
    FORMAT,
    JERK_IMPULSE,
    SegmentDocument,
    breakdown_for,
    csv_headers,
)
from sizer.sizing import check_design, size_design
from sizer.sizing.samples import segment_breakdown

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"
INDEXING = EXAMPLES / "indexing-table.yaml"
RPM_PER_RAD_S = 30.0 / math.pi

CSV_FIELDS = ("start", "end", "peak_torque", "rms_torque", "rms_share", "peak_speed",
              "energy", "acceleration_step")
"""The numeric CSV columns, in order after segment, kind and law."""

ROW_KEYS = ["name", "kind", "law", "start", "end", "peak_torque", "rms_torque", "rms_share",
            "peak_speed", "energy", "acceleration_step", "jerk_impulse"]


def cycle_design(**changes) -> Design:
    """Two motors, an ideal gearbox K = 10 and Coulomb friction 0.5 N*m at the load: out
    by the design's law in 0.5 s, a pressing dwell holding 2 N*m for 0.25 s, back by a
    trapezoid in 0.4 s, a dwell of 0.3 s (cycle time 1.45 s)."""
    motors = (Motor("small", 1e-4, 1.0, 3.0, 314.0), Motor("big", 1e-3, 5.0, 15.0, 300.0))
    cycle = Cycle((Move(1.0, 0.5, name="out"),
                   Dwell(0.25, name="press", load=SegmentLoad(torque=2.0)),
                   Move(-1.0, 0.4, law="trapezoidal(alpha=1/4)", name="back"),
                   Dwell(0.3)))
    design = Design(Task(1.0, 0.5), Load(0.2, friction=0.5),
                    Transmission((Stage("gearbox", 10.0, 1.0, 2e-4),)),
                    laws=("cycloidal", "poly5"), motors=motors, name="two steps",
                    cycle=cycle)
    return replace(design, **changes)


@pytest.fixture(scope="module")
def cycled():
    design = cycle_design()
    sizing = size_design(design)
    result = sizing.results[0]
    return design, sizing, result, breakdown_for(design, result)


def csv_rows(text: str) -> list[list[str]]:
    return list(csv.reader(io.StringIO(text)))


# ------------------------------------------------------------------- the document
def test_csv_cells_are_the_core_breakdown(cycled):
    design, _, result, breakdown = cycled
    again = segment_breakdown(design, result.motor_object, result.spec, result.duration,
                              result.transmission)
    assert again == breakdown  # breakdown_for passes the result's law, duration, ratio
    header, *rows = csv_rows(SegmentDocument(breakdown, design).csv())
    assert tuple(header) == csv_headers(False)
    assert header[3:11] == ["start [s]", "end [s]", "peak_torque [N*m]", "rms_torque [N*m]",
                            "rms_share [1]", "peak_speed [rad/s]", "energy [J]",
                            "acceleration_step [rad/s^2]"]
    assert len(rows) == len(breakdown.rows) == 4
    for cells, row in zip(rows, breakdown.rows, strict=True):
        assert cells[:3] == [row.name, row.kind, row.law or ""]
        assert [float(c) for c in cells[3:11]] == [getattr(row, f) for f in CSV_FIELDS]
        assert cells[11] == (JERK_IMPULSE if row.acceleration_step != 0.0 else "")
    # closed forms of the test cycle: the times add up; the press holds 2 N*m / K = 0.2 N*m
    # at the motor; a rest-to-rest move's work is the friction's, 0.5 N*m * 1 rad
    assert [c[0] for c in rows] == ["out", "press", "back", "dwell"]
    assert float(rows[-1][4]) == pytest.approx(1.45, rel=1e-15)
    assert float(rows[1][5]) == pytest.approx(0.2, rel=1e-15)
    assert float(rows[1][6]) == pytest.approx(0.2, rel=1e-15)
    assert float(rows[0][9]) == pytest.approx(0.5, rel=1e-12)
    # the trapezoid steps its acceleration at both ends, the smooth law joins the dwell
    assert [c[11] for c in rows] == ["", "", JERK_IMPULSE, JERK_IMPULSE]


def test_json_keys_values_and_shares(cycled):
    design, _, _, breakdown = cycled
    data = json.loads(SegmentDocument(breakdown, design, feasible=True).json())
    assert list(data) == ["format", "design", "motor", "law", "feasible", "cycle_time",
                          "rms_torque", "units", "segments"]
    assert data["format"] == FORMAT and data["feasible"] is True
    assert (data["motor"], data["law"]) == (breakdown.motor, breakdown.law)
    assert data["cycle_time"] == breakdown.cycle_time
    assert data["rms_torque"] == breakdown.rms_torque
    assert set(CSV_FIELDS) <= set(data["units"])
    for item, row in zip(data["segments"], breakdown.rows, strict=True):
        assert list(item) == ROW_KEYS
        assert [item[f] for f in CSV_FIELDS] == [getattr(row, f) for f in CSV_FIELDS]
        assert item["jerk_impulse"] is (row.acceleration_step != 0.0)
    assert math.fsum(s["rms_share"] for s in data["segments"]) == pytest.approx(1.0,
                                                                               abs=1e-12)
    # the cycle's RMS^2 times its time is the sum of the segments' RMS^2 times theirs
    integral = math.fsum(s["rms_torque"] ** 2 * (s["end"] - s["start"])
                         for s in data["segments"])
    assert integral == pytest.approx(data["rms_torque"] ** 2 * data["cycle_time"], rel=1e-12)


def test_display_table_units_and_footer(cycled):
    design, _, _, breakdown = cycled
    document = SegmentDocument(breakdown, design)
    table = document.table()
    assert table.headers == ("segment", "kind", "law", "start [ms]", "end [ms]",
                             "peak torque [N*m]", "rms torque [N*m]", "share of rms^2 [%]",
                             "peak speed [rpm]", "energy [J]", "join")
    shares = [float(r[7]) for r in table.rows]
    assert sum(shares) == pytest.approx(100.0, abs=0.05 * len(shares))
    for cells, row in zip(table.rows, breakdown.rows, strict=True):
        assert float(cells[4]) == pytest.approx(row.end * 1000.0, rel=1e-4)
        assert float(cells[8]) == pytest.approx(row.peak_speed * RPM_PER_RAD_S, rel=1e-4)
        assert float(cells[7]) == pytest.approx(row.rms_share * 100.0, abs=0.05)
        assert cells[10].startswith(JERK_IMPULSE) == (row.acceleration_step != 0.0)
    footer = document.footer()
    assert footer[0].startswith("cycle time 1450 ms, cycle rms torque ")
    text = document.plain_text()
    assert text.startswith("two steps: the cycle by segment, motor ")
    assert document.markdown().count("\n| ") == 2 + len(breakdown.rows)


@pytest.mark.parametrize("width", [80, 200])
def test_terminal_table_has_the_rows_and_the_summary(cycled, monkeypatch, capsys, width):
    import sizer.report.segment_table as module
    from sizer.report.formats import Format

    design, _, _, breakdown = cycled
    monkeypatch.setattr(module, "stdout_is_terminal", lambda: True)
    monkeypatch.setenv("COLUMNS", str(width))
    module.publish_segments(SegmentDocument(breakdown, design), Format.TABLE, None)
    out = capsys.readouterr().out
    assert "─" in out  # drawn by rich, not the plain table
    for name in ("out", "press", "back", "dwell", "cycle time 1450 ms"):
        assert name in out
    words = " ".join(out.split())
    if width == 80:  # a column left out to fit is named under the table, never silently
        assert "not shown at this terminal width: kind, energy [J]" in words
    else:
        assert "not shown" not in words and "energy" in words


def test_linear_axis_states_its_acceleration_unit():
    assert csv_headers(True)[10] == "acceleration_step [m/s^2]"


# ------------------------------------------------------------------ sizer segments
def test_segments_defaults_to_the_check_pair_with_the_core_numbers():
    result = run("segments", str(INDEXING), "-f", "json")
    assert result.returncode == 0, result.stderr
    data = json.loads(result.stdout)
    design = api.load(INDEXING)
    motor = next(m for m in design.motors if m.id == "HG-KN43J")
    breakdown = segment_breakdown(design, motor, "modified_sinusoidal", 0.25)
    assert (data["motor"], data["law"]) == ("HG-KN43J", "modified_sinusoidal")
    assert data["cycle_time"] == breakdown.cycle_time == pytest.approx(0.6, rel=1e-15)
    assert data["rms_torque"] == breakdown.rms_torque
    assert [s["name"] for s in data["segments"]] == ["move", "dwell"]
    for item, row in zip(data["segments"], breakdown.rows, strict=True):
        assert [item[f] for f in CSV_FIELDS] == [getattr(row, f) for f in CSV_FIELDS]
    assert run("segments", str(INDEXING), "-f", "json").stdout == result.stdout


def test_segments_formats_and_output_file(tmp_path):
    shown = run("segments", str(INDEXING), "--format", "csv")
    assert shown.returncode == 0
    header = csv_rows(shown.stdout)[0]
    assert tuple(header) == csv_headers(False)
    out = tmp_path / "segments.csv"
    written = run("segments", str(INDEXING), "-f", "csv", "-o", str(out))
    assert written.returncode == 0 and written.stdout == ""
    assert out.read_text() == shown.stdout
    table = run("segments", str(INDEXING))
    assert table.returncode == 0
    assert "cycle time 600 ms, cycle rms torque 0.26541 N*m" in table.stdout
    markdown = run("segments", str(INDEXING), "-f", "md")
    assert "| segment | kind | law | start [ms] |" in markdown.stdout


def test_segments_of_a_motor_and_law_and_of_the_best_ranked_pair(tmp_path):
    chosen = json.loads(run("segments", str(INDEXING), "--motor", "HG-KN73J", "--law",
                            "poly5", "-f", "json").stdout)
    assert (chosen["motor"], chosen["law"]) == ("HG-KN73J", "polynomial(degree=5)")
    text = INDEXING.read_text()
    head = text[:text.index("check:")].replace(
        "motors: catalogs/example-servo.yaml",
        f"motors: {EXAMPLES / 'catalogs' / 'example-servo.yaml'}")
    path = tmp_path / "unchecked.yaml"
    path.write_text(head)
    data = json.loads(run("segments", str(path), "-f", "json").stdout)
    best = next(r for r in api.size(path).results if r.feasible)
    assert (data["motor"], data["law"]) == (best.motor, best.spec)
    assert data["feasible"] is True


def test_segments_bad_inputs_exit_2_with_one_clear_line(tmp_path):
    line = assert_user_error(run("segments", str(INDEXING), "--motor", "NOPE"),
                             "--motor", "unknown motor 'NOPE'", "HG-KN43J")
    assert line.startswith("error: ")
    assert_user_error(run("segments", str(INDEXING), "--law", "cycloid"), "--law")
    assert_user_error(run("segments", str(INDEXING), "-o", str(INDEXING)), "--output",
                      "input")
    assert_user_error(run("segments", str(tmp_path / "missing.yaml")), "missing.yaml")


def test_segments_of_a_pair_without_a_feasible_duration(tmp_path):
    text = INDEXING.read_text().replace("duration: 0.25 s", "duration: minimize").replace(
        "friction: 0.5 N*m", "friction: 0.5 N*m\n  torque: 500 N*m").replace(
        "motors: catalogs/example-servo.yaml",
        f"motors: {EXAMPLES / 'catalogs' / 'example-servo.yaml'}")
    path = tmp_path / "hopeless.yaml"
    path.write_text(text)
    assert_user_error(run("segments", str(path)), "hopeless.yaml", "no feasible duration")
    checked = run("check", str(path))
    assert checked.returncode == 1 and "  segments:" not in checked.stdout
    data = json.loads(run("check", str(path), "-f", "json").stdout)
    assert data["segments"] is None


# ---------------------------------------------------------------------- sizer check
def test_check_shows_the_segments_before_its_verdict():
    result = run("check", str(INDEXING))
    assert result.returncode == 0
    lines = result.stdout.splitlines()
    start = lines.index("  segments:")
    assert lines[-1].startswith("PASS: ") and start < len(lines) - 1
    assert all(line.startswith("  ") for line in lines[start:-1])
    assert lines[start + 1].split()[:3] == ["segment", "kind", "law"]
    assert lines[start + 3].split()[:3] == ["move", "move", "modified_sinusoidal"]
    data = json.loads(run("check", str(INDEXING), "-f", "json").stdout)
    design = api.load(INDEXING)
    motor = next(m for m in design.motors if m.id == "HG-KN43J")
    breakdown = segment_breakdown(design, motor, "modified_sinusoidal", 0.25)
    assert data["segments"]["cycle_time"] == breakdown.cycle_time
    # the breakdown sums its segments' integrals, the engine its moments by matrix-vector
    # products (issue 11): the same integral, summed in another order
    assert data["segments"]["rms_torque"] == breakdown.rms_torque
    assert breakdown.rms_torque == pytest.approx(data["result"]["rms_torque"], rel=1e-14)
    for item, row in zip(data["segments"]["segments"], breakdown.rows, strict=True):
        assert [item[f] for f in CSV_FIELDS] == [getattr(row, f) for f in CSV_FIELDS]


def test_check_document_of_a_cycle_says_cycle_time(cycled):
    design = cycle_design(chosen_motor="big", chosen_law="cycloidal")
    result = check_design(design)
    breakdown = breakdown_for(design, result)
    text = CheckDocument(result, design, (), breakdown).text()
    assert "\n  cycle time = 1450 ms, " in text
    assert "\n  back     move   trapezoidal(alpha=1/4)" in text
    assert text.splitlines()[-1].startswith("PASS: big with cycloidal")


# -------------------------------------------------------------- summary and report
def test_design_summary_describes_a_cycle_and_not_a_task(cycled):
    design = cycled[0]
    summary = design_summary(design)
    keys = list(summary)
    assert keys[keys.index("task") + 1] == "cycle"
    cycle = summary["cycle"]
    assert [s["kind"] for s in cycle["segments"]] == ["move", "dwell", "move", "dwell"]
    assert cycle["segments"][1]["added_torque"] == 2.0
    assert cycle["segments"][2]["law"] == "trapezoidal(alpha=1/4)"
    assert cycle["segments"][0]["law"] is None
    assert "cycle" not in design_summary(api.load(INDEXING))


def test_a_cycle_is_sized_by_its_cycle_time_and_says_so(cycled):
    from sizer.report.cycle_summary import duration_name
    from sizer.report.sizing_table import SizingDocument

    design, sizing, _, _ = cycled
    assert duration_name(design) == "cycle time"
    assert duration_name(api.load(INDEXING)) == "T"
    document = SizingDocument(sizing, design)
    assert document.title.startswith("two steps: a cycle of 4 segments in 1450 ms; ")
    assert "cycle time [ms]" in document.table().headers
    assert all(r.duration == pytest.approx(1.45, rel=1e-15) for r in sizing.results)


def test_report_of_a_cycle(cycled, tmp_path):
    from sizer.report.design_report import write_report

    design, sizing, result, breakdown = cycled
    report = DesignReport(design, sizing, best=1)
    text = report.markdown()
    task = text[text.index("## Task"):text.index("## Load")]
    assert "a machine cycle of 4 segments" in task
    assert "| 2 | press | dwell | 0 | 250 |  | rest | 2 N\\*m |" in task
    section = text[text.index("## Cycle by segment"):]
    table = md(render_markdown_table(SegmentDocument(breakdown, design).table()))
    assert table in section
    assert f"#1 {result.motor} with {result.spec}" in section
    assert report.figures[-1] == TIME_FIGURE and f"]({TIME_FIGURE})" in section
    written = write_report(design, sizing, tmp_path / "r", best=1, dpi=30, samples=41)
    assert [p.name for p in written][-1] == TIME_FIGURE
    assert all(p.is_file() for p in written)


def test_report_of_a_task_has_the_segments_of_its_first_candidate():
    design = api.load(INDEXING)
    sizing = api.size(design)
    report = DesignReport(design, sizing, best=1)
    assert TIME_FIGURE not in report.figures
    first = sizing.feasible[0]
    table = md(render_markdown_table(SegmentDocument(breakdown_for(design, first),
                                                     design).table()))
    assert table in report.markdown()[report.markdown().index("## Cycle by segment"):]


# --------------------------------------------------------------------------- plots
def test_time_figure_draws_the_core_curve_with_the_segments(cycled, tmp_path):
    pytest.importorskip("matplotlib")
    import numpy as np

    from sizer.report.plots import curve_for, time_figure
    from sizer.report.plots.figure_files import figure_bytes
    from sizer.report.plots.time_curves import GID_JOIN, GID_SPAN, GID_SPEED, GID_TORQUE

    design, _, result, _ = cycled
    curve = curve_for(design, result, samples=41)
    figure = time_figure([curve], speed_unit="rad/s", title=design.name)
    torque_axes, speed_axes = figure.axes[:2]
    (torque,) = [line for line in torque_axes.lines if line.get_gid() == GID_TORQUE]
    np.testing.assert_array_equal(torque.get_xdata(), curve.time * 1000.0)
    np.testing.assert_array_equal(torque.get_ydata(), curve.motor_torque)
    (speed,) = [line for line in speed_axes.lines if line.get_gid() == GID_SPEED]
    np.testing.assert_array_equal(speed.get_ydata(), curve.motor_speed)
    joins = [line.get_xdata()[0] for line in torque_axes.lines if line.get_gid() == GID_JOIN]
    assert joins == pytest.approx([s[1] * 1000.0 for s in curve.segments[1:]], rel=1e-15)
    spans = [p for p in torque_axes.patches if p.get_gid() == GID_SPAN]
    assert len(spans) == 2  # every other one of the four segments
    names = [t.get_text() for t in torque_axes.texts]
    assert names == ["out", "press", "back", "dwell"]
    again = time_figure([curve], speed_unit="rad/s", title=design.name)
    assert figure_bytes(figure, "svg") == figure_bytes(again, "svg")


def test_speed_torque_diagram_of_a_cycle_marks_the_segment_starts(cycled):
    pytest.importorskip("matplotlib")
    from sizer.report.plots import curve_for, speed_torque_figure
    from sizer.report.plots.speed_torque import GID_SEGMENT_START

    design, _, result, _ = cycled
    curve = curve_for(design, result, samples=41)
    plain = speed_torque_figure([curve], [result])
    assert not [x for x in plain.axes[0].lines if x.get_gid() == GID_SEGMENT_START]
    marked = speed_torque_figure([curve], [result], mark_segments=True)
    (points,) = [x for x in marked.axes[0].lines if x.get_gid() == GID_SEGMENT_START]
    # at rest: the out move starts against the friction, 0.5 N*m / K; the press holds
    # 2 N*m / K; the last dwell holds nothing; the back move starts with the trapezoid's
    # step of acceleration (negative)
    torques = sorted(points.get_ydata())
    assert torques[1:] == pytest.approx([0.0, 0.05, 0.2], rel=1e-12, abs=1e-15)
    assert torques[0] < 0.0 and set(points.get_xdata()) == {0.0}
    labels = {t.get_text() for t in marked.axes[0].texts}
    assert {"out", "press", "back", "dwell"} == labels


def test_plot_time_option(tmp_path):
    pytest.importorskip("matplotlib")
    out = tmp_path / "time.png"
    result = run("plot", str(INDEXING), "--time", "-o", str(out), "--dpi", "30")
    assert result.returncode == 0, result.stderr
    assert out.read_bytes().startswith(b"\x89PNG")
    assert "torque and speed over time of HG-KN43J" in result.stdout
    assert_user_error(run("plot", str(INDEXING), "--time", "--acceleration", "-o",
                          str(tmp_path / "x.png")), "--time")
