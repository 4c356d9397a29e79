"""Transmission stages, free ratios, gearbox catalogs and linear loads in design files."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from sizer.errors import UserError
from sizer.io import load_design
from sizer.mechanics import GRAVITY, screw_inertia

HEAD = "task: {displacement: 200 mm, duration: 0.5 s}\nload: {mass: 5 kg}\n"
ROTARY = "task: {displacement: 90 deg, duration: 0.5 s}\nload: {inertia: 0.2 kg*m^2}\n"

GEARBOXES = """\
catalog: Illustrative planetary gearboxes (test data, not a product)
gearboxes:
  - id: PG60
    efficiency: 96 %
    max_input_speed: 6000 rpm
    rated_output_torque: 20 N*m
    peak_output_torque: 40 N*m
    backlash: 10 arcmin
    ratios:
      - {ratio: 5, inertia: 0.2 kg*cm^2}
      - {ratio: 10, inertia: 0.15 kg*cm^2, efficiency: 94 %}
  - id: PG90
    efficiency: 0.95
    ratios:
      - {ratio: 20, inertia: 0.5 kg*cm^2, peak_output_torque: 120 N*m}
"""


def load(tmp_path: Path, text: str, name: str = "design.yaml"):
    path = tmp_path / name
    path.write_text(text)
    return load_design(path)


def error(tmp_path: Path, text: str) -> UserError:
    with pytest.raises(UserError) as info:
        load(tmp_path, text)
    return info.value


def test_ball_screw_from_diameter_and_length(tmp_path):
    design = load(tmp_path, HEAD + "transmission: {type: ball_screw, lead: 10 mm, "
                  "diameter: 16 mm, length: 500 mm, efficiency: 90 %, "
                  "preload_torque: 0.02 N*m, max_speed: 3000 rpm}\n")
    (stage,) = design.transmission.stages
    assert stage.ratio == pytest.approx(2 * math.pi / 0.01)
    assert stage.inertia == pytest.approx(screw_inertia(0.016, 0.5))
    assert stage.preload_torque == pytest.approx(0.02)
    assert stage.max_input_speed == pytest.approx(100 * math.pi)
    assert stage.efficiency == pytest.approx(0.9)


def test_gearbox_then_linear_belt_and_rack(tmp_path):
    design = load(tmp_path, HEAD + "transmission:\n"
                  "  - {type: gearbox, ratio: 5, inertia: 0.1 kg*cm^2, "
                  "rated_output_torque: 10 N*m}\n"
                  "  - {type: belt, driver_diameter: 50 mm, driver_inertia: 1 kg*cm^2, "
                  "driven_inertia: 1 kg*cm^2, belt_mass: 0.3 kg, efficiency: 0.95}\n")
    gear, belt = design.transmission.stages
    assert gear.rated_output_torque == 10.0
    assert belt.ratio == pytest.approx(40.0)  # 2/d rad/m: the load rides on the belt
    assert belt.inertia == pytest.approx(2e-4 + 0.3 * 0.025**2)
    rack = load(tmp_path, HEAD + "transmission: {type: rack_pinion, pitch_diameter: 60 mm}\n")
    assert rack.transmission.stages[0].ratio == pytest.approx(1 / 0.03)


def test_rotary_belt_from_diameters(tmp_path):
    design = load(tmp_path, ROTARY + "transmission: {type: belt, driver_diameter: 40 mm, "
                  "driven_diameter: 120 mm}\n")
    assert design.transmission.ratio == pytest.approx(3.0)


def test_linear_load_with_incline_and_friction_coefficient(tmp_path):
    design = load(tmp_path, "task: {displacement: 200 mm, duration: 0.5 s}\n"
                  "load: {mass: 5 kg, incline: 90 deg, friction_coefficient: 0.1, "
                  "friction: 2 N}\ntransmission: {type: ball_screw, lead: 10 mm, inertia: 0}\n")
    assert design.load.torque == pytest.approx(5 * GRAVITY)  # held at rest: vertical
    assert design.load.friction == pytest.approx(2.0, abs=1e-12)  # cos 90 deg = 0
    slope = load(tmp_path, "task: {displacement: 200 mm, duration: 0.5 s}\n"
                 "load: {mass: 5 kg, incline: 30 deg, friction_coefficient: 0.1}\n"
                 "transmission: {type: ball_screw, lead: 10 mm, inertia: 0}\n")
    assert slope.load.friction == pytest.approx(0.1 * 5 * GRAVITY * math.cos(math.pi / 6))


@pytest.mark.parametrize(("ratio", "expected"), [
    ("[3, 5, 10]", {"ratios": (3.0, 5.0, 10.0)}),
    ("optimize", {"bounds": (1.0, 100.0)}),
    ("{optimize: [2, 50]}", {"bounds": (2.0, 50.0)}),
])
def test_free_ratio_forms(tmp_path, ratio, expected):
    design = load(tmp_path, ROTARY + f"transmission: {{type: gearbox, ratio: {ratio}}}\n")
    choice = design.ratio_choice
    assert choice is not None and choice.stage == 0
    for key, value in expected.items():
        assert getattr(choice, key) == value


def test_gearbox_catalog_gives_the_options(tmp_path):
    (tmp_path / "gearboxes.yaml").write_text(GEARBOXES)
    design = load(tmp_path, ROTARY + "transmission:\n  - {type: direct}\n"
                  "  - {type: gearbox, catalog: gearboxes.yaml}\n")
    options = design.ratio_choice.gearboxes
    assert [o.gearbox for o in options] == ["PG60 i=5", "PG60 i=10", "PG90 i=20"]
    assert options[1].stage.efficiency == pytest.approx(0.94)  # per-ratio figure wins
    assert options[0].stage.max_input_speed == pytest.approx(200 * math.pi)
    assert options[0].stage.inertia == pytest.approx(0.2e-4)
    assert options[2].stage.peak_output_torque == 120.0
    assert options[2].stage.rated_output_torque is None


def line(text: str, needle: str) -> int:
    return next(i for i, row in enumerate(text.splitlines(), 1) if needle in row)


@pytest.mark.parametrize(("text", "needle", "field", "message"), [
    (ROTARY + "transmission: {type: gearbox, ratio: 0}\n", "ratio: 0", "transmission.ratio",
     "must be in [0.001, 1e5]"),
    (ROTARY + "transmission: {type: gearbox, ratio: -3}\n", "ratio: -3", "transmission.ratio",
     "must be in [0.001, 1e5]"),
    (ROTARY + "transmission: {type: gearbox, ratio: 5, efficiency: 1.2}\n", "efficiency",
     "transmission.efficiency", "must be in [0.01, 1]"),
    (ROTARY + "transmission: {type: gearbox, ratio: 5, efficiency: 0}\n", "efficiency",
     "transmission.efficiency", "must be in [0.01, 1]"),
    (HEAD + "transmission: {type: ball_screw, lead: 0 mm, inertia: 0}\n", "lead",
     "transmission.lead", "must be in [1e-5, 2] m"),
    (HEAD + "transmission: {type: ball_screw, lead: 10 mm}\n", "ball_screw",
     "transmission", "needs its inertia, or its diameter and length"),
    (HEAD + "transmission: {type: gearbox, ratio: 10}\n", "gearbox", "transmission.type",
     "needs a last stage that turns rotation into travel"),
    (ROTARY + "transmission: {type: ball_screw, lead: 10 mm, inertia: 0}\n", "ball_screw",
     "transmission.type", "the displacement is an angle"),
    ("task: {displacement: 200 mm, duration: 1 s}\nload: {inertia: 0.2 kg*m^2}\n", "inertia",
     "load.inertia", "takes 'mass', not 'inertia'"),
    (ROTARY + "transmission:\n  - {type: gearbox, ratio: optimize}\n"
     "  - {type: belt, ratio: [2, 3]}\n", "belt", "transmission[1]",
     "only one stage may have a free ratio"),
    (ROTARY + "transmission: {type: gearbox, ratio: {optimize: [5, 2]}}\n", "optimize",
     "transmission.ratio", "min < max"),
    (ROTARY + "transmission: {type: gearbox, catalog: none.yaml}\n", "catalog",
     "transmission.catalog", "no gearbox catalog file"),
    (ROTARY.replace("inertia: 0.2 kg*m^2", "inertia: 0.2 kg*m^2, incline: 10 deg"), "incline",
     "load.incline", "for linear axes"),
])
def test_bad_transmissions(tmp_path, text, needle, field, message):
    found = error(tmp_path, text)
    assert message in found.message
    assert found.field == field
    assert found.line == line(text, needle)


# ------------------------------------------------- vendor conventions (issue 9)
def test_ball_screw_density_with_units(tmp_path):
    design = load(tmp_path, HEAD + "transmission: {type: ball_screw, lead: 10 mm, "
                  "diameter: 20 mm, length: 1 m, density: 7.87 g/cm^3}\n")
    (stage,) = design.transmission.stages
    assert stage.inertia == pytest.approx(screw_inertia(0.02, 1.0, 7870.0), rel=1e-12)
    default = load(tmp_path, HEAD + "transmission: {type: ball_screw, lead: 10 mm, "
                   "diameter: 20 mm, length: 1 m}\n")
    assert default.transmission.stages[0].inertia == pytest.approx(
        screw_inertia(0.02, 1.0, 7850.0), rel=1e-12)
    bad = error(tmp_path, HEAD + "transmission: {type: ball_screw, lead: 10 mm, "
                "diameter: 20 mm, length: 1 m, density: 7.8 kg}\n")
    assert bad.field == "transmission.density" and "density" in bad.message


@pytest.mark.parametrize(("given", "expected"), [
    (None, "power_flow"), ("power_flow", "power_flow"), ("steady_load", "steady_load"),
    ("siemens", "power_flow"), ("Mitsubishi", "power_flow"), ("yaskawa", "steady_load")])
def test_efficiency_convention_by_name_or_vendor(tmp_path, given, expected):
    text = HEAD + "transmission: {type: ball_screw, lead: 10 mm, inertia: 1e-5}\n"
    if given is not None:
        text += f"efficiency_applies_to: {given}\n"
    assert load(tmp_path, text).transmission.efficiency_applies_to == expected


def test_unknown_efficiency_convention_is_a_user_error(tmp_path):
    bad = error(tmp_path, ROTARY + "efficiency_applies_to: whole_torque\n")
    assert bad.field == "efficiency_applies_to" and bad.line == 3
    assert "power_flow" in bad.message and "steady_load" in bad.message


def test_inertia_ratio_of_in_limits(tmp_path):
    design = load(tmp_path, ROTARY + "limits: {inertia_ratio: 5, inertia_ratio_of: load}\n")
    assert design.limits.inertia_ratio_of == "load"
    assert load(tmp_path, ROTARY).limits.inertia_ratio_of == "driven"
    bad = error(tmp_path, ROTARY + "limits: {inertia_ratio_of: rotor}\n")
    assert bad.field == "limits.inertia_ratio_of"


def test_negative_displacement_is_accepted(tmp_path):
    design = load(tmp_path, "task: {displacement: -200 mm, duration: 0.5 s}\n"
                  "load: {mass: 5 kg}\ntransmission: {type: ball_screw, lead: 10 mm, "
                  "inertia: 1e-5}\n")
    assert design.task.displacement == pytest.approx(-0.2) and design.task.linear
    zero = error(tmp_path, "task: {displacement: 0 deg, duration: 0.5 s}\n"
                 "load: {inertia: 1}\n")
    assert zero.field == "task.displacement" and "must not be zero" in zero.message
