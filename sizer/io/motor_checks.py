"""Checks of one motor beyond its fields' ranges: how its figures fit together.

Every problem is listed, each with its path inside the motor's mapping, its severity and
whether loading refuses it:

- impossible (an error, refused at load, exit 2): peak torque below the continuous torque,
  max speed below the rated speed, a curve of fewer than 2 points or with speeds not
  strictly increasing, a curve point beyond max_speed, the continuous region above the
  intermittent one at some speed (both regions completed the book's way, compared on the
  union of their corner speeds, where their difference is extreme: it is piecewise linear);
- catalog rules (an error of ``sizer catalog validate`` only; loading accepts them): a
  real motor without rotor inertia (0 is the textbook idealization, its rotor counted in
  the load) and a motor without a source;
- implausible (a warning): the plausibility bands of :mod:`sizer.io.plausibility`, a
  curve's first torque far from the scalar rating, a continuous region reaching beyond the
  intermittent one's speed.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Literal

from sizer.envelope import continuous_region, intermittent_region
from sizer.io.plausibility import IDEALIZED_MARK, bare_note, is_idealized, motor_implausibilities
from sizer.model.domain import Curve, Motor
from sizer.model.inputs import CurvePointInput, MotorInput

Severity = Literal["error", "warning"]

RPM_PER_RAD_S = 30.0 / math.pi

CURVE_START_TOLERANCE = 0.10
"""A curve's first torque may differ from the scalar rating by this fraction (a warning)."""

RELATIVE_TOLERANCE = 1e-9
"""Rounding allowance when comparing figures given in different units."""


@dataclass(frozen=True)
class MotorProblem:
    """A problem at ``path`` inside the motor's mapping, e.g. ("continuous_curve", 2).

    ``at_load``: loading the catalog refuses it (an impossible motor); the other errors
    are rules of ``sizer catalog validate``.
    """

    path: tuple[Any, ...]
    message: str
    severity: Severity = "error"
    at_load: bool = False


def _rpm(speed: float) -> str:
    return f"{speed * RPM_PER_RAD_S:.5g} rpm"


def _nm(torque: float) -> str:
    return f"{torque:.4g} N*m"


def impossibilities(item: MotorInput) -> list[MotorProblem]:
    """The problems that make a motor physically impossible (refused at load)."""
    return [p for p in check_motor(item, rules=False) if p.at_load]


def check_motor(item: MotorInput, *, manufacturer: str | None = None,
                source: str | None = None, given: Mapping[str, Any] | None = None,
                rules: bool = True) -> list[MotorProblem]:
    """Every problem of a motor whose fields are valid, in the order of its fields.

    ``manufacturer`` and ``source`` are the catalog-level defaults, used where the motor
    has none of its own. ``given`` is the motor's mapping as written: a plausibility
    warning names the bare number it involves. ``rules=False`` skips the catalog rules
    and the warnings.
    """
    problems: list[MotorProblem] = []

    def add(path: tuple[Any, ...], message: str, severity: Severity = "error",
            at_load: bool = False) -> None:
        problems.append(MotorProblem(path, message, severity, at_load))

    if item.peak_torque < item.continuous_torque * (1 - RELATIVE_TOLERANCE):
        add(("peak_torque",), f"peak torque {_nm(item.peak_torque)} is below the continuous "
                              f"torque {_nm(item.continuous_torque)}", at_load=True)
    if item.max_speed is not None and item.max_speed < item.rated_speed * (1 - RELATIVE_TOLERANCE):
        add(("max_speed",), f"max speed {_rpm(item.max_speed)} is below the rated speed "
                            f"{_rpm(item.rated_speed)}", at_load=True)
    idealized = is_idealized(item.manufacturer or manufacturer)
    if rules:
        if item.inertia <= 0 and not idealized:
            add(("inertia",), "the rotor inertia is 0: a real motor needs its datasheet "
                              "inertia (only idealized textbook motors, manufacturer "
                              f"'{IDEALIZED_MARK} ...', may have 0)")
        if not (item.source or source or "").strip():
            add(("source",), "no source: give the datasheet's title and web address (on the "
                             "motor, or 'source:' at the catalog level)")
        if not idealized:
            problems += _plausibility(item, given or {})
    curves_ok = True
    for name, rating, rating_name in (
            ("continuous_curve", item.continuous_torque, "continuous_torque"),
            ("intermittent_curve", item.peak_torque, "peak_torque")):
        points = getattr(item, name)
        if points is None:
            continue
        found, usable = _curve_problems(name, points, item.max_speed)
        problems += found
        if not usable:
            curves_ok = False
            continue
        first = points[0].torque
        if rules and abs(first - rating) > CURVE_START_TOLERANCE * rating:
            add((name, 0), f"the curve starts at {_nm(first)}, more than "
                           f"{CURVE_START_TOLERANCE:.0%} away from {rating_name} {_nm(rating)}",
                "warning")
    if curves_ok and (item.continuous_curve or item.intermittent_curve):
        # (two rectangles compare as peak >= continuous torque, checked above)
        problems += [p for p in _region_problems(item) if rules or p.at_load]
    return problems


