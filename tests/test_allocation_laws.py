"""A law per free move with the cycle-time split (issue 39: "choose each move's law from
the design's list"): SegmentCycle.law_split and sizer.allocation.allocate_laws.

Reference independent of the search: every combination of the design's laws over the
free moves times every split of a grid, each written as a fixed design (every move names
its law, every row its durations: SegmentCycle's per-row weights, a cycle of one
candidate each) and evaluated by the engine; the chosen laws and split are no worse than
any, for every motor. One combination is also sized through the api as a written design
with fixed durations: the same RMS.
"""

from __future__ import annotations

import copy
import itertools
from dataclasses import replace

import numpy as np
import pytest

from sizer import allocation, api
from sizer.allocation import allocate_laws
from sizer.laws import law_choice, make_law
from sizer.mechanics import Drive
from sizer.model.cycle import Move
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.cycle import SegmentCycle

MOTOR = {"id": "m1", "inertia": "1e-4 kg*m^2", "continuous_torque": "2 N*m",
         "peak_torque": "6 N*m", "rated_speed": "3000 rpm", "max_speed": "6000 rpm"}
BIG = {**MOTOR, "id": "m2", "inertia": "8e-4 kg*m^2"}
LAWS = ("harmonic", "trapezoidal(alpha=0.1)")
CYCLE_TIME, DWELL = 1.6, 0.2
FREE = (0, 2, 3)  # the free moves' segments


def _design(durations=None, laws=(None, None, None)) -> dict:
    """Three moves and a dwell; the first move carries a heavy part (its inertial term
    dominates: a law of low RMS acceleration), the load has damping (a law of low RMS
    speed for the others): the best law differs by move and by motor."""
    given = [("90 deg", "0.3 kg*m^2"), ("180 deg", None), ("-270 deg", None)]
    moves = []
    for k, (h, inertia) in enumerate(given):
        move: dict = {"displacement": h, "name": f"m{k}",
                      "duration": "free" if durations is None else f"{durations[k]!r} s"}
        if inertia:
            move["inertia"] = inertia
        if laws[k] is not None:
            move["law"] = laws[k]
        moves.append({"move": move})
    segments = [moves[0], {"dwell": {"duration": f"{DWELL} s", "name": "d"}}, *moves[1:]]
    cycle: dict = {"segments": segments}
    if durations is None:
        cycle.update({"share": {"optimize": "rms"}, "cycle_time": f"{CYCLE_TIME} s"})
    return {"name": "laws per move", "cycle": cycle,
            "load": {"inertia": "0.005 kg*m^2", "damping": "0.4 N*m*s/rad",
                     "friction": "0.2 N*m"},
            "transmission": {"type": "gearbox", "ratio": 5, "efficiency": 0.9},
            "laws": list(LAWS), "motors": [MOTOR, BIG]}


def _setup():
    d = api.load(_design())
    motors = MotorArrays.of(list(d.motors), d.limits.envelope)
    laws = tuple(make_law(law_choice(x)) for x in LAWS)
    drive = Drive(d.load, d.transmission)
    return d, motors, laws, drive


def _fixed_rms(d, motors, drive, motor: int, combo, splits: np.ndarray) -> np.ndarray:
    """The RMS torque of ``motor`` for each split (k, 3) with the moves by the laws of
    ``combo``: the engine with each row a fixed split (per-row weights)."""
    segments = list(d.machine_cycle.segments)
    for i, name in zip(FREE, combo, strict=True):
        move = segments[i]
        assert isinstance(move, Move)
        segments[i] = replace(move, law=law_choice(name))
    cycle = replace(d.machine_cycle, segments=tuple(segments))
    k = len(splits)
    weights = np.tile(np.array(cycle.weights()), (k, 1))
    s = (CYCLE_TIME - DWELL) / weights[0].sum()
    weights[:, list(FREE)] = splits / s
    calc = SegmentCycle(cycle, None, drive, motors.subset(np.full(k, motor)),
                        weights=weights)
    return calc.evaluate(np.full(k, s)).rms_torque


def _grid(steps: int) -> np.ndarray:
    F = CYCLE_TIME - DWELL
    out = [(a, b, steps - a - b) for a in range(1, steps) for b in range(1, steps - a)]
    return np.array(out, dtype=float) * (F / steps)


