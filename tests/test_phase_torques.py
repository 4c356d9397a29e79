"""The trapezoid's T_min at each alpha with constant torques per phase
(sizer.sizing.optimal_shapes.trusted_phase_model), the closed forms the shape search
scores it by where they hold: against a hand derivation, against the engine's T_min of
fixed trapezoids, and the search's optimum against a dense grid of fixed shapes sized by
the engine."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from sizer.laws.piecewise_polynomial import DoubleS, Trapezoidal
from sizer.model import Design, Limits, Load, Motor, Stage, Task, Transmission
from sizer.sizing import size_design
from sizer.sizing.candidates import Candidates, MotorArrays
from sizer.sizing.checks import TOLERANCE
from sizer.sizing.choices import score_law
from sizer.sizing.optimal_shapes import phase_model, trusted_phase_model
from tests.dense_shapes import assert_no_slower_than_fixed

MOTORS = tuple(Motor(f"m{i}", inertia=2e-5 * t**1.3, continuous_torque=t, peak_torque=3 * t,
                     rated_speed=3000 * math.pi / 30)
               for i, t in enumerate((0.2, 0.5, 1.1, 2.5, 6.0, 14.0)))


def candidates_of(design: Design) -> Candidates:
    return Candidates.single(MotorArrays.of(design.motors), design.load, design.transmission)


def random_design(seed: int) -> Design:
    """Efficiencies in power flow (one or two stages), Coulomb friction, a constant load of
    either sign, a dwell or none, a return move or none, margins and the load's limits."""
    rng = np.random.default_rng(seed)
    stages = [Stage("gearbox", float(rng.uniform(3.0, 12.0)), float(rng.uniform(0.7, 1.0)),
                    float(rng.uniform(0.0, 2e-4)))]
    if rng.random() < 0.5:
        stages.append(Stage("belt", float(rng.uniform(1.0, 3.0)),
                            float(rng.uniform(0.8, 1.0)), float(rng.uniform(0.0, 5e-5))))
    limits = Limits(torque_margin=float(rng.uniform(0.0, 0.2)),
                    speed_margin=float(rng.uniform(0.0, 0.1)),
                    max_speed=float(rng.uniform(8.0, 40.0)) if rng.random() < 0.3 else None,
                    max_acceleration=float(rng.uniform(200.0, 2000.0))
                    if rng.random() < 0.3 else None)
    load = Load(float(rng.uniform(0.05, 0.8)), friction=float(rng.uniform(0.0, 1.0)),
                torque=float(rng.uniform(-0.8, 0.8)) if rng.random() < 0.5 else 0.0)
    task = Task(math.pi / 2, None, dwell=float(rng.choice([0.0, rng.uniform(0.05, 0.4)])),
                return_move=bool(rng.random() < 0.7))
    return Design(task, load, Transmission(tuple(stages)),
                  laws=("trapezoidal(alpha=auto)",), motors=MOTORS, limits=limits)


def test_the_hand_derivation_of_an_inertial_load_through_a_lossy_gearbox():
    """A load of inertia J_l through a gearbox of ratio K and efficiency eta, a move and
    its return, a dwell d after each: the torque is J_f x while the load accelerates
    (J_f = J_m K + J_l / (eta K), power to the load) and -J_b x while it slows down
    (J_b = J_m K + eta J_l / K, power from it), x = C_a h / T^2. So T_A = sqrt(C_a h J_f /
    tau_p') and the RMS over the cycle, alpha (J_f^2 + J_b^2) x^2 per move, reaches tau_c'
    where T^3 (T + d) = C_a_rms^2 h^2 (J_f^2 + J_b^2) / (2 tau_c'^2) (alpha C_a^2 =
    C_a_rms^2 / 2); the speed T_V = C_v K h / v'."""
    K, eta, J_l, d, h, margin = 8.0, 0.8, 0.4, 0.2, math.pi / 2, 0.1
    design = Design(Task(h, None, dwell=d, return_move=True), Load(J_l),
                    Transmission((Stage("gearbox", K, eta, 0.0),)),
                    laws=("trapezoidal(alpha=auto)",), motors=MOTORS,
                    limits=Limits(torque_margin=margin))
    model = phase_model(design, candidates_of(design))
    assert model is not None
    for alpha in (0.05, 0.2, 1 / 3, 0.5):
        c_v, c_a = 1 / (1 - alpha), 1 / (alpha * (1 - alpha))
        c_a_rms = math.sqrt(2 / alpha) / (1 - alpha)
        for i, motor in enumerate(MOTORS):
            J_f = motor.inertia * K + J_l / (eta * K)
            J_b = motor.inertia * K + eta * J_l / K
            tau_p, tau_c = (1 - margin) * motor.peak_torque, (1 - margin) * motor.continuous_torque
            T_v = c_v * K * h / motor.rated_speed
            T_a = math.sqrt(c_a * h * J_f / tau_p)
            target = c_a_rms**2 * h**2 * (J_f**2 + J_b**2) / (2 * tau_c**2)
            lo, hi = 0.0, 10.0  # T^3 (T + d) increases: bisection to the last bit
            for _ in range(200):
                mid = 0.5 * (lo + hi)
                lo, hi = (mid, hi) if mid**3 * (mid + d) < target else (lo, mid)
            expected = max(T_v, T_a, hi)
            found = model.durations(np.array([alpha]), np.array([i]))[0]
            assert found == pytest.approx(expected, rel=1e-13)


