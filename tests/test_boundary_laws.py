"""Motion laws between non-null boundary speeds, and asymmetric rest-to-rest laws (issue 12).

References: the book's own equations (sec. 2.1.4-2.1.6, 3.2.7 eqs. 3.13, 3.4 eqs. 3.17-3.30)
written out here in real units, its printed examples (3.6, 3.9, 3.10, 2.6/2.9), exact
sympy integration of the constant-jerk profiles, and the registry's rest-to-rest laws.
"""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from sizer.errors import UserError
from sizer.io.schema.law_schema import check_law_spec
from sizer.laws import make_law
from sizer.laws.boundary_speeds import (
    BoundaryBasis,
    boundary_form,
    has_boundary_form,
    meets_accelerations,
)

ROOT = Path(__file__).resolve().parents[1]


def _one_sided(form: BoundaryBasis, s0: float, s1: float, order: int):
    """(left, right) limits of the order-th derivative at every interior break, and the
    values at u = 0 and u = 1, straight from the piece coefficients."""
    c = form.combine(s0, s1, order)[0]  # (P, k)
    widths = np.diff(form.breaks)
    ends = np.array([np.polyval(c[p, ::-1], widths[p]) for p in range(form.pieces)])
    return ends[:-1], c[1:, 0], c[0, 0], ends[-1]


# ------------------------------------------------ boundary conditions and continuity

@st.composite
def forms(draw):
    kind = draw(st.sampled_from(["trapezoidal", "double_s", "poly", "constant_acceleration"]))
    if kind == "constant_acceleration":
        return "constant_acceleration", 1
    if kind == "poly":
        degree = draw(st.sampled_from([3, 5, 7]))
        return f"polynomial(degree={degree})", (degree - 1) // 2
    alpha = draw(st.floats(1e-3, 0.999))
    alpha_d = draw(st.floats(1e-3, 1.0)) * (1.0 - alpha)
    alpha_d = max(alpha_d, 1e-6)
    if kind == "trapezoidal":
        return f"trapezoidal(alpha={alpha!r}, alpha_d={alpha_d!r})", 1
    beta, beta_d = draw(st.floats(1e-3, 0.5)), draw(st.floats(1e-3, 0.5))
    return (f"double_s(alpha={alpha!r}, beta={beta!r}, alpha_d={alpha_d!r}, "
            f"beta_d={beta_d!r})"), 2


@settings(max_examples=150, deadline=None)
@given(forms(), st.floats(-20.0, 20.0), st.floats(-20.0, 20.0))
def test_boundary_speeds_displacement_and_continuity(case, s0, s1):
    spec, continuity = case
    form = boundary_form(spec)
    assert form.continuity == continuity
    assert form.breaks[0] == 0.0 and form.breaks[-1] == 1.0
    assert np.all(np.diff(form.breaks) > 0.0)
    scale = 1.0 + abs(s0) + abs(s1)
    targets = {0: (0.0, 1.0), 1: (s0, s1)}
    for order in range(continuity + 1):
        left, right, start, end = _one_sided(form, s0, s1, order)
        size = scale * max(1.0, np.abs(form.combine(s0, s1, order)).max())
        # continuous at every break up to the family's class
        assert np.allclose(left, right, rtol=0.0, atol=1e-12 * size), (order, left - right)
        want = targets.get(order, (0.0, 0.0))  # orders 2..m vanish at the ends
        assert start == pytest.approx(want[0], abs=1e-12 * size)
        assert end == pytest.approx(want[1], abs=1e-12 * size)


def test_combine_is_one_linear_combination_per_move():
    form = boundary_form("double_s(alpha=0.3, beta=0.2, alpha_d=0.45, beta_d=0.4)")
    s0, s1 = np.array([0.0, 1.5, -2.0]), np.array([0.0, 0.25, 3.0])
    combined = form.combine(s0, s1)
    assert combined.shape == (3, form.pieces, form.degree + 1)
    for i in range(3):
        want = form.coefficients[0] + s0[i] * form.coefficients[1] + s1[i] * form.coefficients[2]
        assert np.array_equal(combined[i], want)
    u = np.linspace(0.0, 1.0, 11)
    values = form.derivative(u, 1, s0, s1)
    assert values.shape == (3, 11)
    assert values[:, 0] == pytest.approx(s0, abs=1e-13)
    assert values[:, -1] == pytest.approx(s1, abs=1e-13)
    assert form.coefficients.flags.writeable is False


# ------------------------------------------------------------- trapezoid (sec. 3.2.7)

