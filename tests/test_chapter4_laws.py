"""The polynomial through n points, least-squares orthogonal polynomials and the
trigonometric polynomial as laws defined by data (book sec. 4.1, 4.2, 4.3).

Expected numbers are the book's (Examples 4.1 to 4.6, to their printed digits), closed
forms (a polynomial or a trigonometric sum sampled at the points is given back; poly3 and
poly5 from their end conditions) or independent computations (scipy's Krogh and
barycentric interpolators, least squares by numpy's lstsq, the book's Lagrange-like form
(4.6), dense sampling refined by scipy's bounded minimizer, scipy's quad), never the
code's own output.
"""

from __future__ import annotations

import json
import math
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
import yaml
from cli_run import assert_user_error, run_cli
from numpy.polynomial import Chebyshev, Polynomial

from sizer.api import size
from sizer.laws import make_law
from sizer.laws.data_law import DataLaw
from sizer.laws.multipoint.interpolating_polynomial import oscillation_warning
from sizer.laws.multipoint.least_squares_polynomial import orthogonal_fit

# Examples 4.2 to 4.5
T42 = [0.0, 1.0, 3.0, 7.0, 8.0, 10.0]
Q42 = [2.0, 3.0, 5.0, 6.0, 8.0, 9.0]
POINTS42 = [[t, q] for t, q in zip(T42, Q42, strict=True)]
# Example 4.6
T46 = [0, 4, 6, 8, 9, 11, 15, 17, 19, 20]
Q46 = [2, 3, 3, 2, 2, 2, 3, 4, 5, 2]


def _law(fields: dict) -> DataLaw:
    law = make_law(yaml.safe_dump(fields, default_flow_style=True, width=10_000).strip())
    assert isinstance(law, DataLaw) and law.law_id == fields["kind"]
    assert make_law(law.spec) is law
    return law


def _curve(law: DataLaw, t: np.ndarray, order: int = 0) -> np.ndarray:
    """The law's curve back in the data's units: q(t) = q_0 + S q_N(tau), q^(k) = S
    q_N^(k) / D^k."""
    t0, span = float(law.curve.x[0]), float(law.curve.x[-1] - law.curve.x[0])
    values = law.derivative((np.asarray(t, dtype=float) - t0) / span, order) * law._size
    return values / span ** order + (law._q0 if order == 0 else 0.0)


# ------------------------------------------------------------- sec. 4.1 (Example 4.1)
A41 = [1, -3, 24, 3, 5, 6, 7, -3, 5, 12, 4]
Q41_PRINTED = [1, 0.943, 1.394, 2.401, 4.052, 6.507, 10.074, 15.359, 23.594, 37.231, 61]


def test_example_4_1_the_polynomial_through_its_points_is_the_polynomial() -> None:
    t = [Fraction(k, 10) for k in range(11)]
    q = [sum(Fraction(a) * tk ** i for i, a in enumerate(A41)) for tk in t]
    # the book's printed via-points are these, truncated to three decimals
    assert all(0 <= float(v) - p < 1e-3 for v, p in zip(q, Q41_PRINTED, strict=True))
    law = _law({"kind": "interpolating_polynomial", "times": [float(v) for v in t],
                "positions": [float(v) for v in q]})
    exact = Polynomial(A41)
    grid = np.linspace(0, 1, 1001)
    for order in range(4):
        expected = exact.deriv(order)(grid)
        assert _curve(law, grid, order) == pytest.approx(expected, rel=1e-10,
                                                         abs=1e-10 * np.max(abs(expected)))
    assert law.report["degree"] == 10


def test_degree_20_keeps_its_digits_where_the_book_loses_them() -> None:
    # Example 4.1, n = 20: the Vandermonde (kappa 9.1e16) leaves an error of 25 in the
    # coefficients; the Chebyshev system gives the polynomial back to 1e-10
    coefficients = np.random.default_rng(4).uniform(-25, 25, 21)
    exact = Polynomial(coefficients)
    t = np.arange(21) / 20
    law = _law({"kind": "interpolating_polynomial", "times": t.tolist(),
                "positions": exact(t).tolist()})
    grid = np.linspace(0, 1, 2001)
    scale = np.max(np.abs(exact(grid)))
    assert np.max(np.abs(_curve(law, grid) - exact(grid))) < 1e-10 * scale
    assert law.report["degree"] == 20


