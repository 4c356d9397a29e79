"""The load's figures as an axis of the candidate arrays (issue 39: robust builds and
sensitivities "another axis of the candidate arrays, not a loop around the engine";
sizer.mechanics.load_figures).

Reference: each build of the load written as its own design (the Load's fields replaced)
and sized separately; one sizing of motor copies, each driving its own build, gives every
row's figures, checks and verdict. Designs: the task shorthand with gravity, a free ratio
and efficiencies (pick-and-place), cycles of segments with a part's mass and a pressing
dwell (vertical pick-and-place, the indexing duty cycle), the steady-load efficiency rule,
and minimize mode.
"""

from __future__ import annotations

from copy import copy
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from sizer import api
from sizer.mechanics.load_figures import LoadFigures
from sizer.sizing.candidates import Builds
from sizer.sizing.engine import reads_builds, size_design

EXAMPLES = Path(__file__).parents[1] / "examples"
BUILDS = [(1.0, 1.0, 1.0, 1.0), (1.2, 0.5, 1.5, 1.0), (0.8, 2.0, 0.7, 1.1),
          (1.1, 1.0, 1.3, 0.9)]
"""Factors on (inertia, damping, friction, torque) of each build."""


def _build(design, factors):
    load = design.load
    changed = {name: getattr(load, name) * f for name, f in
               zip(("inertia", "damping", "friction", "torque"), factors, strict=True)}
    return replace(design, load=replace(load, **changed))


def _rows(sizing) -> dict[int, list]:
    out: dict[int, list] = {}
    for r in sizing.results:
        out.setdefault(id(r.motor_object), []).append(r)
    return out


def _same(a, b) -> None:
    assert a.feasible == b.feasible and a.spec == b.spec and a.limiting == b.limiting
    assert a.transmission.ratio == pytest.approx(b.transmission.ratio, rel=1e-12)
    for name in ("duration", "peak_torque", "rms_torque", "max_speed", "load_torque"):
        x, y = getattr(a, name), getattr(b, name)
        assert (x is None) == (y is None), name
        if x is not None:
            assert x == pytest.approx(y, rel=1e-9, abs=1e-12), name
    assert [c.name for c in a.checks] == [c.name for c in b.checks]
    for c, d in zip(a.checks, b.checks, strict=True):
        assert c.margin == pytest.approx(d.margin, rel=1e-9, abs=1e-12), c.name


def _stages(design, factors):
    """``design`` with its transmission's first stage's ratio and efficiency times these
    factors (a build of the transmission)."""
    if factors is None:
        return design
    stage = design.transmission.stages[0]
    changed = replace(stage, ratio=stage.ratio * factors[0],
                      efficiency=min(stage.efficiency * factors[1], 1.0))
    return replace(design, transmission=design.transmission.with_stage(0, changed))


def _assert_rows_are_separate_sizings(design, motors: int = 3, stages=None) -> None:
    """``stages``: per build factors on the first stage's ratio and efficiency too."""
    chosen = design.motors[:motors]
    design = replace(design, motors=chosen)
    copies = [(m, b, copy(m)) for m in chosen for b in range(len(BUILDS))]
    built = [_stages(_build(design, BUILDS[b]), None if stages is None else stages[b])
             for _, b, _ in copies]
    sized = size_design(api.override(design, motors=[c for *_, c in copies]),
                        builds=Builds.of(built, design))
    rows = _rows(sized)
    for b, factors in enumerate(BUILDS):
        alone = _rows(size_design(_stages(_build(design, factors),
                                          None if stages is None else stages[b])))
        for motor, build, c in copies:
            if build != b:
                continue
            mine = sorted(rows[id(c)], key=lambda r: r.spec)
            theirs = sorted(alone[id(motor)], key=lambda r: r.spec)
            assert len(mine) == len(theirs)
            for x, y in zip(mine, theirs, strict=True):
                _same(x, y)


