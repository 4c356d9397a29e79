"""The motor (crank) motion from an output motion, through dead points (seed 003).

A linkage gives s = f(theta) and its exact derivatives f', f'', f''' (the protocol in
:mod:`sizer.mechanics.linkages`). Away from a dead point the chain rule inverts:

    s_dot = f' theta_dot,  s_ddot = f'' theta_dot^2 + f' theta_ddot,
    s_dddot = f''' theta_dot^3 + 3 f'' theta_dot theta_ddot + f' theta_dddot.

At a dead point f' = 0 and this is 0/0 (eqs. 5, 14). The 1-DOF form of the paper's
results follows from the same identities with f' = 0 and one more derivative,
s'''' = f'''' theta_dot^4 + 6 f''' theta_dot^2 theta_ddot + 3 f'' theta_ddot^2
+ 4 f'' theta_dot theta_dddot + f' theta_ddddot:

    theta_dot^2 = s_ddot / f''                                  (eqs. 26-27)
    theta_ddot = (s_dddot - f''' theta_dot^3) / (3 f'' theta_dot)  (eq. 49), s_ddot != 0
    theta_ddot^2 = s'''' / (3 f'')   when s_ddot = s_dddot = 0    (eq. 60)

They are the paper's with n = 1, q^d = theta, q^i = s, phi = s - f(theta): m = 1,
k = -f'', S = -3 f'', R = -f'''/f'' (:mod:`dead_points`). For its slider-crank at the
top dead centre (theta = 0, e = 0) f'' = -r (r + l) / l and f''' = 0, so
theta_dot^2 = -l s_ddot / (r (r + l)) (eq. 33), theta_ddot = -l s_dddot /
(3 sqrt(-s_ddot r l (r + l))) (eq. 53, with the jerk: docs/errata.md) and
theta_ddot^2 = -l s'''' / (3 r (r + l)) (eq. 61). The rod's eqs. 34, 54, 62 follow from
l sin q2 = r sin q1, whose derivatives at q1 = q2 = 0 give q2_dot = (r / l) q1_dot and
q2_ddot = (r / l) q1_ddot.

Feasibility (secs. 4.1, 4.2.1, 4.2.2, 7): theta_dot ~ sqrt(s_ddot), so through a dead point
s_ddot must be continuous (the law C2) and of the sign of f'' (at the top of the stroke
s_ddot < 0); when s_ddot = 0 there, theta_ddot ~ s_dddot / theta_dot is infinite unless
s_dddot = 0 too (C3): :func:`dead_point_crossings`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from sizer.errors import UserError
from sizer.mechanics.linkages import Linkage, outside_range

DEAD_ZONE = 1e-3
"""Angular distance |f'/f''| (rad) to a dead point under which the limit forms replace
the chain rule. The crank angle found from s alone is only good to ~eps |s| / (|f''| d)
at a distance d (s is flat there), and the chain rule's theta_ddot divides that error by
d^2 (measured on slider-cranks: 6e-2 relative at d = 1e-4, 3e-5 at 1e-3); the limit
forms neglect f' theta_dddot, an error ~d (measured: 4e-6 at 1e-4, 4e-5 at 1e-3). The
two meet near d = 1e-3 at ~4e-5 (tests/test_inverse_motion.py pins the bound)."""

THIRD_ZONE = 0.05
"""Angular distance (rad) to a dead point under which theta_dddot is interpolated
(linear in the crank angle) from the samples just outside: the chain rule divides the
errors of theta_ddot by d again (measured 8e-4 relative at d = 0.01 to 0.03, 2e-5 at
0.03 to 0.1), and its limit needs the output's fourth and fifth derivatives.
theta_dddot only feeds the jerk."""

def output_motion(linkage: Linkage, theta: np.ndarray, theta1: np.ndarray,
                  theta2: np.ndarray, theta3: np.ndarray
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """s and its first three time derivatives from the crank's (mode (a)), by the chain
    rule with the linkage's exact f', f'', f''' (module docstring)."""
    theta = np.asarray(theta, dtype=float)
    w1, w2, w3 = (np.asarray(x, dtype=float) for x in (theta1, theta2, theta3))
    f0, f1, f2, f3 = (linkage.output(theta, k) for k in range(4))
    s1 = f1 * w1
    s2 = f2 * w1 ** 2 + f1 * w2
    s3 = f3 * w1 ** 3 + 3.0 * f2 * w1 * w2 + f1 * w3
    return f0, s1, s2, s3


@dataclass(frozen=True)
class _Visit:
    """The output at an end of its range: samples ``before`` (last moving toward it,
    or None at the start) and ``after`` (first moving away, or None at the end)."""

    before: int | None
    after: int | None
    top: bool


def _visits(linkage: Linkage, s: np.ndarray, s1: np.ndarray,
            s2: np.ndarray) -> list[_Visit]:
    """Where the sampled output reaches an end of its range (a dead point): a reversal
    of s_dot whose extreme (the samples', or s - s_dot^2 / (2 s_ddot) from the two
    samples beside it) is within 0.5 |f''| DEAD_ZONE^2 of the end, the output's gap at
    DEAD_ZONE of crank angle from the dead point; or a start or an end there."""
    low, high = linkage.output_range()
    dead = linkage.dead_points()
    value, curvature = linkage.output(dead), np.abs(linkage.output(dead, 2))
    # within DEAD_ZONE of the crank angle the limit forms hold: a reversal there is a pass
    top_tol = 0.5 * float(curvature[np.argmax(value)]) * DEAD_ZONE ** 2
    bottom_tol = 0.5 * float(curvature[np.argmin(value)]) * DEAD_ZONE ** 2
    scale = float(np.max(np.abs(s1))) if s1.size else 0.0
    moving = np.sign(s1) * (np.abs(s1) > 1e-12 * scale)
    nz = np.flatnonzero(moving)

    def at_top(value: float) -> bool:
        return value >= high - top_tol

    def at_bottom(value: float) -> bool:
        return value <= low + bottom_tol

    visits: list[_Visit] = []
    if nz.size == 0:
        return visits
    first, last = int(nz[0]), int(nz[-1])
    if first > 0 or abs(s1[0]) <= 1e-12 * scale:
        if moving[first] < 0 and at_top(s[0]):
            visits.append(_Visit(None, first, True))
        elif moving[first] > 0 and at_bottom(s[0]):
            visits.append(_Visit(None, first, False))
    turns = np.flatnonzero(moving[nz[1:]] != moving[nz[:-1]])  # s_dot reverses
    for a, b in zip(nz[turns], nz[turns + 1], strict=True):
        a, b = int(a), int(b)
        peak = [*s[a:b + 1]]
        for i in (a, b):  # the extreme between samples, from the Taylor expansion
            if s2[i] != 0.0 and np.sign(s2[i]) != moving[a]:
                peak.append(s[i] - s1[i] ** 2 / (2.0 * s2[i]))
        if moving[a] > 0 and at_top(max(peak)):
            visits.append(_Visit(a, b, True))
        elif moving[a] < 0 and at_bottom(min(peak)):
            visits.append(_Visit(a, b, False))
    if last < s.size - 1 or abs(s1[-1]) <= 1e-12 * scale:
        if moving[last] > 0 and at_top(s[-1]):
            visits.append(_Visit(last, None, True))
        elif moving[last] < 0 and at_bottom(s[-1]):
            visits.append(_Visit(last, None, False))
    return visits


def _check_range(linkage: Linkage, s: np.ndarray) -> None:
    low, high = linkage.output_range()
    value = outside_range(s, low, high)
    if value is not None:
        raise UserError(f"the motion needs the output at {value:g}, outside the "
                        f"linkage's range [{low:g}, {high:g}]", field="output")


def input_motion(linkage: Linkage, s: np.ndarray, s1: np.ndarray, s2: np.ndarray,
                 s3: np.ndarray, start_theta: float, *, s4: np.ndarray | None = None,
                 direction: int = 1
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The crank angle and its first three time derivatives for the output samples
    s, s_dot, s_ddot, s_dddot (in time order), mode (b).

    ``start_theta`` is the crank angle at the first sample: it fixes the half-turn
    (``linkage.input_of``) and the turning direction. The crank keeps turning the same
    way through each dead point (the half flips when the output reverses at an end of
    its range) and reverses where the output reverses inside it. ``direction`` (+1:
    theta increasing) is used only when ``start_theta`` is itself a dead point. The
    angle is continuous (unwrapped) and starts at ``start_theta``.

    Within DEAD_ZONE of a dead point the limit forms (module docstring) replace the
    chain rule: theta_dot and theta_ddot from the roots of f'' x^2 - s_ddot x
    + s_dot (s_dddot - f''' theta_dot^3) / (3 f'') = 0 (x = theta_dot^2; the identities
    above with f' = s_dot / theta_dot and f' theta_dddot neglected), exact at the dead
    point and consistent on both sides of it. Where s_ddot = s_dddot = 0 at the dead
    point, theta_ddot = +-sqrt(s'''' / (3 f'')) (eq. 60; decelerating before, accelerating
    after), with s'''' from ``s4`` or estimated from the neighbouring samples as
    s_dddot^2 / (2 s_ddot) (exact for a quartic). A law that breaks the paper's rules
    gets theta_ddot = +-inf there: check :func:`dead_point_crossings` first.

    UserError (field "output") if a sample is outside the output's range, (field
    "start_theta") if the output at ``start_theta`` is not the first sample."""
    s, s1, s2, s3 = (np.atleast_1d(np.asarray(x, dtype=float)) for x in (s, s1, s2, s3))
    _check_range(linkage, s)
    low, high = linkage.output_range()
    span = high - low
    start = float(start_theta)
    at_start = float(linkage.output(np.array([start]))[0])
    if abs(at_start - s[0]) > 1e-6 * span:
        raise UserError(f"the crank angle {start:g} rad gives the output {at_start:g}, "
                        f"not the motion's first position {s[0]:g}", field="start_theta")
    f1_start = float(linkage.output(np.array([start]), 1)[0])
    f2_start = float(linkage.output(np.array([start]), 2)[0])
    if abs(f1_start) > DEAD_ZONE * abs(f2_start):
        half0 = 1 if f1_start > 0 else -1
    else:
        half0 = int(direction) * (1 if f2_start > 0 else -1)

    n = s.size
    half = np.full(n, half0, dtype=int)
    for visit in _visits(linkage, s, s1, s2):
        if visit.before is not None and visit.after is not None:
            half[visit.after:] *= -1
    raw = np.concatenate([linkage.input_of(s[half == h], h) for h in (1, -1)])
    order = np.concatenate([np.flatnonzero(half == h) for h in (1, -1)])
    theta = np.empty(n)
    theta[order] = raw
    theta = np.unwrap(theta)
    theta += 2.0 * np.pi * np.round((start - theta[0]) / (2.0 * np.pi))

    f1, f2, f3 = (linkage.output(theta, k) for k in (1, 2, 3))
    # the crank's turning direction: s_dot / f' while moving, held through rests
    still = np.abs(s1) <= 1e-12 * _scale(s1)  # as in _visits: round-off is rest
    turning = np.sign(s1) * half
    turning[still] = 0
    held = np.where(turning != 0, np.arange(n), -1)
    held = np.maximum.accumulate(held)
    turning = np.where(held >= 0, turning[np.maximum(held, 0)], int(direction))

    with np.errstate(divide="ignore", invalid="ignore"):
        w1 = s1 / f1
        w2 = (s2 - f2 * w1 ** 2) / f1
        w3 = (s3 - f3 * w1 ** 3 - 3.0 * f2 * w1 * w2) / f1
    distance = np.abs(f1) / np.maximum(np.abs(f2), 1e-300)
    near = distance < DEAD_ZONE
    if np.any(near):
        w1[near], w2[near] = _near_dead_point(
            s1[near], s2[near], s3[near], f2[near], f3[near], turning[near],
            _snap(s2, s3, s4, near, _scale(s2)), _scale(s2), _scale(s3), still[near],
            np.arange(n)[near] == n - 1)
    _bridge(theta, w3, distance < THIRD_ZONE)
    return theta, w1, w2, w3


def _bridge(theta: np.ndarray, w3: np.ndarray, zone: np.ndarray) -> None:
    """theta_dddot over each run of samples in ``zone``, linear in the crank angle
    between the samples just outside it (in the sample index if the angle does not
    move; held at an end of the motion; 0 if every sample is in the zone)."""
    n = zone.size
    if not np.any(zone):
        return
    if np.all(zone):
        w3[:] = 0.0
        return
    edges = np.diff(np.concatenate([[0], zone.astype(int), [0]]))
    for first, stop in zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1),
                           strict=True):
        before, after = first - 1, stop
        run = slice(first, stop)
        if before < 0:
            w3[run] = w3[after]
        elif after >= n:
            w3[run] = w3[before]
        else:
            span = theta[after] - theta[before]
            if abs(span) > 1e-12:
                frac = (theta[run] - theta[before]) / span
            else:
                frac = (np.arange(first, stop) - before) / (after - before)
            w3[run] = w3[before] + frac * (w3[after] - w3[before])


def _scale(x: np.ndarray) -> float:
    return float(np.max(np.abs(x))) if x.size else 0.0


def _snap(s2: np.ndarray, s3: np.ndarray, s4: np.ndarray | None, near: np.ndarray,
          scale2: float) -> np.ndarray:
    """s'''' at the samples ``near``: given, or s_dddot^2 / (2 s_ddot) at the nearest
    sample where s_ddot is not negligible (a law with s_ddot = s_dddot = 0 at the dead
    point has s_ddot ~ s'''' tau^2 / 2 and s_dddot ~ s'''' tau beside it)."""
    if s4 is not None:
        return np.atleast_1d(np.asarray(s4, dtype=float))[near]
    usable = np.flatnonzero(np.abs(s2) > 1e-9 * max(scale2, 1e-300))
    out = np.zeros(int(np.count_nonzero(near)))
    if usable.size == 0:
        return out
    for j, i in enumerate(np.flatnonzero(near)):
        nearest = usable[np.argmin(np.abs(usable - i))]
        out[j] = s3[nearest] ** 2 / (2.0 * s2[nearest])
    return out


def _near_dead_point(s1: np.ndarray, s2: np.ndarray, s3: np.ndarray, f2: np.ndarray,
                     f3: np.ndarray, turning: np.ndarray, snap: np.ndarray,
                     scale2: float, scale3: float, resting: np.ndarray,
                     last: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """theta_dot, theta_ddot by the limit forms (input_motion's docstring)."""
    p = s2 / f2
    w1 = turning * np.sqrt(np.maximum(p, 0.0))
    for _ in range(3):  # the f''' theta_dot^3 term, by fixed-point iteration
        c = s1 * (s3 - f3 * w1 ** 3) / (3.0 * f2 ** 2)
        x = np.maximum(0.5 * (p + np.sqrt(np.maximum(p * p - 4.0 * c, 0.0))), 0.0)
        w1 = turning * np.sqrt(x)
    w2 = np.empty_like(w1)
    moving = w1 != 0.0
    w2[moving] = (s3[moving] - f3[moving] * w1[moving] ** 3) / (3.0 * f2[moving] * w1[moving])
    # at rest at the dead point: s_ddot = 0 there
    rest = ~moving
    flat = np.abs(s3) <= 1e-9 * max(scale3, 1e-300)
    calm = rest & flat
    # the side of the dead point: after it (accelerating) when moving away from the
    # extreme (s_dot of the sign of f''), or resting there and not the last sample
    away = np.sign(s1) * np.sign(f2) > 0
    after = np.where(resting, np.where(last, -1.0, 1.0), np.where(away, 1.0, -1.0))
    w2[calm] = (after * turning * np.sqrt(np.maximum(snap / (3.0 * f2), 0.0)))[calm]
    wild = rest & ~flat  # s_ddot = 0 with a jerk: the infinite crank acceleration
    w2[wild] = np.where(np.sign(s3[wild]) * turning[wild] * np.sign(f2[wild]) < 0,
                        -np.inf, np.inf)
    return w1, w2


