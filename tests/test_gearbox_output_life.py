"""The gearbox output bearings' life check (issue 38, docs/shaft-loads.md): the cycle's
equivalent force on the gearbox's output, F_eq = (int |n_2| F^3 dt / int |n_2| dt)^(1/3)
(Stober's "equivalent values"), against the force the gearbox's maker rates for a bearing
life (Beckhoff's "radial force ... for 20000 h").

The reference F_eq is computed here, apart from sizer: the cycloidal law in closed form,
the gearbox's output torque by hand (the belt's pulleys and the load's inertia, efficiency
1), the belt's radial load by the sharing rule of docs/shaft-loads.md written with numpy,
and the integrals by scipy's adaptive quadrature, broken at the kinks (where the slack
strand goes slack, where the acceleration changes sign)."""

from __future__ import annotations

import json
import math

import pytest
import yaml
from bad_input_cases import Case
from bad_input_cases import run_case as run
from cli_run import run_cli
from scipy.integrate import quad
from test_bad_inputs_catalogs import bad_gears

from sizer.io.loader import load_design_data
from sizer.io.transmission import bundled_gearbox_catalogs, load_gearbox_catalog
from sizer.sizing.checks import TOLERANCE
from sizer.sizing.engine import size_design

H = 3.0  # rad, the load's move
T = 0.4  # s
DWELL = 0.3  # s: the shaft does not turn, it adds nothing
J_LOAD = 0.05  # kg*m^2
K_GEAR = 5.0
D_DRIVER, D_DRIVEN = 0.04, 0.08  # m: the belt's pulleys on the gearbox output and the load
K_BELT = D_DRIVEN / D_DRIVER
J_DRIVER, J_DRIVEN = 2e-5, 1e-4  # kg*m^2
PRETENSION = 30.0  # N per strand
WRAP = math.radians(160.0)
# the gearbox's output torque per unit of the load's acceleration: the belt's pulleys
# reflected to the driver (J_driver + J_driven / k^2) at the driver's acceleration k alpha,
# plus the load's torque J alpha through the belt (k)
TORQUE_PER_ACCELERATION = (J_DRIVER + J_DRIVEN / K_BELT**2) * K_BELT + J_LOAD / K_BELT


def _law(t: float, duration: float) -> tuple[float, float]:
    """The cycloidal law's speed and acceleration at t (closed forms)."""
    u = t / duration
    speed = H / duration * (1.0 - math.cos(2.0 * math.pi * u))
    acceleration = 2.0 * math.pi * H / duration**2 * math.sin(2.0 * math.pi * u)
    return speed, acceleration


def _belt_radial(torque: float) -> float:
    """The belt's radial load on the driver pulley's shaft: the pull F_e = tau / (d/2)
    raises the tight strand and lowers the slack one by F_e/2, the slack one no lower than
    0, and the strands' vector sum over the wrap angle (docs/shaft-loads.md)."""
    pull = abs(torque) / (D_DRIVER / 2.0)
    slack = max(PRETENSION - pull / 2.0, 0.0)
    tight = slack + pull
    return math.sqrt(tight**2 + slack**2 - 2.0 * tight * slack * math.cos(WRAP))


def reference_equivalent_force(duration: float = T) -> float:
    """F_eq over one cycle (move and dwell) by quadrature: n_2 = k_belt * omega (the belt's
    ratio cancels), the dwell adds nothing."""
    peak = 2.0 * math.pi * H / duration**2
    # where the slack strand goes slack: |tau| / (d/2) = 2 F_pre
    c = 2.0 * PRETENSION * (D_DRIVER / 2.0) / (TORQUE_PER_ACCELERATION * peak)
    assert 0.0 < c < 1.0  # both regimes are crossed
    x = math.asin(c) / (2.0 * math.pi)
    points = [x * duration, (0.5 - x) * duration, 0.5 * duration, (0.5 + x) * duration,
              (1.0 - x) * duration]

    def weighted_cube(t: float) -> float:
        speed, acceleration = _law(t, duration)
        return K_BELT * abs(speed) * _belt_radial(TORQUE_PER_ACCELERATION * acceleration)**3

    def weight(t: float) -> float:
        return K_BELT * abs(_law(t, duration)[0])

    cube, _ = quad(weighted_cube, 0.0, duration, points=points, epsabs=0.0, epsrel=1e-13,
                   limit=200)
    revolutions, _ = quad(weight, 0.0, duration, epsabs=0.0, epsrel=1e-13)
    assert revolutions == pytest.approx(K_BELT * H, rel=1e-12)
    return (cube / revolutions) ** (1.0 / 3.0)


