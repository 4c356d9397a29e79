"""A machine sized at its fastest master speed against its axes sized alone (issue 34).

    python benchmarks/bench_machine.py              # the two-axis packer and 8 axes
    python benchmarks/bench_machine.py --repeat 5

Two machines in ``master_speed: minimize``: examples/machines/two-axis-packer.yaml, and a
synthetic machine of 8 axes built from the bundled examples' designs (the packer's two
axes, the indexing tables fastest / with catalog gearboxes / with a vibration limit, the
slider-crank press and the driven four-bar, their moves put on one 360 deg master). Each
is timed (CPU time, best of ``--repeat``) in the same run as:

- reference: each axis sized alone, as its design file would be (``duration: minimize``
  with the dwell it has at the machine's speed: one size_design per axis);
- machine: sizer.sizing.machine.size_machine (each axis's fastest T_c, then every axis
  sized at the slowest one's, then the shared bus);
- search: the same with every axis's T_c found by the search on phi (one sizing per step,
  searched_cycle_time: what size_machine did before issue 34, and still does for laws
  chosen per duration).

Prints machine / reference (goal <= 2) and search / reference, and checks that both
give the same cycle time (to 1e-12). Exits 1 when the goal is missed or they differ.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import yaml

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # this checkout's sizer

from sizer import api  # noqa: E402
from sizer.model.machine import Machine  # noqa: E402
from sizer.sizing import machine as machine_speed  # noqa: E402
from sizer.sizing.engine import size_design  # noqa: E402

EXAMPLES = ROOT / "examples"
GOAL_RATIO = 2.0
PACKER = EXAMPLES / "machines" / "two-axis-packer.yaml"
DESIGNS = (("indexing-table-fastest.yaml", "60 deg"), ("indexing-table-gearboxes.yaml", "80 deg"),
           ("indexing-table-vibration.yaml", "150 deg"), ("press-slider-crank.yaml", "100 deg"),
           ("four-bar-rocker-driven.yaml", "90 deg"), ("indexing-table.yaml", "120 deg"))
"""The examples' designs that become axes, with their moves in master angle."""


def axis_of(file: str, move: str, start: int) -> dict[str, Any]:
    data = yaml.safe_load((EXAMPLES / file).read_text(encoding="utf-8"))
    for key in ("check", "efficiency_applies_to"):
        data.pop(key, None)
    task = data["task"]
    data["task"] = {"displacement": task["displacement"], "move": move,
                    "return": bool(task.get("return", False))}
    data["laws"] = [law for law in data["laws"] if isinstance(law, str) and "auto" not in law]
    return {**data, "name": file.removesuffix(".yaml"), "start": f"{start} deg"}


def eight_axes() -> Machine:
    packer = yaml.safe_load(PACKER.read_text(encoding="utf-8"))
    for a in packer["axes"]:
        a["motors"] = str(EXAMPLES / "catalogs" / "example-servo.yaml")
    axes = packer["axes"] + [axis_of(f, m, 30 * k) for k, (f, m) in enumerate(DESIGNS)]
    data = {"name": "eight axes", "machine": {"cycle": "360 deg", "master_speed": "minimize"},
            "axes": axes}
    return api.load_machine(data, base=EXAMPLES)


def cpu(run: Callable[[], Any], repeat: int) -> tuple[float, Any]:
    best, out = float("inf"), None
    for _ in range(repeat):
        start = time.process_time()
        out = run()
        best = min(best, time.process_time() - start)
    return best, out


def alone(machine: Machine, cycle_time: float) -> None:
    """Each axis sized alone in minimize mode with its dwell at ``cycle_time``."""
    for axis in machine.axes:
        size_design(axis.minimizing(axis.dwell * cycle_time / machine.cycle_angle))


def searched(machine: Machine) -> Any:
    """size_machine with every axis's T_c by the search on phi."""
    kept = machine_speed.axis_cycle_time
    machine_speed.axis_cycle_time = machine_speed.searched_cycle_time  # type: ignore[assignment]
    try:
        return machine_speed.size_machine(machine)
    finally:
        machine_speed.axis_cycle_time = kept  # type: ignore[assignment]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    ok = True
    for machine in (api.load_machine(PACKER), eight_axes()):
        machine_speed.size_machine(machine)  # imports and law caches warm
        fast, result = cpu(lambda m=machine: machine_speed.size_machine(m), args.repeat)
        assert result.cycle_time is not None
        reference, _ = cpu(lambda m=machine, t=result.cycle_time: alone(m, t), args.repeat)
        slow, before = cpu(lambda m=machine: searched(m), args.repeat)
        same = abs(before.cycle_time - result.cycle_time) <= 1e-12 * result.cycle_time
        ratio = fast / reference
        ok &= ratio <= GOAL_RATIO and same
        print(f"{machine.name} ({len(machine.axes)} axes, T_c {result.cycle_time:.12g} s, "
              f"limited by {result.limiting_axis}): axes alone {reference * 1e3:.0f} ms, "
              f"machine {fast * 1e3:.0f} ms = {ratio:.2f}x (goal <= {GOAL_RATIO:g}x), "
              f"search on phi {slow * 1e3:.0f} ms = {slow / reference:.2f}x; "
              f"same T_c: {same} ({abs(before.cycle_time / result.cycle_time - 1):.1e})")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