def test_a_cubic_through_four_points_is_that_cubic() -> None:
    cubic = Polynomial([0.1, -0.4, 2.0, -0.7])  # in t over [0, 2]
    t = np.array([0.0, 0.5, 1.3, 2.0])
    law = _law({"kind": "interpolating_polynomial", "times": t.tolist(),
                "positions": cubic(t).tolist()})
    grid = np.linspace(0, 2, 101)
    for order in range(5):
        assert _curve(law, grid, order) == pytest.approx(cubic.deriv(order)(grid),
                                                         abs=1e-12)


def test_end_velocities_and_accelerations_are_the_books_extra_conditions() -> None:
    # n + 1 = 4 points and v, a at both ends: degree n + 4 = 7, the polynomial itself
    p = Polynomial([0.0, 0.3, -1.0, 0.5, 2.0, -0.8, 0.2, -0.05])
    t = np.array([0.0, 1.0, 2.5, 4.0])
    d1, d2 = p.deriv(1), p.deriv(2)
    law = _law({"kind": "interpolating_polynomial", "times": t.tolist(),
                "positions": p(t).tolist(),
                "start": {"velocity": float(d1(0)), "acceleration": float(d2(0))},
                "end": {"velocity": float(d1(4)), "acceleration": float(d2(4))}})
    grid = np.linspace(0, 4, 201)
    for order in range(4):
        expected = p.deriv(order)(grid)
        assert _curve(law, grid, order) == pytest.approx(
            expected, abs=1e-10 * max(1.0, np.max(np.abs(expected))))
    assert law.report["degree"] == 7


def test_two_points_at_rest_are_poly3_and_poly5() -> None:
    poly3 = _law({"kind": "interpolating_polynomial", "points": [[0, 0], [1, 1]],
                  "start": {"velocity": 0}, "end": {"velocity": 0}}).coefficients
    assert (poly3.C_v, poly3.C_a, poly3.C_j) == pytest.approx((1.5, 6.0, 12.0), rel=1e-12)
    assert poly3.C_v_rms == pytest.approx(math.sqrt(6 / 5), rel=1e-12)
    assert poly3.C_a_rms == pytest.approx(2 * math.sqrt(3), rel=1e-12)
    rest = {"velocity": 0, "acceleration": 0}
    poly5 = _law({"kind": "interpolating_polynomial", "points": [[0, 0], [1, 1]],
                  "start": rest, "end": rest}).coefficients
    assert (poly5.C_v, poly5.C_a, poly5.C_j) == pytest.approx(
        (15 / 8, 10 / math.sqrt(3), 60.0), rel=1e-12)
    assert poly5.C_v_rms == pytest.approx(math.sqrt(10 / 7), rel=1e-12)
    assert poly5.C_a_rms == pytest.approx(math.sqrt(120 / 7), rel=1e-12)
    assert poly5.jerk_bounded and not poly3.jerk_bounded


def test_hermite_data_agree_with_scipys_krogh_interpolator() -> None:
    from scipy.interpolate import KroghInterpolator

    t = [0.0, 0.2, 0.45, 0.8, 1.0]
    q = [0.0, 0.1, 0.5, 0.85, 1.0]
    law = _law({"kind": "interpolating_polynomial", "times": t, "positions": q,
                "start": {"velocity": 0, "acceleration": 0}, "end": {"velocity": 0}})
    krogh = KroghInterpolator([0, 0, 0, *t[1:-1], 1, 1], [0, 0, 0, *q[1:-1], 1, 0])
    grid = np.linspace(0, 1, 301)
    for order in range(4):
        assert law.derivative(grid, order) == pytest.approx(
            krogh.derivative(grid, order), abs=1e-9 * max(1, np.max(abs(
                krogh.derivative(grid, order)))))
    assert law.rest_to_rest


