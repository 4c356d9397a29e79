"""A normalized law placed in time and space: q(t) = q0 + h*q_N((t - t0)/T) (sec. 5.2)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from sizer.laws.base import MotionLaw

SERIES_NAMES = ("t", "q", "v", "a", "j")


@dataclass(frozen=True)
class ScaledMotion:
    """A rest-to-rest move of displacement h (may be negative) in duration T from t0, q0."""

    law: MotionLaw
    displacement: float
    duration: float
    start_time: float = 0.0
    start_position: float = 0.0

    def __post_init__(self) -> None:
        if not self.duration > 0.0:
            raise ValueError("duration must be positive")

    def derivative(self, t: np.ndarray | float, order: int = 0) -> np.ndarray:
        """The order-th time derivative of q at t; the k-th scales by h/T^k."""
        tau = (np.asarray(t, dtype=float) - self.start_time) / self.duration
        value = self.displacement * self.law.derivative(tau, order) / self.duration**order
        return value + self.start_position if order == 0 else value

    def sample(self, samples: int) -> dict[str, np.ndarray]:
        """t, q, v, a, j at ``samples`` equally spaced instants over [t0, t0 + T]."""
        t = self.start_time + self.duration * np.linspace(0.0, 1.0, samples)
        series = {"t": t}
        for order, name in enumerate(SERIES_NAMES[1:]):
            series[name] = self.derivative(t, order)
        return series

    @property
    def peak_velocity(self) -> float:
        return self.law.coefficients.C_v * abs(self.displacement) / self.duration

    @property
    def peak_acceleration(self) -> float:
        return self.law.coefficients.C_a * abs(self.displacement) / self.duration**2

    @property
    def peak_jerk(self) -> float:
        return self.law.coefficients.C_j * abs(self.displacement) / self.duration**3
