"""Reading the records of a CSV text: its separator sniffed, each record with its line.

One reader for every CSV sizer reads (a cam table, a vendor's spreadsheet to import as a
catalog). The separator is given or sniffed from the first lines (:func:`sniff_delimiter`):
``,`` ``;`` tab or ``|``. A spreadsheet saved where the decimal mark is a comma writes
``0,5;1,25``: with a separator other than ``,`` a cell's comma may be a decimal comma
(:func:`decimal_point` reads ``0,5`` as 0.5 and ``1.234,5`` as 1234.5). Records keep the
line where they start (a quoted cell may span lines), for messages.
"""

from __future__ import annotations

import csv
import io
import re
from collections.abc import Iterator

from sizer.errors import UserError

DELIMITERS = ",;\t|"
"""The separators recognized when none is given."""
SNIFF_LINES = 20
"""How many of the first lines (not blank, not comments) choose the separator."""
NUMBER = re.compile(r"^[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?$")
"""A number as a cell writes it (decimal point; ``nan``, ``inf``, ``1_000`` are not)."""
_NOT_COMMA = "\t;|"
"""Separators preferred over ``,`` when every sniffed line splits evenly by both: the
comma is then a decimal comma inside the cells."""


def sniff_delimiter(lines: list[str]) -> str:
    """The separator of a CSV whose first lines are ``lines``: one that splits every line
    into the same number (> 1) of cells, ``\\t`` ``;`` ``|`` before ``,`` (a comma between
    them is a decimal comma); else the most frequent in the first line; else ``,``."""
    if not lines:
        return ","
    even = {}
    for delimiter in DELIMITERS:
        try:
            widths = {len(cells) for cells in csv.reader(lines, delimiter=delimiter)}
        except csv.Error:
            continue
        if len(widths) == 1 and min(widths) > 1:
            even[delimiter] = min(widths)
    for delimiter in (*_NOT_COMMA, ","):
        if delimiter in even:
            return delimiter
    counts = {d: lines[0].count(d) for d in DELIMITERS}
    return max(DELIMITERS, key=lambda d: counts[d]) if any(counts.values()) else ","


def comma_is_decimal(delimiter: str) -> bool:
    """True when a comma inside a cell is a decimal comma: the separator is not ``,``."""
    return delimiter != ","


def decimal_point(cell: str) -> str:
    """'0,38' -> '0.38' (the number part only; '1.234,5' -> '1234.5')."""
    number, _, rest = cell.partition(" ")
    number = number.replace(".", "").replace(",", ".") if "," in number else number
    return f"{number} {rest}".strip()


def _lines(text: str, comment: str | None) -> Iterator[str]:
    """The lines of ``text`` with their ends; a comment line becomes blank (its number kept)."""
    for line in io.StringIO(text, newline=""):
        if comment is not None and line.lstrip().startswith(comment):
            yield "\n"
        else:
            yield line


def _sample(text: str, comment: str | None) -> list[str]:
    """The first SNIFF_LINES lines that are neither blank nor comments."""
    sample: list[str] = []
    for line in _lines(text, comment):
        if line.strip():
            sample.append(line.rstrip("\r\n"))
            if len(sample) == SNIFF_LINES:
                break
    return sample


def csv_delimiter(text: str, delimiter: str | None = None, *, comment: str | None = None
                  ) -> str:
    """``delimiter``, or the one sniffed from the first lines of ``text``."""
    return delimiter if delimiter is not None else sniff_delimiter(_sample(text, comment))


def csv_records(text: str, file: str, delimiter: str, *, comment: str | None = None
                ) -> Iterator[tuple[int, list[str]]]:
    """(line where it starts, cells) of every record of ``text``, blank ones included as
    empty lists; lines starting with ``comment`` are blank. UserError (the file and line)
    for a CSV the csv module cannot read (a quote left open...)."""
    reader = csv.reader(_lines(text, comment), delimiter=delimiter, strict=True)
    start = 1
    try:
        for cells in reader:
            yield start, cells
            start = reader.line_num + 1
    except csv.Error as error:
        raise UserError(f"invalid CSV: {error}", file=file, line=reader.line_num) from None
