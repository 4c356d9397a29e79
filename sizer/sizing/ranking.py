"""Order candidates: feasible first, then by the chosen key, ties by motor and law."""

from __future__ import annotations

import math
from collections.abc import Iterable

from sizer.errors import UserError
from sizer.sizing.results import CandidateResult

RANK_KEYS = ("duration", "margin", "rms", "peak", "price", "mass")


def _value(result: CandidateResult, key: str) -> float | tuple[float, ...]:
    if key == "margin":  # the largest smallest margin first, then the next smallest...
        return tuple(-s for s in result.slacks)
    if key == "duration":
        value = result.duration
    elif key == "rms":
        value = result.rms_torque
    elif key == "peak":
        value = result.peak_torque
    else:
        value = getattr(result, key)
    return math.inf if value is None or math.isnan(value) else float(value)


def rank(results: Iterable[CandidateResult], rank_by: str | None,
         mode: str) -> list[CandidateResult]:
    """Feasible pairs first; by duration in minimize mode, by largest margin otherwise."""
    key = rank_by or ("duration" if mode == "minimize" else "margin")
    if key not in RANK_KEYS:
        raise UserError(f"cannot rank by {key!r}; choose one of {', '.join(RANK_KEYS)}")
    return sorted(results, key=lambda r: (not r.feasible, _value(r, key), r.motor, r.spec))
