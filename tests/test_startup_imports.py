"""What start-up imports (issue 11): nothing heavy before a command needs it.

Each check runs in a fresh interpreter and reads ``sys.modules`` afterwards (no timing:
the times are benchmarks/bench_startup.py's). ``import sizer.cli.app`` and ``sizer
--help`` import no numerical, unit, file-format or plotting library and no rich; sizing a
book example (units the fast table knows) never imports pint or matplotlib.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

HEAVY = ("scipy", "matplotlib", "pint", "numpy", "yaml", "pydantic", "rich", "markdown_it",
         "sizer.sizing", "sizer.laws", "sizer.model", "sizer.io", "sizer.units")


def _modules_after(code: str) -> tuple[list[str], subprocess.CompletedProcess[str]]:
    """The modules loaded after ``code`` in a fresh interpreter (printed as JSON last)."""
    script = (f"{code}\nimport json, sys\n"
              "sys.stdout.write('\\n' + json.dumps(sorted(sys.modules)) + '\\n')\n")
    environment = {**os.environ, "PYTHONPATH": str(ROOT)}
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                            timeout=120, cwd=ROOT, env=environment)
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout.strip().splitlines()[-1]), result


def _heavy(modules: list[str], names: tuple[str, ...] = HEAVY) -> list[str]:
    return [m for m in modules if any(m == n or m.startswith(n + ".") for n in names)]


def test_importing_the_app_imports_nothing_heavy() -> None:
    modules, _ = _modules_after("import sizer.cli.app")
    assert "sizer.cli.app" in modules and "typer" in modules
    assert _heavy(modules) == []


CAPTURED = ("import contextlib, io\n"
            "from sizer.cli.app import run\n"
            "out = io.StringIO()\n"
            "with contextlib.redirect_stdout(out):\n"
            "    code = run({args!r})\n"
            "assert code == {code}, code\n"
            "assert {words!r} in out.getvalue(), out.getvalue()\n")


@pytest.mark.parametrize("args,code,words", [
    (["--help"], 0, "Commands:"),
    ([], 2, "Usage: sizer"),  # no command: the help, on stdout, and exit code 2
    (["catalog"], 2, "Usage: sizer catalog"),
    (["laws", "--help"], 0, "Usage: sizer laws"),
    (["size", "--help"], 0, "--rank-by"),
])
def test_help_imports_nothing_heavy(args: list[str], code: int, words: str) -> None:
    modules, _ = _modules_after(CAPTURED.format(args=args, code=code, words=words))
    assert _heavy(modules) == []


def test_help_keeps_every_command_summary_whole() -> None:
    """The command list shows each command's first paragraph, not a cut one."""
    environment = {**os.environ, "PYTHONPATH": str(ROOT), "COLUMNS": "200"}
    result = subprocess.run([sys.executable, "-m", "sizer", "--help"], capture_output=True,
                            text=True, timeout=120, cwd=ROOT, env=environment)
    assert result.returncode == 0
    text = " ".join(result.stdout.split())
    assert "..." not in text.split("Commands:")[1]
    assert "Check the motor and law each design names (`check: {motor: ID, law: SPEC}`)." \
        in text
    assert "Exit codes: 0 ok" in text and "sizer law cycloidal --displacement" in text


def test_sizing_a_book_example_needs_neither_pint_nor_matplotlib() -> None:
    modules, _ = _modules_after(CAPTURED.format(
        args=["size", "examples/book/ex6_1-6_2.yaml"], code=0, words="ex6_1"))
    # numpy.ma: numpy 2's plain np.unique imports it (60 ms); sizer.numerics.arrays
    assert _heavy(modules, ("pint", "matplotlib", "rich.markdown", "markdown_it",
                            "numpy.ma")) == []
    assert "sizer.sizing" in modules and "yaml" in modules  # it did size the design


def test_a_unit_outside_the_table_still_works_through_pint() -> None:
    modules, result = _modules_after(
        "from sizer.units import to_si\n"
        "print(repr(to_si('12.5 oz*in', 'torque')))\n")
    assert "pint" in modules
    assert float(result.stdout.split()[0]) == pytest.approx(12.5 * 0.00706155181640625)
