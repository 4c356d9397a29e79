"""A shaped law left open: ``{kind: shaped, law: ..., shaper: ...}`` without ``f_T``.

In a design whose load gives its mode (``load.natural_frequency``), such a law is shaped
for that mode at each move's own duration (sizer.sizing.shaped_sizing): its f_T = f_n T
is known only once T is. This module only tells the open spec apart (no scipy, no law
built).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any


def is_open_shaped(fields: Mapping[str, Any] | str) -> bool:
    """True for the fields (or the canonical text) of a shaped law without ``f_T``."""
    if isinstance(fields, str):
        from sizer.laws.data_spec import is_data_spec, read_data_spec

        if not is_data_spec(fields):
            return False
        fields = read_data_spec(fields)
    return fields.get("kind") == "shaped" and fields.get("f_T") is None
