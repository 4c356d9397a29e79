"""The residual vibration of each law over a range of durations (``sizer vibration``).

The rows are the core's :class:`~sizer.sizing.vibration_check.VibrationSweep` as it is:
one line per duration (the move duration T of the task, or the scale of a cycle's free
durations), one column per law, the amplitude of the vibration the moves leave at the
load (book sec. 7.2), and whether it is within the design's limit.

- JSON: ``{"format", "design", "natural_frequency", "damping_ratio", "limit", "unit",
  "durations", "laws": [{"spec", "label", "residual": [...], "tracking_error": [...]}]}``,
  SI (the tracking error: the peak |x - y| during the task's move from rest; null for a
  cycle).
- CSV: one line per duration, SI units in the headers, full precision; the residuals,
  then the tracking errors.
- Markdown and the terminal table: T in ms, amplitudes in um or arcsec, a ``*`` beside
  an amplitude above the limit.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from sizer.laws.data_spec import law_label
from sizer.report.csv_text import render_csv
from sizer.report.formats import Rendered
from sizer.report.json_text import render_json
from sizer.report.markdown_table import render_markdown_table
from sizer.report.numbers import full, short
from sizer.report.table import Column, Table, make_table
from sizer.report.text_table import render_text_table

if TYPE_CHECKING:
    from sizer.model.domain import Design
    from sizer.sizing.vibration_check import VibrationSweep

FORMAT = "sizer.vibration/1"
"""The ``format`` of the JSON document: its name and version."""

OVER = "*"
"""Mark of an amplitude above the design's limit in the human-readable tables."""


def display_unit(linear: bool) -> tuple[str, float]:
    """The display unit of an amplitude at the load and its factor from SI."""
    return ("um", 1e6) if linear else ("arcsec", 180.0 / math.pi * 3600.0)


class VibrationDocument(Rendered):
    """A sweep of durations for every law, in every format."""

    def __init__(self, sweep: VibrationSweep, design: Design) -> None:
        self.sweep = sweep
        self.design = design
        self.linear = design.task.linear
        self.cycle = design.cycle is not None

    @property
    def duration_name(self) -> str:
        return "scale" if self.cycle else "T"

    @property
    def title(self) -> str:
        mode = self.design.load.elastic
        assert mode is not None
        limit = ""
        if self.sweep.limit is not None:
            unit, factor = display_unit(self.linear)
            limit = f", limit {short(self.sweep.limit * factor)} {unit}"
        what = "each cycle's worst move" if self.cycle else "each move"
        return (f"{self.design.name or 'design'}: residual vibration of {what}, mode "
                f"{short(mode.natural_frequency)} Hz, damping {short(mode.damping_ratio)}"
                f"{limit}")

    def _over(self, value: float) -> bool:
        return self.sweep.limit is not None and value > self.sweep.limit * (1.0 + 1e-9)

    def table(self) -> Table:
        unit, factor = display_unit(self.linear)
        head = "scale" if self.cycle else "T [ms]"
        columns = (Column(head), *(Column(f"{law_label(law.spec)} [{unit}]")
                                   for law in self.sweep.laws))
        rows = []
        for i, s in enumerate(self.sweep.scales):
            cells = [short(s) if self.cycle else short(s * 1000.0)]
            for values in self.sweep.residual:
                value = float(values[i])
                cells.append(short(value * factor) + (OVER if self._over(value) else ""))
            rows.append(tuple(cells))
        return make_table(columns, rows, title=self.title)

    def footer(self) -> list[str]:
        lines = ["amplitude of the load's free vibration after each move (book sec. 7.2, "
                 "exact linear response of the mode of sec. 7.1.1)"]
        if self.sweep.tracking is not None:
            lines.append("CSV and JSON also give the peak tracking error |x - y| during the "
                         "move, started at rest")
        if self.design.load.elastic is not None and self.design.load.elastic.damping_ratio > 0:
            lines.append("in the steady state of the repeated cycle (what a move leaves is "
                         "carried through the dwells into the next)")
        else:
            lines.append("undamped: the cycle run once from rest")
        if self.sweep.limit is not None:
            lines.append(f"{OVER}: above the limit")
        return lines

    def csv(self) -> str:
        unit = "m" if self.linear else "rad"
        head = "scale [1]" if self.cycle else "T [s]"
        headers = (head, *(f"{law.spec} [{unit}]" for law in self.sweep.laws))
        columns = list(self.sweep.residual)
        if self.sweep.tracking is not None:
            headers = (*headers, *(f"tracking error {law.spec} [{unit}]"
                                   for law in self.sweep.laws))
            columns += list(self.sweep.tracking)
        rows = ((full(float(s)), *(full(float(v[i])) for v in columns))
                for i, s in enumerate(self.sweep.scales))
        return render_csv(headers, rows)

    def json(self) -> str:
        mode = self.design.load.elastic
        assert mode is not None
        document: dict[str, Any] = {
            "format": FORMAT,
            "design": self.design.name,
            "natural_frequency": mode.natural_frequency,
            "damping_ratio": mode.damping_ratio,
            "limit": self.sweep.limit,
            "unit": "m" if self.linear else "rad",
            "durations": "scale" if self.cycle else "T [s]",
            "scales": [float(s) for s in self.sweep.scales],
            "laws": [{"spec": law.spec, "label": law_label(law.spec),
                      "residual": [float(v) for v in values],
                      "tracking_error": (None if self.sweep.tracking is None else
                                         [float(v) for v in self.sweep.tracking[k]])}
                     for k, (law, values) in enumerate(zip(self.sweep.laws,
                                                           self.sweep.residual, strict=True))],
        }
        return render_json(document)

    def markdown(self) -> str:
        return (f"**{self.title}**\n\n" + render_markdown_table(self.table()) + "\n"
                + "".join(f"- {line}\n" for line in self.footer()))

    def plain_text(self) -> str:
        return (self.title + "\n\n" + render_text_table(self.table()) + "\n"
                + "\n".join(self.footer()) + "\n")
