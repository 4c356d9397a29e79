"""Progress of one long step (issue 32): a 400-segment cycle sized with one law, or one
axis of a machine, calls back only when it starts and ends; the bar must show all the same
on a terminal (a timer), and never for a quick run."""

from __future__ import annotations

import io
import time

from sizer.cli.progress import sizing_progress


class FakeTerminal(io.StringIO):
    def isatty(self) -> bool:
        return True


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
