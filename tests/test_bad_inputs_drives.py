"""Bad values of a drive catalog file (named by a design's ``drives:``) and of the design's
drive fields (issue 32), rule by rule: non-finite, wrong type, wrong unit, out of range,
missing, unknown key, empty, and levels inconsistent with each other. Each is answered by
one ``error:`` line naming the file, the LINE of the field (found by composing the YAML,
tests/bad_input_lines.py) and its path, exit code 2.

tests/test_bad_inputs_catalogs.py holds one case per field of a drive inside a motor
catalog; the cases here read a drive catalog file of its own, and the rules it does not
exercise.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest
import yaml
from bad_input_cases import Case, assert_well_formed, edited, run_case
from bad_input_lines import at
from test_bad_inputs_catalogs import DRIVE, MOTOR_KT

DESIGN = edited("book/ex6_1-6_2.yaml", set={"motors": "motors.yaml", "drives": ["drives.yaml"]},
                delete=("check",))
"""The book's design sized against MOTOR_KT (motors.yaml) with the drives of drives.yaml."""
MOTORS = yaml.safe_dump({"motors": [MOTOR_KT]}, sort_keys=False)
NAN, INF = float("nan"), float("inf")
FINITE = "not a finite number"
CD = "catalog:drives"


def catalog_text(drive: dict[str, Any], top: dict[str, Any] | None = None) -> str:
    data = {"catalog": "Acme drives", "manufacturer": "Acme", "drives": [drive], **(top or {})}
    return yaml.safe_dump(data, sort_keys=False)


def bad(id: str, key: str, value: Any, words: tuple[str, ...], field: str,
        delete: bool = False, more: dict[str, Any] | None = None) -> Case:
    """drives.yaml's drive with ``key`` set to ``value`` (or deleted): the message names
    drives.yaml, the line and ``drives[0].key``."""
    drive = {**DRIVE, **(more or {})}
    if delete:
        del drive[key]
    else:
        drive[key] = value
    text = catalog_text(drive)
    where = "drives[0]" if delete else f"drives[0].{key}"
    words = (*at(text, where, file="drives.yaml"), f"drives[0].{key}", *words)
    return Case(id, design=DESIGN, extra_files={"motors.yaml": MOTORS, "drives.yaml": text},
                words=words, fields=(field,))


def bad_top(id: str, key: str, value: Any, words: tuple[str, ...], field: str) -> Case:
    text = catalog_text(DRIVE, {key: value})
    return Case(id, design=DESIGN, extra_files={"motors.yaml": MOTORS, "drives.yaml": text},
                words=(*at(text, key, file="drives.yaml"), key, *words), fields=(field,))


def bad_design(id: str, path: str, value: Any, words: tuple[str, ...], field: str,
               where: str | None = None) -> Case:
    text = edited("book/ex6_1-6_2.yaml", set={"motors": "motors.yaml", path: value},
                  delete=("check",))
    return Case(id, design=text, extra_files={"motors.yaml": MOTORS,
                                              "drives.yaml": catalog_text(DRIVE)},
                words=(*at(text, where or path), where or path, *words), fields=(field,))