@pytest.mark.parametrize("seed", range(12))
def test_the_model_is_the_engines_T_min_of_each_fixed_trapezoid(seed):
    """Each motor's T_min of fixed trapezoids sized by the engine (its search for the
    shortest duration, sizer.sizing.shortest_duration) against the model's, feasible or
    not alike; the engine stops within its checks' tolerance of the exact crossing."""
    design = random_design(seed)
    candidates = candidates_of(design)
    model = phase_model(design, candidates)
    assert model is not None
    rows = np.arange(len(MOTORS))
    for alpha in (0.01, 0.12, 0.25, 1 / 3, 0.41, 0.5):
        engine = -score_law(Trapezoidal(alpha=alpha), design, candidates)[:, 0]
        mine = model.durations(np.full(len(rows), alpha), rows)
        assert np.array_equal(np.isfinite(engine), np.isfinite(mine))
        ok = np.isfinite(engine)
        assert np.allclose(mine[ok], engine[ok], rtol=2 * TOLERANCE, atol=0.0)


@pytest.mark.parametrize("seed", range(6))
def test_the_searched_optimum_is_no_slower_than_a_dense_grid_of_fixed_trapezoids(seed):
    """The auto trapezoid of random designs in the model's case (scored by the model)
    against the engine's T_min of 97 fixed trapezoids: never slower, to the engine's own
    tolerance (its checks pass within 1e-9 of their limits, so its T_min of a fixed shape
    may lie that much below the exact one)."""
    design = random_design(seed)
    trusted = trusted_phase_model(Trapezoidal, {}, ["alpha"], {"alpha": (1e-3, 0.5)}, design,
                                  candidates_of(design))
    assert trusted is not None and trusted.trusted.all()
    grid = np.linspace(0.02, 0.5, 97).tolist()
    assert_no_slower_than_fixed(design, [f"trapezoidal(alpha={a!r})" for a in grid],
                                2 * TOLERANCE)


def test_outside_its_case_the_engine_scores_the_search():
    """Damping (the torque of a phase follows the speed), a jerk limit, another thermal
    rule, a given duration: no model; a motor whose regions fall past a knee: not scored
    by it."""
    design = random_design(0)
    damped = replace(design, load=replace(design.load, damping=0.02))
    assert phase_model(damped, candidates_of(damped)) is None
    for limits in (replace(design.limits, max_jerk=1e4),
                   replace(design.limits, thermal_speed="rms")):
        assert phase_model(replace(design, limits=limits), candidates_of(design)) is None
    given = replace(design, task=replace(design.task, duration=0.3))
    assert phase_model(given, candidates_of(given)) is None
    m = MOTORS[2]
    knee = replace(m, intermittent_curve=((0.0, m.peak_torque), (0.6 * m.rated_speed,
                                                                 m.peak_torque),
                                          (m.rated_speed, 0.5 * m.peak_torque)))
    mixed = replace(design, motors=(knee, *MOTORS[3:]))
    trusted = trusted_phase_model(Trapezoidal, {}, ["alpha"], {"alpha": (1e-3, 0.5)}, mixed,
                                  candidates_of(mixed))
    assert trusted is not None
    assert trusted.trusted.tolist() == [False] + [True] * (len(MOTORS) - 3)


