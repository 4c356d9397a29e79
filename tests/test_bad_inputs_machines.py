"""Bad values of the fields of a machine file (issue 32), rule by rule: non-finite, wrong
type, wrong unit, out of range, missing, unknown key, beyond the axis limit. Each is
answered by one ``error:`` line naming the file, the LINE of the field (found by composing
the YAML, tests/bad_input_lines.py) and its path under ``axes[i]``, exit code 2.

tests/test_bad_inputs_machine.py holds one case per field (and the rules between fields);
the cases here are the rules it does not exercise. A machine of MAX_MACHINE_AXES axes is
sized under a 2 GiB address-space limit; sizing a machine reports progress per axis.
"""

from __future__ import annotations

import resource
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
import yaml
from bad_input_cases import EXAMPLES, Case, assert_well_formed, edited, run_case
from bad_input_lines import at

from sizer.input_limits import MAX_MACHINE_AXES

BASE = "machines/two-axis-packer.yaml"
HERE = {"axes[0].motors": "catalogs/example-servo.yaml",
        "axes[1].motors": "catalogs/example-servo.yaml"}
"""The cases' folder has the example catalogs beside the file."""
NAN, INF = float("nan"), float("inf")
FINITE = "not a finite number"


def bad(id: str, path: str, value: Any, words: tuple[str, ...], field: str,
        more: dict[str, Any] | None = None, delete: tuple[str, ...] = (),
        where: str | None = None) -> Case:
    """``path`` of the packer set to ``value`` (deleted when in ``delete``): the message
    names the file, the line and the field of ``where`` (default ``path``) and holds
    ``words``."""
    changes = {**HERE, **(more or {})}
    if path not in delete:
        changes[path] = value
    text = edited(BASE, set=changes, delete=delete)
    return Case(id, design=text, words=(*at(text, where or path), *words),
                fields=(f"machine:{field}",))


def missing(id: str, path: str, field: str) -> Case:
    return bad(id, path, None, ("required field is missing",), field, delete=(path,))


def nine_axes() -> dict[str, Any]:
    data = yaml.safe_load(edited(BASE, set=HERE))
    data["axes"] = [{**data["axes"][1], "name": f"axis {i}"}
                    for i in range(MAX_MACHINE_AXES + 1)]
    return data


_NINE = yaml.safe_dump(nine_axes(), sort_keys=False)

CASES = [
    bad("name-nan", "name", NAN, (FINITE,), "name"),
    bad("machine-a-list", "machine", [1], ("expected a mapping",), "machine"),
    bad("machine-unknown-key", "machine.speed", "60 rpm", ("unknown field", "master_speed"),
        "machine"),
    bad("cycle-nan", "machine.cycle", NAN, (FINITE,), "machine.cycle"),
    bad("cycle-a-time", "machine.cycle", "1 s", ("expected an angle",), "machine.cycle"),
    bad("cycle-a-list", "machine.cycle", [1, 2], ("expected an angle",), "machine.cycle"),
    bad("master-speed-inf", "machine.master_speed", INF, (FINITE,), "machine.master_speed"),
    bad("master-speed-a-length", "machine.master_speed", "5 m",
        ("expected an angular speed",), "machine.master_speed"),
    bad("master-speed-a-word", "machine.master_speed", "fastest",
        ("expected an angular speed",), "machine.master_speed"),
    bad("master-speed-huge", "machine.master_speed", 1e300, ("[1e-6, 1e6] rad/s",),
        "machine.master_speed"),
    bad("cycle-time-nan", "machine.cycle_time", NAN, (FINITE,), "machine.cycle_time",
        delete=("machine.master_speed",)),
    bad("cycle-time-an-angle", "machine.cycle_time", "90 deg", ("expected a time",),
        "machine.cycle_time", delete=("machine.master_speed",)),
    bad("axes-a-mapping", "axes", {"table": 1}, ("expected a list",), "axes"),
    bad("axes-null", "axes", None, ("expected a list",), "axes"),
    Case("axes-over-the-limit", design=_NINE,
         words=(*at(_NINE, "axes"), f"{MAX_MACHINE_AXES + 1} axes",
                f"the limit is {MAX_MACHINE_AXES}", "MAX_MACHINE_AXES"),
         fields=("machine:axes",)),
    bad("axis-not-a-mapping", "axes[1]", "pusher", ("expected a mapping",), "axes"),
    bad("axis-unknown-key", "axes[0].phase", "10 deg", ("unknown field", "start"), "axes"),
    bad("axis-name-a-number", "axes[0].name", [1], ("expected text",), "axes.name"),
    bad("axis-name-empty", "axes[0].name", "", ("empty",), "axes.name"),
    bad("axis-task-a-list", "axes[0].task", [1], ("expected a mapping",), "axes.task"),
    bad("axis-task-unknown-key", "axes[0].task.duration", "1 s",
        ("unknown field", "move"), "axes.task"),
    missing("axis-displacement-missing", "axes[0].task.displacement", "axes.task.displacement"),
    bad("axis-displacement-nan", "axes[0].task.displacement", NAN, (FINITE,),
        "axes.task.displacement"),
    bad("axis-displacement-a-time", "axes[0].task.displacement", "1 s",
        ("expected an angle",), "axes.task.displacement"),
    missing("axis-move-missing", "axes[0].task.move", "axes.task.move"),
    bad("axis-move-nan", "axes[0].task.move", NAN, (FINITE,), "axes.task.move"),
    bad("axis-move-a-length", "axes[0].task.move", "10 mm", ("expected an angle",),
        "axes.task.move"),
    bad("axis-dwell-inf", "axes[0].task.dwell", INF, (FINITE,), "axes.task.dwell"),
    bad("axis-dwell-a-time", "axes[0].task.dwell", "1 s", ("expected an angle",),
        "axes.task.dwell"),
    bad("axis-return-a-number", "axes[1].task.return", 1, ("true or false",),
        "axes.task.return"),
    bad("axis-start-nan", "axes[1].start", NAN, (FINITE,), "axes.start"),
    bad("axis-start-a-time", "axes[1].start", "1 s", ("expected an angle",), "axes.start"),
    bad("axis-laws-empty", "axes[0].laws", [], ("laws",), "axes.laws"),
    bad("axis-motors-a-number", "axes[0].motors", 3, ("expected a list",), "axes.motors"),
    bad("axis-drives-unknown", "axes[0].drives", ["no-such-drives"],
        ("unknown drive catalog",), "axes.drives", where="axes[0].drives[0]"),
    bad("axis-load-inertia-nan", "axes[0].load.inertia", NAN, (FINITE,), "axes.load.inertia"),
    bad("axis-ratio-inf", "axes[0].transmission.ratio", INF, (FINITE,),
        "axes.transmission[gearbox].ratio"),
    bad("axis-limits-margin-nan", "axes[0].limits.torque_margin", NAN, (FINITE,),
        "axes.limits.torque_margin"),
    bad("bus-a-list", "bus", [1], ("expected a mapping",), "bus"),
    bad("bus-unknown-key", "bus.volts", "300 V", ("unknown field", "voltage"), "bus"),
    bad("bus-capacitance-nan", "bus.capacitance", NAN, (FINITE,), "bus.capacitance"),
    bad("bus-capacitance-a-voltage", "bus.capacitance", "300 V",
        ("expected a capacitance",), "bus.capacitance"),
    bad("bus-voltage-inf", "bus.voltage", INF, (FINITE,), "bus.voltage"),
    bad("bus-voltage-a-current", "bus.voltage", "3 A", ("expected a voltage",),
        "bus.voltage"),
    bad("bus-threshold-nan", "bus.braking_threshold", NAN, (FINITE,), "bus.braking_threshold"),
    bad("bus-threshold-huge", "bus.braking_threshold", "1e6 V", ("[1, 1e4] V",),
        "bus.braking_threshold"),
    bad("bus-resistor-nan", "bus.braking_resistor_power", NAN, (FINITE,),
        "bus.braking_resistor_power"),
    bad("bus-resistor-a-voltage", "bus.braking_resistor_power", "3 V",
        ("expected a power",), "bus.braking_resistor_power"),
]