@pytest.mark.parametrize("example", ["pick-and-place.yaml", "vertical-pick-and-place.yaml",
                                     "indexing-duty-cycle.yaml", "indexing-table.yaml"])
def test_each_row_is_its_build_sized_on_its_own(example) -> None:
    design = api.load(EXAMPLES / example)
    assert reads_builds(design)
    if example == "pick-and-place.yaml":  # 64 bundled motors (a free ratio): one
        design = replace(design, motors=design.motors[40:41])
    # indexing-table chooses trapezoidal(alpha=auto) per candidate: one motor
    _assert_rows_are_separate_sizings(design, 1 if example == "indexing-table.yaml" else 3)


def test_the_steady_load_rule_and_damping() -> None:
    """Yaskawa's rule (efficiencies on the steady load only) and a load with damping."""
    design = api.load(EXAMPLES / "indexing-duty-cycle.yaml")
    transmission = replace(design.transmission, efficiency_applies_to="steady_load")
    _assert_rows_are_separate_sizings(replace(design, transmission=transmission))


def test_builds_of_the_transmission_are_rows_too() -> None:
    """Each build its own ratio and efficiency of the gearbox (transmission options of the
    drive, one per build) besides its load: still each build sized on its own."""
    design = api.load(EXAMPLES / "indexing-duty-cycle.yaml")
    stages = [(1.0, 1.0), (1.05, 0.98), (0.95, 1.02), (1.0, 0.9)]
    _assert_rows_are_separate_sizings(design, 2, stages)


def test_a_design_whose_engine_reads_the_design_load_refuses_builds() -> None:
    design = api.load(EXAMPLES / "press-slider-crank.yaml")
    assert not reads_builds(design)
    with pytest.raises(ValueError, match="linkage"):
        size_design(design, builds=Builds(LoadFigures.builds([design.load]
                                                              * len(design.motors))))


def test_figures_move_with_a_segment_and_slice_with_the_candidates() -> None:
    """A segment's added part moves every build by what it adds; take slices them."""
    from sizer.model.domain import Load

    base = Load(2.0, 0.1, 3.0, 4.0)
    builds = LoadFigures.builds([base, Load(2.5, 0.2, 1.0, -4.0)])
    moved = builds.moved(base, replace(base, inertia=2.75, torque=5.0))
    np.testing.assert_allclose(moved.inertia, [2.75, 3.25])
    np.testing.assert_allclose(moved.torque, [5.0, -3.0])
    np.testing.assert_array_equal(moved.friction, [3.0, 1.0])
    taken = builds.take(np.array([1, 1, 0]))
    np.testing.assert_array_equal(taken.damping, [0.2, 0.2, 0.1])
    assert LoadFigures.of(base).moved(base, replace(base, inertia=7.0)).inertia == 7.0
    assert not builds.none("torque") and LoadFigures.of(Load(1.0)).none("torque", "friction")


def test_robust_builds_of_the_load_and_motors_are_one_sizing(monkeypatch) -> None:
    """Tolerances on the load's figures, the gearbox's efficiency and the motors' take one
    sizing for all their corners and samples (rows), not one per build; the worst margins
    are still the least over the corners each sized on its own (tests/test_robust*.py
    check that across designs; here the count)."""
    from engine_calls import counted_sizings

    from sizer.model.tolerance import Tolerance
    from sizer.robust import robust_sizing

    design = api.load(EXAMPLES / "indexing-duty-cycle.yaml")
    design = replace(design, motors=design.motors[:2], tolerances=(
        Tolerance("load.inertia", 0.2), Tolerance("load.friction", 0.5),
        Tolerance("transmission.efficiency", 0.02), Tolerance("motor.peak_torque", 0.1)))
    nominal = api.size(design)
    robust, sizings = counted_sizings(
        monkeypatch, lambda: robust_sizing(design, nominal, samples=20))
    assert sizings == 1  # 16 corners and 20 samples x 2 motors: 72 rows of one sizing
    assert all(r.corners == 16 and r.samples == 20 for r in robust.results)