@dataclass(frozen=True)
class DeadPointIssue:
    """A dead point the output law cannot pass (seed 003 secs. 4.1, 4.2, 7)."""

    time: float
    kind: str
    """"discontinuous" (s_ddot jumps), "sign" (s_ddot of the sign the geometry
    forbids) or "jerk" (s_ddot = 0 with a non-zero jerk)."""
    message: str


ACC_TOL = 1e-6
"""A one-sided acceleration or jerk is 0, and two are equal, within this fraction of
the law's largest (from the caller's one-sided values)."""

SAMPLED_TOL = 1e-3
"""The same when the one-sided values are extrapolated from the samples (the error of a
second-order Taylor step over a sample interval)."""


def dead_point_crossings(linkage: Linkage, t: np.ndarray, s: np.ndarray, s1: np.ndarray,
                         s2: np.ndarray, s3: np.ndarray,
                         left: tuple[np.ndarray, np.ndarray] | None = None,
                         right: tuple[np.ndarray, np.ndarray] | None = None,
                         units: str = "m", periodic: bool = False) -> list[DeadPointIssue]:
    """The places where the sampled output motion reaches a dead point (an end of the
    output's range with s_dot = 0) and breaks the paper's rules: s_ddot continuous there
    (the law C2), non-zero and of the sign of f'' at the dead point (below 0 at the top
    of the range, above 0 at the bottom), or else 0 with a zero jerk (C3).

    ``left`` and ``right`` are the one-sided (s_ddot, s_dddot) at every sample, for a
    piecewise law whose pieces meet at a sample (e.g. a knot at the dead point); without
    them the one-sided values at the dead point are extrapolated from the samples on
    each side. Outside the samples the output is at rest (s_ddot = s_dddot = 0), so a
    motion that starts or ends at a dead point is judged against rest, and a rest at a
    dead point inside the motion splits into an arrival and a departure; with
    ``periodic`` the samples are one period and the first follows the last.
    ``units`` names the output's unit ("m", or "rad" for a rocker).
    UserError (field "output") if a sample is outside the output's range."""
    t, s, s1, s2, s3 = (np.atleast_1d(np.asarray(x, dtype=float)) for x in (t, s, s1, s2, s3))
    _check_range(linkage, s)
    n = s.size
    given = left is not None and right is not None
    lo_acc, lo_jerk = hi_acc, hi_jerk = s2, s3
    if left is not None and right is not None:
        lo_acc, lo_jerk = np.asarray(left[0], float), np.asarray(left[1], float)
        hi_acc, hi_jerk = np.asarray(right[0], float), np.asarray(right[1], float)
    tol = ACC_TOL if given else SAMPLED_TOL
    scale_a = max(_scale(s2), 1e-300)
    scale_j = max(_scale(s3), 1e-300)
    dead = linkage.dead_points()
    f2_dead = linkage.output(dead, 2)
    low, high = linkage.output_range()
    top_curvature = float(f2_dead[np.argmax(linkage.output(dead))])
    bottom_curvature = float(f2_dead[np.argmin(linkage.output(dead))])
    scale_v = max(_scale(s1), 1e-300)
    issues: list[DeadPointIssue] = []
    for visit in _visits(linkage, s, s1, s2):
        extreme = high if visit.top else low
        first = 0 if visit.before is None else visit.before + 1
        last = n - 1 if visit.after is None else visit.after - 1
        resting = [i for i in range(first, last + 1)
                   if abs(s[i] - extreme) <= 1e-12 * (high - low) and abs(s1[i]) <= 1e-9 * scale_v]
        # (s_ddot, s_dddot) arriving and leaving
        if visit.before is None:
            arrive = (float(lo_acc[-1]), float(lo_jerk[-1])) if periodic else (0.0, 0.0)
            if given and not periodic:
                arrive = (float(lo_acc[0]), float(lo_jerk[0]))
        elif resting and given:
            arrive = (float(lo_acc[resting[0]]), float(lo_jerk[resting[0]]))
        else:
            arrive = _one_sided(t, s2, s3, visit.before, -1, _crossing_time(
                t, s1, s2, visit) if not resting else float(t[resting[0]]))
        if visit.after is None:
            leave = (float(hi_acc[0]), float(hi_jerk[0])) if periodic else (0.0, 0.0)
            if given and not periodic:
                leave = (float(hi_acc[-1]), float(hi_jerk[-1]))
        elif resting and given:
            leave = (float(hi_acc[resting[-1]]), float(hi_jerk[resting[-1]]))
        else:
            leave = _one_sided(t, s2, s3, visit.after, 1, _crossing_time(
                t, s1, s2, visit) if not resting else float(t[resting[-1]]))
        if resting and t[resting[-1]] > t[resting[0]]:  # a rest at the dead point
            still = (float(s2[resting[0]]), float(s3[resting[0]]))
            events = [(float(t[resting[0]]), arrive, still),
                      (float(t[resting[-1]]), still, leave)]
        else:
            time = float(t[resting[0]]) if resting else _crossing_time(t, s1, s2, visit)
            events = [(time, arrive, leave)]
        curvature = top_curvature if visit.top else bottom_curvature
        for time, before, after in events:
            issue = _judge(time, before, after, curvature, tol * scale_a, tol * scale_j,
                           units)
            if issue is not None:
                issues.append(issue)
    return issues