def test_runge_the_lebesgue_constant_and_the_overshoot_of_even_points() -> None:
    from scipy.interpolate import BarycentricInterpolator

    x = np.linspace(-1, 1, 11)
    runge = 1 / (1 + 25 * x ** 2)
    law = _law({"kind": "interpolating_polynomial", "times": x.tolist(),
                "positions": runge.tolist()})
    grid = np.linspace(-1, 1, 200_001)
    # Lebesgue function from the Lagrange products themselves
    lagrange = np.zeros_like(grid)
    for k in range(11):
        others = np.delete(x, k)
        lagrange += np.abs(np.prod((grid[:, None] - others) / (x[k] - others), axis=1))
    assert law.report["lebesgue_constant"] == pytest.approx(np.max(lagrange), rel=1e-3)
    assert np.max(lagrange) == pytest.approx(29.90, abs=0.01)  # the known Lambda_10
    peak = np.max(BarycentricInterpolator(x, runge)(grid))  # 1.9156 near |x| = 0.94
    assert law.report["overshoot"] == pytest.approx((peak - 1) / (1 - 1 / 26), rel=1e-4)
    assert "Runge" in (oscillation_warning(law.report) or "")
    gentle = _law({"kind": "interpolating_polynomial", "points": [[0, 0], [0.5, 0.5], [1, 1]],
                   "start": {"velocity": 0}, "end": {"velocity": 0}})
    assert oscillation_warning(gentle.report) is None


# ------------------------------------------------------------- sec. 4.2 (Examples 4.2-4.5)
def _monomial(p: Chebyshev) -> np.ndarray:
    return p.convert(kind=Polynomial, domain=[-1, 1], window=[-1, 1]).coef


def test_example_4_2_forsythes_polynomials_and_coefficients() -> None:
    fit = orthogonal_fit(np.array(T42), np.array(Q42), 4, Chebyshev([1.0], domain=[0, 10]))
    printed = [[1], [-4.833, 1], [9.8149, -9.7203, 1], [-28.5693, 59.3370, -15.3917, 1],
               [38.9880, -212.9051, 121.8979, -20.0860, 1]]
    for p, book in zip(fit.polynomials, printed, strict=True):
        assert _monomial(p) == pytest.approx(book, abs=5.1e-4)
    # a_2 is printed -0.049: an erratum for -0.0049, as the book's own p_2 gives
    p2 = np.polyval([1, -9.7203, 9.8149], T42)
    assert np.dot(Q42, p2) / np.dot(p2, p2) == pytest.approx(-0.00485, abs=1e-5)
    book = [5.5, 0.6579, -0.0049, 0.0112, -0.0033]
    assert fit.coefficients == pytest.approx(book, abs=5e-5)


def test_example_4_2_law_is_the_least_squares_quartic() -> None:
    law = _law({"kind": "least_squares_polynomial", "points": POINTS42, "degree": 4})
    t = np.array(T42)
    # independent: least squares on the monomials of tau (well conditioned at degree 4)
    tau = t / 10
    coef = np.linalg.lstsq(np.vander(tau, 5, increasing=True), np.array(Q42), rcond=None)[0]
    grid = np.linspace(0, 10, 201)
    expected = Polynomial(coef)(grid / 10)
    assert _curve(law, grid) == pytest.approx(expected, abs=1e-11)
    residual = Polynomial(coef)(tau) - Q42
    assert law.report["max_residual"] == pytest.approx(np.max(np.abs(residual)), rel=1e-9)
    # the curve does not pass through the points, and its ends move (Fig. 4.1)
    assert law.report["max_residual"] > 0.1 and not law.rest_to_rest


