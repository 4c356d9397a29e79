"""Robust sizing (issue 39, "Robust sizing"; docs/robust.md): every pair at the corners of
the design's tolerances.

The reference is independent of sizer.robust: each corner is a design perturbed here by
hand (dataclasses.replace on the load and on every motor) and sized on its own; the
worst-case margin must be the least margin over those sizings.
"""

from __future__ import annotations

import itertools
import json
from dataclasses import replace

import pytest
from bad_input_cases import EXAMPLES, Case, assert_clean_answer, edited
from bad_input_cases import run_case as run
from cli_run import run_cli

from sizer import api
from sizer.errors import UserError
from sizer.robust import check_tolerances, robust_sizing

TOLERANCES = (("load.inertia", 0.2), ("load.friction", 1.0), ("motor.peak_torque", 0.1),
              ("motor.continuous_torque", 0.1))
MOTORS = ["HG-KN43J", "HG-KN73J"]
LAWS = ["cycloidal", "modified_sinusoidal"]


@pytest.fixture(scope="module")
def design():
    loaded = api.override(api.load(EXAMPLES / "indexing-table.yaml"), motors=MOTORS,
                          laws=LAWS)
    return replace(loaded, tolerances=TOLERANCES)


def _corner(design, signs):
    (_, ti), (_, tf), (_, tp), (_, tc) = TOLERANCES
    si, sf, sp, sc = signs
    load = replace(design.load, inertia=design.load.inertia * (1 + si * ti),
                   friction=design.load.friction * (1 + sf * tf))
    motors = tuple(replace(m, peak_torque=m.peak_torque * (1 + sp * tp),
                           continuous_torque=m.continuous_torque * (1 + sc * tc))
                   for m in design.motors)
    return replace(design, load=load, motors=motors, tolerances=())


def test_worst_margin_is_the_least_over_separately_sized_corners(design):
    robust = robust_sizing(design, api.size(design))
    expected: dict[tuple[str, str], dict[str, float]] = {}
    passes: dict[tuple[str, str], bool] = {}
    for signs in itertools.product((-1, 1), repeat=4):
        for r in api.size(_corner(design, signs)).results:
            key = (r.motor, r.spec)
            worst = expected.setdefault(key, {})
            for check in r.checks:
                worst[str(check.name)] = min(worst.get(str(check.name), 1e300),
                                             float(check.margin))
            passes[key] = passes.get(key, True) and r.feasible
    assert len(robust.results) == len(expected) == 4
    for result in robust.results:
        n = result.nominal
        key = (n.motor, n.spec)
        assert result.corners == 16
        assert result.worst == pytest.approx(expected[key], rel=1e-12, abs=1e-15)
        assert result.feasible == passes[key]
    # the small motor passes nominally but fails where the inertia is 20 % higher
    small = [r for r in robust.results if r.nominal.motor == "HG-KN43J"]
    assert all(r.nominal.feasible and not r.feasible for r in small)
    assert all(dict(r.corner["inertia_ratio"])["load.inertia"] == 0.2 for r in small)
    # ranked: feasible at every corner first
    flags = [r.feasible for r in robust.results]
    assert flags == sorted(flags, reverse=True)
    assert [r.nominal for r in robust.results] == list(robust.sizing.results)


def test_a_law_chosen_at_each_corner_is_matched_by_its_family():
    # trapezoidal(alpha=auto) has another alpha at each corner: still one pair
    loaded = api.override(api.load(EXAMPLES / "indexing-table.yaml"), motors=["HG-KN43J"],
                          laws=["trapezoidal(alpha=auto)"])
    design = replace(loaded, tolerances=(("load.inertia", 0.2),))
    robust = robust_sizing(design, api.size(design))
    assert len(robust.results) == 1
    corners = [api.size(replace(design, tolerances=(), load=replace(
        design.load, inertia=design.load.inertia * f))).results[0] for f in (0.8, 1.2)]
    for name, worst in robust.results[0].worst.items():
        assert worst == min(c.check(name).margin for c in corners)


def test_eleven_tolerances_are_refused(design):
    many = replace(design, tolerances=tuple((f"motor.x{i}", 0.1) for i in range(11)))
    with pytest.raises(UserError, match="at most 10"):
        check_tolerances(many)


def test_a_zero_input_is_refused(design):
    with pytest.raises(UserError, match=r"no load\.torque") as caught:
        check_tolerances(replace(design, tolerances=(("load.torque", 0.1),)))
    assert caught.value.field == "tolerances['load.torque']"


