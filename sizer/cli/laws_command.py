"""``sizer laws``: the shape-coefficient table of motion laws."""

from __future__ import annotations

from typing import Annotated

import typer

from sizer.cli.options import FormatOption, OutputOption, blame_option
from sizer.report.formats import Format

LawOption = Annotated[
    list[str] | None,
    typer.Option(
        "--law", "-l",
        metavar="SPEC",
        help="A law spec, e.g. cycloidal or 'trapezoidal(alpha=1/3)'; repeat for more. "
             "Default: the standard set of laws.",
    ),
]


def laws(
    law: LawOption = None,
    fmt: FormatOption = Format.TABLE,
    output: OutputOption = None,
) -> None:
    """Show the shape coefficients C_v, C_a, C_j, C_v_rms, C_a_rms of motion laws.

    Also the continuity class, whether the jerk is bounded, and where the acceleration
    jumps (jerk impulses) on the normalized time tau in [0, 1].

    Example:

        sizer laws --law cycloidal --law 'double_s(alpha=1/3, beta=1/4)' --format md
    """
    from sizer.cli.output_guard import check_output
    from sizer.laws import DEFAULT_LAW_SPECS, make_law  # lazy: keeps --help fast
    from sizer.report.document import publish
    from sizer.report.laws_table import LawsDocument

    check_output(output)
    specs = law or list(DEFAULT_LAW_SPECS)
    with blame_option("--law"):
        laws = [make_law(spec) for spec in specs]
    check_output(output)  # again: not over a file a law read (a cam table)
    publish(LawsDocument(laws), fmt, output)


def register(app: typer.Typer) -> None:
    app.command("laws")(laws)
