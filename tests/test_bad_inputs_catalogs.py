"""Bad motor catalogs and gearbox catalogs: fields out of range and physically impossible
motors, each refused at loading with the file, the field, the motor and what is allowed;
``sizer catalog validate`` reports the same impossibilities, all of them."""

from __future__ import annotations

import copy
import re
from typing import Any

import pytest
import yaml
from bad_input_cases import Case, edited, run_case
from cli_run import run_cli

DESIGN = edited("book/ex6_1-6_2.yaml", set={"motors": "motors.yaml"}, delete=("check",))
"""The book's design sized against the case's catalog (motors.yaml beside it)."""

GEARED = edited("indexing-table-gearboxes.yaml", set={"transmission.catalog": "gears.yaml"})
"""A design that takes its gearbox from the case's gearbox catalog (gears.yaml)."""

MOTOR: dict[str, Any] = {
    "id": "M1", "inertia": "0.5 kg*cm^2", "continuous_torque": "1.3 N*m",
    "peak_torque": "3.8 N*m", "rated_speed": "3000 rpm", "max_speed": "6000 rpm",
    "damping": "1e-5 N*m*s/rad",
    "continuous_curve": [["0 rpm", "1.3 N*m"], ["3000 rpm", "1.3 N*m"],
                         ["6000 rpm", "0.8 N*m"]],
    "intermittent_curve": [["0 rpm", "3.8 N*m"], ["3000 rpm", "3.8 N*m"],
                           ["6000 rpm", "1.5 N*m"]],
    "source": "a datasheet", "part_number": "M1-A", "manufacturer": "Acme",
    "price": 450, "mass": "1.2 kg", "notes": "for the tests",
}
"""A plausible servomotor with both curves."""

GEARS: dict[str, Any] = {
    "catalog": "test gearboxes", "manufacturer": "Acme", "source": "a datasheet",
    "notes": "for the tests",
    "gearboxes": [{
        "id": "PG60", "efficiency": "95 %", "max_input_speed": "5000 rpm",
        "rated_output_torque": "30 N*m", "peak_output_torque": "60 N*m",
        "backlash": "8 arcmin", "source": "a datasheet", "notes": "n",
        "ratios": [{"ratio": 10, "inertia": "0.15 kg*cm^2"},
                   {"ratio": 16, "inertia": "0.12 kg*cm^2", "efficiency": "94 %",
                    "max_input_speed": "4000 rpm", "rated_output_torque": "32 N*m",
                    "peak_output_torque": "64 N*m"}]}],
}


def _parts(path: str) -> list[str | int]:
    return [int(i) if i else n for n, i in re.findall(r"([^.\[\]]+)|\[(\d+)\]", path)]


def _edit(data: dict[str, Any], set: dict[str, Any], delete: tuple[str, ...]) -> str:
    data = copy.deepcopy(data)
    for path, value in set.items():
        *head, last = _parts(path)
        target: Any = data
        for part in head:
            target = target[part]
        if isinstance(target, list) and last == len(target):
            target.append(value)
        else:
            target[last] = value
    for path in delete:
        *head, last = _parts(path)
        target = data
        for part in head:
            target = target[part]
        del target[last]
    return yaml.safe_dump(data, sort_keys=False)


def motors(set: dict[str, Any] | None = None, delete: tuple[str, ...] = (),
           motor: dict[str, Any] | None = None) -> str:
    """A catalog of MOTOR with keys set ('motors[0].inertia' or 'catalog') and deleted."""
    data = {"catalog": "test motors", "manufacturer": "Acme", "source": "a datasheet",
            "notes": "n", "motors": [motor if motor is not None else MOTOR]}
    return _edit(data, set or {}, delete)


M = "motors[0]"
C = "catalog:motors"


def bad_motor(id: str, set: dict[str, Any], words: tuple[str, ...],
              fields: tuple[str, ...], delete: tuple[str, ...] = ()) -> Case:
    """A catalog with one bad motor, sized by the book's design."""
    return Case(id, design=DESIGN, catalog=motors(set, delete), words=("motors.yaml:", *words),
                fields=fields)


def bad_gears(id: str, set: dict[str, Any], words: tuple[str, ...],
              fields: tuple[str, ...]) -> Case:
    """A gearbox catalog with a bad entry, named by a design's gearbox stage."""
    return Case(id, design=GEARED, extra_files={"gears.yaml": _edit(GEARS, set, ())},
                words=("gears.yaml:", *words), fields=fields)


