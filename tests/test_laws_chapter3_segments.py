"""The composed laws of sec. 3.5, 3.10 and 3.11: fifteen segments, cycloidal blends.

Every coefficient is checked against an independent computation: the segments integrated
exactly by sympy from the law's definition (snap or acceleration per segment, levels
solved from q(1) = 1, v(1) = 0), scipy quad of the book's printed segment formulas, or the
book's own numbers (Example 3.20, sec. 3.10.2's c_1..c_4, sec. 3.10.3). Misprints:
docs/errata.md.
"""

from __future__ import annotations

import csv
import functools
import io
import json
import math

import numpy as np
import pytest
import sympy as sp
from cli_run import assert_user_error, run_cli

from sizer.errors import UserError
from sizer.laws import make_law
from sizer.model import Design, Load, Motor, Task
from sizer.sizing import size_design

PI = math.pi
t = sp.Symbol("t", real=True)


def exact_coefficients(segments, order):
    """C_v, C_a, C_j, C_v_rms, C_a_rms of a rest-to-rest law given as (duration, f) with
    f(u) the derivative of the given order (2: acceleration, 4: snap) in the local time u,
    levels already solved; integrated exactly by sympy, the RMS integrals numerically at
    30 digits (:func:`_square_integral`), peaks by dense sampling of the exact
    expressions."""
    state = [sp.Integer(0)] * order  # q, v, a, j below the given order
    start = sp.Integer(0)
    rows = []
    for duration, f in segments:
        if duration == 0:
            continue
        exprs = [f]
        for k in range(order - 1, -1, -1):
            exprs.insert(0, state[k] + sp.integrate(exprs[0].subs(t, sp.Symbol("s")),
                                                    (sp.Symbol("s"), 0, t)))
        derivs = {k: exprs[k] for k in range(order + 1)}
        for k in range(order + 1, 4):
            derivs[k] = sp.diff(derivs[k - 1], t)
        rows.append((start, duration, derivs))
        state = [derivs[k].subs(t, duration) for k in range(order)]
        start += duration
    assert abs(float(state[0]) - 1.0) < 1e-12 and all(abs(float(s)) < 1e-12 for s in state[1:])
    out = {}
    for name, k in (("C_v", 1), ("C_a", 2), ("C_j", 3)):
        best = 0.0
        for _, d, derivs in rows:
            f = sp.lambdify(t, derivs[k], "numpy")
            u = np.linspace(0.0, float(d), 20001)
            best = max(best, float(np.max(np.abs(f(u) + 0.0 * u))))
        out[name] = best
    for name, k in (("C_v_rms", 1), ("C_a_rms", 2)):
        out[name] = math.sqrt(sum(_square_integral(derivs[k], d) for _, d, derivs in rows))
    return out, rows


def _square_integral(expr, duration) -> float:
    """int_0^d expr^2 dt of one smooth segment's exact expression, by mpmath's tanh-sinh
    quadrature at 30 digits (sympy's symbolic integral gives the same to those digits,
    seconds slower)."""
    import mpmath

    with mpmath.workdps(30):
        f = sp.lambdify(t, expr**2, "mpmath")
        return float(mpmath.quad(f, [0, mpmath.mpf(sp.Rational(duration).p)
                                     / sp.Rational(duration).q]))


def assert_coefficients(law, expected, peak_rel=1e-7, rms_rel=1e-12):
    got = law.coefficients
    for name in ("C_v", "C_a", "C_j"):
        assert getattr(got, name) == pytest.approx(expected[name], rel=peak_rel), name
    for name in ("C_v_rms", "C_a_rms"):
        assert getattr(got, name) == pytest.approx(expected[name], rel=rms_rel), name


def assert_pointwise(law, rows, order_max=2):
    for start, d, derivs in rows:
        u = np.linspace(0.0, float(d), 7)[1:-1]
        for k in range(order_max + 1):
            f = sp.lambdify(t, derivs[k], "numpy")
            np.testing.assert_allclose(law.derivative(float(start) + u, k), f(u) + 0.0 * u,
                                       rtol=1e-10, atol=1e-10)


