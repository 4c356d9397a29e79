"""Robust sizing with samples and distributions (issue 39, "Robust sizing"; docs/robust.md).

The references are independent of sizer.robust: builds drawn here with Python's own
``random`` (not numpy) and sized one by one as designs perturbed by hand
(dataclasses.replace on the load and on every motor); the Wilson interval and the
truncated normal's moments from their closed forms.
"""

from __future__ import annotations

import json
import math
import random
from dataclasses import replace
from types import SimpleNamespace

import pytest
from bad_input_cases import EXAMPLES, assert_clean_answer, edited
from cli_run import run_cli

from sizer import api
from sizer.errors import UserError
from sizer.model.tolerance import Tolerance
from sizer.robust import (
    CORNERS,
    NOMINAL,
    SAMPLES,
    _robust,
    check_tolerances,
    draw,
    robust_sizing,
    wilson_interval,
)

MOTORS = ["HG-KN43J", "HG-KN73J"]
INERTIA = Tolerance("load.inertia", 0.2)                          # uniform, +-20 %
PEAK = Tolerance("motor.peak_torque", 0.1, distribution="normal", sigmas=2.0)  # sigma 5 %
N = 60


@pytest.fixture(scope="module")
def design():
    loaded = api.override(api.load(EXAMPLES / "indexing-table.yaml"), motors=MOTORS,
                          laws=["cycloidal"])
    return replace(loaded, tolerances=(INERTIA, PEAK))


@pytest.fixture(scope="module")
def sampled(design):
    return robust_sizing(design, api.size(design), samples=N, seed=7)


def _by_hand(design, inertia_change, peak_change):
    """The design built with the load's inertia and every motor's peak torque changed."""
    load = replace(design.load, inertia=design.load.inertia * (1.0 + inertia_change))
    motors = tuple(replace(m, peak_torque=m.peak_torque * (1.0 + peak_change))
                   for m in design.motors)
    return replace(design, load=load, motors=motors, tolerances=())


def _passes(design, builds):
    """Per motor, how many of the builds ((inertia, peak) changes) pass, each sized alone."""
    count = dict.fromkeys(MOTORS, 0)
    for inertia_change, peak_change in builds:
        for r in api.size(_by_hand(design, inertia_change, peak_change)).results:
            count[r.motor] += bool(r.feasible)
    return count


def test_the_pass_share_counts_the_builds_sized_one_by_one(design, sampled):
    builds = draw((INERTIA, PEAK), N, seed=7)  # the same builds, sized here by hand
    expected = _passes(design, builds)
    for result in sampled.results:
        assert result.samples == N
        assert result.passing == expected[result.nominal.motor]


def test_the_pass_share_agrees_with_an_independent_monte_carlo(design, sampled):
    rng = random.Random(20261206)

    def peak() -> float:
        while True:  # normal, sigma 5 %, truncated at 2 sigma
            z = rng.gauss(0.0, 1.0)
            if abs(z) <= 2.0:
                return 0.05 * z

    builds = [(rng.uniform(-0.2, 0.2), peak()) for _ in range(N)]
    reference = _passes(design, builds)
    shares = {r.nominal.motor: r for r in sampled.results}
    small = shares["HG-KN43J"]
    assert 0.0 < small.share < 1.0  # the small motor fails where the inertia is high
    for motor, passed in reference.items():
        low, high = shares[motor].interval
        assert low <= passed / N <= high, (motor, passed, shares[motor].interval)


def test_wilson_interval_closed_form():
    # n = 100, 90 passed: (p + z^2/2n -+ z sqrt(p q / n + z^2/4n^2)) / (1 + z^2/n)
    z, n, p = 1.959963984540054, 100, 0.9
    center = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    assert wilson_interval(90, 100) == pytest.approx((center - half, center + half),
                                                     rel=1e-12)
    assert wilson_interval(90, 100) == pytest.approx((0.8256, 0.9448), abs=5e-5)
    low, high = wilson_interval(200, 200)
    assert high == 1.0 and low == pytest.approx(1 / (1 + z * z / 200), rel=1e-12)


def test_draws_follow_their_distributions():
    builds = draw((Tolerance("a", 0.3), Tolerance("b", 0.2, distribution="normal",
                                                   sigmas=2.0)), 200_000, seed=1)
    uniform, normal = builds[:, 0], builds[:, 1]
    assert abs(uniform).max() <= 0.3 and abs(normal).max() <= 0.2
    assert uniform.std() == pytest.approx(0.3 / math.sqrt(3), rel=0.01)
    # a standard normal truncated at +-a: variance 1 - 2 a phi(a) / (2 Phi(a) - 1)
    a = 2.0
    phi = math.exp(-a * a / 2) / math.sqrt(2 * math.pi)
    variance = 1 - 2 * a * phi / math.erf(a / math.sqrt(2))
    assert normal.std() == pytest.approx(0.1 * math.sqrt(variance), rel=0.01)


