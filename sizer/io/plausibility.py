"""Plausible ranges of input figures: warnings for bare numbers, bands for catalog motors.

A bare number is SI, but a bare number far from what the field usually holds is likely a
value in another unit (``duration: 250`` meant as 250 ms, ``rated_speed: 3000`` meant as
rpm). :func:`bare_number_warnings` and :func:`motor_warnings` give located warning texts
(``file:line: field: text``) for them; the loader puts them on the loaded objects. They are
never errors: a bare number keeps its SI meaning.

The bands of servomotor figures (used here for bare numbers and by
``sizer.catalog_tools.checks`` for every motor of ``sizer catalog validate``) are the
range of the 64 bundled motors (sizer/catalogs/*.yaml: Yaskawa, Mitsubishi, Siemens, TECO,
maxon) and of the other motors in the research notes (motor-data.md: Beckhoff AM3000/AM8000,
Wittenstein premo, maxon and Pittman DC motors), widened by a factor of about 3 to 10:

==========================  ==========================  ==========================  =========
figure                      bundled motors              with motor-data.md          band
==========================  ==========================  ==========================  =========
tau_p / tau_c               2.35 .. 5.06                up to 20 (DC stall torque)  1 .. 30
tau_p / J_m [rad/s^2]       7.2e3 .. 2.6e5              up to 4e5 (AM3011)          5e2 .. 5e6
tau_c v_n / J_m [W/kg m^2]  5.7e5 .. 2.7e7              up to 9e7 (AM3011)          5e4 .. 1e9
max speed / rated speed     1.0 .. 2.0                  up to 1.6 (maxon 353297)    1 .. 6
rated speed [rpm]           1500 .. 6000                1000 .. 8000 (AM3000)       50 .. 15000
max speed [rpm]             3000 .. 9000                up to 10530 (premo 1C)      <= 25000
==========================  ==========================  ==========================  =========

tau_p / J_m is the motor's acceleration capacity (its own rotor at peak torque), tau_c v_n /
J_m the rated power per rotor inertia: a 100 W motor of 3 kg*m^2 has 33 W/(kg*m^2). A
speed in rad/s where rpm was meant is 9.55 times too high (3000 rpm written as '3000 rad/s'
is 28648 rpm). Idealized textbook motors (manufacturer 'idealized ...') are not checked.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from sizer.io.yaml_source import YamlSource, format_path

RPM = math.pi / 30
"""rad/s per rpm."""

PEAK_TO_CONTINUOUS = (1.0, 30.0)
ACCELERATION_CAPACITY = (5e2, 5e6)
"""tau_p / J_m, rad/s^2."""
POWER_PER_INERTIA = (5e4, 1e9)
"""tau_c v_n / J_m, W/(kg*m^2)."""
MAX_TO_RATED_SPEED = (1.0, 6.0)
RATED_SPEED = (50 * RPM, 15000 * RPM)
MAX_SPEED = 25000 * RPM

LONG_MOVE = 10.0
"""s: a bare duration above this warns (a move of 250 s is more likely 250 ms)."""
LONG_DWELL = 60.0
"""s: a bare dwell above this warns."""
LARGE_ANGLE = 2 * math.pi
"""rad: a bare displacement above one turn warns (90 is more likely 90 deg)."""

IDEALIZED_MARK = "idealized"
"""A manufacturer text containing this word marks textbook motors: no rotor inertia needed."""

_NUMBER = re.compile(r"^\s*[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?\s*$")


def is_idealized(manufacturer: str | None) -> bool:
    """True for the textbook motors (``manufacturer: idealized ...``)."""
    return manufacturer is not None and IDEALIZED_MARK in manufacturer.lower()


def is_bare(value: Any) -> bool:
    """A number without a unit: an int or float, or a text holding only a number."""
    if isinstance(value, bool):
        return False
    return isinstance(value, int | float) or (isinstance(value, str)
                                              and _NUMBER.match(value) is not None)


@dataclass(frozen=True)
class Implausible:
    """A motor figure outside the band of real servomotors.

    ``field`` is where it is reported; ``fields`` are all the figures involved.
    """

    field: str
    fields: tuple[str, ...]
    message: str


def _rpm(speed: float) -> str:
    return f"{speed / RPM:.5g} rpm"


def motor_implausibilities(inertia: float, continuous_torque: float, peak_torque: float,
                           rated_speed: float, max_speed: float | None) -> list[Implausible]:
    """The figures of a motor (SI) outside the bands of the module's table."""
    found: list[Implausible] = []
    ratio = peak_torque / continuous_torque
    if ratio > PEAK_TO_CONTINUOUS[1]:
        found.append(Implausible(
            "peak_torque", ("peak_torque", "continuous_torque"),
            f"peak torque {peak_torque:.4g} N*m is {ratio:.3g} times the continuous torque "
            f"{continuous_torque:.4g} N*m; servomotors have at most {PEAK_TO_CONTINUOUS[1]:g} "
            f"(check the units)"))
    if inertia > 0:
        power = continuous_torque * rated_speed
        low, high = POWER_PER_INERTIA
        if not low <= power / inertia <= high:
            found.append(Implausible(
                "inertia", ("inertia", "continuous_torque", "rated_speed"),
                f"a rotor inertia of {inertia:.4g} kg*m^2 for {power:.4g} W rated power "
                f"(continuous torque x rated speed) is {power / inertia:.3g} W per kg*m^2, "
                f"outside the range of servomotors ({low:g} to {high:g})"))
        capacity = peak_torque / inertia
        low, high = ACCELERATION_CAPACITY
        if not low <= capacity <= high:
            found.append(Implausible(
                "inertia", ("inertia", "peak_torque"),
                f"peak torque / rotor inertia = {capacity:.3g} rad/s^2 is outside the range "
                f"of servomotors ({low:g} to {high:g} rad/s^2): check the inertia's unit "
                f"(1 kg*cm^2 = 1e-4 kg*m^2)"))
    low, high = RATED_SPEED
    if not low <= rated_speed <= high:
        found.append(Implausible(
            "rated_speed", ("rated_speed",),
            f"rated speed {_rpm(rated_speed)} is outside the range of servomotors "
            f"({_rpm(low)} to {_rpm(high)}): check its unit (a bare number is rad/s)"))
    if max_speed is not None:
        if max_speed > MAX_SPEED:
            found.append(Implausible(
                "max_speed", ("max_speed",),
                f"max speed {_rpm(max_speed)} is above {_rpm(MAX_SPEED)}, beyond servomotors: "
                f"check its unit (a bare number is rad/s)"))
        ratio = max_speed / rated_speed
        if ratio > MAX_TO_RATED_SPEED[1]:
            found.append(Implausible(
                "max_speed", ("max_speed", "rated_speed"),
                f"max speed {_rpm(max_speed)} is {ratio:.3g} times the rated speed "
                f"{_rpm(rated_speed)}; servomotors have at most {MAX_TO_RATED_SPEED[1]:g} "
                f"(are both in the same unit?)"))
    return found


