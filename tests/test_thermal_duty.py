"""A one-off run (``limits.thermal_duty: once``, issue 16): the winding model from the
ambient decides, not the RMS check.

The move of tests/test_energy_design.heat_design: a 1/3 trapezoid of a pure inertia in
10 s, no dwell, its acceleration torque ``ratio`` times the continuous torque for 10/3 s,
cruise 10/3 s, braking 10/3 s. From the ambient the first-order model rises to
r1 = A (1 - e^(-h/tau)) with A = 100 K ratio^2, h = 10/3 s, cools to r2 = r1 e^(-h/tau)
and ends at r3 = A + (r2 - A) e^(-h/tau); the peak is max(r1, r3).
"""

from __future__ import annotations

import math

import pytest
from test_energy_design import heat_design, only

from sizer.errors import UserError
from sizer.io.loader import load_design_data
from sizer.sizing import size_design
from sizer.sizing.energy_check import ONCE_NOTE


def peak_once(ratio: float, tau: float) -> float:
    A, h = 100.0 * ratio**2, 10.0 / 3.0
    r1 = A * (1.0 - math.exp(-h / tau))
    r3 = A + (r1 * math.exp(-h / tau) - A) * math.exp(-h / tau)
    return max(r1, r3)


def once(ratio: float, tau: str):
    return only(size_design(load_design_data(heat_design(ratio, tau,
                                                         thermal_duty="once"))))


def test_with_a_short_time_constant_the_model_fails_what_rms_passes() -> None:
    row = once(1.1, "1 s")
    heat = row.check("winding_temperature_rise")
    assert heat.value == pytest.approx(peak_once(1.1, 1.0), rel=1e-6)
    assert heat.note == ONCE_NOTE and not heat.passed and not row.feasible
    assert row.check("rms") is None  # no criterion for a one-off run
    assert 1.1 * math.sqrt(2.0 / 3.0) < 1.0  # the RMS check would have passed


def test_with_a_long_time_constant_the_model_passes_what_rms_fails() -> None:
    repeated = only(size_design(load_design_data(heat_design(1.3, "1e5 s"))))
    assert not repeated.feasible and not repeated.check("rms").passed
    row = once(1.3, "1e5 s")
    heat = row.check("winding_temperature_rise")
    assert heat.value == pytest.approx(peak_once(1.3, 1e5), rel=1e-6)
    assert heat.passed and row.feasible and row.check("rms") is None
    assert row.rms_torque == pytest.approx(1.3 * 8.0 * math.sqrt(2.0 / 3.0), rel=1e-9)


def test_once_needs_a_given_duration() -> None:
    design = heat_design(1.1, "1 s", thermal_duty="once")
    design["task"]["duration"] = "minimize"
    with pytest.raises(UserError) as caught:
        load_design_data(design)
    assert caught.value.field == "limits.thermal_duty"
