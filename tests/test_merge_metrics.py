"""sizer.sizing.minimum_duration.merge_metrics: the rows of a subset's evaluation put into
the whole equal one evaluation of every candidate at the merged durations (the cycle is
evaluated candidate by candidate, book sec. 6.1.1)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from test_engine_vs_scalar import minimize_design

from sizer.laws import make_law
from sizer.mechanics import Drive
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.evaluation import CycleMetrics
from sizer.sizing.move import CycleCalculator
from sizer.sizing.shortest_duration import merge_metrics


@pytest.mark.parametrize("seed", range(4))
def test_merge_equals_one_evaluation(seed: int) -> None:
    design = minimize_design(seed)
    motors = MotorArrays.of(list(design.motors) * 3, design.limits.envelope)
    calculator = CycleCalculator(None, design.task, Drive(design.load, design.transmission),
                                 motors, design.limits.thermal_speed,
                                 law=make_law(design.laws[0]))
    first = np.linspace(0.05, 0.6, len(motors))
    later = first * 1.7
    index = np.array([1, 4])
    merged = merge_metrics(calculator.evaluate(first), index,
                           calculator.take(index).evaluate(later[index]))
    whole = calculator.evaluate(np.where(np.isin(np.arange(len(motors)), index), later, first))
    for field in dataclasses.fields(CycleMetrics):
        if field.name == "rms_model":
            assert merged.rms_model is None
            continue
        got, want = getattr(merged, field.name), getattr(whole, field.name)
        for g, w in (zip(got, want, strict=True) if isinstance(got, list) else [(got, want)]):
            np.testing.assert_allclose(g, np.broadcast_to(w, g.shape), rtol=1e-13, atol=0.0)
