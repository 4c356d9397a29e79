"""Transmission stages, chains, stage limits and the ratio choice, pinned by hand."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from sizer.mechanics import (
    GRAVITY,
    Drive,
    ball_screw,
    belt,
    gearbox,
    linear_load,
    rack_pinion,
    screw_inertia,
)
from sizer.model import (
    Design,
    GearboxOption,
    Limits,
    Load,
    Motor,
    RatioChoice,
    Stage,
    Task,
    Transmission,
)
from sizer.sizing import size_design

MOTOR = Motor("m", inertia=1e-4, continuous_torque=50.0, peak_torque=150.0,
              rated_speed=1000.0)


def only(design):
    (result,) = size_design(design).results
    return result


# ------------------------------------------------------------- stage formulas
def test_stage_ratios_and_reflected_inertias():
    assert gearbox(10, 0.95, 1.2e-4).ratio == 10
    b = belt(driver_diameter=0.04, driven_diameter=0.12, driver_inertia=1e-5,
             driven_inertia=9e-5, belt_mass=0.2)
    assert b.ratio == pytest.approx(3.0)
    assert b.inertia == pytest.approx(1e-5 + 9e-5 / 9 + 0.2 * 0.02**2)
    lin = belt(driver_diameter=0.05, driver_inertia=2e-5, driven_inertia=2e-5, belt_mass=0.3,
               linear=True)
    assert lin.ratio == pytest.approx(40.0)  # rad/m: v = omega d/2
    assert lin.inertia == pytest.approx(4e-5 + 0.3 * 0.025**2)
    assert screw_inertia(0.016, 0.5) == pytest.approx(math.pi * 7850 * 0.5 * 0.016**4 / 32)
    s = ball_screw(0.01, diameter=0.016, length=0.5, preload_torque=0.02,
                   max_speed=3000 * math.pi / 30)
    assert s.ratio == pytest.approx(2 * math.pi / 0.01)
    assert s.inertia == pytest.approx(screw_inertia(0.016, 0.5))
    assert rack_pinion(0.03, inertia=1e-4).ratio == pytest.approx(1 / 0.03)


def test_chain_reflects_inertia_like_the_book():
    drive = Drive(Load(2.0), Transmission((gearbox(5, inertia=3e-5), ball_screw(0.01,
                                                                              inertia=2e-5))))
    K = 5 * 2 * math.pi / 0.01
    assert drive.ratio == pytest.approx(K)
    assert drive.transmission_inertia == pytest.approx(3e-5 + 2e-5 / 25)
    a_part, _, _ = drive.linear_chain(1.0)
    # shaft torque per load acceleration: (J_gear + J_screw/k1^2) K + m/K
    assert a_part == pytest.approx((3e-5 + 2e-5 / 25) * K + 2.0 / K)


def test_linear_load_on_an_incline():
    load = linear_load(10.0, incline=math.radians(30), friction_coefficient=0.1,
                       friction_force=5.0, force=20.0)
    assert load.torque == pytest.approx(20 + 10 * GRAVITY * 0.5)
    assert load.friction == pytest.approx(5 + 0.1 * 10 * GRAVITY * math.cos(math.radians(30)))
    vertical = linear_load(4.0, incline=math.pi / 2, friction_coefficient=0.3)
    assert vertical.torque == pytest.approx(4 * GRAVITY)
    assert vertical.friction == pytest.approx(0.0, abs=1e-12)


# ----------------------------------------------------- torques through a chain
def trapezoid_phases(alpha, h, T):
    """(duration, load acceleration, peak load speed) of the trapezoid's three phases."""
    a = h / (alpha * (1 - alpha) * T**2)
    return [(alpha * T, a), ((1 - 2 * alpha) * T, 0.0), (alpha * T, -a)]


def reflect(x, k, eta):
    return x / (k * eta) if x >= 0 else x * eta / k


