"""Sanity checks of one catalog motor, beyond its schema: every problem, not the first.

The schema (``sizer.model.inputs.MotorInput``) already holds units, signs and types; these
checks look at how the figures fit together: peak >= continuous torque, max speed >= rated
speed, curves with strictly increasing speeds, the continuous region under the intermittent
one, the curves' first torques against the scalar ratings, a rotor inertia and a source.

Plausibility (warnings): figures whose ratios are far outside what real servomotors have,
a likely unit mistake (an inertia in kg*m^2 that was kg*cm^2, a speed in rad/s that was
rpm). The bands, from the 64 bundled motors and the research notes on motor datasheets
widened by a factor of about 3 to 10 (the table and its sources are in
:mod:`sizer.io.plausibility`, which also warns about such bare numbers at loading):

- peak / continuous torque at most 30 (bundled 2.35 to 5.06);
- acceleration capacity tau_p / J_m in 5e2 to 5e6 rad/s^2 (bundled 7.2e3 to 2.6e5);
- rated power per rotor inertia tau_c v_n / J_m in 5e4 to 1e9 W/(kg*m^2) (bundled 5.7e5
  to 2.7e7; a 100 W motor of 3 kg*m^2 has 33);
- max / rated speed at most 6 (bundled 1 to 2);
- rated speed 50 to 15000 rpm (bundled 1500 to 6000), max speed at most 25000 rpm
  (bundled up to 9000).

Idealized textbook motors (manufacturer 'idealized ...') are not checked for plausibility.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from sizer.catalog_tools.findings import Severity
from sizer.envelope import continuous_region, intermittent_region
from sizer.io.plausibility import IDEALIZED_MARK, bare_note, is_idealized, motor_implausibilities
from sizer.model.domain import Curve, Motor
from sizer.model.inputs import CurvePointInput, MotorInput

RPM_PER_RAD_S = 30.0 / math.pi

CURVE_START_TOLERANCE = 0.10
"""A curve's first torque may differ from the scalar rating by this fraction (a warning)."""

RELATIVE_TOLERANCE = 1e-9
"""Rounding allowance when comparing figures given in different units."""

@dataclass(frozen=True)
class MotorProblem:
    """A problem at ``path`` inside the motor's mapping, e.g. ("continuous_curve", 2)."""

    path: tuple[Any, ...]
    message: str
    severity: Severity = "error"


def _rpm(speed: float) -> str:
    return f"{speed * RPM_PER_RAD_S:.5g} rpm"


def _nm(torque: float) -> str:
    return f"{torque:.4g} N*m"


def check_motor(item: MotorInput, *, manufacturer: str | None = None,
                source: str | None = None,
                given: Mapping[str, Any] | None = None) -> list[MotorProblem]:
    """Every sanity problem of a schema-valid motor.

    ``manufacturer`` and ``source`` are the catalog-level defaults, used where the motor
    has none of its own. ``given`` is the motor's mapping as written: a plausibility
    warning names the bare number it involves.
    """
    problems: list[MotorProblem] = []
    add = problems.append
    if item.peak_torque < item.continuous_torque * (1 - RELATIVE_TOLERANCE):
        add(MotorProblem(("peak_torque",), f"peak torque {_nm(item.peak_torque)} is below the "
                                           f"continuous torque {_nm(item.continuous_torque)}"))
    if item.max_speed is not None and item.max_speed < item.rated_speed * (1 - RELATIVE_TOLERANCE):
        add(MotorProblem(("max_speed",), f"max speed {_rpm(item.max_speed)} is below the rated "
                                         f"speed {_rpm(item.rated_speed)}"))
    if item.inertia <= 0 and not is_idealized(item.manufacturer or manufacturer):
        add(MotorProblem(("inertia",), "the rotor inertia is 0: a real motor needs its "
                                       "datasheet inertia (only idealized textbook motors, "
                                       f"manufacturer '{IDEALIZED_MARK} ...', may have 0)"))
    if not (item.source or source or "").strip():
        add(MotorProblem(("source",), "no source: give the datasheet's title and web address "
                                      "(on the motor, or 'source:' at the catalog level)"))
    if not is_idealized(item.manufacturer or manufacturer):
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
        if abs(first - rating) > CURVE_START_TOLERANCE * rating:
            add(MotorProblem(
                (name, 0), f"the curve starts at {_nm(first)}, more than "
                           f"{CURVE_START_TOLERANCE:.0%} away from {rating_name} {_nm(rating)}",
                "warning"))
    if curves_ok and (item.continuous_curve or item.intermittent_curve):
        # (two rectangles compare as peak >= continuous torque, checked above)
        problems += _region_problems(item)
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
                                              f"got {len(points)}"))
    for index in range(1, len(points)):
        if not points[index].speed > points[index - 1].speed:
            problems.append(MotorProblem(
                (name, index), f"curve speeds must be strictly increasing: "
                               f"{_rpm(points[index].speed)} follows "
                               f"{_rpm(points[index - 1].speed)}"))
    usable = not problems
    if points and max_speed is not None:
        last = len(points) - 1
        if points[last].speed > max_speed * (1 + RELATIVE_TOLERANCE):
            problems.append(MotorProblem(
                (name, last), f"the curve reaches {_rpm(points[last].speed)}, above max_speed "
                              f"{_rpm(max_speed)}"))
    return problems, usable


def _region_problems(item: MotorInput) -> list[MotorProblem]:
    """The continuous region must lie under the intermittent one (as the sizing sees them)."""
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
    for speed in speeds:
        low, high = _limit(continuous, speed), _limit(intermittent, speed)
        if low > high * (1 + RELATIVE_TOLERANCE) + 1e-12:
            problems.append(MotorProblem(
                at, f"the continuous region is above the intermittent region at {_rpm(speed)}: "
                    f"{_nm(low)} > {_nm(high)}"))
            break
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
