"""``times: auto`` (book sec. 4.4.6, issue 34) with exact derivatives: the knot
accelerations and their derivatives with respect to the intervals against scipy's
CubicSpline and central differences, and the optimizer's objective against the previous
optimizer written plainly here (SLSQP over the same softmax variables, scipy's splines,
scipy's default finite differences): the same or better to 1e-9 relative, with the
first-order minimax and stationarity conditions where cheap."""

from __future__ import annotations

import math
import os

import numpy as np
import pytest
from scipy.interpolate import CubicSpline
from scipy.optimize import linprog, minimize

from sizer.laws.multipoint import cubic_splines as cs

Q_4_14 = np.array([0.0, 2, 12, 5, 12, -10, -11, -4, 6, 9])
ENDS = {"v0": 0.0, "vn": 0.0, "a0": 0.0, "an": 0.0}


def spline(t, q, conditions):
    """scipy's CubicSpline with the conditions; with end accelerations, the book's spline of
    sec. 4.4.4 (no scipy equivalent; checked against the book in test_cubic_splines)."""
    if conditions.get("periodic"):
        return CubicSpline(t, q, bc_type="periodic")
    if conditions.get("natural"):
        return CubicSpline(t, q, bc_type="natural")
    if "a0" in conditions:
        return cs.velocity_acceleration_spline(t, q, **conditions)
    return CubicSpline(t, q, bc_type=((1, conditions.get("v0", 0.0)),
                                      (1, conditions.get("vn", 0.0))))


def peak(pp) -> float:
    return float(np.max(np.abs(pp(pp.x, 2))))


def rms(pp) -> float:
    """sqrt(1/D int s''^2): the acceleration is linear on each piece."""
    a, h = pp(pp.x, 2), np.diff(pp.x)
    return math.sqrt(np.sum(h * (a[:-1] ** 2 + a[:-1] * a[1:] + a[1:] ** 2) / 3.0) / h.sum())


MEASURE = {"peak_acceleration": peak, "rms_acceleration": rms}


def softmax_times(y, duration):
    e = np.exp(np.concatenate([[0.0], y]))
    return duration * np.concatenate([[0.0], np.cumsum(e) / e.sum()])


def previous_times(q, duration, objective, conditions):
    """The previous optimizer: SLSQP from the equal times over y, |y_k| <= 5, intervals
    duration * softmax([0, y]); scipy's finite differences; the peak as min z subject to
    -z <= s''(t_j) / scale <= z; the RMS squared; the equal times if no better."""
    n = len(q) - 1

    def curve(y):
        return spline(softmax_times(y, duration), q, conditions)

    y0 = np.zeros(n - 1)
    bounds = [(-5.0, 5.0)] * (n - 1)
    scale = peak(curve(y0))
    if objective == "rms_acceleration":
        y = minimize(lambda y: (rms(curve(y)) / scale) ** 2, y0, method="SLSQP",
                     bounds=bounds, options={"ftol": 1e-15, "maxiter": 500}).x
    else:
        def accelerations(y):
            pp = curve(y)
            return pp(pp.x, 2) / scale

        bands = [{"type": "ineq", "fun": lambda v: v[-1] - accelerations(v[:-1])},
                 {"type": "ineq", "fun": lambda v: v[-1] + accelerations(v[:-1])}]
        y = minimize(lambda v: v[-1], np.append(y0, 1.0), method="SLSQP", constraints=bands,
                     bounds=[*bounds, (0.0, None)],
                     options={"ftol": 1e-14, "maxiter": 500}).x[:-1]
    measure = MEASURE[objective]
    return y if measure(curve(y)) <= measure(curve(y0)) else y0


def bench_positions(n=32):
    """benchmarks/bench_axes.py's 32 positions (printed there to 6 decimals)."""
    q = [0.5 - 0.5 * math.cos(math.pi * i / (n - 1)) + 0.02 * math.sin(3.0 * i)
         for i in range(n)]
    q[0], q[-1] = 0.0, 1.0
    return np.round(q, 6)


def random_problems():
    rng = np.random.default_rng(34)
    for i, duration in enumerate([0.3, 0.7, 1.5, 3.0, 5.0, 7.0]):
        n = int(rng.integers(4, 13))
        q = np.round(np.cumsum(rng.normal(size=n)), 3)
        v0, vn = (float(np.round(v, 2)) for v in rng.normal(size=2))
        yield pytest.param(q, duration, cs.OBJECTIVES[i % 2], {"v0": v0, "vn": vn},
                           id=f"random{i}")


PROBLEMS = [
    pytest.param(Q_4_14, 1.0, "peak_acceleration", {}, id="4.14-peak"),
    pytest.param(Q_4_14, 1.0, "rms_acceleration", {}, id="4.14-rms"),
    pytest.param(np.array([0, 0.15, 0.8, 1.0]), 1.0, "peak_acceleration", {}, id="pusher"),
    pytest.param(np.array([0.0, 1, 3, 2, 5]), 2.0, "peak_acceleration", {"natural": True},
                 id="natural"),
    pytest.param(np.array([0.0, 3, 1, 4, 0]), 2.0, "peak_acceleration", {"periodic": True},
                 id="periodic"),
    pytest.param(Q_4_14, 2.0, "peak_acceleration", ENDS, id="end-accelerations"),
    *random_problems(),
]
SLOW = pytest.mark.skipif(not os.environ.get("SIZER_SLOW_TESTS"),
                          reason="the previous optimizer takes seconds on 32 points: "
                                 "SIZER_SLOW_TESTS=1")