FIELDS = [
    bad_motor("catalog-name-list", {"catalog": [1]}, ("catalog", "expected text"),
              ("catalog:catalog",)),
    bad_motor("catalog-manufacturer-mapping", {"manufacturer": {"x": 1}},
              ("manufacturer", "expected text"), ("catalog:manufacturer",)),
    bad_motor("catalog-source-list", {"source": [1]}, ("source", "expected text"),
              ("catalog:source",)),
    bad_motor("catalog-notes-mapping", {"notes": {"a": "b"}}, ("notes", "expected text"),
              ("catalog:notes",)),
    bad_motor("catalog-no-motors", {"motors": []}, ("motors", "no motors"),
              ("catalog:motors",)),
    bad_motor("motor-not-a-mapping", {"motors": ["M1"]}, ("motors[0]", "expected a mapping"),
              ("catalog:motors",)),
    bad_motor("motor-id-empty", {f"{M}.id": " "}, (f"{M}.id", "must not be empty"),
              (f"{C}.id",)),
    bad_motor("motor-id-twice", {"motors[1]": {**MOTOR, "price": 500}},
              ("motors[1].id", "duplicate motor id 'M1'"), (f"{C}.id",)),
    bad_motor("motor-unknown-field", {f"{M}.colour": "red"},
              (f"{M}.colour", "unknown field 'colour'", "allowed fields"), ("catalog:motors",)),
    bad_motor("inertia-subnormal", {f"{M}.inertia": "1e-320 kg*m^2"},
              (f"{M}.inertia", "0 or in [1e-12, 1000] kg*m^2"), (f"{C}.inertia",)),
    bad_motor("inertia-negative", {f"{M}.inertia": "-0.5 kg*cm^2"},
              (f"{M}.inertia", "0 or in [1e-12, 1000] kg*m^2", "-0.5 kg*cm^2"),
              (f"{C}.inertia",)),
    bad_motor("continuous-torque-huge", {f"{M}.continuous_torque": "1e7 N*m"},
              (f"{M}.continuous_torque", "[1e-6, 1e6] N*m"), (f"{C}.continuous_torque",)),
    bad_motor("continuous-torque-missing", {}, (f"{M}.continuous_torque",
                                                 "required field is missing"),
              (f"{C}.continuous_torque",), delete=(f"{M}.continuous_torque",)),
    bad_motor("peak-torque-zero", {f"{M}.peak_torque": "0 N*m"},
              (f"{M}.peak_torque", "[1e-6, 1e6] N*m"), (f"{C}.peak_torque",)),
    bad_motor("rated-speed-subnormal", {f"{M}.rated_speed": "1e-320 rpm"},
              (f"{M}.rated_speed", "[0.001, 1e5] rad/s"), (f"{C}.rated_speed",)),
    bad_motor("rated-speed-integer-too-large", {f"{M}.rated_speed": 10**400},
              (f"{M}.rated_speed", "too large", "finite"), (f"{C}.rated_speed",)),
    bad_motor("max-speed-1e7-rpm", {f"{M}.max_speed": "1e7 rpm"},
              (f"{M}.max_speed", "[0.001, 1e5] rad/s", "1e7 rpm"), (f"{C}.max_speed",)),
    bad_motor("damping-negative", {f"{M}.damping": "-1e-5 N*m*s/rad"},
              (f"{M}.damping", "0 or in [1e-12, 1000] N*m*s/rad"), (f"{C}.damping",)),
    bad_motor("curve-speed-negative", {f"{M}.continuous_curve[1]": ["-3000 rpm", "1.3 N*m"]},
              (f"{M}.continuous_curve[1].speed", "0 or in [0.001, 1e5] rad/s"),
              (f"{C}.continuous_curve.speed",)),
    bad_motor("curve-torque-1e308", {f"{M}.continuous_curve[2]": ["6000 rpm", 1e308]},
              (f"{M}.continuous_curve[2].torque", "0 or in [1e-6, 1e6] N*m"),
              (f"{C}.continuous_curve.torque",)),
    bad_motor("curve-point-of-three", {f"{M}.continuous_curve[0]": [0, 1.3, 2]},
              (f"{M}.continuous_curve[0]", "[speed, torque]"), (f"{C}.continuous_curve",)),
    bad_motor("intermittent-speed-subnormal",
              {f"{M}.intermittent_curve[0]": ["1e-320 rad/s", "3.8 N*m"]},
              (f"{M}.intermittent_curve[0].speed", "0 or in [0.001, 1e5] rad/s"),
              (f"{C}.intermittent_curve.speed",)),
    bad_motor("intermittent-torque-negative",
              {f"{M}.intermittent_curve[2]": ["6000 rpm", "-1.5 N*m"]},
              (f"{M}.intermittent_curve[2].torque", "0 or in [1e-6, 1e6] N*m"),
              (f"{C}.intermittent_curve.torque",)),
    bad_motor("intermittent-curve-a-number", {f"{M}.intermittent_curve": 3.8},
              (f"{M}.intermittent_curve", "expected a list"), (f"{C}.intermittent_curve",)),
    bad_motor("motor-source-list", {f"{M}.source": ["a"]}, (f"{M}.source", "expected text"),
              (f"{C}.source",)),
    bad_motor("part-number-mapping", {f"{M}.part_number": {"a": 1}},
              (f"{M}.part_number", "expected text"), (f"{C}.part_number",)),
    bad_motor("motor-manufacturer-list", {f"{M}.manufacturer": [1]},
              (f"{M}.manufacturer", "expected text"), (f"{C}.manufacturer",)),
    bad_motor("price-negative", {f"{M}.price": -3},
              (f"{M}.price", "0 or in [0.001, 1e9]"), (f"{C}.price",)),
    bad_motor("mass-zero", {f"{M}.mass": "0 kg"}, (f"{M}.mass", "[1e-4, 1e5] kg"),
              (f"{C}.mass",)),
    bad_motor("motor-notes-list", {f"{M}.notes": [1]}, (f"{M}.notes", "expected text"),
              (f"{C}.notes",)),
    Case("inline-motor-inertia-bool",
         design=edited("book/ex6_3-vmax4.yaml", set={"motors[0].inertia": True}),
         words=("design.yaml:", "motors[0].inertia", "expected an inertia"),
         fields=(f"{C}.inertia",)),
]

