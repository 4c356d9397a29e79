"""The output formats a command can produce, and the dispatch of a document to them."""

from __future__ import annotations

from enum import StrEnum


class Format(StrEnum):
    """An output format; ``table`` is rich on a terminal and plain text otherwise."""

    TABLE = "table"
    CSV = "csv"
    MD = "md"
    JSON = "json"


class Rendered:
    """A document that renders to every format: ``csv()``, ``json()``, ``markdown()`` and
    ``plain_text()`` (the table format's text off a terminal)."""

    def csv(self) -> str:
        raise NotImplementedError

    def json(self) -> str:
        raise NotImplementedError

    def markdown(self) -> str:
        raise NotImplementedError

    def plain_text(self) -> str:
        raise NotImplementedError

    def render(self, fmt: Format) -> str:
        if fmt is Format.CSV:
            return self.csv()
        if fmt is Format.JSON:
            return self.json()
        if fmt is Format.MD:
            return self.markdown()
        return self.plain_text()
