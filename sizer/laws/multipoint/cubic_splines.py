"""Interpolating cubic splines through via-points and their knot times (book sec. 4.4).

The spline s(t) = {q_k(t), t in [t_k, t_{k+1}]}, q_k(t) = a_k0 + a_k1 (t - t_k) +
a_k2 (t - t_k)^2 + a_k3 (t - t_k)^3, is C2 and passes through every (t_k, q_k). Its two
free parameters are fixed by one of:

- assigned end velocities v_0, v_n (sec. 4.4.1, 4.4.3; "clamped"; default 0 and 0);
- zero end accelerations ("natural", sec. 4.4 property 5);
- periodic ends, q_0 = q_n with equal end velocities and accelerations (sec. 4.4.2);
- assigned end velocities and accelerations through two free extra points (sec. 4.4.4).

The first three are exactly scipy's ``CubicSpline`` with ``bc_type`` ``((1, v0), (1, vn))``,
``"natural"`` and ``"periodic"``; the book's own systems (4.10), (4.13) and (4.22) are
here too (``clamped_system``, ``periodic_system``, ``acceleration_system``) so that the
tests can check the book's matrices and both constructions against each other. The
extra-point spline of sec. 4.4.4 has no scipy equivalent (scipy's cubic splines take one
end condition per side) and is built by hand from the book's system (4.28).

The time instants t_k of a spline through positions q_k (sec. 4.4.6):

- ``equal``, ``chord``, ``centripetal``: the book's distributions (4.37), t_k = t_{k-1} +
  d_{k-1}/d over the total time, with d_k constant, |q_{k+1} - q_k| ("cord length") or
  |q_{k+1} - q_k|^(1/2) ("centripetal", the book's exponent mu = 1/2).
- ``auto`` (not in the book): the interior times that minimize the peak or the RMS
  acceleration of the spline for a fixed total time; scipy.optimize SLSQP from the equal
  times, the intervals as a softmax of free variables (always positive, summing to the
  duration), so the times stay strictly increasing; exact derivatives of the knot
  accelerations by implicit differentiation of the spline's system.
- ``minimize: duration`` under velocity/acceleration/jerk limits: the book's iteration
  (4.39), each interval scaled by lambda_k = max{lambda_v,k, lambda_a,k, lambda_j,k} and
  the spline recomputed, until the intervals settle (Example 4.15).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from sizer.errors import UserError
from sizer.input_limits import MAX_AUTO_TIMES_POINTS
from sizer.laws.multipoint import fields as F

KIND = "cubic_spline"
FIELDS = ("points", "times", "positions", "start", "end", "periodic", "natural",
          "extra_times", "duration", "minimize", "limits")
"""The fields of ``kind: cubic_spline`` (see :func:`build_cubic_spline`)."""

_CONDITION_LIMIT = 1e12
"""Largest condition number of a spline system accepted before refusing it as singular."""


# ---------------------------------------------------------------- the book's systems

def intervals(t: np.ndarray) -> np.ndarray:
    """T_k = t_{k+1} - t_k, k = 0 .. n-1."""
    return np.diff(np.asarray(t, dtype=float))


def clamped_system(t: np.ndarray, q: np.ndarray, v0: float, vn: float
                   ) -> tuple[np.ndarray, np.ndarray]:
    """The book's (4.10): A(T) v = c for the interior velocities v_1 .. v_{n-1} (n >= 2)."""
    T = intervals(t)
    dq = np.diff(np.asarray(q, dtype=float))
    n = len(T)  # row k is eq. (4.9) for v_k, v_{k+1}, v_{k+2}
    A = np.diag(2.0 * (T[:-1] + T[1:])) + np.diag(T[2:], -1) + np.diag(T[:-2], 1)
    c = 3.0 / (T[:-1] * T[1:]) * (T[:-1] ** 2 * dq[1:] + T[1:] ** 2 * dq[:-1])
    c[0] -= T[1] * v0
    c[-1] -= T[n - 2] * vn
    return A, c


def clamped_velocities(t: np.ndarray, q: np.ndarray, v0: float = 0.0, vn: float = 0.0
                       ) -> np.ndarray:
    """All velocities v_0 .. v_n of the clamped spline from the book's (4.10)."""
    n = len(t) - 1
    if n == 1:
        return np.array([v0, vn], dtype=float)
    A, c = clamped_system(t, q, v0, vn)
    return np.concatenate([[v0], _solve(A, c, "the end velocities"), [vn]])


