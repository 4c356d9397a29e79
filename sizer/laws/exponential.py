"""Exponential law (book sec. 2.3, eq. 2.24) with f_a(x, lam) = x^2 / |1 - x^2|^lam.

With x = 2*tau - 1 in [-1, 1], the velocity is q_N' = v_c * exp(-sigma*f(x)); it and
all its derivatives vanish at both ends, so the law is C^infinity. The position is the
integral of the velocity, evaluated with composite Gauss-Legendre quadrature on panels
(the integrand is analytic inside [0, 1)); v_c normalizes q_N(1) = 1.
"""

from __future__ import annotations

import numpy as np
from numpy.polynomial.legendre import leggauss

from sizer.laws.base import INFINITELY_SMOOTH, MotionLaw, Parameter
from sizer.laws.pieces import Piece
from sizer.numerics.arrays import sorted_unique

PANELS = 64
NODES = 24


class Exponential(MotionLaw):
    """Exponential law with smoothness parameters sigma and lam (sec. 2.3, Table 2.3)."""

    law_id = "exponential"
    title = "Exponential"
    steep_ends = True
    parameters = (
        Parameter("sigma", 7.1, 1.0, 100.0,
                  description="exponent scale (book optimum 7.1); at least 1, see lam"),
        Parameter("lam", 0.2, 0.15, 5.0,
                  description="exponent of |1 - x^2| (book optimum 0.2); with sigma >= 1 and "
                              "lam >= 0.15 the velocity is below 1e-17 v_c at 1e-12 from the "
                              "ends (smaller values fall to rest closer to the ends than "
                              "double precision resolves)"),
    )

    def _build(self):
        sigma, lam = self.params["sigma"], self.params["lam"]

        def shape(x: np.ndarray) -> np.ndarray:
            """exp(-sigma*f(x)) for |x| < 1, 0 at |x| >= 1."""
            w = 1.0 - x * x
            out = np.zeros_like(x)
            inside = w > 0.0
            with np.errstate(over="ignore", under="ignore", divide="ignore"):
                out[inside] = np.exp(-sigma * x[inside] ** 2 / w[inside] ** lam)
            return out

        # Cumulative integral of shape over [0, 1] on panels graded toward x = 1 (where
        # the velocity falls steeply for small sigma or lam), Gauss-Legendre nodes.
        nodes, weights = leggauss(NODES)
        graded = 1.0 - 10.0 ** -np.arange(2.0, 15.0, 0.5)
        edges = sorted_unique(np.concatenate((np.linspace(0.0, 1.0, PANELS + 1), graded)))
        half = 0.5 * (edges[1:] - edges[:-1])
        mid = 0.5 * (edges[1:] + edges[:-1])
        panel = (shape(mid[:, None] + half[:, None] * nodes) * weights).sum(axis=1) * half
        cumulative = np.concatenate(([0.0], np.cumsum(panel)))
        v_c = 1.0 / cumulative[-1]  # integral over tau in [0, 1] equals integral over x in [0, 1]

        def integral(x_abs: np.ndarray) -> np.ndarray:
            """int_0^X shape(y) dy for X in [0, 1]."""
            k = np.clip(np.searchsorted(edges, x_abs, side="right") - 1, 0, len(edges) - 2)
            left = edges[k]
            h = 0.5 * (x_abs - left)
            partial = (shape((left + h)[:, None] + h[:, None] * nodes) * weights).sum(axis=1) * h
            return cumulative[k] + partial

        def evaluate(tau: np.ndarray, order: int) -> np.ndarray:
            x = 2.0 * tau - 1.0
            if order == 0:
                return 0.5 + np.sign(x) * 0.5 * v_c * integral(np.abs(x))
            out = np.zeros_like(x)
            w = 1.0 - x * x
            live = w > 0.0
            x, w = x[live], w[live]
            x2 = x * x
            with np.errstate(over="ignore", under="ignore", divide="ignore"):
                p = w**-lam  # the one power: w^(-lam - k) = p / w^k
                e = np.exp(-sigma * x2 * p)
            keep = e > 0.0
            if not keep.all():
                x, w, x2, p, e = x[keep], w[keep], x2[keep], p[keep], e[keep]
                live[live] = keep
            if order == 1:
                out[live] = v_c * e
                return out
            r = p / w  # w^(-lam - 1)
            f1 = 2 * x * p + 2 * lam * x * x2 * r
            if order == 2:
                out[live] = 2 * v_c * (-sigma * f1) * e
                return out
            r2 = r / w  # w^(-lam - 2)
            f2 = 2 * p + 10 * lam * x2 * r + 4 * lam * (lam + 1) * x2 * x2 * r2
            if order == 3:
                out[live] = 4 * v_c * (sigma**2 * f1**2 - sigma * f2) * e
                return out
            f3 = (24 * lam * x * r + 36 * lam * (lam + 1) * x * x2 * r2
                  + 8 * lam * (lam + 1) * (lam + 2) * x * x2 * x2 * (r2 / w))
            out[live] = 8 * v_c * (-(sigma**3) * f1**3 + 3 * sigma**2 * f1 * f2
                                   - sigma * f3) * e
            return out

        self._v_c = v_c
        return [Piece(0.0, 1.0, evaluate)], INFINITELY_SMOOTH

    def closed_form_coefficients(self) -> dict[str, float]:
        return {"C_v": self._v_c}