def test_the_laws_and_split_are_no_worse_than_every_combination_on_a_grid() -> None:
    d, motors, laws, drive = _setup()
    found = SegmentCycle(d.machine_cycle, laws[0], drive, motors).law_split(laws)
    np.testing.assert_allclose(found.durations.sum(axis=1), CYCLE_TIME - DWELL, rtol=1e-13)
    assert found.converged.all()
    assert len({tuple(row) for row in found.laws}) == 2  # each motor its own choice
    assert any(len(set(row)) > 1 for row in found.laws)  # a law per move
    grid = _grid(14)
    for motor in range(2):
        chosen = tuple(LAWS[k] for k in found.laws[motor])
        best = _fixed_rms(d, motors, drive, motor, chosen, found.durations[motor][None])[0]
        for combo in itertools.product(LAWS, repeat=3):
            rms = _fixed_rms(d, motors, drive, motor, combo, grid)
            assert best <= rms.min() * (1.0 + 1e-12), (motor, combo)
        # around the split, with the chosen laws: no better either
        near = found.durations[motor] * np.array(
            [[1.0 + a, 1.0 + b, 1.0] for a in (-0.02, 0.0, 0.02) for b in (-0.02, 0.0, 0.02)])
        near[:, 2] = CYCLE_TIME - DWELL - near[:, 0] - near[:, 1]
        assert best <= _fixed_rms(d, motors, drive, motor, chosen, near).min() \
            * (1.0 + 1e-12)


def test_a_chosen_combination_sized_as_a_written_design() -> None:
    """The first motor's laws and split written as a design of fixed durations and laws,
    sized by the api: the RMS the reference computes."""
    d, motors, laws, drive = _setup()
    found = SegmentCycle(d.machine_cycle, laws[0], drive, motors).law_split(laws)
    chosen = tuple(LAWS[k] for k in found.laws[0])
    written = _design(durations=tuple(float(t) for t in found.durations[0]), laws=chosen)
    rows = api.size(copy.deepcopy(written)).to_records()
    rms = next(r["rms_torque"] for r in rows if r["motor"] == "m1")
    expected = _fixed_rms(d, motors, drive, 0, chosen, found.durations[0][None])[0]
    assert rms == pytest.approx(expected, rel=1e-9)


def test_many_combinations_alternate_laws_and_split(monkeypatch) -> None:
    """Above COMBINATIONS the laws and split are chosen in turn from the best single law:
    never worse than it, and here it reaches the enumeration's choice."""
    d, motors, laws, drive = _setup()
    calc = SegmentCycle(d.machine_cycle, laws[0], drive, motors)
    every = calc.law_split(laws)
    monkeypatch.setattr(allocation, "COMBINATIONS", 1)
    turns = calc.law_split(laws)
    single = [calc.law_split((law,)).goal for law in laws]
    assert (turns.goal <= np.min(single, axis=0) * (1.0 + 1e-12)).all()
    np.testing.assert_allclose(turns.goal, every.goal, rtol=1e-9)


def test_allocate_laws_on_closed_forms() -> None:
    """Terms c_jl / T^3 (purely inertial moves, law l's coefficient): the best law of each
    move is the least c_jl, the split T_j ~ c_jl^(1/4) (Lagrange: 3 c_j / T_j^4 equal),
    F = 1."""
    c = np.array([[4.0, 1.0], [1.0, 9.0], [2.0, 2.5]])  # (moves, laws)

    def cost(j: int, law: int, T: np.ndarray, rows: np.ndarray) -> np.ndarray:
        return c[j, law] / T**3

    found = allocate_laws(cost, 2, np.ones(1), np.ones((1, 3)))
    np.testing.assert_array_equal(found.laws[0], [1, 0, 0])
    best = np.array([1.0, 1.0, 2.0]) ** 0.25
    np.testing.assert_allclose(found.durations[0], best / best.sum(), rtol=1e-9)


def test_law_split_needs_an_rms_or_energy_goal() -> None:
    d, motors, laws, drive = _setup()
    cycle = replace(d.machine_cycle, cycle_time=None)
    with pytest.raises(ValueError, match="rms or energy"):
        SegmentCycle(cycle, laws[0], drive, motors).law_split(laws)


def test_a_law_per_move_in_the_file_is_refused_as_not_yet(tmp_path) -> None:
    """The engine does not rank by a law per move yet: the file says so at its line."""
    import yaml
    from cli_run import assert_user_error, run_cli

    design = _design()
    design["cycle"]["share"] = {"optimize": "rms", "laws": "per_move"}
    path = tmp_path / "design.yaml"
    path.write_text(yaml.safe_dump(design, sort_keys=False), encoding="utf-8")
    assert_user_error(run_cli("size", str(path)), "cycle.share", "per_move", "not yet")
