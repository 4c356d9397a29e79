"""Where a bad input's message must point: the line of a field in a YAML text (issue 32).

The line is found by composing the YAML (PyYAML's nodes and their marks), independently of
sizer's own line table: for a mapping key, the line of the key; for a list item, the line
of the item; for a missing key, the line of the deepest key that is there.

    line_of(text, "cycle.segments[2].move.duration") -> 14
    at(text, "cycle.segments[2].move.duration")
        -> ("design.yaml:14:", "cycle.segments[2].move.duration")
"""

from __future__ import annotations

import re

import yaml


def _parts(path: str) -> list[str | int]:
    return [int(i) if i else k for k, i in re.findall(r"([^.\[\]]+)|\[(\d+)\]", path)]


def line_of(text: str, path: str) -> int:
    """The 1-based line of ``path`` (dotted, indices in brackets) in the YAML ``text``."""
    node = yaml.compose(text)
    line = node.start_mark.line + 1
    for part in _parts(path):
        if isinstance(node, yaml.MappingNode):
            found = [(k, v) for k, v in node.value if k.value == str(part)]
            if not found:
                return line
            key, node = found[0]
            line = key.start_mark.line + 1
        elif isinstance(node, yaml.SequenceNode) and isinstance(part, int) \
                and part < len(node.value):
            node = node.value[part]
            line = node.start_mark.line + 1
        else:
            return line
    return line


def at(text: str, path: str, file: str = "design.yaml") -> tuple[str, str]:
    """The words a located message holds: ``file:LINE`` and the field's path."""
    return f"{file}:{line_of(text, path)}:", path
