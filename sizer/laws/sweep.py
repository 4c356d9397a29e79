"""Coefficient studies (book sec. 6.2.1, Figs. 6.10 and 6.14): the shape coefficients of a
law family against one or two of its shape parameters.

A sweep is written like a law spec with ranges, ``trapezoidal(alpha=0.05..0.5)``: a
parameter ``name=a..b`` takes ``DEFAULT_POINTS`` evenly spaced values from a to b, ends
included, and ``name=a..b:n`` takes n; the other arguments stay as written
(``double_s(alpha=0.1..0.4:7, beta=1/4)``). With two ranges every pair is a point (the
first range varies fastest within each value of the second). Each point is a law built
from its spec (closed-form coefficients where the family has them, sec. 6.2), so a sweep
reports exactly what ``sizer laws --law`` reports at that point. A point where the family
does not exist (``alpha`` out of its range) keeps its reason and no coefficients.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np

from sizer.errors import UserError
from sizer.laws.coefficients import COEFFICIENT_NAMES
from sizer.laws.spec import spec_number

DEFAULT_POINTS = 21
"""Points of a range written without ``:n``."""
MAX_POINTS = 2001
"""Most points of one sweep (the product of the ranges' points)."""
MAX_RANGES = 2
"""Parameters swept at once."""

_SPEC = re.compile(r"\s*([A-Za-z_]\w*)\s*\((.*)\)\s*\Z", re.DOTALL)
_RANGE = re.compile(r"(?P<a>[^.:][^:]*?)\s*\.\.\s*(?P<b>[^:]+?)\s*(?::\s*(?P<n>[^:]+))?\Z")
EXAMPLE = "e.g. 'trapezoidal(alpha=0.05..0.5)' or 'double_s(alpha=0.1..0.4:7, beta=1/4)'"


@dataclass(frozen=True)
class SweepRange:
    """One swept parameter: ``points`` values from ``start`` to ``stop``, ends included."""

    name: str
    start: float
    stop: float
    points: int

    @property
    def values(self) -> np.ndarray:
        return np.linspace(self.start, self.stop, self.points)


@dataclass(frozen=True)
class SweepSpec:
    """A parsed sweep: the law's name, its ranges and the arguments kept as written."""

    law: str
    ranges: tuple[SweepRange, ...]
    fixed: tuple[str, ...]
    """The other arguments' texts (``beta=1/4``), in the order written."""

    def spec_at(self, values: tuple[float, ...]) -> str:
        """The law spec of one point (the ranges at ``values``, then the fixed ones)."""
        swept = [f"{r.name}={_number_text(v)}" for r, v in zip(self.ranges, values,
                                                                 strict=True)]
        return f"{self.law}({', '.join([*swept, *self.fixed])})"

    def points(self) -> list[tuple[float, ...]]:
        """Every point, the first range varying fastest."""
        grids = [r.values for r in self.ranges]
        if len(grids) == 1:
            return [(float(v),) for v in grids[0]]
        return [(float(a), float(b)) for b in grids[1] for a in grids[0]]


@dataclass(frozen=True)
class SweepPoint:
    """One point of a sweep: the parameters' values, its spec and its coefficients (None
    where the law does not exist there, ``reason`` saying why)."""

    values: tuple[float, ...]
    spec: str
    coefficients: dict[str, float] | None
    jerk_bounded: bool | None = None
    reason: str = ""


@dataclass(frozen=True)
class SweepResult:
    """The coefficients of a law family over its swept parameters."""

    sweep: SweepSpec
    points: tuple[SweepPoint, ...]

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(r.name for r in self.sweep.ranges)

    def column(self, name: str) -> np.ndarray:
        """One coefficient per point (NaN where the law does not exist)."""
        return np.array([np.nan if p.coefficients is None else p.coefficients[name]
                         for p in self.points], dtype=float)


def _number_text(value: float) -> str:
    """A point's value as a spec writes it: the shortest text of the float (scientific
    notation included: 1e-20 is not 0)."""
    return repr(float(value))


def _fraction(text: str, spec: str, what: str) -> float:
    """An end of a range: a number or a fraction as a law spec writes it, within the spec
    parser's limits (sizer.laws.spec.spec_number: no huge exponent)."""
    parts = text.strip().split("/")
    try:
        if len(parts) > 2:
            raise ValueError
        value = float(spec_number(parts[0].strip(), spec) / (
            spec_number(parts[1].strip(), spec) if len(parts) == 2 else 1))
    except (ValueError, ZeroDivisionError, OverflowError):
        raise UserError(f"{what} {text.strip()!r} of {spec!r} is not a number; "
                        f"{EXAMPLE}") from None
    if not np.isfinite(value):
        raise UserError(f"{what} {text.strip()!r} of {spec!r} is not finite")
    return value


def parse_sweep(text: str) -> SweepSpec:
    """The sweep of ``text`` (``name(param=a..b[:n], ...)``); a UserError naming the part
    that cannot be read."""
    match = _SPEC.match(text)
    if match is None:
        raise UserError(f"cannot read the sweep {text!r}: write a law with a range, "
                        f"{EXAMPLE}")
    law, inner = match.group(1).lower(), match.group(2)
    ranges: list[SweepRange] = []
    fixed: list[str] = []
    for part in (p.strip() for p in inner.split(",")):
        if not part:
            raise UserError(f"an empty argument in the sweep {text!r}; {EXAMPLE}")
        key, equal, value = part.partition("=")
        if ".." not in part:
            fixed.append(part)
            continue
        if not equal or not re.fullmatch(r"\s*[A-Za-z_]\w*\s*", key):
            raise UserError(f"a range needs the parameter's name, {part!r} in {text!r}; "
                            f"{EXAMPLE}")
        found = _RANGE.match(value.strip())
        if found is None:
            raise UserError(f"cannot read the range {value.strip()!r} of {text!r}: write "
                            f"a..b or a..b:n")
        start = _fraction(found["a"], text, "the start")
        stop = _fraction(found["b"], text, "the end")
        points = DEFAULT_POINTS
        if found["n"] is not None:
            try:
                points = int(found["n"])
            except ValueError:
                raise UserError(f"the points {found['n']!r} of {text!r} must be a whole "
                                f"number (a..b:n)") from None
            if points < 2:
                raise UserError(f"a range needs at least 2 points, got {points} in "
                                f"{text!r}")
        if start == stop:
            raise UserError(f"the range {value.strip()!r} of {text!r} is empty: its "
                            f"start equals its end")
        ranges.append(SweepRange(key.strip().lower(), start, stop, points))
    if not ranges:
        raise UserError(f"the sweep {text!r} has no range: write one as name=a..b; "
                        f"{EXAMPLE}")
    if len(ranges) > MAX_RANGES:
        raise UserError(f"the sweep {text!r} has {len(ranges)} ranges: sweep one or two "
                        f"parameters at a time")
    if len({r.name for r in ranges}) < len(ranges):
        raise UserError(f"the sweep {text!r} names a parameter twice")
    total = int(np.prod([r.points for r in ranges]))
    if total > MAX_POINTS:
        raise UserError(f"the sweep {text!r} has {total:,} points: the limit is "
                        f"{MAX_POINTS:,}")
    return SweepSpec(law, tuple(ranges), tuple(fixed))


def sweep_coefficients(sweep: SweepSpec | str) -> SweepResult:
    """The coefficients of every point of ``sweep`` (sec. 6.2); a UserError when the law
    exists at none of them (the first point's reason), or names no law."""
    from sizer.laws.registry import make_law  # the families load with a law

    spec = sweep if isinstance(sweep, SweepSpec) else parse_sweep(sweep)
    points = []
    for values in spec.points():
        text = spec.spec_at(values)
        try:
            law = make_law(text)
            c = law.coefficients
            coefficients = {name: float(getattr(c, name)) for name in COEFFICIENT_NAMES}
        except UserError as error:
            if _names_no_law(error):
                raise
            points.append(SweepPoint(values, text, None, None, error.message))
            continue
        points.append(SweepPoint(values, text, coefficients, bool(c.jerk_bounded)))
    if all(p.coefficients is None for p in points):
        first = points[0]
        raise UserError(f"the law exists at no point of the sweep; at {first.spec}: "
                        f"{first.reason}")
    return SweepResult(spec, tuple(points))


def _names_no_law(error: UserError) -> bool:
    """True for an error about the law's name or a parameter it does not have (the same
    at every point: reported at once, not per point)."""
    text = error.message.lower()
    return "unknown law" in text or "unknown parameter" in text or "no parameter" in text