IMPOSSIBLE = [
    bad_motor("peak-below-continuous", {f"{M}.peak_torque": "1 N*m"},
              (f"{M}.peak_torque", "motor 'M1'", "below the continuous torque"),
              (f"{C}.peak_torque", f"{C}.continuous_torque")),
    bad_motor("max-below-rated-speed", {f"{M}.max_speed": "2000 rpm"},
              (f"{M}.max_speed", "motor 'M1'", "below the rated speed"),
              (f"{C}.max_speed", f"{C}.rated_speed")),
    bad_motor("curve-speeds-not-increasing",
              {f"{M}.continuous_curve[2]": ["3000 rpm", "0.8 N*m"]},
              (f"{M}.continuous_curve[2]", "motor 'M1'", "strictly increasing"),
              (f"{C}.continuous_curve.speed",)),
    bad_motor("curve-of-one-point", {f"{M}.intermittent_curve": [["0 rpm", "3.8 N*m"]]},
              (f"{M}.intermittent_curve", "motor 'M1'", "at least 2 points"),
              (f"{C}.intermittent_curve",)),
    bad_motor("curve-beyond-max-speed",
              {f"{M}.intermittent_curve[2]": ["7000 rpm", "1.5 N*m"]},
              (f"{M}.intermittent_curve[2]", "motor 'M1'", "7000 rpm", "above max_speed"),
              (f"{C}.intermittent_curve", f"{C}.max_speed")),
    bad_motor("continuous-curve-above-intermittent",
              {f"{M}.continuous_curve[2]": ["6000 rpm", "2 N*m"]},
              (f"{M}.continuous_curve", "motor 'M1'", "above the intermittent region at "
               "6000 rpm", "2 N*m > 1.5 N*m", "by 0.5 N*m"),
              (f"{C}.continuous_curve", f"{C}.intermittent_curve")),
    bad_motor("continuous-torque-above-intermittent-curve",
              {f"{M}.continuous_curve": None,
               f"{M}.intermittent_curve[1]": ["3000 rpm", "1 N*m"]},
              (f"{M}.continuous_torque", "motor 'M1'", "above the intermittent region at "
               "3000 rpm", "by 0.3 N*m"),
              (f"{C}.continuous_torque", f"{C}.intermittent_curve")),
]

