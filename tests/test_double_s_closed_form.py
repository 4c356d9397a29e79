"""The time-optimal double S in closed form (sizer.sizing.optimal_shapes.optimal_double_s,
book sec. 3.4.3) against Ruckig's time-optimal 1-DOF rest-to-rest durations, against the
search it replaces where it is exact, and the rows it leaves to that search."""

from __future__ import annotations

import math

import numpy as np
from reference_values import ruckig_duration

from sizer.sizing.optimal_shapes import (
    BoundScales,
    double_s_coefficients,
    optimal_double_s,
    searched_double_s,
)

LOW = 5e-11  # the open ends alpha, beta -> 0 inset as in sizer.sizing.choices
ROWS = 2000
NO_SPEED, NO_ACCELERATION, NO_JERK = range(3)


def scales(speed, torque, rms=None, jerk=None, dwell=0.0, feasible=None) -> BoundScales:
    n = len(speed)
    zero = np.zeros(n)
    return BoundScales(np.asarray(speed, float), np.asarray(torque, float),
                       zero if rms is None else np.asarray(rms, float),
                       zero if jerk is None else np.asarray(jerk, float), dwell,
                       np.ones(n, bool) if feasible is None else feasible)


def random_problems(seed: int, n: int = ROWS):
    """h, v, a, j spanning every case of sec. 3.4.3; the first 100 rows without a speed
    limit, the next 100 without an acceleration limit, the next 100 without a jerk limit
    (inf)."""
    rng = np.random.default_rng(seed)
    h = 10 ** rng.uniform(-2, 1, n)
    v = 10 ** rng.uniform(-1, 1, n)
    a = 10 ** rng.uniform(-1, 2, n)
    j = 10 ** rng.uniform(-1, 3, n)
    for which, limit in enumerate((v, a, j)):
        limit[100 * which:100 * (which + 1)] = math.inf
    return h, v, a, j


def as_scales(h, v, a, j, rms=None, dwell=0.0) -> BoundScales:
    return scales(h / v, h / a, rms, h / j, dwell)  # h / inf = 0: no such limit


def test_closed_form_is_ruckigs_optimum_in_every_case():
    h, v, a, j = random_problems(11)
    solution = optimal_double_s(as_scales(h, v, a, j), LOW, LOW)
    # without a jerk limit beta is held at LOW: the trapezoid under a (1 - LOW) (sec. 3.2)
    a_eff = np.where(np.isinf(j), a * (1.0 - LOW), a)
    reference = np.array([ruckig_duration(*x) for x in zip(h, v, a_eff, j, strict=True)])
    T = solution.duration
    np.testing.assert_allclose(T, reference, rtol=1e-12, atol=0.0)
    # the limits reached (book sec. 3.4.3: v_max reached or not, a_max reached or not)
    alpha, beta = solution.params["alpha"], solution.params["beta"]
    c_v, c_a, _, c_j = double_s_coefficients(alpha, beta)
    speed, acceleration, jerk = c_v * h / T, c_a * h / T**2, c_j * h / T**3
    assert np.all(speed <= v * (1 + 1e-12))
    assert np.all(acceleration <= a * (1 + 1e-12))
    assert np.all(jerk[~np.isinf(j)] <= j[~np.isinf(j)] * (1 + 1e-12))
    v_hit, a_hit = np.isclose(speed, v, rtol=1e-12), np.isclose(acceleration, a_eff, rtol=1e-12)
    limited = slice(300, None)
    np.testing.assert_allclose(jerk[limited], j[limited], rtol=1e-12)  # always reached
    counts = {(vv, aa): int(np.sum((v_hit[limited] == vv) & (a_hit[limited] == aa)))
              for vv in (True, False) for aa in (True, False)}
    # of the 1,700 rows with all three limits: v_max and a_max reached (case 1a) 243, v_max
    # alone (1b) 322, a_max alone (2a) 464, neither (2b) 671; without a speed limit 45 2a and
    # 55 2b, without an acceleration limit 44 1b and 56 2b, without jerk 45 + 55 (trapezoid)
    assert min(counts.values()) >= 100, counts
    # a missing limit is never reached; where beta < 1/2 (T_a > 2 T_j) a_max is reached
    assert not v_hit[:100].any() and not a_hit[100:200].any()
    assert np.all(a_hit[beta < 0.5])
    assert np.all(beta[200:300] == LOW)


