"""Smoothing cubic splines: approximate, not interpolate, the via-points (book sec. 4.4.5).

The spline minimizes (4.29), L = mu sum_k w_k (s(t_k) - q_k)^2 + (1 - mu) int s''(t)^2 dt,
with mu in (0, 1] (mu = 1: interpolation) and per-point weights w_k. The book's spline is
clamped, zero end velocities (4.34); with lambda = (1 - mu)/(6 mu) (4.32) its accelerations
omega solve (4.35), (A + lambda C W^-1 C^T) omega = C q, and its values at the t_k are
(4.36), s = q - lambda W^-1 C^T omega. The book gives W^-1 directly: a zero entry makes
the spline pass through that point exactly.

The book's end velocities and accelerations (Example 4.11) and periodic ends (Example
4.12) re-interpolate the smoothed points s_k with sec. 4.4.4 or 4.4.2 ("at the expense of
a small deformation"); so does :func:`build_smoothing_spline` when ``start``/``end`` or
``periodic`` are given.

scipy's ``make_smoothing_spline(x, y, w, lam)`` minimizes sum w_k (y_k - s(t_k))^2 +
lam int s''^2 with natural ends (zero end accelerations), not the book's clamped ones,
and refuses infinite weights, so it is not used: (4.35) is solved here by hand. For the
record, the book's criterion divided by mu is that functional with lam = (1 - mu)/mu =
6 lambda.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from sizer.errors import UserError
from sizer.laws.multipoint import cubic_splines as cs
from sizer.laws.multipoint import fields as F

KIND = "smoothing_spline"
FIELDS = ("points", "times", "positions", "mu", "tolerance", "point_weights",
          "inverse_weights", "start", "end", "periodic", "extra_times")
"""The fields of ``kind: smoothing_spline`` (see :func:`build_smoothing_spline`)."""


def smoothing_lambda(mu: float) -> float:
    """lambda = (1 - mu)/(6 mu) of (4.32), mu in (0, 1]."""
    return (1.0 - mu) / (6.0 * mu)


def c_matrix(t: np.ndarray) -> np.ndarray:
    """The book's C of (4.34): A omega = C s for the clamped spline through (t_k, s_k)."""
    T = cs.intervals(t)
    n = len(T)
    C = np.zeros((n + 1, n + 1))
    for k in range(n):
        block = 6.0 / T[k] * np.array([[-1.0, 1.0], [1.0, -1.0]])
        C[k:k + 2, k:k + 2] += block
    return C


def smoothing_system(t: np.ndarray, q: np.ndarray, mu: float, inverse_weights: np.ndarray
                     ) -> tuple[np.ndarray, np.ndarray]:
    """The book's (4.35): (A + lambda C W^-1 C^T) omega = C q."""
    A, _ = cs.acceleration_system(t, q, 0.0, 0.0)
    C = c_matrix(t)
    lam = smoothing_lambda(mu)
    return A + lam * C @ np.diag(inverse_weights) @ C.T, C @ np.asarray(q, dtype=float)


def smoothed_points(t: np.ndarray, q: np.ndarray, mu: float,
                    inverse_weights: np.ndarray | None = None
                    ) -> tuple[np.ndarray, np.ndarray]:
    """(s, omega): the spline's values s_k = s(t_k) (4.36) and accelerations omega_k
    (4.35). ``inverse_weights`` is the diagonal of W^-1 (1/w_k, 0 = exact; default 1)."""
    q = np.asarray(q, dtype=float)
    w_inv = np.ones(len(q)) if inverse_weights is None else np.asarray(inverse_weights,
                                                                          dtype=float)
    M, rhs = smoothing_system(t, q, mu, w_inv)
    omega = cs._solve(M, rhs, "the smoothing system (4.35)")
    s = q - smoothing_lambda(mu) * w_inv * (c_matrix(t).T @ omega)
    return s, omega


def smoothing_spline(t: np.ndarray, q: np.ndarray, mu: float,
                     inverse_weights: np.ndarray | None = None):
    """The book's smoothing spline (clamped, v_0 = v_n = 0) as a PPoly, from (4.25)."""
    s, omega = smoothed_points(t, q, mu, inverse_weights)
    return cs.spline_from_coefficients(t, cs.coefficients_from_accelerations(t, s, omega))


