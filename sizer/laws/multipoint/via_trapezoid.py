"""The trapezoidal trajectory through a sequence of points (book sec. 3.2.4, Example 3.4).

Kind ``via_trapezoid`` (the book's "trapezoidal trajectory through a sequence of points",
Fig. 3.5). Every segment q_{k-1} -> q_k is the rest-to-rest trapezoid of sec. 3.2, eq.
(3.4), over T_k = t_k - t_{k-1} with an acceleration period T_a,k:

    v_k = h_k / (T_k - T_a,k),   a_k = v_k / T_a,k,   h_k = q_k - q_{k-1}.

Stopping at every via-point (``blend: false``, Fig. 3.5a) is the concatenation of these
trapezoids: q(t_k) = q_k with null velocity. Sec. 3.2.4 avoids the stops by
"anticipating" segment k + 1: it starts at t_k - T'_a,k, before segment k has ended, and
the velocity and acceleration profiles of the two are added (``blend: true``, Fig. 3.5b).
The book leaves T'_a,k open; here it is min(T_a,k, T_a,k+1), the longest overlap in
which only the deceleration of segment k and the acceleration of segment k + 1 meet. With
one T_a for all segments the overlap is a parabolic blend of duration T_a with constant
acceleration (v_k+1 - v_k) / T_a, between the linear tracts of the two segments; each
linear tract is the line through (tau_k-1, q_k-1) and (tau_k, q_k), tau_k the middle of
the blend, and the trajectory passes at q_k + (v_k+1 - v_k) T_a / 8 at tau_k: it does not
go through the interior via-points, only near them. Every overlap shortens the motion:
it ends at t_n - sum_k T'_a,k (Example 3.4: "the duration T of the trajectory is
shorter"). It starts and ends at rest at q_0 and q_n, as in the book.

The acceleration periods are the book's parameters of sec. 3.2: ``acceleration_time`` T_a
(one for all segments, or a list, T_a,k <= T_k / 2), or ``acceleration`` a_a, each
T_a,k then from eq. (3.6) (which needs a_a >= 4 |h_k| / T_k^2, eq. (3.7)); neither gives
T_a,k = T_k / 3, the book's example choice (v = 3h / 2T, a = 9h / 2T^2). A dwell
between two equal via-points (h_k = 0) has T_a,k = 0: no overlap, the axis stands still
for all of T_k.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np

from sizer.errors import UserError
from sizer.laws.multipoint.fields import boolean, number, numbers, points, refuse_unknown
from sizer.numerics.arrays import sorted_unique

if TYPE_CHECKING:
    from scipy.interpolate import PPoly

KIND = "via_trapezoid"
FIELDS = ("points", "times", "positions", "acceleration_time", "acceleration", "blend")


def build_via_trapezoid(fields: Mapping[str, Any]) -> PPoly:
    """The YAML mapping of a ``via_trapezoid`` law (module docstring) as a PPoly of degree
    2 over [t_0, t_end], t_end = t_n without blends, earlier with them."""
    refuse_unknown(fields, FIELDS, KIND)
    t, q = points(fields, minimum=2)
    durations = np.diff(t)
    if "acceleration_time" in fields and "acceleration" in fields:
        raise UserError("give either acceleration_time or acceleration, not both",
                        field="acceleration")
    if "acceleration" in fields:
        acceleration = number(fields, "acceleration", positive=True)
        accel_times = acceleration_times_from_acceleration(q, durations, acceleration)
    elif "acceleration_time" in fields:
        accel_times = _acceleration_time_field(fields, len(durations))
    else:
        accel_times = durations / 3.0
    return via_trapezoid(t, q, accel_times, blend=boolean(fields, "blend", True))


def _acceleration_time_field(fields: Mapping[str, Any], segments: int) -> np.ndarray:
    raw = fields["acceleration_time"]
    if isinstance(raw, list | tuple):
        values = numbers(fields, "acceleration_time", length=segments)
        for i, value in enumerate(values):
            if not value > 0.0:
                raise UserError(f"must be positive, got {value:g}",
                                field=f"acceleration_time[{i}]")
        return values
    return np.full(segments, number(fields, "acceleration_time", positive=True))


def acceleration_times_from_acceleration(q: np.ndarray, durations: np.ndarray,
                                         acceleration: float) -> np.ndarray:
    """T_a,k of every segment from its acceleration a_a, eq. (3.6); eq. (3.7) checked.

    A segment with h_k = 0 (a dwell between two equal via-points) gets T_a,k = 0.
    """
    h = np.abs(np.diff(q))
    minimum = 4.0 * h / durations ** 2
    bad = np.flatnonzero(acceleration < minimum * (1.0 - 1e-12))
    if bad.size:
        k = int(bad[0])
        raise UserError(f"is too low for segment {k + 1} (points {k} to {k + 1}): it needs "
                        f"at least 4 |h| / T^2 = {minimum[k]:g}, eq. (3.7)",
                        field="acceleration")
    a, T = acceleration, durations
    root = np.sqrt(np.maximum(a * a * T * T - 4.0 * a * h, 0.0))
    return (a * T - root) / (2.0 * a)


def via_trapezoid(t: np.ndarray, q: np.ndarray, acceleration_times: np.ndarray, *,
                  blend: bool = True) -> PPoly:
    """The trajectory of sec. 3.2.4 through the via-points (t_k, q_k) with the
    acceleration periods T_a,k of the segments (module docstring), as a PPoly.

    Segment k starts at s_k: s_1 = t_0, s_k+1 = s_k + T_k - T'_a,k, T'_a,k =
    min(T_a,k, T_a,k+1) with ``blend`` and 0 without.
    """
    from scipy.interpolate import PPoly

    t = np.asarray(t, dtype=float)
    q = np.asarray(q, dtype=float)
    durations = np.diff(t)
    accel = np.asarray(acceleration_times, dtype=float)
    h = np.diff(q)
    if accel.shape != durations.shape:
        raise UserError(f"needs one acceleration time per segment ({len(durations)}), got "
                        f"{accel.size}", field="acceleration_time")
    too_long = np.flatnonzero(accel > 0.5 * durations * (1.0 + 1e-12))
    if too_long.size:
        k = int(too_long[0])
        raise UserError(f"T_a = {accel[k]:g} of segment {k + 1} (points {k} to {k + 1}) "
                        f"exceeds half its duration T/2 = {durations[k] / 2:g}",
                        field="acceleration_time")
    if np.any((accel <= 0.0) & (h != 0.0)):
        k = int(np.flatnonzero((accel <= 0.0) & (h != 0.0))[0])
        raise UserError(f"T_a of segment {k + 1} must be positive", field="acceleration_time")
    # A dwell (h_k = 0) has no acceleration period, so no overlap with its neighbours:
    # the motion stops there for all of T_k.
    accel = np.where(h == 0.0, 0.0, np.minimum(accel, 0.5 * durations))
    overlaps = np.minimum(accel[:-1], accel[1:]) if blend else np.zeros(len(h) - 1)
    starts = t[0] + np.concatenate(([0.0], np.cumsum(durations[:-1] - overlaps)))
    moving = h != 0.0
    s, T, Ta, hk = starts[moving], durations[moving], accel[moving], h[moving]
    cruise = hk / (T - Ta)
    a = cruise / Ta
    end = starts[-1] + durations[-1]
    breaks = sorted_unique(np.concatenate(([t[0], end], s, s + Ta, s + T - Ta, s + T)))
    # one breakpoint where two segments' ends coincide up to rounding
    breaks = breaks[np.concatenate(([True], np.diff(breaks) > 1e-12 * (end - t[0])))]
    breaks[-1] = end
    # Each interval of the union of the segments' breakpoints holds one quadratic: its
    # coefficients are the summed acceleration (constant inside), velocity and position
    # at the interval's left end, from eq. (3.4) of every segment. (Written out because
    # scipy has no sum of PPolys on different breakpoints.)
    left = breaks[:-1, None]
    middle = 0.5 * (breaks[:-1] + breaks[1:])[:, None]
    acc = np.where((middle > s) & (middle < s + Ta), a, 0.0) - np.where(
        (middle > s + T - Ta) & (middle < s + T), a, 0.0)
    u = left - s
    vel = np.select([u <= 0.0, u < Ta, u < T - Ta, u < T],
                    [0.0, a * u, cruise, a * (T - u)], 0.0)
    pos = np.select([u <= 0.0, u < Ta, u < T - Ta, u < T],
                    [0.0, 0.5 * a * u * u, cruise * (u - 0.5 * Ta),
                     hk - 0.5 * a * (T - u) ** 2], hk)
    coefficients = np.vstack((0.5 * acc.sum(axis=1), vel.sum(axis=1),
                              q[0] + pos.sum(axis=1)))
    return PPoly(coefficients, breaks, extrapolate=False)
