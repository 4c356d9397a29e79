"""A rich progress bar for long sizing runs, on a terminal only (never in a pipe or a file).

The core stays pure: ``size_design`` takes a plain ``progress(done, total)`` callback; this
module makes one that draws a transient bar on stderr, and only when stderr is a terminal.
The bar appears once a run has taken ``DELAY`` seconds, so quick runs print nothing; a
timer shows it then even while one long step (a law of a 400-segment cycle, an axis of a
machine) has not called back yet, and its spinner and elapsed time keep moving: a long run
is never silent on a terminal. The bar counts its steps in ``unit`` ('laws', 'steps') and
shows rich's estimate of the time remaining from the steps done so far.
"""

from __future__ import annotations

import os
import sys
import threading
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
    """A ``progress(done, total)`` callback drawing a rich bar on ``console`` after DELAY
    (by a timer: also while no callback comes)."""

    def __init__(self, description: str, console: Any, delay: float = DELAY,
                 unit: str = "") -> None:
        self.description = description
        self.unit = unit
        self.console = console
        self.delay = delay
        self.started = time.monotonic()
        self._bar: Any = None
        self._task: Any = None
        self._state: tuple[int, int] | None = None
        self._lock = threading.Lock()
        self._closed = False
        self._timer: threading.Timer | None = None

    def __call__(self, done: int, total: int) -> None:
        with self._lock:
            self._state = (done, total)
            if self._bar is None:
                if done >= total or self._closed:
                    return
                if time.monotonic() - self.started < self.delay:
                    self._arm()
                    return
                self._start()
            self._bar.update(self._task, completed=done, total=total)

    def _arm(self) -> None:
        """Start the bar when DELAY has passed, whether or not a callback comes."""
        if self._timer is None:
            wait = max(0.0, self.delay - (time.monotonic() - self.started))
            self._timer = threading.Timer(wait, self._on_time)
            self._timer.daemon = True
            self._timer.start()

    def _on_time(self) -> None:
        with self._lock:
            if self._bar is None and not self._closed and self._state is not None \
                    and self._state[0] < self._state[1]:
                self._start()

    def _start(self) -> None:
        from rich.progress import (
            BarColumn,
            MofNCompleteColumn,
            Progress,
            SpinnerColumn,
            TextColumn,
            TimeElapsedColumn,
            TimeRemainingColumn,
        )

        done, total = self._state if self._state is not None else (0, 1)
        unit = (TextColumn(self.unit),) if self.unit else ()
        self._bar = Progress(SpinnerColumn(), TextColumn("{task.description}"), BarColumn(),
                             MofNCompleteColumn(), *unit, TimeElapsedColumn(),
                             TextColumn("eta"), TimeRemainingColumn(),
                             console=self.console, transient=True)
        self._bar.start()
        self._task = self._bar.add_task(self.description, total=total, completed=done)

    def close(self) -> None:
        with self._lock:
            self._closed = True
            if self._timer is not None:
                self._timer.cancel()
            if self._bar is not None:
                self._bar.stop()
                self._bar = None


@contextmanager
def sizing_progress(description: str, stream: IO[str] | None = None,
                    delay: float | None = None, unit: str = ""
                    ) -> Iterator[Callable[[int, int], None] | None]:
    """A progress callback drawing on ``stream`` (default stderr) if it is a terminal, else
    None (nothing is ever written to a pipe or a file); ``unit`` names what it counts."""
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

    progress = TerminalProgress(description, Console(file=stream), delay, unit)
    try:
        yield progress
    finally:
        progress.close()
