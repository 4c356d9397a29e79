"""Options shared by several commands, so they read and behave the same everywhere."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from enum import StrEnum
from pathlib import Path
from typing import Annotated

import typer

from sizer.errors import UserError
from sizer.report.formats import Format


@contextmanager
def blame_option(field: str) -> Iterator[None]:
    """A UserError raised inside names the option ``field``: before the field it names
    inside the option's value (``--law: start.velocity: ...``), unless it is located in a
    file (a cam table's line)."""
    try:
        yield
    except UserError as error:
        if error.file is not None:
            raise
        if error.field and not error.field.startswith(field):
            raise UserError(error.message, line=error.line,
                            field=f"{field}: {error.field}") from None
        raise error.located(field=field) from None


@contextmanager
def as_option(parameter: str, option: str) -> Iterator[None]:
    """A UserError that sizer.api raises about its ``parameter`` (``motors``,
    ``rank_by``...) names the command's ``option`` (``--motor``, ``--rank-by``) instead."""
    try:
        yield
    except UserError as error:
        if error.field != parameter:
            raise
        raise UserError(error.message, file=error.file, line=error.line,
                        field=option) from None


def check_law_specs(specs: list[str] | tuple[str, ...], field: str) -> None:
    """Every spec reads as a law (``auto`` parameters allowed), else a UserError naming
    ``field``: checked before any file is read or any work done."""
    from sizer.laws import law_choice  # lazy: keeps --help fast

    for spec in specs:
        with blame_option(field):
            law_choice(spec)

def scaled_move(displacement: str | None, duration: str | None, neither: str
                ) -> tuple[float, float, bool] | None:
    """(h, T, linear) of --displacement and --duration, None for ``neither``; a UserError
    naming the option when only one is given, T is not positive or h is zero."""
    from sizer.units import parse_displacement, to_si  # lazy: keeps --help fast

    if (displacement is None) != (duration is None):
        given = "--displacement" if displacement is not None else "--duration"
        missing = "--duration" if displacement is not None else "--displacement"
        raise UserError(f"{given} needs {missing} too (or neither, for {neither})",
                        field=missing)
    if displacement is None:
        return None
    h, linear = parse_displacement(displacement, field="--displacement")
    T = to_si(duration, "time", field="--duration")  # finite, else a UserError
    if not T > 0.0:
        raise UserError(f"must be positive, got {duration!r}", field="--duration")
    if h == 0.0:
        raise UserError("must not be zero", field="--displacement")
    return h, T, linear


FormatOption = Annotated[
    Format,
    typer.Option(
        "--format", "-f",
        case_sensitive=False,
        help="Output format: table (rich on a terminal, plain text when piped), "
             "csv, md (Markdown) or json.",
    ),
]

OutputOption = Annotated[
    Path | None,
    typer.Option(
        "--output", "-o",
        dir_okay=False,
        metavar="FILE",
        help="Write to FILE (replaced atomically) instead of stdout.",
    ),
]


class EnvelopeChoice(StrEnum):
    """Completion rules of regions without curves (sizer.envelope.completion)."""

    BOOK = "book"
    LINEAR = "linear"
    LINEAR_INTERMITTENT = "linear_intermittent"
    ELECTRICAL = "electrical"


MotorsOption = Annotated[
    list[str] | None,
    typer.Option(
        "--motor", "-m", metavar="ID", show_default=False,
        help="Size only this motor (an id among the loaded motors); repeat for more.",
    ),
]


JobsOption = Annotated[
    int | None,
    typer.Option(
        "--jobs", "-j", metavar="N", min=1, show_default=False,
        help="Size the laws in N processes (the result is the same). Default: every CPU "
             "for a large design (about 500,000 candidate x law evaluations or more), one "
             "process otherwise.",
    ),
]


EnvelopeOption = Annotated[
    EnvelopeChoice | None,
    typer.Option(
        "--envelope", case_sensitive=False, show_default=False,
        help="How a motor region without a curve is completed up to max_speed: book "
             "(the book's rectangles up to the rated speed), linear (then straight lines "
             "down to max_speed), linear_intermittent, or electrical (the region the "
             "winding's supply allows, for motors with k_t, R and a supply voltage; "
             "linear for the others). Default: the design's 'envelope:' (electrical).",
    ),
]
