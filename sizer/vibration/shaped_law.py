"""A motion law convolved with an input shaper (sec. 7.4.2), as a law of its own.

The base law q of duration T_b convolved with the shaper's impulses A_i at t_i is
y(t) = sum A_i q(t - t_i) (sec. 7.4.2), a rest-to-rest move of duration
T_s = T_b + t_n. Normalized over T_s (tau = t / T_s, r = T_b / T_s):

    q_s(tau) = sum_i A_i q_N((tau - tau_i) / r),   tau_i = t_i / T_s,
    q_s^(k)(tau) = sum_i A_i r^-k q_N^(k)((tau - tau_i) / r)

(q_N at rest outside [0, 1]). The shaper's times are multiples of the damped period,
t_i = c_i / f_d with f_d = f_n sqrt(1 - delta^2), so tau_i = c_i / (f_T sqrt(1 - delta^2))
and the shape depends only on the base law, the shaper, delta and f_T = f_n T_s (the
mode's frequency times the shaped move's whole duration). The base keeps the fraction
r = 1 - tau_n of the move; f_T must leave it positive.

Pieces: the intervals between all shifted breakpoints tau_i + r b_j. On each, every
impulse's term is either at rest (before or after its base move) or inside one base
piece, which evaluates it exactly; the piece's degree is the largest of its terms' (None
if one of them is not polynomial), so the quadrature of sizer.laws stays exact. The
continuity class is the base's.

Effect on torque: the amplitudes are positive and sum to 1, so y^(k)(t) is a convex
combination of base values, |y^(k)| <= max |q^(k)|: at the same base duration the shaped
move's peak velocity, acceleration (the inertia torque) and jerk are at most the base's.
Keeping the total duration instead, the base has T_s - t_n and its peaks grow by
(T_s / T_b)^k before the averaging lowers them.

The data kind ``shaped`` (sizer.laws.data_spec) builds the same law from its mapping
``{kind: shaped, law: cycloidal, shaper: zv, f_T: 4, damping_ratio: 0.02}``.
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping, Sequence
from functools import cached_property
from typing import Any, ClassVar, Literal

import numpy as np

from sizer.errors import UserError
from sizer.laws.base import MotionLaw
from sizer.laws.data_law import data_law_of
from sizer.laws.multipoint.fields import as_number, refuse_unknown
from sizer.laws.pieces import Piece
from sizer.vibration.elastic_load import ElasticLoad
from sizer.vibration.shapers import Shaper, kind_of_shaper, make_shaper

MIN_BASE_FRACTION = 1e-6
"""Smallest share r = T_b / T_s of the shaped move left to the base law."""

MERGE = 1e-13
"""Shifted breakpoints closer than this (in tau) are one breakpoint."""

FIELDS = ("law", "shaper", "f_T", "damping_ratio", "vibration_limit")
"""The fields of the data kind ``shaped``."""


class ShapedLaw(MotionLaw):
    """q_s(tau) = sum A_i q_N((tau - tau_i) / r): a base law shaped for a mode of
    frequency f_n = f_T / T_s and damping ratio delta (sec. 7.4.2)."""

    law_id: ClassVar[str] = "shaped"
    title: ClassVar[str] = "Input-shaped law (sec. 7.4.2)"

    def __init__(self, base: MotionLaw, shaper: str, f_T: float,
                 damping_ratio: float = 0.0, vibration_limit: float | None = None) -> None:
        kind = kind_of_shaper(shaper)
        f_T = as_number(f_T, "f_T")
        damping_ratio = as_number(damping_ratio, "damping_ratio")
        if not 0.0 <= damping_ratio < 1.0:
            raise UserError(f"the damping ratio must be in [0, 1) (an under-damped mode), "
                            f"not {damping_ratio:g}", field="damping_ratio")
        if f_T <= 0.0:
            raise UserError(f"f_T (natural frequency times the shaped move's duration) "
                            f"must be positive, not {f_T:g}", field="f_T")
        _check_base(base)
        # times in units of T_s: the mode of a move of unit duration has f_n = f_T
        unit = kind.build(ElasticLoad(f_T, damping_ratio), vibration_limit)
        fraction = 1.0 - unit.length
        if fraction < MIN_BASE_FRACTION:
            least = f_T * unit.length / (1.0 - MIN_BASE_FRACTION)
            raise UserError(f"f_T = {f_T:g} is too small for the {kind.name} shaper at "
                            f"damping ratio {damping_ratio:g}: its impulses span "
                            f"t_n = {f_T * unit.length:.6g} / f_n of the move's "
                            f"T_s = {f_T:g} / f_n, leaving the base law no time; f_T must "
                            f"exceed {least:.6g}", field="f_T")
        self.base = base
        self.shaper_name = kind.name
        self.f_T = f_T
        self.damping_ratio = damping_ratio
        self.vibration_limit = None if vibration_limit is None else float(vibration_limit)
        self.shaper: Shaper = unit
        """The impulses, times in units of the shaped move's duration T_s."""
        self.base_fraction = fraction
        """r = T_b / T_s."""
        self.max_order = base.max_order  # type: ignore[misc]
        self.steep_ends = base.steep_ends  # type: ignore[misc]
        super().__init__()

    # ----------------------------------------------------------------- naming
    @cached_property
    def spec(self) -> str:
        """The canonical text of the data kind ``shaped`` (reads back to this law)."""
        from sizer.laws.data_spec import data_spec_text, is_data_spec, read_data_spec

        base: Any = self.base.spec
        if is_data_spec(base):
            base = read_data_spec(base)
        fields: dict[str, Any] = {"kind": "shaped", "law": base, "shaper": self.shaper_name,
                                  "f_T": self.f_T}
        if self.damping_ratio != 0.0:
            fields["damping_ratio"] = self.damping_ratio
        if self.vibration_limit is not None:
            fields["vibration_limit"] = self.vibration_limit
        return data_spec_text(fields)

    def __reduce__(self) -> tuple[Any, ...]:
        """Pickled as its spec (a data spec of kind ``shaped``), built again through the
        data laws' cache (sizer.laws.data_law.data_law_of)."""
        return data_law_of, (self.spec,)

    # ------------------------------------------------------------------ shape
    def fine_points(self) -> tuple[float, ...]:
        """The base's fine points, shifted by every impulse."""
        points = self.base.fine_points()
        r = self.base_fraction
        return tuple(float(t + r * p) for t in self.shaper.times for p in points)

    def _build(self) -> tuple[Sequence[Piece], float]:
        base, r = self.base, self.base_fraction
        tau_i = np.asarray(self.shaper.times)  # t_i / T_s
        amplitudes = np.asarray(self.shaper.amplitudes)
        base_starts = np.asarray(base.breakpoints[:-1])
        edges = np.sort((tau_i[:, None] + r * np.asarray(base.breakpoints)[None, :]).ravel())
        edges = edges[np.concatenate(([True], np.diff(edges) > MERGE))]
        edges = edges[(edges > MERGE) & (edges < 1.0 - MERGE)]
        edges = np.concatenate(([0.0], edges, [1.0]))
        pieces = []
        for start, end in itertools.pairwise(edges):
            middle = 0.5 * (start + end)
            offset = 0.0
            terms: list[tuple[float, float, int]] = []
            for a, t in zip(amplitudes, tau_i, strict=True):
                u = (middle - t) / r
                if u >= 1.0:
                    offset += float(a)
                elif u > 0.0:
                    index = int(np.searchsorted(base_starts, u, side="right")) - 1
                    terms.append((float(a), float(t), index))
            pieces.append(self._piece(float(start), float(end), offset, terms))
        return pieces, base.continuity

    def _piece(self, start: float, end: float, offset: float,
               terms: list[tuple[float, float, int]]) -> Piece:
        """The sum of the active terms (each one base piece) plus the finished moves."""
        base, r = self.base, self.base_fraction
        degrees = [base.pieces[index].degree for _, _, index in terms]
        degree = (None if any(d is None for d in degrees)
                  else max([0, *(d for d in degrees if d is not None)]))

        # the terms on one base piece in one call, their arguments in one flat array (the
        # operations of MotionLaw.piece_derivative, elementwise: the same floats); the sum
        # keeps the terms' order
        shared: dict[int, list[int]] = {}
        for k, (_, _, index) in enumerate(terms):
            shared.setdefault(index, []).append(k)
        groups = [(base.pieces[index], np.array([terms[k][1] for k in members])[:, None],
                   members) for index, members in shared.items()]

        def evaluate(tau: np.ndarray, order: int) -> np.ndarray:
            tau = np.asarray(tau, dtype=float)
            out = np.full(tau.shape, offset if order == 0 else 0.0)
            values: list[np.ndarray] = [out] * len(terms)
            for piece, shifts, members in groups:
                u = np.minimum(np.maximum(((tau.reshape(1, -1) - shifts) / r).ravel(),
                                          piece.start), piece.end)
                value = piece.evaluate(u, order).reshape((len(members), *tau.shape))
                for k, row in zip(members, value, strict=True):
                    values[k] = row
            for (a, _, _), value in zip(terms, values, strict=True):
                out += (a * r**-order) * value
            return out

        return Piece(start, end, evaluate, degree)


