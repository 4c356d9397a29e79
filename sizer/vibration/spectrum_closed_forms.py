"""Closed forms of the acceleration spectrum |A_N(fT)| of some law families (book sec. 7.3.1).

A_N(fT) = int_0^1 q_N''(tau) exp(-i 2 pi fT tau) dtau, the Fourier transform of the
normalized acceleration (h = T = 1); the book plots V'_N = |A_N| / pi (eq. 7.8). Each form
is written with sinc(x) = sin(pi x)/(pi x) and spherical Bessel functions, so it holds
through the removable singularities (fT = 1/2 of the harmonic law, fT = 1 of the
cycloidal one, fT -> 0) without a 0/0:

- trapezoid, constant acceleration (alpha = 1/2) and double S, symmetric or not: the
  acceleration is two pulses, a box of width alpha (1 - beta) convolved with one of width
  alpha beta (beta = 0 for the trapezoid) of area v_max, the second one negative:
  |A_N| = (2/(1 - alpha)) |sin((1 - alpha) pi fT)| |sinc(alpha (1 - beta) fT)
  sinc(alpha beta fT)| when symmetric (the book's V'_N times pi);
- harmonic: |A_N| = pi^2 fT |sinc(1/2 - fT)| / (1 + 2 fT) (the book's 2 Omega
  |cos(pi Omega)| / |1 - 4 Omega^2| times pi);
- cycloidal and the Fourier laws (Gutman 1-3, Freudenstein 1-3 and 1-3-5, sec. 2.4):
  q_N'' = sum_k b_k 2 pi k sin(2 pi k tau), |A_N| = 2 pi |sum_k b_k k^2 (-1)^(k+1)
  sinc(fT - k) / (k + fT)|; the cycloidal law is b_1 = 1 (the book's
  2 |sin(pi Omega)| / |1 - Omega^2|);
- polynomials of odd degree n (sec. 2.1.7): with x = 2 tau - 1 the acceleration is a
  polynomial sum_l c_l P_l(x) in Legendre polynomials and
  |A_N| = |sum_l c_l (-i)^l j_l(pi fT)| (j_l the spherical Bessel functions): degree 3
  gives 6 |j_1(pi fT)|, degree 5 gives 6 |j_1 + j_3| = 30 |j_2(pi fT)| / (pi fT). The
  book's printed forms for degrees 3 and 5 drop a phase (docs/errata.md).

Pure numpy; scipy.special only inside the polynomial form.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from functools import lru_cache

import numpy as np
from numpy.polynomial import legendre
from numpy.polynomial import polynomial as P

from sizer.laws.base import MotionLaw

PI = math.pi

ClosedForm = Callable[[MotionLaw, np.ndarray], np.ndarray]
"""|A_N| of a law at an array of f T >= 0."""


def _pulse(alpha: float, beta: float, fT: np.ndarray) -> np.ndarray:
    """Transform of a unit-area pulse on [0, alpha]: a box of width alpha (1 - beta)
    convolved with a box of width alpha beta, shifted to start at 0."""
    return (np.sinc(alpha * (1.0 - beta) * fT) * np.sinc(alpha * beta * fT)
            * np.exp(-1j * PI * alpha * fT))


def _two_pulses(alpha: float, beta: float, alpha_d: float, beta_d: float,
                fT: np.ndarray) -> np.ndarray:
    """|A_N| of an acceleration pulse over [0, alpha] and a deceleration pulse over
    [1 - alpha_d, 1], each of area v_max = 2 / (2 - alpha - alpha_d)."""
    if alpha == alpha_d and beta == beta_d:  # real form: exact zeros, no cancellation
        return (2.0 / (1.0 - alpha) * np.abs(np.sin((1.0 - alpha) * PI * fT))
                * np.abs(np.sinc(alpha * (1.0 - beta) * fT) * np.sinc(alpha * beta * fT)))
    v_max = 2.0 / (2.0 - alpha - alpha_d)
    shift = np.exp(-2j * PI * (1.0 - alpha_d) * fT)
    return v_max * np.abs(_pulse(alpha, beta, fT) - shift * _pulse(alpha_d, beta_d, fT))


def trapezoidal(law: MotionLaw, fT: np.ndarray) -> np.ndarray:
    """Trapezoidal velocity (sec. 7.3.1), alpha_d = alpha unless given."""
    alpha = law.params["alpha"]
    return _two_pulses(alpha, 0.0, law.params.get("alpha_d", alpha), 0.0, fT)


def constant_acceleration(law: MotionLaw, fT: np.ndarray) -> np.ndarray:
    """Constant acceleration: the trapezoid with alpha = 1/2, 4 |sin(pi fT/2) sinc(fT/2)|."""
    return _two_pulses(0.5, 0.0, 0.5, 0.0, fT)


def double_s(law: MotionLaw, fT: np.ndarray) -> np.ndarray:
    """Double S (sec. 7.3.1), alpha_d and beta_d equal to alpha and beta unless given."""
    alpha, beta = law.params["alpha"], law.params["beta"]
    return _two_pulses(alpha, beta, law.params.get("alpha_d", alpha),
                       law.params.get("beta_d", beta), fT)


def harmonic(law: MotionLaw, fT: np.ndarray) -> np.ndarray:
    """Harmonic law, q_N'' = (pi^2/2) cos(pi tau) (sec. 7.3.1)."""
    return PI**2 * fT * np.abs(np.sinc(0.5 - fT)) / (1.0 + 2.0 * fT)


def _sine_series(terms: tuple[tuple[int, float], ...], fT: np.ndarray) -> np.ndarray:
    """|A_N| of q_N'' = sum_k b_k 2 pi k sin(2 pi k tau), for (k, b_k) in terms."""
    total = np.zeros(fT.shape)
    for k, b in terms:
        near = np.abs(fT - k) < 0.5
        # sinc(fT - k) = (-1)^k sin(pi fT) / (pi (fT - k)): sin(pi fT) keeps the small
        # values of fT exact (sin(pi (fT - k)) rounds pi k: 2.4e-16 at fT = 1e-200);
        # near fT = k, sinc itself (its 0/0 there)
        with np.errstate(divide="ignore", invalid="ignore"):
            far = np.sin(PI * fT) / (PI * (k * k - fT * fT))
        total = total + b * k * k * np.where(
            near, (-1.0) ** (k + 1) * np.sinc(fT - k) / (k + fT), far)
    return 2.0 * PI * np.abs(total)


def cycloidal(law: MotionLaw, fT: np.ndarray) -> np.ndarray:
    """Cycloidal law, q_N'' = 2 pi sin(2 pi tau) (sec. 7.3.1): zeros at fT = 2, 3, ..."""
    return _sine_series(((1, 1.0),), fT)


def fourier_law(law: MotionLaw, fT: np.ndarray) -> np.ndarray:
    """Gutman 1-3, Freudenstein 1-3 and 1-3-5 (sec. 2.4): their harmonics b_k."""
    from sizer.laws.fourier import FourierLaw

    if not isinstance(law, FourierLaw):
        raise TypeError(f"{law.spec} is not a law of a Fourier series")
    terms = tuple((int(k), float(b)) for k, b in law.harmonics)
    return _sine_series(terms, fT)


@lru_cache(maxsize=16)
def polynomial_legendre(degree: int) -> tuple[float, ...]:
    """Legendre coefficients c_l of q_N'' of the odd polynomial law of this degree, in
    x = 2 tau - 1: q_N' = K (tau (1 - tau))^m = K ((1 - x^2)/4)^m with
    K = (2m + 1) C(2m, m), and q_N'' = 2 d/dx q_N'."""
    m = (degree - 1) // 2
    scale = (2 * m + 1) * math.comb(2 * m, m) / 4.0**m
    velocity = scale * P.polypow([1.0, 0.0, -1.0], m)
    return tuple(float(c) for c in legendre.poly2leg(2.0 * P.polyder(velocity)))


