"""The RMS screen of the T_min search (sizer.sizing.minimum_duration.rms_lower_bound and
rms_unreachable, book sec. 6.1.1): the bound lies below the RMS torque of the cycle at
every duration, computed one candidate at a time by tests/scalar_reference.py (quad over
the move), and a candidate it screens out has no feasible duration by the reference's
own search either."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scalar_reference import Candidate, evaluate, minimum_duration
from test_engine_vs_scalar import engine_calculator, minimize_design

from sizer.laws import make_law
from sizer.model import Design, Limits, Load, Motor, Stage, Task, Transmission
from sizer.sizing.shortest_duration import rms_lower_bound, rms_unreachable

DURATIONS = tuple(10.0**k for k in (-2.0, -1.5, -1.0, -0.5, 0.0, 0.5, 1.0, 2.0, 3.0))


@pytest.mark.parametrize("seed", range(6))
def test_bound_below_the_scalar_rms_at_every_duration(seed: int) -> None:
    design = minimize_design(seed)
    motor, spec = design.motors[0], design.laws[0]
    option = design.ratio_choice.ratios[0]
    calculator = engine_calculator(design, motor, spec, option)
    bound = rms_lower_bound(calculator)
    assert bound is not None
    stages = list(design.transmission.stages)
    stages[0] = dataclasses.replace(stages[0], ratio=option)
    reference = Candidate(motor, make_law(spec), design.task, design.load, tuple(stages),
                          design.limits)
    for T in DURATIONS:
        assert bound[0] <= evaluate(reference, T).rms_torque * (1.0 + 1e-12)


def _weak_motor_design(friction: float, dwell: float, torque: float = 0.2) -> Design:
    """A motor of 0.1 N*m continuous against a friction of ``friction`` N*m and a
    constant load ``torque`` at the load, through a 3:1 gearbox of efficiency 0.9, with a
    return move."""
    motor = Motor("weak", inertia=2e-5, continuous_torque=0.1, peak_torque=0.4,
                  rated_speed=300.0, max_speed=500.0)
    return Design(Task(1.0, None, dwell=dwell, return_move=True),
                  Load(0.001, damping=0.001, friction=friction, torque=torque),
                  Transmission((Stage("gearbox", 3.0, 0.9, 1e-6),)), laws=("cycloidal",),
                  motors=(motor,), limits=Limits(torque_margin=0.1))


@pytest.mark.parametrize("dwell", [0.0, 0.2])
def test_screened_candidate_has_no_duration(dwell: float) -> None:
    design = _weak_motor_design(friction=0.6, dwell=dwell, torque=0.5)
    calculator = engine_calculator_of(design)
    assert bool(rms_unreachable(calculator, design.limits)[0])
    reference = Candidate(design.motors[0], make_law("cycloidal"), design.task, design.load,
                          design.transmission.stages, design.limits)
    assert minimum_duration(reference) is None
    # and the reference's RMS stays above the limit with the margin at every duration
    for T in DURATIONS:
        value, limit, required = evaluate(reference, T).checks["rms"]
        assert value > (1.0 - required) * limit


def test_feasible_candidate_not_screened() -> None:
    design = _weak_motor_design(friction=0.05, dwell=0.2)
    calculator = engine_calculator_of(design)
    assert not bool(rms_unreachable(calculator, design.limits)[0])
    reference = Candidate(design.motors[0], make_law("cycloidal"), design.task, design.load,
                          design.transmission.stages, design.limits)
    found = minimum_duration(reference)
    assert found is not None and math.isfinite(found)


def engine_calculator_of(design: Design):
    """The engine's calculator of a one-motor design without a ratio choice."""
    from sizer.mechanics import Drive
    from sizer.sizing.candidates import MotorArrays
    from sizer.sizing.move import CycleCalculator

    return CycleCalculator(None, design.task, Drive(design.load, design.transmission),
                           MotorArrays.of(list(design.motors), design.limits.envelope),
                           design.limits.thermal_speed, law=make_law(design.laws[0]))


def test_bound_is_the_constant_torque_mean_without_motion() -> None:
    """With no inertia, damping or dwell the motor torque is the constant shaft torque of
    each move, so the bound is exact: sqrt of the mean of the squared positive
    constants (closed form)."""
    motor = Motor("m", inertia=0.0, continuous_torque=1.0, peak_torque=3.0, rated_speed=300.0)
    design = Design(Task(1.0, None, dwell=0.0, return_move=False),
                    Load(0.0, friction=0.3, torque=0.2),
                    Transmission((Stage("gearbox", 2.0, 0.8, 0.0),)), laws=("cycloidal",),
                    motors=(motor,), limits=Limits())
    bound = rms_lower_bound(engine_calculator_of(design))
    assert bound is not None
    np.testing.assert_allclose(bound, [(0.3 + 0.2) / (2.0 * 0.8)], rtol=1e-15)
