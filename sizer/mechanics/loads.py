"""Linear loads: a mass on an incline with friction, turned into the load model."""

from __future__ import annotations

import math

from sizer.model.domain import Load

GRAVITY = 9.80665
"""Standard gravity, m/s^2."""


def linear_load(mass: float, *, incline: float = 0.0, friction_coefficient: float = 0.0,
                friction_force: float = 0.0, force: float = 0.0,
                damping: float = 0.0) -> Load:
    """A mass moving along an axis inclined by ``incline`` (rad) from the horizontal.

    A positive move goes up the incline: gravity adds m g sin(incline) to the constant
    force opposing it (and helps a move down); Coulomb friction is mu m g cos(incline)
    plus a given friction force. On a vertical axis (90 deg) the load is held at rest
    by the motor, which the RMS over the dwell counts.
    """
    gravity = mass * GRAVITY * math.sin(incline)
    normal = mass * GRAVITY * math.cos(incline)
    return Load(inertia=mass, damping=damping,
                friction=friction_force + friction_coefficient * abs(normal),
                torque=force + gravity)
