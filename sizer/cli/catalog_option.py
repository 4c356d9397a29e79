"""The ``--catalog`` option of the commands that read a design file."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

CatalogOption = Annotated[
    list[str] | None,
    typer.Option(
        "--catalog", "-c",
        metavar="FILE",
        help="A motor catalog added to the design's motors: a YAML file (relative to the "
             "working directory) or a bundled catalog name; repeat for more.",
    ),
]

DesignArgument = Annotated[
    Path,
    typer.Argument(
        metavar="DESIGN.yaml",
        help="The design file: task, load, transmission, laws, motors, limits.",
        show_default=False,
    ),
]
