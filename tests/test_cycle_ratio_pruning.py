"""The ratio search leaves out options that cannot win for a cycle of segments too
(issue 11 on issue 12's engine): the floor from the free moves' peak bounds
(sizer.sizing.duration_floor._cycle_floor), the RMS test on the cycle's model
(sizer.sizing.rms_fails_up_to._cycle_fails_up_to), and the RMS lower bound that skips
the search where no scale can pass (SegmentCycle.rms_lower_bound).

- The choice with options left out equals the choice from every option evaluated, to
  the bit, on random designs written as cycles of segments (their dwell split in two, so
  no shorthand applies).
- The floor is below every feasible cycle time, and the cycle's checks fail just below it.
- Where the RMS test says the check fails up to a cycle time, the cycle's RMS check fails
  at every shorter one on a grid (and the test says so for some options, not for all).
- The RMS lower bound holds at every scale, with dwells holding a load, a run, a fixed
  move and segment loads.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from test_ratio_search_pruning import (
    all_pairs,
    evaluated_in_full,
    floor_below_feasible,
    same,
    wide_design,
)

from sizer.laws import make_law
from sizer.model.cycle import Cycle, Dwell, Move, Run, SegmentLoad
from sizer.model.domain import Limits, Load, Motor, Stage, Transmission
from sizer.sizing.candidates import Candidates, MotorArrays
from sizer.sizing.checks import TOLERANCE, evaluate_checks, feasible
from sizer.sizing.choices import choose_ratio
from sizer.sizing.cycle import SegmentCycle
from sizer.sizing.engine import evaluate_law, evaluate_spec, rms_fails_up_to


def as_cycle(design):
    """The design's task as a cycle of segments with its dwell split (minimize mode)."""
    task = design.task
    dwell = task.dwell if task.dwell > 0 else 0.1
    segments: list = [Move(task.displacement, None), Dwell(dwell / 4), Dwell(3 * dwell / 4)]
    if task.return_move:
        segments += [Move(-task.displacement, None), Dwell(dwell)]
    return dataclasses.replace(design, cycle=Cycle(tuple(segments), linear=task.linear))


def calculator_of(design, spec, pairs) -> SegmentCycle:
    return SegmentCycle(design.cycle, make_law(spec), pairs.drive, pairs.motors,
                        design.limits.thermal_speed)


@pytest.mark.parametrize("seed", range(6))
def test_the_pruned_choice_equals_evaluating_every_option(seed):
    design = as_cycle(wide_design(seed))
    arrays = MotorArrays.of(design.motors, design.limits.envelope)
    for spec in design.laws:
        every = choose_ratio(design, arrays, lambda c, spec=spec: evaluate_law(design, spec, c))
        pruned = evaluate_spec(design, spec, arrays)
        assert [pruned.transmissions[k] for k in pruned.option] == \
            [every.transmissions[k] for k in every.option], spec
        assert same(pruned.stage_ratio, every.stage_ratio), spec
        assert same(pruned.feasible, every.feasible), spec
        for name, value in every.figures.items():
            assert same(pruned.figures[name], value), (spec, name)
        assert same(pruned.slacks, every.slacks), spec


def test_options_are_left_out(monkeypatch):
    evaluated, total = evaluated_in_full(
        monkeypatch, [as_cycle(wide_design(seed)) for seed in range(4)])
    assert evaluated < 0.6 * total, (evaluated, total)


@pytest.mark.parametrize("seed", range(6))
def test_the_floor_is_below_every_feasible_cycle_time(seed):
    design = as_cycle(wide_design(seed))
    pairs, _, _ = all_pairs(design)
    checked = 0
    for spec in design.laws:
        floor = floor_below_feasible(design, spec, pairs)
        calc = calculator_of(design, spec, pairs)
        rows = np.flatnonzero(np.isfinite(floor) & (floor > calc.cycle_time(np.zeros(1))))
        if not len(rows):
            continue
        sub = calc.take(rows)
        below = sub.evaluate(sub.scale_of(floor[rows]) * (1.0 - 1e-7))
        checks = evaluate_checks(below, sub.motors, sub.drive, design.limits, False)
        assert not feasible(checks).any(), spec
        checked += len(rows)
    assert checked >= 10