# ------------------------------------------------------------ sec. 3.5, fifteen segments
@functools.cache  # sympy's exact integration takes seconds; the law command test reuses it
def fifteen_segments_exact(alpha, beta, gamma):
    a, b, g = (sp.Rational(x) for x in (alpha, beta, gamma))
    ta, tj = a, a * b
    ts = tj * g
    v = 1 / (1 - a)
    acc = v / (ta - tj)
    jerk = acc / (tj - ts)
    s = jerk / ts
    half = [(ts, s), (tj - 2 * ts, 0), (ts, -s), (ta - 2 * tj, 0), (ts, -s), (tj - 2 * ts, 0),
            (ts, s), (1 - 2 * ta, 0)]
    second = [(ts, -s), (tj - 2 * ts, 0), (ts, s), (ta - 2 * tj, 0), (ts, s), (tj - 2 * ts, 0),
              (ts, -s)]
    return exact_coefficients([(d, sp.Integer(1) * x) for d, x in half + second], 4)


@pytest.mark.parametrize("params", [("1/3", "1/4", "1/4"), ("2/5", "1/3", "1/5"),
                                    ("1/2", "1/2", "1/2"), ("1/10", "1/20", "3/10")])
def test_fifteen_segments_against_exact_integration(params):
    law = make_law(f"fifteen_segments(alpha={params[0]}, beta={params[1]}, gamma={params[2]})")
    expected, rows = fifteen_segments_exact(*params)
    assert_coefficients(law, expected)
    assert_pointwise(law, rows, order_max=4)
    assert law.numerical_coefficients.as_dict() == pytest.approx(law.coefficients.as_dict(),
                                                                 rel=1e-9)


def test_fifteen_segments_continuity_and_limits():
    law = make_law("fifteen_segments")
    assert law.spec == "fifteen_segments(alpha=1/3, beta=1/4, gamma=1/4)"
    assert law.continuity == 3
    from sizer.laws.coefficients import measured_continuity

    assert measured_continuity(law) == 3
    assert law.coefficients.jerk_bounded
    # gamma -> 0 is the double S of the same alpha, beta
    near = make_law("fifteen_segments(alpha=1/3, beta=1/4, gamma=1e-3)").coefficients
    ds = make_law("double_s(alpha=1/3, beta=1/4)").coefficients
    assert near.as_dict() == pytest.approx(ds.as_dict(), rel=2e-3)
    assert near.C_j * (1 - 1e-3) == pytest.approx(ds.C_j, rel=1e-12)
    with pytest.raises(UserError, match=r"gamma \[0.001, 1/2\]"):
        make_law("fifteen_segments(gamma=0.6)")


