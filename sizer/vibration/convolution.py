"""The exact response of a linear mode to a law: w(tau) = int_0^tau q_N''(u) e^{s (tau - u)} du.

A mode x' = lambda x + beta u driven by u = y'' = (h / T^2) q_N''(t / T) from rest reaches
x(tau T) = beta (h / T) w(tau) with s = lambda T (sec. 7.2: the convolution of eq. 7.2's
input with the mode's impulse response). w is the transform of sizer.vibration.transform
seen from the end of the interval, e^{s tau} F_tau(s): written so, the damped kernel
e^{s (tau - u)} (Re s <= 0) never overflows, however large delta omega_n T.

One grid per law and size of s: the law's own quadrature intervals (sizer.laws.quadrature),
each cut into equal parts whose phase |s| dtau stays below a step, with the transform's
NODES Gauss-Legendre nodes a part (exact to rounding, as the transform). On equal parts of
width d, a part's integral b_k is e^{s d / 2} times the series of e^{(s d / 2) eta} (eta the
node's offset from the part's middle, |s d / 2| <= 2) against the part's precomputed
moments, and w obeys w_{k+1} = e^{s d} w_k + b_k: a few exponentials per value and block
instead of one per node; the weighted sum of the b_k gives w(1), a scaled cumulative sum
w at every edge.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property, lru_cache

import numpy as np

from sizer.laws.base import MotionLaw
from sizer.laws.quadrature import gauss_legendre, law_intervals
from sizer.numerics.arrays import sorted_unique
from sizer.vibration.transform import NODES

CHUNK = 1 << 21
"""Largest rows x (edges + nodes) block evaluated at once (bounded memory)."""

SCALE_LIMIT = 200.0
"""Largest decay exponent -Re(s) d L of a run of L parts summed with one scaling."""


TAYLOR = 26
"""Terms of the kernel's series about a part's middle: e^{x eta}, |x| <= 2, |eta| <= 1, to
2^26 / 26! ~ 1e-19."""


@dataclass(frozen=True)
class Block:
    """Equal parts of width ``width`` between edges first .. first + parts of the grid;
    ``term`` (parts, NODES): Gauss weight times q_N'' at each part's nodes; ``moments``
    (parts, TAYLOR): sum over a part's nodes of term eta^p / p!, eta = 1 - 2 xi the node's
    offset from the part's middle in half widths."""

    first: int
    parts: int
    width: float
    term: np.ndarray

    @cached_property
    def moments(self) -> np.ndarray:
        xi, _ = _gauss01()
        eta = 1.0 - 2.0 * xi
        p = np.arange(TAYLOR)
        factorial = np.cumprod(np.maximum(p, 1).astype(float))
        series = eta[:, None] ** p / factorial
        return self.term @ series


@dataclass(frozen=True)
class Grid:
    """The parts of [0, 1] a law's convolution is summed on: ``edges`` (K + 1,), increasing
    from 0 to 1, in blocks of equal parts; ``xi`` the nodes on [0, 1] of a part, ``weight``
    their weights."""

    law: MotionLaw
    edges: np.ndarray
    blocks: tuple[Block, ...]
    xi: np.ndarray
    weight: np.ndarray


def _gauss01() -> tuple[np.ndarray, np.ndarray]:
    x, w = gauss_legendre(NODES)
    return 0.5 * (x + 1.0), 0.5 * w


@lru_cache(maxsize=256)
def law_grid(law: MotionLaw, s_cap: float, step: float = 2.0, min_parts: int = 1) -> Grid:
    """The grid of a law for |s| <= s_cap: parts of phase at most ``step`` [rad] and of
    width at most 1 / min_parts."""
    xi, weight = _gauss01()
    density = max(s_cap / step, float(min_parts))
    edges = [np.zeros(1)]
    blocks: list[Block] = []
    first = 0
    for part in law_intervals(law):
        e = part.edges
        widths = np.diff(e)
        cuts = np.maximum(1, np.ceil(widths * density * (1.0 - 1e-12))).astype(int)
        for a, b, c in zip(e[:-1], e[1:], cuts, strict=True):
            d = (b - a) / c
            local = a + d * np.arange(1, c + 1)
            local[-1] = b
            nodes = a + d * (np.arange(c)[:, None] + xi)
            term = d * weight * law.piece_derivative(part.index, nodes, 2)
            last = blocks[-1] if blocks else None
            if last is not None and math.isclose(last.width, d, rel_tol=1e-12) and \
                    last.first + last.parts == first:
                blocks[-1] = Block(last.first, last.parts + c, last.width,
                                   np.vstack([last.term, term]))
            else:
                blocks.append(Block(first, c, d, term))
            edges.append(local)
            first += c
    return Grid(law, np.concatenate(edges), tuple(blocks), xi, weight)


def s_cap_of(s_abs: np.ndarray) -> np.ndarray:
    """The power of two at or above |s| (at least 1): values sharing it share a grid."""
    return 2.0 ** np.ceil(np.log2(np.maximum(s_abs, 1.0)))