REL = 1e-6
"""The engine integrates by the trapezoidal rule on its own samples of the cycle (1001 per
move, sizer.sizing.evaluation.SAMPLES): an error O(dt^2) ~ 1e-6 of the integrals, less in
the cube root (1/3 of the relative error); the reference is exact to ~1e-13."""


def _motor() -> dict:
    return {"id": "M", "inertia": "0.2 kg*cm^2", "continuous_torque": "50 N*m",
            "peak_torque": "100 N*m", "rated_speed": "30000 rpm"}


def _gearbox(**fields) -> dict:
    return {"type": "gearbox", "ratio": K_GEAR, "inertia": "1 kg*cm^2",
            "peak_output_torque": "100 N*m", **fields}


def _belt(**fields) -> dict:
    return {"type": "belt", "driver_diameter": f"{D_DRIVER} m",
            "driven_diameter": f"{D_DRIVEN} m", "driver_inertia": f"{J_DRIVER} kg*m^2",
            "driven_inertia": f"{J_DRIVEN} kg*m^2", "on_gearbox_output": True,
            "pretension": f"{PRETENSION} N", "wrap_angle": "160 deg", **fields}


def _rated(force: float | str) -> dict:
    text = force if isinstance(force, str) else f"{force!r} N"
    return {"output_radial_load_life": text, "output_load_life": "20000 h"}


def _design(stages: list[dict], duration: str = f"{T} s") -> dict:
    return {"task": {"displacement": f"{H} rad", "duration": duration,
                     "dwell": f"{DWELL} s"},
            "load": {"inertia": f"{J_LOAD} kg*m^2"}, "transmission": stages,
            "laws": ["cycloidal"], "motors": [_motor()]}


def _result(design: dict):
    return size_design(load_design_data(design))


def _check(row, name: str):
    found = [c for c in row.checks if c.name == name]
    return found[0] if found else None


F_EQ = reference_equivalent_force()


def test_the_value_is_the_cycle_equivalent_force():
    row = _result(_design([_gearbox(**_rated(1000.0)), _belt()])).results[0]
    check = _check(row, "gearbox_radial_life")
    assert check.value == pytest.approx(F_EQ, rel=REL)
    assert check.limit == 1000.0 and check.unit == "N" and check.required == 0.0
    assert check.margin == pytest.approx(1.0 - check.value / 1000.0, rel=1e-12)
    # the mean cubic load lies between the belt's load at rest and its peak
    peak = _check(row, "gearbox_peak").value
    assert peak == pytest.approx(TORQUE_PER_ACCELERATION * 2 * math.pi * H / T**2, rel=1e-9)
    assert 2.0 * PRETENSION * math.sin(WRAP / 2.0) < F_EQ < _belt_radial(peak)


def test_a_rating_equal_to_the_equivalent_force_passes_and_just_below_fails():
    value = _check(_result(_design([_gearbox(**_rated(1000.0)), _belt()])).results[0],
                   "gearbox_radial_life").value
    equal = _result(_design([_gearbox(**_rated(value)), _belt()])).results[0]
    check = _check(equal, "gearbox_radial_life")
    assert check.value == value and check.passed and check.margin >= -TOLERANCE
    assert equal.feasible
    below = value * (1.0 - 1e-6)
    row = _result(_design([_gearbox(**_rated(below)), _belt()])).results[0]
    check = _check(row, "gearbox_radial_life")
    assert not check.passed and not row.feasible
    assert check.margin == pytest.approx(1.0 - value / below, rel=1e-9)
    assert row.limiting == "gearbox_radial_life"
    assert "gearbox_radial_life" in row.reason and "FAILS" in row.reason


