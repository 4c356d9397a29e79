"""The verdict of ``sizer check`` on the design's chosen motor and law: text and JSON.

The text lists every check (``Check.describe()``), then the machine cycle segment by
segment (:mod:`sizer.report.segment_table`, when the pair has a duration), and ends with
one line: ``PASS`` with the binding limit, or ``FAIL`` with each limit that fails and by
how much (in minimize mode with no feasible duration: the engine's reason). The JSON
object has the same segments under ``segments`` (null without a duration).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from sizer.laws.data_spec import law_label
from sizer.report.candidate_row import RPM_PER_RAD_S, check_line, check_passed, result_json
from sizer.report.cycle_summary import duration_name
from sizer.report.design_summary import design_summary
from sizer.report.figure_grades import chosen_provenance
from sizer.report.json_text import render_json
from sizer.report.numbers import short, short_or_na
from sizer.report.segment_table import SegmentDocument, breakdown_json, indented_text
from sizer.report.sizing_table import RESULT_UNITS

if TYPE_CHECKING:
    from sizer.model.domain import Design
    from sizer.sizing import CandidateResult
    from sizer.sizing.samples import SegmentBreakdown


FORMAT = "sizer.check/1"
"""The ``format`` of the JSON document: its name and version, bumped on incompatible changes."""


class CheckDocument:
    """One motor with one law against the design's limits."""

    def __init__(self, result: CandidateResult, design: Design,
                 notes: tuple[str, ...] = (),
                 segments: SegmentBreakdown | None = None) -> None:
        self.result = result
        self.design = design
        self.notes = notes
        self.segments = segments

    @property
    def passed(self) -> bool:
        return bool(self.result.feasible)

    def _requirements(self) -> str:
        r = self.result
        if r.duration is None:
            return "no feasible duration"
        parts = [f"{duration_name(self.design)} = {short(r.duration * 1000.0)} ms"]
        parts.append(f"peak torque {short_or_na(r.peak_torque, unit='N*m')}")
        parts.append(f"rms torque {short_or_na(r.rms_torque, unit='N*m')}")
        if r.max_speed is not None:
            parts.append(f"max speed {short_or_na(r.max_speed, RPM_PER_RAD_S, 'rpm')}")
        return ", ".join(parts) + " (at the motor shaft)"

    def text(self) -> str:
        r = self.result
        name = self.design.name or "design"
        lines = [f"check {name}: motor {r.motor}, law {law_label(r.spec)}",
                 f"  {self._requirements()}"]
        if r.duration is not None:  # else the checks are at no real duration: see FAIL
            lines += [f"  {check_line(r, c)}" for c in r.checks]
        lines += [f"  note: {note}" for note in self.notes]
        if self.segments is not None:
            lines += indented_text(SegmentDocument(self.segments, self.design)).splitlines()
        if self.passed:
            lines.append(f"PASS: {r.motor} with {law_label(r.spec)} meets every limit with "
                         f"the required margins (limiting: {r.limiting})")
        else:
            failing = [check_line(r, c) for c in r.checks if not check_passed(r, c)]
            if self.design.task.minimize or not failing:
                failing = [r.reason]  # 'no duration is feasible: ...'
            lines.append(f"FAIL: {r.motor} with {law_label(r.spec)}: " + "; ".join(failing))
        return "\n".join(lines) + "\n"

    def data(self) -> dict[str, Any]:
        """The JSON object: the design, the verdict, the units and the pair's result."""
        return {
            "format": FORMAT,
            "design": {**design_summary(self.design, self.notes),
                       "figure_sources": chosen_provenance([self.result])},
            "passed": self.passed,
            "units": RESULT_UNITS,
            "result": result_json(self.result),
            "segments": (None if self.segments is None
                         else breakdown_json(self.segments, self.design.task.linear)),
        }

    def json(self) -> str:
        return render_json(self.data())
