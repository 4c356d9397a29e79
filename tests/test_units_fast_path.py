"""Units are converted once per unit, without pint for the common ones, bit for bit as pint.

``sizer.units`` converts a text like '3000 rpm' as ``number * factor`` with the factor of
its unit taken from a small table (the units written most often) or from pint once per
unit and remembered; before, pint converted every value. Pint itself multiplies the
magnitude by one factor of the units, so the results must be identical floats: checked
here against pint directly, for the table and for every unit text in the bundled
catalogs, the examples and the docs.
"""

from __future__ import annotations

import math
import struct
from pathlib import Path
from typing import Any

import pytest
import yaml

from sizer import units
from sizer.errors import UserError

ROOT = Path(__file__).resolve().parents[1]


def _bits(x: float) -> bytes:
    return struct.pack("<d", x)


def _pint_factor(unit: str, kind: str) -> tuple[float, float]:
    """pint's SI factor of ``unit`` (root units for angular motion) and its radian power."""
    ureg = units.registry()
    quantity = ureg.Quantity(1.0, unit)
    if kind in ("angular_speed", "angular_acceleration", "angular_jerk"):
        root = quantity.to_root_units()
        return float(root.magnitude), dict(root.unit_items()).get("radian", 0)
    expected = units.KINDS[kind].dimensionality
    assert quantity.dimensionality == (ureg.get_dimensionality(expected) if expected else {})
    return float(quantity.to_base_units().magnitude), 1


@pytest.mark.parametrize("kind,unit", sorted(units._FAST))
def test_table_factors_are_pints_bit_for_bit(kind: str, unit: str) -> None:
    factor, radian_power = _pint_factor(unit, kind)
    assert radian_power == 1  # the table holds no revolution counts
    assert _bits(units._FAST[(kind, unit)].factor) == _bits(factor)


def _unit_texts() -> set[str]:
    """Every 'number unit' text of the bundled catalogs, the examples and the docs."""
    found: set[str] = set()

    def walk(value: Any) -> None:
        if isinstance(value, dict):
            for item in value.values():
                walk(item)
        elif isinstance(value, list):
            for item in value:
                walk(item)
        elif isinstance(value, str) and len(value) <= 100:
            number, unit = units._split(value.replace("%", " percent"))
            if number and unit:
                found.add(value)

    for path in sorted([*ROOT.glob("sizer/catalogs/*.yaml"), *ROOT.glob("examples/**/*.yaml"),
                        *ROOT.glob("docs/**/*.yaml")]):
        for document in yaml.safe_load_all(path.read_text(encoding="utf-8")):
            walk(document)
    return found


TEXTS = sorted(_unit_texts())


def test_the_files_hold_many_unit_texts() -> None:
    assert len(TEXTS) > 200
    assert {"3000 rpm", "0.3 kg*cm^2"} <= set(TEXTS)


def _outcome(convert, text: str, kind: str) -> float | str:
    """The float a conversion gives, or its refusal's message."""
    try:
        return convert(text, kind, field="f")
    except UserError as error:
        return str(error)


def _same(got: float | str, expected: float | str, text: str, kind: str) -> None:
    if isinstance(expected, float):
        assert isinstance(got, float) and _bits(got) == _bits(expected), (text, kind)
    else:
        assert got == expected, (text, kind)


def test_every_unit_text_of_the_files_converts_as_pint_does() -> None:
    """Each text, in each kind pint accepts it as, gives pint's float; each text pint
    refuses is refused, with the same message.

    Whether a kind accepts a text is a property of its unit (sizer.units remembers a
    unit's recipe per kind; pint checks the unit's dimensionality): every kind is tried
    with the first text of each of the files' units (36 units, 29 kinds), and every text
    in the kinds its unit converts in (bit for bit, twice: the first conversion finds the
    unit, the second reuses it) and in one kind that refuses it (the message)."""
    first: dict[str, str] = {}
    for text in TEXTS:
        first.setdefault(units._split(text)[1], text)
    accepts: dict[str, list[str]] = {}
    refuses: dict[str, list[str]] = {}
    converted = dict.fromkeys(units.KINDS, 0)
    for unit, text in first.items():
        for kind in units.KINDS:
            expected = _outcome(units.to_si_with_pint, text, kind)
            for _ in range(2):
                _same(_outcome(units.to_si, text, kind), expected, text, kind)
            (accepts if isinstance(expected, float) else refuses).setdefault(unit, []).append(
                kind)
    for text in TEXTS:
        unit = units._split(text)[1]
        kinds = [*accepts.get(unit, []), *refuses.get(unit, [])[:1]]
        for kind in kinds:
            expected = _outcome(units.to_si_with_pint, text, kind)
            for _ in range(2):
                _same(_outcome(units.to_si, text, kind), expected, text, kind)
            converted[kind] += isinstance(expected, float)
    for kind in ("time", "angle", "length", "angular_speed", "torque", "inertia", "mass",
                 "rotary_damping", "fraction"):
        assert converted[kind] > 0, kind


@pytest.mark.parametrize("text,kind", [
    ("3000 min^-1", "angular_speed"), ("50 Hz", "angular_speed"),
    ("2 Hz/s", "angular_acceleration"),
    ("12.5 oz*in", "torque"), ("3 lbf*ft", "torque"), ("7 Nm", "torque"), ("1.5 kgf*cm", "torque"),
    ("0.04 kgf*m^2 GD^2", "inertia"), ("2.5 lb*in^2", "inertia"), ("0.01 oz*in*s^2", "inertia"),
    ("0.3 kg·cm²", "inertia"), ("90 degree", "angle"), ("0.1 inch", "length"),
    ("5 N*m/rpm", "rotary_damping"), ("1 r/min", "angular_speed"), ("3 U/min", "angular_speed"),
])
def test_units_from_pint_are_remembered_and_equal(text: str, kind: str) -> None:
    number, unit = units._split(text)
    for shown in (number, "7", "0.001", "-3.3e5"):  # other numbers reuse the recipe
        value = f"{shown} {unit}"
        expected = units.to_si_with_pint(value, kind)
        assert _bits(units.to_si(value, kind)) == _bits(expected), value
        assert math.isfinite(expected)


def test_a_number_in_a_unit_of_the_table_never_builds_pint(monkeypatch) -> None:
    def no_pint() -> None:
        raise AssertionError("pint was asked for")

    monkeypatch.setattr(units, "registry", no_pint)
    assert units.to_si("3000 rpm", "angular_speed") == 3000 * 0.10471975511965977
    assert units.to_si("1.2 kg*cm^2", "inertia") == 1.2 * 0.0001
    assert units.to_si("0.5 N*m", "torque") == 0.5
    assert units.to_si("90 deg", "angle") == 90 * 0.017453292519943295
    assert units.to_si("10 %", "fraction") == 0.1
    assert units.to_si(2.5, "time") == 2.5


def test_wrong_units_still_fail_every_time() -> None:
    for _ in range(2):
        with pytest.raises(UserError, match="expected a torque"):
            units.to_si("3 kg", "torque")
        with pytest.raises(UserError, match="unknown unit"):
            units.to_si("3 furlongz", "torque")
