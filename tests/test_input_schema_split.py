"""The input schema (pydantic, sizer.io.schema) apart from the SI domain (sizer.model), and
the schema's quantity markers as real types (issue 33). Read with ast where it is about
imports; the markers are checked on a small model of their own."""

from __future__ import annotations

import ast
from pathlib import Path
from typing import Annotated

import pytest
from pydantic import ValidationError

from sizer.io.schema.inputs_base import (
    Ranged,
    RangeRef,
    RawQuantity,
    RawValue,
    Strict,
    axis_range,
    field_markers,
)

PACKAGE = Path(__file__).resolve().parents[1] / "sizer"


def _imports(path: Path) -> set[str]:
    names: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module:
            names.add(node.module)
    return names


@pytest.mark.parametrize("path", sorted((PACKAGE / "model").glob("*.py")), ids=lambda p: p.name)
def test_the_domain_imports_neither_pydantic_nor_the_input_side(path):
    bad = [n for n in _imports(path)
           if n.split(".")[0] in ("pydantic", "pydantic_core") or n.startswith("sizer.io")]
    assert bad == []


class _Sample(Strict):
    duration: Annotated[float, Ranged("duration")]
    load: Annotated[RawValue, RawQuantity("'0.2 N*m' or '10 N'", rotary="load_torque",
                                          linear="load_force")] = 0.0


def test_a_ranged_field_converts_to_si_and_names_its_range():
    assert _Sample(duration="250 ms").duration == 0.25  # 250 ms = 0.25 s
    with pytest.raises(ValidationError, match=r"1e-6, 1e6\] s"):
        _Sample(duration="2e6 s")  # beyond the 1e6 s of RANGES["duration"]


def test_a_raw_quantity_stays_as_written_and_refuses_what_is_not_one():
    assert _Sample(duration=1, load="15 N").load == "15 N"
    with pytest.raises(ValidationError, match=r"expected a number or a quantity like "
                                              r"'0.2 N\*m' or '10 N', got True"):
        _Sample(duration=1, load=True)


def test_the_markers_name_their_ranges():
    assert [m.name for m in field_markers(_Sample, "duration")
            if isinstance(m, RangeRef)] == ["duration"]
    assert axis_range(_Sample, "load", linear=False) == "load_torque"
    assert axis_range(_Sample, "load", linear=True) == "load_force"
