"""The trigonometric polynomial through the points of a periodic motion (book sec. 4.3).

Kind ``trigonometric_polynomial``. For a periodic motion, q(t + T) = q(t), the book
interpolates the points (t_k, q_k), k = 0..n, with q_n = q_0, by

    q(t) = a_0 + sum_{k=1..m} a_k cos(k 2 pi (t - t_0) / T) + b_k sin(k 2 pi (t - t_0) / T)

of degree m = (n - 1) / 2 over the period T = t_n - t_0 (the book takes t_0 = 0): the 2m + 1
coefficients are the solution of the system (4.5) of the interpolation conditions at
t_0 .. t_{n-1} (the last point is the first one a period later). So the number of points
n + 1 = 2m + 2 must be even (the book: "an even number of points is therefore
required"), at least 4, and the last position must equal the first.

The curve is periodic by construction, with every derivative continuous across the
period (C-infinity, "periodic conditions"): as a law it is one period of a repeated
motion that returns to its start, normalized by its largest excursion (docs/data-laws.md,
"Laws whose ends move"). It is evaluated as sizer's exact polynomial-plus-sines piece
(:func:`sizer.laws.pieces.trig_poly_piece`, a_k cos x = a_k sin(x + pi / 2)), whose
derivatives of every order are closed forms.

The book's Lagrange-like form (4.6) gives the same curve without solving (4.5); its
product runs over the 2m + 1 distinct points j = 0 .. n - 1 (written to n in the book,
where the factor of t_n = t_0 + T would be sin(pi (t_0 - t_n) / T) = 0 for k = 0).

The system is refused when it is too ill-conditioned to be solved (points crowded
against each other, for their number): MAX_CONDITION. The report gives the degree m,
the coefficients a_k, b_k and the ``overshoot`` (how far the curve leaves the range of
the positions, a share of it: the book notes that a trigonometric polynomial oscillates
more than a spline through the same points, Fig. 4.5).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from sizer.errors import UserError
from sizer.laws.multipoint import FittedCurve
from sizer.laws.multipoint.fields import points, refuse_unknown
from sizer.laws.multipoint.interpolating_polynomial import (
    MAX_CONDITION,
    breakpoints,
    overshoot,
)
from sizer.laws.pieces import Piece, trig_poly_piece

KIND = "trigonometric_polynomial"
FIELDS = ("points", "times", "positions")

CLOSE_TOLERANCE = 1e-12
"""|q_n - q_0| over the positions' largest magnitude below which the points close."""


@dataclass(eq=False)
class TrigonometricCurve:
    """The trigonometric polynomial over [x[0], x[-1]] (x: the data's times) with the
    period ``period``: a_0 + sum a_k cos(k w u) + b_k sin(k w u), u = t - x[0], w = 2 pi /
    period. ``piece`` is the same curve as sizer's closed-form piece (trig_poly_piece: a
    constant plus sines, with its TrigPolyForm for an export that writes coefficients);
    the curve is evaluated from the same coefficients with every harmonic in one matrix
    product (the piece sums its sines one call per harmonic: a law of 100 harmonics
    would take seconds to measure)."""

    x: np.ndarray
    period: float
    cosines: np.ndarray
    sines: np.ndarray
    piece: Piece

    def __call__(self, t: np.ndarray, nu: int = 0) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        flat = t.ravel() - float(self.x[0])
        m = len(self.cosines) - 1
        k = np.arange(1, m + 1)
        omega = 2.0 * math.pi / self.period
        scale = (k * omega) ** nu
        a, b = self.cosines[1:] * scale, self.sines[1:] * scale
        # d^nu/du^nu of a cos(x) + b sin(x) is a cos(x + nu pi/2) + b sin(x + nu pi/2)
        a, b = ((a, b), (b, -a), (-a, -b), (-b, a))[nu % 4]
        out = np.full(flat.shape, self.cosines[0] if nu == 0 else 0.0)
        for part in range(0, len(flat), _CHUNK):
            angle = np.outer(flat[part:part + _CHUNK], k * omega)
            out[part:part + _CHUNK] += np.cos(angle) @ a + np.sin(angle) @ b
        return out.reshape(t.shape)


_CHUNK = 4_096
"""Times evaluated at once (a matrix of times by harmonics)."""


def trigonometric_coefficients(t: np.ndarray, q: np.ndarray
                               ) -> tuple[np.ndarray, np.ndarray, float]:
    """The book's a_0..a_m and b_1..b_m (as (a, b), b[0] = 0) from the system (4.5) at
    t_0..t_{n-1}, and the condition number of its row-scaled matrix."""
    period = float(t[-1] - t[0])
    m = (len(t) - 2) // 2
    x = 2.0 * math.pi * (t[:-1] - t[0]) / period
    k = np.arange(1, m + 1)
    matrix = np.empty((len(x), 2 * m + 1))
    matrix[:, 0] = 1.0
    matrix[:, 1::2] = np.cos(np.outer(x, k))
    matrix[:, 2::2] = np.sin(np.outer(x, k))
    condition = float(np.linalg.cond(matrix))
    if not condition < MAX_CONDITION:
        return np.zeros(m + 1), np.zeros(m + 1), condition
    solution = np.linalg.solve(matrix, q[:-1])
    a = np.concatenate(([solution[0]], solution[1::2]))
    b = np.concatenate(([0.0], solution[2::2]))
    return a, b, condition


def build_trigonometric_polynomial(fields: Mapping[str, Any]) -> FittedCurve:
    """The YAML mapping of a ``trigonometric_polynomial`` law (module docstring)."""
    refuse_unknown(fields, FIELDS, KIND)
    t, q = points(fields, minimum=4)
    where = "points" if "points" in fields else "positions"
    if len(t) % 2:
        raise UserError(f"needs an even number of points (book sec. 4.3: 2m + 1 distinct "
                        f"points for degree m, and the last equal to the first, a period "
                        f"later), got {len(t)}", field=where)
    last = f"points[{len(t) - 1}]" if where == "points" else f"positions[{len(t) - 1}]"
    if abs(q[-1] - q[0]) > CLOSE_TOLERANCE * max(float(np.max(np.abs(q))), 1e-300):
        raise UserError(f"the motion is periodic: the last position must equal the first "
                        f"(q_n = q_0 = {q[0]:g}), got {q[-1]:g}", field=last)
    a, b, condition = trigonometric_coefficients(t, q)
    if not condition < MAX_CONDITION:
        raise UserError(f"the points make an ill-conditioned system (4.5) (condition "
                        f"number {condition:.3g}): times too close together; use a periodic "
                        f"cubic_spline", field=where)
    period = float(t[-1] - t[0])
    omega = 2.0 * math.pi / period
    m = len(a) - 1
    waves = [(float(a[k]), k * omega, math.pi / 2.0) for k in range(1, m + 1)]
    waves += [(float(b[k]), k * omega, 0.0) for k in range(1, m + 1)]
    piece = trig_poly_piece(0.0, period, (float(a[0]),), waves)
    curve = TrigonometricCurve(breakpoints(t), period, a, b, piece)
    report = {"degree": float(m), "overshoot": overshoot(curve, q),
              "condition_number": condition}
    report.update({f"a_{k}": float(a[k]) for k in range(m + 1)})
    report.update({f"b_{k}": float(b[k]) for k in range(1, m + 1)})
    return FittedCurve(curve, report)
