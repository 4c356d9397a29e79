"""The ``sizer`` command: the shared typer app, ``--version``, and ``main``.

Commands live in their own modules and add themselves with ``register(app)``; a new
command (``size``, ``check``, ``catalog ...``) is a new module listed in COMMAND_MODULES.
"""

from __future__ import annotations

import functools
import inspect
import os
import sys
from collections.abc import Sequence
from typing import Annotated, Any

import typer
import typer.main
from typer import Abort, Exit

try:  # typer >= 0.20 has its own copy of click; older ones use click itself
    from typer._click import exceptions as click_exceptions
except ImportError:  # pragma: no cover
    from click import exceptions as click_exceptions  # type: ignore[no-redef, import-not-found]

from sizer import __version__
from sizer.cli import (
    cam_command,
    catalog_command,
    check_command,
    diff_command,
    idta_command,
    law_command,
    laws_command,
    plot_command,
    report_command,
    schema_command,
    segments_command,
    sensitivity_command,
    size_command,
    spectrum_command,
    vibration_command,
)
from sizer.cli.exit_codes import ExitCode
from sizer.cli.reporting import report_internal_error, report_user_error, set_debug
from sizer.errors import UserError
from sizer.report.printable import printable

EXIT_CODES_HELP = ("Exit codes: 0 ok; 1 a check failed (sizer check: a limit not met; "
                   "catalog validate: a finding; sizer diff: a pair that passed fails); 2 "
                   "bad input (one 'error: ...' line naming the file, line and field, or "
                   "the option); 3 internal error (a bug in "
                   "sizer: one 'internal error: ...' line, --debug shows the traceback); "
                   "130 interrupted.")

COMMAND_MODULES = (laws_command, law_command, size_command, check_command, schema_command,
                   catalog_command, plot_command, report_command, segments_command,
                   spectrum_command, vibration_command, cam_command, idta_command, diff_command,
                   sensitivity_command)

app = typer.Typer(
    name="sizer",
    help="Size servo motors and choose motion laws for automatic machines "
         "(Biagiotti & Melchiorri, ch. 6).\n\n"
         "Examples:\n\n"
         "    sizer size examples/indexing-table.yaml\n\n"
         "    sizer check examples/indexing-table.yaml\n\n"
         "    sizer laws --format md\n\n"
         "    sizer law cycloidal --displacement '90 deg' --duration '0.2 s'\n\n"
         + EXIT_CODES_HELP,
    no_args_is_help=True,
    add_help_option=False,  # our own --help below: typer's would import pydantic to coerce
    rich_markup_mode=None,  # click's plain help: typer's rich help imports ~0.15 s of rich
    add_completion=False,
    pretty_exceptions_enable=False,
    pretty_exceptions_show_locals=False,
)


def _show_version(value: bool) -> None:
    if value:
        typer.echo(f"sizer {__version__}")
        raise typer.Exit()


def _show_help(context: typer.Context, value: bool) -> None:
    if value and not context.resilient_parsing:
        typer.echo(context.get_help())
        raise typer.Exit()


@app.callback()
def _root(
    version: Annotated[bool, typer.Option(
        "--version", callback=_show_version, is_eager=True,
        help="Show the version and exit.")] = False,
    debug: Annotated[bool, typer.Option(
        "--debug",
        help="On an internal error (exit code 3) show the traceback (so does "
             "SIZER_DEBUG=1).")] = False,
    show_help: Annotated[bool, typer.Option(
        "--help", callback=_show_help, is_eager=True, expose_value=False,
        help="Show this message and exit.")] = False,
) -> None:
    """Size servo motors and choose motion laws for automatic machines."""
    if debug:
        set_debug(True)


for _module in COMMAND_MODULES:
    _module.register(app)


def _command_words(args: Sequence[str]) -> str:
    """'sizer size' or 'sizer catalog import': the command of ``args``, options left out."""
    words = [a for a in args if not a.startswith("-")][:2]
    if words and words[0] != "catalog":
        words = words[:1]
    return " ".join(["sizer", *words])