def test_ball_screw_pick_and_place_by_hand():
    """A 5 kg carriage moved 200 mm in 0.4 s up a 45 deg incline and back, 0.2 s dwells.

    Motor 1e-4 kg*m^2 drives a 10 mm lead screw (d 16 mm, L 0.5 m: J_s = 2.53e-5
    kg*m^2, efficiency 0.9, preload 0.02 N*m) through a 3:1 belt (efficiency 0.95).
    With a trapezoid (alpha = 1/4) every phase has a constant acceleration a, so along
    the motion: u = m a + F_fric + s m g sin 45 (s = +1 up, -1 down), screw input
    x1 = J_s k2 a + T_pre + R(u; k2, 0.9), motor = (J_m + J_belt) K a + R(x1; 3, 0.95).
    At rest the motor holds m g sin 45 / (K * 0.9 * 0.95).
    """
    m, h, T, dwell, alpha = 5.0, 0.2, 0.4, 0.2, 0.25
    load = linear_load(m, incline=math.pi / 4, friction_coefficient=0.05)
    screw = ball_screw(0.01, efficiency=0.9, diameter=0.016, length=0.5, preload_torque=0.02)
    pulleys = belt(ratio=3.0, driver_inertia=1e-5, driven_inertia=9e-5, efficiency=0.95)
    k1, k2 = 3.0, 2 * math.pi / 0.01
    K = k1 * k2
    design = Design(Task(h, T, dwell=dwell, return_move=True, linear=True), load,
                    Transmission((pulleys, screw)), laws=(f"trapezoidal(alpha={alpha})",),
                    motors=(MOTOR,))
    r = only(design)
    J_in = MOTOR.inertia + pulleys.inertia
    phases = []
    for s in (1.0, -1.0):
        for duration, a in trapezoid_phases(alpha, h, T):
            u = m * a + load.friction + s * load.torque
            x1 = screw.inertia * k2 * a + 0.02 + reflect(u, k2, 0.9)
            phases.append((duration, J_in * K * a + reflect(x1, k1, 0.95)))
    hold = load.torque / (K * 0.9 * 0.95)
    phases += [(dwell, hold)] * 2
    cycle = sum(d for d, _ in phases)
    assert r.rms_torque == pytest.approx(
        math.sqrt(sum(d * t**2 for d, t in phases) / cycle), rel=1e-10)
    assert r.peak_torque == pytest.approx(max(abs(t) for _, t in phases), rel=1e-10)
    assert r.max_speed == pytest.approx(K * h / ((1 - alpha) * T), rel=1e-12)
    assert r.load_speed == pytest.approx(h / ((1 - alpha) * T), rel=1e-12)


def test_gearbox_limits_are_checked_like_the_motor():
    alpha, h, T, J_l, k, eta = 1 / 3, 1.0, 0.5, 1.2, 8.0, 0.9
    stage = gearbox(k, eta, 5e-5, max_input_speed=50.0, rated_output_torque=10.0,
                    peak_output_torque=20.0)
    design = Design(Task(h, T), Load(J_l), Transmission((stage,)),
                    laws=(f"trapezoidal(alpha={alpha})",), motors=(MOTOR,))
    r = only(design)
    a = h / (alpha * (1 - alpha) * T**2)
    out_peak = J_l * a  # the load's torque is the gearbox's output torque
    out_rms = J_l * a * math.sqrt(2 * alpha)
    speed = k * h / ((1 - alpha) * T)
    assert r.check("gearbox_peak").value == pytest.approx(out_peak, rel=1e-10)
    assert r.check("gearbox_peak").margin == pytest.approx(1 - out_peak / 20.0, rel=1e-10)
    assert r.check("gearbox_rms").value == pytest.approx(out_rms, rel=1e-10)
    assert r.check("gearbox_speed").value == pytest.approx(speed, rel=1e-12)
    # a = 18 rad/s^2: output peak 21.6 > 20 and RMS 17.6 > 10 N*m; input speed 24 < 50
    assert r.check("gearbox_speed").passed
    assert not r.feasible
    assert r.limiting == "gearbox_rms"


# ---------------------------------------------------------------- ratio choice
def test_optimal_ratio_is_the_inertia_match_for_a_given_duration():
    J_l = 0.5
    design = Design(Task(1.0, 0.5), Load(J_l), Transmission((gearbox(10.0),)),
                    laws=("cycloidal",), motors=(MOTOR,),
                    ratio_choice=RatioChoice(0, bounds=(1.0, 300.0)))
    r = only(design)
    assert r.ratio == pytest.approx(math.sqrt(J_l / MOTOR.inertia), rel=3e-3)  # 70.7
    # RMS (J_m k + J_l/k) C_a_rms h/T^2 at its minimum 2 sqrt(J_m J_l)
    best = 2 * math.sqrt(MOTOR.inertia * J_l) * math.sqrt(2) * math.pi / 0.25
    assert r.rms_torque == pytest.approx(best, rel=1e-5)


