"""Cycle-time allocation (issue 39): ``share: {optimize: rms | energy}`` gives each
candidate motor its own split of a given cycle time among the free moves.

References independent of the allocation:
- the closed form: purely inertial moves by one law, the RMS goal: the sum of h_i^2/T_i^3
  is least for T_i in proportion to sqrt(|h_i|) (Lagrange: 3 h_i^2/T_i^4 equal);
- grids: each split of a grid written as a design with fixed durations and sized by the
  engine (the api), its RMS torque or cycle energy no better than the chosen split's.
"""

from __future__ import annotations

import copy
import math
from pathlib import Path

import numpy as np
import pytest
from cli_run import assert_user_error, run_cli

from sizer import api
from sizer.allocation import allocate
from sizer.laws import law_choice, make_law
from sizer.mechanics import Drive
from sizer.model.cycle import ShareRule
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.cycle import SegmentCycle

MOTOR = {"id": "m1", "inertia": "1e-4 kg*m^2", "continuous_torque": "2 N*m",
         "peak_torque": "6 N*m", "rated_speed": "3000 rpm", "max_speed": "6000 rpm"}
BIG = {**MOTOR, "id": "m2", "inertia": "8e-4 kg*m^2", "continuous_torque": "4 N*m",
       "peak_torque": "12 N*m"}
HEATED = {**MOTOR, "id": "m3", "torque_constant": "0.5 N*m/A", "winding_resistance": "2 ohm",
          "thermal_time_constant": "2 s", "max_winding_temperature_rise": "100 K"}

ANGLES = (30.0, 90.0, 250.0)  # deg
DWELLS = (0.2, 0.1)  # s
CYCLE_TIME = 1.5  # s
FREE = CYCLE_TIME - sum(DWELLS)


def _design(share, load: dict, motors: list[dict], durations=None, laws=("cycloidal",),
            efficiency: float = 1.0, extra: dict | None = None) -> dict:
    """Three moves and two dwells: free with the cycle time (``share``), or each at its
    given duration (a grid point)."""
    moves = [{"move": {"displacement": f"{h} deg", "name": f"m{i}",
                       "duration": "free" if durations is None
                       else f"{float(durations[i])!r} s"}}
             for i, h in enumerate(ANGLES)]
    segments = [moves[0], {"dwell": {"duration": f"{DWELLS[0]} s", "name": "d0"}}, moves[1],
                moves[2], {"dwell": {"duration": f"{DWELLS[1]} s", "name": "d1"}}]
    cycle: dict = {"segments": segments}
    if durations is None:
        cycle.update({"share": share, "cycle_time": f"{CYCLE_TIME} s"})
    return {"name": "allocation", "cycle": cycle, "load": load,
            "transmission": {"type": "gearbox", "ratio": 5, "efficiency": efficiency},
            "laws": list(laws), "motors": motors, **(extra or {})}


def _durations(design: dict, law: str = "cycloidal") -> np.ndarray:
    """The free moves' durations (motors, moves) the engine sizes the design with."""
    d = api.load(copy.deepcopy(design))
    motors = MotorArrays.of(list(d.motors), d.limits.envelope)
    calc = SegmentCycle(d.machine_cycle, make_law(law_choice(law)),
                        Drive(d.load, d.transmission), motors)
    T = calc.durations(np.full(len(motors), calc.given_scale()))
    return np.stack([T[i] for i in (0, 2, 3)], axis=1)


def _record(design: dict, motor: str, law: str = "cycloidal") -> dict:
    rows = api.size(copy.deepcopy(design)).to_records()
    return next(r for r in rows if r["motor"] == motor and r["spec"] == law)


