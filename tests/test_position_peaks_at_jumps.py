"""Peaks read by the position and linkage engines at a law's breakpoints.

The engines sample each move once at the law's breakpoints and refine a smooth peak by a
parabola through three samples (sizer.sizing.linkage_move.refined_max). Where the law's
acceleration jumps (a trapezoid's, a constant acceleration's) the one sample at the
breakpoint holds one side's value: a parabola through it overshot the peak torque (4 % on
the trapezoid below) and one centred on the speed's kink overshot the top speed. Here a
load of the position that is the same everywhere (a two-knot force table of one value)
must give the figures of the constant force: the top speed by its closed form, the peak
torque as the engine's exact closed-form path gives it for the constant force (the path
tested against the book and the vendors elsewhere)."""

from __future__ import annotations

import copy
import math

import pytest
from test_ball_screw_checks import design

import sizer

MOTOR = "SGM7J-08A"
JUMP_LAWS = ["trapezoidal(alpha=1/4)", "trapezoidal(alpha=1/3)", "constant_acceleration",
             "double_s(alpha=1/3, beta=1/4)"]


def figures(data: dict) -> tuple[float, float]:
    row = sizer.size(data, motors=[MOTOR]).results[0]
    return row.peak_torque, row.max_speed


def as_table(data: dict) -> dict:
    table = copy.deepcopy(data)
    force = table["load"].pop("force")
    table["load"]["force_table"] = {"points": [["0 mm", force], ["300 mm", force]]}
    return table


@pytest.mark.parametrize("law", JUMP_LAWS)
def test_a_constant_table_gives_the_constant_forces_peaks(law: str) -> None:
    base = design(law=law)
    peak, speed = figures(base)
    table_peak, table_speed = figures(as_table(base))
    assert table_peak == pytest.approx(peak, rel=1e-12)
    assert table_speed == pytest.approx(speed, rel=1e-12)


def test_the_trapezoids_top_speed_by_its_closed_form() -> None:
    """v_max = h / ((1 - alpha) T) at the load, 2 pi / lead at the motor: 0.3 m in 0.6 s,
    alpha = 1/4, lead 10 mm."""
    _, speed = figures(as_table(design(law="trapezoidal(alpha=1/4)")))
    assert speed == pytest.approx(0.3 / (0.75 * 0.6) * 2.0 * math.pi / 0.01, rel=1e-12)
