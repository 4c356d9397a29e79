"""Progress of long runs: a plain callback in the core, a rich bar on a terminal only."""

from __future__ import annotations

import io
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

from sizer.cli.progress import TerminalProgress, sizing_progress
from tests.pseudo_terminal import drawn_on_terminal

ROOT = Path(__file__).resolve().parent.parent
DESIGN = ROOT / "examples" / "book" / "ex6_4.yaml"  # quick: minimize over two laws


@pytest.mark.parametrize("axis", [True, False])
def test_size_design_calls_back_as_the_laws_are_sized_and_gives_the_same_results(
        axis: bool, monkeypatch) -> None:
    """(0, n), then (n, n) where the laws are sized together as one axis, else after each
    law."""
    from sizer.io import load_design
    from sizer.sizing import engine, size_design

    if not axis:
        monkeypatch.setattr(engine, "law_axis", lambda *args: None)
    design = load_design(DESIGN)
    calls: list[tuple[int, int]] = []
    with_progress = size_design(design, progress=lambda done, total: calls.append((done, total)))
    n = len(design.laws)
    assert calls == ([(0, n), (n, n)] if axis else [(i, n) for i in range(n + 1)])
    assert with_progress == size_design(design)


class FakeTerminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_no_callback_unless_the_stream_is_a_terminal() -> None:
    with sizing_progress("sizing", stream=io.StringIO(), delay=0.0) as progress:
        assert progress is None
    stream = FakeTerminal()
    with sizing_progress("sizing x.yaml", stream=stream, delay=0.0) as progress:
        assert isinstance(progress, TerminalProgress)
        progress(0, 4)
        progress(2, 4)
    assert "sizing x.yaml" in stream.getvalue()


def test_quick_runs_draw_nothing() -> None:
    stream = FakeTerminal()
    with sizing_progress("sizing", stream=stream, delay=60.0) as progress:
        assert progress is not None
        progress(0, 3)
        progress(3, 3)
    assert stream.getvalue() == ""


def run_sizer(stdout: int, stderr: int) -> subprocess.CompletedProcess:
    env = {**os.environ, "SIZER_PROGRESS_DELAY": "0", "COLUMNS": "100"}
    return subprocess.run([sys.executable, "-m", "sizer", "size", str(DESIGN), "--top", "3"],
                          cwd=ROOT, stdout=stdout, stderr=stderr, env=env, timeout=120)


def test_piped_output_has_no_progress_text() -> None:
    result = run_sizer(subprocess.PIPE, subprocess.PIPE)
    assert result.returncode == 0
    assert result.stderr == b""
    out = result.stdout.decode()
    assert "\x1b" not in out and "sizing ex6_4" not in out
    assert out.startswith("B&M Example 6.4:")


@pytest.mark.skipif(not hasattr(os, "openpty"), reason="needs a pseudo-terminal")
def test_a_terminal_on_stderr_shows_the_bar_and_stdout_stays_clean() -> None:
    result, raw = drawn_on_terminal(lambda fd: run_sizer(subprocess.PIPE, fd))
    drawn = raw
    assert result.returncode == 0
    assert b"sizing ex6_4.yaml" in drawn
    assert b"sizing" not in result.stdout and b"\x1b" not in result.stdout


# one long step (issue 32): a 400-segment cycle sized with one law, or one axis of a
# machine, calls back only when it starts and ends; the bar shows all the same (a timer)

def test_one_long_step_shows_the_bar_without_a_callback() -> None:
    """A single long step (one law of a 400-segment cycle, one axis of a machine) calls
    back only at its start and end: the bar appears after the delay all the same."""
    stream = FakeTerminal()
    with sizing_progress("sizing long.yaml", stream=stream, delay=0.05) as progress:
        assert progress is not None
        progress(0, 1)
        deadline = time.monotonic() + 5.0
        while "sizing long.yaml" not in stream.getvalue() and time.monotonic() < deadline:
            time.sleep(0.02)
        assert "sizing long.yaml" in stream.getvalue()
        progress(1, 1)


def test_a_quick_run_never_draws_from_the_timer() -> None:
    stream = FakeTerminal()
    with sizing_progress("sizing", stream=stream, delay=0.2) as progress:
        assert progress is not None
        progress(0, 2)
        progress(2, 2)
    time.sleep(0.4)  # the timer was cancelled when the run ended
    assert stream.getvalue() == ""