GEARBOX_CASES = [
    bad_gears("gears-catalog-list", {"catalog": [1]}, ("catalog", "expected text"),
              ("gearboxes:catalog",)),
    bad_gears("gears-manufacturer-mapping", {"manufacturer": {"a": 1}},
              ("manufacturer", "expected text"), ("gearboxes:manufacturer",)),
    bad_gears("gears-source-list", {"source": [1]}, ("source", "expected text"),
              ("gearboxes:source",)),
    bad_gears("gears-notes-list", {"notes": [1]}, ("notes", "expected text"),
              ("gearboxes:notes",)),
    bad_gears("gears-no-gearboxes", {"gearboxes": []}, ("gearboxes", "at least 1"),
              ("gearboxes:gearboxes",)),
    bad_gears("gears-id-twice", {"gearboxes[1]": GEARS["gearboxes"][0]},
              ("gearboxes[1].id", "duplicate gearbox id 'PG60'"), ("gearboxes:gearboxes.id",)),
    bad_gears("gears-efficiency-0.1-percent", {"gearboxes[0].efficiency": "0.1 %"},
              ("gearboxes[0].efficiency", "[0.01, 1]"), ("gearboxes:gearboxes.efficiency",)),
    bad_gears("gears-max-input-speed-huge", {"gearboxes[0].max_input_speed": "1e7 rpm"},
              ("gearboxes[0].max_input_speed", "[0.001, 1e5] rad/s"),
              ("gearboxes:gearboxes.max_input_speed",)),
    bad_gears("gears-rated-torque-negative", {"gearboxes[0].rated_output_torque": -1},
              ("gearboxes[0].rated_output_torque", "[1e-6, 1e7] N*m"),
              ("gearboxes:gearboxes.rated_output_torque",)),
    bad_gears("gears-peak-torque-subnormal",
              {"gearboxes[0].peak_output_torque": "1e-320 N*m"},
              ("gearboxes[0].peak_output_torque", "[1e-6, 1e7] N*m"),
              ("gearboxes:gearboxes.peak_output_torque",)),
    bad_gears("gears-backlash-1-rad", {"gearboxes[0].backlash": "1 rad"},
              ("gearboxes[0].backlash", "0 or in [1e-9, 0.5] rad"),
              ("gearboxes:gearboxes.backlash",)),
    bad_gears("gears-series-source-list", {"gearboxes[0].source": [1]},
              ("gearboxes[0].source", "expected text"), ("gearboxes:gearboxes.source",)),
    bad_gears("gears-series-notes-mapping", {"gearboxes[0].notes": {"a": 1}},
              ("gearboxes[0].notes", "expected text"), ("gearboxes:gearboxes.notes",)),
    bad_gears("gears-no-ratios", {"gearboxes[0].ratios": []},
              ("gearboxes[0].ratios", "at least 1"), ("gearboxes:gearboxes.ratios",)),
    bad_gears("gears-ratio-listed-twice", {"gearboxes[0].ratios[1].ratio": 10},
              ("gearboxes[0].ratios[1].ratio", "gearbox 'PG60'", "ratio 10 is listed twice"),
              ("gearboxes:gearboxes.ratios.ratio",)),
    bad_gears("gears-ratio-1e6", {"gearboxes[0].ratios[0].ratio": 1e6},
              ("gearboxes[0].ratios[0].ratio", "[0.001, 1e5]"),
              ("gearboxes:gearboxes.ratios.ratio",)),
    bad_gears("gears-ratio-inertia-negative", {"gearboxes[0].ratios[0].inertia": -1},
              ("gearboxes[0].ratios[0].inertia", "0 or in [1e-12, 1000] kg*m^2"),
              ("gearboxes:gearboxes.ratios.inertia",)),
    bad_gears("gears-ratio-efficiency-2", {"gearboxes[0].ratios[1].efficiency": 2},
              ("gearboxes[0].ratios[1].efficiency", "[0.01, 1]"),
              ("gearboxes:gearboxes.ratios.efficiency",)),
    bad_gears("gears-ratio-max-input-speed-zero",
              {"gearboxes[0].ratios[1].max_input_speed": 0},
              ("gearboxes[0].ratios[1].max_input_speed", "[0.001, 1e5] rad/s"),
              ("gearboxes:gearboxes.ratios.max_input_speed",)),
    bad_gears("gears-ratio-rated-torque-huge",
              {"gearboxes[0].ratios[1].rated_output_torque": "1e8 N*m"},
              ("gearboxes[0].ratios[1].rated_output_torque", "[1e-6, 1e7] N*m"),
              ("gearboxes:gearboxes.ratios.rated_output_torque",)),
    bad_gears("gears-ratio-peak-torque-bool",
              {"gearboxes[0].ratios[1].peak_output_torque": True},
              ("gearboxes[0].ratios[1].peak_output_torque", "expected a torque"),
              ("gearboxes:gearboxes.ratios.peak_output_torque",)),
]

