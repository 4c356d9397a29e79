"""The slider-crank: crank radius r, rod length l, slider line offset e (seed 003 eq. 28).

The crank turns about the origin by theta; its pin is at r (cos theta, sin theta). The
slider moves along the line y = e; its position is s = r cos theta + sqrt(l^2 - u^2) with
u = r sin theta - e (the branch with the slider on the +x side). With e = 0 this is the
paper's q3 = r cos q1 + l cos q2, l sin q2 = r sin q1. The dead points are where crank
and rod are in line: extended, s_max = sqrt((l + r)^2 - e^2) (top dead centre), and
folded, s_min = sqrt((l - r)^2 - e^2) (bottom dead centre). The crank turns fully when
l > r + |e|; sizer asks for it.

Derivatives in theta are exact: w = sqrt(g), g = l^2 - u^2, from w^2 = g differentiated
(2 w w' = g', 2 w'^2 + 2 w w'' = g'', ...), u^(k) = r sin(theta + k pi / 2).

The output may instead be the rod's angle to the slider's line (``coordinate:
rod_angle``), v = asin(u / l) (the paper's q2, l sin q2 = r sin q1, for e = 0). Its
derivatives come from sin v = x = u / l differentiated: x' = cos v v1,
x'' = cos v v2 - sin v v1^2, x''' = cos v v3 - 3 sin v v1 v2 - cos v v1^3,
x'''' = cos v v4 - 4 sin v v1 v3 - 3 sin v v2^2 - 6 cos v v1^2 v2 + sin v v1^4 (vk the
k-th derivative; cos v > 0 since l > r + |e|). Its extremes are at cos theta = 0:
v = asin((r - e) / l) at theta = pi/2, asin((-r - e) / l) at theta = -pi/2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from sizer.errors import UserError
from sizer.mechanics.linkages import MAX_ORDER, outside_range

COORDINATES = ("slider_position", "rod_angle")
"""The output coordinates a slider-crank gives (its ``coordinate`` field)."""


@dataclass(frozen=True)
class SliderCrank:
    """A slider-crank of crank radius r, rod length rod and offset e (m); ``coordinate``
    the output: "slider_position" (m) or "rod_angle" (rad; module docstring)."""

    crank_radius: float
    rod_length: float
    offset: float = 0.0
    coordinate: str = "slider_position"

    @property
    def output_linear(self) -> bool:
        """A slider's position is a length; the rod's angle is not."""
        return self.coordinate == "slider_position"

    def __post_init__(self) -> None:
        r, rod, e = self.crank_radius, self.rod_length, self.offset
        for name, value in (("crank_radius", r), ("rod_length", rod)):
            if not (math.isfinite(value) and value > 0.0):
                raise UserError(f"must be a positive length, got {value!r} m", field=name)
        if not math.isfinite(e):
            raise UserError(f"must be a finite length, got {e!r} m", field="offset")
        if not rod > r + abs(e):
            raise UserError(f"the rod ({rod:g} m) must be longer than the crank radius plus "
                            f"the offset ({r:g} + {abs(e):g} m) for the crank to turn fully",
                            field="rod_length")
        if self.coordinate not in COORDINATES:
            raise UserError(f"must be one of {', '.join(COORDINATES)}, got "
                            f"{self.coordinate!r}", field="coordinate")

    def output(self, theta: np.ndarray, order: int = 0) -> np.ndarray:
        """d^order s / d theta^order (module docstring)."""
        if not 0 <= order <= MAX_ORDER:
            raise ValueError(f"order {order} not in 0..{MAX_ORDER}")
        theta = np.asarray(theta, dtype=float)
        r, rod, e = self.crank_radius, self.rod_length, self.offset
        if not self.output_linear:
            x = [r * np.sin(theta + k * np.pi / 2) / rod for k in range(order + 1)]
            x[0] = x[0] - e / rod
            return _asin_derivatives(x, order)[order]
        u = [r * np.sin(theta + k * np.pi / 2) for k in range(order + 1)]
        u[0] = u[0] - e
        w = _sqrt_derivatives(rod, u, order)
        crank = r * np.cos(theta + order * np.pi / 2)
        return crank + w[order]

    def input_of(self, s: np.ndarray, half: int) -> np.ndarray:
        """theta in the half-turn where ds/dtheta has the sign of ``half``: for the slider,
        from the top dead centre to the bottom one (half = -1: the slider moving in) or
        back (+1); for the rod angle, cos theta of the sign of ``half``."""
        s = np.asarray(s, dtype=float)
        low, high = self.output_range()
        value = outside_range(s, low, high)
        if value is not None:
            name, unit, swing = ("slider position", "m", "stroke") if self.output_linear \
                else ("rod angle", "rad", "swing")
            raise UserError(f"the {name} {value:g} {unit} is outside the {swing} "
                            f"[{low:g}, {high:g}] {unit}", field="output")
        s = np.clip(s, low, high)
        r, rod, e = self.crank_radius, self.rod_length, self.offset
        if not self.output_linear:
            # r sin theta = l sin v + e; dv/dtheta = r cos theta / (l cos v)
            y = np.arcsin(np.clip((rod * np.sin(s) + e) / r, -1.0, 1.0))
            return _wrapped(np.where(np.asarray(half) > 0, y, np.pi - y))
        # 2 r (s cos theta + e sin theta) = s^2 + r^2 + e^2 - rod^2
        rho = np.hypot(s, e)
        c = np.clip((s * s + r * r + e * e - rod * rod) / (2.0 * r * rho), -1.0, 1.0)
        beta = np.arctan2(e, s)
        # ds/dtheta < 0 on the half-turn after the top dead centre (theta - beta in (0, pi))
        return _wrapped(beta - half * np.arccos(c))

    def dead_points(self) -> np.ndarray:
        """Top dead centre atan2(e, s_max), bottom dead centre atan2(-e, -s_min); for the
        rod angle pi/2 (its largest) and -pi/2."""
        if not self.output_linear:
            return np.array([math.pi / 2, -math.pi / 2])
        low, high = self.output_range()
        return np.array([math.atan2(self.offset, high), math.atan2(-self.offset, -low)])

    def output_range(self) -> tuple[float, float]:
        """The stroke (or the rod's swing) between the dead points."""
        r, rod, e = self.crank_radius, self.rod_length, self.offset
        if not self.output_linear:
            return math.asin((-r - e) / rod), math.asin((r - e) / rod)
        return math.sqrt((rod - r) ** 2 - e * e), math.sqrt((rod + r) ** 2 - e * e)


def _sqrt_derivatives(rod: float, u: list[np.ndarray], order: int) -> list[np.ndarray]:
    """w = sqrt(rod^2 - u^2) and its derivatives up to ``order`` from those of u."""
    g = [rod * rod - u[0] ** 2]
    if order >= 1:
        g.append(-2.0 * u[0] * u[1])
    if order >= 2:
        g.append(-2.0 * (u[1] ** 2 + u[0] * u[2]))
    if order >= 3:
        g.append(-2.0 * (3.0 * u[1] * u[2] + u[0] * u[3]))
    if order >= 4:
        g.append(-2.0 * (3.0 * u[2] ** 2 + 4.0 * u[1] * u[3] + u[0] * u[4]))
    w = [np.sqrt(g[0])]
    if order >= 1:
        w.append(g[1] / (2.0 * w[0]))
    if order >= 2:
        w.append((g[2] - 2.0 * w[1] ** 2) / (2.0 * w[0]))
    if order >= 3:
        w.append((g[3] - 6.0 * w[1] * w[2]) / (2.0 * w[0]))
    if order >= 4:
        w.append((g[4] - 8.0 * w[1] * w[3] - 6.0 * w[2] ** 2) / (2.0 * w[0]))
    return w


def _asin_derivatives(x: list[np.ndarray], order: int) -> list[np.ndarray]:
    """v = asin(x) and its derivatives up to ``order`` from those of x (module
    docstring)."""
    v = [np.arcsin(x[0])]
    c, s = np.cos(v[0]), np.sin(v[0])
    if order >= 1:
        v.append(x[1] / c)
    if order >= 2:
        v.append((x[2] + s * v[1] ** 2) / c)
    if order >= 3:
        v.append((x[3] + c * v[1] ** 3 + 3.0 * s * v[1] * v[2]) / c)
    if order >= 4:
        v.append((x[4] - s * v[1] ** 4 + 6.0 * c * v[1] ** 2 * v[2] + 3.0 * s * v[2] ** 2
                  + 4.0 * s * v[1] * v[3]) / c)
    return v


def _wrapped(theta: np.ndarray) -> np.ndarray:
    """theta in [-pi, pi)."""
    return (theta + np.pi) % (2.0 * np.pi) - np.pi
