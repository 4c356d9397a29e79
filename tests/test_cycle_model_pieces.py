"""Each cycle model samples itself (sizer.sizing.evaluation.CycleModel.pieces) and the
sampler asks only that: the pieces end at the model's cycle time, ``scale_of`` inverts the
duration its evaluation reports, a cycle of segments breaks down into its segments, and
a model the sampler has never seen is sampled through the Protocol alone (issue 33)."""

from __future__ import annotations

from itertools import pairwise

import numpy as np
import pytest

from sizer.io.loader import load_design_data
from sizer.laws import make_law
from sizer.mechanics import Drive
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.cycle import SegmentCycle
from sizer.sizing.evaluation import CyclePiece, held_piece
from sizer.sizing.linkage_move import LinkageCalculator, LinkageCycle, linkage_calculator
from sizer.sizing.move import CycleCalculator
from sizer.sizing.samples import sampled

MOTOR = {"id": "M1", "inertia": "1e-3 kg*m^2", "continuous_torque": "100 N*m",
         "peak_torque": "200 N*m", "rated_speed": "300 rad/s"}
LINKAGE = [{"type": "slider_crank", "crank_radius": "50 mm", "rod_length": "200 mm",
            "law_on": "crank"}]


def design(task: dict, linkage: bool = False):
    return load_design_data({
        "task": task, "laws": ["cycloidal"], "motors": [MOTOR],
        **({"load": {"mass": "2 kg", "force": "30 N"}, "transmission": LINKAGE} if linkage
           else {"load": {"inertia": "0.02 kg*m^2", "torque": "1 N*m"}})})


def models():
    """(model, scale, cycle time by hand) of each kind."""
    law = make_law("cycloidal")
    out = []
    # minimize: the moves' durations are free (weight 1 each), the dwells fixed
    d = design({"displacement": "3 rad", "duration": "minimize", "dwell": "0.25 s",
                "return": True})
    motors, drive = MotorArrays.of(d.motors, d.limits.envelope), Drive(d.load, d.transmission)
    task = d.task
    assert task is not None
    # the task: 2 (T + dwell) = 2 (0.5 + 0.25) s at T = 0.5 s
    out.append((CycleCalculator(None, task, drive, motors, law=law), 0.5, 1.5))
    # the same as a cycle of segments
    out.append((SegmentCycle(d.machine_cycle, law, drive, motors), 0.5, 1.5))
    one = design({"displacement": "180 deg", "duration": "0.25 s", "dwell": "0.1 s"}, True)
    calc = linkage_calculator(one, law, MotorArrays.of(one.motors, one.limits.envelope),
                              Drive(one.load, one.transmission))
    assert isinstance(calc, LinkageCalculator)
    out.append((calc, 0.25, 0.35))  # T + dwell
    back = design({"displacement": "180 deg", "duration": "minimize", "dwell": "0.1 s",
                   "return": True}, True)
    calc = linkage_calculator(back, law, MotorArrays.of(back.motors, back.limits.envelope),
                              Drive(back.load, back.transmission))
    assert isinstance(calc, LinkageCycle)
    out.append((calc, 0.25, 0.7))  # 2 (T + dwell)
    return out


@pytest.mark.parametrize("index", range(4))
def test_the_pieces_end_at_the_cycle_time_and_scale_of_inverts_the_duration(index):
    model, s, cycle = models()[index]
    scale = np.array([s])
    assert model.cycle_time(scale) == pytest.approx([cycle], rel=1e-15)
    pieces = model.pieces(scale, 21)
    assert pieces[0].time[0, 0] == 0.0
    assert pieces[-1].time[0, -1] == pytest.approx(cycle, rel=1e-15)
    for before, after in pairwise(pieces):  # joined end to start
        assert after.time[0, 0] == pytest.approx(before.time[0, -1], rel=1e-15)
    got = sampled(model, scale)
    assert got.cycle_time == pytest.approx([cycle], rel=1e-15)
    assert model.scale_of(model.evaluate(scale).duration) == pytest.approx([s], rel=1e-14)


@pytest.mark.parametrize("index", (1, 2, 3))
def test_a_cycle_of_segments_breaks_down_into_its_segments(index):
    model, s, cycle = models()[index]
    parts = model.breakdown(np.array([s]))
    assert sum(float(p.duration[0]) for p in parts) == pytest.approx(cycle, rel=1e-15)
    assert [p.kind for p in parts] == (["move", "dwell"] if index == 2 else
                                       ["move", "dwell", "move", "dwell"])
    # a dwell holds its load without moving: no speed, no work, no acceleration scale
    for p in parts[1::2]:
        assert (float(p.max_speed[0]), float(p.energy[0])) == (0.0, 0.0)
        assert p.acceleration_scale is None and p.law is None


class Held:
    """A move kind the sampler has never seen: one dwell of s holding 2 N*m."""

    def __init__(self, n: int) -> None:
        self.motors = range(n)

    def pieces(self, s: np.ndarray, samples: int | None = None) -> list[CyclePiece]:
        return [held_piece("hold", np.zeros((len(s), 1)), s[:, None], 0.0,
                           np.full(len(s), 2.0))]


def test_the_sampler_asks_the_model_only():
    got = sampled(Held(2), np.array([0.5, 2.0]))  # type: ignore[arg-type]
    assert got.time.tolist() == [[0.0, 0.5], [0.0, 2.0]]
    assert got.torque.tolist() == [[2.0, 2.0], [2.0, 2.0]]
    assert got.speed.tolist() == [[0.0, 0.0], [0.0, 0.0]]
    assert got.cycle_time.tolist() == [0.5, 2.0]