BENCH = [pytest.param(bench_positions(), 1.0, objective, {}, id=f"bench32-{objective}",
                      marks=SLOW) for objective in cs.OBJECTIVES]


@pytest.mark.parametrize("conditions", [{}, {"v0": 0.7, "vn": -1.3}, {"natural": True},
                                        {"periodic": True},
                                        {"v0": 0.2, "vn": -0.4, "a0": 3.0, "an": -1.0}])
@pytest.mark.parametrize("n", [2, 3, 7])
def test_knot_accelerations_and_their_derivatives(conditions, n):
    rng = np.random.default_rng(n)
    q = np.cumsum(rng.normal(size=n + 1))
    if conditions.get("periodic"):
        q[-1] = q[0]
    h = rng.uniform(0.2, 1.0, n)

    def accelerations(h):
        pp = spline(np.concatenate([[0.0], np.cumsum(h)]), q, conditions)
        return pp(pp.x, 2), np.diff(pp.x)

    T, dT, omega, d_omega = cs._knot_accelerations(q, conditions)(h)
    a, pieces = accelerations(h)
    np.testing.assert_allclose(omega, a, rtol=0, atol=1e-12 * np.max(np.abs(a)))
    np.testing.assert_allclose(T, pieces, rtol=1e-14)
    step = 1e-6
    central = np.column_stack([(accelerations(h + step * e)[0]
                                - accelerations(h - step * e)[0]) / (2 * step)
                               for e in np.eye(n)])
    np.testing.assert_allclose(d_omega, central, rtol=0, atol=1e-7 * np.max(np.abs(central)))
    np.testing.assert_allclose(dT, np.column_stack(
        [(accelerations(h + step * e)[1] - accelerations(h - step * e)[1]) / (2 * step)
         for e in np.eye(n)]), rtol=0, atol=1e-8)


@pytest.mark.parametrize(("q", "duration", "objective", "conditions"), [*PROBLEMS, *BENCH])
def test_auto_times_as_good_as_the_previous_optimizer(q, duration, objective, conditions):
    measure = MEASURE[objective]
    t = cs.optimal_times(q, duration, objective, **conditions)
    h = np.diff(t)
    assert t[0] == 0.0 and t[-1] == duration
    # the search space of the previous optimizer: every interval within e^+-5 of the first
    assert np.all(h >= h[0] * math.exp(-5.0) * (1 - 1e-9))
    assert np.all(h <= h[0] * math.exp(5.0) * (1 + 1e-9))
    new = measure(spline(t, q, conditions))
    previous = measure(spline(softmax_times(
        previous_times(q, duration, objective, conditions), duration), q, conditions))
    assert new <= previous * (1 + 1e-9), (new, previous)


def _minimax_step(q, t, conditions) -> float:
    """The best first-order decrease of the peak acceleration over moves of the interior
    times up to 1e-4 of the duration, by LP on central differences of scipy's splines,
    relative to the peak; >= 0 at a minimax point."""
    def accelerations(t):
        pp = spline(t, q, conditions)
        return pp(pp.x, 2)

    a = accelerations(t)
    top = np.max(np.abs(a))
    step = 1e-7 * t[-1]
    J = np.column_stack([(accelerations(t + step * e) - accelerations(t - step * e))
                         / (2 * step) for e in np.eye(len(t))[1:-1]])
    active = np.abs(a) >= top * (1 - 1e-7)
    signs = np.sign(a[active])[:, None]
    # min s subject to sign_j (a_j + J_j d) - top <= s on the active knots, |d| <= r
    A = np.hstack([signs * J[active], -np.ones((active.sum(), 1))])
    r = 1e-4 * t[-1]
    result = linprog(np.r_[np.zeros(len(t) - 2), 1.0], A_ub=A,
                     b_ub=top - np.abs(a[active]),
                     bounds=[(-r, r)] * (len(t) - 2) + [(None, None)])
    return float(result.x[-1]) / top


@pytest.mark.parametrize(("q", "duration", "objective", "conditions"), [
    p for p in PROBLEMS if p.values[2] == "peak_acceleration"])
def test_auto_peak_times_are_a_minimax_point(q, duration, objective, conditions):
    t = cs.optimal_times(q, duration, objective, **conditions)
    assert _minimax_step(q, t, conditions) >= -1e-9


@pytest.mark.parametrize(("q", "duration", "objective", "conditions"), [
    p for p in PROBLEMS if p.values[2] == "rms_acceleration"])
def test_auto_rms_times_are_stationary(q, duration, objective, conditions):
    t = cs.optimal_times(q, duration, objective, **conditions)
    step = 1e-6 * duration
    value = rms(spline(t, q, conditions))
    gradient = [(rms(spline(t + step * e, q, conditions))
                 - rms(spline(t - step * e, q, conditions))) / (2 * step)
                for e in np.eye(len(t))[1:-1]]
    assert np.max(np.abs(gradient)) * duration <= 1e-4 * value  # O(1) at the equal times
