"""The task shorthand and its expanded cycle (issue 12) on every bundled example.

Written as a cycle (move, dwell, move back, dwell: sizer.model.cycle.from_task) every
example gives the results of its task, to the last bit (on its first eight motors); and
with its dwell split in two (no longer the shorthand, so sized segment by segment) the
same verdicts and, as cycle times, the same durations and torques to 1e-9 (on a few
motors: the segment engine searches, it is slower).
"""

from __future__ import annotations

import functools
from dataclasses import replace
from pathlib import Path

import pytest

from sizer.api import load
from sizer.model.cycle import Cycle, Dwell, Move, from_task
from sizer.sizing import size_design

ROOT = Path(__file__).resolve().parent.parent / "examples"
EXAMPLES = sorted([*ROOT.glob("*.yaml"), *(ROOT / "book").glob("*.yaml")])


@functools.cache  # loaded once for the two parametrizations below (at collection)
def task_designs():
    out = []
    for path in EXAMPLES:
        design = load(path)
        if design.cycle is None:
            out.append(pytest.param(design, id=path.stem))
    return out


def key(result):
    return (result.motor, result.law_object.spec, result.feasible, result.duration,
            result.peak_torque, result.rms_torque, result.max_speed, result.limiting)


@pytest.mark.parametrize("design", task_designs())
def test_the_expanded_task_gives_identical_results(design):
    design = replace(design, motors=design.motors[:8])  # the same path: a few motors show it
    expanded = replace(from_task(design.task), shorthand=None)
    a = size_design(design)
    b = size_design(replace(design, cycle=expanded))
    assert [key(r) for r in a.results] == [key(r) for r in b.results]


def split_dwell(design) -> Cycle:
    task = design.task
    first: list = [Move(task.displacement, task.duration)]
    if task.dwell > 0:
        first += [Dwell(task.dwell / 4), Dwell(3 * task.dwell / 4)]
    else:
        first += [Dwell(0.0), Dwell(0.0)]
    back: list = []
    if task.return_move:
        back = [Move(-task.displacement, task.duration)] + \
            ([Dwell(task.dwell)] if task.dwell > 0 else [])
    return Cycle(tuple(first + back), linear=task.linear)


@pytest.mark.parametrize("design", task_designs()[:6])
def test_segment_by_segment_equals_the_task(design):
    design = replace(design, motors=design.motors[:3])
    a = size_design(design)
    b = size_design(replace(design, cycle=split_dwell(design)))
    by_key = {(r.motor, r.law_object.spec): r for r in a.results}
    n = 2 if design.task.return_move else 1
    for r in b.results:
        x = by_key[(r.motor, r.law_object.spec)]
        assert r.feasible == x.feasible, (r.motor, r.law)
        if x.feasible:
            assert r.duration == pytest.approx(n * (x.duration + design.task.dwell), rel=1e-9)
            assert r.peak_torque == pytest.approx(x.peak_torque, rel=1e-9)
            assert r.rms_torque == pytest.approx(x.rms_torque, rel=1e-9)
