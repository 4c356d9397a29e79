"""Loads on a gearbox's output shaft (issue 38, docs/shaft-loads.md): a pinion, a belt's
driver pulley or a ball screw on the output shaft of the gearbox right before it
(``on_gearbox_output: true``), against the gearbox's ``output_radial_load`` and
``output_axial_load``. The forces by hand from the gearbox's peak output torque (itself by
hand: a cycloidal move, peak acceleration C_a h / T^2, of a mass and a pinion's inertia);
the bundled catalogs' figures as the Beckhoff pages print them."""

from __future__ import annotations

import math

import pytest
import yaml
from bad_input_cases import Case
from bad_input_cases import run_case as run
from test_bad_inputs_catalogs import bad_gears

from sizer.errors import UserError
from sizer.io.loader import load_design_data
from sizer.io.transmission import bundled_gearbox_catalogs, load_gearbox_catalog
from sizer.sizing.checks import TOLERANCE, shaft_notes
from sizer.sizing.engine import size_design

H = 0.2  # m
T = 0.5  # s
MASS = 5.0  # kg
C_A = 2.0 * math.pi  # cycloidal
ACCELERATION = C_A * H / T**2  # the load's peak acceleration (m/s^2)
D = 0.04  # the pinion's pitch diameter (m)
J_PINION = 1e-4  # kg*m^2, at the gearbox's output
ALPHA = math.radians(20.0)
# the gearbox's output torque: the load's force at the pinion plus the pinion's own
# inertia torque, both peaking with the acceleration (no friction, efficiency 1)
OUTPUT_TORQUE = (MASS * D / 2.0 + J_PINION / (D / 2.0)) * ACCELERATION
PINION_LOAD = OUTPUT_TORQUE / (D / 2.0) / math.cos(ALPHA)  # F_t / cos(alpha)


def _motor(motor_id: str = "M", **ratings) -> dict:
    return {"id": motor_id, "inertia": "0.2 kg*cm^2", "continuous_torque": "50 N*m",
            "peak_torque": "100 N*m", "rated_speed": "30000 rpm", **ratings}


def _gearbox(**fields) -> dict:
    return {"type": "gearbox", "ratio": 5, "inertia": "1 kg*cm^2",
            "peak_output_torque": "100 N*m", **fields}


def _pinion(**fields) -> dict:
    return {"type": "rack_pinion", "pitch_diameter": f"{D} m",
            "inertia": f"{J_PINION} kg*m^2", "on_gearbox_output": True, **fields}


def _design(stages: list[dict], motors: list[dict] | None = None) -> dict:
    return {"task": {"displacement": f"{H} m", "duration": f"{T} s"},
            "load": {"mass": f"{MASS} kg"}, "transmission": stages,
            "laws": ["cycloidal"], "motors": motors or [_motor()]}


def _rows(design: dict):
    return size_design(load_design_data(design)).results


def _check(row, name: str):
    found = [c for c in row.checks if c.name == name]
    return found[0] if found else None


# --- the force at the gearbox's output torque ---------------------------------------


def test_a_pinion_on_the_gearbox_output_is_loaded_by_the_gearbox_output_torque():
    row = _rows(_design([_gearbox(output_radial_load="100 N"), _pinion()]))[0]
    check = _check(row, "gearbox_radial")
    assert check.value == pytest.approx(PINION_LOAD, rel=1e-9)
    assert check.limit == 100.0 and check.unit == "N"
    assert check.margin == pytest.approx(1.0 - PINION_LOAD / 100.0, rel=1e-9)
    # the engine's peak stage output torque is the same torque
    assert _check(row, "gearbox_peak").value == pytest.approx(OUTPUT_TORQUE, rel=1e-9)
    assert _check(row, "shaft_radial") is None  # nothing on the motor's shaft


def test_a_belt_on_the_gearbox_output_pulls_with_the_gearbox_output_torque():
    d = 0.05
    stages = [_gearbox(output_radial_load="500 N"),
              {"type": "belt", "driver_diameter": f"{d} m", "on_gearbox_output": True,
               "pretension": "5 N"}]
    row = _rows(_design(stages))[0]
    pull = MASS * ACCELERATION  # the belt carries the load: F_e = tau / (d/2) = m a
    assert pull > 2 * 5.0  # the slack strand goes slack: at 180 deg F_r = T_t = F_e
    assert _check(row, "gearbox_radial").value == pytest.approx(pull, rel=1e-9)


