"""The per-segment table of a machine cycle for one motor (``sizer segments``, issue 12).

The rows are the core's :class:`~sizer.sizing.segment_breakdown.SegmentBreakdown` as it
is, nothing recomputed: start and end time, law, peak torque, RMS torque over the segment
and its share of the cycle's integral of tau^2, peak motor speed, work at the motor
shaft, and a mark where the acceleration steps at the join with the previous segment
(a jerk impulse, the book's Fig. 3.x discontinuities).

- JSON: ``{"format", "design", "motor", "law", "cycle_time", "rms_torque", "units",
  "segments"}``, SI, the share as a fraction; ``format`` is FORMAT.
- CSV: one line per segment, SI units in the headers, full precision; no summary line
  (the cycle time is the last ``end``, the cycle's RMS torque is in the JSON and the
  tables' footer).
- Markdown and the terminal table: times in ms, speed in rpm, the share in %; a title
  above and, below, the cycle time and the cycle's RMS torque.

Torques and speeds are at the motor shaft; the acceleration step is at the load (rad/s^2,
m/s^2 on a linear axis).
"""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from sizer.laws.data_spec import law_label
from sizer.report.candidate_row import RPM_PER_RAD_S
from sizer.report.csv_text import render_csv
from sizer.report.design_summary import design_summary
from sizer.report.formats import Format, Rendered
from sizer.report.json_text import render_json
from sizer.report.markdown_table import render_markdown_table
from sizer.report.numbers import finite_or_none, full_or_empty, short, short_or_na
from sizer.report.output import emit, stdout_is_terminal
from sizer.report.table import Column, Table, make_table
from sizer.report.text_table import render_text_table

if TYPE_CHECKING:
    from sizer.model.domain import Design
    from sizer.sizing import CandidateResult
    from sizer.sizing.samples import SegmentBreakdown, SegmentRow

FORMAT = "sizer.segments/1"
"""The ``format`` of the JSON document: its name and version, bumped on incompatible changes."""

JERK_IMPULSE = "jerk impulse"
"""The join mark of a segment whose start steps the acceleration."""

SHARE_HEADER = "share of rms^2 [%]"

DROPPABLE = ("kind", "energy [J]", "start [ms]", "peak speed [rpm]", "rms torque [N*m]")
"""Columns a narrow terminal may leave out, first to last (the footer names them)."""


def acceleration_unit(linear: bool) -> str:
    """The load's acceleration unit of the axis."""
    return "m/s^2" if linear else "rad/s^2"


def segment_units(linear: bool) -> dict[str, str]:
    """Units of the JSON fields of a segment."""
    return {"start": "s", "end": "s", "peak_torque": "N*m (at the motor shaft)",
            "rms_torque": "N*m (at the motor shaft, over the segment)",
            "rms_share": "1 (the segment's part of the cycle's integral of tau^2)",
            "peak_speed": "rad/s (at the motor shaft)",
            "energy": "J (work at the motor shaft: > 0 driving, < 0 braking)",
            "acceleration_step": f"{acceleration_unit(linear)} (at the load, at the join "
                                 f"with the previous segment; nonzero: a jerk impulse)",
            "cycle_time": "s", "cycle_rms_torque": "N*m"}


def csv_headers(linear: bool) -> tuple[str, ...]:
    return ("segment", "kind", "law", "start [s]", "end [s]", "peak_torque [N*m]",
            "rms_torque [N*m]", "rms_share [1]", "peak_speed [rad/s]", "energy [J]",
            f"acceleration_step [{acceleration_unit(linear)}]", "join")


def _join(row: SegmentRow) -> str:
    return JERK_IMPULSE if row.acceleration_step != 0.0 else ""


