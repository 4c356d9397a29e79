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
from dataclasses import dataclass, field

import numpy as np

from sizer.laws.pieces import Piece, TrigPolyForm, polynomial_derivative


@dataclass(frozen=True, eq=False)
class PieceForms:
    """Pieces [starts[i], ends[i]] of a law, each the closed form ``forms[i]`` read at
    tau (``mirror[i]`` False) or reflected (True: q = 1 - f(1 - tau) with f on
    [inner_starts[i], inner_ends[i]]). Each derivative order's rows are built on first
    use (:meth:`rows`)."""

    starts: np.ndarray
    ends: np.ndarray
    mirror: np.ndarray
    inner_starts: np.ndarray
    inner_ends: np.ndarray
    origins: np.ndarray
    forms: tuple[TrigPolyForm, ...]
    _rows: dict[int, OrderRows] = field(default_factory=dict, repr=False)
    _chains: list[list[list[float]]] = field(default_factory=list, repr=False)

    @classmethod
    def of(cls, pieces: Sequence[Piece]) -> PieceForms | None:
        """The table of these pieces, or None where a piece is not a polynomial plus
        sines (or the reflection of one)."""
        forms: list[TrigPolyForm] = []
        inner: list[Piece] = []
        for piece in pieces:
            source = piece if piece.mirror_of is None else piece.mirror_of
            if source.form is None or source.mirror_of is not None:
                return None
            forms.append(source.form)
            inner.append(source)
        return cls(np.array([p.start for p in pieces]), np.array([p.end for p in pieces]),
                   np.array([p.mirror_of is not None for p in pieces]),
                   np.array([p.start for p in inner]), np.array([p.end for p in inner]),
                   np.array([f.origin for f in forms]), tuple(forms))

    @classmethod
    def stacked(cls, tables: Sequence[PieceForms]) -> PieceForms:
        """Several laws' tables as one, their pieces numbered in turn (law k's piece i is
        piece i + the pieces of the laws before it): several laws evaluated at once."""
        def joined(name: str) -> np.ndarray:
            return np.concatenate([getattr(f, name) for f in tables])

        return cls(joined("starts"), joined("ends"), joined("mirror"), joined("inner_starts"),
                   joined("inner_ends"), joined("origins"),
                   tuple(form for f in tables for form in f.forms))

    def rows(self, order: int) -> OrderRows:
        """The ``order``-th derivative's coefficients and sines, a row per piece."""
        if order not in self._rows:
            chains = self._chains
            while len(chains) <= order:  # each derivative from the one before, as the
                # pieces' closures build them (the same function, the same floats)
                chains.append([polynomial_derivative(c) for c in chains[-1]] if chains
                              else [list(form.poly) for form in self.forms])
            self._rows[order] = OrderRows.of(self.forms, order, chains[order])
        return self._rows[order]

    def values(self, piece: np.ndarray, tau: np.ndarray,
               orders: Sequence[int]) -> tuple[np.ndarray, ...]:
        """q_N^(k) for each k of ``orders`` at each (piece, tau) (1-D arrays of one length),
        tau clamped into its piece (one-sided values at the piece ends)."""
        start, end = self.starts[piece], self.ends[piece]
        t = np.minimum(np.maximum(tau, start), end)
        mirror = self.mirror[piece]
        mirrored = bool(mirror.any())
        if mirrored:
            inner_start, inner_end = self.inner_starts[piece], self.inner_ends[piece]
            u = np.where(t <= start, inner_end, np.where(t >= end, inner_start, 1.0 - t))
            t = np.where(mirror, np.minimum(np.maximum(u, inner_start), inner_end), t)
        x = t - self.origins[piece]
        out = []
        for order in orders:
            table = self.rows(order)
            rows = table.poly[piece]
            value = rows[:, -1] + x * 0.0
            for column in range(rows.shape[1] - 2, -1, -1):
                value = rows[:, column] + value * x
            value = value + 0.0  # (-0.0 read as 0.0, as the pieces do)
            for s in range(table.scale.shape[1]):
                value = value + table.scale[piece, s] * np.sin(
                    table.omega[piece, s] * t + table.phase[piece, s] + table.quarter)
            if mirrored:
                value = np.where(mirror, 1.0 - value if order == 0
                                 else -((-1.0) ** order) * value, value)
            out.append(value)
        return tuple(out)


@dataclass(frozen=True)
class OrderRows:
    """One derivative order of every piece: ``poly`` (pieces, width) the polynomial's
    coefficients (zeros at the high end), ``scale``, ``omega``, ``phase`` (pieces, sines)
    its sines A w^k sin(w tau + phi + k pi/2) (zero amplitudes at the end)."""

    poly: np.ndarray
    scale: np.ndarray
    omega: np.ndarray
    phase: np.ndarray
    quarter: float

    @classmethod
    def of(cls, forms: Sequence[TrigPolyForm], order: int,
           rows: Sequence[list[float]]) -> OrderRows:
        """The rows of ``forms`` at ``order``, ``rows`` their polynomials' coefficients
        there (:meth:`PieceForms.rows` keeps each derivative's to build the next)."""
        width = max(len(r) for r in rows)
        count = max(len(form.sines) for form in forms)
        scale, omega, phase = (np.zeros((len(forms), count)) for _ in range(3))
        for i, form in enumerate(forms):
            for s, (amplitude, w, phi) in enumerate(form.sines):
                scale[i, s], omega[i, s], phase[i, s] = amplitude * w**order, w, phi
        return cls(np.array([r + [0.0] * (width - len(r)) for r in rows]), scale, omega,
                   phase, order * math.pi / 2)

