"""Which process sizes which law: the laws of a large design spread over worker processes.

Each law sizes every candidate on its own (sizer.sizing.engine.evaluate_spec), so the
laws are tasks, one law per task, handed to ``workers`` processes as they come free;
the tables come back in the laws' order and the result is the one a single process
gives, bit for bit. The one thing a law takes from another is the option its ratio
search tries first (the choice of the last law finished, sizer.sizing.ratio_choice.
listed_choice), which changes the search's cost, never its answer.

The workers are started clean (``forkserver``, or ``spawn`` where there is none), so
no lock held by another thread of the caller is inherited; like every such pool they
import the caller's main module again, which must keep its work under ``if __name__ ==
"__main__":``. That is why the library sizes in one process unless asked
(``workers``), and the ``sizer`` command, whose entry points are guarded, asks.
"""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING

import numpy as np

from sizer.model.domain import Design
from sizer.sizing.motors import MotorArrays
from sizer.sizing.shared_by_laws import SharedByLaws
from sizer.sizing.table import CandidateTable

if TYPE_CHECKING:
    from concurrent.futures import Future

AUTO_WORK = 500_000
"""Candidate x law evaluations from which ``workers=None`` (auto) uses every CPU: about
five seconds of work in one process, against about half a second to start a worker."""


def usable_cpus() -> int:
    """The CPUs this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


def worker_count(workers: int | None, candidates: int, laws: int) -> int:
    """How many processes size ``laws`` laws of ``candidates`` candidates each: ``workers``
    as given (1: this process), or with None every usable CPU where the work is at least
    AUTO_WORK evaluations; never more than the laws."""
    if workers is None:
        workers = usable_cpus() if candidates * laws >= AUTO_WORK else 1
    return max(1, min(int(workers), laws))


_STATE: dict[str, object] = {}
"""A worker's design and motor arrays, sent once when it starts, and what its laws share."""


def _start(design: Design, motors: MotorArrays) -> None:
    _STATE["design"], _STATE["motors"] = design, motors
    _STATE["shared"] = SharedByLaws(design, motors)


def _size_law(spec: str, first: np.ndarray | None) -> CandidateTable:
    """One law in a worker; the table goes back without its motors (the caller's own
    objects go in again: one copy of the catalog, shared by every table)."""
    from sizer.sizing.engine import evaluate_spec

    design, motors, shared = _STATE["design"], _STATE["motors"], _STATE["shared"]
    assert isinstance(design, Design) and isinstance(motors, MotorArrays)
    assert isinstance(shared, SharedByLaws)
    table = evaluate_spec(design, spec, motors, first, shared)
    return dataclasses.replace(table, motors=())


def tables_in_processes(design: Design, specs: Sequence[str], motors: MotorArrays,
                        workers: int, done: Callable[[int], None] | None = None
                        ) -> list[CandidateTable]:
    """The table of each law spec (sizer.sizing.engine.evaluate_spec), sized in
    ``workers`` processes; ``done(count)`` after each law with the count so far."""
    import multiprocessing  # here: the start-up of a command sized in one process
    from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait

    from sizer.sizing.ratio_choice import listed_choice

    methods = multiprocessing.get_all_start_methods()
    context = multiprocessing.get_context("forkserver" if "forkserver" in methods else "spawn")
    tables: list[CandidateTable | None] = [None] * len(specs)
    hint: np.ndarray | None = None
    with ProcessPoolExecutor(workers, mp_context=context, initializer=_start,
                             initargs=(design, motors)) as pool:
        pending: dict[Future[CandidateTable], int] = {}
        queued = iter(range(len(specs)))

        def submit() -> None:
            k = next(queued, None)
            if k is not None:
                pending[pool.submit(_size_law, specs[k], hint)] = k

        for _ in range(workers):
            submit()
        finished = 0
        try:
            while pending:
                ready, _ = wait(pending, return_when=FIRST_COMPLETED)
                for future in sorted(ready, key=pending.__getitem__):
                    k = pending.pop(future)
                    table = dataclasses.replace(future.result(), motors=motors.catalog)
                    tables[k] = table
                    if design.ratio_choice is not None:
                        hint = listed_choice(design, table)
                    finished += 1
                    if done is not None:
                        done(finished)
                    submit()
        except BaseException:  # a law's error (a UserError) is the sizing's: stop the rest
            for future in pending:
                future.cancel()
            raise
    assert all(t is not None for t in tables)
    return [t for t in tables if t is not None]
