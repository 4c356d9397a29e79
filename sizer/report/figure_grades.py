"""The provenance of catalog figures as the reports show it: each figure's grade (A, B, C,
D; '-' ungraded) and a numbered list of the sources, shared by the figures that cite the
same one. Nothing is decided here: the grades are the catalog's (sizer.model.domain)."""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from sizer.model.domain import (
    GRADES,
    Motor,
    Provenance,
    ServoDrive,
    figure_provenance,
)

if TYPE_CHECKING:
    from sizer.sizing import CandidateResult

UNGRADED = "ungraded"


class SourceIndex:
    """Sources numbered from 1 in the order they are first cited."""

    def __init__(self) -> None:
        self.sources: dict[Provenance, int] = {}

    def number(self, provenance: Provenance | None) -> int | None:
        if provenance is None:
            return None
        return self.sources.setdefault(provenance, len(self.sources) + 1)

    def label(self, provenance: Provenance | None) -> str:
        """'A1' (grade, source number) or '-' (ungraded)."""
        if provenance is None:
            return "-"
        return f"{provenance.grade}{self.number(provenance)}"

    def json(self) -> list[dict[str, Any]]:
        return [{"number": n, "grade": p.grade, "text": p.text}
                for p, n in self.sources.items()]


def grade_counts(item: Motor | ServoDrive) -> str:
    """'A 8, C 2' (figures per grade), 'ungraded' where none has a grade."""
    counts = Counter(UNGRADED if p is None else p.grade
                     for p in figure_provenance(item).values())
    parts = [f"{grade} {counts[grade]}" for grade in (*GRADES, UNGRADED) if counts[grade]]
    if parts == [f"{UNGRADED} {counts[UNGRADED]}"]:
        return UNGRADED
    return ", ".join(parts)


def cited_sources(item: Motor | ServoDrive) -> list[str]:
    """The sources of an item's figures, 'grade A: <text>', by grade; its ``source`` text
    where its figures are ungraded."""
    cited = {p for p in figure_provenance(item).values() if p is not None}
    texts = [f"grade {p.grade}: {p.text}" for p in sorted(cited, key=lambda p: (p.grade,
                                                                              p.text))]
    if item.source and (not cited or None in figure_provenance(item).values()):
        texts.append(item.source)
    return list(dict.fromkeys(texts))


def _figures(item: Motor | ServoDrive, index: SourceIndex) -> dict[str, Any]:
    return {"source": item.source, "grades": grade_counts(item),
            "figures": {name: {"grade": UNGRADED if p is None else p.grade,
                               "source": index.number(p)}
                        for name, p in figure_provenance(item).items()}}


def provenance_json(motors: Iterable[Motor], drives: Iterable[ServoDrive] = ()
                    ) -> dict[str, Any]:
    """{"sources": [{number, grade, text}], "motors": {id: {source, grades, figures:
    {field: {grade, source number}}}}, "drives": {...}}: figures by their SI field names."""
    index = SourceIndex()
    shown_motors = {m.id: _figures(m, index) for m in motors}
    shown_drives = {d.id: _figures(d, index) for d in drives}
    return {"sources": index.json(), "motors": shown_motors, "drives": shown_drives}


def chosen_provenance(results: Iterable[CandidateResult]) -> dict[str, Any]:
    """The provenance of the motors and drives of ``results``, in their order."""
    results = list(results)
    motors = {r.motor_object.id: r.motor_object for r in results}
    drives = {r.drive_object.id: r.drive_object for r in results
              if r.drive_object is not None}
    return provenance_json(motors.values(), drives.values())