def polynomial(law: MotionLaw, fT: np.ndarray) -> np.ndarray:
    """Polynomial law of odd degree n: |sum_l c_l (-i)^l j_l(pi fT)|."""
    from scipy.special import spherical_jn

    coefficients = polynomial_legendre(int(law.params["degree"]))
    x = PI * fT
    tiny = x < SERIES_BELOW
    total = np.zeros(fT.shape, dtype=complex)
    for order, c in enumerate(coefficients):
        if c != 0.0:
            j = spherical_jn(order, np.where(tiny, 1.0, x))
            # j_l(x) = x^l / (2l + 1)!! (1 + O(x^2)): scipy gives nan for subnormal x
            j = np.where(tiny, x**order / _double_factorial(2 * order + 1), j)
            total = total + c * (-1j) ** order * j
    return np.abs(total)


SERIES_BELOW = 1e-100
"""pi fT below which j_l(pi fT) is its leading term x^l / (2l + 1)!! (exact in double
precision: the next term is x^2 smaller)."""


def _double_factorial(n: int) -> float:
    return float(math.prod(range(n, 0, -2)))


CLOSED_FORMS: Mapping[str, ClosedForm] = {
    "trapezoidal": trapezoidal,
    "constant_acceleration": constant_acceleration,
    "double_s": double_s,
    "harmonic": harmonic,
    "cycloidal": cycloidal,
    "gutman_1_3": fourier_law,
    "freudenstein_1_3": fourier_law,
    "freudenstein_1_3_5": fourier_law,
    "polynomial": polynomial,
}
"""The closed form of each family that has one, by law_id (the family's own class only:
a law defined by data never matches)."""


def closed_form_of(law: MotionLaw) -> ClosedForm | None:
    """The closed form of the law's family, or None (then the numerical transform)."""
    from sizer.laws.registry import LAW_FAMILIES

    form = CLOSED_FORMS.get(law.law_id)
    if form is None or type(law) is not LAW_FAMILIES.get(law.law_id):
        return None
    return form


def closed_form_spectrum(law: MotionLaw, fT: np.ndarray) -> np.ndarray | None:
    """|A_N(fT)| from the family's closed form (|fT| used: the spectrum is even), or
    None when the family has none."""
    form = closed_form_of(law)
    if form is None:
        return None
    return np.asarray(form(law, np.abs(np.asarray(fT, dtype=float))), dtype=float)
