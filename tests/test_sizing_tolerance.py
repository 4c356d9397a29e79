"""Limits at equality: one relative tolerance decides every check (sizer.sizing.checks).

A requirement exactly equal to its rating passes, although rounding may leave it one ulp
above; a requirement 1e-6 (relative) above its rating fails, and says so with a margin
that is visibly negative. The ratings are computed here from the closed forms of the
cycloidal law (C_a = 2 pi, C_a_rms = pi sqrt(2)), not from the engine.
"""

from __future__ import annotations

import dataclasses
import math
import textwrap

import numpy as np
import pytest

from sizer.io.loader import load_design
from sizer.model import Design, Limits, Load, Motor, Stage, Task, Transmission
from sizer.sizing import size_design
from sizer.sizing.checks import TOLERANCE, CheckArrays, feasible, worst_slack
from sizer.sizing.results import Check

OVER = 1.0 + 1e-6


def only(design: Design):
    (result,) = size_design(design).results
    assert result.feasible == all(c.passed for c in result.checks)
    return result


def test_the_tolerance_is_relative_to_the_limit() -> None:
    limit = np.array([2.0, 2.0, 2.0, 2.0])
    value = limit * np.array([1.0, 1.0 + 0.5 * TOLERANCE, 1.0 + 2 * TOLERANCE, OVER])
    value[0] = np.nextafter(2.0, 3.0)  # one ulp over
    check = CheckArrays("speed", value, limit, "rad/s", 0.0)
    assert check.passed.tolist() == [True, True, False, False]
    assert feasible([check]).tolist() == [True, True, False, False]
    assert (worst_slack([check]) < 0.0).all()  # the raw slacks are all negative
    with_margin = CheckArrays("rms", 0.9 * limit * np.array([1.0, OVER, 1.0, 1.0]), limit,
                              "N*m", 0.1)
    assert with_margin.passed.tolist() == [True, False, True, True]
    scalar = [Check("speed", float(v), 2.0, "rad/s", float(m))
              for v, m in zip(value, check.margin, strict=True)]
    assert [c.passed for c in scalar] == check.passed.tolist()


POLY5_AT_RATED_SPEED = textwrap.dedent("""\
    # poly5 (C_v = 15/8): 21 * 15/8 * (270 deg) / (0.590625 s) = 100 pi rad/s = 3000 rpm
    task: {displacement: 270 deg, duration: 0.590625 s}
    load: {inertia: 0.01 kg*m^2}
    transmission: {type: gearbox, ratio: 21}
    laws: [poly5]
    motors:
      - {id: m, inertia: 1 kg*cm^2, continuous_torque: 10 N*m, peak_torque: 30 N*m,
         rated_speed: 3000 rpm}
    """)


def test_a_motor_exactly_at_its_rated_speed_passes(tmp_path) -> None:
    path = tmp_path / "rated.yaml"
    path.write_text(POLY5_AT_RATED_SPEED)
    r = only(load_design(path))
    speed = r.check("speed")
    assert speed.limit == 3000 * 2 * math.pi / 60
    assert speed.value == pytest.approx(speed.limit, rel=1e-15)
    assert speed.margin < 0.0  # one ulp over: the raw comparison would fail
    assert speed.passed and r.feasible
    assert speed.describe() == "speed: 314.159 rad/s against 314.159 rad/s, margin 0.00% (ok)"
    # 1e-6 over the rating fails, with a margin that shows it
    path.write_text(POLY5_AT_RATED_SPEED.replace("3000 rpm", f"{3000 / OVER!r} rpm"))
    r = only(load_design(path))
    assert not r.feasible and r.limiting == "speed"
    assert r.check("speed").describe().endswith("margin -0.0001% (FAILS)")


H, T, K = 1.2, 0.3, 4.0
J_M, J_L = 2e-4, 0.05
J_T = J_M + J_L / K**2
PEAK = J_T * K * 2 * math.pi * H / T**2  # motor torque at the peak of the cycloidal law
RMS = J_T * K * math.pi * math.sqrt(2) * H / T**2


