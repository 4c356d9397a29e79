"""The exact time-optimal trapezoid and double S (sizer.sizing.optimal_shapes) against
independent computations: Ruckig (time-optimal 1-DOF rest-to-rest profiles under speed,
acceleration and jerk limits) and a constrained minimization (scipy SLSQP) of the test's
own formulation with the peak-torque and RMS bounds."""

from __future__ import annotations

import math

import numpy as np
import pytest
from reference_values import ruckig_duration
from scipy import optimize

from sizer.laws import make_law
from sizer.sizing.optimal_shapes import (
    BoundScales,
    double_s_coefficients,
    optimal_double_s,
    optimal_trapezoid,
    rms_time,
    speed_rms_alpha,
    speed_torque_alpha,
    trapezoid_coefficients,
)

LOW = 5e-11  # the open ends alpha, beta -> 0 inset as in sizer.sizing.auto_shape
CASES = 120




def scales(speed, torque, rms=None, jerk=None, dwell=0.0) -> BoundScales:
    n = len(speed)
    zero = np.zeros(n)
    return BoundScales(np.asarray(speed), np.asarray(torque),
                       zero if rms is None else np.asarray(rms),
                       zero if jerk is None else np.asarray(jerk), dwell, np.ones(n, bool))


def random_vaj(seed: int):
    rng = np.random.default_rng(seed)
    h = 10 ** rng.uniform(-2, 1, CASES)
    v = 10 ** rng.uniform(-1, 1, CASES)
    a = 10 ** rng.uniform(-1, 2, CASES)
    j = 10 ** rng.uniform(-1, 3, CASES)
    return h, v, a, j


def test_double_s_under_speed_acceleration_jerk_is_ruckigs_optimum():
    h, v, a, j = random_vaj(1)
    solution = optimal_double_s(scales(h / v, h / a, jerk=h / j), LOW, LOW)
    reference = np.array([ruckig_duration(*x) for x in zip(h, v, a, j, strict=True)])
    np.testing.assert_allclose(solution.duration, reference, rtol=1e-9)
    # the optimal shape reaches the limits it is bound by (book sec. 3.4)
    c_v, c_a, _, c_j = double_s_coefficients(solution.params["alpha"], solution.params["beta"])
    T = solution.duration
    assert np.all(c_v * h / T <= v * (1 + 1e-9))
    assert np.all(c_a * h / T**2 <= a * (1 + 1e-9))
    assert np.all(c_j * h / T**3 <= j * (1 + 1e-9))


def test_trapezoid_under_speed_and_acceleration_is_the_closed_form_of_sec_3_2():
    h, v, a, _ = random_vaj(2)
    solution = optimal_trapezoid(scales(h / v, h / a), LOW)
    # sec. 3.2: T = h/v + v/a when the speed is reached (h >= v^2/a), else 2 sqrt(h/a)
    closed = np.where(h >= v * v / a, h / v + v / a, 2.0 * np.sqrt(h / a))
    np.testing.assert_allclose(solution.duration, closed, rtol=1e-9)
    reference = np.array([ruckig_duration(hh, vv, aa, math.inf)
                          for hh, vv, aa in zip(h, v, a, strict=True)])
    np.testing.assert_allclose(solution.duration, reference, rtol=1e-9)
    # alpha = T_a/T with T_a = v/a or T/2 (sec. 3.2)
    alpha = np.where(h >= v * v / a, (v / a) / closed, 0.5)
    np.testing.assert_allclose(solution.params["alpha"], alpha, rtol=1e-9)


def test_double_s_without_jerk_limit_tends_to_the_trapezoid():
    h, v, a, _ = random_vaj(3)
    s = scales(h / v, h / a)
    double_s = optimal_double_s(s, LOW, LOW)
    np.testing.assert_allclose(double_s.duration, optimal_trapezoid(s, LOW).duration, rtol=1e-9)
    assert np.all(double_s.params["beta"] == LOW)