def segment_row_json(row: SegmentRow) -> dict[str, Any]:
    """One segment as a JSON object, keys in a fixed order, SI."""
    return {
        "name": row.name,
        "kind": row.kind,
        "law": row.law,
        "start": finite_or_none(row.start),
        "end": finite_or_none(row.end),
        "peak_torque": finite_or_none(row.peak_torque),
        "rms_torque": finite_or_none(row.rms_torque),
        "rms_share": finite_or_none(row.rms_share),
        "peak_speed": finite_or_none(row.peak_speed),
        "energy": finite_or_none(row.energy),
        "acceleration_step": finite_or_none(row.acceleration_step),
        "jerk_impulse": row.acceleration_step != 0.0,
    }


def breakdown_json(breakdown: SegmentBreakdown, linear: bool) -> dict[str, Any]:
    """The breakdown as a JSON object (what ``sizer check --format json`` embeds)."""
    return {
        "motor": breakdown.motor,
        "law": breakdown.law,
        "cycle_time": finite_or_none(breakdown.cycle_time),
        "rms_torque": finite_or_none(breakdown.rms_torque),
        "units": segment_units(linear),
        "segments": [segment_row_json(row) for row in breakdown.rows],
    }


def breakdown_for(design: Design, result: CandidateResult) -> SegmentBreakdown:
    """The core's segment breakdown of a sizing result: its motor, law, duration (T_min
    in minimize mode) and transmission (its chosen ratio or gearbox). A result without a
    feasible duration has none: a UserError saying why."""
    from sizer.errors import UserError
    from sizer.sizing.checks import CheckName
    from sizer.sizing.samples import segment_breakdown

    if result.duration is None:
        raise UserError(f"{result.motor} with {law_label(result.spec)} has no feasible duration "
                        f"({result.reason}): no segments to show")
    breakdown = segment_breakdown(design, result.motor_object, result.law_object,
                                  result.duration, result.transmission)
    if any(c.name == CheckName.DEAD_POINT and not c.passed for c in result.checks):
        return _unbounded(breakdown)  # the crank's acceleration is infinite at a dead point
    return breakdown


def _unbounded(breakdown: SegmentBreakdown) -> SegmentBreakdown:
    """The breakdown of a law that fails the dead-point check: no torque, share or energy
    is a number (the samples at the dead point were read as 0), so none is shown."""
    nan = math.nan
    rows = tuple(replace(row, peak_torque=nan, rms_torque=nan, rms_share=nan, energy=nan)
                 for row in breakdown.rows)
    return replace(breakdown, rms_torque=nan, rows=rows)


