"""Designs whose transmission ends in a linkage (issue 14), end to end.

The expected numbers are computed here from the slider-crank's own geometry (finite
differences of s(theta) = r cos theta + sqrt(l^2 - r^2 sin^2 theta), dense sums), not by
sizer's code; the verdicts at the dead points are the paper's rules."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import yaml
from cli_run import assert_user_error, run_cli
from scipy.optimize import brentq

from sizer.api import size
from sizer.laws import make_law

ROOT = Path(__file__).resolve().parent.parent
R, L, M = 0.05, 0.2, 5.0
MOTOR = {"id": "m1", "inertia": "1 kg*cm^2", "continuous_torque": "50 N*m",
         "peak_torque": "150 N*m", "rated_speed": "3000 rpm"}


def _design(task: dict, crank: dict, **changes: object) -> dict:
    design = {"task": task, "load": {"mass": f"{M} kg"},
              "transmission": [{"type": "slider_crank", "crank_radius": f"{R} m",
                                "rod_length": f"{L} m", **crank}],
              "laws": ["cycloidal"], "motors": [MOTOR]}
    design.update(changes)
    return design


def _s(theta: np.ndarray) -> np.ndarray:
    return R * np.cos(theta) + np.sqrt(L**2 - (R * np.sin(theta)) ** 2)


def _crank_torque(u: np.ndarray, turn: float, T: float, start: float = 0.0) -> np.ndarray:
    """The crank torque of a cycloidal crank move by this test's own formulas: the motor's
    rotor (1e-4 kg*m^2) plus M s' (s'' w^2 + s' alpha), s', s'' by central differences."""
    theta = start + turn * (u - np.sin(2 * np.pi * u) / (2 * np.pi))
    w = turn * (1 - np.cos(2 * np.pi * u)) / T
    alpha = turn * 2 * np.pi * np.sin(2 * np.pi * u) / T**2
    d = 1e-4
    s1 = (_s(theta + d) - _s(theta - d)) / (2 * d)
    s2 = (_s(theta + d) - 2 * _s(theta) + _s(theta - d)) / d**2
    return 1e-4 * alpha + M * s1 * (s2 * w**2 + s1 * alpha)


def test_crank_law_torque_through_both_dead_points() -> None:
    # the crank turns one revolution from the top dead centre in 0.5 s, then rests 0.2 s
    task = {"displacement": "360 deg", "duration": "0.5 s", "dwell": "0.2 s"}
    (result,) = size(_design(task, {"law_on": "crank"})).results
    u = np.linspace(0.0, 1.0, 400_001)
    torque = _crank_torque(u, 2 * np.pi, 0.5)
    assert result.peak_torque == pytest.approx(np.max(np.abs(torque)), rel=1e-6)
    mean_square = np.trapezoid(torque**2, u) * 0.5 / 0.7
    assert result.rms_torque == pytest.approx(math.sqrt(mean_square), rel=1e-6)
    assert result.max_speed == pytest.approx(2 * 2 * np.pi / 0.5, rel=1e-9)  # C_v h / T
    assert result.feasible


def test_shortest_duration_through_a_linkage_by_time_scaling() -> None:
    # a pure inertia: the torque scales as 1/T^2, so T_min meets the first limit it
    # reaches: the peak (150 N*m), the RMS with the dwell (50 N*m), or the speed
    task = {"displacement": "360 deg", "duration": "minimize", "dwell": "0.2 s"}
    (result,) = size(_design(task, {"law_on": "crank"})).results
    u = np.linspace(0.0, 1.0, 400_001)
    at_one = _crank_torque(u, 2 * np.pi, 1.0)
    t_peak = math.sqrt(np.max(np.abs(at_one)) / 150.0)
    square = np.trapezoid(at_one**2, u)
    t_rms = brentq(lambda T: square / T**3 / (T + 0.2) - 50.0**2, 1e-3, 10.0)
    t_speed = 2 * 2 * np.pi / (3000 * 2 * np.pi / 60)
    assert result.duration == pytest.approx(max(t_peak, t_rms, t_speed), rel=1e-6)


