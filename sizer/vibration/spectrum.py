"""Amplitude spectra of a law's acceleration (book sec. 7.3.1, 7.3.2 and 7.3.4).

Normalization: the move of h in T has the acceleration q''(t) = (h/T^2) q_N''(t/T); its
Fourier transform A(f) = int q''(t) exp(-i 2 pi f t) dt is (h/T) A_N(fT) times a phase,
with A_N(fT) = int_0^1 q_N''(tau) exp(-i 2 pi fT tau) dtau (sec. 7.3.1, A(omega) =
(h/T) A_N(omega T) e^(j omega/2)). :func:`acceleration_spectrum` is |A_N| as a function of
the normalized frequency f T (the book's Omega = omega/omega_0, omega_0 = 2 pi/T, eq.
7.5). The book plots V'_N(Omega) = |A_N| / pi instead (eq. 7.8: the amplitude of
x(t) = int_0^inf V(omega) cos(omega t + phi) d omega): :func:`book_spectrum`.

|A_N| comes from the family's closed form where it has one
(:mod:`sizer.vibration.spectrum_closed_forms`), from the exact numerical transform
otherwise (:func:`sizer.vibration.transform.law_transform`, composite Gauss-Legendre on
the law's pieces, exact to rounding: not a DFT of samples, sec. 7.3.2).
"""

from __future__ import annotations

import math

import numpy as np

from sizer.errors import UserError
from sizer.laws.base import MotionLaw
from sizer.laws.registry import make_law
from sizer.vibration.spectrum_closed_forms import closed_form_spectrum
from sizer.vibration.transform import law_transform

TWO_PI = 2.0 * math.pi

ORDERS = (1, 2, 3)
"""Derivatives with a spectrum: velocity, acceleration, jerk."""

MAX_NUMERICAL_FT = 1e5
"""Largest |f T| of the numerical transform (its nodes grow with f T: 6e6 at 1e5)."""

LawLike = MotionLaw | str
"""A law or its spec text (sizer.laws.make_law)."""


def normalized_frequencies(fT: np.ndarray | float, field: str = "fT") -> np.ndarray:
    """f T as a float array, every value finite (UserError naming ``field`` otherwise)."""
    try:
        values = np.asarray(fT, dtype=float)
    except (TypeError, ValueError):
        raise UserError(f"expected real numbers, got {fT!r}", field=field) from None
    if not np.all(np.isfinite(values)):
        raise UserError("every frequency must be a finite number", field=field)
    return values


def _numerical_frequencies(fT: np.ndarray | float) -> np.ndarray:
    values = normalized_frequencies(fT)
    if np.any(np.abs(values) > MAX_NUMERICAL_FT):
        raise UserError(f"the numerical transform goes up to |f T| = {MAX_NUMERICAL_FT:g}",
                        field="fT")
    return values


def acceleration_transform(law: LawLike, fT: np.ndarray | float) -> np.ndarray:
    """The complex A_N(fT) = int q_N''(tau) exp(-i 2 pi fT tau) dtau over the move.

    The acceleration is the law's distributional one, zero outside the move (the law at
    rest, or at its end speeds, before and after): a law whose velocity jumps inside the
    move (continuity C^0) has an impulse there, which the transform of its pieces'
    q_N'' would miss; it is s F_1(s) + q_N'(1) e^(-s) - q_N'(0) then (F_1 the velocity's
    transform, integration by parts).
    """
    law = make_law(law)
    fT = _numerical_frequencies(fT)
    s = 1j * TWO_PI * fT
    if law.continuity >= 1:
        return law_transform(law, s, order=2)
    start = float(law.piece_derivative(0, 0.0, 1))
    end = float(law.piece_derivative(len(law.pieces) - 1, 1.0, 1))
    return s * law_transform(law, s, order=1) + end * np.exp(-s) - start


def numerical_spectrum(law: LawLike, fT: np.ndarray | float) -> np.ndarray:
    """|A_N(fT)| from the numerical transform only (ignores closed forms): a cross-check."""
    return np.abs(acceleration_transform(law, fT))


def acceleration_spectrum(law: LawLike, fT: np.ndarray | float) -> np.ndarray:
    """|A_N(fT)|, the acceleration's Fourier amplitude normalized by h/T, at f T (sec. 7.3.1).

    The family's closed form where it has one, the exact numerical transform otherwise;
    |A_N(0)| = |q_N'(1) - q_N'(0)| (0 for a rest-to-rest law). Even in f T.
    """
    law = make_law(law)
    fT = normalized_frequencies(fT)
    closed = closed_form_spectrum(law, fT)
    return numerical_spectrum(law, fT) if closed is None else closed


def book_spectrum(law: LawLike, omega: np.ndarray | float) -> np.ndarray:
    """V'_N(Omega) = |A_N(2 pi Omega)| / pi, the book's normalized spectrum (eq. 7.8)."""
    return acceleration_spectrum(law, omega) / math.pi


def spectrum(law: LawLike, fT: np.ndarray | float, order: int = 2) -> np.ndarray:
    """|F_order(fT)|: the amplitude spectrum of q_N^(order) normalized by h/T^(order-1).

    order 1 (velocity): the transform of q_N' over the move (the law at rest outside it;
    |F_1(0)| = 1, the displacement); order 2: :func:`acceleration_spectrum`; order 3 (jerk):
    2 pi |fT| |A_N|, the distributional derivative of the acceleration, with the impulses
    where the acceleration jumps (a trapezoid's jerk spectrum does not decay).
    """
    if order not in ORDERS:
        raise UserError(f"expected one of {', '.join(map(str, ORDERS))} (velocity, "
                        f"acceleration, jerk), got {order!r}", field="order")
    fT = normalized_frequencies(fT)
    if order == 1:
        fT = _numerical_frequencies(fT)
        return np.abs(law_transform(make_law(law), 1j * TWO_PI * fT, order=1))
    amplitude = acceleration_spectrum(law, fT)
    return amplitude if order == 2 else TWO_PI * np.abs(fT) * amplitude


def frequency_spectrum(law: LawLike, frequency: np.ndarray | float, displacement: float,
                       duration: float, order: int = 2) -> np.ndarray:
    """|A(f)| of the move of ``displacement`` h in ``duration`` T at f [Hz] (sec. 7.3.4).

    |A(f)| = (h/T) |A_N(f T)| for the acceleration (order 2; h/T^(order-1) for the other
    orders), in the units of h per second. A time scaling T' = T/lambda gives
    lambda |A(f/lambda)|: slower moves have lower and narrower spectra.
    """
    T, h = _number(duration, "duration"), _number(displacement, "displacement")
    if not T > 0.0:
        raise UserError(f"must be a positive time, got {duration!r}", field="duration")
    f = normalized_frequencies(frequency, field="frequency")
    return abs(h) / T ** (order - 1) * spectrum(law, f * T, order)


def _number(value: float, field: str) -> float:
    """A finite float, else a UserError naming ``field``."""
    try:
        number = float(value)
    except (TypeError, ValueError):
        number = math.nan
    if not math.isfinite(number):
        raise UserError(f"must be a finite number, got {value!r}", field=field)
    return number
