"""Minimize mode never misses a feasible duration (sizer.sizing.minimum_duration).

The reference is the duration mode itself on a log grid of durations: wherever one of
them passes every check, minimize mode must find a feasible T_min no longer than it,
and T_min (1 - 1e-6) must fail.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from sizer.io.loader import default_laws
from sizer.laws import make_law
from sizer.mechanics import Drive
from sizer.model import Design, Limits, Load, Motor, Stage, Task, Transmission
from sizer.sizing import size_design
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.checks import evaluate_checks, feasible, worst_slack
from sizer.sizing.move import CycleCalculator

GRID = np.geomspace(1e-3, 1e3, 121)  # 1e-3 s to 1000 s, 20 points per decade


def shapes():
    alpha = st.floats(0.01, 0.5)
    beta = st.floats(0.0005, 0.5)
    return st.one_of(
        st.sampled_from(default_laws()),
        alpha.map(lambda a: f"trapezoidal(alpha={a!r})"),
        st.tuples(alpha, beta).map(lambda ab: f"double_s(alpha={ab[0]!r}, beta={ab[1]!r})"),
        st.sampled_from(["double_s(alpha=1/2, beta=0.0005)", "double_s(alpha=0.01, beta=1/2)",
                         "trapezoidal(alpha=1/2)"]),
    )


@st.composite
def designs(draw):
    continuous = draw(st.floats(0.05, 20.0))
    motor = Motor("m", inertia=draw(st.floats(1e-5, 1e-2)), continuous_torque=continuous,
                  peak_torque=continuous * draw(st.floats(1.0, 5.0)),
                  rated_speed=draw(st.floats(30.0, 700.0)),
                  damping=draw(st.sampled_from([0.0, 1e-4])))
    stage = Stage("gearbox", draw(st.floats(1.0, 30.0)), draw(st.sampled_from([1.0, 0.9, 0.7])))
    # a friction near the continuous torque (at the load) makes windows of feasible T:
    # the RMS over a cycle with dwell falls with T, then rises to the friction torque
    near = continuous * stage.ratio * stage.efficiency * draw(st.floats(0.7, 1.2))
    load = Load(inertia=draw(st.floats(1e-4, 1.0)),
                damping=draw(st.sampled_from([0.0, 0.02, 0.5])),
                friction=draw(st.sampled_from([0.0, 0.05, 0.5, 2.0, near])),
                torque=draw(st.sampled_from([0.0, 0.0, 0.3, -0.5])))
    task = Task(draw(st.floats(0.1, 10.0)), None, dwell=draw(st.sampled_from([0.0, 0.1, 2.0])),
                return_move=draw(st.booleans()))
    limits = Limits(torque_margin=draw(st.sampled_from([0.0, 0.1, 0.3])),
                    speed_margin=draw(st.sampled_from([0.0, 0.05])),
                    thermal_speed=draw(st.sampled_from(["max", "rms", "mean"])))
    return Design(task, load, Transmission((stage,)), laws=(draw(shapes()),),
                  motors=(motor,), limits=limits)


def checks_at(design: Design, durations: np.ndarray):
    """The duration mode's checks at each duration (one replicated motor per duration)."""
    motors = MotorArrays.of(design.motors * len(durations))
    drive = Drive(design.load, design.transmission)
    calculator = CycleCalculator(None, design.task, drive, motors, design.limits.thermal_speed,
                                 law=make_law(design.laws[0]))
    return evaluate_checks(calculator.evaluate(durations), motors, drive, design.limits)


def passes_at(design: Design, durations: np.ndarray) -> np.ndarray:
    """The duration mode's verdict at each duration."""
    return feasible(checks_at(design, durations))


def at_duration(design: Design, T: float):
    fixed = dataclasses.replace(design, task=dataclasses.replace(design.task, duration=T))
    return size_design(fixed).results[0]


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(designs())
def test_minimize_finds_every_feasible_duration_of_a_grid(design):
    on_grid = passes_at(design, GRID)
    r = size_design(design).results[0]
    if not on_grid.any():
        return
    first = GRID[np.argmax(on_grid)]
    assert r.feasible, r.reason
    assert r.duration <= first * (1 + 1e-12)
    assert at_duration(design, r.duration).feasible
    # T_min is where the binding check reaches its limit: just below it the worst slack
    # is negative (it may still be within the verdict's tolerance where the slack varies
    # slowly with T, as with a friction equal to the peak torque)
    assert worst_slack(checks_at(design, np.array([r.duration * (1 - 1e-6)])))[0] < 0.0


def test_a_narrow_window_between_a_falling_and_a_rising_check_is_found():
    """Friction above the continuous torque with a long dwell: the RMS rises again with T.

    The RMS over the cycle tends to the friction torque at long durations, so the feasible
    durations are a window [T1, T2] that a walk by factors of 2 steps over; the slack's
    maximum is searched there. The friction is set (by bisection, on the grid verdicts)
    just below the value where the window closes.
    """
    motor = Motor("m", inertia=1e-4, continuous_torque=1.0, peak_torque=3.0,
                  rated_speed=300.0)
    base = Design(Task(1.0, None, dwell=1.0), Load(0.01), Transmission((Stage("gearbox", 5.0),)),
                  laws=("cycloidal",), motors=(motor,))

    def with_friction(friction: float) -> Design:
        return dataclasses.replace(base, load=Load(0.01, friction=friction))

    grid = np.geomspace(0.05, 5.0, 1001)
    lo, hi = 5.0, 20.0  # 5 N: the RMS tends to the continuous torque
    for _ in range(25):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if passes_at(with_friction(mid), grid).any() else (lo, mid)
    design = with_friction(lo - 0.003 * (lo - 5.0))
    window = grid[passes_at(design, grid)]
    assert 1.001 < window[-1] / window[0] < 1.2  # a narrow window, well inside the grid
    r = size_design(design).results[0]
    assert r.feasible, r.reason
    assert window[0] / 1.005 < r.duration <= window[0]
    assert not passes_at(design, np.array([r.duration * (1 - 1e-6)]))[0]
    assert not at_duration(design, window[-1] * 1.01).feasible
