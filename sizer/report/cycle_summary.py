"""What a design's machine cycle of segments asks for (``cycle:``, issue 12): JSON data in
SI with the units stated, and the rows of the report's table of segments.

Only a design with a ``cycle`` is described here; the ``task`` shorthand keeps its own
summary (sizer.report.design_summary), byte for byte as before.
"""

from __future__ import annotations

from typing import Any

from sizer.model.cycle import Cycle, Dwell, Move, Run, shorthand_task
from sizer.model.domain import Design
from sizer.report.numbers import finite_or_none, short
from sizer.report.table import Column, Table, make_table


def _kind(segment: Move | Run | Dwell) -> str:
    return "move" if isinstance(segment, Move) else "run" if isinstance(segment, Run) \
        else "dwell"


def cycle_units(linear: bool) -> dict[str, str]:
    """SI units of the cycle's fields (at the load)."""
    length = "m" if linear else "rad"
    return {"displacement": length, "duration": "s (null: free, scaled with the others)",
            "speed": f"{length}/s", "inertia": "kg" if linear else "kg*m^2",
            "torque": "N" if linear else "N*m", "cycle_time": "s"}


def segment_json(segment: Move | Run | Dwell) -> dict[str, Any]:
    """One segment as plain data (fixed key order, SI at the load)."""
    data: dict[str, Any] = {"name": segment.name or _kind(segment), "kind": _kind(segment),
                            "displacement": float(segment.displacement)}
    if isinstance(segment, Move):
        data.update({"duration": finite_or_none(segment.duration),
                     "law": segment.law.text if segment.law else None,
                     "start_speed": float(segment.start_speed),
                     "end_speed": float(segment.end_speed), "weight": float(segment.weight)})
    elif isinstance(segment, Run):
        data.update({"duration": float(segment.duration), "speed": float(segment.speed)})
    else:
        data.update({"duration": finite_or_none(segment.duration),
                     "weight": float(segment.weight)})
    data["added_inertia"] = float(segment.load.inertia)
    data["added_torque"] = float(segment.load.torque)
    return data


def cycle_json(cycle: Cycle) -> dict[str, Any]:
    """The cycle as plain data: its segments, how free durations share the time, the
    target cycle time or minimize, and the units."""
    return {
        "segments": [segment_json(s) for s in cycle.segments],
        "share": cycle.share.value,
        "cycle_time": finite_or_none(cycle.cycle_time),
        "minimize": bool(cycle.minimize),
        "minimize_segment": cycle.minimize_segment,
        "closed": bool(cycle.closed),
        "units": cycle_units(cycle.linear),
    }


def _duration_text(segment: Move | Run | Dwell) -> str:
    if segment.duration is None:
        return "free"
    return short(segment.duration * 1000.0)


def _speeds_text(segment: Move | Run | Dwell, unit: str) -> str:
    if isinstance(segment, Run):
        return f"{short(segment.speed)} {unit}/s"
    if isinstance(segment, Move) and not segment.rest_to_rest:
        return f"{short(segment.start_speed)} to {short(segment.end_speed)} {unit}/s"
    return "rest" if isinstance(segment, Dwell) else "rest to rest"


def _load_text(segment: Move | Run | Dwell, linear: bool) -> str:
    parts = []
    if segment.load.inertia:
        parts.append(f"+{short(segment.load.inertia)} {'kg' if linear else 'kg*m^2'}")
    if segment.load.torque:
        parts.append(f"{short(segment.load.torque)} {'N' if linear else 'N*m'}")
    return ", ".join(parts)


def cycle_table(cycle: Cycle) -> Table:
    """The segments for the report: kind, displacement, duration, law, speeds, load."""
    unit = "m" if cycle.linear else "rad"
    columns = (Column("#"), Column("segment", "left"), Column("kind", "left"),
               Column(f"displacement [{unit}]"), Column("duration [ms]"),
               Column("law", "left"), Column("speeds (at the load)", "left"),
               Column("added load", "left"))
    rows = [(str(i + 1), s.name or _kind(s), _kind(s), short(s.displacement),
             _duration_text(s),
             (s.law.text if s.law else "the design's laws") if isinstance(s, Move) else "",
             _speeds_text(s, unit), _load_text(s, cycle.linear))
            for i, s in enumerate(cycle.segments)]
    return make_table(columns, rows)


def cycle_text(cycle: Cycle) -> str:
    """One sentence under the table: how the free durations are set."""
    if not cycle.free:
        timing = "Every duration is fixed."
    elif cycle.cycle_time is not None:
        timing = (f"The free durations share a cycle time of "
                  f"{short(cycle.cycle_time * 1000.0)} ms ({cycle.share.value}).")
    elif cycle.minimize_segment is not None:
        timing = f"The segment {cycle.minimize_segment} is minimized, the others fixed."
    else:
        timing = (f"The free durations are scaled by one factor to the shortest feasible "
                  f"cycle (book sec. 5.2; shared by {cycle.share.value}).")
    closed = " The cycle ends where it starts." if cycle.closed else ""
    return timing + closed


def sized_as_cycle(design: Design) -> bool:
    """True when the design's results have the cycle time as their duration (a cycle of
    segments that is not the task shorthand; sizer.sizing.samples.scale_of), False when
    it is the move's duration T."""
    return shorthand_task(design.machine_cycle) is None


def duration_name(design: Design) -> str:
    """What a result's duration is called: T or T_min for a task (the move), 'cycle time'
    or 'min cycle time' for a cycle of segments."""
    minimize = design.machine_cycle.minimize
    if sized_as_cycle(design):
        return "min cycle time" if minimize else "cycle time"
    return "T_min" if minimize else "T"


def cycle_heading(cycle: Cycle) -> str:
    """'a cycle of 4 segments in 1450 ms' (or ', shortest cycle time')."""
    count = len(cycle.segments)
    text = f"a cycle of {count} segment{'s' if count != 1 else ''}"
    if cycle.minimize:
        return text + ", shortest cycle time"
    total = cycle.cycle_time if cycle.cycle_time is not None else cycle.fixed_time
    return f"{text} in {short(total * 1000.0)} ms"
