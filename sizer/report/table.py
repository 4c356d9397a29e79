"""A display table: headers, cell texts, alignment. Renderers live in their own modules."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

Align = Literal["left", "right"]


@dataclass(frozen=True)
class Column:
    """A column heading and how its cells align."""

    header: str
    align: Align = "right"


@dataclass(frozen=True)
class Table:
    """Rows of already formatted cells under named columns."""

    columns: tuple[Column, ...]
    rows: tuple[tuple[str, ...], ...]
    title: str = ""
    unicode_rows: tuple[tuple[str, ...], ...] | None = None
    """The same rows with unicode symbols (e.g. 'C∞'), for terminals; None if identical."""

    def __post_init__(self) -> None:
        width = len(self.columns)
        for rows in (self.rows, self.unicode_rows or ()):
            for row in rows:
                if len(row) != width:
                    raise ValueError(f"row {row!r} has {len(row)} cells, expected {width}")

    @property
    def headers(self) -> tuple[str, ...]:
        return tuple(c.header for c in self.columns)


def make_table(columns: Sequence[Column], rows: Sequence[Sequence[str]], *, title: str = "",
               unicode_rows: Sequence[Sequence[str]] | None = None) -> Table:
    """A Table from lists (converted to tuples)."""
    return Table(
        columns=tuple(columns),
        rows=tuple(tuple(r) for r in rows),
        title=title,
        unicode_rows=None if unicode_rows is None else tuple(tuple(r) for r in unicode_rows),
    )
