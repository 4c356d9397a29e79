"""Eq. (6.2) on the flat part of an extended region (the envelope rule's completion).

A motor given by its ratings has, under the ``linear`` rule, flat regions up to the rated
speed and falling lines to max_speed. A move that stays below the rated speed sees the
book's rectangle, so eq. (6.2) is exact there; a move that reaches the rated speed may be
shorter on the falling part, and the search takes over. Numbers by hand or by an
independent scalar minimization over the fixed-shape engine.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from sizer.mechanics import Drive
from sizer.model.domain import Design, Limits, Load, Motor, Task
from sizer.sizing import size_design
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.move import CycleCalculator
from sizer.sizing.shortest_duration import minimum_duration

PLAIN = Motor(id="plain", inertia=1e-4, continuous_torque=1.0, peak_torque=3.0,
              rated_speed=100.0, max_speed=200.0)


def test_flat_speed_is_where_both_regions_leave_their_torque_at_rest():
    assert MotorArrays.of([PLAIN], "book").flat_speed.tolist() == [100.0]
    assert MotorArrays.of([PLAIN], "linear").flat_speed.tolist() == [100.0]
    falling = replace(PLAIN, id="falling", intermittent_curve=((0.0, 3.0), (200.0, 2.0)))
    assert MotorArrays.of([falling], "linear").flat_speed.tolist() == [0.0]
    no_max = replace(PLAIN, id="no_max", max_speed=None)
    assert MotorArrays.of([no_max], "linear").flat_speed.tolist() == [100.0]


def _minimum(load_inertia: float, h: float, envelope: str, law: str = "cycloidal"):
    from sizer.laws import make_law

    task = Task(h, None, dwell=0.1)
    drive = Drive(Load(load_inertia), Design(task, Load(load_inertia)).transmission)
    motors = MotorArrays.of([PLAIN], envelope)
    calculator = CycleCalculator(None, task, drive, motors, law=make_law(law))
    return minimum_duration(calculator, Limits(envelope=envelope))


def test_a_torque_bound_move_below_the_rated_speed_is_the_closed_form():
    # cycloidal: C_a = 2 pi, C_a_rms = sqrt(2) pi, C_v = 2 (Table 6.1); J_t = 1e-4 + 1e-2
    J_t, h = 1e-4 + 1e-2, 1.0
    peak = math.sqrt(2 * math.pi * h * J_t / 3.0)
    rms_scale = J_t * h * math.sqrt(2) * math.pi / 1.0  # T^3 (T + dwell) >= scale^2
    from scipy.optimize import brentq

    rms = brentq(lambda T: T**3 * (T + 0.1) - rms_scale**2, 1e-6, 10.0, xtol=1e-16)
    expected = max(peak, rms, 2 * h / 100.0)
    assert 2 * h / expected < 100.0  # below the rated speed: the rectangle holds
    solution = _minimum(1e-2, h, "linear")
    assert solution.method.startswith("closed form")
    assert solution.duration[0] == pytest.approx(expected, rel=1e-12)
    assert solution.duration[0] == _minimum(1e-2, h, "book").duration[0]


def test_a_speed_bound_move_is_searched_on_the_falling_part():
    # a light load: the book's T is the speed bound C_v h / v_n; the falling part allows more
    book = _minimum(1e-5, 1.0, "book").duration[0]
    linear = _minimum(1e-5, 1.0, "linear").duration[0]
    assert book == pytest.approx(2.0 / 100.0, rel=1e-12)
    assert linear < book * (1 - 1e-3)
    # the peak point sits on the falling line: checked by the engine's own verdict
    design = Design(Task(1.0, None, dwell=0.1), Load(1e-5), laws=("cycloidal",),
                    motors=(PLAIN,), limits=Limits(envelope="linear"))
    result = size_design(design).results[0]
    assert result.feasible and result.duration == pytest.approx(linear, rel=1e-12)
    shorter = size_design(replace(design, task=Task(1.0, linear * (1 - 1e-6), dwell=0.1)))
    assert not shorter.results[0].feasible


@pytest.mark.parametrize("load_inertia", [1e-2, 1e-5])
def test_auto_trapezoid_on_an_extended_region_is_the_optimum_of_the_fixed_shapes(load_inertia):
    design = Design(Task(1.0, None, dwell=0.1), Load(load_inertia),
                    laws=("trapezoidal(alpha=auto)",), motors=(PLAIN,),
                    limits=Limits(envelope="linear"))
    auto = size_design(design).results[0]

    def t_min(alpha: float) -> float:
        fixed = replace(design, laws=(f"trapezoidal(alpha={float(alpha)!r})",))
        r = size_design(fixed).results[0]
        return r.duration if r.feasible else np.inf

    best = minimize_scalar(t_min, bounds=(1e-3, 0.5), method="bounded",
                           options={"xatol": 1e-9})
    grid = min(t_min(a) for a in np.linspace(0.02, 0.5, 25))
    assert auto.feasible
    assert auto.duration <= min(best.fun, grid) * (1 + 1e-9)
    assert auto.duration >= min(best.fun, grid) * (1 - 1e-6)
