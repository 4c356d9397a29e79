"""Exact piece types: a polynomial plus a sum of sines, evaluated to any derivative order."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace

import numpy as np

from sizer.laws.base import Piece


def trig_poly_piece(
    start: float,
    end: float,
    poly: Sequence[float] = (),
    sines: Sequence[tuple[float, float, float]] = (),
    origin: float = 0.0,
) -> Piece:
    """q(tau) = sum_k poly[k]*(tau - origin)^k + sum A*sin(w*tau + phi) on [start, end].

    Covers the cycloidal, harmonic and Fourier laws and the pieces of the modified
    trapezoidal and modified sinusoidal laws (book sec. 2.2, 2.4, 3.7, 3.8) as well as
    the polynomial pieces of the trapezoid and double S (sec. 3.2, 3.4).
    """
    coef = np.asarray(poly, dtype=float) if len(poly) else np.zeros(1)
    sines = tuple(sines)
    derivatives = [coef.tolist()]  # polynomial coefficients of each derivative order, built once

    def evaluate(tau: np.ndarray, order: int) -> np.ndarray:
        while len(derivatives) <= order:
            derivatives.append(_derivative(derivatives[-1]))
        out = _horner(derivatives[order], tau - origin) + 0.0  # (-0.0 read as 0.0)
        for amplitude, omega, phase in sines:
            out = out + amplitude * omega**order * np.sin(omega * tau + phase + order * math.pi / 2)
        return out

    return Piece(start, end, evaluate, None if sines else len(coef) - 1)


def _derivative(coef: list[float]) -> list[float]:
    """Coefficients of the derivative of sum coef[k] x^k (numpy's polyder, as lists)."""
    if len(coef) == 1:
        return [coef[0] * 0.0]
    return [k * c for k, c in enumerate(coef[1:], start=1)]


def _horner(coef: list[float], x: np.ndarray) -> np.ndarray:
    """sum coef[k] x^k by Horner's scheme, the operations of numpy's polyval in its order
    (its result, without its per-call overhead: a law makes many small calls)."""
    out = coef[-1] + x * 0.0
    for c in coef[-2::-1]:
        out = c + out * x
    return out


def constant_jerk_pieces(
    segments: Sequence[tuple[float, float | None, float]], end: float
) -> list[Piece]:
    """Polynomial pieces from (duration, acceleration at start or None, jerk) segments.

    Integrates the jerk exactly from rest at tau = 0; an acceleration given at the start
    of a segment is a step (a jerk impulse), None keeps it continuous. Segments of zero
    length are skipped; the last piece ends exactly at ``end`` (no rounding drift).
    """
    pieces = []
    t = q = v = a = 0.0
    for duration, a_start, jerk in segments:
        if a_start is not None:
            a = a_start
        if duration > 0.0:
            pieces.append(trig_poly_piece(t, t + duration, (q, v, a / 2.0, jerk / 6.0), origin=t))
            d = duration
            q, v, a = (q + v * d + a * d * d / 2.0 + jerk * d**3 / 6.0,
                       v + a * d + jerk * d * d / 2.0,
                       a + jerk * d)
            t += d
    pieces[-1] = replace(pieces[-1], end=end)
    return pieces
