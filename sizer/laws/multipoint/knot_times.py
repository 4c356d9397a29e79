"""The time instants t_k of a spline through positions q_k (book sec. 4.4.6).

- ``equal``, ``chord``, ``centripetal``: the book's distributions (4.37), t_k = t_{k-1} +
  d_{k-1}/d over the total time, with d_k constant, |q_{k+1} - q_k| ("cord length") or
  |q_{k+1} - q_k|^(1/2) ("centripetal", the book's exponent mu = 1/2).
- ``auto`` (not in the book): the interior times that minimize the peak or the RMS
  acceleration of the spline for a fixed total time; scipy.optimize SLSQP from the equal
  times, the intervals as a softmax of free variables (always positive, summing to the
  duration), so the times stay strictly increasing.
- ``minimize: duration`` under velocity/acceleration/jerk limits: the book's iteration
  (4.39), each interval scaled by lambda_k = max{lambda_v,k, lambda_a,k, lambda_j,k} and
  the spline recomputed, until the intervals settle (Example 4.15).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from sizer.errors import UserError
from sizer.input_limits import MAX_AUTO_TIMES_POINTS
from sizer.laws.multipoint import cubic_splines as cs
from sizer.laws.multipoint import fields as F

DISTRIBUTIONS = ("equal", "chord", "centripetal")
OBJECTIVES = ("peak_acceleration", "rms_acceleration")
TIME_WORDS = (*DISTRIBUTIONS, "auto")

_SOFTMAX_BOUND = 5.0
"""Bound on the free variables: no interval shorter than e^-10 times another (keeps the
spline systems well conditioned during the search)."""


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
    z = np.concatenate([[0.0], np.asarray(y, dtype=float)])
    e = np.exp(z - z.max())
    t = start + duration * np.concatenate([[0.0], np.cumsum(e) / e.sum()])
    t[-1] = start + duration
    return t


def optimal_times(q: np.ndarray, duration: float = 1.0,
                  objective: str = "peak_acceleration", **conditions: Any) -> np.ndarray:
    """The times t_0 = 0 < t_1 < ... < t_n = duration minimizing ``objective``
    (``peak_acceleration`` or ``rms_acceleration``) of the cubic spline through q with
    ``conditions`` (the keywords of :func:`cubic_splines.cubic_spline`).

    Deterministic: SLSQP from the equal times. The peak is a minimax, solved as
    min z subject to -z <= s''(t_j) <= z at every breakpoint t_j (the acceleration of a
    cubic spline is piecewise linear, so its peak sits at a breakpoint); the RMS
    acceleration is smooth and minimized directly (its square).
    """
    from scipy.optimize import minimize

    if objective not in MEASURES:
        raise UserError(f"unknown objective {objective!r}; use one of "
                        f"{', '.join(OBJECTIVES)}", field="minimize")
    q = np.asarray(q, dtype=float)
    n = len(q) - 1
    equal = distributed_times(q, "equal", duration)
    if n < 2:
        return equal

    def spline(y: np.ndarray):
        return cs.cubic_spline(times_from_free(y, duration), q, **conditions)

    y0 = np.zeros(n - 1)
    bounds = [(-_SOFTMAX_BOUND, _SOFTMAX_BOUND)] * (n - 1)
    scale = max(peak_acceleration(spline(y0)), 1e-300)
    if objective == "rms_acceleration":
        result = minimize(lambda y: (rms_acceleration(spline(y)) / scale) ** 2, y0,
                          method="SLSQP", bounds=bounds,
                          options={"ftol": 1e-15, "maxiter": 500})
        y = result.x
    else:
        def accelerations(y: np.ndarray) -> np.ndarray:
            pp = spline(y)
            return pp(pp.x, 2) / scale

        constraints = [{"type": "ineq", "fun": lambda v: v[-1] - accelerations(v[:-1])},
                       {"type": "ineq", "fun": lambda v: v[-1] + accelerations(v[:-1])}]
        start = np.append(y0, 1.0)
        result = minimize(lambda v: v[-1], start, method="SLSQP", constraints=constraints,
                          bounds=[*bounds, (0.0, None)],
                          options={"ftol": 1e-14, "maxiter": 500})
        y = result.x[:-1]
    measure = MEASURES[objective]
    if not np.all(np.isfinite(y)) or measure(spline(y)) > measure(spline(y0)):
        return equal  # the search did not improve on the equal times
    return times_from_free(y, duration)


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
        peaks = _segment_peaks(cs.cubic_spline(t, q, **conditions), t)
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
