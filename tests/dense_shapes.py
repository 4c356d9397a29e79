"""A test-only reference for `auto` shapes: each motor's T_min of the auto spec against the
engine's T_min of a dense grid of fixed shapes of the family (the search's optimum is the
same or better)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

from sizer.model import Design
from sizer.sizing import size_design


def assert_no_slower_than_fixed(design: Design, fixed_specs: Sequence[str],
                                rtol: float) -> None:
    """``design`` (one auto spec) sized, each motor's result against the shortest feasible
    T_min of ``fixed_specs`` sized alike: feasible where one of them is, and no slower
    than it by more than ``rtol``."""
    auto = size_design(design).results
    fixed = size_design(replace(design, laws=tuple(fixed_specs))).results
    for motor in design.motors:
        mine = [r for r in auto if r.motor == motor.id]
        dense = [r.duration for r in fixed if r.motor == motor.id and r.feasible]
        assert len(mine) == 1
        if not dense:
            continue
        assert mine[0].feasible
        assert mine[0].duration <= min(dense) * (1 + rtol)
