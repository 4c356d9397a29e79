"""sizer.energy.power.interval_parts: the integrals of the positive and negative parts of
a piecewise-linear signal, per interval, against their closed forms (a trapezoid where
the sign holds, two triangles split at the zero crossing where it changes)."""

from __future__ import annotations

import numpy as np
import pytest

from sizer.energy.power import interval_parts


def _by_hand(t: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    up, down = np.zeros((p.shape[0], p.shape[1] - 1)), np.zeros((p.shape[0], p.shape[1] - 1))
    for i in range(p.shape[0]):
        times = t[0] if t.shape[0] == 1 else t[i]
        for k in range(p.shape[1] - 1):
            a, b, h = p[i, k], p[i, k + 1], times[k + 1] - times[k]
            if a >= 0.0 and b >= 0.0:
                up[i, k] = 0.5 * (a + b) * h
            elif a <= 0.0 and b <= 0.0:
                down[i, k] = -0.5 * (a + b) * h
            else:  # the zero at h |a| / (|a| + |b|): a triangle each side
                zero = h * abs(a) / (abs(a) + abs(b))
                up[i, k] = 0.5 * max(a, b) * (zero if a > 0.0 else h - zero)
                down[i, k] = -0.5 * min(a, b) * (zero if a < 0.0 else h - zero)
    return up, down


@pytest.mark.parametrize("shared_time", [True, False])
def test_parts_match_the_trapezoids_and_triangles(shared_time: bool) -> None:
    rng = np.random.default_rng(3)
    n, m = 7, 60
    t = np.cumsum(rng.uniform(0.001, 0.01, (1 if shared_time else n, m)), axis=1)
    p = rng.standard_normal((n, m)) * np.where(rng.random((n, m)) < 0.15, 0.0, 1.0)
    up, down = interval_parts(t, p)
    want_up, want_down = _by_hand(t, p)
    np.testing.assert_allclose(up, want_up, rtol=1e-12, atol=1e-300)
    np.testing.assert_allclose(down, want_down, rtol=1e-12, atol=1e-300)
    assert np.all(up >= 0.0) and np.all(down >= 0.0)
    # the net integral is their difference, interval by interval
    np.testing.assert_allclose(up - down, 0.5 * (p[:, :-1] + p[:, 1:]) * np.diff(t, axis=1),
                               rtol=1e-12, atol=1e-15)


def test_a_signal_without_sign_change_and_zeros() -> None:
    t = np.array([[0.0, 1.0, 2.0, 3.0]])
    up, down = interval_parts(t, np.array([[0.0, 0.0, 2.0, 0.0], [-1.0, 0.0, 0.0, -3.0]]))
    np.testing.assert_array_equal(up, [[0.0, 1.0, 1.0], [0.0, 0.0, 0.0]])
    np.testing.assert_array_equal(down, [[0.0, 0.0, 0.0], [0.5, 0.0, 1.5]])
