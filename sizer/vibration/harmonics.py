"""Harmonic content of a periodically repeated move (book sec. 7.3.3).

A move of h in T repeated every T_c >= T (rise, then dwell T_c - T; the book's case is
T_c = T) has the periodic acceleration sum_n q''(t - n T_c) = v_0 + sum_k v_k
cos(2 pi k t / T_c + phi_k). Its complex Fourier coefficients are exact samples of the
move's transform (not an FFT of samples):

    c_k = (1/T_c) int_0^T q''(t) exp(-i 2 pi k t / T_c) dt = (h/T^2) (T/T_c) A_N(k T/T_c),

v_k = 2 |c_k|, phi_k = arg c_k (time measured from the start of the rise). With T = T_c
this is the book's v_Nk = 2 pi V'_N(k) (h = T = 1). With ``with_return`` the cycle is
rise, dwell, return (the same law backwards, starting at T_c/2), dwell: the return's
acceleration is -q''(t - T_c/2), so c_k gets the factor 1 - (-1)^k (even harmonics
vanish); it needs T_c >= 2 T.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from sizer.errors import UserError
from sizer.input_limits import MAX_SPECTRUM_LINES
from sizer.laws.base import MotionLaw
from sizer.laws.registry import make_law
from sizer.vibration.spectrum import acceleration_transform

MAX_HARMONICS = MAX_SPECTRUM_LINES
"""Most harmonics computed at once (sizer.input_limits.MAX_SPECTRUM_LINES)."""


@dataclass(frozen=True)
class HarmonicContent:
    """The Fourier-series coefficients of a repeated move, normalized by h/T^2.

    ``k`` the harmonic numbers, ``fT`` their normalized frequencies k T/T_c (f = k/T_c),
    ``coefficient`` the complex c_k / (h/T^2)."""

    law: MotionLaw
    period_ratio: float
    with_return: bool
    k: np.ndarray
    fT: np.ndarray
    coefficient: np.ndarray

    @property
    def amplitude(self) -> np.ndarray:
        """v_Nk = 2 |c_Nk| (k >= 1): the amplitude of the k-th cosine, by h/T^2."""
        return np.where(self.k == 0, 1.0, 2.0) * np.abs(self.coefficient)

    @property
    def phase(self) -> np.ndarray:
        """phi_k = arg c_k [rad], 0 where the harmonic is null to rounding."""
        scale = max(1.0, float(np.max(np.abs(self.coefficient), initial=0.0)))
        return np.where(np.abs(self.coefficient) <= 1e-12 * scale, 0.0,
                        np.angle(self.coefficient))

    def frequency(self, duration: float) -> np.ndarray:
        """f_k = k / T_c [Hz] of a move of ``duration`` T."""
        return self.fT / float(duration)

    def scaled_amplitude(self, displacement: float, duration: float) -> np.ndarray:
        """v_k = (h/T^2) v_Nk, in the units of h per second squared (sec. 7.3.3-7.3.4)."""
        return abs(float(displacement)) / float(duration) ** 2 * self.amplitude


def check_period_ratio(period_ratio: float, with_return: bool = False,
                       field: str = "period") -> float:
    """T_c/T as a float: finite, >= 1 (>= 2 with a return), else a UserError."""
    try:
        ratio = float(period_ratio)
    except (TypeError, ValueError):
        ratio = math.nan
    least = 2.0 if with_return else 1.0
    if not (math.isfinite(ratio) and ratio >= least * (1.0 - 1e-12)):
        need = "twice the duration (rise and return each take T)" if with_return \
            else "the duration"
        raise UserError(f"the period must be at least {need}: T_c/T = {ratio:g}",
                        field=field)
    return max(ratio, least)


def harmonic_numbers(max_ft: float, period_ratio: float) -> np.ndarray:
    """k = 1, 2, ... up to the last harmonic with k T/T_c <= max_ft."""
    top = float(max_ft)
    if not (math.isfinite(top) and top >= 0.0):
        raise UserError(f"must be a finite number >= 0, got {max_ft!r}", field="max_ft")
    span = top * float(period_ratio)
    if not span <= MAX_HARMONICS:  # inf and nan too
        raise UserError(f"f T up to {top:g} with T_c/T = {float(period_ratio):g} is "
                        f"{span:.4g} harmonics, more than {MAX_HARMONICS:,} "
                        f"(MAX_SPECTRUM_LINES): lower the largest f T or the period",
                        field="max_ft")
    count = math.floor(span * (1.0 + 1e-12))
    return np.arange(1, max(count, 0) + 1)


def harmonic_content(law: MotionLaw | str, k: np.ndarray | int, period_ratio: float = 1.0,
                     with_return: bool = False) -> HarmonicContent:
    """The coefficients c_k of the move repeated every T_c = period_ratio * T (sec. 7.3.3)."""
    law = make_law(law)
    ratio = check_period_ratio(period_ratio, with_return)
    numbers = np.atleast_1d(np.asarray(k))
    if numbers.dtype.kind not in "iu" or np.any(numbers < 0):
        raise UserError("harmonic numbers must be integers >= 0", field="k")
    fT = numbers / ratio
    coefficient = acceleration_transform(law, fT) / ratio
    if with_return:
        coefficient = coefficient * np.where(numbers % 2 == 1, 2.0, 0.0)
    return HarmonicContent(law, ratio, with_return, numbers, fT, coefficient)
