"""The exact peaks (maxima of linear functions, support queries, certified minima) equal
the grid search refined by golden section on random drives (sizer.sizing.cycle)."""

from __future__ import annotations

import numpy as np
import pytest

from sizer.laws import make_law
from sizer.mechanics import Drive
from sizer.model.domain import Load, Motor, Stage, Task, Transmission
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.move import CycleCalculator, MoveScales

LAWS = ("cycloidal", "poly5", "trapezoidal(alpha=1/3)", "double_s(alpha=1/3, beta=1/4)",
        "modified_sinusoidal", "harmonic")


def random_case(rng: np.random.Generator):
    stages = tuple(
        Stage("gearbox", float(rng.uniform(1.5, 12.0)), float(rng.choice([1.0, 0.9, 0.7])),
              float(rng.uniform(0.0, 5e-5)), preload_torque=float(rng.uniform(0.0, 0.05)),
              peak_output_torque=1e3, rated_output_torque=1e3)
        for _ in range(int(rng.integers(1, 3))))
    load = Load(float(rng.uniform(0.005, 0.5)), damping=float(rng.uniform(0.0, 0.2)),
                friction=float(rng.uniform(0.0, 3.0)), torque=float(rng.uniform(-4.0, 4.0)))
    motors = tuple(Motor(f"m{i}", float(10 ** rng.uniform(-5, -3)), 5.0, 15.0, 1e4)
                   for i in range(5))
    return Drive(load, Transmission(stages)), MotorArrays.of(motors, "book")


@pytest.mark.parametrize("seed", range(12))
def test_exact_peaks_equal_the_refined_grid(seed):
    rng = np.random.default_rng(seed)
    drive, motors = random_case(rng)
    law = make_law(LAWS[seed % len(LAWS)])
    calculator = CycleCalculator(None, Task(1.0, 0.5, 0.1, return_move=True), drive, motors,
                                 law=law)
    T = rng.uniform(0.05, 0.5, len(motors))
    for direction in (1.0, -1.0):
        scales = MoveScales(1.0 / T / T, 1.0 / T, direction)
        exact = calculator._peaks([scales])[0]
        grid = calculator._sampled_peaks([scales])[0]
        np.testing.assert_allclose(exact[0], grid[0], rtol=1e-9)  # motor torque
        np.testing.assert_allclose(exact[1], grid[1], rtol=1e-9)  # peak ratio
        for mine, theirs in zip(exact[3], grid[3], strict=True):  # stage outputs
            np.testing.assert_allclose(mine, theirs, rtol=1e-9)
        # the load's torque: the grid samples it (no refinement), the exact one is above
        assert np.all(exact[2] >= grid[2] * (1 - 1e-12))
        assert np.all(exact[2] <= grid[2] * (1 + 1e-3))
