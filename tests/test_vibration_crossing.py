"""The smallest scale at which the residual vibration meets its limit (issue 34): the
root finder's answer against a plain bisection to rounding, written here, on the bundled
example's cycle for three laws and starting scales on both sides of the crossings."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from sizer.io import load_design
from sizer.laws import make_law
from sizer.sizing.vibration_check import admissible_scale, cycle_vibration

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "indexing-table-vibration.yaml"
LIMIT = 20 * math.pi / 180.0 / 3600.0


def _bisected(vibration, left: float, right: float) -> float:
    """The first scale in (left, right] meeting the limit, right meeting it."""
    for _ in range(200):
        mid = 0.5 * (left + right)
        if vibration.worst(np.array([mid]))[0] <= LIMIT:
            right = mid
        else:
            left = mid
        if right - left <= 4e-16 * right:
            break
    return right


@pytest.mark.parametrize("spec", ["cycloidal", "double_s(alpha=1/3, beta=1/4)", "poly5",
                                  "trapezoidal(alpha=1/3)"])
def test_admissible_scale_is_the_first_scale_meeting_the_limit(spec):
    design = load_design(EXAMPLE)
    vibration = cycle_vibration(design, make_law(spec))
    assert vibration is not None
    starts = np.linspace(0.2, 1.2, 9)
    found = admissible_scale(vibration, starts, LIMIT)
    moved = found > starts
    assert moved.any()
    for s, T in zip(starts[moved], found[moved], strict=True):
        assert vibration.worst(np.array([T]))[0] <= LIMIT * (1.0 + 1e-12)
        # the reference: a dense scan from s for the first scale meeting the limit, then
        # bisection from the scan point before it
        grid = np.linspace(s, T * (1.0 + 1e-3), 4001)
        ok = np.flatnonzero(vibration.worst(grid) <= LIMIT)
        j = ok[0]
        reference = grid[j] if j == 0 else _bisected(vibration, grid[j - 1], grid[j])
        assert abs(T / reference - 1.0) <= 1e-13