def test_truncated_normal_corners_are_the_uniform_corners_at_its_width(design):
    normal = replace(design, tolerances=(Tolerance("load.inertia", 0.2, distribution="normal",
                                                   sigmas=2.5),))
    uniform = replace(design, tolerances=(Tolerance("load.inertia", 0.2),))
    a = robust_sizing(normal, api.size(normal))
    b = robust_sizing(uniform, api.size(uniform))
    for x, y in zip(a.results, b.results, strict=True):
        assert (x.worst, x.corner, x.feasible, x.failing) == \
            (y.worst, y.corner, y.feasible, y.failing)
        assert dict(x.corner["inertia_ratio"])["load.inertia"] in (-0.2, 0.2)


def test_an_absolute_tolerance_is_the_relative_one_of_its_share(design):
    absolute = replace(design, tolerances=(
        Tolerance("load.inertia", 0.2 * design.load.inertia, absolute=True),))
    relative = replace(design, tolerances=(Tolerance("load.inertia", 0.2),))
    a = robust_sizing(absolute, api.size(absolute))
    b = robust_sizing(relative, api.size(relative))
    for x, y in zip(a.results, b.results, strict=True):
        assert x.worst == pytest.approx(y.worst, rel=1e-12, abs=1e-15)
        assert x.feasible == y.feasible
    with pytest.raises(UserError, match="reaches zero"):
        check_tolerances(replace(design, tolerances=(
            Tolerance("load.inertia", 2 * design.load.inertia, absolute=True),)))


def test_too_many_tolerances_for_corners_are_sampled(design, monkeypatch):
    import sizer.robust as robust

    monkeypatch.setattr(robust, "MAX_TOLERANCES", 1)
    with pytest.raises(UserError, match="--samples"):
        check_tolerances(design)
    sized = robust_sizing(design, api.size(design), samples=10, seed=7)
    assert not sized.corners
    for r in sized.results:
        assert r.corners == 0 and r.samples == 10
        assert set(r.by.values()) == {SAMPLES}


def _fake(margins: dict[str, float], feasible: bool = True) -> SimpleNamespace:
    return SimpleNamespace(feasible=feasible, checks=tuple(
        SimpleNamespace(name=n, margin=m) for n, m in margins.items()))


def test_a_sample_worse_than_every_corner_replaces_the_corners_worst_case():
    # builds 0-1 corners, 2-3 samples; 'rms' is least inside the box (not monotone)
    at = [(0, _fake({"peak": 0.3, "rms": 0.2})), (1, _fake({"peak": 0.1, "rms": 0.2})),
          (2, _fake({"peak": 0.2, "rms": -0.1}, feasible=False)),
          (3, _fake({"peak": 0.15, "rms": 0.2}))]
    result = _robust(_fake({}), at, 2, 2, lambda b: (("x", float(b)),))
    assert result.worst == {"peak": 0.1, "rms": -0.1}
    assert result.by == {"peak": CORNERS, "rms": SAMPLES}
    assert result.corner["rms"] == (("x", 2.0),)
    assert result.sampled_checks == ("rms",)
    assert (result.failing, result.passing, result.feasible) == (0, 1, False)


def test_a_nominal_margin_below_every_corner_shows_a_margin_not_monotone():
    # the box's center is a build too: a margin least there is not monotone
    at = [(0, _fake({"peak": 0.3, "rms": 0.2})), (1, _fake({"peak": 0.1, "rms": 0.25}))]
    nominal = _fake({"peak": 0.2, "rms": 0.05})
    result = _robust(nominal, at, 2, 0, lambda b: (("x", float(b)),))
    assert result.worst == {"peak": 0.1, "rms": 0.05}
    assert result.by == {"peak": CORNERS, "rms": NOMINAL}
    assert result.corner["rms"] == (("x", -1.0),)  # build -1: the nominal machine
    # and within SAMPLE_BELOW of the corners it is the corners' (monotone, a flat margin)
    flat = _robust(_fake({"peak": 0.1, "rms": 0.2}), at, 2, 0, lambda b: (("x", float(b)),))
    assert flat.by == {"peak": CORNERS, "rms": CORNERS}


