"""Candidates evaluated in chunks (bounded memory) give the same table as all at once."""

from __future__ import annotations

from pathlib import Path

import sizer
from sizer.laws import make_law
from sizer.sizing import engine
from sizer.sizing import move as chunks  # the chunk sizes' module

ROOT = Path(__file__).resolve().parents[1]


def test_chunks_change_nothing(monkeypatch):
    design = sizer.load(ROOT / "examples" / "vendor-ballscrew.yaml")  # friction: the grid path
    whole = sizer.size(design).to_records()
    monkeypatch.setattr(chunks, "CHUNK_SAMPLES", 1)
    monkeypatch.setattr(chunks, "MIN_CHUNK", 2)  # 2 candidates a chunk
    assert engine.chunk_size(make_law(design.laws[0])) == 2
    chunked = sizer.size(design).to_records()
    assert len(design.motors) > 4
    assert chunked == whole


def test_a_chunk_of_candidates_never_holds_more_than_the_sample_cap():
    # issue 32: a 400-move linkage cycle took MIN_CHUNK or 256 candidates a chunk whatever
    # its moves (57 x 800,600 samples: a MemoryError under 2 GiB)
    for samples in (1, 100, chunks.CHUNK_SAMPLES // 64, chunks.CHUNK_SAMPLES // 8,
                    chunks.CHUNK_SAMPLES, engine.LINKAGE_SAMPLES * 400,
                    chunks.MAX_CHUNK_SAMPLES * 3):
        size = chunks.candidates_per_chunk(samples)
        assert size >= 1
        assert size * samples <= chunks.MAX_CHUNK_SAMPLES or size == 1
        assert size >= min(chunks.MIN_CHUNK, chunks.MAX_CHUNK_SAMPLES // samples)
    assert chunks.candidates_per_chunk(engine.LINKAGE_SAMPLES * 400) == 5  # 8 x 2^21 // 3.3e6
    assert chunks.candidates_per_chunk(100) == chunks.CHUNK_SAMPLES // 100
