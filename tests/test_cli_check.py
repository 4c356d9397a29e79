"""``sizer check``: exit codes 0 (pass), 1 (a limit fails), 2 (invalid input), for CI."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
from cli_run import run_cli as run

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"
INDEXING = EXAMPLES / "indexing-table.yaml"
EX63 = str(EXAMPLES / "book" / "ex6_3.yaml")




def variant(tmp_path: Path, name: str, old: str, new: str) -> Path:
    """A copy of the indexing-table design with one text replaced (catalog path absolute)."""
    text = INDEXING.read_text()
    assert old in text
    text = text.replace(old, new).replace(
        "motors: catalogs/example-servo.yaml",
        f"motors: {EXAMPLES / 'catalogs' / 'example-servo.yaml'}")
    path = tmp_path / name
    path.write_text(text)
    return path


@pytest.fixture
def failing(tmp_path: Path) -> Path:
    """The same machine with a motor too small for the load's inertia."""
    return variant(tmp_path, "too-small.yaml", "motor: HG-KN43J", "motor: HG-KN23J")


def test_passing_design_exits_0_and_lists_every_limit() -> None:
    result = run("check", str(INDEXING))
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0] == ("check Indexing table, 90 deg in 0.25 s: motor HG-KN43J, "
                        "law modified_sinusoidal")
    for name in ("speed", "peak", "rms", "thermal_speed", "inertia_ratio"):
        assert any(line.startswith(f"  {name}: ") and line.endswith("(ok)") for line in lines)
    assert lines[-1].startswith("PASS: HG-KN43J with modified_sinusoidal")
    assert "limiting: inertia_ratio" in lines[-1]


def test_failing_design_exits_1_and_says_which_limit_by_how_much(failing: Path) -> None:
    result = run("check", str(failing))
    assert result.returncode == 1 and result.stderr == ""
    last = result.stdout.splitlines()[-1]
    # everything driven, (0.034/10^2 + 0.3e-4) kg*m^2, over 0.225e-4 kg*m^2 = 16.444
    assert last == ("FAIL: HG-KN23J with modified_sinusoidal: inertia_ratio: 16.4444 "
                    "against 10 (inertia driven over the rotor's), margin -64.44% (FAILS)")


def test_failing_torque_margin(tmp_path: Path) -> None:
    design = variant(tmp_path, "fast.yaml", "duration: 0.25 s", "duration: 0.1 s")
    result = run("check", str(design))
    assert result.returncode == 1
    last = result.stdout.splitlines()[-1]
    assert last.startswith("FAIL: HG-KN43J with modified_sinusoidal: peak: ")
    assert "10% required (FAILS)" in last


def test_json_verdict(failing: Path) -> None:
    good = run("check", str(INDEXING), "--format", "json")
    assert good.returncode == 0
    data = json.loads(good.stdout)
    assert list(data) == ["format", "design", "passed", "units", "result", "segments"]
    assert data["format"] == "sizer.check/1"
    assert data["passed"] is True and data["result"]["motor"] == "HG-KN43J"
    assert data["result"]["feasible"] is True and data["result"]["duration"] == 0.25
    bad = run("check", str(failing), "-f", "json")
    assert bad.returncode == 1 and json.loads(bad.stdout)["passed"] is False


def test_minimize_design_passes_at_its_limit() -> None:
    # at T_min the RMS torque is at its limit (to rounding): that passes
    result = run("check", EX63)
    assert result.returncode == 0
    assert "T_min = 193.36 ms" in result.stdout
    assert "FAILS" not in result.stdout
    data = json.loads(run("check", EX63, "-f", "json").stdout)
    assert all(c["passed"] for c in data["result"]["checks"])
    assert data["result"]["limiting"] == "rms"


@pytest.mark.parametrize(("text", "fragments"), [
    ("task: {displacement: 1 rad, duration: [1\nload: {inertia: 1}\n",
     ["bad.yaml:2:", "invalid YAML"]),
    ("task:\n  displacement: 1 rad\nload: {inertia: 1}\nmotors: book-examples\n",
     ["bad.yaml:1:", "task.duration", "missing"]),
    ("task:\n  displacement: 1 rad\n  duration: 1 s\nload:\n  inertia: 1 N*m\n"
     "motors: book-examples\n", ["bad.yaml:5:", "load.inertia", "'1 N*m'"]),
    ("task: {displacement: 1 rad, duration: 1 s}\nload: {inertia: 1}\n"
     "motors: book-examples\ncheck:\n  motor: ex6_9\n  law: cycloidal\n",
     ["bad.yaml:5:", "check.motor", "unknown motor 'ex6_9'", "ex6_1"]),
    ("task: {displacement: 1 rad, duration: 1 s}\nload: {inertia: 1}\n"
     "motors: book-examples\n", ["bad.yaml", "check", "names no motor and law"]),
])
def test_invalid_input_exits_2_with_one_located_error(tmp_path: Path, text: str,
                                                      fragments: list[str]) -> None:
    design = tmp_path / "bad.yaml"
    design.write_text(text)
    result = run("check", str(design))
    assert result.returncode == 2 and result.stdout == ""
    assert "Traceback" not in result.stderr
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ")
    for fragment in fragments:
        assert fragment in lines[0]


def test_several_files_the_worst_exit_code_wins(tmp_path: Path, failing: Path) -> None:
    both = run("check", str(INDEXING), str(failing))
    assert both.returncode == 1
    assert both.stdout.count("\nPASS: ") == 1 and both.stdout.count("\nFAIL: ") == 1
    broken = tmp_path / "broken.yaml"
    broken.write_text("task: [\n")
    mixed = run("check", str(broken), str(INDEXING), "--format", "json")
    assert mixed.returncode == 2  # invalid input, and the other file is still checked
    assert mixed.stderr.startswith("error: ") and "broken.yaml" in mixed.stderr
    assert [d["passed"] for d in json.loads(mixed.stdout)] == [True]


def test_check_as_a_real_process(failing: Path) -> None:
    """Exit codes of the installed entry point as CI sees them."""
    def sizer(*args: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run([sys.executable, "-m", "sizer", "check", *args], cwd=ROOT,
                              capture_output=True, text=True, timeout=120, check=False)

    assert sizer("examples/indexing-table.yaml").returncode == 0
    result = sizer(str(failing), "examples/book/no-such-file.yaml")
    assert result.returncode == 2
    assert "Traceback" not in result.stderr
    assert "error: examples/book/no-such-file.yaml" in result.stderr
    assert "FAIL: HG-KN23J" in result.stdout
