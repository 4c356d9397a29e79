"""Catalog YAML text, written the same way every time (key order fixed, no timestamps).

Values are written as given (texts with their units, like '0.637 N*m'), quoted only where
YAML needs it, so the file keeps the datasheet's figures and reads back to the same texts.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import yaml

TOP_KEYS = ("catalog", "manufacturer", "source", "notes")
"""Catalog-level keys, in the order they are written (before ``motors``)."""


def scalar(text: str) -> str:
    """``text`` as a one-line YAML scalar that loads back as exactly this string."""
    style = '"' if any(c in text for c in "\n\r\t") else None
    dumped = yaml.safe_dump(text, allow_unicode=True, width=1_000_000, default_style=style)
    if dumped.endswith("\n...\n"):
        dumped = dumped[: -len("\n...\n")]
    return dumped.rstrip("\n")


def comment(lines: Sequence[str]) -> str:
    """Comment lines (``# ...``); line breaks inside a line become spaces."""
    out = []
    for line in lines:
        text = " ".join(line.splitlines()).rstrip()
        out.append(f"# {text}".rstrip() + "\n")
    return "".join(out)


def render_catalog(header: Mapping[str, str | None], motors: Sequence[Mapping[str, str]],
                   comments: Sequence[str] = ()) -> str:
    """A catalog file: comments, the catalog-level keys of ``header`` that are set, motors.

    Motor fields are written in the order of each mapping.
    """
    parts = [comment(comments)]
    for key in TOP_KEYS:
        value = header.get(key)
        if value is not None:
            parts.append(f"{key}: {scalar(value)}\n")
    parts.append("motors:\n")
    for motor in motors:
        first = True
        for key, value in motor.items():
            lead = "  - " if first else "    "
            parts.append(f"{lead}{key}: {scalar(value)}\n")
            first = False
    return "".join(parts)
