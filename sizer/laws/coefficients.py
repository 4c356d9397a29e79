"""Shape coefficients of a normalized law (book sec. 6.2, Tables 2.2, 6.1 to 6.7).

C_v = max|q_N'|, C_a = max|q_N''|, C_j = max|q_N'''| inside the smooth pieces, and
C_v_rms, C_a_rms the RMS values over [0, 1]. Peaks are found exactly: the candidates
are every point of a scan grid of each piece (its ends included, one-sided) and the
roots of the next derivative inside it (the project's one root finder,
sizer.numerics.roots, on all sign changes of a piece at once); the grid is graded toward
the piece ends and the law's fine points. RMS values are the law's fixed Gauss-Legendre
rule (sizer.laws.quadrature: exact on polynomial pieces). No scipy.
Where the acceleration jumps (between pieces, or against rest at tau = 0 and 1) the
jerk has an impulse: those jumps are reported, and ``jerk_bounded`` is False.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cache
from typing import Protocol

import numpy as np

from sizer.laws.piece_table import PieceTable
from sizer.laws.pieces import LawShape, Piece
from sizer.laws.quadrature import QuadratureRule
from sizer.numerics.arrays import sorted_unique
from sizer.numerics.roots import bracketed_root

GRID_PER_PIECE = 256
"""Uniform sub-intervals per piece scanned for sign changes of the next derivative."""

END_REFINEMENT = 12
"""Decades of geometric refinement toward each piece end (laws like the exponential one
have their steepest features within 1e-6 of the ends)."""

JUMP_TOLERANCE = 1e-9
"""Relative size below which a difference of one-sided limits is rounding, not a jump."""

COEFFICIENT_NAMES = ("C_v", "C_a", "C_j", "C_v_rms", "C_a_rms")


@dataclass(frozen=True)
class AccelerationJump:
    """A step of the normalized acceleration at tau: a jerk impulse of that area (h/T^2)."""

    tau: float
    jump: float


@dataclass(frozen=True)
class LawCoefficients:
    """Dimensionless coefficients of a law's shape (sec. 6.2)."""

    C_v: float
    C_a: float
    C_j: float
    C_v_rms: float
    C_a_rms: float
    acceleration_jumps: tuple[AccelerationJump, ...]

    @property
    def jerk_bounded(self) -> bool:
        """True when the acceleration is continuous everywhere, ends included."""
        return not self.acceleration_jumps

    def as_dict(self) -> dict[str, float]:
        return {name: getattr(self, name) for name in COEFFICIENT_NAMES}


class MeasuredLaw(LawShape, Protocol):
    """A law with its closed forms and its cached rule (sizer.laws.base.MotionLaw)."""

    def closed_form_coefficients(self) -> dict[str, float]: ...
    @property
    def quadrature(self) -> QuadratureRule: ...


def compute_coefficients(law: MeasuredLaw, use_closed_form: bool = True) -> LawCoefficients:
    """All coefficients of a law; closed forms where the law provides them."""
    known = law.closed_form_coefficients() if use_closed_form else {}
    values = {
        "C_v": known.get("C_v") or peak(law, 1)[0],
        "C_a": known.get("C_a") or peak(law, 2)[0],
        "C_j": known.get("C_j") or peak(law, 3)[0],
        "C_v_rms": known.get("C_v_rms") or rms(law, 1),
        "C_a_rms": known.get("C_a_rms") or rms(law, 2),
    }
    values = {name: float(value) for name, value in values.items()}
    return LawCoefficients(**values, acceleration_jumps=tuple(jumps(law, 2)))


def peak(law: LawShape, order: int) -> tuple[float, float]:
    """max |q_N^(order)| over the smooth pieces and the tau where it occurs.

    Each piece is evaluated on its own (one-sided values at both sides of every
    breakpoint). The candidates are every point of its scan grid and the roots of the
    next derivative inside each sign change of its samples, where the value is then
    evaluated: a peak exactly on a grid point or a piece end is a candidate itself,
    whatever the rounding of the next derivative there.
    """
    table = law.piece_table()
    if table is not None:
        return _table_peak(law, table, order)
    best_value, best_tau = -1.0, 0.0
    for index in range(len(law.pieces)):
        taus = _peak_candidates(law, index, order)
        values = np.abs(law.piece_derivative(index, taus, order))
        k = int(np.argmax(values))
        if values[k] > best_value:
            best_value, best_tau = float(values[k]), float(taus[k])
    return best_value, best_tau