def test_press_example_dead_point_verdicts() -> None:
    results = size(ROOT / "examples" / "press-slider-crank.yaml").results
    by_law: dict[str, list] = {}
    for r in results:
        by_law.setdefault(r.spec, []).append(r)
    poly7 = by_law[make_law("poly7").spec]
    assert any(r.feasible for r in poly7)
    for spec in ("poly5", "cycloidal", "trapezoidal(alpha=1/3)"):
        for r in by_law[make_law(spec).spec]:
            assert not r.feasible and r.limiting == "dead_point"
            assert "dead point at t = 0 s" in r.reason, r.reason
            assert r.peak_torque is None or not math.isfinite(r.peak_torque)
    # poly7 meets the rule: the crank's speed and torque stay finite
    assert all(math.isfinite(r.peak_torque) for r in poly7)


def test_press_example_runs_from_the_cli(tmp_path: Path) -> None:
    result = run_cli("size", str(ROOT / "examples" / "press-slider-crank.yaml"), "--all")
    assert result.returncode == 0, result.stderr
    assert "dead point" in result.stdout
    out = tmp_path / "linkage.png"
    plotted = run_cli("plot", str(ROOT / "examples" / "press-slider-crank.yaml"),
                      "--linkage", "-o", str(out))
    assert plotted.returncode == 0, plotted.stderr
    assert out.stat().st_size > 1000


@pytest.mark.parametrize(("stage", "task", "fragments"), [
    ({"type": "slider_crank", "crank_radius": "100 mm", "rod_length": "80 mm"},
     {"displacement": "90 deg", "duration": "0.3 s"}, ("rod_length", "longer than")),
    ({"type": "four_bar", "crank": "0.1 m", "coupler": "0.2 m", "rocker": "0.15 m",
      "ground": "0.9 m"}, {"displacement": "90 deg", "duration": "0.3 s"}, ("cannot close",)),
    ({"type": "slider_crank", "crank_radius": "50 mm", "rod_length": "200 mm",
      "law_on": "output", "start_angle": "180 deg"},
     {"displacement": "150 mm", "duration": "0.3 s"}, ("task.displacement", "beyond its range")),
    ({"type": "slider_crank", "crank_radius": "50 mm", "rod_length": "200 mm",
      "law_on": "crank"}, {"displacement": "50 mm", "duration": "0.3 s"}, ("an angle",)),
])
def test_bad_linkages_exit_2(tmp_path: Path, stage: dict, task: dict,
                             fragments: tuple[str, ...]) -> None:
    design = {"task": task, "load": {"mass": "2 kg"} if stage["type"] == "slider_crank"
              else {"inertia": "0.01 kg*m^2"}, "transmission": [stage], "motors": [MOTOR]}
    path = tmp_path / "bad.yaml"
    path.write_text(yaml.safe_dump(design))
    assert_user_error(run_cli("size", str(path)), "bad.yaml", *fragments)


def test_a_four_bar_rocker_from_its_crank_law() -> None:
    # the paper's four-bar (Table 2) swinging a 0.02 kg*m^2 rocker: the crank turns
    # once in 0.4 s from its extended dead point; the rocker's swing is its whole range
    design = {"task": {"displacement": "360 deg", "duration": "0.4 s", "dwell": "0.1 s"},
              "load": {"inertia": "0.02 kg*m^2"},
              "transmission": [{"type": "four_bar", "crank": "75 mm", "coupler": "175 mm",
                                "rocker": "100 mm", "ground": "175 mm",
                                "start_angle": "0.31756 rad"}],
              "laws": ["cycloidal", "poly5"], "motors": [MOTOR]}
    results = size(design).results
    assert len(results) == 2 and all(r.feasible for r in results)
    low, high = 0.50536, 2.24593  # the rocker's swing (rad), between its dead points
    for r in results:  # the rocker's peak speed is below its swing over the move's time
        assert 0.0 < r.load_speed < 20 * (high - low) / 0.4


