"""``sizer size``: formats, ranking options, determinism and user errors.

All runs but one go through ``sizer.cli.app.main(argv)`` in this process (same argument
and error handling as the real command, without the ~1 s start-up of a subprocess).
"""

from __future__ import annotations

import csv
import io
import json
import math
import subprocess
import sys
from pathlib import Path

import pytest
from cli_run import assert_user_error
from cli_run import run_cli as run

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"
INDEXING = str(EXAMPLES / "indexing-table.yaml")
EX61 = str(EXAMPLES / "book" / "ex6_1-6_2.yaml")
EX64 = str(EXAMPLES / "book" / "ex6_4.yaml")
SERVO_CATALOG = str(EXAMPLES / "catalogs" / "example-servo.yaml")

RESULT_KEYS = ["motor", "law", "spec", "params", "feasible", "front", "duration", "peak_torque",
               "rms_torque", "max_speed", "margin_peak", "margin_rms", "margin_speed",
               "limiting", "reason", "price", "mass", "rated_power", "ratio", "gearbox",
               "load_speed", "load_torque", "checks"]
CHECK_KEYS = ["name", "value", "limit", "unit", "margin", "required", "passed", "reason"]




def ok(*args: str) -> str:
    result = run(*args)
    assert result.returncode == 0, result.stderr
    return result.stdout




@pytest.fixture(scope="module")
def indexing_json() -> dict:
    return json.loads(ok("size", INDEXING, "--all", "--format", "json"))


# ------------------------------------------------------------------ JSON
def test_json_has_the_design_in_si_with_units(indexing_json: dict) -> None:
    assert list(indexing_json) == ["format", "design", "ranked_by", "ranking", "units",
                                   "results"]
    assert indexing_json["format"] == "sizer.sizing/1"
    design = indexing_json["design"]
    assert design["name"] == "Indexing table, 90 deg in 0.25 s"
    assert design["mode"] == "duration" and indexing_json["ranked_by"] == "size"
    assert indexing_json["ranking"].startswith("smallest motor first")
    assert design["task"]["displacement"] == pytest.approx(math.pi / 2, rel=1e-15)
    assert design["task"]["duration"] == 0.25 and design["task"]["dwell"] == 0.35
    assert design["task"]["units"] == {"displacement": "rad", "duration": "s", "dwell": "s"}
    assert design["load"]["inertia"] == 0.034 and design["load"]["units"]["inertia"] == "kg*m^2"
    assert design["transmission"]["ratio"] == 10.0
    assert design["transmission"]["efficiency"] == 0.95
    assert design["transmission"]["inertia"] == pytest.approx(0.3e-4, rel=1e-12)  # kg*m^2
    assert design["limits"]["torque_margin"] == pytest.approx(0.1)
    assert design["limits"]["inertia_ratio"] == 10.0
    assert design["motors"] == 4 and len(design["laws"]) == 6
    assert design["check"] == {"motor": "HG-KN43J", "law": "modified_sinusoidal"}
    assert any(note.startswith("envelope electrical:") for note in design["notes"])
    assert indexing_json["units"]["max_speed"] == "rad/s"


