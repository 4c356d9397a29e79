"""Transmission stages from their catalog or drawing data (ratio, inertia at the input).

Every function returns a ``Stage``: ``ratio`` is input speed over output speed (rad/rad
for rotary outputs, rad/m when the output moves linearly), ``inertia`` is what the stage
moves, reflected to its input. Solid steel parts use STEEL_DENSITY unless given one.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Literal, get_args

import numpy as np

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


Mounting = Literal["fixed-free", "supported-supported", "fixed-supported", "fixed-fixed"]
"""The end mountings of a screw shaft, as THK's catalog names them."""
MOUNTINGS: tuple[str, ...] = get_args(Mounting)

CRITICAL_SPEED_FACTORS: dict[str, float] = {
    "fixed-free": 3.4, "supported-supported": 9.7, "fixed-supported": 15.1, "fixed-fixed": 21.9}
"""lambda_2 of THK's eq. (7) (General Catalog, Ball Screw, "Permissible Rotational Speed",
A15-32): N_1 = lambda_2 d_1 / l_b^2 1e7 min^-1 (d_1 the thread minor diameter, l_b the
distance between the mounting surfaces, mm), the safety factor 0.8 included (THK's first
form, 60 lambda_1^2 / (2 pi l_b^2) sqrt(E I / (gamma A)) 0.8 with lambda_1 = 1.875,
3.142, 3.927, 4.73, E = 2.06e5 N/mm^2, gamma = 7.85e-6 kg/mm^3, rounded). engineersedge.com
("Critical Speed Ball Screw") prints the same numbers as the critical speed itself, without
the 0.8: that convention is speed_factor = 0.64."""

CRITICAL_SPEED_SAFETY = 0.8
"""The safety factor THK's lambda_2 includes (eq. 7: "a safety factor of 0.8 is
multiplied"): the critical speed itself is lambda_2 / 0.8 d_1 / l_b^2 1e7 min^-1."""

BUCKLING_FACTORS: dict[str, float] = {
    "fixed-free": 1.3, "supported-supported": 5.1, "fixed-supported": 10.0, "fixed-fixed": 20.0}
"""eta_2 of THK's eq. (5) (General Catalog, Ball Screw, "Permissible Axial Load", A15-30):
P_1 = eta_2 d_1^4 / l_a^2 1e4 N (l_a the distance between the mounting surfaces, mm), the
safety factor 0.5 included. THK prints fixed-free, fixed-supported and fixed-fixed;
supported-supported is HSK's m = 5.1 (N = 1) of the same formula (HSK, "Ball Screw
Technical Description: Screw Shaft Design", b2b-linearbearing.com, with m = 1.3, 10.2,
20.3 for the others; MISUMI's worked example uses m = 10 for fixed-support)."""

BUCKLING_SAFETY = 0.5
"""The safety factor THK's eta_2 includes (eq. 5: "a safety factor of 0.5 is
multiplied"): the Euler buckling load itself is eta_2 / 0.5 d_1^4 / l_a^2 1e4 N."""

PERMISSIBLE_AXIAL_STRESS = 147e6
"""Pa: THK's permissible tensile-compressive stress of the screw shaft (eq. 6, A15-30:
P_2 = sigma pi/4 d_1^2 = 116 d_1^2 N, d_1 in mm)."""

_RPM = 2.0 * math.pi / 60.0


def screw_critical_speed(root_diameter: float, length: float, mounting: str) -> float:
    """The first bending critical speed of a screw shaft (rad/s): THK's eq. (7) without its
    safety factor, lambda_2 / 0.8 d_r / L^2 1e7 min^-1 (d_r, L in mm); d_r, L in m."""
    factor = CRITICAL_SPEED_FACTORS[mounting] / CRITICAL_SPEED_SAFETY
    rpm = factor * (root_diameter * 1e3) / (length * 1e3) ** 2 * 1e7
    return rpm * _RPM


def screw_buckling_load(root_diameter: float, length: float, mounting: str) -> float:
    """The Euler buckling load of a screw shaft (N): THK's eq. (5) without its safety
    factor, eta_2 / 0.5 d_r^4 / L^2 1e4 N (d_r, L in mm); d_r, L in m."""
    factor = BUCKLING_FACTORS[mounting] / BUCKLING_SAFETY
    return factor * (root_diameter * 1e3) ** 4 / (length * 1e3) ** 2 * 1e4