def _book_trapezoid(t, q0, q1, v0, v1, T, Ta, Td, v_v):
    """Eqs. (3.13a-c), t0 = 0: position, velocity, acceleration."""
    t = np.asarray(t, dtype=float)
    acc, dec, cruise = t < Ta, t >= T - Td, (t >= Ta) & (t < T - Td)
    q = np.select([acc, cruise, dec], [
        q0 + v0 * t + (v_v - v0) / (2 * Ta) * t**2,
        q0 + v0 * Ta / 2 + v_v * (t - Ta / 2),
        q1 - v1 * (T - t) - (v_v - v1) / (2 * Td) * (T - t) ** 2])
    qd = np.select([acc, cruise, dec], [v0 + (v_v - v0) / Ta * t, v_v + 0 * t,
                                        v1 + (v_v - v1) / Td * (T - t)])
    qdd = np.select([acc, cruise, dec], [(v_v - v0) / Ta + 0 * t, 0 * t,
                                         -(v_v - v1) / Td + 0 * t])
    return q, qd, qdd


def _form_in_units(spec, t, q0, h, v0, v1, T):
    form = boundary_form(spec)
    s0, s1 = v0 * T / h, v1 * T / h
    u = np.asarray(t) / T
    return [q0 * (k == 0) + h / T**k * form.derivative(u, k, s0, s1)[0] for k in range(3)]


def _compare_with_book_trapezoid(q0, q1, v0, v1, T, Ta, Td, v_v, rel=1e-12):
    h = q1 - q0
    spec = f"trapezoidal(alpha={Ta / T!r}, alpha_d={Td / T!r})"
    t = np.linspace(0.0, T, 2001)
    t = t[np.min(np.abs(t[:, None] - np.array([Ta, T - Td])[None, :]), axis=1) > 1e-9 * T]
    got, want = _form_in_units(spec, t, q0, h, v0, v1, T), _book_trapezoid(
        t, q0, q1, v0, v1, T, Ta, Td, v_v)
    for k in range(3):
        scale = max(1.0, np.abs(want[k]).max())
        assert np.abs(got[k] - want[k]).max() <= rel * scale, k


def test_example_3_6_trapezoid_with_the_cruise():
    q0, q1, v0, v1, T, a_max = 0.0, 30.0, 5.0, 2.0, 5.0, 10.0
    h = q1 - q0
    assert a_max >= (2 * h - T * (v0 + v1) + math.sqrt(
        4 * h * h - 4 * h * (v0 + v1) * T + 2 * (v0**2 + v1**2) * T**2)) / T**2  # (3.15)
    v_v = 0.5 * (v0 + v1 + a_max * T - math.sqrt(
        a_max**2 * T**2 - 4 * a_max * h + 2 * a_max * (v0 + v1) * T - (v0 - v1) ** 2))
    Ta, Td = (v_v - v0) / a_max, (v_v - v1) / a_max
    assert (Ta, Td) == pytest.approx((0.119, 0.419), abs=5e-4)  # printed
    # the form's cruise speed comes from the displacement alone: it must be the book's v_v,
    # and its accelerations +-a_max
    _compare_with_book_trapezoid(q0, q1, v0, v1, T, Ta, Td, v_v)
    _, qd, qdd = _form_in_units(f"trapezoidal(alpha={Ta / T!r}, alpha_d={Td / T!r})",
                                np.array([Ta / 2, T / 2, T - Td / 2]), q0, h, v0, v1, T)
    assert qd[1] == pytest.approx(v_v, rel=1e-12)
    assert qdd == pytest.approx([a_max, 0.0, -a_max], rel=1e-12, abs=1e-12)


def test_example_3_6_trapezoid_at_the_limit_acceleration():
    q0, q1, v0, v1, T = 0.0, 30.0, 5.0, 2.0, 5.0
    h = q1 - q0
    a_lim = (2 * h - T * (v0 + v1) + math.sqrt(
        4 * h * h - 4 * h * (v0 + v1) * T + 2 * (v0**2 + v1**2) * T**2)) / T**2  # (3.15)
    assert a_lim == pytest.approx(2.1662, abs=5e-5)  # printed; a_max = 1 is below it
    v_v = 0.5 * (v0 + v1 + a_lim * T)  # the square root vanishes at a_lim
    Ta, Td = (v_v - v0) / a_lim, (v_v - v1) / a_lim
    assert (Ta, Td) == pytest.approx((1.8075, 3.1925), abs=5e-5)  # printed
    assert Ta + Td == pytest.approx(T, rel=1e-14)  # no cruise; alpha_d = 0.6385 > 1/2
    form = boundary_form(f"trapezoidal(alpha={Ta / T!r}, alpha_d={Td / T!r})")
    assert form.pieces == 2
    _compare_with_book_trapezoid(q0, q1, v0, v1, T, Ta, Td, v_v, rel=1e-11)


@settings(max_examples=60, deadline=None)
@given(st.floats(0.01, 0.98), st.floats(0.01, 1.0), st.floats(-50.0, 50.0),
       st.floats(-50.0, 50.0), st.floats(0.1, 10.0), st.sampled_from([-7.0, 3.0, 40.0]))
