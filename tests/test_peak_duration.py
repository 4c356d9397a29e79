"""The exact peak ratio against a falling region and the lower bound on T_min from the
peak and speed checks (sizer.laws.linear_peaks.ratio_maximum,
sizer.sizing.peak_duration), against independent computations.

- ratio_maximum: the largest (p a_N + q v_N + c)/(alpha + rate v_N) over 400,001 samples
  of the law (a dense brute force, from law.derivative alone) is reached, to the sampling
  error, and never exceeded.
- peak_duration: on the random designs of test_engine_vs_scalar, the plain scalar
  reference (tests/scalar_reference.py) finds the candidate infeasible just below the
  bound, with a check the bound accounts for failing there (speed, peak, thermal speed,
  a load or stage limit): the bound is a lower bound on T_min and it is tight.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from scalar_reference import evaluate
from test_engine_vs_scalar import LAWS, candidate, engine_calculator, minimize_design, random_design

from sizer.laws import make_law
from sizer.sizing.move import CycleCalculator, peak_duration

BRUTE = 400_001


@pytest.mark.parametrize("spec", ["cycloidal", "poly5", "trapezoidal(alpha=1/3)",
                                  "double_s(alpha=1/3, beta=1/4)", "modified_trapezoidal",
                                  "harmonic"])
def test_ratio_maximum_equals_a_dense_brute_force(spec):
    law = make_law(spec)
    rng = np.random.default_rng(7)
    n = 40
    p = rng.uniform(0.1, 5.0, n) * rng.choice([-1.0, 1.0], n)
    q = rng.uniform(0.0, 3.0, n) * rng.choice([-1.0, 1.0], n)
    c = rng.uniform(-1.0, 1.0, n)
    alpha = rng.uniform(1.0, 4.0, n)
    # the denominator stays above 0.2 alpha over v_N in [0, C_v]
    rate = -rng.uniform(0.0, 0.8, n) * alpha / law.coefficients.C_v
    tau = np.linspace(0.0, 1.0, BRUTE)
    a, v = law.derivative(tau, 2), law.derivative(tau, 1)
    brute = ((p[:, None] * a + q[:, None] * v + c[:, None])
             / (alpha[:, None] + rate[:, None] * v)).max(axis=1)
    exact = law.linear_peaks.ratio_maximum(p, q, c, alpha, rate)
    scale = (np.abs(p) * law.coefficients.C_a + np.abs(q) * law.coefficients.C_v
             + np.abs(c)) / (0.2 * alpha)
    assert np.all(exact.value >= brute - 1e-12 * scale)
    # with samples 2.5e-6 apart the brute force misses a smooth maximum by the curvature
    # times about 1e-12; a maximum at a breakpoint or a kink of a_N (the ratio's slope
    # jumps there) by the slope times the spacing
    smooth = len(law.pieces) == 1
    assert np.all(exact.value <= brute + (1e-9 if smooth else 1e-4) * scale)
    # the value is one the law reaches, at the tau and piece returned
    v1 = np.array([law.piece_derivative(int(k), t, 1) for k, t in zip(exact.piece, exact.tau,
                                                                        strict=True)])
    a1 = np.array([law.piece_derivative(int(k), t, 2) for k, t in zip(exact.piece, exact.tau,
                                                                        strict=True)])
    np.testing.assert_allclose((p * a1 + q * v1 + c) / (alpha + rate * v1), exact.value,
                               rtol=1e-12, atol=1e-14)


BOUNDED = ("speed", "peak", "thermal_speed", "load_speed", "acceleration", "jerk")


def bounded(name: str) -> bool:
    return name in BOUNDED or name.endswith("_peak") or name.endswith("_speed")


@pytest.mark.parametrize("seed", range(6))
def test_the_bound_is_a_tight_lower_bound_on_t_min(seed):
    design = minimize_design(seed)
    checked = 0
    for motor in design.motors:
        for spec in design.laws[:1] + LAWS[seed % len(LAWS):][:1]:
            for ratio in design.ratio_choice.ratios[:2]:
                calculator = engine_calculator(design, motor, spec, ratio)
                bound = peak_duration(calculator, design.limits)
                assert bound is not None
                T = float(bound[0])
                if not np.isfinite(T) or T <= 0.0:
                    continue
                below = evaluate(candidate(design, motor, spec, ratio), T * (1.0 - 1e-7))
                failing = [name for name, (value, limit, required) in below.checks.items()
                           if (1.0 - value / limit if limit > 0 else -np.inf)
                           < required - 1e-9]
                assert failing, f"{motor.id} {spec} {ratio}: feasible below the bound {T}"
                assert any(bounded(name) for name in failing), (motor.id, spec, ratio,
                                                               failing)
                checked += 1
    assert checked >= 4


def test_region_lines_of_a_concave_and_a_convex_region():
    from sizer.envelope import RegionTable

    concave = ((0.0, 3.0), (100.0, 3.0), (200.0, 2.0), (300.0, 0.5))
    convex = ((0.0, 3.0), (100.0, 1.0), (200.0, 0.8))
    alpha, sigma, is_concave = RegionTable([concave, convex]).lines()
    assert list(is_concave) == [True, False]
    np.testing.assert_allclose(alpha[0], [3.0, 4.0, 5.0])
    np.testing.assert_allclose(sigma[0], [0.0, -0.01, -0.015])
    # a convex region keeps one line: flat at its largest torque, above it everywhere
    assert alpha[1, 0] == 3.0 and sigma[1, 0] == 0.0 and np.all(np.isinf(alpha[1, 1:]))


def test_the_peak_ratio_of_moves_past_the_region_equals_the_reference(monkeypatch):
    """Moves faster than the region's top speed (they fail the speed check, and their
    peak ratio is still reported): the engine's ratio, exact where the torque peaks past
    the region's end, against the scalar reference's dense search."""
    design = random_design(2)
    design = dataclasses.replace(design, motors=tuple(
        dataclasses.replace(m, max_speed=m.rated_speed * 1.2,
                            intermittent_curve=((0.0, m.peak_torque),
                                                (m.rated_speed, m.peak_torque),
                                                (m.rated_speed * 1.2, 0.5 * m.peak_torque)),
                            continuous_curve=None)
        for m in design.motors))
    taken = []
    original = CycleCalculator._beyond_ratio

    def spy(self, *args):
        done = original(self, *args)
        taken.append(int(done.sum()))
        return done

    monkeypatch.setattr(CycleCalculator, "_beyond_ratio", spy)
    compared = 0
    for motor in design.motors:
        for spec in ("cycloidal", "poly5", "trapezoidal(alpha=1/3)"):
            for ratio in design.ratio_choice.ratios:
                calculator = engine_calculator(design, motor, spec, ratio)
                top = motor.max_speed
                K = float(np.broadcast_to(calculator.drive.ratio, (1,))[0])
                fast = make_law(spec).coefficients.C_v * K * calculator.h / top
                for T in (0.5 * fast, 0.8 * fast):
                    mine = calculator.evaluate(np.array([T])).peak_ratio[0]
                    theirs = evaluate(candidate(design, motor, spec, ratio), T).peak_ratio
                    assert mine == pytest.approx(theirs, rel=1e-9), (motor.id, spec, ratio, T)
                    compared += 1
    assert compared >= 12
    assert sum(taken) > 0  # some ratios were taken by the exact path for such moves


@pytest.mark.parametrize("seed", range(8))
def test_leaving_out_dominated_queries_gives_the_same_bound(seed):
    """peak_duration solves only the queries (function x region line x direction) whose
    bracket may hold the candidate's largest bound: on all the motors of a random design
    at once, per law and ratio, the bound equals the one from every query, to the bit."""
    from sizer.mechanics import Drive
    from sizer.model import Transmission
    from sizer.sizing.candidates import MotorArrays

    design = minimize_design(seed)
    motors = MotorArrays.of(list(design.motors), design.limits.envelope)
    compared = 0
    for spec in (*design.laws[:2], *LAWS[seed % len(LAWS):][:2]):
        for ratio in design.ratio_choice.ratios[:3]:
            stages = list(design.transmission.stages)
            stages[design.ratio_choice.stage] = dataclasses.replace(stages[0], ratio=ratio)
            calculator = CycleCalculator(None, design.task,
                                         Drive(design.load, Transmission(tuple(stages))),
                                         motors, design.limits.thermal_speed,
                                         law=make_law(spec))
            pruned = peak_duration(calculator, design.limits)
            every = peak_duration(calculator, design.limits, prune=False)
            if every is None:
                assert pruned is None
                continue
            np.testing.assert_array_equal(pruned, every)
            compared += int(np.isfinite(every).sum())
    assert compared >= 10


def competing_calculators():
    """Motors whose moves end near the knee of a falling region (the flat line and the
    falling lines give bounds within a few percent of each other), with friction, a
    constant load, an efficiency and a return move, per law and ratio."""
    from sizer.mechanics import Drive
    from sizer.model import Load, Motor, Stage, Task, Transmission
    from sizer.sizing.candidates import MotorArrays

    rng = np.random.default_rng(3)
    motors = []
    for i in range(60):
        tau_p, v_n = rng.uniform(1.0, 20.0), rng.uniform(100.0, 400.0)
        knee, fall = rng.uniform(0.3, 1.0), rng.uniform(0.3, 0.9)
        motors.append(Motor(
            f"m{i}", rng.uniform(1e-5, 1e-3), tau_p / 3.0, tau_p, v_n, max_speed=2.0 * v_n,
            intermittent_curve=((0.0, tau_p), (knee * v_n, tau_p), (1.3 * v_n, fall * tau_p),
                                (2.0 * v_n, 0.5 * fall * tau_p)),
            continuous_curve=((0.0, tau_p / 3.0), (2.0 * v_n, tau_p / 6.0))))
    arrays = MotorArrays.of(motors, "curves")
    task = Task(1.2, None, dwell=0.1, return_move=True)
    for spec in ("cycloidal", "poly5", "trapezoidal(alpha=1/3)", "modified_sinusoidal"):
        for ratio in (2.0, 5.0, 12.0):
            drive = Drive(Load(0.02, damping=0.01, friction=0.2, torque=0.3),
                          Transmission((Stage("gearbox", ratio, 0.9, 1e-5),)))
            yield CycleCalculator(None, task, drive, arrays, law=make_law(spec))


COMPETING_LIMITS = dict(torque_margin=0.1, speed_margin=0.05)


def test_leaving_out_queries_on_regions_whose_lines_compete():
    from sizer.model import Limits

    limits = Limits(**COMPETING_LIMITS)
    compared = 0
    for calculator in competing_calculators():
        pruned = peak_duration(calculator, limits)
        every = peak_duration(calculator, limits, prune=False)
        np.testing.assert_array_equal(pruned, every)
        compared += int(np.isfinite(every).sum())
    assert compared >= 200


def test_each_query_bound_lies_in_its_bracket():
    """What the pruning rests on: every query's bound 1/u (Newton on the exact linear
    peaks) lies between the closed-form ends of its bracket."""
    from sizer.model import Limits
    from sizer.sizing.move import _brackets, _largest_u, peak_queries

    limits = Limits(**COMPETING_LIMITS)
    checked = 0
    for calculator in competing_calculators():
        law = calculator.law
        who, P, Q, D = peak_queries(calculator, limits)
        c = law.coefficients
        low, high = _brackets(P, Q, D, c.C_a, c.C_v)
        u = _largest_u(calculator, who, P, Q, D, c.C_a, c.C_v)
        with np.errstate(divide="ignore"):
            T = np.where(u > 0.0, 1.0 / u, np.inf)
        finite = np.isfinite(T) & np.isfinite(high)
        assert np.all(T[finite] >= low[finite] * (1.0 - 1e-12))
        assert np.all(T[finite] <= high[finite] * (1.0 + 1e-12))
        checked += int(finite.sum())
    assert checked >= 1000
