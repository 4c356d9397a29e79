"""The one integration scheme of a law: fixed Gauss-Legendre nodes per smooth piece.

Integrals over a move (the RMS coefficients of sec. 6.2, and any integral the sizing
engine needs of q_N and its derivatives) are weighted sums over these nodes, built once
per law (``MotionLaw.quadrature``).

- A polynomial piece of degree d (trapezoid, double S, polynomial laws) gets one
  interval with d + 1 nodes: exact for the square of q_N and of every derivative
  (a polynomial of degree <= 2d <= 2(d + 1) - 1).
- Any other piece (sines, the exponential, elliptic, modified cycloidal laws) is cut into
  base intervals (a few uniform ones, graded by decades toward the law's fine points, and
  toward the piece ends for laws with steep ends), each split into 2^k equal parts with
  NODES nodes on each. k is the first level at which the integrals of v_N^2 and a_N^2
  over the piece agree with the previous level to CONVERGED relative, or at which the
  change stops shrinking (the Gauss rules converge like h^(2 NODES) on analytic pieces,
  so a change that halving does not cut by 16 is the rounding of the law's own values,
  e.g. an elliptic law with n = 1000): a fixed rule, chosen once per law.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.polynomial.legendre import leggauss

from sizer.laws.base import MotionLaw, Piece

NODES = 20
"""Gauss-Legendre nodes per interval of a non-polynomial piece."""

BASE_INTERVALS = 4
"""Uniform base intervals of a non-polynomial piece before grading and splitting."""

GRADED_DECADES = 12
"""Decades of geometric grading toward a fine point or a steep end (two edges a decade)."""

CONVERGED = 1e-15
"""Relative agreement of two successive levels at which a piece's rule is accepted."""

MAX_LEVEL = 8
"""Most halvings of the base intervals (2^8 parts each)."""


@dataclass(frozen=True)
class QuadratureRule:
    """Nodes ``tau``, weights and the piece index of each node; a piece's nodes are
    contiguous, in the order of the pieces (``bounds[i]:bounds[i + 1]``)."""

    tau: np.ndarray
    weight: np.ndarray
    piece: np.ndarray
    bounds: np.ndarray

    def values(self, law: MotionLaw, order: int) -> np.ndarray:
        """q_N^(order) at the nodes, each piece evaluated on its own nodes (one-sided)."""
        out = np.empty_like(self.tau)
        for index in range(len(law.pieces)):
            part = slice(self.bounds[index], self.bounds[index + 1])
            out[part] = law.piece_derivative(index, self.tau[part], order)
        return out

    def integral(self, values: np.ndarray) -> float:
        """The integral over [0, 1] of a function given by its values at the nodes."""
        return float(values @ self.weight)


def quadrature_rule(law: MotionLaw) -> QuadratureRule:
    """The fixed rule of a law (use ``law.quadrature``, which caches it)."""
    taus, weights = [], []
    for index, piece in enumerate(law.pieces):
        tau, weight = _piece_rule(law, index, piece)
        taus.append(tau)
        weights.append(weight)
    sizes = [len(t) for t in taus]
    bounds = np.concatenate(([0], np.cumsum(sizes)))
    piece = np.repeat(np.arange(len(sizes)), sizes)
    return QuadratureRule(np.concatenate(taus), np.concatenate(weights), piece, bounds)


def _gauss(edges: np.ndarray, nodes: int) -> tuple[np.ndarray, np.ndarray]:
    """Composite Gauss-Legendre nodes and weights over the intervals of ``edges``."""
    x, w = leggauss(nodes)
    half = 0.5 * np.diff(edges)
    mid = 0.5 * (edges[:-1] + edges[1:])
    return (mid[:, None] + half[:, None] * x).ravel(), (half[:, None] * w).ravel()


def base_edges(law: MotionLaw, piece: Piece) -> np.ndarray:
    """Uniform edges over a piece, graded by decades toward the law's fine points in it
    (both sides) and toward the piece ends for laws with steep ends."""
    width = piece.end - piece.start
    graded = width * 10.0 ** -np.arange(1.0, GRADED_DECADES + 0.25, 0.5)
    parts = [np.linspace(piece.start, piece.end, BASE_INTERVALS + 1)]
    if law.steep_ends:
        parts += [piece.start + graded, piece.end - graded]
    for point in law.fine_points():
        if piece.start <= point <= piece.end:
            parts += [np.array([point]), point - graded, point + graded]
    edges = np.concatenate(parts)
    return np.unique(edges[(edges >= piece.start) & (edges <= piece.end)])


def _piece_rule(law: MotionLaw, index: int, piece: Piece) -> tuple[np.ndarray, np.ndarray]:
    if piece.degree is not None:
        return _gauss(np.array([piece.start, piece.end]), piece.degree + 1)
    base = base_edges(law, piece)
    previous, change = None, None
    for level in range(MAX_LEVEL + 1):
        parts = 2**level
        steps = np.arange(parts) / parts
        edges = np.append((base[:-1, None] + np.diff(base)[:, None] * steps).ravel(), base[-1])
        tau, weight = _gauss(edges, NODES)
        sums = np.array([law.piece_derivative(index, tau, order) ** 2 @ weight
                         for order in (1, 2)])
        if previous is not None:
            new_change = np.abs(sums - previous) / np.maximum(np.abs(sums), 1e-300)
            if np.all(new_change <= CONVERGED) or (
                    change is not None and np.all(new_change > change / 16.0)):
                break
            change = new_change
        previous = sums
    return tau, weight
