"""The pieces' polynomial evaluation reproduces numpy's polyval and polyder bit for bit
(the exact piece values every law, coefficient and sizing result is built on)."""

from __future__ import annotations

import numpy as np
from numpy.polynomial import polynomial as P

from sizer.laws.pieces import _horner, polynomial_derivative, trig_poly_piece


def test_horner_and_derivative_match_numpy_bitwise():
    rng = np.random.default_rng(11)
    for degree in range(7):
        for _ in range(20):
            coef = rng.normal(size=degree + 1) * 10.0 ** rng.uniform(-6, 6, size=degree + 1)
            x = rng.uniform(-2.0, 2.0, size=64)
            ours, theirs = coef.tolist(), coef
            for _order in range(6):
                expected = P.polyval(x, theirs) + np.zeros_like(x)
                got = _horner(ours, x) + 0.0
                assert got.tobytes() == expected.tobytes()
                theirs, ours = P.polyder(theirs), polynomial_derivative(ours)
                assert np.asarray(ours).tobytes() == theirs.tobytes()


def test_piece_derivatives_of_a_cubic():
    # q = 1 + 2u + 3u^2 + 4u^3 with u = tau - 0.5: q' = 2 + 6u + 12u^2, q'' = 6 + 24u,
    # q''' = 24, q'''' = 0 (exact in binary at these points)
    piece = trig_poly_piece(0.0, 1.0, (1.0, 2.0, 3.0, 4.0), origin=0.5)
    tau = np.array([0.0, 0.25, 0.5, 1.0])
    u = tau - 0.5
    expected = [1 + 2 * u + 3 * u**2 + 4 * u**3, 2 + 6 * u + 12 * u**2, 6 + 24 * u,
                np.full(4, 24.0), np.zeros(4)]
    for order, values in enumerate(expected):
        assert np.array_equal(piece.evaluate(tau, order), values)
    assert not np.signbit(piece.evaluate(tau, 4)).any()  # no -0.0
