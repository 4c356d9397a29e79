"""Laws from truncated Fourier series of the parabolic profile (book sec. 2.4).

Each has velocity q_N' = 1 - sum_k b_k cos(2*pi*k*tau) over odd harmonics k, with
sum b_k = 1 so that the motion starts and ends at rest.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import ClassVar

from sizer.laws.base import MotionLaw
from sizer.laws.pieces import trig_poly_piece

PI = math.pi


class FourierLaw(MotionLaw):
    """q_N = tau - sum_k b_k sin(2*pi*k*tau)/(2*pi*k)."""

    harmonics: ClassVar[tuple[tuple[int, Fraction], ...]] = ()
    max_order = 32

    def _build(self):
        sines = [(-float(b) / (2 * PI * k), 2 * PI * k, 0.0) for k, b in self.harmonics]
        return [trig_poly_piece(0.0, 1.0, (0.0, 1.0), sines)], 2

    def closed_form_coefficients(self) -> dict[str, float]:
        """C_v = 1 + sum b_k at tau = 1/2; RMS by Parseval over [0, 1]."""
        b = [(k, float(bk)) for k, bk in self.harmonics]
        return {
            "C_v": 1.0 + sum(bk for _, bk in b),
            "C_v_rms": math.sqrt(1.0 + sum(bk * bk for _, bk in b) / 2.0),
            "C_a_rms": math.sqrt(sum((2 * PI * k * bk) ** 2 for k, bk in b) / 2.0),
        }


class Gutman13(FourierLaw):
    """Gutman 1-3, sec. 2.4.1."""

    law_id = "gutman_1_3"
    title = "Gutman 1-3"
    harmonics = ((1, Fraction(15, 16)), (3, Fraction(1, 16)))


class Freudenstein13(FourierLaw):
    """Freudenstein 1-3, sec. 2.4.2."""

    law_id = "freudenstein_1_3"
    title = "Freudenstein 1-3"
    harmonics = ((1, Fraction(27, 28)), (3, Fraction(1, 28)))


_ALPHA_135 = Fraction(1125, 1192)


class Freudenstein135(FourierLaw):
    """Freudenstein 1-3-5, sec. 2.4.3, alpha = 1125/1192."""

    law_id = "freudenstein_1_3_5"
    title = "Freudenstein 1-3-5"
    harmonics = ((1, _ALPHA_135), (3, _ALPHA_135 / 18), (5, _ALPHA_135 / 250))
