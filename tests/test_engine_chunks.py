"""Candidates evaluated in chunks (bounded memory) give the same table as all at once."""

from __future__ import annotations

from pathlib import Path

import sizer
from sizer.laws import make_law
from sizer.sizing import engine

ROOT = Path(__file__).resolve().parents[1]


def test_chunks_change_nothing(monkeypatch):
    design = sizer.load(ROOT / "examples" / "vendor-ballscrew.yaml")  # friction: the grid path
    whole = sizer.size(design).to_records()
    monkeypatch.setattr(engine, "CHUNK_SAMPLES", 1)
    monkeypatch.setattr(engine, "MIN_CHUNK", 2)  # 2 candidates a chunk
    assert engine.chunk_size(make_law(design.laws[0])) == 2
    chunked = sizer.size(design).to_records()
    assert len(design.motors) > 4
    assert chunked == whole
