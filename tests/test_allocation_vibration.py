"""``share: {optimize: vibration}`` (issue 39): the split of a given cycle time among the
free moves that minimizes the largest residual vibration over the moves, one for all
motors (the residual depends on the laws and durations only).

Reference independent of the search: a dense grid of splits, each evaluated with the
cycle's residual (sizer.vibration.cycle_residual.CycleVibration) directly; the search
is no worse than the grid's best, and the sizing's residual figure is the residual at
the split.
"""

from __future__ import annotations

import copy
from pathlib import Path

import numpy as np
import pytest
from cli_run import assert_user_error, run_cli

from sizer import api
from sizer.allocation import minimax_split
from sizer.laws import law_choice, make_law
from sizer.mechanics import Drive
from sizer.model.cycle import ShareRule
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.cycle import SegmentCycle, cycle_laws
from sizer.vibration.cycle_residual import CycleVibration

MOTOR = {"id": "m1", "inertia": "1e-4 kg*m^2", "continuous_torque": "2 N*m",
         "peak_torque": "6 N*m", "rated_speed": "3000 rpm", "max_speed": "6000 rpm"}
BIG = {**MOTOR, "id": "m2", "inertia": "8e-4 kg*m^2", "continuous_torque": "4 N*m",
       "peak_torque": "12 N*m"}
MODE = {"inertia": "0.02 kg*m^2", "friction": "0.3 N*m", "natural_frequency": "6 Hz",
        "damping_ratio": 0.03}
DWELLS = (0.2, 0.1)  # s


def _design(angles: tuple[float, ...], cycle_time: float, law: str = "cycloidal",
            share=None, load: dict | None = None) -> dict:
    """Free moves of ``angles`` (deg), a dwell after the first and after the last."""
    moves = [{"move": {"displacement": f"{h} deg", "name": f"m{i}", "duration": "free"}}
             for i, h in enumerate(angles)]
    segments = [moves[0], {"dwell": {"duration": f"{DWELLS[0]} s", "name": "d0"}},
                *moves[1:], {"dwell": {"duration": f"{DWELLS[1]} s", "name": "d1"}}]
    return {"name": "vibration split",
            "cycle": {"share": share or {"optimize": "vibration"},
                      "cycle_time": f"{cycle_time} s", "segments": segments},
            "load": copy.deepcopy(load or MODE),
            "transmission": {"type": "gearbox", "ratio": 5},
            "laws": [law], "motors": [MOTOR, BIG]}


def _setup(design: dict, law: str):
    d = api.load(copy.deepcopy(design))
    motors = MotorArrays.of(list(d.motors), d.limits.envelope)
    spec = make_law(law_choice(law))
    calc = SegmentCycle(d.machine_cycle, spec, Drive(d.load, d.transmission), motors)
    vibration = CycleVibration(d.load.elastic, d.machine_cycle,
                               cycle_laws(d.machine_cycle, spec))
    free = [i for i, s in enumerate(d.machine_cycle.segments) if s.duration is None]
    T = calc.durations(np.full(len(motors), calc.given_scale()))
    return d, vibration, free, np.stack([T[i] for i in free], axis=1)


def _worst(d, vibration: CycleVibration, free: list[int], D: np.ndarray) -> np.ndarray:
    k = len(D)
    columns = dict(zip(free, D.T, strict=True))
    durations = [columns[i] if i in columns else np.full(k, float(s.duration))
                 for i, s in enumerate(d.machine_cycle.segments)]
    return vibration.worst(np.ones(k), durations)


@pytest.mark.parametrize("law", ["cycloidal", "trapezoidal(alpha=1/3)"])
def test_two_moves_no_worse_than_a_dense_grid(law: str) -> None:
    """Every split of a 20001-point grid of T_1 (T_2 = F - T_1) is no better; every motor
    has the same split, summing to F."""
    d, vibration, free, D = _setup(_design((60.0, 150.0), 1.1), law)
    F = 1.1 - sum(DWELLS)
    np.testing.assert_allclose(D.sum(axis=1), F, rtol=1e-13)
    np.testing.assert_array_equal(D[0], D[1])
    T1 = np.linspace(F * 1e-3, F * (1 - 1e-3), 20001)
    grid = _worst(d, vibration, free, np.stack([T1, F - T1], axis=1))
    found = _worst(d, vibration, free, D[:1])[0]
    assert found <= grid.min() * (1.0 + 1e-9)
    even = _worst(d, vibration, free, np.full((1, 2), F / 2))[0]
    assert found < even