DRIVE: dict[str, Any] = {
    "id": "D1", "continuous_current": "3 A", "peak_current": "9 A", "dc_bus_voltage": "300 V",
    "bus_capacitance": "470 uF", "max_bus_voltage": "410 V", "braking_threshold": "380 V",
    "braking_resistor_power": "40 W", "price": 300, "motors": ["M1"], "source": "a datasheet",
    "part_number": "D1-A", "manufacturer": "Acme", "notes": "for the tests",
}
"""A plausible drive for MOTOR (issue 16)."""

MOTOR_KT = {**MOTOR, "torque_constant": "0.5 N*m/Arms", "winding_resistance": "4.2 ohm",
            "thermal_time_constant": "20 min", "max_winding_temperature_rise": "100 K"}
"""MOTOR with the fields a drive needs and the thermal ones."""

D = "drives[0]"
CD = "catalog:drives"


def with_drives(set: dict[str, Any] | None = None, delete: tuple[str, ...] = (),
                motor: dict[str, Any] | None = None) -> str:
    """A catalog of MOTOR_KT (or ``motor``) and DRIVE, with keys set and deleted."""
    data = {"catalog": "test motors", "manufacturer": "Acme", "source": "a datasheet",
            "notes": "n", "motors": [motor if motor is not None else MOTOR_KT],
            "drives": [DRIVE]}
    return _edit(data, set or {}, delete)


def bad_drive(id: str, set: dict[str, Any], words: tuple[str, ...], fields: tuple[str, ...],
              delete: tuple[str, ...] = (), motor: dict[str, Any] | None = None) -> Case:
    """A catalog with a bad drive or a bad new motor field, sized by the book's design."""
    return Case(id, design=DESIGN, catalog=with_drives(set, delete, motor),
                words=("motors.yaml:", *words), fields=fields)


def bad_design(id: str, set: dict[str, Any], words: tuple[str, ...],
               fields: tuple[str, ...]) -> Case:
    """The book's design with drives' fields edited, sized against MOTOR_KT and DRIVE."""
    design = yaml.safe_load(DESIGN)
    for key, value in set.items():
        head, _, last = key.rpartition(".")
        (design.setdefault(head, {}) if head else design)[last] = value
    return Case(id, design=yaml.safe_dump(design, sort_keys=False), catalog=with_drives(),
                words=("design.yaml:", *words), fields=fields)