def test_trapezoid_against_eqs_3_13(alpha, fraction, v0, v1, T, h):
    alpha_d = max(fraction * (1.0 - alpha), 0.005)
    Ta, Td = alpha * T, alpha_d * T
    v_v = (h - (v0 * Ta + v1 * Td) / 2) / (T - Ta / 2 - Td / 2)  # the displacement
    _compare_with_book_trapezoid(0.0, h, v0, v1, T, Ta, Td, v_v, rel=1e-11)


# ---------------------------------------------------------------- double S (sec. 3.4)

def _book_double_s(t, q0, q1, v0, v1, Ta, Tv, Td, Tj1, Tj2):
    """Eqs. (3.30a-g), t0 = 0, with a_lim_a, a_lim_d and v_lim from the phase durations
    (sec. 3.4: a_lim_a = j Tj1, v_lim = v0 + (Ta - Tj1) a_lim_a), jerks a_lim/Tj."""
    T = Ta + Tv + Td
    h = q1 - q0
    # v_lim from the displacement: each phase covers (v_lim + v_k) T_phase / 2 (3.30c, e)
    v_lim = (h - v0 * Ta / 2 - v1 * Td / 2) / (Ta / 2 + Tv + Td / 2)
    a_a = (v_lim - v0) / (Ta - Tj1)
    a_d = -(v_lim - v1) / (Td - Tj2)
    j_a, j_d = a_a / Tj1, -a_d / Tj2
    t = np.asarray(t, dtype=float)
    x = t - T + Td
    rest = np.ones(t.shape, dtype=bool)  # the last piece takes the rest (T rounds)
    pieces = [
        (t < Tj1, q0 + v0 * t + j_a * t**3 / 6, v0 + j_a * t**2 / 2, j_a * t),
        (t < Ta - Tj1, q0 + v0 * t + a_a / 6 * (3 * t**2 - 3 * Tj1 * t + Tj1**2),
         v0 + a_a * (t - Tj1 / 2), a_a + 0 * t),
        (t < Ta, q0 + (v_lim + v0) * Ta / 2 - v_lim * (Ta - t) + j_a * (Ta - t) ** 3 / 6,
         v_lim - j_a * (Ta - t) ** 2 / 2, j_a * (Ta - t)),
        (t < Ta + Tv, q0 + (v_lim + v0) * Ta / 2 + v_lim * (t - Ta), v_lim + 0 * t, 0 * t),
        (t < T - Td + Tj2, q1 - (v_lim + v1) * Td / 2 + v_lim * x - j_d * x**3 / 6,
         v_lim - j_d * x**2 / 2, -j_d * x),
        (t < T - Tj2, q1 - (v_lim + v1) * Td / 2 + v_lim * x
         + a_d / 6 * (3 * x**2 - 3 * Tj2 * x + Tj2**2), v_lim + a_d * (x - Tj2 / 2), a_d + 0 * t),
        (rest, q1 - v1 * (T - t) - j_d * (T - t) ** 3 / 6, v1 + j_d * (T - t) ** 2 / 2,
         -j_d * (T - t)),
    ]
    conditions = [p[0] for p in pieces]
    return [np.select(conditions, [p[k] for p in pieces]) for k in (1, 2, 3)], v_lim, a_a, a_d


def _check_double_s_example(q0, q1, v0, v1, Ta, Tv, Td, Tj1, Tj2, v_lim, a_lim, j_max):
    T = Ta + Tv + Td
    h = q1 - q0
    spec = f"double_s(alpha={Ta / T!r}, beta={Tj1 / Ta!r}, alpha_d={Td / T!r}, beta_d={Tj2 / Td!r})"
    form = boundary_form(spec)
    s0, s1 = v0 * T / h, v1 * T / h
    # v_lim and a_lim come back from the phase durations alone (the form knows no limits)
    u = np.array([Tj1 / 2, Ta / 2, Ta, T - Td / 2, T - Tj2 / 2]) / T
    v = h / T * form.derivative(u, 1, s0, s1)[0]
    a = h / T**2 * form.derivative(u, 2, s0, s1)[0]
    j = h / T**3 * form.derivative(u, 3, s0, s1)[0]
    assert v[2] == pytest.approx(v_lim, rel=1e-12)
    assert a[1] == pytest.approx(a_lim, rel=1e-12) and a[3] == pytest.approx(-a_lim, rel=1e-12)
    assert j[[0, 4]] == pytest.approx([j_max, j_max], rel=1e-12)
    # and the whole profile is eqs. (3.30a-g)
    breaks = np.array([Tj1, Ta - Tj1, Ta, Ta + Tv, T - Td + Tj2, T - Tj2])
    t = np.linspace(0.0, T, 3001)
    t = t[np.min(np.abs(t[:, None] - breaks[None, :]), axis=1) > 1e-9]
    want, *_ = _book_double_s(t, q0, q1, v0, v1, Ta, Tv, Td, Tj1, Tj2)
    for k in range(3):
        got = (q0 if k == 0 else 0.0) + h / T**k * form.derivative(t / T, k, s0, s1)[0]
        assert np.abs(got - want[k]).max() <= 1e-11 * max(1.0, np.abs(want[k]).max()), k