@pytest.mark.parametrize(("start", "power", "printed", "coefficients"), [
    ({}, 1, [[0, 1, -1], [0, -0.5364, 1.5364, -1], [0, 0.1848, -1.1724, 1.9875, -1],
             [0, -0.0520, 0.5513, -1.8255, 2.3261, -1]],
     [0.7465, -10.1223, 28.1252, 317.4603]),
    ({"velocity": 0}, 2,
     [[0, 0, 1, -1], [0, 0, -0.7001, 1.7001, -1], [0, 0, 0.2546, -1.3464, 2.0918, -1],
      [0, 0, -0.1501, 1.0937, -2.6874, 2.7438, -1]],
     [10.3710, -54.7230, 334.9531, -111.9615]),
    ({"velocity": 0, "acceleration": 0}, 3,
     [[0, 0, 0, 1, -1], [0, 0, 0, -0.7422, 1.7422, -1],
      [0, 0, 0, 0.3663, -1.6099, 2.2436, -1],
      [0, 0, 0, -0.1667, 1.1728, -2.8033, 2.7972, -1]],
     [21.7, -134.8, 853.7, -9390]),  # printed to 3 or 4 figures
], ids=["example_4_3", "example_4_4", "example_4_5"])
def test_examples_4_3_to_4_5_held_ends(start: dict, power: int, printed: list,
                                       coefficients: list) -> None:
    tau = np.array(T42) / 10
    q = np.array(Q42)
    first = Chebyshev.identity(domain=[0, 1]) ** power * (1 - Chebyshev.identity(
        domain=[0, 1]))
    fit = orthogonal_fit(tau, q - 2 - 7 * tau ** power, 4, first)
    for p, book in zip(fit.polynomials[:4], printed, strict=True):
        assert _monomial(p) == pytest.approx(book, abs=5.1e-5)
    # p_4 = p_0 (tau - 0.1)(tau - 0.3)(tau - 0.7)(tau - 0.8) vanishes at the four inner
    # points: the book's a_4 = 0 (printed 0.0168 tau^power - ... - tau^(power + 5))
    vanishing = Polynomial.fromroots([0.1, 0.3, 0.7, 0.8]) * Polynomial(
        [0] * power + [1, -1])
    assert _monomial(fit.polynomials[4]) == pytest.approx(vanishing.coef, abs=1e-12)
    assert vanishing.coef[power:] == pytest.approx(
        [0.0168, -0.2858, 1.4590, -3.0900, 2.9000, -1], abs=5e-5)
    assert fit.coefficients[4] == 0.0
    # half a unit of the last printed digit
    digits = [5e-5] * 4 if power < 3 else [0.05, 0.05, 0.05, 5]
    for a, book, tol in zip(fit.coefficients[:4], coefficients, digits, strict=True):
        assert a == pytest.approx(book, abs=tol)
    # the law of degree 3 ("the most appropriate degree") goes through all six points
    fields = {"kind": "least_squares_polynomial", "points": POINTS42, "degree": 3}
    fields.update({"start": start} if start else {"through_ends": True})
    law = _law(fields)
    assert law.report["max_residual"] < 1e-12
    assert [law.report[f"a_{j}"] for j in range(4)] == pytest.approx(fit.coefficients[:4],
                                                                       rel=1e-12)
    for order in range(1, power):
        assert abs(float(law.derivative(0.0, order))) < 1e-9


def test_least_squares_of_full_degree_is_the_interpolating_polynomial() -> None:
    lsq = _law({"kind": "least_squares_polynomial", "points": POINTS42, "degree": 5})
    poly = _law({"kind": "interpolating_polynomial", "points": POINTS42})
    held = _law({"kind": "least_squares_polynomial", "points": POINTS42, "degree": 3,
                 "start": {"velocity": 0}})
    hermite = _law({"kind": "interpolating_polynomial", "points": POINTS42,
                    "start": {"velocity": 0}})
    grid = np.linspace(0, 1, 401)
    for order in range(4):
        assert lsq.derivative(grid, order) == pytest.approx(poly.derivative(grid, order),
                                                            rel=1e-9, abs=1e-9)
        assert held.derivative(grid, order) == pytest.approx(
            hermite.derivative(grid, order), rel=1e-9, abs=1e-8)


