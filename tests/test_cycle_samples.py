"""The sampled machine cycle of all candidates (sizer.sizing.cycle_samples) against the
one-candidate task curve (sizer.sizing.profile.task_curve) and a closed form."""

from __future__ import annotations

import numpy as np
import pytest

from sizer.errors import UserError
from sizer.io.loader import load_design_data
from sizer.laws import make_law
from sizer.mechanics import Drive
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.move import CycleCalculator
from sizer.sizing.samples import cycle_samples, motor_trace, task_curve

MOTORS = [{"id": f"M{k}", "inertia": f"{k * 1e-3} kg*m^2", "continuous_torque": "8 N*m",
           "peak_torque": "20 N*m", "rated_speed": "300 rad/s", "damping": "0.01 N*m*s/rad"}
          for k in (1, 2, 3)]


def design(**load) -> dict:
    return {"task": {"displacement": "3 rad", "duration": "0.4 s", "dwell": "0.25 s",
                     "return": True},
            "load": {"inertia": "0.02 kg*m^2", "damping": "0.05 N*m*s/rad",
                     "friction": "0.3 N*m", **load},
            "transmission": {"type": "gearbox", "ratio": 3, "efficiency": 0.85},
            "laws": ["cycloidal"], "motors": MOTORS}


def calculator(d, law):
    motors = MotorArrays.of(d.motors, d.limits.envelope)
    return CycleCalculator(None, d.task, Drive(d.load, d.transmission), motors,
                           d.limits.thermal_speed, law=law)


@pytest.mark.parametrize("spec", ["cycloidal", "trapezoidal", "modified_trapezoidal"])
@pytest.mark.parametrize("load", [{}, {"torque": "1.5 N*m"}])
def test_each_candidate_matches_its_task_curve(spec, load):
    d = load_design_data(design(**load))
    law = make_law(spec)
    T = np.array([0.4, 0.5, 0.7])
    got = cycle_samples(d, calculator(d, law), T, samples=401)
    for k, motor in enumerate(d.motors):
        curve = task_curve(d, motor, law, float(T[k]), samples=401)
        assert got.time[k] == pytest.approx(curve.time, abs=1e-12)
        np.testing.assert_allclose(got.torque[k], curve.motor_torque, rtol=0, atol=1e-9)
        np.testing.assert_allclose(got.speed[k], curve.motor_speed, rtol=0, atol=1e-9)
        assert got.cycle_time[k] == pytest.approx(2 * T[k] + 2 * 0.25, rel=1e-15)


@pytest.mark.parametrize("spec", ["cycloidal", "modified_trapezoidal"])
def test_the_motor_trace_is_the_task_curves_own_series(spec):
    """sizer.sizing.samples.motor_trace (what the shared DC bus reads) is the task curve's
    time, motor torque and speed without its figures: the same arrays, bit for bit."""
    d = load_design_data(design(torque="1.5 N*m"))
    law = make_law(spec)
    curve = task_curve(d, d.motors[1], law, 0.5, samples=301)
    time, torque, speed = motor_trace(d, d.motors[1], law, 0.5, samples=301)
    for mine, theirs in ((time, curve.time), (torque, curve.motor_torque),
                         (speed, curve.motor_speed)):
        assert np.array_equal(mine, theirs)


def test_a_pure_inertia_on_a_constant_acceleration_move():
    """Trapezoidal speed (1/3 accelerating): tau = J_total K a at the motor, with the load's
    share divided by eta while accelerating and multiplied by it while braking."""
    d = load_design_data({**design(), "load": {"inertia": "0.02 kg*m^2"},
                          "motors": [{**MOTORS[0], "damping": 0}]})
    law = make_law("trapezoidal")
    T, h, K, eta, J_m, J_l = 0.4, 3.0, 3.0, 0.85, 1e-3, 0.02
    got = cycle_samples(d, calculator(d, law), np.array([T]))
    a = 4.5 * h / T**2  # C_a of the 1/3 trapezoid
    t, tau = got.time[0], got.torque[0]
    inside = (t > 0.01 * T) & (t < T / 3 - 0.01 * T)
    assert tau[inside] == pytest.approx(J_m * K * a + J_l * a / K / eta, rel=1e-12)
    braking = (t > 2 * T / 3 + 0.01 * T) & (t < 0.99 * T)
    assert tau[braking] == pytest.approx(-(J_m * K * a + J_l * a / K * eta), rel=1e-12)
    assert got.speed[0].max() == pytest.approx(K * 1.5 * h / T, rel=1e-12)


def test_a_cycle_of_segments_is_refused():
    d = load_design_data({
        "cycle": {"segments": [{"move": {"displacement": "1 rad", "duration": "1 s"}},
                               {"dwell": {"duration": "0.5 s"}}]},
        "load": {"inertia": "0.02 kg*m^2"}, "laws": ["cycloidal"], "motors": MOTORS[:1]})
    with pytest.raises(UserError) as error:
        cycle_samples(d, None, np.array([1.0]))  # type: ignore[arg-type]
    assert error.value.field == "cycle" and "cycle of segments" in str(error.value)