TABLE_CHUNK = 1 << 18
"""Scan points of a piece table evaluated at once (bounds the memory of a peak search)."""


def _table_peak(law: LawShape, table: PieceTable, order: int) -> tuple[float, float]:
    """:func:`peak` of a law of polynomial pieces (a piece table), every piece at once:
    the candidates are each piece's uniform scan points (``piece.intervals`` of them, at
    least 8: a polynomial of degree d has at most d - 1 extrema) and the roots of the
    next derivative in every sign change between them; in chunks of pieces."""
    if order >= law.max_order:
        raise ValueError(f"{law.law_id}: the peak of order {order} needs the derivative of "
                         f"order {order + 1}, above the law's {law.max_order}")
    intervals = max(8, min(GRID_PER_PIECE, law.pieces[0].intervals or GRID_PER_PIECE))
    steps = np.linspace(0.0, 1.0, intervals + 1)
    per_chunk = max(1, TABLE_CHUNK // (intervals + 1))
    best_value, best_tau = -1.0, 0.0
    for first in range(0, table.count, per_chunk):
        pieces = np.arange(first, min(first + per_chunk, table.count))
        start, end = table.starts[pieces, None], table.ends[pieces, None]
        tau = np.minimum(start + (end - start) * steps, end)
        owner = np.broadcast_to(pieces[:, None], tau.shape)
        slope = table.evaluate(owner, tau, order + 1)
        row, col = np.nonzero(slope[:, :-1] * slope[:, 1:] < 0.0)
        at = pieces[row]
        roots = bracketed_root(lambda x, p: table.evaluate(p, x, order + 1), tau[row, col],
                               tau[row, col + 1], slope[row, col], slope[row, col + 1],
                               args=(at,))
        taus = np.concatenate((tau.ravel(), roots))
        values = np.abs(table.evaluate(np.concatenate((owner.ravel(), at)), taus, order))
        k = int(np.argmax(values))
        if values[k] > best_value:
            best_value, best_tau = float(values[k]), float(taus[k])
    return best_value, best_tau


def _peak_candidates(law: LawShape, index: int, order: int) -> np.ndarray:
    """Points of a piece where |q_N^(order)| may peak (its grid points among them).

    On a polynomial piece whose derivative of this order is linear or constant the ends
    are the only candidates. On any other piece: the scan grid and the roots of the next
    derivative in each sign change of its samples (a maximum of |f| inside a smooth piece
    is a root of f'; no scalar search).
    """
    piece = law.pieces[index]
    degree = piece.degree
    if degree is not None and degree - order <= 1:
        return np.array([piece.start, piece.end])
    if order >= law.max_order:
        raise ValueError(f"{law.law_id}: the peak of order {order} needs the derivative of "
                         f"order {order + 1}, above the law's {law.max_order}")
    grid = scan_grid(piece, toward=law.fine_points())
    return np.concatenate((grid, _stationary_points(law, index, order, grid)))


def _stationary_points(law: LawShape, index: int, order: int,
                       grid: np.ndarray) -> np.ndarray:
    """The roots of q_N^(order + 1) in every sign change of its samples on ``grid``, all
    brackets of the piece at once (sizer.numerics.roots.bracketed_root, to an ulp or so): the
    interior extrema of q_N^(order), where its value is then evaluated."""
    slope = law.piece_derivative(index, grid, order + 1)
    k = np.nonzero(slope[:-1] * slope[1:] < 0.0)[0]
    if not k.size:
        return k.astype(float)
    return bracketed_root(lambda x: law.piece_derivative(index, x, order + 1), grid[k], grid[k + 1],
                          slope[k], slope[k + 1])


def scan_grid(piece: Piece, uniform: int = GRID_PER_PIECE, toward: Sequence[float] = (),
              per_decade: int = 4) -> np.ndarray:
    """Uniform points over a piece plus points graded geometrically toward both ends and
    toward each of the ``toward`` points that lie in the piece (from both sides).

    A piece that needs fewer intervals than ``uniform`` (``piece.intervals``: a short
    polynomial piece among many, a cam table's) gets that many, without the grading
    toward its ends (a polynomial has no steep end)."""
    width = piece.end - piece.start
    graded = width * _decades(per_decade)
    if piece.intervals is not None and piece.intervals < uniform:
        parts = [np.linspace(piece.start, piece.end, piece.intervals + 1)]
    else:
        parts = [np.linspace(piece.start, piece.end, uniform + 1), piece.start + graded,
                 piece.end - graded]
    for point in toward:
        if piece.start <= point <= piece.end:
            parts += [np.array([point]), point - graded, point + graded]
    grid = np.concatenate(parts)
    if len(toward) > 0:  # points graded toward a fine point may leave the piece
        grid = grid[(grid >= piece.start) & (grid <= piece.end)]
    return sorted_unique(grid)


@cache
def _decades(per_decade: int) -> np.ndarray:
    """10^-e for e from END_REFINEMENT down to 1 in steps of 1/per_decade (read-only,
    computed once: every law of a shape search asks for the same)."""
    exponents = np.arange(END_REFINEMENT * per_decade, per_decade - 1, -1) / per_decade
    factors = 10.0 ** -exponents
    factors.setflags(write=False)
    return factors


def rms(law: MeasuredLaw, order: int) -> float:
    """sqrt( integral over [0, 1] of (q_N^(order))^2 ), with the law's fixed rule."""
    rule = law.quadrature
    return math.sqrt(rule.integral(rule.values(law, order) ** 2))


def one_sided_limits(law: LawShape, order: int) -> list[tuple[float, float, float]]:
    """(tau, left, right) limits of q_N^(order) at every breakpoint, ends included.

    Outside [0, 1] the law is at rest (0 on the left of tau = 0, 1 or 0 right of tau = 1)
    or, for a law whose ends move, as ``law.outside`` says (the period's wrap).
    """
    pieces = law.pieces
    # each piece's one-sided values at its start and at the next piece's start (its end)
    stops = [p.start for p in pieces[1:]] + [pieces[-1].end]
    table = law.piece_table()
    if table is not None:
        index = np.arange(table.count)
        ends = np.stack((table.evaluate(index, table.starts, order),
                         table.evaluate(index, table.ends, order)), axis=1).tolist()
    elif (forms := law.piece_forms()) is not None:  # every piece at once, the same values
        index = np.arange(len(pieces))
        (starts,) = forms.values(index, np.array([p.start for p in pieces]), (order,))
        (ends_at,) = forms.values(index, np.array(stops), (order,))
        ends = np.stack((starts, ends_at), axis=1).tolist()
    else:
        ends = [law.piece_derivative(i, np.array([piece.start, stop]), order).tolist()
                for i, (piece, stop) in enumerate(zip(pieces, stops, strict=True))]
    before, after = law.outside(order)
    rows = [(pieces[0].start, before, ends[0][0])]
    for i in range(1, len(pieces)):
        rows.append((pieces[i].start, ends[i - 1][1], ends[i][0]))
    rows.append((pieces[-1].end, ends[-1][1], after))
    return rows


def jumps(law: LawShape, order: int) -> list[AccelerationJump]:
    """Breakpoints where q_N^(order) jumps, with the size of the jump."""
    limits = one_sided_limits(law, order)
    scale = max(1.0, *(max(abs(left), abs(right)) for _, left, right in limits))
    return [
        AccelerationJump(tau=tau, jump=right - left)
        for tau, left, right in limits
        if abs(right - left) > JUMP_TOLERANCE * scale
    ]


def measured_continuity(law: LawShape) -> float:
    """The largest k such that q_N is C^k across all breakpoints (up to law.max_order)."""
    for order in range(law.max_order + 1):
        if jumps(law, order):
            return order - 1
    return law.max_order