@pytest.mark.parametrize("case", CASES, ids=str)
def test_bad_machine_field(case: Case, tmp_path: Path) -> None:
    run_case(case, tmp_path)


def test_case_ids_are_unique_and_fields_are_the_models() -> None:
    assert_well_formed(CASES)


# ------------------------------------------------------------ the largest accepted machine

GIB = 1024**3

_UNDER_LIMIT = """
import resource, sys
resource.setrlimit(resource.RLIMIT_AS, ({limit}, {limit}))
from sizer.cli.app import main
main(sys.argv[1:])
"""


def largest_machine() -> dict[str, Any]:
    """MAX_MACHINE_AXES copies of the packer's pusher, one law each, at a given master
    speed (each axis sized once)."""
    data = yaml.safe_load((EXAMPLES / BASE).read_text(encoding="utf-8"))
    pusher = data["axes"][1]
    pusher["motors"] = str(EXAMPLES / "catalogs" / "example-servo.yaml")
    pusher["laws"] = ["cycloidal"]
    data["axes"] = [{**pusher, "name": f"pusher {i}"} for i in range(MAX_MACHINE_AXES)]
    data["machine"] = {"cycle": "360 deg", "master_speed": "30 rpm"}
    return data


@pytest.mark.skipif(not hasattr(resource, "RLIMIT_AS"), reason="needs RLIMIT_AS")
def test_the_largest_machine_is_sized_under_2_gib(tmp_path: Path) -> None:
    path = tmp_path / "machine.yaml"
    path.write_text(yaml.safe_dump(largest_machine(), sort_keys=False), encoding="utf-8")
    result = subprocess.run([sys.executable, "-c", _UNDER_LIMIT.format(limit=2 * GIB),
                             "size", str(path), "-j", "1"],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr[-2000:]
    assert f"pusher {MAX_MACHINE_AXES - 1}" in result.stdout
    assert "Traceback" not in result.stderr


def test_a_minimized_machine_reports_progress_after_each_axis(monkeypatch) -> None:
    """With ``master_speed: minimize`` each axis's search for its speed is a step: the
    callback comes after each axis's search, before the next one starts (not once every
    axis is done)."""
    from sizer.io.machine_loader import load_machine
    from sizer.sizing import machine as machine_speed
    from sizer.sizing.machine import size_machine

    machine = load_machine(EXAMPLES / BASE)
    log: list[str] = []
    search = machine_speed.axis_cycle_time

    def logged(axis, *args, **kwargs):  # type: ignore[no-untyped-def]
        log.append(f"search {axis.name}")
        return search(axis, *args, **kwargs)

    monkeypatch.setattr(machine_speed, "axis_cycle_time", logged)
    size_machine(machine, progress=lambda done, total: log.append(f"{done}/{total}"))
    assert log[:4] == ["0/4", "search table", "1/4", "search pusher"]
    assert log[4:] == ["2/4", "3/4", "4/4"]
