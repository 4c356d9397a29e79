"""``sizer law``: one motion law scaled to a move, sampled in time."""

from __future__ import annotations

import sys
from typing import Annotated

import typer

from sizer.cli.options import FormatOption, OutputOption, blame_option
from sizer.errors import UserError
from sizer.report.formats import Format

MAX_SAMPLES = 1_000_000


def law(
    spec: Annotated[str, typer.Argument(
        help="The law, e.g. cycloidal, poly5 or 'trapezoidal(alpha=1/3)'.",
        show_default=False)],
    displacement: Annotated[str | None, typer.Option(
        "--displacement", metavar="H",
        help="Displacement h: an angle ('90 deg', rad if bare) or a length ('200 mm'); "
             "a law defined by data with units gives its own.",
        show_default=False)] = None,
    duration: Annotated[str | None, typer.Option(
        "--duration", metavar="T", help="Duration T of the move, e.g. '0.2 s' (s if bare); "
             "a law defined by data with time units gives its own.",
        show_default=False)] = None,
    start_time: Annotated[str, typer.Option(
        "--start-time", metavar="T0", help="Time t0 when the move starts.")] = "0",
    start_position: Annotated[str, typer.Option(
        "--start-position", metavar="Q0",
        help="Position q0 at the start, same kind as the displacement.")] = "0",
    samples: Annotated[int, typer.Option(
        "--samples", "-n", metavar="N", help="Number of equally spaced samples, ends included.",
    )] = 101,
    fmt: FormatOption = Format.TABLE,
    output: OutputOption = None,
) -> None:
    """Sample a motion law scaled to a move: time t, position q, velocity v, accel a, jerk j.

    q(t) = q0 + h q_N((t - t0)/T); the columns are in SI units (rad or m based).

    Example:

        sizer law cycloidal --displacement '90 deg' --duration '0.2 s' --format csv
    """
    from sizer.cli.output_guard import check_output
    from sizer.laws import ScaledMotion, make_law  # lazy: keeps --help fast
    from sizer.laws.motion import scale_fault
    from sizer.report.document import publish
    from sizer.report.printable import printable
    from sizer.report.series_table import SeriesDocument, fit_text
    from sizer.units import parse_displacement, to_si

    check_output(output)
    if not 2 <= samples <= MAX_SAMPLES:
        raise UserError(f"must be between 2 and {MAX_SAMPLES}, got {samples}", field="--samples")
    with blame_option("SPEC"):
        law_object = make_law(spec)
    check_output(output)  # again: not over a file the law read (a cam table)
    scale = getattr(law_object, "scale", None)
    if displacement is not None:
        h, linear = parse_displacement(displacement, field="--displacement")
    elif scale is not None:
        h, linear = scale.displacement, scale.linear
    else:
        raise UserError("missing option (the law has no units of its own to give it)",
                        field="--displacement")
    if duration is not None:
        T = to_si(duration, "time", field="--duration")
    elif scale is not None and not scale.master:
        T = scale.span
    else:
        raise UserError("missing option (" + ("the law's abscissa is a master angle: give "
                        "the duration of one period" if scale is not None else
                        "the law has no units of its own to give it") + ")",
                        field="--duration")
    if T <= 0.0:
        raise UserError(f"must be positive, got {duration!r}", field="--duration")
    fault = scale_fault(h, T)
    if fault is not None:
        raise UserError(f"a move of {h:g} in {T:g} s: {fault}", field="--duration")
    t0 = to_si(start_time, "time", field="--start-time")
    q0 = to_si(start_position, "length" if linear else "angle", field="--start-position")
    motion = ScaledMotion(law_object, h, T, start_time=t0, start_position=q0)
    publish(SeriesDocument(motion, motion.sample(samples), linear=linear), fmt, output)
    fit = fit_text(law_object)
    if fit:
        sys.stderr.write(printable(f"note: {law_object.law_id}: {fit}") + "\n")


def register(app: typer.Typer) -> None:
    app.command("law")(law)
