"""The load and transmission seen from the motor shaft (book sec. 6.1.1, eq. 6.1).

Stages run from the motor to the load. Each stage adds, at its input, the torque to
accelerate its own inertia and its preload friction. Two conventions for the efficiency
(``Transmission.efficiency_applies_to``):

- ``power_flow`` (Siemens, Mitsubishi; the default): a torque x at a stage's output (along
  the motion) needs x/(k*eta) at its input while power flows to the load (x >= 0) and
  x*eta/k while the load drives (x < 0); the motor torque is piecewise linear in a, v.
- ``steady_load`` (Yaskawa): only the load's steady torque (friction, damping, constant
  load, preloads) passes the stages with its efficiency, x_s/(k*eta) while its constant
  part opposes the motion and x_s*eta/k while it drives; the inertial torque passes
  without loss (T_L = F P_B / (2 pi R eta), T_a = (J_M + J_L) omega / t_a). The motor
  torque is linear in a, v, and the closed forms of the ideal chain apply.

With eta = 1 everywhere both are the book's J_t = J_m + J_gear + J_l/k^2 and
B_t = B_m + B_l/k^2. A linear axis reads mass for inertia, force for torque, and rad/m
for the last stage's ratio.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from sizer.model.domain import Load, Transmission


@dataclass(frozen=True)
class Drive:
    """Load plus transmission; everything the motor drives apart from its own rotor."""

    load: Load
    transmission: Transmission

    @property
    def stages(self):
        return self.transmission.stages

    @property
    def ratio(self) -> float:
        """Motor speed over load speed, K."""
        return self.transmission.ratio

    @property
    def efficiency(self) -> float:
        return self.transmission.efficiency

    @cached_property
    def input_ratios(self) -> tuple[float, ...]:
        """Speed of each stage's input over the load speed."""
        return self.transmission.input_ratios

    @property
    def steady_load_efficiency(self) -> bool:
        """The efficiencies act on the load's steady torque only (Yaskawa's convention)."""
        return self.transmission.efficiency_applies_to == "steady_load"

    @property
    def is_ideal(self) -> bool:
        """The motor torque is linear in the load's a, v: all efficiencies are 1, or they
        act on the steady load only. The closed forms (``linear_chain``) then apply."""
        return self.steady_load_efficiency or all(s.efficiency == 1.0 for s in self.stages)

    @property
    def transmission_inertia(self) -> float:
        """Inertia of all stages reflected to the motor shaft (no efficiency)."""
        return self.transmission.inertia

    @property
    def reflected_load_inertia(self) -> float:
        """J_l/K^2, the load alone reflected to the motor (no efficiency)."""
        return self.load.inertia / self.ratio**2

    @property
    def driven_inertia(self) -> float:
        """Everything the motor drives, reflected to it: load, screws, gears, couplings."""
        return self.transmission_inertia + self.reflected_load_inertia

    def inertia_ratio_numerator(self, of: str = "driven") -> float:
        """The inertia ratio's numerator: ``driven`` (vendors' definition) or ``load``."""
        return self.driven_inertia if of == "driven" else self.reflected_load_inertia

    def load_torque(self, a_l: np.ndarray, v_l: np.ndarray, direction: float) -> np.ndarray:
        """u = J_l a + B_l v + F + direction*tau_ext: the load's torque along the motion."""
        load = self.load
        return load.inertia * a_l + load.damping * v_l + load.friction + direction * load.torque

    def chain(self, a_l: np.ndarray, v_l: np.ndarray,
              direction: float) -> tuple[np.ndarray, list[np.ndarray]]:
        """Torque the transmission needs at the motor shaft, and each stage's output torque.

        a_l, v_l are the load's acceleration and speed along the motion (magnitudes for
        the move's direction). Returns (shaft torque without the rotor, [output torque of
        stage 0, ..., output torque of the last stage = u]).
        """
        if self.steady_load_efficiency:
            return self._steady_load_chain(a_l, v_l, direction)
        x = self.load_torque(a_l, v_l, direction)
        outputs = [x]
        for stage, k_in in zip(reversed(self.stages), reversed(self.input_ratios), strict=True):
            reflected = np.where(x >= 0.0, x / (stage.ratio * stage.efficiency),
                                 x * stage.efficiency / stage.ratio)
            x = stage.inertia * k_in * a_l + stage.preload_torque + reflected
            outputs.append(x)
        outputs.pop()  # the last one is the shaft torque, not a stage output
        return x, outputs[::-1]

    def _steady_load_chain(self, a_l: np.ndarray, v_l: np.ndarray,
                           direction: float) -> tuple[np.ndarray, list[np.ndarray]]:
        """``chain`` with the efficiencies on the steady torque only (Yaskawa)."""
        load = self.load
        inertial = load.inertia * a_l
        steady = load.damping * v_l + load.friction + direction * load.torque
        constant = load.friction + direction * load.torque
        outputs = [inertial + steady]
        for stage, k_in in zip(reversed(self.stages), reversed(self.input_ratios), strict=True):
            factor = _steady_factor(stage.efficiency, constant)
            inertial = stage.inertia * k_in * a_l + inertial / stage.ratio
            steady = stage.preload_torque + steady * factor / stage.ratio
            constant = stage.preload_torque + constant * factor / stage.ratio
            outputs.append(inertial + steady)
        outputs.pop()
        return inertial + steady, outputs[::-1]

    def linear_chain(self, direction: float) -> tuple[float, float, float]:
        """(A, B, C) with shaft torque = A a_l + B v_l + C, valid when ``is_ideal``."""
        K = self.ratio
        a_part = self.load.inertia / K + sum(
            s.inertia * k_in**2 / K for s, k_in in zip(self.stages, self.input_ratios, strict=True))
        v_part = self.load.damping
        const = self.load.friction + direction * self.load.torque
        for stage in reversed(self.stages):
            factor = _steady_factor(stage.efficiency, const) if self.steady_load_efficiency \
                else 1.0
            v_part = v_part * factor / stage.ratio
            const = stage.preload_torque + const * factor / stage.ratio
        return a_part, v_part, const

    def holding_torques(self) -> tuple[float, list[float]]:
        """|Torque| at the motor shaft and at each stage output holding the constant load.

        At rest the power flow is undefined; holding counts as driving (divide by eta),
        the conservative choice.
        """
        x = abs(self.load.torque)
        outputs = [x]
        for stage in reversed(self.stages):
            x = x / (stage.ratio * stage.efficiency)
            outputs.append(x)
        outputs.pop()
        return x, outputs[::-1]

    @property
    def holding_torque(self) -> float:
        return self.holding_torques()[0]


def _steady_factor(efficiency: float, constant: float) -> float:
    """1/eta while the steady torque opposes the motion, eta while it drives."""
    return 1.0 / efficiency if constant >= 0.0 else efficiency
