"""End-to-end tests of ``sizer laws`` and ``sizer law``.

Each output format and each kind of user error runs once as a real subprocess
(``python -m sizer``); variations run ``main()`` in this process, which is faster (the
law library imports scipy) and goes through the same argument and error handling.
"""

from __future__ import annotations

import csv
import io
import json
import math
import subprocess
import sys
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path
from unittest.mock import patch

import pytest
from cli_run import assert_user_error

LAW_KEYS = ["law", "spec", "params", "continuity", "C_v", "C_a", "C_j", "jerk_bounded",
            "C_v_rms", "C_a_rms", "acceleration_jumps"]

CYCLOIDAL_MOVE = ["law", "cycloidal", "--displacement", "90 deg", "--duration", "0.5 s",
                  "--samples", "11"]


def sizer(*args: str) -> subprocess.CompletedProcess[str]:
    """Run ``python -m sizer`` with the arguments; stdout is a pipe (not a terminal)."""
    return subprocess.run([sys.executable, "-m", "sizer", *args], capture_output=True,
                          text=True, timeout=120, check=False)


def sizer_in_process(*args: str) -> subprocess.CompletedProcess[str]:
    """Run ``sizer.cli.app.main`` here with the arguments, capturing its output and exit."""
    from sizer.cli.app import main

    stdout, stderr = io.StringIO(), io.StringIO()
    code = 0
    with (patch.object(sys, "argv", ["sizer", *args]), redirect_stdout(stdout),
          redirect_stderr(stderr)):
        try:
            main()
        except SystemExit as exit_:
            code = exit_.code if isinstance(exit_.code, int) else 1
    return subprocess.CompletedProcess(args, code, stdout.getvalue(), stderr.getvalue())


def ok(*args: str, in_process: bool = False) -> str:
    result = (sizer_in_process if in_process else sizer)(*args)
    assert result.returncode == 0, result.stderr
    return result.stdout




# ------------------------------------------------------------------ sizer laws
@pytest.fixture(scope="module")
def laws_json() -> list[dict]:
    return json.loads(ok("laws", "--format", "json"))


def test_laws_json_has_every_default_law_with_the_required_keys(laws_json: list[dict]) -> None:
    from sizer.laws import DEFAULT_LAW_SPECS

    assert len(laws_json) == len(DEFAULT_LAW_SPECS)
    for row in laws_json:
        assert list(row) == LAW_KEYS  # this order, always
        assert isinstance(row["params"], dict)
        assert isinstance(row["continuity"], int) or row["continuity"] == "inf"
        assert row["jerk_bounded"] == (row["acceleration_jumps"] == [])
        for jump in row["acceleration_jumps"]:
            assert set(jump) == {"tau", "jump"}


def test_laws_json_cycloidal_coefficients_are_exact(laws_json: list[dict]) -> None:
    cycloidal = next(row for row in laws_json if row["law"] == "cycloidal")
    assert cycloidal["spec"] == "cycloidal"
    assert cycloidal["C_v"] == pytest.approx(2.0, abs=1e-12)
    assert cycloidal["C_a"] == pytest.approx(2.0 * math.pi, abs=1e-12)
    assert cycloidal["continuity"] == 2
    assert cycloidal["jerk_bounded"] is True


def test_laws_json_trapezoid_reports_where_the_acceleration_jumps(laws_json: list[dict]) -> None:
    trapezoid = next(row for row in laws_json if row["law"] == "trapezoidal")
    assert trapezoid["params"] == {"alpha": pytest.approx(1 / 3)}
    assert [j["tau"] for j in trapezoid["acceleration_jumps"]] == pytest.approx(
        [0.0, 1 / 3, 2 / 3, 1.0])
    assert trapezoid["jerk_bounded"] is False


def test_laws_csv_is_full_precision_and_deterministic() -> None:
    args = ("laws", "--law", "cycloidal", "--law", "trapezoidal(alpha=1/3)", "--format", "csv")
    first, second = ok(*args), ok(*args)
    assert first == second
    assert first.endswith("\n") and "\r" not in first
    rows = list(csv.DictReader(io.StringIO(first)))
    assert [r["law"] for r in rows] == ["cycloidal", "trapezoidal"]
    assert float(rows[0]["C_a"]) == pytest.approx(2 * math.pi, abs=1e-15)
    assert rows[0]["jerk_bounded"] == "true" and rows[0]["acceleration_jump_tau"] == ""
    assert len(rows[1]["acceleration_jump_tau"].split(";")) == 4


