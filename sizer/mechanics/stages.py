"""Transmission stages from their catalog or drawing data (ratio, inertia at the input).

Every function returns a ``Stage``: ``ratio`` is input speed over output speed (rad/rad
for rotary outputs, rad/m when the output moves linearly), ``inertia`` is what the stage
moves, reflected to its input. Solid steel parts use STEEL_DENSITY unless given one.
"""

from __future__ import annotations

import math

from sizer.model.domain import Stage

STEEL_DENSITY = 7850.0
"""kg/m^3, for a screw given by diameter and length."""


def gearbox(ratio: float, efficiency: float = 1.0, inertia: float = 0.0, *,
            max_input_speed: float | None = None, rated_output_torque: float | None = None,
            peak_output_torque: float | None = None, backlash: float | None = None,
            name: str = "") -> Stage:
    """A gearbox: motor speed = ratio x output speed; inertia at its input."""
    return Stage("gearbox", ratio, efficiency, inertia, name=name,
                 max_input_speed=max_input_speed, rated_output_torque=rated_output_torque,
                 peak_output_torque=peak_output_torque, backlash=backlash)


def belt(*, ratio: float | None = None, driver_diameter: float | None = None,
         driven_diameter: float | None = None, driver_inertia: float = 0.0,
         driven_inertia: float = 0.0, belt_mass: float = 0.0, efficiency: float = 1.0,
         linear: bool = False, name: str = "") -> Stage:
    """A timing belt on two pulleys.

    Rotary output: ratio = d_driven/d_driver (or given); the belt moves at the driver's rim
    speed, so J_in = J_driver + J_driven/k^2 + m_belt (d_driver/2)^2.
    Linear output (the load rides on the belt): ratio = 2/d_driver rad/m, and the idler
    pulley turns like the driver when both diameters are equal:
    J_in = J_driver + J_driven (d_driver/d_driven)^2 + m_belt (d_driver/2)^2.
    """
    if linear:
        if driver_diameter is None:
            raise ValueError("a linear belt axis needs the driver pulley diameter")
        k = 2.0 / driver_diameter
        idler = driven_diameter or driver_diameter
        inertia = driver_inertia + driven_inertia * (driver_diameter / idler) ** 2
    else:
        if ratio is None:
            if driver_diameter is None or driven_diameter is None:
                raise ValueError("a belt needs its ratio or both pulley diameters")
            ratio = driven_diameter / driver_diameter
        k = ratio
        inertia = driver_inertia + driven_inertia / k**2
    if belt_mass:
        if driver_diameter is None:
            raise ValueError("a belt mass needs the driver pulley diameter")
        inertia += belt_mass * (driver_diameter / 2.0) ** 2
    return Stage("belt", k, efficiency, inertia, name=name)


def screw_inertia(diameter: float, length: float, density: float = STEEL_DENSITY) -> float:
    """Inertia of a solid cylinder about its axis: pi rho L d^4 / 32."""
    return math.pi * density * length * diameter**4 / 32.0


def ball_screw(lead: float, *, efficiency: float = 0.9, inertia: float | None = None,
               diameter: float | None = None, length: float | None = None,
               density: float = STEEL_DENSITY, preload_torque: float = 0.0,
               max_speed: float | None = None, name: str = "") -> Stage:
    """A ball screw: ratio 2 pi / lead (rad/m); screw inertia given or from d, L, density.

    ``density`` is the screw material's (kg/m^3; vendors use 7.87e3 or 7.8e3 for steel).
    ``max_speed`` is the user's screw speed limit (critical speed, ball recirculation).
    """
    if inertia is None:
        if diameter is None or length is None:
            raise ValueError("a ball screw needs its inertia or its diameter and length")
        inertia = screw_inertia(diameter, length, density)
    return Stage("ball_screw", 2.0 * math.pi / lead, efficiency, inertia, name=name,
                 preload_torque=preload_torque, max_input_speed=max_speed)


def rack_pinion(pitch_radius: float, *, inertia: float = 0.0, efficiency: float = 1.0,
                name: str = "") -> Stage:
    """A rack and pinion: ratio 1/r (rad/m)."""
    return Stage("rack_pinion", 1.0 / pitch_radius, efficiency, inertia, name=name)