SI_UNITS = {"inertia": "kg*m^2", "continuous_torque": "N*m", "peak_torque": "N*m",
            "rated_speed": "rad/s", "max_speed": "rad/s"}


def bare_note(found: Implausible, given: Mapping[str, Any]) -> str:
    """'bare number 3 read as 3 kg*m^2' for the first bare figure involved, or ''."""
    for name in found.fields:
        value = given.get(name)
        if is_bare(value):
            shown = str(value).strip()
            return f"bare number {shown} read as {shown} {SI_UNITS[name]}"
    return ""


def warning_text(source: YamlSource, path: Sequence[Any], message: str) -> str:
    """``file:line: field: message``, the parts that are known."""
    where = ""
    if source.file:
        line = source.line_of(path)
        where = source.file + (f":{line}" if line is not None else "") + ": "
    field = format_path(path)
    return f"{where}{field + ': ' if field else ''}{message}"


def motor_warnings(source: YamlSource, at: Sequence[Any], given: Any, inertia: float,
                   continuous_torque: float, peak_torque: float, rated_speed: float,
                   max_speed: float | None, manufacturer: str | None) -> list[str]:
    """Warnings for a motor's bare numbers that make it implausible (see the table)."""
    if not isinstance(given, Mapping) or is_idealized(manufacturer):
        return []
    out, warned = [], set()
    for found in motor_implausibilities(inertia, continuous_torque, peak_torque, rated_speed,
                                        max_speed):
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