DRIVE_CASES = [
    bad_drive("torque-constant-negative", {f"{M}.torque_constant": "-0.5 N*m/A"},
              (f"{M}.torque_constant", "[1e-5, 1000] N*m/A"), (f"{C}.torque_constant",)),
    bad_drive("torque-constant-a-torque", {f"{M}.torque_constant": "0.5 N*m"},
              (f"{M}.torque_constant", "expected a torque constant"), ()),
    bad_drive("winding-resistance-negative", {f"{M}.winding_resistance": "-4.2 ohm"},
              (f"{M}.winding_resistance", "[1e-4, 1e4] ohm", "-4.2 ohm"),
              (f"{C}.winding_resistance",)),
    bad_drive("phase-resistance-zero", {f"{M}.phase_resistance": "0 ohm"},
              (f"{M}.phase_resistance", "[1e-4, 1e4] ohm"), (f"{C}.phase_resistance",),
              delete=(f"{M}.winding_resistance",)),
    bad_drive("phase-and-winding-resistance", {f"{M}.phase_resistance": "2.1 ohm"},
              (f"{M}.phase_resistance", "not both"), (f"{C}.phase_resistance",)),
    bad_drive("thermal-time-constant-zero", {f"{M}.thermal_time_constant": "0 min"},
              (f"{M}.thermal_time_constant", "[0.1, 1e6] s"), (f"{C}.thermal_time_constant",)),
    bad_drive("winding-temperature-rise-negative",
              {f"{M}.max_winding_temperature_rise": "-10 K"},
              (f"{M}.max_winding_temperature_rise", "[1, 400] K"),
              (f"{C}.max_winding_temperature_rise",)),
    bad_drive("torque-current-curve-falling",
              {f"{M}.torque_current_curve": [["0 A", "0 N*m"], ["4 A", "2 N*m"],
                                             ["8 A", "1.9 N*m"]]},
              (f"{M}.torque_current_curve", "increase strictly"),
              (f"{C}.torque_current_curve",)),
    bad_drive("torque-current-curve-one-point",
              {f"{M}.torque_current_curve": [["4 A", "2 N*m"]]},
              (f"{M}.torque_current_curve", "at least 2 points"), ()),
    bad_drive("torque-current-current-negative",
              {f"{M}.torque_current_curve": [["-1 A", "0 N*m"], ["4 A", "2 N*m"]]},
              (f"{M}.torque_current_curve[0].current", "0 or in [1e-4, 1e5] A"),
              (f"{C}.torque_current_curve.current",)),
    bad_drive("torque-current-torque-a-speed",
              {f"{M}.torque_current_curve": [["0 A", "0 rpm"], ["4 A", "2 N*m"]]},
              (f"{M}.torque_current_curve[0].torque", "expected a torque"),
              (f"{C}.torque_current_curve.torque",)),
    bad_drive("drives-not-a-list", {"drives": "D1"}, ("drives",), (CD,)),
    bad_drive("drive-id-empty", {f"{D}.id": " "}, (f"{D}.id", "must not be empty"),
              (f"{CD}.id",)),
    bad_drive("drive-id-twice", {"drives[1]": DRIVE}, ("drives[1].id", "duplicate drive id"),
              (f"{CD}.id",)),
    bad_drive("drive-no-current", {}, (f"{D}.continuous_current", "required field is missing"),
              (f"{CD}.continuous_current",), delete=(f"{D}.continuous_current",)),
    bad_drive("drive-continuous-current-zero", {f"{D}.continuous_current": "0 A"},
              (f"{D}.continuous_current", "[1e-4, 1e5] A"), (f"{CD}.continuous_current",)),
    bad_drive("drive-peak-current-a-torque", {f"{D}.peak_current": "9 N*m"},
              (f"{D}.peak_current", "expected a current"), (f"{CD}.peak_current",)),
    bad_drive("drive-peak-below-continuous", {f"{D}.peak_current": "2 A"},
              (f"{D}.peak_current", "below the continuous current 3 A"),
              (f"{CD}.peak_current",)),
    bad_drive("drive-bus-voltage-negative", {f"{D}.dc_bus_voltage": "-300 V"},
              (f"{D}.dc_bus_voltage", "[1, 1e4] V"), (f"{CD}.dc_bus_voltage",)),
    bad_drive("drive-bus-capacitance-huge", {f"{D}.bus_capacitance": "100 F"},
              (f"{D}.bus_capacitance", "[1e-9, 10] F"), (f"{CD}.bus_capacitance",)),
    bad_drive("drive-max-bus-voltage-a-current", {f"{D}.max_bus_voltage": "410 A"},
              (f"{D}.max_bus_voltage", "expected a voltage"), (f"{CD}.max_bus_voltage",)),
    bad_drive("drive-braking-above-trip", {f"{D}.braking_threshold": "450 V"},
              (f"{D}.braking_threshold", "above the maximum bus voltage 410 V"),
              (f"{CD}.braking_threshold",)),
    bad_drive("drive-braking-power-negative", {f"{D}.braking_resistor_power": "-40 W"},
              (f"{D}.braking_resistor_power", "0 or in [0.001, 1e7] W"),
              (f"{CD}.braking_resistor_power",)),
    bad_drive("drive-price-negative", {f"{D}.price": -5}, (f"{D}.price", "0 or in [0.001, 1e9]"),
              (f"{CD}.price",)),
    bad_drive("drive-unknown-motor", {f"{D}.motors": ["M9"]},
              (f"{D}.motors[0]", "no loaded motor is 'M9'", "loaded motors: M1"),
              (f"{CD}.motors",)),
    bad_drive("drive-motor-without-torque-constant", {}, (
        f"{D}.motors[0]", "motor 'M1' gives no torque_constant"), (f"{CD}.motors",),
        motor=MOTOR),
    bad_drive("drive-source-list", {f"{D}.source": [1]}, (f"{D}.source", "expected text"),
              (f"{CD}.source",)),
    bad_drive("drive-part-number-list", {f"{D}.part_number": [1]},
              (f"{D}.part_number", "expected text"), (f"{CD}.part_number",)),
    bad_drive("drive-manufacturer-mapping", {f"{D}.manufacturer": {"a": 1}},
              (f"{D}.manufacturer", "expected text"), (f"{CD}.manufacturer",)),
    bad_drive("drive-notes-mapping", {f"{D}.notes": {"a": 1}}, (f"{D}.notes", "expected text"),
              (f"{CD}.notes",)),
    bad_design("design-drives-unknown", {"drives": ["no-such-drives"]},
               ("drives[0]", "unknown drive catalog 'no-such-drives'", "siemens-s120"),
               ("drives",)),
    bad_design("drive-current-margin-one", {"limits.drive_current_margin": 1.0},
               ("limits.drive_current_margin", "0 or in [1e-9, 0.95]"),
               ("limits.drive_current_margin",)),
]

