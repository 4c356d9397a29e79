"""The ``sizer`` command: the shared typer app, ``--version``, and ``main``.

Commands live in their own modules and add themselves with ``register(app)``; a new
command (``size``, ``check``, ``catalog ...``) is a new module listed in COMMAND_MODULES.
"""

from __future__ import annotations

import sys
from collections.abc import Iterable, Sequence
from typing import Annotated

import typer

from sizer import __version__
from sizer.cli import (
    catalog_command,
    check_command,
    law_command,
    laws_command,
    plot_command,
    report_command,
    schema_command,
    size_command,
)
from sizer.errors import UserError

USER_ERROR_EXIT_CODE = 2
"""Exit code for mistakes in the user's input (click uses 2 for usage errors too)."""

COMMAND_MODULES = (laws_command, law_command, size_command, check_command, schema_command,
                   catalog_command, plot_command, report_command)

app = typer.Typer(
    name="sizer",
    help="Size servo motors and choose motion laws for automatic machines "
         "(Biagiotti & Melchiorri, ch. 6).\n\n"
         "Examples:\n\n"
         "    sizer size examples/indexing-table.yaml\n\n"
         "    sizer check examples/indexing-table.yaml\n\n"
         "    sizer laws --format md\n\n"
         "    sizer law cycloidal --displacement '90 deg' --duration '0.2 s'",
    no_args_is_help=True,
    rich_markup_mode="markdown",
    add_completion=False,
    pretty_exceptions_show_locals=False,
)


def _show_version(value: bool) -> None:
    if value:
        typer.echo(f"sizer {__version__}")
        raise typer.Exit()


@app.callback()
def _root(
    version: Annotated[bool, typer.Option(
        "--version", callback=_show_version, is_eager=True,
        help="Show the version and exit.")] = False,
) -> None:
    """Size servo motors and choose motion laws for automatic machines."""


for _module in COMMAND_MODULES:
    _module.register(app)


def report_user_error(error: UserError) -> None:
    """One line on stderr: 'error: file:line: field: message'."""
    text = " ".join(str(error).split("\n"))
    sys.stderr.write(f"error: {text}\n")
    sys.stderr.flush()


def report_warnings(warnings: Iterable[str]) -> None:
    """One 'warning: ...' line on stderr per warning; nothing when there are none."""
    for warning in warnings:
        sys.stderr.write(f"warning: {' '.join(warning.split())}\n")
    sys.stderr.flush()


def main(argv: Sequence[str] | None = None) -> None:
    """Run the app on ``argv`` (default: the command line).

    A UserError ends with one line on stderr and exit code 2.
    """
    try:
        app(args=None if argv is None else list(argv))
    except UserError as error:
        report_user_error(error)
        sys.exit(USER_ERROR_EXIT_CODE)
