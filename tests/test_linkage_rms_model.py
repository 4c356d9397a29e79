"""The RMS model, thermal speed and peak crossing of a cycle through a linkage (issue 34).

Each is checked against the calculator's own evaluation, the plain computation: the model
equals the evaluated RMS where it is built and differs little near it; the
cheap thermal speed equals the evaluated one; the peak crossing is where the evaluated
peak check reaches its limit; and the shortest scales with them equal the search on the
evaluated slack (sizer.sizing.shortest_duration.bisect_duration)."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from sizer.io.loader import load_design
from sizer.laws import law_choice
from sizer.mechanics.drive import Drive
from sizer.model.cycle import Dwell, Move, ShareRule, from_task
from sizer.model.domain import Motor
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.linkage_move import LinkageCycle, linkage_calculator
from sizer.sizing.shortest_duration import bisect_duration, minimum_duration

ROOT = Path(__file__).resolve().parent.parent


def _motors(count: int) -> tuple[Motor, ...]:
    """Falling speed-torque curves, small to large (some bound by the peak, some by the
    RMS, some by the speed in the press cycle)."""
    out = []
    for k in range(count):
        tau_p, v_n = 0.6 + 1.5 * k, 150.0 + 25.0 * k
        out.append(Motor(id=f"m{k}", inertia=1e-4 * (1 + k), continuous_torque=tau_p / 3,
                         peak_torque=tau_p, rated_speed=v_n, max_speed=2 * v_n,
                         intermittent_curve=((0.0, tau_p), (0.8 * v_n, tau_p),
                                             (1.4 * v_n, 0.7 * tau_p), (2 * v_n, 0.35 * tau_p)),
                         continuous_curve=((0.0, tau_p / 3), (2 * v_n, tau_p / 5))))
    return tuple(out)


def _press(count: int, file: str = "press-slider-crank-cycle.yaml"):
    design = load_design(ROOT / "examples" / file)
    design = replace(design, motors=_motors(count))
    motors = MotorArrays.of(design.motors, design.limits.envelope)
    calculator = linkage_calculator(design, law_choice("poly7").law, motors,
                                    Drive(design.load, design.transmission))
    return calculator, design


@pytest.mark.parametrize("file", ["press-slider-crank-cycle.yaml", "press-slider-crank.yaml"])
def test_rms_model_is_exact_where_built_and_close_near(file):
    calculator, _ = _press(6, file)
    s = np.linspace(0.15, 0.5, 6) * (1.0 if isinstance(calculator, LinkageCycle) else 0.5)
    model = calculator.evaluate(s, model=True).rms_model
    assert model is not None
    exact = calculator.evaluate(s).rms_torque
    assert np.allclose(model.rms(s), exact, rtol=1e-12, atol=0.0)
    # near it the model is off only where samples change the power flow's direction (the
    # crank torque changes sign there): small, growing with the distance
    errors = []
    for step in (1e-2, 5e-2):
        near = calculator.evaluate(s * (1.0 + step)).rms_torque
        errors.append(np.max(np.abs(model.rms(s * (1.0 + step)) / near - 1.0)))
    assert errors[0] < 1e-6 and errors[1] < 2e-5


def test_cycle_thermal_speed_is_the_evaluated_one():
    for rule in ("max", "rms", "mean"):
        calculator, _ = _press(5)
        assert isinstance(calculator, LinkageCycle)
        calculator.thermal_rule = rule
        s = np.linspace(0.2, 0.7, 5)
        assert np.allclose(calculator.thermal_speed(s), calculator.evaluate(s).thermal_speed,
                           rtol=1e-14, atol=0.0)
        index = np.array([3, 0])
        assert np.allclose(calculator.take(index).thermal_speed(s[index]),
                           calculator.evaluate(s).thermal_speed[index], rtol=1e-14, atol=0.0)


@pytest.mark.parametrize("file", ["press-slider-crank-cycle.yaml", "press-slider-crank.yaml"])
def test_peak_floor_is_where_the_peak_check_starts_to_pass_for_good(file):
    calculator, design = _press(8, file)
    limits = design.limits
    low = calculator.speed_bound(limits)
    floor = calculator.search_start(limits)
    grip = 1.0 - limits.torque_margin
    finite = np.isfinite(floor)
    assert finite.any() and np.all(floor[finite] >= low[finite])
    moved = finite & (floor > low * (1.0 + 1e-12))  # the peak binds above the speed bound
    assert moved.any()
    at = calculator.evaluate(np.where(finite, floor, 1.0)).peak_ratio
    assert np.all(at[moved] <= grip * (1.0 + 1e-12))
    assert np.allclose(at[moved], grip, rtol=1e-9, atol=0.0)
    below = calculator.evaluate(np.where(moved, floor * (1.0 - 1e-7), 1.0)).peak_ratio
    assert np.all(below[moved] > grip)
    for factor in (1.0 + 1e-9, 1.3, 2.0, 5.0, 40.0):  # and it passes at every longer one
        later = calculator.evaluate(np.where(finite, floor * factor, 1.0)).peak_ratio
        assert np.all(later[finite] <= grip * (1.0 + 1e-12))
    # inf: no duration passes (the ratio does not fall below the limit however long)
    for factor in (1.0, 10.0, 1e3):
        never = calculator.evaluate(np.where(finite, 1.0, low * factor)).peak_ratio
        assert np.all(never[~finite] > grip)


@pytest.mark.parametrize("file", ["press-slider-crank-cycle.yaml", "press-slider-crank.yaml"])
def test_shortest_scales_equal_the_search_on_the_evaluated_slack(file):
    calculator, design = _press(10, file)
    solution = minimum_duration(calculator, design.limits)
    searched = bisect_duration(calculator, design.limits)
    assert np.array_equal(np.isfinite(searched), solution.feasible)
    ok = solution.feasible
    assert ok.sum() >= 5
    assert np.allclose(solution.duration[ok], searched[ok], rtol=1e-12, atol=0.0)


def _rocker_scaled(count: int):
    """The driven four-bar's move and dwell both free, in shares 1 : 3 (a machine axis at
    a free master speed, sizer.model.machine.MachineAxis.scaled): the dwell holds the
    rocker's load."""
    design = load_design(ROOT / "examples" / "four-bar-rocker-driven.yaml")
    cycle = from_task(replace(design.task, duration=None, dwell=0.75))
    segments = tuple(replace(s, weight=0.25) if isinstance(s, Move) else
                     Dwell(None, weight=0.75, name=s.name) for s in cycle.segments)
    design = replace(design, motors=_motors(count), machine_cycle=replace(
        cycle, segments=segments, share=ShareRule.WEIGHTS, shorthand=None))
    motors = MotorArrays.of(design.motors, design.limits.envelope)
    calculator = linkage_calculator(design, law_choice("poly7").law, motors,
                                    Drive(design.load, design.transmission))
    assert isinstance(calculator, LinkageCycle)
    return calculator


def test_cycle_rms_lower_bound_holds_at_every_scale():
    calculator = _rocker_scaled(6)
    bound = calculator.rms_lower_bound()
    assert bound is not None and np.all(bound > 0.0)  # the dwell holds the rocker's load
    for s in np.geomspace(1e-2, 1e3, 12):
        rms = calculator.evaluate(np.full(len(bound), s)).rms_torque
        assert np.all(bound <= rms * (1.0 + 1e-12))
    # at long scales the holding dwell makes most of the RMS (the move adds its static
    # load over a quarter of the cycle): the bound is close to it there, not a trivial 0
    far = calculator.evaluate(np.full(len(bound), 1e6)).rms_torque
    assert np.all(bound <= far) and np.all(bound >= 0.9 * far)