# ------------------------------------------------------------ the command
ROTARY = "indexing-table.yaml"
GIVEN = {"tolerances": {"load.inertia": "20 %", "motor.peak_torque": "10 %"},
         "motors": str(EXAMPLES / "catalogs" / "example-servo.yaml")}


def test_robust_without_tolerances_says_so(tmp_path):
    path = tmp_path / "design.yaml"
    path.write_text(edited(ROTARY, set={"motors": GIVEN["motors"]}), encoding="utf-8")
    result = run_cli("size", str(path), "--robust")
    assert_clean_answer(result, 2, ("--robust", "no tolerances"))


def test_json_keeps_the_normal_keys_and_adds_robust(tmp_path):
    path = tmp_path / "design.yaml"
    path.write_text(edited(ROTARY, set=GIVEN), encoding="utf-8")
    plain = run_cli("size", str(path), "--all", "--format", "json", "--law", "cycloidal")
    robust = run_cli("size", str(path), "--all", "--format", "json", "--law", "cycloidal",
                     "--robust")
    assert plain.returncode == robust.returncode == 0, robust.stderr
    normal, extended = json.loads(plain.stdout), json.loads(robust.stdout)
    assert "robust" not in plain.stdout and "tolerances" not in normal
    assert set(normal) <= set(extended)
    stripped = [{k: v for k, v in item.items() if k != "robust"}
                for item in extended["results"]]
    by_motor = {item["motor"]: item for item in normal["results"]}
    for item in stripped:
        mine = by_motor[item["motor"]]
        assert {k: v for k, v in item.items() if k != "rank"} == \
            {k: v for k, v in mine.items() if k != "rank"}
    first = extended["results"][0]["robust"]
    assert first["corners"] == 4
    assert first["margin"] == min(c["margin"] for c in first["checks"].values())


def test_tolerances_do_not_change_the_plain_answer(tmp_path):
    with_tol, without = tmp_path / "a.yaml", tmp_path / "b.yaml"
    with_tol.write_text(edited(ROTARY, set=GIVEN), encoding="utf-8")
    without.write_text(edited(ROTARY, set={"motors": GIVEN["motors"]}), encoding="utf-8")
    a = run_cli("size", str(with_tol), "--all", "--format", "json", "--law", "cycloidal")
    b = run_cli("size", str(without), "--all", "--format", "json", "--law", "cycloidal")
    assert a.stdout.replace("a.yaml", "b.yaml") == b.stdout.replace("b.yaml", "b.yaml")


# ------------------------------------------------------------ bad fields, located
D = "design.yaml:"


def case(id: str, value: dict, words: tuple[str, ...]) -> Case:
    return Case(id, design=edited(ROTARY, set={"tolerances": value}), words=(D, *words),
                fields=("tolerances",))


FIELD_CASES = [
    case("tolerance-unknown-input", {"load.colour": "5 %"},
         ("tolerances['load.colour']", "one of", "load.inertia")),
    case("tolerance-linear-name-on-a-rotary-axis", {"load.mass": "5 %"},
         ("tolerances['load.mass']", "load.inertia")),
    case("tolerance-a-force", {"load.inertia": "20 N"},
         ("tolerances['load.inertia']", "fraction")),
    case("tolerance-over-100-percent", {"load.friction": "150 %"},
         ("tolerances['load.friction']", "(0, 100 %]")),
    case("tolerance-100-percent-of-inertia", {"load.inertia": "100 %"},
         ("tolerances['load.inertia']", "(0, 100 %)")),
    case("tolerance-zero", {"motor.peak_torque": 0},
         ("tolerances['motor.peak_torque']", "(0, 100 %)")),
    case("tolerances-not-a-mapping", ["load.inertia"], ("tolerances",)),
]
"""The bad ``tolerances:`` cases (tests/test_bad_inputs_fields.py's walk over every field
needs these ``fields``)."""


@pytest.mark.parametrize("case", FIELD_CASES, ids=str)
def test_bad_tolerance_field(case, tmp_path):
    run(case, tmp_path)


def test_a_zero_input_names_the_file(tmp_path):
    path = tmp_path / "design.yaml"
    path.write_text(edited(ROTARY, set={"tolerances": {"load.torque": "10 %"},
                                        "motors": GIVEN["motors"]}), encoding="utf-8")
    result = run_cli("size", str(path), "--robust")
    assert_clean_answer(result, 2, (D, "tolerances['load.torque']", "no load.torque"))
