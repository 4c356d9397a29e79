"""``sizer size --law SPEC``: other laws than the design's, without editing it."""

from __future__ import annotations

import json
from pathlib import Path

from cli_run import assert_user_error
from cli_run import run_cli as run

from sizer import api

ROOT = Path(__file__).resolve().parent.parent
INDEXING = str(ROOT / "examples" / "indexing-table.yaml")
MACHINE = str(ROOT / "examples" / "machines" / "two-axis-packer.yaml")


def sized(*args: str) -> dict:
    result = run("size", INDEXING, "--format", "json", "--all", *args)
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout)


def test_the_laws_given_replace_the_designs() -> None:
    data = sized("--law", "cycloidal", "--law", "trapezoidal(alpha=0.2)")
    specs = {r["spec"] for r in data["results"]}
    assert specs == {"cycloidal", "trapezoidal(alpha=1/5)"}  # canonical spec
    assert len(data["results"]) == 4 * 2  # every motor with each of the two laws
    # the same figures as the API with laws= (sizer.api.override)
    expected = api.size(INDEXING, laws=["cycloidal", "trapezoidal(alpha=0.2)"])
    by_pair = {(r["motor"], r["spec"]): r for r in data["results"]}
    for r in expected.results:
        row = by_pair[(r.motor, r.spec)]
        assert row["feasible"] == r.feasible and row["rms_torque"] == r.rms_torque


def test_a_law_given_twice_is_sized_once_and_the_design_is_unchanged() -> None:
    before = Path(INDEXING).read_bytes()
    data = sized("--law", "poly5", "--law", "poly5")
    assert len(data["results"]) == 4
    assert Path(INDEXING).read_bytes() == before
    assert len(data["design"]["laws"]) == 1  # the report states the laws it sized


def test_a_bad_spec_is_a_user_error_naming_the_option() -> None:
    assert_user_error(run("size", INDEXING, "--law", "cycloidal(alpha=2)"), "--law")
    assert_user_error(run("size", INDEXING, "--law", "no_such_law"), "--law")
    assert_user_error(run("size", INDEXING, "--law", "trapezoidal(alpha=1.5)"), "--law")


def test_not_for_a_machine_file() -> None:
    assert_user_error(run("size", MACHINE, "--law", "cycloidal"), "--law", "machine")
