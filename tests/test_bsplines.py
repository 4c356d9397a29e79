"""B-spline trajectories (book sec. 4.5, slides "B-Splines"): the book's Examples 4.16 to
4.19 to their printed digits, the slides' example against the classic spline, scipy's
make_interp_spline as an independent reference, and the refusals of bad input."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.interpolate import BSpline, make_interp_spline

from sizer.errors import UserError
from sizer.laws.multipoint.bsplines import (
    basis_matrix,
    bspline_system,
    build_bspline,
    default_knots,
    interpolating_bspline,
)
from sizer.laws.multipoint.poly_splines import build_poly_spline, end_conditions

BOOK_T = [0.0, 5.0, 7.0, 8.0, 10.0, 15.0, 18.0]
BOOK_Q = [3.0, -2.0, -5.0, 0.0, 6.0, 12.0, 8.0]
BOOK_Q_CYCLIC = [3.0, -2.0, -5.0, 0.0, 6.0, 12.0, 3.0]  # Examples 4.17 and 4.19


def printed(values: np.ndarray, book: list[float]) -> None:
    """The book prints two decimals, mostly truncated (7.4499 as 7.44), a few rounded
    (0.0067 as 0.01): every printed figure is within 0.01 of the exact value."""
    assert np.all(np.abs(np.asarray(values) - np.asarray(book)) < 0.01 + 1e-12), values


def test_example_4_16_degree_4_midpoint_knots() -> None:
    knots = default_knots(np.array(BOOK_T), 4)  # even degree: eq. (4.43)
    np.testing.assert_allclose(knots, [0, 0, 0, 0, 0, 2.5, 6, 7.5, 9, 12.5, 16.5, 18, 18, 18,
                                       18, 18])
    conditions = end_conditions(0.0, 18.0, {1: 2.0, 2: 0.0}, {1: -3.0, 2: 0.0})
    A, c, labels = bspline_system(np.array(BOOK_T), BOOK_Q,
                                  lambda x, nu: basis_matrix(knots, 4, x, nu), conditions)
    # The book's row order (4.47): q0, v0, a0, q1 ... q5, a6, v6, q6.
    order = ["points[0]", "start.velocity", "start.acceleration", *[
        f"points[{i}]" for i in range(1, 6)], "end.acceleration", "end.velocity", "points[6]"]
    at = {text: i for i, (_, text) in enumerate(labels)}
    A = A[[at[name] for name in order]]
    c = c[[at[name] for name in order]]
    np.testing.assert_allclose(c, [3, 2, 0, -2, -5, 0, 6, 12, 0, -3, 8])
    book_A = [
        [1.00, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0],
        [-1.60, 1.60, 0, 0, 0, 0, 0, 0, 0, 0, 0],
        [1.92, -2.72, 0.80, 0, 0, 0, 0, 0, 0, 0, 0],
        [0, 0.00, 0.08, 0.43, 0.44, 0.03, 0, 0, 0, 0, 0],
        [0, 0, 0.00, 0.05, 0.58, 0.34, 0.00, 0, 0, 0, 0],
        [0, 0, 0, 0.00, 0.34, 0.59, 0.05, 0.00, 0, 0, 0],
        [0, 0, 0, 0, 0.03, 0.50, 0.40, 0.05, 0.00, 0, 0],
        [0, 0, 0, 0, 0, 0.00, 0.08, 0.39, 0.45, 0.05, 0],
        [0, 0, 0, 0, 0, 0, 0, 0, 1.45, -6.78, 5.33],
        [0, 0, 0, 0, 0, 0, 0, 0, 0, -2.66, 2.66],
        [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1.00]]
    printed(A, book_A)
    spline = interpolating_bspline(np.array(BOOK_T), np.array(BOOK_Q), 4, None,
                                   {1: 2.0, 2: 0.0}, {1: -3.0, 2: 0.0})
    printed(spline.c, [3, 4.25, 7.25, 7.39, -13.66, 7.44, 4.98, 12.59, 13.25, 9.12, 8])
    curve = build_bspline({"times": BOOK_T, "positions": BOOK_Q, "degree": 4,
                           "start": {"velocity": 2, "acceleration": 0},
                           "end": {"velocity": -3, "acceleration": 0}})
    np.testing.assert_allclose(curve.x, [0, 2.5, 6, 7.5, 9, 12.5, 16.5, 18])
    np.testing.assert_allclose(curve(np.array(BOOK_T)), BOOK_Q, atol=1e-12)
    np.testing.assert_allclose([curve(0, 1), curve(0, 2), curve(18, 1), curve(18, 2)],
                               [2, 0, -3, 0], atol=1e-12)


def test_example_4_16_with_the_extra_knot_of_eq_4_48() -> None:
    """(4.42) with an extra knot at 16.5 (the book prints four 18s; five are needed)."""
    knots = [0] * 5 + [5, 7, 8, 10, 15, 16.5] + [18] * 5
    curve = build_bspline({"times": BOOK_T, "positions": BOOK_Q, "degree": 4, "knots": knots,
                           "start": {"velocity": 2, "acceleration": 0},
                           "end": {"velocity": -3, "acceleration": 0}})
    np.testing.assert_allclose(curve(np.array(BOOK_T)), BOOK_Q, atol=1e-12)
    np.testing.assert_allclose([curve(0, 1), curve(0, 2), curve(18, 1), curve(18, 2)],
                               [2, 0, -3, 0], atol=1e-12)


def test_example_4_17_cyclic_degree_4() -> None:
    t = np.array(BOOK_T)
    knots = default_knots(t, 4, "midpoints")
    A, c, _ = bspline_system(t, BOOK_Q_CYCLIC, lambda x, nu: basis_matrix(knots, 4, x, nu),
                             periodic=[1, 2, 3, 4])
    assert A.shape == (11, 11)  # the book prints 12 columns and a stray 2 in c
    np.testing.assert_allclose(c, [3, -2, -5, 0, 6, 12, 3, 0, 0, 0, 0])
    printed(A[7:], [  # rows B^(i)(t_0) - B^(i)(t_n), i = 1..4
        [-1.60, 1.60, 0, 0, 0, 0, 0, 0, 0, 2.66, -2.66],
        [1.92, -2.72, 0.80, 0, 0, 0, 0, 0, -1.45, 6.78, -5.33],
        [-1.53, 2.44, -1.12, 0.21, 0, 0, 0, 0.32, -2.79, 9.57, -7.11],
        [0.61, -1.02, 0.55, -0.17, 0.02, 0, -0.03, 0.34, -2.05, 6.48, -4.74]])
    curve = build_bspline({"times": BOOK_T, "positions": BOOK_Q_CYCLIC, "degree": 4,
                           "periodic": ["velocity", "acceleration", "jerk", "snap"]})
    np.testing.assert_allclose(curve(t), BOOK_Q_CYCLIC, atol=1e-12)
    for nu in (1, 2, 3, 4):
        start, end = curve(0.0, nu), curve(18.0, nu)
        assert abs(start - end) <= 1e-9 * max(1.0, abs(start)), nu
    spline = interpolating_bspline(t, np.array(BOOK_Q_CYCLIC), 4, None, periodic=[1, 2, 3, 4])
    printed(spline.c, [3, 1.82, 1.30, 8.88, -13.96, 7.73, 3.66, 20.41, 7.53, 3.70, 3])


def test_example_4_17_with_knots_at_the_points_is_singular_not_ill_conditioned() -> None:
    """The book calls the (4.42) system with cyclic v, a, j "ill-conditioned" (Fig. 4.22,
    values to 1e17): its matrix has rank 9 of 10 (numpy here, on scipy's basis)."""
    t = np.array(BOOK_T)
    knots = np.array([0] * 5 + [5, 7, 8, 10, 15] + [18] * 5, dtype=float)
    basis = BSpline(knots, np.eye(10), 4)
    A = np.vstack([basis(t)] + [basis(t[:1], r) - basis(t[-1:], r) for r in (1, 2, 3)])
    assert np.linalg.matrix_rank(A) == 9
    with pytest.raises(UserError) as caught:
        build_bspline({"times": BOOK_T, "positions": BOOK_Q_CYCLIC, "degree": 4,
                       "knots": "points", "periodic": ["velocity", "acceleration", "jerk"]})
    assert caught.value.field == "periodic"
    assert "singular" in caught.value.message
    assert "periodic.velocity" in caught.value.message


def test_example_4_18_degree_5() -> None:
    spline = interpolating_bspline(np.array(BOOK_T), np.array(BOOK_Q), 5, None,
                                   {1: 2.0, 2: 0.0}, {1: -3.0, 2: 0.0})
    np.testing.assert_allclose(spline.t, [0] * 6 + [5, 7, 8, 10, 15] + [18] * 6)
    # Printed "35, 7.80, ..." (ten numbers): p_0 = 3, p_1 = 5 (docs/errata.md).
    printed(spline.c, [3, 5, 7.80, 9.69, -18.83, 12.01, 1.5137, 12.33, 14.60, 9.80, 8])
    assert abs(spline.c[6] - 1.5137) < 5e-5


def test_example_4_19_degree_5_mixed_conditions() -> None:
    fields = {"times": BOOK_T, "positions": BOOK_Q_CYCLIC, "degree": 5,
              "start": {"velocity": 2}, "end": {"velocity": 2},
              "periodic": ["acceleration", "jerk"]}
    spline = interpolating_bspline(np.array(BOOK_T), np.array(BOOK_Q_CYCLIC), 5, None,
                                   {1: 2.0}, {1: 2.0}, periodic=[2, 3])
    printed(spline.c, [3, 5.00, 13.13, 8.34, -18.96, 12.57, -2.81, 34.44, 2.26, 1.80, 3])
    knots = spline.t
    A, c, labels = bspline_system(np.array(BOOK_T), BOOK_Q_CYCLIC,
                                  lambda x, nu: basis_matrix(knots, 5, x, nu),
                                  end_conditions(0.0, 18.0, {1: 2.0}, {1: 2.0}), [2, 3])
    # The book's order: q0, v0, q1 ... q5, v6, q6, then the two cyclic rows; it prints
    # c with a twelfth entry (an extra 0) for eleven unknowns.
    order = ["points[0]", "start.velocity", *[f"points[{i}]" for i in range(1, 6)],
             "end.velocity", "points[6]", "periodic.acceleration", "periodic.jerk"]
    at = {text: i for i, (_, text) in enumerate(labels)}
    np.testing.assert_allclose(c[[at[name] for name in order]],
                               [3, 2, -2, -5, 0, 6, 12, 2, 3, 0, 0])
    printed(A[-2:], [[0.80, -1.37, 0.57, 0, 0, 0, 0, 0, -0.83, 3.05, -2.22],
                     [-0.48, 1.06, -0.80, 0.21, 0, 0, 0, 0.25, -1.39, 3.36, -2.22]])
    curve = build_bspline(fields)
    assert abs(curve(0.0, 2) - curve(18.0, 2)) < 1e-9
    assert abs(curve(0.0, 3) - curve(18.0, 3)) < 1e-9


SLIDES_CONDITIONS = {"start": {"velocity": 0, "acceleration": 0},
                     "end": {"velocity": 0, "jerk": 0}}


def assert_same(a, b, x: np.ndarray, highest: int = 5, rtol: float = 1e-9) -> None:
    for nu in range(highest + 1):
        ya, yb = a(x, nu), b(x, nu)
        assert np.max(np.abs(ya - yb)) <= rtol * max(1.0, np.max(np.abs(yb))), nu


def test_the_slides_knots_give_the_classic_spline() -> None:
    """Slides: T = [0 x 6, 0.3, 0.55, 1 x 6] (k + n = 14 knots). With the interior knots
    at the interior via-times (0.3, 0.55), the order-6 B-splines with simple knots span
    exactly the C4 quintic splines with breakpoints at the via-points, the classic
    spline's space; both meet the same 8 conditions, which fix one spline: equal."""
    fields = {"times": [0.0, 0.3, 0.55, 1.0], "positions": [0, 0.15, 0.8, 1], "order": 6,
              **SLIDES_CONDITIONS}
    slides_knots = [0] * 6 + [0.3, 0.55] + [1] * 6
    bspline = build_bspline({**fields, "knots": slides_knots})
    classic = build_poly_spline(fields)
    assert_same(bspline, classic, np.linspace(0, 1, 2001))
    np.testing.assert_allclose(bspline([0.0, 0.3, 0.55, 1.0]), [0, 0.15, 0.8, 1], atol=1e-12)
    checks = [bspline(0.0, 1), bspline(0.0, 2), bspline(1.0, 1), bspline(1.0, 3)]
    np.testing.assert_allclose(checks, 0.0, atol=1e-9)
    for knot in (0.3, 0.55):  # C4 (left and right derivatives), not C5
        for nu in range(5):
            j = int(np.searchsorted(bspline.x, knot)) - 1
            left = np.polynomial.Polynomial(bspline.c[::-1, j]).deriv(nu)(knot - bspline.x[j])
            assert abs(left - bspline(knot, nu)) <= 1e-9 * max(1.0, abs(left))


def test_the_slides_example_in_its_own_times_with_the_default_knots() -> None:
    """The classic example's times (0, 15, 31.5, 62.5 degrees): the default knots for an
    odd degree are the via-times (4.42), so the B-spline is the classic spline."""
    t = list(np.radians([0.0, 15.0, 31.5, 62.5]))
    fields = {"times": t, "positions": [0, 0.15, 0.8, 1], "order": 6, **SLIDES_CONDITIONS}
    knots = default_knots(np.array(t), 5)
    assert len(knots) == 14  # k + n = 6 + 8 (slides, Fase 1)
    assert_same(build_bspline(fields), build_poly_spline(fields), np.linspace(t[0], t[-1],
                                                                              2001))


def test_the_slides_knot_fractions_on_other_times_are_another_spline() -> None:
    """Knots 0.3, 0.55 of the interval with the via-points elsewhere: still every
    condition met, but breakpoints away from the via-points, so not the classic spline."""
    t = np.radians([0.0, 15.0, 31.5, 62.5])
    T = t[-1]
    fields = {"times": list(t), "positions": [0, 0.15, 0.8, 1], "order": 6,
              "knots": [0.0] * 6 + [0.3 * T, 0.55 * T] + [T] * 6, **SLIDES_CONDITIONS}
    curve = build_bspline(fields)
    np.testing.assert_allclose(curve.x, [0, 0.3 * T, 0.55 * T, T])
    np.testing.assert_allclose(curve(t), [0, 0.15, 0.8, 1], atol=1e-12)
    scale = np.max(np.abs(curve(np.linspace(0, T, 201), 3)))
    for value in (curve(0.0, 1), curve(0.0, 2), curve(T, 1), curve(T, 3)):
        assert abs(value) <= 1e-9 * scale
    classic = build_poly_spline({k: v for k, v in fields.items() if k != "knots"})
    assert np.max(np.abs(curve(np.linspace(0, T, 201)) - classic(np.linspace(0, T, 201)))
                  ) > 1e-3


def test_scipy_make_interp_spline_agrees_for_end_conditions() -> None:
    t = np.array([0.0, 0.4, 1.1, 1.5, 2.2, 3.0])
    q = np.array([0.0, 0.3, 0.2, 0.9, 1.4, 2.0])
    reference = make_interp_spline(t, q, k=5, bc_type=([(1, 0.5), (2, 0.0)],
                                                       [(1, 0.0), (3, 1.0)]))
    curve = build_bspline({"times": list(t), "positions": list(q), "order": 6,
                           "start": {"velocity": 0.5, "acceleration": 0},
                           "end": {"velocity": 0, "jerk": 1}})
    assert_same(curve, reference, np.linspace(0, 3, 601))


def test_interior_conditions_are_met() -> None:
    fields = {"times": [0, 1, 2, 3], "positions": [0, 0.5, 0.6, 1], "order": 6,
              "knots": [0] * 6 + [0.5, 1, 2] + [3] * 6, "start": {"velocity": 0},
              "end": {"velocity": 0, "acceleration": 0},
              "conditions": [{"t": 1.5, "velocity": 0.1, "acceleration": 0}]}
    curve = build_bspline(fields)
    np.testing.assert_allclose([curve(1.5, 1), curve(1.5, 2)], [0.1, 0.0], atol=1e-12)
    np.testing.assert_allclose(curve([0, 1, 2, 3]), [0, 0.5, 0.6, 1], atol=1e-12)


def test_a_bspline_given_by_its_control_points() -> None:
    knots = [0, 0, 0, 0, 1, 2, 2.5, 4, 4, 4, 4]
    P = [0.0, 1.0, -0.5, 2.0, 1.5, 0.3, 1.0]
    curve = build_bspline({"order": 4, "knots": knots, "control_points": P})
    reference = BSpline(np.array(knots, float), np.array(P), 3)
    np.testing.assert_allclose(curve.x, [0, 1, 2, 2.5, 4])
    assert_same(curve, reference, np.linspace(0, 4, 401), highest=4, rtol=1e-12)


def _error(fields: dict) -> UserError:
    with pytest.raises(UserError) as caught:
        build_bspline(fields)
    return caught.value


SLIDES_B = {"times": [0.0, 0.3, 0.55, 1.0], "positions": [0, 0.15, 0.8, 1], "order": 6,
            **SLIDES_CONDITIONS}


@pytest.mark.parametrize(("fields", "field", "text"), [
    ({**SLIDES_B, "knots": [0] * 6 + [0.55, 0.3] + [1] * 6}, "knots",
     "must be non-decreasing: knots[7] = 0.3 follows 0.55"),
    ({**SLIDES_B, "knots": [0] * 5 + [1] * 5}, "knots", "needs at least 12 knots"),
    ({**SLIDES_B, "knots": [0] * 6 + [0.3, 0.3, 0.3, 0.3, 0.3, 0.3] + [1] * 6}, "knots",
     "repeated 6 times"),
    ({**SLIDES_B, "knots": [0] * 6 + [0.3, 0.55] + [2] * 6}, "knots", "base interval"),
    ({**SLIDES_B, "knots": "uniform"}, "knots", "points, midpoints"),
    ({**SLIDES_B, "end": {"velocity": 0}}, "end",
     "order 6 (degree 5) through 4 points (8 control points, 4 via-points) needs 4 "
     "conditions"),
    ({**SLIDES_B, "knots": [0] * 6 + [0.3] + [1] * 6}, "end",
     "(7 control points, 4 via-points) needs 3 conditions"),
    ({**SLIDES_B, "knots": [0] * 6 + [0.3, 0.55] + [1] * 6,
      "start": {"velocity": 0, "acceleration": 0, "jerk": 0}}, "end", "got 5 (start.velocity, "
     "start.acceleration, start.jerk, end.velocity, end.jerk): 1 too many"),
    ({"order": 6, "knots": [0] * 6 + [1] * 6, "control_points": [0, 1, 2]},
     "control_points", "order 6 needs at least 6 control points, got 3"),
    ({"order": 4, "knots": [0] * 4 + [0.5] + [1] * 4, "control_points": [0, 1, 2, 3]},
     "control_points", "must have 5 numbers (one per control point: 9 knots - order 4)"),
    ({"order": 4, "control_points": [0, 1, 2, 3]}, "knots", "list of numbers"),
    ({"order": 4, "knots": [0] * 4 + [1] * 4, "control_points": [0, 1, 2, 3],
      "points": [[0, 0], [1, 1]]}, "points", "takes no points"),
    ({**SLIDES_B, "start": {"velocity": 0}, "conditions": [{"t": 0.0, "velocity": 0}]},
     "start", "start.velocity, conditions[0].velocity"),
    ({**SLIDES_B, "weights": [1] * 8}, "weights", "no field"),
    ({**SLIDES_B, "order": 5, "knots": [0] * 5 + [0.3, 0.55] + [1] * 5,
      "start": {"velocity": 0}, "end": {"velocity": 0},
      "conditions": [{"t": 0.3, "snap": 0}]},
     "conditions[0].snap", "only C^3 at the knot t = 0.3 (repeated 1 times): its "
     "derivative 4 jumps"),
])
def test_bad_input_names_the_field(fields: dict, field: str, text: str) -> None:
    error = _error(fields)
    assert error.field == field
    assert text in error.message


def test_knots_that_cannot_interpolate_are_a_singular_system() -> None:
    """Schoenberg-Whitney: the cubic B-splines on [0 x 4, 2.5, 2.6, 2.7, 3 x 4] cannot
    pass through four points at 0.1 ... 0.4 spaced apart: named as singular."""
    error = _error({"times": [0, 0.1, 0.2, 0.3, 3], "positions": [0, 1, 0, 1, 0],
                    "order": 4, "knots": [0] * 4 + [2.5, 2.6] + [3] * 4,
                    "start": {"velocity": 0}})
    assert error.field == "start"
    assert "singular" in error.message and "points[" in error.message


def test_many_points_in_milliseconds_classic_and_bspline_agree() -> None:
    """81 uneven via-points over 2000 ms: both systems stay well conditioned (the classic
    one is solved per piece in ((t - t_j)/h_j)^m) and give the same C4 quintic spline."""
    t = np.linspace(0.0, 1.0, 81) ** 1.2 * 2000.0
    fields = {"times": list(t), "positions": list(np.sin(t / 150.0)), "order": 6,
              **SLIDES_CONDITIONS}
    assert_same(build_bspline(fields), build_poly_spline(fields),
                np.linspace(0.0, 2000.0, 4001))
