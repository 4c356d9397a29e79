"""The law spec grammar: ``name`` or ``name(arg, key=value, ...)``.

    spec  := NAME [ "(" [ arg ("," arg)* ] ")" ]
    arg   := [ NAME "=" ] value
    value := NUMBER [ "/" NUMBER ] | "auto"

Numbers are decimal or scientific; fractions like 1/3 are exact (fractions.Fraction).
No eval. ``auto`` marks a shape parameter left to the solver. The work is bounded
(sizer.input_limits): a spec of at most MAX_LAW_SPEC_CHARS characters, numbers of at most
MAX_NUMBER_CHARS characters with a decimal exponent of at most MAX_EXPONENT (``1e999999999``
would build a huge exact Fraction), ASCII digits only; ``nan`` and ``inf`` are refused.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from fractions import Fraction

from sizer.errors import UserError
from sizer.input_limits import MAX_EXPONENT, MAX_LAW_SPEC_CHARS, MAX_NUMBER_CHARS

AUTO = "auto"

_TOKEN = re.compile(
    r"\s*(?:(?P<number>[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)"
    r"|(?P<name>[A-Za-z_][A-Za-z0-9_]*)|(?P<punct>[(),=/]))",
    re.ASCII,
)
_EXPONENT = re.compile(r"[eE]([+-]?\d+)$")
_NON_FINITE = frozenset({"nan", "inf", "infinity"})
_FLOAT_MAX = Fraction(1.7976931348623157e308)


@dataclass(frozen=True)
class LawSpec:
    """A parsed spec: the law name and its arguments (positional ones have key None)."""

    name: str
    args: tuple[tuple[str | None, Fraction | str], ...] = ()


def _tokens(text: str) -> list[tuple[str, str]]:
    if len(text) > MAX_LAW_SPEC_CHARS:
        raise UserError(f"a law spec of {len(text):,} characters: the limit is "
                        f"{MAX_LAW_SPEC_CHARS} (e.g. 'double_s(alpha=1/3, beta=1/4)')")
    tokens, pos = [], 0
    text = text.rstrip()
    while pos < len(text):
        match = _TOKEN.match(text, pos)
        if not match or match.end() == pos:
            rest = text[pos:].strip()
            if re.match(r"[+-]?(nan|inf)", rest, re.IGNORECASE):
                raise UserError(f"cannot read law spec {_short(text)}: {rest.rstrip(')')!r} is "
                                f"not a finite number; a parameter must be a finite number "
                                f"like 0.25 or 1/3, or 'auto'")
            raise UserError(f"cannot read law spec {_short(text)} at "
                            f"{rest if len(rest) <= 30 else rest[:27] + '...'!r}")
        kind = match.lastgroup
        assert kind is not None  # every alternative of the pattern is a named group
        tokens.append((kind, match.group(kind)))
        pos = match.end()
    return tokens


def parse_law_spec(text: str) -> LawSpec:
    """Parse ``trapezoidal(alpha=1/3)`` and the like into a LawSpec."""
    tokens = _tokens(text)
    expected = "expected e.g. 'cycloidal' or 'trapezoidal(alpha=1/3)'"
    if not tokens or tokens[0][0] != "name":
        raise UserError(f"cannot read law spec {text!r}: {expected}")
    name = tokens[0][1].lower()
    rest = tokens[1:]
    if not rest:
        return LawSpec(name)
    if rest[0] != ("punct", "(") or rest[-1] != ("punct", ")"):
        raise UserError(f"cannot read law spec {text!r}: {expected}")
    inner = rest[1:-1]
    args: list[tuple[str | None, Fraction | str]] = []
    groups: list[list[tuple[str, str]]] = [[]]
    for token in inner:
        if token == ("punct", ","):
            groups.append([])
        else:
            groups[-1].append(token)
    if groups == [[]]:
        return LawSpec(name)
    for group in groups:
        key = None
        if len(group) >= 2 and group[0][0] == "name" and group[1] == ("punct", "="):
            key, group = group[0][1].lower(), group[2:]
        args.append((key, _value(group, text)))
    return LawSpec(name, tuple(args))


def spec_number(token: str, text: str) -> Fraction:
    """The exact value of a number token, refused before any huge work."""
    exponent = _EXPONENT.search(token)
    if len(token) > MAX_NUMBER_CHARS or (exponent and abs(int(exponent.group(1))) > MAX_EXPONENT):
        shown = token if len(token) <= 30 else f"{token[:27]}..."
        raise UserError(f"cannot read law spec {_short(text)}: the number {shown!r} is out of "
                        f"range (at most {MAX_NUMBER_CHARS} characters and an exponent of at "
                        f"most {MAX_EXPONENT}; parameters are finite numbers like 0.25 or 1/3)")
    return Fraction(token)


def _short(text: str) -> str:
    shown = repr(text)
    return shown if len(shown) <= 80 else f"{shown[:77]}...'"


def _value(group: list[tuple[str, str]], text: str) -> Fraction | str:
    kinds = [k for k, _ in group]
    values = [v for _, v in group]
    if kinds and kinds[-1] == "name" and values[-1].lower() in _NON_FINITE:
        raise UserError(f"cannot read law spec {_short(text)}: {''.join(values)!r} is not a "
                        f"finite number; a parameter must be a finite number like 0.25 or 1/3, "
                        f"or 'auto'")
    try:
        if kinds == ["name"] and values[0].lower() == AUTO:
            return AUTO
        value = None
        if kinds == ["number"]:
            value = spec_number(values[0], text)
        if kinds == ["number", "punct", "number"] and values[1] == "/":
            value = spec_number(values[0], text) / spec_number(values[2], text)
    except (ValueError, ZeroDivisionError):
        value = None
    if value is not None:
        if abs(value) > _FLOAT_MAX:
            raise UserError(f"cannot read law spec {_short(text)}: {''.join(values)!r} is too "
                            f"large, beyond the float range; a parameter must be a finite number "
                            f"like 0.25 or 1/3")
        return value
    shown = "".join(values) or "nothing"
    raise UserError(f"cannot read law spec {text!r}: {shown!r} is not a number, "
                    f"a fraction like 1/3, or 'auto'")
