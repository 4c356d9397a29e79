"""The environment for timing sizer in child processes as an installed sizer runs.

An installed package has its bytecode (pip compiles it); a host that sets
PYTHONDONTWRITEBYTECODE (this development machine does) would otherwise make every timed
run compile each of sizer's modules again (about 0.1 s). The children write and read
their bytecode in a private cache (PYTHONPYCACHEPREFIX, a temporary folder, so the tree
is not touched); the caller fills it with one untimed run of each command.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager


@contextmanager
def bytecode_env() -> Iterator[dict[str, str]]:
    """os.environ with bytecode written and read in a private cache, removed on exit."""
    with tempfile.TemporaryDirectory(prefix="sizer-bench-pyc-") as cache:
        env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
        env["PYTHONPYCACHEPREFIX"] = cache
        yield env
