"""The elastic load of sec. 7.1.1: a mass on a spring and damper behind the actuator.

With y the input position (the motion law) and x the load's, z = x - y obeys
z'' + 2 delta omega_n z' + omega_n^2 z = -y''   (eq. 7.2),
so the deflection is driven by the law's acceleration alone. The natural frequency is
given in Hz (f_n = omega_n / 2 pi), the damping ratio delta in [0, 1): the residual
vibration formulas need an under-damped mode.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from sizer.errors import UserError


@dataclass(frozen=True)
class ElasticLoad:
    """One vibration mode of the load: natural frequency f_n [Hz], damping ratio delta."""

    natural_frequency: float
    damping_ratio: float = 0.0

    def __post_init__(self) -> None:
        f, delta = self.natural_frequency, self.damping_ratio
        if not (math.isfinite(f) and f > 0.0):
            raise UserError(f"natural_frequency must be a positive frequency, not {f:g} Hz",
                            field="load.natural_frequency")
        if not (math.isfinite(delta) and 0.0 <= delta < 1.0):
            raise UserError(f"damping_ratio must be in [0, 1) (an under-damped mode), "
                            f"not {delta:g}", field="load.damping_ratio")

    @property
    def omega_n(self) -> float:
        """Natural angular frequency omega_n = 2 pi f_n [rad/s]."""
        return 2.0 * math.pi * self.natural_frequency

    @property
    def omega_d(self) -> float:
        """Damped angular frequency omega_n sqrt(1 - delta^2) [rad/s]."""
        return self.omega_n * math.sqrt(1.0 - self.damping_ratio**2)

    @property
    def damped_period(self) -> float:
        """Period of the damped free vibration 2 pi / omega_d [s]."""
        return 2.0 * math.pi / self.omega_d
