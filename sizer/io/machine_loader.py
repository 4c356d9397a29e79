"""Load a machine file (several axes on one master, book sec. 5.3) into a Machine.

    load_machine("packer.yaml")        -> Machine
    is_machine_file("packer.yaml")     -> True when the file has ``axes:`` (sizer.io.file_kind)
    machine_schema()                   -> JSON Schema (draft 2020-12)

Each axis is loaded as a design file would be (sizer.io.loader: its load, transmission,
laws, motors and drives, with the same messages), its task built from the master angles;
an error in an axis names the machine file, the line and the field under ``axes[i]``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from sizer.errors import UserError
from sizer.input_limits import MAX_DESIGN_BYTES, MAX_DESIGN_NODES
from sizer.io.file_kind import is_machine_data, is_machine_file
from sizer.io.schema.machine_inputs import MINIMIZE, AxisInput, MachineFile
from sizer.io.validation import validate
from sizer.io.yaml_source import YamlSource, format_path, parse_mapping, read_yaml
from sizer.model.machine import Bus, Machine, MachineAxis, bus_level_fault

__all__ = ["is_machine_data", "is_machine_file", "load_machine", "load_machine_data",
           "machine_schema"]

FIT = 1e-9
"""Relative tolerance of an axis's moves and dwells against the machine cycle."""


def load_machine(path: str | Path) -> Machine:
    """Read a machine file into a Machine (SI)."""
    path = Path(path)
    source = read_yaml(path, limit=MAX_DESIGN_BYTES, max_nodes=MAX_DESIGN_NODES)
    return _machine_of(source, path.parent, path.stem, [path])


def load_machine_data(data: Mapping[str, Any], *, base: Path | None = None,
                      name: str = "machine") -> Machine:
    """A machine given as a mapping (``<machine>`` for the file name in messages)."""
    source = parse_mapping(data, "machine")
    return _machine_of(source, base or Path.cwd(), name, [])


def _machine_of(source: YamlSource, folder: Path, name: str, files: list[Path]) -> Machine:
    model = validate(MachineFile, source)
    cycle = model.machine.cycle
    axes = []
    warnings: list[str] = []
    read: list[Path] = list(files)
    for i, (given, raw) in enumerate(zip(model.axes, source.data["axes"], strict=True)):
        axis = _axis(given, raw, i, cycle, source, folder, files)
        axes.append(axis)
        warnings += axis.design.warnings
        read += [f for f in axis.design.files if f not in read]
    speed = model.machine.master_speed
    if model.machine.cycle_time is not None:
        speed = cycle / model.machine.cycle_time
    assert speed is not None  # master_speed or cycle_time: one of them (MachineInput._speed)
    bus = None
    if model.bus is not None:
        bus = Bus(model.bus.capacitance, model.bus.voltage, model.bus.braking_threshold,
                  model.bus.braking_resistor_power)
        fault = bus_level_fault(bus.voltage, bus.braking_threshold)
        if fault is not None:
            raise source.error(fault[1], ("bus", fault[0]))
    return Machine(axes=tuple(axes), cycle_angle=cycle,
                   master_speed=None if speed == MINIMIZE else float(speed),
                   bus=bus, name=model.name if model.name is not None else name,
                   warnings=tuple(warnings), files=tuple(read))


def _axis(given: AxisInput, raw: Mapping[str, Any], index: int, cycle: float,
          source: YamlSource, folder: Path, files: list[Path]) -> MachineAxis:
    """One axis: its design through the design loader, its timing on the master."""
    from sizer.io.loader import design_of_source

    at = ("axes", index)
    moves = 2 if given.task.return_move else 1
    move = given.task.move
    dwell = given.task.dwell
    if dwell is None:
        dwell = cycle / moves - move
        if dwell < -FIT * cycle:
            raise source.error(f"{moves} x {math.degrees(move):.6g} deg of moves do not fit "
                               f"in the machine cycle of {math.degrees(cycle):.6g} deg",
                               (*at, "task", "move"))
        dwell = max(dwell, 0.0)
    elif abs(moves * (move + dwell) - cycle) > FIT * cycle:
        raise source.error(f"move and dwell take {moves * math.degrees(move + dwell):.6g} "
                           f"deg, the machine cycle {math.degrees(cycle):.6g} deg: they must "
                           "add up (omit dwell to rest for the rest of the cycle)",
                           (*at, "task", "dwell"))
    else:
        dwell = max(cycle / moves - move, 0.0)  # the same, to the last digit
    if given.start >= cycle:
        raise source.error(f"must be below the machine cycle of {math.degrees(cycle):.6g} deg",
                           (*at, "start"))
    data = {k: v for k, v in raw.items() if k != "start"}
    task = raw["task"]
    data["task"] = {"displacement": task["displacement"], "duration": MINIMIZE,
                    "return": bool(task.get("return", False))}
    lines = {path[2:]: line for path, line in source.lines.items() if path[:2] == at}
    sub = YamlSource(data, source.file, lines)
    try:
        design = design_of_source(sub, folder, given.name, files, plans=False)
    except UserError as error:
        if error.file not in (None, source.file) or not error.field:
            raise
        raise UserError(error.message, file=error.file, line=error.line,
                        field=f"{format_path(at)}.{error.field}") from None
    return MachineAxis(given.name, design, move, dwell, given.start)


def machine_schema() -> dict[str, Any]:
    """JSON Schema of the machine file (for ``sizer schema machine``)."""
    from sizer.io.loader import schema_document

    return schema_document(MachineFile, "machine")
