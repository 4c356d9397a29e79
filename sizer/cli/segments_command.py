"""``sizer segments``: the machine cycle of a design segment by segment, for one motor."""

from __future__ import annotations

from typing import TYPE_CHECKING, Annotated

import typer

from sizer.cli.catalog_option import CatalogOption, DesignArgument, load_design_file
from sizer.cli.options import (
    EnvelopeOption,
    FormatOption,
    OutputOption,
    as_option,
    check_law_specs,
)
from sizer.errors import UserError
from sizer.report.formats import Format

if TYPE_CHECKING:
    from sizer.model.domain import Design
    from sizer.sizing import CandidateResult


def segments(
    design: DesignArgument,
    motor: Annotated[str | None, typer.Option(
        "--motor", "-m", metavar="ID",
        help="The motor (an id among the loaded motors). Default: the design's check "
             "motor, else the motor of the best-ranked feasible pair.",
        show_default=False)] = None,
    law: Annotated[str | None, typer.Option(
        "--law", "-l", metavar="SPEC",
        help="The law of the moves that name none. Default: the design's check law, else "
             "the best-ranked law for the motor.", show_default=False)] = None,
    catalog: CatalogOption = None,
    fmt: FormatOption = Format.TABLE,
    output: OutputOption = None,
    envelope: EnvelopeOption = None,
) -> None:
    """Show the machine cycle segment by segment for one motor and law.

    For each segment (move, run, dwell) its start and end time, law, peak and RMS
    torque, share of the cycle's RMS^2, peak motor speed and work at the motor shaft, and
    where the acceleration steps at a join (a jerk impulse); under the table the cycle
    time and the cycle's RMS torque. The pair is sized as in 'sizer size' (its duration,
    T_min with 'duration: minimize', its ratio where chosen). Exit code 0 (also for a
    pair that fails a limit: 'sizer check' is the verdict), 2 for bad input or a pair
    with no feasible duration, 3 for an internal error.

    Examples:

        sizer segments examples/indexing-table.yaml

        sizer segments examples/indexing-table.yaml --motor HG-KN73J --law poly5 -f csv
    """
    from sizer import api
    from sizer.cli.output_guard import check_output, check_outputs
    from sizer.report.segment_table import SegmentDocument, breakdown_for, publish_segments

    check_law_specs([] if law is None else [law], "--law")  # '' is refused too
    check_output(output, [design, *(catalog or ())])
    loaded = api.override(load_design_file(design, catalog), envelope=envelope or None)
    check_outputs(() if output is None else (output,), loaded.files)
    try:
        with as_option("laws", "--law"):  # the sizing's word on --law names the option
            result = segments_pair(loaded, motor, law)
        breakdown = breakdown_for(loaded, result)
    except UserError as error:
        if (error.field or "").startswith("--"):  # an option's mistake, not the file's
            raise
        raise error.located(file=str(design)) from None
    document = SegmentDocument(breakdown, loaded, api.assumptions(loaded),
                               feasible=bool(result.feasible))
    publish_segments(document, fmt, output)


def segments_pair(design: Design, motor: str | None, law: str | None) -> CandidateResult:
    """The sizing result to break down: the design's check pair (``sizer check``'s
    result) without --motor and --law, else the pair ``sizer plot`` would draw."""
    from sizer import api
    from sizer.cli.plot_command import plot_pairs

    if motor is None and law is None and design.chosen_motor and design.chosen_law:
        return api.check(design)
    return plot_pairs(design, motor, (law,) if law else ())[0]


def register(app: typer.Typer) -> None:
    app.command("segments")(segments)
