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

from sizer.laws.base import MotionLaw, Parameter
from sizer.laws.pieces import Piece

TWO_PI = 2.0 * math.pi
WILDT_KAPPA = 1.0 - math.sqrt(3.0) / 2.0
MAX_KAPPA = 0.99
"""The law degenerates as |kappa| -> 1 (at -0.99, C_v = 200 and C_a = 4.6e5)."""


def solve_tau_m(tau: np.ndarray, kappa: float) -> np.ndarray:
    """Invert tau = tau_m - kappa*sin(2*pi*tau_m)/(2*pi) for tau_m (vectorized).

    Safeguarded Newton (bisection where a step leaves the sign bracket), each step on the
    points still moving: a point is done when its step falls to the rounding of f
    amplified by 1/f' (f' = 1 - kappa cos >= 1 - |kappa|), so that near |kappa| = 1 the
    iterates' wandering by a few ulps around the root does not keep every point going."""
    tau = np.asarray(tau, dtype=float)
    shape = tau.shape
    flat = tau.ravel()
    spread = abs(kappa) / TWO_PI
    lo, hi = flat - spread, flat + spread
    x = flat + kappa * np.sin(TWO_PI * flat) / TWO_PI  # one fixed-point step: inside [lo, hi]
    out = x.copy()
    index = np.arange(flat.size)
    target = flat
    settle = 4e-16 / (1.0 - abs(kappa))
    for _ in range(100):
        theta = TWO_PI * x
        f = x - kappa * np.sin(theta) / TWO_PI - target
        lo = np.where(f < 0.0, x, lo)
        hi = np.where(f > 0.0, x, hi)
        step = f / (1.0 - kappa * np.cos(theta))
        new = x - step
        # strictly outside: a converged x is itself a bracket end, and its Newton step
        # (zero, or an ulp toward the root) must not be taken for a divergence
        outside = (new < lo) | (new > hi)
        new = np.where(outside, 0.5 * (lo + hi), new)
        out[index] = new
        moving = np.abs(new - x) > settle * np.maximum(1.0, np.abs(x))
        if not moving.any():
            break
        index, x, target = index[moving], new[moving], target[moving]
        lo, hi = lo[moving], hi[moving]
    return out.reshape(shape)


class ModifiedCycloidal(MotionLaw):
    """Modified cycloidal law with distortion kappa = tan(delta)/tan(gamma) (sec. 3.9)."""

    law_id = "modified_cycloidal"
    title = "Modified cycloidal"
    parameters = (
        Parameter("kappa", WILDT_KAPPA, -MAX_KAPPA, MAX_KAPPA,
                  description="distortion; 1 - sqrt(3)/2 minimizes C_a, 0 is cycloidal; "
                              "|kappa| <= 0.99: toward -1 C_v = 2/(1 + kappa) diverges, "
                              "toward 1 C_a does"),
    )

    def _build(self):
        kappa = self.params["kappa"]
        scale = 1.0 - kappa

        last: list[tuple[np.ndarray, np.ndarray]] = []  # the latest (tau, theta) solved

        def angle(tau: np.ndarray) -> np.ndarray:
            """2 pi tau_m; the derivatives of one set of points share one inversion."""
            memo = last[-1] if last else None
            if memo is not None and memo[0].shape == tau.shape and np.array_equal(memo[0], tau):
                return memo[1]
            theta = TWO_PI * solve_tau_m(tau, kappa)
            last[:] = [(tau.copy(), theta)]
            return theta

        def evaluate(tau: np.ndarray, order: int) -> np.ndarray:
            theta = angle(np.asarray(tau, dtype=float))
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

    def fine_points(self) -> tuple[float, ...]:
        """Where 1 - kappa cos(2 pi tau_m) is smallest: tau = 1/2 for kappa < 0, the ends
        for kappa > 0 (the profile narrows there as |kappa| -> 1)."""
        kappa = self.params["kappa"]
        return (0.5,) if kappa < 0.0 else (0.0, 1.0) if kappa > 0.0 else ()

    def closed_form_coefficients(self) -> dict[str, float]:
        """C_v = 2/(1 + kappa) at tau = 1/2 (eq. 3.54 misprints it, see errata); C_a and
        C_j at the roots in c = cos(2 pi tau_m) of the next derivative, see
        :func:`peak_coefficients`."""
        return peak_coefficients(self.params["kappa"])


def peak_coefficients(kappa: float) -> dict[str, float]:
    """C_v, C_a, C_j of the modified cycloidal law in closed form.

    With c = cos(theta), theta = 2 pi tau_m, g = 1 - kappa c: v = (1 - c)/g,
    a = 2 pi (1 - kappa) sin(theta)/g^3 and j = 4 pi^2 (1 - kappa)(c + 2 kappa c^2 - 3 kappa)/g^5.
    da/dtheta = 0 where 2 kappa c^2 + c - 3 kappa = 0, i.e. c = 6 kappa/(1 + sqrt(1 + 24 kappa^2));
    dj/dtheta = 0 where sin(theta) = 0 (c = +-1) or 6 kappa^2 c^2 + 8 kappa c + 1 - 15 kappa^2 = 0.
    """
    c_a = 6.0 * kappa / (1.0 + math.sqrt(1.0 + 24.0 * kappa * kappa))
    s_a = math.sqrt(max(0.0, 1.0 - c_a * c_a))
    C_a = TWO_PI * (1.0 - kappa) * s_a / (1.0 - kappa * c_a) ** 3
    cs = [1.0, -1.0]
    if kappa != 0.0:
        r = math.sqrt(40.0 + 360.0 * kappa * kappa)
        cs += [c for c in ((-8.0 + r) / (12.0 * kappa), (-8.0 - r) / (12.0 * kappa))
               if -1.0 <= c <= 1.0]

    def jerk(c: float) -> float:
        return abs(TWO_PI**2 * (1.0 - kappa) * (c + 2.0 * kappa * c * c - 3.0 * kappa)
                   / (1.0 - kappa * c) ** 5)

    return {"C_v": 2.0 / (1.0 + kappa), "C_a": C_a, "C_j": max(jerk(c) for c in cs)}
