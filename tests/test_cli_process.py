"""The ``sizer`` process's collector setting (sizer.cli.process): made by the command's
entry point only, never by importing or calling the app."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

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
