"""Acceleration spectra (book sec. 7.3): closed forms against the numerical transform of the
same law, against the book's printed forms (where they are right) and against an
independent scipy quad; harmonic content of repeated moves (sec. 7.3.3) against quad of
the periodic signal; time scaling (sec. 7.3.4)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from sizer.errors import UserError
from sizer.laws import make_law
from sizer.vibration.harmonics import harmonic_content, harmonic_numbers
from sizer.vibration.spectrum import (
    acceleration_spectrum,
    book_spectrum,
    frequency_spectrum,
    numerical_spectrum,
    spectrum,
)
from sizer.vibration.spectrum_closed_forms import closed_form_of, polynomial_legendre

PI = math.pi

CLOSED_FORM_SPECS = [
    "harmonic",
    "cycloidal",
    "poly3",
    "poly5",
    "poly7",
    "polynomial(degree=21)",
    "constant_acceleration",
    "trapezoidal(alpha=1/3)",
    "trapezoidal(alpha=0.05)",
    "trapezoidal(alpha=1/2)",
    "trapezoidal(alpha=0.1, alpha_d=0.4)",
    "double_s(alpha=1/3, beta=1/4)",
    "double_s(alpha=1/4, beta=1/2)",
    "double_s(alpha=0.45, beta=0.01)",
    "double_s(alpha=0.2, beta=0.5, alpha_d=0.4, beta_d=0.1)",
    "gutman_1_3",
    "freudenstein_1_3",
    "freudenstein_1_3_5",
]

# every zero of the spectra above up to fT = 50 that the closed forms make exact, plus
# the removable singularities (harmonic 1/2, cycloidal 1) and tiny frequencies
SPECIAL_FT = np.concatenate([np.arange(0.0, 50.5, 0.5), 1.5 * np.arange(1, 34),
                             np.arange(1, 17) / (1 / 3 * 3 / 4), [1e-9, 1e-6, 1e-3]])
FT = np.concatenate([np.linspace(0.0, 50.0, 1001), SPECIAL_FT])


def assert_close(actual: np.ndarray, expected: np.ndarray, tol: float = 1e-6) -> None:
    np.testing.assert_allclose(actual, expected, rtol=tol, atol=tol)


@pytest.mark.parametrize("spec", CLOSED_FORM_SPECS)
def test_closed_form_matches_numerical_transform(spec: str) -> None:
    law = make_law(spec)
    assert closed_form_of(law) is not None
    assert_close(acceleration_spectrum(law, FT), numerical_spectrum(law, FT))


def _quad_transform(function, s: complex, points) -> complex:
    """int_0^1 function(tau) exp(-s tau) dtau by adaptive quadrature (independent)."""
    kwargs = {"points": points, "limit": 400, "epsabs": 1e-12, "epsrel": 1e-11}
    re = quad(lambda t: function(t) * math.cos(s.imag * t), 0.0, 1.0, **kwargs)[0]
    im = quad(lambda t: -function(t) * math.sin(s.imag * t), 0.0, 1.0, **kwargs)[0]
    return complex(re, im)


@pytest.mark.parametrize("spec", ["poly3", "poly5", "harmonic", "cycloidal",
                                  "double_s(alpha=1/3, beta=1/4)", "modified_trapezoidal",
                                  "elliptic(n=2)", "modified_sinusoidal"])
@pytest.mark.parametrize("fT", [0.3, 1.0, 2.5, 7.25])
def test_spectrum_against_quad(spec: str, fT: float) -> None:
    law = make_law(spec)
    expected = abs(_quad_transform(lambda t: float(law.derivative(t, 2)), 2j * PI * fT,
                                   law.breakpoints[1:-1] if law.breakpoints.size > 2
                                   else None))
    assert acceleration_spectrum(law, fT) == pytest.approx(expected, rel=1e-9, abs=1e-12)


# ------------------------------------------------------- the book's printed closed forms
OMEGA = np.linspace(0.013, 20.013, 1001)  # off the removable singularities


def test_book_harmonic_and_cycloidal() -> None:
    """V'_N of sec. 7.3.1 (with |1 - 4 Omega^2|, |1 - Omega^2|): book_spectrum is |A_N|/pi."""
    harmonic = 2 * OMEGA / np.abs(1 - 4 * OMEGA**2) * np.abs(np.cos(PI * OMEGA))
    cycloidal = 2 / (PI * np.abs(1 - OMEGA**2)) * np.abs(np.sin(PI * OMEGA))
    assert_close(book_spectrum(make_law("harmonic"), OMEGA), harmonic, 1e-12)
    assert_close(book_spectrum(make_law("cycloidal"), OMEGA), cycloidal, 1e-12)
    # the limits at the removable singularities: harmonic pi/4 at 1/2, cycloidal 1 at 1
    assert book_spectrum(make_law("harmonic"), 0.5) == pytest.approx(PI / 4, rel=1e-15)
    assert book_spectrum(make_law("cycloidal"), 1.0) == pytest.approx(1.0, rel=1e-15)


