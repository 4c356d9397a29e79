"""Coefficients and profiles pinned to closed forms derived by hand (not by the code).

Every law also checks its closed-form coefficients (where the code has them) against the
purely numerical computation (roots of the next derivative, adaptive quadrature).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate

from sizer.laws import DEFAULT_LAW_SPECS, INFINITELY_SMOOTH, make_law
from sizer.laws.coefficients import COEFFICIENT_NAMES, measured_continuity

PI = math.pi
REL = 1e-9

SPECS = [
    *DEFAULT_LAW_SPECS,
    "trapezoidal(alpha=1/2)", "trapezoidal(alpha=0.1)", "double_s(alpha=1/2, beta=1/2)",
    "double_s(alpha=0.2, beta=0.05)", "elliptic(n=1)", "elliptic(n=3.5)",
    "polynomial(9)", "polynomial(21)", "modified_cycloidal(kappa=0)",
    "modified_cycloidal(kappa=-0.3)", "modified_cycloidal(kappa=0.6)",
    "exponential(sigma=2, lam=0.61)", "exponential(sigma=4, lam=0.29)",
]


@pytest.mark.parametrize("spec", SPECS)
def test_closed_forms_agree_with_numerics(spec):
    law = make_law(spec)
    closed, numeric = law.coefficients, law.numerical_coefficients
    for name in COEFFICIENT_NAMES:
        assert getattr(closed, name) == pytest.approx(getattr(numeric, name), rel=REL, abs=1e-12)


@pytest.mark.parametrize("spec", SPECS)
def test_declared_continuity_is_measured(spec):
    law = make_law(spec)
    measured = measured_continuity(law)
    if law.continuity == INFINITELY_SMOOTH:
        assert measured == law.max_order
    else:
        assert measured == law.continuity
    assert law.coefficients.jerk_bounded == (law.continuity >= 2)


def test_trapezoid_formulas_of_section_6_2_1():
    for alpha in (0.05, 0.2, 1 / 3, 0.45, 0.5):
        c = make_law(f"trapezoidal(alpha={alpha})").numerical_coefficients
        assert c.C_v == pytest.approx(1 / (1 - alpha), rel=REL)
        assert c.C_a == pytest.approx(1 / (alpha * (1 - alpha)), rel=REL)
        assert c.C_a_rms == pytest.approx(math.sqrt(2 * alpha) / (alpha * (1 - alpha)), rel=REL)
        # velocity ramps over alpha at both ends: int v^2 = V^2 (1 - 4 alpha / 3)
        assert c.C_v_rms == pytest.approx(math.sqrt(1 - 4 * alpha / 3) / (1 - alpha), rel=REL)
        assert c.C_j == 0.0  # inside the pieces; the impulses are reported apart


def test_trapezoid_jerk_impulses_located():
    law = make_law("trapezoidal(alpha=1/4)")
    jumps = law.coefficients.acceleration_jumps
    a_max = 1 / (0.25 * 0.75)
    assert [j.tau for j in jumps] == pytest.approx([0, 0.25, 0.75, 1])
    assert [j.jump for j in jumps] == pytest.approx([a_max, -a_max, -a_max, a_max])
    assert not law.coefficients.jerk_bounded


def test_double_s_formulas_of_section_6_2_1():
    for alpha, beta in ((1 / 3, 1 / 4), (0.5, 0.5), (0.1, 0.2), (0.45, 0.05)):
        c = make_law(f"double_s(alpha={alpha}, beta={beta})").numerical_coefficients
        assert c.C_v == pytest.approx(1 / (1 - alpha), rel=REL)
        assert c.C_a == pytest.approx(1 / (alpha * (1 - alpha) * (1 - beta)), rel=REL)
        assert c.C_j == pytest.approx(1 / (alpha**2 * beta * (1 - alpha) * (1 - beta)), rel=REL)
        expected = math.sqrt((6 - 8 * beta) / (3 * alpha)) / ((1 - alpha) * (1 - beta))
        assert c.C_a_rms == pytest.approx(expected, rel=REL)
        assert c.jerk_bounded


def test_harmonic_and_cycloidal():
    h = make_law("harmonic").numerical_coefficients
    assert (h.C_v, h.C_a, h.C_j) == pytest.approx((PI / 2, PI**2 / 2, PI**3 / 2), rel=REL)
    assert h.C_v_rms == pytest.approx(PI / (2 * math.sqrt(2)), rel=REL)
    assert h.C_a_rms == pytest.approx(PI**2 / (2 * math.sqrt(2)), rel=REL)
    assert [j.tau for j in h.acceleration_jumps] == [0.0, 1.0]
    assert [j.jump for j in h.acceleration_jumps] == pytest.approx([PI**2 / 2, PI**2 / 2])
    c = make_law("cycloidal").numerical_coefficients
    assert (c.C_v, c.C_a, c.C_j) == pytest.approx((2, 2 * PI, 4 * PI**2), rel=REL)
    assert (c.C_v_rms, c.C_a_rms) == pytest.approx((math.sqrt(1.5), math.sqrt(2) * PI), rel=REL)


def test_polynomial_degree_9_is_example_2_13():
    law = make_law("polynomial(9)")
    tau = np.linspace(0, 1, 11)
    a = [0, 0, 0, 0, 0, 126, -420, 540, -315, 70]
    assert law.position(tau) == pytest.approx(np.polyval(a[::-1], tau), abs=1e-13)


@pytest.mark.parametrize("degree", [3, 5, 7, 9, 15, 21])
def test_polynomial_closed_forms(degree):
    m = (degree - 1) // 2
    k = (2 * m + 1) * math.comb(2 * m, m)
    tau = np.linspace(0, 1, 7)
    law = make_law(f"polynomial({degree})")
    assert law.velocity(tau) == pytest.approx(k * (tau * (1 - tau)) ** m, abs=1e-12)
    c = law.numerical_coefficients
    assert c.C_v == pytest.approx(k / 4**m, rel=REL)
    # velocity k*u^m: int v^2 = k^2 B(2m+1, 2m+1)
    v2, _ = integrate.quad(lambda t: (k * (t * (1 - t)) ** m) ** 2, 0, 1, epsrel=1e-13)
    assert c.C_v_rms == pytest.approx(math.sqrt(v2), rel=REL)


def test_cubic_and_345_rms():
    assert make_law("poly3").numerical_coefficients.C_a_rms == pytest.approx(math.sqrt(12), rel=REL)
    assert make_law("poly5").numerical_coefficients.C_a_rms == pytest.approx(
        math.sqrt(120 / 7), rel=REL)
    assert make_law("poly5").numerical_coefficients.C_a == pytest.approx(10 / math.sqrt(3), rel=REL)


def test_modified_trapezoidal():
    c = make_law("modified_trapezoidal").numerical_coefficients
    c_a = 8 * PI / (2 + PI)
    assert (c.C_v, c.C_a, c.C_j) == pytest.approx((2, c_a, 32 * PI**2 / (2 + PI)), rel=REL)
    # sine ramps over T/8 and a constant over T/4 per quarter: int a^2 = C_a^2 * 3/4
    assert c.C_a_rms == pytest.approx(c_a * math.sqrt(3) / 2, rel=REL)
    assert c.jerk_bounded


def test_modified_sinusoidal():
    c = make_law("modified_sinusoidal").numerical_coefficients
    c_a = 4 * PI**2 / (PI + 4)
    assert (c.C_v, c.C_a) == pytest.approx((4 * PI / (PI + 4), c_a), rel=REL)
    assert c.C_j == pytest.approx(16 * PI**3 / (PI + 4), rel=REL)
    # quarter periods of sine everywhere: int a^2 = C_a^2 / 2
    assert c.C_a_rms == pytest.approx(c_a / math.sqrt(2), rel=REL)


def test_fourier_laws():
    g = make_law("gutman_1_3").numerical_coefficients
    assert g.C_a == pytest.approx(2 * PI * math.sqrt(2 / 3), rel=REL)  # at cos(2 pi tau) = 1/sqrt 3
    assert g.C_j == pytest.approx(6 * PI**2, rel=REL)
    assert g.C_v_rms == pytest.approx(math.sqrt(1 + (225 + 1) / 512), rel=REL)
    f = make_law("freudenstein_1_3").numerical_coefficients
    assert f.C_a == pytest.approx(2 * PI * 6 / 7, rel=REL)
    assert f.C_j == pytest.approx(4 * PI**2 * (27 + 9) / 28, rel=REL)
    f5 = make_law("freudenstein_1_3_5").numerical_coefficients
    assert f5.C_j == pytest.approx(4 * PI**2 * 1125 / 1192 * 1.6, rel=REL)
    for c in (g, f, f5):
        assert c.C_v == pytest.approx(2, rel=REL)


def test_modified_cycloidal_is_eq_3_52_and_3_53():
    kappa = 1 - math.sqrt(3) / 2
    law = make_law("modified_cycloidal")
    assert law.params["kappa"] == pytest.approx(kappa)
    tau_m = np.linspace(0, 1, 101)
    tau = tau_m - kappa * np.sin(2 * PI * tau_m) / (2 * PI)
    assert law.position(tau) == pytest.approx(tau_m - np.sin(2 * PI * tau_m) / (2 * PI), abs=1e-14)
    theta = 2 * PI * tau_m
    v = (1 - np.cos(theta)) / (1 - kappa * np.cos(theta))
    a = 2 * PI * (1 - kappa) * np.sin(theta) / (1 - kappa * np.cos(theta)) ** 3
    assert law.velocity(tau) == pytest.approx(v, abs=1e-13)
    assert law.acceleration(tau) == pytest.approx(a, abs=1e-12)
    c = law.numerical_coefficients
    assert c.C_v == pytest.approx(2 / (1 + kappa), rel=REL)  # not eq. (3.54): errata
    assert c.C_a == pytest.approx(5.888253, abs=1e-6)  # book: 5.88


def test_wildt_kappa_minimizes_peak_acceleration():
    best = make_law("modified_cycloidal").coefficients.C_a
    for kappa in (0.12, 0.125, 0.14, 0.15):
        assert make_law(f"modified_cycloidal(kappa={kappa})").coefficients.C_a > best


def test_modified_cycloidal_kappa_zero_is_cycloidal():
    tau = np.linspace(0, 1, 33)
    for order in range(4):
        assert make_law("modified_cycloidal(kappa=0)").derivative(tau, order) == pytest.approx(
            make_law("cycloidal").derivative(tau, order), abs=1e-11)


def test_elliptic_matches_book_formulas_and_n1_is_harmonic():
    n = 2.0
    alpha = (n * n - 1) / (n * n)
    tau = np.linspace(0, 1, 41)
    x = PI * tau
    law = make_law("elliptic(n=2)")
    d = 1 - alpha * np.sin(x) ** 2
    assert law.position(tau) == pytest.approx(0.5 * (1 - np.cos(x) / np.sqrt(d)), abs=1e-14)
    assert law.velocity(tau) == pytest.approx(PI / 2 * np.sin(x) / (n * n * d**1.5), abs=1e-12)
    acc = PI**2 / 2 * np.cos(x) * (1 + 2 * alpha * np.sin(x) ** 2) / (n * n * d**2.5)
    assert law.acceleration(tau) == pytest.approx(acc, abs=1e-11)
    harmonic = make_law("harmonic")
    for order in range(5):
        assert make_law("elliptic(n=1)").derivative(tau, order) == pytest.approx(
            harmonic.derivative(tau, order), abs=1e-11)


def test_exponential_integrates_its_velocity():
    law = make_law("exponential(sigma=7.1, lam=0.2)")
    for tau in (0.05, 0.3, 0.5, 0.77, 0.999):
        expected, _ = integrate.quad(lambda t: float(law.velocity(np.array([t]))[0]), 0, tau,
                                     epsabs=0, epsrel=1e-13, limit=200)
        assert float(law.position(np.array([tau]))[0]) == pytest.approx(expected, rel=1e-11)
    assert float(law.position(np.array([1.0]))[0]) == pytest.approx(1.0, abs=1e-14)
    tau = np.linspace(0, 1, 21)
    assert law.velocity(tau) == pytest.approx(law.velocity(1 - tau), abs=1e-13)
    assert law.coefficients.jerk_bounded