def test_weighted_rest_to_rest_fit_is_the_constrained_least_squares() -> None:
    t = np.linspace(0, 2, 9)
    q = np.array([0.0, 0.05, 0.3, 0.55, 0.9, 1.3, 1.62, 1.9, 2.0])
    w = np.array([1, 2, 1, 0.5, 1, 3, 1, 1, 1.0])
    law = _law({"kind": "least_squares_polynomial", "times": t.tolist(),
                "positions": q.tolist(), "degree": 3, "weights": w.tolist(),
                "start": {"velocity": 0}, "end": {"velocity": 0}})
    tau = t / 2
    # independent: q = q_0 + (q_n - q_0)(3 tau^2 - 2 tau^3) + tau^2 (1 - tau)^2 sum c_j tau^j
    held = q[0] + (q[-1] - q[0]) * (3 * tau ** 2 - 2 * tau ** 3)
    basis = (tau ** 2 * (1 - tau) ** 2)[:, None] * np.vander(tau, 4, increasing=True)
    root = np.sqrt(w)
    c = np.linalg.lstsq(basis * root[:, None], (q - held) * root, rcond=None)[0]
    grid = np.linspace(0, 1, 301)
    expected = (q[0] + (q[-1] - q[0]) * (3 * grid ** 2 - 2 * grid ** 3)
                + grid ** 2 * (1 - grid) ** 2 * Polynomial(c)(grid))
    assert _curve(law, 2 * grid) == pytest.approx(expected, abs=1e-12)
    assert law.rest_to_rest and law.position(1.0) == pytest.approx(1.0)


# ------------------------------------------------------------- sec. 4.3 (Example 4.6)
def test_example_4_6_coefficients() -> None:
    law = _law({"kind": "trigonometric_polynomial", "times": T46, "positions": Q46})
    book = {"a_0": 2.53, "a_1": -0.21, "a_2": -0.73, "a_3": 0.30, "a_4": 0.11,
            "b_1": -1.08, "b_2": -1.03, "b_3": -1.47, "b_4": -0.96}
    for name, value in book.items():  # printed with two decimals, mostly truncated
        assert law.report[name] == pytest.approx(value, abs=0.01), name
    assert law.report["degree"] == 4
    assert law.periodic and not law.rest_to_rest and law.end_position == 0.0


def test_example_4_6_is_the_books_lagrange_form() -> None:
    law = _law({"kind": "trigonometric_polynomial", "times": T46, "positions": Q46})
    t = np.array(T46[:-1], dtype=float)  # (4.6) over the 2m + 1 distinct points
    period = 20.0
    grid = np.linspace(0, 20, 1001)
    expected = np.zeros_like(grid)
    for k in range(len(t)):
        others = np.delete(t, k)
        expected += Q46[k] * np.prod(np.sin(np.pi / period * (grid[:, None] - others))
                                     / np.sin(np.pi / period * (t[k] - others)), axis=1)
    assert _curve(law, grid) == pytest.approx(expected, abs=1e-11)


def test_samples_of_a_trigonometric_sum_give_the_sum_back() -> None:
    period = 0.8

    def f(t: np.ndarray, order: int = 0) -> np.ndarray:
        w = 2 * np.pi / period
        terms = [(0.4, w, 0.3), (-0.15, 2 * w, 1.1), (0.05, 3 * w, -0.2)]
        out = sum(a * (k ** order) * np.sin(k * t + p + order * np.pi / 2)
                  for a, k, p in terms)
        return out + (1.0 if order == 0 else 0.0)

    t = np.array([0, 0.07, 0.2, 0.31, 0.4, 0.47, 0.6, 0.8])  # 7 distinct: degree 3
    law = _law({"kind": "trigonometric_polynomial", "times": t.tolist(),
                "positions": f(t).tolist()})
    grid = np.linspace(0, period, 401)
    for order in range(5):
        expected = f(grid, order)
        assert _curve(law, grid, order) == pytest.approx(
            expected, abs=1e-9 * np.max(np.abs(expected)))
    assert law.continuity >= 4 and law.wraps(1) and law.wraps(2) and law.wraps(3)
    # the same curve as the project's closed-form piece (constant plus sines)
    for order in range(5):
        assert law.curve(grid, order) == pytest.approx(
            law.curve.piece.evaluate(grid, order), abs=1e-12 * np.max(np.abs(f(grid, order))))


