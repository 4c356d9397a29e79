"""A Table drawn with rich on a terminal (rich is imported only when used).

A table wider than the terminal keeps its columns readable: the columns named in
``droppable`` are left out, in that order, until the rest fits, and the caller is told
which ones (to say so under the table). Nothing is ever dropped silently. Where that is
not enough (or a word would be cut), the headers and cells with a short form
(sizer.report.abbreviations: the margins, the law, the limiting check) are abbreviated,
and a line under the table says so; then fewer columns may need to be left out.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from sizer.report.table import Table

MAX_WORD_WIDTH = 16
"""A text column is at least as wide as the longest word of its cells, up to this."""


def without_columns(table: Table, headers: Sequence[str]) -> Table:
    """The table without the columns of these headers."""
    keep = [i for i, c in enumerate(table.columns) if c.header not in set(headers)]

    def pick(rows: tuple[tuple[str, ...], ...]) -> tuple[tuple[str, ...], ...]:
        return tuple(tuple(row[i] for i in keep) for row in rows)

    return Table(tuple(table.columns[i] for i in keep), pick(table.rows), table.title,
                 None if table.unicode_rows is None else pick(table.unicode_rows))


COLUMN_GAP = 2
"""Characters between two columns (padding and the blank divider of box.SIMPLE_HEAD)."""


def _column_width(table: Table, index: int, wrap_headers: bool,
                  longest: int = MAX_WORD_WIDTH) -> int:
    """The narrowest a column gets: numbers are never cut, words not into slivers (words
    longer than ``longest`` fold)."""
    column = table.columns[index]
    cells = [row[index] for row in (table.unicode_rows or table.rows)]
    header_words = (column.header.split() or [""]) if wrap_headers else []
    if column.align == "right" and wrap_headers:
        return max([*map(len, cells), *map(len, header_words)])
    if column.align == "right":
        return max([len(column.header), *map(len, cells)])
    words = [w for cell in cells for w in cell.split()] or [""]
    return min(max(map(len, words + header_words)), longest)


def minimum_width(table: Table, wrap_headers: bool = False,
                  longest: int = MAX_WORD_WIDTH) -> int:
    """The width below which the table's columns would be cut or squeezed (with
    ``longest`` larger: below which a word longer than MAX_WORD_WIDTH would fold)."""
    widths = [_column_width(table, i, wrap_headers, longest)
              for i in range(len(table.columns))]
    return sum(widths) + COLUMN_GAP * max(len(widths) - 1, 0)


WHOLE_WORDS = 10**6
"""``longest`` of minimum_width when no word may fold."""


def _rich_table(table: Table, wrap_headers: bool) -> Any:
    from rich import box
    from rich.table import Table as RichTable
    from rich.text import Text

    rows = table.unicode_rows or table.rows
    rich_table = RichTable(title=Text(table.title) if table.title else None,
                           box=box.SIMPLE_HEAD, show_edge=False, pad_edge=False,
                           collapse_padding=True)
    for index, column in enumerate(table.columns):
        width = _column_width(table, index, wrap_headers)
        if column.align == "right" and wrap_headers:  # numbers never cut; headers wrap
            rich_table.add_column(Text(column.header), justify="right", width=width)
        elif column.align == "right":  # numbers: never shrink or cut
            rich_table.add_column(Text(column.header), justify="right", no_wrap=True,
                                  min_width=width)
        else:  # words: wrap on a narrow terminal, but not into slivers
            rich_table.add_column(Text(column.header), justify="left", overflow="fold",
                                  min_width=width)
    for row in rows:
        rich_table.add_row(*(Text(cell) for cell in row))
    return rich_table


def _drop(table: Table, names: Sequence[str], width: int, droppable: Sequence[str],
          wrap_headers: bool) -> tuple[Table, list[str]]:
    """Leave out ``droppable`` columns in order until the table fits; ``names`` are the
    full headers of ``table``'s columns (the droppable and the dropped are named by them)."""
    dropped: list[str] = []
    header = dict(zip(names, table.headers, strict=True))
    candidates = [h for h in droppable if h in header]
    while minimum_width(table, wrap_headers) > width and candidates:
        dropped.append(candidates.pop(0))
        table = without_columns(table, [header[dropped[-1]]])
    return table, dropped


def fit_table(table: Table, width: int, droppable: Sequence[str] = (), *,
              wrap_headers: bool = False) -> tuple[Table, list[str]]:
    """The table without as few ``droppable`` columns (in that order) as make it fit in
    ``width`` characters, and the (full) headers left out; abbreviated
    (sizer.report.abbreviations) where the full words would still not fit whole."""
    fitted, dropped, _ = _fit(table, width, droppable, wrap_headers)
    return fitted, dropped


def _fit(table: Table, width: int, droppable: Sequence[str],
         wrap_headers: bool) -> tuple[Table, list[str], bool]:
    """fit_table, and whether the table was abbreviated."""
    fitted, dropped = _drop(table, table.headers, width, droppable, wrap_headers)
    if minimum_width(fitted, wrap_headers, WHOLE_WORDS) <= width:
        return fitted, dropped, False
    from sizer.report.abbreviations import abbreviated

    short = abbreviated(table)
    if short is table:
        return fitted, dropped, False
    fitted, dropped = _drop(short, table.headers, width, droppable, wrap_headers)
    return fitted, dropped, True


def print_rich_table(table: Table, wrap_headers: bool = False, *,
                     droppable: Sequence[str] = (), title_above: bool = False,
                     console: Any = None) -> list[str]:
    """Print with box drawing; cell text is never read as rich markup. Returns the headers
    of the columns left out to fit the terminal (only ever from ``droppable``).

    With ``wrap_headers`` (tables with a dozen numeric columns, ``sizer size``) a numeric
    column is only as wide as its widest number or header word, and its header wraps.
    With ``title_above`` a long title wraps as plain text above the table rather than
    centered over it. ``console`` defaults to a rich Console on stdout.
    """
    from rich.console import Console
    from rich.text import Text

    console = console or Console(highlight=False)
    table, dropped, short = _fit(table, console.width, droppable, wrap_headers)
    if table.title and title_above:
        console.print(Text(table.title))
        console.print()
        table = Table(table.columns, table.rows, "", table.unicode_rows)
    console.print(_rich_table(table, wrap_headers))
    if short:
        from sizer.report.abbreviations import CAPTION

        console.print(Text(CAPTION))
    return dropped
