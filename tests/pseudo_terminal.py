"""Run a child with a pseudo-terminal as one of its streams and collect what it draws there
(the progress tests: a bar is drawn only on a terminal)."""

from __future__ import annotations

import os
import subprocess
import threading
from collections.abc import Callable


def drawn_on_terminal(run: Callable[[int], subprocess.CompletedProcess[bytes]]
                      ) -> tuple[subprocess.CompletedProcess[bytes], bytes]:
    """``run(fd)`` with ``fd`` the slave end of a new pseudo-terminal; (its result, the bytes
    it wrote there). The master end is read while the child runs: a full pty buffer would
    block it."""
    master, slave = os.openpty()
    chunks: list[bytes] = []

    def drain() -> None:
        while True:
            try:
                chunk = os.read(master, 65536)
            except OSError:
                return
            if not chunk:
                return
            chunks.append(chunk)

    reader = threading.Thread(target=drain, daemon=True)
    reader.start()
    try:
        result = run(slave)
    finally:
        os.close(slave)
        reader.join(timeout=30)
        os.close(master)
    return result, b"".join(chunks)