def test_json_results_have_fixed_keys_and_consistent_margins(indexing_json: dict) -> None:
    results = indexing_json["results"]
    assert len(results) == 24  # 4 motors x 6 laws, --all
    feasible = [r["feasible"] for r in results]
    assert feasible == sorted(feasible, reverse=True)  # feasible first
    for row in results:
        assert list(row) == RESULT_KEYS
        assert row["feasible"] == (row["reason"] == "")
        checks = {c["name"]: c for c in row["checks"]}
        for check in row["checks"]:
            assert list(check) == CHECK_KEYS
        for name in ("peak", "rms", "speed"):
            assert row[f"margin_{name}"] == checks[name]["margin"]
        assert row["feasible"] == all(c["passed"] for c in row["checks"])
        assert row["limiting"] in checks
    by_pair = {(r["motor"], r["spec"]): r for r in results}
    chosen = by_pair[("HG-KN43J", "modified_sinusoidal")]
    assert chosen["feasible"] and chosen["duration"] == 0.25
    assert chosen["ratio"] == 10.0 and chosen["gearbox"] is None
    assert chosen["load_speed"] == pytest.approx(chosen["max_speed"] / 10, rel=1e-12)
    assert chosen["max_speed"] == pytest.approx(10 * 1.7596 * (math.pi / 2) / 0.25, rel=1e-4)
    # HG-KN23J: 0.034/10^2 over 0.225e-4 kg*m^2 is above the inertia ratio of 10
    weak = by_pair[("HG-KN23J", "cycloidal")]
    assert not weak["feasible"] and weak["limiting"] == "inertia_ratio"
    assert "inertia_ratio" in weak["reason"]


def test_auto_shape_reports_the_chosen_parameter(indexing_json: dict) -> None:
    auto = [r for r in indexing_json["results"] if r["law"] == "trapezoidal"
            and r["spec"] != "trapezoidal(alpha=1/3)"]
    assert len(auto) == 4
    for row in auto:
        assert 0.0 < row["params"]["alpha"] <= 0.5
        assert row["spec"].startswith("trapezoidal(alpha=")


def test_json_and_csv_are_deterministic() -> None:
    for fmt in ("json", "csv"):
        args = ("size", EX64, "--format", fmt)
        first, second = ok(*args), ok(*args)
        assert first == second and first.endswith("\n") and "\r" not in first


def test_json_nulls_for_non_finite_numbers(tmp_path: Path) -> None:
    # a trapezoid has jerk impulses: against a jerk limit its margin is -inf
    design = tmp_path / "jerk.yaml"
    design.write_text(
        "task: {displacement: 1 rad, duration: 1 s}\nload: {inertia: 1}\n"
        "laws: ['trapezoidal(alpha=1/3)']\nmotors: book-examples\n"
        "limits: {max_jerk: 1000 rad/s^3}\n")
    data = json.loads(ok("size", str(design), "--all", "--format", "json"))
    assert data["design"]["limits"]["max_jerk"] == 1000.0
    for row in data["results"]:
        jerk = next(c for c in row["checks"] if c["name"] == "jerk")
        assert jerk["value"] is None and jerk["margin"] is None and not jerk["passed"]
        assert not row["feasible"] and row["limiting"] == "jerk"
    table = ok("size", str(design), "--all")
    assert "no feasible motor/law pair" in table and "the law has jerk impulses" in table


# ------------------------------------------------------------------ CSV, Markdown, table
def test_csv_is_si_with_units_in_the_headers() -> None:
    text = ok("size", EX61, "--format", "csv", "--motor", "ex6_1")
    rows = list(csv.DictReader(io.StringIO(text)))
    assert list(rows[0]) == ["rank", "motor", "law", "spec", "feasible", "duration [s]",
                             "peak_torque [N*m]", "rms_torque [N*m]", "max_speed [rad/s]",
                             "margin_peak [1]", "margin_rms [1]", "margin_speed [1]",
                             "limiting", "reason", "price", "mass [kg]", "ratio",
                             "gearbox", "envelope", "front"]
    assert {r["envelope"] for r in rows} == {"electrical"}  # the rule is stated in the CSV too
    by_law = {r["law"]: r for r in rows}
    assert float(by_law["cycloidal"]["max_speed [rad/s]"]) == pytest.approx(10.0, rel=1e-12)
    assert round(float(by_law["cycloidal"]["rms_torque [N*m]"]), 4) == 7.6293
    assert round(float(by_law["trapezoidal"]["rms_torque [N*m]"]), 4) == 7.7297
    assert by_law["cycloidal"]["duration [s]"] == "3.0"
    assert by_law["cycloidal"]["price"] == "" and by_law["cycloidal"]["feasible"] == "true"


