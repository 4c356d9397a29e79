"""The plain-document path of the YAML reader gives what the general path gives.

``sizer.io.yaml_source.parse_yaml`` reads a plain document (no anchor, alias, tag or
merge key, no error) straight from libyaml's events; anything else goes the general way
(PyYAML's composer under the counting loader). Here both are run on the same texts: the
repository's YAML files, the texts of the bad-input cases and a list of tricky scalars
and structures; where the plain path answers, its data (types included) and lines equal
the general path's; where the general path refuses a text, the plain path must not
answer.
"""

from __future__ import annotations

import importlib
import math
import sys
from pathlib import Path
from typing import Any

import pytest

from sizer.errors import UserError
from sizer.io import yaml_source

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).parent))

SCALARS = [
    "3000 rpm", "'3000 rpm'", '"x: y"', "1.2e-4 kg*m^2", "12", "-12", "+3", "0x1F",
    "0o17", "017", "0b101", "1_000", "1:30", "1:30.5", "1.5", ".5", "-.inf", ".inf", ".NaN",
    "1e3", "1.0e3", "1.0e+3", "~", "null", "Null", "", "yes", "No", "on", "OFF", "true",
    "False", "y", "n", "2024-02-29", "2024-02-30", "2001-12-14 21:59:43.10 -5",
    "2001-12-14t21:59:43.10-05:00", "2002-12-14", "2024-1-5 1:2:3", "1 2", "a b c",
    "-", "- x", "=", "<< x", "N·m", "é", "1" * 401, "1" * 300, "9" * 320, "1e999",
    "'multi\n  line'", "|\n  block\n  text\n", ">\n  folded\n  text\n",
]

STRUCTURES = [
    "a: 1\nb: [1, 2, {c: 3}]\n",
    "a:\n  - x\n  - y: 1\n    z: [[0 rpm, 1 N*m], [3000 rpm, 1 N*m]]\n",
    "a: {}\nb: []\nc: [[], [[]], {d: {}}]\n",
    "a: 1\na: 2\n",
    "a: {b: 1, b: 2}\n",
    "1: x\ntrue: y\n",
    "1: x\n1.0: y\n",
    "? [a, b]\n: c\n",
    "? {a: 1}\n: c\n",
    "base: &b {x: 1}\nuse: *b\n",
    "a: !!str 12\n",
    "a: !!float 12\n",
    "a: !custom x\n",
    "<<: {x: 1}\ny: 2\n",
    "a: {<<: {x: 1}, y: 2}\n",
    "a: =\n",
    "- a\n- b\n",
    "just text\n",
    "",
    "# only a comment\n",
    "a: 1\n---\nb: 2\n",
    "--- \na: 1\n...\n",
    "a: [1, 2\n",
    "a: 'unterminated\n",
    "a: \"\\x00\"\n",
    "\ta: 1\n",
    "a: b: c\n",
    "a: 1\n  b: 2\n",
    "a:\n" + "".join("  " * (i + 1) + f"k{i}:\n" for i in range(99)) + "  " * 100 + "v: 1\n",
    "a:\n" + "".join("  " * (i + 1) + f"k{i}:\n" for i in range(98)) + "  " * 99 + "v: 1\n",
    "a: " + "[" * 99 + "]" * 99 + "\n",
    "a: " + "[" * 101 + "]" * 101 + "\n",
    "a: " + "x" * 70_000 + "\n",
    "x" * 70_000 + ": 1\n",
    "motors:\n" + "".join(f"  - {{id: m{i}, inertia: {i} kg*cm^2}}\n" for i in range(50)),
]


def _texts() -> list[tuple[str, str]]:
    texts = [(f"scalar {s[:30]!r}", f"a: {s}\nb: [{s}]\n{s}: k\n") for s in SCALARS
             if "\n" not in s]
    texts += [(f"block scalar {s[:10]!r}", f"a: {s}") for s in SCALARS if "\n" in s]
    texts += [(f"structure {i}", s) for i, s in enumerate(STRUCTURES)]
    for path in sorted([*ROOT.glob("examples/**/*.yaml"), *ROOT.glob("sizer/catalogs/*.yaml"),
                        *ROOT.glob("docs/**/*.yaml")]):
        texts.append((str(path.relative_to(ROOT)), path.read_text(encoding="utf-8")))
    for module in ("test_bad_inputs_catalogs", "test_bad_inputs_fields",
                   "test_bad_inputs_inputs", "test_bad_inputs_numbers", "test_bad_inputs_cli"):
        cases = getattr(importlib.import_module(module), "CASES", [])
        for case in cases:
            for name, text in (("design", case.design), ("catalog", case.catalog),
                               *case.extra_files.items()):
                if isinstance(text, str):
                    texts.append((f"{case.id} {name}", text))
    return texts


def _general(text: str, max_nodes: int) -> Any:
    """The general path alone (the plain one switched off)."""
    plain = yaml_source._parse_plain
    yaml_source._parse_plain = lambda *args: None  # type: ignore[assignment]
    try:
        return yaml_source.parse_yaml(text, "f.yaml", max_nodes=max_nodes)
    except UserError as error:
        return error
    finally:
        yaml_source._parse_plain = plain  # type: ignore[assignment]


def _typed(value: Any) -> Any:
    """The value with the type of every part, so that 1 and 1.0 and True differ."""
    if isinstance(value, dict):
        return {_typed_key(k): _typed(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_typed(v) for v in value]
    if isinstance(value, float) and math.isnan(value):
        return ("nan", float)
    return (value, type(value))


def _typed_key(key: Any) -> Any:
    return (key, type(key))


TEXTS = _texts()


@pytest.mark.parametrize("max_nodes", [5_000_000, 60])
def test_plain_path_equals_the_general_path(max_nodes: int) -> None:
    answered = 0
    for label, text in TEXTS:
        general = _general(text, max_nodes)
        plain = yaml_source._parse_plain(text, "f.yaml", max_nodes)
        if plain is None:
            continue
        answered += 1
        assert not isinstance(general, UserError), (label, general)
        assert _typed(plain.data) == _typed(general.data), label
        assert list(plain.data) == list(general.data), label  # key order
        assert plain.lines == general.lines, label
        assert plain.file == general.file
    assert answered >= 40  # the plain path is taken for ordinary files


def test_general_path_for_what_is_not_plain() -> None:
    for text in ("base: &b {x: 1}\nuse: *b\n", "a: !!str 12\n", "<<: {x: 1}\ny: 2\n",
                 "a: 1\na: 2\n", "- a\n", "a: 2024-02-30\n", "a: 1.0e+999\n", "a: [1, 2\n"):
        assert yaml_source._parse_plain(text, "f.yaml", 1000) is None, text