def test_optimal_ratio_for_t_min_matches_a_brute_force_scan():
    motor = Motor("s", inertia=2e-4, continuous_torque=2.0, peak_torque=6.0, rated_speed=300.0)
    load = Load(0.5, friction=0.5)
    base = Design(Task(math.pi / 2, None, dwell=0.1), load, Transmission((gearbox(10.0, 0.95),)),
                  laws=("poly5",), motors=(motor,))
    free = Design(**{**base.__dict__, "ratio_choice": RatioChoice(0, bounds=(2.0, 100.0))})
    r = only(free)
    scan = np.geomspace(2.0, 100.0, 150)
    durations = []
    for k in scan:
        fixed = Design(**{**base.__dict__, "transmission": Transmission((gearbox(k, 0.95),))})
        res = only(fixed)
        durations.append(res.duration if res.feasible else np.inf)
    best = int(np.argmin(durations))
    assert r.feasible
    # the optimizer searches finer than the scan (2.7 % steps): never worse, barely better
    assert r.duration <= durations[best] * (1 + 1e-9)
    assert r.duration >= durations[best] * (1 - 2e-3)
    assert r.ratio == pytest.approx(scan[best], rel=5e-2)


def test_ratio_list_and_gearbox_catalog_options():
    J_l = 0.5
    listed = Design(Task(1.0, 0.5), Load(J_l), Transmission((gearbox(10.0),)),
                    laws=("cycloidal",), motors=(MOTOR,),
                    ratio_choice=RatioChoice(0, ratios=(5.0, 50.0, 100.0)))
    assert only(listed).ratio == 50.0  # nearest to the inertia match 70.7 in RMS
    strong = GearboxOption("GB-big", gearbox(20.0, 0.9, 1e-4, peak_output_torque=500.0))
    weak = GearboxOption("GB-small", gearbox(50.0, 0.97, 2e-5, peak_output_torque=10.0))
    catalog = Design(Task(1.0, 0.5), Load(J_l), Transmission((gearbox(10.0),)),
                     laws=("cycloidal",), motors=(MOTOR,),
                     ratio_choice=RatioChoice(0, gearboxes=(strong, weak)))
    r = only(catalog)
    # the 50:1 gearbox would give the lower RMS, but its output peak J_l*2pi*4 = 12.6 > 10
    assert r.gearbox == "GB-big"
    assert r.ratio == 20.0
    assert r.feasible


def test_limits_margin_applies_to_stage_torques():
    stage = gearbox(8.0, 1.0, 0.0, peak_output_torque=20.0)
    design = Design(Task(1.0, 0.5), Load(0.4), Transmission((stage,)), laws=("cycloidal",),
                    motors=(MOTOR,), limits=Limits(torque_margin=0.2))
    r = only(design)
    out_peak = 0.4 * 2 * math.pi / 0.25
    assert r.check("gearbox_peak").required == 0.2
    assert r.check("gearbox_peak").passed == (1 - out_peak / 20 >= 0.2)


def test_stage_without_efficiency_loss_keeps_the_closed_form():
    stage = Stage("gearbox", 4.0, 1.0, 1e-5)
    design = Design(Task(2.0, None), Load(0.3), Transmission((stage,)), laws=("cycloidal",),
                    motors=(MOTOR,))
    r = only(design)
    J_t = MOTOR.inertia + 1e-5 + 0.3 / 16
    expected = max(2 * 4 * 2.0 / 1000.0, math.sqrt(2 * math.pi * 4 * 2.0 * J_t / 150.0),
                   math.sqrt(math.sqrt(2) * math.pi * 4 * 2.0 * J_t / 50.0))
    assert r.duration == pytest.approx(expected, rel=1e-12)


# ------------------------------------------------- vendor conventions (issue 9)
def test_ball_screw_density_is_a_parameter():
    # Yaskawa's 7.87e3 and Mitsubishi's 7.8e3 kg/m^3 against the default 7.85e3
    for rho in (7870.0, 7800.0):
        s = ball_screw(0.01, diameter=0.02, length=1.0, density=rho)
        assert s.inertia == pytest.approx(math.pi * rho * 1.0 * 0.02**4 / 32, rel=1e-14)
    assert ball_screw(0.01, diameter=0.02, length=1.0).inertia == pytest.approx(
        math.pi * 7850 * 0.02**4 / 32, rel=1e-14)