def test_example_3_9_double_s_with_a_cruise():
    q0, q1, v0, v1, v_max, a_max, j_max = 0.0, 10.0, 1.0, 0.0, 5.0, 10.0, 30.0
    # (3.19), (3.20): a_max is reached in both phases; (3.22), (3.24), (3.25)
    assert (v_max - v0) * j_max >= a_max**2 and (v_max - v1) * j_max >= a_max**2
    Tj1 = Tj2 = a_max / j_max
    Ta = Tj1 + (v_max - v0) / a_max
    Td = Tj2 + (v_max - v1) / a_max
    Tv = (q1 - q0) / v_max - Ta / 2 * (1 + v0 / v_max) - Td / 2 * (1 + v1 / v_max)
    assert (Ta, Tv, Td, Tj1, Tj2) == pytest.approx((0.7333, 1.1433, 0.8333, 0.3333, 0.3333),
                                                   abs=5e-5)  # printed
    _check_double_s_example(q0, q1, v0, v1, Ta, Tv, Td, Tj1, Tj2, v_max, a_max, j_max)


def test_example_3_10_double_s_without_a_cruise():
    q0, q1, v0, v1, a_max, j_max = 0.0, 10.0, 1.0, 0.0, 10.0, 30.0
    h = q1 - q0
    Tj = a_max / j_max  # (3.26a)
    delta = a_max**4 / j_max**2 + 2 * (v0**2 + v1**2) + a_max * (
        4 * h - 2 * a_max / j_max * (v0 + v1))  # (3.27)
    Ta = (a_max**2 / j_max - 2 * v0 + math.sqrt(delta)) / (2 * a_max)  # (3.26b)
    Td = (a_max**2 / j_max - 2 * v1 + math.sqrt(delta)) / (2 * a_max)  # (3.26c)
    v_lim = v0 + (Ta - Tj) * a_max
    assert (Ta, Td, Tj) == pytest.approx((1.0747, 1.1747, 0.3333), abs=5e-5)  # printed
    assert v_lim == pytest.approx(8.4136, abs=5e-5)  # printed
    assert Ta > 2 * Tj and Td > 2 * Tj  # (3.26) applies
    _check_double_s_example(q0, q1, v0, v1, Ta, 0.0, Td, Tj, Tj, v_lim, a_max, j_max)


@settings(max_examples=40, deadline=None)
@given(st.floats(0.02, 0.9), st.floats(0.02, 1.0), st.floats(0.01, 0.5), st.floats(0.01, 0.5),
       st.floats(-30.0, 30.0), st.floats(-30.0, 30.0), st.floats(-5.0, 12.0))
def test_double_s_against_eqs_3_30(alpha, fraction, beta, beta_d, v0, v1, h):
    if abs(h) < 0.1:
        h = 0.1
    T = 2.0
    alpha_d = max(fraction * (1.0 - alpha), 0.02)
    Ta, Td = alpha * T, alpha_d * T
    Tv = max(T - Ta - Td, 0.0)
    spec = f"double_s(alpha={alpha!r}, beta={beta!r}, alpha_d={alpha_d!r}, beta_d={beta_d!r})"
    form = boundary_form(spec)
    Tj1, Tj2 = beta * Ta, beta_d * Td
    breaks = np.array([Tj1, Ta - Tj1, Ta, Ta + Tv, T - Td + Tj2, T - Tj2])
    t = np.linspace(0.0, T, 1001)
    t = t[np.min(np.abs(t[:, None] - breaks[None, :]), axis=1) > 1e-9]
    want, *_ = _book_double_s(t, 0.0, h, v0, v1, Ta, Tv, Td, Tj1, Tj2)
    s0, s1 = v0 * T / h, v1 * T / h
    for k in range(3):
        got = h / T**k * form.derivative(t / T, k, s0, s1)[0]
        assert np.abs(got - want[k]).max() <= 1e-10 * max(1.0, np.abs(want[k]).max()), k


# --------------------------------------------------------- polynomials (sec. 2.1.4-6)

