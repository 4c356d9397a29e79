"""The composed rest-to-rest laws of chapter 3: linear with polynomial blends (sec. 3.3),
the 4-3-4 piecewise polynomial (sec. 3.6), linear with circular blends (sec. 3.1).

Every reference is built here from the book's construction written plainly (sympy solves
the section's conditions; scipy quad integrates the book's formulas), not from the laws'
code; the laws' closed forms and their numerical path are both checked against it.
"""

from __future__ import annotations

import itertools
import json
import math

import numpy as np
import pytest
import sympy as sp
from cli_run import run_cli
from scipy.integrate import quad

from sizer.laws import make_law
from sizer.laws.coefficients import COEFFICIENT_NAMES, measured_continuity
from sizer.model import Design, Load, Motor, Task
from sizer.sizing import size_design

t = sp.Symbol("t", real=True)
ORDER = {"C_v": 1, "C_a": 2, "C_j": 3}


def exact_coefficients(pieces: list[tuple[sp.Expr, sp.Rational, sp.Rational]]
                       ) -> dict[str, float]:
    """C_v, C_a, C_j (at the ends and the real roots of the next derivative in each
    polynomial piece) and the RMS values (exact integrals) of a piecewise polynomial."""
    out = {}
    for name, order in ORDER.items():
        best = sp.Integer(0)
        for expr, a, b in pieces:
            f = sp.diff(expr, t, order)
            points = [a, b] + [r for r in sp.Poly(sp.diff(f, t), t).real_roots() if a < r < b] \
                if sp.diff(f, t) != 0 else [a, b]
            best = max([best, *(abs(f.subs(t, p)) for p in points)], key=lambda x: float(x))
        out[name] = float(best)
    for name, order in (("C_v_rms", 1), ("C_a_rms", 2)):
        total = sum(sp.integrate(sp.diff(expr, t, order) ** 2, (t, a, b)) for expr, a, b in pieces)
        out[name] = float(sp.sqrt(total))
    return out


def assert_coefficients(law, expected: dict[str, float], rel: float = 1e-12) -> None:
    for coefficients in (law.coefficients, law.numerical_coefficients):
        for name in COEFFICIENT_NAMES:
            assert getattr(coefficients, name) == pytest.approx(expected[name], rel=rel,
                                                                abs=1e-12), name


def assert_same_profile(law, pieces, orders=(0, 1, 2, 3)) -> None:
    """The law's derivatives equal the reference pieces (evaluated exactly, at rational
    points) inside each piece of positive length."""
    for expr, a, b in pieces:
        if a == b:
            continue
        points = [a + (b - a) * sp.Rational(k, 22) for k in range(1, 22)]
        taus = np.array([float(p) for p in points])
        for order in orders:
            f = sp.Poly(sp.diff(expr, t, order), t)
            want = np.array([float(f.eval(p)) for p in points])
            assert law.derivative(taus, order) == pytest.approx(want, rel=1e-10, abs=1e-9)


# ------------------------------------------------------------- polynomial blends, 3.3
def blend_law_pieces(alpha: sp.Rational, n: int):
    """Sec. 3.3 with h = T = 1, T_a = alpha: the line through (T_s, 0) and (1 - T_s, 1),
    T_s = T_a/2, and on each blend the polynomial of degree n meeting it at the blend
    end (position, and derivatives up to (n - 1)/2: velocity v_c, the others 0) from
    rest (derivatives up to (n - 1)/2 null), solved from the conditions."""
    m = (n - 1) // 2
    t_s = alpha / 2
    v_c = 1 / (1 - 2 * t_s)  # slope of the line q_r
    line = v_c * (t - t_s)
    q_a, q_b = line.subs(t, alpha), line.subs(t, 1 - alpha)
    c = sp.symbols(f"c0:{n + 1}")

    def blend(start, end, q_start, v_start, q_end, v_end):
        p = sum(ck * t**k for k, ck in enumerate(c))
        conditions = [p.subs(t, start) - q_start, p.subs(t, end) - q_end,
                      sp.diff(p, t).subs(t, start) - v_start, sp.diff(p, t).subs(t, end) - v_end]
        for k in range(2, m + 1):
            conditions += [sp.diff(p, t, k).subs(t, start), sp.diff(p, t, k).subs(t, end)]
        return sp.expand(p.subs(sp.solve(conditions, c)))

    return [(blend(0, alpha, 0, 0, q_a, v_c), sp.Integer(0), alpha),
            (sp.expand(line), alpha, 1 - alpha),
            (blend(1 - alpha, 1, q_b, v_c, 1, 0), 1 - alpha, sp.Integer(1))]


