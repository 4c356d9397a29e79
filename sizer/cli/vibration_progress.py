"""``sizer vibration``'s sweep in steps, for a progress bar with an estimate (issue 36: a
52 s sweep showed no progress): each law's durations in ``CHUNKS`` runs of the core's
:func:`~sizer.sizing.vibration_check.vibration_sweep`, the callback after each.

The residual at a duration depends on that duration only (every operation of the sweep is
elementwise over the durations), so the pieces put together are the one-run sweep's
numbers (to the last bit or two of numpy's vectorized functions; tests/test_progress_
vibration.py). The sweep is stepped whether or not a bar is drawn, so that a terminal and
a pipe get the same numbers.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from sizer.laws import MotionLaw
    from sizer.model.domain import Design
    from sizer.sizing.vibration_check import VibrationSweep

CHUNKS = 16
"""Steps per law: the bar moves every 1/16 of a law's durations."""


def stepped_sweep(design: Design, laws: tuple[MotionLaw, ...], scales: np.ndarray,
                  progress: Callable[[int, int], None] | None = None,
                  chunks: int = CHUNKS) -> VibrationSweep:
    """vibration_sweep(design, laws, scales), calling ``progress(done, total)`` with (0,
    total) and then after each of the len(laws) x chunks steps."""
    from sizer.sizing.vibration_check import VibrationSweep, vibration_sweep

    scales = np.asarray(scales, dtype=float)
    pieces = [p for p in np.array_split(scales, max(1, min(chunks, scales.size))) if p.size]
    if not laws:
        return vibration_sweep(design, laws, scales)
    total = len(laws) * len(pieces)
    if progress is not None:
        progress(0, total)
    residual: list[np.ndarray] = []
    tracking: list[np.ndarray] = []
    limit = design.limits.residual_vibration
    for k, law in enumerate(laws):
        parts = []
        for j, piece in enumerate(pieces, start=1):
            parts.append(vibration_sweep(design, (law,), piece))
            if progress is not None:
                progress(k * len(pieces) + j, total)
        residual.append(np.concatenate([p.residual[0] for p in parts]))
        if parts[0].tracking is not None:
            tracking.append(np.concatenate([p.tracking[0] for p in parts
                                            if p.tracking is not None]))
        limit = parts[0].limit
    return VibrationSweep(scales, laws, tuple(residual), limit,
                          tuple(tracking) if design.machine_cycle.shorthand is not None
                          else None)