def _book_polynomial(degree, h, T, v0, v1):
    """Coefficients a_0..a_n of eqs. (2.2), (2.5) and sec. 2.1.6 with q0 = 0 and null
    boundary accelerations and jerks."""
    if degree == 3:
        return [0.0, v0, (3 * h - (2 * v0 + v1) * T) / T**2, (-2 * h + (v0 + v1) * T) / T**3]
    if degree == 5:
        return [0.0, v0, 0.0, (20 * h - (8 * v1 + 12 * v0) * T) / (2 * T**3),
                (-30 * h + (14 * v1 + 16 * v0) * T) / (2 * T**4),
                (12 * h - 6 * (v1 + v0) * T) / (2 * T**5)]
    return [0.0, v0, 0.0, 0.0, (210 * h - T * (120 * v0 + 90 * v1)) / (6 * T**4),
            (-168 * h + T * (90 * v0 + 78 * v1)) / (2 * T**5),
            (420 * h - T * (216 * v0 + 204 * v1)) / (6 * T**6),
            (-120 * h + T * (60 * v0 + 60 * v1)) / (6 * T**7)]


@pytest.mark.parametrize("degree", [3, 5, 7])
@pytest.mark.parametrize(("v0", "v1"), [(-5.0, -10.0), (0.0, 0.0), (3.0, 1.25)])
def test_polynomial_against_the_book_coefficients(degree, v0, v1):
    h, T = 10.0, 8.0  # Examples 2.6, 2.9, 2.11: q0 = 0, q1 = 10, t1 = 8 (v0 = -5, v1 = -10)
    book = np.polynomial.Polynomial(_book_polynomial(degree, h, T, v0, v1))
    form = boundary_form(f"poly{degree}")
    assert form.pieces == 1 and form.degree == degree
    t = np.linspace(0.0, T, 801)
    for k in range(4):
        got = h / T**k * form.derivative(t / T, k, v0 * T / h, v1 * T / h)[0]
        want = book.deriv(k)(t) if k else book(t)
        assert np.abs(got - want).max() <= 1e-12 * max(1.0, np.abs(want).max()), k
    # and the coefficients themselves, in powers of u = t/T
    scaled = np.array(_book_polynomial(degree, 1.0, 1.0, v0 * T / h, v1 * T / h))
    assert form.combine(v0 * T / h, v1 * T / h)[0, 0] == pytest.approx(scaled, abs=1e-12)


# ------------------------------------- boundary accelerations (sec. 2.1.5-2.1.6)

def _book_polynomial_with_accelerations(degree, h, T, v0, v1, a0, a1):
    """Eq. (2.5) (degree 5) and sec. 2.1.6 with j0 = j1 = 0 (degree 7), q0 = 0: the
    coefficients a_0..a_n with the boundary accelerations a0, a1 given."""
    if degree == 5:
        return [0.0, v0, a0 / 2,
                (20 * h - (8 * v1 + 12 * v0) * T - (3 * a0 - a1) * T**2) / (2 * T**3),
                (-30 * h + (14 * v1 + 16 * v0) * T + (3 * a0 - 2 * a1) * T**2) / (2 * T**4),
                (12 * h - 6 * (v1 + v0) * T + (a1 - a0) * T**2) / (2 * T**5)]
    return [0.0, v0, a0 / 2, 0.0,
            (210 * h - T * (120 * v0 + 90 * v1) - T**2 * (30 * a0 - 15 * a1)) / (6 * T**4),
            (-168 * h + T * (90 * v0 + 78 * v1) + T**2 * (20 * a0 - 14 * a1)) / (2 * T**5),
            (420 * h - T * (216 * v0 + 204 * v1) - T**2 * (45 * a0 - 39 * a1)) / (6 * T**6),
            (-120 * h + T * (60 * v0 + 60 * v1) + T**2 * (12 * a0 - 12 * a1)) / (6 * T**7)]


@pytest.mark.parametrize("degree", [5, 7])
@pytest.mark.parametrize(("v0", "v1", "a0", "a1"), [
    (0.0, 0.0, 2.0, -3.0), (-5.0, -10.0, 1.5, 4.0), (3.0, 1.25, -0.75, 0.0),
    (0.0, 0.0, 0.0, 0.0),
])
def test_polynomial_with_boundary_accelerations_against_the_book(degree, v0, v1, a0, a1):
    h, T = 10.0, 8.0  # the book's q0 = 0, q1 = 10, t1 = 8, in rad, s
    book = np.polynomial.Polynomial(
        _book_polynomial_with_accelerations(degree, h, T, v0, v1, a0, a1))
    form = boundary_form(f"poly{degree}")
    assert form.meets_accelerations
    s0, s1, r0, r1 = v0 * T / h, v1 * T / h, a0 * T**2 / h, a1 * T**2 / h
    t = np.linspace(0.0, T, 801)
    for k in range(4):
        got = h / T**k * form.derivative(t / T, k, s0, s1, r0=r0, r1=r1)[0]
        want = book.deriv(k)(t) if k else book(t)
        assert np.abs(got - want).max() <= 1e-12 * max(1.0, np.abs(want).max()), k
    scaled = np.array(_book_polynomial_with_accelerations(degree, 1.0, 1.0, s0, s1, r0, r1))
    assert form.combine(s0, s1, r0=np.array([r0]), r1=np.array([r1]))[0, 0] == pytest.approx(
        scaled, abs=1e-12 * max(1.0, np.abs(scaled).max()))