# ------------------------------------------------------------------ closed form
def test_purely_inertial_moves_split_as_sqrt_displacement() -> None:
    """No friction, damping or losses, one law, the RMS goal: T_i = F sqrt(h_i)/sum
    sqrt(h_j) to 1e-9, for every motor (each its own row of the array)."""
    design = _design({"optimize": "rms"}, {"inertia": "0.02 kg*m^2"}, [MOTOR, BIG])
    found = _durations(design)
    root = np.sqrt(ANGLES)
    expected = FREE * root / root.sum()
    assert found.shape == (2, 3)
    np.testing.assert_allclose(found, np.tile(expected, (2, 1)), rtol=1e-9, atol=0.0)


def test_the_search_from_an_equal_start_reaches_the_closed_form() -> None:
    """sizer.allocation alone on E_j = c_j / T^3 (c_j = h_j^2 per candidate, two
    candidates with other displacements), started from an equal split."""
    h = np.array([[1.0, 2.0, 5.0], [0.3, 4.0, 0.5]])

    def cost(j, T, rows):
        return h[rows, j] ** 2 / T**3

    split = allocate(cost, np.array([1.2, 0.7]), np.ones((2, 3)))
    expected = np.sqrt(h) / np.sqrt(h).sum(axis=1)[:, None] * np.array([[1.2], [0.7]])
    assert split.converged.all()
    np.testing.assert_allclose(split.durations, expected, rtol=1e-9, atol=0.0)


def test_a_cost_that_grows_with_time_is_balanced_against_inertia() -> None:
    """E_j = c_j/T^3 + f_j T (inertia and a constant torque's square): the KKT condition
    3 c_j / T_j^4 - f_j equal for every j, checked on the result."""
    c = np.array([[1.0, 0.2, 3.0]])
    f = np.array([[2.0, 30.0, 0.5]])

    def cost(j, T, rows):
        return c[rows, j] / T**3 + f[rows, j] * T

    split = allocate(cost, np.array([2.0]), np.ones((1, 3)))
    T = split.durations[0]
    marginal = -3.0 * c[0] / T**4 + f[0]
    assert split.converged.all() and math.isclose(T.sum(), 2.0, rel_tol=1e-14)
    np.testing.assert_allclose(marginal, marginal.mean(), rtol=1e-8)


# ------------------------------------------------------------------ grids
LOSSY = {"inertia": "0.02 kg*m^2", "friction": "0.6 N*m", "damping": "0.05 N*m*s/rad"}


def _grid(steps: int = 5) -> list[tuple[float, float, float]]:
    """Splits of FREE around the sqrt rule: T_0, T_1 scaled by factors, T_2 the rest."""
    root = np.sqrt(ANGLES)
    base = FREE * root / root.sum()
    out = []
    for a in np.linspace(0.7, 1.3, steps):
        for b in np.linspace(0.7, 1.3, steps):
            t0, t1 = base[0] * a, base[1] * b
            out.append((t0, t1, FREE - t0 - t1))
    return out


def test_the_rms_split_is_no_worse_than_a_grid_of_fixed_splits() -> None:
    """With friction, damping and a lossy gearbox each motor has its own split; its RMS
    torque is no larger than that of every split on a grid sized as a design of fixed
    durations, and the grid's best is within a few per cent above it."""
    optimal = _design({"optimize": "rms"}, LOSSY, [MOTOR, BIG], efficiency=0.85)
    splits = _durations(optimal)
    assert not np.allclose(splits[0], splits[1], rtol=1e-6)  # a split per motor
    np.testing.assert_allclose(splits.sum(axis=1), FREE, rtol=1e-13)
    best = {m: _record(optimal, m)["rms_torque"] for m in ("m1", "m2")}
    grid: dict[str, list[float]] = {"m1": [], "m2": []}
    for t in _grid():
        fixed = _design(None, LOSSY, [MOTOR, BIG], durations=t, efficiency=0.85)
        rows = api.size(fixed).to_records()
        for r in rows:
            assert r["duration"] == pytest.approx(CYCLE_TIME, rel=1e-12)
            assert best[r["motor"]] <= r["rms_torque"] * (1.0 + 1e-12), (t, r["motor"])
            grid[r["motor"]].append(r["rms_torque"])
    for motor, values in grid.items():
        assert min(values) <= best[motor] * 1.01
    # the split itself, as fixed durations, sizes to the same RMS (the engine's figures)
    for row, motor in enumerate(("m1", "m2")):
        again = _design(None, LOSSY, [MOTOR, BIG], durations=tuple(splits[row]),
                        efficiency=0.85)
        assert _record(again, motor)["rms_torque"] == pytest.approx(best[motor], rel=1e-12)


