"""A machine's sizing (``sizer size`` of a machine file) in every format.

- JSON: ``{"format", "machine", "axes", "bus", "feasible", "reason"}``, SI (rad, rad/s, s,
  W, J); each axis holds its timing, its choice and its ranked sizing (the JSON of
  sizer.report.sizing_table, without its ``format``).
- CSV: the shown rows of every axis, one header (the union of the axes' columns) with
  ``axis`` first.
- Markdown and the terminal: the machine's lines (master speed, which axis sets it, each
  axis's timing and choice, the bus), then each axis's table.

Nothing is decided here: the verdicts are the MachineResult's (sizer.sizing.machine).
"""

from __future__ import annotations

import csv
import io
import json
import math
from pathlib import Path
from typing import Any

from sizer.model.machine import Machine
from sizer.report.csv_text import render_csv
from sizer.report.formats import Format, Rendered
from sizer.report.json_text import render_json
from sizer.report.numbers import finite_or_none, short
from sizer.report.output import emit, stdout_is_terminal
from sizer.report.sizing_table import SizingDocument, print_terminal_table
from sizer.sizing.machine import BusResult, MachineResult

FORMAT = "sizer.machine/1"
RPM = 30.0 / math.pi
BUS_UNITS = {"power": "W", "energy": "J (per machine cycle, or per stop)",
             "capacitance": "F", "time": "s"}


def _deg(value: float) -> str:
    return f"{short(math.degrees(value))} deg"


def _ms(value: float) -> str:
    return f"{short(value * 1000.0)} ms"


def _in_ms(value: float | None) -> str:
    """' (172.76 ms)' after an angle, or nothing for an unknown time."""
    return "" if value is None else f" ({_ms(value)})"


class MachineDocument(Rendered):
    """The result of a machine with one SizingDocument per axis."""

    def __init__(self, result: MachineResult, machine: Machine, *, rank_by: str | None = None,
                 top: int | None = None, include_infeasible: bool = False) -> None:
        self.result = result
        self.machine = machine
        self.documents = [
            SizingDocument(r.sizing, r.design, rank_by=rank_by, top=top,
                           include_infeasible=include_infeasible)
            for r in result.axes]

    @property
    def any_feasible(self) -> bool:
        return self.result.feasible

    # ---------------------------------------------------------------- lines
    def lines(self) -> list[str]:
        r = self.result
        head = (f"{r.name or 'machine'}: {len(r.axes)} axes on a "
                f"{_deg(r.cycle_angle)} master cycle")
        if r.cycle_time is None or r.master_speed is None:  # both None or neither
            head += ", no master speed suits every axis"
        else:
            speed = f"{short(r.master_speed * RPM)} rpm (cycle {_ms(r.cycle_time)})"
            by = f", set by {r.limiting_axis}" if r.limiting_axis is not None else ""
            head += (f", as fast as the slowest axis allows: {speed}{by}"
                     if r.minimize else f" at {speed}")
        out = [head]
        for axis, given in zip(r.axes, self.machine.axes, strict=True):
            text = (f"  {axis.name}: move {_deg(given.move)}{_in_ms(axis.move_time)}, dwell "
                    f"{_deg(given.dwell)}{_in_ms(axis.dwell_time)}, start {_deg(given.start)}")
            if r.minimize:
                text += (f"; alone it allows a cycle of {_ms(axis.fastest_cycle_time)}"
                         if axis.fastest_cycle_time is not None
                         else "; no master speed suits it")
            c = axis.chosen
            text += ("; chosen " + " ".join(x for x in (c.motor, c.drive, c.spec) if x)
                     if c is not None else "; no feasible pair")
            out.append(text)
        if r.bus is not None:
            out += _bus_lines(r.bus)
        out.append("machine: feasible" if r.feasible else f"machine: NOT feasible ({r.reason})")
        return out

    # ---------------------------------------------------------------- formats
    def plain_text(self) -> str:
        text = "\n".join(self.lines()) + "\n"
        for axis, doc in zip(self.result.axes, self.documents, strict=True):
            text += f"\naxis {axis.name}\n" + doc.plain_text()
        return text

    def markdown(self) -> str:
        head, *rest = self.lines()
        text = f"**{head}**\n\n" + "".join(f"- {line.strip()}\n" for line in rest)
        for axis, doc in zip(self.result.axes, self.documents, strict=True):
            text += f"\n### Axis {axis.name}\n\n" + doc.markdown()
        return text

    def csv(self) -> str:
        headers: list[str] = ["axis"]
        rows: list[dict[str, str]] = []
        for axis, doc in zip(self.result.axes, self.documents, strict=True):
            reader = csv.DictReader(io.StringIO(doc.csv()))
            headers += [h for h in reader.fieldnames or () if h not in headers]
            rows += [{"axis": axis.name, **row} for row in reader]
        return render_csv(headers, ([row.get(h, "") for h in headers] for row in rows))

    def json(self) -> str:
        r = self.result
        axes = []
        for axis, given, doc in zip(r.axes, self.machine.axes, self.documents, strict=True):
            sizing = json.loads(doc.json())
            sizing.pop("format", None)
            c = axis.chosen
            axes.append({
                "name": axis.name, "move": given.move, "dwell": given.dwell,
                "start": given.start, "move_time": axis.move_time,
                "dwell_time": axis.dwell_time, "phase": axis.phase,
                "fastest_cycle_time": finite_or_none(axis.fastest_cycle_time),
                "chosen": None if c is None else {"motor": c.motor, "drive": c.drive,
                                                  "law": c.spec, "ratio": c.ratio},
                "sizing": sizing})
        return render_json({
            "format": FORMAT,
            "machine": {"name": r.name, "mode": "minimize" if r.minimize else "given",
                        "cycle_angle": r.cycle_angle, "cycle_time": finite_or_none(r.cycle_time),
                        "master_speed": finite_or_none(r.master_speed),
                        "limiting_axis": r.limiting_axis},
            "axes": axes,
            "bus": None if r.bus is None else _bus_json(r.bus),
            "feasible": r.feasible, "reason": r.reason})


