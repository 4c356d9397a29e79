"""The polynomial pieces of a law as one table: every piece evaluated at once.

A law of many polynomial pieces (a cam table of 100,000 rows, a spline through many
via-points) is evaluated through this table rather than piece by piece: the Taylor
coefficients of each derivative order of every piece are rows of an array, and a point
bound to its piece is evaluated by Horner's scheme on its row, all points at once (no
Python loop per piece). The law's own pieces read the same rows, so both agree exactly.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True, eq=False)
class PieceTable:
    """Pieces [starts[i], ends[i]] of q_N(tau) = (sum_p rows[0][i, p] (tau - starts[i])^p
    - offset) / size; ``rows[k]`` holds the coefficients of the k-th derivative."""

    starts: np.ndarray
    ends: np.ndarray
    rows: tuple[np.ndarray, ...]
    offset: float
    size: float

    @property
    def count(self) -> int:
        return len(self.starts)

    def locate(self, tau: np.ndarray) -> np.ndarray:
        """The piece of each tau (the piece on the right at a breakpoint, the last at 1)."""
        index = np.searchsorted(self.starts, tau, side="right") - 1
        return np.clip(index, 0, self.count - 1)

    def evaluate(self, piece: np.ndarray, tau: np.ndarray, order: int) -> np.ndarray:
        """q_N^(order) at tau on the given pieces (arrays of one shape), each tau clamped
        into its piece (one-sided values at the piece ends)."""
        piece = np.asarray(piece, dtype=np.intp)
        tau = np.asarray(tau, dtype=float)
        u = np.minimum(np.maximum(tau, self.starts[piece]), self.ends[piece]) - \
            self.starts[piece]
        rows = self.rows[order]
        out = rows[piece, -1] + u * 0.0
        for column in range(rows.shape[1] - 2, -1, -1):
            out = rows[piece, column] + out * u
        if order == 0:
            out = out - self.offset
        return out / self.size
