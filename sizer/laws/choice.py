"""A law choice as the input gives it, read once: its text, family, values, ``auto`` names.

A design's ``laws:``, ``check.law``, a cycle move's ``law`` and the CLI's ``--law`` are spec
texts (sizer.laws.spec, or a data law's canonical mapping text, sizer.laws.data_spec). They
become :class:`LawChoice` objects where the input is read; the engine and the reports read
the parsed parts from it instead of parsing the text again.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from functools import lru_cache

from sizer.laws.base import LAW_CACHE_SIZE, MotionLaw
from sizer.laws.open_shaped import is_open_shaped
from sizer.laws.registry import canonical_spec, make_law, resolve
from sizer.laws.spec import AUTO


@dataclass(frozen=True, eq=False)
class LawChoice:
    """One law choice: ``text`` as written (a mapping's canonical text), what reports print;
    ``family``; ``values`` by parameter name (an alias's fixed ones first, ``'auto'`` for
    a parameter the solver chooses); ``open_shaped``: a shaped law without ``f_T``, shaped
    for the load's mode at each duration (sizer.laws.open_shaped).

    A choice is known by its text: it equals (and hashes like) its text, so a choice
    and the spec it was read from find each other in sets and comparisons."""

    text: str
    family: type[MotionLaw]
    values: tuple[tuple[str, Fraction | str], ...] = ()
    open_shaped: bool = False

    @property
    def auto(self) -> tuple[str, ...]:
        """The names of the ``auto`` parameters, in the family's order."""
        return tuple(p.name for p in self.family.parameters
                     if dict(self.values).get(p.name) == AUTO)

    @property
    def fixed(self) -> dict[str, Fraction]:
        """The values given as numbers, by parameter name."""
        return {k: v for k, v in self.values if isinstance(v, Fraction)}

    @property
    def is_fixed(self) -> bool:
        """One law: no ``auto`` parameter and not shaped at each duration."""
        return not self.open_shaped and all(v != AUTO for _, v in self.values)

    @property
    def law(self) -> MotionLaw:
        """The law itself (built once per canonical spec: sizer.laws.make_law); a
        UserError for a choice that is not :attr:`is_fixed`."""
        return make_law(self.text)

    def __str__(self) -> str:
        return self.text

    def __eq__(self, other: object) -> bool:
        if isinstance(other, LawChoice):
            return self.text == other.text
        return isinstance(other, str) and self.text == other

    def __hash__(self) -> int:
        return hash(self.text)

    def __reduce__(self) -> tuple[object, tuple[str]]:
        """Pickled as its text (a data law's family is made at run time: sizer.laws.
        data_law.data_family), read again in the process that loads it."""
        return law_choice, (self.text,)


def law_choice(spec: LawChoice | str) -> LawChoice:
    """The choice of a spec text (parsed once per text); a choice passes through. A
    UserError for a text that names no law."""
    return spec if isinstance(spec, LawChoice) else _choice(spec)


@lru_cache(maxsize=LAW_CACHE_SIZE)
def _choice(text: str) -> LawChoice:
    family, values = resolve(text)
    canonical = canonical_spec(text)
    return LawChoice(canonical, family, tuple(values.items()), is_open_shaped(canonical))
