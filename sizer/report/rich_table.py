"""A Table drawn with rich on a terminal (rich is imported only when used)."""

from __future__ import annotations

from sizer.report.table import Table

MAX_WORD_WIDTH = 16
"""A text column is at least as wide as the longest word of its cells, up to this."""


def print_rich_table(table: Table, wrap_headers: bool = False) -> None:
    """Print to stdout with box drawing; cell text is never read as rich markup.

    With ``wrap_headers`` (tables with a dozen numeric columns, ``sizer size``) a numeric
    column is only as wide as its widest number or header word, and its header wraps.
    """
    from rich import box
    from rich.console import Console
    from rich.table import Table as RichTable
    from rich.text import Text

    rows = table.unicode_rows or table.rows
    rich_table = RichTable(title=Text(table.title) if table.title else None,
                           box=box.SIMPLE_HEAD, show_edge=False, pad_edge=False,
                           collapse_padding=True)
    for index, column in enumerate(table.columns):
        cells = [row[index] for row in rows]
        header_words = (column.header.split() or [""]) if wrap_headers else []
        if column.align == "right" and wrap_headers:  # numbers never cut; headers wrap
            width = max([*map(len, cells), *map(len, header_words)])
            rich_table.add_column(Text(column.header), justify="right", width=width)
        elif column.align == "right":  # numbers: never shrink or cut
            width = max([len(column.header), *map(len, cells)])
            rich_table.add_column(Text(column.header), justify="right", no_wrap=True,
                                  min_width=width)
        else:  # words: wrap on a narrow terminal, but not into slivers
            words = [w for cell in cells for w in cell.split()] or [""]
            width = min(max(map(len, words + header_words)), MAX_WORD_WIDTH)
            rich_table.add_column(Text(column.header), justify="left", overflow="fold",
                                  min_width=width)
    for row in rows:
        rich_table.add_row(*(Text(cell) for cell in row))
    Console(highlight=False).print(rich_table)
