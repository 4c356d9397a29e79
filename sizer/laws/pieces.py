"""The pieces of a law and what its analyses read of it; exact piece types: a polynomial
plus a sum of sines, evaluated to any derivative order."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Protocol

import numpy as np

if TYPE_CHECKING:
    from sizer.laws.piece_forms import PieceForms
    from sizer.laws.piece_table import PieceTable

PieceFunction = Callable[[np.ndarray, int], np.ndarray]
"""Evaluate the derivative of the given order of q_N at an array of tau in the piece."""


@dataclass(frozen=True)
class Piece:
    """One smooth piece of a law: q_N restricted to [start, end].

    ``degree`` is the degree of q_N on the piece when it is a polynomial (the trapezoid,
    double S and polynomial laws), None otherwise; quadrature is then exact with a node
    count chosen from it. ``intervals``, when set, is the most uniform sub-intervals a
    scan or a grid of this piece needs (a law of many short polynomial pieces, a cam
    table, shares a fixed budget among them: sizer.laws.data_law); None: the caller's.
    ``form``, when set, is the piece's exact closed form (a polynomial plus sines, as
    :func:`trig_poly_piece` builds it): what an export that writes coefficients reads
    (sizer.export.coefficient_segments). ``mirror_of``, when set, is the piece this one
    reflects (:func:`mirrored`). sizer.laws.piece_forms evaluates many pieces at once
    from these, with the arithmetic of their own ``evaluate``.
    """

    start: float
    end: float
    evaluate: PieceFunction
    degree: int | None = None
    intervals: int | None = None
    form: TrigPolyForm | None = None
    mirror_of: Piece | None = None

    def clamp(self, tau: np.ndarray) -> np.ndarray:
        """tau moved into [start, end]: a point one ulp outside reads the end's value."""
        # np.minimum(np.maximum()) is np.clip's result without its ~10 us of overhead
        return np.minimum(np.maximum(tau, self.start), self.end)


@dataclass(frozen=True)
class TrigPolyForm:
    """q(tau) = sum_k poly[k] * (tau - origin)^k + sum A * sin(w * tau + phi) for
    (A, w, phi) in ``sines``: a piece's exact closed form."""

    poly: tuple[float, ...]
    origin: float = 0.0
    sines: tuple[tuple[float, float, float], ...] = ()

    def mirrored(self) -> TrigPolyForm:
        """The form of 1 - q(1 - tau): (1 - tau - o)^k = (-1)^k (tau - (1 - o))^k, and
        -A sin(w (1 - tau) + phi) = A sin(w tau - w - phi)."""
        poly = tuple((1.0 if k == 0 else 0.0) - (-1.0) ** k * c
                     for k, c in enumerate(self.poly))
        return TrigPolyForm(poly, 1.0 - self.origin,
                            tuple((a, w, -w - phi) for a, w, phi in self.sines))


class LawShape(Protocol):
    """What a law's analyses (sizer.laws.coefficients, quadrature, linear_peaks) read of
    it: its pieces and their derivatives. sizer.laws.base.MotionLaw is one; the analyses
    depend on this, not on the law class, which caches their results per law."""

    @property
    def law_id(self) -> str: ...
    @property
    def max_order(self) -> int: ...
    @property
    def steep_ends(self) -> bool: ...
    @property
    def pieces(self) -> tuple[Piece, ...]: ...
    def fine_points(self) -> tuple[float, ...]: ...
    def piece_table(self) -> PieceTable | None: ...
    def piece_forms(self) -> PieceForms | None: ...
    def piece_derivative(self, index: int, tau: np.ndarray | float, order: int) -> np.ndarray: ...
    def outside(self, order: int) -> tuple[float, float]: ...


def mirrored(pieces: Sequence[Piece]) -> list[Piece]:
    """Complete the first half [0, 1/2] of a symmetric law: q_N(tau) = 1 - q_N(1 - tau).

    The k-th derivative of 1 - f(1 - tau) is -(-1)^k f^(k)(1 - tau) (book sec. 5.1).
    """

    def reflect(piece: Piece) -> Piece:
        start, end = 1.0 - piece.end, 1.0 - piece.start

        def evaluate(tau: np.ndarray, order: int) -> np.ndarray:
            # 1 - (1 - end) may differ from end by an ulp: the reflected piece's own ends
            # map exactly onto the piece's ends, and every argument stays in the piece
            u = np.where(tau <= start, piece.end, np.where(tau >= end, piece.start, 1.0 - tau))
            value = piece.evaluate(piece.clamp(u), order)
            if order == 0:
                return 1.0 - value
            return -((-1.0) ** order) * value

        form = None if piece.form is None else piece.form.mirrored()
        return Piece(start, end, evaluate, piece.degree, piece.intervals, form, mirror_of=piece)

    return list(pieces) + [reflect(p) for p in reversed(pieces)]


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

    waves: dict[int, list[tuple[float, float, float, float]]] = {}  # per order, built once

    def evaluate(tau: np.ndarray, order: int) -> np.ndarray:
        while len(derivatives) <= order:
            derivatives.append(polynomial_derivative(derivatives[-1]))
        out = _horner(derivatives[order], tau - origin) + 0.0  # (-0.0 read as 0.0)
        if order not in waves:
            waves[order] = [(amplitude * omega**order, omega, phase, order * math.pi / 2)
                            for amplitude, omega, phase in sines]
        for scale, omega, phase, quarter in waves[order]:
            out = out + scale * np.sin(omega * tau + phase + quarter)
        return out

    form = TrigPolyForm(tuple(float(c) for c in coef), float(origin),
                        tuple((float(a), float(w), float(p)) for a, w, p in sines))
    return Piece(start, end, evaluate, None if sines else len(coef) - 1, form=form)


def polynomial_derivative(coef: list[float]) -> list[float]:
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
