"""The load-side speed limit ``limits.max_speed`` (a belt's or a screw's maximum speed).

Hand numbers: the peak load speed of a law is C_v h / T (trapezoid alpha = 1/3: C_v = 3/2,
cycloidal: C_v = 2), and in minimize mode the limit bounds T from below by C_v h / v_max.
"""

from __future__ import annotations

import math
import textwrap

import pytest
from cli_run import assert_user_error, run_cli

from sizer.io.loader import load_design
from sizer.sizing import size_design

BELT = textwrap.dedent("""\
    task: {{displacement: 500 mm, duration: {duration}}}
    load: {{mass: 4 kg, friction: {friction}}}
    transmission: {{type: belt, driver_diameter: 50 mm, driven_diameter: 50 mm}}
    laws: ['trapezoidal(alpha=1/3)']
    motors:
      - {{id: big, inertia: 1 kg*cm^2, continuous_torque: 50 N*m, peak_torque: 150 N*m,
         rated_speed: 6000 rpm}}
    limits: {{max_speed: {max_speed}}}
    """)


def belt(tmp_path, duration="0.5 s", max_speed="90 m/min", friction="0 N"):
    path = tmp_path / "belt.yaml"
    path.write_text(BELT.format(duration=duration, max_speed=max_speed, friction=friction))
    return load_design(path)


def test_a_belt_speed_limit_in_m_per_min(tmp_path) -> None:
    design = belt(tmp_path)
    assert design.limits.max_speed == pytest.approx(1.5, rel=1e-15)  # 90 m/min
    (r,) = size_design(design).results
    check = r.check("load_speed")
    assert check.value == pytest.approx(1.5 * 0.5 / 0.5, rel=1e-12)  # C_v h / T, m/s
    assert check.unit == "m/s" and check.passed and r.feasible  # exactly at the limit
    (r,) = size_design(belt(tmp_path, max_speed="89 m/min")).results
    assert not r.feasible and r.limiting == "load_speed"
    margin = 1 - 1.5 / (89 / 60)
    assert r.check("load_speed").margin == pytest.approx(margin, rel=1e-12)
    assert f"margin {100 * margin:.2f}% (FAILS)" in r.reason  # -1.12 %


@pytest.mark.parametrize("friction", ["0 N", "5 N"])  # closed form, then the search
def test_minimize_stops_at_the_load_speed_limit(tmp_path, friction) -> None:
    (r,) = size_design(belt(tmp_path, "minimize", "1 m/s", friction)).results
    assert r.feasible and r.limiting == "load_speed"
    assert r.duration == pytest.approx(1.5 * 0.5 / 1.0, rel=1e-9)  # C_v h / v_max
    assert r.load_speed == pytest.approx(1.0, rel=1e-9)


def test_the_closed_form_has_the_load_speed_bound(tmp_path) -> None:
    from sizer.laws import make_law
    from sizer.mechanics import Drive
    from sizer.sizing.candidates import MotorArrays
    from sizer.sizing.move import CycleCalculator
    from sizer.sizing.shortest_duration import closed_form_duration, is_purely_inertial

    design = belt(tmp_path, "minimize", "1 m/s")
    calculator = CycleCalculator(None, design.task, Drive(design.load, design.transmission),
                                 MotorArrays.of(design.motors), law=make_law(design.laws[0]))
    assert is_purely_inertial(calculator)
    assert closed_form_duration(calculator, design.limits)[0] == pytest.approx(0.75, rel=1e-15)


def test_a_rotary_load_speed_limit_in_rpm(tmp_path) -> None:
    path = tmp_path / "rotary.yaml"
    path.write_text(textwrap.dedent("""\
        task: {displacement: 90 deg, duration: minimize}
        load: {inertia: 0.01 kg*m^2}
        transmission: {type: gearbox, ratio: 10}
        laws: [cycloidal]
        motors:
          - {id: m, inertia: 1 kg*cm^2, continuous_torque: 20 N*m, peak_torque: 60 N*m,
             rated_speed: 3000 rpm}
        limits: {max_speed: 30 rpm}
        """))
    design = load_design(path)
    assert design.limits.max_speed == pytest.approx(math.pi, rel=1e-15)
    (r,) = size_design(design).results
    # 2 (pi/2) / T = pi rad/s: T = 1 s, where the motor runs at 300 rpm
    assert r.limiting == "load_speed" and r.duration == pytest.approx(1.0, rel=1e-12)
    assert r.check("load_speed").unit == "rad/s"


def test_a_load_speed_of_the_wrong_kind_is_a_user_error(tmp_path) -> None:
    path = tmp_path / "wrong.yaml"
    path.write_text(BELT.format(duration="0.5 s", max_speed="300 rpm", friction="0 N"))
    assert_user_error(run_cli("size", str(path)), "wrong.yaml", "limits.max_speed",
                      "linear speed")
