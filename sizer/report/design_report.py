"""A Markdown report of a sized design (``sizer report``): report.md and PNG figures.

The report states the task, the load, the transmission and the limits; the coefficient
table of the laws considered with a figure of their profiles; the ranking (the first
``top`` feasible pairs and how many are infeasible); and, for the ``best`` first
candidates, the speed-torque diagram and every check with its margin.

The text is deterministic (the same design and results give the same bytes) and reads
well rendered: headings, tables, figures linked by relative paths beside report.md.
Figures are drawn by :func:`write_report` only; :class:`DesignReport` itself never loads
matplotlib. Nothing here computes physics: the numbers are the sizing results and the
core's task curves.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING

from sizer import __version__
from sizer.errors import UserError
from sizer.laws.data_spec import law_label
from sizer.report.candidate_row import RPM_PER_RAD_S, check_line, percent
from sizer.report.cycle_summary import duration_name
from sizer.report.figure_grades import cited_sources, grade_counts
from sizer.report.laws_table import LawsDocument
from sizer.report.markdown_table import render_markdown_table
from sizer.report.numbers import short, short_or_na
from sizer.report.output import write_text_atomically
from sizer.report.sizing_table import SizingDocument
from sizer.report.table import Column, make_table
from sizer.sizing.results import Mode

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from sizer.laws import MotionLaw
    from sizer.model.domain import Design, Motor
    from sizer.sizing import CandidateResult, SizingResult
    from sizer.sizing.results import Check

REPORT_FILE = "report.md"
LAWS_FIGURE = "laws.png"
TIME_FIGURE = "cycle-1.png"
"""Motor torque and speed over the cycle of the first candidate (designs with a cycle of
segments only; a task's single move is the speed-torque diagram's curve)."""
TIME_FIGURE_SIZE = (10.0, 6.0)
MAX_LAWS_IN_FIGURE = 8
DEFAULT_TOP = 5
DEFAULT_BEST = 3
FIGURE_SIZE = (8.0, 6.0)
LAWS_FIGURE_SIZE = (8.0, 9.0)

THERMAL_SPEED_TEXT = {
    "max": "the cycle's peak speed (as the book)",
    "rms": "the cycle's RMS speed",
    "mean": "the cycle's mean speed",
}


def md(text: str) -> str:
    """Text for Markdown: '*' (as in N*m) escaped, so 'N*m*s' is not read as emphasis."""
    return text.replace("*", "\\*")


def candidate_figure(rank: int) -> str:
    """File name of the speed-torque diagram of the pair ranked ``rank``."""
    return f"speed-torque-{rank}.png"


@dataclass(frozen=True)
class Candidate:
    """One of the best pairs: its rank among all pairs, its result and its figure (None
    when it has no duration to draw)."""

    rank: int
    result: CandidateResult
    figure: str | None


class DesignReport:
    """The report's text and the list of its figures; ``write_report`` draws and writes."""

    def __init__(self, design: Design, sizing: SizingResult, *, top: int = DEFAULT_TOP,
                 best: int = DEFAULT_BEST, rank_by: str | None = None,
                 source: str | None = None) -> None:
        self.design = design
        self.sizing = sizing
        self.top = top
        from sizer.sizing.ranking import rank_rule

        self.rank_rule = rank_rule(rank_by, sizing.mode)
        self.rank_key = self.rank_rule.key
        self.source = source
        ranked = list(enumerate(sizing.results, start=1))
        feasible = [(rank, r) for rank, r in ranked if r.feasible]
        chosen = (feasible or ranked)[:best]
        self.candidates = [
            Candidate(rank, r, candidate_figure(rank) if r.duration is not None else None)
            for rank, r in chosen
        ]
        self.laws = self._laws()
        first = self.candidates[0] if self.candidates else None
        self.time_figure = (TIME_FIGURE if design.cycle is not None and first is not None
                            and first.result.duration is not None else None)

    # ------------------------------------------------------------------ content
    @property
    def minimize(self) -> bool:
        return self.sizing.mode is Mode.MINIMIZE

    @property
    def figures(self) -> list[str]:
        """Every figure file the report links to, relative to its directory."""
        files = [LAWS_FIGURE] if self.laws else []
        files += [c.figure for c in self.candidates if c.figure]
        return files + ([self.time_figure] if self.time_figure else [])

    def _laws(self) -> list[MotionLaw]:
        """The design's laws with fixed shapes, then the shapes the solver chose for 'auto'
        parameters among the pairs shown (ranking and best candidates)."""
        from sizer.laws.per_move import LawsPerMove
        laws: dict[str, MotionLaw] = {}
        for choice in self.design.laws:
            if choice.is_fixed:
                laws.setdefault(choice.law.spec, choice.law)
        if not all(s.is_fixed for s in self.design.laws):  # auto shapes, shaped for each T
            for result in self._shown_results():
                if result.spec not in laws and not isinstance(result.law_object,
                                                              LawsPerMove):
                    laws[result.spec] = result.law_object
        return list(laws.values())

    def _ranking_document(self) -> SizingDocument:
        none_feasible = not self.sizing.feasible
        return SizingDocument(self.sizing, self.design, rank_by=self.rank_key, top=self.top,
                              include_infeasible=none_feasible)

    def _shown_results(self) -> list[CandidateResult]:
        rows = [r for _, r in self._ranking_document().rows]
        return rows + [c.result for c in self.candidates if c.result not in rows]

    # ------------------------------------------------------------------- text
    def markdown(self) -> str:
        parts = [
            self._heading(),
            self._task(),
            self._load(),
            self._transmission(),
            self._limits(),
            self._motors(),
            self._laws_section(),
            self._ranking(),
            self._best(),
            self._segments(),
        ]
        return "\n".join(parts)

    def _heading(self) -> str:
        name = self.design.name or "design"
        total = len(self.sizing.results)
        feasible = len(self.sizing.feasible)
        lines = [f"# Sizing report: {md(name)}", ""]
        if self.source:  # the file name only: no path of the machine it ran on
            lines += [f"Design file: `{Path(self.source).name}`. "
                      f"Written by sizer {__version__} (Biagiotti & Melchiorri, ch. 6).", ""]
        else:
            lines += [f"Written by sizer {__version__} (Biagiotti & Melchiorri, ch. 6).", ""]
        motors = len(self.design.motors)
        summary = (f"{motors} motor{'s' if motors != 1 else ''} x "
                   f"{len(self.design.laws)} law{'s' if len(self.design.laws) != 1 else ''}: "
                   f"{feasible} of {total} pairs feasible")
        if feasible:
            best = self.sizing.feasible[0]
            assert best.duration is not None, "a feasible result has a duration"
            label = duration_name(self.design)
            summary += (f". Best, ranked by {self.rank_key}: {best.motor} with "
                        f"{law_label(best.spec)} "
                        f"({label} = {short(best.duration * 1000.0)} ms, limiting: "
                        f"{best.limiting}).")
        else:
            summary += ": no feasible motor/law pair."
        lines += [md(summary), "",
                  "Torques, speeds and accelerations are at the motor shaft unless said "
                  "otherwise; margins are the share of a limit left unused "
                  "(1 - value/limit).", ""]
        return "\n".join(lines)

    def _task(self) -> str:
        task = self.design.task
        if self.design.cycle is not None:
            return self._cycle()
        if task.linear:
            move = f"{short(task.displacement)} m ({short(task.displacement * 1000.0)} mm)"
        else:
            move = (f"{short(task.displacement)} rad "
                    f"({short(math.degrees(task.displacement))} deg)")
        duration = ("minimized for each pair (T_min)" if task.duration is None  # minimize
                    else f"{short(task.duration * 1000.0)} ms")
        cycle = ("move, dwell, move back, dwell" if task.return_move
                 else "move, dwell (then the next move)")
        rows = [
            ("axis", "linear" if task.linear else "rotary"),
            ("displacement h (at the load)", move),
            ("duration T", duration),
            ("dwell", f"{short(task.dwell * 1000.0)} ms"),
            ("machine cycle (for the RMS torque)", cycle),
        ]
        return _section("Task", _key_value_table(rows))

    def _cycle(self) -> str:
        """The Task section of a design with a cycle of segments: its segments."""
        from sizer.report.cycle_summary import cycle_table, cycle_text

        cycle = self.design.cycle
        assert cycle is not None
        count = len(cycle.segments)
        text = md(f"Axis {'linear' if cycle.linear else 'rotary'}; a machine cycle of "
                  f"{count} segment{'s' if count != 1 else ''}, repeated (the RMS torque "
                  f"is over the whole cycle):") + "\n\n"
        text += md(render_markdown_table(cycle_table(cycle)))
        return _section("Task", text + "\n" + md(cycle_text(cycle)) + "\n")

    def _load(self) -> str:
        load, linear = self.design.load, self.design.task.linear
        rows = [
            ("mass" if linear else "inertia J_l",
             f"{short(load.inertia)} {'kg' if linear else 'kg*m^2'}"),
            ("damping B_l", f"{short(load.damping)} {'N*s/m' if linear else 'N*m*s/rad'}"),
            ("Coulomb friction", f"{short(load.friction)} {'N' if linear else 'N*m'}"),
            ("constant external " + ("force" if linear else "torque"),
             f"{short(load.torque)} {'N' if linear else 'N*m'}"),
        ]
        return _section("Load", _key_value_table(rows))

    def _transmission(self) -> str:
        transmission = self.design.transmission
        choice = self.design.ratio_choice
        chosen = choice.stage if choice is not None else None
        from_catalog = choice is not None and bool(choice.gearboxes)
        if not transmission.stages:
            body = "Direct drive: the motor turns the load (ratio 1).\n"
        else:
            columns = (Column("#"), Column("type", "left"), Column("name", "left"),
                       Column("ratio"), Column("efficiency"),
                       Column("inertia at its input [kg*m^2]"))
            rows = []
            for i, s in enumerate(transmission.stages):
                if i == chosen and from_catalog:  # nothing of it is known before the choice
                    rows.append((str(i + 1), s.kind, "from the gearbox catalog", "per pair",
                                 "per pair", "per pair"))
                elif i == chosen:
                    rows.append((str(i + 1), s.kind, s.name, "per pair", short(s.efficiency),
                                 short(s.inertia)))
                else:
                    rows.append((str(i + 1), s.kind, s.name, short(s.ratio),
                                 short(s.efficiency), short(s.inertia)))
            body = md(render_markdown_table(make_table(columns, rows)))
            if chosen is None:
                body += ("\n" + md(f"From the motor to the load. Total ratio K = "
                                   f"{short(transmission.ratio)} (motor speed / load speed), "
                                   f"efficiency {short(transmission.efficiency)}, inertia at "
                                   f"the motor shaft {short(transmission.inertia)} kg*m^2.")
                         + "\n")
            else:
                body += "\n" + md("From the motor to the load.") + "\n"
        if choice is not None:
            options = []
            if choice.ratios:
                options.append("the ratios " + ", ".join(short(r) for r in choice.ratios))
            if choice.bounds is not None:
                options.append(f"any ratio from {short(choice.bounds[0])} to "
                               f"{short(choice.bounds[1])}")
            if choice.gearboxes:
                names = dict.fromkeys(o.gearbox for o in choice.gearboxes)
                options.append("the catalog gearboxes " + ", ".join(names))
            body += ("\n" + md(f"The ratio of stage {choice.stage + 1} is chosen for each "
                               f"pair among {'; '.join(options)}; each candidate below "
                               f"states its own.") + "\n")
        return _section("Transmission", body)

    def _limits(self) -> str:
        limits, linear = self.design.limits, self.design.task.linear
        unit = "m" if linear else "rad"

        def optional(value: float | None, text: str) -> str:
            return "none" if value is None else f"at most {short(value)}{text}"

        rows = [
            ("torque margin (peak and RMS)", f"{percent(limits.torque_margin)} %"),
            ("speed margin", f"{percent(limits.speed_margin)} %"),
            ("inertia ratio J_l/(K^2 J_m)", optional(limits.inertia_ratio, "")),
            ("acceleration (at the load)", optional(limits.max_acceleration, f" {unit}/s^2")),
            ("jerk (at the load)", optional(limits.max_jerk, f" {unit}/s^3")),
            ("thermal speed (where the RMS torque meets the continuous region)",
             THERMAL_SPEED_TEXT.get(limits.thermal_speed, limits.thermal_speed)),
        ]
        return _section("Limits", _key_value_table(rows))

    def _motors(self) -> str:
        """The motors of the pairs shown (a catalog can hold hundreds), then their sources."""
        shown = dict.fromkeys(r.motor for r in self._shown_results())
        motors = [m for m in self.design.motors if m.id in shown]
        count = len(self.design.motors)
        text = md(f"{count} motor{'s' if count != 1 else ''} considered; those in the "
                  f"ranking below:") + "\n\n"
        columns = (Column("motor", "left"), Column("rotor inertia [kg*m^2]"),
                   Column("continuous torque [N*m]"), Column("peak torque [N*m]"),
                   Column("rated speed [rpm]"), Column("max speed [rpm]"),
                   Column("speed-torque curves", "left"), Column("part number", "left"),
                   Column("figures by grade", "left"))
        rows = [(m.id, short(m.inertia), short(m.continuous_torque), short(m.peak_torque),
                 short(m.rated_speed * RPM_PER_RAD_S),
                 "" if m.max_speed is None else short(m.max_speed * RPM_PER_RAD_S),
                 "catalog" if m.continuous_curve or m.intermittent_curve
                 else f"none (envelope {self.design.limits.envelope})",
                 m.part_number or "", grade_counts(m)) for m in motors]
        text += md(render_markdown_table(make_table(columns, rows)))
        sources: dict[str, list[str]] = {}
        for m in motors:
            for source in cited_sources(m):
                sources.setdefault(source, []).append(m.id)
        if sources:
            text += "\nSources:\n\n" + "".join(
                f"- {md(', '.join(ids))}: {md(source)}\n" for source, ids in sources.items())
        return _section("Motors", text)

    def _laws_section(self) -> str:
        if not self.laws:
            return _section("Motion laws", "No motion law.\n")
        table = md(render_markdown_table(LawsDocument(self.laws).table()))
        text = ("Shape coefficients of the normalized laws (dimensionless; h/T, h/T^2 ... "
                "give the real values): peak velocity C_v, peak acceleration C_a, peak jerk "
                "C_j, RMS velocity C_v_rms and RMS acceleration C_a_rms.\n\n" + table)
        autos = [s.text for s in self.design.laws if s.auto]
        if autos:
            text += ("\n" + md(f"{', '.join(autos)}: the shape is chosen for each motor; the "
                               f"table lists the shapes of the pairs shown below.") + "\n")
        shown = self.laws[:MAX_LAWS_IN_FIGURE]
        caption = "Position, velocity, acceleration and jerk of the laws, normalized"
        if len(shown) < len(self.laws):
            caption += f" (the first {len(shown)})"
        text += f"\n![{md(caption)}]({LAWS_FIGURE})\n"
        return _section("Motion laws", text)

    def _ranking(self) -> str:
        document = self._ranking_document()
        total = len(self.sizing.results)
        feasible = len(self.sizing.feasible)
        label = duration_name(self.design)
        text = md(f"{feasible} of {total} motor/law pairs are feasible; ranked by "
                  f"{self.rank_key} ({self.rank_rule.text}). Durations {label} in "
                  f"ms, speeds in rpm, margins in %.") + "\n\n"
        text += md(render_markdown_table(document.table()))
        notes = []
        if not feasible:
            notes.append("No feasible motor/law pair: the table shows the first pairs "
                         "and why they fail.")
            notes += [f"#{rank} {r.motor}, {law_label(r.spec)}: {r.reason}"
                      for rank, r in document.rows]
        else:
            infeasible = total - feasible
            if infeasible:
                notes.append(f"{infeasible} infeasible pair{'s' if infeasible != 1 else ''} "
                             f"not shown (`sizer size --all` lists them with the reason).")
            if document.cut:
                notes.append(f"{document.cut} more feasible pair"
                             f"{'s' if document.cut != 1 else ''} not shown.")
        notes += [f"Note: {note}." for note in self.sizing.notes]
        if notes:
            text += "\n" + "".join(f"- {md(note)}\n" for note in notes)
        return _section("Ranking", text)

    def _best(self) -> str:
        if self.sizing.feasible:
            heading = "Best candidates"
            intro = (f"The first {len(self.candidates)} feasible pairs of the ranking."
                     if len(self.candidates) > 1 else "The best feasible pair.")
        else:
            heading = "Closest candidates (none is feasible)"
            intro = "The first pairs of the ranking, none of which meets every limit."
        parts = [f"## {heading}", "", intro, ""]
        for candidate in self.candidates:
            parts.append(self._candidate(candidate))
        return "\n".join(parts)

    def _segments(self) -> str:
        """The machine cycle segment by segment for the first candidate (the core's
        breakdown, sizer.sizing.segment_breakdown)."""
        from sizer.report.segment_table import SegmentDocument, breakdown_for

        heading = "Cycle by segment"
        first = self.candidates[0] if self.candidates else None
        if first is None or first.result.duration is None:
            return _section(heading, "No breakdown: the first pair has no feasible "
                                     "duration.\n")
        r = first.result
        document = SegmentDocument(breakdown_for(self.design, r), self.design)
        text = md(f"#{first.rank} {r.motor} with {law_label(r.spec)}: each segment's start "
                  f"and end, peak and RMS torque, share of the cycle's RMS^2, peak motor speed and "
                  f"work at the motor shaft; a jerk impulse where the acceleration steps at "
                  f"a join.") + "\n\n"
        text += md(document.markdown(title=False))
        if self.time_figure:
            alt = f"Motor torque and speed over the cycle of {r.motor} with {law_label(r.spec)}"
            text += f"\n![{md(alt)}]({self.time_figure})\n"
        return _section(heading, text)

    def _candidate(self, candidate: Candidate) -> str:
        r = candidate.result
        lines = [f"### {candidate.rank}. {md(r.motor)} with {md(law_label(r.spec))}", ""]
        lines.append(f"- {md(_motor_text(r.motor_object))}")
        lines.append(f"- {md(self._requirements(r))}")
        if r.ratio != 1.0 or r.gearbox:
            lines.append(f"- {md(self._transmission_of(r))}")
        verdict = (f"feasible; limiting check: {r.limiting}" if r.feasible
                   else f"not feasible: {r.reason}")
        lines += [f"- Verdict: {md(verdict)}", ""]
        if candidate.figure:
            alt = f"Speed-torque diagram of {r.motor} with {law_label(r.spec)}"
            lines += [f"![{md(alt)}]({candidate.figure})", ""]
            lines += [md("The motor's intermittent and continuous regions, the task curve "
                         "(speed(t), torque(t)) over the machine cycle and its RMS point "
                         "(thermal speed, RMS torque)."), ""]
        else:
            lines += ["No figure: the pair has no feasible duration.", ""]
        lines += ["Checks (value against limit, margin left, margin required):", ""]
        lines += [f"- {md(check_line(r, display_check(check)))}" for check in r.checks]
        lines.append("")
        return "\n".join(lines)

    def _transmission_of(self, r: CandidateResult) -> str:
        """The pair's ratio and, when it was chosen, the stage it was computed with."""
        text = f"Transmission ratio K = {short(r.ratio)}"
        choice = self.design.ratio_choice
        if choice is None or choice.stage >= len(r.transmission.stages):
            return text + (f", gearbox {r.gearbox}" if r.gearbox else "")
        stage = r.transmission.stages[choice.stage]
        name = f"gearbox {r.gearbox} (from the catalog)" if r.gearbox else \
            f"stage {choice.stage + 1} ({stage.kind})"
        figures = [f"ratio {short(stage.ratio)}", f"efficiency {short(stage.efficiency)}",
                   f"inertia {short(stage.inertia)} kg*m^2 at its input"]
        if stage.max_input_speed is not None:
            figures.append(f"max input speed {short(stage.max_input_speed * RPM_PER_RAD_S)} "
                           f"rpm")
        if stage.rated_output_torque is not None:
            figures.append(f"rated output torque {short(stage.rated_output_torque)} N*m")
        if stage.peak_output_torque is not None:
            figures.append(f"peak output torque {short(stage.peak_output_torque)} N*m")
        return f"{text}; {name}: {', '.join(figures)}"

    def _requirements(self, r: CandidateResult) -> str:
        if r.duration is None:
            return "No feasible duration"
        label = duration_name(self.design)
        parts = [f"{label} = {short(r.duration * 1000.0)} ms"]
        parts.append(f"peak torque {short_or_na(r.peak_torque, unit='N*m')}")
        parts.append(f"RMS torque {short_or_na(r.rms_torque, unit='N*m')}")
        if r.max_speed is not None:
            parts.append(f"max speed {short_or_na(r.max_speed, RPM_PER_RAD_S, 'rpm')}")
        if r.drive is not None:
            parts.append(f"drive {r.drive}")
        for value, text in ((r.peak_power, "W peak motoring power"),
                            (r.mean_power, "W mean motoring power"),
                            (r.copper_loss, "W mean copper loss"),
                            (r.cycle_energy, "J per cycle drawn from the DC bus (net)"),
                            (r.regenerated_energy, "J per cycle returned to the DC bus"),
                            (r.stop_energy, "J returned by the largest stop"),
                            (r.braking_power, "W braking resistor (continuous)"),
                            (r.braking_peak_power, "W braking resistor (peak)"),
                            (r.winding_rise, "K winding temperature rise")):
            if value is not None and math.isfinite(value):
                parts.append(f"{short(value)} {text}")
        return ", ".join(parts)


