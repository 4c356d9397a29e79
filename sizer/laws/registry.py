"""Law families by id, aliases, and construction from spec text."""

from __future__ import annotations

from collections.abc import Mapping
from fractions import Fraction
from functools import lru_cache
from typing import Protocol

from sizer.errors import UserError
from sizer.laws.base import LAW_CACHE_SIZE, MotionLaw, law_of
from sizer.laws.blended_constant import CycloidalBlendAcceleration, CycloidalBlends
from sizer.laws.blended_linear import CircularBlends, PolynomialBlends
from sizer.laws.cubic_blends import CubicBlendAcceleration
from sizer.laws.data_law import data_family, data_law_of
from sizer.laws.data_spec import canonical_data_spec, is_data_spec, read_data_spec
from sizer.laws.exponential import Exponential
from sizer.laws.fifteen_segments import FifteenSegments
from sizer.laws.fourier import Freudenstein13, Freudenstein135, Gutman13
from sizer.laws.modified import ModifiedSinusoidal, ModifiedTrapezoidal
from sizer.laws.modified_cycloidal import ModifiedCycloidal
from sizer.laws.piecewise_polynomial import ConstantAcceleration, DoubleS, Trapezoidal
from sizer.laws.polynomial import Polynomial
from sizer.laws.polynomial_434 import Polynomial434
from sizer.laws.spec import AUTO, LawSpec, parse_law_spec
from sizer.laws.trigonometric import Cycloidal, Elliptic, Harmonic

LAW_FAMILIES: Mapping[str, type[MotionLaw]] = {
    cls.law_id: cls
    for cls in (
        ConstantAcceleration, Trapezoidal, DoubleS, Harmonic, Cycloidal, Elliptic, Polynomial,
        ModifiedTrapezoidal, ModifiedSinusoidal, ModifiedCycloidal,
        Gutman13, Freudenstein13, Freudenstein135, Exponential,
        PolynomialBlends, Polynomial434, CircularBlends,
        FifteenSegments,
        CycloidalBlends, CycloidalBlendAcceleration,
        CubicBlendAcceleration,
    )
}

ALIASES: Mapping[str, tuple[str, dict[str, Fraction]]] = {
    "poly3": ("polynomial", {"degree": Fraction(3)}),
    "poly5": ("polynomial", {"degree": Fraction(5)}),
    "poly7": ("polynomial", {"degree": Fraction(7)}),
    "triangular": ("constant_acceleration", {}),
}

DEFAULT_LAW_SPECS: tuple[str, ...] = (
    "constant_acceleration",
    "trapezoidal(alpha=1/3)",
    "double_s(alpha=1/3, beta=1/4)",
    "harmonic",
    "cycloidal",
    "elliptic(n=2)",
    "poly3",
    "poly5",
    "poly7",
    "modified_trapezoidal",
    "modified_sinusoidal",
    "modified_cycloidal",
    "gutman_1_3",
    "freudenstein_1_3",
    "freudenstein_1_3_5",
    "exponential(sigma=7.1, lam=0.2)",
)
"""The laws of ``sizer laws`` when none is named (Table 6.2 plus the other families)."""


def known_law_ids() -> list[str]:
    return sorted([*LAW_FAMILIES, *ALIASES])


def resolve(spec: LawSpec | str) -> tuple[type[MotionLaw], dict[str, Fraction | str]]:
    """The family of a spec and its arguments by parameter name (positional ones named).

    Parsed once per spec text (cached); the dictionary returned is the caller's copy.
    """
    if is_data_spec(spec):
        return data_family(read_data_spec(canonical_spec(spec))["kind"]), {}
    family, values = _resolved(spec)
    return family, dict(values)


Arguments = tuple[tuple[str, Fraction | str], ...]


@lru_cache(maxsize=LAW_CACHE_SIZE)
def _resolved(spec: LawSpec | str) -> tuple[type[MotionLaw], Arguments]:
    if isinstance(spec, str):
        spec = parse_law_spec(spec)
    name, fixed = spec.name, {}
    if name in ALIASES:
        name, fixed = ALIASES[name][0], dict(ALIASES[name][1])
    family = LAW_FAMILIES.get(name)
    if family is None:
        raise UserError(f"unknown law {spec.name!r}; known laws: {', '.join(known_law_ids())}; "
                        f"or a law defined by data, a mapping like {{kind: cubic_spline, "
                        f"points: [[0, 0], [0.5, 0.4], [1, 1]]}}")
    free = [p.name for p in family.parameters if p.name not in fixed]
    values: dict[str, Fraction | str] = dict(fixed)
    for position, (key, value) in enumerate(spec.args):
        if key is None:
            if position >= len(free):
                raise UserError(f"{spec.name}: too many arguments; parameters: "
                                f"{', '.join(free) or 'none'}")
            key = free[position]
        if key in values:
            raise UserError(f"{spec.name}: parameter {key} given twice")
        values[key] = value
    return family, tuple(values.items())


class SpecText(Protocol):
    """A law choice (sizer.laws.choice.LawChoice): what it was read from."""

    @property
    def text(self) -> str: ...


def make_law(spec: LawSpec | str | MotionLaw | SpecText) -> MotionLaw:
    """The law of a spec text, e.g. ``make_law('double_s(alpha=1/3, beta=1/4)')``.

    Laws are built once per canonical spec: two spellings of one law ('double_s',
    'double_s(beta=0.25, alpha=1/3)') give the same object, whose coefficients, grids and
    peak tables are then computed once per process. A law passes through unchanged; a law
    choice gives its law.
    """
    if isinstance(spec, MotionLaw):
        return spec
    if not isinstance(spec, (str, LawSpec)):
        spec = spec.text
    if is_data_spec(spec):
        return data_law_of(canonical_spec(spec))
    return _law_of_text(spec)


def canonical_spec(spec: LawSpec | str) -> str:
    """The canonical text of a law defined by data (``{kind: ...}``); a named spec's text
    as given (its canonical form is its law's ``spec``)."""
    if is_data_spec(spec):
        return _canonical_data(spec)
    return spec if isinstance(spec, str) else spec.name


@lru_cache(maxsize=LAW_CACHE_SIZE)
def _canonical_data(text: str) -> str:
    return canonical_data_spec(text)


@lru_cache(maxsize=LAW_CACHE_SIZE)
def _law_of_text(spec: LawSpec | str) -> MotionLaw:
    family, values = _resolved(spec)
    if any(v == AUTO for _, v in values):
        raise UserError(f"{family.law_id}: 'auto' parameters are chosen by the sizing "
                        f"solver and need a design file; give a number here")
    return law_of(family, {k: float(v) for k, v in values})