@pytest.mark.parametrize("alpha", [0.05, 0.2, 1 / 3, 0.5])
def test_book_trapezoid(alpha: float) -> None:
    book = (2 / ((1 - alpha) * alpha * PI**2 * OMEGA)
            * np.abs(np.sin((1 - alpha) * PI * OMEGA) * np.sin(alpha * PI * OMEGA)))
    assert_close(book_spectrum(make_law(f"trapezoidal(alpha={alpha!r})"), OMEGA), book, 1e-12)


@pytest.mark.parametrize(("alpha", "beta"), [(1 / 3, 1 / 4), (1 / 4, 0.1), (1 / 4, 1 / 2),
                                             (0.45, 0.3)])
def test_book_double_s(alpha: float, beta: float) -> None:
    book = (2 / (alpha**2 * beta * (1 - alpha) * (1 - beta) * PI**3 * OMEGA**2)
            * np.abs(np.sin((1 - alpha) * PI * OMEGA) * np.sin(alpha * (1 - beta) * PI * OMEGA)
                     * np.sin(alpha * beta * PI * OMEGA)))
    law = make_law(f"double_s(alpha={alpha!r}, beta={beta!r})")
    assert_close(book_spectrum(law, OMEGA), book, 1e-12)


def test_constant_acceleration_is_the_trapezoid_at_one_half() -> None:
    book = 8 / (PI**2 * OMEGA) * np.sin(PI * OMEGA / 2) ** 2  # alpha = 1/2 in the book's form
    assert_close(book_spectrum(make_law("constant_acceleration"), OMEGA), book, 1e-12)


def test_polynomials_corrected_forms() -> None:
    """The book's printed V'_N of degrees 3 and 5 drop a phase (docs/errata.md); the right
    ones, checked against quad above, and their values at Omega = 1."""
    x = PI * OMEGA
    poly3 = 6 / (PI**3 * OMEGA**2) * np.abs(np.sin(x) - x * np.cos(x))
    poly5 = 30 / (PI**5 * OMEGA**4) * np.abs((3 - x**2) * np.sin(x) - 3 * x * np.cos(x))
    assert_close(book_spectrum(make_law("poly3"), OMEGA), poly3, 1e-9)
    assert_close(book_spectrum(make_law("poly5"), OMEGA), poly5, 1e-9)
    # by hand: int (6 - 12 tau) e^(-i 2 pi tau) = 6/(i pi)...: |A_N(1)| = 6/pi and 90/pi^3
    assert acceleration_spectrum(make_law("poly3"), 1.0) == pytest.approx(6 / PI, rel=1e-14)
    assert acceleration_spectrum(make_law("poly5"), 1.0) == pytest.approx(90 / PI**3,
                                                                          rel=1e-14)
    printed3 = 6 / (PI**3) * math.sqrt(1 + PI**2) * abs(math.sin(PI))  # the book's, 0
    assert printed3 < 1e-15 < book_spectrum(make_law("poly3"), 1.0)