def slsqp_reference(sv, sa, sr, sj, dwell, double_s):
    """min T over (alpha, beta, T) s.t. T >= C_v sv, T^2 >= C_a sa, T^3 (T + dwell) >=
    (C_a_rms sr)^2, T^3 >= C_j sj, from several starting points (the book's sec. 6.2.1
    coefficients, written here independently)."""
    def coefficients(a, b):
        if not double_s:
            return 1 / (1 - a), 1 / (a * (1 - a)), math.sqrt(2 * a) / (a * (1 - a)), 0.0
        c_a = 1 / (a * (1 - a) * (1 - b))
        return (1 / (1 - a), c_a, math.sqrt((6 - 8 * b) / (3 * a)) / ((1 - a) * (1 - b)),
                1 / (a * a * b * (1 - a) * (1 - b)))

    c = coefficients(1 / 3, 1 / 4)
    T0 = max(c[0] * sv, math.sqrt(c[1] * sa), math.sqrt(c[2] * sr), (c[3] * sj) ** (1 / 3))

    def constraints(x):
        a, b, t = x
        T = t * T0
        c_v, c_a, c_r, c_j = coefficients(a, b)
        return np.array([1 - c_v * sv / T, 1 - c_a * sa / T**2,
                         1 - (c_r * sr) ** 2 / (T**3 * (T + dwell)), 1 - c_j * sj / T**3])

    best = math.inf
    starts = ((0.15, 0.1), (0.3, 0.25), (0.45, 0.45)) if double_s else ((0.1, 0), (0.4, 0))
    for a0, b0 in starts:
        bounds = [(LOW, 0.5), (LOW, 0.5) if double_s else (0.0, 0.0), (1e-6, None)]
        r = optimize.minimize(lambda x: x[2], np.array([a0, b0, 2.0]), method="SLSQP",
                              bounds=bounds, constraints=[{"type": "ineq", "fun": constraints}],
                              options={"ftol": 1e-16, "maxiter": 500})
        if np.all(constraints(r.x) >= -1e-13):
            best = min(best, r.x[2] * T0)
    return best


@pytest.mark.parametrize("double_s", [False, True])
def test_peak_torque_rms_speed_and_jerk_bounds_against_a_constrained_minimization(double_s):
    rng = np.random.default_rng(4 + double_s)
    n = 100
    sv, sa = 10 ** rng.uniform(-2, 0, n), 10 ** rng.uniform(-3, -1, n)
    sr, sj = 10 ** rng.uniform(-3, -1, n), 10 ** rng.uniform(-4, -1, n)
    dwell = 0.3
    if double_s:
        solution = optimal_double_s(scales(sv, sa, sr, sj, dwell), LOW, LOW)
    else:
        solution = optimal_trapezoid(scales(sv, sa, sr, None, dwell), LOW)
        sj = np.zeros(n)
    reference = np.array([slsqp_reference(*x, dwell, double_s)
                          for x in zip(sv, sa, sr, sj, strict=True)])
    # never worse than the reference; equal to 1e-9 (SLSQP may stop a little above)
    assert np.all(solution.duration <= reference * (1 + 1e-12))
    np.testing.assert_allclose(solution.duration, reference, rtol=1e-9)
    # the cases cover each bound being active at the optimum
    T = solution.duration
    a = solution.params["alpha"]
    if double_s:
        c_v, c_a, c_r, c_j = double_s_coefficients(a, solution.params["beta"])
    else:
        (c_v, c_a, c_r), c_j = trapezoid_coefficients(a), 0.0
    active = [np.isclose(c_v * sv, T, rtol=1e-9), np.isclose(np.sqrt(c_a * sa), T, rtol=1e-9),
              np.isclose(T**3 * (T + dwell), (c_r * sr) ** 2, rtol=1e-8)]
    if double_s:
        active.append(np.isclose(np.cbrt(c_j * sj), T, rtol=1e-9))
    assert all(x.sum() >= 3 for x in active)


