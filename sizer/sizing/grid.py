"""A law's fixed sampling and quadrature grid on [0, 1], computed once per law.

The intervals and nodes are the law's one integration scheme (sizer.laws.quadrature) at
the engine's resolution (ENGINE_RESOLUTION); each interval carries Gauss-Legendre nodes
and weights and the one-sided values of the normalized velocity and acceleration at its
ends. Polynomial pieces (trapezoid, double S, polynomial laws) are integrated exactly
with few nodes (their degree plus one), the other pieces to machine
precision; all intervals of a law carry the same count (the largest its pieces need:
arrays are rectangular).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from sizer.laws import MotionLaw
from sizer.laws.quadrature import PieceIntervals, Resolution, law_intervals
from sizer.numerics.arrays import sorted_unique

POLYNOMIAL_INTERVALS = 16
"""Uniform intervals per polynomial piece. One would be exact for the integrals, but the
engine needs more (sizer.sizing.cycle): it finds the power-flow reversals of a stage
inside a move from the signs of the output torque at interval ends (a reversal and its
return within one interval go unseen: with one interval per piece the RMS torque of
3-4-5 and 4-5-6-7 laws through a reversing stage was 5e-4 low against
tests/scalar_reference.py), and it samples the load's torque at the nodes without
refinement (then 4.5e-3 below its peak on a 3-4-5 law, tests/test_exact_peaks.py
allows 1e-3)."""

SMOOTH_INTERVALS = 16
"""Uniform base intervals per non-polynomial piece (before grading and halving), for
the same reasons."""

ENGINE_RESOLUTION = Resolution(POLYNOMIAL_INTERVALS, SMOOTH_INTERVALS)
"""Node counts as the laws' own rule: d + 1 on a polynomial piece of degree d, exact for
q_N^2 and up (d would do for the torques' squares, but the load's torque sampled at the
nodes of a 3-4-5 law then misses its peak by 1.3e-3, 6.8e-4 with d + 1)."""


@dataclass(frozen=True)
class LawGrid:
    """Base intervals of a law with nodes, weights and normalized v, a (arrays are (G, n));
    v, a and j at both ends of each interval, one-sided on its piece ((G, 2))."""

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
    end_jerk: np.ndarray

    @property
    def size(self) -> int:
        return len(self.left)


@lru_cache(maxsize=256)
def law_grid(law: MotionLaw) -> LawGrid:
    """The grid of a law (cached: laws hash by their canonical spec)."""
    parts = law_intervals(law, ENGINE_RESOLUTION)
    count = max(part.nodes for part in parts)
    rules = [part.gauss(count) for part in parts]
    left = np.concatenate([part.edges[:-1] for part in parts])
    right = np.concatenate([part.edges[1:] for part in parts])
    piece = np.concatenate([np.full(len(part.edges) - 1, part.index) for part in parts])
    nodes = np.concatenate([tau for tau, _ in rules])
    weights = np.concatenate([weight for _, weight in rules])
    # nodes are evaluated on their interval's piece: in an interval a few ulps wide a node
    # may round onto the next piece's start, where law.derivative would switch pieces
    on_pieces = [_edge_and_node_values(law, part, tau)
                 for part, (tau, _) in zip(parts, rules, strict=True)]
    end_v, end_a, end_j, velocity, acceleration = (
        np.concatenate(columns) for columns in zip(*on_pieces, strict=True))
    return LawGrid(law, left, right, piece, nodes, weights, velocity, acceleration,
                   end_v, end_a, end_j)


def _edge_and_node_values(law: MotionLaw, part: PieceIntervals, tau: np.ndarray
                          ) -> tuple[np.ndarray, ...]:
    """v_N, a_N and j_N of one piece (one-sided at its ends) at its intervals' ends,
    (intervals, 2) arrays, and v_N, a_N at their nodes ``tau``, (intervals, nodes)."""
    edges = len(part.edges)
    at = np.concatenate((part.edges, tau.ravel()))
    v, a = (law.piece_derivative(part.index, at, order) for order in (1, 2))
    j = law.piece_derivative(part.index, part.edges, 3)
    return (np.stack((v[:edges - 1], v[1:edges]), axis=1),
            np.stack((a[:edges - 1], a[1:edges]), axis=1),
            np.stack((j[:-1], j[1:]), axis=1),
            v[edges:].reshape(tau.shape), a[edges:].reshape(tau.shape))


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
        self.groups = [(int(i), np.nonzero(flat == i)[0]) for i in sorted_unique(flat)]

    def __call__(self, tau: np.ndarray, order: int) -> np.ndarray:
        return self.orders(tau, (order,))[0]

    def orders(self, tau: np.ndarray, orders: tuple[int, ...]) -> tuple[np.ndarray, ...]:
        """The derivatives of the given orders at tau, each point clamped into its piece
        once for all of them (MotionLaw.piece_derivative of each)."""
        flat = tau.ravel()
        if len(self.groups) == 1:  # every point on one piece: no gathering
            piece = self.law.pieces[self.groups[0][0]]
            at = piece.clamp(flat)
            out = [np.empty(flat.shape) for _ in orders]
            for values, k in zip(out, orders, strict=True):
                values[:] = piece.evaluate(at, k)
            return tuple(values.reshape(self.shape) for values in out)
        out = [np.empty(flat.shape) for _ in orders]
        for index, where in self.groups:
            piece = self.law.pieces[index]
            at = piece.clamp(flat[where])
            for values, k in zip(out, orders, strict=True):
                values[where] = piece.evaluate(at, k)
        return tuple(values.reshape(self.shape) for values in out)


def piecewise(law: MotionLaw, tau: np.ndarray, piece: np.ndarray, order: int) -> np.ndarray:
    """Derivative of the given order at tau, each point evaluated on its own piece index."""
    return PieceEvaluator(law, piece)(tau, order)
