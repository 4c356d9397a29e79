"""Quantities written the way people type them: a number glued to its unit ('0.5s',
'3000rpm', '90deg', '1.2kg*cm^2', '10%', '1e-3s', '2e3rpm') is read everywhere a quantity
is (design files, catalogs, command-line options), and the JSON Schema's pattern and the
loader give the same verdict on every form.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import pytest
import yaml
from cli_run import assert_user_error, run_cli
from jsonschema import Draft202012Validator

from sizer.errors import UserError
from sizer.io.loader import design_schema, load_design
from sizer.units import column_to_si, to_si

ROOT = Path(__file__).resolve().parents[1]

GLUED = [  # text, kind, SI value by hand
    ("0.5s", "time", 0.5),
    ("250ms", "time", 0.25),
    ("1e-3s", "time", 1e-3),
    ("3000rpm", "angular_speed", 3000 * 2 * math.pi / 60),
    ("2e3rpm", "angular_speed", 2000 * 2 * math.pi / 60),
    ("90deg", "angle", math.pi / 2),
    ("1.2kg*cm^2", "inertia", 1.2e-4),
    ("10%", "fraction", 0.1),
    (".5Nm", "torque", 0.5),
    ("-20mm", "length", -0.02),
    ("1e5", "time", 1e5),  # an exponent, not a unit 'e5'
    ("1E+2s", "time", 100.0),
]


@pytest.mark.parametrize("text,kind,value", GLUED)
def test_a_number_glued_to_its_unit_is_read(text: str, kind: str, value: float) -> None:
    assert to_si(text, kind) == pytest.approx(value, rel=1e-12)
    assert column_to_si([text, text], kind) == pytest.approx([value, value], rel=1e-12)


def test_the_command_line_reads_a_glued_duration() -> None:
    result = run_cli("law", "cycloidal", "--displacement", "90deg", "--duration", "0.5s")
    assert result.returncode == 0, result.stderr
    spaced = run_cli("law", "cycloidal", "--displacement", "90 deg", "--duration", "0.5 s")
    assert result.stdout == spaced.stdout


def test_a_design_and_a_catalog_read_glued_units(tmp_path: Path) -> None:
    catalog = tmp_path / "motors.yaml"
    design = yaml.safe_load((ROOT / "examples/indexing-table.yaml").read_text())
    source = yaml.safe_load((ROOT / "examples/catalogs/example-servo.yaml").read_text())
    motor = source["motors"][0]
    glued = {**motor, "inertia": "0.0783e-4kg*m^2", "continuous_torque": "0.32Nm",
             "rated_speed": "3000rpm", "max_speed": "5000rev/min"}
    catalog.write_text(yaml.safe_dump({**source, "motors": [glued]}))
    design["motors"] = str(catalog)
    design.pop("check")
    design["task"] = {"displacement": "90deg", "duration": "0.25s", "dwell": "0.35s"}
    design["load"]["inertia"] = "0.034kg*m^2"
    design["limits"]["torque_margin"] = "10%"
    path = tmp_path / "design.yaml"
    path.write_text(yaml.safe_dump(design))
    loaded = load_design(path)
    assert loaded.task.displacement == pytest.approx(math.pi / 2)
    assert loaded.task.duration == pytest.approx(0.25)
    assert loaded.task.dwell == pytest.approx(0.35)
    assert loaded.load.inertia == pytest.approx(0.034)
    (read,) = loaded.motors
    assert read.inertia == pytest.approx(0.0783e-4)
    assert read.continuous_torque == pytest.approx(0.32)
    assert read.rated_speed == pytest.approx(3000 * 2 * math.pi / 60)
    assert read.max_speed == pytest.approx(5000 * 2 * math.pi / 60)


ACCEPTED = ["0.35 s", "0.35s", " 0.35 s ", "350ms", "350 ms", "3.5e-1s", "3.5E-1 s", ".35s",
            "+0.35s", "0.35", "35e-2", "0.35 (s)", "0.35\ts", "0.35 s\n"]
REFUSED = ["s", "", " ", "0.3.5 s", "0.35 , s", "0.35 +s", "0.35 *s", "0.35 /s", "0.35 1 s",
           "nan s", "inf", ".inf s", "-inf", "e5 s", "0.35 s" + " " * 100,
           "1,5 s", "--0.35 s", "0.35 s\nfoo"]


def _schema_accepts(validator: Draft202012Validator, design: dict[str, Any],
                    text: str) -> bool:
    trial = {**design, "task": {**design["task"], "dwell": text}}
    return validator.is_valid(trial)


def _loader_accepts(tmp_path: Path, design: dict[str, Any], text: str) -> bool:
    trial = {**design, "task": {**design["task"], "dwell": text}}
    path = tmp_path / "trial.yaml"
    path.write_text(yaml.safe_dump(trial))
    try:
        load_design(path)
    except UserError as error:
        assert error.field == "task.dwell", error
        assert error.file is not None and error.line is not None
        return False
    return True


def test_schema_pattern_and_loader_agree(tmp_path: Path) -> None:
    design = yaml.safe_load((ROOT / "examples/indexing-table.yaml").read_text())
    design["motors"] = str(ROOT / "examples/catalogs/example-servo.yaml")
    validator = Draft202012Validator(design_schema())
    assert _schema_accepts(validator, design, "0.35 s")
    for text in ACCEPTED + REFUSED:
        expected = text in ACCEPTED
        assert _schema_accepts(validator, design, text) is expected, text
        assert _loader_accepts(tmp_path, design, text) is expected, text


def test_the_schema_states_the_pattern() -> None:
    text = yaml.safe_dump(design_schema())
    assert "pattern" in text and "maxLength" in text


@pytest.mark.parametrize("text", ["0.5.5s", "0.5 , s", "infs"])
def test_the_command_line_refuses_a_malformed_duration(text: str) -> None:
    result = run_cli("law", "cycloidal", "--displacement", "1", "--duration", text)
    assert_user_error(result, "--duration", repr(text))
