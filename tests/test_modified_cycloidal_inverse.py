"""The modified cycloidal law's time map tau = tau_m - kappa sin(2 pi tau_m)/(2 pi),
inverted (sizer.laws.modified_cycloidal.solve_tau_m), against plain bisection: the map is
increasing for |kappa| < 1, so 200 halvings of [tau - |kappa|/2pi, tau + |kappa|/2pi]
give the root to rounding."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sizer.laws.modified_cycloidal import MAX_KAPPA, WILDT_KAPPA, solve_tau_m


def bisection(tau: np.ndarray, kappa: float) -> np.ndarray:
    lo = tau - abs(kappa) / (2 * math.pi)
    hi = tau + abs(kappa) / (2 * math.pi)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        below = mid - kappa * np.sin(2 * math.pi * mid) / (2 * math.pi) < tau
        lo, hi = np.where(below, mid, lo), np.where(below, hi, mid)
    return 0.5 * (lo + hi)


@pytest.mark.parametrize("kappa", [WILDT_KAPPA, 0.5, -0.5, -0.9, MAX_KAPPA, -MAX_KAPPA, 0.0])
def test_the_inverse_equals_bisection(kappa):
    tau = np.concatenate(([0.0, 0.5, 1.0], np.random.default_rng(1).uniform(0.0, 1.0, 5000)))
    found = solve_tau_m(tau, kappa)
    # the root's conditioning is 1/f', f' = 1 - kappa cos >= 1 - |kappa|
    np.testing.assert_allclose(found, bisection(tau, kappa), rtol=0,
                               atol=1e-15 / (1.0 - abs(kappa)) + 1e-15)


def test_the_shape_is_kept():
    tau = np.linspace(0.0, 1.0, 12).reshape(3, 4)
    assert solve_tau_m(tau, 0.3).shape == (3, 4)
