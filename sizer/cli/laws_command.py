"""``sizer laws``: the shape-coefficient table of motion laws."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from sizer.cli.options import FormatOption, OutputOption, blame_option
from sizer.report.formats import Format

if TYPE_CHECKING:
    from sizer.laws.sweep import SweepResult

LawOption = Annotated[
    list[str] | None,
    typer.Option(
        "--law", "-l",
        metavar="SPEC",
        help="A law spec, e.g. cycloidal or 'trapezoidal(alpha=1/3)'; repeat for more. "
             "Default: the standard set of laws.",
    ),
]


SweepOption = Annotated[
    str | None,
    typer.Option(
        "--sweep",
        metavar="SPEC",
        help="A coefficient study (book sec. 6.2.1): a law with one or two parameters "
             "given as ranges name=a..b (21 points) or name=a..b:n, e.g. "
             "'trapezoidal(alpha=0.05..0.5)' or 'double_s(alpha=0.1..0.4:7, beta=1/4)'. "
             "Tabulates C_v, C_a, C_j, C_v_rms, C_a_rms at every point.",
    ),
]

PlotOption = Annotated[
    Path | None,
    typer.Option(
        "--plot",
        metavar="FILE",
        help="With --sweep: also plot the coefficients against the parameter (PNG or "
             "SVG, by the suffix).",
    ),
]


DesignOption = Annotated[
    Path | None,
    typer.Option(
        "--design",
        metavar="FILE",
        help="With --sweep: also the design's T_min at every point (a design with "
             "'duration: minimize'; the fastest feasible motor, eq. (6.2)).",
    ),
]


def laws(
    law: LawOption = None,
    fmt: FormatOption = Format.TABLE,
    output: OutputOption = None,
    sweep: SweepOption = None,
    plot: PlotOption = None,
    design: DesignOption = None,
) -> None:
    """Show the shape coefficients C_v, C_a, C_j, C_v_rms, C_a_rms of motion laws.

    Also the continuity class, whether the jerk is bounded, and where the acceleration
    jumps (jerk impulses) on the normalized time tau in [0, 1].

    With --sweep, the coefficients of one law family against one or two of its shape
    parameters (book Figs. 6.10 and 6.14), a row per point; --plot draws them.

    Examples:

        sizer laws --law cycloidal --law 'double_s(alpha=1/3, beta=1/4)' --format md

        sizer laws --sweep 'trapezoidal(alpha=0.05..0.5)' --plot trapezoid.png
    """
    from sizer.cli.output_guard import check_output
    from sizer.laws import DEFAULT_LAW_SPECS, make_law  # lazy: keeps --help fast
    from sizer.report.document import publish
    from sizer.report.laws_table import LawsDocument

    check_output(output)
    if sweep is not None or plot is not None or design is not None:
        _sweep(sweep, law, fmt, output, plot, design)
        return
    specs = law or list(DEFAULT_LAW_SPECS)
    with blame_option("--law"):
        laws = [make_law(spec) for spec in specs]
    check_output(output)  # again: not over a file a law read (a cam table)
    publish(LawsDocument(laws), fmt, output)


def _sweep(sweep: str | None, law: list[str] | None, fmt: Format, output: Path | None,
           plot: Path | None, design: Path | None = None) -> None:
    """``sizer laws --sweep``: the table of the coefficients (with a design's T_min at
    each point), and their plot."""
    from sizer.cli.output_guard import check_output
    from sizer.errors import UserError
    from sizer.laws.sweep import parse_sweep, sweep_coefficients
    from sizer.report.document import publish
    from sizer.report.laws_sweep import SweepDocument, plot_sweep
    from sizer.report.plots.figure_files import figure_format

    if sweep is None and design is not None:
        raise UserError("gives T_min in a coefficient study: give --sweep too, e.g. "
                        "--sweep 'trapezoidal(alpha=0.05..0.5)'", field="--design")
    if sweep is None:
        raise UserError("draws a coefficient study: give --sweep too, e.g. "
                        "--sweep 'trapezoidal(alpha=0.05..0.5)'", field="--plot")
    if law:
        raise UserError("--law and --sweep are separate studies: give one of them",
                        field="--sweep")
    if plot is not None:
        figure_format(plot, "--plot")
        check_output(plot, field="--plot")
        if output is not None and Path(plot).absolute() == Path(output).absolute():
            raise UserError("the plot and the table would be the same file",
                            field="--plot")
    with blame_option("--sweep"):
        result = sweep_coefficients(parse_sweep(sweep))
    fastest = None if design is None else _fastest(design, result, [output, plot])
    publish(SweepDocument(result, fastest), fmt, output)
    if plot is not None:
        plot_sweep(result, plot, fastest)


def _fastest(design: Path, result: SweepResult, outputs: list[Path | None]
             ) -> list[tuple[float | None, str | None]]:
    """Per point of the sweep: the design's T_min with the point's law (the fastest
    feasible motor, sizer.api.size) and that motor; (None, None) where no motor is
    feasible or the law does not exist. A UserError for a design without ``minimize``."""
    from sizer import api
    from sizer.cli.catalog_option import load_design_file
    from sizer.cli.output_guard import check_outputs
    from sizer.cli.progress import sizing_progress
    from sizer.errors import UserError

    loaded = load_design_file(design, None)
    check_outputs([o for o in outputs if o is not None], loaded.files)
    existing = [point.spec for point in result.points if point.coefficients is not None]
    try:
        with sizing_progress(f"T_min of {design.name}", unit="laws") as progress:
            fastest = iter(api.fastest_by_law(loaded, existing, progress=progress))
    except UserError as error:
        if error.field == "laws":
            raise UserError(error.message, file=str(design), field="--design") from None
        raise error.located(file=str(design)) from None
    return [(None, None) if point.coefficients is None else next(fastest)
            for point in result.points]


def register(app: typer.Typer) -> None:
    app.command("laws")(laws)
