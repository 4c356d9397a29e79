"""Bad values of every field a machine file adds to a design's (``machine:``, ``axes:``'
timing, ``bus:``): each answered by one located message naming the file, the field
under ``axes[i]`` where it is an axis's, and what is allowed. An axis's design fields are
read by the design loader: their cases are those of tests/test_bad_inputs_fields.py (one
here shows the location)."""

from __future__ import annotations

import pytest
from bad_input_cases import Case, edited
from bad_input_cases import run_case as run

BASE = "machines/two-axis-packer.yaml"
HERE = {"axes[0].motors": "catalogs/example-servo.yaml",
        "axes[1].motors": "catalogs/example-servo.yaml"}
"""The cases' folder has the example catalogs beside the file."""
D = "design.yaml:"


def case(id: str, value: dict, words: tuple[str, ...], fields: tuple[str, ...],
         delete: tuple[str, ...] = ()) -> Case:
    return Case(id, design=edited(BASE, set={**HERE, **value}, delete=delete),
                words=(D, *words), fields=fields)


CASES = [
    case("machine-name-a-list", {"name": [1]}, ("name",), ("machine:name",)),
    case("machine-missing", {}, ("machine", "required"), ("machine:machine",),
         delete=("machine",)),
    case("machine-cycle-zero", {"machine.cycle": "0 deg"},
         ("machine.cycle", "[1e-6, 1e7] rad"), ("machine:machine.cycle",)),
    case("machine-speed-negative", {"machine.master_speed": "-60 rpm"},
         ("machine.master_speed", "[1e-6, 1e6] rad/s"), ("machine:machine.master_speed",)),
    case("machine-speed-and-cycle-time", {"machine.cycle_time": "1 s"},
         ("machine.master_speed", "one of the two"), ("machine:machine.cycle_time",)),
    case("machine-cycle-time-zero", {"machine.cycle_time": "0 s"},
         ("machine.cycle_time", "[1e-6, 1e6] s"), ("machine:machine.cycle_time",),
         delete=("machine.master_speed",)),
    case("axes-empty", {"axes": []}, ("axes", "at least 1"), ("machine:axes",)),
    case("axis-name-twice", {"axes[1].name": "table"}, ("axes[1].name", "twice"),
         ("machine:axes.name",)),
    case("axis-name-missing", {}, ("axes[0].name", "required"), ("machine:axes.name",),
         delete=("axes[0].name",)),
    case("axis-task-missing", {}, ("axes[0].task", "required"), ("machine:axes.task",),
         delete=("axes[0].task",)),
    case("axis-displacement-zero", {"axes[0].task.displacement": "0 deg"},
         ("axes[0].task.displacement", "must not be zero"),
         ("machine:axes.task.displacement",)),
    case("axis-move-too-long", {"axes[0].task.move": "400 deg"},
         ("axes[0].task.move", "do not fit"), ("machine:axes.task.move",)),
    case("axis-move-zero", {"axes[0].task.move": "0 deg"},
         ("axes[0].task.move", "[1e-6, 1e7] rad"), ("machine:axes.task.move",)),
    case("axis-dwell-off", {"axes[0].task.dwell": "100 deg"},
         ("axes[0].task.dwell", "add up"), ("machine:axes.task.dwell",)),
    case("axis-dwell-negative", {"axes[0].task.dwell": "-10 deg"},
         ("axes[0].task.dwell", "0 or in [1e-6, 1e7] rad"), ("machine:axes.task.dwell",)),
    case("axis-return-a-text", {"axes[1].task.return": "yes"},
         ("axes[1].task.return",), ("machine:axes.task.return",)),
    case("axis-start-past-the-cycle", {"axes[1].start": "360 deg"},
         ("axes[1].start", "below"), ("machine:axes.start",)),
    case("axis-start-negative", {"axes[1].start": "-10 deg"},
         ("axes[1].start", "0 or in [1e-6, 1e7] rad"), ("machine:axes.start",)),
    case("axis-with-a-cycle", {"axes[0].cycle": {"segments": []}},
         ("axes[0].cycle", "task"), ("machine:axes.cycle",)),
    case("axis-with-a-check", {"axes[0].check": {"motor": "HG-KN43J"}},
         ("axes[0].check", "design files"), ("machine:axes.check",)),
    case("axis-load-located-under-axes", {"axes[1].load.mass": "-3 kg"},
         ("axes[1].load.mass",), ()),
    case("bus-null", {"bus": None}, ("bus", "None"), ("machine:bus",)),
    case("bus-capacitance-negative", {"bus.capacitance": "-1 uF"},
         ("bus.capacitance", "[1e-9, 10] F"), ("machine:bus.capacitance",)),
    case("bus-voltage-zero", {"bus.voltage": "0 V"}, ("bus.voltage", "[1, 1e4] V"),
         ("machine:bus.voltage",)),
    case("bus-threshold-below-the-voltage", {"bus.braking_threshold": "300 V"},
         ("bus.braking_threshold", "above the bus voltage"),
         ("machine:bus.braking_threshold",)),
    case("bus-resistor-negative", {"bus.braking_resistor_power": "-5 W"},
         ("bus.braking_resistor_power", "-5"), ("machine:bus.braking_resistor_power",)),
]


@pytest.mark.parametrize("case", CASES, ids=str)
def test_bad_machine(case, tmp_path):
    run(case, tmp_path)
