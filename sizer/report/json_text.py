"""JSON text with fixed conventions: exact floats, no NaN, stable key order, final newline."""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import Any


def render_json(value: Any) -> str:
    """Indented JSON; keys keep their insertion order (callers fix it)."""
    return json.dumps(value, indent=2, allow_nan=False) + "\n"


def render_json_flat_arrays(value: Mapping[str, Any]) -> str:
    """An object with one key per line and each value (arrays too) on that line.

    Long numeric series stay readable and diff line by line per series.
    """
    items = [f"  {json.dumps(key)}: {json.dumps(item, allow_nan=False)}"
             for key, item in value.items()]
    return "{\n" + ",\n".join(items) + "\n}\n"