def test_markdown_shows_ms_rpm_and_percent() -> None:
    md = ok("size", EX61, "--format", "md", "--motor", "ex6_1").splitlines()
    assert md[0].startswith("**B&M Examples 6.1-6.2: h = 15 rad in T = 3000 ms")
    header = md[2]
    for column in ("T [ms]", "peak [N*m]", "rms [N*m]", "max speed [rpm]",
                   "peak margin [%]", "rms margin [%]", "speed margin [%]", "limiting"):
        assert f"| {column} |" in header or header.endswith(f"| {column} |")
    assert set(md[3]) <= set("|-: ")
    cycloidal = next(line for line in md if "| cycloidal |" in line)
    assert "| 95.493 |" in cycloidal  # 10 rad/s in rpm
    assert "| 7.6293 |" in cycloidal and "| 4.6 |" in cycloidal  # rms margin 1 - 7.6293/8
    assert any(line.startswith("- note: ") for line in md)


def test_plain_table_when_piped_and_output_file(tmp_path: Path) -> None:
    table = ok("size", EX64)
    lines = table.splitlines()
    assert lines[0].startswith("B&M Example 6.4: h = 1 rad, shortest duration; 6 of 6")
    assert lines[2].split()[:5] == ["#", "motor", "law", "feasible", "T_min"]
    assert "│" not in table
    target = tmp_path / "out.txt"
    assert ok("size", EX64, "--output", str(target)) == ""
    assert target.read_text() == table
    assert [p.name for p in tmp_path.iterdir()] == ["out.txt"]


# ------------------------------------------------------------------ options
def test_default_output_hides_infeasible_pairs_and_all_shows_them() -> None:
    vendor = str(EXAMPLES / "vendor-ballscrew.yaml")  # quick, with two infeasible pairs
    default = json.loads(ok("size", vendor, "--format", "json"))["results"]
    assert default and all(r["feasible"] for r in default)
    text = ok("size", vendor)
    assert "infeasible pairs not shown (--all shows them)" in text
    everything = ok("size", vendor, "--all")
    assert "why these pairs fail:" in everything and "SGM7J-A5A" in everything


def test_top_keeps_the_first_rows() -> None:
    full = json.loads(ok("size", EX64, "--format", "json"))["results"]
    top = json.loads(ok("size", EX64, "--format", "json", "--top", "2"))["results"]
    assert top == full[:2]
    assert "4 more pairs not shown (--top)" in ok("size", EX64, "--top", "2")
    assert run("size", EX64, "--top", "0").returncode == 2


def test_minimize_ranks_by_duration_and_rank_by_changes_the_order() -> None:
    by_duration = json.loads(ok("size", EX64, "--format", "json"))
    durations = [r["duration"] for r in by_duration["results"]]
    assert by_duration["ranked_by"] == "duration" and durations == sorted(durations)
    by_rms = json.loads(ok("size", EX64, "--format", "json", "--rank-by", "rms"))
    assert by_rms["ranked_by"] == "rms"
    rms = [r["rms_torque"] for r in by_rms["results"]]
    assert rms == sorted(rms) and rms != [r["rms_torque"] for r in by_duration["results"]]
    for key in ("margin", "peak", "price", "mass", "size"):
        assert json.loads(ok("size", EX64, "-f", "json", "-r", key))["ranked_by"] == key
    assert json.loads(ok("size", EX64, "-f", "json", "-r", "power"))["ranked_by"] == "size"


def test_bad_rank_key_lists_the_keys() -> None:
    from sizer.sizing import RANK_KEYS

    line = assert_user_error(run("size", EX64, "--rank-by", "speed"),
                             "--rank-by: unknown key 'speed'; choose one of")
    assert all(key in line for key in RANK_KEYS)
    help_text = ok("size", "--help")
    assert all(key in help_text for key in RANK_KEYS)