def test_the_hand_derivation_of_a_double_s_through_a_lossy_gearbox():
    """The double S of an inertial load through a gearbox of efficiency eta: the torque
    is J_f a while power flows to the load (a > 0) and J_b a while it flows back, so its
    square integrates to (J_f^2 + J_b^2) C_a_rms^2 / 2 per move (the law's halves mirror
    each other): T^3 (T + d) = C_a_rms^2 h^2 (J_f^2 + J_b^2) / (2 tau_c'^2), with T_A =
    sqrt(C_a h J_f / tau_p'), T_V = C_v K h / v' and the load's jerk T_J = cbrt(C_j h /
    j_max) (C_a = 1/(a (1-a) (1-b)), C_j = C_a / (a b), C_a_rms = sqrt((6 - 8b) / (3a)) /
    ((1-a)(1-b)), sec. 3.4, 6.2.1)."""
    K, eta, J_l, d, h, margin, jerk = 8.0, 0.8, 0.4, 0.2, math.pi / 2, 0.1, 2e3
    design = Design(Task(h, None, dwell=d, return_move=True), Load(J_l),
                    Transmission((Stage("gearbox", K, eta, 0.0),)),
                    laws=("double_s(alpha=auto, beta=auto)",), motors=MOTORS,
                    limits=Limits(torque_margin=margin, max_jerk=jerk))
    model = phase_model(design, candidates_of(design), DoubleS)
    assert model is not None
    for a, b in ((0.1, 0.4), (0.25, 0.25), (1 / 3, 0.05), (0.5, 0.5)):
        c_v, c_a = 1 / (1 - a), 1 / (a * (1 - a) * (1 - b))
        c_j, c_a_rms = c_a / (a * b), math.sqrt((6 - 8 * b) / (3 * a)) / ((1 - a) * (1 - b))
        for i, motor in enumerate(MOTORS):
            J_f = motor.inertia * K + J_l / (eta * K)
            J_b = motor.inertia * K + eta * J_l / K
            tau_p, tau_c = (1 - margin) * motor.peak_torque, (1 - margin) * motor.continuous_torque
            target = c_a_rms**2 * h**2 * (J_f**2 + J_b**2) / (2 * tau_c**2)
            lo, hi = 0.0, 10.0
            for _ in range(200):
                mid = 0.5 * (lo + hi)
                lo, hi = (mid, hi) if mid**3 * (mid + d) < target else (lo, mid)
            expected = max(c_v * K * h / motor.rated_speed, math.sqrt(c_a * h * J_f / tau_p),
                           hi, (c_j * h / jerk) ** (1 / 3))
            found = model.durations(np.array([a]), np.array([i]), np.array([b]))[0]
            assert found == pytest.approx(expected, rel=1e-13)


@pytest.mark.parametrize("seed", range(12))
def test_the_model_is_the_engines_T_min_of_each_fixed_double_s(seed):
    """As for the trapezoid, with the double S's ramps (the torque's square over a
    uniform sweep of the acceleration, the power flow turning inside a ramp where the
    friction or the constant load outweighs the inertia) and the load's jerk."""
    design = random_design(seed)
    design = replace(design, limits=replace(design.limits,
                                            max_jerk=(None, 3e3, 3e4)[seed % 3]))
    candidates = candidates_of(design)
    model = phase_model(design, candidates, DoubleS)
    assert model is not None
    rows = np.arange(len(MOTORS))
    for a, b in ((0.1, 0.1), (0.25, 0.4), (1 / 3, 0.25), (0.45, 0.05), (0.5, 0.5)):
        engine = -score_law(DoubleS(alpha=a, beta=b), design, candidates)[:, 0]
        mine = model.durations(np.full(len(rows), a), rows, np.full(len(rows), b))
        assert np.array_equal(np.isfinite(engine), np.isfinite(mine))
        ok = np.isfinite(engine)
        assert np.allclose(mine[ok], engine[ok], rtol=2 * TOLERANCE, atol=0.0)


@pytest.mark.parametrize("seed", range(3))
def test_the_searched_double_s_is_no_slower_than_a_dense_grid_of_fixed_ones(seed):
    """The auto double S (alpha and beta, a jerk limit) against the engine's T_min of
    13 x 13 fixed double S: never slower, to the engine's tolerance."""
    design = random_design(seed)
    design = replace(design, laws=("double_s(alpha=auto, beta=auto)",),
                     motors=MOTORS[2:4],
                     limits=replace(design.limits, max_jerk=(3e3, 3e4, None)[seed]))
    trusted = trusted_phase_model(DoubleS, {}, ["alpha", "beta"],
                                  {"alpha": (1e-3, 0.5), "beta": (1e-3, 0.5)}, design,
                                  candidates_of(design))
    assert trusted is not None and trusted.trusted.all()
    grid = np.linspace(0.02, 0.5, 13).tolist()
    assert_no_slower_than_fixed(design, [f"double_s(alpha={a!r}, beta={b!r})"
                                         for a in grid for b in grid], 2 * TOLERANCE)


def test_a_motor_failing_a_check_of_no_shape_is_left_to_the_engine():
    """The inertia ratio does not depend on the shape: a motor that fails it is infeasible
    at every alpha for the engine, not for the model, so the model does not score it."""
    design = random_design(3)
    candidates = candidates_of(design)
    driven = candidates.drive.inertia_ratio_numerator() / candidates.motors.inertia
    limit = float(np.median(driven))
    limited = replace(design, limits=replace(design.limits, inertia_ratio=limit))
    trusted = trusted_phase_model(Trapezoidal, {}, ["alpha"], {"alpha": (1e-3, 0.5)}, limited,
                                  candidates_of(limited))
    assert trusted is not None
    assert trusted.trusted.tolist() == (driven <= limit).tolist()
    auto = size_design(limited).results
    assert sorted(r.motor for r in auto if r.feasible) == sorted(
        m.id for m, ok in zip(MOTORS, driven <= limit, strict=True) if ok)
