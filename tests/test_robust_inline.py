"""Robust sizing (issue 39, "Robust sizing"; docs/robust.md): tolerances written beside a
value, a ratio choice, ``duration: minimize``.

``inertia: 0.034 kg*m^2 +- 20 %`` is the ``tolerances:`` section's ``load.inertia: 20 %``:
the reference is the section form of the same design (the same tolerances, corners, JSON
byte for byte). With a ratio choice each pair keeps the ratio the nominal sizing chose;
in minimize mode its worst-case T_min is the largest over the corners: the reference sizes
each corner on its own with that ratio fixed by hand.
"""

from __future__ import annotations

import itertools
import json
import math
from dataclasses import replace

import pytest
from bad_input_cases import EXAMPLES, assert_clean_answer, edited
from cli_run import run_cli

from sizer import api
from sizer.io.schema.inputs import split_inline_tolerance
from sizer.model.tolerance import Tolerance
from sizer.robust import robust_sizing

ROTARY = "indexing-table.yaml"
LINEAR = "pick-and-place.yaml"
MOTORS = str(EXAMPLES / "catalogs" / "example-servo.yaml")
FAST = ("--law", "cycloidal", "--motor", "HG-KN43J", "--motor", "HG-KN73J")


def _write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.parametrize(("text", "split"), [
    ("0.35 kg*m^2 +- 20 %", ("0.35 kg*m^2", "20 %")),
    ("0.35 kg*m^2 ± 0.05 kg*m^2", ("0.35 kg*m^2", "0.05 kg*m^2")),
    ("0.2 N*m +/- 0.1", ("0.2 N*m", "0.1")),
    ("0.35 kg*m^2", ("0.35 kg*m^2", None)),
    (0.35, (0.35, None)),
])
def test_the_value_and_its_tolerance_are_split(text, split):
    assert split_inline_tolerance(text) == split


@pytest.mark.parametrize("text", ["+- 20 %", "0.35 kg*m^2 +-", "1 kg +- 2 % +- 3 %"])
def test_a_half_written_tolerance_is_refused(text):
    with pytest.raises(ValueError, match="tolerance"):
        split_inline_tolerance(text)


def test_inline_tolerances_are_the_section_s(tmp_path):
    inline = _write(tmp_path, "design.yaml", edited(ROTARY, set={
        "load.inertia": "0.034 kg*m^2 +- 20 %", "load.friction": "0.5 N*m ± 0.1 N*m",
        "load.damping": "0.02 N*m*s/rad +/- 50 %", "motors": MOTORS}))
    section = tmp_path / "section" / "design.yaml"
    section.parent.mkdir()
    section.write_text(edited(ROTARY, set={
        "tolerances": {"load.inertia": "20 %", "load.damping": "50 %",
                       "load.friction": "0.1 N*m"}, "motors": MOTORS}), encoding="utf-8")
    a, b = api.load(inline), api.load(section)
    assert a.tolerances == b.tolerances == (
        Tolerance("load.inertia", 0.2), Tolerance("load.damping", 0.5),
        Tolerance("load.friction", 0.1, absolute=True))  # in the order of the file
    assert (a.load.inertia, a.load.friction, a.load.damping) == (0.034, 0.5, 0.02)
    assert a.load == b.load
    runs = [run_cli("size", str(p), "--robust", "--all", "--format", "json", *FAST)
            for p in (inline, section)]
    assert runs[0].returncode == runs[1].returncode == 0, runs[0].stderr
    assert runs[0].stdout == runs[1].stdout
    first = json.loads(runs[0].stdout)["results"][0]["robust"]
    assert first["corners"] == 8


def test_a_linear_axis_takes_the_mass_s(tmp_path):
    path = _write(tmp_path, "design.yaml", edited(LINEAR, set={"load.mass": "4 kg +- 0.5 kg"}))
    assert api.load(path).tolerances == (Tolerance("load.mass", 0.5, absolute=True),)


def test_without_robust_a_note_and_the_nominal_answer(tmp_path):
    inline = _write(tmp_path, "a.yaml", edited(ROTARY, set={
        "load.inertia": "0.034 kg*m^2 +- 20 %", "motors": MOTORS}))
    plain = _write(tmp_path, "b.yaml", edited(ROTARY, set={"motors": MOTORS}))
    a = run_cli("size", str(inline), "--all", "--format", "json", *FAST)
    b = run_cli("size", str(plain), "--all", "--format", "json", *FAST)
    assert a.returncode == b.returncode == 0, a.stderr
    assert a.stdout.replace("a.yaml", "b.yaml") == b.stdout
    assert "load.inertia" in a.stderr and "--robust" in a.stderr
    assert "--robust" not in b.stderr


