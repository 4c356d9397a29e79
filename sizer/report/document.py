"""A result that can be shown in every format, and ``publish`` to send it somewhere."""

from __future__ import annotations

from pathlib import Path
from typing import Protocol

from sizer.report.formats import Format
from sizer.report.markdown_table import render_markdown_table
from sizer.report.output import emit, stdout_is_terminal
from sizer.report.rich_table import print_rich_table
from sizer.report.table import Table
from sizer.report.text_table import render_text_table


class Document(Protocol):
    """Something with a display table, a CSV text and a JSON text."""

    def table(self) -> Table: ...

    def csv(self) -> str: ...

    def json(self) -> str: ...


def render_text(document: Document, fmt: Format) -> str:
    """The document as text in the given format (``table`` is the plain-text table)."""
    if fmt is Format.CSV:
        return document.csv()
    if fmt is Format.JSON:
        return document.json()
    if fmt is Format.MD:
        return render_markdown_table(document.table())
    return render_text_table(document.table())


def publish(document: Document, fmt: Format, output: Path | None) -> None:
    """Write the document to ``output`` or stdout; a rich table on an interactive terminal."""
    if fmt is Format.TABLE and output is None and stdout_is_terminal():
        print_rich_table(document.table())
        return
    emit(render_text(document, fmt), output, escape=fmt in (Format.TABLE, Format.MD))