def test_laws_markdown_to_an_output_file(tmp_path: Path) -> None:
    target = tmp_path / "laws.md"
    assert ok("laws", "--law", "poly5", "--law", "harmonic", "--format", "md",
              "--output", str(target)) == ""
    assert [p.name for p in tmp_path.iterdir()] == ["laws.md"]  # no temporary left over
    md = target.read_text().splitlines()
    assert md[0].startswith("| law |") and "C_a_rms" in md[0]
    assert set(md[1]) <= set("|-: ")
    assert md[2].startswith("| polynomial(degree=5) |")
    assert len(md) == 4


def test_laws_plain_table_when_piped() -> None:
    table = ok("laws", "--law", "poly5", "--law", "trapezoidal(alpha=1/4)")
    lines = table.splitlines()
    assert lines[0].split()[:3] == ["law", "continuity", "C_v"]
    assert "1.875" in lines[2] and "│" not in table
    assert lines[3].endswith("impulses at 0, 1/4, 3/4, 1")


def test_laws_output_replaces_an_existing_file(tmp_path: Path) -> None:
    target = tmp_path / "laws.json"
    target.write_text("old")
    ok("laws", "--law", "harmonic", "--format", "json", "--output", str(target),
       in_process=True)
    assert json.loads(target.read_text())[0]["law"] == "harmonic"
    assert [p.name for p in tmp_path.iterdir()] == ["laws.json"]


def test_unwritable_output_is_a_user_error(tmp_path: Path) -> None:
    missing = tmp_path / "no" / "such" / "dir" / "laws.csv"
    assert_user_error(sizer_in_process("laws", "--law", "harmonic", "--output", str(missing)),
                      str(missing))


def test_unknown_law_lists_the_known_ones() -> None:
    line = assert_user_error(sizer("laws", "--law", "sinusoidal_wave"), "sinusoidal_wave")
    assert "cycloidal" in line and "trapezoidal" in line


def test_out_of_range_parameter_names_the_valid_range() -> None:
    assert_user_error(sizer("laws", "--law", "trapezoidal(alpha=0.7)"), "alpha", "[1e-06, 1/2]")


def test_bad_format_is_a_usage_error() -> None:
    assert sizer_in_process("laws", "--format", "xml").returncode == 2


# ------------------------------------------------------------------- sizer law
def test_law_json_cycloidal_move() -> None:
    data = json.loads(ok(*CYCLOIDAL_MOVE, "--format", "json"))
    h, T = math.pi / 2, 0.5
    assert data["law"] == "cycloidal" and data["spec"] == "cycloidal"
    assert data["displacement"] == pytest.approx(h) and data["duration"] == T
    assert data["units"] == {"t": "s", "q": "rad", "v": "rad/s", "a": "rad/s^2",
                             "j": "rad/s^3"}
    assert all(len(data[k]) == 11 for k in "tqvaj")
    assert data["t"][0] == 0.0 and data["t"][-1] == pytest.approx(T)
    assert data["q"][0] == pytest.approx(0.0, abs=1e-15)
    assert data["q"][-1] == pytest.approx(h, rel=1e-15)
    assert max(data["v"]) == pytest.approx(2 * h / T, rel=1e-14)  # C_v = 2 at t = T/2


def test_law_csv_linear_axis_with_start_point_is_deterministic() -> None:
    args = ("law", "poly5", "--displacement", "200 mm", "--duration", "0.4",
            "--start-time", "1 s", "--start-position", "50 mm", "--samples", "5",
            "--format", "csv")
    first, second = ok(*args), ok(*args)
    assert first == second
    rows = list(csv.reader(io.StringIO(first)))
    assert rows[0] == ["t [s]", "q [m]", "v [m/s]", "a [m/s^2]", "j [m/s^3]"]
    assert len(rows) == 6
    assert [float(x) for x in rows[1][:3]] == pytest.approx([1.0, 0.05, 0.0], abs=1e-15)
    assert float(rows[-1][1]) == pytest.approx(0.25, rel=1e-15)
    assert float(rows[3][2]) == pytest.approx(1.875 * 0.2 / 0.4, rel=1e-14)  # C_v h/T


def test_law_json_is_deterministic_and_written_to_a_file(tmp_path: Path) -> None:
    first, second = tmp_path / "a.json", tmp_path / "b.json"
    ok(*CYCLOIDAL_MOVE, "--format", "json", "--output", str(first))
    ok(*CYCLOIDAL_MOVE, "--format", "json", "-o", str(second))
    assert first.read_bytes() == second.read_bytes()
    assert first.read_bytes().endswith(b"}\n")