def test_trapezoid_crossings_in_closed_form_meet_their_bounds():
    """T_V = S_V/(1-a) meets T_A = sqrt(S_A/(a(1-a))) and T_R (T^3 (T + d) = 2 S_R^2 /
    (a (1-a)^2), sec. 6.2.1) at the closed forms' alphas."""
    rng = np.random.default_rng(11)
    n = 400
    sv, sa, sr = (10 ** rng.uniform(-4, 1, n) for _ in range(3))
    dwell = np.where(rng.random(n) < 0.2, 0.0, 10 ** rng.uniform(-4, 1, n))
    a = speed_torque_alpha(scales(sv, sa))
    half = a <= 0.5  # the trapezoid's range (a -> 1 would lose 1 - a to rounding)
    assert half.sum() > n / 4
    np.testing.assert_allclose((sv / (1 - a))[half], np.sqrt(sa / (a * (1 - a)))[half],
                               rtol=1e-14)
    a = speed_rms_alpha(scales(sv, sa, sr, None, dwell))
    assert np.all((a > 0) & (a < 1))
    half = a <= 0.5
    assert half.sum() > n / 4
    T = sv / (1 - a)
    np.testing.assert_allclose((T**3 * (T + dwell))[half],
                               (2 * sr**2 / (a * (1 - a) ** 2))[half], rtol=1e-13)
    # a negative dwell' (the hold above the rating) has no closed form here
    assert np.isnan(speed_rms_alpha(scales(sv[:3], sa[:3], sr[:3], None, -0.1))).all()


def smallest_rms_time(x, dwell):
    """The smallest T > max(0, -dwell) with T^3 (T + dwell) >= x^2, by bisection."""
    lo = np.maximum(-dwell, 0.0) + np.zeros_like(x)
    hi = lo + np.sqrt(x) + np.cbrt(x * x / np.maximum(np.abs(dwell), 1e-300)) + 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        ok = mid**3 * (mid + dwell) >= x * x
        lo, hi = np.where(ok, lo, mid), np.where(ok, mid, hi)
    return hi


def test_trapezoid_with_a_dwell_per_motor_against_a_dense_search():
    """Each motor its own dwell', some negative (constant torques held above the rating in
    the dwells): never worse than the best of a dense grid of alpha, and within its step."""
    rng = np.random.default_rng(12)
    n = 60
    sv, sa, sr = 10 ** rng.uniform(-2, 0, n), 10 ** rng.uniform(-3, -1, n), \
        10 ** rng.uniform(-3, -1, n)
    dwell = rng.uniform(-0.05, 0.5, n)
    solution = optimal_trapezoid(scales(sv, sa, sr, None, dwell), LOW)
    a = np.linspace(1e-3, 0.5, 4001)[None, :]
    c_v, c_a, c_r = trapezoid_coefficients(a)
    T = np.maximum(np.maximum(c_v * sv[:, None], np.sqrt(c_a * sa[:, None])),
                   smallest_rms_time(c_r * sr[:, None], dwell[:, None]))
    best = T.min(axis=1)
    assert np.all(solution.duration <= best * (1 + 1e-12))
    np.testing.assert_allclose(solution.duration, best, rtol=1e-3)  # the grid's step


def test_rms_time_solves_the_quartic():
    x = 10 ** np.linspace(-6, 3, 50)
    for dwell in (0.0, 1e-3, 0.3, 100.0):
        T = rms_time(x, dwell)
        np.testing.assert_allclose(T**3 * (T + dwell), x * x, rtol=1e-13)


def test_vectorized_coefficients_are_the_laws_coefficients():
    rng = np.random.default_rng(7)
    for a, b in rng.uniform(0.01, 0.5, (20, 2)).tolist():
        trapezoid = make_law(f"trapezoidal(alpha={a!r})").coefficients
        assert trapezoid_coefficients(a) == pytest.approx(
            (trapezoid.C_v, trapezoid.C_a, trapezoid.C_a_rms), rel=1e-12)
        law = make_law(f"double_s(alpha={a!r}, beta={b!r})").coefficients
        assert double_s_coefficients(a, b) == pytest.approx(
            (law.C_v, law.C_a, law.C_a_rms, law.C_j), rel=1e-12)
