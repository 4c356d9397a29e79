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


# ------------------------------------------------------------ ranked by the engine
def _per_move(goal: str = "rms", **changes) -> dict:
    design = _design()
    design["cycle"]["share"] = {"optimize": goal, "laws": "per_move"}
    design.update(changes)
    return design


def _written(design: dict, combo: tuple[str, ...]) -> dict:
    """``design`` with the moves that name no law naming those of ``combo`` in order and
    the share's goal without the law choice: one fixed combination, sized on its own."""
    out = copy.deepcopy(design)
    laws = iter(combo)
    for segment in out["cycle"]["segments"]:
        move = segment.get("move")
        if move is not None and "law" not in move:
            move["law"] = next(laws)
    out["cycle"]["share"] = {"optimize": out["cycle"]["share"]["optimize"]}
    return out


def _by_motor(design: dict) -> dict[str, dict]:
    return {r["motor"]: r for r in api.size(copy.deepcopy(design)).to_records()}


FIGURES = ("duration", "peak_torque", "rms_torque", "max_speed", "load_torque")


def _assert_best_of_written(design: dict, open_moves: int, goal: str) -> dict[str, dict]:
    """Each motor's row is the best of the combinations each sized on its own (the goal's
    figure least), with that combination's laws and every figure of its row."""
    ranked = _by_motor(design)
    written = {combo: _by_motor(_written(design, combo))
               for combo in itertools.product(LAWS, repeat=open_moves)}
    figure = "rms_torque" if goal == "rms" else "cycle_energy"
    for motor, row in ranked.items():
        best = min(written, key=lambda c: written[c][motor][figure])
        expected = written[best][motor]
        laws = [make_law(law_choice(x)).spec for x in best]
        spec = laws[0] if len(set(laws)) == 1 else f"per_move({'; '.join(laws)})"
        assert row["spec"] == spec, (motor, row["spec"], best)
        assert row["feasible"] == expected["feasible"]
        for name in (*FIGURES, figure):
            assert row[name] == pytest.approx(expected[name], rel=1e-9), (motor, name)
        for check, other in zip(row["checks"], expected["checks"], strict=True):
            assert check["name"] == other["name"]
            assert check["margin"] == pytest.approx(other["margin"], rel=1e-9, abs=1e-12)
    return ranked


def test_each_motor_ranks_the_best_of_every_written_combination() -> None:
    """``share: {optimize: rms, laws: per_move}``: every motor's one row is the combination
    of laws (with its split) of least RMS among all 2^3 combinations, each written as a
    design of its own and sized separately (its split found by the engine for those
    laws); here the motors choose differently, one of them a law per move."""
    ranked = _assert_best_of_written(_per_move(), 3, "rms")
    assert ranked["m1"]["law"] == "per_move"
    assert {r["spec"] for r in ranked.values()} != {ranked["m1"]["spec"]}


def test_a_move_of_fixed_duration_takes_its_best_law_too() -> None:
    """A move with a given duration and no law of its own gets the law of least RMS at
    that duration (its term does not depend on the split): still the best of every
    written combination."""
    design = _per_move()
    design["cycle"]["segments"][2]["move"]["duration"] = "0.45 s"
    _assert_best_of_written(design, 3, "rms")


def test_the_energy_goal_chooses_the_laws_of_least_energy() -> None:
    """``{optimize: energy, laws: per_move}`` with motors that give k_t and R (a copper
    loss to weigh): each row the combination of least energy per cycle."""
    electrical = {"torque_constant": "0.6 N*m/A", "winding_resistance": "2.5 ohm"}
    design = _per_move("energy", motors=[{**MOTOR, **electrical}, {**BIG, **electrical}],
                       limits={"braking_resistor_power": "100 W"})  # the energy figures
    _assert_best_of_written(design, 3, "energy")


def test_a_pair_with_a_law_per_move_is_broken_down_and_exported(tmp_path) -> None:
    """`sizer segments` and `sizer cam` of the best pair read its laws and split: each
    move's law and start time as the written combination's."""
    import json

    import yaml
    from cli_run import run_cli

    design = _per_move()
    path = tmp_path / "design.yaml"
    path.write_text(yaml.safe_dump(design, sort_keys=False), encoding="utf-8")
    got = run_cli("segments", str(path), "--motor", "m1", "--format", "json")
    assert got.returncode == 0, got.stderr
    rows = json.loads(got.stdout)["segments"]
    combo = tuple(r["law"] for r in rows if r["kind"] == "move")
    assert len(set(combo)) > 1
    written = tmp_path / "written.yaml"
    written.write_text(yaml.safe_dump(_written(design, combo), sort_keys=False),
                       encoding="utf-8")
    again = run_cli("segments", str(written), "--motor", "m1", "--format", "json")
    assert again.returncode == 0, again.stderr
    for row, other in zip(rows, json.loads(again.stdout)["segments"], strict=True):
        assert row["law"] == other["law"]
        assert row["start"] == pytest.approx(other["start"], rel=1e-9, abs=1e-12)
    cam = run_cli("cam", str(path), "--motor", "m1", "--to", "csv",
                  "--output", str(tmp_path / "cam.csv"))
    assert cam.returncode == 0, cam.stderr
    assert all(law in cam.stdout + cam.stderr for law in combo)