def test_three_moves_no_worse_than_a_dense_grid() -> None:
    """Three free moves: no split of a 120-step grid of the simplex (7021 splits) is
    better than the search's."""
    d, vibration, free, D = _setup(_design((40.0, 90.0, 150.0), 1.4), "cycloidal")
    F = 1.4 - sum(DWELLS)
    n = 120
    i, j = np.meshgrid(np.arange(1, n), np.arange(1, n), indexing="ij")
    keep = i + j < n
    grid = np.stack([i[keep], j[keep], n - i[keep] - j[keep]], axis=1) * (F / n)
    values = _worst(d, vibration, free, grid)
    found = _worst(d, vibration, free, D[:1])[0]
    assert D[0].sum() == pytest.approx(F, rel=1e-13)
    assert found <= values.min() * (1.0 + 1e-9)


def test_the_sizing_reports_the_residual_at_the_split() -> None:
    """The residual vibration check reads the split: the figure of every pair is the
    residual at the split's durations, the same for every motor."""
    design = _design((60.0, 150.0), 1.1)
    d, vibration, free, D = _setup(design, "cycloidal")
    expected = _worst(d, vibration, free, D[:1])[0]
    result = api.size(copy.deepcopy(design))
    figures = [r.residual_vibration for r in result.results]
    assert len(figures) == 2
    for value in figures:
        assert value == pytest.approx(expected, rel=1e-9)
    assert d.machine_cycle.share is ShareRule.OPTIMIZE_VIBRATION
    assert ShareRule.OPTIMIZE_VIBRATION.goal == "vibration"


def test_minimax_split_on_a_closed_form() -> None:
    """max(|T_1 - 0.3|, |T_2 - 0.5|, |T_3 - 0.2|) is least (0) at (0.3, 0.5, 0.2), F = 1;
    max(T_1, 2 T_2) at T_1 = 2/3 (the two equal), F = 1."""
    target = np.array([0.3, 0.5, 0.2])
    found = minimax_split(lambda D: np.abs(D - target).max(axis=1), 1.0, 3)
    np.testing.assert_allclose(found, target, atol=1e-9)
    found = minimax_split(lambda D: np.maximum(D[:, 0], 2.0 * D[:, 1]), 1.0, 2)
    np.testing.assert_allclose(found, [2.0 / 3.0, 1.0 / 3.0], atol=1e-9)


# ------------------------------------------------------------------ errors
def _write(tmp_path: Path, design: dict) -> Path:
    import yaml

    path = tmp_path / "design.yaml"
    path.write_text(yaml.safe_dump(design, sort_keys=False), encoding="utf-8")
    return path


def test_without_a_mode_the_goal_is_refused_at_the_share(tmp_path: Path) -> None:
    load = {k: v for k, v in MODE.items() if k not in ("natural_frequency", "damping_ratio")}
    path = _write(tmp_path, _design((60.0, 150.0), 1.1, load=load))
    line = assert_user_error(run_cli("size", str(path)), "cycle.share",
                             "load.natural_frequency")
    text = path.read_text().splitlines()
    share_line = 1 + next(i for i, x in enumerate(text) if x.strip().startswith("share:"))
    assert f"design.yaml:{share_line}:" in line


def test_without_a_cycle_time_the_goal_is_refused(tmp_path: Path) -> None:
    design = _design((60.0, 150.0), 1.1)
    del design["cycle"]["cycle_time"]
    path = _write(tmp_path, design)
    assert_user_error(run_cli("size", str(path)), "cycle.share", "cycle_time")