def screw_rated_life(dynamic_load_rating: float, mean_load: Any,
                     load_factor: float = 1.0) -> Any:
    """The rated life L_10 of a ball screw in revolutions: (C_a / (f_w F_m))^3 1e6 (THK,
    General Catalog, Ball Screw, "Studying the Service Life"), for a mean load F_m or an
    array of them; inf with no load."""
    load = np.asarray(mean_load, dtype=float)
    with np.errstate(divide="ignore", over="ignore"):
        life = np.where(load > 0.0, (dynamic_load_rating / (load_factor * load)) ** 3 * 1e6,
                        np.inf)
    return float(life) if life.ndim == 0 else life


@dataclass(frozen=True)
class ScrewRatings:
    """What a ball screw's datasheet and mounting give for its own checks (SI).

    ``mounting`` (:data:`MOUNTINGS`), ``root_diameter`` d_r (the thread minor diameter),
    ``support_distance`` (between the mounting surfaces, for the critical speed) and
    ``buckling_length`` (between the nut and the mounting that takes the thrust, for
    buckling) give the critical speed and buckling checks; ``speed_factor`` and
    ``buckling_factor`` are the safety factors the makers apply (0.8 and 0.5).
    ``dynamic_load_rating`` C_a, ``load_factor`` f_w and ``required_life`` (s) give the
    life check. A group left out (None) has no check.
    """

    mounting: Mounting | None = None
    root_diameter: float | None = None
    support_distance: float | None = None
    buckling_length: float | None = None
    speed_factor: float = CRITICAL_SPEED_SAFETY
    buckling_factor: float = BUCKLING_SAFETY
    dynamic_load_rating: float | None = None
    load_factor: float = 1.0
    required_life: float | None = None

    @property
    def has_shaft_checks(self) -> bool:
        return (self.mounting is not None and self.root_diameter is not None
                and self.support_distance is not None)

    @property
    def has_life_check(self) -> bool:
        return self.dynamic_load_rating is not None and self.required_life is not None

    @property
    def permissible_speed(self) -> float:
        """speed_factor x the critical speed (rad/s): THK's N_1 at the default 0.8."""
        assert self.has_shaft_checks
        assert self.mounting is not None and self.root_diameter is not None
        assert self.support_distance is not None
        return self.speed_factor * screw_critical_speed(self.root_diameter,
                                                        self.support_distance, self.mounting)

    @property
    def permissible_buckling_load(self) -> float:
        """buckling_factor x the buckling load (N): THK's P_1 at the default 0.5."""
        assert self.has_shaft_checks
        assert self.mounting is not None and self.root_diameter is not None
        length = self.buckling_length if self.buckling_length is not None \
            else self.support_distance
        assert length is not None
        return self.buckling_factor * screw_buckling_load(self.root_diameter, length,
                                                          self.mounting)


    @property
    def permissible_tensile_compressive_load(self) -> float:
        """THK's P_2 (N): the permissible stress over the root section, sigma pi d_r^2 / 4
        (116 d_1^2 N with d_1 in mm)."""
        assert self.root_diameter is not None
        return PERMISSIBLE_AXIAL_STRESS * math.pi * self.root_diameter**2 / 4.0


@dataclass(frozen=True)
class BallScrewStage(Stage):
    """A ball screw stage with its own ratings (:class:`ScrewRatings`, None: none given)."""

    screw: ScrewRatings | None = None


def ball_screw(lead: float, *, efficiency: float = 0.9, inertia: float | None = None,
               diameter: float | None = None, length: float | None = None,
               density: float = STEEL_DENSITY, preload_torque: float = 0.0,
               max_speed: float | None = None, screw: ScrewRatings | None = None,
               name: str = "") -> Stage:
    """A ball screw: ratio 2 pi / lead (rad/m); screw inertia given or from d, L, density.

    ``density`` is the screw material's (kg/m^3; vendors use 7.87e3 or 7.8e3 for steel).
    ``max_speed`` is the user's screw speed limit (e.g. the nut's DN limit).
    ``screw``: the ratings for the critical speed, buckling and life checks (a
    :class:`BallScrewStage` then; a plain Stage without).
    """
    if inertia is None:
        if diameter is None or length is None:
            raise ValueError("a ball screw needs its inertia or its diameter and length")
        inertia = screw_inertia(diameter, length, density)
    if screw is not None:
        return BallScrewStage("ball_screw", 2.0 * math.pi / lead, efficiency, inertia,
                              name=name, preload_torque=preload_torque,
                              max_input_speed=max_speed, screw=screw)
    return Stage("ball_screw", 2.0 * math.pi / lead, efficiency, inertia, name=name,
                 preload_torque=preload_torque, max_input_speed=max_speed)


def rack_pinion(pitch_radius: float, *, inertia: float = 0.0, efficiency: float = 1.0,
                name: str = "") -> Stage:
    """A rack and pinion: ratio 1/r (rad/m)."""
    return Stage("rack_pinion", 1.0 / pitch_radius, efficiency, inertia, name=name)