def steady(x, k, eta):
    """Yaskawa: a steady torque x at a stage output needs x/(k eta) while it opposes the
    motion, x eta/k while it drives."""
    return x / (k * eta) if x >= 0 else x * eta / k


def test_steady_load_convention_by_hand():
    """The pick-and-place axis above with the efficiencies on the steady load only.

    Inertial torque at the motor: (J_m + J_belt) K a + (J_s k2 a + m a / k2) / k1, no
    efficiency; steady torque: F = F_fric + s m g sin 45 through the screw (0.9, plus the
    preload) and the belt (0.95), divided while it opposes the move and multiplied while
    gravity drives it (the move down: F < 0).
    """
    m, h, T, dwell, alpha = 5.0, 0.2, 0.4, 0.2, 0.25
    load = linear_load(m, incline=math.pi / 4, friction_coefficient=0.05)
    screw = ball_screw(0.01, efficiency=0.9, diameter=0.016, length=0.5, preload_torque=0.02)
    pulleys = belt(ratio=3.0, driver_inertia=1e-5, driven_inertia=9e-5, efficiency=0.95)
    k1, k2 = 3.0, 2 * math.pi / 0.01
    K = k1 * k2
    transmission = Transmission((pulleys, screw), efficiency_applies_to="steady_load")
    design = Design(Task(h, T, dwell=dwell, return_move=True, linear=True), load,
                    transmission, laws=(f"trapezoidal(alpha={alpha})",), motors=(MOTOR,))
    r = only(design)
    phases = []
    for s in (1.0, -1.0):
        F = load.friction + s * load.torque
        steady_torque = steady(0.02 + steady(F, k2, 0.9), k1, 0.95)
        for duration, a in trapezoid_phases(alpha, h, T):
            inertial = (MOTOR.inertia + pulleys.inertia) * K * a + (
                screw.inertia * k2 * a + m * a / k2) / k1
            phases.append((duration, inertial + steady_torque))
    hold = load.torque / (K * 0.9 * 0.95)
    phases += [(dwell, hold)] * 2
    cycle = sum(d for d, _ in phases)
    assert r.rms_torque == pytest.approx(
        math.sqrt(sum(d * t**2 for d, t in phases) / cycle), rel=1e-10)
    assert r.peak_torque == pytest.approx(max(abs(t) for _, t in phases), rel=1e-10)
    assert "efficiency applied to the load's steady torque only" in " ".join(
        size_design(design).notes)


def test_steady_load_chain_is_linear_and_matches_its_coefficients():
    load = Load(0.05, damping=0.3, friction=2.0, torque=-5.0)
    stages = (gearbox(4.0, 0.9, 2e-5), Stage("gearbox", 3.0, 0.8, 1e-5, preload_torque=0.1))
    drive = Drive(load, Transmission(stages, efficiency_applies_to="steady_load"))
    assert drive.is_ideal
    rng = np.random.default_rng(9)
    a, v = rng.normal(size=50) * 100, rng.normal(size=50) * 10
    for direction in (1.0, -1.0):
        shaft, outputs = drive.chain(a, v, direction)
        a_part, v_part, const = drive.linear_chain(direction)
        assert shaft == pytest.approx(a_part * a + v_part * v + const, rel=1e-12, abs=1e-12)
        # the load's steady torque 2 - 5 s drives (s = +1: x eta) or opposes (s = -1: /eta)
        f2 = 0.8 if direction > 0 else 1 / 0.8
        const_out = 2.0 - 5.0 * direction
        x2 = 0.1 + const_out * f2 / 3.0
        f1 = 0.9 if x2 < 0 else 1 / 0.9
        assert const == pytest.approx(x2 * f1 / 4.0, rel=1e-14)
        assert v_part == pytest.approx(0.3 * f2 / 3.0 * f1 / 4.0, rel=1e-14)
        assert a_part == pytest.approx(2e-5 * 12 + 1e-5 * 9 / 12 + 0.05 / 12, rel=1e-14)
        # the output of the first stage is the second's input torque
        assert outputs[0] == pytest.approx(1e-5 * 3 * a + 0.05 * a / 3 + x2
                                           + 0.3 * v * f2 / 3, rel=1e-12, abs=1e-12)


