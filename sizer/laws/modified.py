"""Modified trapezoidal and modified sinusoidal laws (book sec. 3.7 and 3.8).

Both are symmetric: the first half is written as in the book (T = 1, h = 1) and mirrored.
"""

from __future__ import annotations

import math

from sizer.laws.base import MotionLaw
from sizer.laws.pieces import mirrored, trig_poly_piece

PI = math.pi


class ModifiedTrapezoidal(MotionLaw):
    """Cycloidal blends and constant acceleration, h' = h/(2 + pi) (sec. 3.7)."""

    law_id = "modified_trapezoidal"
    title = "Modified trapezoidal"
    max_order = 32

    def _build(self):
        hp = 1.0 / (2.0 + PI)
        half = [
            trig_poly_piece(0.0, 1 / 8, (0.0, 2 * hp), [(-hp / (2 * PI), 4 * PI, 0.0)]),
            trig_poly_piece(1 / 8, 3 / 8, (hp * (0.25 - 1 / (2 * PI)), 2 * hp, 4 * PI * hp),
                            origin=1 / 8),
            trig_poly_piece(3 / 8, 1 / 2, (-hp * PI / 2, 2 * (1 + PI) * hp),
                            [(-hp / (2 * PI), 4 * PI, -PI)]),
        ]
        return mirrored(half), 2

    def closed_form_coefficients(self) -> dict[str, float]:
        hp = 1.0 / (2.0 + PI)
        return {"C_v": 2.0, "C_a": 8 * PI * hp, "C_j": 32 * PI**2 * hp}


class ModifiedSinusoidal(MotionLaw):
    """Cycloidal start blended into a harmonic, h' = pi*h/(2(pi + 4)) (sec. 3.8)."""

    law_id = "modified_sinusoidal"
    title = "Modified sinusoidal"
    max_order = 32

    def _build(self):
        hp = PI / (2.0 * (PI + 4.0))
        half = [
            trig_poly_piece(0.0, 1 / 8, (0.0, 2 * hp), [(-hp / (2 * PI), 4 * PI, 0.0)]),
            trig_poly_piece(1 / 8, 1 / 2, (4 * hp / PI, 2 * hp),
                            [(-9 * hp / (2 * PI), 4 * PI / 3, PI / 3)]),
        ]
        return mirrored(half), 2

    def closed_form_coefficients(self) -> dict[str, float]:
        hp = PI / (2.0 * (PI + 4.0))
        return {"C_v": 8 * hp, "C_a": 8 * PI * hp, "C_j": 32 * PI**2 * hp}