@settings(max_examples=100, deadline=None)
@given(st.sampled_from([5, 7]), st.floats(-20.0, 20.0), st.floats(-20.0, 20.0),
       st.floats(-200.0, 200.0), st.floats(-200.0, 200.0))
def test_boundary_accelerations_are_met(degree, s0, s1, r0, r1):
    form = boundary_form(f"polynomial(degree={degree})")
    scale = 1.0 + abs(s0) + abs(s1) + abs(r0) + abs(r1)
    targets = [(0.0, 1.0), (s0, s1), (r0, r1)] + [(0.0, 0.0)] * (degree == 7)
    for order, (start, end) in enumerate(targets):
        got = form.derivative([0.0, 1.0], order, s0, s1, r0=r0, r1=r1)[0]
        # the k-th derivative sums coefficients up to ~10^k times the basis' own: its
        # rounding grows with it (poly7, r1 = 1e-14: a jerk of 1.3e-12 at tau = 1)
        tolerance = 1e-12 * scale * 10.0**order
        assert got[0] == pytest.approx(start, abs=tolerance), order
        assert got[1] == pytest.approx(end, abs=tolerance), order


def test_accelerations_are_two_more_basis_functions():
    form = boundary_form("poly7")
    s0, s1 = np.array([0.0, 1.5, -2.0]), np.array([0.0, 0.25, 3.0])
    r0, r1 = np.array([0.0, -4.0, 7.0]), np.array([0.0, 2.0, 0.5])
    combined = form.combine(s0, s1, 2, r0=r0, r1=r1)
    plain = form.combine(s0, s1, 2)
    extra = form.acceleration_basis(2)
    assert extra.shape == (2, 1, 6) and form.acceleration_coefficients.flags.writeable is False
    for i in range(3):
        assert np.array_equal(combined[i], plain[i] + r0[i] * extra[0] + r1[i] * extra[1])
    # no accelerations given: the speeds' form exactly, as every caller had it
    assert np.array_equal(form.combine(s0, s1, r0=np.zeros(3), r1=None), form.combine(s0, s1))
    assert np.array_equal(combined[0], form.combine(0.0, 0.0, 2)[0])


@pytest.mark.parametrize("spec", ["trapezoidal(alpha=1/3)", "constant_acceleration",
                                  "double_s", "poly3", "trapezoidal(alpha=0.2, alpha_d=0.7)"])
def test_the_other_forms_cannot_meet_accelerations(spec):
    form = boundary_form(spec)
    assert not form.meets_accelerations and form.acceleration_coefficients is None
    # zeros are no accelerations: accepted, and the form unchanged
    assert np.array_equal(form.combine(1.0, -2.0, 1, r0=np.zeros(1), r1=np.zeros(1)),
                          form.combine(1.0, -2.0, 1))
    with pytest.raises(ValueError, match="cannot start or end at a non-zero acceleration"):
        form.combine(1.0, -2.0, r0=np.array([0.5]))
    with pytest.raises(ValueError, match="polynomials of degree 5 and 7 can"):
        form.derivative(0.5, 2, r1=-1.0)
    with pytest.raises(ValueError, match="cannot start or end"):
        form.acceleration_basis(0)


def test_which_laws_meet_accelerations():
    for spec in ("poly5", "poly7", "polynomial(degree=5)", "polynomial(7)"):
        assert meets_accelerations(spec), spec
    for spec in ("poly3", "trapezoidal", "double_s", "constant_acceleration", "cycloidal",
                 "polynomial(9)", "modified_sinusoidal"):
        assert not meets_accelerations(spec), spec


def test_only_the_families_with_a_boundary_speed_form_have_one():
    for spec in ("trapezoidal", "trapezoidal(alpha=1/5, alpha_d=0.7)", "double_s",
                 "constant_acceleration", "triangular", "poly3", "poly5", "poly7",
                 "polynomial(degree=5)"):
        assert has_boundary_form(spec), spec
    for spec in ("cycloidal", "harmonic", "elliptic", "modified_trapezoidal",
                 "modified_sinusoidal", "modified_cycloidal", "gutman_1_3",
                 "freudenstein_1_3", "freudenstein_1_3_5", "exponential", "polynomial(9)"):
        assert boundary_form(spec) is None, spec
    assert boundary_form(make_law("double_s")) is boundary_form("double_s(1/3, 1/4)")
    assert boundary_form("poly5") is boundary_form("polynomial(5)")
    assert boundary_form("triangular").spec == "constant_acceleration"


