"""Normalized rest-to-rest motion laws q_N(tau), tau in [0, 1] (book sec. 6.2).

A law is a sequence of smooth pieces. Each piece evaluates the position and its
derivatives exactly on its own interval (a tau outside it is clamped to the nearer end);
the law dispatches a vectorized tau to its pieces and is at rest outside [0, 1]
(q_N = 0 before, q_N = 1 after, derivatives 0). Parameter ranges and the rules for
``auto``: see :class:`Parameter`.
The real motion is q(t) = q0 + h*q_N((t - t0)/T); the k-th derivative scales by h/T^k.
A law's analyses (coefficients, quadrature rule, linear peaks) are computed by their own
modules from what a law is (sizer.laws.pieces.LawShape) and cached here, once per law
object; the registry of families (sizer.laws.registry) is above them all.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from functools import cached_property, lru_cache
from types import MappingProxyType
from typing import Any, ClassVar

import numpy as np

import sizer.laws.coefficients as law_coefficients
from sizer.errors import UserError
from sizer.laws.coefficients import LawCoefficients
from sizer.laws.linear_peaks import (
    LinearAcceleration,
    LinearPeaks,
    linear_acceleration,
    samples_together,
)
from sizer.laws.piece_forms import PieceForms
from sizer.laws.piece_table import PieceTable
from sizer.laws.pieces import Piece
from sizer.laws.quadrature import QuadratureRule, quadrature_rule

INFINITELY_SMOOTH = math.inf
"""Continuity class of a law whose position is C^infinity (e.g. the exponential law)."""


@dataclass(frozen=True)
class Parameter:
    """A shape parameter of a law family, with its admissible range.

    Parameter ranges: [low, high] (ends excluded where ``low_open``/``high_open``) is the
    range over which the law is exact: its pieces, its coefficients (closed forms and the
    numerical path agree to 1e-9) and the sizing grids. A value outside it is a user error
    naming the range. Where a family degenerates toward an end (a step, or a profile
    steeper than double precision resolves), the range stops short of it and
    ``description`` says why.

    ``auto``: a shape parameter written ``auto`` is chosen by the sizing solver within
    ``auto_range``, a finite interval inside the admissible range (its ends excluded where
    they are the parameter's open ends). It is the parameter's own range unless
    ``auto_low``/``auto_high`` narrow it. ``no_auto`` refuses ``auto`` with that reason
    (and what to write instead); so does an unbounded range with no finite auto range.
    """

    name: str
    default: float | None
    low: float
    high: float
    low_open: bool = False
    high_open: bool = False
    integer: bool = False
    odd: bool = False
    description: str = ""
    auto_low: float | None = None
    auto_high: float | None = None
    no_auto: str = ""

    @property
    def auto_range(self) -> tuple[float, float] | None:
        """The finite interval an ``auto`` search may use, or None when auto is refused."""
        if self.no_auto:
            return None
        low = self.low if self.auto_low is None else self.auto_low
        high = self.high if self.auto_high is None else self.auto_high
        if not (math.isfinite(low) and math.isfinite(high)):
            return None
        return low, high

    def auto_refusal(self, law_id: str) -> str | None:
        """The one-line message refusing ``auto`` for this parameter, or None if allowed."""
        if self.auto_range is not None:
            return None
        reason = self.no_auto or (f"its range {self.range_text()} is unbounded; "
                                  f"write a number")
        return f"{law_id}: {self.name}=auto is not supported: {reason}"

    def range_text(self) -> str:
        """The admissible range written as an interval, e.g. '(0, 1/2]'."""
        low = "-inf" if self.low == -math.inf else _short(self.low)
        high = "inf" if self.high == math.inf else _short(self.high)
        left = "(" if self.low_open else "["
        right = ")" if self.high_open else "]"
        kind = "odd integer in " if self.odd else "integer in " if self.integer else ""
        return f"{kind}{left}{low}, {high}{right}"

    def validate(self, law_id: str, value: float) -> float:
        """Return the value as float, or raise a UserError naming the valid range."""
        value = float(value)
        ok = math.isfinite(value)
        ok = ok and (value > self.low if self.low_open else value >= self.low)
        ok = ok and (value < self.high if self.high_open else value <= self.high)
        if ok and self.integer:
            ok = value == int(value)
        if ok and self.odd:
            ok = int(value) % 2 == 1
        if not ok:
            raise UserError(
                f"{law_id}: parameter {self.name}={_short(value)} is out of range; "
                f"valid: {self.name} {self.range_text()}"
            )
        return value


def _short(value: float) -> str:
    """A compact text that reads back to the same float: 3, 1/3, 7.1 or the full repr."""
    if value == int(value) and abs(value) < 1e15:
        return str(int(value))
    frac = Fraction(value).limit_denominator(16)
    if float(frac) == value and abs(frac.numerator) <= 16:
        return f"{frac.numerator}/{frac.denominator}"
    return repr(value)


def format_parameter(value: float) -> str:
    """Text of a parameter value in a law spec; reads back to the same float."""
    return _short(value)


class MotionLaw:
    """A normalized rest-to-rest motion law on [0, 1].

    Subclasses set ``law_id``, ``parameters``, and build their pieces and continuity
    class in ``__init__`` via ``_setup``.
    """

    law_id: ClassVar[str] = ""
    title: ClassVar[str] = ""
    parameters: ClassVar[tuple[Parameter, ...]] = ()
    max_order: ClassVar[int] = 4
    """Highest derivative order the pieces evaluate exactly."""
    steep_ends: ClassVar[bool] = False
    """True when the profile varies on scales far below the piece width near the piece
    ends (the exponential law): samplers then grade their grids toward the ends."""

    def fine_points(self) -> tuple[float, ...]:
        """Points of [0, 1] near which the profile varies on scales far below its piece
        widths (e.g. tau = 1/2 of an elliptic law with a large n); samplers grade their
        grids geometrically toward them, from both sides. None by default."""
        return ()

    def __init__(self, **params: float) -> None:
        self.params: Mapping[str, float] = MappingProxyType(self.canonical_params(params))
        pieces, continuity = self._build()
        self.pieces: tuple[Piece, ...] = tuple(p for p in pieces if p.end > p.start)
        self.continuity: float = continuity
        starts = np.array([p.start for p in self.pieces])
        self._starts = starts
        self.breakpoints = np.append(starts, self.pieces[-1].end)

    @classmethod
    def canonical_params(cls, params: Mapping[str, float]) -> dict[str, float]:
        """Every parameter of the family by name, in declaration order: the given values
        validated, the others at their defaults. UserError for an unknown, missing or
        out-of-range parameter."""
        unknown = set(params) - {p.name for p in cls.parameters}
        if unknown:
            names = ", ".join(p.name for p in cls.parameters) or "none"
            raise UserError(
                f"{cls.law_id}: unknown parameter(s) {', '.join(sorted(unknown))}; "
                f"parameters: {names}"
            )
        values: dict[str, float] = {}
        for p in cls.parameters:
            if p.name in params:
                values[p.name] = p.validate(cls.law_id, params[p.name])
            elif p.default is not None:
                values[p.name] = float(p.default)
            else:
                raise UserError(f"{cls.law_id}: parameter {p.name} is required "
                                f"({p.name} {p.range_text()})")
        return values

    @classmethod
    def canonical_spec(cls, params: Mapping[str, float]) -> str:
        """The canonical spec text of the family's law with these (canonical) parameters."""
        if not cls.parameters:
            return cls.law_id
        args = ", ".join(f"{k}={format_parameter(v)}" for k, v in params.items())
        return f"{cls.law_id}({args})"

    def _build(self) -> tuple[Sequence[Piece], float]:
        """Return the pieces covering [0, 1] in order and the continuity class k (C^k)."""
        raise NotImplementedError

    # ----------------------------------------------------------------- naming
    @cached_property
    def spec(self) -> str:
        """Canonical spec text, e.g. 'trapezoidal(alpha=1/3)'; parses back to this law.

        Laws compare and hash by it, so equal laws share dictionary entries and caches."""
        return self.canonical_spec(self.params)

    def __repr__(self) -> str:
        return f"<MotionLaw {self.spec}>"

    def __eq__(self, other: object) -> bool:
        return isinstance(other, MotionLaw) and other.spec == self.spec

    def __hash__(self) -> int:
        return hash(self.spec)

    def __reduce__(self) -> tuple[Any, ...]:
        """Pickled as its family and parameters, built again on loading through the cache
        of :func:`law_of` (the object ``make_law`` of its spec gives): the pieces are
        closures, and a law is its spec (the worker processes of a sizing send results
        that hold laws: sizer.sizing.law_processes)."""
        return law_of, (type(self), dict(self.params))

    def outside(self, order: int) -> tuple[float, float]:
        """q_N^(order) just before tau = 0 and just after tau = 1: at rest, at 0 and 1."""
        return 0.0, 1.0 if order == 0 else 0.0

    # ------------------------------------------------------------- evaluation
    def piece_table(self) -> PieceTable | None:
        """The pieces as one table evaluated all at once (sizer.laws.piece_table), for a
        law of many polynomial pieces; None: evaluate piece by piece."""
        return None

    def piece_forms(self) -> PieceForms | None:
        """The pieces as data evaluated all at once (sizer.laws.piece_forms), for a law of
        several pieces that are polynomials plus sines (or their reflections); None:
        evaluate piece by piece."""
        return self._piece_forms

    @cached_property
    def _piece_forms(self) -> PieceForms | None:
        if len(self.pieces) < 2:  # one piece: its own closure, no gathering
            return None
        return PieceForms.of(self.pieces)

    def derivative(self, tau: np.ndarray | float, order: int = 0) -> np.ndarray:
        """The order-th derivative of q_N at tau (vectorized); rest outside [0, 1].

        At an interior breakpoint the piece on the right is used; tau = 1 belongs to the
        last piece.
        """
        if order < 0 or order > self.max_order:
            raise ValueError(f"{self.law_id}: derivative order {order} not in 0..{self.max_order}")
        tau = np.asarray(tau, dtype=float)
        out = np.zeros(tau.shape)
        if order == 0:
            out[tau > 1.0] = 1.0
        inside = (tau >= 0.0) & (tau <= 1.0)
        if not inside.any():
            return out
        index = np.searchsorted(self._starts, tau, side="right") - 1
        table = self.piece_table()
        if table is not None:
            out[inside] = table.evaluate(np.maximum(index[inside], 0), tau[inside], order)
            return out
        forms = self.piece_forms()
        if forms is not None:
            out[inside] = forms.values(index[inside], tau[inside], (order,))[0]
            return out
        for i, piece in enumerate(self.pieces):
            mask = inside & (index == i)
            if mask.any():
                out[mask] = piece.evaluate(piece.clamp(tau[mask]), order)
        return out

    def piece_derivative(self, index: int, tau: np.ndarray | float, order: int) -> np.ndarray:
        """The order-th derivative of piece ``index`` at tau (its one-sided values at ends).

        tau is clamped into the piece's interval, so a point a rounding error outside
        reads the end's one-sided value, never the piece's extrapolation.
        """
        piece = self.pieces[index]
        return piece.evaluate(piece.clamp(np.asarray(tau, dtype=float)), order)

    def position(self, tau: np.ndarray | float) -> np.ndarray:
        return self.derivative(tau, 0)

    def velocity(self, tau: np.ndarray | float) -> np.ndarray:
        return self.derivative(tau, 1)

    def acceleration(self, tau: np.ndarray | float) -> np.ndarray:
        return self.derivative(tau, 2)

    def jerk(self, tau: np.ndarray | float) -> np.ndarray:
        return self.derivative(tau, 3)

    # ----------------------------------------------------------- coefficients
    def closed_form_coefficients(self) -> dict[str, float]:
        """Coefficients known in closed form (book formulas); used in place of numerics."""
        return {}

    @cached_property
    def coefficients(self) -> LawCoefficients:
        """C_v, C_a, C_j, C_v_rms, C_a_rms and the acceleration jumps (sec. 6.2)."""
        return law_coefficients.compute_coefficients(self)

    @cached_property
    def numerical_coefficients(self) -> LawCoefficients:
        """The coefficients computed numerically only (ignores closed forms): a cross-check."""
        return law_coefficients.compute_coefficients(self, use_closed_form=False)

    @cached_property
    def quadrature(self) -> QuadratureRule:
        """The law's fixed Gauss-Legendre rule over its pieces (computed once per law)."""
        return quadrature_rule(self)

    def moves_backwards(self) -> bool:
        """Whether v_N < 0 somewhere (its linear peaks' least v_N, beyond rounding): no
        peak bound on T_min holds for it (sizer.sizing.move.peak_duration)."""
        return self._moves_backwards

    @cached_property
    def _moves_backwards(self) -> bool:
        """:meth:`moves_backwards`, asked once per law (each model of a search step asks
        it of every law of its rows); a law whose acceleration is linear on every piece
        reads its least v_N from its pieces (:attr:`linear_acceleration`), no hull."""
        linear = self.linear_acceleration
        slowest = linear.slowest if linear is not None else \
            float(self.linear_peaks.minimum(0.0, 1.0).value)
        return slowest < -1e-12

    @cached_property
    def linear_acceleration(self) -> LinearAcceleration | None:
        """The least and largest a_N and the least v_N of a law whose acceleration is
        linear on every piece, from its pieces (sizer.laws.linear_peaks.
        linear_acceleration); None for other laws."""
        return linear_acceleration(self)

    @cached_property
    def linear_peaks(self) -> LinearPeaks:
        """Sampled (v_N, a_N) curve and its convex hull, for exact peaks of p*a_N + q*v_N."""
        return LinearPeaks(self)


def build_linear_peaks(laws: Sequence[MotionLaw]) -> None:
    """Each law's ``linear_peaks`` built where it is not yet, the samples of the laws
    with their pieces as data in one pass (sizer.laws.linear_peaks.samples_together: the
    same samples, so the same peaks as each law builds alone): the laws of a search step
    or of one sizing build their hulls together."""
    todo = [law for law in dict.fromkeys(laws)
            if "linear_peaks" not in law.__dict__ and law.piece_forms() is not None]
    if len(todo) < 2:
        return
    for law, samples in zip(todo, samples_together(todo), strict=True):
        law.__dict__["linear_peaks"] = LinearPeaks(law, samples)  # the cached property's


LAW_CACHE_SIZE = 4096
"""Laws kept by canonical spec; past it the least recently used are rebuilt on demand."""


def law_of(family: type[MotionLaw], params: Mapping[str, float]) -> MotionLaw:
    """The (cached) law of a family with these parameter values, defaults filled in.

    The key is the canonical spec, so equal parameter values give the same object; use it
    where laws are built from numbers (auto-shape searches) to share their computations.
    """
    values = family.canonical_params(params)
    build: Callable[..., MotionLaw] = family  # hashable (see _law_of_spec)
    return _law_of_spec(build, family.canonical_spec(values), tuple(values.items()))


@lru_cache(maxsize=LAW_CACHE_SIZE)
def _law_of_spec(family: Callable[..., MotionLaw], spec: str,
                 values: tuple[tuple[str, float], ...]) -> MotionLaw:
    """Keyed by the family and the canonical spec text (the values ride along to build
    the law). ``family`` is a law class typed as its constructor: mypy takes the
    ``__hash__`` of a class's instances for the class's own, and a ``type[MotionLaw]``
    for an unhashable key."""
    return family(**dict(values))