@pytest.mark.parametrize(("value", "extra", "words"), [
    ("0.034 kg*m^2 +- 20 %", {"tolerances": {"load.inertia": "10 %"}},
     ("design.yaml:", "load.inertia", "in one place")),
    ("0.034 kg*m^2 +- 2 kg", {}, ("design.yaml:", "load.inertia", "absolute inertia")),
    ("0.034 kg*m^2 +- 120 %", {}, ("design.yaml:", "load.inertia", "(0, 100 %)")),
    ("+- 20 %", {}, ("design.yaml:", "load.inertia", "its tolerance")),
    ("0.034 kg*m^2 +- 1 % +- 2 %", {}, ("design.yaml:", "load.inertia", "one tolerance")),
])
def test_located_errors(tmp_path, value, extra, words):
    path = _write(tmp_path, "design.yaml", edited(ROTARY, set={
        "load.inertia": value, "motors": MOTORS, **extra}))
    result = run_cli("size", str(path), "--robust")
    assert_clean_answer(result, 2, words)
    line = next(n for n, text in enumerate(path.read_text().splitlines(), 1)
                if text.strip().startswith("inertia:") and "+-" in text)
    assert f"design.yaml:{line}:" in result.stderr


# ------------------------------------------------ a ratio choice, duration: minimize
# The reference sizes each corner on its own (sizer.api), with the ratio the nominal sizing
# chose for the pair fixed by hand: the transmission it reports, no ratio choice.
GEARBOXES = str(EXAMPLES / "catalogs" / "example-gearboxes.yaml")
TWO = ["HG-KN43J", "HG-KN73J"]
CORNER_TOLERANCES = (("load.inertia", 0.2), ("load.friction", 0.5))


def _ratio_design(tmp_path, transmission, duration):
    path = _write(tmp_path, "design.yaml", edited("indexing-table-gearboxes.yaml", set={
        "transmission": transmission, "task.duration": duration, "motors": MOTORS}))
    return replace(api.override(api.load(path), motors=TWO, laws=["poly5", "cycloidal"]),
                   tolerances=CORNER_TOLERANCES)


def _separately(design, r):
    """Per corner: the pair's result with the nominal ratio fixed, sized on its own."""
    out = []
    for signs in itertools.product((-1, 1), repeat=len(CORNER_TOLERANCES)):
        (_, ti), (_, tf) = CORNER_TOLERANCES
        load = replace(design.load, inertia=design.load.inertia * (1 + signs[0] * ti),
                       friction=design.load.friction * (1 + signs[1] * tf))
        fixed = replace(design, load=load, ratio_choice=None, transmission=r.transmission,
                        tolerances=())
        found = [c for c in api.size(fixed, motors=[r.motor_object]).results
                 if c.spec == r.spec]
        assert len(found) == 1
        out.append(found[0])
    return out


@pytest.mark.parametrize("transmission", [
    {"type": "gearbox", "catalog": GEARBOXES},
    {"type": "gearbox", "ratio": {"optimize": [4, 30]}, "efficiency": 0.95}])
def test_a_ratio_choice_is_fixed_at_the_nominal_pair_s(tmp_path, transmission):
    design = _ratio_design(tmp_path, transmission, "0.2 s")
    nominal = api.size(design)
    robust = robust_sizing(design, nominal)
    assert robust.fixed_ratio and len(robust.results) == 4
    for result in robust.results:
        builds = _separately(design, result.nominal)
        least: dict[str, float] = {}
        for b in builds:
            for check in b.checks:
                least[str(check.name)] = min(least.get(str(check.name), math.inf),
                                             float(check.margin))
        assert result.worst.keys() == least.keys()
        for name, margin in least.items():
            assert result.worst[name] == pytest.approx(margin, rel=1e-12, abs=1e-12), name
        assert result.failing == sum(not b.feasible for b in builds)


