"""The ``sizer`` process: the collector's setting for a short run, then the app.

A run of the command line creates a few hundred thousand long-lived objects while it
imports its modules and builds the input schema, and few reference cycles after that.
With the interpreter's default thresholds (700, 10, 10) the cyclic collector walks them
about 140 times in a book example, and once more at exit: 30-45 ms of its ~0.5 s of CPU
(issue 34). Here the first threshold is 200,000 allocations (mypy's setting, for the same
reason), and what is left at exit is frozen so that the interpreter's last collection
skips it: the process ends anyway. Memory is still reclaimed at once by reference
counting, cycles at the next collection (a sizing of 100 segments on 64 motors peaks at
the same memory).

The process also runs numpy's BLAS on one thread unless the user chose a count
(OPENBLAS_NUM_THREADS, GOTO_NUM_THREADS, OMP_NUM_THREADS or MKL_NUM_THREADS set): the
wheels' OpenBLAS starts a worker per core when numpy is imported, and after each call a
worker spins for its timeout (~0.1 s) before sleeping. sizer's matrix products are small
(a law's polynomial pieces, a spline's system, a modal state), so the workers only spin:
40-60 ms of CPU in a book example's run, none of its wall time saved (10,000 motors x 20
laws: 15.7 s wall on one thread against 16.2 s on two). Worker processes (``--workers``)
inherit the setting, so they do not multiply the pools.

Only the process started by ``sizer`` / ``python -m sizer`` is set so: a program or a
test calling :func:`sizer.cli.app.main` keeps its own settings.
"""

from __future__ import annotations

import gc
import os
from collections.abc import MutableMapping, Sequence

GC_THRESHOLDS = (200_000, 20, 100)
"""gc.set_threshold of a command-line run (the interpreter's default: (700, 10, 10))."""
THREAD_SETTINGS = ("OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "OMP_NUM_THREADS",
                   "MKL_NUM_THREADS")
"""The variables by which a user sets the BLAS threads (OpenBLAS reads the first three in
this order, MKL the last and OMP_NUM_THREADS): any of them set, sizer sets none."""


def one_blas_thread(environ: MutableMapping[str, str]) -> None:
    """One BLAS thread (OpenBLAS and MKL) unless ``environ`` already sets a count; read
    when numpy is first imported, so set before."""
    if not any(name in environ for name in THREAD_SETTINGS):
        environ["OPENBLAS_NUM_THREADS"] = environ["MKL_NUM_THREADS"] = "1"


def main(argv: Sequence[str] | None = None) -> None:
    """The ``sizer`` entry point: the collector's thresholds and one BLAS thread, then
    :func:`sizer.cli.app.main`; at its exit what is left is frozen."""
    gc.set_threshold(*GC_THRESHOLDS)
    one_blas_thread(os.environ)
    # imported after the setting on purpose (no import circle): its imports are most of
    # the objects the setting spares
    from sizer.cli.app import main as run_app

    try:
        run_app(argv)
    finally:
        gc.freeze()  # the interpreter's collection at exit skips frozen objects
