"""A law's pieces as data: every piece of a polynomial-plus-sines law evaluated at once.

The laws of sec. 2.2-3.8 built from :func:`sizer.laws.pieces.trig_poly_piece` (the
trapezoid, double S, modified trapezoidal and sinusoidal, the fifteen segments...) and
their mirrored halves (:func:`sizer.laws.pieces.mirrored`) are, piece by piece,
q(tau) = sum_k c_k (tau - origin)^k + sum A sin(w tau + phi). This table holds those
numbers as rows (one per piece, padded: zero coefficients at the high end, zero
amplitudes at the end), so points on different pieces are evaluated in one pass with no
Python loop per piece: the first step of the law as an array axis (issue 34).

Each value is the one the piece's own closure gives, bit for bit: the same clamping,
the same reflection of a mirrored piece (q = 1 - f(1 - tau), its k-th derivative
-(-1)^k f^(k)(1 - tau)), the same derivative coefficients (built by the same function)
and Horner's scheme in the same order; a padded zero coefficient or amplitude adds an
exact zero.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from sizer.laws.pieces import Piece, TrigPolyForm, polynomial_derivative


@dataclass(frozen=True, eq=False)
class PieceForms:
    """Pieces [starts[i], ends[i]] of a law, each the closed form ``form`` of piece
    ``source[i]`` read at tau (``mirror[i]`` False) or reflected (True: q = 1 - f(1 - tau)
    with f on [inner_starts[i], inner_ends[i]]). ``poly[k]`` (pieces, width) holds the
    k-th derivative's polynomial coefficients; ``waves[k]`` the (scale, omega, phase)
    columns (pieces, sines) of its sines and ``quarters[k]`` their phase shift k pi/2."""

    starts: np.ndarray
    ends: np.ndarray
    mirror: np.ndarray
    inner_starts: np.ndarray
    inner_ends: np.ndarray
    origins: np.ndarray
    poly: tuple[np.ndarray, ...]
    waves: tuple[tuple[np.ndarray, np.ndarray, np.ndarray], ...]
    quarters: tuple[float, ...]

    @classmethod
    def of(cls, pieces: Sequence[Piece], max_order: int) -> PieceForms | None:
        """The table of these pieces up to derivative ``max_order``, or None where a piece
        is not a polynomial plus sines (or the reflection of one)."""
        forms: list[TrigPolyForm] = []
        inner: list[Piece] = []
        for piece in pieces:
            source = piece if piece.mirror_of is None else piece.mirror_of
            if source.form is None or source.mirror_of is not None:
                return None
            forms.append(source.form)
            inner.append(source)
        poly, waves = [], []
        for order in range(max_order + 1):
            rows = [_derivative_coefficients(form, order) for form in forms]
            width = max(len(r) for r in rows)
            poly.append(np.array([r + [0.0] * (width - len(r)) for r in rows]))
            count = max(len(form.sines) for form in forms)
            columns = [np.zeros((len(forms), count)) for _ in range(3)]
            for i, form in enumerate(forms):
                for s, (amplitude, omega, phase) in enumerate(form.sines):
                    columns[0][i, s] = amplitude * omega**order
                    columns[1][i, s], columns[2][i, s] = omega, phase
            waves.append((columns[0], columns[1], columns[2]))
        return cls(np.array([p.start for p in pieces]), np.array([p.end for p in pieces]),
                   np.array([p.mirror_of is not None for p in pieces]),
                   np.array([p.start for p in inner]), np.array([p.end for p in inner]),
                   np.array([f.origin for f in forms]), tuple(poly), tuple(waves),
                   tuple(order * math.pi / 2 for order in range(max_order + 1)))

    def values(self, piece: np.ndarray, tau: np.ndarray,
               orders: Sequence[int]) -> tuple[np.ndarray, ...]:
        """q_N^(k) for each k of ``orders`` at each (piece, tau) (1-D arrays of one length),
        tau clamped into its piece (one-sided values at the piece ends)."""
        t = np.minimum(np.maximum(tau, self.starts[piece]), self.ends[piece])
        mirror = self.mirror[piece]
        if mirror.any():
            start, end = self.starts[piece], self.ends[piece]
            inner_start, inner_end = self.inner_starts[piece], self.inner_ends[piece]
            u = np.where(t <= start, inner_end, np.where(t >= end, inner_start, 1.0 - t))
            t = np.where(mirror, np.minimum(np.maximum(u, inner_start), inner_end), t)
        x = t - self.origins[piece]
        out = []
        for order in orders:
            rows = self.poly[order][piece]
            value = rows[:, -1] + x * 0.0
            for column in range(rows.shape[1] - 2, -1, -1):
                value = rows[:, column] + value * x
            value = value + 0.0  # (-0.0 read as 0.0, as the pieces do)
            scale, omega, phase = (w[piece] for w in self.waves[order])
            quarter = self.quarters[order]
            for s in range(scale.shape[1]):
                value = value + scale[:, s] * np.sin(omega[:, s] * t + phase[:, s] + quarter)
            if mirror.any():
                value = np.where(mirror, 1.0 - value if order == 0
                                 else -((-1.0) ** order) * value, value)
            out.append(value)
        return tuple(out)


def _derivative_coefficients(form: TrigPolyForm, order: int) -> list[float]:
    """The polynomial coefficients of the form's ``order``-th derivative, as the piece's
    closure builds them (the same function, the same floats)."""
    coefficients = list(form.poly) if form.poly else [0.0]
    for _ in range(order):
        coefficients = polynomial_derivative(coefficients)
    return coefficients
