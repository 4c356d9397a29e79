"""A rich progress bar for long sizing runs, on a terminal only (never in a pipe or a file).

The core stays pure: ``size_design`` takes a plain ``progress(done, total)`` callback; this
module makes one that draws a transient bar on stderr, and only when stderr is a terminal.
The bar appears once a run has taken ``DELAY`` seconds, so quick runs print nothing.
"""

from __future__ import annotations

import os
import sys
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import IO, Any

DELAY = 0.5
"""Seconds before the bar appears (the environment variable SIZER_PROGRESS_DELAY sets
another, e.g. 0 to see it at once)."""


def is_terminal(stream: IO[str] | Any) -> bool:
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError):
        return False


class TerminalProgress:
    """A ``progress(done, total)`` callback drawing a rich bar on ``console`` after DELAY."""

    def __init__(self, description: str, console: Any, delay: float = DELAY) -> None:
        self.description = description
        self.console = console
        self.delay = delay
        self.started = time.monotonic()
        self._bar: Any = None
        self._task: Any = None

    def __call__(self, done: int, total: int) -> None:
        if self._bar is None:
            if time.monotonic() - self.started < self.delay or done >= total:
                return
            from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn

            self._bar = Progress(TextColumn("{task.description}"), BarColumn(),
                                 MofNCompleteColumn(), TextColumn("laws"),
                                 console=self.console, transient=True)
            self._bar.start()
            self._task = self._bar.add_task(self.description, total=total)
        self._bar.update(self._task, completed=done, total=total)

    def close(self) -> None:
        if self._bar is not None:
            self._bar.stop()
            self._bar = None


@contextmanager
def sizing_progress(description: str, stream: IO[str] | None = None,
                    delay: float | None = None) -> Iterator[Callable[[int, int], None] | None]:
    """A progress callback drawing on ``stream`` (default stderr) if it is a terminal, else
    None (nothing is ever written to a pipe or a file)."""
    stream = sys.stderr if stream is None else stream
    if not is_terminal(stream):
        yield None
        return
    from rich.console import Console

    if delay is None:
        try:
            delay = float(os.environ.get("SIZER_PROGRESS_DELAY", DELAY))
        except ValueError:
            delay = DELAY

    progress = TerminalProgress(description, Console(file=stream), delay)
    try:
        yield progress
    finally:
        progress.close()