def test_minimize_stops_at_the_shortest_duration_the_life_rating_allows():
    # F_eq falls as the move lengthens; the rating is between its value at rest and at T
    rating = 0.5 * (F_EQ + 2.0 * PRETENSION * math.sin(WRAP / 2.0))
    stages = [_gearbox(**_rated(rating)), _belt()]
    row = _result(_design(stages, "minimize")).results[0]
    assert row.feasible and row.limiting == "gearbox_radial_life"
    t_min = row.duration
    assert t_min > T
    # the reference: F_eq(t_min) = rating, to the engine's integration error
    assert reference_equivalent_force(t_min) == pytest.approx(rating, rel=REL)
    # at t_min the check passes, one step (1e-6) shorter it fails
    at = _result(_design(stages, f"{t_min!r} s")).results[0]
    assert _check(at, "gearbox_radial_life").passed
    shorter = _result(_design(stages, f"{t_min * (1.0 - 1e-6)!r} s")).results[0]
    check = _check(shorter, "gearbox_radial_life")
    assert not check.passed and check.margin < -TOLERANCE


PLE_20000_H = {"PLE040": (200.0, 200.0), "PLE060": (400.0, 500.0), "PLE080": (750.0, 1000.0),
               "PLE160": (5000.0, 7000.0)}
"""The radial and axial forces "for 20000 h" as the AG2250 technical data pages print them
(quoted in each frame's notes)."""


def test_the_ple_catalog_gives_the_20000_h_forces_with_their_source():
    for option in load_gearbox_catalog(bundled_gearbox_catalogs()["beckhoff-ag2250-ple"]):
        frame = option.gearbox.split(" i=")[0]
        stage = option.stage
        assert (stage.output_radial_load_life, stage.output_axial_load_life) \
            == PLE_20000_H[frame]
        assert stage.output_load_life == 20000 * 3600.0
        for name in ("output_radial_load_life", "output_axial_load_life", "output_load_life"):
            source = option.provenance.of(name)
            assert source.grade == "A" and f"{frame} technical data" in source.text


def test_a_ple_gearbox_of_the_catalog_gets_the_check_with_its_20000_h_force():
    design = _design([{"type": "gearbox", "catalog": "beckhoff-ag2250-ple"}, _belt()])
    rows = _result(design).results
    assert rows
    for row in rows:
        check = _check(row, "gearbox_radial_life")
        assert check.limit == PLE_20000_H[row.gearbox.split(" i=")[0]][0]
        # the gearbox's own inertia and ratio are on its input side: its output torque,
        # and so F_eq, are those of the inline design
        assert check.value == pytest.approx(F_EQ, rel=REL)
        assert check.margin == pytest.approx(1.0 - check.value / check.limit, rel=1e-12)


def test_the_tp_and_npt_catalogs_print_no_force_for_a_life():
    for name in ("beckhoff-ag2400-tp", "beckhoff-ag3400-npt"):
        for option in load_gearbox_catalog(bundled_gearbox_catalogs()[name]):
            assert option.stage.output_radial_load_life is None
            assert option.stage.output_axial_load_life is None
            assert option.stage.output_load_life is None


def test_the_npt_catalog_gives_no_life_rating_and_a_note_says_so():
    design = _design([{"type": "gearbox", "catalog": "beckhoff-ag3400-npt"},
                      {"type": "ball_screw", "lead": "10 mm", "inertia": 0,
                       "on_gearbox_output": True}])
    design["task"] = {"displacement": "0.1 m", "duration": "0.5 s"}
    design["load"] = {"mass": "5 kg"}
    result = _result(design)
    assert all(_check(r, "gearbox_axial_life") is None for r in result.results)
    assert any(n.startswith("no gearbox_axial_life check for NPT005-MF-C14, NPT015")
               and "output_axial_load_life" in n for n in result.notes), result.notes


def test_no_rating_no_check_and_a_note():
    result = _result(_design([_gearbox(), _belt()]))
    assert _check(result.results[0], "gearbox_radial_life") is None
    assert ("no gearbox_radial_life check for the gearbox: its ratings give no "
            "output_radial_load_life") in result.notes


def test_without_stage_torques_the_existing_note_applies():
    gearbox = _gearbox(**_rated(1000.0))
    del gearbox["peak_output_torque"]
    result = _result(_design([gearbox, _belt()]))
    assert _check(result.results[0], "gearbox_radial_life") is None
    assert any(n.startswith("no gearbox_radial or gearbox_axial check: the gearbox's output "
                            "torque is computed where") for n in result.notes)


