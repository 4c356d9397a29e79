"""A normalized law placed in time and space: q(t) = q0 + h*q_N((t - t0)/T) (sec. 5.2)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from sizer.laws.base import MotionLaw

SERIES_NAMES = ("t", "q", "v", "a", "j")

DERIVATIVE_NAMES = ("position", "velocity", "acceleration", "jerk")

PEAK_HEADROOM = 1e6
"""Room left above h / T^k for a law's own normalized peak |q_N^(k)| (C_v, C_a, C_j of the
steepest laws stay far below it): the scale of a derivative order times this must be a
float."""


def scale_fault(h: float, T: float, orders: int = 3) -> str | None:
    """Why a move of h in T cannot be written in double precision, or None: the first
    derivative order k <= ``orders`` whose scale |h| / T^k (sec. 5.2: the k-th derivative
    scales by h / T^k), times PEAK_HEADROOM, overflows, or whose T^k does (computed in
    logarithms)."""
    if h == 0.0 or not (math.isfinite(h) and math.isfinite(T) and T > 0.0):
        return None
    largest = math.log10(float(np.finfo(float).max))
    limit = largest - math.log10(PEAK_HEADROOM)
    for k in range(orders + 1):
        exponent = math.log10(abs(h)) - k * math.log10(T)
        if exponent > limit:
            return (f"its {DERIVATIVE_NAMES[k]} scales as h / T^{k} = 1e{exponent:.0f}, "
                    f"beyond the float range (about 1.8e308) with room for the law's peak")
        if k * math.log10(T) > largest:
            return (f"its {DERIVATIVE_NAMES[k]} divides by T^{k} = 1e"
                    f"{k * math.log10(T):.0f}, beyond the float range (about 1.8e308)")
    return None


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
