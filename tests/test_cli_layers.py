"""The CLI's layers (issue 33): the commands share sizer.cli.reporting and options, and
never import the app that assembles them."""

from __future__ import annotations

import ast
import io
import math
from contextlib import redirect_stderr
from pathlib import Path

import pytest

from sizer.cli import reporting
from sizer.cli.options import scaled_move
from sizer.errors import UserError

CLI = Path(__file__).resolve().parents[1] / "sizer" / "cli"


def _imported(path: Path) -> set[str]:
    """Every module ``path`` imports, at the top or inside a function."""
    names: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module:
            names.add(node.module)
            names.update(f"{node.module}.{alias.name}" for alias in node.names)
    return names


@pytest.mark.parametrize("path", sorted(p for p in CLI.glob("*.py")
                                        # the app, and the process entry point that runs it
                                        if p.name not in ("app.py", "process.py")),
                         ids=lambda p: p.name)
def test_no_cli_module_imports_the_app(path: Path) -> None:
    assert "sizer.cli.app" not in _imported(path)


def test_warnings_are_one_line_each() -> None:
    err = io.StringIO()
    with redirect_stderr(err):
        reporting.report_warnings(["a\n  b", "c"])
    assert err.getvalue() == "warning: a b\nwarning: c\n"


def test_a_user_error_is_one_line() -> None:
    err = io.StringIO()
    with redirect_stderr(err):
        reporting.report_user_error(UserError("bad\nvalue", file="d.yaml", line=3))
    assert err.getvalue().count("\n") == 1 and err.getvalue().startswith("error: d.yaml:3")


def test_debug_is_off_unless_asked(monkeypatch) -> None:
    monkeypatch.delenv("SIZER_DEBUG", raising=False)
    reporting.set_debug(False)
    assert not reporting.debug_enabled()
    reporting.set_debug(True)
    assert reporting.debug_enabled()
    reporting.set_debug(False)


def test_scaled_move_reads_both_options() -> None:
    h, T, linear = scaled_move("90 deg", "0.2 s", "normalized laws") or (0.0, 0.0, True)
    assert h == pytest.approx(math.pi / 2, rel=1e-15) and T == 0.2 and not linear
    assert scaled_move("200 mm", "1", "x") == pytest.approx((0.2, 1.0, True))
    assert scaled_move(None, None, "x") is None


@pytest.mark.parametrize("displacement,duration,field", [
    ("1", None, "--duration"), (None, "1", "--displacement"),
    ("0", "1", "--displacement"), ("1", "0", "--duration"), ("1", "-2 s", "--duration")])
def test_scaled_move_names_the_option_at_fault(displacement, duration, field) -> None:
    with pytest.raises(UserError) as caught:
        scaled_move(displacement, duration, "x")
    assert caught.value.field == field
