"""``sizer schema design|catalog``: the JSON Schemas of the input files."""

from __future__ import annotations

import io
import json
import subprocess
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

import pytest


def run(*args: str) -> subprocess.CompletedProcess[str]:
    """``sizer ARGS`` in this process: exit code, stdout and stderr."""
    from sizer.cli.app import main

    stdout, stderr = io.StringIO(), io.StringIO()
    code = 0
    with redirect_stdout(stdout), redirect_stderr(stderr):
        try:
            main(list(args))
        except SystemExit as exit_:
            code = exit_.code if isinstance(exit_.code, int) else int(exit_.code is not None)
    return subprocess.CompletedProcess(args, code, stdout.getvalue(), stderr.getvalue())


@pytest.mark.parametrize(("which", "fields"), [
    ("design", {"task", "load", "transmission", "laws", "motors", "check", "limits"}),
    ("catalog", {"catalog", "motors"}),
])
def test_schema_is_json_with_the_file_fields(which: str, fields: set[str]) -> None:
    from sizer.io import catalog_schema, design_schema

    result = run("schema", which)
    assert result.returncode == 0, result.stderr
    schema = json.loads(result.stdout)
    assert fields <= set(schema["properties"])
    assert schema == (design_schema() if which == "design" else catalog_schema())
    assert result.stdout.endswith("}\n") and run("schema", which).stdout == result.stdout


def test_schema_to_a_file(tmp_path: Path) -> None:
    target = tmp_path / "design.schema.json"
    assert run("schema", "design", "--output", str(target)).stdout == ""
    assert "task" in json.loads(target.read_text())["properties"]


def test_unknown_schema_is_a_usage_error() -> None:
    result = run("schema", "motor")
    assert result.returncode == 2 and "Traceback" not in result.stderr
