"""Several laws over the rows of one model: row i moves with ``laws[index[i]]`` (the law as
an array axis of the candidates, issue 34).

A search over shape parameters asks at each step for a different law per motor, and a
sizing of several fixed laws asks the same candidates of each: one model over all those
rows runs its search for T_min, its checks and its closed forms once, each row reading its
own law's coefficients (arrays over the rows, :class:`RowCoefficients`), its own law's
linear peaks and its own law's pieces (:class:`RowPeaks`, :meth:`RowLaws.values`: the
queries of each law answered by that law's objects, so every row's numbers are those
its law gives alone, bit for bit: the laws' analyses are elementwise over their queries).
What depends only on a law (coefficients, hull, grid) is still computed once per law
object and shared by its rows.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np

from sizer.laws.base import build_linear_peaks
from sizer.laws.linear_peaks import LinearPeak, piece_values

if TYPE_CHECKING:
    from sizer.laws.base import MotionLaw


@dataclass(frozen=True)
class RowCoefficients:
    """The coefficients of sec. 6.2 of each row's law, arrays over the rows (as
    sizer.laws.coefficients.LawCoefficients holds them for one law)."""

    C_v: np.ndarray
    C_a: np.ndarray
    C_j: np.ndarray
    C_v_rms: np.ndarray
    C_a_rms: np.ndarray
    jerk_bounded: np.ndarray
    """Per row: its law's acceleration is continuous everywhere, ends included."""


class RowLaws:
    """Row i moves with ``laws[index[i]]``; the laws in their given order."""

    def __init__(self, laws: Sequence[MotionLaw], index: np.ndarray,
                 shared: dict[str, object] | None = None) -> None:
        self.laws = tuple(laws)
        self.index = np.asarray(index, dtype=np.intp)
        self.shared: dict[str, object] = {} if shared is None else shared
        """What a model of these rows builds once for the laws (their grids padded into
        one: sizer.sizing.move), shared by every :meth:`take`."""

    def __len__(self) -> int:
        return len(self.index)

    def take(self, rows: np.ndarray) -> RowLaws:
        """The rows at ``rows`` (repeats allowed), the same laws."""
        return RowLaws(self.laws, self.index[np.asarray(rows, dtype=np.intp)], self.shared)

    @cached_property
    def coefficients(self) -> RowCoefficients:
        """Each row's law's coefficients (computed once per law)."""
        table = [law.coefficients for law in self.laws]

        def column(name: str) -> np.ndarray:
            return np.array([getattr(c, name) for c in table], dtype=float)[self.index]

        bounded = np.array([c.jerk_bounded for c in table], dtype=bool)[self.index]
        return RowCoefficients(column("C_v"), column("C_a"), column("C_j"),
                               column("C_v_rms"), column("C_a_rms"), bounded)

    def groups(self, rows: np.ndarray | None = None) -> list[tuple[int, np.ndarray]]:
        """Per law that some of ``rows`` (default: every row) move with, in the laws'
        order: (its index, the positions in ``rows`` of its rows, in their order)."""
        which = self.index if rows is None else self.index[np.asarray(rows, dtype=np.intp)]
        order = np.argsort(which, kind="stable")
        present, starts = np.unique(which[order], return_index=True)
        ends = np.append(starts[1:], len(order))
        return [(int(k), order[a:b]) for k, a, b in zip(present, starts, ends, strict=True)]

    def peaks(self, rows: np.ndarray) -> RowPeaks:
        """The linear peaks of the queries asked for the rows ``rows`` (one row each)."""
        return RowPeaks(self, np.asarray(rows, dtype=np.intp))

    def values(self, rows: np.ndarray, tau: np.ndarray, piece: np.ndarray,
               order: int | Sequence[int]) -> np.ndarray | tuple[np.ndarray, ...]:
        """sizer.laws.linear_peaks.piece_values of each point on its row's law (``rows``,
        ``tau`` and ``piece``: one per point, the piece numbered in that law)."""
        orders = (order,) if isinstance(order, int) else tuple(order)
        tau = np.asarray(tau, dtype=float)
        piece = np.asarray(piece)
        out = [np.empty(tau.shape) for _ in orders]
        for k, at in self.groups(rows):
            found = piece_values(self.laws[k], tau[at], piece[at], orders)
            for values, v in zip(out, found, strict=True):
                values[at] = v
        return out[0] if isinstance(order, int) else tuple(out)

    def moves_backwards(self) -> bool:
        """Whether some law may move backwards (v_N < 0 somewhere); the linear peaks of
        the laws that need them for it (an acceleration not linear on every piece:
        MotionLaw.linear_acceleration) built together where they are not yet
        (sizer.laws.base.build_linear_peaks)."""
        build_linear_peaks([law for law in self.laws if law.linear_acceleration is None])
        return any(law.moves_backwards() for law in self.laws)

    @cached_property
    def acceleration_range(self) -> tuple[np.ndarray, np.ndarray] | None:
        """Each row's law's least and largest a_N (MotionLaw.linear_acceleration), arrays
        over the rows; None unless every law's acceleration is linear on every piece."""
        found = [law.linear_acceleration for law in self.laws]
        if any(linear is None for linear in found):
            return None
        lowest = np.array([linear.lowest for linear in found if linear is not None])
        highest = np.array([linear.highest for linear in found if linear is not None])
        return lowest[self.index], highest[self.index]


class RowPeaks:
    """The linear peaks (sizer.laws.linear_peaks.LinearPeaks) of queries each asked of its
    own row's law: query i of the row ``rows[i]``; tau and piece as that law has them."""

    def __init__(self, laws: RowLaws, rows: np.ndarray) -> None:
        self.laws = laws
        self.rows = rows

    def maximum(self, p: np.ndarray | float, q: np.ndarray | float) -> LinearPeak:
        """max over tau of p*a_N + q*v_N (LinearPeaks.maximum), each query on its row's
        law."""
        count = len(self.rows)
        P, Q = (np.broadcast_to(np.asarray(x, dtype=float), (count,)) for x in (p, q))
        value, tau = np.empty(count), np.empty(count)
        piece = np.empty(count, dtype=np.intp)
        for k, at in self.laws.groups(self.rows):
            found = self.laws.laws[k].linear_peaks.maximum(P[at], Q[at])
            value[at], tau[at], piece[at] = found.value, found.tau, found.piece
        return LinearPeak(value, tau, piece)
