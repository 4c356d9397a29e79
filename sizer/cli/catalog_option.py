"""The ``--catalog`` option of the commands that read a design file."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

if TYPE_CHECKING:
    from sizer.model.domain import Design

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


def check_catalog_references(catalogs: Sequence[str], field: str = "--catalog") -> None:
    """Each ``--catalog`` names a file or a bundled catalog, else a UserError naming the
    option (before the design is read)."""
    from sizer.cli.options import blame_option
    from sizer.io import resolve_catalog

    for reference in catalogs:
        with blame_option(field):
            resolve_catalog(reference, Path.cwd())


def load_design_file(design: Path, catalogs: Sequence[str] | None) -> Design:
    """The design with its catalogs plus ``--catalog`` ones (sizer.api.load; a design that
    names no catalog, and no --catalog, gets the bundled motors); its warnings on stderr."""
    from sizer import api  # lazy: keeps --help fast
    from sizer.cli.app import report_warnings

    check_catalog_references(catalogs or ())
    _refuse_machine(design)
    loaded = api.load(design, catalogs or ())
    report_warnings(loaded.warnings)
    return loaded


def _refuse_machine(design: Path) -> None:
    """A machine file given to a command that reads design files: say so (``sizer size``,
    ``check`` and ``report`` read machine files before they get here)."""
    from sizer.errors import UserError
    from sizer.io.file_kind import is_machine_file

    try:
        machine = design.is_file() and is_machine_file(design)
    except (UserError, OSError):
        return  # the design loader says what is wrong with the file
    if machine:
        raise UserError("a machine file (axes:): this command reads a design file; sizer "
                        "size, check and report read machine files (or copy an axis into "
                        "a design file of its own)", file=str(design))
