"""Every failing check's reason gives its value and its limit with their unit and the
margin (issue 36: a failing ``winding_temperature_rise`` used to show its note only).
The numbers are set by hand: margin = 1 - value / limit."""

from __future__ import annotations

import math
from types import SimpleNamespace

import pytest

from sizer.io.loader import load_design_data
from sizer.sizing.checks import CHECKS, OWN_CHECKS, STAGE_CHECKS, CheckName
from sizer.sizing.energy_check import RMS_NOTE, THERMAL_NOTE
from sizer.sizing.engine import size_design
from sizer.sizing.results import RATIO_MEANING, Check


def _units() -> dict[str, str]:
    rotary = SimpleNamespace(axis_unit="rad")
    units = {str(kind.name): kind.unit(rotary) for kind in CHECKS}
    units |= {str(kind.name): kind.unit for kind in OWN_CHECKS}
    units |= {f"gearbox_{kind.suffix}": ("N*m" if kind.torque else "rad/s")
              for kind in STAGE_CHECKS}
    return units


UNITS = _units()
NUMBERED = sorted(set(UNITS) - {CheckName.DEAD_POINT})
"""Every check kind with a number (a dead point's rule has none: its note says which)."""


def test_every_check_kind_is_covered() -> None:
    assert {str(n) for n in CheckName} <= set(UNITS)
    assert {u for n, u in UNITS.items() if not u} == {""}
    assert {n for n, u in UNITS.items() if not u} - {"dead_point"} == set(RATIO_MEANING)


@pytest.mark.parametrize("name", NUMBERED)
@pytest.mark.parametrize("note", ["", "how the value was found"])
def test_a_failing_reason_gives_value_limit_and_margin_with_the_unit(name: str,
                                                                     note: str) -> None:
    unit = UNITS[name]
    check = Check(name, 218.0, 100.0, unit, 1.0 - 218.0 / 100.0, 0.0, note)
    text = check.describe()
    shown = f" {unit}" if unit else ""
    assert text.startswith(f"{name}: 218{shown} against 100{shown}")
    assert "margin -118.00%" in text and "(FAILS" in text
    if not unit:
        assert RATIO_MEANING[name] in text  # what the ratio is of
    if note:
        assert note in text


@pytest.mark.parametrize("name", NUMBERED)
def test_a_passing_reason_keeps_its_words(name: str) -> None:
    unit = UNITS[name]
    check = Check(name, 50.0, 100.0, unit, 0.5, 0.1, "a note")
    assert check.describe().endswith("margin 50.00%, 10% required (ok)")


def heat_design(tau_th: str) -> dict:
    """A dwell-free 1/3 trapezoid of 1 kg*m^2 in 10 s, its torque 1.3 x the continuous."""
    a = 1.3 * 8.0  # N*m over 1 kg*m^2
    h = a * 10.0**2 / 4.5
    motor = {"id": "M", "inertia": 0, "continuous_torque": "8 N*m", "peak_torque": "40 N*m",
             "rated_speed": "300 rad/s", "torque_constant": "2 N*m/Arms",
             "thermal_time_constant": tau_th, "max_winding_temperature_rise": "100 K"}
    return {"task": {"displacement": f"{h!r} rad", "duration": "10 s"},
            "load": {"inertia": "1 kg*m^2"}, "laws": ["trapezoidal"], "motors": [motor]}


@pytest.mark.parametrize("tau_th, note", [("1 s", THERMAL_NOTE), ("1e5 s", RMS_NOTE)])
def test_the_winding_temperature_rise_reason_has_its_numbers(tau_th: str, note: str) -> None:
    (row,) = size_design(load_design_data(heat_design(tau_th))).results
    heat = row.check("winding_temperature_rise")
    assert not heat.passed and heat.note == note
    if note == RMS_NOTE:  # RMS rise: 100 K x (tau_rms / tau_c)^2, tau_rms = a sqrt(2/3)
        assert heat.value == pytest.approx(100.0 * 1.3**2 * 2.0 / 3.0, rel=1e-9)
    margin = 1.0 - heat.value / 100.0
    words = (f"winding_temperature_rise: {heat.value:.6g} K against 100 K, "
             f"margin {100.0 * margin:.2f}%")
    assert words in row.reason and note in row.reason
    assert math.isfinite(heat.value)
