"""Trigonometric laws: harmonic, cycloidal, elliptic (book sec. 2.2)."""

from __future__ import annotations

import math

import numpy as np

from sizer.laws.base import MotionLaw, Parameter, Piece
from sizer.laws.pieces import trig_poly_piece

PI = math.pi


class Harmonic(MotionLaw):
    """q_N = (1 - cos(pi*tau))/2, eq. (2.21); acceleration jumps at both ends."""

    law_id = "harmonic"
    title = "Harmonic"
    max_order = 32

    def _build(self):
        return [trig_poly_piece(0.0, 1.0, (0.5,), [(0.5, PI, -PI / 2)])], 1

    def closed_form_coefficients(self) -> dict[str, float]:
        return {
            "C_v": PI / 2,
            "C_a": PI**2 / 2,
            "C_j": PI**3 / 2,
            "C_v_rms": PI / (2 * math.sqrt(2)),
            "C_a_rms": PI**2 / (2 * math.sqrt(2)),
        }


class Cycloidal(MotionLaw):
    """q_N = tau - sin(2*pi*tau)/(2*pi), eq. (2.22)."""

    law_id = "cycloidal"
    title = "Cycloidal"
    max_order = 32

    def _build(self):
        return [trig_poly_piece(0.0, 1.0, (0.0, 1.0), [(-1 / (2 * PI), 2 * PI, 0.0)])], 2

    def closed_form_coefficients(self) -> dict[str, float]:
        return {
            "C_v": 2.0,
            "C_a": 2 * PI,
            "C_j": 4 * PI**2,
            "C_v_rms": math.sqrt(1.5),
            "C_a_rms": math.sqrt(2) * PI,
        }


class Elliptic(MotionLaw):
    """Elliptic law, eq. (2.23): q_N = (1 - cos x / sqrt(1 - a sin^2 x))/2, x = pi*tau.

    a = (n^2 - 1)/n^2 with n the ratio of the ellipse axes; n = 1 is the harmonic law.
    Derivatives: dq/dx = sin x / (2 n^2 D^(3/2)), D = 1 - a sin^2 x, differentiated
    exactly below (the velocity and acceleration agree with the book's formulas).
    """

    law_id = "elliptic"
    title = "Elliptic"
    parameters = (
        Parameter("n", 2, 1.0, math.inf, high_open=True,
                  description="ratio of major to minor ellipse axis (1 = harmonic)"),
    )

    def _build(self):
        n = self.params["n"]
        a = (n * n - 1.0) / (n * n)
        k = 1.0 / (2.0 * n * n)

        def evaluate(tau: np.ndarray, order: int) -> np.ndarray:
            x = PI * tau
            s, c = np.sin(x), np.cos(x)
            d = 1.0 - a * s * s
            if order == 0:
                return 0.5 * (1.0 - c / np.sqrt(d))
            # g = sin x * D^(-3/2) and its x-derivatives; d^k q/dtau^k = k * pi^k * g^(k-1).
            s2 = s * s
            if order == 1:
                g = s * d**-1.5
            elif order == 2:
                g = c * (1.0 + 2.0 * a * s2) * d**-2.5
            elif order == 3:
                g = -s * (4 * a * a * s2 * s2 - 6 * a * a * s2 + 10 * a * s2 - 9 * a + 1) * d**-3.5
            else:
                g = -c * (8 * a**3 * s2**3 - 24 * a**3 * s2 * s2 + 60 * a * a * s2 * s2
                          - 72 * a * a * s2 + 36 * a * s2 - 9 * a + 1) * d**-4.5
            return k * PI**order * g

        return [Piece(0.0, 1.0, evaluate)], 1