@pytest.mark.parametrize(("spec", "needle"), [
    ("trapezoidal(alpha=0.7)", "alpha + alpha_d = 1.4 is more than 1"),
    ("trapezoidal(alpha=0.6, alpha_d=0.5)", "alpha + alpha_d = 1.1 is more than 1"),
    ("double_s(alpha=0.8, alpha_d=0.3)", "alpha + alpha_d"),
    ("double_s(alpha=1/3, beta=0.6)", "beta [1e-06, 1/2]"),
    ("double_s(alpha_d=1/3, beta_d=0)", "beta_d [1e-06, 1/2]"),
    ("trapezoidal(alpha=0)", "alpha [1e-06"),
    ("trapezoidal(alpha=1/4, alpha_d=1)", "alpha_d [1e-06"),
    ("trapezoidal(beta=1/3)", "unknown parameter(s) beta"),
    ("trapezoidal(alpha=auto)", "not 'auto'"),
    ("polynomial(4)", "odd integer in [3, 21]"),
    ("cycloid", "unknown law"),
])
def test_bad_boundary_specs_are_user_errors(spec, needle):
    with pytest.raises(UserError) as error:
        boundary_form(spec)
    assert needle in str(error.value)


def test_a_share_sum_a_rounding_above_one_has_no_cruise():
    alpha = 0.3615
    form = boundary_form(f"trapezoidal(alpha={alpha!r}, alpha_d={(1 - alpha) + 2e-16!r})")
    assert form.pieces == 2 and form.breaks[1] == alpha


# ------------------------------------------------ rest to rest: the registry's laws

@pytest.mark.parametrize("spec", [
    "trapezoidal", "trapezoidal(alpha=1/5)", "trapezoidal(alpha=1/2)",
    "trapezoidal(alpha=1/4, alpha_d=1/3)", "trapezoidal(alpha=0.01, alpha_d=1/2)",
    "constant_acceleration", "triangular", "double_s", "double_s(alpha=1/2, beta=1/2)",
    "double_s(alpha=0.21, beta=0.37)", "double_s(alpha=1/4, beta=1/5, alpha_d=0.4, beta_d=1/2)",
    "double_s(alpha=1/3, beta=1/4, beta_d=0.1)", "poly3", "poly5", "poly7",
])
def test_at_rest_the_form_is_the_registry_law(spec):
    law, form = make_law(spec), boundary_form(spec)
    assert form.spec == law.spec
    assert form.continuity == law.continuity
    assert form.jerk_bounded == law.coefficients.jerk_bounded
    u = np.unique(np.concatenate([np.linspace(0.0, 1.0, 4001), law.breakpoints]))
    for k in range(3):
        got = form.derivative(u, k)[0]
        want = law.derivative(u, k)
        # at a break where the acceleration steps both sides take the right piece
        assert np.abs(got - want).max() <= 1e-12 * max(1.0, np.abs(want).max()), k


def test_the_symmetric_laws_keep_their_specs_and_parameters():
    assert make_law("trapezoidal(alpha=1/4, alpha_d=1/4)") is make_law("trapezoidal(alpha=1/4)")
    assert make_law("trapezoidal(alpha=1/4)").params == {"alpha": 0.25}
    assert make_law("double_s(beta_d=1/4, alpha_d=1/3)") is make_law("double_s")
    law = make_law("double_s(alpha=1/3, beta=1/4, beta_d=1/5)")
    assert law.spec == "double_s(alpha=1/3, beta=1/4, beta_d=1/5)"
    assert make_law(law.spec) is law
    assert make_law("trapezoidal(1/4, 1/3)").spec == "trapezoidal(alpha=1/4, alpha_d=1/3)"
    with pytest.raises(ValueError, match="alpha_d=auto is not supported"):
        check_law_spec("trapezoidal(alpha=1/4, alpha_d=auto)")
    with pytest.raises(UserError, match=r"alpha_d \[1e-06, 1/2\]"):
        make_law("trapezoidal(alpha=1/4, alpha_d=0.6)")


# ------------------------------------- asymmetric rest-to-rest coefficients (sympy)

_t = sp.symbols("t", real=True)


def _sympy_profile(phases):
    """Exact velocity and acceleration pieces of a rest-to-rest constant-jerk profile.

    ``phases`` is a list of (duration, jerk) with the jerks in terms of the cruise speed
    symbol V; V is then solved from q(1) = 1, and v(1) = 0 is checked."""
    V = sp.Symbol("V", positive=True)
    pieces, q, v, a = [], sp.Integer(0), sp.Integer(0), sp.Integer(0)
    for duration, jerk in phases:
        jerk = sp.sympify(jerk).subs("V", V)
        acc = a + jerk * _t
        vel = v + a * _t + jerk * _t**2 / 2
        pieces.append((duration, vel, acc, jerk))
        q = q + v * duration + a * duration**2 / 2 + jerk * duration**3 / 6
        v, a = vel.subs(_t, duration), acc.subs(_t, duration)
    value = sp.solve(sp.Eq(q, 1), V)[0]
    assert sp.simplify(v.subs(V, value)) == 0 and sp.simplify(a.subs(V, value)) == 0
    return [(d, vel.subs(V, value), acc.subs(V, value), sp.sympify(j).subs(V, value))
            for d, vel, acc, j in pieces]