def test_a_screw_on_the_gearbox_output_loads_it_axially_with_the_load_force():
    stages = [_gearbox(output_axial_load="2119 N", output_radial_load="10 N"),
              {"type": "ball_screw", "lead": "10 mm", "inertia": 0, "efficiency": 1,
               "on_gearbox_output": True}]
    row = _rows(_design(stages))[0]
    assert _check(row, "gearbox_axial").value == pytest.approx(MASS * ACCELERATION,
                                                               rel=1e-9)
    assert _check(row, "gearbox_radial") is None  # a screw: no radial load


def test_equal_to_the_rating_passes_and_just_above_fails():
    for factor, passes in ((1.0, True), (1.0 - 1e-6, False)):
        rating = PINION_LOAD * factor
        row = _rows(_design([_gearbox(output_radial_load=f"{rating!r} N"), _pinion()]))[0]
        check = _check(row, "gearbox_radial")
        assert check.passed is passes
        if passes:
            assert check.margin >= -TOLERANCE
        assert row.feasible is passes


# --- the catalogs' ratings ----------------------------------------------------------


def _catalog(name: str) -> dict:
    options = load_gearbox_catalog(bundled_gearbox_catalogs()[name])
    return {o.gearbox.split(" i=")[0]: o for o in options}


def test_the_ple_catalog_gives_f2rmax_and_fastat_with_their_source():
    ple = _catalog("beckhoff-ag2250-ple")
    # PLE060 technical data: F2RMax 800 N, FaStat 700 N; PLE160: 11000 N, 5000 N
    assert (ple["PLE060"].stage.output_radial_load, ple["PLE060"].stage.output_axial_load) \
        == (800.0, 700.0)
    assert (ple["PLE160"].stage.output_radial_load, ple["PLE160"].stage.output_axial_load) \
        == (11000.0, 5000.0)
    source = ple["PLE060"].provenance.of("output_radial_load")
    assert source.grade == "A" and "PLE060 technical data" in source.text


def test_the_tp_and_npt_catalogs_give_f2amax_and_no_radial_force():
    tp, npt = _catalog("beckhoff-ag2400-tp"), _catalog("beckhoff-ag3400-npt")
    assert tp["TP004-MF-E19"].stage.output_axial_load == 2119.0
    assert tp["TP004-MF-E19"].stage.output_radial_load is None
    assert npt["NPT035-MF-K38"].stage.output_axial_load == 3500.0
    assert npt["NPT045-MF-1stage-K38"].stage.output_axial_load is None  # not read
    assert tp["TP004-MF-E19"].provenance.of("output_axial_load").grade == "A"


def test_a_catalog_gearbox_checks_each_candidate_against_its_own_rating():
    design = _design([{"type": "gearbox", "catalog": "beckhoff-ag2250-ple"}, _pinion()])
    rows = _rows(design)
    ratings = {"PLE040": 240.0, "PLE060": 800.0, "PLE080": 1600.0, "PLE160": 11000.0}
    seen = set()
    for row in rows:
        series = row.gearbox.split(" i=")[0]
        check = _check(row, "gearbox_radial")
        assert check.limit == ratings[series]
        seen.add(series)
    assert seen  # the rows have the check


# --- no rating, no check ------------------------------------------------------------


def test_no_rating_no_check_and_a_note():
    design = _design([_gearbox(name="reducer"), _pinion()])
    row = _rows(design)[0]
    assert _check(row, "gearbox_radial") is None
    loaded = load_design_data(design)
    notes = shaft_notes(loaded.motors, loaded.transmission)
    assert notes == ["no gearbox_radial check for reducer: its ratings give no "
                     "output_radial_load",
                     # and its bearing life (tests/test_gearbox_output_life.py)
                     "no gearbox_radial_life check for reducer: its ratings give no "
                     "output_radial_load_life"]
    assert set(notes) <= set(size_design(loaded).notes)


def test_a_catalog_without_radial_forces_is_named_in_the_note():
    design = _design([{"type": "gearbox", "catalog": "beckhoff-ag2400-tp"}, _pinion()])
    loaded = load_design_data(design)
    assert all(_check(r, "gearbox_radial") is None for r in _rows(design))
    notes = shaft_notes(loaded.motors, loaded.transmission, loaded.ratio_choice)
    assert len(notes) == 2 and notes[0].startswith("no gearbox_radial check for TP004-MF-E19")
    assert notes[1].startswith("no gearbox_radial_life check for TP004-MF-E19")
    assert notes[0] in size_design(loaded).notes  # the results name the catalog's gearboxes


def test_without_a_torque_rating_the_output_torque_is_not_computed_and_the_note_says_so():
    stages = [{"type": "gearbox", "ratio": 5, "output_radial_load": "100 N"}, _pinion()]
    design = _design(stages)
    assert _check(_rows(design)[0], "gearbox_radial") is None
    loaded = load_design_data(design)
    assert "torque rating" in shaft_notes(loaded.motors, loaded.transmission)[0]