def test_polynomial_legendre_coefficients() -> None:
    """q_N'' in x = 2 tau - 1: degree 3 is -6 x = -6 P_1, degree 5 is 15 x^3 - 15 x =
    6 P_3 - 6 P_1."""
    assert polynomial_legendre(3) == pytest.approx((0.0, -6.0))
    assert polynomial_legendre(5) == pytest.approx((0.0, -6.0, 0.0, 6.0), abs=1e-13)


# ------------------------------------------------------------------- zeros and limits
def test_cycloidal_zeros() -> None:
    law = make_law("cycloidal")
    k = np.arange(2.0, 51.0)
    assert np.all(acceleration_spectrum(law, k) < 1e-14)  # sin(pi k) ~ 1e-16, not 0
    assert np.all(numerical_spectrum(law, k) < 1e-12)
    assert acceleration_spectrum(law, 1.0) == pytest.approx(PI, rel=1e-15)
    assert acceleration_spectrum(law, 0.0) == pytest.approx(0.0, abs=1e-15)


def test_trapezoid_and_double_s_zeros() -> None:
    """Trapezoid 1/3: sin(2 pi fT/3) = 0 at fT = 3k/2; double S (1/3, 1/4): also
    sinc(fT/4) = 0 at fT = 4k and sinc(fT/12) at 12 k."""
    trapezoid = make_law("trapezoidal(alpha=1/3)")
    zeros = 1.5 * np.arange(1, 34)
    assert np.all(acceleration_spectrum(trapezoid, zeros) < 1e-14)
    assert np.all(numerical_spectrum(trapezoid, zeros) < 1e-12)
    double_s = make_law("double_s(alpha=1/3, beta=1/4)")
    zeros = np.concatenate([1.5 * np.arange(1, 34), 4.0 * np.arange(1, 13)])
    assert np.all(acceleration_spectrum(double_s, zeros) < 1e-14)
    assert np.all(numerical_spectrum(double_s, zeros) < 1e-12)


def test_even_and_rest_to_rest() -> None:
    law = make_law("modified_sinusoidal")
    fT = np.array([0.7, 3.3, 11.0])
    assert_close(acceleration_spectrum(law, -fT), acceleration_spectrum(law, fT), 1e-12)
    for spec in CLOSED_FORM_SPECS:
        assert acceleration_spectrum(make_law(spec), 0.0) == pytest.approx(0.0, abs=1e-14)


# ------------------------------------------------------------------- other orders
def test_velocity_and_jerk_against_quad() -> None:
    law = make_law("cycloidal")  # continuous jerk: no impulses
    for fT in (0.4, 1.7, 6.0):
        s = 2j * PI * fT
        velocity = abs(_quad_transform(lambda t: float(law.derivative(t, 1)), s, None))
        jerk = abs(_quad_transform(lambda t: float(law.derivative(t, 3)), s, None))
        assert spectrum(law, fT, 1) == pytest.approx(velocity, rel=1e-10)
        assert spectrum(law, fT, 3) == pytest.approx(jerk, rel=1e-10)
    assert spectrum(law, 0.0, 1) == pytest.approx(1.0, rel=1e-14)  # the displacement


def test_trapezoid_jerk_impulses() -> None:
    """The jerk of the trapezoid is four impulses of a = 1/(alpha (1 - alpha)): at 0
    (+a), alpha (-a), 1 - alpha (-a), 1 (+a); its spectrum does not decay."""
    alpha = 1 / 3
    a = 1 / (alpha * (1 - alpha))
    fT = np.linspace(0.0, 50.0, 501)
    s = 2j * PI * fT
    impulses = a * np.abs(1 - np.exp(-s * alpha) - np.exp(-s * (1 - alpha)) + np.exp(-s))
    assert_close(spectrum(make_law("trapezoidal(alpha=1/3)"), fT, 3), impulses, 1e-9)


