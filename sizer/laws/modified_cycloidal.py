"""Modified cycloidal law (book sec. 3.9, eq. 3.52-3.53), with the exact inverse t_m(t).

q_N = tau_m - sin(2 pi tau_m)/(2 pi) with tau = tau_m - kappa sin(2 pi tau_m)/(2 pi).
The implicit equation is solved to machine precision by safeguarded Newton iteration
(its derivative 1 - kappa cos(2 pi tau_m) >= 1 - |kappa| > 0), not by the book's
fifth-degree polynomial shortcut. kappa = 0 is the cycloidal law; kappa = 1 - sqrt(3)/2
minimizes the peak acceleration (Wildt); kappa < 0 gives Alt-type modifications.
"""

from __future__ import annotations

import math

import numpy as np

from sizer.laws.base import MotionLaw, Parameter, Piece

TWO_PI = 2.0 * math.pi
WILDT_KAPPA = 1.0 - math.sqrt(3.0) / 2.0


def solve_tau_m(tau: np.ndarray, kappa: float) -> np.ndarray:
    """Invert tau = tau_m - kappa*sin(2*pi*tau_m)/(2*pi) for tau_m (vectorized)."""
    tau = np.asarray(tau, dtype=float)
    spread = abs(kappa) / TWO_PI
    lo, hi = tau - spread, tau + spread
    x = tau.copy()
    for _ in range(100):
        theta = TWO_PI * x
        f = x - kappa * np.sin(theta) / TWO_PI - tau
        lo = np.where(f < 0.0, x, lo)
        hi = np.where(f > 0.0, x, hi)
        step = f / (1.0 - kappa * np.cos(theta))
        new = x - step
        outside = (new <= lo) | (new >= hi)
        new = np.where(outside, 0.5 * (lo + hi), new)
        if np.all(np.abs(new - x) <= 4e-16 * np.maximum(1.0, np.abs(x))):
            return new
        x = new
    return x


class ModifiedCycloidal(MotionLaw):
    """Modified cycloidal law with distortion kappa = tan(delta)/tan(gamma) (sec. 3.9)."""

    law_id = "modified_cycloidal"
    title = "Modified cycloidal"
    parameters = (
        Parameter("kappa", WILDT_KAPPA, -1.0, 1.0, low_open=True, high_open=True,
                  description="distortion; 1 - sqrt(3)/2 minimizes C_a, 0 is cycloidal"),
    )

    def _build(self):
        kappa = self.params["kappa"]
        scale = 1.0 - kappa

        def evaluate(tau: np.ndarray, order: int) -> np.ndarray:
            theta = TWO_PI * solve_tau_m(tau, kappa)
            s, c = np.sin(theta), np.cos(theta)
            g = 1.0 - kappa * c  # d tau / d tau_m
            if order == 0:
                return theta / TWO_PI - s / TWO_PI
            if order == 1:
                return (1.0 - c) / g
            if order == 2:
                return TWO_PI * scale * s / g**3
            n = c + 2.0 * kappa * c * c - 3.0 * kappa
            if order == 3:
                return TWO_PI**2 * scale * n / g**5
            return -(TWO_PI**3) * scale * s * ((1.0 + 4.0 * kappa * c) * g + 5.0 * kappa * n) / g**7

        return [Piece(0.0, 1.0, evaluate)], 2

    def closed_form_coefficients(self) -> dict[str, float]:
        """Peak velocity at tau = 1/2: 2/(1 + kappa) (eq. 3.54 misprints it, see errata)."""
        kappa = self.params["kappa"]
        return {"C_v": 2.0 / (1.0 + kappa)}