def test_the_energy_split_is_no_worse_than_a_grid_of_fixed_splits() -> None:
    """The energy goal (shaft work plus copper loss) against the engine's cycle energy of
    every grid split (the braking check makes the engine report it)."""
    extra = {"limits": {"braking_resistor_power": "1000 W"}}
    optimal = _design({"optimize": "energy"}, LOSSY, [HEATED], efficiency=0.85, extra=extra)
    best = _record(optimal, "m3")["cycle_energy"]
    assert math.isfinite(best)
    grid = []
    for t in _grid(3):
        fixed = _design(None, LOSSY, [HEATED], durations=t, efficiency=0.85, extra=extra)
        grid.append(_record(fixed, "m3")["cycle_energy"])
    # the engine's cycle energy is sampled (piecewise-linear power): equal to 1e-6
    assert best <= min(grid) * (1.0 + 1e-6)
    assert min(grid) <= best * 1.05


def _saw(share, durations=None) -> dict:
    """A flying saw (moves with boundary speeds, a run, a dwell): its three moves free
    with a cycle time of 1.2 s, or at given durations."""
    speeds = [{"end_speed": "0.5 m/s"}, {"start_speed": "0.5 m/s"}, {}]
    moves = [{"move": {"displacement": h, **v, "duration": "free" if durations is None
                       else f"{float(durations[i])!r} s"}}
             for i, (h, v) in enumerate(zip(("150 mm", "100 mm", "-450 mm"), speeds,
                                            strict=True))]
    cycle: dict = {"closed": True, "segments": [
        moves[0], {"run": {"speed": "0.5 m/s", "duration": "0.4 s", "force": "120 N"}},
        moves[1], moves[2], {"dwell": {"duration": "0.1 s"}}]}
    if durations is None:
        cycle.update({"share": share, "cycle_time": "1.2 s"})
    return {"name": "saw", "cycle": cycle, "load": {"mass": "25 kg", "friction": "30 N"},
            "transmission": [{"type": "belt", "ratio": 3, "efficiency": 0.95},
                             {"type": "rack_pinion", "pitch_radius": "30 mm",
                              "efficiency": 0.95}],
            "laws": ["trapezoidal(alpha=1/3)"], "motors": [MOTOR]}


def test_moves_with_boundary_speeds_against_a_grid() -> None:
    """Moves between speeds (exact piecewise polynomials of each duration) take the same
    search: no split of a grid around the optimum is better."""
    law = "trapezoidal(alpha=1/3)"
    d = api.load(_saw({"optimize": "rms"}))
    motors = MotorArrays.of(list(d.motors), d.limits.envelope)
    calc = SegmentCycle(d.machine_cycle, make_law(law_choice(law)),
                        Drive(d.load, d.transmission), motors)
    T = calc.durations(np.full(1, calc.given_scale()))
    split = np.array([T[0][0], T[2][0], T[3][0]])
    assert split.sum() == pytest.approx(0.7, rel=1e-13)
    best = _record(_saw({"optimize": "rms"}), "m1", law)["rms_torque"]
    values = []
    for a in (0.9, 1.0, 1.1):
        for b in (0.9, 1.0, 1.1):
            t = (split[0] * a, split[1] * b, 0.7 - split[0] * a - split[1] * b)
            values.append(_record(_saw(None, t), "m1", law)["rms_torque"])
            assert best <= values[-1] * (1.0 + 1e-12), t
    assert values[4] == pytest.approx(best, rel=1e-12)  # the split itself, fixed
    assert best < _record(_saw("sqrt_displacement"), "m1", law)["rms_torque"]