def test_velocity_jumps_give_acceleration_impulses() -> None:
    """A degree-1 B-spline through the book's via-points of sec. 7.3.2 (0, 0), (0.3, 0.2),
    (0.6, 0.7), (1, 1): speeds 2/3, 5/3, 3/4, so impulses +1 at 0.3 and -11/12 at 0.6."""
    law = make_law("{kind: bspline, degree: 1, points: [[0, 0], [0.3, 0.2], [0.6, 0.7], "
                   "[1, 1]]}")
    assert law.continuity == 0
    fT = np.linspace(0.0, 20.0, 201)
    s = 2j * PI * fT
    expected = np.abs(np.exp(-0.3 * s) - 11 / 12 * np.exp(-0.6 * s))
    assert_close(acceleration_spectrum(law, fT), expected, 1e-9)


# ------------------------------------------------------------ harmonic content, 7.3.3
def _quad_coefficients(law, ratio: float, k: np.ndarray, with_return: bool) -> np.ndarray:
    """c_k = (1/T_c) int_0^T_c a(t) exp(-i 2 pi k t/T_c) dt (T = 1) of the periodic
    acceleration built from the law's samples: rise at 0, return at T_c/2."""
    def a(t: float) -> float:
        value = float(law.derivative(t, 2)) if t <= 1.0 else 0.0
        if with_return and ratio / 2 <= t <= ratio / 2 + 1.0:
            value -= float(law.derivative(t - ratio / 2, 2))
        return value

    points = [*law.breakpoints[1:-1], 1.0]
    if with_return:
        points += [ratio / 2 + p for p in law.breakpoints]
    out = []
    for n in k:
        w = 2 * PI * n / ratio
        kwargs = {"points": points, "limit": 800, "epsabs": 1e-13, "epsrel": 1e-12}
        re = quad(lambda t, w=w: a(t) * math.cos(w * t), 0.0, ratio, **kwargs)[0]
        im = quad(lambda t, w=w: -a(t) * math.sin(w * t), 0.0, ratio, **kwargs)[0]
        out.append(complex(re, im) / ratio)
    return np.array(out)


@pytest.mark.parametrize("spec", ["cycloidal", "poly5", "trapezoidal(alpha=1/3)",
                                  "modified_sinusoidal", "harmonic"])
@pytest.mark.parametrize(("ratio", "with_return"), [(1.0, False), (1.7, False),
                                                    (2.5, True), (2.0, True)])
def test_harmonics_against_quad(spec: str, ratio: float, with_return: bool) -> None:
    law = make_law(spec)
    k = np.arange(1, 13)
    content = harmonic_content(law, k, ratio, with_return)
    expected = _quad_coefficients(law, ratio, k, with_return)
    np.testing.assert_allclose(content.coefficient, expected, rtol=1e-8, atol=1e-9)
    np.testing.assert_allclose(content.amplitude, 2 * np.abs(expected), rtol=1e-8, atol=1e-9)
    np.testing.assert_allclose(content.fT, k / ratio)


def test_book_periodic_statements() -> None:
    """Sec. 7.3.3: the repeated cycloidal law has one harmonic (k = 1, amplitude 2 pi:
    q_N'' = 2 pi sin(2 pi tau)); Gutman and Freudenstein 1-3 only k = 1 and 3,
    Freudenstein 1-3-5 also k = 5; v_Nk = 2 pi V'_N(k)."""
    k = np.arange(1, 21)
    cycloidal = harmonic_content(make_law("cycloidal"), k)
    assert cycloidal.amplitude[0] == pytest.approx(2 * PI, rel=1e-14)
    assert cycloidal.phase[0] == pytest.approx(-PI / 2, abs=1e-12)  # 2 pi sin = cos(. - pi/2)
    assert np.all(cycloidal.amplitude[1:] < 1e-12)
    for spec, present in (("gutman_1_3", {1, 3}), ("freudenstein_1_3", {1, 3}),
                          ("freudenstein_1_3_5", {1, 3, 5})):
        amplitude = harmonic_content(make_law(spec), k).amplitude
        assert {int(n) for n in k[amplitude > 1e-9]} == present
    law = make_law("poly5")
    assert_close(harmonic_content(law, k).amplitude, 2 * PI * book_spectrum(law, k), 1e-12)