def test_fifteen_segments_book_formulas_3_48():
    """(3.48a)-(3.48h) with v0 = 0, q0 = 0 against the law at T = 1, h = 1."""
    alpha, beta, gamma = 0.3, 0.4, 0.2
    law = make_law(f"fifteen_segments(alpha={alpha}, beta={beta}, gamma={gamma})")
    Ta, Tj = alpha, alpha * beta
    Ts = gamma * Tj
    vmax = 1 / (1 - alpha)
    amax = vmax / (Ta - Tj)
    jmax = amax / (Tj - Ts)
    smax = jmax / Ts
    x = np.linspace(0, Ts, 5)
    np.testing.assert_allclose(law.derivative(x, 2), smax / 2 * x**2, atol=1e-12)
    np.testing.assert_allclose(law.position(x), smax / 24 * x**4, atol=1e-14)
    x = np.linspace(Ts, Tj - Ts, 5)
    np.testing.assert_allclose(law.derivative(x, 2), jmax * x - jmax * Ts / 2, rtol=1e-12)
    np.testing.assert_allclose(law.velocity(x), jmax / 6 * Ts**2 + jmax / 2 * x * (x - Ts),
                               rtol=1e-12)
    np.testing.assert_allclose(
        law.position(x), jmax / 24 * (2 * x - Ts) * (2 * x * (x - Ts) + Ts**2), rtol=1e-12)
    x = np.linspace(Tj - Ts, Tj, 5)
    np.testing.assert_allclose(law.derivative(x, 2), -smax / 2 * (x - Tj) ** 2 + amax,
                               rtol=1e-12)
    np.testing.assert_allclose(
        law.velocity(x), smax / 6 * (7 * Ts**3 - 9 * Ts**2 * (x + Ts) + 3 * Ts * (x + Ts) ** 2
                                     - (x - Tj + Ts) ** 3), rtol=1e-11)
    x = np.linspace(Tj, Ta - Tj, 5)
    np.testing.assert_allclose(law.velocity(x), amax / 2 * (2 * x - Tj), rtol=1e-12)
    np.testing.assert_allclose(
        law.position(x), amax / 12 * (6 * x**2 - 6 * x * Tj + 2 * Tj**2 - Tj * Ts + Ts**2),
        rtol=1e-12)
    x = np.linspace(Ta - Ts, Ta, 5)
    np.testing.assert_allclose(law.velocity(x), smax / 6 * (x - Ta) ** 3 + amax * (Ta - Tj),
                               rtol=1e-12)
    x = np.linspace(Ta, 1 - Ta, 5)
    np.testing.assert_allclose(law.velocity(x), vmax, rtol=1e-12)
    x = np.linspace(1 - Ts, 1, 5)
    np.testing.assert_allclose(law.derivative(x, 3), smax * (1 - x), atol=1e-9)  # (3.48o)


def test_example_3_20_durations_and_the_limits_as_a_normalized_law():
    v, a, j, s, h, v0, v1 = 5.0, 10.0, 30.0, 500.0, 10.0, 1.0, 0.0
    Ts = j / s
    Tj = a / j + Ts
    Ta = Tj + (v - v0) / a
    Td = Tj + (v - v1) / a
    Tv = h / v - Ta / 2 * (1 + v0 / v) - Td / 2 * (1 + v1 / v)
    assert [round(x, 4) for x in (Ta, Tv, Td, Tj, Ts)] == [0.7933, 1.0773, 0.8933, 0.3933, 0.06]
    assert round(Ta + Tv + Td, 4) == 2.7640
    assert round(Tj + (v - v1) / a, 4) != 0.7933  # eq. (3.43) as printed: errata
    # the same limits from rest to rest: the law scaled to h, T meets each of them
    Ta = Td = Tj + v / a
    T = 2 * Ta + h / v - Ta
    law = make_law(f"fifteen_segments(alpha={Ta / T!r}, beta={Tj / Ta!r}, gamma={Ts / Tj!r})")
    c = law.coefficients
    assert (c.C_v * h / T, c.C_a * h / T**2, c.C_j * h / T**3) == pytest.approx((v, a, j),
                                                                              rel=1e-12)
    snap = np.abs(law.derivative(np.linspace(0, 1, 4001), 4)).max() * h / T**4
    assert snap == pytest.approx(s, rel=1e-9)