@pytest.mark.parametrize(("alpha", "n"), [(sp.Rational(1, 3), 5), (sp.Rational(1, 5), 5),
                                          (sp.Rational(1, 2), 5), (sp.Rational(1, 4), 7),
                                          (sp.Rational(1, 10), 9), (sp.Rational(2, 5), 3)])
def test_polynomial_blends_follow_the_books_construction(alpha, n):
    pieces = blend_law_pieces(alpha, n)
    law = make_law(f"polynomial_blends(alpha={alpha}, degree={n})")
    assert_same_profile(law, pieces)
    assert_coefficients(law, exact_coefficients(pieces))
    assert law.continuity == measured_continuity(law) == (n - 1) // 2
    assert law.coefficients.jerk_bounded == (n >= 5)


def test_the_quintic_blend_is_of_degree_four():
    """The six conditions of sec. 3.3 with n = 5 leave the fifth-degree coefficient 0:
    the blend is v_c T_a (u^3 - u^4/2), u = t/T_a."""
    alpha = sp.Symbol("alpha", positive=True)
    blend = blend_law_pieces(alpha, 5)[0][0]
    u = sp.Symbol("u")
    assert sp.simplify(blend.subs(t, u * alpha) - alpha / (1 - alpha) * (u**3 - u**4 / 2)) == 0


def test_polynomial_blends_closed_forms_for_the_quintic():
    """C_a = 3/(2 alpha (1 - alpha)) at mid-blend, C_j = 6/(alpha^2 (1 - alpha)) at the
    blend ends, C_v_rms^2 = (1 - 2 alpha + 26 alpha/35)/(1 - alpha)^2 and
    C_a_rms^2 = 12/(5 alpha (1 - alpha)^2), derived by hand from u^3 - u^4/2."""
    for alpha in (1e-6, 0.05, 1 / 3, 0.5):
        law = make_law(f"polynomial_blends(alpha={alpha!r})")
        v_c = 1 / (1 - alpha)
        assert_coefficients(law, {
            "C_v": v_c, "C_a": 1.5 * v_c / alpha, "C_j": 6 * v_c / alpha**2,
            "C_v_rms": v_c * math.sqrt(1 - 2 * alpha + 26 * alpha / 35),
            "C_a_rms": v_c * math.sqrt(12 / (5 * alpha)),
        }, rel=1e-9)


@pytest.mark.parametrize("alpha", ["1/3", "1/5", "1e-06", "1/2"])
def test_cubic_blends_are_the_trapezoid(alpha):
    law, trapezoid = make_law(f"polynomial_blends({alpha}, 3)"), make_law(f"trapezoidal({alpha})")
    taus = np.linspace(0, 1, 1001)
    for order in (0, 1, 2):
        assert law.derivative(taus, order) == pytest.approx(trapezoid.derivative(taus, order),
                                                            rel=1e-12, abs=1e-12)
    for name in COEFFICIENT_NAMES:
        assert getattr(law.coefficients, name) == pytest.approx(
            getattr(trapezoid.coefficients, name), rel=1e-9)
    assert [j.tau for j in law.coefficients.acceleration_jumps] == pytest.approx(
        [j.tau for j in trapezoid.coefficients.acceleration_jumps])


