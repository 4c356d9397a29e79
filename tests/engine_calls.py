"""Counting the engine's sizings (sizer.sizing.engine.size_design) a call makes: how a
test tells rows of one sizing from a loop of sizings."""

from __future__ import annotations

from collections.abc import Callable
from typing import TypeVar

import sizer.sizing.engine as engine

T = TypeVar("T")


def counted_sizings(monkeypatch, run: Callable[[], T]) -> tuple[T, int]:
    """``run()``'s value and the number of sizings it made."""
    calls: list[int] = []
    sized = engine.size_design

    def counted(*args, **kwargs):
        calls.append(1)
        return sized(*args, **kwargs)

    with monkeypatch.context() as patch:
        patch.setattr(engine, "size_design", counted)
        value = run()
    return value, len(calls)
