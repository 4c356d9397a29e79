"""The table of input ranges: used by every quantity field, printed in the docs and the
schemas, and its extreme values still size to finite figures."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import pytest
from cli_run import run_cli

from sizer.io.loader import catalog_schema, design_schema, gearbox_catalog_schema
from sizer.io.schema.fields import fields_by_range as used
from sizer.io.schema.fields import input_fields
from sizer.io.schema.ranges import RANGES, Range, number_text, ranges_markdown

ROOT = Path(__file__).resolve().parents[1]


def test_the_document_lists_exactly_the_table():
    text = (ROOT / "docs" / "input-ranges.md").read_text(encoding="utf-8")
    block = re.search(r"<!-- ranges:start -->\n(.*)<!-- ranges:end -->", text, re.S)
    assert block is not None
    assert block.group(1) == ranges_markdown(used()), (
        "docs/input-ranges.md is out of date; its table is ranges_markdown(fields_by_range())")
    rows = [line.split(" | ")[0].lstrip("| ") for line in block.group(1).splitlines()[2:]]
    assert rows == list(RANGES)


def test_every_quantity_names_a_range_and_every_range_is_used():
    fields = input_fields()
    unranged = [f.path for f in fields.values() if f.quantity and not f.ranges]
    assert unranged == []
    assert set(RANGES) == set(used())
    assert all(r in RANGES for f in fields.values() for r in f.ranges)


def _numbers_with_bounds(schema: object) -> list[dict]:
    found = []
    if isinstance(schema, dict):
        if schema.get("type") == "number" and "minimum" in schema:
            found.append(schema)
        for value in schema.values():
            found += _numbers_with_bounds(value)
    elif isinstance(schema, list):
        for value in schema:
            found += _numbers_with_bounds(value)
    return found


def test_the_schemas_carry_the_ranges():
    design = design_schema()
    duration = design["$defs"]["TaskInput"]["properties"]["duration"]
    assert {"type": "number", "minimum": 1e-6, "maximum": 1e6} in duration["anyOf"]
    inertia = catalog_schema()["$defs"]["MotorInput"]["properties"]["inertia"]
    assert inertia["anyOf"][0] == {"type": "number", "minimum": 0.0, "maximum": 1e3}
    assert "0 or in [1e-12, 1000] kg*m^2" in inertia["description"]
    ratio = gearbox_catalog_schema()["$defs"]["GearboxRatioInput"]["properties"]["ratio"]
    assert ratio["anyOf"][0] == {"type": "number", "minimum": 1e-3, "maximum": 1e5}
    torque = design["$defs"]["LoadInput"]["properties"]["torque"]
    assert torque["anyOf"][0]["anyOf"][0] == {"type": "number", "minimum": -1e8,
                                              "maximum": 1e8}
    spans = {(s["minimum"], s["maximum"]) for schema in (design, catalog_schema())
             for s in _numbers_with_bounds(schema)}
    assert spans <= {r.span for r in RANGES.values()}


@pytest.mark.parametrize(("allowed", "value", "ok"), [
    (Range("time", 1e-6, 1e6, ""), 1e-6, True),
    (Range("time", 1e-6, 1e6, ""), 1e-320, False),
    (Range("time", 1e-6, 1e6, ""), 0.0, False),
    (Range("time", 1e-6, 1e6, ""), math.nextafter(1e6, math.inf), False),
    (Range("time", 1e-6, 1e6, "", zero=True), -0.0, True),
    (Range("time", 1e-6, 1e6, "", zero=True), 1e-320, False),
    (Range("torque", 1e-9, 1e8, "", zero=True, signed=True), -1e8, True),
    (Range("torque", 1e-9, 1e8, "", zero=True, signed=True), -1e-320, False),
    (Range("torque", 1e-9, 1e8, "", signed=True), -1e9, False),
    (Range("ratio", 1e-3, 1e5, ""), math.inf, False),
    (Range("ratio", 1e-3, 1e5, ""), math.nan, False),
])
def test_a_range_holds_its_bounds_and_no_subnormal(allowed, value, ok):
    assert allowed.contains(value) is ok


def test_bounds_print_short():
    assert [number_text(x) for x in (1e-6, 1e5, 1000.0, 0.95, math.pi / 2, 1e-320)] == \
        ["1e-6", "1e5", "1000", "0.95", "1.5708", "1e-320"]


# ------------------------------------------------------------------ extreme designs

MOTORS = """\
source: extreme figures of the ranges
manufacturer: idealized extremes
motors:
  - {id: BIG, inertia: 1000, continuous_torque: 1e6, peak_torque: 1e6, rated_speed: 1e5,
     max_speed: 1e5, damping: 1000, price: 1e9, mass: 1e5}
  - {id: SMALL, inertia: 1e-12, continuous_torque: 1e-6, peak_torque: 1e-6,
     rated_speed: 1e-3, max_speed: 1e-3, damping: 1e-12, price: 1e-3, mass: 1e-4}
  - {id: ZERO, inertia: 0, continuous_torque: 1e-6, peak_torque: 1e6, rated_speed: 1e-3,
     max_speed: 1e5}
  - id: CURVE
    inertia: 1e-12
    continuous_torque: 1e-6
    peak_torque: 1e6
    rated_speed: 1e-3
    continuous_curve: [[0, 1e-6], [1e-3, 1e-6], [1e5, 1e-6]]
    intermittent_curve: [[0, 1e6], [1e-3, 1e6], [1e5, 1e-6]]
