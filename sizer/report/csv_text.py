"""CSV text with fixed conventions: comma separated, minimal quoting, '\\n' line endings.

A cell holding a line break of either kind (a CR from a name in a file, too) is quoted,
so every reader sees the same rows; the text itself is kept exactly.
"""

from __future__ import annotations

import csv
import io
from collections.abc import Iterable, Sequence

_TERMINATOR = "\r\n"
"""The writer's terminator: it quotes cells holding any of its characters (CR and LF)."""


def render_csv(headers: Sequence[str], rows: Iterable[Sequence[str]]) -> str:
    """A header line and one line per row, ending with a newline."""
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator=_TERMINATOR)
    lines = []
    for row in (headers, *rows):
        buffer.seek(0)
        buffer.truncate()
        writer.writerow(row)
        lines.append(buffer.getvalue()[:-len(_TERMINATOR)])
    return "\n".join(lines) + "\n"