@pytest.mark.parametrize(("share", "field", "fragments"), [
    ({"optimize": "vibration", "laws": "per_move"}, "cycle.share", ("per_move", "rms")),
    ({"optimize": "rms", "laws": "all"}, "cycle.share", ("per_move",)),
])
def test_a_law_per_move_needs_a_sum_goal(tmp_path, share, field, fragments) -> None:
    import yaml
    from cli_run import assert_user_error, run_cli

    design = _design()
    design["cycle"]["share"] = share
    path = tmp_path / "design.yaml"
    path.write_text(yaml.safe_dump(design, sort_keys=False), encoding="utf-8")
    assert_user_error(run_cli("size", str(path)), field, *fragments)


def test_a_law_per_move_pair_keeps_its_laws_for_its_sensitivities() -> None:
    """The sensitivities of a pair with a law per move are those of the design with its
    laws written in (the laws a discrete choice, kept; the split found again for each
    perturbed design, as with one law)."""
    from sizer.sensitivity import sensitivity

    design = api.load(_per_move())
    got = sensitivity(design, "m1")
    assert got.result.law == "per_move"
    combo = tuple(got.result.law_object.laws[k].spec for k in range(3))
    written = sensitivity(api.load(_written(_per_move(), combo)), "m1")
    assert len(got.inputs) == len(written.inputs)
    expected = {item.name: item for item in written.inputs}
    for item in got.inputs:
        other = expected[item.name]
        for check, slope in item.slopes.items():
            for side in ("central", "minus", "plus"):
                assert getattr(slope, side) == pytest.approx(
                    getattr(other.slopes[check], side), rel=1e-9, abs=1e-12), (item.name,
                                                                                check)


def test_robust_margins_of_a_law_per_move_are_the_least_over_the_corners() -> None:
    """Each corner (a build of the machine) chooses its laws per move again, as the
    nominal sizing does: the worst-case margins are the least over the four corner designs
    each sized separately."""
    from sizer.robust import robust_sizing

    def with_load(inertia: float, damping: float, tolerances: bool = False) -> dict:
        d = _per_move()
        tol = " +- 20 %" if tolerances else ""
        d["load"]["inertia"] = f"{inertia!r} kg*m^2{tol}"
        d["load"]["damping"] = f"{damping!r} N*m*s/rad" + (" +- 50 %" if tolerances else "")
        return d

    design = api.load(with_load(0.005, 0.4, tolerances=True))
    robust = robust_sizing(design, api.size(design))
    corners = [_by_motor(with_load(0.005 * a, 0.4 * b)) for a in (0.8, 1.2)
               for b in (0.5, 1.5)]
    for result in robust.results:
        motor = result.nominal.motor
        for check, worst in result.worst.items():
            least = min(next(c["margin"] for c in corner[motor]["checks"]
                             if c["name"] == check) for corner in corners)
            assert worst == pytest.approx(least, rel=1e-9, abs=1e-12), (motor, check)


def test_a_diff_of_laws_per_move_pairs_each_motor_with_itself(tmp_path) -> None:
    """`sizer diff` keys a law-per-move sizing's rows by motor (each has one row, whatever
    laws it took): a change of damping that changes a motor's laws is a changed pair whose
    spec changed, with the rows of the two sizings run on their own."""
    import json

    import yaml
    from cli_run import run_cli

    a, b = _per_move(), _per_move()
    b["load"]["damping"] = "0.5 N*m*s/rad"
    paths = []
    for name, design in (("a.yaml", a), ("b.yaml", b)):
        path = tmp_path / name
        path.write_text(yaml.safe_dump(design, sort_keys=False), encoding="utf-8")
        paths.append(str(path))
    got = run_cli("diff", *paths, "--format", "json")
    assert got.returncode == 0, got.stderr
    pairs = {p["motor"]: p for p in json.loads(got.stdout)["pairs"]}
    rows_a, rows_b = _by_motor(a), _by_motor(b)
    assert set(pairs) == {"m1", "m2"}
    for motor, pair in pairs.items():
        assert pair["status"] == "changed" and pair["law"] == "per_move"
        changes = {c["field"]: c for c in pair["changes"]}
        assert changes["rms_torque"]["before"] == rows_a[motor]["rms_torque"]
        assert changes["rms_torque"]["after"] == rows_b[motor]["rms_torque"]
        if rows_a[motor]["spec"] != rows_b[motor]["spec"]:
            assert changes["spec"]["after"] == rows_b[motor]["spec"]
    assert rows_a["m2"]["spec"] != rows_b["m2"]["spec"]  # the case the key is for


def test_the_laws_per_move_are_chosen_in_bounded_chunks(monkeypatch) -> None:
    """The search of each candidate's laws runs in chunks of candidates (memory bounded
    whatever the catalog): one candidate a chunk gives the same rows."""
    import sizer.sizing.engine as engine

    whole = _by_motor(_per_move())
    monkeypatch.setattr(engine, "_rows_per_candidate", lambda cycle, laws: 10**9)
    for motor, row in _by_motor(_per_move()).items():
        assert row == whole[motor]
