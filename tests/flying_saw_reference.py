"""The flying saw's cycle (examples/flying-saw.yaml) built independently of sizer, as
piecewise polynomials in time (issue 37, a cycle with boundary speeds in
tests/test_cam_matrix.py).

The approach of tests/test_cam_export_cycle.py, written out here (no sizer import) and
extended to the double S: the segment durations from the cycle time the export reports
(the run 0.4 s and the wait 0.1 s fixed, the three moves sharing the rest in proportion to
their lengths 150 : 100 : 450 mm); each move between its boundary speeds

- trapezoid (Biagiotti & Melchiorri, sec. 3.2.7, eqs. 3.13a-c): T_a = T_d = alpha T, the
  cruise speed v_v = (h - (v0 T_a + v1 T_d)/2) / (T - T_a/2 - T_d/2), constant
  accelerations (v_v - v0)/T_a, 0, (v1 - v_v)/T_d;
- double S (sec. 3.4, eqs. 3.30a-g, phase durations assigned as in sec. 3.4.6): T_a = T_d
  = alpha T, T_j1 = T_j2 = beta T_a, the trapezoid's cruise speed (each phase covers
  (v_v + v_k) T_phase / 2 with symmetric jerk phases), peak accelerations
  (v_v - v0)/(T_a - T_j1) and (v1 - v_v)/(T_d - T_j2), the jerk that reaches them in T_j;
- a polynomial of degree 2m + 1 (sec. 2.1.4-2.1.6): the one with q(0) = 0, q(T) = h,
  q'(0) = v0, q'(T) = v1 and null derivatives of orders 2..m at both ends, its 2m + 2
  conditions solved by numpy.linalg.solve;

the trapezoid and the double S integrated exactly from (0, v0, 0) phase by phase (constant
jerk), their end conditions (h, v1, a = 0 for the double S) asserted. The cut runs at the
line's 0.5 m/s, the return is the law rest to rest, the wait holds 0.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

LINE = 500.0
"""The line's 0.5 m/s in mm/s."""
RUN, WAIT = 0.4, 0.1
"""The cut and the wait, s (process times, fixed)."""
MOVES = (150.0, 100.0, -450.0)
"""accelerate, stop, return, mm."""
TRAPEZOID = "trapezoidal(alpha=1/3)"
DOUBLE_S = "double_s(alpha=1/3, beta=1/4)"
NAMES = ("accelerate", "cut", "stop", "return", "wait")


@dataclass(frozen=True)
class Piece:
    """y(t) = sum c[k] (t - t0)^k on [t0, t1] (s, mm)."""

    t0: float
    t1: float
    c: tuple[float, ...]

    def at(self, t: np.ndarray, order: int) -> np.ndarray:
        s = t - self.t0
        out = np.zeros_like(t)
        for k, ck in enumerate(self.c):
            if k >= order:
                out = out + ck * math.perm(k, order) * s ** (k - order)
        return out


def durations(cycle_time: float) -> list[float]:
    """accelerate, cut, stop, return, wait (s)."""
    free = cycle_time - RUN - WAIT
    total = sum(abs(h) for h in MOVES)
    return [free * 150.0 / total, RUN, free * 100.0 / total, free * 450.0 / total, WAIT]


def constant_jerk(phases: list[tuple[float, float, float | None]], v0: float
                  ) -> tuple[list[Piece], tuple[float, float, float]]:
    """Phases (duration, jerk, acceleration at its start or None to continue), integrated
    exactly from (0, v0, 0): the pieces (local time from 0) and the end (q, v, a)."""
    pieces, t, q, v, a = [], 0.0, 0.0, v0, 0.0
    for d, j, start_a in phases:
        a = a if start_a is None else start_a
        if d > 0.0:
            pieces.append(Piece(t, t + d, (q, v, a / 2, j / 6)))
        q, v, a = q + v * d + a * d * d / 2 + j * d ** 3 / 6, v + a * d + j * d * d / 2, \
            a + j * d
        t += d
    return pieces, (q, v, a)


