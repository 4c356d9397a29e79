"""Energy and heat in the sizing results (issue 16; sizer.sizing.energy_check).

Closed forms: a constant-acceleration move (the 1/3 trapezoid, C_a = 4.5, C_v = 1.5) of a
pure inertia stops with E = J_m w^2 / 2 + eta J_L (w/K)^2 / 2 returned to the bus; the
first-order winding under a loss switched between A and 0 settles periodically at
x_peak = A (1 - e^{-h/tau}) / (1 - e^{-(h+c)/tau}) (h heating, c cooling).
"""

from __future__ import annotations

import math

import pytest
import yaml

from sizer.io.loader import load_design_data
from sizer.sizing.energy_check import RMS_NOTE, THERMAL_NOTE
from sizer.sizing.engine import size_design
from sizer.sizing.results import record

MOTOR = {"id": "M", "inertia": "0.002 kg*m^2", "continuous_torque": "8 N*m",
         "peak_torque": "40 N*m", "rated_speed": "300 rad/s", "torque_constant": "2 N*m/Arms"}


def only(result):
    assert len(result.results) == 1
    return result.results[0]


def braking_design(tmp_path, drive: dict, **limits) -> dict:
    """A 1/3 trapezoid of h = 20 rad in 0.5 s through a 4:1 gearbox of 90 %, then 1 s of
    dwell: one stop per cycle."""
    catalog = {"catalog": "drives", "source": "test",
               "drives": [{"id": "D", "continuous_current": "20 A", "peak_current": "40 A",
                           **drive}]}
    (tmp_path / "drives.yaml").write_text(yaml.safe_dump(catalog), encoding="utf-8")
    design = {"task": {"displacement": "20 rad", "duration": "0.5 s", "dwell": "1 s"},
              "load": {"inertia": "0.3 kg*m^2"},
              "transmission": {"type": "gearbox", "ratio": 4, "efficiency": 0.9},
              "laws": ["trapezoidal"], "motors": [MOTOR], "drives": ["drives.yaml"]}
    if limits:
        design["limits"] = limits
    return design


def stop_energy() -> float:
    w = 4.0 * 1.5 * 20.0 / 0.5  # motor speed at the end of the cruise
    return 0.5 * 0.002 * w**2 + 0.9 * 0.5 * 0.3 * (w / 4.0) ** 2


def test_the_regenerated_energy_per_stop_is_the_kinetic_energy_through_the_efficiency(
        tmp_path):
    row = only(size_design(load_design_data(braking_design(
        tmp_path, {"braking_resistor_power": "500 W"}), base=tmp_path)))
    assert row.regenerated_energy == pytest.approx(stop_energy(), rel=1e-12)
    assert row.braking_power == pytest.approx(stop_energy() / 1.5, rel=1e-12)  # no capacitor
    check = row.check("braking_resistor_power")
    assert check.value == pytest.approx(stop_energy() / 1.5, rel=1e-12)
    assert check.limit == 500.0 and check.unit == "W" and check.passed


def test_the_bus_capacitor_takes_its_share_and_the_design_limit_overrides(tmp_path):
    drive = {"braking_resistor_power": "500 W", "bus_capacitance": "1000 uF",
             "dc_bus_voltage": "320 V", "braking_threshold": "390 V", "max_bus_voltage": "420 V"}
    design = braking_design(tmp_path, drive, braking_resistor_power="50 W")
    row = only(size_design(load_design_data(design, base=tmp_path)))
    absorbed = 0.5 * 1e-3 * (390.0**2 - 320.0**2)
    assert stop_energy() > absorbed
    check = row.check("braking_resistor_power")
    assert check.value == pytest.approx((stop_energy() - absorbed) / 1.5, rel=1e-12)
    assert check.limit == 50.0
    assert check.passed == ((stop_energy() - absorbed) / 1.5 <= 50.0)
    assert row.regenerated_energy == pytest.approx(stop_energy(), rel=1e-12)


def heat_design(ratio: float, tau_th: str, **limits) -> dict:
    """A dwell-free 1/3 trapezoid of a 1 kg*m^2 inertia on a direct drive in 10 s, its
    acceleration torque ``ratio`` times the continuous 8 N*m."""
    a = ratio * 8.0  # J = 1 (the motor's rotor is 0)
    h = a * 10.0**2 / 4.5
    motor = {**MOTOR, "inertia": 0, "thermal_time_constant": tau_th,
             "max_winding_temperature_rise": "100 K"}
    design = {"task": {"displacement": f"{h!r} rad", "duration": "10 s"},
              "load": {"inertia": "1 kg*m^2"}, "laws": ["trapezoidal"], "motors": [motor]}
    if limits:
        design["limits"] = limits
    return design


def test_a_short_time_constant_fails_the_heat_check_that_rms_passes():
    row = only(size_design(load_design_data(heat_design(1.1, "1 s"))))
    rms = row.check("rms")
    assert rms.passed and rms.value == pytest.approx(8.8 * math.sqrt(2.0 / 3.0), rel=1e-9)
    heat = row.check("winding_temperature_rise")
    # one cycle: accelerate 10/3 s, cruise 10/3 s, brake 10/3 s; braking runs into the
    # next acceleration: 20/3 s heating at 100 K x 1.1^2, 10/3 s cooling
    h, c, A = 20.0 / 3.0, 10.0 / 3.0, 100.0 * 1.1**2
    peak = A * (1.0 - math.exp(-h)) / (1.0 - math.exp(-(h + c)))
    assert heat.value == pytest.approx(peak, rel=1e-9)
    assert heat.limit == 100.0 and heat.unit == "K" and not heat.passed
    assert heat.note == THERMAL_NOTE and "thermal model applied" in row.reason
    assert not row.feasible and row.limiting == "winding_temperature_rise"
    assert row.winding_rise == pytest.approx(peak, rel=1e-9)