def _check_base(base: MotionLaw) -> None:
    """A base law must go rest to rest from 0 to 1 (shifted copies then add up)."""
    if not getattr(base, "rest_to_rest", True) or getattr(base, "end_position", 1.0) != 1.0:
        raise UserError(f"the law to shape must start and end at rest and rise from 0 to 1 "
                        f"(normalized); {base.spec} does not", field="law")


# ------------------------------------------------------------- design helpers
def shaped_for_duration(base: MotionLaw, shaper_kind: str, load: ElasticLoad,
                        duration: float, keep: Literal["total", "base"] = "total",
                        vibration_limit: float | None = None) -> tuple[ShapedLaw, float]:
    """The base law shaped for ``load`` and the shaped move's duration T_s [s].

    ``keep="total"``: T_s = duration, the base law gets duration - t_n; ``keep="base"``:
    the base law keeps ``duration`` and the move grows to duration + t_n (sec. 7.4.2).
    """
    duration = as_number(duration, "duration")
    if duration <= 0.0:
        raise UserError(f"must be a positive duration, not {duration:g} s", field="duration")
    if keep not in ("total", "base"):
        raise UserError(f"keep must be 'total' or 'base', not {keep!r}", field="keep")
    length = make_shaper(shaper_kind, load, vibration_limit).length
    total = duration if keep == "total" else duration + length
    if keep == "total" and duration * (1.0 - MIN_BASE_FRACTION) <= length:
        raise UserError(f"a {shaper_kind} shaper for a {load.natural_frequency:g} Hz mode "
                        f"lasts {length:.6g} s: the move's duration {duration:g} s leaves "
                        f"no time for the law; make it longer or keep the base duration",
                        field="duration")
    law = ShapedLaw(base, shaper_kind, load.natural_frequency * total, load.damping_ratio,
                    vibration_limit)
    return law, total


