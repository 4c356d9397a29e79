"""``sizer schema``: the JSON Schema of the design file or of the motor catalog."""

from __future__ import annotations

from enum import StrEnum
from typing import Annotated

import typer

from sizer.cli.options import OutputOption


class SchemaName(StrEnum):
    """The file formats with a schema."""

    DESIGN = "design"
    CATALOG = "catalog"


def schema(
    which: Annotated[SchemaName, typer.Argument(
        metavar="design|catalog", case_sensitive=False,
        help="design (a design file) or catalog (a motor catalog).", show_default=False)],
    output: OutputOption = None,
) -> None:
    """Print the JSON Schema of a design file or a motor catalog (for editors and CI).

    Example:

        sizer schema design --output design.schema.json
    """
    from sizer.io import catalog_schema, design_schema  # lazy: keeps --help fast
    from sizer.report.json_text import render_json
    from sizer.report.output import emit

    document = design_schema() if which is SchemaName.DESIGN else catalog_schema()
    emit(render_json(document), output)


def register(app: typer.Typer) -> None:
    app.command("schema")(schema)