class SegmentDocument(Rendered):
    """The segments of a design's cycle for one motor and law, in every format."""

    def __init__(self, breakdown: SegmentBreakdown, design: Design,
                 notes: tuple[str, ...] = (), *, feasible: bool | None = None) -> None:
        self.breakdown = breakdown
        self.design = design
        self.notes = notes
        self.feasible = feasible
        self.linear = design.task.linear

    @property
    def title(self) -> str:
        b = self.breakdown
        name = self.design.name or "design"
        return f"{name}: the cycle by segment, motor {b.motor}, law {law_label(b.law)}"

    def table(self) -> Table:
        columns = (Column("segment", "left"), Column("kind", "left"), Column("law", "left"),
                   Column("start [ms]"), Column("end [ms]"), Column("peak torque [N*m]"),
                   Column("rms torque [N*m]"), Column(SHARE_HEADER),
                   Column("peak speed [rpm]"), Column("energy [J]"),
                   Column("join", "left"))
        rows = [(row.name, row.kind, law_label(row.law or ""), short_or_na(row.start, 1000.0),
                 short_or_na(row.end, 1000.0), short_or_na(row.peak_torque),
                 short_or_na(row.rms_torque), _share(row.rms_share),
                 short_or_na(row.peak_speed, RPM_PER_RAD_S), short_or_na(row.energy),
                 self._join_text(row))
                for row in self.breakdown.rows]
        return make_table(columns, rows, title=self.title)

    def _join_text(self, row: SegmentRow) -> str:
        if row.acceleration_step == 0.0:
            return ""
        return (f"{JERK_IMPULSE} (acceleration step {short(row.acceleration_step)} "
                f"{acceleration_unit(self.linear)})")

    def summary(self) -> list[str]:
        """The cycle time and the cycle's RMS torque, and what a jerk impulse means."""
        b = self.breakdown
        rms = short_or_na(b.rms_torque, unit="N*m")
        lines = [f"cycle time {short_or_na(b.cycle_time, 1000.0)} ms, cycle rms torque {rms} (at "
                 f"the motor shaft); the shares are of the cycle's integral of tau^2"]
        if any(row.acceleration_step != 0.0 for row in b.rows):
            lines.append(f"{JERK_IMPULSE}: the acceleration steps at the segment's start (at "
                         f"the load), so the jerk is an impulse there")
        return lines

    def footer(self) -> list[str]:
        """The lines under a human-readable table: the summary, then the notes."""
        b = self.breakdown
        lines = self.summary()
        if math.isnan(b.rms_torque):
            lines.append(f"note: {b.motor} with {law_label(b.law)}: the torques are unbounded "
                         f"(the law breaks the linkage's dead-point rule: sizer check says "
                         f"where); none is shown")
        elif self.feasible is False:
            lines.append(f"note: {b.motor} with {law_label(b.law)} does not meet every "
                         f"limit (sizer check or sizer size --all say which)")
        lines += [f"note: {note}" for note in self.notes]
        return lines

    def csv(self) -> str:
        rows = ((row.name, row.kind, row.law or "",
                 *map(full_or_empty, (row.start, row.end, row.peak_torque, row.rms_torque,
                                      row.rms_share, row.peak_speed, row.energy,
                                      row.acceleration_step)), _join(row))
                for row in self.breakdown.rows)
        return render_csv(csv_headers(self.linear), rows)

    def data(self) -> dict[str, Any]:
        b = self.breakdown
        return {
            "format": FORMAT,
            "design": design_summary(self.design, self.notes),
            "motor": b.motor,
            "law": b.law,
            "feasible": self.feasible,
            "cycle_time": finite_or_none(b.cycle_time),
            "rms_torque": finite_or_none(b.rms_torque),
            "units": segment_units(self.linear),
            "segments": [segment_row_json(row) for row in b.rows],
        }

    def json(self) -> str:
        return render_json(self.data())

    def markdown(self, title: bool = True) -> str:
        text = f"**{self.title}**\n\n" if title else ""
        text += render_markdown_table(self.table())
        return text + "\n" + "".join(f"- {line}\n" for line in self.footer())

    def plain_text(self) -> str:
        return (self.title + "\n\n" + render_text_table(self.table()) + "\n"
                + "\n".join(self.footer()) + "\n")


def _share(fraction: float) -> str:
    """A share in % with one decimal ('12.5'), 'n/a' when not finite."""
    if not math.isfinite(fraction):
        return "n/a"
    return f"{fraction * 100.0:.1f}"


def indented_text(document: SegmentDocument, indent: str = "  ") -> str:
    """The plain table and its summary, each line indented (inside a ``sizer check``
    report)."""
    lines = ["segments:", *render_text_table(document.table()).splitlines(),
             *document.summary()]
    return "".join(f"{indent}{line}".rstrip() + "\n" for line in lines)


def publish_segments(document: SegmentDocument, fmt: Format, output: Path | None) -> None:
    """Write the document to ``output`` or stdout (a rich table on a terminal)."""
    if fmt is Format.TABLE and output is None and stdout_is_terminal():
        from rich.console import Console
        from rich.text import Text

        from sizer.report.printable import printable
        from sizer.report.rich_table import print_rich_table

        console = Console(highlight=False)
        dropped = print_rich_table(document.table(), wrap_headers=True, droppable=DROPPABLE,
                                   title_above=True, console=console)
        console.print()
        lines = document.footer()
        if dropped:
            lines.insert(0, f"not shown at this terminal width: {', '.join(dropped)} (a wider "
                            f"terminal, --format md or csv show every column)")
        for line in lines:
            console.print(Text(printable(line)))
        return
    emit(document.render(fmt), output, escape=fmt in (Format.TABLE, Format.MD))