# ------------------------------------------------------------------------- 4-3-4, 3.6
def law_434_pieces(t_l, t_s, h_l, h_s):
    """The 14 conditions of sec. 3.6 written in the global tau (h = T = 1): no per-piece
    normalization, a different system from the book's seven equations."""
    t_a, t_b = t_l, 1 - t_s
    q_a, q_b = h_l, 1 - h_s
    a, b, c = sp.symbols("a0:5"), sp.symbols("b0:4"), sp.symbols("c0:5")
    lift = sum(ak * t**k for k, ak in enumerate(a))
    travel = sum(bk * t**k for k, bk in enumerate(b))
    down = sum(ck * t**k for k, ck in enumerate(c))

    def d(f, k, x):
        return sp.diff(f, t, k).subs(t, x)

    conditions = [d(lift, 0, 0), d(lift, 0, t_a) - q_a, d(travel, 0, t_a) - q_a,
                  d(travel, 0, t_b) - q_b, d(down, 0, t_b) - q_b, d(down, 0, 1) - 1,
                  d(lift, 1, 0), d(down, 1, 1), d(lift, 2, 0), d(down, 2, 1),
                  d(lift, 1, t_a) - d(travel, 1, t_a), d(lift, 2, t_a) - d(travel, 2, t_a),
                  d(travel, 1, t_b) - d(down, 1, t_b), d(travel, 2, t_b) - d(down, 2, t_b)]
    solution = sp.solve(conditions, [*a, *b, *c])
    return [(sp.expand(lift.subs(solution)), sp.Integer(0), t_a),
            (sp.expand(travel.subs(solution)), t_a, t_b),
            (sp.expand(down.subs(solution)), t_b, sp.Integer(1))]


@pytest.mark.parametrize("shares", [("1/4", "1/4", "1/10", "1/10"), ("1/10", "3/10", "1/20", "1/5"),
                                    ("1/100", "49/100", "1/2", "0"), ("2/5", "1/5", "1/3", "1/7")])
def test_434_solves_the_sections_conditions(shares):
    pieces = law_434_pieces(*(sp.Rational(s) for s in shares))
    spec = "polynomial_4_3_4(t_l={}, t_s={}, h_l={}, h_s={})".format(*shares)
    law = make_law(spec)
    assert_same_profile(law, pieces)
    assert_coefficients(law, exact_coefficients(pieces), rel=1e-10)
    assert law.continuity == measured_continuity(law) == 2
    assert law.coefficients.jerk_bounded


def test_434_defaults_and_their_exact_coefficients():
    law = make_law("polynomial_4_3_4")
    assert law.spec == "polynomial_4_3_4(t_l=1/4, t_s=1/4, h_l=1/10, h_s=1/10)"
    pieces = law_434_pieces(sp.Rational(1, 4), sp.Rational(1, 4), sp.Rational(1, 10),
                            sp.Rational(1, 10))
    # the lift-off 128/15 (tau^3 - tau^4) reaches 1/10 at tau = 1/4 with its largest
    # acceleration 128/15 * 3/4 = 32/5 (its vertex); the travel cubic peaks in speed at
    # tau = 1/2: 28/15; the jerk is largest at rest: 128/15 * 6 = 256/5
    lift, travel, _ = (expr for expr, _, _ in pieces)
    assert sp.expand(lift - sp.Rational(128, 15) * (t**3 - t**4)) == 0
    assert sp.diff(travel, t).subs(t, sp.Rational(1, 2)) == sp.Rational(28, 15)
    assert law.coefficients.C_v == pytest.approx(28 / 15, rel=1e-14)
    assert law.coefficients.C_a == pytest.approx(32 / 5, rel=1e-14)
    assert law.coefficients.C_j == pytest.approx(256 / 5, rel=1e-14)