BRAKE_CASES = [
    bad_motor("brake-torque-negative", {f"{M}.brake_holding_torque": "-1 N*m"},
              (f"{M}.brake_holding_torque", "[1e-6, 1e6] N*m"), (f"{C}.brake_holding_torque",)),
    bad_motor("brake-torque-an-inertia", {f"{M}.brake_holding_torque": "1 kg*m^2"},
              (f"{M}.brake_holding_torque",), ()),
    bad_motor("brake-inertia-negative", {f"{M}.brake_inertia": "-0.1 kg*cm^2"},
              (f"{M}.brake_inertia",), (f"{C}.brake_inertia",)),
]

MOTOR_WINDING = {**MOTOR_KT, "winding_inductance": "8 mH", "back_emf_constant": "30 V/krpm",
                 "poles": 8, "continuous_current": "2.6 A", "peak_current": "7.6 A",
                 "dc_bus_voltage": "320 V", "commutation": "sinusoidal"}
"""MOTOR_KT with its winding's electrical data (issue 35: the electrical envelope)."""

ELECTRICAL_CASES = [
    bad_drive("inductance-negative", {f"{M}.winding_inductance": "-8 mH"},
              (f"{M}.winding_inductance", "[1e-8, 10] H", "-8 mH"),
              (f"{C}.winding_inductance",), motor=MOTOR_WINDING),
    bad_drive("phase-and-winding-inductance", {f"{M}.phase_inductance": "4 mH"},
              (f"{M}.phase_inductance", "not both"), (f"{C}.phase_inductance",),
              motor=MOTOR_WINDING),
    bad_drive("back-emf-a-voltage", {f"{M}.back_emf_constant": "30 V"},
              (f"{M}.back_emf_constant", "expected a back emf constant"),
              (f"{C}.back_emf_constant",), motor=MOTOR_WINDING),
    bad_drive("poles-odd", {f"{M}.poles": 7}, (f"{M}.poles", "even whole number"),
              (f"{C}.poles",), motor=MOTOR_WINDING),
    bad_drive("continuous-current-zero", {f"{M}.continuous_current": "0 A"},
              (f"{M}.continuous_current", "[1e-4, 1e5] A"), (f"{C}.continuous_current",),
              motor=MOTOR_WINDING),
    bad_drive("peak-current-below-continuous", {f"{M}.peak_current": "2 A"},
              (f"{M}.peak_current", "below continuous_current"), (f"{C}.peak_current",),
              motor=MOTOR_WINDING),
    bad_drive("bus-voltage-huge", {f"{M}.dc_bus_voltage": "20 kV"},
              (f"{M}.dc_bus_voltage", "[1, 1e4] V"), (f"{C}.dc_bus_voltage",),
              motor=MOTOR_WINDING),
    bad_drive("bus-and-supply-voltage", {f"{M}.supply_voltage": "230 V"},
              (f"{M}.supply_voltage", "not both"), (f"{C}.supply_voltage",),
              motor=MOTOR_WINDING),
    bad_drive("commutation-unknown", {f"{M}.commutation": "trapezoidal"},
              (f"{M}.commutation", "'sinusoidal'", "'block'"), (f"{C}.commutation",),
              motor=MOTOR_WINDING),
]

def graded() -> dict[str, Any]:
    """A file's provenance (issue 35): its sources with grades and the default one (a
    fresh copy: the cases edit it)."""
    return {"sources": {"ds": {"grade": "A", "text": "Acme, datasheet M1, p. 3"},
                        "calc": {"grade": "C", "text": "computed from the datasheet"}},
            "default_source": "ds"}

