"""Which kind of input file is this? A machine file has ``axes:``; a design ``task:`` or
``cycle:``. Reads the YAML only (no models), so that a command can choose its path
without importing the loaders it does not need."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from sizer.input_limits import MAX_DESIGN_BYTES, MAX_DESIGN_NODES
from sizer.io.yaml_source import read_yaml


def is_machine_data(data: Any) -> bool:
    """A machine file's content: a mapping with ``axes:``."""
    return isinstance(data, Mapping) and "axes" in data


def is_machine_file(path: str | Path) -> bool:
    """Whether ``path`` holds a machine file (UserError for a file that cannot be read)."""
    source = read_yaml(path, limit=MAX_DESIGN_BYTES, max_nodes=MAX_DESIGN_NODES)
    return is_machine_data(source.data)
