"""The transform of a law's derivative, F(s) = int_0^1 q_N^(k)(tau) exp(-s tau) dtau.

At s = i 2 pi (f T) it is the Fourier transform of the normalized acceleration (k = 2)
that sec. 7.3 plots, |A(f)| = (h / T) |F(i 2 pi f T)| (sec. 7.3.4: a time scaling only
moves it along f T); at a complex s it is the convolution integral of the exact response
of a linear mode to the law (sec. 7.2). One numerical scheme for both: composite
Gauss-Legendre on the law's own quadrature intervals (sizer.laws.quadrature), each cut so
that the phase |s| dtau of a part stays below PHASE_STEP, with NODES nodes a part: on a
smooth piece times an exponential whose phase turns by at most 6 rad, 20 nodes are exact
to rounding.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from sizer.laws.base import MotionLaw
from sizer.laws.quadrature import gauss, law_intervals
from sizer.numerics.arrays import sorted_unique
from sizer.vibration import far_field as far

NODES = 20
"""Gauss-Legendre nodes on each part."""

PHASE_STEP = 6.0
"""Largest |s| * width of a part [rad]."""

CHUNK = 1 << 22
"""Largest s x nodes block evaluated at once (bounded memory)."""

FAR_MIN = 256.0
"""Smallest |s| = 2 pi f T at which a spectrum takes the end series of
sizer.vibration.far_field (cost free of f T) where its terms allow."""


def transform_nodes(law: MotionLaw, order: int, s_max: float
                    ) -> tuple[np.ndarray, np.ndarray]:
    """Nodes tau and weights times q_N^(order)(tau), fine enough for |s| <= s_max: built
    for the next power of two of s_max and cached per law (a law's quadrature intervals
    cost more than many transforms)."""
    return _nodes(law, order, 2.0 ** max(0, math.ceil(math.log2(max(s_max, 1.0)))))


@lru_cache(maxsize=256)
def _intervals(law: MotionLaw) -> tuple[tuple[int, np.ndarray], ...]:
    return tuple((part.index, part.edges) for part in law_intervals(law))


@lru_cache(maxsize=256)
def _nodes(law: MotionLaw, order: int, s_max: float) -> tuple[np.ndarray, np.ndarray]:
    taus, terms = [], []
    for index, edges in _intervals(law):
        width = np.diff(edges)
        cuts = np.maximum(1, np.ceil(s_max * width / PHASE_STEP)).astype(int)
        first = np.repeat(np.cumsum(cuts) - cuts, cuts)
        step = np.arange(first.size) - first
        fine = np.append(np.repeat(edges[:-1], cuts) + np.repeat(width / cuts, cuts) * step,
                         edges[-1])
        tau, weight = gauss(fine, NODES)
        tau, weight = tau.ravel(), weight.ravel()
        taus.append(tau)
        terms.append(weight * law.piece_derivative(index, tau, order))
    tau, term = np.concatenate(taus), np.concatenate(terms)
    tau.flags.writeable = False
    term.flags.writeable = False
    return tau, term


def law_transform(law: MotionLaw, s: np.ndarray | complex, order: int = 2) -> np.ndarray:
    """F(s) = int_0^1 q_N^(order)(tau) exp(-s tau) dtau for every s (complex array).

    Only the move itself, tau in [0, 1], is integrated (the law is at rest outside it;
    for order 0 the caller adds the rest position after the move where it needs it).
    """
    s = np.asarray(s, dtype=complex)
    flat = s.ravel()
    out = np.empty(flat.shape, dtype=complex)
    # fast phases on the imaginary axis (a spectrum): the end series, cost free of |s|
    series = far.end_series(law, order)
    is_far = (np.abs(flat) >= max(series.s_low, FAR_MIN)) & (flat.real == 0.0)
    if is_far.any():
        out[is_far] = np.exp(-flat[is_far]) * far.end_values(law, flat[is_far], order)
    caps = 2.0 ** np.ceil(np.log2(np.maximum(np.abs(flat), 1.0)))
    for cap in sorted_unique(caps[~is_far]):  # nodes for the |s| of each group only
        near = np.flatnonzero((caps == cap) & ~is_far)
        out[near] = _gauss_transform(law, flat[near], order)
    return out.reshape(s.shape)


def _gauss_transform(law: MotionLaw, flat: np.ndarray, order: int) -> np.ndarray:
    """F(s) by composite Gauss-Legendre (nodes grow with the largest |s|), in blocks."""
    s_max = float(np.max(np.abs(flat), initial=0.0))
    tau, term = transform_nodes(law, order, s_max)
    out = np.empty(flat.shape, dtype=complex)
    rows = max(1, CHUNK // max(1, tau.size))
    for start in range(0, flat.size, rows):
        block = flat[start:start + rows]
        out[start:start + rows] = np.exp(-np.multiply.outer(block, tau)) @ term
    return out