PROVENANCE_CASES = [
    bad_drive("source-grade-unknown", {**graded(), "sources.ds.grade": "E"},
              ("sources.ds.grade", "'A'", "'D'"), ("catalog:sources",)),
    bad_drive("default-source-unknown", {**graded(), "default_source": "dss"},
              ("default_source", "'dss'", "ds"), ("catalog:default_source",)),
    bad_drive("motor-figure-source-unknown",
              {**graded(), f"{M}.figure_sources": {"torque_constant": "calcx"}},
              (f"{M}.figure_sources.torque_constant", "unknown source 'calcx'"),
              ("catalog:motors.figure_sources",)),
    bad_drive("drive-figure-source-not-a-figure",
              {**graded(), f"{D}.figure_sources": {"torque": "calc"}},
              (f"{D}.figure_sources", "torque"), ("catalog:drives.figure_sources",)),
    bad_gears("gears-source-grade-unknown", {**graded(), "sources.ds.grade": 1},
              ("sources.ds.grade",), ("gearboxes:sources",)),
    bad_gears("gears-default-source-unknown", {**graded(), "default_source": "x"},
              ("default_source", "'x'"), ("gearboxes:default_source",)),
    bad_gears("gears-series-figure-source-unknown",
              {**graded(), "gearboxes[0].figure_sources": {"backlash": "dsx"}},
              ("gearboxes[0].figure_sources.backlash", "unknown source 'dsx'"),
              ("gearboxes:gearboxes.figure_sources",)),
    bad_gears("gears-ratio-figure-source-not-a-figure",
              {**graded(), "gearboxes[0].ratios[0].figure_sources": {"stiffness": "ds"}},
              ("gearboxes[0].ratios[0].figure_sources", "stiffness"),
              ("gearboxes:gearboxes.ratios.figure_sources",)),
]

CASES = [*FIELDS, *IMPOSSIBLE, *GEARBOX_CASES, *DRIVE_CASES, *BRAKE_CASES, *ELECTRICAL_CASES,
         *PROVENANCE_CASES]


@pytest.mark.parametrize("case", CASES, ids=str)
def test_bad_input(case, tmp_path):
    run_case(case, tmp_path)


def test_the_base_files_are_good(tmp_path):
    (tmp_path / "motors.yaml").write_text(motors(), encoding="utf-8")
    result = run_cli("catalog", "validate", str(tmp_path / "motors.yaml"))
    assert result.returncode == 0, result.stdout + result.stderr


def test_the_base_drive_catalog_is_good(tmp_path):
    (tmp_path / "motors.yaml").write_text(with_drives(), encoding="utf-8")
    (tmp_path / "design.yaml").write_text(DESIGN, encoding="utf-8")
    result = run_cli("size", str(tmp_path / "design.yaml"), "--format", "csv", "--all")
    assert result.returncode in (0, 1), result.stdout + result.stderr
    assert result.stdout.splitlines()[0].startswith("rank,motor,drive,law")
    assert ",M1,D1," in result.stdout


def _error_field(stderr: str) -> str:
    line = next(line for line in stderr.splitlines() if line.startswith("error:"))
    return line.split(": ")[2]


@pytest.mark.parametrize("case", IMPOSSIBLE, ids=str)
def test_validate_reports_what_loading_refuses(case, tmp_path):
    loaded = run_case(case, tmp_path)
    field = _error_field(loaded.stderr)
    result = run_cli("catalog", "validate", str(tmp_path / "motors.yaml"))
    assert result.returncode == 1, result.stdout + result.stderr
    errors = [line for line in result.stdout.splitlines() if "(warning)" not in line]
    assert any(f": {field}: " in line for line in errors), (field, result.stdout)


def test_validate_lists_every_impossibility_where_loading_stops_at_the_first(tmp_path):
    text = motors({f"{M}.peak_torque": "1 N*m", f"{M}.max_speed": "2000 rpm",
                   f"{M}.continuous_curve[2]": ["3000 rpm", "0.8 N*m"]})
    (tmp_path / "motors.yaml").write_text(text, encoding="utf-8")
    (tmp_path / "design.yaml").write_text(DESIGN, encoding="utf-8")
    loaded = run_cli("size", str(tmp_path / "design.yaml"))
    assert loaded.returncode == 2
    assert "motor 'M1': peak torque 1 N*m is below" in loaded.stderr
    assert "(and 4 more problems of this motor)" in loaded.stderr
    result = run_cli("catalog", "validate", str(tmp_path / "motors.yaml"))
    fields = {line.split(": ")[1] for line in result.stdout.splitlines()
              if line.startswith(str(tmp_path)) or "motors.yaml:" in line}
    assert {f"{M}.peak_torque", f"{M}.max_speed", f"{M}.continuous_curve[2]",
            f"{M}.continuous_curve[1]",
            f"{M}.intermittent_curve[1]"} <= fields, result.stdout