def mu_for_tolerance(t: np.ndarray, q: np.ndarray, tolerance: float,
                     inverse_weights: np.ndarray | None = None, iterations: int = 20
                     ) -> float:
    """The book's bisection on mu (sec. 4.4.5, "prescribed tolerance"): ``iterations``
    halvings of [L, R] = [0, 1]; the last mu tried with max_k |s_k - q_k| <= tolerance
    (the book returns the last mu = (L + R)/2; here the last one that meets it, R)."""
    low, high = 0.0, 1.0
    q = np.asarray(q, dtype=float)
    for _ in range(iterations):
        mu = (low + high) / 2.0
        s, _ = smoothed_points(t, q, mu, inverse_weights)
        if np.max(np.abs(s - q)) > tolerance:
            low = mu
        else:
            high = mu
    return high


def build_smoothing_spline(fields: Mapping[str, Any]):
    """``kind: smoothing_spline``: the smoothing cubic spline of sec. 4.4.5 as a PPoly.

    Fields: ``points`` or ``times``/``positions`` (at least 2); ``mu`` in (0, 1] (the
    book's weight of the fit against the smoothness; 1 interpolates), or ``tolerance``
    (the largest |s(t_k) - q_k|; mu found by the book's bisection, 20 halvings); the
    book's weights as ``inverse_weights`` (the diagonal of W^-1, >= 0, 0 = pass exactly;
    default [0, 1, ..., 1, 0]: the ends exact, as in all the book's examples) or
    ``point_weights`` (w_k > 0, default as above); ``start``/``end``
    ({velocity, acceleration}) or ``periodic: true`` re-interpolate the smoothed points
    with sec. 4.4.1/4.4.4/4.4.2 (Examples 4.11, 4.12; ``extra_times`` as in
    cubic_spline). Without them the spline has zero end velocities (4.34).
    """
    F.refuse_unknown(fields, FIELDS, KIND)
    t, q = F.points(fields)
    w_inv = _inverse_weights(fields, len(q))
    if "mu" in fields and "tolerance" in fields:
        raise UserError("give mu or tolerance, not both", field="tolerance")
    if "tolerance" in fields:
        mu = mu_for_tolerance(t, q, F.number(fields, "tolerance", positive=True), w_inv)
    else:
        mu = F.number(fields, "mu")
        if not 0.0 < mu <= 1.0:
            raise UserError(f"must be in (0, 1] (1 interpolates the points), got {mu:g}",
                            field="mu")
    if not any(key in fields for key in ("start", "end", "periodic", "extra_times")):
        return smoothing_spline(t, q, mu, w_inv)
    if fields.get("periodic") is True:
        cs.check_periodic(q)
        if w_inv[0] != 0.0 or w_inv[-1] != 0.0:
            raise UserError("a periodic smoothing spline must pass through the first and "
                            "the last point: give them inverse_weights 0 (the default)",
                            field="periodic")
    s, _ = smoothed_points(t, q, mu, w_inv)
    return cs.cubic_spline(t, s, **cs.end_conditions(fields))


def _inverse_weights(fields: Mapping[str, Any], count: int) -> np.ndarray:
    if "inverse_weights" in fields and "point_weights" in fields:
        raise UserError("give point_weights or inverse_weights, not both",
                        field="inverse_weights")
    if "point_weights" in fields:
        w = F.numbers(fields, "point_weights", length=count)
        bad = np.flatnonzero(w <= 0.0)
        if bad.size:
            i = int(bad[0])
            raise UserError(f"weights must be positive (use inverse_weights 0 to pass "
                            f"exactly through a point), got {w[i]:g}",
                            field=f"point_weights[{i}]")
        return 1.0 / w
    if "inverse_weights" in fields:
        w_inv = F.numbers(fields, "inverse_weights", length=count)
        bad = np.flatnonzero(w_inv < 0.0)
        if bad.size:
            i = int(bad[0])
            raise UserError(f"inverse weights must be >= 0, got {w_inv[i]:g}",
                            field=f"inverse_weights[{i}]")
        return w_inv
    w_inv = np.ones(count)
    w_inv[[0, -1]] = 0.0
    return w_inv
