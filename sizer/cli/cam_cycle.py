"""``sizer cam`` of a design with a ``cycle:`` of segments: the sized cycle's profile
(sizer.export.cycle_profile) and what its certificate adds (each segment's kind, law,
span and boundary speeds; the stroke is the cycle's travel). Formats, decides nothing."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

from sizer.errors import UserError

if TYPE_CHECKING:
    from sizer.export.profile import CamProfile
    from sizer.laws.base import MotionLaw
    from sizer.model.domain import Design


def sized_cycle(design: Design, law: MotionLaw, duration: float,
                master_range: float | None, source: Path) -> CamProfile:
    """The whole cycle of the design at the result's cycle time ``duration``."""
    from sizer.export.cycle_profile import cycle_profile

    try:
        return cycle_profile(design, law, duration, master_range)
    except ValueError as error:
        raise UserError(str(error), file=str(source), field="cycle") from None


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


def with_cycle(record: dict[str, Any], profile: CamProfile, cycle_time: float
               ) -> dict[str, Any]:
    """The certificate ``record`` of a cycle of segments: the segments in full, the cycle
    time, and a note that says what was exported."""
    out = dict(record)
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