def powers(x: np.ndarray, count: int) -> np.ndarray:
    """e^{x n} for n = 0 .. count - 1, (rows, count): e^{x (q B + r)} = e^{x q B} e^{x r},
    2 sqrt(count) exponentials a row and one rounding more than a direct exp."""
    base = max(1, math.isqrt(max(count - 1, 0)) + 1)
    low = np.exp(np.multiply.outer(x, np.arange(base, dtype=float)))
    high = np.exp(np.multiply.outer(x * base, np.arange(-(-count // base), dtype=float)))
    return (high[:, :, None] * low[:, None, :]).reshape(x.size, -1)[:, :count]


def _real_matmul(a: np.ndarray, real: np.ndarray) -> np.ndarray:
    """a @ real for complex a and a real matrix (two contiguous real products: BLAS)."""
    real = np.ascontiguousarray(real)
    return np.ascontiguousarray(a.real) @ real + 1j * (np.ascontiguousarray(a.imag) @ real)


def _series(x: np.ndarray) -> np.ndarray:
    """x^p, p = 0 .. TAYLOR - 1, (rows, TAYLOR)."""
    out = np.empty((x.size, TAYLOR), dtype=complex)
    out[:, 0] = 1.0
    out[:, 1:] = x[:, None]
    return np.cumprod(out, axis=1)


def _part_sums(grid: Grid, block: Block, s: np.ndarray) -> np.ndarray:
    """b_k = int over part k of q_N''(u) e^{s (end_k - u)} du, (rows, parts): the kernel
    e^{s d / 2} e^{(s d / 2) eta} summed by its series against the part's moments."""
    half = s * (0.5 * block.width)
    return np.exp(half)[:, None] * _real_matmul(_series(half), block.moments.T)


def end_values(grid: Grid, s: np.ndarray) -> np.ndarray:
    """w(1) for every s (1-D complex, Re s <= 0): sum_k e^{s d (parts - 1 - k)} b_k a block,
    b_k by the kernel's series (one exponential and 2 sqrt(parts) a row and block)."""
    out = np.zeros(s.shape, dtype=complex)
    for block in grid.blocks:
        half = s * (0.5 * block.width)
        weights = powers(s * block.width, block.parts)[:, ::-1]  # (rows, parts)
        inner = _real_matmul(weights, block.moments)  # (rows, TAYLOR)
        out = (np.exp(s * block.width * block.parts) * out
               + np.exp(half) * np.sum(_series(half) * inner, axis=1))
    return out


def edge_values(grid: Grid, s: np.ndarray) -> np.ndarray:
    """w at every edge of the grid, (rows, K + 1), w = 0 at tau = 0."""
    out = np.zeros((s.size, grid.edges.size), dtype=complex)
    decay = float(np.max(-s.real, initial=0.0))
    for block in grid.blocks:
        b = _part_sums(grid, block, s)
        run = block.parts if decay * block.width * block.parts <= SCALE_LIMIT else \
            max(1, int(SCALE_LIMIT / (decay * block.width)))
        for i in range(0, block.parts, run):
            n = min(run, block.parts - i)
            grow = powers(s * block.width, n)  # e^{s d j}, j = 0 .. n - 1
            scaled = np.cumsum(b[:, i:i + n] / grow, axis=1)
            start = out[:, block.first + i]
            out[:, block.first + i + 1:block.first + i + 1 + n] = grow * (
                np.exp(s * block.width)[:, None] * start[:, None] + scaled)
    return out


def values_at(grid: Grid, s: np.ndarray, at_edges: np.ndarray, tau: np.ndarray,
              row: np.ndarray | None = None) -> np.ndarray:
    """w(tau) for each s and tau in [0, 1] (1-D arrays), from w at the edge at or below
    tau (row ``row[i]`` of ``at_edges``, from :func:`edge_values`; row i by default) and
    the nodes of [edge, tau]."""
    tau = np.clip(tau, 0.0, 1.0)
    k = np.clip(np.searchsorted(grid.edges, tau, side="right") - 1, 0, grid.edges.size - 2)
    left = grid.edges[k]
    d = tau - left
    nodes = left[:, None] + d[:, None] * grid.xi
    term = d[:, None] * grid.weight * grid.law.derivative(nodes, 2)
    rest = np.sum(term * np.exp(s[:, None] * (tau[:, None] - nodes)), axis=1)
    if row is None:
        row = np.arange(tau.size)
    return np.exp(s * d) * at_edges[row, k] + rest


def grouped(s: np.ndarray, width: int) -> list[tuple[np.ndarray, float]]:
    """Row indices of s sharing a grid (:func:`s_cap_of`), cut into chunks of bounded
    memory for ``width`` columns a row, each with its grid's s_cap."""
    caps = s_cap_of(np.abs(s))
    out: list[tuple[np.ndarray, float]] = []
    for cap in sorted_unique(caps):
        rows = np.flatnonzero(caps == cap)
        size = max(1, CHUNK // max(1, width))
        out.extend((rows[i:i + size], float(cap)) for i in range(0, rows.size, size))
    return out