@pytest.mark.parametrize("seed", range(6))
def test_rms_fails_up_to_means_failing_at_every_shorter_cycle_time(seed):
    design = as_cycle(wide_design(seed))
    pairs, motor, _ = all_pairs(design)
    said = {True: 0, False: 0}
    margin = 1.0 - design.limits.torque_margin + TOLERANCE
    for spec in design.laws:
        table = evaluate_law(design, spec, pairs)
        # the cycle times the ratio search asks about: another option's best
        T = np.roll(table.figures["duration"], 1)
        calc = calculator_of(design, spec, pairs)
        T = np.where(np.isfinite(T), T, calc.cycle_time(np.full(len(T), 0.1)))
        fails = rms_fails_up_to(design, spec, pairs, T, motor)
        said[True] += int(fails.sum())
        said[False] += int((~fails).sum())
        rows = np.flatnonzero(fails)
        if not len(rows):
            continue
        sub = calc.take(rows)
        scale = sub.scale_of(T[rows])
        for factor in np.geomspace(0.25, 1.0, 6):
            m = sub.evaluate(scale * factor, peaks=False)
            limit = sub.motors.continuous.limit_clipped(m.thermal_speed)
            assert np.all(m.rms_torque > margin * limit), (spec, factor)
    assert said[True] >= 3 and said[False] >= 3, said


@pytest.mark.parametrize("seed", range(8))
def test_the_rms_lower_bound_holds_at_every_scale(seed):
    rng = np.random.default_rng(seed)
    motors = MotorArrays.of([Motor(f"m{i}", 1e-4 * (i + 1), 0.5 + i, 1.5 + 3 * i, 300.0)
                             for i in range(4)], "linear")
    load = Load(0.02, damping=float(rng.uniform(0, 0.02)), friction=float(rng.uniform(0, 0.4)),
                torque=float(rng.uniform(-0.6, 0.6)))
    stages = (Stage("gearbox", float(rng.uniform(4, 12)), float(rng.uniform(0.85, 1.0)), 2e-5),)
    heavy = SegmentLoad(inertia=float(rng.uniform(0, 0.05)), torque=float(rng.uniform(0, 0.5)))
    segments = (Move(1.2, None, load=heavy), Dwell(0.1, load=heavy), Run(2.0, 0.05),
                Move(0.4, 0.08), Move(-1.6, None), Dwell(float(rng.uniform(0.05, 0.3))))
    cycle = Cycle(segments)
    pairs = Candidates.single(motors, load, Transmission(stages))
    for spec in ("cycloidal", "trapezoidal(alpha=1/3)", "poly5"):
        calc = SegmentCycle(cycle, make_law(spec), pairs.drive, pairs.motors, "max")
        bound = calc.rms_lower_bound()
        assert bound is not None and np.all(bound > 0.0)
        for s in np.geomspace(0.02, 50.0, 25):
            rms = calc.evaluate(np.full(len(motors), s), peaks=False).rms_torque
            assert np.all(rms >= bound * (1.0 - 1e-12)), (spec, s)


def test_a_held_load_the_rating_cannot_carry_is_not_searched(monkeypatch):
    """Dwells holding 3 N*m at the load through 10:1 (0.3 N*m and more at the motor) for
    most of the cycle, a motor rated 0.1 N*m: no scale passes the RMS check, and the
    search is skipped (the candidate infeasible with the RMS check failing)."""
    import sizer.sizing.shortest_duration as md

    calls = []
    original = md.bisect_duration
    monkeypatch.setattr(md, "bisect_duration",
                        lambda *a, **k: calls.append(1) or original(*a, **k))
    motor = Motor("small", 1e-5, 0.1, 0.3, 300.0)
    load = Load(0.001, torque=3.0)
    cycle = Cycle((Move(0.5, None), Dwell(2.0), Move(-0.5, None), Dwell(2.0)))
    pairs = Candidates.single(MotorArrays.of([motor], "book"), load,
                              Transmission((Stage("gearbox", 10.0, 0.9, 0.0),)))
    calc = SegmentCycle(cycle, make_law("cycloidal"), pairs.drive, pairs.motors, "max")
    solution = md.minimum_duration(calc, Limits())
    assert not solution.feasible[0]
    assert not calls
    rms = next(c for c in solution.checks if c.name == "rms")
    assert not rms.passed[0]
