"""Designs through a four-bar driven from its rocker, or with the coupler's or the rod's
angle as the output (issue 14), end to end.

The expected numbers come from this test's own geometry (tests/test_linkage_readings.py's
two circles), differences in time and the energy balance: the motor's work over a move
from rest to rest is the work against the output's load and friction."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from cli_run import run_cli
from scipy.optimize import brentq
from test_linkage_readings import angles

from sizer.api import size
from sizer.io.loader import load_design_data
from sizer.sizing.samples import segment_breakdown

ROOT = Path(__file__).resolve().parent.parent
PAPER = (0.075, 0.175, 0.100, 0.175)
MOTOR = {"id": "m1", "inertia": "1 kg*cm^2", "continuous_torque": "50 N*m",
         "peak_torque": "150 N*m", "rated_speed": "3000 rpm"}


def _four_bar(**fields: object) -> dict:
    l1, l2, l3, l4 = (f"{x * 1000:g} mm" for x in PAPER)
    return {"type": "four_bar", "crank": l1, "coupler": l2, "rocker": l3, "ground": l4,
            **fields}


def _rocker_dead_points() -> tuple[float, float]:
    """The crank angles where crank and coupler are in line (law of cosines), extended
    and folded, the folded one after the extended one."""
    l1, l2, l3, l4 = PAPER
    extended = math.acos(((l1 + l2) ** 2 + l4**2 - l3**2) / (2 * (l1 + l2) * l4))
    folded = math.acos(((l2 - l1) ** 2 + l4**2 - l3**2) / (2 * (l2 - l1) * l4)) + math.pi
    return extended, folded


def _cycloidal(u: np.ndarray) -> np.ndarray:
    return u - np.sin(2 * np.pi * u) / (2 * np.pi)


def test_a_rocker_driving_a_coasting_crank_through_its_dead_points() -> None:
    # the motor swings the rocker (0.01 kg*m^2: 1 kg at 100 mm) and the massless crank
    # turns half a turn between the rocker's dead points, cycloidal in 0.5 s: the crank
    # needs no torque, so the motor's is (J_m + J_r) times the rocker's acceleration, also
    # at the dead points (the rocker's ratio is 0 there)
    extended, folded = _rocker_dead_points()
    design = {"task": {"displacement": f"{folded - extended!r} rad", "duration": "0.5 s"},
              "load": {"inertia": "1e-12 kg*m^2"},
              "transmission": [_four_bar(driven_link="rocker", law_on="output",
                                         start_angle=f"{extended!r} rad",
                                         coupler_mass_at_rocker="1 kg")],
              "laws": ["cycloidal"], "motors": [MOTOR]}
    (result,) = size(design).results
    u = np.linspace(0.0, 1.0, 200_001)
    dt = 0.5 * (u[1] - u[0])
    q3 = angles(PAPER, 1, extended + (folded - extended) * _cycloidal(u))[1]
    acceleration = np.gradient(np.gradient(q3, dt), dt)
    torque = (1e-4 + 0.01) * acceleration[5:-5]
    assert result.check("dead_point").passed
    assert result.peak_torque == pytest.approx(np.max(np.abs(torque)), rel=1e-4)
    assert result.rms_torque == pytest.approx(
        math.sqrt(np.trapezoid(torque**2, u[5:-5]) / (u[-6] - u[5])), rel=1e-3)
    assert result.max_speed == pytest.approx(np.max(np.abs(np.gradient(q3, dt))), rel=1e-5)


def test_a_rocker_cannot_push_a_heavy_crank_through_a_dead_point() -> None:
    extended, folded = _rocker_dead_points()
    # (and with a load on the crank, cannot hold it at the dead point where it stops)
    design = {"task": {"displacement": f"{folded - extended!r} rad", "duration": "0.5 s",
                       "dwell": "0.1 s"},
              "load": {"inertia": "0.01 kg*m^2", "torque": "1 N*m"},
              "transmission": [_four_bar(driven_link="rocker", law_on="output",
                                         start_angle=f"{extended!r} rad")],
              "laws": ["cycloidal"], "motors": [MOTOR]}
    (result,) = size(design).results
    assert not result.feasible and result.limiting == "dead_point"
    assert "cannot drive the crank through its dead point" in result.reason
    assert "at t = 0 s" in result.reason
    assert "cannot hold the output's load at the dead point" in result.reason


@pytest.mark.parametrize("law_on", ["crank", "output"])
def test_energy_balance_of_a_rocker_drive_inside_its_swing(law_on: str) -> None:
    # the rocker swings 0.4 rad down from where the crank is at 2 rad (inside its swing,
    # no dead point), turning a 0.01 kg*m^2 crank against 2 N*m and 0.5 N*m of friction:
    # the motor's work is 2 dq1 + 0.5 |dq1| (at rest at both ends)
    start = 2.0
    q3_start = float(angles(PAPER, 1, np.array([start]))[1][0])
    end = brentq(lambda x: float(angles(PAPER, 1, np.array([x]))[1][0]) - (q3_start - 0.4),
                 start, start + 2.0)
    turn = end - start
    displacement = "-0.4 rad" if law_on == "crank" else f"{turn!r} rad"
    data = {"task": {"displacement": displacement, "duration": "0.4 s", "dwell": "0.1 s"},
            "load": {"inertia": "0.01 kg*m^2", "torque": "2 N*m", "friction": "0.5 N*m"},
            "transmission": [_four_bar(driven_link="rocker", law_on=law_on,
                                       start_angle=f"{start!r} rad", crank_inertia=
                                       "0.002 kg*m^2", coupler_mass_at_crank="0.3 kg",
                                       coupler_mass_at_rocker="0.2 kg")],
            "laws": ["poly5"], "motors": [MOTOR]}
    design = load_design_data(data)
    (result,) = size(design).results
    assert result.check("dead_point").passed
    rows = segment_breakdown(design, design.motors[0], result.spec, result.duration).rows
    assert rows[0].energy == pytest.approx(2.0 * turn + 0.5 * abs(turn), rel=1e-6)
    # holding 2 N*m on the crank at the end: 2 / (dq3/dq1) at the motor
    h = 1e-6
    slope = (angles(PAPER, 1, np.array([end + h]))[1][0]
             - angles(PAPER, 1, np.array([end - h]))[1][0]) / (2 * h)
    assert rows[1].peak_torque == pytest.approx(abs(2.0 / slope), rel=1e-6)


def test_energy_balance_through_the_coupler_angle() -> None:
    # the crank turns from the coupler's largest angle to its least, the load (a 0.01
    # kg*m^2 disc on the coupler, against 3 N*m and 1 N*m of friction) swings with it:
    # the motor's work is 3 dq2 + 1 |dq2|
    grid = np.linspace(-np.pi, np.pi, 200_001)
    q2 = np.unwrap(angles(PAPER, 1, grid)[0])
    top, bottom = float(grid[np.argmax(q2)]), float(grid[np.argmin(q2)])
    turn = float((bottom - top) % (2 * np.pi))
    swing = float(q2.min() - q2.max())
    data = {"task": {"displacement": f"{turn!r} rad", "duration": "0.3 s", "dwell": "0.1 s"},
            "load": {"inertia": "0.01 kg*m^2", "torque": "3 N*m", "friction": "1 N*m"},
            "transmission": [_four_bar(output="coupler_angle", start_angle=f"{top!r} rad",
                                       coupler_mass_at_rocker="0.5 kg")],
            "laws": ["cycloidal"], "motors": [MOTOR]}
    design = load_design_data(data)
    (result,) = size(design).results
    rows = segment_breakdown(design, design.motors[0], result.spec, result.duration).rows
    assert rows[0].energy == pytest.approx(3.0 * swing + abs(swing), rel=1e-6)
    assert result.load_speed > 0.0


def test_energy_balance_through_the_rod_angle() -> None:
    # half a crank turn from pi/2 (the rod's largest angle) to 3 pi/2, against 4 N*m on the
    # rod and a 2 kg slider: the work is 4 dv with dv = -2 asin(r / l)
    r, rod = 0.05, 0.2
    data = {"task": {"displacement": "180 deg", "duration": "0.25 s", "dwell": "0.1 s"},
            "load": {"inertia": "0.001 kg*m^2", "torque": "4 N*m"},
            "transmission": [{"type": "slider_crank", "crank_radius": "50 mm",
                              "rod_length": "200 mm", "output": "rod_angle",
                              "start_angle": "90 deg", "rod_mass_at_slider": "2 kg"}],
            "laws": ["cycloidal"], "motors": [MOTOR]}
    design = load_design_data(data)
    (result,) = size(design).results
    rows = segment_breakdown(design, design.motors[0], result.spec, result.duration).rows
    assert rows[0].energy == pytest.approx(4.0 * (-2 * math.asin(r / rod)), rel=1e-6)
    # at the end the rod is at its least angle: holding it takes no torque
    assert rows[1].peak_torque == pytest.approx(0.0, abs=1e-9)


def test_rocker_drive_plot_from_the_cli(tmp_path: Path) -> None:
    path = ROOT / "examples" / "four-bar-rocker-driven.yaml"
    result = run_cli("size", str(path), "--all")
    assert result.returncode == 0, result.stderr
    assert "the rocker turns -0.69813 rad in T = 250 ms" in result.stdout  # -40 deg
    out = tmp_path / "linkage.png"
    plotted = run_cli("plot", str(path), "--linkage", "-o", str(out))
    assert plotted.returncode == 0, plotted.stderr
    assert out.stat().st_size > 0


def test_coupler_example_dead_point_verdicts() -> None:
    # both ends of the flap's swing are dead points of the coupler's angle: only poly7
    # (zero acceleration and jerk there, C3) passes the paper's rule
    results = size(ROOT / "examples" / "four-bar-coupler.yaml").results
    for r in results:
        if r.spec.startswith("polynomial(degree=7)"):
            assert r.check("dead_point").passed and math.isfinite(r.peak_torque)
        else:
            assert not r.feasible and r.limiting == "dead_point"
            assert "(C3)" in r.reason
    assert any(r.feasible for r in results)


def test_the_documented_linkage_block_loads() -> None:
    import re

    import yaml

    doc = (ROOT / "docs" / "input-files.md").read_text()
    block = re.search(r"```yaml\n(transmission:.*?four_bar.*?)```", doc, re.S)
    assert block is not None
    data = {**yaml.safe_load(block.group(1)), "load": {"inertia": "0.02 kg*m^2"},
            "task": {"displacement": "-40 deg", "duration": "0.25 s"}, "motors": [MOTOR]}
    stage = load_design_data(data).transmission.linkage
    assert stage is not None and stage.driven_link == "rocker"
    assert stage.output == "crank_angle" and stage.start_angle == 2.0


def test_the_paper_s_rules_on_a_driven_rocker_s_law() -> None:
    # the law on the rocker (the motor's link) over its whole swing, from one dead point
    # to the other, the crank massless (it coasts) and the rocker 0.01 kg*m^2: the rules
    # are the paper's with input and output swapped, so the cycloidal law (a jerk at the
    # dead points, C3 broken) fails and poly7 passes; poly7's motor torque is then
    # (J_m + J_r) h q''(u) / T^2, the rocker's own law
    extended, folded = _rocker_dead_points()
    low = float(angles(PAPER, 1, np.array([folded]))[1][0])
    high = float(angles(PAPER, 1, np.array([extended]))[1][0])
    design = {"task": {"displacement": f"{low - high!r} rad", "duration": "0.5 s"},
              "load": {"inertia": "1e-12 kg*m^2"},
              "transmission": [_four_bar(driven_link="rocker", law_on="crank",
                                         start_angle=f"{extended!r} rad",
                                         coupler_mass_at_rocker="1 kg")],
              "laws": ["cycloidal", "poly7"], "motors": [MOTOR]}
    by_law = {r.spec: r for r in size(design).results}
    cycloidal = by_law["cycloidal"]
    assert not cycloidal.feasible and cycloidal.limiting == "dead_point"
    assert "(C3)" in cycloidal.reason
    poly7 = by_law["polynomial(degree=7)"]
    assert poly7.check("dead_point").passed
    u = np.linspace(0.0, 1.0, 100_001)
    q2 = np.polynomial.Polynomial([0, 0, 0, 0, 35, -84, 70, -20]).deriv(2)(u)
    torque = (1e-4 + 0.01) * (low - high) * q2 / 0.5**2
    assert poly7.peak_torque == pytest.approx(np.max(np.abs(torque)), rel=1e-4)
    assert poly7.rms_torque == pytest.approx(math.sqrt(np.trapezoid(torque**2, u)), rel=1e-4)
