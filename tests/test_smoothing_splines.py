"""Smoothing cubic splines (book sec. 4.4.5): Examples 4.10 to 4.13 to their printed
digits, the book's (4.35), (4.36) against a direct minimization of (4.29), and the bad
inputs of ``kind: smoothing_spline``."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.interpolate import CubicSpline
from test_cubic_splines import Q_BOOK, Q_PERIODIC, T_BOOK, agrees, assert_c2, assert_printed

from sizer.errors import UserError
from sizer.laws.multipoint import cubic_splines as cs
from sizer.laws.multipoint import smoothing_splines as ss

ENDS_EXACT = np.array([0.0, 1, 1, 1, 1, 1, 0])


@pytest.mark.parametrize(("mu", "w_inv", "printed"), [
    (0.3, ENDS_EXACT, "3 -2.29 -2.22 -0.41 4.79 10.33 8"),
    (0.6, ENDS_EXACT, "3 -2.55 -3.11 -0.76 5.62 11.38 8"),
    (0.6, [0, 1, 0.1, 1, 1, 1, 0], "3 -3.14 -4.66 -1.73 5.60 11.42 8"),
])
def test_example_4_10_smoothed_points(mu, w_inv, printed):
    s, _ = ss.smoothed_points(T_BOOK, Q_BOOK, mu, np.array(w_inv, dtype=float))
    assert_printed(s, printed)
    assert s[0] == Q_BOOK[0] and s[-1] == Q_BOOK[-1]


def test_mu_one_interpolates_with_zero_end_velocities():
    pp = ss.smoothing_spline(T_BOOK, Q_BOOK, 1.0, ENDS_EXACT)
    np.testing.assert_allclose(pp.c, cs.clamped_spline(T_BOOK, Q_BOOK, 0.0, 0.0).c,
                               rtol=0, atol=1e-9)


def direct_minimum(t, q, mu, w_inv) -> np.ndarray:
    """s minimizing (4.29)/mu over the clamped (zero end velocity) cubic splines, the
    points with w_inv = 0 held exactly: the spline is linear in its knot values s, its
    energy int s''^2 = s^T G s with G from Simpson's rule (exact: s'' is piecewise
    linear)."""
    n = len(t)
    basis = [CubicSpline(t, np.eye(n)[j], bc_type="clamped") for j in range(n)]
    mid = (t[:-1] + t[1:]) / 2
    h = np.diff(t)
    acc = [np.array([b(t[:-1], 2), b(mid, 2), b(t[1:], 2)]) for b in basis]
    G = np.array([[np.sum(h / 6 * (ai[0] * aj[0] + 4 * ai[1] * aj[1] + ai[2] * aj[2]))
                   for aj in acc] for ai in acc])
    lam = (1 - mu) / mu
    free = w_inv > 0
    W = np.diag(np.where(free, 1 / np.where(free, w_inv, 1), 0.0))
    # stationarity on the free values, the others fixed at q
    H = W + lam * G
    s = q.astype(float).copy()
    rhs = (W @ q)[free] - H[np.ix_(free, ~free)] @ q[~free]
    s[free] = np.linalg.solve(H[np.ix_(free, free)], rhs)
    return s


@pytest.mark.parametrize("mu", [0.1, 0.3, 0.6, 0.9])
def test_book_solution_is_the_minimum_of_4_29(mu):
    for w_inv in (ENDS_EXACT, np.array([0.0, 1, 0.1, 2, 1, 0.5, 0]),
                  np.array([1.0, 1, 1, 1, 1, 1, 1])):
        s, _ = ss.smoothed_points(T_BOOK, Q_BOOK, mu, w_inv)
        np.testing.assert_allclose(s, direct_minimum(T_BOOK, Q_BOOK, mu, w_inv),
                                   rtol=0, atol=1e-9)


def test_smoothing_spline_conditions():
    pp = ss.smoothing_spline(T_BOOK, Q_BOOK, 0.6, ENDS_EXACT)
    s, omega = ss.smoothed_points(T_BOOK, Q_BOOK, 0.6, ENDS_EXACT)
    np.testing.assert_allclose(pp(T_BOOK), s, rtol=0, atol=1e-9)
    np.testing.assert_allclose(pp(T_BOOK, 2), omega, rtol=0, atol=1e-9)
    np.testing.assert_allclose(pp(T_BOOK[[0, -1]], 1), 0.0, rtol=0, atol=1e-9)
    assert_c2(pp)


def test_example_4_11_end_velocities_and_accelerations():
    fields = {"kind": "smoothing_spline", "times": T_BOOK.tolist(),
              "positions": Q_PERIODIC.tolist(), "mu": 0.9,
              "inverse_weights": ENDS_EXACT.tolist(),
              "start": {"velocity": 2, "acceleration": 0},
              "end": {"velocity": -3, "acceleration": 0}}
    s, _ = ss.smoothed_points(T_BOOK, Q_PERIODIC, 0.9, ENDS_EXACT)
    assert_printed(s, "3 -2.28 -4.10 -0.65 6.09 11.71 3")
    pp = ss.build_smoothing_spline(fields)
    np.testing.assert_allclose(pp.x, [0, 2.5, 5, 7, 8, 10, 15, 16.5, 18])
    assert_printed(pp(pp.x, 2), "0 -2.65 1.23 4.06 -0.66 -0.25 -1.71 0.16 0")
    assert_printed(pp(pp.x[[1, 7]]), "5.23 7.56")
    np.testing.assert_allclose(pp(T_BOOK), s, rtol=0, atol=1e-9)
    np.testing.assert_allclose(pp(T_BOOK[[0, -1]], 1), [2, -3], rtol=0, atol=1e-9)
    assert_c2(pp)


def test_example_4_12_periodic():
    pp = ss.build_smoothing_spline({"times": T_BOOK.tolist(), "mu": 0.9,
                                    "positions": Q_PERIODIC.tolist(), "periodic": True})
    assert_printed(pp.c[::-1].T, """3 -2.39 0.67 -0.08   -2.28 -1.78 -0.55 0.49
        -4.10 1.96 2.43 -0.94   -0.65 3.99 -0.40 0.04   6.09 2.94 -0.12 -0.04
        11.71 -1.89 -0.84 0.16""")
    for nu in range(3):
        assert abs(pp(0.0, nu) - pp(18.0, nu)) < 1e-9


@pytest.mark.parametrize(("tolerance", "printed"), [(0.1, "0.9931"), (1.0, "0.8792")])
def test_example_4_13_tolerance(tolerance, printed):
    mu = ss.mu_for_tolerance(T_BOOK, Q_PERIODIC, tolerance, ENDS_EXACT)
    assert agrees(mu, printed)
    s, _ = ss.smoothed_points(T_BOOK, Q_PERIODIC, mu, ENDS_EXACT)
    assert np.max(np.abs(s - Q_PERIODIC)) <= tolerance
    pp = ss.build_smoothing_spline({"times": T_BOOK.tolist(), "tolerance": tolerance,
                                    "positions": Q_PERIODIC.tolist()})
    np.testing.assert_allclose(pp(T_BOOK), s, rtol=0, atol=1e-9)


def test_default_and_point_weights():
    base = {"times": T_BOOK.tolist(), "positions": Q_BOOK.tolist(), "mu": 0.6}
    default = ss.build_smoothing_spline(base)
    np.testing.assert_allclose(default(T_BOOK[[0, -1]]), Q_BOOK[[0, -1]], atol=1e-12)
    w = [0.5, 1, 10, 1, 2, 1, 4]
    by_weights = ss.build_smoothing_spline({**base, "point_weights": w})
    by_inverse = ss.build_smoothing_spline({**base, "inverse_weights":
                                            (1 / np.array(w)).tolist()})
    np.testing.assert_allclose(by_weights.c, by_inverse.c, rtol=0, atol=1e-12)
    # zero end velocities given explicitly re-interpolate s with the same spline
    same = ss.build_smoothing_spline({**base, "start": {"velocity": 0}})
    np.testing.assert_allclose(same.c, default.c, rtol=0, atol=1e-9)


POINTS = {"times": [0, 1, 2], "positions": [0, 1, 3]}
BAD = [
    ({**POINTS, "mu": 0}, "mu", "must be in (0, 1]"),
    ({**POINTS, "mu": 1.5}, "mu", "must be in (0, 1]"),
    ({**POINTS}, "mu", "is required"),
    ({**POINTS, "mu": 0.5, "tolerance": 0.1}, "tolerance", "not both"),
    ({**POINTS, "mu": 0.5, "point_weights": [1, 0, 1]}, "point_weights[1]", "positive"),
    ({**POINTS, "mu": 0.5, "inverse_weights": [0, -1, 0]}, "inverse_weights[1]", ">= 0"),
    ({**POINTS, "mu": 0.5, "inverse_weights": [0, 1]}, "inverse_weights", "must have 3"),
    ({**POINTS, "mu": 0.5, "lambda": 2}, "lambda", "has no field 'lambda'"),
    ({**POINTS, "mu": 0.5, "periodic": True}, "periodic", "last position equal"),
    ({"times": [0, 1, 2], "positions": [0, 1, 0], "mu": 0.5, "periodic": True,
      "point_weights": [1, 1, 1]}, "periodic", "inverse_weights 0"),
    ({"times": [0, 2, 1], "positions": [0, 1, 3], "mu": 0.5}, "times", "increasing"),
    ({"times": [0], "positions": [0], "mu": 0.5}, "positions", "at least 2"),
]


@pytest.mark.parametrize(("fields", "field", "text"), BAD)
def test_bad_input_names_the_field(fields, field, text):
    with pytest.raises(UserError) as caught:
        ss.build_smoothing_spline(fields)
    assert caught.value.field == field
    assert text in caught.value.message
