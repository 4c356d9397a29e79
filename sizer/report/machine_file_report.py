"""A Markdown report of a sized machine (``sizer report`` of a machine file).

DIR/report.md states the master speed, the axis that sets it, each axis's timing and
choice and the shared bus, with the bus power figure (bus.png); each axis has its own
design report (sizer.report.design_report) in DIR/<axis>/, linked from the table.
Deterministic text; the numbers are the MachineResult's.
"""

from __future__ import annotations

import re
from pathlib import Path

from sizer.model.machine import Machine
from sizer.report.design_report import REPORT_FILE, report_directory, write_report
from sizer.report.machine_report import MachineDocument
from sizer.report.output import write_text_atomically
from sizer.sizing.machine import MachineResult

BUS_FIGURE = "bus.png"


def axis_folder(name: str, index: int) -> str:
    """A folder name for an axis: its name's letters, digits, '-' and '_', numbered."""
    slug = re.sub(r"[^A-Za-z0-9_-]+", "-", name).strip("-")[:40] or "axis"
    return f"{index + 1}-{slug}"


def machine_markdown(document: MachineDocument, folders: list[str], bus_figure: bool) -> str:
    head, *rest = document.lines()
    text = f"# {head}\n\n" + "".join(f"- {line.strip()}\n" for line in rest)
    if bus_figure:
        text += f"\n![DC bus power over the machine cycle]({BUS_FIGURE})\n"
    text += "\n## Axes\n\n| axis | chosen pair | report |\n| --- | --- | --- |\n"
    for axis, folder in zip(document.result.axes, folders, strict=True):
        c = axis.chosen
        pair = " ".join(x for x in (c.motor, c.drive, c.spec) if x) if c else "none feasible"
        text += f"| {axis.name} | {pair} | [{folder}/{REPORT_FILE}]({folder}/{REPORT_FILE}) |\n"
    return text


def write_machine_report(machine: Machine, result: MachineResult, directory: Path | str, *,
                         top: int, best: int, rank_by: str | None, dpi: float) -> list[Path]:
    """Write DIR/report.md, the bus figure and each axis's report; the paths written,
    report.md first."""
    from sizer.report.plots import save_figure
    from sizer.report.plots.bus_power import bus_figure

    directory = report_directory(directory)
    document = MachineDocument(result, machine, rank_by=rank_by, top=top)
    folders = [axis_folder(a.name, i) for i, a in enumerate(result.axes)]
    written: list[Path] = []
    for axis, folder in zip(result.axes, folders, strict=True):
        written += write_report(axis.design, axis.sizing, directory / folder, top=top,
                                best=best, rank_by=rank_by, source=axis.name, dpi=dpi)
    if result.bus is not None:
        figure = bus_figure(result.bus, dpi=dpi, title=result.name)
        written.insert(0, save_figure(figure, directory / BUS_FIGURE, dpi=dpi))
    path = directory / REPORT_FILE
    write_text_atomically(path, machine_markdown(document, folders, result.bus is not None))
    return [path, *written]