def test_harmonic_numbers_and_scaling() -> None:
    assert list(harmonic_numbers(2.0, 2.5)) == [1, 2, 3, 4, 5]
    content = harmonic_content(make_law("cycloidal"), np.arange(1, 4), 2.0)
    h, T = 0.5, 0.2  # v_k = (h/T^2) v_Nk at f = k/T_c
    assert_close(content.scaled_amplitude(h, T), h / T**2 * content.amplitude, 1e-15)
    assert_close(content.frequency(T), np.arange(1, 4) / (2.0 * T), 1e-15)


@pytest.mark.parametrize(("ratio", "with_return"), [(0.9, False), (1.5, True),
                                                    (math.inf, False), (math.nan, False),
                                                    ("x", False)])
def test_bad_period(ratio: float, with_return: bool) -> None:
    with pytest.raises(UserError) as caught:
        harmonic_content(make_law("cycloidal"), np.arange(1, 3), ratio, with_return)
    assert caught.value.field == "period"


# ------------------------------------------------------------------ time scaling, 7.3.4
def test_time_scaling_example_7_1() -> None:
    """Example 7.1: poly5 from q0 = 10 to q1 = 15 in T = 15, lambda = 0.5 -> T' = 30;
    |A(f)| against quad of the physical acceleration, and V_lambda(f) = lambda V(f/lambda)."""
    law = make_law("poly5")
    h, T, lam = 5.0, 15.0, 0.5
    f = np.linspace(0.0, 0.4, 41)
    direct = frequency_spectrum(law, f, h, T)
    for fi, value in zip(f[::8], direct[::8], strict=True):
        w = 2 * PI * fi
        re = quad(lambda t, w=w: h / T**2 * float(law.derivative(t / T, 2)) * math.cos(w * t),
                  0.0, T, epsabs=1e-13, limit=200)[0]
        im = quad(lambda t, w=w: h / T**2 * float(law.derivative(t / T, 2)) * math.sin(w * t),
                  0.0, T, epsabs=1e-13, limit=200)[0]
        assert value == pytest.approx(math.hypot(re, im), rel=1e-9, abs=1e-12)
    slower = frequency_spectrum(law, f, h, T / lam)
    assert_close(slower, lam * frequency_spectrum(law, f / lam, h, T), 1e-13)
    assert_close(direct, h / T * acceleration_spectrum(law, f * T), 1e-15)


# ------------------------------------------------------------------------- bad input
def test_bad_inputs() -> None:
    law = make_law("cycloidal")
    with pytest.raises(UserError) as caught:
        acceleration_spectrum(law, [1.0, math.nan])
    assert caught.value.field == "fT"
    with pytest.raises(UserError) as caught:
        spectrum(law, 1.0, order=4)
    assert caught.value.field == "order"
    with pytest.raises(UserError) as caught:
        frequency_spectrum(law, 1.0, 1.0, 0.0)
    assert caught.value.field == "duration"
    with pytest.raises(UserError) as caught:
        frequency_spectrum(law, 1.0, "x", 1.0)
    assert caught.value.field == "displacement"
    with pytest.raises(UserError) as caught:
        harmonic_numbers(math.nan, 1.0)
    assert caught.value.field == "max_ft"
    with pytest.raises(UserError) as caught:  # no closed form: the transform's range
        acceleration_spectrum("modified_sinusoidal", 2e5)
    assert caught.value.field == "fT"
    with pytest.raises(UserError, match="unknown law"):
        acceleration_spectrum("nosuch", 1.0)


def test_spec_text_is_a_law() -> None:
    assert acceleration_spectrum("cycloidal", 1.0) == pytest.approx(PI, rel=1e-15)
    assert harmonic_content("cycloidal", 1).amplitude[0] == pytest.approx(2 * PI)