def cycloidal(motor: Motor, limits: Limits | None = None) -> Design:
    return Design(Task(H, T), Load(J_L), Transmission((Stage("gearbox", K),)),
                  laws=("cycloidal",), motors=(motor,), limits=limits or Limits())


def motor(peak: float, continuous: float) -> Motor:
    return Motor("m", inertia=J_M, continuous_torque=continuous, peak_torque=peak,
                 rated_speed=1e6)


@pytest.mark.parametrize("scale", [1.0, 1.0 - 1e-15, 1.0 + 1e-15])
def test_torque_and_rms_exactly_at_their_ratings_pass(scale) -> None:
    r = only(cycloidal(motor(PEAK * scale, 0.9 * PEAK)))
    assert r.check("peak").value == pytest.approx(1.0, rel=1e-12) and r.feasible
    r = only(cycloidal(motor(10 * RMS, RMS * scale)))
    assert r.check("rms").value == pytest.approx(RMS, rel=1e-12) and r.feasible
    # with a required margin: exactly at (1 - margin) of the rating
    r = only(cycloidal(motor(PEAK * scale / 0.9, 10 * PEAK), Limits(torque_margin=0.1)))
    assert r.check("peak").margin == pytest.approx(0.1, abs=1e-12) and r.feasible


def test_torque_and_rms_1e6_over_their_ratings_fail() -> None:
    r = only(cycloidal(motor(PEAK / OVER, 0.9 * PEAK)))
    assert not r.feasible and [c.name for c in r.checks if not c.passed] == ["peak"]
    assert "margin -0.0001% (FAILS)" in r.reason
    r = only(cycloidal(motor(10 * RMS, RMS / OVER)))
    assert not r.feasible and [c.name for c in r.checks if not c.passed] == ["rms"]
    r = only(cycloidal(motor(PEAK / (0.9 * OVER), 10 * PEAK), Limits(torque_margin=0.1)))
    assert not r.feasible
    assert r.check("peak").describe().endswith("10% required (FAILS)")
    assert "margin 9.9999" in r.check("peak").describe()  # visibly below 10 %


@pytest.mark.parametrize("over, passes", [(1.0, True), (OVER, False)])
def test_inertia_ratio_at_its_limit(over, passes) -> None:
    ratio = J_L / K**2 / J_M  # no transmission inertia: every definition agrees
    r = only(cycloidal(motor(10 * PEAK, 10 * PEAK), Limits(inertia_ratio=ratio / over)))
    assert r.check("inertia_ratio").passed is passes and r.feasible is passes


def test_minimize_at_equality_reports_the_limit_as_passing() -> None:
    """At T_min the binding check is at its limit: it passes and shows 0.00 %."""
    design = dataclasses.replace(cycloidal(motor(PEAK, 10 * PEAK)),
                                 task=Task(H, None))
    r = only(design)
    assert r.duration == pytest.approx(T, rel=1e-12)
    assert r.limiting == "peak" and "margin 0.00% (ok)" in r.check("peak").describe()


def test_sizer_check_passes_at_the_rated_speed_and_prints_a_failing_margin(tmp_path) -> None:
    from cli_run import run_cli

    path = tmp_path / "rated.yaml"
    check = "check: {motor: m, law: poly5}\n"
    path.write_text(POLY5_AT_RATED_SPEED + check)
    result = run_cli("check", str(path))
    assert result.returncode == 0, result.stdout
    assert "speed: 314.159 rad/s against 314.159 rad/s, margin 0.00% (ok)" in result.stdout
    path.write_text(POLY5_AT_RATED_SPEED.replace("3000 rpm", f"{3000 / OVER!r} rpm") + check)
    result = run_cli("check", str(path))
    assert result.returncode == 1
    assert "margin -0.0001% (FAILS)" in result.stdout and "-0.00%" not in result.stdout
