"""Transmissions and loads seen from the motor shaft (sec. 6.1.1)."""

from sizer.mechanics.drive import Drive
from sizer.mechanics.loads import GRAVITY, linear_load
from sizer.mechanics.stages import (
    STEEL_DENSITY,
    ball_screw,
    belt,
    gearbox,
    rack_pinion,
    screw_inertia,
)

__all__ = [
    "GRAVITY",
    "STEEL_DENSITY",
    "Drive",
    "ball_screw",
    "belt",
    "gearbox",
    "linear_load",
    "rack_pinion",
    "screw_inertia",
]
