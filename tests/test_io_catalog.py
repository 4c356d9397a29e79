"""Motor catalogs: units to SI, checks with file, line and field, bundled catalogs."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from sizer.errors import UserError
from sizer.io import bundled_catalogs, catalog_schema, load_catalog

CATALOG = """\
catalog: Example servo motors
manufacturer: Example Corp
source: "Example datasheet, https://example.com/ds.pdf"
motors:
  - id: EX-100
    inertia: 1.2 kg*cm^2
    continuous_torque: 0.32 N*m
    peak_torque: 0.95 N*m
    rated_speed: 3000 rpm
    max_speed: 6000 rpm
    damping: 1e-5 N*m*s/rad
    continuous_curve: [[0 rpm, 0.32 N*m], [3000 rpm, 0.30 N*m], [6000 rpm, 0.2 N*m]]
    intermittent_curve:
      - {speed: 0 rpm, torque: 0.95 N*m}
      - {speed: 4000 rpm, torque: 0.95 N*m}
      - [6000 rpm, 0.5 N*m]
    part_number: EX-100-A1
    price: 450
    mass: 0.3 kg
  - id: EX-200
    inertia: 0.0002
    continuous_torque: 0.64
    peak_torque: 1.9
    rated_speed: 314.159
    manufacturer: Other Corp
    source: other datasheet
