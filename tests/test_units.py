"""Units at the boundary: text with a unit in, SI float out (sizer.units)."""

from __future__ import annotations

import math
import re

import pytest

from sizer.errors import UserError
from sizer.units import parse_displacement, to_si


@pytest.mark.parametrize(
    ("text", "kind", "expected"),
    [
        ("3000 rpm", "angular_speed", 100 * math.pi),
        ("1.2 kg*cm^2", "inertia", 1.2e-4),
        ("10 %", "fraction", 0.1),
        ("90 deg", "angle", math.pi / 2),
        ("1 rev", "angle", 2 * math.pi),
        ("0.2 s", "time", 0.2),
        ("250 ms", "time", 0.25),
        ("200 mm", "length", 0.2),
        ("0.5 N*m", "torque", 0.5),
        ("12 kg", "mass", 12.0),
        ("1e3 rad/s^2", "angular_acceleration", 1000.0),
    ],
)
def test_text_with_unit_converts_to_si(text: str, kind: str, expected: float) -> None:
    assert to_si(text, kind) == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize(("value", "kind"), [(2.5, "time"), (3, "torque"), ("0.35", "inertia"),
                                             (" 7 ", "angle"), ("-1.5e-3", "length")])
def test_bare_number_is_already_si(value: object, kind: str) -> None:
    assert to_si(value, kind) == pytest.approx(float(str(value)))


@pytest.mark.parametrize(
    ("value", "kind"),
    [
        ("3 kg", "time"),          # wrong dimension
        ("5 m", "angle"),           # a length is not an angle
        ("2 parsecs/fortnight", "angular_speed"),  # wrong dimension
        ("3 flurbs", "torque"),     # unknown unit
        ("nan", "time"),            # not finite
        (float("inf"), "time"),
        ("fast", "angular_speed"),  # not a number
        (True, "ratio"),
        (None, "time"),
    ],
)
def test_bad_values_raise_user_error_naming_the_field(value: object, kind: str) -> None:
    with pytest.raises(UserError) as caught:
        to_si(value, kind, field="motor.speed")
    assert caught.value.field == "motor.speed"
    assert str(caught.value).startswith("motor.speed: ")


def test_wrong_dimension_message_gives_an_example() -> None:
    with pytest.raises(UserError, match=re.escape("expected a time like '0.2 s'")):
        to_si("3 kg", "time")


def test_displacement_tells_angles_from_lengths() -> None:
    h, linear = parse_displacement("90 deg")
    assert (h, linear) == (pytest.approx(math.pi / 2), False)
    h, linear = parse_displacement("200 mm")
    assert (h, linear) == (pytest.approx(0.2), True)
    assert parse_displacement(1.5) == (1.5, False)  # bare number: radians
    with pytest.raises(UserError) as caught:
        parse_displacement("3 kg", field="task.displacement")
    assert caught.value.field == "task.displacement"