"""

LAWS = "laws: [cycloidal, poly5, 'trapezoidal(alpha=1/3)', 'double_s(alpha=1/3, beta=1/4)']"

EXTREMES = {
    "fast-long-steep": """\
task: {displacement: 1e7 rad, duration: 1e-6 s, dwell: 1e6 s, return: true}
load: {inertia: 1e8, damping: 1e8, friction: 1e8, torque: -1e8}
transmission: [{type: gearbox, ratio: 1e5, efficiency: 0.01, inertia: 1000},
               {type: gearbox, ratio: 1e4, efficiency: 0.01, inertia: 1e-12}]
limits: {torque_margin: 0.95, speed_margin: 0.95, inertia_ratio: 1e-3, max_speed: 1e6,
         max_acceleration: 1e9, max_jerk: 1e13}
""",
    "slow-short-speed-up": """\
task: {displacement: -1e-6 rad, duration: 1e6 s, dwell: 1e-6 s}
load: {inertia: 1e-12, damping: 1e-12, friction: 1e-9, torque: 1e-9}
transmission: [{type: gearbox, ratio: 1e-3, efficiency: 0.01}, {type: belt, ratio: 1e-3}]
limits: {inertia_ratio: 1e6, max_speed: 1e-6, max_acceleration: 1e-6, max_jerk: 1e-6}
""",
    "linear-heavy-fine-screw": """\
task: {displacement: 1e4 m, duration: 1e-6 s, dwell: 1e6 s}
load: {mass: 1e7, damping: 1e9, friction: 1e9, force: -1e9, incline: 1.5707963267948966,
       friction_coefficient: 10}
transmission: [{type: gearbox, ratio: 1000, efficiency: 0.1, inertia: 1000},
               {type: ball_screw, lead: 1e-5, diameter: 1, length: 100, density: 1e5,
                preload_torque: 1e4, max_speed: 1e5, efficiency: 0.01}]
limits: {max_speed: 1e4, max_acceleration: 1e8, max_jerk: 1e12, inertia_ratio: 1e6}
""",
    "linear-tiny-minimize": """\
task: {displacement: 1e-7 m, duration: minimize}
load: {mass: 1e-6}
transmission: [{type: belt, driver_diameter: 10, belt_mass: 1e4, driver_inertia: 1000,
                driven_inertia: 1000, efficiency: 0.01}]
""",
    "rotary-minimize-ratio-list": """\
task: {displacement: 1e7 rad, duration: minimize}
load: {inertia: 1e8}
transmission: [{type: gearbox, ratio: [1e-3, 1e5], efficiency: 0.01}]
""",
}


def _no_constant(name: str) -> float:
    raise AssertionError(f"{name} in the JSON output")


@pytest.mark.parametrize("name", list(EXTREMES))
def test_the_extremes_of_the_ranges_size_to_finite_figures(name, tmp_path):
    (tmp_path / "motors.yaml").write_text(MOTORS, encoding="utf-8")
    design = tmp_path / "design.yaml"
    design.write_text(f"{EXTREMES[name]}{LAWS}\nmotors: motors.yaml\n", encoding="utf-8")
    result = run_cli("size", str(design), "--all", "--format", "json")
    assert result.returncode == 0, result.stderr
    assert "Warning" not in result.stderr and "Traceback" not in result.stderr
    data = json.loads(result.stdout, parse_constant=_no_constant)
    assert len(data["results"]) == 4 * 4
    assert not re.search(r"\b(nan|-?inf)\b", result.stdout, re.I)