def _bus_lines(bus: BusResult) -> list[str]:
    stored = (f"the capacitors take {short(bus.absorbable_energy)} J per stop"
              if bus.absorbable_energy > 0.0 else "no bus capacitance known: the resistor "
              "takes every stop")
    lines = [
        f"  DC bus ({', '.join(bus.axes)} with their phases): peak {short(bus.peak_power)} W "
        f"drawn, {short(bus.peak_regenerative_power)} W returned, mean {short(bus.mean_power)} "
        f"W; per cycle {short(bus.motoring_energy)} J drawn, {short(bus.regenerated_energy)} J "
        f"returned",
        f"  braking: {stored}, the worst stop returns {short(bus.worst_stop_energy)} J; "
        f"resistor {short(bus.resistor_power)} W continuous (peak "
        f"{short(bus.resistor_peak_power)} W); each axis on a bus of its own (its drive's "
        f"capacitance): {short(bus.separate_resistor_power)} W",
    ]
    if bus.resistor_limit is not None:
        verdict = "ok" if bus.passed else "FAILS"
        lines.append(f"  braking resistor: {short(bus.resistor_power)} W against "
                     f"{short(bus.resistor_limit)} W ({verdict})")
    return lines


def _bus_json(bus: BusResult) -> dict[str, Any]:
    names = ("cycle_time", "peak_power", "peak_regenerative_power", "mean_power",
             "motoring_energy", "regenerated_energy", "net_energy", "capacitance",
             "absorbable_energy", "worst_stop_energy", "resistor_energy",
             "resistor_peak_power", "resistor_power", "separate_resistor_power",
             "resistor_limit")
    out: dict[str, Any] = {"axes": list(bus.axes)}
    out.update({name: finite_or_none(getattr(bus, name)) for name in names})
    out["passed"] = bus.passed
    out["units"] = BUS_UNITS
    return out


class MachineCheckDocument:
    """``sizer check`` of a machine file: the machine's lines, then PASS (every axis has a
    feasible pair at the master speed and the bus copes) or FAIL with the reason."""

    def __init__(self, result: MachineResult, machine: Machine, source: str) -> None:
        self.document = MachineDocument(result, machine)
        self.result = result
        self.source = source

    @property
    def passed(self) -> bool:
        return self.result.feasible

    def text(self) -> str:
        lines = self.document.lines()[:-1]  # the verdict line is the PASS/FAIL below
        r = self.result
        if r.feasible:
            chosen = ", ".join(f"{a.name}: {a.chosen.motor} with {a.chosen.spec}"
                               for a in r.axes if a.chosen is not None)
            lines.append(f"PASS: machine {r.name or self.source}: every axis has a feasible "
                         f"pair ({chosen})")
        else:
            lines.append(f"FAIL: machine {r.name or self.source}: {r.reason}")
        return "\n".join(lines) + "\n"

    def data(self) -> dict[str, Any]:
        out = json.loads(self.document.json())
        out["passed"] = self.passed
        return out


def publish_machine(document: MachineDocument, fmt: Format, output: Path | None) -> None:
    """Write the document to ``output`` or stdout (rich tables on a terminal)."""
    if fmt is Format.TABLE and output is None and stdout_is_terminal():
        from rich.console import Console
        from rich.text import Text

        console = Console(highlight=False)
        for line in document.lines():
            console.print(Text(line))
        for axis, doc in zip(document.result.axes, document.documents, strict=True):
            console.print()
            console.print(Text(f"axis {axis.name}", style="bold"))
            print_terminal_table(doc, console)
        return
    emit(document.render(fmt), output, escape=fmt in (Format.TABLE, Format.MD))
