"""A catalog's quantities are converted column by column, with the same floats and errors.

``sizer.io.loader`` reads a catalog in the common form as columns
(``sizer.io.catalog_table``: one unit conversion per distinct unit of a column,
``sizer.units.column_to_si``, the ranges checked as arrays, no model per motor); any
other catalog, and every catalog with a mistake, is validated field by field, which words
the problem. Here the loaded motors and the error messages are compared with the
field-by-field validation (the columns switched off), and ``column_to_si`` with ``to_si``
value by value.
"""

from __future__ import annotations

import math
import struct
from pathlib import Path

import pytest

from sizer import units
from sizer.errors import UserError
from sizer.io import loader, read_catalog, read_yaml
from sizer.io.catalog_table import read_table

ROOT = Path(__file__).resolve().parents[1]

TEXTS = [
    "3000 rpm", "3000  rpm", "3000 rpm ", " 3000 rpm", "3000rpm", "1.2e-4 kg*m^2",
    "1.2E-4 kg*m^2", "1.e3 rpm", ".5 rpm", "-.5 rpm", "+5 rpm", "1.2.3 rpm", "1- rpm",
    "1e rpm", "e5 rpm", "inf rpm", ".inf rpm", "nan rpm", "1e400 rpm", "3000 min^-1",
    "50 Hz", "3000 r/min", "3000 RPM", "12 N*m", "12 Nm", "12 mN*m", "0.3 kg*cm^2",
    "92.5 g*cm^2", "0.3 kg·cm²", "3 kg", "3 furlongs", "10 %", "10", "1e-3", "", " ",
    "rpm", "3000 rpm\nx", "3000 rpm\xa0", "1_000 rpm", "0x10 rpm", 3000, 3000.0, -0.0, 0,
    10**400, float("inf"), float("nan"), True, None, [1, 2], "9" * 120 + " rpm",
]
KINDS = ["angular_speed", "torque", "inertia", "mass", "fraction", "ratio", "angle"]


def _same(a: float, b: float) -> bool:
    return struct.pack("<d", a) == struct.pack("<d", b)


@pytest.mark.parametrize("kind", KINDS)
def test_column_to_si_equals_to_si_value_by_value(kind: str) -> None:
    for _ in range(2):  # units found, then remembered
        column = units.column_to_si(TEXTS, kind)
        assert len(column) == len(TEXTS)
        for value, got in zip(TEXTS, column, strict=True):
            try:
                expected = units.to_si(value, kind)
            except (UserError, TypeError):
                expected = None
            if got is None:
                assert expected is None, (value, kind, expected)
            else:
                assert expected is not None and _same(got, expected), (value, kind)
                assert math.isfinite(got)


def _field_by_field(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(loader, "read_table", lambda data: None)


def _load(path: Path) -> object:
    try:
        return read_catalog(path)
    except UserError as error:
        return str(error)


def test_bundled_catalogs_load_as_field_by_field(monkeypatch: pytest.MonkeyPatch) -> None:
    paths = [*sorted(ROOT.glob("sizer/catalogs/*.yaml")),
             ROOT / "examples/catalogs/example-servo.yaml"]
    assert all(read_table(read_yaml(p).data) is not None for p in paths)  # read as columns
    columns = [repr(_load(p)) for p in paths]
    _field_by_field(monkeypatch)
    assert columns == [repr(_load(p)) for p in paths]
    assert all("motors=" in c for c in columns)


MOTOR = """\
  - id: M{i}
    inertia: {inertia}
    continuous_torque: {torque}
    peak_torque: 3 N*m
    rated_speed: {speed}
    max_speed: 4500 rpm
    mass: 1.2 kg
    continuous_curve: {curve}
"""

GOOD = dict(inertia="0.3 kg*cm^2", torque="1.1 N*m", speed="3000 rpm",
            curve="[[0 rpm, 1.1 N*m], [3000 rpm, 1.0 N*m], {speed: 4500 rpm, torque: 0.5 N*m}]")
BAD = [
    ("inertia", "3 furlongs"), ("inertia", "-1 kg*cm^2"), ("inertia", "1e9 kg*m^2"),
    ("torque", "1.1 kg"), ("torque", "nan N*m"), ("torque", "1.2.3 N*m"), ("torque", "[1]"),
    ("speed", "3000 rpm rpm"), ("speed", "0 rpm"), ("speed", "'3000'"), ("speed", "true"),
    ("curve", "[[0 rpm, 1.1 N*m], [3000 rpm]]"), ("curve", "[[0 rpm, 1.1 N*m], 5]"),
    ("curve", "[[0 rpm, 1.1 N*m], {speed: 1e9 rpm, torque: 1 N*m}]"),
    ("curve", "[[0 rpm, 1.1 kg], [3000 rpm, 1 N*m]]"), ("curve", "x"),
]


def _catalog(tmp_path: Path, name: str, motors: list[dict[str, str]]) -> Path:
    text = "catalog: test\nsource: a test\nmotors:\n" + "".join(
        MOTOR.format(i=i, **m) for i, m in enumerate(motors))
    path = tmp_path / f"{name}.yaml"
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.parametrize("field,value", BAD, ids=[f"{f}={v}" for f, v in BAD])
def test_a_bad_value_reads_as_field_by_field(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                             field: str, value: str) -> None:
    motors = [GOOD, {**GOOD, field: value}, GOOD, {**GOOD, field: value}]
    path = _catalog(tmp_path, "bad", motors)
    columns = _load(path)
    _field_by_field(monkeypatch)
    assert columns == _load(path)
    assert isinstance(columns, str) and "bad.yaml:" in columns  # located: file and line


def test_mixed_units_in_a_column_load_as_field_by_field(tmp_path: Path,
                                                        monkeypatch: pytest.MonkeyPatch) -> None:
    motors = [{**GOOD, "inertia": inertia, "torque": torque, "speed": speed}
              for inertia in ("0.3 kg*cm^2", "3e-5 kg*m^2", "300 g*cm^2", "3e-5", "0.3 kgcm^2")
              for torque in ("1.1 N*m", "1100 mN*m", "1.1 Nm", "156 oz*in", "1.1")
              for speed in ("3000 rpm", "3000 min^-1", "314.159 rad/s", "50 Hz")]
    path = _catalog(tmp_path, "mixed", motors)
    columns = _load(path)
    _field_by_field(monkeypatch)
    assert repr(columns) == repr(_load(path))
    assert not isinstance(columns, str) and len(columns.motors) == len(motors)  # type: ignore[attr-defined]