def _cycle_design(segments: list, laws: list | None = None) -> dict:
    design = _design({}, {"law_on": "crank"})
    del design["task"]
    design["cycle"] = {"segments": segments}
    if laws:
        design["laws"] = laws
    return design


def test_a_cycle_of_two_half_turns_through_the_linkage() -> None:
    # down from the top dead centre in 0.2 s, 0.1 s at the bottom, up in 0.3 s, 0.1 s at
    # the top: each half-turn is a cycloidal crank move from where the last one stopped
    segments = [{"move": {"displacement": "180 deg", "duration": "0.2 s", "name": "down"}},
                {"dwell": {"duration": "0.1 s", "name": "bottom"}},
                {"move": {"displacement": "180 deg", "duration": "0.3 s", "name": "up"}},
                {"dwell": {"duration": "0.1 s", "name": "top"}}]
    (result,) = size(_cycle_design(segments)).results
    u = np.linspace(0.0, 1.0, 400_001)
    down = _crank_torque(u, np.pi, 0.2)
    up = _crank_torque(u, np.pi, 0.3, start=np.pi)
    assert result.duration == pytest.approx(0.7)
    assert result.peak_torque == pytest.approx(max(np.abs(down).max(), np.abs(up).max()),
                                               rel=1e-6)
    square = 0.2 * np.trapezoid(down**2, u) + 0.3 * np.trapezoid(up**2, u)
    assert result.rms_torque == pytest.approx(math.sqrt(square / 0.7), rel=1e-6)


def test_a_cycle_through_the_linkage_minimized_by_time_scaling() -> None:
    # both half-turns free, sharing the time equally, the dwells fixed: the scale s is
    # the smallest that meets the limits; each half-turn then takes s
    segments = [{"move": {"displacement": "180 deg"}}, {"dwell": {"duration": "0.1 s"}},
                {"move": {"displacement": "180 deg"}}, {"dwell": {"duration": "0.1 s"}}]
    (result,) = size(_cycle_design(segments)).results
    u = np.linspace(0.0, 1.0, 400_001)
    at_one = [_crank_torque(u, np.pi, 1.0), _crank_torque(u, np.pi, 1.0, start=np.pi)]
    peak = max(np.abs(x).max() for x in at_one)
    square = sum(np.trapezoid(x**2, u) for x in at_one)
    t_peak = math.sqrt(peak / 150.0)
    t_rms = brentq(lambda T: square / T**3 / (2 * T + 0.2) - 50.0**2, 1e-3, 10.0)
    t_speed = 2 * np.pi / (3000 * 2 * np.pi / 60)  # C_v h / v_max, h = pi
    T = max(t_peak, t_rms, t_speed)
    assert result.duration == pytest.approx(2 * T + 0.2, rel=1e-6)


@pytest.mark.parametrize("crank, words", [
    ({"law_on": "output"}, ("cycle.segments", "needs the law on the crank")),
    ({"law_on": "crank", "duration": None}, ("cycle.segments", "needs its own duration"))])