def test_434_with_its_inner_points_on_a_line_is_the_quintic_blend_law():
    """h_l = h_s = t_l/(2 (1 - t_l)) puts the inner points on the blend law's line: the
    4-3-4 solution is then the linear trajectory with quintic blends of sec. 3.3."""
    for share in ("1/4", "1/5", "2/5"):
        t_l = float(sp.Rational(share))
        h = t_l / (2 * (1 - t_l))
        law = make_law(f"polynomial_4_3_4(t_l={share}, t_s={share}, h_l={h!r}, h_s={h!r})")
        blends = make_law(f"polynomial_blends(alpha={share}, degree=5)")
        taus = np.linspace(0, 1, 501)
        for order in range(4):
            assert law.derivative(taus, order) == pytest.approx(blends.derivative(taus, order),
                                                                rel=1e-9, abs=1e-9)


def test_appendix_a2_closed_forms_violate_the_sections_equations():
    """Errata: the expressions of Appendix A.2 (a4l printed) do not solve the seven
    equations of sec. 3.6: with every duration and displacement 1 they give
    a4l = -1/3, a3l = 5/9, where the system (and the law) have -3/2 and 5/2."""
    from sizer.laws.polynomial_434 import solve_434

    T_l = T_t = T_s = h_a = h_b = h_1 = 1
    m0 = 7 * T_s * (2 * T_l + T_t) + 3 * T_t * (3 * T_l + 2 * T_t)
    a4l_printed = (-3 * T_s * T_t * (T_s + 2 * T_t) * h_a + T_l * (
        -2 * T_t**2 * h_1 + T_s**2 * (-2 * h_a + h_b) + 3 * T_s * T_t * (-h_a + h_b))) / (T_s * m0)
    a3l_printed = (4 * T_s * T_t * (T_s + 2 * T_t) * h_a + T_l * (
        2 * T_t**2 * h_1 + T_s**2 * (4 * h_a - h_b) + T_t * (6 * T_s * h_a - 3 * T_s * h_b))
        ) / (T_s * m0)
    assert (a4l_printed, a3l_printed) == pytest.approx((-1 / 3, 5 / 9))
    assert a4l_printed + a3l_printed != pytest.approx(h_a)  # first equation of sec. 3.6
    solved = solve_434(1.0, 1.0, 1.0, 1.0, 1.0, 1.0)
    assert solved[:2] == pytest.approx([-1.5, 2.5])
    assert solved[0] + solved[1] == pytest.approx(h_a)


# ------------------------------------------------------------------ circular blends, 3.1
def book_circular(t0: float, t1: float, q0: float, q1: float):
    """Sec. 3.1 as printed: arcs of radius h centered (t0, q0 + h) and (t1, q0 [+ 0]),
    the line a0 + a1 (t - t0) tangent to both; returns q, v, a as functions of t."""
    h, T = q1 - q0, t1 - t0
    alpha = math.acos((2 * h * h + T * math.sqrt(max(0.0, T * T - 3 * h * h))) / (h * h + T * T))
    T_a = h * math.sin(alpha)
    a1, a0 = math.tan(alpha), h * (math.cos(alpha) - 1) / math.cos(alpha) + q0

    def q(x):
        if x < t0 + T_a:
            return h * (1 - math.sqrt(1 - (x - t0) ** 2 / h**2)) + q0
        if x < t1 - T_a:
            return a0 + a1 * (x - t0)
        return q0 + math.sqrt(h * h - (t1 - x) ** 2)

    def v(x):
        if x < t0 + T_a:
            return (x - t0) / math.sqrt(h * h - (x - t0) ** 2)
        if x < t1 - T_a:
            return a1
        return (t1 - x) / math.sqrt(h * h - (t1 - x) ** 2)

    def a(x):
        if x < t0 + T_a:
            return h * h / math.sqrt((h * h - (x - t0) ** 2) ** 3)
        if x < t1 - T_a:
            return 0.0
        return -h * h / math.sqrt((h * h - (t1 - x) ** 2) ** 3)

    return q, v, a, alpha, T_a, a0, a1