DISPLAY_UNITS = {"rad/s": ("rpm", RPM_PER_RAD_S)}
"""Units a reader reads otherwise: a check in rad/s is shown in rpm (CSV and JSON stay SI)."""


def display_check(check: Check) -> Check:
    """The check with its value and limit in the report's units (speeds in rpm); the
    margin, a ratio, is unchanged, and so is the verdict."""
    shown = DISPLAY_UNITS.get(check.unit)
    if shown is None:
        return check
    unit, factor = shown
    return replace(check, value=check.value * factor, limit=check.limit * factor, unit=unit)


def _motor_text(motor: Motor) -> str:
    return (f"Motor {motor.id}: rotor inertia {short(motor.inertia)} kg*m^2, continuous torque "
            f"{short(motor.continuous_torque)} N*m, peak torque {short(motor.peak_torque)} N*m, "
            f"rated speed {short(motor.rated_speed * RPM_PER_RAD_S)} rpm")


def _section(title: str, body: str) -> str:
    return f"## {title}\n\n{body}"


def _key_value_table(rows: Sequence[tuple[str, str]]) -> str:
    table = make_table((Column("quantity", "left"), Column("value", "left")), rows)
    return md(render_markdown_table(table))


# --------------------------------------------------------------------- writing
def report_directory(directory: Path | str) -> Path:
    """``directory``, created if needed (a UserError saying why it cannot be)."""
    directory = Path(directory)
    try:
        directory.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise UserError(f"cannot create the report directory: {error.strerror or error}",
                        file=str(directory)) from error
    return directory


