"""The Python interface (sizer.size / sizer.check / sizer.load): a path, a mapping and a
Design give the same results; results are plain data and hold the objects sized."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import yaml

import sizer
from sizer.errors import UserError
from sizer.model.domain import Design
from sizer.sizing import SizingResult

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "book" / "ex6_3.yaml"


def test_a_path_a_mapping_and_a_design_size_alike():
    from_path = sizer.size(EXAMPLE)
    data = yaml.safe_load(EXAMPLE.read_text())
    design = sizer.load(data, base=EXAMPLE.parent)
    assert isinstance(design, Design)
    from_mapping = sizer.size(design)
    assert isinstance(from_path, SizingResult)
    assert from_path.to_records() == from_mapping.to_records()
    assert sizer.size(sizer.load(EXAMPLE)).to_dict() == from_path.to_dict()


def test_records_are_json_ready_and_ranked_feasible_first():
    result = sizer.size(EXAMPLE)
    records = result.to_records()
    text = json.dumps(result.to_dict(), allow_nan=False)  # no NaN or inf anywhere
    assert json.loads(text)["candidates"] == records
    verdicts = [r["feasible"] for r in records]
    assert verdicts == sorted(verdicts, reverse=True)
    assert len(records) == len(result.results) == len(result.table)


def test_rows_hold_the_motor_and_law_objects_sized():
    result = sizer.size(EXAMPLE)
    row = result.results[0]
    assert row.motor_object is not None and row.motor_object.id == row.motor
    assert row.law_object is not None and row.law_object.spec == row.spec
    assert row.motor_object in sizer.load(EXAMPLE).motors


def test_a_bad_mapping_is_a_located_user_error():
    data = yaml.safe_load(EXAMPLE.read_text())
    data["task"]["duration"] = "-1 s"
    with pytest.raises(UserError) as error:
        sizer.load(data, base=EXAMPLE.parent)
    assert "task.duration" in str(error.value) and "<design>" in str(error.value)


def test_check_gives_the_named_pair():
    data = yaml.safe_load(EXAMPLE.read_text())
    first = sizer.size(EXAMPLE).results[0]
    data["check"] = {"motor": first.motor, "law": first.spec}
    checked = sizer.check(sizer.load(data, base=EXAMPLE.parent))
    assert checked.motor == first.motor and checked.feasible == first.feasible
    assert checked.duration == pytest.approx(first.duration, rel=1e-12)
