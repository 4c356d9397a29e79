"""Linear trajectories with blends: polynomial blends (book sec. 3.3), circular blends
(sec. 3.1).

Polynomial blends. Sec. 3.3 joins the line through (t0 + T_s, q0) and (t1 - T_s, q1)
(T_a = 2 T_s the blend time) to rest with a polynomial of degree n on [t0, t0 + T_a],
which meets the line at t0 + T_a in position, velocity and, for n = 5, acceleration (the
book's conditions 1-4; its item 3 prints the velocity where the acceleration is meant, see
docs/errata.md). Normalized (h = T = 1, alpha = T_a/T): the cruise speed is
v_c = 1/(1 - alpha), and with n = 2m + 1 the blend has the 2m + 2 conditions q, and its
derivatives up to order m, at both ends. Their unique solution has degree 2m, not n:
its velocity is v_c times the rest-to-rest polynomial law of degree 2m - 1 in
u = tau/alpha (I_u(m, m), sec. 2.1.7), whose integral 1/2 is the blend's displacement
v_c alpha/2. So n = 3 gives the trapezoid (sec. 3.2) and n = 5 the blend
q = v_c alpha (u^3 - u^4/2), continuous up to the acceleration (C^2). The blend is
evaluated in Bernstein form (stable for every degree, as sizer.laws.polynomial).

Circular blends: see :class:`CircularBlends`.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from fractions import Fraction

import numpy as np

from sizer.laws.base import MotionLaw, Parameter
from sizer.laws.pieces import Piece, mirrored, trig_poly_piece
from sizer.laws.piecewise_polynomial import MIN_FRACTION
from sizer.laws.polynomial import Polynomial


def bernstein_piece(start: float, end: float, coefficients: Sequence[Fraction], scale: float,
                    max_order: int) -> Piece:
    """q(tau) = scale * sum_k c_k B_{k,N}(u), u = (tau - start)/(end - start), on [start, end].

    The r-th derivative is scale/width^r * N!/(N - r)! * sum (Delta^r c)_k B_{k,N-r}(u)
    (forward differences of the coefficients, taken exactly: a derivative that vanishes
    at a piece end is exactly 0 there), as in sizer.laws.polynomial.
    """
    width = end - start
    degree = len(coefficients) - 1
    scaled = []
    diff = list(coefficients)
    for r in range(max_order + 1):
        if r > degree:
            scaled.append(np.zeros(1))
            continue
        if r:
            diff = [b - a for a, b in itertools.pairwise(diff)]
        factor = math.factorial(degree) // math.factorial(degree - r)
        exact = [d * factor * math.comb(degree - r, k) for k, d in enumerate(diff)]
        scaled.append(np.array([float(e) for e in exact]) * (scale / width**r))

    def evaluate(tau: np.ndarray, order: int) -> np.ndarray:
        u = (np.asarray(tau, dtype=float) - start) / width
        c = scaled[order]
        n = len(c) - 1
        t = 1.0 - u
        out = np.zeros(u.shape)
        for k in np.nonzero(c)[0]:
            out += c[k] * u**k * t ** (n - k)
        return out

    return Piece(start, end, evaluate, degree=degree)


def smoothstep_square_integral(m: int) -> Fraction:
    """int_0^1 I_u(m, m)^2 du, exactly: I_u(m, m) = sum_{k>=m} B_{k,2m-1}(u) and
    int B_{j,n} B_{k,n} = C(n,j) C(n,k) / ((2n + 1) C(2n, j + k))."""
    n = 2 * m - 1
    return sum((Fraction(math.comb(n, j) * math.comb(n, k), (2 * n + 1) * math.comb(2 * n, j + k))
                for j in range(m, n + 1) for k in range(m, n + 1)), Fraction(0))


class PolynomialBlends(MotionLaw):
    """Constant speed with polynomial blends of odd degree n over T_a = alpha*T at both
    ends (sec. 3.3); n = 3 is the trapezoid, n = 5 (the book's Fig. 3.11) is C^2."""

    law_id = "polynomial_blends"
    title = "Linear with polynomial blends"
    parameters = (
        Parameter("alpha", 1 / 3, MIN_FRACTION, 0.5,
                  description="blend time over duration, T_a/T; at least 1e-6"),
        Parameter("degree", 5, 3, 21, integer=True, odd=True,
                  description="odd blend degree n; continuity C^((n-1)/2)",
                  no_auto="the degree is a discrete choice; list the degrees to compare "
                          "instead, e.g. polynomial_blends(degree=5), "
                          "polynomial_blends(degree=7)"),
    )
    max_order = 22

    @property
    def m(self) -> int:
        return (int(self.params["degree"]) - 1) // 2

    def _build(self):
        alpha, m = self.params["alpha"], self.m
        v_c = 1.0 / (1.0 - alpha)
        # Bernstein coefficients of the blend in u: max(0, k - m)/(2m), k = 0..2m (the
        # integral of I_u(m, m) = sum_{k>=m} B_{k,2m-1}); times v_c*alpha in tau
        coefficients = [Fraction(max(0, k - m), 2 * m) for k in range(2 * m + 1)]
        blend = bernstein_piece(0.0, alpha, coefficients, v_c * alpha, self.max_order)
        cruise = trig_poly_piece(alpha, 0.5, (v_c * alpha / 2.0, v_c), origin=alpha)
        return mirrored([blend, cruise]), m

    def closed_form_coefficients(self) -> dict[str, float]:
        """With g = I_u(m, m): C_v = v_c; C_a = v_c/alpha max g' and C_j = v_c/alpha^2
        max |g''| (g' is the velocity of the polynomial law of degree 2m - 1, so these are
        its C_v and C_a); C_v_rms^2 = v_c^2 (1 - 2 alpha + 2 alpha int g^2) and
        C_a_rms^2 = 2 v_c^2/alpha int g'^2 (its C_v_rms^2)."""
        alpha, m = self.params["alpha"], self.m
        v_c = 1.0 / (1.0 - alpha)
        if m == 1:  # g = u: the trapezoid
            peak_v, peak_a, rms_v = 1.0, 0.0, 1.0
        else:
            inner = Polynomial(degree=2 * m - 1).closed_form_coefficients()
            peak_v, peak_a, rms_v = inner["C_v"], inner["C_a"], inner["C_v_rms"]
        g2 = float(smoothstep_square_integral(m))
        out = {
            "C_v": v_c,
            "C_a": v_c / alpha * peak_v,
            "C_v_rms": v_c * math.sqrt(1.0 - 2.0 * alpha + 2.0 * alpha * g2),
            "C_a_rms": v_c * rms_v * math.sqrt(2.0 / alpha),
        }
        if peak_a:
            out["C_j"] = v_c / alpha**2 * peak_a
        return out


class CircularBlends(MotionLaw):
    """Constant speed with circular blends in the (t, q) plane (sec. 3.1, Fig. 3.1).

    The book's arcs have radius h, centers (t0, q0 + h) and (t1, q0), and need T >= sqrt(3) h:
    the construction is not invariant to the time and position units, so the normalized
    law has one parameter, ``ratio`` = T/h in the units the arcs are drawn in (the book's
    Example 3.1: T = 6, h = 3, ratio 2). With rho = ratio and h = T = 1 normalized:
    cos(alpha) = (2 + rho sqrt(rho^2 - 3))/(1 + rho^2), blend time tau_a = sin(alpha)/rho,
    q_N = 1 - sqrt(1 - (rho tau)^2) on the first blend, slope rho tan(alpha) in between.
    The velocity is continuous, the acceleration bounded but not continuous: it steps to
    rho^2 from rest at tau = 0 (the arc's curvature) and from rho^2/cos^3(alpha) to 0 at the blend
    end (C^1; jerk impulses at 0, tau_a, 1 - tau_a and 1).
    """

    law_id = "circular_blends"
    title = "Linear with circular blends"
    MAX_RATIO = 1000.0
    parameters = (
        Parameter("ratio", 2, math.sqrt(3.0), MAX_RATIO,
                  description="T/h in the units the arcs of radius h are drawn in; at least "
                              "sqrt(3) (the book's bound), up to 1000 (blends of 1/1000 of T, "
                              "C_a ~ ratio^2)"),
    )

    @property
    def angle(self) -> float:
        """alpha of sec. 3.1: the slope angle of the line, cos(alpha) as the book gives."""
        rho = self.params["ratio"]
        return math.acos((2.0 + rho * math.sqrt(max(0.0, rho * rho - 3.0))) / (1.0 + rho * rho))

    def _build(self):
        rho = self.params["ratio"]
        alpha = self.angle
        tau_a = min(0.5, math.sin(alpha) / rho)
        slope = rho * math.tan(alpha)
        q_a = 1.0 - math.cos(alpha)

        def arc(tau: np.ndarray, order: int) -> np.ndarray:
            s = rho * np.asarray(tau, dtype=float)
            w = 1.0 - s * s
            if order == 0:
                return s * s / (1.0 + np.sqrt(w))  # 1 - sqrt(w), no cancellation
            if order == 1:
                return rho * s / np.sqrt(w)
            if order == 2:
                return rho**2 * w**-1.5
            if order == 3:
                return 3.0 * rho**3 * s * w**-2.5
            return 3.0 * rho**4 * (1.0 + 4.0 * s * s) * w**-3.5

        half = [Piece(0.0, tau_a, arc),
                trig_poly_piece(tau_a, 0.5, (q_a, slope), origin=tau_a)]
        return mirrored(half), 1

    def closed_form_coefficients(self) -> dict[str, float]:
        """With s = sin(alpha), c = cos(alpha): C_v = rho tan(alpha), C_a = rho^2/c^3 and
        C_j = 3 rho^3 s/c^5 at the blend end; int v^2 = 2 rho (artanh s - s) +
        (1 - 2 s/rho) rho^2 tan^2(alpha) and int a^2 = 2 rho^3 F(s), F(s) = int_0^s
        (1 - x^2)^-3 dx = s/(4 c^4) + 3 s/(8 c^2) + 3/8 artanh s."""
        rho = self.params["ratio"]
        alpha = self.angle
        s, c = math.sin(alpha), math.cos(alpha)
        tan = s / c
        v2 = 2.0 * rho * (math.atanh(s) - s) + (1.0 - 2.0 * s / rho) * (rho * tan) ** 2
        f = s / (4.0 * c**4) + 3.0 * s / (8.0 * c * c) + 3.0 / 8.0 * math.atanh(s)
        return {
            "C_v": rho * tan,
            "C_a": rho * rho / c**3,
            "C_j": 3.0 * rho**3 * s / c**5,
            "C_v_rms": math.sqrt(v2),
            "C_a_rms": math.sqrt(2.0 * rho**3 * f),
        }