def draw_figures(design: Design, report: DesignReport, *, dpi: float = 100.0,
                 samples: int = 401) -> Iterator[tuple[str, Figure]]:
    """Each figure the report links to, as (file name, matplotlib figure), drawn one at a
    time (the Markdown report saves them as PNG, the HTML report inlines them as SVG)."""
    from sizer.report.plots import (
        curve_for,
        law_profiles_figure,
        speed_torque_figure,
        time_figure,
    )

    if report.laws:
        yield LAWS_FIGURE, law_profiles_figure(report.laws[:MAX_LAWS_IN_FIGURE],
                                               size=LAWS_FIGURE_SIZE, dpi=dpi, samples=samples)
    for candidate in report.candidates:
        if candidate.figure is None:
            continue
        result = candidate.result
        curve = curve_for(design, result, samples=samples)
        yield candidate.figure, speed_torque_figure(
            [curve], [result], size=FIGURE_SIZE, dpi=dpi,
            title=f"#{candidate.rank} {design.name}".rstrip(),
            duration_name=duration_name(design), mark_segments=design.cycle is not None)
    if report.time_figure:
        first = report.candidates[0]
        curve = curve_for(design, first.result, samples=samples)
        yield report.time_figure, time_figure([curve], size=TIME_FIGURE_SIZE, dpi=dpi,
                                              title=f"#{first.rank} {design.name}".rstrip(),
                                              duration_name=duration_name(design))


def write_report(design: Design, sizing: SizingResult, directory: Path | str, *,
                 top: int = DEFAULT_TOP, best: int = DEFAULT_BEST, rank_by: str | None = None,
                 source: str | None = None, dpi: float = 100.0,
                 samples: int = 401) -> list[Path]:
    """Write ``directory``/report.md and its figures (the directory is created if needed).

    Returns the paths written, report.md first.
    """
    from sizer.report.plots import save_figure

    directory = report_directory(directory)
    report = DesignReport(design, sizing, top=top, best=best, rank_by=rank_by, source=source)
    written = [save_figure(figure, directory / name, dpi=dpi)
               for name, figure in draw_figures(design, report, dpi=dpi, samples=samples)]
    path = directory / REPORT_FILE
    write_text_atomically(path, report.markdown())  # failures: a UserError naming the file
    return [path, *written]