def test_circular_blends_reproduce_example_3_1():
    """Example 3.1 (Fig. 3.2): t0 = 2, t1 = 8, q0 = 5, q1 = 8: T/h = 2, cos(alpha) = 4/5,
    T_a = 9/5, slope 3/4, a0 = 17/4, and the book's q, v, a (in its units) at every t."""
    t0, t1, q0, q1 = 2.0, 8.0, 5.0, 8.0
    q, v, a, alpha, T_a, a0, a1 = book_circular(t0, t1, q0, q1)
    assert (math.cos(alpha), T_a, a1, a0) == pytest.approx((0.8, 1.8, 0.75, 4.25))
    # the geometric condition the book solves: tan(alpha) = (h - 2h(1 - cos))/(T - 2h sin)
    h, T = q1 - q0, t1 - t0
    assert math.tan(alpha) == pytest.approx(
        (h - 2 * h * (1 - math.cos(alpha))) / (T - 2 * h * math.sin(alpha)))
    law = make_law("circular_blends")  # ratio = 2 is the book's example
    assert law.spec == "circular_blends(ratio=2)"
    times = np.concatenate((np.linspace(t0 + 1e-9, t1 - 1e-9, 601), [t0 + T_a - 1e-9]))
    tau = (times - t0) / T
    assert q0 + h * law.position(tau) == pytest.approx([q(x) for x in times], rel=1e-12)
    assert h / T * law.velocity(tau) == pytest.approx([v(x) for x in times], rel=1e-9)
    assert h / T**2 * law.acceleration(tau) == pytest.approx([a(x) for x in times], rel=1e-9,
                                                             abs=1e-12)
    # the blends end at T_a/T = 3/10: acceleration steps of rho^2 = 4 and 4/0.8^3 there
    jumps = law.coefficients.acceleration_jumps
    assert [j.tau for j in jumps] == pytest.approx([0.0, 0.3, 0.7, 1.0])
    assert [j.jump for j in jumps] == pytest.approx([4.0, -4 / 0.512, -4 / 0.512, 4.0])
    assert law.continuity == measured_continuity(law) == 1


@pytest.mark.parametrize("ratio", [math.sqrt(3.0), 1.8, 2.0, 5.0, 40.0])
def test_circular_blends_coefficients_by_quadrature_of_the_books_formulas(ratio):
    """h = 1, T = ratio in the book's formulas; normalized by h/T^k."""
    T = ratio
    _, v, a, alpha, T_a, _, _ = book_circular(0.0, T, 0.0, 1.0)
    breaks = sorted({0.0, min(T_a, T / 2), max(T - T_a, T / 2), T})
    v2 = sum(quad(lambda x: v(x) ** 2, lo, hi, epsabs=0, epsrel=1e-13)[0]
             for lo, hi in itertools.pairwise(breaks))
    a2 = sum(quad(lambda x: a(x) ** 2, lo, hi, epsabs=0, epsrel=1e-13)[0]
             for lo, hi in itertools.pairwise(breaks))
    c, s = math.cos(alpha), math.sin(alpha)
    expected = {
        "C_v": math.tan(alpha) * T,  # the line's slope (the largest speed)
        "C_a": 1 / c**3 * T**2,  # h^2 / (h^2 - T_a^2)^(3/2) at the blend end
        "C_j": 3 * s / c**5 * T**3,  # d/dt of it: 3 h^2 t / (h^2 - t^2)^(5/2)
        "C_v_rms": math.sqrt(v2 / T) * T,
        "C_a_rms": math.sqrt(a2 / T) * T**2,
    }
    law = make_law(f"circular_blends(ratio={ratio!r})")
    assert_coefficients(law, expected, rel=1e-9)


def test_circular_blends_refuse_a_duration_below_sqrt3_h():
    from sizer.errors import UserError

    with pytest.raises(UserError, match="ratio"):
        make_law("circular_blends(ratio=1.7)")


