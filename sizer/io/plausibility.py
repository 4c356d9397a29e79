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


def bare_number_warnings(source: YamlSource) -> list[str]:
    """Warnings for the bare numbers of a design file's task far from a plausible range."""
    task = source.data.get("task") if isinstance(source.data, dict) else None
    if not isinstance(task, dict):
        return []
    out = []
    for key, limit in (("duration", LONG_MOVE), ("dwell", LONG_DWELL)):
        number = _bare_float(task.get(key))
        if number is not None and number > limit:
            shown = f"{number:g}"
            out.append(warning_text(source, ("task", key),
                                    f"bare number {shown} read as {shown} s; write "
                                    f"'{shown} ms' if that was meant"))
    number = _bare_float(task.get("displacement"))
    if number is not None and abs(number) > LARGE_ANGLE:
        shown = f"{number:g}"
        turns = abs(number) / (2 * math.pi)
        out.append(warning_text(source, ("task", "displacement"),
                                f"bare number {shown} read as {shown} rad ({turns:.3g} "
                                f"turns); write '{shown} deg' if that was meant"))
    return out


def cycle_bare_number_warnings(source: YamlSource, linear: bool) -> list[str]:
    """Warnings for the bare durations of a ``cycle:``'s segments and, on a rotary axis,
    its bare displacements, far from a plausible range (as a task's)."""
    cycle = source.data.get("cycle") if isinstance(source.data, dict) else None
    segments = cycle.get("segments") if isinstance(cycle, dict) else None
    if not isinstance(segments, list):
        return []
    out = []
    for index, item in enumerate(segments):
        if not (isinstance(item, dict) and len(item) == 1):
            continue
        kind, fields = next(iter(item.items()))
        if not isinstance(fields, dict):
            continue
        at = ("cycle", "segments", index, kind)
        number = _bare_float(fields.get("duration"))
        limit = LONG_DWELL if kind == "dwell" else LONG_MOVE
        if number is not None and number > limit:
            shown = f"{number:g}"
            out.append(warning_text(source, (*at, "duration"),
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
