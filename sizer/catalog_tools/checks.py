"""Sanity checks of one catalog motor, beyond its schema: every problem, not the first.

The schema (``sizer.model.inputs.MotorInput``) already holds units, ranges and types; these
checks look at how the figures fit together: peak >= continuous torque, max speed >= rated
speed, curves with strictly increasing speeds within max_speed, the continuous region under
the intermittent one (the impossible motors, which loading refuses too), the curves' first
torques against the scalar ratings, a rotor inertia and a source. They are written once, in
:mod:`sizer.io.motor_checks`, which the loader uses too; this module gives them to the
catalog tools.

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

from sizer.io.motor_checks import (
    CURVE_START_TOLERANCE,
    RELATIVE_TOLERANCE,
    MotorProblem,
    check_motor,
    impossibilities,
)

__all__ = ["CURVE_START_TOLERANCE", "RELATIVE_TOLERANCE", "MotorProblem", "check_motor",
           "impossibilities"]
