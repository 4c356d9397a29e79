"""How the ``sizer`` command reports on stderr: one 'warning: ...' line per warning, one
'error: ...' line per user error, one 'internal error: ...' line per bug (the traceback
first with ``--debug`` or SIZER_DEBUG=1). The app and its commands share these lines."""

from __future__ import annotations

import os
import sys
import traceback
from collections.abc import Iterable

from sizer import __version__
from sizer.errors import UserError
from sizer.report.printable import printable

_debug = False
"""Set by ``--debug``: an internal error shows its traceback."""


def set_debug(on: bool) -> None:
    """``--debug`` was given (True), or a new run starts (False)."""
    global _debug
    _debug = on


def debug_enabled() -> bool:
    """``--debug`` was given or SIZER_DEBUG is set (to anything but '', 0, false, no)."""
    flag = os.environ.get("SIZER_DEBUG", "").strip().lower()
    return _debug or flag not in ("", "0", "false", "no", "off")


def report_user_error(error: UserError) -> None:
    """One line on stderr: 'error: file:line: field: message' (control characters
    escaped)."""
    text = " ".join(str(error).split("\n"))  # a CR or another control stays, escaped
    sys.stderr.write(f"error: {printable(text)}\n")
    sys.stderr.flush()


def report_warnings(warnings: Iterable[str]) -> None:
    """One 'warning: ...' line on stderr per warning; nothing when there are none."""
    for warning in warnings:
        sys.stderr.write(f"warning: {printable(' '.join(warning.split()))}\n")
    sys.stderr.flush()


def internal_error_line(error: BaseException, what: str = "") -> str:
    """The one line that reports a bug: what failed (the command or file, and where in
    sizer), the exception's type and message, how to report it."""
    message = " ".join(str(error).split())
    where = _where(error)
    failed = " ".join(part for part in (what, where) if part)
    return printable(f"internal error{' in ' + failed if failed else ''}: "
                     f"{type(error).__name__}{': ' + message if message else ''} - this is a "
                     f"bug in sizer {__version__}; please report it with the command and its "
                     f"input files (run again with --debug for the traceback)")


def _where(error: BaseException) -> str:
    """'(at sizer/x.py:12 in f)': the innermost frame of the sizer package, if any."""
    package = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    frames = [f for f in traceback.extract_tb(error.__traceback__)
              if os.path.abspath(f.filename).startswith(package + os.sep)]
    if not frames:
        return ""
    frame = frames[-1]
    shown = os.path.relpath(os.path.abspath(frame.filename), os.path.dirname(package))
    return f"(at {shown}:{frame.lineno} in {frame.name})"


def report_internal_error(error: BaseException, what: str = "") -> None:
    """The traceback (with --debug or SIZER_DEBUG=1), then the one internal-error line."""
    if debug_enabled():
        traceback.print_exception(error, file=sys.stderr)
    sys.stderr.write(internal_error_line(error, what) + "\n")
    sys.stderr.flush()
