"""A motion law defined by data: a curve q(t) normalized into q_N(tau) (book ch. 4).

The curve of a data-defined law (a spline through via-points, a B-spline, a NURBS, a cam
table) runs over [t_0, t_n]; the law is q_N(tau) = (q(t_0 + tau D) - q_0) / S with
D = t_n - t_0 and S its displacement q_n - q_0, or, for a curve that returns to its start
(a cam that goes out and back), its largest excursion from the start. Its k-th
derivative is D^k q^(k) / S (sec. 6.2 scaling). On a piecewise polynomial curve
(``scipy.interpolate.PPoly``) every piece is evaluated from its own coefficients, so the
one-sided values at the breakpoints are exact and the coefficients are exact (peaks at
the roots of the next derivative, Gauss-Legendre integrals exact for polynomials).

Unlike the rest-to-rest laws, a data-defined law may start and end moving (a periodic
electronic cam, sec. 4.4.2): ``rest_to_rest`` says which; its continuity class counts
its joins, its ends against rest or, when the ends move, against each other (the
period's wrap).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cached_property, lru_cache
from typing import Any, ClassVar

import numpy as np

from sizer.errors import UserError
from sizer.input_limits import MAX_DATA_LAW_EXCURSION
from sizer.laws.base import LAW_CACHE_SIZE, MotionLaw
from sizer.laws.coefficients import measured_continuity, peak
from sizer.laws.data_spec import DATA_LAW_KINDS, read_data_spec
from sizer.laws.multipoint import Curve, FittedCurve
from sizer.laws.piece_table import PieceTable
from sizer.laws.pieces import Piece

REST_TOLERANCE = 1e-9
"""|v_N| at an end below which the law starts or ends at rest; also the relative size of
a jump that counts as a discontinuity in the continuity class."""

RETURN_TOLERANCE = 1e-12
"""|q_n - q_0| over the curve's excursion below which the curve returns to its start."""

INTERVAL_BUDGET = 16_384
"""Uniform intervals shared among the polynomial pieces of a law for every scan and grid
of it (Piece.intervals): a spline of a few pieces keeps the callers' own counts (up to
1024 a piece), a cam table of 100,000 rows gets 2 a piece, so that the work of every
command grows with the rows, not with the rows times a fixed count per piece."""

MIN_PIECE_INTERVALS = 2
"""Fewest uniform intervals of a piece in a scan (its ends and middle)."""


