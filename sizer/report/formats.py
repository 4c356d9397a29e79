"""The output formats a command can produce."""

from __future__ import annotations

from enum import StrEnum


class Format(StrEnum):
    """An output format; ``table`` is rich on a terminal and plain text otherwise."""

    TABLE = "table"
    CSV = "csv"
    MD = "md"
    JSON = "json"
