"""Interpolating cubic splines (book sec. 4.4.1 to 4.4.4): the book's Examples 4.7 to 4.9,
every condition of each spline, the book's systems against scipy and against an
independent B-spline collocation, and the bad inputs of ``kind: cubic_spline``."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.interpolate import BSpline, PPoly

from sizer.errors import UserError
from sizer.laws.multipoint import cubic_splines as cs

T_BOOK = np.array([0.0, 5.0, 7.0, 8.0, 10.0, 15.0, 18.0])
Q_BOOK = np.array([3.0, -2.0, -5.0, 0.0, 6.0, 12.0, 8.0])
Q_PERIODIC = np.array([3.0, -2.0, -5.0, 0.0, 6.0, 12.0, 3.0])


def agrees(value: float, text: str) -> bool:
    """``value`` agrees with the printed ``text`` to its printed digits: within one unit
    of the last printed digit (the book rounds some figures and truncates others, e.g.
    0.6687 printed 0.66 and 0.7139 printed 0.71)."""
    decimals = len(text.split(".")[1]) if "." in text else 0
    return abs(value - float(text)) < 10.0 ** -decimals * (1 + 1e-9)


def assert_printed(values, texts: str) -> None:
    values = np.ravel(values)
    texts = texts.split()
    assert len(values) == len(texts)
    bad = [(v, p) for v, p in zip(values, texts, strict=True) if not agrees(v, p)]
    assert not bad, bad


def one_sided(pp: PPoly, nu: int) -> tuple[np.ndarray, np.ndarray]:
    """The nu-th derivative at the interior breakpoints from the left and the right
    piece, each evaluated from its own polynomial."""
    d = pp.derivative(nu) if nu else pp
    h = np.diff(pp.x)
    left = np.array([np.polyval(d.c[:, k], h[k]) for k in range(len(h) - 1)])
    right = d.c[-1, 1:]
    return left, right


def assert_c2(pp: PPoly) -> None:
    for nu in range(3):
        left, right = one_sided(pp, nu)
        np.testing.assert_allclose(left, right, rtol=0, atol=1e-9)


def coefficient_rows(pp: PPoly) -> np.ndarray:
    """Rows [a_k0, a_k1, a_k2, a_k3] of a cubic PPoly."""
    return pp.c[::-1].T


# ---------------------------------------------------------------- Example 4.7 (sec. 4.4.1)

def test_example_4_7_matrix_and_known_terms():
    A, c = cs.clamped_system(T_BOOK, Q_BOOK, 2.0, -3.0)
    np.testing.assert_array_equal(A, [[14, 5, 0, 0, 0], [1, 6, 2, 0, 0], [0, 2, 6, 1, 0],
                                      [0, 0, 5, 14, 2], [0, 0, 0, 3, 16]])
    np.testing.assert_allclose(c, [-32.5, 25.5, 39, 52.2, 5.8], rtol=0, atol=1e-12)


def test_example_4_7_velocities_and_coefficients():
    v = cs.clamped_velocities(T_BOOK, Q_BOOK, 2.0, -3.0)
    # printed v = [-3.43, 3.10, 5.10, 1.88, 0.008]; v_3 = 5.1504 (erratum): the book's
    # own spline prints 5.15 (t - 8) for the same velocity
    assert_printed(v[[1, 2, 4, 5]], "-3.43 3.10 1.88 0.008")
    assert agrees(v[3], "5.15") and not agrees(v[3], "5.10")
    pp = cs.clamped_spline(T_BOOK, Q_BOOK, 2.0, -3.0)
    assert_printed(coefficient_rows(pp), """3 2 -0.71 0.02
        -2 -3.4 -0.37 0.66    -5 3.1 3.64 -1.74    0 5.15 -1.59 0.25
        6 1.88 -0.03 -0.02    12 0.008 -0.34 -0.03""")
    # the book's construction (4.10), (4.8) is scipy's clamped CubicSpline
    np.testing.assert_allclose(cs.coefficients_from_velocities(T_BOOK, Q_BOOK, v),
                               coefficient_rows(pp), rtol=0, atol=1e-12)


def test_clamped_spline_meets_every_condition():
    pp = cs.clamped_spline(T_BOOK, Q_BOOK, 2.0, -3.0)
    np.testing.assert_allclose(pp(T_BOOK), Q_BOOK, rtol=0, atol=1e-9)
    np.testing.assert_allclose(pp(T_BOOK[[0, -1]], 1), [2.0, -3.0], rtol=0, atol=1e-9)
    assert_c2(pp)
    assert np.all(pp(np.linspace(0, 18, 7), 4) == 0.0)


def test_acceleration_method_gives_the_same_spline():
    """Sec. 4.4.3: (4.22)-(4.24) and (4.25) give the spline of sec. 4.4.1."""
    A, c = cs.acceleration_system(T_BOOK, Q_BOOK, 2.0, -3.0)
    np.testing.assert_array_equal(A, A.T)
    omega = np.linalg.solve(A, c)
    rows = cs.coefficients_from_accelerations(T_BOOK, Q_BOOK, omega)
    np.testing.assert_allclose(rows, coefficient_rows(cs.clamped_spline(
        T_BOOK, Q_BOOK, 2.0, -3.0)), rtol=0, atol=1e-12)


def test_natural_spline_has_zero_end_accelerations():
    pp = cs.natural_spline(T_BOOK, Q_BOOK)
    np.testing.assert_allclose(pp(T_BOOK), Q_BOOK, rtol=0, atol=1e-9)
    np.testing.assert_allclose(pp(T_BOOK[[0, -1]], 2), 0.0, rtol=0, atol=1e-9)
    assert_c2(pp)


def test_two_points_give_the_cubic_hermite_piece():
    pp = cs.clamped_spline([0.0, 2.0], [1.0, 3.0], 0.5, -1.0)
    # a0 = 1, a1 = 0.5, a2 = (3*2/2 - 1 + 1)/2 = 1.5, a3 = (-2*2/2 + 0.5 - 1)/4 = -0.625
    np.testing.assert_allclose(coefficient_rows(pp), [[1.0, 0.5, 1.5, -0.625]], atol=1e-12)


# ---------------------------------------------------------------- Example 4.8 (sec. 4.4.2)

def test_example_4_8_periodic_system():
    A, c = cs.periodic_system(T_BOOK, Q_PERIODIC)
    # printed last row [3 0 0 0 3 16]: its first entry is T_{n-2} = 5, the coefficient of
    # v_n = v_0 in (4.9) for k = n-2 (erratum; the velocities printed need it)
    np.testing.assert_array_equal(A, [[16, 3, 0, 0, 0, 5], [2, 14, 5, 0, 0, 0],
                                      [0, 1, 6, 2, 0, 0], [0, 0, 2, 6, 1, 0],
                                      [0, 0, 0, 5, 14, 2], [5, 0, 0, 0, 3, 16]])
    # printed c_1 = -28: 3/(5*2) (25*(-3) + 4*(-5)) = -28.5 (erratum)
    np.testing.assert_allclose(c, [-54, -28.5, 25.5, 39, 52.2, -34.2], rtol=0, atol=1e-12)


def test_example_4_8_velocities_and_coefficients():
    v = cs.periodic_velocities(T_BOOK, Q_PERIODIC)
    assert_printed(v[:6], "-2.28 -2.78 2.99 5.14 2.15 -1.8281")
    assert agrees(v[0], "-2.2823") and v[6] == v[0]
    pp = cs.periodic_spline(T_BOOK, Q_PERIODIC)
    rows = coefficient_rows(pp)
    np.testing.assert_allclose(cs.coefficients_from_velocities(T_BOOK, Q_PERIODIC, v), rows,
                               rtol=0, atol=1e-12)
    # the footnote's omega_0 = 2 a_02 = 1.72 is twice the truncated 0.86: 2 a_02 = 1.7382
    assert agrees(2 * rows[0, 2], "1.74") and not agrees(2 * rows[0, 2], "1.72")
    # two printed coefficients are off (errata): a_43 = -0.083 (printed -0.008) and
    # a_51 = v_5 = -1.8281 (printed +1.82; the printed v has -1.8281)
    assert agrees(rows[4, 3], "-0.08") and agrees(rows[5, 1], "-1.82")
    rows = rows.copy()
    rows[4, 3], rows[5, 1] = -0.008, 1.82
    assert_printed(rows, """3 -2.28 0.86 -0.12   -2 -2.78 -0.96 0.80   -5 2.99 3.85 -1.85
        0 5.14 -1.71 0.32   6 2.15 0.22 -0.008   12 1.82 -1.02 0.21""")


def test_periodic_spline_is_c2_across_the_period():
    pp = cs.periodic_spline(T_BOOK, Q_PERIODIC)
    np.testing.assert_allclose(pp(T_BOOK), Q_PERIODIC, rtol=0, atol=1e-9)
    assert_c2(pp)
    for nu in range(3):
        start, end = pp(T_BOOK[[0, -1]], nu)
        assert abs(start - end) < 1e-9


# ---------------------------------------------------------------- Example 4.9 (sec. 4.4.4)

def collocation_spline(t_bar, q, v0, vn, a0, an) -> PPoly:
    """Independent construction: the C2 cubic B-spline on the knots t_bar through the
    given points (all knots but the two free ones) with v and a at both ends."""
    t_bar = np.asarray(t_bar, dtype=float)
    knots = np.concatenate([[t_bar[0]] * 3, t_bar, [t_bar[-1]] * 3])
    count = len(knots) - 4
    basis = [BSpline(knots, np.eye(count)[i], 3) for i in range(count)]
    given = np.concatenate([[t_bar[0]], t_bar[2:-2], [t_bar[-1]]])
    rows = [[b(x) for b in basis] for x in given]
    rows += [[b(x, nu) for b in basis] for x, nu in
             ((t_bar[0], 1), (t_bar[0], 2), (t_bar[-1], 1), (t_bar[-1], 2))]
    rhs = np.concatenate([q, [v0, a0, vn, an]])
    coefficients = np.linalg.solve(np.array(rows), rhs)
    return PPoly.from_spline(BSpline(knots, coefficients, 3))


def test_example_4_9_against_the_collocation():
    pp = cs.velocity_acceleration_spline(T_BOOK, Q_BOOK, 2.0, -3.0, 0.0, 0.0)
    np.testing.assert_allclose(pp.x, [0, 2.5, 5, 7, 8, 10, 15, 16.5, 18])
    other = collocation_spline(pp.x, Q_BOOK, 2.0, -3.0, 0.0, 0.0)
    samples = np.linspace(0.0, 18.0, 361)
    for nu in range(4):
        np.testing.assert_allclose(pp(samples, nu), other(samples, nu), rtol=0, atol=1e-9)


def test_example_4_9_extra_points_and_pieces():
    pp = cs.velocity_acceleration_spline(T_BOOK, Q_BOOK, 2.0, -3.0, 0.0, 0.0)
    t_bar = pp.x
    q_bar, omega, T = pp(t_bar), pp(t_bar, 2), np.diff(t_bar)
    assert_printed(q_bar[[1, 7]], "5.48 11.68")
    # (4.14): coefficients of (t_{k+1} - t)^3, (t - t_k)^3, (t - t_k), (t_{k+1} - t)
    pieces = np.column_stack([omega[:-1] / (6 * T), omega[1:] / (6 * T),
                              q_bar[1:] / T - T * omega[1:] / 6,
                              q_bar[:-1] / T - T * omega[:-1] / 6])
    assert_printed(pieces, """0 -0.16 3.2 1.2     -0.16 0.007 -0.84 3.2
        0.009 0.58 -4.82 -1.03    1.16 -0.51 0.51 -6.16    -0.25 -0.018 3.07 1.03
        -0.007 -0.01 2.66 1.38    -0.03 -0.24 8.33 8.07    -0.24 0 5.33 8.33""")
    # the printed 6x6 A, c and omega = [-4.50, 3.03, -1.58, 1.12, -0.28, -1.95] belong to
    # no spline of this example (erratum): the pieces printed above need these seven
    assert_printed(omega[1:-1], "-2.42 0.12 6.98 -3.09 -0.22 -0.32 -2.17")
    A, c = cs.velocity_acceleration_system(t_bar, Q_BOOK, 2.0, -3.0, 0.0, 0.0)
    # by hand from the printed formulas: A_00 = 2 T_1 + T_0 (3 + T_0/T_1) = 5 + 2.5 * 4,
    # c_0 = 6 ((q_2 - q_0)/T_1 - v_0 (1 + T_0/T_1)) = 6 (-2 - 4), ...
    np.testing.assert_allclose(A[0, :2], [15.0, 2.5], rtol=0, atol=1e-12)
    np.testing.assert_allclose(c, [-36, 15, 39, -12, -10.8, -5.2, -20], rtol=0, atol=1e-12)


def test_system_4_28_rows_are_the_printed_formulas():
    t_bar = np.array([0, 2.5, 5, 7, 8, 10, 15, 16.5, 18])
    T = np.diff(t_bar)
    q, v0, vn, a0, an = Q_BOOK, 2.0, -3.0, 0.4, -0.7
    A, c = cs.velocity_acceleration_system(t_bar, q, v0, vn, a0, an)
    n = len(T)
    assert A[0, 0] == pytest.approx(2 * T[1] + T[0] * (3 + T[0] / T[1]))
    assert A[1, 0] == pytest.approx(T[1] - T[0] ** 2 / T[1])
    assert A[-2, -1] == pytest.approx(T[n - 2] - T[n - 1] ** 2 / T[n - 2])
    assert A[-1, -1] == pytest.approx(2 * T[n - 2] + T[n - 1] * (3 + T[n - 1] / T[n - 2]))
    assert c[0] == pytest.approx(6 * ((q[1] - q[0]) / T[1] - v0 * (1 + T[0] / T[1])
                                      - a0 * (0.5 + T[0] / (3 * T[1])) * T[0]))
    assert c[1] == pytest.approx(6 * ((q[2] - q[1]) / T[2] - (q[1] - q[0]) / T[1]
                                      + v0 * T[0] / T[1] + a0 * T[0] ** 2 / (3 * T[1])))
    assert c[-2] == pytest.approx(6 * ((q[-1] - q[-2]) / T[n - 2] - (q[-2] - q[-3]) / T[n - 3]
                                       - vn * T[n - 1] / T[n - 2]
                                       + an * T[n - 1] ** 2 / (3 * T[n - 2])))
    assert c[-1] == pytest.approx(6 * ((q[-2] - q[-1]) / T[n - 2] + vn * (1 + T[n - 1] / T[n - 2])
                                       - an * (0.5 + T[n - 1] / (3 * T[n - 2])) * T[n - 1]))


@pytest.mark.parametrize("count", [2, 3, 4, 7])
def test_velocity_acceleration_spline_meets_every_condition(count):
    t, q = T_BOOK[:count].copy(), Q_BOOK[:count]
    t[-1] = T_BOOK[count - 1] if count > 2 else 5.0
    pp = cs.velocity_acceleration_spline(t, q, 1.5, -0.5, 0.3, -0.2)
    np.testing.assert_allclose(pp(t), q, rtol=0, atol=1e-9)
    np.testing.assert_allclose(pp(t[[0, -1]], 1), [1.5, -0.5], rtol=0, atol=1e-9)
    np.testing.assert_allclose(pp(t[[0, -1]], 2), [0.3, -0.2], rtol=0, atol=1e-9)
    assert_c2(pp)
    other = collocation_spline(pp.x, q, 1.5, -0.5, 0.3, -0.2)
    samples = np.linspace(t[0], t[-1], 101)
    np.testing.assert_allclose(pp(samples), other(samples), rtol=0, atol=1e-9)


# ---------------------------------------------------------------- the builder

def test_builder_reads_points_and_end_conditions():
    pp = cs.build_cubic_spline({"kind": "cubic_spline", "points": [[float(a), float(b)] for
                                a, b in zip(T_BOOK, Q_BOOK, strict=True)],
                                "start": {"velocity": 2}, "end": {"velocity": -3}})
    np.testing.assert_allclose(pp.c, cs.clamped_spline(T_BOOK, Q_BOOK, 2, -3).c, atol=1e-12)
    pp = cs.build_cubic_spline({"times": T_BOOK.tolist(), "positions": Q_BOOK.tolist()})
    np.testing.assert_allclose(pp(T_BOOK[[0, -1]], 1), 0.0, atol=1e-9)  # default v = 0


def test_builder_periodic_natural_and_accelerations():
    base = {"times": T_BOOK.tolist()}
    pp = cs.build_cubic_spline({**base, "positions": Q_PERIODIC.tolist(), "periodic": True})
    assert abs(pp(0.0, 2) - pp(18.0, 2)) < 1e-9
    pp = cs.build_cubic_spline({**base, "positions": Q_BOOK.tolist(), "natural": True})
    np.testing.assert_allclose(pp(T_BOOK[[0, -1]], 2), 0.0, atol=1e-9)
    pp = cs.build_cubic_spline({**base, "positions": Q_BOOK.tolist(),
                                "start": {"velocity": 2, "acceleration": 0},
                                "end": {"velocity": -3, "acceleration": 0},
                                "extra_times": [1.0, 17.0]})
    np.testing.assert_allclose(pp.x[[1, -2]], [1.0, 17.0])
    np.testing.assert_allclose(pp(T_BOOK[[0, -1]], 2), 0.0, atol=1e-9)


BAD = [
    ({"times": [0, 2, 1], "positions": [0, 1, 2]}, "times", "must be increasing"),
    ({"points": [[0, 0], [1, 1], [1, 2]]}, "points[2]", "times must increase"),
    ({"points": [[0, 0]]}, "points", "at least 2 points"),
    ({"times": [0], "positions": [0]}, "positions", "at least 2"),
    ({"times": [0, 1, 2], "positions": [0, 1, 2], "periodic": True}, "periodic",
     "last position equal to the first"),
    ({"times": [0, 1, 2], "positions": [0, 1, 0], "periodic": True,
      "start": {"velocity": 1}}, "start", "fixes both ends"),
    ({"times": [0, 1], "positions": [0, 1], "speed": 3}, "speed", "has no field 'speed'"),
    ({"times": [0, 1], "positions": [0, 1], "start": {"acceleration": 0}},
     "end.acceleration", "needs one at the other end"),
    ({"times": [0, 1], "positions": [0, 1], "start": {"jerk": 0}}, "start.jerk",
     "unknown condition"),
    ({"times": [0, 1], "positions": [0, 1], "periodic": "yes"}, "periodic", "true or false"),
    ({"times": [0, 1, 2], "positions": [0, 1, 2], "start": {"velocity": 0,
      "acceleration": 0}, "end": {"velocity": 0, "acceleration": 0},
      "extra_times": [1.5, 1.8]}, "extra_times", "inside the first and the last"),
    ({"times": [0, 1, 2], "positions": [0, 1, 2], "extra_times": [0.5, 1.5]},
     "extra_times", "only used with end accelerations"),
]


@pytest.mark.parametrize(("fields", "field", "text"), BAD)
def test_bad_input_names_the_field(fields, field, text):
    with pytest.raises(UserError) as caught:
        cs.build_cubic_spline(fields)
    assert caught.value.field == field
    assert text in caught.value.message