# ------------------------------------------------------ sec. 3.10.1 / 3.10.3, velocity
@pytest.mark.parametrize("alpha", [1 / 3, 0.1, 0.25, 0.5, 1e-3])
def test_cycloidal_blends_against_quad_of_the_plain_formula(alpha):
    from scipy.integrate import quad

    V = 1 / (1 - alpha)

    def v(x):
        x = min(x, 1 - x)
        return V / 2 * (1 - math.cos(PI * x / alpha)) if x < alpha else V

    def a(x):
        if x < alpha:
            return V / 2 * PI / alpha * math.sin(PI * x / alpha)
        if x > 1 - alpha:
            return -V / 2 * PI / alpha * math.sin(PI * (1 - x) / alpha)
        return 0.0

    law = make_law(f"cycloidal_blends(alpha={alpha!r})")
    pts = [alpha, 1 - alpha]
    c = law.coefficients
    assert c.C_v_rms**2 == pytest.approx(quad(lambda x: v(x) ** 2, 0, 1, points=pts,
                                              epsabs=1e-14, epsrel=1e-13)[0], rel=1e-11)
    assert c.C_a_rms**2 == pytest.approx(quad(lambda x: a(x) ** 2, 0, 1, points=pts,
                                              epsabs=1e-14, epsrel=1e-13)[0], rel=1e-11)
    assert quad(v, 0, 1, points=pts, epsabs=1e-14)[0] == pytest.approx(1.0, rel=1e-12)
    x = np.linspace(0, 1, 101)
    np.testing.assert_allclose(law.velocity(x), [v(y) for y in x], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(law.acceleration(x), [a(y) for y in x], rtol=1e-10, atol=1e-9)
    assert (c.C_v, c.C_a, c.C_j) == pytest.approx(
        (V, V * PI / (2 * alpha), V * PI**2 / (2 * alpha**2)), rel=1e-12)
    num = law.numerical_coefficients
    assert num.as_dict() == pytest.approx(c.as_dict(), rel=1e-9)
    assert law.continuity == 2 and c.jerk_bounded


def test_cycloidal_blends_at_one_half_is_the_cycloidal_law():
    law, cyc = make_law("cycloidal_blends(alpha=1/2)"), make_law("cycloidal")
    x = np.linspace(0, 1, 57)
    for k in range(4):
        np.testing.assert_allclose(law.derivative(x, k), cyc.derivative(x, k), atol=1e-11)
    assert law.coefficients.as_dict() == pytest.approx(cyc.coefficients.as_dict(), rel=1e-12)


def test_example_3_24_b_segments_of_eq_3_55():
    """t = [0, 1, 2, 3], v = [0, 1, 0]: h = 2 in T = 3 is cycloidal_blends(alpha=1/3)."""
    law = make_law("cycloidal_blends(alpha=1/3)")
    h, T = 2.0, 3.0

    def book(x):  # sec. 3.10.1: odd segments V_k, K_k, omega_k = pi/(t_k - t_{k-1})
        if x <= 1:
            V, K, q0, u = 0.5, 0.5, 0.0, x
        elif x <= 2:
            return 0.5 + (x - 1), 1.0, 0.0
        else:
            V, K, q0, u = -0.5, 0.5, 1.5, x - 2
        w = PI
        return (-V / w * math.sin(w * u) + K * u + q0, -V * math.cos(w * u) + K,
                V * w * math.sin(w * u))

    x = np.linspace(0, 3, 31)
    want = np.array([book(y) for y in x])
    got = [law.derivative(x / T, k) * h / T**k for k in range(3)]
    for k in range(3):
        np.testing.assert_allclose(got[k], want[:, k], atol=1e-12)


def test_minimum_time_of_sec_3_10_3():
    from sizer.laws.blended_constant import cycloidal_blends_minimum_time

    v, a = 1.0, 2.0
    for h in (2.0, 5.0, PI * v * v / (2 * a)):  # with a cruise (the last: none left)
        T, alpha = cycloidal_blends_minimum_time(h, v, a)
        assert pytest.approx((2 * h * a + PI * v * v) / (2 * a * v), rel=1e-14) == T
        assert alpha * T == pytest.approx(PI * v / (2 * a), rel=1e-14)
        c = make_law(f"cycloidal_blends(alpha={alpha!r})").coefficients
        assert (c.C_v * h / T, c.C_a * h / T**2) == pytest.approx((v, a), rel=1e-12)
    h = 0.5  # below pi v^2/(2 a): no cruise, the cycloidal law
    T, alpha = cycloidal_blends_minimum_time(h, v, a)
    assert alpha == 0.5 and pytest.approx(2 * math.sqrt(h * PI / (2 * a)), rel=1e-14) == T
    c = make_law("cycloidal").coefficients
    assert c.C_a * h / T**2 == pytest.approx(a, rel=1e-12)
    assert c.C_v * h / T == pytest.approx(math.sqrt(2 * h * a / PI), rel=1e-12)  # v_lim
    # the printed bound h >= (pi/4) v^2/a would give a cruise of negative length: errata
    v, a, h = 1.0, 1.0, 1.0
    assert h >= PI / 4 * v * v / a and h / v - PI * v / (2 * a) < 0


# ------------------------------------------------------------- sec. 3.10.2 and 3.11
@functools.cache  # as fifteen_segments_exact: read only, shared with the law command test
def seven_segments_exact(shares, kinds):
    """Exact (sympy) law of seven acceleration segments: kinds 's' quarter sine, 'c'
    linear ramp for the blends 1, 3, 5, 7; a1, a2 from q(1) = 1, v(1) = 0."""
    a1, a2 = sp.symbols("a1 a2", positive=True)
    T = [sp.nsimplify(x) for x in shares]

    def blend(kind, d, level, rising):
        if kind == "s":
            return level * (sp.sin(sp.pi * t / (2 * d)) if rising else sp.cos(sp.pi * t / (2 * d)))
        return level * (t / d if rising else 1 - t / d)

    accel = [(T[0], lambda d: blend(kinds[0], d, a1, True)), (T[1], lambda d: a1),
             (T[2], lambda d: blend(kinds[1], d, a1, False)), (T[3], lambda d: sp.Integer(0)),
             (T[4], lambda d: blend(kinds[2], d, -a2, True)), (T[5], lambda d: -a2),
             (T[6], lambda d: blend(kinds[3], d, -a2, False))]
    q = v = sp.Integer(0)
    for d, f in accel:
        if d == 0:
            continue
        acc = f(d)
        vel = v + sp.integrate(acc, (t, 0, t))
        q = q + sp.integrate(vel, (t, 0, d))
        v = vel.subs(t, d)
    sol = sp.solve([q - 1, v], [a1, a2], dict=True)[0]
    segments = [(d, f(d).subs(sol)) for d, f in accel]
    out, rows = exact_coefficients(segments, 2)
    return out, rows, float(sol[a1]), float(sol[a2])


def shares_spec(shares):
    names = ("seg1", "seg2", "seg3", "seg5", "seg6", "seg7")
    values = shares[:3] + shares[4:]
    return ", ".join(f"{n}={x}" for n, x in zip(names, values, strict=True))


SETS_3_10_2 = [
    ("1/8", "1/4", "1/8", "0", "1/8", "1/4", "1/8"),  # Example 3.25, first set
    ("1/8", "1/4", "1/4", "0", "1/8", "1/4", "0"),  # Example 3.25, second set
    ("1/10", "1/5", "1/20", "3/20", "1/5", "1/10", "1/5"),
]


def book_a2_a6(T1, T2, T3, T4, T5, T6, T7):
    """a_2 and a_6 of sec. 3.10.2 from the printed c_1..c_4."""
    c1 = 2 * T1 / PI + T2 + 2 * T3 / PI
    c2 = -2 * T5 / PI - T6 - 2 * T7 / PI
    c3 = (2 * T1 / PI * ((PI - 2) / PI * T1 + T2 / 2)
          + (2 * T1 / PI + T2) * (T2 / 2 + (PI - 2) / PI * T3)
          + c1 * (2 * T3 / PI + T4 + 2 * T5 / PI))
    c4 = (2 * T7 / PI + T6) * ((PI - 2) / PI * T5 + T6 / 2) + 2 * T7 / PI * (T6 / 2 + (PI - 2)
                                                                            / PI * T7)
    d = c1 * c4 - c2 * c3
    return -c2 / d, c1 / d


@pytest.mark.parametrize("shares", SETS_3_10_2)
def test_cycloidal_blend_acceleration_sec_3_10_2(shares):
    law = make_law(f"cycloidal_blend_acceleration({shares_spec(shares)})")
    expected, rows, a1, a2 = seven_segments_exact(shares, "ssss")
    assert_coefficients(law, expected)
    assert_pointwise(law, rows)
    book = book_a2_a6(*(float(sp.Rational(x)) for x in shares))
    assert (a1, a2) == pytest.approx(book, rel=1e-12)
    assert law.levels == pytest.approx(book, rel=1e-12)
    assert law.coefficients.C_a == pytest.approx(max(book), rel=1e-12)
    assert law.numerical_coefficients.as_dict() == pytest.approx(
        law.coefficients.as_dict(), rel=1e-9)


def test_example_3_25_sets():
    first = make_law("cycloidal_blend_acceleration")
    mt = make_law("modified_trapezoidal")
    x = np.linspace(0, 1, 81)
    for k in range(4):
        np.testing.assert_allclose(first.derivative(x, k), mt.derivative(x, k), atol=1e-10)
    assert first.continuity == 2 and first.coefficients.jerk_bounded
    second = make_law(f"cycloidal_blend_acceleration({shares_spec(SETS_3_10_2[1])})")
    assert second.continuity == 1
    (jump,) = second.coefficients.acceleration_jumps
    a6 = book_a2_a6(0.125, 0.25, 0.25, 0, 0.125, 0.25, 0)[1]
    assert jump.tau == 1.0 and jump.jump == pytest.approx(a6, rel=1e-12)


@pytest.mark.parametrize(("shares", "kinds"), [
    (("0", "1/12", "1/4", "1/6", "0", "1/3", "1/6"), "sccs"),  # Example 3.27 (a), / 6
    (("1/5", "0", "1/5", "1/5", "1/5", "1/5", "0"), "sccs"),  # 3.27 (b): T2 = T4 = T7 = 0
    (("1/8", "1/4", "1/8", "0", "1/8", "1/4", "1/8"), "cccc"),
    (("1/10", "1/5", "1/20", "3/20", "1/5", "1/10", "1/5"), "cscs"),
])
def test_cubic_blend_acceleration_sec_3_11(shares, kinds):
    flags = ", ".join(f"cubic{n}={int(k == 'c')}" for n, k in zip((1, 3, 5, 7), kinds,
                                                                    strict=True))
    law = make_law(f"cubic_blend_acceleration({shares_spec(shares)}, {flags})")
    expected, rows, _, _ = seven_segments_exact(shares, kinds)
    assert_coefficients(law, expected)
    assert_pointwise(law, rows)
    assert law.numerical_coefficients.as_dict() == pytest.approx(
        law.coefficients.as_dict(), rel=1e-9)


def test_example_3_26_special_cases():
    x = np.linspace(0, 1, 65)

    def same(spec, other):
        a, b = make_law(spec), make_law(other)
        for k in range(3):
            np.testing.assert_allclose(a.derivative(x, k), b.derivative(x, k), atol=1e-10)
        assert a.coefficients.as_dict() == pytest.approx(b.coefficients.as_dict(), rel=1e-10)
        assert a.continuity == b.continuity

    same("cubic_blend_acceleration", "double_s(alpha=1/2, beta=1/4)")  # Fig. 3.54 (a)
    same("cubic_blend_acceleration(seg1=0, seg2=1/2, seg3=0, seg5=0, seg6=1/2, seg7=0)",
         "constant_acceleration")  # parabolic
    same("cubic_blend_acceleration(seg1=1/4, seg2=0, seg3=1/4, seg5=1/4, seg6=0, seg7=1/4, "
         "cubic1=0, cubic3=0, cubic5=0, cubic7=0)", "cycloidal")
    same("cubic_blend_acceleration(cubic1=0, cubic3=0, cubic5=0, cubic7=0)",
         "modified_trapezoidal")  # Fig. 3.54 (b)


def test_seven_segment_bad_shares():
    with pytest.raises(UserError, match="add up to more than 1"):
        make_law("cycloidal_blend_acceleration(seg2=1/2, seg6=1/2)")
    with pytest.raises(UserError, match="seg3 = 0 or at least 1e-6"):
        make_law("cycloidal_blend_acceleration(seg3=1e-9)")
    with pytest.raises(UserError, match="must both be positive"):
        make_law("cubic_blend_acceleration(seg1=0, seg2=0, seg3=0)")
    assert_user_error(run_cli("laws", "--law", "cubic_blend_acceleration(seg2=0.9)"),
                      "add up to more than 1")


# ------------------------------------------------------------------ CLI and sizing
NEW_LAWS = ("fifteen_segments", "cycloidal_blends", "cycloidal_blend_acceleration",
            "cubic_blend_acceleration")


def test_laws_table_and_law_command():
    expected = {
        "fifteen_segments": fifteen_segments_exact("1/3", "1/4", "1/4")[0],
        "cycloidal_blends": {"C_v": 1.5, "C_a": 1.5 * PI * 1.5, "C_j": 1.5 * PI**2 * 4.5,
                             "C_v_rms": 1.5 * math.sqrt(1 - 5 / 12),
                             "C_a_rms": 1.5 * PI / (2 * math.sqrt(1 / 3))},
        "cycloidal_blend_acceleration": seven_segments_exact(SETS_3_10_2[0], "ssss")[0],
        "cubic_blend_acceleration": seven_segments_exact(SETS_3_10_2[0], "cccc")[0],
    }
    args = ["laws", "--format", "json"]
    for law_id in NEW_LAWS:
        args += ["--law", law_id]
    out = run_cli(*args)
    assert out.returncode == 0, out.stderr
    rows = {row["law"]: row for row in json.loads(out.stdout)}
    for law_id in NEW_LAWS:
        for name, value in expected[law_id].items():
            assert rows[law_id][name] == pytest.approx(value, rel=1e-7), (law_id, name)
    assert rows["fifteen_segments"]["continuity"] == 3
    for law_id in NEW_LAWS:
        out = run_cli("law", law_id, "--displacement", "1", "--duration", "1",
                      "--format", "csv", "--samples", "5")
        assert out.returncode == 0, out.stderr
        table = list(csv.reader(io.StringIO(out.stdout)))
        assert table[0][:3] == ["t [s]", "q [m]", "v [m/s]"] or table[0][0] == "t [s]"
        values = np.array(table[1:], dtype=float)
        assert values[0, 1] == pytest.approx(0.0, abs=1e-15)
        assert values[-1, 1] == pytest.approx(1.0, rel=1e-14)
        assert values[2, 2] == pytest.approx(expected[law_id]["C_v"], rel=1e-12)  # at T/2


def test_new_laws_size_through_the_engine():
    motor = Motor("m", inertia=1e-4, continuous_torque=8.0, peak_torque=20.0,
                  rated_speed=10.0)
    design = Design(Task(2.0, 1.5), Load(inertia=1.0, damping=0.3), laws=NEW_LAWS,
                    motors=(motor,))
    results = {r.spec.split("(")[0]: r for r in size_design(design).results}
    assert set(results) == set(NEW_LAWS)
    for law_id, r in results.items():
        c = make_law(law_id).coefficients
        assert math.isfinite(r.peak_torque) and math.isfinite(r.rms_torque)
        assert r.max_speed == pytest.approx(c.C_v * 2.0 / 1.5, rel=1e-9), law_id
        # tau = J a + B v: the RMS torque from the coefficients (cross term integrates
        # to (v^2/2) over a rest-to-rest move: zero)
        rms = math.hypot((1.0 + 1e-4) * c.C_a_rms * 2.0 / 1.5**2, 0.3 * c.C_v_rms * 2.0 / 1.5)
        assert r.rms_torque == pytest.approx(rms, rel=1e-9), law_id