def test_catalog_option_adds_motors_and_motor_option_selects(tmp_path: Path) -> None:
    design = tmp_path / "bare.yaml"
    design.write_text("task: {displacement: 90 deg, duration: 0.25 s}\n"
                      "load: {inertia: 0.01 kg*m^2}\n"
                      "transmission: {type: gearbox, ratio: 10}\nlaws: [cycloidal]\n")
    # a design that names no catalog is sized against the bundled real motors (issue 5)
    bundled = json.loads(ok("size", str(design), "-f", "json", "--all"))
    assert {"SGM7J-02A", "HG-KN43J"} <= {r["motor"] for r in bundled["results"]}
    data = json.loads(ok("size", str(design), "--catalog", SERVO_CATALOG, "-f", "json"))
    assert sorted(r["motor"] for r in data["results"]) == ["HG-KN13J", "HG-KN23J",
                                                           "HG-KN43J", "HG-KN73J"]
    one = json.loads(ok("size", str(design), "-c", SERVO_CATALOG, "-m", "HG-KN43J",
                        "-f", "json", "--all"))
    assert [r["motor"] for r in one["results"]] == ["HG-KN43J"]
    assert_user_error(run("size", str(design), "-c", SERVO_CATALOG, "-m", "HG-KN99J"),
                      "--motor", "HG-KN99J")


def test_no_feasible_pair_is_a_result_not_an_error(tmp_path: Path) -> None:
    design = tmp_path / "hopeless.yaml"
    design.write_text("task: {displacement: 100 rad, duration: 0.1 s}\nload: {inertia: 10}\n"
                      "laws: [cycloidal]\nmotors: book-examples\n")
    table = run("size", str(design))
    assert table.returncode == 0 and "no feasible motor/law pair" in table.stdout
    assert table.stderr == ""
    machine = run("size", str(design), "--format", "csv")
    assert machine.returncode == 0 and machine.stdout.count("\n") == 1  # the header only
    assert machine.stderr == "no feasible motor/law pair\n"


# ------------------------------------------------------------------ user errors
@pytest.mark.parametrize(("text", "fragments"), [
    ("task: {displacement: 1 rad, duration: [1\nload: {inertia: 1}\n",
     ["bad.yaml:2:", "invalid YAML"]),
    ("task:\n  displacement: 1 rad\nload: {inertia: 1}\nmotors: book-examples\n",
     ["bad.yaml:1:", "task.duration", "missing"]),
    ("task:\n  displacement: 1 rad\n  duration: 2 kg\nload: {inertia: 1}\n"
     "motors: book-examples\n", ["bad.yaml:3:", "task.duration", "'2 kg'"]),
    ("task: {displacement: 1 rad, duration: 1 s}\nload: {inertia: 1}\n"
     "motors: [book-examples]\nlaws: [cycloid]\n", ["bad.yaml:4:", "laws"]),
])
def test_bad_design_is_a_located_user_error(tmp_path: Path, text: str,
                                            fragments: list[str]) -> None:
    design = tmp_path / "bad.yaml"
    design.write_text(text)
    assert_user_error(run("size", str(design)), *fragments)


def test_missing_file_and_bad_format() -> None:
    assert_user_error(run("size", "no-such-design.yaml"), "no-such-design.yaml", "not found")
    assert run("size", EX64, "--format", "xml").returncode == 2


def test_a_real_process_reports_a_user_error_without_traceback(tmp_path: Path) -> None:
    design = tmp_path / "bad.yaml"
    design.write_text("task:\n  displacement: 1 rad\n  duration: 2 kg\nload: {inertia: 1}\n")
    result = subprocess.run([sys.executable, "-m", "sizer", "size", str(design)], cwd=ROOT,
                            capture_output=True, text=True, timeout=120, check=False)
    assert_user_error(result, "bad.yaml:3:", "task.duration")
    assert result.stdout == ""
