"""One cycle model (issue 33): a design holds one Cycle, the task shorthand is one at the
input boundary, and the engine reads the cycle only (its closed-form path chosen by the
cycle's shape, sizer.model.cycle.shorthand_task)."""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from sizer.errors import UserError
from sizer.io.loader import load_design_data
from sizer.model.cycle import Cycle, Dwell, Move, Task, from_task
from sizer.model.domain import Design, Load, Motor
from sizer.sizing import size_design

SIZING = Path(__file__).resolve().parents[1] / "sizer" / "sizing"

H, J_M, J_L, TAU = 1.0, 1e-4, 1e-3, 1.0
C_A = 2.0 * math.pi  # the cycloidal law's acceleration coefficient (book sec. 4.4)
T_MIN = math.sqrt(C_A * H * (J_M + J_L) / TAU)
"""Book sec. 6.2: a purely inertial direct drive whose peak torque binds."""
MOTOR = Motor("m", J_M, TAU, TAU, 1e4)


def test_the_core_reads_the_cycle_only() -> None:
    for path in sorted(SIZING.glob("*.py")):
        text = path.read_text()
        assert not re.search(r"\bdesign\.task\b", text), path.name
        assert not re.search(r"\.cycle is (not )?None", text), path.name


def test_a_task_is_stored_as_its_cycle() -> None:
    task = Task(H, None, dwell=0.2, return_move=True)
    design = Design(task, Load(J_L))
    assert design.machine_cycle == from_task(task) and design.machine_cycle.shorthand == task
    assert design.task == task and design.cycle is None  # written as a task


def _duration(design: Design) -> float:
    (result,) = size_design(design).results
    assert result.feasible and result.duration is not None
    return result.duration


def _design(motion: Task | Cycle) -> Design:
    task = motion if isinstance(motion, Task) else None
    return Design(task, Load(J_L), laws=("cycloidal",), motors=(MOTOR,),
                  cycle=motion if isinstance(motion, Cycle) else None)


def test_a_task_and_the_same_cycle_give_the_closed_form() -> None:
    assert _duration(_design(Task(H, None))) == pytest.approx(T_MIN, rel=1e-9)
    written = Cycle((Move(H, None), Move(-H, None)), closed=True)
    assert _duration(_design(written)) == pytest.approx(T_MIN, rel=1e-9)
    assert _duration(_design(Task(H, None, return_move=True))) == pytest.approx(T_MIN, rel=1e-9)


def test_a_cycle_of_segments_reports_its_cycle_time() -> None:
    cycle = Cycle((Move(H, None), Dwell(0.2), Move(-H, None), Dwell(0.1)), closed=True)
    assert _duration(_design(cycle)) == pytest.approx(2 * T_MIN + 0.3, rel=1e-9)


CYCLE = {"cycle": {"segments": [{"move": {"displacement": "90 deg", "duration": "free"}},
                                {"dwell": {"duration": "0.3 s"}},
                                {"move": {"displacement": "180 deg", "duration": "free"}}]},
         "load": {"inertia": "0.034 kg*m^2", "natural_frequency": "20 Hz"},
         "motors": [{"id": "m", "inertia": "1e-4 kg*m^2", "continuous_torque": "1 N*m",
                     "peak_torque": "3 N*m", "rated_speed": "3000 rpm"}]}


@pytest.mark.parametrize("law, why", [
    ("trapezoidal(alpha=auto)", "`auto` shape parameters"),
    ({"kind": "shaped", "law": "cycloidal", "shaper": "zv"}, "give f_T")])
def test_a_law_chosen_per_duration_is_refused_in_a_cycle_at_its_line(law, why) -> None:
    with pytest.raises(UserError) as error:
        load_design_data({**CYCLE, "laws": ["poly5", law]})
    text = str(error.value)
    assert re.match(r"<design>:\d+: laws\[1\]: ", text) and why in text, text


def test_no_law_for_the_boundary_speeds_is_refused_at_the_laws_line() -> None:
    segments = [{"move": {"displacement": "90 deg", "duration": "0.3 s", "end_speed": "1 rad/s"}},
                {"move": {"displacement": "90 deg", "duration": "0.3 s",
                          "start_speed": "1 rad/s"}}]
    with pytest.raises(UserError) as error:
        load_design_data({**CYCLE, "cycle": {"segments": segments}, "laws": ["cycloidal"]})
    assert re.match(r"<design>:\d+: laws: none of the laws can start or end a move at a "
                    r"non-zero speed", str(error.value)), str(error.value)
