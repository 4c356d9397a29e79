"""A ball screw's critical speed, buckling and L10 life checks (issue 38, "Mechanics checks";
docs/ball-screws.md).

Numbers come from the makers' printed worked examples (MISUMI, THK), from THK's first-
principles forms of its own coefficients, and from independent integrations of known
cycles (closed forms of the trapezoidal profile; a hand-written poly5 on a fine grid),
never from the code's output.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from bad_input_cases import Case, edited
from bad_input_cases import run_case as run

import sizer
from sizer.mechanics.stages import (
    ScrewRatings,
    screw_buckling_load,
    screw_critical_speed,
    screw_rated_life,
)

RPM = 2.0 * math.pi / 60.0


# ------------------------------------------------------------ the makers' formulas
def test_buckling_misumi_worked_example():
    # MISUMI Economy Series e-catalog 2025, p. 1676, "Allowable Axial Load Calculation
    # Example": thread shaft 15, lead 5, fixed-support, l = 820 mm, root d = 12.5 mm:
    # P = m d^4 / l^2 1e4 = 10 x 12.5^4 / 820^2 x 1e4 = 3630 N (printed)
    screw = ScrewRatings(mounting="fixed-supported", root_diameter=12.5e-3,
                         support_distance=0.82)
    assert screw.permissible_buckling_load == pytest.approx(3630.0, abs=1.0)


def test_buckling_thk_worked_example():
    # THK LM Guide Actuator KR catalog, "Evaluating the Rated Life Span of the Ball Screw":
    # fixed-fixed, l_a = 1300 mm, d_1 = 17.5 mm, safety factor 0.5: P_1 = 11000 N (printed,
    # rounded)
    screw = ScrewRatings(mounting="fixed-fixed", root_diameter=17.5e-3, support_distance=1.3)
    assert screw.permissible_buckling_load == pytest.approx(11000.0, rel=0.01)


@pytest.mark.parametrize(("mounting", "eta_2"), [("fixed-free", 1.3),
                                                ("supported-supported", 5.1),
                                                ("fixed-supported", 10.0),
                                                ("fixed-fixed", 20.0)])
def test_buckling_closed_form(mounting, eta_2):
    # by hand: P = eta_2 d^4 / L^2 1e4 N, d and L in mm (THK eq. 5; HSK's m = 5.1)
    d, L = 20.0, 800.0
    screw = ScrewRatings(mounting=mounting, root_diameter=d / 1e3, support_distance=L / 1e3)
    assert screw.permissible_buckling_load == pytest.approx(eta_2 * d**4 / L**2 * 1e4, rel=1e-12)
    # without its safety factor 0.5: the Euler load
    assert screw_buckling_load(d / 1e3, L / 1e3, mounting) == pytest.approx(
        eta_2 / 0.5 * d**4 / L**2 * 1e4, rel=1e-12)
    # THK eq. (5), first form: eta_1 pi^2 E I / l^2 x 0.5, E = 2.06e5 N/mm^2, I = pi d^4/64
    eta_1 = {"fixed-free": 0.25, "supported-supported": 1.0, "fixed-supported": 2.0,
             "fixed-fixed": 4.0}[mounting]
    euler = eta_1 * math.pi**2 * 2.06e5 * math.pi * d**4 / 64.0 / L**2 * 0.5
    assert screw.permissible_buckling_load == pytest.approx(euler, rel=0.045)  # eta_2 rounded


@pytest.mark.parametrize(("mounting", "lambda_1", "lambda_2"),
                         [("fixed-free", 1.875, 3.4), ("supported-supported", 3.142, 9.7),
                          ("fixed-supported", 3.927, 15.1), ("fixed-fixed", 4.73, 21.9)])
def test_critical_speed_closed_form(mounting, lambda_1, lambda_2):
    d, L = 17.5, 1000.0  # mm
    screw = ScrewRatings(mounting=mounting, root_diameter=d / 1e3, support_distance=L / 1e3)
    # by hand: THK eq. (7) N_1 = lambda_2 d_1 / l_b^2 1e7 min^-1, 0.8 included
    assert screw.permissible_speed == pytest.approx(lambda_2 * d / L**2 * 1e7 * RPM, rel=1e-12)
    assert screw_critical_speed(d / 1e3, L / 1e3, mounting) == pytest.approx(
        lambda_2 / 0.8 * d / L**2 * 1e7 * RPM, rel=1e-12)
    # THK eq. (7), first form: 60 lambda_1^2 / (2 pi l_b^2) sqrt(E 1e3 I / (gamma A)) 0.8
    E, gamma = 2.06e5, 7.85e-6  # N/mm^2, kg/mm^3
    inertia, A = math.pi * d**4 / 64.0, math.pi * d**2 / 4.0
    first = 60.0 * lambda_1**2 / (2.0 * math.pi * L**2) * math.sqrt(E * 1e3 * inertia / (gamma * A))
    assert screw.permissible_speed == pytest.approx(0.8 * first * RPM, rel=0.015)


def test_tensile_compressive_load_closed_form():
    # THK eq. (6): P_2 = sigma pi/4 d_1^2 = 116 d_1^2 N, sigma = 147 MPa, d_1 in mm
    d = 17.5
    screw = ScrewRatings(mounting="fixed-fixed", root_diameter=d / 1e3, support_distance=1.0)
    assert screw.permissible_tensile_compressive_load == pytest.approx(
        147.0 * math.pi / 4.0 * d**2, rel=1e-12)
    assert screw.permissible_tensile_compressive_load == pytest.approx(116.0 * d**2, rel=0.005)


def test_safety_factors_scale_the_limits():
    base = ScrewRatings(mounting="fixed-fixed", root_diameter=0.02, support_distance=1.0)
    other = ScrewRatings(mounting="fixed-fixed", root_diameter=0.02, support_distance=1.0,
                         speed_factor=0.4, buckling_factor=0.25, buckling_length=0.5)
    assert other.permissible_speed == pytest.approx(base.permissible_speed / 2, rel=1e-12)
    # half the factor, half the length: twice the load
    assert other.permissible_buckling_load == pytest.approx(2 * base.permissible_buckling_load,
                                                         rel=1e-12)


def test_rated_life_mitcalc_example():
    # MITCalc "Ball Screw Design & Calculations" (scribd 717970337): F_m = 1000 N,
    # n_m = 2400 min^-1, f_w = 1.2, L_h = 20000 h: required C_a = 17073.1 N (printed)
    revolutions = screw_rated_life(17073.1, 1000.0, 1.2)
    assert revolutions / (2400.0 * 60.0) == pytest.approx(20000.0, rel=1e-5)


# ------------------------------------------------------------ a design with its checks
def design(law: str = "trapezoidal(alpha=1/4)", duration: str = "0.6 s",
           **screw: object) -> dict:
    return {
        "name": "screw checks",
        "task": {"displacement": "300 mm", "duration": duration, "dwell": "0.4 s",
                 "return": True},
        "load": {"mass": "80 kg", "friction": "150 N", "force": "200 N"},
        "transmission": [{"type": "ball_screw", "lead": "10 mm", "diameter": "20 mm",
                          "length": "1 m", "efficiency": 0.9, **screw}],
        "laws": [law],
        "motors": ["yaskawa-sgm7j"],
    }


SHAFT = {"mounting": "fixed-supported", "root_diameter": "17.5 mm",
         "support_distance": "900 mm", "buckling_length": "800 mm"}
LIFE = {"dynamic_load_rating": "9 kN", "load_factor": 1.2, "required_life": "20000 h"}


def best(result):
    return result.results[0]


def test_no_ratings_no_checks():
    row = best(sizer.size(design(), motors=["SGM7J-08A"]))
    assert not [c for c in row.checks if c.name.startswith("ball_screw_")]


def test_each_group_only_with_its_data():
    shaft = best(sizer.size(design(**SHAFT), motors=["SGM7J-08A"]))
    assert {c.name for c in shaft.checks if c.name.startswith("ball_screw_")} == {
        "ball_screw_critical_speed", "ball_screw_buckling", "ball_screw_axial_load"}
    life = best(sizer.size(design(**LIFE), motors=["SGM7J-08A"]))
    assert {c.name for c in life.checks if c.name.startswith("ball_screw_")} == {
        "ball_screw_life"}


def _trapezoid_cycle(alpha: float, h: float, T: float, dwell: float, m: float, friction: float,
                     force: float):
    """(revolutions-weighted F^3 sum, travel, cycle time, peak |F|) of move + dwell + return
    + dwell with the trapezoidal profile: constant force on each phase, by hand."""
    v = h / (T * (1.0 - alpha))
    a = v / (alpha * T)
    d_ramp, d_cruise = v * alpha * T / 2.0, v * (1.0 - 2.0 * alpha) * T
    cube, travel, peak = 0.0, 0.0, 0.0
    for along in (force, -force):  # forward: the force opposes; back: it drives
        for F, d in ((m * a + friction + along, d_ramp), (friction + along, d_cruise),
                     (-m * a + friction + along, d_ramp)):
            cube += abs(F) ** 3 * d
            travel += d
            peak = max(peak, abs(F))
    return cube, travel, 2.0 * (T + dwell), max(peak, abs(force))


def test_trapezoid_cycle_against_closed_forms():
    row = best(sizer.size(design(**SHAFT, **LIFE), motors=["SGM7J-08A"]))
    cube, travel, cycle, peak = _trapezoid_cycle(0.25, 0.3, 0.6, 0.4, 80.0, 150.0, 200.0)
    F_m = (cube / travel) ** (1.0 / 3.0)
    revolutions = travel / 0.01
    life = (9000.0 / (1.2 * F_m)) ** 3 * 1e6 * cycle / revolutions
    check = row.check("ball_screw_life")
    assert check.value == pytest.approx(20000 * 3600.0, rel=1e-15)
    assert check.limit == pytest.approx(life, rel=1e-9)
    assert check.margin == pytest.approx(1.0 - 20000 * 3600.0 / life, rel=1e-9)
    buckling = row.check("ball_screw_buckling")
    assert buckling.value == pytest.approx(peak, rel=1e-12)
    assert buckling.limit == pytest.approx(10.0 * 17.5**4 / 800.0**2 * 1e4, rel=1e-12)
    axial = row.check("ball_screw_axial_load")
    assert axial.value == pytest.approx(peak, rel=1e-12)
    assert axial.limit == pytest.approx(147.0 * math.pi / 4.0 * 17.5**2, rel=1e-12)
    speed = row.check("ball_screw_critical_speed")
    v_max = 0.3 / (0.6 * 0.75)
    assert speed.value == pytest.approx(v_max * 2.0 * math.pi / 0.01, rel=1e-12)
    assert speed.limit == pytest.approx(15.1 * 17.5 / 900.0**2 * 1e7 * RPM, rel=1e-12)


def test_poly5_cycle_against_a_fine_integration():
    row = best(sizer.size(design(law="poly5", **LIFE), motors=["SGM7J-08A"]))
    h, T, dwell, m, friction, force = 0.3, 0.6, 0.4, 80.0, 150.0, 200.0
    tau = np.linspace(0.0, 1.0, 400_001)
    v = h / T * (30 * tau**2 - 60 * tau**3 + 30 * tau**4)
    a = h / T**2 * (60 * tau - 180 * tau**2 + 120 * tau**3)
    t = tau * T
    cube = travel = 0.0
    for along in (force, -force):
        F = np.abs(m * a + friction + along)
        cube += np.trapezoid(F**3 * v, t)
        travel += np.trapezoid(v, t)
    assert travel == pytest.approx(2 * h, rel=1e-9)
    F_m = (cube / travel) ** (1.0 / 3.0)
    life = (9000.0 / (1.2 * F_m)) ** 3 * 1e6 * 2.0 * (T + dwell) / (travel / 0.01)
    assert row.check("ball_screw_life").limit == pytest.approx(life, rel=1e-4)


def test_a_failing_screw_names_its_limit_and_margin():
    short = {**SHAFT, "support_distance": "2 m", "buckling_length": "2 m",
             "dynamic_load_rating": "1 kN", "required_life": "20000 h"}
    result = sizer.size(design(**short), motors=["SGM7J-08A"])
    row = best(result)
    assert not row.feasible
    speed = row.check("ball_screw_critical_speed")
    limit = 15.1 * 17.5 / 2000.0**2 * 1e7 * RPM
    assert speed.limit == pytest.approx(limit, rel=1e-12)
    assert speed.margin == pytest.approx(1.0 - speed.value / limit, rel=1e-12)
    assert speed.margin < 0.0
    assert row.check("ball_screw_life").margin < 0.0
    assert "ball_screw_critical_speed" in row.reason and "FAILS" in row.reason


def test_minimize_moves_to_the_critical_speed():
    # the screw's speed limit binds: T_min is where the peak speed meets it
    tight = {**SHAFT, "support_distance": "1.6 m"}
    row = best(sizer.size(design(duration="minimize", **tight), motors=["SGM7J-08A"]))
    assert row.feasible
    limit = 15.1 * 17.5 / 1600.0**2 * 1e7 * RPM / (2.0 * math.pi / 0.01)  # m/s at the load
    T = 0.3 / (limit * 0.75)  # v_max = h / (T (1 - alpha))
    assert row.duration == pytest.approx(T, rel=1e-9)
    assert row.limiting == "ball_screw_critical_speed"


# ------------------------------------------------------------ bad fields, located
SCREW = "transmission[1]"
LINEAR = "vendor-ballscrew.yaml"
FIELD = "transmission[ball_screw]"
D = "design.yaml:"


def case(id: str, value: dict, words: tuple[str, ...], fields: tuple[str, ...]) -> Case:
    return Case(id, design=edited(LINEAR, set=value), words=(D, *words), fields=fields)


FIELD_CASES = [
    case("screw-mounting-unknown", {f"{SCREW}.mounting": "clamped", f"{SCREW}.root_diameter":
                                    "17 mm"},
         (f"{SCREW}.mounting", "fixed-free"), (f"{FIELD}.mounting",)),
    case("screw-root-diameter-without-mounting", {f"{SCREW}.root_diameter": "17 mm"},
         (f"{SCREW}.root_diameter", "need the screw's end mounting"),
         (f"{FIELD}.root_diameter",)),
    case("screw-mounting-without-root-diameter", {f"{SCREW}.mounting": "fixed-fixed"},
         (f"{SCREW}.mounting", "root_diameter", "thread minor diameter"), ()),
    case("screw-root-diameter-over-nominal", {f"{SCREW}.mounting": "fixed-fixed",
                                              f"{SCREW}.root_diameter": "25 mm"},
         (f"{SCREW}.root_diameter", "must not exceed the nominal diameter"), ()),
    case("screw-root-diameter-2-m", {f"{SCREW}.root_diameter": "2 m"},
         (f"{SCREW}.root_diameter", "[0.001, 1] m"), (f"{FIELD}.root_diameter",)),
    case("screw-support-distance-1-km", {f"{SCREW}.support_distance": "1 km"},
         (f"{SCREW}.support_distance", "[0.001, 100] m"), (f"{FIELD}.support_distance",)),
    case("screw-buckling-length-zero", {f"{SCREW}.buckling_length": 0},
         (f"{SCREW}.buckling_length", "[0.001, 100] m"), (f"{FIELD}.buckling_length",)),
    case("screw-speed-factor-over-one", {f"{SCREW}.speed_factor": 1.5},
         (f"{SCREW}.speed_factor", "[0.01, 1]"), (f"{FIELD}.speed_factor",)),
    case("screw-buckling-factor-without-mounting", {f"{SCREW}.buckling_factor": 0.4},
         (f"{SCREW}.buckling_factor", "mounting"), (f"{FIELD}.buckling_factor",)),
    case("screw-load-rating-a-torque", {f"{SCREW}.dynamic_load_rating": "5 N*m"},
         (f"{SCREW}.dynamic_load_rating",), (f"{FIELD}.dynamic_load_rating",)),
    case("screw-load-rating-without-life", {f"{SCREW}.dynamic_load_rating": "5 kN"},
         (f"{SCREW}.dynamic_load_rating", "required_life is missing"), ()),
    case("screw-load-factor-under-one", {f"{SCREW}.load_factor": 0.5},
         (f"{SCREW}.load_factor", "[1, 10]"), (f"{FIELD}.load_factor",)),
    case("screw-required-life-negative", {f"{SCREW}.required_life": "-5 h"},
         (f"{SCREW}.required_life", "[1, 1e10] s"), (f"{FIELD}.required_life",)),
]
"""The new fields' bad values: each one located message (for tests/test_bad_inputs_fields.py's
walk over every field: it needs these ``fields``)."""


@pytest.mark.parametrize("case", FIELD_CASES, ids=str)
def test_bad_screw_field(case, tmp_path):
    run(case, tmp_path)


def test_ratings_only_on_the_last_stage(tmp_path):
    # a ball screw before another stage: its axial force is not the load's
    text = edited(LINEAR, set={"transmission": [
        {"type": "ball_screw", "lead": "10 mm", "inertia": 0, "mounting": "fixed-fixed",
         "root_diameter": "17 mm", "support_distance": "1 m"},
        {"type": "rack_pinion", "pitch_radius": "20 mm"}]})
    run(Case("screw-not-last", design=text, words=(D, "transmission[0].mounting",
                                                   "last stage")), tmp_path)
