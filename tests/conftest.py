"""Shared by every test module: sizer's click command tree, built once a test process.

typer builds the click commands from the functions' annotations on every call of
``typer.main.get_command`` (about 30 ms for sizer's commands), and ``sizer.cli.app.run``
asks for it on every run: the tests run the CLI in their own process a few thousand times
(tests/cli_run.py), so building the tree was a large part of the suite's time. The tree
depends only on the commands registered when ``sizer.cli.app`` is imported; the first one
built serves every run of this process. Any other typer app is built as before, and a real
process (``python -m sizer``) builds its own.
"""

from __future__ import annotations

from typing import Any

import typer
import typer.main

_build = typer.main.get_command
_built: dict[int, Any] = {}


def _sizer_command_once(typer_instance: typer.Typer) -> Any:
    from sizer.cli.app import app

    if typer_instance is not app:
        return _build(typer_instance)
    if id(app) not in _built:
        _built[id(app)] = _build(app)
    return _built[id(app)]


typer.main.get_command = _sizer_command_once
