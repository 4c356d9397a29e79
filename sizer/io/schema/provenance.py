"""The provenance of a catalog's figures: its ``sources:``, its ``default_source:`` and each
row's ``figure_sources:`` (motor, drive and gearbox catalogs alike).

    sources:
      maker-2024: {grade: A, text: "<maker>, <document>, <section>, p. <n>, <URL>"}
    default_source: maker-2024      # every figure's source unless the row names another
    motors:
      - id: ...
        figure_sources: {winding_inductance: other-key}

Grades: A printed as a number in the maker's own document, B the maker's document read
from a mirror or secondary copy, C computed from printed figures, D assumed. A file
without ``sources:`` keeps its ``source:`` text; its figures are ungraded.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable, Mapping
from functools import cache, lru_cache
from typing import Annotated, Any, Literal

from pydantic import BaseModel, Field, TypeAdapter, ValidationError
from pydantic_core import PydanticCustomError

from sizer.io.schema.inputs_base import Identifier, Strict, Text
from sizer.model.domain import NOT_FIGURES, FigureSources, Provenance


class SourceInput(Strict):
    """One source of a catalog's figures: its grade and its citation."""

    grade: Literal["A", "B", "C", "D"] = Field(
        description="A: printed as a number in the maker's own document; B: the maker's "
                    "document read from a mirror or secondary copy; C: computed from "
                    "printed figures; D: assumed")
    text: Text = Field(description="'<maker>, <document>, <section>, p. <n>, <URL>'")


Sources = Annotated[dict[Identifier, SourceInput], Field(
    description="the sources of the file's figures by key: {grade, text} each")]
SourceKey = Annotated[Identifier, Field(description="a key of the file's sources")]
FigureSourcesInput = Annotated[dict[Identifier, Identifier], Field(
    description="figure (a field given in this row) -> the key of its source in the "
                "file's sources, where it is not the default_source")]

ROW_ALIASES = {"phase_resistance": "winding_resistance",
               "phase_inductance": "winding_inductance",
               "supply_voltage": "dc_bus_voltage"}
"""A figure written in another convention, and the domain field it is read into."""

ROW_TEXTS = frozenset({"notes", "figure_sources", "ratios"})
"""Fields of a row (beside the domain's NOT_FIGURES) that are no figures."""


def figure_names(model: type[BaseModel]) -> list[str]:
    """The fields of a row model that are figures."""
    return [name for name in model.model_fields
            if name not in NOT_FIGURES and name not in ROW_TEXTS]


def _fail(message: str, at: tuple[Any, ...]) -> PydanticCustomError:
    return PydanticCustomError("provenance", message, {"at": at})


def check_provenance(sources: Mapping[str, SourceInput] | None, default: str | None,
                     rows: Iterable[tuple[tuple[Any, ...], BaseModel]]) -> None:
    """The file's provenance agrees with itself: ``default_source`` and every
    ``figure_sources`` value name a source of the file, every key a figure given in its
    row (``rows``: each row's path in the file and its validated model). The first
    problem is raised at its field."""
    known = dict(sources or {})
    if default is not None:
        _known_source(default, known, ("default_source",))
    for path, row in rows:
        named = getattr(row, "figure_sources", None)
        if not named:
            continue
        figures = figure_names(type(row))
        for figure, key in named.items():
            at = (*path, "figure_sources", figure)
            if figure not in figures:
                close = difflib.get_close_matches(figure, figures, n=1)
                hint = f" (did you mean {close[0]!r}?)" if close else ""
                raise _fail(f"{figure!r} is not a figure of this row{hint}; figures: "
                            f"{', '.join(figures)}", at)
            if figure not in row.model_fields_set:
                raise _fail(f"{figure!r} is not given in this row: figure_sources names the "
                            f"sources of the figures written in it", at)
            _known_source(key, known, at)


def _known_source(key: str, known: Mapping[str, Any], at: tuple[Any, ...]) -> None:
    if key in known:
        return
    if not known:
        raise _fail(f"unknown source {key!r}: the file has no `sources:` (give them as "
                    f"`sources: {{{key}: {{grade: A, text: ...}}}}`)", at)
    close = difflib.get_close_matches(key, list(known), n=1)
    hint = f" (did you mean {close[0]!r}?)" if close else ""
    raise _fail(f"unknown source {key!r}{hint}; sources of this file: "
                f"{', '.join(known)}", at)


def provenance_of(source: SourceInput) -> Provenance:
    return Provenance(source.grade, source.text)


def file_sources(sources: Mapping[str, SourceInput] | None, default: str | None
                 ) -> tuple[dict[str, Provenance], FigureSources | None]:
    """A file's sources as shared Provenance objects, and the FigureSources of its rows
    that name none of their own (None: the file has no default source: ungraded)."""
    shared = {key: provenance_of(item) for key, item in (sources or {}).items()}
    if default is None:
        return shared, None
    return shared, FigureSources(shared[default])


def row_sources(named: Mapping[str, str] | None, shared: Mapping[str, Provenance],
                common: FigureSources | None) -> FigureSources | None:
    """A row's FigureSources from its ``figure_sources`` (figure -> source key): the
    file's common one where it names none, else its own (figures by their domain names,
    sorted; the rest the file's default)."""
    if not named:
        return common
    figures = tuple(sorted((ROW_ALIASES.get(figure, figure), shared[key])
                           for figure, key in named.items()))
    return _interned(None if common is None else common.default, figures)


@lru_cache(maxsize=4096)
def _interned(default: Provenance | None,
              figures: tuple[tuple[str, Provenance], ...]) -> FigureSources:
    """One FigureSources for the rows that name the same sources."""
    return FigureSources(default, figures)


def catalog_source_text(text: str | None, common: FigureSources | None) -> str | None:
    """A catalog's source text: its ``source:``, else its default source's citation."""
    if text is not None or common is None or common.default is None:
        return text
    return common.default.text


@cache
def sources_adapter() -> TypeAdapter[dict[str, SourceInput]]:
    return TypeAdapter(dict[Identifier, SourceInput])


def common_sources(data: Mapping[str, Any]) -> FigureSources | None:
    """The FigureSources of a catalog's rows that name none of their own, read from its
    data without its model; ValueError where the section is not valid (the model then
    words it)."""
    given, default = data.get("sources"), data.get("default_source")
    if given is None and default is None:
        return None
    try:
        sources = sources_adapter().validate_python(given)
    except ValidationError:
        raise ValueError("sources") from None
    if default is None:
        return None
    if type(default) is not str or default.strip() not in sources:
        raise ValueError("default_source")
    return file_sources(sources, default.strip())[1]


def gearbox_sources(series: Any, ratio: Any, shared: Mapping[str, Provenance],
                    common: FigureSources | None) -> FigureSources | None:
    """The FigureSources of one ratio of a gearbox series (a GearboxOption's): the ratio
    row's figure_sources, then the series row's, then the file's default."""
    return row_sources({**(series.figure_sources or {}), **(ratio.figure_sources or {})},
                       shared, common)
