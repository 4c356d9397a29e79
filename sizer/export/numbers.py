"""Numbers as the writers print them: the shortest text that reads back to the same float,
so that a certificate computed on the table holds for the file."""

from __future__ import annotations

from collections.abc import Iterable


def exact(value: float) -> str:
    """'0.25', '1e-05', '-3.0': Python's shortest round-trip repr of a float."""
    return repr(float(value))


def pairs(master: Iterable[float], slave: Iterable[float], separator: str) -> list[str]:
    """One line 'master<separator>slave' per point."""
    return [f"{exact(x)}{separator}{exact(y)}" for x, y in zip(master, slave, strict=True)]
