"""The sanity rules of catalog motors: one registry, run by the loader and the validator.

The loader reads a common catalog as columns (sizer.io.catalog_table) and runs each
impossible rule only on the motors its screen (a numpy test of the columns) selects; the
screens must select every motor the rule refuses. Here the screens are compared with the
rules motor by motor on random catalogs, and the columnar reading with the field-by-field
validation on catalogs in the less common forms.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import sizer.catalog_tools
from sizer.catalog_tools import csv_import, validate
from sizer.errors import UserError
from sizer.io import loader, motor_rules, read_catalog
from sizer.io.catalog_table import read_table
from sizer.io.motor_rules import RULES, check_motor, impossibilities, maybe_impossible

RPM = math.pi / 30


def test_the_rules_are_one_registry_used_by_loader_validator_and_import() -> None:
    names = [rule.name for rule in RULES]
    assert len(set(names)) == len(names)
    assert {rule.kind for rule in RULES} == {"impossible", "catalog", "warning"}
    for rule in RULES:
        assert rule.checks and rule.severity == ("warning" if rule.kind == "warning"
                                                 else "error")
        assert (rule.screen is not None) or rule.kind != "impossible", rule.name
    assert sizer.catalog_tools.check_motor is check_motor
    assert validate.check_motor is check_motor and csv_import.check_motor is check_motor
    assert loader.impossibilities is impossibilities


def _random_motor(rng: np.random.Generator, index: int) -> dict[str, Any]:
    """A motor in SI, often broken: torques and speeds swapped, curves out of order,
    beyond max_speed, crossing, too short, figures outside the bands."""
    tau_c = float(10 ** rng.uniform(-2, 2))
    tau_p = tau_c * float(rng.choice([0.5, 0.999999, 1.0, 3.0, 40.0]))
    rated = float(rng.choice([30, 1000, 3000, 20000])) * RPM
    motor: dict[str, Any] = {
        "id": f"M{index}", "continuous_torque": tau_c, "peak_torque": tau_p,
        "rated_speed": rated,
        "inertia": float(rng.choice([0.0, 1e-6, 1e-4, 1.0])) * tau_c,
    }
    if rng.random() < 0.8:
        motor["max_speed"] = rated * float(rng.choice([0.5, 1.0, 1.5, 10.0]))
    for key, rating in (("continuous_curve", tau_c), ("intermittent_curve", tau_p)):
        if rng.random() < 0.5:
            continue
        size = int(rng.integers(0, 5))
        top = motor.get("max_speed", rated) * float(rng.choice([0.9, 1.0, 1.2]))
        speeds = np.sort(rng.uniform(0, top, size))
        if size and rng.random() < 0.3:
            speeds[-1] = speeds[0]  # not increasing
        torques = rating * rng.uniform(0.2, 1.5, size)
        motor[key] = [[float(s), float(t)] for s, t in zip(speeds, torques, strict=True)]
    return motor


@pytest.mark.parametrize("seed", range(8))
def test_the_screens_select_every_motor_a_rule_concerns(seed: int) -> None:
    rng = np.random.default_rng(seed)
    rows = [_random_motor(rng, i) for i in range(300)]
    table = read_table({"source": "s", "motors": rows})
    assert table is not None
    impossible = maybe_impossible(table.columns)
    implausible = motor_rules.maybe_implausible(table.columns)
    hits = {"impossible": 0, "implausible": 0}
    for index, motor in enumerate(table.motors):
        problems = check_motor(motor)
        if impossibilities(motor):
            assert impossible[index], (motor, impossibilities(motor))
            hits["impossible"] += 1
        if any(p.message.startswith("implausible:") for p in problems):
            assert implausible[index], motor
            hits["implausible"] += 1
        for rule in RULES:  # the scalar rules' screens are the rules themselves
            if rule.kind == "impossible" and "_curve" not in rule.name and \
                    rule.name != "regions_nested":
                assert bool(rule.screen(table.columns)[index]) == bool(
                    rule.problems(motor, motor_rules.Context())), (rule.name, motor)
    assert hits["impossible"] > 30 and hits["implausible"] > 30  # the test sees both


def _yaml_motor(lines: list[str]) -> str:
    return "".join(f"    {line}\n" if i else f"  - {line}\n" for i, line in enumerate(lines))


COMMON = ["id: A1", "inertia: 0.3 kg*cm^2", "continuous_torque: 1.1 N*m",
          "peak_torque: 3.3 N*m", "rated_speed: 3000 rpm", "max_speed: 4500 rpm"]

LESS_COMMON = [
    COMMON,
    ["id: 1234", "inertia: 3e-5", "continuous_torque: 1.1", "peak_torque: 3.3",
     "rated_speed: 314.159", "max_speed: null", "price: 450", "mass: null",
     "part_number: 5.5", "notes: null", "source: null", "manufacturer: 12"],
    ["id: '  B2  '", "inertia: 0 kg*m^2", "continuous_torque: 1.1 N*m",
     "peak_torque: 3.3 N*m", "rated_speed: 3000 rpm", "damping: -0.0 N*m*s/rad",
     "continuous_curve: [{speed: 0 rpm, torque: 1.1 N*m}, {torque: 0.5 N*m, speed: 3000 rpm}]",
     "intermittent_curve: null"],
    ["id: 7.5", "inertia: 2 g*cm^2", "continuous_torque: 110 mN*m",
     "peak_torque: 0.33 N*m", "rated_speed: 50 Hz", "max_speed: 4500 min^-1",
     "intermittent_curve: [[0, 0.33], [314, 0.33], [471, -0.0]]"],
    ["id: C3", "inertia: 3", "continuous_torque: 0.3 N*m", "peak_torque: 1 N*m",
     "rated_speed: 3000", "max_speed: 6000"],  # bare numbers that warn
]


def _text(motors: list[list[str]], head: str = "catalog: t\nsource: s\n") -> str:
    return head + "motors:\n" + "".join(_yaml_motor(m) for m in motors)


def _both(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, text: str) -> tuple[str, str]:
    path = tmp_path / "c.yaml"
    path.write_text(text, encoding="utf-8")

    def load() -> str:
        try:
            return repr(read_catalog(path))
        except UserError as error:
            return f"error: {error}"

    columns = load()
    with monkeypatch.context() as patch:
        patch.setattr(loader, "read_table", lambda data: None)
        fields = load()
    return columns, fields


@pytest.mark.parametrize("index", range(len(LESS_COMMON)))
def test_less_common_forms_read_as_columns_as_field_by_field(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch, index: int) -> None:
    import yaml

    text = _text([LESS_COMMON[index]], head="catalog: 5\nmanufacturer: 1.5\nsource: s\n")
    assert read_table(yaml.safe_load(text)) is not None  # the columns, not the fallback
    columns, fields = _both(tmp_path, monkeypatch, text)
    assert columns == fields and not columns.startswith("error")


IMPOSSIBLE = [
    ["peak_torque: 0.5 N*m"],
    ["max_speed: 2000 rpm"],
    ["continuous_curve: [[0 rpm, 1.1 N*m]]"],
    ["continuous_curve: []"],
    ["continuous_curve: [[0 rpm, 1.1 N*m], [3000 rpm, 1 N*m], [2000 rpm, 0.5 N*m]]"],
    ["intermittent_curve: [[0 rpm, 3.3 N*m], [5000 rpm, 2 N*m]]"],
    ["intermittent_curve: [[0 rpm, 3.3 N*m], [3000 rpm, 0.5 N*m]]"],
    ["continuous_curve: [[0 rpm, 1.1 N*m], [3000 rpm, 4 N*m]]", "peak_torque: 0.5 N*m"],
]


@pytest.mark.parametrize("change", IMPOSSIBLE, ids=[" ".join(c) for c in IMPOSSIBLE])
def test_the_first_impossible_motor_is_refused_as_field_by_field(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch, change: list[str]) -> None:
    keys = {line.split(":")[0] for line in change}
    broken = ["id: X2", *(line for line in COMMON[1:] if line.split(":")[0] not in keys),
              *change]
    motors = [["id: X1", *COMMON[1:]], broken, ["id: X3", *broken[1:]]]
    columns, fields = _both(tmp_path, monkeypatch, _text(motors))
    assert columns == fields
    assert columns.startswith("error: ") and "c.yaml:" in columns and "motor 'X2'" in columns
