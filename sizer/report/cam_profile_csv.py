"""A disc cam's profile as points, CSV (``sizer plot --cam --points FILE.csv``).

A few ``#`` lines give what the points are of (the design, the motor and law, the base
radius the sizing chose, the roller, the offset or arm, the cam's speed and its frame);
then a header naming each column with its unit and one line per cam angle: the cam angle
(deg), the follower's lift (mm; an oscillating follower's swing, deg), the pitch curve
(the roller's centre) and the actual profile (what is cut), x and y in mm in the cam's
own frame. The last line is the first again (a closed outline). Numbers are written in
their shortest exact form (a float read back is the float written). The points come from
sizer.mechanics.disc_cam.profile_points; here metres become millimetres and radians
degrees.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from sizer.report.csv_text import render_csv
from sizer.report.numbers import short
from sizer.report.printable import printable

if TYPE_CHECKING:
    from sizer.mechanics.disc_cam import CamPoints, CamStage

COLUMNS_TRANSLATING = ("cam angle [deg]", "lift [mm]", "pitch x [mm]", "pitch y [mm]",
                       "profile x [mm]", "profile y [mm]")
COLUMNS_OSCILLATING = ("cam angle [deg]", "swing [deg]", "pitch x [mm]", "pitch y [mm]",
                       "profile x [mm]", "profile y [mm]")


def _number(value: float) -> str:
    return "0" if value == 0.0 else repr(float(value))


def profile_csv(stage: CamStage, points: CamPoints, *, title: str = "",
                label: str = "") -> str:
    """The CSV text of one resolved cam's points (module docstring)."""
    assert stage.base_radius is not None and stage.lift is not None, "the cam resolved"
    lift = stage.lift.output(points.theta)
    if stage.arm is None:
        columns, lift_scale = COLUMNS_TRANSLATING, 1000.0
        follower = (f"translating roller follower, offset e = "
                    f"{short(stage.offset * 1000.0, 12)} mm")
    else:
        columns, lift_scale = COLUMNS_OSCILLATING, math.degrees(1.0)
        follower = (f"oscillating roller follower, pivot distance a = "
                    f"{short(stage.arm[0] * 1000.0, 12)} mm, arm length L = "
                    f"{short(stage.arm[1] * 1000.0, 12)} mm")
    comments = [
        f"disc cam profile{': ' + title if title else ''}",
        *([f"candidate: {label}"] if label else []),
        f"base radius R_b [mm]: {_number(stage.base_radius * 1000.0)}",
        f"roller radius R_f [mm]: {_number(stage.roller_radius * 1000.0)}",
        f"prime radius R_p [mm]: {_number(stage.prime_radius * 1000.0)}",
        follower,
        f"cam speed [rpm]: {short(stage.speed * 60.0 / (2.0 * math.pi), 12)} "
        f"(one turn per machine cycle)",
        "frame: the cam's, its centre at the origin, the fixed frame at cam angle 0 ("
        + ("the follower's axis parallel to y at x = e, the roller moving along +y"
           if stage.arm is None else "the arm's pivot at (a, 0)")
        + "); the cam turns counterclockwise",
    ]
    head = "".join(f"# {printable(line)}\n" for line in comments)
    table = np.column_stack((np.degrees(points.theta), lift * lift_scale,
                             points.pitch_x * 1000.0, points.pitch_y * 1000.0,
                             points.profile_x * 1000.0, points.profile_y * 1000.0))
    rows = ([_number(float(x)) for x in row] for row in table)
    return head + render_csv(columns, rows)
