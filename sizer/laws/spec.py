"""The law spec grammar: ``name`` or ``name(arg, key=value, ...)``.

    spec  := NAME [ "(" [ arg ("," arg)* ] ")" ]
    arg   := [ NAME "=" ] value
    value := NUMBER [ "/" NUMBER ] | "auto"

Numbers are decimal or scientific; fractions like 1/3 are exact (fractions.Fraction).
No eval. ``auto`` marks a shape parameter left to the solver.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from fractions import Fraction

from sizer.errors import UserError

AUTO = "auto"

_TOKEN = re.compile(
    r"\s*(?:(?P<number>[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)"
    r"|(?P<name>[A-Za-z_][A-Za-z0-9_]*)|(?P<punct>[(),=/]))"
)


@dataclass(frozen=True)
class LawSpec:
    """A parsed spec: the law name and its arguments (positional ones have key None)."""

    name: str
    args: tuple[tuple[str | None, Fraction | str], ...] = ()


def _tokens(text: str) -> list[tuple[str, str]]:
    tokens, pos = [], 0
    text = text.rstrip()
    while pos < len(text):
        match = _TOKEN.match(text, pos)
        if not match or match.end() == pos:
            raise UserError(f"cannot read law spec {text!r} at {text[pos:].strip()!r}")
        kind = match.lastgroup
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


def _value(group: list[tuple[str, str]], text: str) -> Fraction | str:
    kinds = [k for k, _ in group]
    values = [v for _, v in group]
    try:
        if kinds == ["name"] and values[0].lower() == AUTO:
            return AUTO
        if kinds == ["number"]:
            return Fraction(values[0])
        if kinds == ["number", "punct", "number"] and values[1] == "/":
            return Fraction(values[0]) / Fraction(values[2])
    except (ValueError, ZeroDivisionError):
        pass
    shown = "".join(values) or "nothing"
    raise UserError(f"cannot read law spec {text!r}: {shown!r} is not a number, "
                    f"a fraction like 1/3, or 'auto'")
