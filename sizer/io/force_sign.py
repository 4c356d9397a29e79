"""A warning where a segment's own force (or torque) helps the motion through the whole
segment: usually a sign mistake (issue 36: the intuitive sign of a pressing force gave an
18 % lower RMS torque on a press).

The convention (docs/process-forces.md): a positive ``force``/``torque`` opposes a positive
move, so a force that resists the motion (pressing, cutting, lifting a part) has the sign
of the segment's displacement. One of the other sign pushes the axis along for the whole
segment: possible (a spring that drives it, gravity on a lowered part), but more often a
force written as it points in the machine rather than against the motion.
"""

from __future__ import annotations

from sizer.io.plausibility import warning_text
from sizer.io.schema.ranges import number_text
from sizer.io.yaml_source import YamlSource
from sizer.model.cycle import Cycle, Dwell, Move

DOC = "docs/process-forces.md"


def aids_the_whole_segment(force: float, displacement: float, start_speed: float,
                           end_speed: float) -> bool:
    """True when the force is against the displacement and the segment moves one way
    (its boundary speeds are not against it): the force then helps all along."""
    if force == 0.0 or displacement == 0.0:
        return False
    one_way = start_speed * displacement >= 0.0 and end_speed * displacement >= 0.0
    return force * displacement < 0.0 and one_way


def force_sign_warnings(cycle: Cycle, source: YamlSource) -> list[str]:
    """One located warning per move or run whose own force (torque) helps its motion."""
    key, unit, length = (("force", "N", "m") if cycle.linear else ("torque", "N*m", "rad"))
    out = []
    for i, segment in enumerate(cycle.segments):
        if isinstance(segment, Dwell):
            continue
        kind = "move" if isinstance(segment, Move) else "run"
        h = segment.displacement if isinstance(segment, Move) else segment.speed
        force = segment.load.torque
        if not aids_the_whole_segment(force, h, segment.start_speed, segment.end_speed):
            continue
        moving = (f"a displacement of {number_text(h)} {length}" if isinstance(segment, Move)
                  else f"a speed of {number_text(h)} {length}/s")
        out.append(warning_text(source, ("cycle", "segments", i, kind, key), (
            f"{number_text(force)} {unit} helps the motion through the whole segment "
            f"({moving}): a positive {key} opposes a positive move, so a force the motion "
            f"works against (pressing, cutting, lifting) has the sign of the displacement; "
            f"if it really drives the axis, ignore this warning ({DOC})")))
    return out