# ------------------------------------------------------------------- CLI and sizing
NEW_SPECS = ["polynomial_blends", "polynomial_4_3_4", "circular_blends"]


def test_sizer_laws_lists_the_new_laws_with_their_coefficients():
    args = ["laws", "--format", "json"]
    for spec in NEW_SPECS:
        args += ["--law", spec]
    result = run_cli(*args)
    assert result.returncode == 0, result.stderr
    rows = {row["law"]: row for row in json.loads(result.stdout)}
    assert rows["polynomial_blends"]["C_a"] == pytest.approx(6.75, rel=1e-14)  # 3/(2 a (1-a))
    assert rows["polynomial_blends"]["continuity"] == 2
    assert rows["polynomial_4_3_4"]["C_v"] == pytest.approx(28 / 15, rel=1e-14)
    assert rows["polynomial_4_3_4"]["jerk_bounded"] is True
    circular = rows["circular_blends"]
    assert (circular["C_v"], circular["C_a"]) == pytest.approx((1.5, 4 / 0.512), rel=1e-14)
    assert circular["continuity"] == 1 and circular["jerk_bounded"] is False
    assert [j["tau"] for j in circular["acceleration_jumps"]] == pytest.approx([0, 0.3, 0.7, 1])


@pytest.mark.parametrize("spec", NEW_SPECS)
def test_sizer_law_samples_the_new_laws(spec):
    result = run_cli("law", spec, "--displacement", "1", "--duration", "1", "--samples", "11",
                     "--format", "json")
    assert result.returncode == 0, result.stderr
    data = json.loads(result.stdout)
    law = make_law(spec)
    taus = np.linspace(0, 1, 11)
    assert data["q"][0] == 0 and data["q"][-1] == pytest.approx(1.0, abs=1e-15)
    assert data["v"] == pytest.approx(law.velocity(taus), abs=1e-12)
    assert max(abs(x) for x in data["v"]) <= law.coefficients.C_v * (1 + 1e-12)


MOTOR = Motor("m", inertia=0.0, continuous_torque=8.0, peak_torque=20.0, rated_speed=10.0)
LOAD = Load(inertia=1.0, damping=0.3)


@pytest.mark.parametrize("spec", NEW_SPECS)
def test_new_laws_size_through_the_engine(spec):
    """h = 15 rad in T = 3 s (Example 6.1's move): tau_rms^2 = J^2 (h/T^2)^2 C_a_rms^2 +
    B^2 (h/T)^2 C_v_rms^2 (sec. 6.2, no dwell), max speed C_v h/T, and a free-T design
    finds a finite shortest duration."""
    h, T = 15.0, 3.0
    law = make_law(spec)
    c = law.coefficients
    r = next(iter(size_design(Design(Task(h, T), LOAD, laws=(spec,), motors=(MOTOR,))).results))
    assert r.spec == law.spec
    assert r.rms_torque == pytest.approx(math.hypot(c.C_a_rms * h / T**2,
                                                    0.3 * c.C_v_rms * h / T), rel=1e-9)
    assert r.max_speed == pytest.approx(c.C_v * h / T, rel=1e-9)
    # each piece sampled on its own, ends included (one-sided values at the steps)
    sampled = max(np.max(law.piece_derivative(i, taus, 2) * h / T**2
                         + 0.3 * law.piece_derivative(i, taus, 1) * h / T)
                  for i, piece in enumerate(law.pieces)
                  for taus in [np.linspace(piece.start, piece.end, 20001)])
    assert sampled <= r.peak_torque * (1 + 1e-12)
    assert r.peak_torque == pytest.approx(sampled, rel=1e-8)
    free = next(iter(size_design(Design(Task(h, None), LOAD, laws=(spec,),
                                        motors=(MOTOR,))).results))
    assert free.feasible and math.isfinite(free.duration) and free.duration > 0