def _judge(time: float, before: tuple[float, float], after: tuple[float, float],
           curvature: float, tol_a: float, tol_j: float,
           units: str) -> DeadPointIssue | None:
    """The paper's rule at one dead point from the one-sided (s_ddot, s_dddot)."""
    when = f"at the dead point at t = {time:.6g} s"
    if abs(before[0] - after[0]) > tol_a:
        return DeadPointIssue(time, "discontinuous", (
            f"acceleration discontinuous {when} ({before[0]:+.4g} {units}/s^2 before, "
            f"{after[0]:+.4g} {units}/s^2 after): the crank's speed would jump; the law "
            "must be C2 there"))
    a = 0.5 * (before[0] + after[0])
    if abs(a) > tol_a:
        if np.sign(a) != np.sign(curvature):
            need = "below 0" if curvature < 0 else "above 0"
            return DeadPointIssue(time, "sign", (
                f"acceleration {a:+.4g} {units}/s^2 {when}: the geometry needs it {need}"))
        return None
    worst = max(before[1], after[1], key=abs)
    if abs(worst) > tol_j:
        return DeadPointIssue(time, "jerk", (
            f"acceleration 0 with jerk {worst:.4g} {units}/s^3 {when}: the crank's "
            "acceleration is infinite; the jerk must be 0 too (C3)"))
    return None