def test_inertia_ratio_counts_everything_driven_by_default():
    J_gear, J_l, k = 3e-5, 0.02, 10.0
    base = Design(Task(1.0, 0.5), Load(J_l), Transmission((gearbox(k, 0.95, J_gear),)),
                  laws=("cycloidal",), motors=(MOTOR,), limits=Limits(inertia_ratio=5.0))
    driven = only(base).check("inertia_ratio")
    assert driven.value == pytest.approx((J_gear + J_l / k**2) / MOTOR.inertia, rel=1e-14)
    load_only = only(dataclasses.replace(
        base, limits=Limits(inertia_ratio=5.0, inertia_ratio_of="load"))).check("inertia_ratio")
    assert load_only.value == pytest.approx(J_l / k**2 / MOTOR.inertia, rel=1e-14)
    # 2.0 (load alone) passes, 2.3 (driven) does not against 2.2
    tight = Limits(inertia_ratio=2.2)
    assert not only(dataclasses.replace(base, limits=tight)).feasible
    assert only(dataclasses.replace(base, limits=dataclasses.replace(
        tight, inertia_ratio_of="load"))).check("inertia_ratio").passed


@pytest.mark.parametrize("return_move", [False, True])
def test_negative_displacement_moves_back_first(return_move):
    """A vertical 4 kg axis moved down first (-h): gravity drives the first move.

    Direct ball screw, efficiency 0.9 in the direction of power flow: along the motion
    u = m a + s m g (s = -1 down, +1 up), motor torque = J_m K a + R(u; K, 0.9); the motor
    holds m g / (K 0.9) at rest.
    """
    m, h, T, dwell, alpha = 4.0, 0.15, 0.3, 0.2, 1 / 3
    load = linear_load(m, incline=math.pi / 2)
    screw = ball_screw(0.02, efficiency=0.9, inertia=0.0)
    K = 2 * math.pi / 0.02
    design = Design(Task(-h, T, dwell=dwell, return_move=return_move, linear=True), load,
                    Transmission((screw,)), laws=(f"trapezoidal(alpha={alpha})",),
                    motors=(MOTOR,))
    r = only(design)
    phases = []
    for s in ((-1.0, 1.0) if return_move else (-1.0,)):
        for duration, a in trapezoid_phases(alpha, h, T):
            phases.append((duration, MOTOR.inertia * K * a
                           + reflect(m * a + s * m * GRAVITY, K, 0.9)))
        phases.append((dwell, m * GRAVITY / (K * 0.9)))
    cycle = sum(d for d, _ in phases)
    assert r.rms_torque == pytest.approx(
        math.sqrt(sum(d * t**2 for d, t in phases) / cycle), rel=1e-10)
    assert r.peak_torque == pytest.approx(max(abs(t) for _, t in phases), rel=1e-10)
    up_first = only(dataclasses.replace(design, task=dataclasses.replace(design.task,
                                                                         displacement=h)))
    if return_move:  # the same cycle, started elsewhere
        assert up_first.rms_torque == pytest.approx(r.rms_torque, rel=1e-12)
    else:  # lifting through the screw needs more torque than lowering
        assert up_first.rms_torque > 1.05 * r.rms_torque


def test_steady_load_keeps_eq_6_2_for_a_pure_inertia():
    """With the efficiency on the steady load only, a pure inertia sees no efficiency:
    T_min is eq. (6.2) with J_t = J_m + J_gear + J_l/k^2, as with an ideal gearbox."""
    stage = Stage("gearbox", 4.0, 0.7, 1e-5)
    design = Design(Task(2.0, None), Load(0.3),
                    Transmission((stage,), efficiency_applies_to="steady_load"),
                    laws=("cycloidal",), motors=(MOTOR,))
    r = only(design)
    J_t = MOTOR.inertia + 1e-5 + 0.3 / 16
    expected = max(2 * 4 * 2.0 / 1000.0, math.sqrt(2 * math.pi * 4 * 2.0 * J_t / 150.0),
                   math.sqrt(math.sqrt(2) * math.pi * 4 * 2.0 * J_t / 50.0))
    assert r.duration == pytest.approx(expected, rel=1e-12)
    flow = only(dataclasses.replace(design, transmission=Transmission((stage,))))
    assert flow.duration > 1.03 * r.duration  # J_l/(k^2 eta) while accelerating
