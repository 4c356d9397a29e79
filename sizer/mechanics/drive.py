"""The load and transmission reflected to the motor shaft (book sec. 6.1.1, eq. 6.1).

With total ratio k (motor speed over load speed) and efficiency eta, a load-side torque
u (or force on a linear axis) needs u/(k*eta) from the motor while the motor drives the
load (power flows to the load) and u*eta/k while the load drives the motor. So
J_t = J_m + J_gear + J_l/k^2 and B_t = B_m + B_l/k^2 when eta = 1.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from sizer.model.domain import Load, Transmission


@dataclass(frozen=True)
class Drive:
    """Load plus transmission; everything the motor sees apart from its own rotor."""

    load: Load
    transmission: Transmission

    @property
    def ratio(self) -> float:
        return self.transmission.ratio

    @property
    def efficiency(self) -> float:
        return self.transmission.efficiency

    @property
    def transmission_inertia(self) -> float:
        """Inertia of the transmission at the motor shaft, J_gear."""
        return self.transmission.inertia

    @property
    def reflected_load_inertia(self) -> float:
        """J_l/k^2 (the inertia ratio's numerator, without efficiency)."""
        return self.load.inertia / self.ratio**2

    def reflect(self, load_torque: np.ndarray) -> np.ndarray:
        """Motor-shaft torque for a load-side torque u along the motion direction.

        u >= 0: the motor drives the load, u/(k*eta); u < 0: the load drives, u*eta/k.
        """
        k, eta = self.ratio, self.efficiency
        return np.where(load_torque >= 0.0, load_torque / (k * eta), load_torque * eta / k)

    def load_torque(self, a_n: np.ndarray, v_n: np.ndarray, h: float, T: np.ndarray,
                    direction: float) -> np.ndarray:
        """Load-side torque along a move of |h| in T, direction +1 or -1 (eq. 6.1 + loads).

        u = J_l a + B_l v + F + direction*tau_ext, with a, v the load's magnitudes.
        """
        load = self.load
        return (load.inertia * h * a_n / T**2 + load.damping * h * v_n / T
                + load.friction + direction * load.torque)

    @property
    def holding_torque(self) -> float:
        """|Motor torque| holding the constant external load at rest (counted as driving)."""
        return abs(self.load.torque) / (self.ratio * self.efficiency)
