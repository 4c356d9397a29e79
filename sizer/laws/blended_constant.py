"""Constant velocity or acceleration with sinusoidal blends (book sec. 3.10).

- ``cycloidal_blends``: constant velocity reached and left through half-cosine velocity
  blends, eq. (3.55) with phi = 3 pi/2 (sec. 3.10.1, the minimum-time law of 3.10.3);
  alpha = T_1/T is the blend share, alpha = 1/2 the cycloidal law (Fig. 3.51).
- ``cycloidal_blend_acceleration``: the seven-segment acceleration profile of sec. 3.10.2
  (Fig. 3.48), quarter-sine blends between constant accelerations a2, 0 and -a6.
"""

from __future__ import annotations

import math

from sizer.laws.base import MotionLaw, Parameter
from sizer.laws.pieces import mirrored, trig_poly_piece
from sizer.laws.seven_segments import SINE, SevenSegmentLaw, shares_parameters

PI = math.pi

MIN_BLEND = 1e-6
"""Smallest blend share: C_a = pi/(2 alpha (1 - alpha)) stays finite."""


class CycloidalBlends(MotionLaw):
    """Constant velocity with cycloidal blends (sec. 3.10.1, 3.10.3), rest to rest.

    v_N = V (1 - cos(pi tau/alpha))/2 on [0, alpha], V = 1/(1 - alpha) on the cruise,
    mirrored. The acceleration is continuous (half sines), the jerk steps at the joins."""

    law_id = "cycloidal_blends"
    title = "Constant velocity, cycloidal blends"
    max_order = 32
    parameters = (
        Parameter("alpha", 1 / 3, MIN_BLEND, 0.5,
                  description="blend time over duration, T_1/T (Example 3.24 b: 1/3); 1/2 "
                              "is the cycloidal law"),
    )

    def _build(self):
        alpha = self.params["alpha"]
        v = 1.0 / (1.0 - alpha)
        w = PI / alpha
        half = [
            trig_poly_piece(0.0, alpha, (0.0, v / 2.0), [(-v / (2.0 * w), w, 0.0)]),
            trig_poly_piece(alpha, 0.5, (v * alpha / 2.0, v), origin=alpha),
        ]
        return mirrored(half), 2

    def closed_form_coefficients(self) -> dict[str, float]:
        """C_v = V, C_a = V pi/(2 alpha), C_j = V pi^2/(2 alpha^2) (at the joins);
        int v^2 = V^2 (1 - 5 alpha/4), int a^2 = V^2 pi^2/(4 alpha)."""
        a = self.params["alpha"]
        v = 1.0 / (1.0 - a)
        return {"C_v": v, "C_a": v * PI / (2.0 * a), "C_j": v * PI**2 / (2.0 * a * a),
                "C_v_rms": v * math.sqrt(1.0 - 1.25 * a),
                "C_a_rms": v * PI / (2.0 * math.sqrt(a))}


def cycloidal_blends_minimum_time(h: float, v_max: float, a_max: float
                                  ) -> tuple[float, float]:
    """(T, alpha) of the minimum-time move of sec. 3.10.3 over h > 0 with |v| <= v_max,
    |a| <= a_max: T_1 = pi v_max/(2 a_max), T = T_1 + h/v_max when
    h >= pi v_max^2/(2 a_max) (printed pi/4, see docs/errata.md); otherwise no cruise,
    T = 2 sqrt(h pi/(2 a_max)) and alpha = 1/2 (the cycloidal law)."""
    if h >= PI * v_max * v_max / (2.0 * a_max):
        t1 = PI * v_max / (2.0 * a_max)
        total = t1 + h / v_max
        return total, t1 / total
    return 2.0 * math.sqrt(h * PI / (2.0 * a_max)), 0.5


class CycloidalBlendAcceleration(SevenSegmentLaw):
    """Constant acceleration with sinusoidal (cycloidal) blends, sec. 3.10.2.

    The defaults are Example 3.25's first set, (1/8, 1/4, 1/8, 0, 1/8, 1/4, 1/8): the
    modified trapezoidal law (sec. 3.7)."""

    law_id = "cycloidal_blend_acceleration"
    title = "Constant acceleration, cycloidal blends"
    parameters = shares_parameters((1 / 8, 1 / 4, 1 / 8, 1 / 8, 1 / 4, 1 / 8))

    def blend_kinds(self) -> tuple[str, str, str, str]:
        return SINE, SINE, SINE, SINE
