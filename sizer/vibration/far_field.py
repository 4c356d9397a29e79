"""The convolution of a law with a fast mode from its pieces' ends: a cost free of f_n T.

On a part [a, b] where q_N'' is a polynomial p (a law's polynomial pieces), or is
interpolated by one to rounding (Chebyshev interpolation, the part halved until its tail
vanishes), integration by parts ends (book sec. 7.2's convolution, s = lambda T):

    int_a^tau p(u) e^{s (tau - u)} du = sum_k (e^{s (tau - a)} p^(k)(a) - p^(k)(tau)) / s^(k+1)

a finite sum whose cost does not grow with |s|: the residual vibration of a 1e6 s move on a
25 Hz mode costs what a 1 s move does, where sampling needs 16 points a period (4e8). It is
used where every term p^(k) / s^k stays below GAIN times the law's largest |q_N''| (the
rounding then stays below GAIN eps of the leading term); below that |s| the grids of
sizer.vibration.convolution (cost ~ |s|) are exact and cheap.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from sizer.laws.base import MotionLaw
from sizer.numerics.arrays import sorted_unique

POINTS = 33
"""Chebyshev points a part (a polynomial of degree 32 interpolates it)."""

TAIL = 1e-14
"""A part is resolved when its last three Chebyshev coefficients are below TAIL times the
law's largest |q_N''|."""

GAIN = 1e3
"""Largest |p^(k)| / |s|^k allowed, in units of the law's largest |q_N''|."""

MAX_PARTS = 20_000
"""Most parts of one law's interpolation (beyond: not resolved, the grids only)."""

FAR_MIN = 4096.0
"""Smallest |s| the end series is used at (below, the grids cost little)."""

CHUNK = 1 << 21
"""Largest rows x parts block evaluated at once (bounded memory)."""


@dataclass(frozen=True)
class EndSeries:
    """A law's q_N'' as polynomials on parts [start, end] (in order, covering [0, 1]):
    ``coefficients`` (parts, POINTS) Chebyshev on each part; ``at_start``, ``at_end``
    (parts, POINTS) p^(k) at its ends, k = 0 .. POINTS - 1; ``s_min`` the smallest |s|
    the series is used at (inf when q_N'' is not resolved)."""

    start: np.ndarray
    end: np.ndarray
    coefficients: np.ndarray
    at_start: np.ndarray
    at_end: np.ndarray
    s_min: float
    s_low: float