def test_a_screw_on_the_gearbox_output_gets_the_axial_life_check():
    # a screw's axial force is the load's force: a pure mass on a cycloidal move, so
    # F_eq^3 = int |v| |m a|^3 dt / h in closed form over u = t / T
    h, duration, mass = 0.1, 0.5, 5.0
    stages = [_gearbox(output_axial_load_life="1000 N", output_load_life="20000 h"),
              {"type": "ball_screw", "lead": "10 mm", "inertia": 0,
               "on_gearbox_output": True}]
    design = {"task": {"displacement": f"{h} m", "duration": f"{duration} s"},
              "load": {"mass": f"{mass} kg"}, "transmission": stages,
              "laws": ["cycloidal"], "motors": [_motor()]}
    check = _check(_result(design).results[0], "gearbox_axial_life")
    peak = mass * 2.0 * math.pi * h / duration**2

    def integrand(u: float) -> float:
        return (1.0 - math.cos(2.0 * math.pi * u)) * abs(math.sin(2.0 * math.pi * u))**3

    cube, _ = quad(integrand, 0.0, 1.0, points=[0.5], epsabs=0.0, epsrel=1e-13)
    assert check.value == pytest.approx(peak * cube ** (1.0 / 3.0), rel=REL)
    assert check.limit == 1000.0


def test_the_cli_json_shows_the_check(tmp_path):
    design = _design([_gearbox(**_rated(1000.0)), _belt()])
    path = tmp_path / "design.yaml"
    path.write_text(yaml.safe_dump(design), encoding="utf-8")
    done = run_cli("size", str(path), "--format", "json")
    assert done.returncode == 0, done.stderr
    data = json.loads(done.stdout)
    rows = data["results"]
    check = next(c for c in rows[0]["checks"] if c["name"] == "gearbox_radial_life")
    assert check["value"] == pytest.approx(F_EQ, rel=REL)
    assert check["limit"] == 1000.0


def _bad(id: str, gearbox: dict, words: tuple[str, ...], fields: tuple[str, ...]) -> Case:
    return Case(id, design=yaml.safe_dump(_design([_gearbox(**gearbox), _belt()])),
                words=("design.yaml:", *words), fields=fields)


FIELD_CASES = [
    _bad("gearbox-radial-life-a-torque", _rated("5 N*m"),
         ("transmission[0].output_radial_load_life",),
         ("transmission[gearbox].output_radial_load_life",)),
    _bad("gearbox-axial-life-negative",
         {"output_axial_load_life": "-5 N", "output_load_life": "20000 h"},
         ("transmission[0].output_axial_load_life", "[0.001, 1e7] N"),
         ("transmission[gearbox].output_axial_load_life",)),
    _bad("gearbox-load-life-zero", {"output_radial_load_life": "100 N",
                                    "output_load_life": "0 h"},
         ("transmission[0].output_load_life", "[1, 1e10] s"),
         ("transmission[gearbox].output_load_life",)),
    _bad("gearbox-life-force-without-its-life", {"output_radial_load_life": "100 N"},
         ("transmission[0].output_radial_load_life", "needs output_load_life"), ()),
    _bad("gearbox-life-without-a-force", {"output_load_life": "20000 h"},
         ("transmission[0].output_load_life", "give one of them"), ()),
    bad_gears("gears-radial-life-a-length", {"gearboxes[0].output_radial_load_life": "5 mm",
                                             "gearboxes[0].output_load_life": "20000 h"},
              ("gearboxes[0].output_radial_load_life",),
              ("gearboxes:gearboxes.output_radial_load_life",)),
    bad_gears("gears-axial-life-zero", {"gearboxes[0].output_axial_load_life": "0 N",
                                        "gearboxes[0].output_load_life": "20000 h"},
              ("gearboxes[0].output_axial_load_life", "[0.001, 1e7] N"),
              ("gearboxes:gearboxes.output_axial_load_life",)),
    bad_gears("gears-load-life-a-force", {"gearboxes[0].output_axial_load_life": "10 N",
                                          "gearboxes[0].output_load_life": "5 N"},
              ("gearboxes[0].output_load_life",),
              ("gearboxes:gearboxes.output_load_life",)),
    bad_gears("gears-life-force-without-its-life",
              {"gearboxes[0].output_axial_load_life": "10 N"},
              ("gearboxes[0].output_axial_load_life", "needs output_load_life"), ()),
]
"""A bad value of every field of the gearbox output bearing life, located."""


@pytest.mark.parametrize("case", FIELD_CASES, ids=str)
def test_bad_gearbox_output_life_field(case, tmp_path):
    run(case, tmp_path)