@pytest.mark.parametrize("ratio", [1.1, 1.3])
def test_with_a_long_time_constant_the_verdict_is_the_rms_checks(ratio):
    row = only(size_design(load_design_data(heat_design(ratio, "1e5 s"))))
    rms, heat = row.check("rms"), row.check("winding_temperature_rise")
    assert heat.passed == rms.passed == (ratio * math.sqrt(2.0 / 3.0) <= 1.0)
    assert heat.value == pytest.approx(100.0 * ratio**2 * 2.0 / 3.0, rel=1e-9)
    assert heat.note == RMS_NOTE


def test_the_design_limit_and_the_torque_margin_apply_to_the_rise():
    row = only(size_design(load_design_data(heat_design(
        1.1, "1e5 s", winding_temperature_rise="70 K", torque_margin=0.1))))
    heat, rms = row.check("winding_temperature_rise"), row.check("rms")
    assert heat.limit == 70.0
    assert heat.value == pytest.approx(100.0 * 1.21 * 2.0 / 3.0, rel=1e-9)  # R_th: the motor's
    assert heat.required == pytest.approx(1.0 - 0.9**2, rel=1e-12)
    assert not heat.passed and rms.passed


def test_designs_without_the_fields_have_no_energy_figures(tmp_path):
    design = braking_design(tmp_path, {})
    row = only(size_design(load_design_data(design, base=tmp_path)))
    assert row.check("braking_resistor_power") is None
    assert row.check("winding_temperature_rise") is None
    assert row.regenerated_energy is None and row.winding_rise is None
    assert "regenerated_energy" not in record(row)


def test_minimize_checks_the_rise_at_t_min_and_says_so():
    design = heat_design(1.1, "1e5 s")
    design["task"] = {**design["task"], "duration": "minimize"}
    result = size_design(load_design_data(design))
    row = only(result)
    assert any("lengthened to the first duration" in note for note in result.notes)
    h = 1.1 * 8.0 * 100.0 / 4.5  # the RMS check's T_min, not moved: tau sqrt(2/3) = 8
    assert row.duration == pytest.approx(math.sqrt(4.5 * h * math.sqrt(2.0 / 3.0) / 8.0),
                                         rel=1e-9)
    heat = row.check("winding_temperature_rise")
    assert row.feasible and heat.passed and heat.note == RMS_NOTE
    rms, tau_c = row.check("rms").value, row.check("rms").limit
    assert heat.value == pytest.approx(100.0 * (rms / tau_c) ** 2, rel=1e-12)


def test_minimize_lengthens_the_move_until_the_winding_model_passes():
    """tau_th = 1 s against a cycle of about 10 s: at the RMS check's T_min the winding
    model's periodic peak is over 100 K; the move is lengthened to the T where it is
    100 K: the torque of the 1/3 trapezoid is tau = 4.5 h / T^2 (J = 1), the loss A(T) =
    100 (tau/8)^2 K for 2T/3 of each cycle, 0 for T/3 (the closed form of the module's
    docstring), solved here by brentq."""
    from scipy.optimize import brentq

    design = heat_design(1.1, "1 s")
    design["task"] = {**design["task"], "duration": "minimize"}
    h = 1.1 * 8.0 * 100.0 / 4.5

    def peak(T):
        A = 100.0 * (4.5 * h / T**2 / 8.0) ** 2
        return A * (1.0 - math.exp(-2.0 * T / 3.0)) / (1.0 - math.exp(-T))

    T_rms = math.sqrt(4.5 * h * math.sqrt(2.0 / 3.0) / 8.0)  # tau_rms = tau sqrt(2/3) = 8
    assert peak(T_rms) > 100.0
    expected = brentq(lambda T: peak(T) - 100.0, T_rms, 4.0 * T_rms, xtol=1e-14)
    row = only(size_design(load_design_data(design)))
    assert row.feasible
    assert row.duration == pytest.approx(expected, rel=1e-9)
    heat = row.check("winding_temperature_rise")
    assert heat.note == THERMAL_NOTE and heat.passed
    assert heat.value == pytest.approx(100.0, rel=1e-9)



def test_minimize_lengthens_the_move_until_the_braking_resistor_passes(tmp_path):
    """No bus capacitor: the resistor takes the whole stop energy E(T) = J_m w^2 / 2 +
    eta J_L (w/K)^2 / 2 with w = K 1.5 h / T, once per cycle of T + 1 s; the duration is
    where E(T) / (T + 1) = 50 W (brentq), longer than the torque checks' T_min."""
    from scipy.optimize import brentq

    design = braking_design(tmp_path, {}, braking_resistor_power="50 W")
    design["task"] = {**design["task"], "duration": "minimize"}

    def power(T):
        w = 4.0 * 1.5 * 20.0 / T
        return (0.5 * 0.002 * w**2 + 0.9 * 0.5 * 0.3 * (w / 4.0) ** 2) / (T + 1.0)

    expected = brentq(lambda T: power(T) - 50.0, 0.1, 10.0, xtol=1e-14)
    row = only(size_design(load_design_data(design, base=tmp_path)))
    assert row.feasible
    assert row.duration == pytest.approx(expected, rel=1e-9)
    check = row.check("braking_resistor_power")
    assert check.passed and check.value == pytest.approx(50.0, rel=1e-9)
    # every other check has room left: they alone would allow a shorter move
    assert all(c.margin - c.required > 1e-3 for c in row.checks
               if c.name != "braking_resistor_power")