# ------------------------------------------- coefficients against independent evaluation
def _peak(function, count: int = 20_001) -> float:
    from scipy.optimize import minimize_scalar

    grid = np.linspace(0, 1, count)
    values = np.abs(function(grid))
    i = int(np.argmax(values))
    low, high = grid[max(i - 1, 0)], grid[min(i + 1, count - 1)]
    refined = minimize_scalar(lambda s: -abs(float(function(np.array([s]))[0])),
                              bounds=(low, high), method="bounded",
                              options={"xatol": 1e-13})
    return max(float(values[i]), -float(refined.fun))


def _rms(function) -> float:
    from scipy.integrate import quad

    return math.sqrt(quad(lambda s: float(function(np.array([s]))[0]) ** 2, 0, 1,
                          limit=400, epsabs=1e-14, epsrel=1e-13)[0])


def _independent_interpolant():
    from scipy.interpolate import KroghInterpolator

    t = [0.0, 0.3, 0.7, 1.0]
    q = [0.0, 0.2, 0.8, 1.0]
    law = _law({"kind": "interpolating_polynomial", "points": [list(p) for p in zip(
        t, q, strict=True)], "start": {"velocity": 0}, "end": {"velocity": 0}})
    krogh = KroghInterpolator([0, 0, 0.3, 0.7, 1, 1], [0, 0, 0.2, 0.8, 1, 0])
    return law, lambda s, k: krogh.derivative(s, k)


def _independent_least_squares():
    tau = np.array(T42) / 10
    q = np.array(Q42)
    law = _law({"kind": "least_squares_polynomial", "points": POINTS42, "degree": 2,
                "start": {"velocity": 0}, "end": {"velocity": 0}})
    held = Polynomial([2, 0, 21, -14])  # 2 + 7 (3 tau^2 - 2 tau^3)
    base = Polynomial([0, 0, 1, -2, 1])  # tau^2 (1 - tau)^2
    basis = np.array([(base * Polynomial.basis(j))(tau) for j in range(3)]).T
    c = np.linalg.lstsq(basis, q - held(tau), rcond=None)[0]
    curve = (held + base * Polynomial(c) - 2) / 7
    return law, lambda s, k: curve.deriv(k)(s)


def _independent_trigonometric():
    t = np.array(T46, dtype=float)
    law = _law({"kind": "trigonometric_polynomial", "times": T46, "positions": Q46})
    w = 2 * np.pi / 20
    m = np.column_stack([np.ones(9)] + [f(k * w * t[:-1]) for k in range(1, 5)
                                        for f in (np.cos, np.sin)])
    c = np.linalg.solve(m, np.array(Q46[:-1], dtype=float))

    def q(s: np.ndarray, k: int) -> np.ndarray:
        x = 20 * np.asarray(s)
        out = np.full_like(x, c[0] if k == 0 else 0.0)
        for j in range(1, 5):
            scale = (j * w) ** k
            out = out + scale * (c[2 * j - 1] * np.cos(j * w * x + k * np.pi / 2)
                                 + c[2 * j] * np.sin(j * w * x + k * np.pi / 2))
        return out * 20 ** k

    excursion = _peak(lambda s: q(s, 0) - q(np.zeros(1), 0))
    return law, lambda s, k: (q(s, k) - (q(np.zeros(1), 0) if k == 0 else 0)) / excursion


@pytest.mark.parametrize("make", [_independent_interpolant, _independent_least_squares,
                                  _independent_trigonometric],
                         ids=["interpolating", "least_squares", "trigonometric"])
def test_coefficients_against_independent_evaluation(make) -> None:
    law, q = make()
    c = law.coefficients
    assert c.C_v == pytest.approx(_peak(lambda s: q(s, 1)), rel=1e-9)
    assert c.C_a == pytest.approx(_peak(lambda s: q(s, 2)), rel=1e-9)
    assert c.C_j == pytest.approx(_peak(lambda s: q(s, 3)), rel=1e-9)
    assert c.C_v_rms == pytest.approx(_rms(lambda s: q(s, 1)), rel=1e-9)
    assert c.C_a_rms == pytest.approx(_rms(lambda s: q(s, 2)), rel=1e-9)