def _plausibility(item: MotorInput, given: Mapping[str, Any]) -> list[MotorProblem]:
    """Figures far outside the bands of real servomotors (a warning each)."""
    problems = []
    for found in motor_implausibilities(item.inertia, item.continuous_torque,
                                        item.peak_torque, item.rated_speed, item.max_speed):
        note = bare_note(found, given)
        message = f"implausible: {found.message}" + (f" ({note})" if note else "")
        problems.append(MotorProblem((found.field,), message, "warning"))
    return problems


def _curve_problems(name: str, points: Sequence[CurvePointInput],
                    max_speed: float | None) -> tuple[list[MotorProblem], bool]:
    """The curve's problems, and whether it is still a usable region (>= 2 points, speeds
    strictly increasing)."""
    problems = []
    if len(points) < 2:
        problems.append(MotorProblem((name,), f"a speed-torque curve needs at least 2 points, "
                                              f"got {len(points)}", at_load=True))
    for index in range(1, len(points)):
        if not points[index].speed > points[index - 1].speed:
            problems.append(MotorProblem(
                (name, index), f"curve speeds must be strictly increasing: "
                               f"{_rpm(points[index].speed)} follows "
                               f"{_rpm(points[index - 1].speed)}", at_load=True))
    usable = not problems
    if points and max_speed is not None:
        last = len(points) - 1
        if points[last].speed > max_speed * (1 + RELATIVE_TOLERANCE):
            beyond = next(i for i, p in enumerate(points)
                          if p.speed > max_speed * (1 + RELATIVE_TOLERANCE))
            problems.append(MotorProblem(
                (name, beyond), f"the curve reaches {_rpm(points[beyond].speed)}, above "
                                f"max_speed {_rpm(max_speed)}", at_load=True))
    return problems, usable


def _region_problems(item: MotorInput) -> list[MotorProblem]:
    """The continuous region must lie under the intermittent one, compared where both are
    defined (the regions completed the book's way: rectangles up to the rated speed)."""
    motor = Motor(
        id=item.id, inertia=item.inertia, continuous_torque=item.continuous_torque,
        peak_torque=item.peak_torque, rated_speed=item.rated_speed,
        continuous_curve=_points(item.continuous_curve),
        intermittent_curve=_points(item.intermittent_curve))
    continuous, intermittent = continuous_region(motor), intermittent_region(motor)
    at = ("continuous_curve",) if item.continuous_curve else ("continuous_torque",)
    problems = []
    top = min(continuous[-1][0], intermittent[-1][0])
    speeds = sorted({s for s, _ in (*continuous, *intermittent) if s <= top})
    excess = [(_limit(continuous, s) - _limit(intermittent, s), s) for s in speeds]
    worst, speed = max(excess)
    low, high = _limit(continuous, speed), _limit(intermittent, speed)
    if low > high * (1 + RELATIVE_TOLERANCE) + 1e-12:
        what = "curve" if item.continuous_curve else "torque"
        problems.append(MotorProblem(
            at, f"the continuous region is above the intermittent region at {_rpm(speed)} "
                f"({speed:.5g} rad/s): {_nm(low)} > {_nm(high)}, by {_nm(worst)} (the "
                f"continuous {what} must lie under the intermittent one at every speed)",
            at_load=True))
    if continuous[-1][0] > intermittent[-1][0] * (1 + RELATIVE_TOLERANCE):
        problems.append(MotorProblem(
            at, f"the continuous region reaches {_rpm(continuous[-1][0])}, beyond the "
                f"intermittent region (up to {_rpm(intermittent[-1][0])}); the sizing limits "
                f"the speed to the intermittent region", "warning"))
    return problems


def _points(points: Sequence[CurvePointInput] | None) -> Curve | None:
    if not points:
        return None
    return tuple((p.speed, p.torque) for p in points)


def _limit(curve: Curve, speed: float) -> float:
    """The piecewise linear torque limit of ``curve`` at ``speed`` (inside its range)."""
    for (s0, t0), (s1, t1) in itertools.pairwise(curve):
        if s0 <= speed <= s1:
            return t0 + (t1 - t0) * (speed - s0) / (s1 - s0)
    return curve[-1][1] if speed >= curve[-1][0] else curve[0][1]