def test_closed_form_equals_the_search_it_replaces():
    h, v, a, j = random_problems(12, 500)
    s = as_scales(h, v, a, j)
    exact = optimal_double_s(s, LOW, LOW)
    _, T = searched_double_s(s, LOW, LOW, 0.5, 0.5)
    # the search stops at a bracket of 1e-13 in alpha: never better, equal to 1e-12
    assert np.all(exact.duration <= T * (1 + 1e-15))
    np.testing.assert_allclose(exact.duration, T, rtol=1e-12)


def test_a_binding_rms_bound_falls_back_to_the_search_bit_for_bit():
    h, v, a, j = random_problems(13, 400)
    for dwell in (0.0, 0.3):
        base = as_scales(h, v, a, j)
        # the RMS scale spans from far below to far above the other bounds' T
        rms = 10 ** np.random.default_rng(14).uniform(-1, 2, len(h)) * base.torque
        s = as_scales(h, v, a, j, rms, dwell)
        solution = optimal_double_s(s, LOW, LOW)
        searched, T = searched_double_s(s, LOW, LOW, 0.5, 0.5)
        unbound = optimal_double_s(base, LOW, LOW).duration
        binds = solution.duration > unbound * (1 + 1e-9)
        assert 50 <= binds.sum() <= len(h) - 50, binds.sum()
        # where the RMS bound binds: the search's output, the same bits
        np.testing.assert_array_equal(solution.duration[binds], T[binds])
        for name in ("alpha", "beta"):
            np.testing.assert_array_equal(solution.params[name][binds], searched[name][binds])
        # elsewhere the RMS-free optimum, never worse than the search
        np.testing.assert_allclose(solution.duration[~binds], unbound[~binds], rtol=1e-15)
        assert np.all(solution.duration <= T * (1 + 1e-15))


def test_an_optimum_outside_the_ranges_is_searched():
    h, v, a, j = (x[300:] for x in random_problems(15, 600))  # every limit present
    s = as_scales(h, v, a, j)
    free = optimal_double_s(s, LOW, LOW)
    for box in ((0.2, LOW, 0.5, 0.5), (LOW, LOW, 0.3, 0.4), (LOW, 0.1, 0.5, 0.5)):
        solution = optimal_double_s(s, *box)
        low_a, low_b, high_a, high_b = box
        params, T = searched_double_s(s, *box)
        inside = ((free.params["alpha"] >= low_a) & (free.params["alpha"] <= high_a)
                  & (free.params["beta"] >= low_b) & (free.params["beta"] <= high_b))
        assert 10 <= inside.sum() <= len(h) - 10, (box, inside.sum())
        np.testing.assert_array_equal(solution.duration[~inside], T[~inside])
        np.testing.assert_array_equal(solution.params["alpha"][~inside],
                                      params["alpha"][~inside])
        np.testing.assert_array_equal(solution.duration[inside], free.duration[inside])


def test_degenerate_rows_match_the_search():
    # only a speed limit, only a torque limit, nothing, infeasible
    s = scales([1.0, 0.0, 0.0, 2.0, 0.5], [0.0, 0.3, 0.0, 0.1, 0.2],
               jerk=[0.0, 0.0, 0.0, 0.1, 0.05], feasible=np.array([True, True, True, False, True]))
    solution = optimal_double_s(s, LOW, LOW)
    params, T = searched_double_s(s.take(np.array([0, 2])), LOW, LOW, 0.5, 0.5)
    np.testing.assert_array_equal(solution.duration[[0, 2]], T)
    np.testing.assert_array_equal(solution.params["alpha"][[0, 2]], params["alpha"])
    # only a torque limit: the triangle under a (1 - LOW), alpha = 1/2, beta at its low end
    assert solution.duration[1] == 2.0 * math.sqrt(0.3 / (1.0 - LOW))
    assert (solution.params["alpha"][1], solution.params["beta"][1]) == (0.5, LOW)
    # infeasible: the default shape, T = inf (as before)
    assert solution.duration[3] == math.inf
    assert (solution.params["alpha"][3], solution.params["beta"][3]) == (1.0 / 3.0, 0.25)
    # a feasible row next to them, h = 1, v_max = 2, a_max = 5, j_max = 20 (sec. 3.4.3):
    # T_j = a_max/j_max, T_a = T_j + v_max/a_max = 0.65 > h/v_max: v_max is not reached;
    # h >= 2 a_max^3/j_max^2 = 0.625: a_max is (case 2a)
    T_j = 0.25
    T_a = T_j / 2 + math.sqrt(T_j**2 / 4 + 0.2)
    assert math.isclose(solution.duration[4], 2 * T_a, rel_tol=1e-14)
    assert math.isclose(solution.params["beta"][4], T_j / T_a, rel_tol=1e-14)
