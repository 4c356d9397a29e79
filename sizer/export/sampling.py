"""Equidistant point tables, and the number of points an error budget needs.

The budget is the largest position error of the linearly interpolated table against the
law, as a fraction of the stroke. For a law with a bounded acceleration the classic bound
|e| <= max|y''| dx^2 / 8 gives a number of points that always meets it; the smallest
number that meets it (by the certificate, a true maximum) is then found by bisection
below it, within the target's limit. When even the limit misses the budget, the table is
clipped to the limit and says so.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from sizer.export.linear_certificate import LinearErrors, linear_errors
from sizer.export.profile import CamProfile

MAX_POINTS = 1_000_000
"""Points of a table whose target sets no limit of its own."""


@dataclass(frozen=True)
class PointTable:
    """An equidistant table over the profile's master span, with its certificate.

    ``limit`` is the target's largest number of points; ``clipped`` when the tolerance
    needed more than that and the table has ``limit`` points instead; ``tolerance`` None
    when the number of points was given."""

    profile: CamProfile
    master: np.ndarray
    slave: np.ndarray
    errors: LinearErrors
    tolerance: float | None
    limit: int
    clipped: bool = False
    needed: int | None = None
    """With ``clipped``: the points the tolerance needs (None when not known)."""

    @property
    def points(self) -> int:
        return len(self.master)

    @property
    def relative_position_error(self) -> float:
        return self.errors.position / abs(self.profile.stroke)

    @property
    def met(self) -> bool:
        """True when no tolerance was asked or the table meets it."""
        return self.tolerance is None or self.relative_position_error <= self.tolerance


def fewest_points(profile: CamProfile, per_segment: bool = False) -> int:
    """The fewest points of a table: 2, or per segment every segment's ends."""
    return len(profile.segments) + 1 if per_segment else 2


def master_values(profile: CamProfile, points: int, per_segment: bool = False
                  ) -> np.ndarray:
    """``points`` master values over [0, span]: equidistant; or ``per_segment``, every
    segment's ends, a dwell nothing else, and the other points equidistant within each
    move, shared among the moves in proportion to sqrt(|H| C_a) (the spacing that gives
    each move the same error bound; a run of a ``cycle:``, linear, has C_a = 0 and gets
    its two ends only)."""
    if points < fewest_points(profile, per_segment):
        raise ValueError(f"a table needs at least {fewest_points(profile, per_segment)} "
                         f"points")
    if not per_segment or not profile.is_cycle:
        return np.linspace(0.0, profile.span, points)
    moves = [i for i, s in enumerate(profile.segments) if s.law is not None]
    weights = np.array([math.sqrt(abs(profile.segments[i].stroke)
                                  * profile.segments[i].law.coefficients.C_a)  # type: ignore[union-attr]
                        for i in moves])
    weights = np.where(np.isfinite(weights), weights, 1.0)
    if not weights.sum() > 0.0:  # runs only (linear: exact between their ends)
        weights = np.ones_like(weights)
    interior = points - fewest_points(profile, True)
    share = interior * weights / weights.sum()
    counts = np.floor(share).astype(int)
    for k in np.argsort(-(share - counts), kind="stable")[:interior - counts.sum()]:
        counts[k] += 1
    inside = dict(zip(moves, counts, strict=True))
    parts = [np.zeros(1)]
    for i, s in enumerate(profile.segments):
        inner = inside.get(i, 0)
        end = profile.span if i == len(profile.segments) - 1 else profile.segments[i + 1].start
        parts.append(np.linspace(s.start, end, inner + 2)[1:])
    return np.concatenate(parts)


def table_of(profile: CamProfile, points: int, limit: int = MAX_POINTS,
             tolerance: float | None = None, per_segment: bool = False) -> PointTable:
    """The table of ``points`` points (:func:`master_values`), certified."""
    x = master_values(profile, points, per_segment)
    y = profile.position(x)
    return PointTable(profile, x, y, linear_errors(profile, x, y), tolerance, limit)


def table_for_tolerance(profile: CamProfile, tolerance: float,
                        limit: int = MAX_POINTS, per_segment: bool = False) -> PointTable:
    """The table of the fewest points (found by bisection; equidistant, or per segment:
    :func:`master_values`) whose position error is at most ``tolerance`` * |stroke|;
    clipped to ``limit`` points when that is not enough."""
    if not (tolerance > 0.0 and math.isfinite(tolerance)):
        raise ValueError(f"the tolerance must be positive, got {tolerance!r}")

    fewest = fewest_points(profile, per_segment)
    if limit < fewest:
        raise ValueError(f"a table of this profile needs at least {fewest} points")

    def certified(n: int, most: int = limit) -> PointTable:
        return table_of(profile, n, most, tolerance, per_segment)

    # |e| <= max|y''| dx^2 / 8 on an equidistant table of spacing dx
    peak = profile.peak_acceleration
    budget = tolerance * abs(profile.stroke)
    estimate = (math.ceil(profile.span * math.sqrt(peak / (8.0 * budget))) + 1
                if math.isfinite(peak) else 2)
    high = max(fewest, min(estimate, limit))
    table = certified(high)
    while not table.met:  # the bound holds for C1 laws; grow otherwise
        if high >= limit:
            return PointTable(profile, table.master, table.slave, table.errors, tolerance,
                              limit, clipped=True, needed=_needed(certified, estimate,
                                                                  limit))
        high = min(limit, max(high + 1, 2 * high))
        table = certified(high)
    low = fewest - 1  # a table of `low` points misses (too few: no table)
    while high - low > 1:
        middle = (low + high) // 2
        trial = certified(middle)
        if trial.met:
            high, table = middle, trial
        else:
            low = middle
    return table


def _needed(certified, estimate: int, limit: int) -> int | None:
    """The fewest points past ``limit`` that meet the tolerance (by bisection below the
    bound's estimate), or None when the estimate is past MAX_POINTS or misses it."""
    if estimate <= limit or estimate > MAX_POINTS:
        return None
    if not certified(estimate, MAX_POINTS).met:
        return None
    low, high = limit, estimate  # `limit` points miss
    while high - low > 1:
        middle = (low + high) // 2
        if certified(middle, MAX_POINTS).met:
            high = middle
        else:
            low = middle
    return high
