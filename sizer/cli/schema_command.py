"""``sizer schema``: the JSON Schema of the design file, the motor or the gearbox catalog,
or the machine file."""

from __future__ import annotations

from enum import StrEnum
from typing import Annotated

import typer

from sizer.cli.options import OutputOption


class SchemaName(StrEnum):
    """The file formats with a schema."""

    DESIGN = "design"
    CATALOG = "catalog"
    GEARBOXES = "gearboxes"
    MACHINE = "machine"


def schema(
    which: Annotated[SchemaName, typer.Argument(
        metavar="design|catalog|gearboxes|machine", case_sensitive=False,
        help="design (a design file), catalog (a motor catalog), gearboxes (a gearbox "
             "catalog) or machine (several axes on one master).", show_default=False)],
    output: OutputOption = None,
) -> None:
    """Print the JSON Schema (draft 2020-12) of a design file, a motor catalog or a gearbox
    catalog, for editors and CI. Put the line
    '# yaml-language-server: $schema=design.schema.json' at the top of a design file to
    have an editor with the YAML language server complete and check it.

    Example:

        sizer schema design --output design.schema.json
    """
    from sizer.cli.output_guard import check_output
    from sizer.io.loader import (  # lazy: keeps --help fast
        catalog_schema,
        design_schema,
        gearbox_catalog_schema,
    )
    from sizer.report.json_text import render_json
    from sizer.report.output import emit

    check_output(output)
    from sizer.io.machine_loader import machine_schema

    build = {SchemaName.DESIGN: design_schema, SchemaName.CATALOG: catalog_schema,
             SchemaName.GEARBOXES: gearbox_catalog_schema,
             SchemaName.MACHINE: machine_schema}[which]
    emit(render_json(build()), output)


def register(app: typer.Typer) -> None:
    app.command("schema")(schema)
