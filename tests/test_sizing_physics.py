"""Torque at the motor shaft pinned to hand-derived values (sec. 6.1.1 plus real loads)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sizer.laws import make_law
from sizer.model import Design, Limits, Load, Motor, Stage, Task, Transmission
from sizer.sizing import size_design

BIG = Motor("big", inertia=2e-4, continuous_torque=50.0, peak_torque=150.0, rated_speed=500.0)


def only(design):
    results = size_design(design).results
    assert len(results) == 1
    return results[0]


def gearbox(ratio, efficiency=1.0, inertia=0.0):
    return Transmission((Stage("gearbox", ratio, efficiency, inertia),))


def test_gearbox_reflects_inertia_as_j_l_over_k_squared():
    h, T, k, J_l, J_g = math.pi / 2, 0.25, 10.0, 0.35, 1.2e-4
    design = Design(Task(h, T), Load(J_l), gearbox(k, 1.0, J_g), laws=("cycloidal",),
                    motors=(BIG,))
    r = only(design)
    J_t = BIG.inertia + J_g + J_l / k**2
    assert r.max_speed == pytest.approx(2 * k * h / T, rel=1e-12)
    assert r.peak_torque == pytest.approx(J_t * k * 2 * math.pi * h / T**2, rel=1e-12)
    assert r.rms_torque == pytest.approx(J_t * k * math.sqrt(2) * math.pi * h / T**2, rel=1e-12)


def test_efficiency_divides_while_driving_and_multiplies_while_braking():
    h, T, k, eta, J_l = 1.0, 0.5, 5.0, 0.8, 0.2
    design = Design(Task(h, T), Load(J_l), gearbox(k, eta), laws=("cycloidal",), motors=(BIG,))
    r = only(design)
    a_peak = 2 * math.pi * h / T**2
    accelerating = BIG.inertia * k + J_l / (k * eta)
    braking = BIG.inertia * k + J_l * eta / k
    assert r.peak_torque == pytest.approx(accelerating * a_peak, rel=1e-10)
    # symmetric law: half of int a^2 while accelerating, half while braking
    a_rms = math.sqrt(2) * math.pi * h / T**2
    expected = a_rms * math.sqrt((accelerating**2 + braking**2) / 2)
    assert r.rms_torque == pytest.approx(expected, rel=1e-10)


def test_damping_and_friction_in_the_rms_closed_form():
    h, T, k, J_l, B_l, F = 2.0, 0.4, 3.0, 0.05, 0.2, 0.7
    motor = Motor("m", inertia=1e-4, continuous_torque=50, peak_torque=150, rated_speed=500,
                  damping=1e-3)
    design = Design(Task(h, T), Load(J_l, damping=B_l, friction=F), gearbox(k),
                    laws=("poly5",), motors=(motor,))
    r = only(design)
    c = make_law("poly5").coefficients
    P = (motor.inertia * k + J_l / k) * h / T**2
    Q = (motor.damping * k + B_l / k) * h / T
    R = F / k
    # (1/T) int (P a_N + Q v_N + R)^2 dt with int a_N = 0, int a_N v_N = 0, int v_N = 1
    expected = math.sqrt(P**2 * c.C_a_rms**2 + Q**2 * c.C_v_rms**2 + R**2 + 2 * Q * R)
    assert r.rms_torque == pytest.approx(expected, rel=1e-12)


def test_rms_over_a_cycle_with_return_and_dwell():
    h, T, dwell, J_l = 1.0, 0.3, 0.2, 0.1
    design = Design(Task(h, T, dwell=dwell, return_move=True), Load(J_l), laws=("cycloidal",),
                    motors=(BIG,))
    r = only(design)
    J_t = BIG.inertia + J_l
    per_move = J_t * math.sqrt(2) * math.pi * h / T**2
    assert r.rms_torque == pytest.approx(per_move * math.sqrt(T / (T + dwell)), rel=1e-12)


def vertical_axis_by_hand(alpha, h, T, dwell, k, eta, J_m, J_l, G):
    """Trapezoid up, dwell, down, dwell with gravity torque G at the load (by hand).

    Up (direction +1) the load torque is J_l a + G; down it is J_l a - G along the motion.
    Each phase has constant acceleration, so every torque is constant per phase.
    """
    a = h / (alpha * (1 - alpha) * T**2)

    def motor(a_load, u):
        reflected = u / (k * eta) if u >= 0 else u * eta / k
        return J_m * k * a_load + reflected

    phases = []
    for g in (G, -G):  # up, then down
        phases += [(alpha * T, motor(a, J_l * a + g)),
                   ((1 - 2 * alpha) * T, motor(0.0, g)),
                   (alpha * T, motor(-a, -J_l * a + g))]
    hold = abs(G) / (k * eta)
    phases += [(dwell, hold), (dwell, hold)]
    cycle = sum(t for t, _ in phases)
    rms = math.sqrt(sum(t * tau**2 for t, tau in phases) / cycle)
    peak = max(abs(tau) for _, tau in phases)
    return rms, peak


@pytest.mark.parametrize("G", [0.5, 3.0, -1.0])
def test_vertical_axis_with_gravity_and_efficiency(G):
    alpha, h, T, dwell, k, eta, J_l = 0.25, 1.5, 0.6, 0.4, 4.0, 0.85, 0.3
    design = Design(Task(h, T, dwell=dwell, return_move=True), Load(J_l, torque=G),
                    gearbox(k, eta), laws=(f"trapezoidal(alpha={alpha})",), motors=(BIG,))
    r = only(design)
    rms, peak = vertical_axis_by_hand(alpha, h, T, dwell, k, eta, BIG.inertia, J_l, G)
    assert r.rms_torque == pytest.approx(rms, rel=1e-10)
    assert r.peak_torque == pytest.approx(peak, rel=1e-10)


def test_constant_load_alone_beyond_continuous_torque_is_infeasible():
    motor = Motor("small", inertia=1e-4, continuous_torque=1.0, peak_torque=3.0,
                  rated_speed=300.0)
    design = Design(Task(1.0, None, dwell=1.0), Load(0.01, torque=2.0), laws=("cycloidal",),
                    motors=(motor,))
    r = only(design)
    assert not r.feasible
    assert r.duration is None
    assert r.limiting == "rms"
    assert "no duration is feasible" in r.reason


def test_limits_on_inertia_ratio_acceleration_and_jerk():
    design = Design(Task(1.0, None), Load(0.1), laws=("trapezoidal(alpha=1/3)", "cycloidal"),
                    motors=(BIG,), limits=Limits(inertia_ratio=100.0))
    assert all(not r.feasible and r.limiting == "inertia_ratio"
               for r in size_design(design).results)  # 0.1 / 2e-4 = 500 > 100
    limits = Limits(max_acceleration=50.0, max_jerk=2000.0)
    design = Design(Task(1.0, None), Load(1e-3), laws=("trapezoidal(alpha=1/3)", "cycloidal"),
                    motors=(BIG,), limits=limits)
    by_law = {r.law: r for r in size_design(design).results}
    assert not by_law["trapezoidal"].feasible  # jerk impulses: no jerk limit holds
    assert by_law["trapezoidal"].limiting == "jerk"
    cyc = by_law["cycloidal"]
    t_acc = math.sqrt(2 * math.pi / 50.0)
    t_jerk = (4 * math.pi**2 / 2000.0) ** (1 / 3)
    assert cyc.duration == pytest.approx(max(t_acc, t_jerk), rel=1e-12)
    assert cyc.limiting == ("acceleration" if t_acc > t_jerk else "jerk")


def test_speed_torque_curve_limits_the_peak_at_speed():
    # intermittent torque falls from 10 N*m at 100 rad/s to 2 N*m at 200 rad/s
    curve = ((0.0, 10.0), (100.0, 10.0), (200.0, 2.0))
    motor = Motor("curve", inertia=1e-3, continuous_torque=9.0, peak_torque=10.0,
                  rated_speed=100.0, max_speed=200.0, intermittent_curve=curve,
                  continuous_curve=((0.0, 9.0), (200.0, 9.0)))
    h, J = 30.0, 0.004
    design = Design(Task(h, 0.2), Load(J), laws=("cycloidal",), motors=(motor,))
    r = only(design)
    assert r.check("speed").margin == pytest.approx(1 - 300 / 200)  # 2 h / T = 300 rad/s
    assert not r.feasible

    def worst_ratio(T):  # brute force on a dense grid, independent of the engine
        tau = np.linspace(0.0, 1.0, 200_001)
        speed = h / T * (1 - np.cos(2 * np.pi * tau))
        torque = np.abs((motor.inertia + J) * 2 * np.pi * h / T**2 * np.sin(2 * np.pi * tau))
        limit = np.interp(speed, [0, 100, 200], [10, 10, 2])
        return np.max(torque / limit)

    lo, hi = 0.3, 1.0  # speed alone needs T >= 0.3
    assert worst_ratio(lo) > 1.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if worst_ratio(mid) <= 1.0 else (mid, hi)
    t_min = only(Design(Task(h, None), Load(J), laws=("cycloidal",), motors=(motor,)))
    assert t_min.feasible
    assert t_min.limiting == "peak"
    assert t_min.duration == pytest.approx(hi, rel=1e-8)
    assert t_min.check("peak").margin == pytest.approx(0.0, abs=1e-9)


def test_task_curve_samples_the_cycle_of_example_6_1():
    from sizer.sizing.samples import task_curve

    motor = Motor("ex6_1", inertia=0.0, continuous_torque=8.0, peak_torque=20.0,
                  rated_speed=10.0)
    design = Design(Task(15.0, 3.0, dwell=1.0, return_move=True), Load(1.0, damping=0.3),
                    laws=("cycloidal",), motors=(motor,))
    curve = task_curve(design, motor, "cycloidal", 3.0, samples=201)
    t = curve.time[:201]
    x = 2 * np.pi * t / 3.0
    speed = 15 / 3 * (1 - np.cos(x))
    torque = 2 * np.pi * 15 / 9 * np.sin(x) + 0.3 * speed  # J a + B v of eq. (6.1)
    assert curve.motor_speed[:201] == pytest.approx(speed, abs=1e-12)
    assert curve.motor_torque[:201] == pytest.approx(torque, abs=1e-12)
    assert curve.motor_speed.min() == pytest.approx(-10.0)  # the move back
    assert curve.time[-1] == pytest.approx(8.0)
    assert curve.position[-1] == pytest.approx(0.0, abs=1e-12)
    assert curve.intermittent_region == ((0.0, 20.0), (10.0, 20.0))
