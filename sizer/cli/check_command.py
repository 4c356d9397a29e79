"""``sizer check``: do the designs' chosen motor and law pass? (for CI and pre-commit)"""

from __future__ import annotations

from enum import StrEnum
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from sizer.cli.catalog_option import CatalogOption, check_catalog_references, load_design_file
from sizer.cli.exit_codes import ExitCode
from sizer.cli.options import EnvelopeOption
from sizer.errors import UserError

if TYPE_CHECKING:
    from sizer.report.check_report import CheckDocument
    from sizer.report.machine_report import MachineCheckDocument



class CheckFormat(StrEnum):
    """Output formats of ``sizer check``."""

    TABLE = "table"
    JSON = "json"


def check(
    designs: Annotated[list[Path], typer.Argument(
        metavar="DESIGN.yaml...",
        help="Design files, each naming the motor and law to check, or machine files.",
        show_default=False)],
    catalog: CatalogOption = None,
    fmt: Annotated[CheckFormat, typer.Option(
        "--format", "-f", case_sensitive=False,
        help="Output format: table (one line per limit, then PASS or FAIL) or json "
             "(an object; a list of objects for several files).",
    )] = CheckFormat.TABLE,
    envelope: EnvelopeOption = None,
) -> None:
    """Check the motor and law each design names (`check: {motor: ID, law: SPEC}`).

    A machine file (`axes:`) passes when every axis has a feasible pair at the master
    speed and the bus copes.

    Exit code 0 when every design's pair meets every limit with the required margins,
    1 when one does not (the output says which limit fails and by how much), 2 when a
    file is invalid (one 'error: ...' line on stderr per invalid file), 3 when sizer
    fails on a file (an internal error, a bug: one 'internal error: ...' line naming the
    file). The other files are still checked; the exit code is the gravest: 3, else 2,
    else 1, else 0.

    Examples:

        sizer check examples/indexing-table.yaml

        sizer check designs/*.yaml --format json
    """
    from sizer.cli.reporting import report_internal_error, report_user_error
    from sizer.report.json_text import render_json
    from sizer.report.output import emit

    check_catalog_references(catalog or ())  # an option's mistake: once, before any file
    documents: list[CheckDocument | MachineCheckDocument] = []
    invalid = internal = False
    for design in designs:
        try:
            document = check_one(design, catalog or (), envelope)
        except UserError as error:
            report_user_error(error)
            invalid = True
            continue
        except Exception as error:  # a bug in sizer: reported, the other files checked
            report_internal_error(error, f"checking {design}")
            internal = True
            continue
        documents.append(document)
        if fmt is CheckFormat.TABLE:
            emit(("\n" if len(documents) > 1 else "") + document.text(), None, escape=True)
    if fmt is CheckFormat.JSON and documents:
        data = [d.data() for d in documents]
        emit(render_json(data[0] if len(designs) == 1 else data), None)
    if internal:
        raise typer.Exit(ExitCode.INTERNAL_ERROR)
    if invalid:
        raise typer.Exit(ExitCode.USER_ERROR)
    if not all(d.passed for d in documents):
        raise typer.Exit(ExitCode.CHECK_FAILED)


def check_one(design: Path, catalogs: list[str] | tuple[str, ...],
              envelope: str | None = None) -> CheckDocument | MachineCheckDocument:
    """Load a design (with --envelope) and check its chosen pair (sizer.api); UserErrors
    name the file."""
    from sizer import api
    from sizer.cli.catalog_option import is_machine
    from sizer.report.check_report import CheckDocument
    from sizer.report.segment_table import breakdown_for

    if is_machine(design):
        return _check_machine(design, catalogs, envelope)
    loaded = api.override(load_design_file(design, catalogs), envelope=envelope or None)
    try:
        result = api.check(loaded)
        segments = breakdown_for(loaded, result) if result.duration is not None else None
    except UserError as error:
        from sizer.io.loader import at_its_line

        raise at_its_line(error, design) from None
    return CheckDocument(result, loaded, api.assumptions(loaded), segments)


def _check_machine(path: Path, catalogs: list[str] | tuple[str, ...],
                   envelope: str | None) -> MachineCheckDocument:
    """A machine file: PASS when every axis has a feasible pair at the master speed (the
    slowest axis's with minimize) and the bus copes."""
    from sizer import api
    from sizer.cli.catalog_option import refuse_motor_options
    from sizer.report.machine_report import MachineCheckDocument

    refuse_motor_options(catalogs)
    machine = api.load_machine(path)
    from sizer.cli.progress import sizing_progress

    try:
        with sizing_progress(f"sizing {path.name}") as progress:
            result = api.size_machine(machine, envelope=envelope or None, progress=progress)
    except UserError as error:
        raise error.located(file=str(path)) from None
    return MachineCheckDocument(result, machine, path.stem)


def register(app: typer.Typer) -> None:
    app.command("check")(check)
