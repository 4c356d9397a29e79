"""Options shared by several commands, so they read and behave the same everywhere."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from sizer.report.formats import Format

FormatOption = Annotated[
    Format,
    typer.Option(
        "--format", "-f",
        case_sensitive=False,
        help="Output format: table (rich on a terminal, plain text when piped), "
             "csv, md (Markdown) or json.",
    ),
]

OutputOption = Annotated[
    Path | None,
    typer.Option(
        "--output", "-o",
        dir_okay=False,
        metavar="FILE",
        help="Write to FILE (replaced atomically) instead of stdout.",
    ),
]
