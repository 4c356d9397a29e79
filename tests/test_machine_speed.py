"""An axis's smallest machine cycle time in one sizing (issue 34): its cycle with move
f s and dwell g s minimized over s equals the search on phi(T_c) = T_c - H(T_c), which
sizes the move with a fixed dwell at each step (an independent computation: the task
shorthand's T_min per step, the root of phi by the Illinois method)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import pytest

from sizer import api
from sizer.sizing.machine import axis_cycle_time, scaled_cycle_time, searched_cycle_time

ROOT = Path(__file__).resolve().parent.parent
SERVOS = str(ROOT / "examples" / "catalogs" / "example-servo.yaml")
GEARBOXES = str(ROOT / "examples" / "catalogs" / "example-gearboxes.yaml")


def table(name: str, **extra: Any) -> dict[str, Any]:
    """The indexing table of the examples as an axis: 90 deg in 150 deg of master."""
    limits = {"torque_margin": "10 %", **extra.pop("limits", {})}
    load = {"inertia": "0.034 kg*m^2", "damping": "0.02 N*m*s/rad", "friction": "0.5 N*m"}
    return {"name": name, "task": extra.pop("task", {"displacement": "90 deg",
                                                     "move": "150 deg"}),
            "load": extra.pop("load", load),
            "transmission": extra.pop("transmission", {"type": "gearbox", "ratio": 10,
                                                       "efficiency": 0.95}),
            "laws": extra.pop("laws", ["cycloidal", "trapezoidal(alpha=1/3)"]),
            "motors": SERVOS, "limits": limits, **extra}


AXES = {
    "packer": None,  # the example's two axes: the dwell relieves the RMS torque
    "vibration": table("vibration", load={"inertia": "0.034 kg*m^2", "friction": "0.5 N*m",
                                          "natural_frequency": "25 Hz",
                                          "damping_ratio": 0.02},
                       limits={"residual_vibration": "20 arcsec"},
                       laws=["cycloidal", "trapezoidal(alpha=1/3)",
                             "double_s(alpha=1/3, beta=1/4)"]),
    "held load": table("held load", load={"inertia": "0.034 kg*m^2",
                                                   "torque": "9 N*m"}),  # held in the dwell too
    "gearbox catalog": table("gearbox catalog", transmission={
        "type": "gearbox", "catalog": GEARBOXES}, laws=["modified_sinusoidal", "poly5"]),
    "pusher with return": table("pusher", task={"displacement": "120 mm", "move": "60 deg",
                                                "return": True},
                                load={"mass": 3, "friction": "10 N"},
                                transmission={"type": "belt", "driver_diameter": "40 mm",
                                              "efficiency": "90 %"}),
}


def machine_of(case: str) -> Any:
    if AXES[case] is None:
        return api.load_machine(ROOT / "examples" / "machines" / "two-axis-packer.yaml")
    return api.load_machine({"name": case, "machine": {"cycle": "360 deg",
                                                       "master_speed": "minimize"},
                             "axes": [AXES[case]]})


@pytest.mark.parametrize("case", list(AXES))
def test_one_sizing_of_the_scaled_cycle_gives_the_searched_cycle_time(case: str) -> None:
    machine = machine_of(case)
    for axis in machine.axes:
        scaled = scaled_cycle_time(axis, machine.cycle_angle)
        searched = searched_cycle_time(axis, machine.cycle_angle)
        assert scaled is not None and searched is not None
        # the search stops once its bracket is 1e-12 s wide (RELATIVE_TOLERANCE, T_c < 1 s)
        assert scaled == pytest.approx(searched, rel=1e-12, abs=2e-12)
        assert axis_cycle_time(axis, machine.cycle_angle) == scaled


def test_an_axis_no_speed_suits_is_none_either_way() -> None:
    """A held torque above every motor's continuous torque: no T_c is feasible."""
    machine = api.load_machine({"name": "m", "machine": {"master_speed": "minimize"},
                                "axes": [table("lift", load={"inertia": "0.034 kg*m^2",
                                                                "torque": "500 N*m"})]})
    axis = machine.axes[0]
    assert scaled_cycle_time(axis, machine.cycle_angle) is None
    assert searched_cycle_time(axis, machine.cycle_angle) is None


def test_the_cycle_time_is_the_scale_of_the_shares() -> None:
    """The scaled design's moves and dwells take f s and g s: at the axis's T_c they are
    the durations the machine gives it (MachineAxis.at)."""
    machine = machine_of("pusher with return")
    axis = machine.axes[0]
    cycle = axis.scaled(machine.cycle_angle).machine_cycle
    f, g = 60 / 360, 120 / 360
    assert [s.weight for s in cycle.segments] == pytest.approx([f, g, f, g], rel=1e-15)
    assert math.fsum(cycle.weights()) == pytest.approx(1.0, rel=1e-15)
    assert cycle.minimize and cycle.closed
