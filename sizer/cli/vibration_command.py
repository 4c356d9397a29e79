"""``sizer vibration``: each law's residual vibration over a range of durations."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from sizer.cli.catalog_option import CatalogOption, DesignArgument, load_design_file
from sizer.cli.options import FormatOption, OutputOption, blame_option, check_law_specs
from sizer.errors import UserError
from sizer.input_limits import MAX_VIBRATION_POINTS
from sizer.report.formats import Format

if TYPE_CHECKING:
    from sizer.model.domain import Design

POINTS = 201
"""Durations in the sweep by default."""

MAX_POINTS = MAX_VIBRATION_POINTS
SWEEP_STEPS = 16
"""Runs of each law's sweep: the progress bar moves every 1/16 of its durations."""
"""The most durations one sweep evaluates (sizer.input_limits)."""


def vibration(
    design: DesignArgument,
    law: Annotated[list[str] | None, typer.Option(
        "--law", "-l", metavar="SPEC",
        help="A law to sweep (repeatable). Default: the design's laws.",
        show_default=False)] = None,
    start: Annotated[str | None, typer.Option(
        "--from", metavar="DURATION",
        help="The shortest duration, e.g. '0.2 s' (a number: seconds; for a cycle, the "
             "scale of its free durations). Default: half the design's duration, or the "
             "shortest T_min of its feasible pairs in minimize mode.",
        show_default=False)] = None,
    stop: Annotated[str | None, typer.Option(
        "--to", metavar="DURATION",
        help="The longest duration. Default: twice the design's duration, or four times "
             "the shortest T_min.", show_default=False)] = None,
    points: Annotated[int, typer.Option(
        "--points", "-n", help="Durations in the sweep, evenly spaced.")] = POINTS,
    plot: Annotated[Path | None, typer.Option(
        "--plot", dir_okay=False, metavar="FILE",
        help="Also draw the residual against the duration to FILE (.png or .svg).",
        show_default=False)] = None,
    catalog: CatalogOption = None,
    fmt: FormatOption = Format.TABLE,
    output: OutputOption = None,
) -> None:
    """Show each law's residual vibration over a range of move durations.

    The design's load must give its mode (load.natural_frequency, load.damping_ratio;
    book sec. 7.1.1). For each duration, the amplitude of the load's free vibration after
    each move (sec. 7.2, the exact linear response; in the steady state of the repeated
    cycle when damped), the largest over the cycle's moves; '*' marks an amplitude above
    limits.residual_vibration. Read it to pick T: the shortest duration whose residual is
    small enough. Exit code 0, 2 for bad input, 3 for an internal error.

    Examples:

        sizer vibration examples/indexing-table-vibration.yaml

        sizer vibration examples/indexing-table-vibration.yaml --from 0.2s --to 0.6s --plot r.png
    """
    from sizer.cli.output_guard import check_output, check_outputs
    from sizer.laws import law_choice
    from sizer.laws.data_spec import law_label
    from sizer.report.output import emit
    from sizer.report.vibration_table import VibrationDocument

    check_law_specs(law or [], "--law")
    if not 2 <= points <= MAX_POINTS:
        raise UserError(f"must be in [2, {MAX_POINTS:,}] (MAX_VIBRATION_POINTS), got "
                        f"{points}", field="--points")
    check_output(output, [design, *(catalog or ())])
    check_output(plot, [design, *(catalog or ())], field="--plot")
    if plot is not None:
        from sizer.report.plots.figure_files import figure_format

        figure_format(plot, "--plot")
    loaded = load_design_file(design, catalog)
    check_outputs([output] if output is not None else [], loaded.files)
    check_outputs([plot] if plot is not None else [], loaded.files, field="--plot")
    if loaded.load.elastic is None:
        raise UserError("the design gives no mode of the load: add load.natural_frequency "
                        "(and damping_ratio)", file=str(design), field="load.natural_frequency")
    specs = [law_choice(spec) for spec in law] if law else list(loaded.laws)
    if not law:  # a law shaped for every duration leaves nothing to sweep: left out
        specs = [spec for spec in specs if not spec.open_shaped] or specs
    for spec in specs:
        if spec.auto:
            raise UserError(f"{spec}: give the shape (auto parameters depend on the motor)",
                            field="--law" if law else "laws")
        if spec.open_shaped:
            raise UserError(f"{law_label(spec.text)}: shaped for the mode at every duration, its "
                            "residual is zero by construction; give f_T to sweep one "
                            "shaping", field="--law" if law else "laws")
    laws = tuple(spec.law for spec in specs)
    check_output(output)  # again: not over a file a law read (a cam table)
    check_output(plot, field="--plot")
    try:
        low, high = _range(loaded, start, stop)
        import numpy as np

        from sizer.cli.progress import sizing_progress
        from sizer.sizing.vibration_check import vibration_sweep

        with sizing_progress(f"sweeping {design.name}", unit="steps") as progress:
            # in SWEEP_STEPS runs per law, so that the bar moves (the same numbers)
            sweep = vibration_sweep(loaded, laws, np.linspace(low, high, points), progress,
                                    SWEEP_STEPS)
    except UserError as error:
        if (error.field or "").startswith("--"):
            raise
        raise error.located(file=str(design)) from None
    document = VibrationDocument(sweep, loaded)
    emit(document.render(fmt), output, escape=fmt in (Format.TABLE, Format.MD))
    if plot is not None:
        from sizer.report.plots.figure_files import save_figure
        from sizer.report.plots.vibration_plot import vibration_figure

        save_figure(vibration_figure(sweep, loaded.task.linear, loaded.cycle is not None),
                    plot)


def _seconds(text: str, field: str) -> float:
    from sizer.units import to_si

    with blame_option(field):
        try:
            value = float(text)
        except ValueError:
            try:
                value = to_si(text, "time")
            except ValueError as error:
                raise UserError(str(error)) from None
    if not (value > 0.0 and value < 1e6):
        raise UserError(f"must be a positive duration, got {text}", field=field)
    return value


def _range(design: Design, start: str | None, stop: str | None) -> tuple[float, float]:
    """The sweep's durations (or scales): the options, else around the design's own."""
    low = None if start is None else _seconds(start, "--from")
    high = None if stop is None else _seconds(stop, "--to")
    if low is None or high is None:
        base = _base_scale(design)
        low = base / 2.0 if low is None else low
        high = (base * (4.0 if _minimize(design) else 2.0)) if high is None else high
        if _minimize(design) and start is None:
            low = base
    if not low < high:
        raise UserError(f"--from ({low:g}) must be shorter than --to ({high:g})",
                        field="--to")
    return low, high


def _minimize(design: Design) -> bool:
    return design.machine_cycle.minimize


def _base_scale(design: Design) -> float:
    """The design's duration (scale), or in minimize mode the shortest T_min of its
    feasible pairs (a task) -- a cycle in minimize mode needs --from and --to."""
    from sizer.sizing.cycle import given_scale

    if design.cycle is not None:
        if design.cycle.minimize:
            raise UserError("a cycle in minimize mode: give the scales with --from and --to",
                            field="--from")
        return given_scale(design.cycle)
    if design.task.duration is not None:
        return design.task.duration
    from sizer import api
    from sizer.cli.progress import sizing_progress

    with sizing_progress("sizing for the shortest T_min", unit="laws") as progress:
        sized = api.size(design, progress=progress)
    best = [r.duration for r in sized.results if r.feasible and r.duration is not None]
    if not best:
        raise UserError("no motor/law pair is feasible: give the durations with --from "
                        "and --to", field="--from")
    return min(best)


def register(app: typer.Typer) -> None:
    app.command("vibration")(vibration)
