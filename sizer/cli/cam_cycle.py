"""``sizer cam`` of a design with a ``cycle:`` of segments: the sized cycle's profile
(sizer.export.cycle_profile), what its certificate adds (each segment's kind, law,
span and boundary speeds; the stroke is the cycle's travel), and the cycle re-sized on
the written file (:func:`resized_cycle`: each move's law the file's span of that move,
sizer.export.resized.resize_cycle). Formats, decides nothing."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from collections.abc import Callable

    from sizer.export.resized import Resized
    from sizer.laws.per_move import RankedLaw
    from sizer.sizing.results import CandidateResult

from sizer.errors import UserError

if TYPE_CHECKING:
    from sizer.export.profile import CamProfile
    from sizer.model.domain import Design


def sized_cycle(design: Design, law: RankedLaw, duration: float,
                master_range: float | None, source: Path,
                pair: CandidateResult | None = None) -> CamProfile:
    """The whole cycle of the design at the result's cycle time ``duration`` (the
    ``pair``'s own split where the share is chosen per motor)."""
    from sizer.export.cycle_profile import cycle_profile

    try:
        return cycle_profile(design, law, duration, master_range, pair)
    except ValueError as error:
        raise UserError(str(error), file=str(source), field="cycle") from None


def move_spans(profile: CamProfile) -> list[tuple[float, float] | None]:
    """Each segment's [x0, x1] in the file's master units where it is a move (None for a
    run or a dwell): its start and the next segment's (the profile's span for the last),
    the numbers the file writes at the segment's ends."""
    from sizer.export.cycle_profile import FrozenShape

    out: list[tuple[float, float] | None] = []
    for i, s in enumerate(profile.segments):
        if s.law is None or (isinstance(s.law, FrozenShape) and s.law.is_run):
            out.append(None)
            continue
        end = profile.segments[i + 1].start if i + 1 < len(profile.segments) \
            else profile.span
        out.append((s.start, end))
    return out


def resized_cycle(design: Path, catalog: list[str] | None, pair: CandidateResult,
                  profile: CamProfile, spec_of: Callable[[tuple[float, float]], str]
                  ) -> tuple[Resized, list[str | None]]:
    """The cycle re-sized on the written file: each move's law ``spec_of(span)`` (the
    file's span of that move, read back as a user would), the pair and the sized
    durations fixed (sizer.export.resized.resize_cycle); and the specs."""
    from sizer import api
    from sizer.export.resized import resize_cycle
    from sizer.laws import make_law

    specs = [None if span is None else spec_of(span) for span in move_spans(profile)]
    for spec in specs:
        if spec is not None:
            make_law(spec)  # read back here: a span that does not read is said before sizing
    try:
        return resize_cycle(api.load(design, catalog or ()), pair, specs), specs
    except ValueError as error:
        raise UserError(f"the written file does not make the sized cycle: {error}",
                        file=str(design), field="cycle") from None


def with_specs(record: dict[str, Any], specs: list[str | None] | None) -> dict[str, Any]:
    """``record`` whose torques were re-sized on a cycle's file: the moves' laws (the
    file's spans, by segment; None for a run or a dwell) in place of the one spec."""
    out = dict(record)
    if specs is not None and out.get("torques", {}).get("computed"):
        torques = dict(out["torques"])
        torques["exported_spec"] = None
        torques["exported_specs"] = specs
        torques["exported_is"] = ("the design's cycle with each move's law the file's span "
                                  "of that move (exported_specs, by segment), every move "
                                  "and dwell at its sized duration, for the same pair")
        out["torques"] = torques
    return out


def segments_record(profile: CamProfile) -> list[dict[str, Any]]:
    """Each segment: name, kind, law, master start and span, stroke, and its slave
    velocity at both ends (slave unit per master unit)."""
    from sizer.export.cycle_profile import FrozenShape

    out = []
    for s in profile.segments:
        if s.law is None:
            kind, law = "dwell", None
        elif isinstance(s.law, FrozenShape) and s.law.is_run:
            kind, law = "run", "linear"
        elif isinstance(s.law, FrozenShape):
            kind, law = "move", s.law.source.spec if s.law.source else s.law.spec
        else:
            kind, law = "move", s.law.spec
        # the boundary speeds the move was sized for (its law's ends, exactly)
        ends = (0.0, 0.0) if s.law is None else s.law.outside(1)
        start, end = s.end_speeds or tuple(s.stroke / s.span * e for e in ends)
        out.append({"name": s.name, "kind": kind, "law": law, "start": s.start,
                    "span": s.span, "stroke": s.stroke, "start_velocity": start,
                    "end_velocity": end})
    return out


def with_cycle(record: dict[str, Any], profile: CamProfile, cycle_time: float,
               specs: list[str | None] | None = None) -> dict[str, Any]:
    """The certificate ``record`` of a cycle of segments: the segments in full, the cycle
    time, a note that says what was exported and, with ``specs`` (the moves' laws the
    torques were re-sized with), those laws."""
    out = with_specs(record, specs)
    master = dict(out["master"])
    master.pop("move_duration_s", None)
    master["cycle_time_s"] = cycle_time
    out["master"] = master
    out["segments"] = segments_record(profile)
    out["stroke_is"] = "the cycle's travel (largest position less smallest)"
    vu = f"{profile.slave_unit}/{profile.master_unit}"
    parts = []
    for s in out["segments"]:
        what = s["kind"] if s["law"] is None else f"{s['kind']} {s['law']}"
        speeds = ""
        if s["kind"] != "dwell" and (s["start_velocity"] or s["end_velocity"]):
            speeds = (f" from {_g(s['start_velocity'])} to {_g(s['end_velocity'])} {vu}")
        parts.append(f"{s['name']} ({what}{speeds})")
    notes = [f"the design's whole cycle of {len(parts)} segments at the sized cycle time "
             f"{cycle_time:.6g} s: " + ", ".join(parts) + "; the stroke is the cycle's "
             "travel", *out.get("notes", [])]
    out["notes"] = notes
    return out


def _g(value: float) -> str:
    return f"{value:.6g}"