def test_law_plain_table() -> None:
    table = ok(*CYCLOIDAL_MOVE).splitlines()
    assert table[0].split() == ["t", "[s]", "q", "[rad]", "v", "[rad/s]", "a", "[rad/s^2]",
                                "j", "[rad/s^3]"]
    assert len(table) == 2 + 11
    middle = table[2 + 5].split()  # t = T/2: v = 2 h/T, a = 0 (not rounding noise)
    assert middle[:3] == ["0.25", "0.7854", "6.2832"] and middle[3] == "0"


def test_law_markdown() -> None:
    md = ok(*CYCLOIDAL_MOVE, "--format", "md", in_process=True).splitlines()
    assert md[0] == "| t [s] | q [rad] | v [rad/s] | a [rad/s^2] | j [rad/s^3] |"
    assert len(md) == 2 + 11


def test_law_wrong_unit_is_a_user_error() -> None:
    args = [*CYCLOIDAL_MOVE[:-4], "--duration", "3 kg"]
    assert_user_error(sizer(*args), "--duration", "3 kg", "time")


@pytest.mark.parametrize(
    ("change", "fragments"),
    [
        (["--duration", "0 s"], ["--duration", "positive"]),
        (["--duration", "-2"], ["--duration", "positive"]),
        (["--samples", "1"], ["--samples", "2"]),
        (["--displacement", "2 N"], ["--displacement", "angle", "length"]),
        (["--start-time", "1 m"], ["--start-time"]),
    ],
)
def test_law_bad_input_is_a_user_error(change: list[str], fragments: list[str]) -> None:
    args = list(CYCLOIDAL_MOVE)
    if change[0] in args:
        args[args.index(change[0]) + 1] = change[1]
    else:
        args += change
    assert_user_error(sizer_in_process(*args), *fragments)


def test_linear_move_needs_a_length_start_position() -> None:
    args = ["law", "poly5", "--displacement", "200 mm", "--duration", "1",
            "--start-position", "10 deg"]
    assert_user_error(sizer_in_process(*args), "--start-position", "length")


def test_bad_samples_value_is_a_usage_error() -> None:
    assert sizer_in_process(*CYCLOIDAL_MOVE[:-1], "many").returncode == 2


# ------------------------------------------------------------------------ help
@pytest.mark.parametrize("args", [["--help"], ["laws", "--help"], ["law", "--help"]])
def test_help_exits_zero_and_shows_an_example(args: list[str]) -> None:
    # the top-level help as a real process; the commands' helps are variations (in this
    # process: the same text, without a process start each)
    out = ok(*args, in_process=args != ["--help"])
    assert "Usage" in out and "sizer" in out and "Example" in out


def test_version() -> None:
    from sizer import __version__

    assert ok("--version", in_process=True).strip() == f"sizer {__version__}"


# ---------------------------------------------------------------- the README
ROOT = Path(__file__).resolve().parent.parent


def test_readme_starts_with_the_run_and_test_commands_that_ci_runs() -> None:
    readme = (ROOT / "README.md").read_text().splitlines()
    assert readme[1].startswith("python -m pip install . && python -m sizer ")
    assert readme[2] == "python -m pip install '.[test]' && python -m pytest -q"
    ci = (ROOT / ".ci" / "run").read_text().splitlines()
    assert ci[0] == "#!/usr/bin/env bash" and "set -euo pipefail" in ci
    commands = [line for line in ci if line.startswith("python ")]
    assert commands[-1] == readme[2]  # the README's test command, last: its summary closes
    assert all(" ruff " in c or " mypy " in c or c == "python -m pip install '.[test]'"
               for c in commands[:-1])  # before it only the install, ruff and mypy


def test_readme_documents_every_law_and_its_example_output() -> None:
    from sizer.laws import LAW_FAMILIES, known_law_ids

    readme = (ROOT / "docs" / "motion-laws.md").read_text()  # moved out of the README
    for law_id in known_law_ids():
        assert f"`{law_id}`" in readme
    for family in LAW_FAMILIES.values():
        for parameter in family.parameters:
            assert f"`{parameter.name}` {parameter.range_text()}" in readme
    md = ok("laws", "--law", "cycloidal", "--law", "double_s(alpha=1/3, beta=1/4)",
            "--format", "md", in_process=True)
    assert md in readme
