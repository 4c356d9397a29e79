"""A law that breaks a linkage's dead-point rule (seed 003: a trapezoidal law's jumping
acceleration at the slider-crank's dead centres) has no finite torque: the pair is
infeasible, its failed check names the dead point, and no command or format prints inf or
nan as a figure; the result holds None.
"""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml
from bad_input_cases import EXAMPLES, NON_FINITE, assert_clean_answer
from cli_run import run_cli

from sizer.io.loader import load_design
from sizer.sizing.engine import check_design

LAW = "trapezoidal(alpha=1/3)"  # C1 only: its acceleration jumps at the dead centres


@pytest.fixture()
def design(tmp_path: Path) -> Path:
    """examples/press-slider-crank.yaml (bottom to top dead centre) checked with LAW."""
    data = yaml.safe_load((EXAMPLES / "press-slider-crank.yaml").read_text(encoding="utf-8"))
    data["laws"] = [LAW, "poly7"]
    data["check"] = {"motor": "HG-KN43J", "law": LAW}
    path = tmp_path / "press.yaml"
    path.write_text(yaml.safe_dump(data, sort_keys=False), encoding="utf-8")
    return path


def test_check_prints_a_verdict_not_inf(design: Path) -> None:
    result = run_cli("check", str(design))
    assert_clean_answer(result, 1)
    assert not NON_FINITE.search(result.stdout), result.stdout
    assert "peak torque n/a" in result.stdout and "rms torque n/a" in result.stdout
    fail = next(line for line in result.stdout.splitlines() if line.startswith("FAIL:"))
    assert "dead_point" in fail and "dead point" in fail


def test_the_result_holds_none(design: Path) -> None:
    result = check_design(load_design(design))
    assert not result.feasible and result.limiting == "dead_point"
    assert result.peak_torque is None and result.rms_torque is None


@pytest.mark.parametrize("args", [
    ("check", "--format", "json"),
    ("size", "--all"), ("size", "--all", "--format", "csv"),
    ("size", "--all", "--format", "json"), ("size", "--all", "--format", "md"),
    ("segments",), ("segments", "--format", "csv"), ("segments", "--format", "json"),
    ("segments", "--format", "md"),
], ids=" ".join)
def test_no_format_prints_a_non_finite_figure(design: Path, args: tuple[str, ...]) -> None:
    result = run_cli(args[0], str(design), *args[1:])
    assert_clean_answer(result, 1 if args[0] == "check" else 0)
    assert not NON_FINITE.search(result.stdout), [
        line for line in result.stdout.splitlines() if NON_FINITE.search(line)][:3]
    if args[0] != "segments" or args[-1] in ("segments", "md"):  # csv and json: figures
        assert "dead_point" in result.stdout or "dead-point" in result.stdout


def test_the_report_holds_no_non_finite_figure(design: Path, tmp_path: Path) -> None:
    out = tmp_path / "report"
    result = run_cli("report", str(design), "-o", str(out))
    assert_clean_answer(result, 0)
    for page in out.rglob("*.md"):
        text = page.read_text(encoding="utf-8")
        assert not NON_FINITE.search(text), page


def test_segments_show_no_torque_of_a_singular_law(design: Path) -> None:
    result = run_cli("segments", str(design))
    assert_clean_answer(result, 0)
    move = next(line for line in result.stdout.splitlines() if line.startswith("move "))
    assert move.count("n/a") == 4  # peak, rms, share, energy; the speed stays a number
    assert "unbounded" in result.stdout and "dead-point rule" in result.stdout


def test_segments_json_holds_null_torques(design: Path) -> None:
    import json

    result = run_cli("segments", str(design), "--format", "json")
    data = json.loads(result.stdout)
    assert data["rms_torque"] is None and data["feasible"] is False
    assert all(row["peak_torque"] is None for row in data["segments"])
