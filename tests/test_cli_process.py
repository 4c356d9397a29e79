"""The ``sizer`` process's collector setting (sizer.cli.process): made by the command's
entry point only, never by importing or calling the app."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from sizer.cli.process import GC_THRESHOLDS

ROOT = Path(__file__).resolve().parent.parent

SHOW = ("import atexit, gc, sys; atexit.register(lambda: sys.stderr.write("
        "'gc %r %d\\n' % (gc.get_threshold(), gc.get_freeze_count()))); ")


def _collector_at_exit(code: str) -> tuple[tuple[int, ...], int]:
    """The thresholds and the count of frozen objects when the process ends."""
    done = subprocess.run([sys.executable, "-c", SHOW + code], cwd=ROOT, capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    line = [x for x in done.stderr.splitlines() if x.startswith("gc (")][-1]
    inner, frozen = line[len("gc ("):].split(")")
    return tuple(int(x) for x in inner.split(",")), int(frozen)


def test_the_entry_point_raises_the_first_threshold_and_freezes_at_exit() -> None:
    thresholds, frozen = _collector_at_exit(
        "from sizer.cli.process import main; main(['laws'])")
    assert thresholds == GC_THRESHOLDS
    assert GC_THRESHOLDS[0] > 700  # above the interpreter's default
    assert frozen > 10_000  # the modules and schema, skipped by the last collection


def test_the_app_called_from_a_program_keeps_its_setting() -> None:
    thresholds, frozen = _collector_at_exit(
        "import gc; gc.set_threshold(701, 11, 12); "
        "from sizer.cli.app import main; main(['laws'])")
    assert (thresholds, frozen) == ((701, 11, 12), 0)


def test_python_m_sizer_goes_through_the_entry_point() -> None:
    done = subprocess.run([sys.executable, "-c", SHOW + "import runpy, sys; "
                           "sys.argv = ['sizer', 'laws']; "
                           "runpy.run_module('sizer', run_name='__main__')"],
                          cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert f"gc {GC_THRESHOLDS!r}" in done.stderr


def test_the_entry_point_runs_blas_on_one_thread_unless_the_user_chose() -> None:
    from sizer.cli.process import one_blas_thread

    empty: dict[str, str] = {}
    one_blas_thread(empty)
    assert empty == {"OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
    for name in ("OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "OMP_NUM_THREADS",
                 "MKL_NUM_THREADS"):
        chosen = {name: "4"}
        one_blas_thread(chosen)
        assert chosen == {name: "4"}


def _threads_at_exit(code: str, **environ: str) -> tuple[int, str]:
    """The process's thread count at exit (Linux's /proc) and OPENBLAS_NUM_THREADS."""
    show = ("import atexit, os, sys; atexit.register(lambda: sys.stderr.write("
            "'threads %d %s\\n' % (len(os.listdir('/proc/self/task')), "
            "os.environ.get('OPENBLAS_NUM_THREADS')))); ")
    env = {k: v for k, v in os.environ.items() if k not in
           ("OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")}
    done = subprocess.run([sys.executable, "-c", show + code], cwd=ROOT, capture_output=True,
                          text=True, timeout=120, env={**env, **environ})
    assert done.returncode == 0, done.stderr
    line = [x for x in done.stderr.splitlines() if x.startswith("threads ")][-1]
    count, value = line.split()[1:]
    return int(count), value


@pytest.mark.skipif(not Path("/proc/self/task").is_dir(), reason="needs Linux's /proc")
def test_a_sized_design_starts_no_blas_workers() -> None:
    """The book's example sized through the entry point: numpy imported, one thread (the
    wheels' OpenBLAS starts one per core on a machine with several, as a program
    importing numpy shows)."""
    size = ("from sizer.cli.process import main; "
            "main(['size', 'examples/book/ex6_1-6_2.yaml', '--format', 'json'])")
    assert _threads_at_exit(size) == (1, "1")
    assert _threads_at_exit(size, OPENBLAS_NUM_THREADS="2")[1] == "2"  # the user's
