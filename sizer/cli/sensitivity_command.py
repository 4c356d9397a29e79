"""``sizer sensitivity``: which input moves a pair's margins most (docs/sensitivity.md)."""

from __future__ import annotations

from typing import Annotated

import typer

from sizer.cli.catalog_option import CatalogOption, DesignArgument
from sizer.cli.options import EnvelopeOption, FormatOption, OutputOption
from sizer.errors import UserError
from sizer.report.formats import Format


def sensitivity(
    design: DesignArgument,
    motor: Annotated[str | None, typer.Option(
        "--motor", "-m", metavar="ID",
        help="The motor (default: the design's check: motor, else the top-ranked "
             "feasible pair's).", show_default=False)] = None,
    law: Annotated[str | None, typer.Option(
        "--law", "-l", metavar="SPEC",
        help="The law (default: the design's check: law, else the top-ranked feasible "
             "pair's).", show_default=False)] = None,
    catalog: CatalogOption = None,
    envelope: EnvelopeOption = None,
    fmt: FormatOption = Format.TABLE,
    output: OutputOption = None,
) -> None:
    """How much each margin of a motor and law pair moves per relative change of each
    input: the quantity to measure before buying.

    For every input present in the design (the load's inertia or mass, friction,
    damping, torque or force; each stage's ratio and efficiency; the task's
    displacement, duration and dwell, or a cycle's cycle time, segment durations and
    move displacements; the motor's rated and peak torque, rated speed and rotor
    inertia) the change of every check's margin (and of T_min with minimize) per
    relative change of the input, d margin / d ln x, by central differences of sizings;
    inputs most influential first. Where a margin has a kink there (the limiting check
    changes) the cell shows both one-sided values, a|b.

    Exit code 0; 2 for bad input (an unknown motor or law, a pair with no feasible
    duration to minimize). The step, the kinks and the records: docs/sensitivity.md.

    Examples:

        sizer sensitivity examples/book/ex6_3.yaml

        sizer sensitivity examples/indexing-table.yaml --motor HG-KN43J --law cycloidal --format md
    """
    from sizer import api
    from sizer.cli.catalog_option import load_design_file
    from sizer.cli.output_guard import check_output
    from sizer.report.sensitivity_table import SensitivityDocument, publish
    from sizer.sensitivity import sensitivity as compute

    check_output(output, [design, *(catalog or ())])
    loaded = api.override(load_design_file(design, catalog), envelope=envelope or None)
    if not loaded.motors:
        raise UserError("the design has no motors to take the sensitivities of",
                        file=str(design))
    try:
        result = compute(loaded, motor, law)
    except UserError as error:
        if error.field in ("motor", "law"):
            raise UserError(error.message, field=f"--{error.field}") from None
        raise error.located(file=str(design)) from None
    publish(SensitivityDocument(result, loaded.name), fmt, output)


def register(app: typer.Typer) -> None:
    app.command("sensitivity")(sensitivity)
