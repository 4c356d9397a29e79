"""Synthetic motors and designs shared by the engine benchmarks (issue 11).

The motors are a geometric family of ratings, NOT datasheet figures: they only exercise
the engine's code paths at catalog sizes. Everything is SI.

- ``book_problem``: the book's case of eq. (6.2): rectangular regions, an inertial load,
  an ideal gearbox with a list of ratios, minimize mode, a cycle with dwell and return.
- ``scale_problem``: the same task with everything real: speed-torque curves on every
  motor, friction, damping and a constant load, an efficiency, a dwell.
"""

from __future__ import annotations

import math

from sizer.laws import DEFAULT_LAW_SPECS
from sizer.model import Design, Limits, Load, Motor, RatioChoice, Stage, Task, Transmission

RPM = math.pi / 30.0

BOOK_LAWS: tuple[str, ...] = tuple(s for s in DEFAULT_LAW_SPECS if not s.startswith("exponential"))
"""15 laws: the default list without the exponential law."""

SCALE_LAWS: tuple[str, ...] = (*DEFAULT_LAW_SPECS, "trapezoidal(alpha=1/4)",
                               "trapezoidal(alpha=1/5)", "double_s(alpha=1/4, beta=1/3)",
                               "polynomial(degree=9)")
"""20 laws: the default list and four more shapes."""

RATIOS: tuple[float, ...] = tuple(round(3.0 * 1.3**i, 6) for i in range(12))
"""12 gearbox ratios from 3 to about 54."""

H = math.pi / 2
DWELL = 0.15
LOAD_INERTIA = 0.35
GEAR_INERTIA = 1.2e-4
TORQUE_MARGIN = 0.1
SPEED_MARGIN = 0.05


def rectangular_motors(count: int) -> tuple[Motor, ...]:
    """``count`` motors, 0.1 to 50 N*m continuous, ratings only (the book's rectangles)."""
    motors = []
    for i in range(count):
        torque = 0.1 * 500.0 ** (i / max(count - 1, 1))
        motors.append(Motor(id=f"syn-{i:05d}", inertia=2e-5 * torque**1.3,
                            continuous_torque=torque, peak_torque=3.0 * torque,
                            rated_speed=(3000.0 - 1000.0 * (i % 3)) * RPM))
    return tuple(motors)


def curved_motors(count: int) -> tuple[Motor, ...]:
    """``count`` motors with intermittent and continuous speed-torque curves."""
    motors = []
    for m in rectangular_motors(count):
        tau_c, tau_p, v_n = m.continuous_torque, m.peak_torque, m.rated_speed
        v_max = 2.0 * v_n
        motors.append(Motor(
            id=m.id, inertia=m.inertia, continuous_torque=tau_c, peak_torque=tau_p,
            rated_speed=v_n, max_speed=v_max,
            intermittent_curve=((0.0, tau_p), (0.8 * v_n, tau_p), (1.4 * v_n, 0.7 * tau_p),
                                (v_max, 0.35 * tau_p)),
            continuous_curve=((0.0, 1.05 * tau_c), (v_n, tau_c), (v_max, 0.5 * tau_c)),
        ))
    return tuple(motors)


def book_problem(motors: int, laws: tuple[str, ...] = BOOK_LAWS,
                 ratios: tuple[float, ...] = RATIOS) -> Design:
    """Rectangular regions, inertial load, ideal gearbox with ratio choice, minimize."""
    return Design(
        Task(H, None, dwell=DWELL, return_move=True), Load(LOAD_INERTIA),
        Transmission((Stage("gearbox", ratios[0], 1.0, GEAR_INERTIA),)),
        laws=laws, motors=rectangular_motors(motors),
        limits=Limits(torque_margin=TORQUE_MARGIN, speed_margin=SPEED_MARGIN, envelope="book"),
        ratio_choice=RatioChoice(stage=0, ratios=ratios), name="synthetic book problem")


def scale_problem(motors: int, laws: tuple[str, ...] = SCALE_LAWS,
                  ratios: tuple[float, ...] = RATIOS) -> Design:
    """Curves, friction, damping, a constant load and an efficiency; minimize."""
    return Design(
        Task(H, None, dwell=DWELL, return_move=True),
        Load(LOAD_INERTIA, damping=0.01, friction=0.2, torque=0.5),
        Transmission((Stage("gearbox", ratios[0], 0.95, GEAR_INERTIA),)),
        laws=laws, motors=curved_motors(motors),
        limits=Limits(torque_margin=TORQUE_MARGIN, speed_margin=SPEED_MARGIN),
        ratio_choice=RatioChoice(stage=0, ratios=ratios), name="synthetic scale problem")


def motor_id(result) -> str:
    """A result's motor id (results may hold the motor object or its id)."""
    return getattr(result.motor, "id", result.motor)


def spec_of(result) -> str:
    """A result's canonical law spec (results may hold the law object or its spec)."""
    law = getattr(result, "law", None)
    return law.spec if hasattr(law, "spec") else result.spec