def cruise(h: float, T: float, v0: float, v1: float, alpha: float) -> float:
    """Eq. 3.13: the cruise speed of the trapezoid with T_a = T_d = alpha T."""
    ta = td = alpha * T
    return (h - (v0 * ta + v1 * td) / 2) / (T - ta / 2 - td / 2)


def trapezoid(h: float, T: float, v0: float, v1: float, alpha: float = 1 / 3
              ) -> list[Piece]:
    ta = td = alpha * T
    vv = cruise(h, T, v0, v1, alpha)
    pieces, (q, v, _) = constant_jerk([(ta, 0.0, (vv - v0) / ta), (T - ta - td, 0.0, 0.0),
                                       (td, 0.0, (v1 - vv) / td)], v0)
    assert abs(q - h) <= 1e-12 * abs(h) and abs(v - v1) <= 1e-9 * max(abs(vv), 1.0)
    return pieces


def double_s(h: float, T: float, v0: float, v1: float, alpha: float = 1 / 3,
             beta: float = 1 / 4) -> list[Piece]:
    ta = td = alpha * T
    tj = beta * ta
    vv = cruise(h, T, v0, v1, alpha)
    ja = (vv - v0) / ((ta - tj) * tj)
    jd = (v1 - vv) / ((td - tj) * tj)
    pieces, (q, v, a) = constant_jerk(
        [(tj, ja, 0.0), (ta - 2 * tj, 0.0, None), (tj, -ja, None), (T - ta - td, 0.0, 0.0),
         (tj, jd, 0.0), (td - 2 * tj, 0.0, None), (tj, -jd, None)], v0)
    assert abs(q - h) <= 1e-12 * abs(h) and abs(v - v1) <= 1e-9 * max(abs(vv), 1.0)
    assert abs(a) <= 1e-9 * abs(ja) * tj
    return pieces


def polynomial(h: float, T: float, v0: float, v1: float, degree: int = 5) -> list[Piece]:
    m = (degree - 1) // 2
    rows = [[math.perm(j, k) * t ** (j - k) if j >= k else 0.0 for j in range(degree + 1)]
            for t in (0.0, T) for k in range(m + 1)]
    rhs = [0.0, v0] + [0.0] * (m - 1) + [h, v1] + [0.0] * (m - 1)
    c = np.linalg.solve(np.array(rows), np.array(rhs))
    return [Piece(0.0, T, tuple(float(v) for v in c))]


def move(law: str, h: float, T: float, v0: float, v1: float) -> list[Piece]:
    if law == TRAPEZOID:
        return trapezoid(h, T, v0, v1)
    if law == DOUBLE_S:
        return double_s(h, T, v0, v1)
    degree = {"poly3": 3, "poly5": 5, "poly7": 7}[law]
    return polynomial(h, T, v0, v1, degree)


def cycle(law: str, cycle_time: float) -> tuple[list[float], list[Piece]]:
    """The segments' starts (and the cycle's end) and the pieces of the whole cycle by
    ``law`` (TRAPEZOID, DOUBLE_S, poly3/5/7), in absolute time."""
    T = durations(cycle_time)
    starts = [0.0, *np.cumsum(T).tolist()]
    local = [(move(law, 150.0, T[0], 0.0, LINE), 0.0),
             ([Piece(0.0, T[1], (0.0, LINE))], 150.0),
             (move(law, 100.0, T[2], LINE, 0.0), 350.0),
             (move(law, -450.0, T[3], 0.0, 0.0), 450.0),
             ([Piece(0.0, T[4], (0.0,))], 0.0)]
    pieces = []
    for start, (parts, origin) in zip(starts, local, strict=False):
        for p in parts:
            # shift to absolute time: the same polynomial about t0 + start
            c = list(p.c)
            c[0] += origin
            pieces.append(Piece(start + p.t0, start + p.t1, tuple(c)))
    return starts, pieces
