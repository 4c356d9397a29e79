"""The ``--catalog`` option of the commands that read a design file, and the design or
machine file they are given."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from sizer.errors import UserError

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
    from sizer.cli.reporting import report_warnings

    check_catalog_references(catalogs or ())
    if is_machine(design):  # sizer size, check and report read machine files before here
        raise UserError("a machine file (axes:): this command reads a design file; sizer "
                        "size, check and report read machine files (or copy an axis into "
                        "a design file of its own)", file=str(design))
    loaded = api.load(design, catalogs or ())
    report_warnings(loaded.warnings)
    return loaded


def is_machine(path: Path) -> bool:
    """A machine file (``axes:``); anything unreadable goes the design's way, whose
    loader says what is wrong."""
    from sizer.io.file_kind import is_machine_file

    try:
        return path.is_file() and is_machine_file(path)
    except (UserError, OSError):
        return False


def refuse_motor_options(catalog: Sequence[str] | None,
                         motor: Sequence[str] | None = None) -> None:
    """--catalog and --motor are for design files: a machine's axes name their motors."""
    for given, option in ((catalog, "--catalog"), (motor, "--motor")):
        if given:
            raise UserError("not for a machine file: each axis names its motors",
                            field=option)
