"""``sizer catalog ...``: list, show, validate and import motor catalogs."""

from __future__ import annotations

import codecs
import sys
from pathlib import Path
from typing import Annotated

import typer

from sizer.cli.catalog_option import check_catalog_references
from sizer.cli.exit_codes import ExitCode
from sizer.cli.options import FormatOption, OutputOption
from sizer.errors import UserError
from sizer.report.formats import Format
from sizer.report.printable import printable

catalog_app = typer.Typer(
    name="catalog",
    help="Motor catalogs: list the bundled ones and their motors, show one motor, "
         "validate catalog files (for CI), import a vendor's CSV.",
    no_args_is_help=True,
    rich_markup_mode=None,  # plain help, as the app (sizer.cli.app)
    add_completion=False,
)

CatalogFilesOption = Annotated[
    list[str] | None,
    typer.Option(
        "--catalog", "-c",
        metavar="FILE",
        help="Search this catalog (a YAML file or a bundled catalog name); repeat for more. "
             "Default: every bundled catalog.",
    ),
]


@catalog_app.command("list")
def list_catalogs(
    catalog: Annotated[str | None, typer.Argument(
        metavar="[NAME|FILE]",
        help="A bundled catalog name or a catalog file: list its motors.",
        show_default=False)] = None,
    fmt: FormatOption = Format.TABLE,
    output: OutputOption = None,
) -> None:
    """List the bundled catalogs, or the motors of one catalog.

    Without an argument: each bundled catalog with its number of motors, its
    manufacturers, whether a design that names no catalog uses it (default), and its file.
    With one: its motors (continuous and peak torque in N*m, rated and max speed in rpm,
    rotor inertia in kg*cm^2, and whether speed-torque curves are given). CSV and JSON
    are in SI units.

    Examples:

        sizer catalog list

        sizer catalog list yaskawa-sgm7j

        sizer catalog list my-motors.yaml --format csv
    """
    from sizer.catalog_tools import catalog_entries, catalog_summaries, summarize_catalog
    from sizer.cli.output_guard import check_output
    from sizer.io import bundled_catalogs
    from sizer.report.catalog_tables import CatalogsDocument, MotorsDocument
    from sizer.report.document import publish

    if catalog is None:
        check_output(output, bundled_catalogs().values())
        publish(CatalogsDocument(catalog_summaries()), fmt, output)
        return
    check_output(output, [catalog])
    summary = summarize_catalog(catalog)
    check_output(output, [summary.path])
    title = f"{summary.title or summary.name} ({summary.path})"
    publish(MotorsDocument(catalog_entries(summary.path), title=title), fmt, output)


@catalog_app.command("show")
def show(
    motor_id: Annotated[str, typer.Argument(
        metavar="ID", help="The motor's id, e.g. SGM7J-02A.", show_default=False)],
    catalog: CatalogFilesOption = None,
    fmt: FormatOption = Format.TABLE,
    output: OutputOption = None,
) -> None:
    """Show one motor: every field as written and in display units, its speed-torque
    regions as the sizing uses them (rpm, N*m), its source and notes.

    Without curves the regions are the book's rectangles: the continuous and the peak
    torque from standstill up to the rated speed.

    Examples:

        sizer catalog show SGM7J-02A

        sizer catalog show MY-MOTOR --catalog my-motors.yaml --format json
    """
    from sizer.catalog_tools import find_motor
    from sizer.cli.output_guard import check_output
    from sizer.io import bundled_catalogs, resolve_catalog
    from sizer.report.catalog_tables import MotorDocument
    from sizer.report.document import publish

    check_catalog_references(catalog or ())
    check_output(output, catalog or ())
    if output is not None:  # the catalogs searched: named (resolved) or every bundled one
        read = ([resolve_catalog(c, Path.cwd()) for c in catalog] if catalog
                else list(bundled_catalogs().values()))
        check_output(output, read)
    publish(MotorDocument(find_motor(motor_id, catalog or None)), fmt, output)


@catalog_app.command("validate")
def validate(
    files: Annotated[list[str] | None, typer.Argument(
        metavar="[FILE...]",
        help="Catalog files (or bundled catalog names). Default: every bundled catalog.",
        show_default=False)] = None,
    quiet: Annotated[bool, typer.Option(
        "--quiet", "-q", help="Print the findings only, not the summary line.")] = False,
) -> None:
    """Check catalog files: the schema, then sanity checks, listing every finding.

    Each finding is one line 'file:line: field: message'. Checked: units and fields,
    peak >= continuous torque, max speed >= rated speed, curves with strictly increasing
    speeds and torques >= 0, the continuous region under the intermittent one, each
    curve's first torque within 10 % of the rating (a warning), a rotor inertia > 0 for
    real motors, a source on every motor, duplicate ids (also across the files given),
    the provenance (sources, default_source, figure_sources).

    Consistency (warnings, 3 % unless said): k_t = sqrt(3) k_e (block: k_t = k_e) and
    k_t x continuous_current = continuous_torque (15 %: figures printed cold and warm),
    peak_torque <= k_t x peak_current, a continuous curve through the rated point, the
    intermittent region holding the continuous one (linear rule). Rated power = torque x
    speed is not checked: a motor has no rated power field. The summary gives each file's
    figures per grade (A, B, C, D, ungraded) and the total.

    Exit code: 0 when clean, 1 on any finding, 2 when a file cannot be read at all.

    Examples:

        sizer catalog validate catalogs/*.yaml

        sizer catalog validate my-motors.yaml
    """
    from sizer.catalog_tools import validate_catalogs
    from sizer.io import bundled_catalogs
    from sizer.io.loader import bundled_drive_catalogs
    from sizer.io.transmission import bundled_gearbox_catalogs

    references = files or [str(p) for p in (*bundled_catalogs().values(),
                                             *bundled_drive_catalogs().values(),
                                             *bundled_gearbox_catalogs().values())]
    report = validate_catalogs(references)
    for finding in report.findings:
        typer.echo(printable(str(finding)))
    for error in report.unreadable:
        typer.echo(printable(f"error: {error}"), err=True)
    if not quiet:
        for file, mix in report.grades.items():
            typer.echo(printable(f"grades of {file}: {mix.text()}"), err=True)
        typer.echo(f"grades of all files: {report.total_grades.text()}", err=True)
        for note in report.not_checked:
            typer.echo(f"not checked: {note}", err=True)
        count = len(report.findings)
        drives = f", {report.drives} drive(s)" if report.drives else ""
        drives += f", {report.gearboxes} gearbox series" if report.gearboxes else ""
        summary = (f"{len(report.files)} file(s), {report.motors} motor(s){drives}: "
                   f"{count or 'no'} finding{'s' * (count != 1)}")
        if report.unreadable:
            summary += f", {len(report.unreadable)} file(s) not readable"
        typer.echo(summary, err=True)
    raise typer.Exit(report.exit_code)


