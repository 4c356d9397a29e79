"""The piecewise polynomial 4-3-4 law: lift-off, travel, set-down (book sec. 3.6).

Three polynomials of degree 4, 3 and 4 on [0, t_l], [t_l, 1 - t_s], [1 - t_s, 1]
(normalized: h = T = 1), through the inner points (t_l, h_l) and (1 - t_s, 1 - h_s),
at rest with null acceleration at tau = 0 and 1, with continuous velocity and
acceleration at the joins: the 14 conditions of sec. 3.6. The seven coefficients left are
the solution of the section's seven equations (each piece in its own tau in [0, 1]),
solved here as the linear system they are: the closed forms printed in Appendix A.2 do
not satisfy the section's equations (see docs/errata.md). The jerk steps at the joins in
general (C^2). The book gives no numbers for its Fig. 3.33; the defaults are a
symmetric move whose lift-off and set-down take a quarter of the time each and cover a
tenth of the displacement each. With h_l = h_s = t_l/(2 (1 - t_l)) and t_l = t_s the law
is the linear trajectory with quintic blends of sec. 3.3 (polynomial_blends, degree 5).
"""

from __future__ import annotations

import numpy as np
from numpy.polynomial import polynomial as P

from sizer.laws.base import MotionLaw, Parameter
from sizer.laws.pieces import trig_poly_piece

MIN_SHARE = 0.01
"""Smallest phase share: the polynomials' coefficients grow like 1/share^4."""

MAX_SHARE = 0.49
"""Largest lift-off or set-down share: the travel phase keeps at least 2% of T."""

NO_AUTO = "the 4-3-4 law's phases and inner points are given, not searched: write numbers"


def _share(name: str, default: float, description: str) -> Parameter:
    return Parameter(name, default, MIN_SHARE, MAX_SHARE, description=description,
                     no_auto=NO_AUTO)


def solve_434(t_l: float, t_t: float, t_s: float, h_a: float, h_b: float, h_1: float
              ) -> np.ndarray:
    """(a4l, a3l, a3t, a2t, a1t, a4s, a3s) of sec. 3.6: its seven equations, solved."""
    a = np.array([
        [1, 1, 0, 0, 0, 0, 0],
        [0, 0, 1, 1, 1, 0, 0],
        [0, 0, 0, 0, 0, -1, 1],
        [4 / t_l, 3 / t_l, 0, 0, -1 / t_t, 0, 0],
        [12 / t_l**2, 6 / t_l**2, 0, -2 / t_t**2, 0, 0, 0],
        [0, 0, 3 / t_t, 2 / t_t, 1 / t_t, 4 / t_s, -3 / t_s],
        [0, 0, 6 / t_t**2, 2 / t_t**2, 0, -12 / t_s**2, 6 / t_s**2],
    ], dtype=float)
    return np.linalg.solve(a, np.array([h_a, h_b, h_1, 0, 0, 0, 0], dtype=float))


class Polynomial434(MotionLaw):
    """4-3-4 piecewise polynomial (sec. 3.6), shares of time t_l, t_s and of displacement
    h_l, h_s for the lift-off and set-down phases."""

    law_id = "polynomial_4_3_4"
    title = "4-3-4 piecewise polynomial"
    parameters = (
        _share("t_l", 0.25, "lift-off time over duration, T_l/T"),
        _share("t_s", 0.25, "set-down time over duration, T_s/T"),
        Parameter("h_l", 0.1, 0.0, 0.5, description="lift-off displacement over h, "
                  "(q_a - q_0)/h", no_auto=NO_AUTO),
        Parameter("h_s", 0.1, 0.0, 0.5, description="set-down displacement over h, "
                  "(q_1 - q_b)/h", no_auto=NO_AUTO),
    )

    @property
    def polynomials(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Coefficients (ascending) of the three pieces in tau - their start."""
        t_l, t_s = self.params["t_l"], self.params["t_s"]
        t_t = 1.0 - t_l - t_s
        h_a, h_1 = self.params["h_l"], self.params["h_s"]
        a4l, a3l, a3t, a2t, a1t, a4s, a3s = solve_434(t_l, t_t, t_s, h_a, 1.0 - h_a - h_1, h_1)
        lift = np.array([0.0, 0.0, 0.0, a3l / t_l**3, a4l / t_l**4])
        travel = np.array([h_a, a1t / t_t, a2t / t_t**2, a3t / t_t**3])
        # q_s = a4s (tau_s - 1)^4 + a3s (tau_s - 1)^3 + 1 in its own tau_s = x/t_s, x the
        # time since the set-down's start: re-expanded in x
        set_down = _reexpand(np.array([1.0, 0.0, 0.0, a3s, a4s]), -1.0, t_s)
        return lift, travel, set_down

    def _build(self):
        t_l, t_s = self.params["t_l"], self.params["t_s"]
        lift, travel, set_down = self.polynomials
        b = 1.0 - t_s
        pieces = [trig_poly_piece(0.0, t_l, lift),
                  trig_poly_piece(t_l, b, travel, origin=t_l),
                  trig_poly_piece(b, 1.0, set_down, origin=b)]
        return pieces, 2

    def closed_form_coefficients(self) -> dict[str, float]:
        """C_v, C_a, C_j at the piece ends and the real roots of the next derivative of
        each polynomial (degree <= 3: the quadratic and cubic formulas, numpy's roots);
        the RMS values from the exact integrals of the squared polynomials."""
        starts = (0.0, self.params["t_l"], 1.0 - self.params["t_s"])
        ends = (*starts[1:], 1.0)
        peaks = {1: 0.0, 2: 0.0, 3: 0.0}
        squares = {1: 0.0, 2: 0.0}
        for poly, start, end in zip(self.polynomials, starts, ends, strict=True):
            width = end - start
            for order in (1, 2, 3):
                f = P.polyder(poly, order)
                g = P.polyder(f)
                points = [0.0, width]
                if len(g) > 1 or g[0] != 0.0:
                    roots = P.polyroots(g) if len(g) > 1 else np.array([])
                    points += [r.real for r in np.atleast_1d(roots)
                               if abs(r.imag) < 1e-12 and 0.0 < r.real < width]
                peaks[order] = max(peaks[order], float(np.max(np.abs(P.polyval(points, f)))))
            for order in (1, 2):
                square = P.polyint(P.polymul(P.polyder(poly, order), P.polyder(poly, order)))
                squares[order] += float(P.polyval(width, square))
        return {"C_v": peaks[1], "C_a": peaks[2], "C_j": peaks[3],
                "C_v_rms": float(np.sqrt(squares[1])), "C_a_rms": float(np.sqrt(squares[2]))}


def _reexpand(coefficients: np.ndarray, shift: float, width: float) -> np.ndarray:
    """The polynomial p(u + shift), u = x/width, as ascending coefficients in x."""
    out = np.zeros(len(coefficients))
    # p(y) with y = x/width + shift: expand each power by the binomial theorem
    for k, c in enumerate(coefficients):
        term = P.polypow([shift, 1.0 / width], k)
        out[: len(term)] += c * term
    return out