def periodic_system(t: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The book's cyclic system of sec. 4.4.2 for v_0 .. v_{n-1} (v_n = v_0; n >= 2)."""
    T = intervals(t)
    dq = np.diff(np.asarray(q, dtype=float))
    n = len(T)
    # row k + 1 is eq. (4.9) for v_k, v_{k+1}, v_{k+2}, indices mod n (v_n = v_0); row 0
    # (k = -1) is eq. (4.13), the acceleration at t_0 equal to the one at t_n
    k = np.arange(-1, n - 1)
    A = np.zeros((n, n))
    for col, value in ((k % n, T[k + 1]), (k + 1, 2.0 * (T[k] + T[k + 1])), ((k + 2) % n, T[k])):
        np.add.at(A, (k + 1, col), value)
    return A, 3.0 / (T[k] * T[k + 1]) * (T[k] ** 2 * dq[k + 1] + T[k + 1] ** 2 * dq[k])


def periodic_velocities(t: np.ndarray, q: np.ndarray) -> np.ndarray:
    """All velocities v_0 .. v_n (v_n = v_0) of the periodic spline (sec. 4.4.2)."""
    if len(t) == 2:
        return np.zeros(2)
    A, c = periodic_system(t, q)
    v = _solve(A, c, "the periodic conditions")
    return np.append(v, v[0])


def coefficients_from_velocities(t: np.ndarray, q: np.ndarray, v: np.ndarray
                                 ) -> np.ndarray:
    """The book's (4.8): rows [a_k0, a_k1, a_k2, a_k3] from the positions and velocities."""
    T = intervals(t)
    q = np.asarray(q, dtype=float)
    v = np.asarray(v, dtype=float)
    dq = np.diff(q)
    return np.column_stack([q[:-1], v[:-1],
                            (3.0 * dq / T - 2.0 * v[:-1] - v[1:]) / T,
                            (-2.0 * dq / T + v[:-1] + v[1:]) / T ** 2])


def acceleration_system(t: np.ndarray, q: np.ndarray, v0: float, vn: float
                        ) -> tuple[np.ndarray, np.ndarray]:
    """The book's (4.22)-(4.24): A omega = c for the accelerations omega_0 .. omega_n."""
    T = intervals(t)
    q = np.asarray(q, dtype=float)
    n = len(T)
    A = np.zeros((n + 1, n + 1))
    A[np.arange(n), np.arange(1, n + 1)] = T
    A[np.arange(1, n + 1), np.arange(n)] = T
    A[np.arange(n + 1), np.arange(n + 1)] = 2.0 * (np.append(T, 0.0) + np.append(0.0, T))
    slopes = np.diff(q) / T
    c = 6.0 * np.concatenate([[slopes[0] - v0], np.diff(slopes), [vn - slopes[-1]]])
    return A, c


def coefficients_from_accelerations(t: np.ndarray, q: np.ndarray, omega: np.ndarray
                                    ) -> np.ndarray:
    """The book's (4.25): rows [a_k0, a_k1, a_k2, a_k3] from positions and accelerations."""
    T = intervals(t)
    q = np.asarray(q, dtype=float)
    w = np.asarray(omega, dtype=float)
    return np.column_stack([q[:-1], np.diff(q) / T - T / 6.0 * (w[1:] + 2.0 * w[:-1]),
                            w[:-1] / 2.0, np.diff(w) / (6.0 * T)])


def spline_from_coefficients(t: np.ndarray, coefficients: ArrayLike):
    """The PPoly of the rows [a_k0, a_k1, a_k2, a_k3] (powers of t - t_k)."""
    from scipy.interpolate import PPoly

    return PPoly(np.asarray(coefficients, dtype=float)[:, ::-1].T.copy(),
                 np.asarray(t, dtype=float))


# ---------------------------------------------------------------- the splines

def _scipy_spline(t: np.ndarray, q: np.ndarray, bc_type: Any):
    from scipy.interpolate import CubicSpline, PPoly

    spline = CubicSpline(np.asarray(t, dtype=float), np.asarray(q, dtype=float),
                         bc_type=bc_type)
    return PPoly(spline.c.copy(), spline.x.copy())


def clamped_spline(t: np.ndarray, q: np.ndarray, v0: float = 0.0, vn: float = 0.0):
    """The spline with end velocities v_0, v_n (sec. 4.4.1): CubicSpline, bc ((1,v0),(1,vn))."""
    return _scipy_spline(t, q, ((1, float(v0)), (1, float(vn))))


def natural_spline(t: np.ndarray, q: np.ndarray):
    """The natural spline, zero end accelerations (sec. 4.4): CubicSpline, bc "natural"."""
    return _scipy_spline(t, q, "natural")


def periodic_spline(t: np.ndarray, q: np.ndarray):
    """The periodic spline (sec. 4.4.2), q_0 = q_n: CubicSpline, bc "periodic"."""
    check_periodic(q)
    q = np.array(q, dtype=float)
    q[-1] = q[0]
    if len(t) == 2:
        return spline_from_coefficients(t, [[q[0], 0.0, 0.0, 0.0]])
    return _scipy_spline(t, q, "periodic")


def check_periodic(q: np.ndarray) -> None:
    """UserError unless q_n = q_0 (to 1e-12 of the positions' range)."""
    if not np.isclose(q[0], q[-1], rtol=0.0, atol=1e-12 * max(1.0, float(np.ptp(q)))):
        raise UserError(f"a periodic spline needs the last position equal to the first, "
                        f"got q_0 = {q[0]:g} and q_n = {q[-1]:g}", field="periodic")


def extra_point_times(t: np.ndarray) -> tuple[float, float]:
    """The book's choice of the two free points' times (sec. 4.4.4): the midpoints of
    (t_0, t_2) and (t_{n-2}, t_n) of the extended sequence, that is of the first and last
    given intervals; with only two given points, the thirds of the interval."""
    t = np.asarray(t, dtype=float)
    if len(t) == 2:
        return float(t[0] + (t[1] - t[0]) / 3.0), float(t[0] + 2.0 * (t[1] - t[0]) / 3.0)
    return float((t[0] + t[1]) / 2.0), float((t[-2] + t[-1]) / 2.0)


def velocity_acceleration_system(t_bar: np.ndarray, q: np.ndarray, v0: float, vn: float,
                                 a0: float, an: float) -> tuple[np.ndarray, np.ndarray]:
    """The book's (4.28): A omega = c for omega_1 .. omega_{n-1} on the extended times
    t_bar = [t_0, t1_bar, t_2, ..., t_{n-2}, t_{n-1}_bar, t_n]; q are the given positions
    [q_0, q_2, ..., q_{n-2}, q_n] (n - 1 of them).

    Assembled from (4.19) for k = 1 .. n-1 with q_1, q_{n-1} replaced by (4.26), (4.27)
    and omega_0 = a_0, omega_n = a_n; for n >= 5 the rows are those printed in sec. 4.4.4,
    and the assembly also covers two or three given points, where the two substitutions
    meet in the same rows.
    """
    T = intervals(t_bar)
    n = len(T)
    qg = np.asarray(q, dtype=float)
    # q_bar = base + slope * omega: only q_1 and q_{n-1} depend on omega (on omega_1, omega_{n-1})
    base = np.concatenate([[qg[0], np.nan], qg[1:-1], [np.nan, qg[-1]]])
    slope = np.zeros((n + 1, n + 1))
    base[1] = qg[0] + T[0] * v0 + T[0] ** 2 / 3.0 * a0                       # (4.26)
    slope[1, 1] = T[0] ** 2 / 6.0
    base[n - 1] = qg[-1] - T[n - 1] * vn + T[n - 1] ** 2 / 3.0 * an          # (4.27)
    slope[n - 1, n - 1] = T[n - 1] ** 2 / 6.0
    # (4.19) times T_k: T_{k-1} w_{k-1} + 2 (T_{k-1} + T_k) w_k + T_k w_{k+1} = D q_bar
    M = np.zeros((n - 1, n + 1))
    D = np.zeros((n - 1, n + 1))
    for row, k in enumerate(range(1, n)):
        M[row, k - 1:k + 2] = [T[k - 1], 2.0 * (T[k - 1] + T[k]), T[k]]
        D[row, k - 1:k + 2] = [6.0 / T[k - 1], -6.0 / T[k - 1] - 6.0 / T[k], 6.0 / T[k]]
    full = M - D @ slope
    rhs = D @ base
    rhs -= full[:, 0] * a0 + full[:, n] * an
    return full[:, 1:n], rhs


def velocity_acceleration_spline(t: np.ndarray, q: np.ndarray, v0: float, vn: float,
                                 a0: float, an: float,
                                 extra_times: tuple[float, float] | None = None):
    """The spline with end velocities and accelerations (sec. 4.4.4): two free points at
    ``extra_times`` (default :func:`extra_point_times`), omega from (4.28), the free
    points from (4.26), (4.27), the pieces from (4.14) (as (4.25))."""
    t = np.asarray(t, dtype=float)
    t1, tn1 = extra_point_times(t) if extra_times is None else extra_times
    if not (t[0] < t1 < tn1 < t[-1] and t1 < t[1] and (len(t) == 2 or tn1 > t[-2])):
        raise UserError(f"the extra points' times must lie inside the first and the last "
                        f"intervals, in order, got {t1:g} and {tn1:g}", field="extra_times")
    t_bar = np.concatenate([[t[0], t1], t[1:-1], [tn1, t[-1]]])
    A, c = velocity_acceleration_system(t_bar, q, v0, vn, a0, an)
    omega = np.concatenate([[a0], _solve(A, c, "the end velocities and accelerations"),
                            [an]])
    return spline_from_coefficients(t_bar, coefficients_from_accelerations(
        t_bar, extra_positions(t_bar, q, omega, v0, vn, a0, an), omega))


def extra_positions(t_bar: np.ndarray, q: np.ndarray, omega: np.ndarray, v0: float,
                    vn: float, a0: float, an: float) -> np.ndarray:
    """q_bar = [q_0, q1_bar, q_2, ..., q_{n-2}, q_{n-1}_bar, q_n]: the given positions with
    the two free points of (4.26), (4.27)."""
    T = intervals(t_bar)
    q = np.asarray(q, dtype=float)
    q1 = q[0] + T[0] * v0 + T[0] ** 2 / 3.0 * a0 + T[0] ** 2 / 6.0 * omega[1]
    qn1 = q[-1] - T[-1] * vn + T[-1] ** 2 / 3.0 * an + T[-1] ** 2 / 6.0 * omega[-2]
    return np.concatenate([[q[0], q1], q[1:-1], [qn1, q[-1]]])


def cubic_spline(t: np.ndarray, q: np.ndarray, *, v0: float = 0.0, vn: float = 0.0,
                 a0: float | None = None, an: float | None = None, periodic: bool = False,
                 natural: bool = False, extra_times: tuple[float, float] | None = None):
    """The cubic spline through (t, q) with the given end conditions (see the module)."""
    if periodic:
        return periodic_spline(t, q)
    if natural:
        return natural_spline(t, q)
    if a0 is not None or an is not None:
        return velocity_acceleration_spline(t, q, v0, vn, a0 or 0.0, an or 0.0, extra_times)
    return clamped_spline(t, q, v0, vn)


def _solve(A: np.ndarray, c: np.ndarray, what: str) -> np.ndarray:
    """np.linalg.solve, refusing a singular or ill-conditioned system as a UserError."""
    condition = np.linalg.cond(A)
    if not np.isfinite(condition) or condition > _CONDITION_LIMIT:
        raise UserError(f"the conditions make the spline's system singular "
                        f"(condition number {condition:.3g}): {what}", field="points")
    return np.linalg.solve(A, c)


# ---------------------------------------------------------------- the YAML builder

def end_conditions(fields: Mapping[str, Any]) -> dict[str, Any]:
    """The keyword end conditions of :func:`cubic_spline` read from ``start``, ``end``,
    ``periodic``, ``natural`` and ``extra_times``."""
    periodic = _flag(fields, "periodic")
    natural = _flag(fields, "natural")
    start = F.conditions(fields, "start", highest=2)
    end = F.conditions(fields, "end", highest=2)
    for key, given in (("start", start), ("end", end)):
        if 0 in given:
            raise UserError("the position comes from the via-points; give velocity and, "
                            "optionally, acceleration", field=f"{key}.position")
    if periodic or natural:
        word = "periodic" if periodic else "natural"
        for key in ("start", "end", "extra_times"):
            if key in fields:
                raise UserError(f"a {word} spline fixes both ends itself: remove {key}",
                                field=key)
        if periodic and natural:
            raise UserError("give periodic or natural, not both", field="natural")
        return {"periodic": periodic, "natural": natural}
    if (2 in start) != (2 in end):
        missing = "end" if 2 in start else "start"
        raise UserError("an acceleration at one end needs one at the other end too "
                        "(sec. 4.4.4); a cubic spline has two free parameters",
                        field=f"{missing}.acceleration")
    out: dict[str, Any] = {"v0": start.get(1, 0.0), "vn": end.get(1, 0.0)}
    if 2 in start:
        out.update(a0=start[2], an=end[2])
        if "extra_times" in fields:
            extra = F.numbers(fields, "extra_times", length=2)
            out["extra_times"] = (float(extra[0]), float(extra[1]))
    elif "extra_times" in fields:
        raise UserError("extra points are only used with end accelerations (sec. 4.4.4)",
                        field="extra_times")
    return out


def _flag(fields: Mapping[str, Any], key: str) -> bool:
    value = fields.get(key, False)
    if not isinstance(value, bool):
        raise UserError(f"must be true or false, got {value!r}", field=key)
    return value


# ---------------------------------------------------------------- knot times (4.4.6)

DISTRIBUTIONS = ("equal", "chord", "centripetal")
OBJECTIVES = ("peak_acceleration", "rms_acceleration")
TIME_WORDS = (*DISTRIBUTIONS, "auto")

_SOFTMAX_BOUND = 5.0
"""Bound on the free variables: every interval between e^-5 and e^5 times the first one
(keeps the spline systems well conditioned during the search)."""

_FREE_SCALE = 10.0
"""SLSQP's variables are y / 10: its first quasi-Newton metric (the identity) fits better (a
third of the iterations of y itself on the 32 points of bench_axes.py --case spline)."""


def distributed_times(q: np.ndarray, rule: str, duration: float = 1.0,
                      start: float = 0.0) -> np.ndarray:
    """The book's (4.37) over [start, start + duration]: ``equal``, ``chord`` or
    ``centripetal`` spacing of the positions q."""
    q = np.asarray(q, dtype=float)
    steps = np.abs(np.diff(q))
    if rule == "equal":
        d = np.ones_like(steps)
    elif rule in ("chord", "centripetal"):
        d = steps if rule == "chord" else np.sqrt(steps)
        same = np.flatnonzero(steps == 0.0)
        if same.size:
            i = int(same[0]) + 1
            raise UserError(f"{rule} times need consecutive positions to differ: "
                            f"positions[{i}] = positions[{i - 1}] = {q[i]:g}", field="times")
    else:
        raise UserError(f"unknown time distribution {rule!r}; use a list of times or "
                        f"one of {', '.join(TIME_WORDS)}", field="times")
    t = start + duration * np.concatenate([[0.0], np.cumsum(d) / d.sum()])
    t[-1] = start + duration
    return t


# ---------------------------------------------------------------- exact measures

def _acceleration_ends(curve) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(h_k, a at the start of piece k, a at its end) of a piecewise cubic PPoly."""
    c = np.asarray(curve.c)
    h = np.diff(curve.x)
    degree = c.shape[0] - 1
    if degree > 3:
        raise ValueError("exact acceleration measures need a piecewise cubic")
    c = np.concatenate([np.zeros((3 - degree, c.shape[1])), c]) if degree < 3 else c
    return h, 2.0 * c[1], 6.0 * c[0] * h + 2.0 * c[1]


def peak_acceleration(curve) -> float:
    """max |s''(t)| of a piecewise cubic: the acceleration is linear on each piece."""
    _, a_start, a_end = _acceleration_ends(curve)
    return float(max(np.max(np.abs(a_start)), np.max(np.abs(a_end))))


def rms_acceleration(curve) -> float:
    """sqrt(1/T int s''^2 dt) of a piecewise cubic, by (4.31) on each piece."""
    h, a0, a1 = _acceleration_ends(curve)
    return float(math.sqrt(np.sum(h / 3.0 * (a0 ** 2 + a0 * a1 + a1 ** 2)) / h.sum()))


MEASURES = {"peak_acceleration": peak_acceleration, "rms_acceleration": rms_acceleration}


# ---------------------------------------------------------------- auto: best interior times

def times_from_free(y: np.ndarray, duration: float, start: float = 0.0) -> np.ndarray:
    """The times of the free variables y (n - 1 of them, y_0 = 0 implied): intervals
    T_k = duration * softmax([0, y])_k."""
    z = np.concatenate([[0.0], y])
    e = np.exp(z - z.max())
    t = start + duration * np.concatenate([[0.0], np.cumsum(e) / e.sum()])
    t[-1] = start + duration
    return t


_Knots = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]


def _knot_accelerations(q: np.ndarray, conditions: Mapping[str, Any]
                        ) -> Callable[[np.ndarray], _Knots]:
    """The map from the intervals h of the given times to (T, dT/dh, omega, d omega/dh):
    the pieces T of the spline through q with ``conditions`` (the given intervals; with end
    accelerations, the first and last ones halved by the free points of sec. 4.4.4) and
    its accelerations omega at every breakpoint, with their exact derivatives.

    Piece k adds to the conditions at its ends ((4.19) times T_k, (4.22)) row k:
    2 T_k w_k + T_k w_{k+1} - 6 (q_{k+1} - q_k) / T_k and row k + 1: T_k w_k +
    2 T_k w_{k+1} + 6 (q_{k+1} - q_k) / T_k; with z = (omega, positions), K(T) z = c:
    clamped (c_0 = -6 v_0, c_n = 6 v_n), natural (rows 0, n out, omega_0 = omega_n = 0),
    periodic (row n added to row 0, omega_n = omega_0), end accelerations (omega_0 = a_0,
    omega_n = a_n, the free points' positions unknown). With z = S x + z0 and rows R,
    A x = R (c - K z0), A = R K S, and dx/dT_k = -A^-1 R (dK/dT_k) z: all the columns
    from one inverse of A, each (dK/dT_k) z nonzero in rows k and k + 1 only.
    """
    q = np.array(q, dtype=float)
    n = len(q) - 1
    periodic, natural = bool(conditions.get("periodic")), bool(conditions.get("natural"))
    ends = not (periodic or natural) and (conditions.get("a0") is not None
                                          or conditions.get("an") is not None)
    pieces = n + 2 if ends else n
    size = 2 * (pieces + 1)
    P = np.eye(n)[np.r_[0, 0:n, n - 1] if ends else np.arange(n)]  # the pieces T = P h
    P[[0, 1, -2, -1] if ends else []] *= 0.5
    z0, c = np.zeros(size), np.zeros(pieces + 1)
    if periodic:
        check_periodic(q)
        q[-1] = q[0]
    z0[pieces + 1:] = np.r_[q[0], 0.0, q[1:-1], 0.0, q[-1]] if ends else q
    z0[[0, pieces]] = (conditions.get("a0") or 0.0, conditions.get("an") or 0.0) if ends else 0
    if not (periodic or natural):
        c[[0, pieces]] = -6.0 * conditions.get("v0", 0.0), 6.0 * conditions.get("vn", 0.0)
    unknown = (np.r_[1:pieces, pieces + 2, 2 * pieces] if ends else
               np.arange(1 if natural else 0, pieces if natural or periodic else pieces + 1))
    S = np.eye(size)[:, unknown]
    R = np.eye(pieces + 1)[1:pieces] if natural else np.eye(pieces + 1)
    if periodic:
        S[pieces, 0] = R[0, pieces] = 1.0
        R = R[:pieces]
    k = np.arange(pieces)
    flat = (np.r_[k, k, k + 1, k + 1, k, k, k + 1, k + 1] * size
            + np.r_[k, k + 1, k, k + 1, k + pieces + 1, k + pieces + 2, k + pieces + 1,
                    k + pieces + 2])

    def accelerations(h: np.ndarray) -> _Knots:
        T = P @ h
        w = 6.0 / T
        K = np.bincount(flat, np.concatenate([2 * T, T, T, 2 * T, w, -w, -w, w]),
                        len(c) * size).reshape(len(c), size)
        A_inv = np.linalg.inv(R @ K @ S)  # at most 35 x 35: the values and all columns
        z = S @ (A_inv @ (R @ (c - K @ z0))) + z0
        omega, slope = z[:pieces + 1], np.diff(z[pieces + 1:]) / T
        G = np.zeros((pieces + 1, pieces))
        G[k, k] = 2.0 * omega[:-1] + omega[1:] + slope * w
        G[k + 1, k] = omega[:-1] + 2.0 * omega[1:] - slope * w
        return T, P, omega, -S[:pieces + 1] @ (A_inv @ (R @ G @ P))

    return accelerations


def optimal_times(q: np.ndarray, duration: float = 1.0,
                  objective: str = "peak_acceleration", **conditions: Any) -> np.ndarray:
    """The times t_0 = 0 < t_1 < ... < t_n = duration minimizing ``objective``
    (``peak_acceleration`` or ``rms_acceleration``) of the cubic spline through q with
    ``conditions`` (the keywords of :func:`cubic_spline`; with end accelerations, the
    free points at the midpoints).

    Deterministic: SLSQP from the equal times, with the exact derivatives of
    :func:`_knot_accelerations` through the softmax of :func:`times_from_free`. The peak
    is a minimax, solved as min z subject to -z <= s''(t_j) <= z at every breakpoint t_j
    (the acceleration of a cubic spline is piecewise linear, so its peak sits at a
    breakpoint); the RMS acceleration is smooth and minimized directly (its square, by
    (4.31) on each piece).
    """
    from scipy.optimize import minimize

    if objective not in MEASURES:
        raise UserError(f"unknown objective {objective!r}; use one of "
                        f"{', '.join(OBJECTIVES)}", field="minimize")
    if conditions.get("extra_times") is not None:
        raise UserError("with times: auto the free points are at the midpoints of the "
                        "first and last intervals", field="extra_times")
    q = np.asarray(q, dtype=float)
    n = len(q) - 1
    equal = distributed_times(q, "equal", duration)
    if n < 2:
        return equal
    start = cubic_spline(equal, q, **conditions)
    scale = max(peak_acceleration(start), 1e-300)
    knots = _knot_accelerations(q, conditions)
    memo: dict[bytes, _Knots] = {}

    def solved(x: np.ndarray) -> _Knots:  # (T, dT/dx, omega / scale, d(omega / scale)/dx)
        key = x.tobytes()
        if key not in memo:
            memo.clear()
            h = np.diff(times_from_free(_FREE_SCALE * x, duration))
            p = h / duration  # dh/dy = duration (diag(p) - p p^T), without y_0
            dh = (np.diag(h) - np.outer(h, p))[:, 1:] * _FREE_SCALE
            T, dT, omega, d_omega = knots(h)
            memo[key] = T, dT @ dh, omega / scale, d_omega @ dh / scale
        return memo[key]

    bounds = [(-_SOFTMAX_BOUND / _FREE_SCALE, _SOFTMAX_BOUND / _FREE_SCALE)] * (n - 1)
    x0 = np.zeros(n - 1)
    if objective == "rms_acceleration":
        def mean_square(x: np.ndarray) -> tuple[float, np.ndarray]:
            T, dT, a, da = solved(x)
            a0, a1 = a[:-1], a[1:]
            value = T @ (a0 * a0 + a0 * a1 + a1 * a1) / (3.0 * duration)
            gradient = ((a0 * a0 + a0 * a1 + a1 * a1) @ dT
                        + (np.r_[T * (2.0 * a0 + a1), 0.0] + np.r_[0.0, T * (a0 + 2.0 * a1)])
                        @ da) / (3.0 * duration)
            return value, gradient

        x = minimize(mean_square, x0, jac=True, method="SLSQP", bounds=bounds,
                     options={"ftol": 1e-15, "maxiter": 500}).x  # its value ~ 1: as before
    else:
        def bands(v: np.ndarray) -> np.ndarray:  # z -+ s''(t_j) >= 0
            a = solved(v[:-1])[2]
            return np.concatenate([v[-1] - a, v[-1] + a])

        def bands_jacobian(v: np.ndarray) -> np.ndarray:
            da = solved(v[:-1])[3]
            return np.hstack([np.vstack([-da, da]), np.ones((2 * len(da), 1))])

        last = np.eye(n)[-1]
        x = minimize(lambda v: v[-1], np.append(x0, 1.0), jac=lambda v: last, method="SLSQP",
                     constraints=[{"type": "ineq", "fun": bands, "jac": bands_jacobian}],
                     bounds=[*bounds, (0.0, None)],  # z ~ 1; below 1e-12 only roundoff
                     options={"ftol": 1e-12, "maxiter": 500}).x[:-1]
    measure = MEASURES[objective]
    t = times_from_free(_FREE_SCALE * x, duration)
    if not np.all(np.isfinite(t)) or measure(cubic_spline(t, q, **conditions)) > measure(start):
        return equal  # the search did not improve on the equal times
    return t


# ---------------------------------------------------------------- minimum duration (4.39)

def _segment_peaks(curve, t: np.ndarray) -> np.ndarray:
    """Rows (max |v|, max |a|, max |j|) over each given interval [t_k, t_{k+1}]."""
    c = np.asarray(curve.c)
    x = np.asarray(curve.x)
    h = np.diff(x)
    c3, c2, c1 = c[0], c[1], c[2]
    v_ends = np.maximum(np.abs(c1), np.abs(3 * c3 * h ** 2 + 2 * c2 * h + c1))
    with np.errstate(divide="ignore", invalid="ignore"):
        tau = np.where(c3 != 0.0, -c2 / (3.0 * np.where(c3 != 0.0, c3, 1.0)), -1.0)
    inside = (tau > 0.0) & (tau < h)
    v_vertex = np.where(inside, np.abs(3 * c3 * tau ** 2 + 2 * c2 * tau + c1), 0.0)
    piece = np.column_stack([np.maximum(v_ends, v_vertex),
                             np.maximum(np.abs(2 * c2), np.abs(6 * c3 * h + 2 * c2)),
                             np.abs(6 * c3)])
    owner = np.searchsorted(t, (x[:-1] + x[1:]) / 2.0) - 1  # given interval of each piece
    out = np.zeros((len(t) - 1, 3))
    np.maximum.at(out, owner, piece)
    return out


def minimum_duration_times(q: np.ndarray, t: np.ndarray, limits: Mapping[int, float],
                           iterations: int = 1000, rtol: float = 1e-12,
                           **conditions: Any) -> np.ndarray:
    """The book's iteration (4.39) from the times ``t``: T'_k = lambda_k T_k with
    lambda_k = max over the limits {1: v_max, 2: a_max, 3: j_max} of
    (peak of |s^(i)| on [t_k, t_{k+1}] / limit)^(1/i), the spline recomputed each time,
    at most ``iterations`` times or until no interval changes by more than ``rtol``."""
    q = np.asarray(q, dtype=float)
    t = np.asarray(t, dtype=float)
    for _ in range(iterations):
        peaks = _segment_peaks(cubic_spline(t, q, **conditions), t)
        lam = np.zeros(len(t) - 1)
        for order, limit in limits.items():
            lam = np.maximum(lam, (peaks[:, order - 1] / limit) ** (1.0 / order))
        if not np.all(lam > 0.0):
            raise UserError("an interval has no motion to limit (equal positions with "
                            "zero velocity and acceleration)", field="limits")
        T = np.diff(t) * lam
        t_new = t[0] + np.concatenate([[0.0], np.cumsum(T)])
        done = np.max(np.abs(lam - 1.0)) <= rtol
        t = t_new
        if done:
            break
    return t


# ---------------------------------------------------------------- the YAML fields

def via_points(fields: Mapping[str, Any], conditions: Mapping[str, Any]
               ) -> tuple[np.ndarray, np.ndarray]:
    """(t, q) of a spline's fields: ``points`` or ``times``/``positions``, where
    ``times`` may be a word (:data:`TIME_WORDS`) with ``duration`` (default 1) and, for
    ``auto``, ``minimize`` (:data:`OBJECTIVES`); or ``minimize: duration`` with
    ``limits`` (the times, default ``chord`` as in the book's Example 4.15, only start
    the iteration)."""
    minimize = fields.get("minimize")
    if minimize is not None and minimize not in (*OBJECTIVES, "duration"):
        raise UserError(f"unknown objective {minimize!r}; use one of "
                        f"{', '.join((*OBJECTIVES, 'duration'))}", field="minimize")
    word = fields.get("times")
    if minimize == "duration" and word is None and "points" not in fields:
        word = "chord"
    if (isinstance(word, str) or minimize == "duration") and "extra_times" in fields:
        raise UserError("extra_times fix the free points of given times; with times chosen "
                        "by a rule or by minimize: duration they are the midpoints",
                        field="extra_times")
    if isinstance(word, str):
        if "points" in fields:
            raise UserError("give points or times and positions, not both", field="points")
        if word not in TIME_WORDS:
            raise UserError(f"unknown time distribution {word!r}; use a list of times or "
                            f"one of {', '.join(TIME_WORDS)}", field="times")
        q = F.numbers(fields, "positions", minimum=2)
        if minimize == "duration":
            if word == "auto":
                raise UserError("with minimize: duration the times only start the book's "
                                "iteration: give a list or equal, chord or centripetal",
                                field="times")
            if "duration" in fields:
                raise UserError("minimize: duration finds the duration; remove duration",
                                field="duration")
            duration = 1.0
        else:
            duration = F.number(fields, "duration", 1.0, positive=True)
        if word == "auto":
            if len(q) > MAX_AUTO_TIMES_POINTS:
                raise UserError(f"times: auto through {len(q):,} positions: the limit is "
                                f"{MAX_AUTO_TIMES_POINTS} (MAX_AUTO_TIMES_POINTS, the "
                                f"search costs the cube of the count); give the times or "
                                f"a rule (equal, chord, centripetal)", field="positions")
            t = optimal_times(q, duration, minimize or "peak_acceleration", **conditions)
        else:
            if minimize in OBJECTIVES:
                raise UserError(f"minimize: {minimize} chooses the times: use times: auto",
                                field="minimize")
            t = distributed_times(q, word, duration)
    else:
        t, q = F.points(fields)
        if "duration" in fields:
            raise UserError("duration is the total time of times: equal, chord, "
                            "centripetal or auto; with listed times it is t_n - t_0",
                            field="duration")
        if minimize in OBJECTIVES:
            raise UserError(f"minimize: {minimize} chooses the times: use times: auto",
                            field="minimize")
    if minimize == "duration":
        return minimum_duration_times(q, t, _limits(fields), **conditions), q
    if "limits" in fields:
        raise UserError("limits are used with minimize: duration", field="limits")
    return t, q


def _limits(fields: Mapping[str, Any]) -> dict[int, float]:
    if "limits" not in fields:
        raise UserError("minimize: duration needs limits: {velocity: .., acceleration: ..}",
                        field="limits")
    limits = F.conditions(fields, "limits", highest=3)
    if 0 in limits:
        raise UserError("limits are on velocity, acceleration and jerk",
                        field="limits.position")
    if not limits:
        raise UserError("give at least one of velocity, acceleration, jerk", field="limits")
    for order, value in limits.items():
        if not value > 0.0:
            name = next(k for k, v in F.ORDER_NAMES.items() if v == order)
            raise UserError(f"must be positive, got {value:g}", field=f"limits.{name}")
    return limits


def build_cubic_spline(fields: Mapping[str, Any]):
    """``kind: cubic_spline``: the interpolating cubic spline of sec. 4.4 as a PPoly.

    Fields: ``points: [[t, q], ...]`` or ``times: [...]`` with ``positions: [...]``
    (at least 2 points); ``times`` may instead be a word (``equal``, ``chord``,
    ``centripetal``, ``auto``; see :func:`via_points`) with
    ``duration`` (default 1) and, for ``auto``, ``minimize`` (``peak_acceleration``,
    default, or ``rms_acceleration``); ``minimize: duration`` with
    ``limits: {velocity, acceleration, jerk}`` scales the intervals as in sec. 4.4.6.
    Ends: ``start: {velocity: v0}``, ``end: {velocity: vn}`` (default 0, 0); with
    ``acceleration`` at both ends, the two free points of sec. 4.4.4 at ``extra_times``
    (default: midpoints of the first and last intervals); or ``periodic: true``
    (q_0 = q_n) or ``natural: true`` (zero end accelerations).
    """
    F.refuse_unknown(fields, FIELDS, KIND)
    conditions = end_conditions(fields)
    t, q = via_points(fields, conditions)
    return cubic_spline(t, q, **conditions)
