"""A display table: headers, cell texts, alignment. Renderers live in their own modules.

Every text of a Table is made printable (terminal control characters escaped,
:mod:`sizer.report.printable`) when it is built, so no renderer (rich, plain text,
Markdown) can show a raw ESC or bidi override from a motor id or a design name.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

from sizer.report.printable import printable

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
        # names and ids from files are shown with terminal control characters escaped
        object.__setattr__(self, "title", printable(self.title))
        object.__setattr__(self, "columns", tuple(
            c if printable(c.header) == c.header else Column(printable(c.header), c.align)
            for c in self.columns))
        object.__setattr__(self, "rows", _printable_rows(self.rows))
        if self.unicode_rows is not None:
            object.__setattr__(self, "unicode_rows", _printable_rows(self.unicode_rows))
        width = len(self.columns)
        for rows in (self.rows, self.unicode_rows or ()):
            for row in rows:
                if len(row) != width:
                    raise ValueError(f"row {row!r} has {len(row)} cells, expected {width}")

    @property
    def headers(self) -> tuple[str, ...]:
        return tuple(c.header for c in self.columns)


def _printable_rows(rows: tuple[tuple[str, ...], ...]) -> tuple[tuple[str, ...], ...]:
    return tuple(tuple(printable(cell) for cell in row) for row in rows)


def make_table(columns: Sequence[Column], rows: Sequence[Sequence[str]], *, title: str = "",
               unicode_rows: Sequence[Sequence[str]] | None = None) -> Table:
    """A Table from lists (converted to tuples)."""
    return Table(
        columns=tuple(columns),
        rows=tuple(tuple(r) for r in rows),
        title=title,
        unicode_rows=None if unicode_rows is None else tuple(tuple(r) for r in unicode_rows),
    )