def _sympy_coefficients(pieces):
    c_v = max(max(abs(vel.subs(_t, 0)), abs(vel.subs(_t, d))) for d, vel, _, _ in pieces)
    c_a = max(max(abs(acc.subs(_t, 0)), abs(acc.subs(_t, d))) for d, _, acc, _ in pieces)
    c_j = max(abs(j) for *_, j in pieces)
    v2 = sum(sp.integrate(vel**2, (_t, 0, d)) for d, vel, _, _ in pieces)
    a2 = sum(sp.integrate(acc**2, (_t, 0, d)) for d, _, acc, _ in pieces)
    return {"C_v": float(c_v), "C_a": float(c_a), "C_j": float(c_j),
            "C_v_rms": math.sqrt(float(v2)), "C_a_rms": math.sqrt(float(a2))}


@pytest.mark.parametrize(("a", "d"), [("1/4", "1/3"), ("1/2", "1/10"), ("1/50", "1/2")])
def test_asymmetric_trapezoid_coefficients(a, d):
    law = make_law(f"trapezoidal(alpha={a}, alpha_d={d})")
    a, d = sp.Rational(a), sp.Rational(d)
    V = sp.Symbol("V")
    # steps of acceleration: a jerk impulse is not a constant jerk, so the acceleration
    # phases are written out (V/a over a, 0, -V/d over d)
    pieces, q, v = [], sp.Integer(0), sp.Integer(0)
    for duration, acc in ((a, V / a), (1 - a - d, sp.Integer(0)), (d, -V / d)):
        pieces.append((duration, v + acc * _t, acc + 0 * _t, 0))
        q, v = q + v * duration + acc * duration**2 / 2, v + acc * duration
    value = sp.solve(sp.Eq(q, 1), V)[0]
    assert sp.simplify(v.subs(V, value)) == 0
    pieces = [(du, vel.subs(V, value), acc.subs(V, value), 0) for du, vel, acc, _ in pieces]
    want = _sympy_coefficients(pieces)
    # the closed form of the brief: the acceleration phase's C_a
    assert float(pieces[0][2]) == pytest.approx(float(2 / (a * (2 - a - d))), rel=1e-15)
    for name in ("C_v", "C_a", "C_v_rms", "C_a_rms"):
        assert getattr(law.coefficients, name) == pytest.approx(want[name], rel=1e-12), name
        assert getattr(law.numerical_coefficients, name) == pytest.approx(want[name], rel=1e-9)
    assert law.coefficients.C_j == 0.0 and not law.coefficients.jerk_bounded


@pytest.mark.parametrize(("a", "b", "d", "e"), [
    ("1/4", "1/3", "1/3", "1/4"), ("1/2", "1/2", "1/5", "1/10"), ("1/10", "1/20", "1/2", "1/2"),
    ("1/3", "1/4", "1/3", "1/5"),
])
def test_asymmetric_double_s_coefficients(a, b, d, e):
    law = make_law(f"double_s(alpha={a}, beta={b}, alpha_d={d}, beta_d={e})")
    a, b, d, e = (sp.Rational(x) for x in (a, b, d, e))
    V = sp.Symbol("V")
    ja = V / (a * b * (a - a * b))  # reaches V: a_lim (T_a - T_j) = V, a_lim = j T_j
    jd = V / (d * e * (d - d * e))
    pieces = _sympy_profile([(a * b, ja), (a - 2 * a * b, 0), (a * b, -ja), (1 - a - d, 0),
                             (d * e, -jd), (d - 2 * d * e, 0), (d * e, jd)])
    pieces = [p for p in pieces if p[0] > 0]
    want = _sympy_coefficients(pieces)
    for name in ("C_v", "C_a", "C_j", "C_v_rms", "C_a_rms"):
        assert getattr(law.coefficients, name) == pytest.approx(want[name], rel=1e-12), name
        assert getattr(law.numerical_coefficients, name) == pytest.approx(want[name], rel=1e-9)
    assert law.coefficients.jerk_bounded and law.continuity == 2


def test_the_module_imports_no_scipy():
    code = ("import sys, sizer.laws.boundary_speeds as b; b.boundary_form('double_s'); "
            "print(any(m == 'scipy' or m.startswith('scipy.') for m in sys.modules))")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            cwd=ROOT, timeout=120, check=True)
    assert result.stdout.strip() == "False"
