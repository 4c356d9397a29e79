"""Shape parameters written `auto` are chosen by the solver (checked by brute force)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sizer.model import Design, Limits, Load, Motor, Task
from sizer.sizing import size_design

MOTOR = Motor("m", inertia=1e-3, continuous_torque=4.0, peak_torque=12.0, rated_speed=3.0)
J_T = 1.0 + MOTOR.inertia


def trapezoid_t_min(alpha, v_max, tau_p, tau_c):
    """eq. (6.2) with the closed-form trapezoid coefficients (sec. 6.2.1)."""
    c_v, c_a = 1 / (1 - alpha), 1 / (alpha * (1 - alpha))
    c_a_rms = math.sqrt(2 * alpha) * c_a
    return max(c_v / v_max, math.sqrt(c_a * J_T / tau_p), math.sqrt(c_a_rms * J_T / tau_c))


def test_fastest_trapezoid_under_speed_peak_and_rms():
    design = Design(Task(1.0, None), Load(1.0), laws=("trapezoidal(alpha=auto)",),
                    motors=(MOTOR,))
    r = size_design(design).results[0]
    alphas = np.linspace(1e-4, 0.5, 100_001)
    brute = [trapezoid_t_min(a, 3.0, 12.0, 4.0) for a in alphas]
    best = int(np.argmin(brute))
    assert r.law == "trapezoidal"
    assert r.params["alpha"] == pytest.approx(alphas[best], abs=2e-3)
    assert r.duration == pytest.approx(brute[best], rel=1e-5)
    assert r.duration == pytest.approx(trapezoid_t_min(r.params["alpha"], 3.0, 12.0, 4.0),
                                       rel=1e-12)


def test_fastest_double_s_under_speed_acceleration_and_jerk_limits():
    # a strong motor: the load's acceleration and jerk limits bind (sec. 3.4)
    strong = Motor("s", inertia=1e-3, continuous_torque=1e4, peak_torque=1e4, rated_speed=1e4)
    v_max, a_max, j_max, h = 2.0, 10.0, 60.0, 1.0
    limits = Limits(max_acceleration=a_max, max_jerk=j_max)
    design = Design(Task(h, None), Load(1.0), laws=("double_s(alpha=auto, beta=auto)",),
                    motors=(strong,), limits=limits)
    design_speed = Design(Task(h, None), Load(1.0), laws=("double_s(alpha=auto, beta=auto)",),
                          motors=(Motor("v", 1e-3, 1e4, 1e4, v_max),), limits=limits)
    for d, speed in ((design, 1e4), (design_speed, v_max)):
        r = size_design(d).results[0]
        a, b = np.meshgrid(np.linspace(0.01, 0.5, 400), np.linspace(0.01, 0.5, 400))
        c_v = 1 / (1 - a)
        c_a = 1 / (a * (1 - a) * (1 - b))
        c_j = 1 / (a**2 * b * (1 - a) * (1 - b))
        t = np.maximum.reduce([c_v * h / speed, np.sqrt(c_a * h / a_max),
                               np.cbrt(c_j * h / j_max)])
        assert r.feasible
        assert r.duration <= t.min() * (1 + 2e-3)
        assert r.duration >= t.min() * (1 - 2e-3)


def test_auto_with_a_given_duration_maximizes_the_margin():
    design = Design(Task(1.0, 1.2), Load(1.0), laws=("trapezoidal(alpha=auto)",),
                    motors=(MOTOR,))
    r = size_design(design).results[0]
    assert r.feasible
    for alpha in (0.2, 0.3, 0.4, 0.5):
        fixed = Design(Task(1.0, 1.2), Load(1.0), laws=(f"trapezoidal(alpha={alpha})",),
                       motors=(MOTOR,))
        assert size_design(fixed).results[0].worst_slack <= r.worst_slack + 1e-12