def test_a_run_through_a_linkage_needs_the_law_on_the_crank_and_durations(
        tmp_path: Path, crank: dict, words: tuple) -> None:
    # the output cannot keep moving through its dead points; a move with boundary speeds
    # has a shape that depends on its duration, so it must be given
    first = {"displacement": "180 deg", "duration": "0.2 s", "end_speed": "60 rpm"}
    if crank.get("duration", "") is None:
        del first["duration"]
    segments = [{"move": first},
                {"run": {"speed": "60 rpm", "duration": "0.2 s"}},
                {"move": {"displacement": "180 deg", "duration": "0.2 s",
                          "start_speed": "60 rpm", "law": "poly5"}}]
    design = _cycle_design(segments, ["poly5"])
    design["transmission"][0]["law_on"] = crank["law_on"]
    if crank["law_on"] == "output":
        for segment in segments:
            key = "move" if "move" in segment else "run"
            if key == "move":
                segment[key]["displacement"] = "20 mm"
            for name in ("speed", "start_speed", "end_speed"):
                if name in segment[key]:
                    segment[key][name] = "0.1 m/s"
    path = tmp_path / "cycle.yaml"
    path.write_text(yaml.safe_dump(design))
    assert_user_error(run_cli("size", str(path)), "cycle.yaml", *words)


def test_energy_balance_of_a_move_through_the_linkage() -> None:
    # the crank turns half a revolution, top to bottom dead centre, against 20 N of
    # friction on the slider and a 30 N load, directly driven: the motor's work over the
    # move is the change of kinetic energy (0: at rest at both ends) plus the losses,
    # 20 N x 2r, plus the work against the load, 30 N x (-2r)
    from sizer.io.loader import load_design_data
    from sizer.sizing.samples import segment_breakdown

    task = {"displacement": "180 deg", "duration": "0.25 s", "dwell": "0.1 s"}
    data = _design(task, {"law_on": "crank"}, load={"mass": f"{M} kg", "friction": "20 N",
                                                    "force": "30 N"})
    design = load_design_data(data)
    (result,) = size(design).results
    breakdown = segment_breakdown(design, design.motors[0], result.spec, result.duration)
    move = breakdown.rows[0]
    assert move.energy == pytest.approx(20.0 * 2 * R - 30.0 * 2 * R, rel=1e-6)
    # holding the slider at the bottom dead centre takes no torque (s' = 0 there)
    assert breakdown.rows[1].peak_torque == pytest.approx(0.0, abs=1e-9)


def test_a_return_move_through_the_linkage_is_the_cycle_it_means() -> None:
    # half a turn out and half a turn back (the crank turns back), each 0.2 s, 0.1 s
    # dwells: the same as the cycle written out, with the task's duration reported
    task = {"displacement": "180 deg", "duration": "0.2 s", "dwell": "0.1 s",
            "return": True}
    (as_task,) = size(_design(task, {"law_on": "crank"})).results
    segments = [{"move": {"displacement": "180 deg", "duration": "0.2 s"}},
                {"dwell": {"duration": "0.1 s"}},
                {"move": {"displacement": "-180 deg", "duration": "0.2 s"}},
                {"dwell": {"duration": "0.1 s"}}]
    (as_cycle,) = size(_cycle_design(segments)).results
    assert as_task.duration == pytest.approx(0.2)
    assert as_task.rms_torque == pytest.approx(as_cycle.rms_torque, rel=1e-12)
    assert as_task.peak_torque == pytest.approx(as_cycle.peak_torque, rel=1e-12)
    u = np.linspace(0.0, 1.0, 400_001)
    out, back = _crank_torque(u, np.pi, 0.2), _crank_torque(u, -np.pi, 0.2, start=np.pi)
    square = 0.2 * (np.trapezoid(out**2, u) + np.trapezoid(back**2, u))
    assert as_task.rms_torque == pytest.approx(math.sqrt(square / 0.6), rel=1e-6)


def _quintic(s0: float, s1: float) -> np.ndarray:
    """The quintic q(u) with q(0) = 0, q(1) = 1, q'(0) = s0, q'(1) = s1 and q'' = 0 at
    both ends (ascending coefficients), by solving its six conditions."""
    rows = [[1, 0, 0, 0, 0, 0], [1, 1, 1, 1, 1, 1], [0, 1, 0, 0, 0, 0],
            [0, 1, 2, 3, 4, 5], [0, 0, 2, 0, 0, 0], [0, 0, 2, 6, 12, 20]]
    return np.linalg.solve(np.array(rows, dtype=float), [0, 1, s0, s1, 0, 0])


