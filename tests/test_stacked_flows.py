"""The power-flow sums of several laws' rows in one pass (sizer.sizing.move.StackedFlows)
against each law's calculator computing its own (the same numbers, bit for bit).

Laws of different families mixed in one model: their grids differ in length (padding),
in node count (Gauss-Legendre groups) and in pieces (numbered across the laws); two
stages of efficiency below one, the second with output ratings (its channel checked), a
return move (two directions) and a dwell; with and without the RMS model."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sizer.laws.registry import make_law
from sizer.model import Load, Motor, Stage, Task, Transmission
from sizer.sizing.candidates import Candidates, MotorArrays
from sizer.sizing.evaluation import LawRows
from sizer.sizing.move import StackedFlows, law_rows

LAWS = ("trapezoidal(alpha=0.2)", "double_s(alpha=0.3, beta=0.15)",
        "fifteen_segments(alpha=0.3, beta=0.2, gamma=0.25)", "modified_sinusoidal",
        "trapezoidal(alpha=0.45)")


def _model(seed: int):
    rng = np.random.default_rng(seed)
    motors = tuple(Motor(f"m{i}", inertia=2e-5 * t**1.3, continuous_torque=t,
                         peak_torque=3 * t, rated_speed=3000 * math.pi / 30)
                   for i, t in enumerate(rng.uniform(0.3, 8.0, 11)))
    stages = (Stage("gearbox", rng.uniform(3.0, 12.0), rng.uniform(0.7, 0.95), 1e-4),
              Stage("belt", rng.uniform(1.0, 3.0), rng.uniform(0.8, 0.97), 2e-5,
                    rated_output_torque=40.0, peak_output_torque=90.0))
    load = Load(rng.uniform(0.05, 0.6), friction=rng.uniform(0.0, 1.5),
                torque=rng.uniform(-2.0, 2.0))
    task = Task(math.pi / 2, None, dwell=rng.uniform(0.0, 0.3), return_move=True)
    candidates = Candidates.single(MotorArrays.of(motors), load, Transmission(stages))
    laws = [make_law(spec) for spec in LAWS]
    part = rng.integers(0, len(laws), len(motors))
    part[:len(laws)] = np.arange(len(laws))  # every law has rows
    return laws, part, task, candidates


@pytest.mark.parametrize("seed", [0, 1, 2])
@pytest.mark.parametrize("model", [False, True])
def test_the_stacked_sums_are_each_laws_own(seed: int, model: bool) -> None:
    laws, part, task, candidates = _model(seed)
    stacked = law_rows(laws, part, task, candidates.drive, candidates.motors)
    assert isinstance(stacked._flows, StackedFlows)  # every law has its pieces as data
    alone = LawRows(stacked.parts, stacked.part, stacked.motors, stacked.drive)
    rng = np.random.default_rng(seed + 10)
    for T in (rng.uniform(0.05, 2.0, len(part)), np.full(len(part), 0.3)):
        ours, theirs = stacked.evaluate(T, model=model), alone.evaluate(T, model=model)
        for name in ("rms_torque", "peak_torque", "thermal_speed", "load_torque"):
            assert np.array_equal(getattr(ours, name), getattr(theirs, name)), name
        for mine, other in zip(ours.stage_rms, theirs.stage_rms, strict=True):
            assert np.array_equal(mine, other)
        if model:
            assert ours.rms_model is not None and theirs.rms_model is not None
            later = T * 1.01
            assert np.array_equal(ours.rms_model.rms(later), theirs.rms_model.rms(later))
    # a subset of the rows (the searches take the rows still open) keeps its laws
    index = np.array([4, 0, 7, 2])
    T = rng.uniform(0.1, 1.0, len(index))
    assert np.array_equal(stacked.take(index).evaluate(T).rms_torque,
                          alone.take(index).evaluate(T).rms_torque)


def test_an_ideal_drive_or_a_law_without_its_pieces_as_data_keeps_the_parts_sums() -> None:
    laws, part, task, candidates = _model(0)
    ideal = Candidates.single(candidates.motors, Load(0.2), Transmission((Stage("gearbox", 5.0),)))
    assert law_rows(laws, part, task, ideal.drive, ideal.motors)._flows is None
    mixed = [*laws[:-1], make_law("poly5")]  # one piece, its own closure
    assert law_rows(mixed, part, task, candidates.drive, candidates.motors)._flows is None


def test_several_laws_grids_refuse_a_law_without_its_pieces_as_data() -> None:
    """Their pieces are numbered across the laws: a law evaluated piece by piece cannot
    join them (law_rows then keeps each part's own sums)."""
    from sizer.sizing.move import GridRows

    with pytest.raises(ValueError):
        GridRows([make_law("trapezoidal(alpha=0.2)"), make_law("poly5")], several=True)