# ------------------------------------------------------------------ errors
@pytest.mark.parametrize(("law", "fragments"), [
    ("{kind: interpolating_polynomial, points: [[0, 0]]}", ("points", "at least 2")),
    ("{kind: interpolating_polynomial, points: [[0, 0], [0.5, 1], [0.5, 2]]}",
     ("points[2]", "times must increase")),
    ("{kind: interpolating_polynomial, times: [" + ", ".join(map(str, range(22)))
     + "], positions: [" + ", ".join(map(str, range(22))) + "]}",
     ("positions", "degree 21", "limit is 20")),
    ("{kind: interpolating_polynomial, points: [[0, 0], [1, 1]], start: {position: 0}}",
     ("start.position",)),
    ("{kind: interpolating_polynomial, points: [[0, 0], [1.0e-9, 0], [2.0e-9, 0], "
     "[0.5, 1], [1, 1]]}", ("points", "ill-conditioned")),
    ("{kind: least_squares_polynomial, points: [[0, 0], [1, 1]]}", ("degree", "required")),
    ("{kind: least_squares_polynomial, points: [[0, 2], [1, 3], [3, 5], [7, 6], [8, 8], "
     "[10, 9]], degree: 4, through_ends: true}", ("degree", "at most 3")),
    ("{kind: least_squares_polynomial, points: [[0, 2], [1, 3]], degree: 0, "
     "start: {velocity: 0}}", ("points", "inner point")),
    ("{kind: least_squares_polynomial, points: [[0, 2], [1, 3], [3, 5]], degree: 3}",
     ("degree", "at most 2")),
    ("{kind: least_squares_polynomial, points: [[0, 2], [1, 3], [3, 5]], degree: 0, "
     "start: {velocity: 1}}", ("start.velocity", "null")),
    ("{kind: least_squares_polynomial, points: [[0, 2], [1, 3], [2, 4], [3, 5]], "
     "degree: 1, end: {acceleration: 0}}", ("end.acceleration", "null velocity")),
    ("{kind: least_squares_polynomial, points: [[0, 2], [1, 3], [3, 5]], degree: 1, "
     "weights: [1, 0, 1]}", ("weights[1]", "positive")),
    ("{kind: least_squares_polynomial, points: [[0, 2], [1, 3], [3, 5]], degree: 1, "
     "weights: [1, 1]}", ("weights", "3 numbers")),
    ("{kind: trigonometric_polynomial, points: [[0, 0], [1, 1], [2, 0], [3, 0], [4, 0]]}",
     ("points", "even number")),
    ("{kind: trigonometric_polynomial, points: [[0, 0], [1, 1], [2, 0], [3, 1]]}",
     ("points[3]", "periodic")),
    ("{kind: trigonometric_polynomial, points: [[0, 0], [1, 1], [2, 0], [3, 0]], "
     "degree: 1}", ("degree", "has no field")),
    ("{kind: least_squares_polynomial, degree: 2, points: ["
     + ", ".join(f"[{i}, {i}]" for i in range(251)) + "]}", ("points", "MAX_VIA_POINTS")),
])
def test_mistakes_are_one_located_message(law: str, fragments: tuple[str, ...]) -> None:
    assert_user_error(run_cli("laws", "--law", law), *fragments)


# ------------------------------------------------------------------ end to end
def _design(**changes: object) -> dict:
    design = {"task": {"displacement": "60 mm", "duration": "0.4 s", "dwell": "0.2 s"},
              "load": {"mass": "6 kg", "friction": "15 N"},
              "transmission": {"type": "ball_screw", "lead": "10 mm", "diameter": "16 mm",
                               "length": "300 mm", "efficiency": 0.9},
              "laws": ["poly5"], "motors": ["yaskawa-sgm7j"]}
    design.update(changes)
    return design