"""


def write(tmp_path: Path, text: str, name: str = "catalog.yaml") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


def line_of(text: str, needle: str) -> int:
    """1-based line of the last line containing ``needle`` (the whole line if it ends in $)."""
    if needle.endswith("$"):
        hits = [i for i, line in enumerate(text.splitlines(), 1)
                if line.strip() == needle[:-1].strip()]
    else:
        hits = [i for i, line in enumerate(text.splitlines(), 1) if needle in line]
    return hits[-1]


def error_of(path: Path | str) -> UserError:
    with pytest.raises(UserError) as info:
        load_catalog(path)
    return info.value


# ------------------------------------------------------------------ valid


def test_catalog_loads_in_si(tmp_path):
    first, second = load_catalog(write(tmp_path, CATALOG))
    assert first.id == "EX-100"
    assert first.inertia == pytest.approx(1.2e-4)
    assert first.continuous_torque == pytest.approx(0.32)
    assert first.peak_torque == pytest.approx(0.95)
    assert first.rated_speed == pytest.approx(100 * math.pi)
    assert first.max_speed == pytest.approx(200 * math.pi)
    assert first.damping == pytest.approx(1e-5)
    assert first.continuous_curve is not None and first.intermittent_curve is not None
    assert [v for p in first.continuous_curve for v in p] == pytest.approx(
        [0.0, 0.32, 100 * math.pi, 0.30, 200 * math.pi, 0.2])
    assert [v for p in first.intermittent_curve for v in p] == pytest.approx(
        [0.0, 0.95, 400 * math.pi / 3, 0.95, 200 * math.pi, 0.5])
    assert first.part_number == "EX-100-A1"
    assert first.price == 450
    assert first.mass == pytest.approx(0.3)
    # catalog-level defaults apply where a motor gives none
    assert first.manufacturer == "Example Corp"
    assert first.source == "Example datasheet, https://example.com/ds.pdf"
    assert second.manufacturer == "Other Corp"
    assert second.source == "other datasheet"
    assert second.inertia == pytest.approx(2e-4)
    assert second.max_speed is None
    assert second.continuous_curve is None


def test_numeric_id_and_part_number_are_text(tmp_path):
    text = CATALOG.replace("id: EX-100", "id: 100").replace("part_number: EX-100-A1",
                                                            "part_number: 12345")
    motor = load_catalog(write(tmp_path, text))[0]
    assert motor.id == "100"
    assert motor.part_number == "12345"


def test_zero_rotor_inertia_is_allowed(tmp_path):
    text = CATALOG.replace("inertia: 1.2 kg*cm^2", "inertia: 0")
    assert load_catalog(write(tmp_path, text))[0].inertia == 0.0


def test_bundled_book_examples():
    catalogs = bundled_catalogs()
    assert "book-examples" in catalogs
    assert catalogs["book-examples"].is_file()
    motors = {m.id: m for m in load_catalog("book-examples")}
    assert set(motors) == {"ex6_1", "ex6_3", "ex6_4"}
    ex1, ex3, ex4 = motors["ex6_1"], motors["ex6_3"], motors["ex6_4"]
    assert (ex1.rated_speed, ex1.peak_torque, ex1.continuous_torque) == (10, 20, 8)
    assert (ex3.rated_speed, ex3.peak_torque, ex3.continuous_torque) == (6, 30, 14)
    assert (ex4.rated_speed, ex4.continuous_torque) == (2, 4)
    assert ex4.peak_torque > 6  # the book implies it is not binding in Examples 6.4-6.5
    for motor in motors.values():
        assert motor.inertia == 0.0
        assert "Biagiotti" in (motor.source or "")


def test_bundled_catalog_by_path_through_top_level_symlink():
    root = Path(__file__).resolve().parent.parent
    assert load_catalog(root / "catalogs" / "book-examples.yaml") == \
        load_catalog("book-examples")


def test_schema_lists_motor_fields():
    schema = catalog_schema()
    motor = schema["$defs"]["MotorInput"]
    assert {"id", "inertia", "continuous_torque", "peak_torque", "rated_speed"} <= \
        set(motor["required"])
    assert motor["additionalProperties"] is False


# ------------------------------------------------------------------ errors

BAD_CASES = [
    # (replace old, with new, line needle, field, message part)
    ("    peak_torque: 0.95 N*m\n", "", "- id: EX-100", "motors[0].peak_torque",
     "required field is missing"),
    ("    mass: 0.3 kg\n", "    mass: 0.3 kg\n    colour: blue\n", "colour: blue",
     "motors[0].colour", "unknown field 'colour'"),
    ("    max_speed: 6000 rpm\n", "    max_sped: 6000 rpm\n", "max_sped",
     "motors[0].max_sped", "did you mean 'max_speed'"),
    ("rated_speed: 3000 rpm", "rated_speed: 3000 N*m", "rated_speed: 3000 N*m",
     "motors[0].rated_speed", "expected an angular speed"),
    ("inertia: 1.2 kg*cm^2", "inertia: 1.2 kg", "inertia: 1.2 kg",
     "motors[0].inertia", "expected an inertia"),
    ("inertia: 1.2 kg*cm^2", "inertia: -1.2 kg*cm^2", "inertia: -1.2",
     "motors[0].inertia", "must be 0 or in [1e-12, 1000] kg*m^2"),
    ("continuous_torque: 0.64", "continuous_torque: 0", "continuous_torque: 0$",
     "motors[1].continuous_torque", "must be in [1e-6, 1e6] N*m"),
    ("peak_torque: 0.95 N*m", "peak_torque: -1 N*m", "peak_torque: -1",
     "motors[0].peak_torque", "must be in [1e-6, 1e6] N*m"),
    ("rated_speed: 314.159", "rated_speed: 0 rpm", "rated_speed: 0 rpm",
     "motors[1].rated_speed", "must be in [0.001, 1e5] rad/s"),
    ("rated_speed: 3000 rpm", "rated_speed: .nan", "rated_speed: .nan",
     "motors[0].rated_speed", "not a finite number"),
    ("peak_torque: 0.95 N*m", "peak_torque: inf N*m", "peak_torque: inf",
     "motors[0].peak_torque", "not a finite number"),
    ("rated_speed: 3000 rpm", "rated_speed: fast", "rated_speed: fast",
     "motors[0].rated_speed", "expected an angular speed"),
    ("rated_speed: 3000 rpm", "rated_speed: [1, 2]", "rated_speed: [1, 2]",
     "motors[0].rated_speed", "expected an angular speed"),
    ("rated_speed: 3000 rpm", "rated_speed: 3000 blorps", "rated_speed: 3000 blorps",
     "motors[0].rated_speed", "unknown unit"),
    ("max_speed: 6000 rpm", "max_speed: 2000 rpm", "max_speed: 2000 rpm",
     "motors[0].max_speed", "below the rated speed"),
    ("peak_torque: 1.9", "peak_torque: 0.5", "peak_torque: 0.5",
     "motors[1].peak_torque", "below the continuous torque"),
    ("damping: 1e-5 N*m*s/rad", "damping: -1e-5 N*m*s/rad", "damping: -1e-5",
     "motors[0].damping", "must be 0 or in [1e-12, 1000] N*m*s/rad"),
    ("price: 450", "price: -3", "price: -3", "motors[0].price", "must be 0 or in [0.001, 1e9]"),
    ("mass: 0.3 kg", "mass: 0.3 N", "mass: 0.3 N", "motors[0].mass", "expected a mass"),
    ("      - {speed: 4000 rpm, torque: 0.95 N*m}\n",
     "      - {speed: 0 rpm, torque: 0.95 N*m}\n", "{speed: 0 rpm",
     "motors[0].intermittent_curve[1]", "strictly increasing"),
    ("      - [6000 rpm, 0.5 N*m]\n", "      - [4000 rpm, 0.5 N*m]\n", "[4000 rpm, 0.5",
     "motors[0].intermittent_curve[2]", "strictly increasing"),
    ("      - {speed: 4000 rpm, torque: 0.95 N*m}\n",
     "      - {speed: 4000 rpm, torque: -0.95 N*m}\n", "torque: -0.95",
     "motors[0].intermittent_curve[1].torque", "must be 0 or in [1e-6, 1e6] N*m"),
    ("      - [6000 rpm, 0.5 N*m]\n", "      - [6000 rpm, 0.5 N*m, 3]\n", "0.5 N*m, 3]",
     "motors[0].intermittent_curve[2]", "a curve point is [speed, torque]"),
    ("      - [6000 rpm, 0.5 N*m]\n", "      - [6000 rpm, 3000 rpm]\n", "[6000 rpm, 3000 rpm]",
     "motors[0].intermittent_curve[2].torque", "expected a torque"),
    ("      - {speed: 4000 rpm, torque: 0.95 N*m}\n",
     "      - {speed: 4000 rpm, torq: 0.95 N*m}\n", "torq: 0.95",
     "motors[0].intermittent_curve[1].torq", "unknown field 'torq'"),
    ("continuous_curve: [[0 rpm, 0.32 N*m], [3000 rpm, 0.30 N*m], [6000 rpm, 0.2 N*m]]",
     "continuous_curve: [[0 rpm, 0.32 N*m]]", "continuous_curve:",
     "motors[0].continuous_curve", "at least 2 points"),
    ("continuous_curve: [[0 rpm, 0.32 N*m], [3000 rpm, 0.30 N*m], [6000 rpm, 0.2 N*m]]",
     "continuous_curve: 0.32 N*m", "continuous_curve:",
     "motors[0].continuous_curve", "expected a list"),
    ("  - id: EX-200\n", "  - id: EX-100\n", "id: EX-100", "motors[1].id",
     "duplicate motor id 'EX-100'"),
    ("  - id: EX-200\n", "  - id: ''\n", "id: ''", "motors[1].id", "must not be empty"),
    ("  - id: EX-200\n", "  - id: [EX-200]\n", "id: [EX-200]", "motors[1].id",
     "expected text"),
    ("catalog: Example servo motors\n", "catalog: Example servo motors\nvendor: X\n",
     "vendor: X", "vendor", "unknown field 'vendor'"),
    ("rated_speed: 3000 rpm\n", "rated_speed: 3000 rpm\n    rated_speed: 2000 rpm\n",
     "rated_speed: 2000 rpm", "motors[0].rated_speed", "duplicate key 'rated_speed'"),
    ("    mass: 0.3 kg\n", "    mass: [0.3 kg\n", "- id: EX-200", None, "invalid YAML"),
]


@pytest.mark.parametrize(("old", "new", "needle", "field", "message"), BAD_CASES,
                         ids=[f"{i}-{c[4][:20]}" for i, c in enumerate(BAD_CASES)])
def test_bad_catalog(tmp_path, old, new, needle, field, message):
    assert old in CATALOG
    text = CATALOG.replace(old, new, 1)
    path = write(tmp_path, text)
    error = error_of(path)
    assert message in error.message
    assert error.file == str(path)
    assert error.field == field
    assert error.line == line_of(text, needle)
    assert str(error).startswith(f"{path}:{error.line}: ")


def test_first_of_several_problems_in_file_order(tmp_path):
    text = CATALOG.replace("rated_speed: 314.159", "rated_speed: -1").replace(
        "peak_torque: 0.95 N*m", "peak_torque: 0 N*m")
    error = error_of(write(tmp_path, text))
    assert error.line == line_of(text, "peak_torque: 0 N*m")
    assert error.field == "motors[0].peak_torque"
    assert "(and 1 more problem in this file)" in error.message


def test_empty_catalog(tmp_path):
    text = "catalog: nothing\nmotors: []\n"
    error = error_of(write(tmp_path, text))
    assert (error.line, error.field) == (2, "motors")
    assert "no motors" in error.message


def test_catalog_without_motors_key(tmp_path):
    error = error_of(write(tmp_path, "catalog: nothing\n"))
    assert (error.line, error.field) == (1, "motors")
    assert "required field is missing" in error.message


def test_catalog_motors_not_a_list(tmp_path):
    error = error_of(write(tmp_path, "catalog: x\nmotors:\n  id: A\n"))
    assert (error.line, error.field) == (2, "motors")
    assert "expected a list" in error.message


def test_motor_item_not_a_mapping(tmp_path):
    error = error_of(write(tmp_path, "motors:\n  - EX-100\n"))
    assert (error.line, error.field) == (2, "motors[0]")
    assert "expected a mapping" in error.message


def test_top_level_not_a_mapping(tmp_path):
    error = error_of(write(tmp_path, "- id: A\n"))
    assert error.line == 1
    assert "mapping" in error.message


def test_empty_file(tmp_path):
    error = error_of(write(tmp_path, ""))
    assert error.line == 1
    assert "empty" in error.message


def test_malformed_yaml_line(tmp_path):
    text = "motors:\n  - id: A\n    inertia: 1\n   bad: indent\n"
    error = error_of(write(tmp_path, text))
    assert error.message.startswith("invalid YAML")
    assert error.line == 4


def test_unknown_bundled_catalog_name():
    error = error_of("book-exampels")
    assert "unknown catalog 'book-exampels'" in error.message
    assert "did you mean 'book-examples'" in error.message


def test_missing_catalog_file(tmp_path):
    error = error_of(tmp_path / "nope.yaml")
    assert "catalog file not found" in error.message


def test_catalog_is_a_directory(tmp_path):
    (tmp_path / "dir.yaml").mkdir()
    error = error_of(tmp_path / "dir.yaml")
    assert "directory" in error.message


def test_not_utf8(tmp_path):
    path = tmp_path / "latin.yaml"
    path.write_bytes(b"motors:\n  - id: caf\xe9\n")
    error = error_of(path)
    assert error.line == 2
    assert "UTF-8" in error.message
