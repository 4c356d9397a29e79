"""The inner step of ``times: auto`` (book sec. 4.4.6, issue 34): the unchecked clamped
spline is scipy's CubicSpline bit for bit and the batched Jacobian is SLSQP's own, so the
optimizer's path and its times are those of the plain construction."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import minimize

from sizer.laws.multipoint import cubic_splines as cs


@pytest.mark.parametrize("seed", range(20))
def test_unchecked_clamped_spline_is_scipys_bit_for_bit(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(3, 40))
    duration = float(rng.choice([0.01, 1.0, 3.0, 50.0]))  # long intervals: gtsv pivots
    t = np.concatenate([[0.0], np.cumsum(rng.uniform(0.01, 1.0, n - 1))])
    t *= duration / t[-1]
    q = np.cumsum(rng.normal(size=n))
    v0, vn = (float(v) for v in rng.normal(size=2))
    fast = cs._clamped_spline_unchecked(t, q, v0, vn)
    slow = cs.clamped_spline(t, q, v0, vn)
    np.testing.assert_array_equal(fast.x, slow.x)
    np.testing.assert_array_equal(fast.c, slow.c)
    np.testing.assert_array_equal(fast(fast.x, 2), slow(slow.x, 2))


def _peak_times_the_plain_way(q, duration, v0, vn):
    """optimal_times' minimax with scipy's checked splines and SLSQP's own Jacobian."""
    def spline(y):
        return cs.clamped_spline(cs.times_from_free(y, duration), q, v0, vn)

    def accelerations(y):
        pp = spline(y)
        return pp(pp.x, 2) / scale

    n = len(q) - 1
    scale = cs.peak_acceleration(spline(np.zeros(n - 1)))
    bands = [{"type": "ineq", "fun": lambda v: v[-1] - accelerations(v[:-1])},
             {"type": "ineq", "fun": lambda v: v[-1] + accelerations(v[:-1])}]
    result = minimize(lambda v: v[-1], np.append(np.zeros(n - 1), 1.0), method="SLSQP",
                      constraints=bands,
                      bounds=[(-5.0, 5.0)] * (n - 1) + [(0.0, None)],
                      options={"ftol": 1e-14, "maxiter": 500})
    return cs.times_from_free(result.x[:-1], duration)


@pytest.mark.parametrize(("q", "duration", "v0", "vn"), [
    (np.array([0.0, 2, 12, 5, 12, -10]), 2.0, 0.5, -1.0),
    (np.array([0.0, 0.1, 0.5, 0.45, 0.9, 1.0, 0.7, 1.2]), 1.0, 0.0, 0.0),
    (np.array([0.0, 2, 12, 5, 12, -10, -11, -4, 6, 9]), 30.0, 0.0, 0.0),  # gtsv pivots
])
def test_auto_times_equal_the_plain_slsqp_ones(q, duration, v0, vn):
    np.testing.assert_array_equal(cs.optimal_times(q, duration, v0=v0, vn=vn),
                                  _peak_times_the_plain_way(q, duration, v0, vn))


def test_auto_rms_times_equal_those_of_the_checked_spline(monkeypatch):
    q = np.array([0.0, 2, 12, 5, 12, -10])
    fast = cs.optimal_times(q, 2.0, "rms_acceleration", v0=0.5, vn=-1.0)
    monkeypatch.setattr(cs, "_clamped_spline_unchecked", cs.clamped_spline)
    np.testing.assert_array_equal(
        fast, cs.optimal_times(q, 2.0, "rms_acceleration", v0=0.5, vn=-1.0))