# ------------------------------------------------------------ the command
GIVEN = {"tolerances": {"load.inertia": "20 %",
                        "motor.peak_torque": {"distribution": "normal", "sigma": "5 %",
                                              "truncate": 2}},
         "motors": str(EXAMPLES / "catalogs" / "example-servo.yaml")}


@pytest.fixture(scope="module")
def path(tmp_path_factory):
    path = tmp_path_factory.mktemp("robust") / "design.yaml"
    path.write_text(edited("indexing-table.yaml", set=GIVEN), encoding="utf-8")
    return path


def _size(path, *options):
    return run_cli("size", str(path), "--law", "cycloidal", "--all", *options)


def test_the_seed_makes_the_output_byte_identical(path):
    a = _size(path, "--samples", "12", "--seed", "3", "--format", "json")
    b = _size(path, "--samples", "12", "--seed", "3", "--format", "json")
    assert a.returncode == 0, a.stderr
    assert a.stdout == b.stdout
    default, zero = _size(path, "--samples", "12"), _size(path, "--samples", "12", "--seed",
                                                          "0")
    assert default.stdout == zero.stdout and "seed 0" in default.stdout
    assert "pass [%]" in default.stdout and "100.0 [75.8, 100.0]" in default.stdout
    data = json.loads(a.stdout)
    assert data["robust_method"] == {"corners": True, "samples": 12, "seed": 3}
    details = {d["name"]: d for d in data["tolerance_details"]}
    assert details["motor.peak_torque"]["sigma"] == pytest.approx(0.05)
    assert details["motor.peak_torque"]["truncate"] == 2.0
    for item in data["results"]:
        robust = item["robust"]
        assert robust["samples"] == 12
        low, high = wilson_interval(robust["passing_samples"], 12)
        assert robust["interval"] == pytest.approx([low, high], rel=1e-12)


def test_rank_by_worst_margin(path):
    result = _size(path, "--robust", "--rank-by", "worst_margin", "--format", "json")
    assert result.returncode == 0, result.stderr
    data = json.loads(result.stdout)
    keys = [(not i["robust"]["feasible"], -i["robust"]["margin"]) for i in data["results"]]
    assert keys == sorted(keys)
    assert "worst-case margin" in data["robust_ranking"]
    plain = _size(path, "--rank-by", "worst_margin")
    assert_clean_answer(plain, 2, ("--rank-by", "--robust"))


@pytest.mark.parametrize(("options", "words"), [
    (("--samples", "-5"), ("--samples", "-5")),
    (("--samples", "0"), ("--samples",)),
    (("--robust", "--seed", "4"), ("--seed", "--samples")),
])
def test_bad_options(path, options, words):
    assert_clean_answer(_size(path, *options), 2, words)


@pytest.mark.parametrize(("value", "words"), [
    ({"distribution": "gauss", "sigma": "5 %"},
     ("tolerances['load.inertia'].distribution", "'uniform' or 'normal'")),
    ({"distribution": "normal", "sigma": "40 %"},
     ("tolerances['load.inertia'].sigma", "(0, 100 %)", "truncate x sigma")),
    ({"distribution": "normal", "plus_minus": "5 %"},
     ("tolerances['load.inertia']", "sigma")),
    ({"plus_minus": "5 %", "truncate": 2}, ("tolerances['load.inertia'].truncate",)),
    ("20 N", ("tolerances['load.inertia']", "fraction", "inertia")),
])
def test_bad_tolerance_fields(tmp_path, value, words):
    path = tmp_path / "design.yaml"
    path.write_text(edited("indexing-table.yaml", set={**GIVEN, "tolerances": {
        "load.inertia": value}}), encoding="utf-8")
    assert_clean_answer(_size(path, "--robust"), 2, ("design.yaml:", *words))


def test_absolute_and_normal_tolerances_load(tmp_path):
    path = tmp_path / "design.yaml"
    path.write_text(edited("indexing-table.yaml", set={"motors": GIVEN["motors"], "tolerances": {
        "load.friction": "0.1 N*m", "load.inertia": {"distribution": "normal",
                                                     "sigma": "1 g*m^2"}}}),
                    encoding="utf-8")
    loaded = {t.name: t for t in api.load(path).tolerances}
    friction, inertia = loaded["load.friction"], loaded["load.inertia"]
    assert (friction.absolute, friction.width, friction.distribution) == (True, 0.1,
                                                                          "uniform")
    assert inertia.absolute and inertia.distribution == "normal"
    assert inertia.sigma == pytest.approx(1e-3) and inertia.sigmas == 3.0
    assert inertia.width == pytest.approx(3e-3)
