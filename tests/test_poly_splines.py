"""The slides' classic polynomial spline of order k (seed 002, "Spline classica
polinomiale"): its system of conditions as printed, the worked example, closed forms and
scipy's own splines as independent references, and the refusals of bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.interpolate import CubicSpline

from sizer.errors import UserError
from sizer.laws.multipoint.poly_splines import (
    build_poly_spline,
    classic_system,
    end_conditions,
    poly_spline,
)

# The slides' example: 4 via-points, 3 pieces of widths 15, 16.5 and 31 degrees (their
# matrix prints h_1 = 0.2618, h_2 = 0.2880, h_3 = 0.5411 rad and their powers).
SLIDES_TIMES = np.radians([0.0, 15.0, 31.5, 62.5])
SLIDES_POSITIONS = [0.0, 0.15, 0.8, 1.0]
SLIDES_START = {"velocity": 0, "acceleration": 0}
SLIDES_END = {"velocity": 0, "jerk": 0}
SLIDES_FIELDS = {"kind": "poly_spline", "order": 6, "times": list(SLIDES_TIMES),
                 "positions": SLIDES_POSITIONS, "start": SLIDES_START, "end": SLIDES_END}


def piece_derivative(curve, j: int, r: int, at: float) -> float:
    """The r-th derivative of piece j's own polynomial at ``at`` (numpy.polynomial on the
    PPoly's coefficients: the left value at the piece's right end)."""
    coefficients = curve.c[::-1, j]  # ascending powers of (t - x_j)
    poly = np.polynomial.Polynomial(coefficients).deriv(r)
    return float(poly(at - curve.x[j]))


def test_the_slides_matrix_is_reproduced_to_the_printed_digits() -> None:
    conditions = end_conditions(SLIDES_TIMES[0], SLIDES_TIMES[-1], {1: 0.0, 2: 0.0},
                                {1: 0.0, 3: 0.0})
    A, b, labels = classic_system(SLIDES_TIMES, SLIDES_POSITIONS, 6, conditions)
    assert A.shape == (18, 18)
    row = {text: A[i] for i, (_, text) in enumerate(labels)}
    # Rows 1-5 and 6-10 of the slides (continuity at x_1 and x_2), columns F_j ... A_j.
    printed_1 = [[1, 0.2618, 0.0685, 0.0179, 0.0047, 0.0012], [0, 1, 0.5236, 0.2056, 0.0718,
                 0.0235], [0, 0, 2, 1.5708, 0.8225, 0.3589], [0, 0, 0, 6, 6.2832, 4.1123]]
    printed_2 = [[1, 0.2880, 0.0829, 0.0239, 0.0069, 0.0020], [0, 1, 0.5760, 0.2488, 0.0955,
                 0.0344], [0, 0, 2, 1.7279, 0.9952, 0.4777], [0, 0, 0, 6, 6.9115, 4.9759]]
    for r in range(4):
        np.testing.assert_allclose(A[r, :6], printed_1[r], atol=5e-5)
        np.testing.assert_allclose(A[5 + r, 6:12], printed_2[r], atol=5e-5)
        assert A[r, 6 + r] == A[5 + r, 12 + r] == -math.factorial(r)
    # Printed "31.41..." and "34.55...": 120 h_1 and 120 h_2.
    assert A[4, 4] == 24 and math.floor(A[4, 5] * 100) == 3141
    assert A[9, 10] == 24 and math.floor(A[9, 11] * 100) == 3455
    # Rows 15, 16, 18 (positions), 11-13 (start), 14 (end velocity: the slides print
    # 0.6335 once and 0.6555 once; 4 h_3^3 = 0.63354, see docs/errata.md), 17 (end jerk).
    np.testing.assert_allclose(row["points[1]"][:6], printed_1[0], atol=5e-5)
    np.testing.assert_allclose(row["points[2]"][6:12], printed_2[0], atol=5e-5)
    np.testing.assert_allclose(row["points[3]"][12:],
                               [1, 0.5411, 0.2927, 0.1584, 0.0857, 0.0464], atol=5e-5)
    np.testing.assert_allclose(row["end.velocity"][13:],
                               [1, 1.0821, 0.8782, 0.6335, 0.4285], atol=5e-5)
    np.testing.assert_allclose(row["end.jerk"][15:16], [6])
    assert math.floor(row["end.jerk"][16] * 100) == 1298
    assert math.floor(row["end.jerk"][17] * 100) == 1756
    assert list(np.flatnonzero(row["points[0]"])) == [0] and row["points[0]"][0] == 1
    assert list(np.flatnonzero(row["start.velocity"])) == [1]
    assert list(np.flatnonzero(row["start.acceleration"])) == [2]
    assert row["start.acceleration"][2] == 2  # 2 D_1 = 0 (the slides misprint D_2 = 0)
    np.testing.assert_array_equal(b, [0] * 10 + [0.15, 0.8, 0, 1, 0, 0, 0, 0])


def test_the_slides_example_meets_every_condition() -> None:
    curve = build_poly_spline(SLIDES_FIELDS)
    t = SLIDES_TIMES
    np.testing.assert_allclose(curve.x, t)
    assert curve.c.shape == (6, 3)
    np.testing.assert_allclose(curve(t), SLIDES_POSITIONS, atol=1e-12)
    for r, value in ((1, curve(t[0], 1)), (2, curve(t[0], 2))):
        assert abs(value) < 1e-9, r
    assert abs(curve(t[-1], 1)) < 1e-9
    assert abs(piece_derivative(curve, 2, 3, t[-1])) < 1e-9
    # C4 at the interior points: the left piece's derivatives at its right end equal the
    # right piece's at its left end, up to the fourth (the slides' "jounce").
    for j in (1, 2):
        for r in range(5):
            left = piece_derivative(curve, j - 1, r, t[j])
            right = piece_derivative(curve, j, r, t[j])
            assert abs(left - right) <= 1e-9 * max(1.0, abs(right)), (j, r)
        # ... and not the fifth: the spline is of order 6, C^(k-2) only.
        assert abs(piece_derivative(curve, j - 1, 5, t[j]) -
                   piece_derivative(curve, j, 5, t[j])) > 1e-3


def test_an_independent_numpy_solve_of_the_eighteen_conditions_agrees() -> None:
    """The 18 conditions written out here coefficient by coefficient and solved with
    numpy, in degrees (another time unit: the code solves in normalized time)."""
    h = np.array([15.0, 16.5, 31.0])
    rows, rhs = [], []

    def der(j: int, r: int, dt: float) -> np.ndarray:
        row = np.zeros(18)
        for m in range(r, 6):
            row[6 * j + m] = math.factorial(m) / math.factorial(m - r) * dt ** (m - r)
        return row

    for j in (0, 1):
        for r in range(5):
            rows.append(der(j, r, h[j]) - der(j + 1, r, 0.0))
            rhs.append(0.0)
    for j, value in ((0, 0.15), (1, 0.8), (2, 1.0)):
        rows.append(der(j, 0, h[j]))
        rhs.append(value)
    for j, r, dt in ((0, 0, 0.0), (0, 1, 0.0), (0, 2, 0.0), (2, 1, h[2]), (2, 3, h[2])):
        rows.append(der(j, r, dt))
        rhs.append(0.0)
    a = np.linalg.solve(np.array(rows), np.array(rhs)).reshape(3, 6)
    fields = dict(SLIDES_FIELDS, times=[0.0, 15.0, 31.5, 62.5])
    curve = build_poly_spline(fields)
    np.testing.assert_allclose(curve.c[::-1].T, a, rtol=1e-9, atol=1e-12)


def test_two_points_order_six_is_the_quintic_of_the_book() -> None:
    """Rest to rest with v = a = 0 at both ends: q = h (10 s^3 - 15 s^4 + 6 s^5)."""
    curve = build_poly_spline({"points": [[0, 0], [2, 3]], "order": 6,
                               "start": {"velocity": 0, "acceleration": 0},
                               "end": {"velocity": 0, "acceleration": 0}})
    t = np.linspace(0, 2, 41)
    s = t / 2
    np.testing.assert_allclose(curve(t), 3 * (10 * s**3 - 15 * s**4 + 6 * s**5), atol=1e-12)
    np.testing.assert_allclose(curve(t, 1), 3 * (30 * s**2 - 60 * s**3 + 30 * s**4) / 2,
                               atol=1e-11)


def test_order_four_is_the_clamped_and_the_periodic_cubic_spline() -> None:
    t = [0.0, 0.7, 1.5, 2.0, 3.2]
    q = [1.0, -0.5, 2.0, 0.3, 1.0]
    grid = np.linspace(0, 3.2, 301)
    clamped = build_poly_spline({"times": t, "positions": q, "order": 4,
                                 "start": {"velocity": 0.5}, "end": {"velocity": -1}})
    reference = CubicSpline(t, q, bc_type=((1, 0.5), (1, -1.0)))
    for nu in range(4):
        np.testing.assert_allclose(clamped(grid, nu), reference(grid, nu), atol=1e-10)
    cyclic = build_poly_spline({"times": t, "positions": q, "degree": 3,
                                "periodic": ["velocity", "acceleration"]})
    reference = CubicSpline(t, q, bc_type="periodic")
    inside = grid[:-1]  # CubicSpline extrapolates periodically: t_n is its t_0
    for nu in range(4):
        np.testing.assert_allclose(cyclic(inside, nu), reference(inside, nu), atol=1e-10)


def test_order_two_is_the_broken_line() -> None:
    curve = build_poly_spline({"points": [[0, 0], [1, 2], [3, 1]], "order": 2})
    np.testing.assert_allclose(curve(np.array([0.5, 2.0])), [1.0, 1.5])


def test_interior_conditions_are_met() -> None:
    fields = {"points": [[0, 0], [1, 0.4], [2, 0.5], [3, 1]], "order": 5,
              "start": {"velocity": 0}, "end": {"velocity": 0},
              "conditions": [{"t": 0.5, "velocity": 0.2}]}
    curve = poly_spline(*np.array(fields["points"]).T, 5, {1: 0.0}, {1: 0.0},
                        [(0.5, 1, 0.2, "conditions[0].velocity")])
    assert abs(curve(0.5, 1) - 0.2) < 1e-12
    np.testing.assert_allclose(build_poly_spline(fields)(np.linspace(0, 3, 31)),
                               curve(np.linspace(0, 3, 31)), atol=1e-12)


def _error(fields: dict) -> UserError:
    with pytest.raises(UserError) as caught:
        build_poly_spline(fields)
    return caught.value


def test_too_few_conditions_says_how_many_are_missing() -> None:
    error = _error(dict(SLIDES_FIELDS, end={"velocity": 0}))
    assert error.field == "end"
    assert "order 6 through 4 points needs 4 conditions" in error.message
    assert "got 3" in error.message and "add 1" in error.message


def test_too_many_conditions_says_how_many() -> None:
    error = _error(dict(SLIDES_FIELDS, conditions=[{"t": 0.3, "velocity": 1}]))
    assert error.field == "conditions"
    assert "needs 4 conditions" in error.message and "1 too many" in error.message


def test_dependent_conditions_are_named() -> None:
    fields = dict(SLIDES_FIELDS, start={"velocity": 0},
                  conditions=[{"t": 0.0, "velocity": 0}])
    error = _error(fields)
    assert error.field == "start"
    assert "singular" in error.message
    assert "start.velocity" in error.message and "conditions[0].velocity" in error.message
    assert "end.jerk" not in error.message


def test_contradictory_cyclic_and_end_conditions_are_named() -> None:
    # v(t_0) = v(t_n) given twice: as values and as a cyclic condition.
    error = _error({"points": [[0, 0], [1, 1], [2, 0]], "order": 5,
                    "start": {"velocity": 0}, "end": {"velocity": 1},
                    "periodic": ["velocity"]})
    assert error.field == "start" and "singular" in error.message
    for name in ("start.velocity", "end.velocity", "periodic.velocity"):
        assert name in error.message


@pytest.mark.parametrize(("fields", "field", "text"), [
    ({"points": [[0, 0]], "order": 4}, "points", "at least 2 points"),
    ({"points": [[0, 0], [1, 1], [1, 2]], "order": 3, "start": {"velocity": 0}},
     "points[2]", "times must increase"),
    ({"points": [[0, 0], [1, 1]], "order": 1}, "order", "between 2 and 12"),
    ({"points": [[0, 0], [1, 1]]}, "order", "is required"),
    ({"points": [[0, 0], [1, 1]], "order": 4, "degree": 3}, "order", "not both"),
    ({"points": [[0, 0], [1, 1]], "order": 4, "knots": [0, 1]}, "knots", "no field"),
    ({"points": [[0, 0], [1, 1]], "order": 4, "start": {"speed": 0}}, "start.speed",
     "unknown condition"),
    ({"points": [[0, 0], [1, 1]], "order": 4, "start": {"velocity": 0},
      "conditions": [{"t": 2, "velocity": 0}]}, "conditions[0]", "outside"),
    ({"points": [[0, 0], [1, 1]], "order": 3, "start": {"jerk": 0}}, "start.jerk",
     "derivative 3 is not defined"),
    ({"points": [[0, 0], [1, 1], [2, 0]], "order": 5, "start": {"velocity": 0},
      "end": {"velocity": 0}, "conditions": [{"t": 1, "snap": 0}]},
     "conditions[0].snap", "derivative 4 jumps"),
    ({"points": [[0, 0], [1, 1]], "order": 4, "periodic": ["velocity", "velocity"]},
     "periodic[1]", "listed twice"),
])
def test_bad_input_names_the_field(fields: dict, field: str, text: str) -> None:
    error = _error(fields)
    assert error.field == field
    assert text in error.message
