"""A finding of the catalog validator: where (file, line, field), what, and how serious."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

Severity = Literal["error", "warning"]


@dataclass(frozen=True)
class Finding:
    """One problem in a catalog file. Warnings (a likely mistake) count as findings too."""

    file: str
    line: int | None
    field: str | None
    message: str
    severity: Severity = "error"

    def __str__(self) -> str:
        """``file:line: field: message``, with ``(warning)`` after a warning's message."""
        where = self.file + (f":{self.line}" if self.line is not None else "")
        field = f" {self.field}:" if self.field else ""
        tail = " (warning)" if self.severity == "warning" else ""
        return f"{where}:{field} {self.message}{tail}"

    def sort_key(self) -> tuple[str, int, str]:
        return (self.file, self.line if self.line is not None else 0, self.field or "")
