"""``sizer report``: a Markdown report of a design (report.md and PNG figures in a folder),
or with ``--html`` one self-contained report.html (figures inline as SVG)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from sizer.cli.catalog_option import CatalogOption, DesignArgument, is_machine, refuse_motor_options
from sizer.cli.options import MotorsOption
from sizer.cli.plot_command import DpiOption
from sizer.errors import UserError
from sizer.report.printable import printable


def report(
    design: DesignArgument,
    output: Annotated[Path, typer.Option(
        "--output", "-o", file_okay=False, metavar="DIR",
        help="The folder for report.md and its figures, or for report.html with --html "
             "(created if missing; files of the same names are replaced).",
        show_default=False)],
    catalog: CatalogOption = None,
    motor: MotorsOption = None,
    rank_by: Annotated[str | None, typer.Option(
        "--rank-by", "-r", metavar="KEY",
        help="Ranking as in 'sizer size': size (alias power), duration, margin, rms, "
             "peak, price or mass.",
        show_default=False)] = None,
    top: Annotated[int, typer.Option(
        "--top", "-n", metavar="N", min=1, help="Rows of the ranking table.")] = 5,
    best: Annotated[int, typer.Option(
        "--best", "-b", metavar="N", min=0, max=50,
        help="Candidates with a speed-torque diagram and every check.")] = 3,
    dpi: DpiOption = 100,
    html: Annotated[bool, typer.Option(
        "--html", help="Write one self-contained DIR/report.html instead (figures inline "
                       "as SVG, the design file and the provenance; no external file or "
                       "link; prints to PDF from a browser).")] = False,
) -> None:
    """Write a Markdown report of a design: DIR/report.md plus PNG figures beside it.

    The task, load, transmission and limits; the coefficient table and the profiles of
    the laws considered; the ranking (first N feasible pairs, and how many are not); for
    the best candidates the speed-torque diagram and every check with its margin; the
    machine cycle of the first one segment by segment (with a cycle of segments, also its
    torque and speed over time).

    With --html, the same content as one self-contained DIR/report.html, plus the
    design file as written and the provenance (docs/reports.md).

    Examples:

        sizer report examples/indexing-table.yaml -o report/

        sizer report examples/indexing-table.yaml -o report/ --html
    """
    from sizer.cli.output_guard import check_outputs
    from sizer.cli.size_command import check_rank_key, load_and_size
    from sizer.report.design_report import (
        LAWS_FIGURE,
        REPORT_FILE,
        TIME_FIGURE,
        candidate_figure,
        write_report,
    )

    check_rank_key(rank_by)
    if output.is_symlink() and not output.is_dir():
        raise UserError(f"{printable(str(output))} is a symbolic link to a missing folder "
                        f"or to a file; name a folder", field="--output")
    if output.exists() and not output.is_dir():
        raise UserError(f"{printable(str(output))} is not a folder; name a folder",
                        field="--output")
    if html:
        _html_report(design, output, catalog, motor, rank_by, top, best, dpi)
        return
    targets = [output / REPORT_FILE, output / LAWS_FIGURE, output / TIME_FIGURE,
               *(output / candidate_figure(rank) for rank in range(1, best + 1))]
    check_outputs(targets, [design, *(catalog or ())])
    if is_machine(design):
        _machine_report(design, output, catalog, motor, rank_by, top, best, dpi, targets)
        return
    loaded, sizing = load_and_size(design, catalog, motor, rank_by, outputs=targets)
    written = write_report(loaded, sizing, output, top=top, best=best, rank_by=rank_by,
                           source=design.name, dpi=dpi)
    typer.echo(printable(f"{written[0]}: report with {len(written) - 1} figures"))


def _html_report(design: Path, output: Path, catalog, motor, rank_by: str | None, top: int,
                 best: int, dpi: float) -> None:
    """``sizer report --html``: DIR/report.html, one self-contained file."""
    from sizer.cli.output_guard import check_outputs
    from sizer.cli.size_command import load_and_size
    from sizer.report.html_report import HTML_FILE, write_html_report

    if is_machine(design):
        raise UserError("a machine file's report is Markdown only: leave out --html, or "
                        "give one axis's design file", field="--html")
    targets = [output / HTML_FILE]
    check_outputs(targets, [design, *(catalog or ())])
    try:
        design_bytes = design.read_bytes()
    except OSError as error:
        raise UserError(f"cannot read it: {error.strerror or error}",
                        file=str(design)) from None
    loaded, sizing = load_and_size(design, catalog, motor, rank_by, outputs=targets)
    path = write_html_report(loaded, sizing, output, top=top, best=best, rank_by=rank_by,
                             source=design.name, design_bytes=design_bytes, dpi=dpi)
    typer.echo(printable(f"{path}: self-contained HTML report"))


def _machine_report(path: Path, output: Path, catalog, motor, rank_by: str | None, top: int,
                    best: int, dpi: float, targets: list[Path]) -> None:
    """``sizer report`` of a machine file: DIR/report.md, the bus figure, and each axis's
    design report in DIR/<n>-<axis>/."""
    from sizer import api
    from sizer.cli.output_guard import check_outputs
    from sizer.cli.progress import sizing_progress
    from sizer.report.machine_file_report import BUS_FIGURE, axis_folder, write_machine_report

    refuse_motor_options(catalog, motor)
    machine = api.load_machine(path)
    folders = [output / axis_folder(a.name, i) for i, a in enumerate(machine.axes)]
    check_outputs([*targets, output / BUS_FIGURE,
                   *(f / t.name for f in folders for t in targets)], machine.files)
    try:
        with sizing_progress(f"sizing {path.name}", unit="laws") as progress:
            result = api.size_machine(machine, rank_by=rank_by, progress=progress)
    except UserError as error:
        raise error.located(file=str(path)) from None
    written = write_machine_report(machine, result, output, top=top, best=best,
                                   rank_by=rank_by, dpi=dpi)
    typer.echo(printable(f"{written[0]}: machine report with {len(written) - 1} files"))


def register(app: typer.Typer) -> None:
    app.command("report")(report)