CATALOG = [
    bad("id-missing", "id", None, ("required field is missing",), f"{CD}.id", delete=True),
    bad("id-a-list", "id", ["D1"], ("expected text",), f"{CD}.id"),
    bad("id-empty", "id", " ", ("empty",), f"{CD}.id"),
    bad("continuous-current-nan", "continuous_current", NAN, (FINITE,),
        f"{CD}.continuous_current"),
    bad("continuous-current-a-voltage", "continuous_current", "3 V", ("expected a current",),
        f"{CD}.continuous_current"),
    bad("continuous-current-missing", "continuous_current", None,
        ("required field is missing",), f"{CD}.continuous_current", delete=True),
    bad("peak-current-inf-text", "peak_current", "inf A", (FINITE,), f"{CD}.peak_current"),
    bad("peak-current-huge", "peak_current", "1e6 A", ("[1e-4, 1e5] A",),
        f"{CD}.peak_current"),
    bad("peak-current-a-list", "peak_current", [9], ("expected a current",),
        f"{CD}.peak_current"),
    bad("dc-bus-voltage-nan", "dc_bus_voltage", NAN, (FINITE,), f"{CD}.dc_bus_voltage"),
    bad("dc-bus-voltage-a-current", "dc_bus_voltage", "3 A", ("expected a voltage",),
        f"{CD}.dc_bus_voltage"),
    bad("bus-capacitance-inf", "bus_capacitance", INF, (FINITE,), f"{CD}.bus_capacitance"),
    bad("bus-capacitance-a-voltage", "bus_capacitance", "300 V", ("expected a capacitance",),
        f"{CD}.bus_capacitance"),
    bad("bus-capacitance-zero", "bus_capacitance", 0, ("[1e-9, 10] F",),
        f"{CD}.bus_capacitance"),
    bad("max-bus-voltage-nan", "max_bus_voltage", NAN, (FINITE,), f"{CD}.max_bus_voltage"),
    bad("max-bus-voltage-huge", "max_bus_voltage", "1e5 V", ("[1, 1e4] V",),
        f"{CD}.max_bus_voltage"),
    bad("braking-threshold-nan", "braking_threshold", NAN, (FINITE,),
        f"{CD}.braking_threshold"),
    bad("braking-threshold-a-power", "braking_threshold", "40 W", ("expected a voltage",),
        f"{CD}.braking_threshold"),
    bad("braking-power-nan", "braking_resistor_power", NAN, (FINITE,),
        f"{CD}.braking_resistor_power"),
    bad("braking-power-a-voltage", "braking_resistor_power", "40 V", ("expected a power",),
        f"{CD}.braking_resistor_power"),
    bad("price-nan", "price", NAN, (FINITE,), f"{CD}.price"),
    bad("price-a-bool", "price", True, ("expected",), f"{CD}.price"),
    bad("motors-a-number", "motors", 5, ("expected",), f"{CD}.motors"),
    bad("source-a-list", "source", ["a", "b"], ("expected text",), f"{CD}.source"),
    bad("part-number-nan", "part_number", NAN, (FINITE,), f"{CD}.part_number"),
    bad("manufacturer-a-bool", "manufacturer", True, ("expected text",), f"{CD}.manufacturer"),
    bad("notes-a-mapping", "notes", {"a": 1}, ("expected text",), f"{CD}.notes"),
    bad("unknown-key", "voltage", "300 V", ("unknown field 'voltage'", "dc_bus_voltage"),
        f"{CD}"),
    bad_top("drives-empty", "drives", [], ("no drives",), "catalog:drives"),
    bad_top("drives-a-mapping", "drives", {"id": "D1"}, ("expected a list",),
            "catalog:drives"),
    bad_top("catalog-a-list", "catalog", [1], ("expected text",), "catalog:drives"),
    bad_top("top-unknown-key", "motors_for", "M1", ("unknown field",), "catalog:drives"),
]

DESIGN_FIELDS = [
    bad_design("design-drives-a-number", "drives", 5, ("expected a list",), "drives"),
    bad_design("design-drives-nan", "drives", NAN, (FINITE,), "drives"),
    bad_design("design-drives-unknown", "drives", ["no-such-drives"],
               ("unknown drive catalog", "siemens-s120"), "drives", where="drives[0]"),
    Case("design-drives-a-motor-catalog", extra_files={"motors.yaml": MOTORS},
         design=edited("book/ex6_1-6_2.yaml", set={"motors": "motors.yaml",
                                                   "drives": ["motors.yaml"]},
                       delete=("check",)),
         words=("motors.yaml:1:", "drives", "the catalog has no drives"), fields=("drives",)),
    bad_design("drive-current-margin-nan", "limits", {"drive_current_margin": NAN},
               (FINITE,), "limits.drive_current_margin", where="limits.drive_current_margin"),
    bad_design("drive-current-margin-a-current", "limits", {"drive_current_margin": "3 A"},
               ("expected",), "limits.drive_current_margin",
               where="limits.drive_current_margin"),
]

CASES = [*CATALOG, *DESIGN_FIELDS]

FAULTS = [
    bad("braking-threshold-below-the-bus-voltage", "braking_threshold", "200 V",
        ("braking_threshold", "dc_bus_voltage"), f"{CD}.braking_threshold"),
    bad("max-bus-voltage-below-the-bus-voltage", "max_bus_voltage", "200 V",
        ("max_bus_voltage", "dc_bus_voltage"), f"{CD}.max_bus_voltage",
        more={"braking_threshold": "150 V"}),
    bad_design("design-drives-empty-list", "drives", [], ("drives",), "drives"),
]


@pytest.mark.parametrize("case", CASES, ids=str)
def test_bad_drive_field(case: Case, tmp_path: Path) -> None:
    run_case(case, tmp_path)


@pytest.mark.parametrize("case", FAULTS, ids=str)
def test_bad_drive_levels_and_empty_drives(case: Case, tmp_path: Path) -> None:
    run_case(case, tmp_path)


def test_case_ids_are_unique_and_fields_are_the_models() -> None:
    assert_well_formed(CASES)
