"""Trigonometric laws: harmonic, cycloidal, elliptic (book sec. 2.2)."""

from __future__ import annotations

import math
from typing import ClassVar

import numpy as np

from sizer.laws.base import MotionLaw, Parameter
from sizer.laws.pieces import Piece, trig_poly_piece

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
    With e = 1/n^2 = 1 - a, the radicand is written D = cos^2 x + e sin^2 x and the
    x-derivatives of q are (e/2) D^-(2k+1)/2 times polynomials in w = cos^2 x and e
    (derived with sympy), free of the cancellation the book's form has near x = pi/2
    when n is large. Velocity and acceleration agree with the book's formulas.
    For large n the law tends to a step at tau = 1/2 (C_v = pi n/2, C_a ~ n^2,
    C_j ~ n^3), hence the range n <= MAX_N. ``n=auto`` searches [1, 2]: C_a is smallest
    near n = 1.085 (below the harmonic law's pi^2/2) and every coefficient grows with n
    beyond it, so no optimum lies above 2.
    """

    law_id = "elliptic"
    title = "Elliptic"
    MAX_N: ClassVar[float] = 1000.0
    parameters = (
        Parameter("n", 2, 1.0, MAX_N,
                  description="ratio of major to minor ellipse axis (1 = harmonic); up to "
                              "1000: beyond, the law is a step at T/2 (C_v = pi n/2)",
                  auto_high=2.0),
    )
    max_order = 4

    def _build(self):
        n = self.params["n"]
        e = 1.0 / (n * n)
        a = (n - 1.0) * (n + 1.0) / (n * n)  # 1 - e without cancellation near n = 1
        half_e = 0.5 * e

        def evaluate(tau: np.ndarray, order: int) -> np.ndarray:
            x = PI * tau
            s, c = np.sin(x), np.cos(x)
            w = c * c
            d = w + e * s * s
            if order == 0:
                root = np.sqrt(d)
                # 1 - c/sqrt(D) = e sin^2 x / (sqrt(D) (sqrt(D) + c)) where c > 0
                with np.errstate(divide="ignore", invalid="ignore"):
                    small = e * s * s / (root * (root + c))
                return 0.5 * np.where(c > 0.0, small, 1.0 - c / root)
            if order == 1:
                g = s
            elif order == 2:
                g = c * (3.0 - 2.0 * e - 2.0 * a * w)
            elif order == 3:
                g = s * (-4.0 * a * a * w * w + 2.0 * a * (6.0 - e) * w - e * (3.0 - 2.0 * e))
            else:
                g = c * (8.0 * a**3 * w**3 - 60.0 * a * a * w * w
                         + 12.0 * a * (5.0 - 2.0 * e * e) * w
                         - e * (16.0 * e * e - 60.0 * e + 45.0))
            return half_e * PI**order * g * d ** -(order + 0.5)

        return [Piece(0.0, 1.0, evaluate)], 1

    def fine_points(self) -> tuple[float, ...]:
        """tau = 1/2, where the profile narrows to a width of about 1/n."""
        return (0.5,)

    def closed_form_coefficients(self) -> dict[str, float]:
        """C_v = pi n/2 at tau = 1/2; C_a at tau = 0 (pi^2/(2 n^2)) or where the jerk
        vanishes: 4 a^2 w^2 - 2 a (6 - e) w + e (3 - 2 e) = 0, the smaller root
        w = cos^2 x = e (3 - 2e) / (a (6 - e + sqrt(36 - 24 e + 9 e^2))) when w <= 1."""
        n = self.params["n"]
        e = 1.0 / (n * n)
        a = (n - 1.0) * (n + 1.0) / (n * n)
        C_a = PI**2 * e / 2.0  # at tau = 0: |q''| = pi^2 e/2 * 1
        if a > 0.0:
            w = e * (3.0 - 2.0 * e) / (a * (6.0 - e + math.sqrt(36.0 - 24.0 * e + 9.0 * e * e)))
            if w <= 1.0:
                d = w + e * (1.0 - w)
                inner = math.sqrt(w) * (3.0 - 2.0 * e - 2.0 * a * w) * d**-2.5
                C_a = max(C_a, PI**2 * e / 2.0 * inner)
        return {"C_v": PI * n / 2.0, "C_a": C_a}