def test_minimize_worst_duration_is_the_largest_over_the_corners(tmp_path):
    design = _ratio_design(tmp_path, {"type": "gearbox", "catalog": GEARBOXES}, "minimize")
    robust = robust_sizing(design, api.size(design), samples=8)
    assert robust.minimize and robust.by_worst_duration
    worst = []
    for result in robust.results:
        durations = [b.duration if b.feasible else math.inf
                     for b in _separately(design, result.nominal)]
        assert result.duration is not None
        assert result.duration.worst == pytest.approx(max(durations), rel=1e-12)
        assert result.duration.by == "corners"
        assert result.duration.p95 <= result.duration.worst * (1 + 1e-9)
        worst.append(result.duration.worst)
    feasible = [w for r, w in zip(robust.results, worst, strict=True) if r.feasible]
    assert feasible == sorted(feasible)  # ranked by the worst-case T_min


def test_the_output_says_the_ratio_is_fixed(tmp_path):
    path = _write(tmp_path, "design.yaml", edited("indexing-table-gearboxes.yaml", set={
        "transmission": {"type": "gearbox", "catalog": GEARBOXES}, "motors": MOTORS,
        "load.inertia": "0.034 kg*m^2 +- 20 %"}))
    result = run_cli("size", str(path), "--robust", "--law", "poly5", "--motor", "HG-KN73J",
                     "--samples", "4")
    assert result.returncode == 0, result.stderr
    assert "chosen at the nominal design" in result.stdout
    assert "worst T_min [ms]" in result.stdout and "T_min p95 [ms]" in result.stdout


INLINE_MOTORS = """\
name: two inline motors
task: {{displacement: 90 deg, duration: 0.25 s, dwell: 0.2 s}}
load: {{inertia: 0.002 kg*m^2, friction: 0.2 N*m}}
laws: [cycloidal, poly5]
motors:
  - {{id: M1, inertia: 1.2 kg*cm^2, continuous_torque: 1.3 N*m, peak_torque: {m1},
     rated_speed: 3000 rpm}}
  - {{id: M2, inertia: 0.9 kg*cm^2, continuous_torque: 1.0 N*m, peak_torque: 2.1 N*m,
     rated_speed: 3000 rpm}}
"""


def test_a_tolerance_beside_an_inline_motor_s_figure_is_that_motor_s_alone(tmp_path):
    """``peak_torque: 3 N*m +- 10 %`` on M1: M1's pairs' worst-case margins are the least
    over the two corners, each sized on its own with M1's peak torque set by hand (2.7 and
    3.3 N*m); M2's pairs are their nominal ones (the tolerance is not M2's)."""
    design = api.load(_write(tmp_path, "d.yaml", INLINE_MOTORS.format(m1="3 N*m +- 10 %")))
    (tolerance,) = design.tolerances
    assert (tolerance.name, tolerance.input, tolerance.motor) == (
        "motor.peak_torque[M1]", "motor.peak_torque", "M1")
    robust = robust_sizing(design, api.size(design))
    corners = [api.size(api.load(_write(tmp_path, f"c{k}.yaml",
                                        INLINE_MOTORS.format(m1=f"{peak} N*m"))))
               for k, peak in enumerate((2.7, 3.3))]
    for result in robust.results:
        nominal = result.nominal
        if nominal.motor == "M2":
            expected = {c.name: float(c.margin) for c in nominal.checks}
        else:
            expected = {}
            for sized in corners:
                (row,) = [r for r in sized.results
                          if (r.motor, r.spec) == (nominal.motor, nominal.spec)]
                for c in row.checks:
                    expected[c.name] = min(expected.get(c.name, math.inf), float(c.margin))
        assert result.worst.keys() == expected.keys()
        for name, margin in expected.items():
            assert result.worst[name] == pytest.approx(margin, rel=1e-12, abs=1e-12), name
    m1_peak = next(r for r in robust.results if r.nominal.motor == "M1")
    assert m1_peak.worst["peak"] < min(c.margin for c in m1_peak.nominal.checks
                                       if c.name == "peak")


def test_a_catalog_motor_takes_no_tolerance_beside_its_figure(tmp_path):
    catalog = _write(tmp_path, "cat.yaml", "catalog: c\nmanufacturer: m\nsource: s\nmotors:\n"
                     "  - {id: C1, inertia: 1 kg*cm^2, continuous_torque: 1 N*m, "
                     "peak_torque: 3 N*m +- 10 %, rated_speed: 3000 rpm}\n")
    design = _write(tmp_path, "d.yaml", INLINE_MOTORS.format(m1="3 N*m").split("motors:")[0]
                    + f"motors: [{catalog.name}]\n")
    assert_clean_answer(run_cli("size", str(design)), 2,
                        ("peak_torque", "tolerance beside a catalog motor"))