def _crossing_time(t: np.ndarray, s1: np.ndarray, s2: np.ndarray, visit: _Visit) -> float:
    """The time of the dead point between two samples: the root of s_dot's cubic Hermite
    interpolant (values s_dot, slopes s_ddot) on that interval."""
    from scipy.interpolate import CubicHermiteSpline

    a, b = visit.before, visit.after
    if a is None or b is None:
        return float(t[a if b is None else b])
    if t[b] <= t[a]:
        return float(t[a])
    roots = CubicHermiteSpline([t[a], t[b]], [s1[a], s1[b]], [s2[a], s2[b]]).roots(
        extrapolate=False)
    roots = roots[np.isfinite(roots)]
    if roots.size:
        return float(roots[0])
    return float(t[a] - s1[a] * (t[b] - t[a]) / (s1[b] - s1[a]))


def _one_sided(t: np.ndarray, s2: np.ndarray, s3: np.ndarray, i: int, step: int,
               time: float) -> tuple[float, float]:
    """(s_ddot, s_dddot) at ``time`` from sample i on one side (``step`` -1: before, +1:
    after): a Taylor step, the jerk's slope from the next sample outward."""
    j = i + step
    slope = 0.0
    if 0 <= j < t.size and t[j] != t[i]:
        slope = (s3[i] - s3[j]) / (t[i] - t[j])
    tau = time - t[i]
    return float(s2[i] + s3[i] * tau + 0.5 * slope * tau * tau), float(s3[i] + slope * tau)
