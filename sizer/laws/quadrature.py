"""The one integration scheme of a law: Gauss-Legendre nodes on intervals of its pieces.

Integrals over a move (the RMS coefficients of sec. 6.2, and the integrals the sizing
engine needs of q_N and its derivatives: sizer.sizing.grid) are weighted sums over the
nodes of a law's intervals. The intervals and nodes are defined here once (the grading
rules, the node counts, the level of refinement); the callers only choose how many
uniform intervals a piece starts from (:class:`Resolution`).

- A polynomial piece of degree d (trapezoid, double S, polynomial laws) gets its uniform
  intervals (one for the laws' coefficients) with the fewest nodes exact for the square
  of every derivative of q_N from a lowest order on: the square of q_N^(k) has degree
  2(d - k), and n nodes are exact to degree 2n - 1, so n = d - k + 1 (d + 1 from q_N
  itself, d from the velocity on).
- Any other piece (sines, the exponential, elliptic, modified cycloidal laws) is cut into
  base intervals (uniform ones, graded by decades toward the law's fine points, and
  toward the piece ends for laws with steep ends), each split into its own 2^k equal parts
  with NODES nodes on each. k is the first level whose integrals of v_N^2 and a_N^2 over
  the base interval agree with the next level's to CONVERGED of its share of the piece,
  or past which the change stops shrinking while below STALLED (the Gauss rules converge
  like h^(2 NODES) on analytic pieces, so a change that halving does not cut by 16 is the
  rounding of the law's own values, e.g. an elliptic law with n = 1000): a fixed rule,
  chosen once per law and resolution.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import numpy as np
from numpy.polynomial.legendre import leggauss

from sizer.laws.pieces import LawShape, Piece
from sizer.numerics.arrays import sorted_unique

NODES = 12
"""Gauss-Legendre nodes per interval of a non-polynomial piece."""

BASE_INTERVALS = 4
"""Uniform base intervals of a non-polynomial piece (the laws' rule) before grading and
splitting."""

GRADED_DECADES = 12
"""Decades of geometric grading toward a fine point or a steep end (one edge a decade)."""

CONVERGED = 1e-15
"""Relative agreement of two successive levels at which a base interval's level is
accepted."""

STALLED = 1e-12
"""Largest change between levels read as rounding when halving stops cutting it."""

MAX_LEVEL = 8
"""Most halvings of a base interval (2^8 parts)."""


@dataclass(frozen=True)
class Resolution:
    """How finely a caller wants a law cut: the uniform intervals a polynomial piece gets
    (exact with one) and those a non-polynomial piece starts from, and the lowest order
    of derivative whose square must be exact on polynomial pieces."""

    polynomial_intervals: int = 1
    smooth_intervals: int = BASE_INTERVALS
    lowest_order: int = 0


LAW_RESOLUTION = Resolution()
"""The laws' own rule: one interval per polynomial piece, exact for q_N^2 and up."""


@dataclass(frozen=True)
class PieceIntervals:
    """The intervals of one piece (``edges``, increasing) and the nodes on each."""

    index: int
    edges: np.ndarray
    nodes: int

    def gauss(self, nodes: int | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Nodes and weights, arrays (intervals, nodes), with the piece's own node count
        or a larger ``nodes`` (as exact: the engine's rectangular grid)."""
        return gauss(self.edges, self.nodes if nodes is None else nodes)


@dataclass(frozen=True)
class QuadratureRule:
    """Nodes ``tau``, weights and the piece index of each node; a piece's nodes are
    contiguous, in the order of the pieces (``bounds[i]:bounds[i + 1]``)."""

    tau: np.ndarray
    weight: np.ndarray
    piece: np.ndarray
    bounds: np.ndarray

    def values(self, law: LawShape, order: int) -> np.ndarray:
        """q_N^(order) at the nodes, each piece evaluated on its own nodes (one-sided)."""
        forms = law.piece_forms()
        if forms is not None:  # every piece at once, the same values
            return forms.values(self.piece, self.tau, (order,))[0]
        out = np.empty_like(self.tau)
        for index in range(len(law.pieces)):
            part = slice(self.bounds[index], self.bounds[index + 1])
            out[part] = law.piece_derivative(index, self.tau[part], order)
        return out

    def integral(self, values: np.ndarray) -> float:
        """The integral over [0, 1] of a function given by its values at the nodes."""
        return float(values @ self.weight)


def quadrature_rule(law: LawShape) -> QuadratureRule:
    """The fixed rule of a law (use ``law.quadrature``, which caches it)."""
    taus, weights = [], []
    for part in law_intervals(law, LAW_RESOLUTION):
        tau, weight = part.gauss()
        taus.append(tau.ravel())
        weights.append(weight.ravel())
    sizes = [len(t) for t in taus]
    bounds = np.concatenate(([0], np.cumsum(sizes)))
    piece = np.repeat(np.arange(len(sizes)), sizes)
    return QuadratureRule(np.concatenate(taus), np.concatenate(weights), piece, bounds)


def law_intervals(law: LawShape, resolution: Resolution = LAW_RESOLUTION
                  ) -> list[PieceIntervals]:
    """The intervals and node counts of every piece of a law, in order."""
    return [piece_intervals(law, index, resolution) for index in range(len(law.pieces))]


def exact_nodes(degree: int, lowest_order: int) -> int:
    """Gauss-Legendre nodes exact for the square of q_N^(k), k >= lowest_order, on a
    polynomial piece of this degree (degree 2(d - k) <= 2n - 1)."""
    return max(1, degree - lowest_order + 1)


@cache
def gauss_legendre(nodes: int) -> tuple[np.ndarray, np.ndarray]:
    """numpy's Gauss-Legendre nodes and weights on [-1, 1], computed once per count
    (read-only: every law of a shape search asks for the same few)."""
    x, w = leggauss(nodes)
    x.setflags(write=False)
    w.setflags(write=False)
    return x, w


def gauss(edges: np.ndarray, nodes: int) -> tuple[np.ndarray, np.ndarray]:
    """Composite Gauss-Legendre nodes and weights, arrays (intervals, nodes)."""
    x, w = gauss_legendre(nodes)
    half = 0.5 * np.diff(edges)
    mid = 0.5 * (edges[:-1] + edges[1:])
    return mid[:, None] + half[:, None] * x, half[:, None] * w


def base_edges(law: LawShape, piece: Piece, uniform: int = BASE_INTERVALS) -> np.ndarray:
    """Uniform edges over a piece, graded by decades toward the law's fine points in it
    (both sides) and toward the piece ends for laws with steep ends."""
    width = piece.end - piece.start
    graded = width * 10.0 ** -np.arange(1.0, GRADED_DECADES + 0.5, 1.0)
    parts = [np.linspace(piece.start, piece.end, uniform + 1)]
    if law.steep_ends:
        parts += [piece.start + graded, piece.end - graded]
    for point in law.fine_points():
        if piece.start <= point <= piece.end:
            parts += [np.array([point]), point - graded, point + graded]
    edges = np.concatenate(parts)
    return sorted_unique(edges[(edges >= piece.start) & (edges <= piece.end)])


def piece_intervals(law: LawShape, index: int,
                    resolution: Resolution = LAW_RESOLUTION) -> PieceIntervals:
    """The intervals of one piece and the nodes on each (the rules of the module doc)."""
    piece = law.pieces[index]
    if piece.degree is not None:
        count = resolution.polynomial_intervals
        if piece.intervals is not None:
            count = max(1, min(count, piece.intervals))
        edges = np.linspace(piece.start, piece.end, count + 1)
        return PieceIntervals(index, edges, exact_nodes(piece.degree, resolution.lowest_order))
    return PieceIntervals(index, _refined(law, index, base_edges(law, piece,
                                                                 resolution.smooth_intervals)),
                          NODES)


def _refined(law: LawShape, index: int, base: np.ndarray) -> np.ndarray:
    """The base intervals of a smooth piece, each split into its own 2^k equal parts."""
    count = len(base) - 1
    width = np.diff(base)
    level = np.full(count, MAX_LEVEL)
    open_ = np.ones(count, dtype=bool)
    previous = change = None
    for k in range(MAX_LEVEL + 1):
        sums = _interval_sums(law, index, base, k)  # (2, count): v_N^2 and a_N^2
        if previous is not None:
            # the change is the coarser level's error (the finer one's is far smaller)
            # relative to the interval's share of the piece, at least an average share
            share = np.maximum(sums, sums.sum(axis=1, keepdims=True) / count)
            new_change = np.abs(sums - previous) / np.maximum(share, 1e-300)
            done = np.all(new_change <= CONVERGED, axis=0)
            if change is not None:  # rounding: halving no longer cuts the change
                done |= np.all((new_change > change / 16.0) & (new_change <= STALLED), axis=0)
            level[open_ & done] = k - 1
            open_ &= ~done
            if not open_.any():
                break
            change = new_change
        previous = sums
    parts = 2**level
    first = np.repeat(np.cumsum(parts) - parts, parts)  # each part's interval's first part
    step = np.arange(first.size) - first
    edges = np.repeat(base[:-1], parts) + np.repeat(width / parts, parts) * step
    return np.append(edges, base[-1])


def _interval_sums(law: LawShape, index: int, base: np.ndarray, level: int) -> np.ndarray:
    """Integrals of v_N^2 and a_N^2 over each base interval, cut into 2^level parts."""
    parts = 2**level
    steps = np.arange(parts + 1) / parts
    edges = (base[:-1, None] + np.diff(base)[:, None] * steps)  # (count, parts + 1)
    x, w = gauss_legendre(NODES)
    half = 0.5 * np.diff(edges, axis=1)
    tau = (0.5 * (edges[:, :-1] + edges[:, 1:]))[..., None] + half[..., None] * x
    weight = half[..., None] * w
    return np.stack([np.sum(law.piece_derivative(index, tau, order) ** 2 * weight, axis=(1, 2))
                     for order in (1, 2)])
