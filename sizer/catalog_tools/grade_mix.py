"""How a catalog's figures are known: counts of figures per grade (A, B, C, D, ungraded),
read from the file as written (its ``sources:``, ``default_source:`` and each row's
``figure_sources:``). A figure is a field given in a row of ``motors:``, ``drives:`` or
``gearboxes:`` (and their ``ratios:``) that is not a name or a text."""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from typing import Any

from pydantic import BaseModel

from sizer.io.schema.inputs import DriveInput, MotorInput
from sizer.io.schema.provenance import figure_names
from sizer.io.schema.transmission_inputs import GearboxRatioInput, GearboxSeriesInput

GRADE_KEYS = ("A", "B", "C", "D", "ungraded")


@dataclass
class GradeMix:
    """Figures per grade."""

    counts: dict[str, int] = field(default_factory=lambda: dict.fromkeys(GRADE_KEYS, 0))

    @property
    def total(self) -> int:
        return sum(self.counts.values())

    def add(self, other: GradeMix) -> GradeMix:
        for key, count in other.counts.items():
            self.counts[key] += count
        return self

    def text(self) -> str:
        """'A 120, B 4, C 2, D 0, ungraded 0 (126 figures)'."""
        counts = ", ".join(f"{key} {self.counts[key]}" for key in GRADE_KEYS)
        return f"{counts} ({self.total} figures)"


def total(mixes: Iterable[GradeMix]) -> GradeMix:
    out = GradeMix()
    for mix in mixes:
        out.add(mix)
    return out


def _rows(data: dict[str, Any]) -> Iterator[tuple[dict[str, Any], type[BaseModel]]]:
    for key, model in (("motors", MotorInput), ("drives", DriveInput),
                       ("gearboxes", GearboxSeriesInput)):
        rows = data.get(key)
        for row in rows if isinstance(rows, list) else ():
            if not isinstance(row, dict):
                continue
            yield row, model
            ratios = row.get("ratios") if model is GearboxSeriesInput else None
            for ratio in ratios if isinstance(ratios, list) else ():
                if isinstance(ratio, dict):
                    yield ratio, GearboxRatioInput


def grade_mix(data: Any) -> GradeMix:
    """The grade mix of a catalog's data (a mapping from YAML); what is not well formed
    counts as ungraded (the schema reports it)."""
    mix = GradeMix()
    if not isinstance(data, dict):
        return mix
    given = data.get("sources")
    sources: dict[str, Any] = given if isinstance(given, dict) else {}
    default = data.get("default_source")
    names: dict[type[BaseModel], frozenset[str]] = {
        model: frozenset(figure_names(model))
        for model in (MotorInput, DriveInput, GearboxSeriesInput, GearboxRatioInput)}
    for row, model in _rows(data):
        named = row.get("figure_sources")
        named = named if isinstance(named, dict) else {}
        for figure in row:
            if figure in names[model]:
                key = named.get(figure, default)
                source = sources.get(key.strip()) if isinstance(key, str) else None
                mix.counts[_grade(source)] += 1
    return mix


def _grade(source: Any) -> str:
    grade = source.get("grade") if isinstance(source, dict) else None
    return grade if grade in GRADE_KEYS[:4] else "ungraded"
