"""A run of one command builds the root with that command alone (issue 34: start-up); its
help and its parsing are those of the whole tree."""

from __future__ import annotations

import io
from contextlib import redirect_stdout
from typing import Any

import pytest
from typer import Exit

from sizer.cli import app as app_module

NAMES = [c.name for c in app_module.app.registered_commands] + \
    [g.name for g in app_module.app.registered_groups]


def _help(tree: Any, args: list[str]) -> str:
    out = io.StringIO()
    with redirect_stdout(out), pytest.raises(Exit), tree.make_context("sizer", args) as context:
        tree.invoke(context)
    return out.getvalue()


@pytest.mark.parametrize("name", NAMES)
def test_a_command_alone_has_the_help_of_the_whole_tree(name: str) -> None:
    whole = _help(app_module._command(), [name, "--help"])
    assert "Usage: sizer " + name in whole
    assert _help(app_module._command(name), [name, "--help"]) == whole


def test_catalog_subcommands_alone_have_the_help_of_the_whole_tree() -> None:
    for sub in ("list", "show", "validate", "import"):
        args = ["catalog", sub, "--help"]
        assert _help(app_module._command("catalog"), args) == \
            _help(app_module._command(), args)


@pytest.mark.parametrize("args,name", [
    (["size", "design.yaml"], "size"),
    (["--debug", "check", "design.yaml"], "check"),
    (["catalog", "list"], "catalog"),
    (["plot-law", "cycloidal"], "plot-law"),
    ([], None),  # the group's help
    (["--debug"], None),
    (["--help", "size"], None),  # the root's help lists every command
    (["--version"], None),
    (["nosuch"], None),  # click's 'No such command' against the whole list
])
def test_the_invoked_command(args: list[str], name: str | None) -> None:
    assert app_module._invoked(args) == name