def pieces_intervals(pieces: int) -> int:
    """The uniform intervals a piece of a law of ``pieces`` polynomial pieces needs."""
    return max(MIN_PIECE_INTERVALS, INTERVAL_BUDGET // max(pieces, 1))


def data_overflow(spec: str, what: str = "its coefficients") -> UserError:
    """The error for data whose law is not finite in double precision (an overflow)."""
    return UserError(f"the law these data make is not finite in double precision "
                     f"({what} overflow): the values are too large, or the times too "
                     f"close for their positions", field=_largest_field(spec))


HUGE_DATA = 1e100
"""A data value of this magnitude or more (or a nonzero one this small): an error of the
fit is read as an overflow of the data."""


def _data_numbers(fields: Mapping[str, Any]) -> list[tuple[float, str]]:
    """(|value|, field) of every number of a data law's lists and conditions, e.g.
    (8e299, 'positions[2]'); a pair of ``points`` is named as the user wrote it."""
    found: list[tuple[float, str]] = []

    def walk(value: Any, path: str) -> None:
        if isinstance(value, Mapping):
            for key, item in value.items():
                walk(item, f"{path}.{key}" if path else str(key))
        elif isinstance(value, list | tuple):
            for i, item in enumerate(value):
                walk(item, f"{path}[{i}]")
        elif (isinstance(value, int | float) and not isinstance(value, bool)
              and ("[" in path or "." in path)):  # a list or a condition, not order: 4
            found.append((abs(float(value)), path))

    walk({k: v for k, v in fields.items() if k not in ("kind", "units", "name")}, "")
    return [(size, path[:path.index("]") + 1] if path.startswith("points[") else path)
            for size, path in found]


def _extreme(fields: Mapping[str, Any]) -> bool:
    """True when a number of the data has a magnitude of HUGE_DATA or more, or a nonzero
    one of 1 / HUGE_DATA or less."""
    return any(v >= HUGE_DATA or 0.0 < v <= 1.0 / HUGE_DATA for v, _ in _data_numbers(fields))


def _largest_field(spec: str) -> str | None:
    """The data field, e.g. ``positions[2]``, of the number of largest magnitude in a
    data-law spec (the likely cause of an overflow), or None."""
    try:
        numbers = _data_numbers(read_data_spec(spec))
    except UserError:
        return None
    return max(numbers, key=lambda number: number[0])[1] if numbers else None


@dataclass(frozen=True)
class LawScale:
    """The absolute size of a law whose data carry units: its displacement (or stroke
    for a curve that returns), in m or rad, and the span of its abscissa: a duration in
    s or, for a cam on a master axis, a master angle in rad."""

    displacement: float
    linear: bool
    span: float
    master: bool


class DataLaw(MotionLaw):
    """A law built from a curve; ``spec`` is the canonical text of its mapping."""

    law_id: ClassVar[str] = "data"
    title: ClassVar[str] = "Law defined by data"

    def __init__(self, spec: str, curve: Curve, scale: LawScale | None = None,
                 report: Any = None) -> None:
        self._spec_text = spec
        self.curve = curve
        self.scale = scale
        self.report = report
        """What the builder says about the fit (a cam table's fit error and noise)."""
        x = np.asarray(curve.x, dtype=float)
        self._t0, self._span = float(x[0]), float(x[-1] - x[0])
        self._q0 = float(np.asarray(curve(np.array([x[0]]), 0))[0])
        self._size = 1.0
        super().__init__()
        self._size = self._normalizer()
        self.breakpoints = np.append(self._starts, 1.0)
        self.continuity = self._measured_continuity()
        self._check_finite()

    @cached_property
    def spec(self) -> str:
        return self._spec_text

    def __reduce__(self) -> tuple[Any, ...]:
        """Pickled as its spec, built again through :func:`data_law_of`'s cache."""
        return data_law_of, (self.spec,)

    def piece_table(self) -> PieceTable | None:
        """The polynomial pieces as one table (a PPoly curve), None for a NURBS."""
        rows = getattr(self, "_rows", None)
        if rows is None:
            return None
        return PieceTable(self._starts, np.append(self._starts[1:], 1.0), tuple(rows),
                          self._q0, self._size)

    # ------------------------------------------------------------ the curve
    def _build(self) -> tuple[list[Piece], float]:
        x = np.asarray(self.curve.x, dtype=float)
        taus = (x - self._t0) / self._span
        taus[0], taus[-1] = 0.0, 1.0
        coefficients = getattr(self.curve, "c", None)  # a PPoly's (a NURBS has none)
        if coefficients is not None:
            return self._polynomial_pieces(taus, coefficients), 0.0
        pieces = [self._curve_piece(taus[i], taus[i + 1], x[i], x[i + 1])
                  for i in range(len(x) - 1)]
        return pieces, 0.0  # continuity measured once the normalizer is known

    def _polynomial_pieces(self, taus: np.ndarray, coefficients: np.ndarray) -> list[Piece]:
        """The pieces of a PPoly from its own coefficients, in tau: their one-sided
        values at both ends are exact. The Taylor coefficients of every derivative of
        every piece are computed at once (arrays (pieces, terms)); each piece evaluates
        its row by Horner's scheme."""
        c = np.asarray(coefficients, dtype=np.float64)
        m = c.shape[0] - 1
        # in u = tau - start: q(t) = sum_p local[:, p] u^p, local = c[m - p] D^p
        with np.errstate(over="ignore", invalid="ignore"):
            local = (c[::-1] * self._span ** np.arange(m + 1.0)[:, None]).T
        if not np.all(np.isfinite(local)):
            raise data_overflow(self._spec_text)
        nonzero = local != 0.0
        degree = np.where(nonzero.any(axis=1), m - np.argmax(nonzero[:, ::-1], axis=1), 0)
        rows = [local]
        for _ in range(self.max_order):
            last = rows[-1]
            rows.append(last[:, 1:] * np.arange(1.0, last.shape[1]) if last.shape[1] > 1
                        else np.zeros_like(last))
        self._rows = rows
        intervals = pieces_intervals(len(taus) - 1)
        return [Piece(float(taus[i]), float(taus[i + 1]), self._row_evaluator(i, float(taus[i])),
                      int(degree[i]), intervals) for i in range(len(taus) - 1)]

    def _row_evaluator(self, index: int, start: float) -> Any:
        rows = self._rows

        def evaluate(tau: np.ndarray, order: int) -> np.ndarray:
            coef = rows[order][index].tolist()  # Python floats: Horner on small arrays
            u = tau - start
            out = coef[-1] + u * 0.0
            for value in coef[-2::-1]:
                out = value + out * u
            return ((out - self._q0) if order == 0 else out) / self._size

        return evaluate

    def _curve_piece(self, start: float, end: float, left: float, right: float) -> Piece:
        """A piece of a general curve (a NURBS): evaluated inside [left, right], a point
        on the right end read one ulp inside so that it takes this piece's side."""
        inside = np.nextafter(right, left)

        def evaluate(tau: np.ndarray, order: int) -> np.ndarray:
            t = np.clip(self._t0 + tau * self._span, left, inside)
            value = np.asarray(self.curve(t, order), dtype=float) * self._span ** order
            return ((value - self._q0) if order == 0 else value) / self._size

        return Piece(float(start), float(end), evaluate, None)

    def _normalizer(self) -> float:
        """S: the displacement, or the largest excursion of a curve that returns."""
        end = float(self.piece_derivative(len(self.pieces) - 1, 1.0, 0))
        excursion = peak(self, 0)[0]
        if not (math.isfinite(end) and math.isfinite(excursion)):
            raise data_overflow(self._spec_text, "its positions")
        if excursion <= 0.0:
            raise UserError("the curve does not move: every point has the same position",
                            field="points")
        if abs(end) > RETURN_TOLERANCE * excursion:
            if excursion > MAX_DATA_LAW_EXCURSION * abs(end):
                raise UserError(f"the curve swings {excursion / abs(end):.3g} times its "
                                f"displacement {end:.6g} away from its start: the limit is "
                                f"{MAX_DATA_LAW_EXCURSION:.0e} (MAX_DATA_LAW_EXCURSION); "
                                f"check the data's magnitudes",
                                field=_largest_field(self._spec_text))
            return end
        return excursion

    def _check_finite(self) -> None:
        """UserError unless every coefficient of the normalized law is finite."""
        values = self.coefficients.as_dict()
        bad = [name for name, value in values.items() if not math.isfinite(value)]
        if bad:
            raise data_overflow(self._spec_text, ", ".join(bad))

    # ----------------------------------------------------------- the shape
    @cached_property
    def end_position(self) -> float:
        """q_N(1): 1, or 0 for a curve that returns to its start."""
        value = float(self.piece_derivative(len(self.pieces) - 1, 1.0, 0))
        return 1.0 if abs(value - 1.0) < 1e-9 else 0.0 if abs(value) < 1e-9 else value

    @cached_property
    def end_speeds(self) -> tuple[float, float]:
        """v_N(0) and v_N(1) (normalized), zero for a rest-to-rest law."""
        first = float(self.piece_derivative(0, 0.0, 1))
        last = float(self.piece_derivative(len(self.pieces) - 1, 1.0, 1))
        report = self.report or {}
        rest = (report.get("rest_start") == 1.0, report.get("rest_end") == 1.0)
        # a cam table at rest within its resolution (sizer.laws.cam_interpolation): its
        # fit is clamped to v = 0 there, or, a broken line (order 2), steps from rest at
        # its end as it does at every sample
        return tuple(0.0 if abs(v) < REST_TOLERANCE or at_rest  # type: ignore[return-value]
                     else v for v, at_rest in zip((first, last), rest, strict=True))

    @property
    def rest_to_rest(self) -> bool:
        return self.end_speeds == (0.0, 0.0)

    def wraps(self, order: int) -> bool:
        """True when q_N^(order) takes the same value at both ends (a periodic join)."""
        first = float(self.piece_derivative(0, 0.0, order))
        last = float(self.piece_derivative(len(self.pieces) - 1, 1.0, order))
        return abs(first - last) <= REST_TOLERANCE * max(1.0, abs(first), abs(last))

    @property
    def periodic(self) -> bool:
        """Ends that move and join as one period of a repeated motion: speed and
        acceleration equal at tau = 0 and 1 (sec. 4.4.2)."""
        return not self.rest_to_rest and self.wraps(1) and self.wraps(2)

    def outside(self, order: int) -> tuple[float, float]:
        """q_N^(order) just before tau = 0 and just after tau = 1: at rest (the start,
        the end position) for a law that rests at its ends; the wrap of the period
        otherwise (the end's value before, the start's after)."""
        if order == 0:
            return 0.0, self.end_position
        if self.rest_to_rest:
            return 0.0, 0.0
        return (float(self.piece_derivative(len(self.pieces) - 1, 1.0, order)),
                float(self.piece_derivative(0, 0.0, order)))

    def _measured_continuity(self) -> float:
        """The largest k with q_N C^k at every join and at the ends (sec. 6.2)."""
        return float(measured_continuity(self))

    def derivative(self, tau: np.ndarray | float, order: int = 0) -> np.ndarray:
        out = super().derivative(tau, order)
        if order == 0 and self.end_position != 1.0:
            out = np.where(np.asarray(tau, dtype=float) > 1.0, self.end_position, out)
        return out


# ------------------------------------------------------------------ building
def data_family(kind: str) -> type[DataLaw]:
    """The law class of a data kind (``law_id`` is the kind), one per kind."""
    if kind not in _FAMILIES:
        entry = DATA_LAW_KINDS[kind]
        _FAMILIES[kind] = type(f"DataLaw_{kind}", (DataLaw,),
                               {"law_id": kind, "title": entry.title,
                                "__doc__": f"{entry.title}: a law defined by data."})
    return _FAMILIES[kind]


_FAMILIES: dict[str, type[DataLaw]] = {}


@lru_cache(maxsize=LAW_CACHE_SIZE)
def data_law_of(text: str) -> MotionLaw:
    """The law of a canonical data-spec text, built once per process (the one
    sizer.laws.make_law gives; a data law and a shaped law unpickle through it)."""
    return build_data_law(text)


def build_data_law(text: str) -> DataLaw:
    """The law of a canonical data-spec text: its kind's builder reads the fields, the
    curve is normalized, and the units (field ``units``, or those the data carry) give
    its absolute size. UserError (with the field) for bad data."""
    fields = read_data_spec(text)
    kind = DATA_LAW_KINDS[fields["kind"]]
    units = _unit_texts(fields.pop("units", None))
    name = fields.pop("name", None)
    if name is not None and not isinstance(name, str):
        raise UserError(f"must be a text, got {name!r}", field="name")
    # data near the float range overflow inside the fits and the law's measures: the
    # results are checked (finite coefficients, a finite law), the warnings not shown
    with np.errstate(over="ignore", invalid="ignore", divide="ignore", under="ignore"):
        return _built_law(text, kind, fields, units, name)


def _built_law(text: str, kind: Any, fields: dict[str, Any],
               units: tuple[str | None, str | None], name: str | None) -> DataLaw:
    extreme = _extreme(fields)  # before the builder reads (and may consume) the fields
    try:
        built = kind.build()(fields)
    except (ValueError, ZeroDivisionError, OverflowError, np.linalg.LinAlgError):
        if not extreme:
            raise
        raise data_overflow(text, "the fit's numbers") from None
    exact = getattr(built, "law", None)
    if isinstance(exact, MotionLaw) and units == (None, None) and name is None:
        return exact  # type: ignore[return-value]  # a law of its own (a shaped law)
    report: dict[str, float] = {}
    if isinstance(built, FittedCurve):
        report = dict(built.report)
        units = (units[0] or built.units[0], units[1] or built.units[1])
        built = built.curve
    law = data_family(kind.name)(text, built, None, report)
    law.scale = _scale(law, units)
    return law


def _unit_texts(raw: Any) -> tuple[str | None, str | None]:
    if raw is None:
        return None, None
    if not isinstance(raw, dict) or set(raw) - {"time", "position"}:
        raise UserError("must be a mapping like {time: ms, position: mm} (time may be a "
                        "master angle unit like deg)", field="units")
    return tuple(None if raw.get(k) is None else str(raw[k])  # type: ignore[return-value]
                 for k in ("time", "position"))


def _scale(law: DataLaw, units: tuple[str | None, str | None]) -> LawScale | None:
    """The law's absolute size from its units; None when they are not both known."""
    from sizer.units import is_angle_unit, parse_displacement, to_si

    time_unit, position_unit = units
    if time_unit is None or position_unit is None:
        return None
    try:
        size, linear = parse_displacement(f"1 {position_unit}", field="units.position")
    except UserError as error:
        raise _at_unit(error, position_unit) from None
    master = is_angle_unit(time_unit)
    try:
        span = to_si(f"1 {time_unit}", "angle" if master else "time", field="units.time")
    except UserError:
        raise _at_unit(UserError(f"expected a time unit like 's' or 'ms', or a master angle "
                                 f"unit like 'deg', got {time_unit!r}", field="units.time"),
                       time_unit) from None
    return LawScale(displacement=law._size * size, linear=linear,
                    span=law._span * span, master=master)


def _at_unit(error: UserError, unit: str) -> UserError:
    """The error at the place its unit is written when the unit knows it (a cam table's
    header cell: sizer.io.cam_table_law.HeaderUnit), else as raised."""
    where = getattr(unit, "where", None)
    return error if where is None else UserError(error.message, **where)
