"""The JSON schema of a law entry: a spec text, or a mapping for a law defined by data."""

from __future__ import annotations

from typing import Any

from sizer.laws.data_spec import DATA_LAW_KINDS


def _data_law_schema() -> dict[str, Any]:
    return {"type": "object", "required": ["kind"],
            "properties": {"kind": {"enum": list(DATA_LAW_KINDS)},
                           "units": {"type": "object",
                                     "properties": {"time": {"type": "string"},
                                                    "position": {"type": "string"}},
                                     "additionalProperties": False}},
            "description": "a law defined by data (docs/data-laws.md), e.g. {kind: "
                           "cubic_spline, points: [[0, 0], [0.4, 0.3], [1, 1]]}"}


LAW_SPEC_SCHEMA: dict[str, Any] = {"anyOf": [
    {"type": "string",
     "description": "a motion law spec like 'cycloidal', 'poly5', "
                    "'trapezoidal(alpha=1/3)' or 'double_s(alpha=auto, beta=1/4)'"},
    _data_law_schema()]}

