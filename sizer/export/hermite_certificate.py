"""XYVA point tables (x, y, v, a) run as quintic Hermite curves, and their certificate.

A controller given position, velocity and acceleration at each point (CODESYS SMC_CAMXYVA)
runs, between two points, the quintic that matches y, v and a at both (scipy
``BPoly.from_derivatives`` with orders 5, as sizer.laws.cam_interpolation reads such a
table back). The curve is C2: the certificate gives the largest position, velocity and
acceleration errors against the law, as true maxima:

- the table's intervals are cut into cells at the law's breakpoints; on a cell the law is
  one smooth piece (evaluated exactly, one-sided at its ends) and the curve one quintic,
  so the k-th derivative of the difference e = y_law - H is smooth there;
- the extrema of e^(k) on a cell are at its ends or at the roots of e^(k+1): e^(k+1) is
  sampled at SAMPLES + 1 points across each cell, and every sign change between two
  neighbours is a bracket whose root is found by scipy's elementwise Chandrupatla root
  finder (vectorized over all brackets at once); the maximum of |e^(k)| is taken over the
  cell ends and these roots (k = 0, 1, 2; e''' uses the law's jerk, piece by piece).

A pair of roots closer than a cell's 1/SAMPLES is not bracketed: the method's one
assumption (the tests check the maxima against a 10^6-point grid refined by brentq).

The points are the law's breakpoints (where a piecewise law's pieces meet: a law whose
pieces are quintics, poly5, is reproduced exactly) plus equidistant ones; their number
is the fewest that meets the position tolerance, clipped to the target's limit.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from sizer.export.extremes import Extreme, largest_difference
from sizer.export.profile import CamProfile
from sizer.export.sampling import MAX_POINTS
from sizer.laws.cam_interpolation import interpolated_curve
from sizer.numerics.arrays import sorted_unique

SAMPLES = 32
"""Samples of e^(k+1) per cell (sign changes between them bracket the extrema of e^(k))."""


@dataclass(frozen=True)
class HermiteErrors:
    """The largest errors of the quintic Hermite curve against the law (file units)."""

    position: Extreme
    velocity: Extreme
    acceleration: Extreme


@dataclass(frozen=True)
class HermiteTable:
    """An XYVA table of the profile (y, v, a the law's at each master value), certified."""

    profile: CamProfile
    master: np.ndarray
    slave: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    errors: HermiteErrors
    tolerance: float | None
    limit: int
    clipped: bool = False
    needed: int | None = None

    @property
    def points(self) -> int:
        return len(self.master)

    @property
    def relative_position_error(self) -> float:
        return self.errors.position.max / abs(self.profile.stroke)

    @property
    def met(self) -> bool:
        return self.tolerance is None or self.relative_position_error <= self.tolerance


def hermite_errors(profile: CamProfile, x: np.ndarray, y: np.ndarray, v: np.ndarray,
                   a: np.ndarray) -> HermiteErrors:
    """The certificate of the XYVA table (module docstring)."""
    x = np.asarray(x, dtype=float)
    if x.ndim != 1 or len(x) < 2 or not np.all(np.diff(x) > 0):
        raise ValueError("a table needs at least 2 points with increasing master values")
    curve = interpolated_curve("quintic_hermite", x, np.asarray(y, float), np.asarray(v, float),
                          np.asarray(a, float))
    breaks = profile.breakpoints
    edges = sorted_unique(np.concatenate([x, breaks[(breaks > x[0]) & (breaks < x[-1])]]))
    lo, hi = edges[:-1], edges[1:]
    keep = hi > lo
    lo, hi = lo[keep], hi[keep]
    piece = profile.piece_of(0.5 * (lo + hi))
    interval = np.clip(np.searchsorted(x, 0.5 * (lo + hi), side="right") - 1, 0,
                       len(x) - 2)

    def difference(t: np.ndarray, p: np.ndarray, i: np.ndarray, order: int) -> np.ndarray:
        # the curve's derivative on interval i, evaluated from its own polynomial
        dt = t - x[i]
        c = curve.c[:, i]
        poly = np.zeros_like(t)
        degree = c.shape[0] - 1
        for j in range(degree - order + 1):  # coefficient of dt^(degree - j - order)
            power = degree - j
            factor = math.perm(power, order)
            poly = poly * dt + factor * c[j]
        return profile.derivative(t, order, p) - poly

    def on_cells(t: np.ndarray, cell: np.ndarray, order: int) -> np.ndarray:
        return difference(t, piece[cell], interval[cell], order)

    return HermiteErrors(*(largest_difference(on_cells, lo, hi, order, SAMPLES)
                           for order in (0, 1, 2)))


def master_values(profile: CamProfile, points: int) -> np.ndarray:
    """``points`` master values: the profile's breakpoints (its ends included) and
    equidistant ones between them (those within 1e-9 of the span of a breakpoint left
    out, then those nearest a breakpoint until the count is ``points``)."""
    breaks = sorted_unique(profile.breakpoints)
    if points < len(breaks):
        raise ValueError(f"an XYVA table of this profile needs at least {len(breaks)} "
                         f"points (the law's breakpoints)")
    n = points - len(breaks) + 2
    while True:
        grid = np.linspace(0.0, profile.span, n)[1:-1]
        distance = np.min(np.abs(grid[:, None] - breaks[None, :]), axis=1)
        inner = grid[distance > 1e-9 * profile.span]
        if len(inner) >= points - len(breaks):
            break
        n += points - len(breaks) - len(inner)
    surplus = len(inner) - (points - len(breaks))
    if surplus > 0:
        distance = np.min(np.abs(inner[:, None] - breaks[None, :]), axis=1)
        inner = np.delete(inner, np.argsort(distance, kind="stable")[:surplus])
    return np.sort(np.concatenate([breaks, inner]))


def fewest_points(profile: CamProfile) -> int:
    return len(sorted_unique(profile.breakpoints))


def table_of(profile: CamProfile, points: int, limit: int = MAX_POINTS,
             tolerance: float | None = None) -> HermiteTable:
    x = master_values(profile, points)
    y, v, a = (profile.derivative(x, k) for k in (0, 1, 2))
    # at a breakpoint the law's one-sided values agree (C2 laws); take the right one, as
    # profile.derivative does, and the end's left one at the span
    last = profile.piece_of(x[-1:])
    for k, column in ((0, y), (1, v), (2, a)):
        column[-1] = profile.derivative(x[-1:], k, last)[0]
    return HermiteTable(profile, x, y, v, a, hermite_errors(profile, x, y, v, a),
                        tolerance, limit)


def table_for_tolerance(profile: CamProfile, tolerance: float,
                        limit: int = MAX_POINTS) -> HermiteTable:
    """The fewest points (from the breakpoints up, by doubling then bisection) whose
    position error is at most ``tolerance`` * |stroke|; clipped to ``limit``."""
    if not (tolerance > 0.0 and math.isfinite(tolerance)):
        raise ValueError(f"the tolerance must be positive, got {tolerance!r}")
    fewest = fewest_points(profile)
    if limit < fewest:
        raise ValueError(f"an XYVA table of this profile needs at least {fewest} points")
    low, high = fewest - 1, fewest
    table = table_of(profile, high, limit, tolerance)
    while not table.met:
        if high >= limit:
            needed = _needed(profile, tolerance, limit)
            return HermiteTable(profile, table.master, table.slave, table.velocity,
                                table.acceleration, table.errors, tolerance, limit,
                                clipped=True, needed=needed)
        low, high = high, min(limit, 2 * high)
        table = table_of(profile, high, limit, tolerance)
    while high - low > 1:
        middle = (low + high) // 2
        trial = table_of(profile, middle, limit, tolerance)
        if trial.met:
            high, table = middle, trial
        else:
            low = middle
    return table


def _needed(profile: CamProfile, tolerance: float, limit: int) -> int | None:
    """The fewest points past ``limit`` that meet the tolerance (None past 16 limits)."""
    low, high = limit, 2 * limit
    while not table_of(profile, high, MAX_POINTS, tolerance).met:
        if high > 16 * limit:
            return None
        low, high = high, 2 * high
    while high - low > 1:
        middle = (low + high) // 2
        if table_of(profile, middle, MAX_POINTS, tolerance).met:
            high = middle
        else:
            low = middle
    return high
