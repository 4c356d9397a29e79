"""Plain aligned text for a Table: what a pipe or a file gets for ``--format table``."""

from __future__ import annotations

from sizer.report.table import Table

GAP = "  "


def render_text_table(table: Table) -> str:
    """Columns padded to a common width, a dashed rule under the headers, '\\n' endings."""
    widths = [len(h) for h in table.headers]
    for row in table.rows:
        widths = [max(w, len(cell)) for w, cell in zip(widths, row, strict=True)]

    def line(cells: tuple[str, ...]) -> str:
        padded = [
            cell.rjust(w) if column.align == "right" else cell.ljust(w)
            for cell, w, column in zip(cells, widths, table.columns, strict=True)
        ]
        return GAP.join(padded).rstrip()

    lines = [line(table.headers), GAP.join("-" * w for w in widths)]
    lines += [line(row) for row in table.rows]
    return "\n".join(lines) + "\n"