@catalog_app.command("import")
def import_command(
    csv_file: Annotated[Path, typer.Argument(
        metavar="FILE.csv", help="The vendor's spreadsheet saved as CSV, a header line first.",
        show_default=False, dir_okay=False)],
    maps: Annotated[list[str], typer.Option(
        "--map", "-m", metavar="COLUMN=FIELD[:UNIT]",
        help="A CSV column fills a motor field, its numbers in UNIT, e.g. "
             "'Rated torque (Nm)=continuous_torque:N*m'; repeat for each column. Fields: "
             "id, part_number, manufacturer, inertia, continuous_torque, peak_torque, "
             "rated_speed, max_speed, damping, mass, price, source, notes. Without a unit a "
             "cell is copied as written.",
        show_default=False)],
    catalog_name: Annotated[str | None, typer.Option(
        "--catalog-name", metavar="NAME", help="The catalog's name. Default: the CSV's name.",
        show_default=False)] = None,
    manufacturer: Annotated[str | None, typer.Option(
        "--manufacturer", metavar="M", help="The manufacturer of every motor.",
        show_default=False)] = None,
    source: Annotated[str | None, typer.Option(
        "--source", metavar="S",
        help="The datasheet's title and web address, for every motor (required unless a "
             "column maps to source).", show_default=False)] = None,
    delimiter: Annotated[str | None, typer.Option(
        "--delimiter", metavar="CHAR",
        help="The CSV delimiter. Default: found in the header line (, ; tab or |).",
        show_default=False)] = None,
    decimal_comma: Annotated[bool, typer.Option(
        "--decimal-comma", help="Numbers are written with a decimal comma (0,38).")] = False,
    encoding: Annotated[str, typer.Option(
        "--encoding", metavar="NAME", help="The CSV's text encoding, e.g. cp1252.")] = "utf-8",
    output: OutputOption = None,
) -> None:
    """Convert a vendor's spreadsheet (CSV) into a catalog YAML, with units per column.

    Every figure keeps the spreadsheet's value, written with its column's unit
    ('0.637 N*m'); empty cells stay absent. Every row is checked like a catalog motor; any
    problem is reported as 'file.csv:line: field (column ...): message' and nothing is
    written (exit code 2). The output is the same for the same input, and replaces FILE
    atomically.

    Example:

        sizer catalog import motors.csv --map Model=id \\
          --map 'J (kgcm2)=inertia:kg*cm^2' \\
          --map 'Rated torque (Nm)=continuous_torque:N*m' \\
          --map 'Peak torque (Nm)=peak_torque:N*m' --map 'n_N=rated_speed:rpm' \\
          --manufacturer ACME --source 'ACME catalog 2024, https://...' -o acme.yaml
    """
    from sizer.catalog_tools import CatalogImportError, import_csv, parse_column_map
    from sizer.cli.output_guard import check_output
    from sizer.report.output import emit

    check_output(output, [csv_file])
    try:
        codecs.lookup(encoding)
    except LookupError:
        raise UserError(f"unknown text encoding {encoding!r}; e.g. utf-8, cp1252, "
                        f"latin-1, shift_jis", field="--encoding") from None
    if delimiter is not None and len(delimiter.replace("\\t", "\t")) != 1:
        raise UserError(f"expected one character, got {delimiter!r}", field="--delimiter")
    try:
        catalog = import_csv(
            csv_file, [parse_column_map(text) for text in maps], catalog_name=catalog_name,
            manufacturer=manufacturer, source=source,
            delimiter=None if delimiter is None else delimiter.replace("\\t", "\t"),
            decimal_comma=decimal_comma, encoding=encoding)
    except CatalogImportError as error:
        for problem in error.problems:
            sys.stderr.write(printable(f"error: {problem}") + "\n")
        sys.stderr.flush()
        raise typer.Exit(ExitCode.USER_ERROR) from None
    from sizer.cli.reporting import report_warnings

    report_warnings(catalog.warnings)
    emit(catalog.yaml(), output)
    if output is not None:
        typer.echo(printable(f"{len(catalog.motors)} motor(s) written to {output}"), err=True)


def register(app: typer.Typer) -> None:
    app.add_typer(catalog_app, name="catalog")