@lru_cache(maxsize=1)
def _chebyshev() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Points x_j on [-1, 1] (first kind), the matrix values -> coefficients, and
    T_j^(k)(1), (k, j)."""
    n = POINTS
    theta = math.pi * (np.arange(n) + 0.5) / n
    x = np.cos(theta)
    to_coefficients = (2.0 / n) * np.cos(np.outer(np.arange(n), theta))
    to_coefficients[0] *= 0.5
    j2 = np.arange(n, dtype=float) ** 2
    ends = np.ones((n, n))
    for k in range(1, n):  # T_j^(k)(1) = prod_{i < k} (j^2 - i^2) / (2 i + 1)
        ends[k] = ends[k - 1] * (j2 - (k - 1) ** 2) / (2 * k - 1)
    return x, to_coefficients.T, ends


def _sample(law: MotionLaw, index: np.ndarray, a: np.ndarray, b: np.ndarray,
            order: int = 2) -> np.ndarray:
    """q_N^(order) at the Chebyshev points of each part (parts, POINTS)."""
    x, _, _ = _chebyshev()
    nodes = a[:, None] + (0.5 * (x + 1.0)) * (b - a)[:, None]
    out = np.empty(nodes.shape)
    for i in sorted_unique(index):
        rows = index == i
        out[rows] = law.piece_derivative(int(i), nodes[rows], order)
    return out


@lru_cache(maxsize=64)
def end_series(law: MotionLaw, order: int = 2) -> EndSeries:
    """The law's parts, halved until each is resolved, for q_N^(order) (q_N'' by
    default; cached per law)."""
    _, to_coefficients, ends = _chebyshev()
    pieces = law.pieces
    index = np.arange(len(pieces))
    a = np.array([p.start for p in pieces], dtype=float)
    b = np.array([p.end for p in pieces], dtype=float)
    keep = b > a
    index, a, b = index[keep], a[keep], b[keep]
    done: list[tuple[np.ndarray, ...]] = []
    scale = 0.0
    with np.errstate(all="ignore"):
        while a.size and sum(d[0].size for d in done) + a.size <= MAX_PARTS:
            c = _sample(law, index, a, b, order) @ to_coefficients
            if not np.all(np.isfinite(c)):
                return _unresolved()
            scale = max(scale, float(np.max(np.abs(c).sum(axis=1), initial=0.0)))
            tail = np.max(np.abs(c[:, -3:]), axis=1)
            ok = (tail <= TAIL * scale) | (b - a <= 1e-12 * np.maximum(1.0, np.abs(a)))
            done.append((index[ok], a[ok], b[ok], c[ok]))
            mid = 0.5 * (a + b)
            index = np.repeat(index[~ok], 2)
            a, b = (np.column_stack([a[~ok], mid[~ok]]).ravel(),
                    np.column_stack([mid[~ok], b[~ok]]).ravel())
        if a.size or scale == 0.0:
            return _unresolved()
        a = np.concatenate([d[1] for d in done])
        rank = np.argsort(a, kind="stable")
        a = a[rank]
        b = np.concatenate([d[2] for d in done])[rank]
        c = np.concatenate([d[3] for d in done])[rank]
        c = np.where(np.abs(c) <= 1e-3 * TAIL * scale, 0.0, c)  # the rounding's tail
        grow = (2.0 / (b - a))[:, None] ** np.arange(POINTS)  # d/du = (2 / (b - a)) d/dx
        sign = (-1.0) ** np.add.outer(np.arange(POINTS), np.arange(POINTS))  # (k, j)
        at_end = (c @ ends.T) * grow
        at_start = (c @ (ends * sign).T) * grow
        if not (np.all(np.isfinite(at_end)) and np.all(np.isfinite(at_start))):
            return _unresolved()
        worst = np.max(np.maximum(np.abs(at_start), np.abs(at_end)), axis=0)[1:]
        k = np.arange(1, POINTS)
        s_min = float(np.max((worst / (GAIN * scale)) ** (1.0 / k), initial=0.0))
    return EndSeries(a, b, c, at_start, at_end, max(s_min, FAR_MIN), s_min)


def _unresolved() -> EndSeries:
    empty = np.zeros((0, POINTS))
    return EndSeries(np.zeros(0), np.zeros(0), empty, empty, empty, math.inf, math.inf)


def usable(law: MotionLaw, s_abs: np.ndarray) -> np.ndarray:
    """Where the end series is used (True) rather than the grids."""
    return np.asarray(s_abs) >= end_series(law).s_min


def _inverse_powers(s: np.ndarray) -> np.ndarray:
    """1 / s^(k+1), k = 0 .. POINTS - 1, (rows, POINTS) (underflow to 0 is harmless)."""
    inv = 1.0 / s
    out = np.empty((s.size, POINTS), dtype=complex)
    out[:, 0] = inv
    with np.errstate(under="ignore", over="ignore", invalid="ignore"):
        out[:, 1:] = inv[:, None]
        out = np.cumprod(out, axis=1)
    return out


def end_values(law: MotionLaw, s: np.ndarray, order: int = 2) -> np.ndarray:
    """w(1) = int_0^1 q_N^(order)(u) e^{s (1 - u)} du for every s (1-D complex, Re s <= 0,
    |s| >= the law's s_min): the sum over parts, in blocks of bounded memory."""
    series = end_series(law, order)
    out = np.empty(s.shape, dtype=complex)
    rows = max(1, CHUNK // max(1, series.start.size))
    for i in range(0, s.size, rows):
        part = s[i:i + rows]
        inv = _inverse_powers(part)
        first = _real_matmul(inv, series.at_start.T)  # (rows, parts)
        last = _real_matmul(inv, series.at_end.T)
        out[i:i + rows] = np.sum(np.exp(np.multiply.outer(part, 1.0 - series.start)) * first
                                 - np.exp(np.multiply.outer(part, 1.0 - series.end)) * last,
                                 axis=1)
    return out


def _real_matmul(a: np.ndarray, real: np.ndarray) -> np.ndarray:
    return a.real @ real + 1j * (a.imag @ real)


SAMPLES = 129
"""Points a part at which the envelope of the tracking error is looked at."""

NEWTON_STEPS = 4
"""Newton iterations refining the peak of the tracking error near the envelope's."""


def peak_error(law: MotionLaw, s: np.ndarray) -> np.ndarray:
    """max over tau in [0, 1] of |Im w(tau)| from rest, w(tau) = e^{s (tau - a)} R - Q(tau)
    on each part: R the free vibration it carries, Q(tau) = sum_k p^(k)(tau) / s^(k+1)
    the quasi-static part. The largest of the envelope |R| e^{Re s (tau - a)} + |Im Q| on
    SAMPLES points a part is found, and w evaluated exactly at the nearest instant where
    the vibration's phase adds to Q (and at the parts' ends): the value returned is
    |Im w| at a point of the move, short of the peak by O(|Q'| / |s|) (|s| >= s_min)."""
    from numpy.polynomial import chebyshev as C

    series = end_series(law)
    s = np.asarray(s, dtype=complex)
    inv = _inverse_powers(s)  # (rows, POINTS)
    x = np.linspace(-1.0, 1.0, SAMPLES)
    best = np.zeros(s.shape)
    w_a = np.zeros(s.shape, dtype=complex)  # w at the part's start
    for j in range(series.start.size):
        a, b, c = series.start[j], series.end[j], series.coefficients[j]
        d = b - a
        derivatives = [c]
        for _ in range(1, POINTS):
            derivatives.append(C.chebder(derivatives[-1]) * (2.0 / d)
                               if derivatives[-1].size > 1 else np.zeros(1))
        R = w_a + inv @ series.at_start[j]

        def quasi(xs: np.ndarray, _der: list = derivatives) -> np.ndarray:
            table = np.stack([C.chebval(xs, der) * np.ones_like(xs) for der in _der])
            return table  # (POINTS, len(xs))

        Q = _real_matmul(inv, quasi(x))  # (rows, SAMPLES)
        u = a + 0.5 * (x + 1.0) * d
        decay = np.exp(np.multiply.outer(s.real, u - a))
        envelope = np.abs(R)[:, None] * decay + np.abs(Q.imag)
        k = np.argmax(envelope, axis=1)
        tau = u[k]
        q_at = Q[np.arange(s.size), k]
        # the phase at which Im(e^{s (tau - a)} R) has the sign of -Im Q there
        target = np.where(-q_at.imag >= 0.0, 0.5 * math.pi, -0.5 * math.pi)
        theta = s.imag * (tau - a) + np.angle(R)
        with np.errstate(divide="ignore", invalid="ignore"):
            shift = np.where(s.imag != 0.0, (np.mod(target - theta + math.pi, 2.0 * math.pi)
                                              - math.pi) / s.imag, 0.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            period = np.where(s.imag != 0.0, 2.0 * math.pi / np.abs(s.imag), 0.0)
        near = tau + shift
        points = np.stack([np.full(s.shape, a), np.clip(near - period, a, b),
                           np.clip(near, a, b), np.clip(near + period, a, b),
                           np.full(s.shape, b)], axis=1)  # (rows, 5): the ends last

        def values(at: np.ndarray, order: int, _der: list = derivatives,
                   _a: float = a, _d: float = d, _R: np.ndarray = R) -> np.ndarray:
            """The order-th tau-derivative of w at the points (rows, n)."""
            xs = 2.0 * (at - _a) / _d - 1.0
            table = np.stack([C.chebval(xs, der) * np.ones_like(xs)
                              for der in _der[order:]], axis=-1)
            q = np.einsum("rpk,rk->rp", table.astype(complex), inv[:, :POINTS - order])
            return s[:, None] ** order * np.exp(s[:, None] * (at - _a)) * _R[:, None] - q

        # and the first two periods after the part's start (a damped transient's peak)
        window = np.clip(a + period[:, None] * np.linspace(0.0, 2.0, 33), a, b)
        points = np.concatenate([window, points], axis=1)
        w = values(points, 0)
        best = np.maximum(best, np.max(np.abs(w.imag), axis=1))
        w_a = w[:, -1]
        pick = np.argsort(-np.abs(w.imag), axis=1)[:, :3]
        inner = np.take_along_axis(points, pick, axis=1)
        for _ in range(NEWTON_STEPS):  # refine on f' = 0, f = Im w
            f1, f2 = values(inner, 1).imag, values(inner, 2).imag
            with np.errstate(divide="ignore", invalid="ignore"):
                step = np.where(f2 != 0.0, f1 / f2, 0.0)
            inner = np.clip(inner - np.clip(step, -period[:, None], period[:, None]), a, b)
            best = np.maximum(best, np.max(np.abs(values(inner, 0).imag), axis=1))
    return best


def polynomial_end_values(acceleration: Callable[[np.ndarray], np.ndarray],
                          breaks: np.ndarray, s: np.ndarray
                          ) -> tuple[np.ndarray, np.ndarray]:
    """w(1) for accelerations that differ per row (``acceleration(u)`` gives (rows,
    len(u)), polynomial between ``breaks``: a move between boundary speeds), and where it
    is usable (|s| >= FAR_MIN and the terms p^(k) / s^k within GAIN of the largest |a|);
    elsewhere the value is 0 and the caller integrates."""
    x, to_coefficients, ends = _chebyshev()
    edges = np.asarray(breaks, dtype=float)
    a, b = edges[:-1], edges[1:]
    d = b - a
    nodes = (a[:, None] + (0.5 * (x + 1.0)) * d[:, None]).ravel()
    with np.errstate(all="ignore"):
        values = np.asarray(acceleration(nodes), dtype=float).reshape(s.size, a.size, POINTS)
        c = values @ to_coefficients  # (rows, pieces, POINTS)
        scale = np.max(np.abs(c).sum(axis=2), axis=1)  # (rows,)
        c = np.where(np.abs(c) <= 1e-3 * TAIL * scale[:, None, None], 0.0, c)
        grow = (2.0 / d)[:, None] ** np.arange(POINTS)  # (pieces, k)
        sign = (-1.0) ** np.add.outer(np.arange(POINTS), np.arange(POINTS))
        at_end = (c @ ends.T) * grow
        at_start = (c @ (ends * sign).T) * grow
        inv = _inverse_powers(s)  # (rows, k)
        size = np.abs(s)
        terms = np.maximum(np.abs(at_start), np.abs(at_end)).max(axis=1)  # (rows, k)
        gain = np.max(terms[:, 1:] * np.abs(inv[:, :-1] / inv[:, :1]), axis=1)
        ok = (size >= FAR_MIN) & np.isfinite(gain) & (gain <= GAIN * scale) & \
            np.all(np.isfinite(at_start) & np.isfinite(at_end), axis=(1, 2))
        first = np.einsum("rpk,rk->rp", at_start.astype(complex), inv)
        last = np.einsum("rpk,rk->rp", at_end.astype(complex), inv)
        out = np.sum(np.exp(np.multiply.outer(s, 1.0 - a)) * first
                     - np.exp(np.multiply.outer(s, 1.0 - b)) * last, axis=1)
    return np.where(ok, out, 0.0), ok
