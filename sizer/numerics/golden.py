"""Vectorized golden-section search: the step shared by every bracketed extremum search.

Each caller keeps its own stopping rule (a fixed count, a width, a feasible point found)
and decides per element which side holds the extremum; the step then shrinks the
brackets and evaluates the objective once, at one new point per element.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

INV_PHI = (math.sqrt(5.0) - 1.0) / 2.0

Bracket = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]
"""(lo, hi, x1, x2, f1, f2) with lo < x1 < x2 < hi and f1 = f(x1), f2 = f(x2)."""


def interior_points(lo: np.ndarray, hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The two golden points x1 < x2 of [lo, hi]."""
    return hi - INV_PHI * (hi - lo), lo + INV_PHI * (hi - lo)


def golden_step(f: Callable[[np.ndarray], np.ndarray], bracket: Bracket,
                left: np.ndarray) -> Bracket:
    """One step: where ``left`` the extremum lies in [lo, x2], elsewhere in [x1, hi]."""
    lo, hi, x1, x2, f1, f2 = bracket
    hi, lo = np.where(left, x2, hi), np.where(left, lo, x1)
    new_x1 = np.where(left, hi - INV_PHI * (hi - lo), x2)
    new_x2 = np.where(left, x1, lo + INV_PHI * (hi - lo))
    f_new = f(np.where(left, new_x1, new_x2))
    return (lo, hi, new_x1, new_x2,
            np.where(left, f_new, f2), np.where(left, f1, f_new))
