"""The cubic Hermite model's root (sizer.numerics.hermite.hermite_root) against the
roots of the same cubic from numpy.roots (its companion matrix), on random brackets."""

from __future__ import annotations

import numpy as np

from sizer.numerics.hermite import hermite_root


def test_the_root_is_a_root_of_the_cubic_inside_the_bracket():
    rng = np.random.default_rng(5)
    n = 400
    g0 = rng.standard_normal(n)
    g1 = -np.sign(g0) * np.abs(rng.standard_normal(n))
    d0, d1 = 3.0 * rng.standard_normal(n), 3.0 * rng.standard_normal(n)
    s = hermite_root(g0, g1, d0, d1)
    c2 = 3.0 * (g1 - g0) - 2.0 * d0 - d1
    c3 = 2.0 * (g0 - g1) + d0 + d1
    for k in range(n):
        roots = np.roots([c3[k], c2[k], d0[k], g0[k]])
        real = roots[np.abs(roots.imag) < 1e-9].real
        inside = real[(real >= -1e-12) & (real <= 1.0 + 1e-12)]
        assert len(inside), k  # opposite signs at the ends: a root in [0, 1]
        assert np.min(np.abs(inside - s[k])) < 1e-9, (k, s[k], inside)


def test_shapes_broadcast_and_are_kept():
    g0 = np.full((2, 3), -1.0)
    s = hermite_root(g0, 1.0, 2.0, 2.0)  # the line -1 + 2 s: root 1/2
    assert s.shape == (2, 3)
    np.testing.assert_allclose(s, 0.5, rtol=1e-15)
