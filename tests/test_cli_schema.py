"""``sizer schema design|catalog``: the JSON Schemas of the input files."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from cli_run import run_cli as run


@pytest.mark.parametrize(("which", "fields"), [
    ("design", {"task", "load", "transmission", "laws", "motors", "check", "limits"}),
    ("catalog", {"catalog", "motors"}),
    ("gearboxes", {"catalog", "gearboxes"}),
])
def test_schema_is_json_with_the_file_fields(which: str, fields: set[str]) -> None:
    from sizer.io.loader import catalog_schema, design_schema, gearbox_catalog_schema

    result = run("schema", which)
    assert result.returncode == 0, result.stderr
    schema = json.loads(result.stdout)
    assert fields <= set(schema["properties"])
    expected = {"design": design_schema, "catalog": catalog_schema,
                "gearboxes": gearbox_catalog_schema}[which]()
    assert schema == expected and schema["$id"].endswith(f":{which}:1")
    assert result.stdout.endswith("}\n") and run("schema", which).stdout == result.stdout


def test_schema_to_a_file(tmp_path: Path) -> None:
    target = tmp_path / "design.schema.json"
    assert run("schema", "design", "--output", str(target)).stdout == ""
    assert "task" in json.loads(target.read_text())["properties"]


def test_unknown_schema_is_a_usage_error() -> None:
    result = run("schema", "motor")
    assert result.returncode == 2 and "Traceback" not in result.stderr
