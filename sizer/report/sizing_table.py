"""The ranked motor/law table of a design (``sizer size``) in every format.

- JSON: ``{"format", "design", "ranked_by", "ranking", "units", "results"}``, SI, margins
  as fractions; ``format`` is FORMAT, ``ranking`` the rule of ``ranked_by`` in words;
  ``design.provenance`` the grades and sources of the listed motors' and drives' figures.
- CSV: one line per pair, SI units in the headers, full precision.
- Markdown and the terminal table: duration in ms, speed in rpm, margins in %; a title
  line above and, below, why the shown infeasible pairs fail and what was assumed.

Rows are the ranked results (feasible first); infeasible pairs only when asked for,
and at most ``top`` rows. The rank is the position among all pairs, so it does not
change with the options.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from sizer.laws.data_spec import law_label
from sizer.report.candidate_row import (
    CSV_HEADERS,
    percent,
    result_csv_cells,
    result_display_cells,
    result_json,
)
from sizer.report.csv_text import render_csv
from sizer.report.cycle_summary import cycle_heading, duration_name, sized_as_cycle
from sizer.report.design_summary import design_summary
from sizer.report.figure_grades import chosen_provenance
from sizer.report.formats import Format, Rendered
from sizer.report.json_text import render_json
from sizer.report.markdown_table import render_markdown_table
from sizer.report.numbers import finite_or_none, full_or_empty, short
from sizer.report.output import emit, stdout_is_terminal
from sizer.report.printable import printable
from sizer.report.rich_table import print_rich_table
from sizer.report.table import Column, Table, make_table
from sizer.report.text_table import render_text_table
from sizer.report.transmission_text import listed_ratio_text, ratio_header
from sizer.sizing.front import SIZE_OBJECTIVES
from sizer.sizing.results import Mode

if TYPE_CHECKING:
    from sizer.model.domain import Design
    from sizer.sizing import CandidateResult, SizingResult
    from sizer.sizing.front import Front

NO_FEASIBLE = "no feasible motor/law pair"
NO_DURATION_NOTE = ("n/a: no duration is feasible for the pair, so it has no operating "
                    "point (duration, torques, speed, margins); the limit that fails and by "
                    "how much are below")

FEASIBLE = {False: "feasible", True: "ok"}
SPEED = {False: "max speed [rpm]", True: "speed [rpm]"}
"""Headers of the full (False) and the compact (True, terminal) table."""

RESULT_UNITS = {"duration": "s", "peak_torque": "N*m", "rms_torque": "N*m",
                "max_speed": "rad/s", "margin": "1 (fraction of the limit left unused)",
                "price": "as in the catalog", "mass": "kg",
                "rated_power": "W (the motor's tau_c*v_n, the size it is ranked by)",
                "ratio": "motor speed / load speed (rad/rad; rad/m on a linear axis)",
                "load_speed": "rad/s (m/s on a linear axis)",
                "load_torque": "N*m (N on a linear axis)"}
"""Units of the JSON result fields (torques and speeds at the motor shaft but the load's)."""


FORMAT = "sizer.sizing/1"
"""The ``format`` of the JSON document: its name and version, bumped on incompatible changes."""


class SizingDocument(Rendered):
    """The ranked results of a design, filtered for display, in every format."""

    def __init__(self, sizing: SizingResult, design: Design, *, rank_by: str | None = None,
                 top: int | None = None, include_infeasible: bool = False,
                 front: Front | None = None, front_only: bool = False) -> None:
        self.sizing = sizing
        self.design = design
        from sizer.sizing.ranking import rank_rule

        self.rank_rule = rank_rule(rank_by, sizing.mode)
        self.rank_key = self.rank_rule.key
        if front is None:  # the default front (rated power), for the 'front' column
            from sizer.sizing.front import trade_off

            front = trade_off(sizing)
        self.front = front
        self.front_only = front_only
        ranked = list(enumerate(sizing.results, start=1))
        if front_only:  # the front alone, smallest motor first
            shown = [ranked[int(i)] for i in front.members]
        else:
            shown = [(rank, r) for rank, r in ranked if include_infeasible or r.feasible]
        self.hidden_infeasible = 0 if front_only else len(ranked) - len(shown)
        self.cut = max(0, len(shown) - top) if top is not None else 0
        self.rows: list[tuple[int, CandidateResult]] = shown[:top] if top is not None else shown

    # ---------------------------------------------------------------- texts
    @property
    def any_feasible(self) -> bool:
        return any(r.feasible for r in self.sizing.results)

    @property
    def title(self) -> str:
        task = self.design.task
        unit = "m" if task.linear else "rad"
        move = f"h = {short(task.displacement)} {unit}"
        linkage = self.design.transmission.linkage
        if linkage is not None and linkage.law_on == "crank":
            move = f"the {linkage.driven_link} turns {short(task.displacement)} rad"
        elif linkage is not None:
            from sizer.mechanics.linkages.of_stage import output_name

            move = f"the {output_name(linkage).split('_')[0]} moves {move}"
        move += (", shortest duration" if task.duration is None  # minimize
                 else f" in T = {short(task.duration * 1000.0)} ms")
        if sized_as_cycle(self.design):
            move = cycle_heading(self.design.machine_cycle)
        feasible = sum(r.feasible for r in self.sizing.results)
        name = self.design.name or "design"
        if self.front_only:
            return (f"{name}: {move}; the trade-off front: {len(self.front.members)} of "
                    f"{feasible} feasible pairs, {self.front_axes}")
        return (f"{name}: {move}; {feasible} of {len(self.sizing.results)} motor/law pairs "
                f"feasible, ranked by {self.rank_key}")

    # ---------------------------------------------------------------- the front
    @property
    def front_axes(self) -> str:
        """The front's two objectives in words ('T_min against rated power')."""
        time = (duration_name(self.design) if self.front.time_name == "duration"
                else "smallest margin")
        return f"{time} against {SIZE_OBJECTIVES[self.front.by].name}"

    def front_status(self, rank: int) -> str:
        """``knee``, ``front`` or '' for the pair of rank ``rank`` (1-based)."""
        return self.front.statuses[rank - 1]

    @property
    def with_front_column(self) -> bool:
        """The human-readable table shows the front column: with --front, and in minimize
        mode (where each row stands on the front of T_min against motor size)."""
        return self.front_only or self.sizing.mode is Mode.MINIMIZE

    def front_lines(self) -> list[str]:
        """What the front column means, the knee and what was left out."""
        if not self.with_front_column:
            return []
        better = ("faster" if self.front.time_name == "duration"
                  else "leaves more margin")
        lines = [f"front: on the trade-off front of {self.front_axes}: no other feasible "
                 f"pair both {better} and smaller; knee: the front point farthest from the "
                 f"line through its two ends, both scaled to [0, 1] (docs/trade-off.md; "
                 f"--front shows the front alone, --front-by chooses the size)"]
        knee = self.front.knee
        if knee is not None:
            r = self.sizing.results[knee]
            lines.append(f"knee: #{knee + 1} {r.motor}, {law_label(r.spec)}: "
                         f"{self._time_text(knee)}, {self._size_text(knee)}")
        elif len(self.front.members):
            lines.append("no knee: the front has fewer than 3 distinct points or does not "
                         "bulge towards the ideal point")
        if self.front.left_out:
            lines.append(f"{self.front.left_out} feasible pairs without "
                         f"{SIZE_OBJECTIVES[self.front.by].name} left out of the front")
        return lines

    def _time_text(self, position: int) -> str:
        value = float(self.front.time[position])
        if self.front.time_name == "duration":
            return f"{duration_name(self.design)} {short(value * 1000.0)} ms"
        return f"smallest margin {percent(value)} %"

    def _size_text(self, position: int) -> str:
        size = SIZE_OBJECTIVES[self.front.by]
        value = short(float(self.front.size[position]))
        return f"{size.name} {value}{f' {size.unit}' if size.unit else ''}"

    def _size_cell(self, rank: int) -> str:
        value = float(self.front.size[rank - 1])
        return short(value) if math.isfinite(value) else "n/a"

    def _front_json(self) -> dict[str, Any]:
        front = self.front

        def point(i: int) -> dict[str, Any]:
            r = self.sizing.results[i]
            return {"rank": i + 1, "motor": r.motor, "spec": r.spec,
                    "ratio": finite_or_none(r.ratio), "status": front.statuses[i],
                    "time": finite_or_none(float(front.time[i])),
                    "size": finite_or_none(float(front.size[i]))}
        return {"by": front.by.value, "time": front.time_name, "size": front.size_field,
                "units": {"time": "s" if front.time_name == "duration"
                          else "1 (the smallest margin beyond the required one)",
                          "size": SIZE_OBJECTIVES[front.by].json_unit},
                "rule": front.rule, "left_out": front.left_out,
                "knee": None if front.knee is None else point(front.knee),
                "points": [point(int(i)) for i in front.members]}

    def footer(self, dropped: Sequence[str] = ()) -> list[str]:
        """Lines under a human-readable table (``dropped``: columns a terminal left out)."""
        lines = []
        if dropped:
            every_row_ok = all(r.feasible for _, r in self.rows)
            names = [f"{h} (every row: yes)" if h in FEASIBLE.values() and every_row_ok else h
                     for h in dropped]
            lines.append(f"not shown at this terminal width: {', '.join(names)} (a wider "
                         f"terminal, --format md or csv show every column)")
        if not self.any_feasible:
            lines.append(NO_FEASIBLE)
        failing = [(rank, r) for rank, r in self.rows if not r.feasible]
        if any(r.duration is None for _, r in failing):
            lines.append(NO_DURATION_NOTE)
        if failing:
            lines.append("why these pairs fail:")
            lines += [f"  #{rank} {r.motor}, {law_label(r.spec)}: {r.reason}"
                      for rank, r in failing]
        if self.hidden_infeasible:
            lines.append(f"{self.hidden_infeasible} infeasible pairs not shown (--all shows "
                         f"them)")
        if self.cut:
            lines.append(f"{self.cut} more pairs not shown (--top)")
        lines += self.front_lines()
        if not self.front_only:
            lines.append(f"ranked by {self.rank_key}: {self.rank_rule.text}")
        lines += [f"note: {note}" for note in self.sizing.notes]
        return lines

    # --------------------------------------------------------------- formats
    @property
    def ratio_varies(self) -> bool:
        """True when the pairs do not all share one transmission ratio (a free ratio)."""
        results = self.sizing.results
        return (len({r.ratio for r in results}) > 1
                or any(r.gearbox for r in results))

    @property
    def with_drives(self) -> bool:
        """True when the design pairs motors with drives: rows show the drive."""
        return bool(self.design.drives)

    @property
    def with_vibration(self) -> bool:
        """True when the design gives the load's mode: rows show the residual vibration."""
        return self.design.load.elastic is not None

    @property
    def residual_unit(self) -> tuple[str, float]:
        """The display unit of the residual vibration and its factor from SI."""
        return ("um", 1e6) if self.design.task.linear else ("arcsec", 180.0 / math.pi * 3600.0)

    @property
    def energy_figures(self) -> tuple[str, ...]:
        """The energy and heat figures the results carry (sizer.sizing.energy_check), in
        order: the CSV and JSON show them; none for designs without those checks."""
        from sizer.sizing.energy_check import ENERGY_FIGURES

        table = self.sizing.table
        present = () if table is None else tuple(table.figures)
        return tuple(k for k in ENERGY_FIGURES if k in present)

    def table(self, compact: bool = False) -> Table:
        """The display table; ``compact`` headers for a terminal (they wrap in rich)."""
        duration = "T_min [ms]" if self.sizing.mode is Mode.MINIMIZE else "T [ms]"
        if sized_as_cycle(self.design):
            duration = f"{duration_name(self.design)} [ms]"
        with_ratio = self.ratio_varies
        with_drive = self.with_drives
        columns = (
            Column("#"), Column("motor", "left"),
            *((Column("drive", "left"),) if with_drive else ()), Column("law", "left"),
            *((Column(ratio_header(self.design), "left"),) if with_ratio else ()),
            Column(FEASIBLE[compact], "left"), Column(duration), Column("peak [N*m]"),
            Column("rms [N*m]"), Column(SPEED[compact]), Column("peak margin [%]"),
            Column("rms margin [%]"), Column("speed margin [%]"), Column("limiting", "left"),
        )
        rows = [result_display_cells(
            rank, r, ratio=listed_ratio_text(self.design, r) if with_ratio else None,
            with_drive=with_drive) for rank, r in self.rows]
        if self.with_vibration:
            unit, factor = self.residual_unit
            columns = (*columns[:-1], Column(f"residual [{unit}]"), columns[-1])
            rows = [(*row[:-1], _residual_cell(r, factor), row[-1])
                    for row, (_, r) in zip(rows, self.rows, strict=True)]
        if self.front_only:  # the objectives of the front: margin (given T), size
            size = SIZE_OBJECTIVES[self.front.by]
            extra: tuple[Column, ...] = (Column(f"{size.name} [{size.unit}]" if size.unit
                                                else size.name),)
            cells: list[tuple[str, ...]] = [(self._size_cell(rank),) for rank, _ in self.rows]
            if self.front.time_name != "duration":
                extra = (Column("min margin [%]"), *extra)
                cells = [(percent(float(self.front.time[rank - 1])), *c)
                         for c, (rank, _) in zip(cells, self.rows, strict=True)]
            columns = (*columns, *extra)
            rows = [(*row, *c) for row, c in zip(rows, cells, strict=True)]
        if self.with_front_column:
            columns = (*columns, Column("front", "left"))
            rows = [(*row, self.front_status(rank))
                    for row, (rank, _) in zip(rows, self.rows, strict=True)]
        return make_table(columns, rows, title=self.title)

    def droppable(self, compact: bool = True) -> list[str]:
        """Columns a narrow terminal may leave out, first to last: the motor's torques and
        speed (the margins say how close they are to the limits), the feasible column
        where every row is feasible, then the ratio. Margins and limiting always stay."""
        feasible = FEASIBLE[compact]
        every_row_ok = all(r.feasible for _, r in self.rows)
        order = [SPEED[compact], "peak [N*m]", "rms [N*m]", feasible,
                 ratio_header(self.design)]
        if every_row_ok:
            order.insert(0, order.pop(order.index(feasible)))
        return order

    def csv(self) -> str:
        envelope = self.design.limits.envelope
        headers: tuple[str, ...] = CSV_HEADERS
        rows = [result_csv_cells(rank, r, envelope, self.front_status(rank))
                for rank, r in self.rows]
        if self.with_vibration:
            unit = "m" if self.design.task.linear else "rad"
            headers = (*headers, f"residual_vibration [{unit}]")
            rows = [(*row, full_or_empty(r.residual_vibration))
                    for row, (_, r) in zip(rows, self.rows, strict=True)]
        energy = self.energy_figures
        if energy:  # energy and heat (issue 16), designs with those checks only
            headers = (*headers, *(f"{k} [{ENERGY_UNITS[k]}]" for k in energy))
            rows = [(*row, *(full_or_empty(r.figures.get(k)) for k in energy))
                    for row, (_, r) in zip(rows, self.rows, strict=True)]
        if self.with_drives:  # the drive after the motor (issue 16)
            headers = (*headers[:2], "drive", *headers[2:])
            rows = [(*row[:2], r.drive or "", *row[2:])
                    for row, (_, r) in zip(rows, self.rows, strict=True)]
        return render_csv(headers, rows)

    def json(self) -> str:
        return render_json({
            "format": FORMAT,
            "design": {**design_summary(self.design, self.sizing.notes),
                       "figure_sources": chosen_provenance(r for _, r in self.rows)},
            "ranked_by": self.rank_key,
            "ranking": self.rank_rule.text,
            **({"front": self._front_json()} if self.front_only else {}),
            "units": {**RESULT_UNITS, **({"residual_vibration": RESIDUAL_UNIT}
                                         if self.with_vibration else {}),
                      **{k: ENERGY_UNITS[k] for k in self.energy_figures},
                      "front": (f"'knee', 'front' or '': the pair's place on the trade-off "
                                f"front of {self.front_axes}; {self.front.rule}")},
            "results": [_with_energy(_with_residual(result_json(r, self.front_status(rank)),
                                                    r, self.with_vibration),
                                     r, self.energy_figures)
                        for rank, r in self.rows],
        })

    def markdown(self) -> str:
        footer = self.footer()
        text = f"**{self.title}**\n\n" + render_markdown_table(self.table())
        if footer:
            text += "\n" + "".join(_markdown_item(line) for line in footer)
        return text

    def plain_text(self) -> str:
        footer = self.footer()
        text = self.title + "\n\n" + render_text_table(self.table())
        if footer:
            text += "\n" + "\n".join(footer) + "\n"
        return text



RESIDUAL_UNIT = "rad (m on a linear axis): amplitude at the load (book sec. 7.2)"


def _with_residual(fields: dict[str, Any], result: CandidateResult,
                   shown: bool) -> dict[str, Any]:
    """The JSON of a result with its residual vibration (designs with a mode only)."""
    if shown:
        fields["residual_vibration"] = result.residual_vibration
    return fields


ENERGY_UNITS = {"regenerated_energy": "J", "braking_power": "W", "winding_rise": "K",
                "peak_power": "W", "mean_power": "W", "copper_loss": "W",
                "cycle_energy": "J", "stop_energy": "J", "braking_peak_power": "W"}
"""Units of the energy and heat figures: J per machine cycle returned to the DC bus, the
braking resistor's continuous power, the winding's temperature rise over the ambient, the
peak and mean motoring power at the shaft, the mean copper loss, the net energy drawn
from the bus per machine cycle, the largest stop's energy and the resistor's peak power."""


def _with_energy(fields: dict[str, Any], result: CandidateResult,
                 shown: tuple[str, ...]) -> dict[str, Any]:
    """The JSON of a result with the energy and heat figures the design has."""
    return fields | {name: result.figures.get(name) for name in shown}


def _residual_cell(result: CandidateResult, factor: float) -> str:
    value = result.residual_vibration
    return "n/a" if value is None else short(value * factor)


def _markdown_item(line: str) -> str:
    if line.startswith("  "):
        return f"  - {line.strip()}\n"
    return f"- {line}\n"


def print_terminal_table(document: SizingDocument, console: Any = None) -> None:
    """The rich table with compact headers, fitted to the terminal's width (``console``:
    a rich Console, default stdout), then the footer, which names any column left out."""
    from rich.console import Console

    console = console or Console(highlight=False)
    dropped = print_rich_table(document.table(compact=True), wrap_headers=True,
                               droppable=document.droppable(), title_above=True,
                               console=console)
    footer = document.footer(dropped)
    if footer:
        from rich.text import Text

        console.print()
        for line in footer:  # wrapped to the terminal, never read as markup
            console.print(Text(printable(line)))


def publish_sizing(document: SizingDocument, fmt: Format, output: Path | None) -> None:
    """Write the document to ``output`` or stdout (a rich table on a terminal).

    When no pair is feasible and stdout does not show a human-readable report (CSV or
    JSON, or a file), the line 'no feasible motor/law pair' also goes to stderr.
    """
    if fmt is Format.TABLE and output is None and stdout_is_terminal():
        print_terminal_table(document)
        return
    emit(document.render(fmt), output, escape=fmt in (Format.TABLE, Format.MD))
    shown_to_user = output is None and fmt in (Format.TABLE, Format.MD)
    if not document.any_feasible and not shown_to_user:
        sys.stderr.write(NO_FEASIBLE + "\n")
        sys.stderr.flush()
