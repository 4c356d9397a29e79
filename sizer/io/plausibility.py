"""Warnings for bare numbers far from their plausible range.

A bare number is SI, but a bare number far from what the field usually holds is likely a
value in another unit (``duration: 250`` meant as 250 ms, ``rated_speed: 3000`` meant as
rpm). :func:`bare_number_warnings` and :func:`motor_warnings` give located warning texts
(``file:line: field: text``) for them; the loader puts them on the loaded objects. They are
never errors: a bare number keeps its SI meaning. A motor's figures are judged by the
plausibility bands of servomotors, :data:`sizer.io.motor_rules.BANDS` (the table and its
sources are there; ``sizer catalog validate`` warns about every figure outside them).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

from sizer.io.motor_rules import bare_note, implausibilities, is_bare, is_idealized
from sizer.io.yaml_source import YamlSource, format_path
from sizer.model.domain import Motor

LONG_MOVE = 10.0
"""s: a bare duration above this warns (a move of 250 s is more likely 250 ms)."""
LONG_DWELL = 60.0
"""s: a bare dwell above this warns."""
LARGE_ANGLE = 2 * math.pi
"""rad: a bare displacement above one turn warns (90 is more likely 90 deg)."""

def warning_text(source: YamlSource, path: Sequence[Any], message: str) -> str:
    """``file:line: field: message``, the parts that are known."""
    where = ""
    if source.file:
        line = source.line_of(path)
        where = source.file + (f":{line}" if line is not None else "") + ": "
    field = format_path(path)
    return f"{where}{field + ': ' if field else ''}{message}"


def motor_warnings(source: YamlSource, at: Sequence[Any], given: Any,
                   motor: Motor) -> list[str]:
    """Warnings for a motor's bare numbers that make it implausible (the bands of
    :mod:`sizer.io.motor_rules`); ``motor.manufacturer`` holds the catalog's default."""
    if not isinstance(given, Mapping) or is_idealized(motor.manufacturer):
        return []
    out, warned = [], set()
    for found in implausibilities(motor):
        note = bare_note(found, given)
        name = next((n for n in found.fields if is_bare(given.get(n))), None)
        if note and name not in warned:
            warned.add(name)
            out.append(warning_text(source, (*at, name),
                                    f"{note}, but {found.message}; write the unit if "
                                    f"another was meant"))
    return out


def bare_number_warnings(source: YamlSource, linear: bool) -> list[str]:
    """Warnings for the bare numbers of a design's task or cycle far from a plausible
    range: durations (a segment's as a task's), and on a rotary axis displacements."""
    data = source.data if isinstance(source.data, dict) else {}
    places: list[tuple[tuple[Any, ...], Mapping[str, Any], tuple[tuple[str, float], ...]]] = []
    task, cycle = data.get("task"), data.get("cycle")
    if isinstance(task, dict):
        places.append((("task",), task, (("duration", LONG_MOVE), ("dwell", LONG_DWELL))))
    segments = cycle.get("segments") if isinstance(cycle, dict) else None
    for index, item in enumerate(segments if isinstance(segments, list) else ()):
        if isinstance(item, dict) and len(item) == 1:
            kind, fields = next(iter(item.items()))
            if isinstance(fields, dict):
                limit = LONG_DWELL if kind == "dwell" else LONG_MOVE
                places.append((("cycle", "segments", index, kind), fields,
                               (("duration", limit),)))
    out = []
    for at, fields, durations in places:
        for key, limit in durations:
            number = _bare_float(fields.get(key))
            if number is not None and number > limit:
                shown = f"{number:g}"
                out.append(warning_text(source, (*at, key),
                                        f"bare number {shown} read as {shown} s; write "
                                        f"'{shown} ms' if that was meant"))
        number = _bare_float(fields.get("displacement"))
        if not linear and number is not None and abs(number) > LARGE_ANGLE:
            shown = f"{number:g}"
            turns = abs(number) / (2 * math.pi)
            out.append(warning_text(source, (*at, "displacement"),
                                    f"bare number {shown} read as {shown} rad ({turns:.3g} "
                                    f"turns); write '{shown} deg' if that was meant"))
    return out


def _bare_float(value: Any) -> float | None:
    """The float of a bare number, None for anything else or a number beyond the floats
    (the field's range refuses it)."""
    if not is_bare(value):
        return None
    try:
        number = float(value)
    except OverflowError:
        return None
    return number if math.isfinite(number) else None
