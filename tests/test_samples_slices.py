"""One sampled cycle and its slices (sizer.sizing.samples): one candidate's curves are its
row of every candidate's samples, the segments the curves mark are the sampled times, and a
move through a linkage that starts and ends at rest shows no acceleration step."""

from __future__ import annotations

import numpy as np
import pytest

from sizer.io.loader import load_design_data
from sizer.laws import make_law
from sizer.mechanics import Drive
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.cycle import SegmentCycle
from sizer.sizing.samples import segment_breakdown, segment_samples, task_curve

MOTORS = [{"id": f"M{k}", "inertia": f"{k * 1e-3} kg*m^2", "continuous_torque": "8 N*m",
           "peak_torque": "20 N*m", "rated_speed": "300 rad/s", "damping": "0.01 N*m*s/rad"}
          for k in (1, 2)]
LOAD = {"inertia": "0.02 kg*m^2", "damping": "0.05 N*m*s/rad", "friction": "0.3 N*m"}


def test_the_curves_mark_the_segments_at_the_duration_asked() -> None:
    # a task of 0.4 s moves drawn at 0.5 s: move, dwell, return, dwell end at
    # T, T + d, 2T + d, 2T + 2d with T = 0.5 s, d = 0.25 s
    d = load_design_data({"task": {"displacement": "3 rad", "duration": "0.4 s",
                                   "dwell": "0.25 s", "return": True},
                          "load": LOAD, "laws": ["cycloidal"], "motors": MOTORS[:1]})
    curve = task_curve(d, d.motors[0], "cycloidal", 0.5, samples=51)
    assert [name for name, _, _ in curve.segments] == ["move", "dwell", "return", "dwell 2"]
    ends = [end for _, _, end in curve.segments]
    assert ends == pytest.approx([0.5, 0.75, 1.25, 1.5], rel=1e-15)
    assert curve.time[-1] == pytest.approx(1.5, rel=1e-15)


def test_each_candidate_of_a_cycle_of_segments_is_its_curve() -> None:
    # from rest to 1 rad/s, a run at 1 rad/s, back to rest, a dwell; the moves by poly5
    # between their boundary speeds (each candidate's own polynomial)
    d = load_design_data({
        "cycle": {"segments": [
            {"move": {"displacement": "0.4 rad", "duration": "0.5 s", "end_speed": "1 rad/s"}},
            {"run": {"speed": "1 rad/s", "duration": "0.3 s"}},
            {"move": {"displacement": "0.4 rad", "duration": "0.5 s",
                      "start_speed": "1 rad/s"}},
            {"dwell": {"duration": "0.2 s"}}]},
        "load": LOAD, "laws": ["poly5"], "motors": MOTORS})
    law = make_law("poly5")
    motors = MotorArrays.of(d.motors, d.limits.envelope)
    assert d.cycle is not None
    calc = SegmentCycle(d.cycle, law, Drive(d.load, d.transmission), motors,
                        d.limits.thermal_speed)
    got = segment_samples(calc, np.ones(2), samples=101)
    assert got.cycle_time == pytest.approx([1.5, 1.5], rel=1e-15)
    for k, motor in enumerate(d.motors):
        curve = task_curve(d, motor, law, 1.5, samples=101)
        np.testing.assert_allclose(got.time[k], curve.time, rtol=1e-15)
        np.testing.assert_allclose(got.torque[k], curve.motor_torque, rtol=0, atol=1e-12)
        np.testing.assert_allclose(got.speed[k], curve.motor_speed, rtol=0, atol=1e-12)
    # the run at 1 rad/s, directly driven: no acceleration, so the torque is the load's
    # damping and friction at that speed plus the rotor's damping, (0.05 + 0.3 + 0.01) N*m
    run = np.flatnonzero((curve.time >= 0.5) & (curve.time <= 0.8))[-3:-1]
    assert curve.time[run] == pytest.approx([0.5, 0.8], rel=1e-15)
    assert curve.motor_torque[run] == pytest.approx([0.36, 0.36], rel=1e-12)

def test_a_move_from_rest_through_a_linkage_has_no_acceleration_step() -> None:
    # cycloidal on the crank: the acceleration is 0 at both ends, so the joins with the
    # dwell show no jerk impulse (round-off below the join tolerance reads 0)
    d = load_design_data({
        "task": {"displacement": "180 deg", "duration": "0.25 s", "dwell": "0.1 s"},
        "load": {"mass": "2 kg", "force": "30 N"},
        "transmission": [{"type": "slider_crank", "crank_radius": "50 mm",
                          "rod_length": "200 mm", "law_on": "crank"}],
        "laws": ["cycloidal"], "motors": [{**MOTORS[0], "peak_torque": "200 N*m",
                                          "continuous_torque": "100 N*m"}]})
    rows = segment_breakdown(d, d.motors[0], "cycloidal", 0.25).rows
    assert [(r.kind, r.start, r.end) for r in rows] == [("move", 0.0, 0.25),
                                                       ("dwell", 0.25, pytest.approx(0.35))]
    assert [r.acceleration_step for r in rows] == [0.0, 0.0]
