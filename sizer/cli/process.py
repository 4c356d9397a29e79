"""The ``sizer`` process: the collector's setting for a short run, then the app.

A run of the command line creates a few hundred thousand long-lived objects while it
imports its modules and builds the input schema, and few reference cycles after that.
With the interpreter's default thresholds (700, 10, 10) the cyclic collector walks them
about 140 times in a book example, and once more at exit: 30-45 ms of its ~0.5 s of CPU
(issue 34). Here the first threshold is 200,000 allocations (mypy's setting, for the same
reason), and what is left at exit is frozen so that the interpreter's last collection
skips it: the process ends anyway. Memory is still reclaimed at once by reference
counting, cycles at the next collection (a sizing of 100 segments on 64 motors peaks at
the same memory). Only the process started by ``sizer`` / ``python -m sizer`` is set so:
a program or a test calling :func:`sizer.cli.app.main` keeps its own setting.
"""

from __future__ import annotations

import gc
from collections.abc import Sequence

GC_THRESHOLDS = (200_000, 20, 100)
"""gc.set_threshold of a command-line run (the interpreter's default: (700, 10, 10))."""


def main(argv: Sequence[str] | None = None) -> None:
    """The ``sizer`` entry point: the collector's thresholds, then
    :func:`sizer.cli.app.main`; at its exit what is left is frozen."""
    gc.set_threshold(*GC_THRESHOLDS)
    # imported after the setting on purpose (no import circle): its imports are most of
    # the objects the setting spares
    from sizer.cli.app import main as run_app

    try:
        run_app(argv)
    finally:
        gc.freeze()  # the interpreter's collection at exit skips frozen objects
