"""The RMS model of a cycle and the RMS crossing built on it (sizer.sizing.cycle.RmsModel,
sizer.sizing.minimum_duration.rms_crossing).

- The model equals the cycle's own RMS at the durations it was built at, and near them
  its error falls like the square of the step (the power-flow split points are held,
  and moving them changes the integral to second order only); with an ideal drive (no
  split points) it is exact at every duration.
- rms_crossing lands where the plain scalar reference (tests/scalar_reference.py) finds
  the RMS check exactly at its required margin, with the check failing just below; the
  RMS it gives with each crossing (its last model's) is the cycle's own RMS there, and
  an evaluation given it skips only the power-flow integrals.
"""

from __future__ import annotations

import numpy as np
import pytest
from scalar_reference import evaluate
from test_engine_vs_scalar import candidate, engine_calculator, minimize_design

from sizer.laws import make_law
from sizer.mechanics import Drive
from sizer.model import Limits, Load, Motor, Stage, Task, Transmission
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.move import CycleCalculator
from sizer.sizing.shortest_duration import rms_crossing, rms_crossing_with_rms


def calculator_of(efficiency: float, spec: str = "cycloidal") -> CycleCalculator:
    motors = MotorArrays.of([Motor(f"m{i}", 1e-4 * (i + 1), 1.0 + i, 3.0 + 3 * i, 300.0)
                             for i in range(4)], "book")
    drive = Drive(Load(0.05, damping=0.02, friction=0.3, torque=0.4),
                  Transmission((Stage("gearbox", 8.0, efficiency, 2e-5),)))
    return CycleCalculator(None, Task(1.5, None, dwell=0.2, return_move=True), drive, motors,
                           law=make_law(spec))


@pytest.mark.parametrize("spec", ["cycloidal", "poly5", "double_s(alpha=1/3, beta=1/4)"])
def test_the_model_is_exact_where_built_and_second_order_near(spec):
    calc = calculator_of(0.9, spec)
    T = np.array([0.15, 0.2, 0.3, 0.5])
    model = calc.evaluate(T, peaks=False, model=True).rms_model
    np.testing.assert_allclose(model.rms(T), calc.evaluate(T, peaks=False).rms_torque,
                               rtol=1e-14)
    errors = []
    for step in (1e-2, 1e-3):
        exact = calc.evaluate(T * (1 + step), peaks=False).rms_torque
        errors.append(np.max(np.abs(model.rms(T * (1 + step)) / exact - 1.0)))
    assert errors[0] < 1e-5
    assert errors[1] < errors[0] / 30.0  # at least second order (1e-3 vs 1e-2: 100x)


def test_the_model_is_exact_everywhere_with_an_ideal_drive():
    calc = calculator_of(1.0)
    T = np.array([0.15, 0.2, 0.3, 0.5])
    model = calc.evaluate(T, peaks=False, model=True).rms_model
    for factor in (0.5, 1.7, 4.0):
        np.testing.assert_allclose(model.rms(T * factor),
                                   calc.evaluate(T * factor, peaks=False).rms_torque,
                                   rtol=1e-13)


@pytest.mark.parametrize("seed", range(4))
def test_the_crossing_is_where_the_reference_rms_check_binds(seed):
    design = minimize_design(seed)
    checked = 0
    for motor in design.motors:
        for spec in design.laws:
            ratio = design.ratio_choice.ratios[0]
            calc = engine_calculator(design, motor, spec, ratio)
            start = np.array([0.02])
            if calc.evaluate(start, peaks=False).rms_torque[0] <= 0.0:
                continue
            T = float(rms_crossing(calc, design.limits, start)[0])
            if not np.isfinite(T):
                continue
            c = candidate(design, motor, spec, ratio)
            at = evaluate(c, T)
            value, limit, required = at.checks["rms"]
            assert 1.0 - value / limit == pytest.approx(required, abs=1e-9)
            value, limit, required = evaluate(c, T * (1 - 1e-6)).checks["rms"]
            assert 1.0 - value / limit < required
            checked += 1
    assert checked >= 1


@pytest.mark.parametrize("spec", ["cycloidal", "modified_trapezoidal"])
def test_a_crossing_from_a_model_built_for_more_candidates_is_the_same(spec):
    """The first round of rms_crossing may take the model of a larger evaluation at the
    same durations (minimum_duration builds it at the peak bound): the same crossings,
    to the bit, as when the round evaluates the candidates again."""
    calc = calculator_of(0.9, spec)
    T = np.array([0.05, 0.08, 0.12, 0.2])
    model = calc.evaluate(T, peaks=True, model=True).rms_model
    limits = Limits(torque_margin=0.1)
    index = np.array([3, 1, 2])
    alone = rms_crossing(calc.take(index), limits, T[index])
    reused = rms_crossing(calc.take(index), limits, T[index], (model, index))
    assert np.isfinite(alone).all()
    np.testing.assert_array_equal(reused, alone)


@pytest.mark.parametrize("spec", ["cycloidal", "trapezoidal(alpha=1/3)", "modified_trapezoidal",
                                  "double_s(alpha=1/4, beta=1/3)"])
def test_the_rms_given_with_a_crossing_is_the_cycles_own_there(spec):
    """The RMS that rms_crossing_with_rms gives with each crossing (the value of its last
    round's model, built within CONVERGED of it) against a full evaluation at that
    duration: the same to rounding; and an evaluation given that RMS equals the full one
    in every other figure, to the bit."""
    calc = calculator_of(0.9, spec)
    limits = Limits(torque_margin=0.1)
    T, rms = rms_crossing_with_rms(calc, limits, np.array([0.05, 0.08, 0.12, 0.2]))
    assert np.isfinite(T).all()
    np.testing.assert_array_equal(T, rms_crossing(calc, limits, np.array([0.05, 0.08, 0.12,
                                                                          0.2])))
    full = calc.evaluate(T)
    np.testing.assert_allclose(rms, full.rms_torque, rtol=1e-13)
    given = calc.evaluate(T, rms=rms)
    np.testing.assert_array_equal(given.rms_torque, rms)
    for name in ("peak_torque", "peak_ratio", "max_speed", "thermal_speed", "load_torque"):
        np.testing.assert_array_equal(getattr(given, name), getattr(full, name))


def test_a_given_rms_is_not_used_where_a_stage_rms_is_checked():
    """A stage with a rated output torque needs its own RMS: the evaluation then
    integrates everything and the given value is ignored."""
    motors = MotorArrays.of([Motor(f"m{i}", 1e-4 * (i + 1), 1.0 + i, 3.0 + 3 * i, 300.0)
                             for i in range(2)], "book")
    stage = Stage("gearbox", 8.0, 0.9, 2e-5, rated_output_torque=20.0)
    drive = Drive(Load(0.05, damping=0.02, friction=0.3, torque=0.4),
                  Transmission((stage,)))
    calc = CycleCalculator(None, Task(1.5, None, dwell=0.2, return_move=True), drive, motors,
                           law=make_law("cycloidal"))
    T = np.array([0.2, 0.3])
    full = calc.evaluate(T)
    given = calc.evaluate(T, rms=np.array([1.0, 2.0]))
    np.testing.assert_array_equal(given.rms_torque, full.rms_torque)
    np.testing.assert_array_equal(given.stage_rms[0], full.stage_rms[0])
    assert np.all(full.stage_rms[0] > 0.0)