def test_sizer_size_with_the_polynomial_laws(tmp_path: Path) -> None:
    rest = {"velocity": 0, "acceleration": 0}
    laws = ["poly5",
            {"kind": "interpolating_polynomial", "points": [[0, 0], [1, 1]],
             "start": rest, "end": rest, "name": "through2"},
            {"kind": "interpolating_polynomial",
             "points": [[0, 0], [0.3, 0.2], [0.7, 0.8], [1, 1]],
             "start": {"velocity": 0}, "end": {"velocity": 0}},
            {"kind": "least_squares_polynomial", "points": POINTS42, "degree": 3,
             "start": {"velocity": 0}, "end": {"velocity": 0},
             "units": {"time": "s", "position": "mm"}}]
    design = tmp_path / "chapter4.yaml"
    design.write_text(yaml.safe_dump(_design(laws=laws), sort_keys=False))
    result = run_cli("size", str(design), "--all", "--format", "json")
    assert result.returncode == 0, result.stderr
    records = json.loads(result.stdout)
    rows = records["results"] if isinstance(records, dict) else records
    text = json.dumps(rows)
    for kind in ("interpolating_polynomial", "least_squares_polynomial"):
        assert kind in text
    # the polynomial through two points at rest (v = a = 0) is poly5: same sizing
    by_motor: dict[str, dict[str, dict]] = {}
    for r in size(_design(laws=laws)).to_records():
        name = "through2" if "through2" in r["spec"] else r["law"]
        by_motor.setdefault(r["motor"], {})[name] = r
    assert by_motor
    for found in by_motor.values():
        a, b = found["polynomial"], found["through2"]
        for key in ("peak_torque", "rms_torque", "max_speed"):
            assert b[key] == pytest.approx(a[key], rel=1e-9), key
            assert a[key] > 0


def test_sizer_size_with_a_trigonometric_cam(tmp_path: Path) -> None:
    design = {"task": {"displacement": "20 deg", "duration": "2 s", "dwell": "0 s"},
              "load": {"inertia": "0.06 kg*m^2", "friction": "0.4 N*m"},
              "transmission": {"type": "belt", "ratio": 4, "efficiency": "95 %"},
              "laws": [{"kind": "trigonometric_polynomial", "times": T46,
                        "positions": Q46}],
              "motors": ["mitsubishi-hg-kn"]}
    path = tmp_path / "cam.yaml"
    path.write_text(yaml.safe_dump(design, sort_keys=False))
    result = run_cli("size", str(path), "--all", "--format", "json")
    assert result.returncode == 0, result.stderr
    assert "trigonometric_polynomial" in result.stdout


def test_a_design_error_points_at_the_line_of_the_field(tmp_path: Path) -> None:
    text = yaml.safe_dump(_design(laws=["poly5"]), sort_keys=False).replace(
        "laws:\n- poly5\n", "laws:\n- kind: least_squares_polynomial\n  points: [[0, 0], "
        "[0.5, 0.4], [1, 1]]\n  degree: 1\n  start:\n    velocity: 0.5\n")
    design = tmp_path / "bad.yaml"
    design.write_text(text)
    line = text.splitlines().index("    velocity: 0.5") + 1
    assert_user_error(run_cli("size", str(design)), f"bad.yaml:{line}: laws[0].start.velocity",
                      "null end conditions")


def test_an_oscillating_polynomial_is_a_warning_at_its_line(tmp_path: Path) -> None:
    """A step through 17 equidistant points (8 at 0, 0.5, 8 at 1) held at rest: the degree
    18 polynomial swings far beyond the points (Runge, Fig. 4.5); the design loader warns
    at the law's line, and a cubic spline through the same points does not."""
    points = [[i / 16, 0.0 if i < 8 else (0.5 if i == 8 else 1.0)] for i in range(17)]
    rest = {"velocity": 0}
    law = {"kind": "interpolating_polynomial", "points": points, "start": rest, "end": rest}
    design = tmp_path / "runge.yaml"
    design.write_text(yaml.safe_dump(_design(laws=[law]), sort_keys=False))
    result = run_cli("size", str(design), "--format", "json")
    assert result.returncode == 0
    assert f"warning: {design}:" in result.stderr and "Runge" in result.stderr
    spline = {"kind": "cubic_spline", "points": points}
    design.write_text(yaml.safe_dump(_design(laws=[spline]), sort_keys=False))
    assert "Runge" not in run_cli("size", str(design), "--format", "json").stderr