# ---------------------------------------------------------------- data kind
class ShapedCurve:
    """The shaped law as the curve of a data kind (sizer.laws.data_law normalizes it: it
    is already normalized, over tau in [0, 1]); ``law`` is the :class:`ShapedLaw`."""

    def __init__(self, law: ShapedLaw) -> None:
        self.law = law
        self.x = np.asarray(law.breakpoints, dtype=float)

    def __call__(self, t: np.ndarray, nu: int = 0) -> np.ndarray:
        return self.law.derivative(t, nu)


def build_shaped(fields: Mapping[str, Any]) -> ShapedCurve:
    """The builder of the data kind ``shaped``: ``law`` (a law's spec text or a data
    mapping), ``shaper`` (a name of SHAPER_KINDS), ``f_T`` (> 0), ``damping_ratio``
    (default 0), ``vibration_limit`` (the ei shaper's z, default 0.05)."""
    from sizer.laws.data_spec import data_spec_text
    from sizer.laws.registry import make_law

    refuse_unknown(fields, FIELDS, "shaped")
    for key in ("law", "shaper", "f_T"):
        if fields.get(key) is None:
            raise UserError("is required", field=key)
    raw = fields["law"]
    if isinstance(raw, Mapping):
        raw = data_spec_text(raw)
    if not isinstance(raw, str):
        raise UserError(f"must be a law's name or a mapping, got {raw!r}", field="law")
    try:
        base = make_law(raw)
    except UserError as error:
        raise error.located(field="law") from None
    limit = fields.get("vibration_limit")
    if limit is not None:
        limit = as_number(limit, "vibration_limit")
    law = ShapedLaw(base, fields["shaper"], fields["f_T"], fields.get("damping_ratio", 0.0),
                    limit)
    return ShapedCurve(law)
