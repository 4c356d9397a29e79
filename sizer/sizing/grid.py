"""A law's fixed sampling and quadrature grid on [0, 1], computed once per law.

Each piece is cut into base intervals (uniform, graded toward the ends for laws with
steep ends); each interval carries Gauss-Legendre nodes and weights and the one-sided
values of the normalized velocity and acceleration at its ends. Polynomial pieces of
the trapezoid or double S are integrated exactly; smooth pieces to machine precision.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from numpy.polynomial.legendre import leggauss

from sizer.laws import MotionLaw

INTERVALS_PER_PIECE = 16
NODES = 12
GRADED_DECADES = np.arange(2.0, 11.0)
FINE_DECADES = np.arange(1.0, 11.0, 0.25)
"""Graded edges toward a law's fine points: four per decade, from 1e-1 to 1e-10 of the
piece width (the profile varies there on scales down to its distance from the point)."""


@dataclass(frozen=True)
class LawGrid:
    """Base intervals of a law with nodes, weights and normalized v, a (arrays are (G, n))."""

    law: MotionLaw
    left: np.ndarray
    right: np.ndarray
    piece: np.ndarray
    nodes: np.ndarray
    weights: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    end_velocity: np.ndarray
    end_acceleration: np.ndarray

    @property
    def size(self) -> int:
        return len(self.left)


def _edges(law: MotionLaw, start: float, end: float) -> np.ndarray:
    """Uniform edges over a piece, graded by decades toward its ends (steep_ends laws)
    and toward the law's fine points inside or at the ends of the piece."""
    edges = [np.linspace(start, end, INTERVALS_PER_PIECE + 1)]
    graded = (end - start) * 10.0**-GRADED_DECADES
    if law.steep_ends:
        edges += [start + graded, end - graded]
    fine = (end - start) * 10.0**-FINE_DECADES
    for point in law.fine_points():
        if start <= point <= end:
            edges += [np.array([point]), point - fine, point + fine]
    edges = np.concatenate(edges)
    return np.unique(edges[(edges >= start) & (edges <= end)])


@lru_cache(maxsize=256)
def law_grid(law: MotionLaw) -> LawGrid:
    """The grid of a law (cached: laws hash by their canonical spec)."""
    x, w = leggauss(NODES)
    lefts, rights, pieces = [], [], []
    for index, piece in enumerate(law.pieces):
        edges = _edges(law, piece.start, piece.end)
        lefts.append(edges[:-1])
        rights.append(edges[1:])
        pieces.append(np.full(len(edges) - 1, index))
    left, right, piece = np.concatenate(lefts), np.concatenate(rights), np.concatenate(pieces)
    half = 0.5 * (right - left)
    nodes = (0.5 * (left + right))[:, None] + half[:, None] * x
    weights = half[:, None] * w
    end_v = np.empty((len(left), 2))
    end_a = np.empty((len(left), 2))
    for index in range(len(law.pieces)):
        mask = piece == index
        for side, where in enumerate((left[mask], right[mask])):
            end_v[mask, side] = law.piece_derivative(index, where, 1)
            end_a[mask, side] = law.piece_derivative(index, where, 2)
    # nodes are evaluated on their interval's piece: in an interval a few ulps wide a node
    # may round onto the next piece's start, where law.derivative would switch pieces
    on_pieces = PieceEvaluator(law, np.broadcast_to(piece[:, None], nodes.shape))
    return LawGrid(law, left, right, piece, nodes, weights, on_pieces(nodes, 1),
                   on_pieces(nodes, 2), end_v, end_a)


class PieceEvaluator:
    """Evaluates a law at points each bound to its own piece (one-sided at piece ends).

    The grouping of points by piece is computed once, for repeated evaluations at moving
    points that stay in their pieces (root and peak searches). Each point is clamped into
    its piece's interval: a search point a rounding error outside reads the end's
    one-sided value, never the piece's extrapolation (with a steep double S that overshoot
    exceeded C_a and put a check's slack below zero).
    """

    def __init__(self, law: MotionLaw, piece: np.ndarray) -> None:
        self.law = law
        self.shape = piece.shape
        flat = piece.ravel()
        self.groups = [(int(i), np.nonzero(flat == i)[0]) for i in np.unique(flat)]

    def __call__(self, tau: np.ndarray, order: int) -> np.ndarray:
        flat = tau.ravel()
        out = np.empty(flat.shape)
        for index, where in self.groups:
            piece = self.law.pieces[index]
            out[where] = self.law.piece_derivative(index, piece.clamp(flat[where]), order)
        return out.reshape(self.shape)


def piecewise(law: MotionLaw, tau: np.ndarray, piece: np.ndarray, order: int) -> np.ndarray:
    """Derivative of the given order at tau, each point evaluated on its own piece index."""
    return PieceEvaluator(law, piece)(tau, order)
