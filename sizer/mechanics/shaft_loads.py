"""The forces a transmission stage puts on the shaft it sits on (docs/shaft-loads.md): the
motor's (the first stage), or the output shaft of the gearbox right before it.

For the torque tau on the shaft (on the motor's, the motor's peak |torque| over the cycle:
an upper bound, the rotor's own inertia torque J_m a does not pass through the shaft; on a
gearbox's output, the gearbox's peak |output torque|):

- a belt whose driver pulley (pitch diameter d) sits on the shaft, installed with the
  static tension F_pre in each strand, wrapping the pulley over the angle theta: the
  effective pull F_e = tau / (d/2) raises the tight strand and lowers the slack one by
  F_e/2 each (their sum stays 2 F_pre, the belt makers' rule for timing belts), the slack
  strand no lower than 0: T_s = max(F_pre - F_e/2, 0), T_t = T_s + F_e; the radial load is
  the two strands' vector sum, F_r = sqrt(T_t^2 + T_s^2 - 2 T_t T_s cos theta), at rest
  (and while T_s > 0 with theta = 180 deg) 2 F_pre sin(theta/2);
- a spur pinion of pitch diameter d and pressure angle alpha: the tangential tooth force
  F_t = tau / (d/2) and the radial (separating) force F_t tan(alpha), together
  F_r = F_t / cos(alpha) on the shaft;
- a ball screw coupled directly whose axial force the motor's bearing takes: the axial
  load is the screw's axial force.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from sizer.model.domain import ShaftLoad


def belt_radial_load(pretension: Any, effective_pull: Any, wrap_angle: Any) -> np.ndarray:
    """F_r (N) of a belt on its driver pulley: static tension ``pretension`` per strand,
    ``effective_pull`` (tight minus slack, N) and ``wrap_angle`` (rad), module docstring."""
    pull = np.abs(np.asarray(effective_pull, dtype=float))
    slack = np.maximum(np.asarray(pretension, dtype=float) - 0.5 * pull, 0.0)
    tight = slack + pull
    square = tight**2 + slack**2 - 2.0 * tight * slack * np.cos(wrap_angle)
    return np.sqrt(np.maximum(square, 0.0))


def pinion_radial_load(tangential_force: Any, pressure_angle: Any) -> np.ndarray:
    """The tooth force of a spur pinion on its shaft (N): the tangential force F_t and
    the radial F_t tan(alpha) together, |F_t| / cos(alpha)."""
    return np.abs(np.asarray(tangential_force, dtype=float)) / np.cos(pressure_angle)


@dataclass(frozen=True)
class ShaftForces:
    """The radial and axial loads on the shaft per candidate (N); None where the stage
    puts no such load on it."""

    radial: np.ndarray | None
    axial: np.ndarray | None


def shaft_forces(load: ShaftLoad, torque: Any, axial_force: Any) -> ShaftForces:
    """The loads of ``load`` on the shaft for the shaft's peak |``torque``| (N*m) and, for
    a ball screw, its peak |``axial_force``| (N)."""
    tau = np.abs(np.asarray(torque, dtype=float))
    if load.kind == "belt":
        return ShaftForces(belt_radial_load(load.pretension, tau / (0.5 * load.diameter),
                                            load.wrap_angle), None)
    if load.kind == "pinion":
        return ShaftForces(pinion_radial_load(tau / (0.5 * load.diameter),
                                              load.pressure_angle), None)
    return ShaftForces(None, np.abs(np.asarray(axial_force, dtype=float)))
