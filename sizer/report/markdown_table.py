"""A Table as a GitHub-flavoured Markdown table."""

from __future__ import annotations

from sizer.report.table import Table


def _cell(text: str) -> str:
    return text.replace("\\", "\\\\").replace("|", "\\|")


def render_markdown_table(table: Table) -> str:
    """Header row, alignment row, one row per line; '\\n' endings."""
    rule = ["---:" if c.align == "right" else ":---" for c in table.columns]
    lines = ["| " + " | ".join(_cell(h) for h in table.headers) + " |",
             "| " + " | ".join(rule) + " |"]
    lines += ["| " + " | ".join(_cell(c) for c in row) + " |" for row in table.rows]
    return "\n".join(lines) + "\n"
