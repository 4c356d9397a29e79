"""NURBS curves (slides "NURBS"): unit weights give the B-spline, a weight acts only on
its basis function's support, the exact derivatives against finite differences of an
independent evaluation, the slides' weighted example solved, and bad input."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.interpolate import BSpline

from sizer.errors import UserError
from sizer.laws.multipoint.bsplines import build_bspline
from sizer.laws.multipoint.nurbs import NURBS, build_nurbs, rational_basis

KNOTS = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.3, 0.55, 0.8, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0]
POINTS = [0.0, 0.1, -0.3, 0.7, 1.2, 0.9, 1.4, 1.1, 1.0]  # 15 knots - order 6
WEIGHTS = [1.0, 0.8, 1.5, 2.0, 0.7, 1.0, 1.3, 0.9, 1.0]


def cox_de_boor(knots: np.ndarray, k: int, x: float) -> np.ndarray:
    """Independent evaluation of the order-k basis N_{j,k}(x) by the Cox-de Boor
    recursion as it should read (docs/errata.md: the slides' second denominator):
    N_{j,k} = (x - T_j)/(T_{j+k-1} - T_j) N_{j,k-1} + (T_{j+k} - x)/(T_{j+k} - T_{j+1})
    N_{j+1,k-1}, 0/0 = 0; half-open spans, the last one closed."""
    T = np.asarray(knots, dtype=float)
    last = np.flatnonzero(T[-1] > T)[-1]
    N = np.array([1.0 if (T[j] <= x < T[j + 1]) or (j == last and x == T[-1]) else 0.0
                  for j in range(len(T) - 1)])
    for order in range(2, k + 1):
        new = np.zeros(len(T) - order)
        for j in range(len(new)):
            left = T[j + order - 1] - T[j]
            right = T[j + order] - T[j + 1]
            a = (x - T[j]) / left * N[j] if left > 0 else 0.0
            b = (T[j + order] - x) / right * N[j + 1] if right > 0 else 0.0
            new[j] = a + b
        N = new
    return N


def independent_nurbs(x: float, knots=KNOTS, points=POINTS, weights=WEIGHTS, k=6) -> float:
    N = cox_de_boor(np.array(knots), k, x) * np.array(weights)
    return float(N @ np.array(points) / N.sum())


def test_unit_weights_give_the_bspline() -> None:
    nurbs = build_nurbs({"order": 6, "knots": KNOTS, "control_points": POINTS,
                         "weights": [1] * 9})
    bspline = build_bspline({"order": 6, "knots": KNOTS, "control_points": POINTS})
    x = np.linspace(0, 1, 1001)
    np.testing.assert_allclose(nurbs.x, [0, 0.3, 0.55, 0.8, 1])
    for nu in range(4):
        reference = bspline(x, nu)
        assert np.max(np.abs(nurbs(x, nu) - reference)) <= 1e-12 * max(
            1.0, np.max(np.abs(reference))), nu


def test_one_weight_moves_the_curve_only_on_its_support() -> None:
    """N_{i,k} vanishes outside [u_i, u_{i+k}]: there the sums over j of W_j N_j P_j and
    W_j N_j do not contain W_i, so the curve is exactly the same."""
    x = np.linspace(0, 1, 2001)
    base = NURBS(np.array(KNOTS), np.array(POINTS), np.array(WEIGHTS), 5)
    for i in (0, 3, 6, 8):
        weights = np.array(WEIGHTS)
        weights[i] *= 3.0
        moved = NURBS(np.array(KNOTS), np.array(POINTS), weights, 5)
        lo, hi = KNOTS[i], KNOTS[i + 6]
        outside = (x < lo) | (x > hi)
        inside = (x > lo) & (x < hi)
        for nu in range(3):
            np.testing.assert_array_equal(moved(x[outside], nu), base(x[outside], nu))
        assert np.max(np.abs(moved(x[inside]) - base(x[inside]))) > 1e-4, i


def test_values_match_the_independent_evaluation() -> None:
    curve = NURBS(np.array(KNOTS), np.array(POINTS), np.array(WEIGHTS), 5)
    x = np.linspace(0, 1, 37)
    np.testing.assert_allclose(curve(x), [independent_nurbs(v) for v in x], atol=1e-13)


@pytest.mark.parametrize("nu", [1, 2, 3, 4])
def test_derivatives_match_finite_differences(nu: int) -> None:
    """Central differences of the independent evaluation, Richardson-extrapolated from
    steps h and h/2 (error O(h^4)), inside the knot spans."""
    stencils = {1: [-0.5, 0, 0.5], 2: [1, -2, 1], 3: [-0.5, 1, 0, -1, 0.5],
                4: [1, -4, 6, -4, 1]}
    weights = np.array(stencils[nu], dtype=float)
    offsets = np.arange(len(weights)) - len(weights) // 2
    curve = NURBS(np.array(KNOTS), np.array(POINTS), np.array(WEIGHTS), 5)

    def difference(x: float, h: float) -> float:
        return sum(w * independent_nurbs(x + o * h) for w, o in zip(weights, offsets,
                                                                     strict=True)) / h**nu

    for x in (0.1, 0.2, 0.42, 0.67, 0.9):
        h = 0.002
        estimate = (4 * difference(x, h / 2) - difference(x, h)) / 3
        exact = float(curve(x, nu))
        assert abs(exact - estimate) <= 1e-5 * max(1.0, abs(exact)), (x, exact, estimate)


def test_the_rational_basis_is_a_partition_of_unity() -> None:
    x = np.linspace(0, 1, 53)
    R = rational_basis(np.array(KNOTS), 5, np.array(WEIGHTS), x)
    np.testing.assert_allclose(R.sum(axis=1), 1.0, atol=1e-14)
    for nu in (1, 2, 3):
        derivative = rational_basis(np.array(KNOTS), 5, np.array(WEIGHTS), x, nu)
        assert np.max(np.abs(derivative.sum(axis=1))) <= 1e-9 * np.max(np.abs(derivative))


SLIDES = {"times": [0.0, 0.3, 0.55, 1.0], "positions": [0, 0.15, 0.8, 1], "order": 6,
          "start": {"velocity": 0, "acceleration": 0}, "end": {"velocity": 0, "jerk": 0},
          "knots": [0] * 6 + [0.3, 0.55] + [1] * 6}


def test_the_slides_weights_solved_through_the_points() -> None:
    """Slides: W = [2, 1, 1, 1, 1, 1, 1, 1] on the 8-condition example: for fixed weights
    the conditions are linear in the control points; all met."""
    curve = build_nurbs({**SLIDES, "weights": [2, 1, 1, 1, 1, 1, 1, 1]})
    np.testing.assert_allclose(curve(np.array([0, 0.3, 0.55, 1.0])), [0, 0.15, 0.8, 1],
                               atol=1e-12)
    np.testing.assert_allclose([independent_nurbs(v, SLIDES["knots"], curve.control_points,
                                                  [2, 1, 1, 1, 1, 1, 1, 1])
                                for v in (0.3, 0.55)], [0.15, 0.8], atol=1e-12)
    for value in (curve(0.0, 1), curve(0.0, 2), curve(1.0, 1), curve(1.0, 3)):
        assert abs(value) < 1e-9
    unit = build_nurbs({**SLIDES, "weights": [1] * 8})
    bspline = build_bspline(SLIDES)
    x = np.linspace(0, 1, 501)
    np.testing.assert_allclose(unit(x), bspline(x), atol=1e-12)
    assert np.max(np.abs(curve(x) - bspline(x))) > 1e-4


def test_default_knots_and_scipy_agree_on_the_numerator() -> None:
    curve = build_nurbs({"times": [0, 1, 2, 3], "positions": [0, 1, 0, 2], "order": 4,
                         "start": {"velocity": 0}, "end": {"acceleration": 0},
                         "weights": [1, 2, 1, 1, 1, 1]})
    numerator = BSpline(curve.knots, curve.weights * curve.control_points, 3)
    denominator = BSpline(curve.knots, curve.weights, 3)
    x = np.linspace(0, 3, 31)
    np.testing.assert_allclose(curve(x), numerator(x) / denominator(x), atol=1e-13)
    np.testing.assert_allclose(curve.knots, [0, 0, 0, 0, 1, 2, 3, 3, 3, 3])  # (4.42)
    assert abs(curve(0.0, 1)) < 1e-12 and abs(curve(3.0, 2)) < 1e-11


def _error(fields: dict) -> UserError:
    with pytest.raises(UserError) as caught:
        build_nurbs(fields)
    return caught.value


@pytest.mark.parametrize(("fields", "field", "text"), [
    ({**SLIDES, "weights": [1, 1, 0, 1, 1, 1, 1, 1]}, "weights",
     "must be positive: weights[2] = 0"),
    ({**SLIDES, "weights": [1, 1, -2, 1, 1, 1, 1, 1]}, "weights", "weights[2] = -2"),
    ({**SLIDES, "weights": [1] * 7}, "weights",
     "must have 8 numbers (one per control point: 14 knots - order 6), got 7"),
    (SLIDES, "weights", "is required"),
    ({"order": 6, "knots": KNOTS, "control_points": POINTS, "weights": [1] * 10},
     "weights", "must have 9 numbers"),
    ({"order": 6, "knots": KNOTS, "control_points": POINTS[:5], "weights": [1] * 5},
     "control_points", "order 6 needs at least 6 control points, got 5"),
    ({"order": 6, "knots": KNOTS[::-1], "control_points": POINTS, "weights": WEIGHTS},
     "knots", "non-decreasing"),
    ({**SLIDES, "weights": [1] * 8, "start": {"velocity": 0},
      "conditions": [{"t": 0, "velocity": 0}]}, "start", "singular"),
    ({**SLIDES, "weights": [1] * 8, "end": {"velocity": 0}}, "end", "add 1"),
])
def test_bad_input_names_the_field(fields: dict, field: str, text: str) -> None:
    error = _error(fields)
    assert error.field == field
    assert text in error.message
