"""Text for numbers: exact for machines (CSV, JSON), short for people (tables)."""

from __future__ import annotations

import math
from collections.abc import Iterable
from fractions import Fraction

SIGNIFICANT_DIGITS = 5
"""Significant digits of numbers in human-readable tables."""


def full(value: float) -> str:
    """The shortest text that reads back to exactly the same float (repr of a float)."""
    return repr(float(value))


def short(value: float, digits: int = SIGNIFICANT_DIGITS) -> str:
    """A number rounded to a few significant digits for a table, e.g. '6.2832'."""
    value = float(value)
    if value == 0.0:
        return "0"  # also turns -0.0 into 0
    return f"{value:.{digits}g}"


def finite_or_none(value: float | None) -> float | None:
    """A float for JSON: None (null) for a missing or non-finite number."""
    if value is None:
        return None
    value = float(value)
    return value if math.isfinite(value) else None


def full_or_empty(value: float | None) -> str:
    """A CSV cell: :func:`full`, or empty for a missing or non-finite number."""
    return "" if value is None or not math.isfinite(value) else full(value)


NOT_A_NUMBER = "n/a"
"""How a table shows a figure that is not a number (none, or not finite: a law that breaks
a linkage's dead-point rule has no peak torque; its failed check says why)."""


def short_or_na(value: float | None, scale: float = 1.0, unit: str = "") -> str:
    """:func:`short` of ``value * scale`` with its unit, or :data:`NOT_A_NUMBER` (no
    unit) for None, inf or NaN."""
    if value is None or not math.isfinite(float(value) * scale):
        return NOT_A_NUMBER
    return short(float(value) * scale) + (f" {unit}" if unit else "")


NOISE = 1e-12
"""Relative size, against the largest value of a column, below which a value is rounding."""


def short_column(values: Iterable[float], digits: int = SIGNIFICANT_DIGITS) -> list[str]:
    """Short texts for one column; rounding noise (e.g. 3e-15 next to 246.7) shows as 0."""
    values = [float(v) for v in values]
    scale = max((abs(v) for v in values if math.isfinite(v)), default=0.0)
    return [short(0.0 if abs(v) <= NOISE * scale else v, digits) for v in values]


def fraction_or_short(value: float, max_denominator: int = 100) -> str:
    """'1/3' when the value is a small fraction to rounding error, else a short number."""
    value = float(value)
    if math.isfinite(value):
        frac = Fraction(value).limit_denominator(max_denominator)
        if abs(float(frac) - value) <= 1e-12 * max(1.0, abs(value)):
            return str(frac)
    return short(value)


def continuity_value(k: float) -> int | str:
    """The continuity class for JSON and CSV: an int k, or the string 'inf'."""
    return "inf" if math.isinf(k) else int(k)


def continuity_text(k: float, *, unicode: bool = False) -> str:
    """The continuity class for a table: 'C^2' and 'C^inf', or 'C²' and 'C∞'."""
    if not unicode:
        return f"C^{continuity_value(k)}"
    if math.isinf(k):
        return "C∞"
    superscripts = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")
    return "C" + str(int(k)).translate(superscripts)