def test_a_crank_turning_on_through_a_run_between_moves() -> None:
    # the crank speeds up to 60 rpm over 90 deg in 0.2 s, runs at 60 rpm for 0.5 s (half a
    # turn), slows down to rest over 90 deg in 0.2 s and rests 0.1 s: each part's crank
    # motion is known (the run's theta = theta_0 + w t, the moves' quintics with those
    # boundary speeds), and so the torque (this test's formulas)
    w = 2 * np.pi
    segments = [{"move": {"displacement": "90 deg", "duration": "0.2 s",
                          "end_speed": "60 rpm"}},
                {"run": {"speed": "60 rpm", "duration": "0.5 s"}},
                {"move": {"displacement": "90 deg", "duration": "0.2 s",
                          "start_speed": "60 rpm"}},
                {"dwell": {"duration": "0.1 s"}}]
    (result,) = size(_cycle_design(segments, ["poly5"])).results
    u = np.linspace(0.0, 1.0, 200_001)
    h = np.pi / 2
    torques, squares, fastest = [], 0.0, w
    for start, (s0, s1), T in ((0.0, (0.0, w * 0.2 / h), 0.2),
                               (np.pi / 2 + np.pi, (w * 0.2 / h, 0.0), 0.2)):
        c = _quintic(s0, s1)
        poly = np.polynomial.Polynomial(c)
        theta = start + h * poly(u)
        speed, alpha = h * poly.deriv(1)(u) / T, h * poly.deriv(2)(u) / T**2
        d = 1e-4
        s1_ = (_s(theta + d) - _s(theta - d)) / (2 * d)
        s2_ = (_s(theta + d) - 2 * _s(theta) + _s(theta - d)) / d**2
        tau = 1e-4 * alpha + M * s1_ * (s2_ * speed**2 + s1_ * alpha)
        torques.append(tau)
        fastest = max(fastest, float(np.max(np.abs(speed))))
        squares += T * np.trapezoid(tau**2, u)
    theta = np.pi / 2 + np.pi * u  # the run
    d = 1e-4
    s1_ = (_s(theta + d) - _s(theta - d)) / (2 * d)
    s2_ = (_s(theta + d) - 2 * _s(theta) + _s(theta - d)) / d**2
    run = M * s1_ * s2_ * w**2
    squares += 0.5 * np.trapezoid(run**2, u)
    assert result.duration == pytest.approx(1.0)
    peak = max(np.abs(x).max() for x in [*torques, run])
    assert result.peak_torque == pytest.approx(peak, rel=1e-6)
    assert result.rms_torque == pytest.approx(math.sqrt(squares / 1.0), rel=1e-6)
    assert result.max_speed == pytest.approx(fastest, rel=1e-6)


def test_an_auto_shape_through_the_linkage_is_the_best_of_its_family() -> None:
    # a trapezoid with alpha = auto turning the crank once in 0.4 s: its smallest margin
    # is at least that of every fixed alpha of a grid, each sized through the linkage
    task = {"displacement": "360 deg", "duration": "0.4 s", "dwell": "0.1 s"}
    motor = {**MOTOR, "continuous_torque": "1 N*m", "peak_torque": "3 N*m"}
    (chosen,) = size(_design(task, {"law_on": "crank"}, laws=["trapezoidal(alpha=auto)"],
                             motors=[motor])).results
    grid = [f"trapezoidal(alpha={a:.2f})" for a in np.linspace(0.05, 0.5, 10)]
    fixed = size(_design(task, {"law_on": "crank"}, laws=grid, motors=[motor])).results
    assert chosen.spec.startswith("trapezoidal(alpha=") and "auto" not in chosen.spec
    assert chosen.worst_slack >= max(r.worst_slack for r in fixed) - 1e-6
