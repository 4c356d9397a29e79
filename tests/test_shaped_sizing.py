"""Input-shaped laws shaped for the load's mode at each candidate's duration (issue 15,
sizer.sizing.shaped_sizing): `{kind: shaped, law: L, shaper: zv}` without f_T.

References: the same design sized with the law shaped at a fixed f_T (the shaped law of
sec. 7.4.2, whose own tests pin it against a dense convolution), the integrated ODE of the
mode for the residual, and the convexity bound T <= T_min(base) + t_n.
"""

from __future__ import annotations

import math
from dataclasses import replace

import pytest
from cli_run import assert_user_error, run_cli
from test_vibration_design import simulated_residuals

from sizer.io import load_design
from sizer.laws.data_spec import data_spec_text
from sizer.sizing.engine import size_design
from sizer.vibration.elastic_load import ElasticLoad
from sizer.vibration.shapers import shaper_length

ROOT = __import__("pathlib").Path(__file__).resolve().parents[1]
DESIGN = """
task: {displacement: 90 deg, duration: DURATION, dwell: 0.35 s}
load: {inertia: 0.034 kg*m^2, friction: 0.5 N*m, natural_frequency: 25 Hz, damping_ratio: 0.02}
transmission: {type: gearbox, ratio: 10, efficiency: 0.95}
laws: [LAWS]
motors: MOTORS
limits: {torque_margin: 10 %}
"""
MODE = ElasticLoad(25.0, 0.02)


def design(tmp_path, laws: str, duration: str = "minimize"):
    path = tmp_path / "d.yaml"
    motors = ROOT / "examples" / "catalogs" / "example-servo.yaml"
    path.write_text(DESIGN.replace("DURATION", duration).replace("LAWS", laws)
                    .replace("MOTORS", str(motors)))
    loaded = load_design(path)
    return replace(loaded, motors=loaded.motors[1:3])


def fixed(loaded, shaper: str, base: str, f_T: float):
    spec = data_spec_text({"kind": "shaped", "law": base, "shaper": shaper, "f_T": f_T,
                           "damping_ratio": 0.02})
    return size_design(replace(loaded, laws=(spec,)))


def test_a_given_duration_is_shaped_for_it_and_leaves_no_residual(tmp_path):
    loaded = design(tmp_path, "{kind: shaped, law: cycloidal, shaper: zv}", "0.2 s")
    result = size_design(loaded).results
    reference = fixed(loaded, "zv", "cycloidal", 25.0 * 0.2).results
    for got, want in zip(result, reference, strict=True):
        assert got.duration == 0.2
        assert got.peak_torque == pytest.approx(want.peak_torque, rel=1e-12)
        assert got.residual_vibration < 1e-10 * math.pi / 2
    assert result[0].law_object is not None
    # every move leaves nothing, so one cycle from rest is the steady state
    assert max(simulated_residuals(result[0].spec, math.pi / 2, 0.2, 0.35, MODE, False,
                                   1)) < 1e-9


@pytest.mark.parametrize("shaper, base", [("zv", "cycloidal"),
                                          ("zvd", "trapezoidal(alpha=1/3)")])
def test_minimize_finds_the_duration_its_own_shaping_needs(tmp_path, shaper, base):
    loaded = design(tmp_path, f'{{kind: shaped, law: "{base}", shaper: {shaper}}}')
    results = {r.motor: r for r in size_design(loaded).results}
    unshaped = {r.motor: r for r in size_design(replace(loaded, laws=(base,))).results}
    t_n = shaper_length(shaper, MODE)
    for motor, r in results.items():
        assert r.feasible
        T = r.duration
        # self-consistent: the law shaped for T has its T_min at T
        again = {x.motor: x for x in fixed(loaded, shaper, base, 25.0 * T).results}
        assert again[motor].duration == pytest.approx(T, rel=1e-8)
        # no longer than the base move at its own T_min convolved with the shaper
        assert unshaped[motor].duration + t_n + 1e-12 >= T
        assert t_n < T
        assert r.residual_vibration < 1e-8 * math.pi / 2


def test_open_shaped_laws_need_the_mode_and_one_duration(tmp_path):
    text = DESIGN.replace("DURATION", "0.2 s").replace(
        "LAWS", "{kind: shaped, law: cycloidal, shaper: zv}").replace(
        "MOTORS", str(ROOT / "examples" / "catalogs" / "example-servo.yaml"))
    path = tmp_path / "no-mode.yaml"
    path.write_text(text.replace(", natural_frequency: 25 Hz, damping_ratio: 0.02", ""))
    assert_user_error(run_cli("size", str(path)), "no-mode.yaml:5", "laws[0]",
                      "natural_frequency")
    path = tmp_path / "mode.yaml"
    path.write_text(text)
    assert_user_error(run_cli("vibration", str(path)), "f_T")


def test_a_residual_limit_does_not_move_a_law_shaped_for_its_duration(tmp_path):
    loaded = design(tmp_path, "{kind: shaped, law: cycloidal, shaper: zv}")
    free = {r.motor: r.duration for r in size_design(loaded).results}
    bound = size_design(replace(loaded, limits=replace(loaded.limits,
                                                       residual_vibration=1e-6)))
    for r in bound.results:
        assert r.feasible and r.duration == pytest.approx(free[r.motor], rel=1e-12)
        assert r.check("residual_vibration").passed