def test_on_motor_shaft_is_unchanged_beside_a_gearbox_output_load():
    stages = [{"type": "belt", "ratio": 2, "driver_diameter": "40 mm",
               "driven_diameter": "80 mm", "on_motor_shaft": True, "pretension": "50 N"},
              _gearbox(output_radial_load="1000 N"), _pinion()]
    row = _rows(_design(stages, [_motor(radial_load="1000 N")]))[0]
    assert _check(row, "shaft_radial").value == pytest.approx(100.0, rel=1e-9)  # 2 F_pre
    assert _check(row, "gearbox_radial").value == pytest.approx(PINION_LOAD, rel=1e-9)


# --- user errors --------------------------------------------------------------------


@pytest.mark.parametrize("stages, words", [
    ([_pinion()], "right after a gearbox"),
    ([{"type": "gearbox", "ratio": 2}, {"type": "belt", "ratio": 2},
      {"type": "rack_pinion", "pitch_diameter": "40 mm", "on_gearbox_output": True}],
     "right after a gearbox"),
    ([_gearbox(), _pinion(on_motor_shaft=True)], "not both"),
    ([_gearbox(), {"type": "belt", "driver_diameter": "50 mm", "on_gearbox_output": True}],
     "pretension"),
    ([_gearbox(), {"type": "ball_screw", "lead": "10 mm", "inertia": 0,
                   "on_gearbox_output": True}, _pinion(on_gearbox_output=False)],
     "last stage"),
])
def test_a_misplaced_or_incomplete_stage_is_refused(stages, words):
    with pytest.raises(UserError, match=words):
        load_design_data(_design(stages))


def _bad(id: str, stages: list[dict], words: tuple[str, ...], fields: tuple[str, ...]) -> Case:
    return Case(id, design=yaml.safe_dump(_design(stages)), words=("design.yaml:", *words),
                fields=fields)


FIELD_CASES = [
    _bad("gearbox-output-radial-a-torque", [_gearbox(output_radial_load="5 N*m"), _pinion()],
         ("transmission[0].output_radial_load",),
         ("transmission[gearbox].output_radial_load",)),
    _bad("gearbox-output-axial-negative", [_gearbox(output_axial_load="-5 N"), _pinion()],
         ("transmission[0].output_axial_load", "[0.001, 1e7] N"),
         ("transmission[gearbox].output_axial_load",)),
    _bad("pinion-on-gearbox-output-not-a-bool", [_gearbox(), _pinion(on_gearbox_output="x")],
         ("transmission[1].on_gearbox_output",),
         ("transmission[rack_pinion].on_gearbox_output",)),
    _bad("belt-on-gearbox-output-not-a-bool",
         [_gearbox(), {"type": "belt", "driver_diameter": "50 mm", "on_gearbox_output": "x"}],
         ("transmission[1].on_gearbox_output",), ("transmission[belt].on_gearbox_output",)),
    _bad("screw-on-gearbox-output-not-a-bool",
         [_gearbox(), {"type": "ball_screw", "lead": "10 mm", "inertia": 0,
                       "on_gearbox_output": "x"}],
         ("transmission[1].on_gearbox_output",),
         ("transmission[ball_screw].on_gearbox_output",)),
    bad_gears("gears-output-radial-a-length", {"gearboxes[0].output_radial_load": "5 mm"},
              ("gearboxes[0].output_radial_load",),
              ("gearboxes:gearboxes.output_radial_load",)),
    bad_gears("gears-output-axial-zero", {"gearboxes[0].output_axial_load": "0 N"},
              ("gearboxes[0].output_axial_load", "[0.001, 1e7] N"),
              ("gearboxes:gearboxes.output_axial_load",)),
]
"""A bad value of every field of the gearbox output loads, located (file, line, field)."""


@pytest.mark.parametrize("case", FIELD_CASES, ids=str)
def test_bad_gearbox_output_load_field(case, tmp_path):
    run(case, tmp_path)


def test_minimize_stops_where_the_pinion_meets_the_gearbox_rating():
    # the load scales as 1/T^2: PINION_LOAD (T/T_min)^2 = rating
    rating = 50.0
    design = _design([_gearbox(output_radial_load=f"{rating} N"), _pinion()])
    design["task"]["duration"] = "minimize"
    row = _rows(design)[0]
    assert row.duration == pytest.approx(T * math.sqrt(PINION_LOAD / rating), rel=1e-9)
    assert row.limiting == "gearbox_radial"
