"""Quantities with units at the boundary, SI floats inside (pint).

``to_si("3000 rpm", "angular_speed") == 314.159...``. A bare number (or a string with no
unit) is already SI. Angles are dimensionless in pint, so an angle and a plain number
are told apart by the unit text, not the dimension.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from functools import cache
from typing import Any

from sizer.errors import UserError


@dataclass(frozen=True)
class Kind:
    """A physical kind of quantity: its pint dimensionality and an example for messages."""

    name: str
    dimensionality: str
    example: str
    si_unit: str


KINDS: dict[str, Kind] = {
    k.name: k
    for k in (
        Kind("time", "[time]", "0.2 s", "s"),
        Kind("angle", "", "90 deg", "rad"),
        Kind("length", "[length]", "200 mm", "m"),
        Kind("angular_speed", "1/[time]", "3000 rpm", "rad/s"),
        Kind("linear_speed", "[length]/[time]", "1.5 m/s", "m/s"),
        Kind("angular_acceleration", "1/[time]**2", "500 rad/s^2", "rad/s^2"),
        Kind("linear_acceleration", "[length]/[time]**2", "9.81 m/s^2", "m/s^2"),
        Kind("angular_jerk", "1/[time]**3", "1e5 rad/s^3", "rad/s^3"),
        Kind("linear_jerk", "[length]/[time]**3", "100 m/s^3", "m/s^3"),
        Kind("torque", "[mass]*[length]**2/[time]**2", "0.5 N*m", "N*m"),
        Kind("force", "[mass]*[length]/[time]**2", "100 N", "N"),
        Kind("inertia", "[mass]*[length]**2", "1.2 kg*cm^2", "kg*m^2"),
        Kind("mass", "[mass]", "12 kg", "kg"),
        Kind("rotary_damping", "[mass]*[length]**2/[time]", "0.01 N*m*s/rad", "N*m*s/rad"),
        Kind("linear_damping", "[mass]/[time]", "5 N*s/m", "N*s/m"),
        Kind("fraction", "", "10 %", "1"),
        Kind("ratio", "", "10", "1"),
        Kind("money", "", "450", "1"),
        Kind("temperature_rise", "[temperature]", "100 K", "K"),
    )
}

_ANGLE_UNITS = re.compile(r"^(rad|radian|radians|deg|degree|degrees|rev|revolution|revolutions|"
                          r"turn|turns|arcmin|arcminute|arcsec|arcsecond)$")


@cache
def registry() -> Any:
    """The shared pint UnitRegistry, created on first use (pint is slow to import)."""
    import pint

    ureg = pint.UnitRegistry()
    ureg.define("rev = revolution")
    return ureg


_NUMBER_AND_UNIT = re.compile(
    r"^\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?|[+-]?nan|[+-]?inf)\s*(.*?)\s*$",
    re.IGNORECASE,
)


def _expected(spec: Kind, got: Any, field: str | None) -> UserError:
    name = spec.name.replace("_", " ")
    article = "an" if name[0] in "aeiou" else "a"
    return UserError(f"expected {article} {name} like {spec.example!r}, got {got!r}", field=field)


def _split(text: str) -> tuple[str, str]:
    """('90', 'deg') from '90 deg'; the unit part may be empty."""
    match = _NUMBER_AND_UNIT.match(text)
    if not match:
        return "", text.strip()
    return match.group(1), match.group(2)


def to_si(value: Any, kind: str, *, field: str | None = None) -> float:
    """Convert a number or a text like '3000 rpm' of the given kind to an SI float.

    Raises UserError (with ``field``) for a wrong unit, a non-number or a non-finite value.
    """
    spec = KINDS[kind]
    if isinstance(value, bool) or value is None:
        raise _expected(spec, value, field)
    if isinstance(value, int | float):
        result = float(value)
    elif isinstance(value, str):
        result = _parse_text(value, spec, field)
    else:
        raise _expected(spec, value, field)
    if not math.isfinite(result):
        raise UserError(f"{value!r} is not a finite number", field=field)
    return result


def _parse_text(text: str, spec: Kind, field: str | None) -> float:
    number, unit = _split(text.replace("%", " percent"))
    wrong = _expected(spec, text, field)
    if not number:
        raise wrong
    if not unit:
        return float(number)
    if spec.name == "fraction":
        if unit not in ("percent", "pct"):
            raise wrong
        return float(number) / 100.0
    if spec.name in ("ratio", "money"):
        raise wrong
    if spec.name == "angle" and not _ANGLE_UNITS.match(unit):
        raise wrong
    ureg = registry()
    try:
        quantity = ureg.Quantity(float(number), unit.replace("^", "**"))
    except Exception as error:  # pint raises several unrelated error types
        raise UserError(f"unknown unit {unit!r} in {text!r} ({spec.name.replace('_', ' ')} "
                        f"expected, e.g. {spec.example!r})", field=field) from error
    expected = ureg.get_dimensionality(spec.dimensionality) if spec.dimensionality else {}
    if quantity.dimensionality != expected:
        raise wrong
    return float(quantity.to_base_units().magnitude)


def parse_displacement(value: Any, *, field: str | None = None) -> tuple[float, bool]:
    """A displacement h in SI and whether it is linear (a length) rather than an angle."""
    if isinstance(value, str):
        _, unit = _split(value)
        if unit and not _ANGLE_UNITS.match(unit):
            try:
                return to_si(value, "length", field=field), True
            except UserError as error:
                raise UserError(f"expected an angle like '90 deg' or a length like '200 mm', "
                                f"got {value!r}", field=field) from error
    return to_si(value, "angle", field=field), False