def test_without_k_t_or_r_the_energy_goal_is_the_rms_goal() -> None:
    """A motor without k_t and R has no copper loss to weigh: its split is the RMS one."""
    rms = _durations(_design({"optimize": "rms"}, LOSSY, [MOTOR], efficiency=0.85))
    energy = _durations(_design({"optimize": "energy"}, LOSSY, [MOTOR], efficiency=0.85))
    np.testing.assert_allclose(energy, rms, rtol=1e-14)


def test_per_candidate_weights_are_an_array_axis() -> None:
    """SegmentCycle with weights (candidates, segments): each row as a fixed rule of the
    same weights (a cycle of one candidate each) gives the same RMS."""
    d = api.load(_design("weights", LOSSY, [MOTOR, BIG], efficiency=0.85))
    motors = MotorArrays.of(list(d.motors), d.limits.envelope)
    law = make_law(law_choice("cycloidal"))
    drive = Drive(d.load, d.transmission)
    rows = np.array([[1.0, 0.0, 1.5, 0.5, 0.0], [0.5, 0.0, 1.0, 1.5, 0.0]])
    both = SegmentCycle(d.machine_cycle, law, drive, motors, weights=rows)
    s = np.full(2, both.given_scale())
    rms = both.evaluate(s).rms_torque
    for i, w in enumerate(rows):
        one = SegmentCycle(d.machine_cycle, law, drive, motors.subset(np.array([i])),
                           weights=w[None])
        assert one.evaluate(s[:1]).rms_torque[0] == pytest.approx(rms[i], rel=1e-14)
    assert both.take(np.array([1])).split is not None


# ------------------------------------------------------------------ inputs
def _write(tmp_path: Path, design: dict) -> Path:
    import yaml

    path = tmp_path / "design.yaml"
    path.write_text(yaml.safe_dump(design, sort_keys=False), encoding="utf-8")
    return path


def test_an_optimized_share_without_a_cycle_time_is_refused(tmp_path: Path) -> None:
    design = _design({"optimize": "rms"}, LOSSY, [MOTOR])
    del design["cycle"]["cycle_time"]
    path = _write(tmp_path, design)
    line = assert_user_error(run_cli("size", str(path)), "cycle.share", "cycle_time")
    share_line = 1 + path.read_text().splitlines().index(
        next(x for x in path.read_text().splitlines() if x.strip().startswith("share:")))
    assert f"design.yaml:{share_line}:" in line


@pytest.mark.parametrize(("share", "fragments"), [
    ({"optimize": "vibration"}, ("cycle.share", "load.natural_frequency")),
    ({"optimize": "speed"}, ("cycle.share", "rms or energy or vibration")),
    ("optimal", ("cycle.share", "sqrt_displacement", "{optimize: rms | energy | vibration}")),
])
def test_bad_shares_are_refused(tmp_path: Path, share, fragments) -> None:
    path = _write(tmp_path, _design(share, LOSSY, [MOTOR]))
    assert_user_error(run_cli("size", str(path)), *fragments)


def test_the_share_reads_as_its_rule() -> None:
    d = api.load(_design({"optimize": "energy"}, LOSSY, [MOTOR]))
    assert d.machine_cycle.share is ShareRule.OPTIMIZE_ENERGY
    assert d.machine_cycle.share.goal == "energy" and ShareRule.EQUAL.goal is None


@pytest.mark.parametrize(("share", "valid"), [
    ({"optimize": "rms"}, True), ({"optimize": "energy"}, True), ("weights", True),
    ({"optimize": "vibration"}, True), ({"optimize": "rms", "x": 1}, False),
])
def test_the_json_schema_describes_the_share(share, valid: bool) -> None:
    from jsonschema import Draft202012Validator

    from sizer.io.loader import design_schema

    data = _design(share, LOSSY, [MOTOR])
    errors = list(Draft202012Validator(design_schema()).iter_errors(data))
    assert (not errors) is valid, errors
