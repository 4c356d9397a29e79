"""A Table with many numeric columns drawn with rich: headers wrap, numbers never do.

The shared ``print_rich_table`` keeps every header on one line; with a dozen columns
(``sizer size``) that makes the table wider than most terminals. Here a numeric column is
as wide as its widest number, and its header wraps onto several lines if it must.
"""

from __future__ import annotations

from sizer.report.rich_table import MAX_WORD_WIDTH
from sizer.report.table import Table


def print_wide_rich_table(table: Table) -> None:
    """Print to stdout with box drawing; cell text is never read as rich markup."""
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
        header_words = column.header.split() or [""]
        if column.align == "right":  # numbers: never shrink or cut; the header wraps
            width = max([*map(len, cells), *map(len, header_words)])
            rich_table.add_column(Text(column.header), justify="right", width=width)
        else:  # words: wrap on a narrow terminal, but not into slivers
            words = [w for cell in cells for w in cell.split()] or [""]
            width = min(max(map(len, words + header_words)), MAX_WORD_WIDTH)
            rich_table.add_column(Text(column.header), justify="left", overflow="fold",
                                  min_width=width)
    for row in rows:
        rich_table.add_row(*(Text(cell) for cell in row))
    Console(highlight=False).print(rich_table)
