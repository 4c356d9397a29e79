"""Rest-to-rest polynomials of odd degree n = 2m+1 with null boundary derivatives.

Book sec. 2.1.7, Tables 2.1 and 2.2. In Bernstein form the position is
q_N = sum_{k=m+1}^{n} B_{k,n}(tau), the regularized incomplete beta function
I_tau(m+1, m+1); the velocity is (2m+1)*C(2m, m)*(tau*(1-tau))^m. The Bernstein form
is evaluated stably for every degree (no ill-conditioned linear system): the r-th
derivative of sum c_k B_{k,n} is n!/(n-r)! * sum (Delta^r c)_k B_{k,n-r} (forward
differences of the coefficients), a sum of terms of one sign per difference.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

from sizer.laws.base import MotionLaw, Parameter
from sizer.laws.pieces import Piece


class Polynomial(MotionLaw):
    """Polynomial of odd degree 3..21 with null derivatives up to order (n-1)/2 at both ends."""

    law_id = "polynomial"
    title = "Polynomial"
    parameters = (
        Parameter("degree", 5, 3, 21, integer=True, odd=True,
                  description="odd degree n; continuity C^((n-1)/2)",
                  no_auto="the degree is a discrete choice; list the degrees to compare "
                          "instead, e.g. poly3, poly5, poly7"),
    )
    max_order = 22

    @property
    def m(self) -> int:
        return (int(self.params["degree"]) - 1) // 2

    def _build(self):
        m = self.m
        n = 2 * m + 1
        coefficients = np.array([0.0] * (m + 1) + [1.0] * (m + 1))
        # Bernstein coefficients of each derivative, times C(n - r, k), built once
        scaled = []
        for r in range(self.max_order + 1):
            if r > n:
                scaled.append(np.zeros(1))
                continue
            diff = np.diff(coefficients, r) * (math.factorial(n) / math.factorial(n - r))
            scaled.append(diff * np.array([math.comb(n - r, k) for k in range(n - r + 1)]))

        def evaluate(tau: np.ndarray, order: int) -> np.ndarray:
            tau = np.asarray(tau, dtype=float)
            c = scaled[order]
            degree = len(c) - 1
            s, t = tau, 1.0 - tau
            out = np.zeros(tau.shape)
            for k in np.nonzero(c)[0]:
                out += c[k] * s**k * t ** (degree - k)
            return out

        return [Piece(0.0, 1.0, evaluate, degree=n)], m

    def closed_form_coefficients(self) -> dict[str, float]:
        """C_v at tau = 1/2; C_a where 1 - 2 tau = 1/sqrt(2m - 1); RMS via beta functions."""
        m = self.m
        k = (2 * m + 1) * math.comb(2 * m, m)  # velocity = k * u^m, u = tau(1 - tau)
        s = 1.0 / math.sqrt(2 * m - 1)
        u = (1.0 - s * s) / 4.0
        return {
            "C_v": k / 4.0**m,
            "C_a": k * m * u ** (m - 1) * s,
            "C_v_rms": k * math.sqrt(_beta(2 * m + 1, 2 * m + 1)),
            "C_a_rms": k * m * math.sqrt(_beta(2 * m - 1, 2 * m - 1) - 4 * _beta(2 * m, 2 * m)),
        }


def _beta(a: int, b: int) -> Fraction:
    """The beta function B(a, b) = (a-1)! (b-1)! / (a+b-1)! of positive integers, exact."""
    return Fraction(math.factorial(a - 1) * math.factorial(b - 1), math.factorial(a + b - 1))
