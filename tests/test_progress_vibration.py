"""Progress with an estimate (issue 36: ``sizer vibration`` ran 52 s with the bar stuck):
the sweep calls back in steps and gives the one-run numbers exactly; the bar shows the
steps and rich's time remaining on a terminal, and nothing at all reaches a pipe."""

from __future__ import annotations

import io
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from sizer.cli.progress import sizing_progress
from tests.pseudo_terminal import drawn_on_terminal

ROOT = Path(__file__).resolve().parent.parent
DESIGN = ROOT / "examples" / "indexing-table-vibration.yaml"
BAR = ("━", "\x1b", "\r", " eta ", " steps ", " laws ", "sweeping", "sizing for")


class FakeTerminal(io.StringIO):
    def isatty(self) -> bool:
        return True


@pytest.fixture(scope="module")
def design():
    from sizer.io import load_design

    return load_design(DESIGN, default_motors=True)


@pytest.mark.parametrize("points, chunks", [(201, 16), (7, 16), (50, 3)])
def test_the_stepped_sweep_is_the_one_run_sweep(design, points: int, chunks: int) -> None:
    from sizer.sizing.vibration_check import vibration_sweep

    laws = tuple(s.law for s in design.laws if not s.open_shaped and not s.auto)
    scales = np.linspace(0.05, 0.5, points)
    calls: list[tuple[int, int]] = []
    stepped = vibration_sweep(design, laws, scales, lambda d, t: calls.append((d, t)), chunks)
    whole = vibration_sweep(design, laws, scales)
    steps = len(laws) * min(chunks, points)
    assert calls == [(i, steps) for i in range(steps + 1)]  # every step, in order
    assert np.array_equal(stepped.scales, whole.scales) and stepped.laws == whole.laws
    assert stepped.limit == whole.limit
    for a, b in zip(stepped.residual, whole.residual, strict=True):
        np.testing.assert_allclose(a, b, rtol=1e-13, atol=0.0)
    assert (stepped.tracking is None) == (whole.tracking is None)
    for a, b in zip(stepped.tracking or (), whole.tracking or (), strict=True):
        np.testing.assert_allclose(a, b, rtol=1e-13, atol=0.0)
    quiet = vibration_sweep(design, laws, scales, None, chunks)  # a pipe: the same numbers
    for a, b in zip(stepped.residual, quiet.residual, strict=True):
        assert np.array_equal(a, b)


def test_the_bar_shows_the_unit_and_an_estimate() -> None:
    stream = FakeTerminal()
    with sizing_progress("sweeping x.yaml", stream=stream, delay=0.0, unit="steps") as progress:
        assert progress is not None
        progress(0, 10)
        progress(4, 10)
    text = stream.getvalue()
    assert "sweeping x.yaml" in text and "steps" in text and "eta" in text


def run(args: list[str], stderr: int) -> subprocess.CompletedProcess:
    env = {**os.environ, "SIZER_PROGRESS_DELAY": "0", "COLUMNS": "100"}
    return subprocess.run([sys.executable, "-m", "sizer", *args], cwd=ROOT,
                          stdout=subprocess.PIPE, stderr=stderr, env=env, timeout=300)


def test_piped_vibration_has_no_progress_characters() -> None:
    result = run(["vibration", str(DESIGN), "--points", "40"], subprocess.PIPE)
    assert result.returncode == 0
    assert result.stderr == b""
    out = result.stdout.decode()
    assert not any(mark in out for mark in BAR)


@pytest.mark.skipif(not hasattr(os, "openpty"), reason="needs a pseudo-terminal")
def test_a_terminal_shows_the_sweep_with_an_estimate() -> None:
    args = ["vibration", str(DESIGN), "--points", "400"]
    result, raw = drawn_on_terminal(lambda fd: run(args, fd))
    drawn = raw.decode(errors="replace")
    assert result.returncode == 0
    assert "sweeping indexing-table-vibration.yaml" in drawn
    assert "steps" in drawn and "eta" in drawn
    assert b"\x1b" not in result.stdout and b"sweeping" not in result.stdout