def _usage_error_line(error: click_exceptions.ClickException) -> str:
    """A click usage error as one 'error: ...' line (no box, no usage text)."""
    message = " ".join(error.format_message().replace("Value error, ", "").split())
    context = getattr(error, "ctx", None)
    if isinstance(error, click_exceptions.UsageError) and context is not None:
        message += f" (see '{context.command_path} --help')"
    return f"error: {printable(message)}"


def _silence_stdout() -> None:
    """After a broken pipe: point stdout at /dev/null so the final flush stays quiet."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError, AttributeError):
        pass


def _whole_summaries(command: Any) -> None:
    """The first paragraph of each command's help as its line in the command lists, whole
    (click would cut it to ~45 characters)."""
    for sub in getattr(command, "commands", {}).values():
        if not sub.short_help and sub.help:
            sub.short_help = " ".join(inspect.cleandoc(sub.help).split("\n\n")[0].split())
        _whole_summaries(sub)


def _invoked(args: Sequence[str]) -> str | None:
    """The command of ``args`` when only --debug precedes it, else None (the whole tree: a
    root --help or --version, no command, an unknown one)."""
    first = next((a for a in args if a != "--debug"), None)
    known = [c.name for c in app.registered_commands] + [g.name for g in app.registered_groups]
    return first if first in known else None


@functools.cache
def _command(name: str | None = None) -> Any:
    """sizer's click command tree (typer builds it from the annotations), once a process;
    with ``name`` the root with that one command, all its run needs (building every
    command costs ~20 ms more of each start-up, issue 34)."""
    commands, groups = app.registered_commands, app.registered_groups
    if name is not None:
        app.registered_commands = [c for c in commands if c.name == name]
        app.registered_groups = [g for g in groups if g.name == name]
    try:
        command = typer.main.get_command(app)
    finally:
        app.registered_commands, app.registered_groups = commands, groups
    _whole_summaries(command)
    return command


def run(argv: Sequence[str] | None = None) -> int:
    """Run the app on ``argv`` (default: the command line) and return the exit code.

    0 ok, 1 a check failed, 2 a user or usage error (one 'error:' line), 3 an internal
    error (one 'internal error:' line; the traceback with --debug or SIZER_DEBUG=1),
    130 interrupted, 141 stdout closed by its reader.
    """
    set_debug(False)
    args = sys.argv[1:] if argv is None else list(argv)
    command = _command(_invoked(args))
    try:
        try:
            with command.make_context("sizer", args) as context:
                command.invoke(context)
        except Exit as exit_:
            return exit_.exit_code
        except click_exceptions.NoArgsIsHelpError as error:
            shown = error.format_message()  # the help of the command group
            if shown.strip():
                sys.stdout.write(shown.rstrip("\n") + "\n")
            return ExitCode.USER_ERROR
        except click_exceptions.ClickException as error:
            sys.stderr.write(_usage_error_line(error) + "\n")
            sys.stderr.flush()
            return ExitCode.USER_ERROR if isinstance(error, click_exceptions.UsageError) \
                else error.exit_code
        except UserError as error:
            report_user_error(error)
            return ExitCode.USER_ERROR
    except (KeyboardInterrupt, Abort):
        sys.stderr.write("interrupted\n")
        sys.stderr.flush()
        return ExitCode.INTERRUPTED
    except BrokenPipeError:
        _silence_stdout()
        return ExitCode.BROKEN_PIPE
    except Exception as error:  # a bug: one line, the traceback only on request
        report_internal_error(error, f"'{_command_words(args)}'")
        return ExitCode.INTERNAL_ERROR
    return ExitCode.OK


def main(argv: Sequence[str] | None = None) -> None:
    """Run the app on ``argv`` (default: the command line) and exit with its code."""
    code = run(argv)
    try:
        sys.stdout.flush()
    except BrokenPipeError:  # the reader left after the last write: quiet, like above
        _silence_stdout()
        code = code or ExitCode.BROKEN_PIPE
    except (OSError, ValueError):
        pass
    sys.exit(code)
