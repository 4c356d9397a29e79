"""Shaft loads on the motor (issue 38, docs/shaft-loads.md): a belt's, a pinion's and a
directly coupled ball screw's loads on the motor's shaft against the motor's catalog
ratings. The forces against their closed forms; the checks' values by hand from the
motor's peak torque (itself by hand: a cycloidal move of a rotor-free motor)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sizer import api
from sizer.errors import UserError
from sizer.io.loader import load_design_data
from sizer.mechanics.shaft_loads import belt_radial_load, pinion_radial_load
from sizer.sizing.checks import TOLERANCE
from sizer.sizing.engine import size_design

# --- forces against closed forms -------------------------------------------------------


@pytest.mark.parametrize("wrap_deg", [60.0, 120.0, 180.0, 210.0])
def test_a_belt_at_rest_loads_the_shaft_with_twice_its_pretension_times_sin_half_wrap(
        wrap_deg):
    theta = math.radians(wrap_deg)
    assert belt_radial_load(200.0, 0.0, theta) == pytest.approx(
        2.0 * 200.0 * math.sin(theta / 2.0), rel=1e-12)


def test_a_pulling_belt_keeps_2_pretension_at_180_deg_while_its_slack_strand_is_taut():
    # T_t = 200 + 50, T_s = 200 - 50: parallel strands sum to 400 N
    assert belt_radial_load(200.0, 100.0, math.pi) == pytest.approx(400.0, rel=1e-12)


def test_a_pulling_belt_at_90_deg_adds_its_strands_as_vectors():
    # T_t = 250, T_s = 150 at 90 deg apart: sqrt(250^2 + 150^2)
    assert belt_radial_load(200.0, 100.0, math.pi / 2) == pytest.approx(
        math.hypot(250.0, 150.0), rel=1e-12)


def test_a_belt_whose_slack_strand_goes_slack_is_pulled_by_its_tight_strand_alone():
    # F_e = 500 > 2 F_pre: T_s = 0, T_t = 500
    assert belt_radial_load(200.0, 500.0, math.radians(150.0)) == pytest.approx(500.0,
                                                                                 rel=1e-12)


def test_a_pinion_loads_the_shaft_with_its_tooth_force_over_cos_alpha():
    alpha = math.radians(20.0)
    f_t = 1000.0
    radial = f_t * math.tan(alpha)
    assert pinion_radial_load(-f_t, alpha) == pytest.approx(math.hypot(f_t, radial),
                                                            rel=1e-12)


# --- checks in a sizing ------------------------------------------------------------------

H = 0.2  # m
T = 0.5  # s
MASS = 5.0  # kg
C_A = 2.0 * math.pi  # cycloidal
PEAK_FORCE = MASS * C_A * H / T**2  # N at the load, no friction or gravity


def _motor(motor_id: str, **ratings) -> dict:
    return {"id": motor_id, "inertia": 0, "continuous_torque": "50 N*m",
            "peak_torque": "100 N*m", "rated_speed": "3000 rpm", **ratings}


def _design(stage: dict, motors: list[dict]) -> dict:
    return {"task": {"displacement": f"{H} m", "duration": f"{T} s"},
            "load": {"mass": f"{MASS} kg"}, "transmission": stage,
            "laws": ["cycloidal"], "motors": motors}


def _size(design: dict):
    return {r.motor_object.id: r for r in size_design(load_design_data(design)).results}


def test_a_pinion_on_the_bundled_sgmah_02a_against_its_cited_245_n():
    d = 0.04
    design = _design({"type": "rack_pinion", "pitch_diameter": f"{d} m",
                      "on_motor_shaft": True}, [])
    design["motors"] = "yaskawa-sgmah"
    row = _size(design)["SGMAH-02A"]
    check = row.check("shaft_radial")
    j_m = row.motor_object.inertia  # the catalog's rotor inertia, 0.106e-4 kg*m^2
    alpha_m = C_A * H / T**2 / (d / 2.0)  # the motor's peak angular acceleration
    tau = (j_m + MASS * (d / 2.0) ** 2) * alpha_m
    assert check.value == pytest.approx(tau / (d / 2.0) / math.cos(math.radians(20.0)),
                                        rel=1e-9)
    assert check.limit == 245.0 and check.unit == "N"  # Sigma II manual, Table 2.1
    assert check.margin == pytest.approx(1.0 - check.value / 245.0, rel=1e-12)


def test_a_belt_on_the_motor_shaft_with_its_pretension_and_pull():
    d = 0.05
    rows = _size(_design({"type": "belt", "driver_diameter": f"{d} m",
                          "on_motor_shaft": True, "pretension": "100 N",
                          "wrap_angle": "180 deg"},
                         [_motor("M", radial_load="245 N")]))
    check = rows["M"].check("shaft_radial")
    pull = PEAK_FORCE  # the belt carries the load: its pull is the load's force
    slack = max(100.0 - pull / 2.0, 0.0)
    assert check.value == pytest.approx(slack + pull + slack, rel=1e-9)
    assert check.margin == pytest.approx(1.0 - check.value / 245.0, rel=1e-9)


def test_a_directly_coupled_screw_loads_the_motor_axially():
    lead = 0.01
    rows = _size(_design({"type": "ball_screw", "lead": f"{lead} m",
                          "inertia": 0, "efficiency": 1, "on_motor_shaft": True},
                         [_motor("M", axial_load="74 N", radial_load="245 N")]))
    row = rows["M"]
    assert row.check("shaft_axial").value == pytest.approx(PEAK_FORCE, rel=1e-9)
    assert row.check("shaft_axial").limit == 74.0
    assert not any(c.name == "shaft_radial" for c in row.checks)  # a screw: no radial load


def test_a_motor_without_the_rating_has_no_check_and_the_design_says_so():
    design = _design({"type": "rack_pinion", "pitch_diameter": "40 mm",
                      "on_motor_shaft": True},
                     [_motor("RATED", radial_load="245 N"), _motor("BARE")])
    rows = _size(design)
    assert any(c.name == "shaft_radial" for c in rows["RATED"].checks)
    assert not any(c.name == "shaft_radial" for c in rows["BARE"].checks)
    from sizer.sizing.checks import shaft_notes

    loaded = load_design_data(design)
    notes = shaft_notes(loaded.motors, loaded.transmission)
    assert notes == ["no shaft_radial check for BARE: the catalog gives no radial_load"]
    assert notes[0] in api.size(design).notes  # the results say which motors have no check


def test_no_stage_on_the_motor_shaft_no_check():
    rows = _size(_design({"type": "rack_pinion", "pitch_diameter": "40 mm"},
                         [_motor("M", radial_load="1 N")]))
    assert not any(c.name.startswith("shaft_") for c in rows["M"].checks)


def test_minimize_stops_where_the_pinion_meets_the_rating():
    # m C_a h / T^2 / cos(alpha) = 100 N: T = sqrt(m C_a h / (100 cos alpha))
    design = _design({"type": "rack_pinion", "pitch_diameter": "40 mm",
                      "on_motor_shaft": True},
                     [_motor("M", radial_load="100 N", rated_speed="30000 rpm")])
    design["task"]["duration"] = "minimize"
    row = _size(design)["M"]
    expected = math.sqrt(MASS * C_A * H / (100.0 * math.cos(math.radians(20.0))))
    assert row.duration == pytest.approx(expected, rel=1e-9)
    assert row.limiting == "shaft_radial"


def test_a_pretension_above_the_rating_fails_at_every_duration():
    design = _design({"type": "belt", "driver_diameter": "40 mm", "on_motor_shaft": True,
                      "pretension": "100 N"}, [_motor("M", radial_load="150 N")])
    design["task"]["duration"] = "minimize"
    row = _size(design)["M"]
    assert not row.feasible and row.limiting == "shaft_radial"
    assert row.check("shaft_radial").value == pytest.approx(200.0, rel=1e-12)  # 2 F_pre


def test_a_requirement_equal_to_the_rating_passes_and_one_just_above_fails():
    d = 0.04
    f_t = PEAK_FORCE
    rating = f_t / math.cos(math.radians(20.0))  # the pinion's load exactly
    for factor, passes in ((1.0, True), (1.0 - 1e-6, False)):
        rows = _size(_design({"type": "rack_pinion", "pitch_diameter": f"{d} m",
                              "on_motor_shaft": True},
                             [_motor("M", radial_load=f"{rating * factor!r} N")]))
        check = rows["M"].check("shaft_radial")
        assert check.passed is passes
        if passes:
            assert check.margin >= -TOLERANCE
        assert rows["M"].feasible is passes


def test_the_bundled_sgmah_ratings_load_with_their_source():
    design = {"task": {"displacement": "90 deg", "duration": "1 s"},
              "load": {"inertia": "1e-4 kg*m^2"}, "laws": ["cycloidal"],
              "motors": "yaskawa-sgmah"}
    motors = {m.id: m for m in load_design_data(design).motors}
    assert (motors["SGMAH-02A"].radial_load, motors["SGMAH-02A"].axial_load) == (245.0, 74.0)
    assert motors["SGMAH-08A"].radial_load_point == pytest.approx(0.035)
    assert motors["SGMAH-02A"].provenance is not None


@pytest.mark.parametrize("stage, field", [
    ({"type": "belt", "driver_diameter": "50 mm", "on_motor_shaft": True}, "pretension"),
    ({"type": "belt", "driver_diameter": "50 mm", "pretension": "100 N"}, "on_motor_shaft"),
    ({"type": "rack_pinion", "pitch_diameter": "40 mm", "pressure_angle": "20 deg"},
     "on_motor_shaft"),
])
def test_a_stage_on_the_motor_shaft_names_what_it_misses(stage, field):
    with pytest.raises(UserError) as caught:
        load_design_data(_design(stage, [_motor("M")]))
    assert field in str(caught.value) + str(caught.value.field)


def test_a_stage_on_the_motor_shaft_is_the_first():
    stages = [{"type": "gearbox", "ratio": 2},
              {"type": "rack_pinion", "pitch_diameter": "40 mm", "on_motor_shaft": True}]
    with pytest.raises(UserError, match="first stage"):
        load_design_data(_design(stages, [_motor("M")]))


def test_forces_are_arrays_over_candidates():
    out = belt_radial_load(100.0, np.array([0.0, 100.0, 400.0]), math.pi)
    assert out == pytest.approx([200.0, 200.0, 400.0], rel=1e-12)


# --- bad fields, located (FIELD_CASES: for tests/test_bad_inputs_fields.py's walk) -----

import yaml  # noqa: E402
from bad_input_cases import Case  # noqa: E402
from bad_input_cases import run_case as run  # noqa: E402
from test_bad_inputs_catalogs import C, M, bad_motor  # noqa: E402


def _bad_stage(id: str, stage: dict, words: tuple[str, ...], fields: tuple[str, ...]) -> Case:
    text = yaml.safe_dump(_design(stage, [_motor("M", radial_load="245 N")]))
    return Case(id, design=text, words=("design.yaml:", *words), fields=fields)


B = {"type": "belt", "driver_diameter": "50 mm", "on_motor_shaft": True,
     "pretension": "100 N"}
P = {"type": "rack_pinion", "pitch_diameter": "40 mm", "on_motor_shaft": True}
FIELD_CASES = [
    bad_motor("radial-load-a-torque", {f"{M}.radial_load": "5 N*m"},
              (f"{M}.radial_load",), (f"{C}.radial_load",)),
    bad_motor("axial-load-negative", {f"{M}.axial_load": "-5 N"},
              (f"{M}.axial_load", "[0.001, 1e7] N"), (f"{C}.axial_load",)),
    bad_motor("radial-load-point-1-km", {f"{M}.radial_load_point": "1 km"},
              (f"{M}.radial_load_point", "[1e-4, 10] m"), (f"{C}.radial_load_point",)),
    _bad_stage("belt-pretension-a-torque", {**B, "pretension": "5 N*m"},
               ("transmission.pretension",), ("transmission[belt].pretension",)),
    _bad_stage("belt-wrap-over-a-turn", {**B, "wrap_angle": "400 deg"},
               ("transmission.wrap_angle", "6.28319] rad"), ("transmission[belt].wrap_angle",)),
    _bad_stage("belt-on-shaft-not-a-bool", {**B, "on_motor_shaft": "maybe"},
               ("transmission.on_motor_shaft",), ("transmission[belt].on_motor_shaft",)),
    _bad_stage("pinion-pressure-angle-90-deg", {**P, "pressure_angle": "90 deg"},
               ("transmission.pressure_angle", "[0.001, 1] rad"),
               ("transmission[rack_pinion].pressure_angle",)),
    _bad_stage("pinion-on-shaft-not-a-bool", {**P, "on_motor_shaft": "maybe"},
               ("transmission.on_motor_shaft",), ("transmission[rack_pinion].on_motor_shaft",)),
    _bad_stage("screw-on-shaft-not-a-bool",
               {"type": "ball_screw", "lead": "10 mm", "inertia": 0, "on_motor_shaft": "maybe"},
               ("transmission.on_motor_shaft",), ("transmission[ball_screw].on_motor_shaft",)),
]
"""A bad value of every field of the shaft loads, located (file, line, field)."""


@pytest.mark.parametrize("case", FIELD_CASES, ids=str)
def test_bad_shaft_load_field(case, tmp_path):
    run(case, tmp_path)
