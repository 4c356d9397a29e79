"""The exit codes of every sizer command, written once (documented in docs/errors.md)."""

from __future__ import annotations

from enum import IntEnum


class ExitCode(IntEnum):
    """0 ok, 1 a check failed, 2 bad input, 3 a bug in sizer; 130 and 141 as shells say."""

    OK = 0
    CHECK_FAILED = 1
    """``sizer check``: a limit not met; ``catalog validate``: a finding."""
    USER_ERROR = 2
    """A mistake in the input or the options (click uses 2 for usage errors too)."""
    INTERNAL_ERROR = 3
    """An exception that is not a UserError: a bug in sizer."""
    INTERRUPTED = 130
    """Ctrl-C (128 + SIGINT)."""
    BROKEN_PIPE = 141
    """stdout's reader went away (128 + SIGPIPE, e.g. ``sizer laws | head -1``)."""
