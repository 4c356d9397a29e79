"""CSV text with fixed conventions: comma separated, minimal quoting, '\\n' line endings."""

from __future__ import annotations

import csv
import io
from collections.abc import Iterable, Sequence


def render_csv(headers: Sequence[str], rows: Iterable[Sequence[str]]) -> str:
    """A header line and one line per row, ending with a newline."""
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(headers)
    writer.writerows(rows)
    return buffer.getvalue()
