"""One cycle model over several laws' rows (sizer.laws.row_laws.RowLaws in
sizer.sizing.move.CycleCalculator) against each law's own calculator of its rows: the same
numbers, bit for bit.

The laws mix families with their pieces as data (padded grids, pieces numbered across the
laws) and one-piece laws (their power-flow sums law by law); the motors have speed-torque
curves (the exact ratio against a falling region: linear-fractional peaks, and moves that
leave the region) or rectangles; the drives are ideal with friction and a constant load
(the closed forms with constant torques), or two stages of efficiency below one, the
second with output ratings; a return move and a dwell. Compared: the evaluation (with and
without the RMS model, on a subset of the rows), the peak bound, the closed form and the
shortest duration with its checks.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from sizer.laws.registry import make_law
from sizer.laws.row_laws import RowLaws
from sizer.model import Limits, Load, Motor, Stage, Task, Transmission
from sizer.sizing.candidates import Candidates, MotorArrays
from sizer.sizing.move import CycleCalculator
from sizer.sizing.shortest_duration import (
    closed_form_duration,
    has_constant_torques,
    minimum_duration,
)

LAWS = ("trapezoidal(alpha=0.2)", "double_s(alpha=0.3, beta=0.15)", "cycloidal",
        "fifteen_segments(alpha=0.3, beta=0.2, gamma=0.25)", "modified_sinusoidal", "poly5",
        "trapezoidal(alpha=0.45)")
PIECEWISE = (0, 1, 3, 4, 6)
"""The laws with their pieces as data: their power-flow sums in one pass."""

METRICS = ("duration", "max_speed", "peak_torque", "peak_ratio", "rms_torque",
           "thermal_speed", "load_speed", "load_acceleration", "load_jerk", "load_torque")


REGIONS = ("rectangle", "concave", "kinked")
"""The motors' intermittent regions: the ratings alone; falling concave curves (the exact
ratio against them, moves that leave them); every other motor's curve not concave (its
candidates left to the grid search of the peaks)."""


def _motors(rng: np.random.Generator, region: str) -> tuple[Motor, ...]:
    out = []
    for i, t in enumerate(rng.uniform(0.3, 8.0, 13)):
        v_n = 3000 * math.pi / 30
        curve = ((0.0, 3 * t), (0.8 * v_n, 3 * t), (1.4 * v_n, 2.1 * t), (2.0 * v_n, 1.05 * t))
        if region == "kinked" and i % 2:
            curve = ((0.0, 3 * t), (0.5 * v_n, 3 * t), (0.8 * v_n, 1.5 * t),
                     (1.4 * v_n, 1.4 * t), (2.0 * v_n, 0.3 * t))
        curves = {} if region == "rectangle" else {
            "max_speed": 2.0 * v_n, "intermittent_curve": curve,
            "continuous_curve": ((0.0, 1.05 * t), (v_n, t), (2.0 * v_n, 0.5 * t))}
        out.append(Motor(f"m{i}", inertia=2e-5 * t**1.3, continuous_torque=t,
                         peak_torque=3 * t, rated_speed=v_n, **curves))
    return tuple(out)


def _rows(seed: int, region: str, ideal: bool, laws: tuple[int, ...] = tuple(range(len(LAWS)))):
    """Per law its calculator of its rows, and the calculator of all rows (RowLaws)."""
    rng = np.random.default_rng(seed)
    motors = _motors(rng, region)
    if ideal:
        stages = (Stage("gearbox", rng.uniform(3.0, 12.0), 1.0, 1e-4),)
    else:
        stages = (Stage("gearbox", rng.uniform(3.0, 12.0), rng.uniform(0.7, 0.95), 1e-4),
                  Stage("belt", rng.uniform(1.0, 3.0), rng.uniform(0.8, 0.97), 2e-5,
                        rated_output_torque=40.0, peak_output_torque=90.0))
    load = Load(rng.uniform(0.05, 0.6), friction=rng.uniform(0.0, 1.5),
                torque=rng.uniform(-2.0, 2.0))
    task = Task(math.pi / 2, None, dwell=rng.uniform(0.0, 0.3), return_move=True)
    candidates = Candidates.single(MotorArrays.of(motors), load, Transmission(stages))
    chosen = [make_law(LAWS[k]) for k in laws]
    index = rng.integers(0, len(chosen), len(motors))
    index[:len(chosen)] = np.arange(len(chosen))  # every law has rows
    drive, arrays = candidates.drive, candidates.motors
    together = CycleCalculator(None, task, drive, arrays, law=RowLaws(chosen, index))
    alone = []
    for k, law in enumerate(chosen):
        mine = np.flatnonzero(index == k)
        alone.append((mine, CycleCalculator(None, task, drive.take(mine), arrays.subset(mine),
                                            law=law)))
    return together, alone, rng


def _same(ours: np.ndarray, theirs: np.ndarray, mine: np.ndarray, name: str) -> None:
    assert np.array_equal(np.asarray(ours)[mine], theirs, equal_nan=True), name


def _same_metrics(ours, alone, found) -> None:
    for (mine, _), theirs in zip(alone, found, strict=True):
        for name in METRICS:
            _same(getattr(ours, name), getattr(theirs, name), mine, name)
        for a, b in zip(ours.stage_peak + ours.stage_rms, theirs.stage_peak + theirs.stage_rms,
                        strict=True):
            _same(a, b, mine, "stage")


@pytest.mark.parametrize("seed", [0, 1])
@pytest.mark.parametrize("region", REGIONS)
@pytest.mark.parametrize("ideal", [False, True])
def test_the_rows_evaluate_as_their_laws_alone(seed: int, region: str, ideal: bool) -> None:
    together, alone, rng = _rows(seed, region, ideal)
    n = len(together.motors)
    # durations short enough for moves that leave a curved region, long ones too
    for T in (rng.uniform(0.02, 1.5, n), np.full(n, 0.3), np.full(n, 0.05)):
        for model in (False, True):
            ours = together.evaluate(T, model=model)
            found = [calc.evaluate(T[mine], model=model) for mine, calc in alone]
            _same_metrics(ours, alone, found)
            if model:
                later = T * 1.01
                for (mine, _), theirs in zip(alone, found, strict=True):
                    assert ours.rms_model is not None and theirs.rms_model is not None
                    _same(ours.rms_model.rms(later), theirs.rms_model.rms(later[mine]),
                          mine, "rms model")
    # a subset of the rows, repeats included (the searches take the rows still open)
    index = np.array([4, 0, 7, 2, 4, 12])
    T = rng.uniform(0.1, 1.0, len(index))
    ours = together.take(index).evaluate(T)
    for k, (_, calc) in enumerate(alone):
        at = np.flatnonzero(together.law.index[index] == k)
        if len(at):
            place = np.searchsorted(alone[k][0], index[at])
            theirs = calc.take(place).evaluate(T[at])
            assert np.array_equal(ours.rms_torque[at], theirs.rms_torque)
            assert np.array_equal(ours.peak_ratio[at], theirs.peak_ratio)


@pytest.mark.parametrize("seed", [0, 1])
@pytest.mark.parametrize("region", REGIONS)
@pytest.mark.parametrize("ideal", [False, True])
def test_the_rows_bounds_and_shortest_durations_are_their_laws(seed: int, region: str,
                                                                ideal: bool) -> None:
    together, alone, _ = _rows(seed, region, ideal)
    limits = Limits(torque_margin=0.1, speed_margin=0.05, max_jerk=3e4)
    bound = together.peak_bound(limits)
    solution = minimum_duration(together, limits)
    for mine, calc in alone:
        theirs = calc.peak_bound(limits)
        assert bound is not None and theirs is not None
        _same(bound, theirs, mine, "peak bound")
        one = minimum_duration(calc, limits)
        _same(solution.duration, one.duration, mine, "T_min")
        _same(solution.feasible, one.feasible, mine, "feasible")
        for name in ("peak_torque", "rms_torque", "peak_ratio"):
            _same(getattr(solution.metrics, name), getattr(one.metrics, name), mine, name)
        for a, b in zip(solution.checks, one.checks, strict=True):
            _same(a.value, b.value, mine, a.name)
    if ideal:  # friction and a constant load: the closed forms with constant torques
        assert has_constant_torques(together)
        ours = closed_form_duration(together, limits)
        for mine, calc in alone:
            _same(ours, closed_form_duration(calc, limits), mine, "closed form")


def test_one_piece_laws_and_laws_with_their_pieces_as_data_sum_alike() -> None:
    """The power-flow sums of laws all with their pieces as data in one pass over the
    rows (their grids padded into one), the others law by law: both as the laws alone."""
    for laws, one_pass in ((PIECEWISE, True), ((2, 5), False), ((0, 2), False)):
        together, alone, rng = _rows(3, "concave", False, laws)
        T = rng.uniform(0.05, 1.0, len(together.motors))
        ours = together.evaluate(T)
        _same_metrics(ours, alone, [calc.evaluate(T[mine]) for mine, calc in alone])
        assert ("grids" in together.law.shared) == one_pass


def test_a_row_laws_model_samples_no_one_law() -> None:
    together, _, _ = _rows(0, "rectangle", True)
    with pytest.raises(TypeError):
        together.pieces(np.full(len(together.motors), 0.3))


def test_several_laws_grids_refuse_a_law_without_its_pieces_as_data() -> None:
    """Their pieces are numbered across the laws: a law evaluated piece by piece cannot
    join them (its rows' power-flow sums are then summed law by law)."""
    from sizer.sizing.move import GridRows

    with pytest.raises(ValueError):
        GridRows([make_law("trapezoidal(alpha=0.2)"), make_law("poly5")], several=True)


def test_a_cycle_of_row_laws_gives_its_moves_each_rows_law_and_reads_no_one_law() -> None:
    """A cycle of rest-to-rest moves over several laws' rows (SegmentCycle with RowLaws,
    sizer.sizing.engine.rows_cycle): a move naming no law moves with each row's own
    (sizer.sizing.cycle.segment_laws), a move naming one with it; the paths that read one
    law's shape (the cycle's samples, its breakdown) refuse the rows, and cycle_laws
    takes one law only."""
    from sizer.laws import law_choice
    from sizer.model.cycle import Cycle, Dwell, Move
    from sizer.sizing.cycle import SegmentCycle, cycle_laws, segment_laws, single_law

    together, _, _ = _rows(1, "rectangle", True)
    named = make_law("cycloidal")
    cycle = Cycle((Move(0.5, None), Dwell(0.1), Move(-0.5, None, law=law_choice("cycloidal"))),
                  closed=True)
    rows = together.law
    assert isinstance(rows, RowLaws)
    laws = segment_laws(cycle, rows)
    assert laws[0] is rows and laws[1] is None and laws[2] == named
    assert cycle_laws(cycle, named) == (named, None, named)
    assert single_law(named) is named and single_law(None) is None
    with pytest.raises(TypeError):
        single_law(rows)
    model = SegmentCycle(cycle, rows, together.drive, together.motors)
    s = np.full(len(together.motors), 0.4)
    assert np.all(np.isfinite(model.evaluate(s).rms_torque))
    for refused in (model.pieces, model.breakdown):
        with pytest.raises(TypeError):
            refused(s)
