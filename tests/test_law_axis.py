"""Several fixed laws sized as one axis (sizer.sizing.engine.evaluate_law_axis: the motors
laid out once per law, each row with its own law in one model, the ratio chosen for every
row at once) against the laws sized one after another: the same results, to the bit.

The designs: the random designs of test_engine_vs_scalar with three laws (friction,
damping, a constant load, efficiencies, stage ratings and speeds, limits on the load's
motion, dwells and returns, a list of ratios: minimize and given durations), a continuous
ratio range, no ratio choice, a residual-vibration limit, cycles of segments (free and
fixed moves and dwells, weights; minimized and at a given cycle time; a model of several
laws' rows in sizer.sizing.cycle.SegmentCycle) and bundled examples."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest
from test_engine_vs_scalar import LAWS, random_design

from sizer.io.loader import load_design
from sizer.model import RatioChoice
from sizer.model.cycle import Cycle, Dwell, Move
from sizer.sizing import engine
from sizer.vibration.elastic_load import ElasticLoad

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def _both(design, monkeypatch) -> tuple[str, str]:
    """The sizing's JSON with the law axis and law by law."""
    laws = engine.ranked_laws(design)
    assert engine.law_axis(design, laws, len(design.motors)) is not None  # the axis is taken
    together = engine.size_design(design)
    with monkeypatch.context() as m:
        m.setattr(engine, "law_axis", lambda *args: None)
        alone = engine.size_design(design)
    return (json.dumps(together.to_dict(), sort_keys=True),
            json.dumps(alone.to_dict(), sort_keys=True))


def _three_laws(seed: int):
    design = random_design(seed)
    rng = np.random.default_rng(seed + 100)
    laws = tuple(str(s) for s in rng.choice(LAWS, size=3, replace=False))
    return dataclasses.replace(design, laws=laws)


@pytest.mark.parametrize("seed", range(8))
@pytest.mark.parametrize("minimize", [True, False])
def test_random_designs_size_alike_as_one_axis(seed: int, minimize: bool, monkeypatch) -> None:
    design = _three_laws(seed)
    if minimize:
        design = dataclasses.replace(design, task=dataclasses.replace(design.task,
                                                                        duration=None))
    together, alone = _both(design, monkeypatch)
    assert together == alone


@pytest.mark.parametrize("choice", ["bounds", "none", "residual"])
def test_a_ratio_range_no_ratio_choice_and_a_residual_limit_size_alike(choice: str,
                                                                       monkeypatch) -> None:
    design = _three_laws(3)
    design = dataclasses.replace(design, task=dataclasses.replace(design.task, duration=None))
    if choice == "bounds":
        design = dataclasses.replace(design, ratio_choice=RatioChoice(0, bounds=(3.0, 20.0)))
    elif choice == "none":
        design = dataclasses.replace(design, ratio_choice=None)
    else:
        load = dataclasses.replace(design.load, elastic=ElasticLoad(30.0, 0.02))
        design = dataclasses.replace(design, load=load, limits=dataclasses.replace(
            design.limits, residual_vibration=1e-4))
    together, alone = _both(design, monkeypatch)
    assert together == alone


@pytest.mark.parametrize("example", ["indexing-table-fastest.yaml",
                                     "indexing-table-gearboxes.yaml", "book/ex6_4.yaml"])
def test_bundled_examples_size_alike_as_one_axis(example: str, monkeypatch) -> None:
    together, alone = _both(load_design(EXAMPLES / example), monkeypatch)
    assert together == alone


def test_a_large_design_or_a_law_with_auto_parameters_takes_its_laws_one_by_one() -> None:
    design = _three_laws(0)
    laws = engine.ranked_laws(design)
    assert engine.law_axis(design, laws, 2) is not None
    assert engine.law_axis(design, laws, engine.AXIS_ROWS) is None
    auto = dataclasses.replace(design, laws=(*design.laws[:2], "trapezoidal(alpha=auto)"))
    assert engine.law_axis(auto, engine.ranked_laws(auto), 2) is None


def _cycle(seed: int, minimize: bool):
    design = _three_laws(seed)
    h = design.task.displacement
    rng = np.random.default_rng(seed + 200)
    segments = (Move(h, None), Dwell(float(rng.uniform(0.05, 0.2))),
                Move(-h / 2, float(rng.uniform(0.15, 0.3))), Move(-h / 2, None, weight=2.0),
                Dwell(None))
    cycle = Cycle(segments, closed=True, cycle_time=None if minimize else 2.0)
    return dataclasses.replace(design, cycle=cycle)


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("minimize", [True, False])
def test_cycles_of_segments_size_alike_as_one_axis(seed: int, minimize: bool,
                                                   monkeypatch) -> None:
    design = _cycle(seed, minimize)
    assert engine.shorthand_task(design.machine_cycle) is None
    together, alone = _both(design, monkeypatch)
    assert together == alone


@pytest.mark.parametrize("limit", [None, 2e-4])
def test_a_cycles_residual_vibration_over_several_laws_rows_is_each_laws(limit, monkeypatch):
    """The residual over the rows of a cycle of several laws (ResidualRows with
    SegmentCycle.by_law): reported, then limited, as each law alone."""
    design = _cycle(1, True)
    load = dataclasses.replace(design.load, elastic=ElasticLoad(30.0, 0.02))
    design = dataclasses.replace(design, load=load, limits=dataclasses.replace(
        design.limits, residual_vibration=limit))
    seen = []
    rows = engine._law_rows

    def spy(*args):
        found = rows(*args)
        seen.append(found is not None and bool(found[1]))
        return found

    monkeypatch.setattr(engine, "_law_rows", spy)
    together, alone = _both(design, monkeypatch)
    assert any(seen)  # one model with its residual limit over the rows
    assert together == alone
    residual = engine.size_design(design).table.figures["residual_vibration"]
    with monkeypatch.context() as m:
        m.setattr(engine, "law_axis", lambda *args: None)
        by_law = engine.size_design(design).table.figures["residual_vibration"]
    assert np.isfinite(residual).any() and np.array_equal(residual, by_law, equal_nan=True)
