"""A move through a linkage at the load (issue 14, seed 003): a position-dependent ratio,
alone with its dwell or in a cycle of segments (issue 12's cycles).

The motion of the move has a fixed shape over normalized time u = t/T (book sec. 5.2):
with the law on the crank, theta(u) = theta_0 + h q_N(u); with the law on the output,
s(u) = s_0 + h q_N(u) and the crank follows by inverse kinematics, through the dead
points by the paper's limits (sizer.mechanics.linkages.inverse_motion). The torque the
crank needs is tau_c(u; T) = A(u)/T^2 + D(u)/T + B(u) by Lagrange, with the d(J_eq)/dq
term (sizer.mechanics.linkages.dynamics). Computed once per law and start angle
(:func:`profile_of`) on a fixed grid: composite Gauss-Legendre nodes for the integrals
(RMS), a uniform grid of PEAK_POINTS points plus the law's breakpoints for the peaks.

Per candidate (:class:`LinkageCalculator`), the gear stages between motor and crank
(ratio N, efficiency eta in the direction of power flow, their inertia) give the motor's
speed N theta'(u)/T and torque (J_m + J_stages) N theta''(u)/T^2 + tau_c/(N eta^{+-1}):
peaks and the speed-torque envelope over the samples, the RMS over the cycle with the
dwell holding the output's static load. A law that breaks the paper's dead-point rule is
infeasible for every candidate, with its reason (check ``dead_point``).

In a cycle (:class:`LinkageCycle`) each move starts where the crank stopped, so it has its
own profile; a dwell holds the output's static load at the crank angle reached. With the
law on the crank a run turns the crank at its constant speed and a move may start and end
at its neighbours' crank speeds (its shape, the law's boundary form, depends on its fixed
duration: :class:`FixedShape`). The free durations scale with one factor s (book sec.
5.2): peaks are the largest over the segments, the RMS torque sums the segments' exact
squares over the cycle time.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import lru_cache
from typing import Any, NamedTuple, Self

import numpy as np

from sizer.envelope import RegionTable
from sizer.errors import UserError
from sizer.laws import MotionLaw
from sizer.laws.per_move import RankedLaw
from sizer.laws.quadrature import gauss_legendre
from sizer.mechanics.disc_cam import CamStage
from sizer.mechanics.drive import Drive
from sizer.mechanics.linkages import outside_range
from sizer.model.cycle import Cycle, Move, Run, from_task, shorthand_task
from sizer.model.domain import Design, Limits, LinkageStage, Load, Task
from sizer.numerics.arrays import sorted_unique
from sizer.numerics.roots import bracketed_root, quadratic_roots
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.checks import evaluate_checks, worst_slack
from sizer.sizing.cycle import (
    CycleRmsModel,
    cycle_laws,
    given_scale,
    rms_floor,
    segment_load,
)
from sizer.sizing.evaluation import CycleMetrics, CyclePiece, SegmentPart, held_piece, rms_of_powers
from sizer.sizing.move import rule_speed
from sizer.sizing.shortest_duration import mechanical_answer

PEAK_POINTS = 4001
"""Uniform samples of u in [0, 1] where the peaks are read (with the law's breakpoints):
a smooth peak is read to about (1/4000)^2 of its curvature, 1e-7 relative."""
GAUSS_PIECES = 128
"""Composite Gauss-Legendre: sub-intervals of [0, 1] (split at the law's breakpoints)."""
GAUSS_NODES = 8
"""Nodes per sub-interval: exact for polynomials of degree 15 in each."""
EXTRA_GAP = 1e-12
"""An extra breakpoint (a table's knot crossed) this close (in u) to another cut is that
cut: a kink at rounding's distance from a sample is sampled."""


@dataclass(frozen=True)
class LinkageProfile:
    """A move through a linkage over normalized time u (T = 1), the same for every
    candidate: the samples, the crank's motion, the output's, the crank torque's parts and
    the static crank torque holding the output at the end; ``issues`` are the reasons the
    law breaks the dead-point rule (empty: none)."""

    u: np.ndarray
    weights: np.ndarray
    theta: np.ndarray
    ratio: np.ndarray
    """ds/dtheta at the samples: the linkage's transmission ratio (m/rad or rad/rad)."""
    s: np.ndarray
    theta1: np.ndarray
    theta2: np.ndarray
    s1: np.ndarray
    s2: np.ndarray
    s3: np.ndarray
    inertial: np.ndarray
    damping: np.ndarray
    steady: np.ndarray
    hold: float
    turn: float
    output_mass: float
    load: Load
    max_inertia: float
    issues: tuple[str, ...]
    jumps: np.ndarray
    """The samples (a mask over u) at and beside the law's breakpoints, where its
    acceleration (and so the torque) may jump (:func:`jump_mask`): no parabola is read
    through them (:func:`profile_max`)."""


def _grid(law: MotionLaw | FixedShape | CamTurn, extra: np.ndarray | None = None
          ) -> tuple[np.ndarray, np.ndarray]:
    """Sample points of [0, 1] and their quadrature weights (0 for the peak-only ones);
    ``extra`` breakpoints (a position table's knot crossings) split the quadrature and are
    peak samples as the law's are."""
    breaks = law.breakpoints
    if extra is not None and extra.size:  # none within rounding of another cut: no
        # piece of zero width (a knot reached at a move's end up to rounding)
        base = sorted_unique(np.concatenate((breaks, np.linspace(0.0, 1.0, GAUSS_PIECES + 1))))
        extra = sorted_unique(extra)
        near = np.abs(extra[:, None] - base[None, :]).min(axis=1) <= EXTRA_GAP
        apart = np.concatenate(([True], np.diff(extra) > EXTRA_GAP))
        breaks = np.concatenate((breaks, extra[~near & apart]))
    cuts = sorted_unique(np.concatenate((breaks, np.linspace(0.0, 1.0, GAUSS_PIECES + 1))))
    x, w = gauss_legendre(GAUSS_NODES)
    left, width = cuts[:-1, None], np.diff(cuts)[:, None]
    nodes = (left + 0.5 * width * (x + 1.0)).ravel()
    weights = (0.5 * width * w).ravel()
    peaks = sorted_unique(np.concatenate((np.linspace(0.0, 1.0, PEAK_POINTS), breaks,
                                      _beside(law.breakpoints))))
    u = np.concatenate((nodes, peaks))
    order = np.argsort(u, kind="stable")  # in time order, as the inverse kinematics needs
    return u[order], np.concatenate((weights, np.zeros(len(peaks))))[order]


def _beside(breakpoints: np.ndarray) -> np.ndarray:
    """The points one rounding step either side of each interior breakpoint: the law's
    acceleration may jump there, and the one sample at the breakpoint holds one side's
    value; these hold both (peak samples, no quadrature weight)."""
    b = np.asarray(breakpoints, dtype=float)
    inner = b[(b > 0.0) & (b < 1.0)]
    return np.concatenate((np.nextafter(inner, 0.0), np.nextafter(inner, 1.0)))


def jump_mask(law: MotionLaw | FixedShape | CamTurn, u: np.ndarray) -> np.ndarray:
    """The samples u at and beside the law's breakpoints (:func:`_beside`), where the
    torque may jump: no parabola is read through them (:func:`profile_max`)."""
    b = np.asarray(law.breakpoints, dtype=float)
    return np.isin(u, np.concatenate((b, _beside(b))))


@dataclass(frozen=True)
class FixedShape:
    """The normalized shape q_N(u) of a segment whose shape depends on its (fixed)
    duration, for :func:`profile_of`: a run (``spec`` None: q_N = u, the crank at constant
    speed) or a move with boundary speeds, the law ``spec``'s boundary form
    (sizer.laws.boundary_speeds) with normalized boundary speeds s0 = v0 T / h,
    s1 = v1 T / h and accelerations r0 = a0 T^2 / h, r1 = a1 T^2 / h."""

    spec: str | None = None
    s0: float = 0.0
    s1: float = 0.0
    r0: float = 0.0
    r1: float = 0.0

    @property
    def breakpoints(self) -> np.ndarray:
        return np.array([0.0, 1.0]) if self.spec is None else self._basis().breaks

    def derivative(self, u: np.ndarray, order: int = 0) -> np.ndarray:
        u = np.asarray(u, dtype=float)
        if self.spec is None:
            return u.copy() if order == 0 else np.full(u.shape, float(order == 1))
        r = (self.r0, self.r1) if (self.r0 or self.r1) else (None, None)
        return self._basis().derivative(u, order, self.s0, self.s1, r0=r[0], r1=r[1])[0]

    def _basis(self):
        from sizer.laws.boundary_speeds import boundary_form

        basis = boundary_form(self.spec)
        if basis is None:
            raise UserError(f"{self.spec} has no form with boundary speeds", field="laws")
        return basis


@lru_cache(maxsize=256)
def profile_of(stage: LinkageStage, load: Load, h: float, duration: float | None,
               law: MotionLaw | FixedShape | CamTurn) -> LinkageProfile:
    """The profile of a move of ``h`` by ``law`` from the stage's start angle (cached)."""
    from sizer.mechanics.linkages.dynamics import LinkageDynamics, LinkageMasses
    from sizer.mechanics.linkages.inverse_motion import input_motion, output_motion
    from sizer.mechanics.linkages.of_stage import linkages_of

    views = linkages_of(stage)
    theta0 = stage.start_angle
    # the coordinate the law is on: the driven link's (law_on: crank) or the load's
    given = views.motor if stage.law_on == "crank" else views.output
    x0 = float(given.output(np.array([theta0]))[0])
    table = load.table if load.table is not None and load.table.active else None
    crossings = None
    if table is not None:  # its knots' crossings are breakpoints (output_table_load)
        crossings = crossings_of(_output_position(views, given, x0, h, law, theta0),
                                 law.breakpoints, table.knots)
    u, weights = _grid(law, crossings)
    q = [law.derivative(u, k) for k in range(4)]
    issues: tuple[str, ...] = ()
    x = [x0 + h * q[0], h * q[1], h * q[2], h * q[3]]
    if not given.dead_points().size:  # the law is on the crank angle itself
        theta = x
    else:
        # a run or a move with boundary speeds is on the crank (sizer.io.linkage says so)
        assert isinstance(law, MotionLaw), "a fixed shape is on the crank, no dead point"
        _within_range(given, law, x[0])
        issues = _issues(given, law, u, x, h, duration)
        with np.errstate(all="ignore"):
            theta = list(input_motion(given, x[0], x[1], x[2], x[3], start_theta=theta0,
                                      direction=stage.direction))
    with np.errstate(all="ignore"):
        s = x if given is views.output else list(output_motion(views.output, *theta))
        motor = theta if views.crank_driven else list(output_motion(views.motor, *theta))
    spring = (getattr(stage, "spring_rate", 0.0), getattr(stage, "spring_preload", 0.0))
    masses = LinkageMasses(crank_inertia=stage.crank_inertia, output_inertia=load.inertia,
                           link_mass_at_crank=stage.link_mass_at_crank,
                           link_mass_at_output=stage.link_mass_at_output,
                           load=load.torque, friction=load.friction, damping=load.damping,
                           spring_rate=spring[0], spring_preload=spring[1])
    crank_radius = stage.lengths[0]
    rocker_length = None if stage.kind == "slider_crank" else stage.lengths[2]
    joint = None if views.joint == views.output else views.joint
    dynamics = LinkageDynamics(views.output, masses, crank_radius=crank_radius,
                               rocker_length=rocker_length, joint=joint)
    with np.errstate(all="ignore"):
        parts = dynamics.time_scaling_parts(theta[0], theta[1], theta[2])
    inertial, damping, steady = parts.inertial, parts.damping, parts.steady
    end = theta[0][-1:]  # u is in time order
    held = load.torque
    if table is not None:  # the output's force of its position, F(s) ds/dtheta
        _check_table_span(load, np.asarray(s[0]), views.output.output_linear)
        with np.errstate(all="ignore"):
            steady = steady + views.output.output(theta[0], 1) * table.torque(s[0])
        held = held + float(table.torque(views.output.output(end, 0))[0])
    if spring[0] or spring[1]:  # a cam's follower spring (sizer.mechanics.disc_cam)
        held = held + spring[1] + spring[0] * float(views.output.output(end, 0)[0])
    hold = float(views.output.output(end, 1)[0] * held)
    grid = np.linspace(-np.pi, np.pi, 721)
    max_inertia = float(np.max(dynamics.inertia(grid)))
    if views.crank_driven:
        turn = float(theta[0][-1] - theta[0][0])
        ratio = views.output.output(_finite(theta[0]), 1)
    else:  # the torque at the rocker: the crank's over dq3/dq1 (virtual work)
        g1 = views.motor.output(_finite(theta[0]), 1)
        issues += _rocker_issues(u, g1, (inertial, damping, steady), hold,
                                 float(views.motor.output(end, 1)[0]), duration)
        inertial, damping, steady = (_over(x, g1) for x in (inertial, damping, steady))
        hold = static_torque(stage, held, float(end[0]))
        hold = hold if math.isfinite(hold) else 0.0  # unbounded: the issue says so
        turn = float(np.sum(np.abs(np.diff(motor[0]))))
        ratio = _over(views.output.output(_finite(theta[0]), 1), g1)
        with np.errstate(all="ignore"):
            reflected = dynamics.inertia(theta[0]) / g1**2
        max_inertia = float(np.max(reflected[np.isfinite(reflected)], initial=0.0))
    fields = (u, weights, _finite(theta[0]), _finite(ratio), s[0], _finite(motor[1]),
              _finite(motor[2]), s[1], s[2], s[3], _finite(inertial), _finite(damping),
              _finite(steady), hold, turn, dynamics.output_side_inertia, load, max_inertia,
              issues)
    jumps = jump_mask(law, u)
    if crossings is not None:  # the force's kinks: no parabola through them (peaks)
        return PositionProfile(*fields, jumps=jumps, kinks=np.isin(u, crossings))
    return LinkageProfile(*fields, jumps=jumps)


def _output_position(views: Any, given: Any, x0: float, h: float,
                     law: MotionLaw | FixedShape | CamTurn, theta0: float) -> Any:
    """The output's position over normalized time u of a move of ``h`` from the crank
    angle theta0: the law's coordinate itself (law_on: output), else the output of the
    crank at theta0 + h q_N(u) (a crank turned by the motor: output_table_load refuses a
    table with the law on a driven rocker)."""
    if given is views.output:
        return lambda u: x0 + h * law.derivative(u, 0)
    return lambda u: views.output.output(theta0 + h * law.derivative(u, 0), 0)


def output_table_load(stage: LinkageStage, load: Load) -> Load:
    """The load with its force (torque) table of the output's position (docs/position-
    loads.md: the output's travel from where the cycle starts, at the stage's start
    angle, plus the table's offset) read at the output's own coordinate (its offset
    less the output's position at the start), as the profiles read it. A table needs the
    crank turned by the motor or the law on the output."""
    table = load.table
    if table is None or not table.active:
        return load
    from sizer.mechanics.linkages.of_stage import linkages_of

    if isinstance(stage, CamStage) or (stage.law_on == "crank"
                                       and stage.driven_link != "crank"):
        raise UserError("a table of the output's position through a disc cam, or with the "
                        "law on a driven rocker, is not supported", field="load")
    start = float(linkages_of(stage).output.output(np.array([stage.start_angle]), 0)[0])
    return replace(load, table=replace(table, offset=table.offset - start))


def static_torque(stage: LinkageStage, torque: float, theta: float) -> float:
    """The torque at the driven link holding the output's constant load ``torque`` at
    crank angle theta: s'(theta) F, over dq3/dq1 for a driven rocker (inf where that is 0
    and the load is not)."""
    from sizer.mechanics.linkages.of_stage import linkages_of

    views = linkages_of(stage)
    at = np.array([theta])
    crank = float(views.output.output(at, 1)[0] * torque)
    if views.crank_driven:
        return crank
    g1 = float(views.motor.output(at, 1)[0])
    if crank == 0.0:
        return 0.0
    return crank / g1 if g1 != 0.0 else math.inf


ROCKER_TOL = 1e-6
"""The crank's torque at a dead point of a driven rocker is 0 within this fraction of its
largest over the move (each of its parts A, D, B)."""


def _over(x: np.ndarray, g1: np.ndarray) -> np.ndarray:
    """x / g1 with the samples where g1 = 0 (a dead point of the driven rocker, where x
    must be 0 too: :func:`_rocker_issues`; within its round-off) interpolated from their
    neighbours."""
    with np.errstate(all="ignore"):
        out = np.asarray(x, dtype=float) / g1
    bad = ~np.isfinite(out) | (np.abs(g1) <= 1e-9 * max(float(np.max(np.abs(g1))), 1e-300))
    if np.any(bad) and not np.all(bad):
        index = np.arange(out.size)
        out[bad] = np.interp(index[bad], index[~bad], out[~bad])
    return out


def _rocker_issues(u: np.ndarray, g1: np.ndarray, parts: tuple, hold: float,
                   g1_end: float, duration: float | None) -> tuple[str, ...]:
    """Where the driven rocker reaches a dead point (dq3/dq1 = 0: crank and coupler in
    line) the motor's torque, the crank's over dq3/dq1, is unbounded unless the crank's
    torque is 0 there (each part for every duration): the rocker cannot push the crank
    through, only let it coast. Also the output's load held at the end on a dead point."""
    T = duration or 1.0
    scale = [max(float(np.max(np.abs(x))), 1e-300) for x in parts]
    worst = max(float(np.max(np.abs(g1))), 1e-300)
    zero = np.abs(g1) <= 1e-9 * worst
    cross = np.flatnonzero((np.sign(g1[:-1]) * np.sign(g1[1:]) < 0) & ~zero[:-1] & ~zero[1:])
    found = []
    for i in np.flatnonzero(zero):
        found.append((float(u[i]), [float(x[i]) for x in parts]))
    for i in cross:
        f = g1[i] / (g1[i] - g1[i + 1])
        found.append((float(u[i] + f * (u[i + 1] - u[i])),
                      [float(x[i] + f * (x[i + 1] - x[i])) for x in parts]))
    issues: list[str] = []
    for at, values in sorted(found):
        if all(abs(v) <= ROCKER_TOL * s for v, s in zip(values, scale, strict=True)):
            continue
        a, d, b = values
        tau = a / T**2 + d / T + b
        issues.append(f"the motor on the rocker cannot drive the crank through its dead "
                      f"point (crank and coupler in line) at t = {at * T:.6g} s: the crank "
                      f"needs {tau:+.4g} N*m there and the rocker's ratio dq3/dq1 is 0, so "
                      f"the motor's torque is unbounded; only a crank coasting through it "
                      f"(no acceleration, no load) passes"
                      + ("" if duration else " (for a move of 1 s)"))
        break
    if abs(g1_end) <= 1e-9 * worst and abs(hold) > 0.0:
        issues.append(f"the motor on the rocker cannot hold the output's load at the dead "
                      f"point where the move ends (the crank needs {hold:+.4g} N*m, the "
                      f"rocker's ratio is 0)")
    return tuple(issues)


def _one_sided(law: MotionLaw, u: np.ndarray, h: float, T: float
               ) -> tuple[tuple[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]:
    """The output's (acceleration, jerk) just before and just after every sample: where
    the law's pieces join they differ; outside [0, 1] the law is at rest."""
    starts = np.array([piece.start for piece in law.pieces])
    last = len(law.pieces) - 1
    after = np.clip(np.searchsorted(starts, u, side="right") - 1, 0, last)
    before = np.clip(np.searchsorted(starts, u, side="left") - 1, 0, last)

    def values(index: np.ndarray, order: int) -> np.ndarray:
        out = np.empty(len(u))
        for i in sorted_unique(index):
            mask = index == i
            out[mask] = law.piece_derivative(int(i), u[mask], order)
        return h * out / T**order

    left = [values(before, k) for k in (2, 3)]
    right = [values(after, k) for k in (2, 3)]
    for k, (outside_before, outside_after) in enumerate(law.outside(order) for order in (2, 3)):
        left[k][0] = h * outside_before / T ** (k + 2)
        right[k][-1] = h * outside_after / T ** (k + 2)
    return (left[0], left[1]), (right[0], right[1])


def _within_range(linkage, law: MotionLaw, s: np.ndarray) -> None:
    """Refuse a law whose output positions ``s`` leave the linkage's range: sizer.io
    keeps the stroke from start_angle inside it, so the law's own excursion past its
    ends (q_N outside [0, 1]) takes it there. Located at the law, with the farthest
    position and by how much (the range's end alone would print as the position)."""
    low, high = linkage.output_range()
    if outside_range(s, low, high) is None:
        return
    unit = "m" if linkage.output_linear else "rad"
    below, above = low - float(np.min(s)), float(np.max(s)) - high
    side, far, end = (("below", float(np.min(s)), low) if below >= above
                      else ("above", float(np.max(s)), high))
    raise UserError(f"{law.spec} takes the output to {far:.6g} {unit}, {abs(far - end):.3g} "
                    f"{unit} {side} the end {end:.6g} {unit} of the linkage's range "
                    f"[{low:.6g}, {high:.6g}] {unit}: the law's position leaves [0, 1] "
                    "(it overshoots its stroke) where the stroke reaches that end; give a "
                    "law that stays within its stroke, or start away from the end",
                    field="laws")


def _issues(linkage, law: MotionLaw, u: np.ndarray, s: list,
            h: float, duration: float | None) -> tuple[str, ...]:
    """The paper's rule at every dead point the output reaches, in the move's own time
    and units (for a shortest-duration task, at T = 1 s: the verdict does not depend on
    T, the values scale with it)."""
    from sizer.mechanics.linkages.inverse_motion import dead_point_crossings

    T = duration or 1.0
    scaled = [s[0], *(x / T**k for k, x in enumerate(s[1:], start=1))]
    left, right = _one_sided(law, u, h, T)
    found = dead_point_crossings(linkage, u * T, scaled[0], scaled[1], scaled[2], scaled[3],
                                 left, right, units="m" if linkage.output_linear else "rad")
    suffix = "" if duration else " (for a move of 1 s; the values scale with its duration)"
    return tuple(issue.message + suffix for issue in found)


def _finite(x: np.ndarray) -> np.ndarray:
    """The samples where the motion is singular (a law that breaks the dead-point rule)
    read 0: the verdict is the dead-point check's, no inf or NaN reaches a result."""
    x = np.asarray(x, dtype=float)
    return np.where(np.isfinite(x), x, 0.0)


@dataclass(frozen=True)
class LinkageRms:
    """The motor's RMS torque through a linkage near the durations it was built at
    (:meth:`LinkageCalculator.powers`), with the task's dwell holding ``hold``: the form
    of sizer.sizing.move.RmsModel, so the RMS crossing
    (sizer.sizing.shortest_duration.rms_crossing_with_rms) finds where the RMS check
    binds in a few rounds instead of a search on the evaluated slack."""

    powers: np.ndarray
    dwell: float
    hold: np.ndarray

    def rms(self, T: np.ndarray, index: np.ndarray | None = None) -> np.ndarray:
        c = self.powers if index is None else self.powers[:, index]
        hold = self.hold if index is None else self.hold[index]
        return rms_of_powers(c, T, 1, self.dwell, hold)


class LinkageCalculator:
    """The requirements of one law through a linkage for each candidate at durations T
    (a sizer.sizing.evaluation.CycleModel)."""

    segmented = True

    def __init__(self, profile: LinkageProfile, task: Task, drive: Drive,
                 motors: MotorArrays, thermal_rule: str, law: MotionLaw | None) -> None:
        self.profile, self.task, self.drive, self.motors = profile, task, drive, motors
        self.thermal_rule, self.law = thermal_rule, law
        self._start: tuple[Limits, np.ndarray] | None = None  # search_start's

    def reported(self, metrics: CycleMetrics) -> np.ndarray:
        """The duration a result reports: the one :meth:`evaluate` gives."""
        return metrics.duration

    def dead_point_issues(self) -> tuple[str, ...]:
        return self.profile.issues

    def given_scale(self) -> float:
        assert self.task.duration is not None, "a given duration"
        return self.task.duration

    def law_move(self) -> None:
        return None  # no closed form (sizer.sizing.evaluation.CycleModel)

    def cycle_time(self, T: np.ndarray) -> np.ndarray:
        return np.asarray(T, dtype=float) + self.task.dwell

    def scale_of(self, duration: np.ndarray) -> np.ndarray:
        """The move durations T themselves (:meth:`evaluate` reports T)."""
        return np.asarray(duration, dtype=float)

    def segments(self, T: np.ndarray) -> list[LinkagePart]:
        """The move at durations T and, where the task has one, its dwell holding the
        output's static load."""
        p = self.profile
        out = [LinkagePart("move", "move", self.law, p, T, move_calculator(self, p))]
        if self.task.dwell > 0.0:
            out.append(LinkagePart("dwell", "dwell", None, HeldDwell(p.hold, abs(p.load.torque)),
                                   np.full_like(T, self.task.dwell), None))
        return out

    def pieces(self, s: np.ndarray, samples: int | None = None) -> list[CyclePiece]:
        """The move and its dwell sampled (:func:`linkage_pieces`), the dwell's torque
        with the sign of the static load it holds."""
        out = linkage_pieces(self, s, samples)
        sign = np.sign(self.profile.hold)
        return out[:1] + [replace(p, torque=p.torque * sign) for p in out[1:]]

    def breakdown(self, s: np.ndarray) -> list[SegmentPart]:
        return linkage_breakdown(self, s)

    def take(self, index: np.ndarray) -> LinkageCalculator:
        return LinkageCalculator(self.profile, self.task, self.drive.take(index),
                                 self.motors.subset(index), self.thermal_rule, self.law)

    def peak_bound(self, limits: Limits) -> np.ndarray:
        """The search start where it is the shortest duration (:func:`answer_bound`)."""
        return answer_bound(self, limits, self.search_start(limits))

    def speed_bound(self, limits: Limits) -> np.ndarray:
        """The duration where the motor's peak speed, N max|theta'(u)| / T (read as
        :meth:`evaluate` reads it), reaches the speed limit with its margin: the speed
        check's slack is 0 there and negative below (inf: no duration meets it)."""
        p, N = self.profile, self.drive.ratio
        fastest = profile_max(np.abs(N[:, None] * p.theta1), p)  # at T = 1
        limit = (1.0 - limits.speed_margin) * self.motors.speed_limit
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(limit > 0.0, fastest / limit, np.inf)

    def search_start(self, limits: Limits) -> np.ndarray:
        """The larger of the speed bound and the peak floor (:func:`peak_floor`): below
        it the speed or the peak check fails, from it on the peak check passes (inf: no
        duration passes them); computed once per calculator and limits."""
        if self._start is None or self._start[0] is not limits:
            self._start = (limits, peak_floor(self, limits, self.speed_bound(limits)))
        return self._start[1]

    def rms_lower_bound(self) -> None:
        return None  # none known through a linkage (sizer.sizing.evaluation.CycleModel)

    def initial_guess(self) -> np.ndarray:
        """A duration from the speed bound and the inertial bound at the peak torque."""
        p, motors, N = self.profile, self.motors, self.drive.ratio
        speed = np.max(np.abs(p.theta1)) * N / np.maximum(motors.speed_limit, 1e-300)
        tau_p = np.maximum(motors.intermittent.torques.max(axis=1), 1e-300)
        inertial = np.max(np.abs(p.inertial)) / N + (motors.inertia + self.drive.
                                                     transmission_inertia) * N * \
            np.max(np.abs(p.theta2))
        guess = np.maximum(speed, np.sqrt(inertial / tau_p))
        return np.where(np.isfinite(guess) & (guess > 0.0), guess, 1.0)

    def motor_samples(self, duration: np.ndarray
                      ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(motor speed, motor torque, crank torque) at the profile's samples for each
        candidate's duration: arrays (candidates, samples)."""
        return self._motor_samples(self._crank(duration))

    def _motor_samples(self, state: tuple[np.ndarray, ...]
                       ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """:meth:`motor_samples` from the crank's state at the durations (:meth:`_crank`)."""
        p = self.profile
        T, N, eta, rotor, crank, driving = state
        torque = rotor * N * p.theta2 / T**2 + np.where(driving, crank / (N * eta),
                                                         crank * eta / N)
        return N * p.theta1 / T, torque, crank

    def _crank(self, duration: np.ndarray) -> tuple[np.ndarray, ...]:
        """(T, N, eta, the rotor's and stages' inertia, the crank torque, where the power
        flows from the motor) at the durations, as (candidates, 1) columns and
        (candidates, samples) arrays."""
        p, motors, drive = self.profile, self.motors, self.drive
        T = np.broadcast_to(np.asarray(duration, dtype=float), (len(motors),))[:, None]
        N, eta = drive.ratio[:, None], drive.efficiency[:, None]
        rotor = (motors.inertia + drive.transmission_inertia)[:, None]
        crank = p.inertial / T**2 + p.damping / T + p.steady
        return T, N, eta, rotor, crank, crank * p.theta1 >= 0.0

    def powers(self, duration: np.ndarray) -> np.ndarray:
        """The motor's int tau^2 dt over the move near the durations T0 = ``duration``, as
        c_3/T^3 + c_2/T^2 + c_1/T + c_0 + c_(-1) T (sizer.sizing.move.RmsModel.powers):
        at each sample the torque is A/T^2 + B/T + C (A the inertias, B the damping, C the
        static load, through the gearbox's efficiency in the power flow's direction at T0,
        held), so T int (A/T^2 + B/T + C)^2 du gives the five integrals. Exact at T0;
        near it off only at the samples where the crank torque changes sign between the
        two durations (the torque is small there: 1e-7 relative at 1 % from T0 in the
        bundled press cycle, tests/test_linkage_rms_model.py)."""
        return self._powers(self._crank(duration))

    def _powers(self, state: tuple[np.ndarray, ...]) -> np.ndarray:
        """:meth:`powers` from the crank's state at the durations (:meth:`_crank`)."""
        p = self.profile
        _, N, eta, rotor, _, driving = state
        through = np.where(driving, 1.0 / (N * eta), eta / N)
        A = rotor * N * p.theta2 + through * p.inertial
        B, C = through * p.damping, through * p.steady
        w = p.weights
        return np.stack([(A * A) @ w, 2.0 * ((A * B) @ w), (B * B + 2.0 * A * C) @ w,
                         2.0 * ((B * C) @ w), (C * C) @ w])

    def evaluate(self, duration: np.ndarray, peaks: bool = True, model: bool = False,
                 rms: np.ndarray | None = None) -> CycleMetrics:
        """The requirements at ``duration`` (every one sampled: ``peaks`` and ``rms``
        change nothing), with ``model`` the RMS model there (:class:`LinkageRms`); the
        crank's torques computed once for both."""
        state = self._crank(duration)
        metrics = self._sampled(duration, state)[0]
        if not model:
            return metrics
        curve = LinkageRms(self._powers(state), self.task.dwell,
                           held_torque(self.profile.hold, self.drive, len(self.motors)))
        return replace(metrics, rms_model=curve)

    def sampled(self, duration: np.ndarray
                ) -> tuple[CycleMetrics, np.ndarray, np.ndarray]:
        """:meth:`evaluate` and the samples it read: (metrics, motor speed, torque)."""
        return self._sampled(duration, self._crank(duration))

    def _sampled(self, duration: np.ndarray, state: tuple[np.ndarray, ...]
                 ) -> tuple[CycleMetrics, np.ndarray, np.ndarray]:
        """:meth:`sampled` from the crank's state at the durations (:meth:`_crank`)."""
        p, motors, drive = self.profile, self.motors, self.drive
        T = np.broadcast_to(np.asarray(duration, dtype=float), (len(motors),))[:, None]
        speed, torque, crank = self._motor_samples(state)
        dwell = self.task.dwell
        hold = held_torque(p.hold, drive, len(motors))
        cycle = T[:, 0] + dwell
        square = T[:, 0] * (torque**2 @ p.weights) + dwell * hold**2
        load = p.load
        force = (p.output_mass * p.s2 / T**2 + load.damping * p.s1 / T + load.torque
                 + load.friction * np.sign(p.s1))
        kinks = getattr(p, "kinks", None)
        if kinks is not None and load.table is not None:  # a force table at the output
            force = force + load.table.torque(p.s)
        stage_torque, stage_speed = self._stages(crank, T)
        metrics = CycleMetrics(
            duration=T[:, 0], max_speed=profile_max(np.abs(speed), p),
            peak_torque=profile_max(np.abs(torque), p, jumping=True),
            peak_ratio=peak_ratio(motors, torque, speed),
            rms_torque=np.sqrt(square / cycle), thermal_speed=self.thermal_speed(T[:, 0]),
            load_speed=np.max(np.abs(p.s1)) / T[:, 0],
            load_acceleration=np.max(np.abs(p.s2)) / T[:, 0] ** 2,
            load_jerk=np.max(np.abs(p.s3)) / T[:, 0] ** 3,
            load_torque=profile_max(np.abs(force), p, jumping=True),
            stage_peak=[np.max(np.abs(x), axis=1) for x in stage_torque],
            stage_rms=[np.sqrt(T[:, 0] * (x**2 @ p.weights) / cycle) for x in stage_torque],
            stage_speed=stage_speed)
        if dwell > 0.0 and bool(np.any(hold > 0.0)):  # the dwell holds it (as move.py does)
            at_rest = peak_ratio(motors, hold[:, None], np.zeros((len(motors), 1)))
            held, _ = self._stages(np.full((len(motors), 1), abs(p.hold)), T)
            metrics = replace(metrics, peak_torque=np.maximum(metrics.peak_torque, hold),
                              peak_ratio=np.maximum(metrics.peak_ratio, at_rest),
                              stage_peak=[np.maximum(x, h[:, 0]) for x, h in
                                          zip(metrics.stage_peak, held, strict=True)])
        return metrics, speed, torque

    def thermal_speed(self, T: np.ndarray) -> np.ndarray:
        """The speed the continuous region is read at: the peak (book), RMS or mean."""
        p, N = self.profile, self.drive.ratio
        cycle = T + self.task.dwell
        # the profile's crank speed is per unit T: w = N theta1 / T over the move
        return rule_speed(self.thermal_rule, N * np.max(np.abs(p.theta1)) / T,
                          N**2 * float(p.theta1**2 @ p.weights) / T, N * abs(p.turn), cycle)

    def _stages(self, crank: np.ndarray, T: np.ndarray):
        """Each gear stage's output torque (the crank torque reflected through the
        stages after it; their own inertia and losses left out) and peak input speed."""
        ratios = self.drive.input_ratios
        torques, speeds = [], []
        peak = np.max(np.abs(self.profile.theta1))
        for stage, into in zip(self.drive.stages, ratios, strict=True):
            after = into / stage.ratio
            torques.append(crank / after[:, None])
            speeds.append(into * peak / T[:, 0])
        return torques, speeds


def peak_ratio(motors: MotorArrays, torque: np.ndarray, speed: np.ndarray) -> np.ndarray:
    """The largest |tau| / tau_int(|speed|) over each candidate's samples (candidates,
    samples): infinite where a torque meets a zero limit. Read only at the samples that
    may hold it (:func:`_contenders`): those of the candidates with few, together; the
    others' all."""
    region = motors.intermittent
    keep = _contenders(region, torque, speed)
    if keep is None:
        return _ratio(region, torque, speed)
    narrow = keep.sum(axis=1) <= keep.shape[1] // 8
    out = np.empty(len(torque))
    for rows, few in ((np.flatnonzero(narrow), True), (np.flatnonzero(~narrow), False)):
        if len(rows):
            columns = np.flatnonzero(keep[rows].any(axis=0)) if few else slice(None)
            out[rows] = _ratio(region.take(rows), torque[rows][:, columns],
                               speed[rows][:, columns])
    return out


def _ratio(region: RegionTable, torque: np.ndarray, speed: np.ndarray) -> np.ndarray:
    """:func:`peak_ratio` at every sample given."""
    with np.errstate(divide="ignore", invalid="ignore"):
        limit = region.limit_clipped(speed)
        ratio = np.where(limit > 0.0, np.abs(torque) / limit,
                         np.where(torque == 0.0, 0.0, np.inf))
    return np.max(ratio, axis=1)


PRUNE_MARGIN = 1e-9
"""Relative margin of :func:`_contenders`' threshold, far above the rounding of a ratio."""


def _contenders(region: RegionTable, torque: np.ndarray, speed: np.ndarray
                ) -> np.ndarray | None:
    """Per candidate the samples where its |tau| / tau_int(|speed|) may be its largest
    (None: few samples, all of them). Its ratio at its largest |tau| is a lower bound R
    of its largest, and its limit over the speeds it reaches is at least L, the least of
    the piecewise-linear region at 0, at its corners up to the fastest sample and there;
    a sample with |tau| < R L (1 - PRUNE_MARGIN) has a ratio below R."""
    n, m = torque.shape
    if m < 64:
        return None
    magnitude = np.abs(torque)
    top = np.argmax(magnitude, axis=1)[:, None]
    fastest = np.minimum(np.max(np.abs(speed), axis=1), region.max_speed)
    with np.errstate(divide="ignore", invalid="ignore"):
        first = np.take_along_axis(magnitude, top, 1)[:, 0] / \
            region.limit_clipped(np.take_along_axis(speed, top, 1))[:, 0]
        ends = region.limit(np.stack((np.zeros(n), fastest), axis=1)).min(axis=1)
        corners = np.where(region.speeds <= fastest[:, None], region.torques, np.inf)
        least = np.minimum(ends, corners.min(axis=1))
        threshold = first * least * (1.0 - PRUNE_MARGIN)
    usable = np.isfinite(threshold) & (least > 0.0)  # elsewhere every sample is kept
    return magnitude >= np.where(usable, threshold, -np.inf)[:, None]


def refined_max(values: np.ndarray, u: np.ndarray, kinks: np.ndarray | None = None,
                jumps: np.ndarray | None = None) -> np.ndarray:
    """The largest value of each row of samples at the increasing points u, refined by
    a parabola through three neighbouring samples (a smooth peak between samples is then
    read to the third order of their spacing, not the second).

    Without ``kinks`` the parabola through the largest sample and its two neighbours.
    With ``kinks`` (a mask: samples where the values have a kink) a parabola is read only
    through three samples whose middle one is not a kink (smooth between them), centred on
    the largest sample or either neighbour (a smooth peak beside a kink); ``jumps`` (a
    mask: samples where the values may jump, the one sample holding one side's value) are
    kinks that may not be an end of the three either. The parabola centred on the largest
    sample where it is valid (its neighbours' extrapolate: each overshoots by about the
    third derivative times the spacing cubed, and the largest of them would be kept)."""
    m = values.shape[1]
    rows = np.arange(values.shape[0])
    top_i = np.argmax(values, axis=1)
    best = values[rows, top_i]  # the largest (NaN where a row has one, as np.max)
    centred = np.zeros(len(rows), dtype=bool)
    for shift in ((0,) if kinks is None else (0, -1, 1)):
        i = np.minimum(np.maximum(top_i + shift, 1), m - 2)  # np.clip's ~10 us a call
        x0, x1, x2 = u[i - 1], u[i], u[i + 1]
        f0, f1, f2 = values[rows, i - 1], values[rows, i], values[rows, i + 1]
        d01 = (f1 - f0) / (x1 - x0)
        curvature = ((f2 - f1) / (x2 - x1) - d01) / (x2 - x0)
        with np.errstate(divide="ignore", invalid="ignore"):
            # p(x) = f0 + d01 (x - x0) + c (x - x0)(x - x1): p'(x*) = 0
            vertex = 0.5 * (x0 + x1) - d01 / (2.0 * curvature)
            top = f0 + d01 * (vertex - x0) + curvature * (vertex - x0) * (vertex - x1)
        inside = (curvature < 0.0) & (vertex > x0) & (vertex < x2) & np.isfinite(top) \
            & ~centred
        if kinks is not None:
            inside &= ~kinks[i]
        if jumps is not None:
            inside &= ~jumps[i - 1] & ~jumps[i + 1]
        best = np.where(inside, np.maximum(best, top), best)
        if shift == 0:
            centred = inside
    return best


def profile_max(values: np.ndarray, p: LinkageProfile, jumping: bool = False
                ) -> np.ndarray:
    """:func:`refined_max` of samples on the profile ``p``'s grid: its law's breakpoints
    (``p.jumps``) and a position table's knot crossings (``kinks`` of a
    :class:`PositionProfile`) are kinks; ``jumping`` (a torque: the law's acceleration may
    jump at its breakpoints) the breakpoints are jumps too. A speed is continuous there,
    so its kinks may be a parabola's ends."""
    kinks = getattr(p, "kinks", None)
    every = p.jumps if kinks is None else p.jumps | kinks
    return refined_max(values, p.u, every, p.jumps if jumping else None)


def crank_drive(design: Design, drive: Drive, profile: LinkageProfile) -> Drive:
    """The drive of the gear stages with the linkage's largest equivalent inertia at
    the crank as their load (for the inertia ratio: the worst over a turn)."""
    load = replace(design.load, inertia=profile.max_inertia, damping=0.0, friction=0.0,
                   torque=0.0)
    stage = design.transmission.linkage
    options = tuple(t if t.linkage is stage else replace(t, linkage=stage)
                    for t in drive.transmissions)  # a cam's, resolved per law
    return Drive(load, options, drive.option)


def linkage_calculator(design: Design, law: MotionLaw, motors: MotorArrays, drive: Drive
                       ) -> LinkageCalculator | LinkageCycle:
    """The calculator the engine sizes a linkage design with: one move and its dwell, or
    the cycle (a task with a return is the cycle it means)."""
    task = shorthand_task(design.machine_cycle)
    design = cam_design(design, law)
    stage = design.transmission.linkage
    assert stage is not None, "a linkage design"
    design = replace(design, load=output_table_load(stage, design.load))
    if task is None or task.return_move:
        # a task with a return move is the cycle it means: the way back starts where the
        # way out stopped
        cyc = design if task is None else replace(design, machine_cycle=from_task(task))
        return LinkageCycle(cyc, law, drive, motors, design.limits.thermal_speed)
    profile = profile_of(stage, design.load, task.displacement, task.duration, law)
    return LinkageCalculator(profile, task, crank_drive(design, drive, profile),
                             motors, design.limits.thermal_speed, law)


def cam_design(design: Design, law: RankedLaw | None) -> Design:
    """The design with its cam's lift (the follower's cycle over one turn of the cam,
    each segment by its law: ``law`` where it names none) and base radius (``auto``: the
    smallest that keeps the geometry checks) resolved; any other design as it is."""
    from sizer.mechanics.disc_cam import cam_lift

    stage = design.transmission.linkage
    if not isinstance(stage, CamStage) or stage.lift is not None:
        return design
    task = shorthand_task(design.machine_cycle)
    cycle = design.machine_cycle if task is None else from_task(task)
    laws = cycle_laws(cycle, law)
    lift = cam_lift([(s.displacement, float(s.duration or 0.0), own if isinstance(
        s, Move) else None) for s, own in zip(cycle.segments, laws, strict=True)])
    total = math.fsum(float(s.duration or 0.0) for s in cycle.segments)
    load = design.load
    cam = _resolved(stage, lift, 2.0 * math.pi / total,
                    (load.inertia, load.torque, load.friction, load.damping))
    return replace(design, transmission=replace(design.transmission, linkage=cam),
                   machine_cycle=cycle)


@lru_cache(maxsize=64)
def _resolved(stage: CamStage, lift: Any, speed: float,
              load: tuple[float, float, float, float]) -> CamStage:
    """sizer.mechanics.disc_cam.resolved, once per cam, lift and load (an ``auto`` base
    radius is a search)."""
    from sizer.mechanics.disc_cam import resolved

    return resolved(stage, lift, speed, load)


@dataclass(frozen=True)
class CamTurn:
    """The cam's turn through a segment at its constant speed (q_N = u), sampled at the
    follower's law's breakpoints too (``breaks``; None: a dwell)."""

    breaks: np.ndarray | None = None

    @property
    def breakpoints(self) -> np.ndarray:
        return np.array([0.0, 1.0]) if self.breaks is None else np.asarray(self.breaks)

    def derivative(self, u: np.ndarray, order: int = 0) -> np.ndarray:
        u = np.asarray(u, dtype=float)
        return u.copy() if order == 0 else np.full(u.shape, float(order == 1))

    def __hash__(self) -> int:
        return hash(None if self.breaks is None else tuple(np.asarray(self.breaks).tolist()))

    def __eq__(self, other: object) -> bool:
        return isinstance(other, CamTurn) and hash(self) == hash(other)


def result_calculator(design: Design, motor, law: MotionLaw, transmission=None
                      ) -> LinkageCalculator | LinkageCycle:
    """The calculator of one result (a motor, a law, the result's transmission)."""
    return linkage_calculator(design, law, MotorArrays.of([motor], design.limits.envelope),
                              Drive(design.load, transmission or design.transmission))


def evaluate_linkage(design: Design, law: MotionLaw, motors: MotorArrays, drive: Drive):
    """(duration, metrics, checks, feasible) of one law through the design's linkage: the
    move's T alone, the cycle time of a cycle, each move's T of a task with a return."""
    calculator = linkage_calculator(design, law, motors, drive)
    _, metrics, checks, passed = mechanical_answer(calculator, design.limits,
                                                   design.machine_cycle.minimize)
    duration = calculator.reported(metrics)
    if design.machine_cycle.minimize:
        duration = np.where(passed, duration, np.nan)
    return duration, metrics, checks, passed


def dead_points(stage: LinkageStage) -> dict[str, float]:
    """The linkage's dead points by name: crank angles (rad), the output's, and a driven
    rocker's (crank and coupler in line)."""
    from sizer.mechanics.linkages.of_stage import linkages_of, output_name

    if isinstance(stage, CamStage):
        return {}  # the cam turns on at constant speed: no inverse kinematics
    views = linkages_of(stage)
    out: dict[str, float] = {}
    if not views.crank_driven:
        out.update(zip(("largest rocker angle", "least rocker angle"),
                       (float(x) for x in views.motor.dead_points()), strict=True))
    name = output_name(stage)
    if name == "slider_position":
        names: tuple[str, ...] = ("top dead centre", "bottom dead centre")
    else:
        word = name.split("_")[0]
        names = (f"largest {word} angle", f"least {word} angle")
    points = views.output.dead_points()
    if points.size:
        out.update(zip(names, (float(x) for x in points), strict=True))
    return out


def held_torque(hold: float, drive: Drive, n: int) -> np.ndarray:
    """The motor torque holding the static crank torque ``hold`` through the gear
    stages, |hold| / (N eta), per candidate."""
    return np.broadcast_to(abs(hold) / (drive.ratio * drive.efficiency), (n,))


@dataclass(frozen=True)
class HeldDwell:
    """A dwell on the linkage: its static crank torque (the output's load through the
    ratio at the crank angle reached; 0 at a dead point)."""

    hold: float
    force: float
    """The output's static load held (N or N*m)."""


class LinkageCycle:
    """The requirements of a cycle through a linkage for each candidate at scales s (a
    sizer.sizing.evaluation.CycleModel)."""

    segmented = True

    def __init__(self, design: Design, law: MotionLaw | None, drive: Drive,
                 motors: MotorArrays, thermal_rule: str) -> None:
        cycle = design.machine_cycle
        stage = design.transmission.linkage
        assert stage is not None
        self._setup(cycle, law, motors, thermal_rule)
        theta = stage.start_angle
        cam = stage if isinstance(stage, CamStage) and stage.lift is not None else None
        for i, (segment, own) in enumerate(zip(cycle.segments, self.laws, strict=True)):
            load = segment_load(design.load, segment)
            if cam is not None:  # the cam turns on at its speed; the law is the lift's
                fixed = float(self.fixed[i])
                profile = profile_of(replace(cam, start_angle=theta, law_on="crank"), load,
                                     cam.speed * fixed, fixed,
                                     CamTurn(own.breakpoints if own is not None else None))
                self.parts.append(profile)
                theta = float(profile.theta[-1])
            elif isinstance(segment, Move | Run):
                duration = None if np.isnan(self.fixed[i]) else float(self.fixed[i])
                shape = _shape(segment, own, duration)
                profile = profile_of(replace(stage, start_angle=theta), load,
                                     segment.displacement, duration, shape)
                self.parts.append(profile)
                theta = float(profile.theta[-1])
            else:
                force = load.torque
                if load.table is not None and load.table.active:  # F(s) where it rests
                    from sizer.mechanics.linkages.of_stage import linkages_of

                    force = force + float(load.table.torque(
                        linkages_of(stage).output.output(np.array([theta]), 0))[0])
                self.parts.append(HeldDwell(static_torque(stage, force, theta), abs(force)))
        profiles = [p for p in self.parts if isinstance(p, LinkageProfile)]
        heaviest = max(profiles, key=lambda p: p.max_inertia)
        self.drive = crank_drive(design, drive, heaviest)

    def _setup(self, cycle: Cycle, law: MotionLaw | None, motors: MotorArrays,
               thermal_rule: str) -> None:
        """What every cycle keeps besides its parts and drive: the segments' laws, free
        weights and fixed durations."""
        if cycle.share.goal is not None:
            raise UserError(f"share: {{{cycle.share.value}}} splits the cycle time for each "
                            "motor; a cycle through a linkage or against loads of the "
                            "position shares it by one rule (equal, displacement, "
                            "sqrt_displacement or weights)", field="cycle.share")
        self.cycle, self.motors, self.thermal_rule = cycle, motors, thermal_rule
        self.law = law
        self.laws = cycle_laws(cycle, law)
        self.weights = np.array(cycle.weights())
        free = cycle.free
        self.fixed = np.array([np.nan if s.duration is None or i in free else s.duration
                               for i, s in enumerate(cycle.segments)], dtype=float)
        self.parts: list[LinkageProfile | HeldDwell] = []
        self.known: dict[int, dict[str, Any]] = {}  # fixed moves: figures; free: speeds
        self.task = Task(cycle.moves[0].displacement if cycle.moves else 0.0, None,
                         linear=cycle.linear)
        self._start: tuple[Limits, np.ndarray] | None = None  # search_start's

    def dead_point_issues(self) -> tuple[str, ...]:
        """The dead-point rule broken by any move, each named by its segment."""
        out = []
        for segment, part in zip(self.cycle.segments, self.parts, strict=True):
            if isinstance(part, LinkageProfile):
                name = segment.name or "move"
                out += [f"{name}: {issue}" for issue in part.issues]
            elif not np.isfinite(part.hold):
                out.append(f"{segment.name or 'dwell'}: the motor on the rocker cannot hold "
                           f"the output's load at a dead point (crank and coupler in line)")
        return tuple(out)

    def durations(self, s: np.ndarray) -> list[np.ndarray]:
        return [np.full_like(s, fixed) if np.isfinite(fixed) else w * s
                for fixed, w in zip(self.fixed, self.weights, strict=True)]

    def reported(self, metrics: CycleMetrics) -> np.ndarray:
        """The duration a result reports: the cycle time; for a task with a return (the
        cycle it means) each move's T."""
        task = shorthand_task(self.cycle)
        if task is None or not task.return_move:
            return metrics.duration
        if task.minimize:
            return (metrics.duration - self.cycle.fixed_time) / len(self.cycle.moves)
        return np.full(len(metrics.duration), task.duration)

    def given_scale(self) -> float:
        return given_scale(self.cycle)

    def law_move(self) -> None:
        return None  # no closed form (sizer.sizing.evaluation.CycleModel)

    def cycle_time(self, s: np.ndarray) -> np.ndarray:
        s = np.asarray(s, dtype=float)
        return sum(self.durations(s), np.zeros_like(s))

    def scale_of(self, duration: np.ndarray) -> np.ndarray:
        """The scales s at cycle times ``duration``: (cycle time - fixed time) / the sum of
        the free weights (1 with none)."""
        fixed = float(np.nansum(self.fixed))
        weights = math.fsum(w for w, f in zip(self.weights, self.fixed, strict=True)
                            if not np.isfinite(f))
        if weights == 0.0:
            return np.ones_like(np.asarray(duration, dtype=float))
        return (np.asarray(duration, dtype=float) - fixed) / weights

    def segments(self, s: np.ndarray) -> list[LinkagePart]:
        """Each segment at scales s: a move or run on its profile, a dwell held."""
        out = []
        for segment, law, part, T in zip(self.cycle.segments, self.laws, self.parts,
                                         self.durations(s), strict=True):
            kind = type(segment).__name__.lower()
            move = move_calculator(self, part) if isinstance(part, LinkageProfile) else None
            out.append(LinkagePart(segment.name or kind, kind, law, part, T, move))
        return out

    def pieces(self, s: np.ndarray, samples: int | None = None) -> list[CyclePiece]:
        return linkage_pieces(self, s, samples)

    def breakdown(self, s: np.ndarray) -> list[SegmentPart]:
        return linkage_breakdown(self, s)

    def fixed_figures(self, i: int) -> dict[str, Any]:
        """The figures (:func:`linkage_figures`) of the move ``i`` of fixed duration, the
        same at every scale: computed once per calculator, its rows passed on by
        :meth:`take`."""
        if i not in self.known:
            part = self.parts[i]
            assert isinstance(part, LinkageProfile)
            self.known[i] = _move_figures(move_calculator(self, part),
                                          np.full(len(self.motors), self.fixed[i]))
        return self.known[i]

    def take(self, index: np.ndarray) -> Self:
        out = object.__new__(type(self))  # a PositionCycle's too
        out.__dict__.update(self.__dict__)
        out.motors = self.motors.subset(index)
        out.drive = self.drive.take(index)
        n = len(self.motors)

        def rows(x: Any) -> Any:
            if isinstance(x, list):
                return [rows(v) for v in x]
            return np.asarray(x)[index] if np.ndim(x) and len(x) == n else x

        out._start = None
        out.known = {i: {k: rows(v) for k, v in figures.items()}
                     for i, figures in self.known.items()}
        return out

    def peak_bound(self, limits: Limits) -> np.ndarray:
        """The search start where it is the shortest scale (:func:`answer_bound`)."""
        return answer_bound(self, limits, self.search_start(limits))

    def peak_floor(self, limits: Limits) -> np.ndarray:
        """The scale below which the speed or the peak check fails and from which on the
        peak check passes: the largest of the free moves' (:func:`peak_floor`, each from
        its speed bound) over their weights; inf where a part that does not scale (a move
        of fixed duration, a dwell's holding) fails it."""
        n = len(self.motors)
        grip = 1.0 - limits.torque_margin
        floor = np.zeros(n)
        for i, (part, w) in enumerate(zip(self.parts, self.weights, strict=True)):
            if isinstance(part, HeldDwell):
                hold = held_torque(part.hold, self.drive, n)
                fixed = peak_ratio(self.motors, hold[:, None], np.zeros((n, 1)))
            elif np.isfinite(self.fixed[i]):
                fixed = self.fixed_figures(i)["peak_ratio"]
            else:
                move = move_calculator(self, part)
                floor = np.maximum(floor, move.search_start(limits) / w)
                continue
            floor = np.where(fixed > grip, np.inf, floor)
        return floor

    def speed_bound(self, limits: Limits) -> np.ndarray:
        """The scale below which the speed check fails: the largest of the free moves'
        (LinkageCalculator.speed_bound) over their weights, the cycle's peak speed being
        the largest over its segments."""
        bound = np.zeros(len(self.motors))
        for part, w, fixed in zip(self.parts, self.weights, self.fixed, strict=True):
            if isinstance(part, LinkageProfile) and w > 0.0 and not np.isfinite(fixed):
                bound = np.maximum(bound, move_calculator(self, part).speed_bound(limits) / w)
        return bound

    def search_start(self, limits: Limits) -> np.ndarray:
        """The larger of the speed bound and the peak floor (:meth:`peak_floor`; inf: no
        scale passes them); computed once per calculator and limits."""
        if self._start is None or self._start[0] is not limits:
            self._start = (limits, self.peak_floor(limits))
        return self._start[1]

    def rms_lower_bound(self) -> np.ndarray | None:
        """Per candidate a torque the motor's RMS over the cycle exceeds at every scale
        (sizer.sizing.cycle.rms_floor): each dwell's holding torque squared (exact), 0 for
        a move."""
        n = len(self.motors)
        rates = [np.zeros(n) if isinstance(part, LinkageProfile) else
                 np.square(held_torque(part.hold, self.drive, n)) for part in self.parts]
        return rms_floor(rates, self.fixed, self.weights, n)

    def thermal_speed(self, s: np.ndarray) -> np.ndarray:
        """The thermal speed at scales s (sizer.sizing.evaluation.CycleModel) from each
        part's figures at unit duration: a free move's peak speed and int omega^2 dt go
        as 1/T, its turn stays; the fixed moves' are known (:meth:`fixed_figures`)."""
        s = np.asarray(s, dtype=float)
        n = len(self.motors)
        top, square, turn = np.zeros(n), np.zeros(n), np.zeros(n)
        N = self.drive.ratio
        for i, (part, T) in enumerate(zip(self.parts, self.durations(s), strict=True)):
            if not isinstance(part, LinkageProfile):
                continue
            if np.isfinite(self.fixed[i]):
                known = self.fixed_figures(i)
                peak, spin = known["max_speed"], known["speed_square"]
            else:
                unit = self.unit_speeds(i)
                peak, spin = unit[0] / T, unit[1] / T
            top, square = np.maximum(top, peak), square + spin
            turn = turn + N * abs(part.turn)
        return rule_speed(self.thermal_rule, top, square, turn, self.cycle_time(s))

    def unit_speeds(self, i: int) -> tuple[np.ndarray, np.ndarray]:
        """The free move ``i``'s peak motor speed and int omega^2 dt at T = 1 (as
        :func:`linkage_figures` reads them), computed once per calculator."""
        if i not in self.known:
            part = self.parts[i]
            assert isinstance(part, LinkageProfile)
            speed = self.drive.ratio[:, None] * part.theta1
            self.known[i] = {"unit": [profile_max(np.abs(speed), part),
                                      speed**2 @ part.weights]}
        return self.known[i]["unit"][0], self.known[i]["unit"][1]

    def initial_guess(self) -> np.ndarray:
        """A scale from the free moves' speed and inertial bounds."""
        guess = np.full(len(self.motors), 1e-3)
        for part, w in zip(self.parts, self.weights, strict=True):
            if isinstance(part, LinkageProfile) and w > 0.0:
                guess = np.maximum(guess, move_calculator(self, part).initial_guess() / w)
        return np.where(np.isfinite(guess) & (guess > 0.0), guess, 1.0)

    def evaluate(self, duration: np.ndarray, peaks: bool = True, model: bool = False,
                 rms: np.ndarray | None = None) -> CycleMetrics:
        """The requirements at scales ``duration`` (every one sampled: ``peaks`` and
        ``rms`` change nothing), with ``model`` the cycle's RMS model there
        (sizer.sizing.cycle.CycleRmsModel over each free move's :class:`LinkageRms`)."""
        metrics = self._evaluate(duration)
        return replace(metrics, rms_model=self._rms_model(duration)) if model else metrics

    def _rms_model(self, s: np.ndarray) -> CycleRmsModel:
        """Free moves by their models, fixed parts as constants, free dwells' holding as
        linear in s (sizer.sizing.cycle.CycleRmsModel)."""
        n = len(self.motors)
        moves, constant, hold_rate = [], np.zeros(n), np.zeros(n)
        none = np.zeros(n)
        for i, (part, w, T) in enumerate(zip(self.parts, self.weights, self.durations(s),
                                             strict=True)):
            free = not np.isfinite(self.fixed[i])
            if isinstance(part, LinkageProfile):
                if free:
                    powers = move_calculator(self, part).powers(T)
                    moves.append((LinkageRms(powers, 0.0, none), float(w)))
                else:
                    constant = constant + self.fixed_figures(i)["square"]
            else:
                hold = held_torque(part.hold, self.drive, n)
                if free:
                    hold_rate = hold_rate + hold * hold * w
                else:
                    constant = constant + self.fixed[i] * hold**2
        weights = math.fsum(w for w, f in zip(self.weights, self.fixed, strict=True)
                            if not np.isfinite(f))
        return CycleRmsModel(tuple(moves), constant, hold_rate,
                             float(np.nansum(self.fixed)), weights)

    def _evaluate(self, duration: np.ndarray) -> CycleMetrics:
        parts = linkage_figures(self, duration)
        cycle = sum((p["duration"] for p in parts), np.zeros(len(self.motors)))

        def most(name: str) -> np.ndarray:
            return np.max([np.broadcast_to(p[name], cycle.shape) for p in parts], axis=0)

        def total(name: str) -> np.ndarray:
            return sum((p[name] for p in parts), np.zeros_like(cycle))

        stages = len(self.drive.stages)
        thermal = rule_speed(self.thermal_rule, most("max_speed"), total("speed_square"),
                             total("turn"), cycle)
        return CycleMetrics(
            duration=cycle, max_speed=most("max_speed"), peak_torque=most("peak_torque"),
            peak_ratio=most("peak_ratio"), rms_torque=np.sqrt(total("square") / cycle),
            thermal_speed=thermal, load_speed=most("load_speed"),
            load_acceleration=most("load_acceleration"), load_jerk=most("load_jerk"),
            load_torque=most("load_torque"),
            stage_peak=[np.max([p["stage_peak"][k] for p in parts], axis=0)
                        for k in range(stages)],
            stage_rms=[np.sqrt(sum(p["stage_square"][k] for p in parts) / cycle)
                       for k in range(stages)],
            stage_speed=[np.max([np.broadcast_to(p["stage_speed"][k], cycle.shape)
                                 for p in parts], axis=0) for k in range(stages)])


def answer_bound(calculator: LinkageCalculator | LinkageCycle, limits: Limits,
                 bound: np.ndarray) -> np.ndarray:
    """``bound`` (a scale below which a check fails) where every check passes there, to
    rounding and not by the tolerance alone: it is then the shortest scale, the one the
    search would find (sizer.sizing.shortest_duration); 0 elsewhere, where the search runs
    as without a bound."""
    usable = np.isfinite(bound) & (bound > 0.0)
    checks = evaluate_checks(calculator.evaluate(np.where(usable, bound, 1.0)),
                             calculator.motors, calculator.drive, limits,
                             calculator.task.linear)
    return np.where(usable & (worst_slack(checks) >= -ROUNDING), bound, 0.0)


ROUNDING = 1e-12
"""The slack of a check exactly at its limit, to rounding (:func:`answer_bound`)."""


def peak_floor(calculator: LinkageCalculator, limits: Limits, low: np.ndarray) -> np.ndarray:
    """Per candidate the larger of ``low`` (a duration below which a check fails) and the
    shortest duration from which on the move's peak check passes (its peak ratio at most
    1 - torque margin at every longer duration); inf where none.

    In closed form on the samples (:func:`_sample_floors`). Most samples cannot bind: the
    one with the largest ratio at ``low`` gives a first floor T0, and a sample passes at
    every duration past T0 where the largest |P u^2 + Q u + C| for u <= 1/T0 (either
    direction of the power flow) stays within the least limit at the speeds up to its
    own at T0; only the others are solved."""
    p, motors, drive = calculator.profile, calculator.motors, calculator.drive
    region, grip = motors.intermittent, 1.0 - limits.torque_margin
    n = len(motors)
    usable = np.isfinite(low) & (low > 0.0)
    probe = np.where(usable, low, calculator.initial_guess())
    speed, torque, _ = calculator.motor_samples(probe)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.abs(torque) / region.limit_clipped(speed)
    rows = np.arange(n)
    first = _sample_floors(calculator, limits, rows,
                           np.argmax(np.where(np.isnan(ratio), np.inf, ratio), axis=1))
    T0 = np.maximum(np.where(usable, low, 0.0), first)
    N = np.broadcast_to(drive.ratio, (n,))[:, None]
    eta = np.broadcast_to(drive.efficiency, (n,))[:, None]
    rotor = (motors.inertia + drive.transmission_inertia)[:, None]
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        u0 = np.where(T0 > 0.0, 1.0 / T0, np.inf)[:, None]
        bound = np.zeros(torque.shape)
        for through in (1.0 / (N * eta), eta / N):  # either direction of the power flow
            P, Q, C = rotor * N * p.theta2 + through * p.inertial, through * p.damping, \
                through * p.steady
            vertex = -Q / (2.0 * P)
            top = np.maximum(np.abs(C), np.abs((P * u0 + Q) * u0 + C))
            inside = (vertex > 0.0) & (vertex < u0)
            bound = np.maximum(bound, np.where(inside, np.maximum(top, np.abs(
                C + Q * vertex / 2.0)), top))
        reach = np.minimum(np.abs(N * p.theta1) * u0, region.max_speed[:, None])
        # first against the least limit up to the fastest sample, then each survivor
        # against the least up to its own speed
        fastest = reach.max(axis=1)
        corners = np.where(region.speeds <= fastest[:, None], region.torques, np.inf)
        ends = region.limit_clipped(np.stack((np.zeros(n), fastest), axis=1)).min(axis=1)
        cand, sample = np.nonzero(~(bound <= grip * np.minimum(ends, corners.min(axis=1))
                                    [:, None] * (1.0 - 1e-9)) & np.isfinite(T0)[:, None])
        if len(cand):
            own = reach[cand, sample]
            table = region.take(cand)
            corners = np.where(table.speeds <= own[:, None], table.torques, np.inf).min(axis=1)
            least = np.minimum(np.minimum(corners, table.limit_clipped(own[:, None])[:, 0]),
                               table.limit_clipped(np.zeros((len(cand), 1)))[:, 0])
            keep = ~(bound[cand, sample] <= grip * least * (1.0 - 1e-9))
            cand, sample = cand[keep], sample[keep]
    out = T0.copy()
    if len(cand):
        np.maximum.at(out, cand, _sample_floors(calculator, limits, cand, sample))
    return out


def _sample_floors(calculator: LinkageCalculator, limits: Limits, cand: np.ndarray,
                   sample: np.ndarray) -> np.ndarray:
    """For pairs (candidate, sample) the shortest duration from which on the sample's
    torque stays within 1 - torque margin of the limit at its speed; inf where none.

    With u = 1/T the motor torque at a sample is P u^2 + Q u + C
    (:meth:`LinkageCalculator.motor_samples`: P the inertias, Q the damping, C the static
    load, through the gearbox's efficiency in the power flow's direction, which changes
    only where the crank torque I u^2 + D u + S does) and the limit a line a + b u on each
    segment of the region (the speed N |theta'| u, clipped at its end). Between those
    breakpoints the check is two quadratic inequalities; the first u where one rises
    above zero is the pair's, and T = 1/u."""
    p, motors, drive = calculator.profile, calculator.motors, calculator.drive
    region, grip = motors.intermittent, 1.0 - limits.torque_margin
    n = len(motors)
    N = np.broadcast_to(drive.ratio, (n,))[cand][:, None]
    eta = np.broadcast_to(drive.efficiency, (n,))[cand][:, None]
    rotor = (motors.inertia + drive.transmission_inertia)[cand][:, None]
    inert, D, S = (np.broadcast_to(x, p.u.shape)[sample][:, None]
                   for x in (p.inertial, p.damping, p.steady))
    theta1, theta2 = p.theta1[sample][:, None], p.theta2[sample][:, None]
    speeds, torques, top = region.speeds[cand], region.torques[cand], region.max_speed[cand]
    rate = np.abs(N * theta1)  # the motor speed per unit u
    with np.errstate(divide="ignore", invalid="ignore"):
        ends = np.concatenate((np.zeros((len(cand), 1)), _positive_roots(inert, D, S)[:, 0],
                               speeds[:, 1:] / rate), axis=1)
    lo = np.sort(np.where(np.isnan(ends) | (ends < 0.0), np.inf, ends), axis=1)
    hi = np.concatenate((lo[:, 1:], np.full((len(cand), 1), np.inf)), axis=1)
    middle = np.where(np.isfinite(hi), 0.5 * (lo + hi), np.where(lo > 0.0, 2.0 * lo, 1.0))
    middle = np.where(np.isfinite(lo), middle, 1.0)
    at = np.minimum(middle * rate, top[:, None])  # the speed, clipped at the region's end
    segment = np.minimum((speeds[:, None, 1:-1] <= at[:, :, None]).sum(axis=-1),
                         speeds.shape[1] - 2)  # a count: >= 0
    row = np.arange(len(cand))[:, None]
    s0, s1 = speeds[row, segment], speeds[row, segment + 1]
    t0, t1 = torques[row, segment], torques[row, segment + 1]
    slope = (t1 - t0) / (s1 - s0)
    beyond = middle * rate >= top[:, None]
    a = np.where(beyond, t0 + slope * (top[:, None] - s0), t0 - slope * s0)
    b = np.where(beyond, 0.0, slope * rate)  # the limit a + b u
    through = np.where(((inert * middle + D) * middle + S) * theta1 >= 0.0, 1.0 / (N * eta),
                       eta / N)
    P, Q, C = rotor * N * theta2 + through * inert, through * D, through * S
    first = np.minimum(_first_rise(P, Q - grip * b, C - grip * a, lo, hi),
                       _first_rise(-P, -Q - grip * b, -C - grip * a, lo, hi))
    u = np.min(np.where(np.isfinite(lo), first, np.inf), axis=1)
    with np.errstate(divide="ignore"):
        return np.where(u > 0.0, 1.0 / u, np.inf)


def _positive_roots(a2: np.ndarray, a1: np.ndarray, a0: np.ndarray) -> np.ndarray:
    """The real roots of a2 x^2 + a1 x + a0 (x > 0 or nan), two per element: (..., 2)."""
    out = np.stack(quadratic_roots(a2, a1, a0), axis=-1)
    with np.errstate(invalid="ignore"):
        return np.where(out > 0.0, out, np.nan)


def _first_rise(a2: np.ndarray, a1: np.ndarray, a0: np.ndarray, lo: np.ndarray,
                hi: np.ndarray) -> np.ndarray:
    """The least x in [lo, hi) where q = a2 x^2 + a1 x + a0 > 0 (inf: none): lo where q
    is positive there, else the root where q rises (the larger of a convex q, the
    smaller of a concave one, a line's with a positive slope) if it lies before hi."""
    x1, x2 = quadratic_roots(a2, a1, a0)  # nan without real roots: no rise
    with np.errstate(over="ignore", invalid="ignore"):
        at_lo = (a2 * lo + a1) * lo + a0
        rise = np.where(a2 > 0.0, np.maximum(x1, x2), np.where(
            a2 < 0.0, np.minimum(x1, x2), np.where(a1 > 0.0, x2, np.inf)))
        inside = (rise > lo) & (rise < hi)
    return np.where(at_lo > 0.0, lo, np.where(inside, rise, np.inf))


def linkage_figures(calculator: LinkageCalculator | LinkageCycle, s: np.ndarray
                    ) -> list[dict[str, Any]]:
    """Per part of the cycle and candidate: duration, peak torque, peak ratio, the
    integral of tau^2 and of omega^2, peak speed, the crank's turn, the work at the motor
    shaft, the load's peaks, the stages' figures and the load's acceleration at both ends."""
    out = []
    n = len(calculator.motors)
    drive = calculator.drive
    for i, (_, _, _, part, T, calc) in enumerate(calculator.segments(np.asarray(s, float))):
        if calc is not None and isinstance(calculator, LinkageCycle) \
                and np.isfinite(calculator.fixed[i]):  # the same at every scale: once
            out.append(calculator.fixed_figures(i))
        elif calc is not None:
            out.append(_move_figures(calc, T))
        elif isinstance(part, HeldDwell):
            hold = held_torque(part.hold, drive, n)
            zeros = np.zeros(n)
            ratio = peak_ratio(calculator.motors, hold[:, None], zeros[:, None])
            stages = len(drive.stages)
            out.append({"duration": T, "peak_torque": hold, "peak_ratio": ratio,
                        "square": T * hold**2, "speed_square": zeros, "max_speed": zeros,
                        "turn": zeros, "energy": zeros, "load_speed": zeros,
                        "load_acceleration": zeros, "load_jerk": zeros,
                        "load_torque": np.full(n, part.force),
                        "stage_peak": [zeros] * stages, "stage_square": [zeros] * stages,
                        "stage_speed": [zeros] * stages, "start_acceleration": zeros,
                        "end_acceleration": zeros})
    return out


def _move_figures(calc: LinkageCalculator, T: np.ndarray) -> dict[str, Any]:
    """The figures of :func:`linkage_figures` of one move at durations T."""
    n, part, N = len(calc.motors), calc.profile, calc.drive.ratio
    metrics, speed, torque = calc.sampled(T)
    weights = part.weights
    return {
            "duration": T, "peak_torque": metrics.peak_torque,
            "peak_ratio": metrics.peak_ratio, "square": T * (torque**2 @ weights),
            "speed_square": T * (speed**2 @ weights), "max_speed": metrics.max_speed,
            "turn": np.broadcast_to(N * abs(part.turn), (n,)),
            "energy": T * ((torque * speed) @ weights),
            "load_speed": metrics.load_speed,
            "load_acceleration": metrics.load_acceleration,
            "load_jerk": metrics.load_jerk, "load_torque": metrics.load_torque,
            "stage_peak": metrics.stage_peak,
            "stage_square": [T * r**2 for r in metrics.stage_rms],
            "stage_speed": metrics.stage_speed,
            "start_acceleration": np.full(n, part.s2[0]) / T**2,
            "end_acceleration": np.full(n, part.s2[-1]) / T**2}


def move_calculator(calculator: LinkageCalculator | LinkageCycle,
                    profile: LinkageProfile) -> LinkageCalculator:
    """The calculator of one move of the cycle (no dwell): ``profile`` at its durations
    (against position-dependent loads, :class:`PositionCalculator`: their load and peaks)."""
    if isinstance(calculator, PositionCycle):
        return PositionCalculator(profile, Task(0.0, None), calculator.drive,
                                  calculator.motors, calculator.thermal_rule, calculator.law)
    return LinkageCalculator(profile, Task(0.0, None), calculator.drive, calculator.motors,
                             calculator.thermal_rule, calculator.law)


class LinkagePart(NamedTuple):
    """One part of a machine cycle through a linkage at durations (one move) or scales s:
    its name, kind and law, the move's profile or the dwell, its durations, the move's
    calculator (None for a dwell)."""

    name: str
    kind: str
    law: MotionLaw | None
    part: LinkageProfile | HeldDwell
    duration: np.ndarray
    move: LinkageCalculator | None


def linkage_pieces(calculator: LinkageCalculator | LinkageCycle, s: np.ndarray,
                   samples: int | None) -> list[CyclePiece]:
    """The cycle through a linkage at durations (one move) or scales s: each move on
    ``samples`` of its profile's uniform grid (all of them with None), each dwell holding
    the output."""
    n = len(calculator.motors)
    N = np.broadcast_to(np.asarray(calculator.drive.ratio, dtype=float), (n,))[:, None]
    out, start, position = [], np.zeros((n, 1)), 0.0
    # against loads of the position (no linkage) each move carries the load it moves,
    # its terms of the position with it; through a linkage the samples are the output's
    own_load = calculator.drive.transmission.linkage is None
    for name, _, _, part, T, move in calculator.segments(s):
        Tc = np.asarray(T, dtype=float)[:, None]
        if isinstance(part, HeldDwell):
            out.append(held_piece(name, start, Tc, position,
                                  held_torque(part.hold, calculator.drive, n)))
        else:
            assert move is not None
            speed, torque, _ = move.motor_samples(np.asarray(T, dtype=float))
            pick = np.flatnonzero(part.weights == 0.0)  # the uniform grid, in order
            if samples is not None:
                pick = pick[np.linspace(0, len(pick) - 1, samples).round().astype(int)]
            out.append(CyclePiece(name, start + Tc * part.u[pick][None], part.s[pick],
                                  part.s1[pick][None] / Tc, part.s2[pick][None] / Tc**2,
                                  speed[:, pick], N * part.theta2[pick][None] / Tc**2,
                                  torque[:, pick], part.theta[pick], part.ratio[pick],
                                  part.load if own_load else None))
            position = float(part.s[-1])
        start = start + Tc
    return out


def linkage_breakdown(calculator: LinkageCalculator | LinkageCycle, s: np.ndarray
                      ) -> list[SegmentPart]:
    """Each part's figures (:func:`linkage_figures`); a move's acceleration scale is its
    output's largest |s''| / T^2."""
    out = []
    for (name, kind, law, part, T, _), f in zip(calculator.segments(s),
                                                linkage_figures(calculator, s), strict=True):
        scale = float(np.max(np.abs(part.s2))) / T ** 2 \
            if isinstance(part, LinkageProfile) else None
        out.append(SegmentPart(name, kind, law, f["duration"], f["peak_torque"], f["square"],
                               f["max_speed"], f["energy"], f["start_acceleration"],
                               f["end_acceleration"], scale))
    return out


def _shape(segment: Move | Run, law: MotionLaw | None,
           duration: float | None) -> MotionLaw | FixedShape:
    """The shape of a move or run over u = t/T: the law itself for a move from rest to
    rest; for a run or a move with boundary speeds, at its fixed duration T."""
    if isinstance(segment, Run):
        return FixedShape()
    assert law is not None
    if segment.rest_to_rest:
        return law
    assert duration is not None  # sizer.io.linkage asks for it
    h, T = segment.displacement, duration
    return FixedShape(law.spec, segment.start_speed * T / h, segment.end_speed * T / h,
                      segment.start_acceleration * T * T / h,
                      segment.end_acceleration * T * T / h)


# ------------------------------------------------------ loads that depend on position
# A move against loads of the load's position (book sec. 5.2.2, eqs. 5.13-5.19): gravity
# on an arm, a spring (sizer.model.domain.GravityLoad, SpringLoad). The load's torque
# along a move of h by q_N over u = t/T is tau_l(u; T) = J_l h q_N''/T^2 + B_l h q_N'/T
# + g(q(u)), g(q) = F s + tau_ext + gravity(q) + spring(q), q measured from the move's
# start: eq. 5.15, tau_s (scaling as 1/T^2 and 1/T, eq. 5.18) plus the position terms
# tau_p = g(q), which do not scale. That is the form of a move through a linkage
# (A(u)/T^2 + D(u)/T + B(u)) with the identity as the linkage (ratio 1), so the move is
# sized by this engine unchanged: its grid, torque, peak floor and RMS model. The dwell
# holds the static load at the end position, g(h) without the friction. One move
# (``task:`` without a return); stages' preload torques and the steady-load efficiency
# rule are refused. An inertia table J(q) (added to J_l) puts J(q) q'' + 1/2 J'(q) q'^2 in
# the inertial part (both as 1/T^2); the ratio check reads the largest inertia over the
# move (position_calculator's drive). docs/position-loads.md.

@dataclass(frozen=True)
class PositionProfile(LinkageProfile):
    """:class:`LinkageProfile` with ``kinks``: the samples (a mask over u) where a
    position table's knot is crossed, the torque's kinks (none without a table)."""

    kinks: np.ndarray | None = None


TABLE_SLACK = 1e-9
"""How far (relative to the table's span) a move may pass a table's end: rounding."""


def knot_crossings(law: MotionLaw | FixedShape, h: float, knots: tuple[float, ...]
                   ) -> np.ndarray:
    """The u in (0, 1) where the move's position h q_N(u) crosses a knot: each sign
    change of h q_N(u) - knot on a fine grid, bisected to rounding."""
    return crossings_of(lambda u: h * law.derivative(u, 0), law.breakpoints, knots)


def crossings_of(position: Any, breakpoints: np.ndarray, knots: tuple[float, ...]
                 ) -> np.ndarray:
    """The u in (0, 1) where ``position(u)`` (a move's position over normalized time)
    crosses a knot: each sign change of position(u) - knot on a fine grid (with the
    law's ``breakpoints``), bisected to rounding."""
    if not knots:
        return np.empty(0)
    u = sorted_unique(np.concatenate((np.linspace(0.0, 1.0, PEAK_POINTS), breakpoints)))
    f = position(u)[None, :] - np.asarray(knots, dtype=float)[:, None]
    k, i = np.nonzero(np.sign(f[:, :-1]) * np.sign(f[:, 1:]) <= 0.0)
    lo, hi = u[i], u[i + 1]
    flo = f[k, i]
    target = np.asarray(knots, dtype=float)[k]
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        fmid = position(mid) - target
        left = np.sign(fmid) * np.sign(flo) <= 0.0
        hi, lo = np.where(left, mid, hi), np.where(left, lo, mid)
        flo = np.where(left, flo, fmid)
    roots = np.where(f[k, i] == 0.0, u[i], np.where(f[k, i + 1] == 0.0, u[i + 1], lo))
    return sorted_unique(roots[(roots > 0.0) & (roots < 1.0)])


def _check_table_span(load: Load, q: np.ndarray, linear: bool) -> None:
    """A move that leaves its position table is the user's mistake (a located message)."""
    for table, field in ((load.table, "load.force_table" if linear else "load.torque_table"),
                         (load.inertia_table,
                          "load.mass_table" if linear else "load.inertia_table")):
        if table is None or not table.active:
            continue
        x = np.asarray(q, dtype=float) + table.offset
        lo, hi = table.x[0], table.x[-1]
        slack = TABLE_SLACK * (hi - lo)
        if np.min(x) < lo - slack or np.max(x) > hi + slack:
            raise UserError(f"the move reaches the table's positions {np.min(x):.6g} to "
                            f"{np.max(x):.6g} (SI, with its offset): the table covers "
                            f"{lo:.6g} to {hi:.6g}; extend it or check its offset",
                            field=field)


def position_profile(load: Load, displacement: float, law: MotionLaw | FixedShape,
                     linear: bool = False, start: float = 0.0) -> LinkageProfile:
    """The move of ``displacement`` (signed, rad or m) by ``law`` from the load's position
    ``start`` (from where the cycle starts: 0 for its first move) against ``load`` as the
    linkage engine's profile at T = 1 (module docs). A position table's knot crossings
    are breakpoints of the grid: the torque's kinks are sampled, the quadrature split
    there (exact peaks and RMS for the piecewise-linear term)."""
    h = float(displacement)
    knots = tuple(k - start for k in load.position_knots)
    crossings = knot_crossings(law, h, knots) if knots else None
    u, weights = _grid(law, crossings)  # the linkage engine's grid
    direction = 1.0 if h >= 0.0 else -1.0
    q = [h * law.derivative(u, k) for k in range(4)]
    q[0] = start + q[0]
    _check_table_span(load, q[0], linear)
    sense = np.where(q[1] > 0.0, 1.0, np.where(q[1] < 0.0, -1.0, direction))
    # J(q) q'' + 1/2 J'(q) q'^2 (both as 1/T^2) and g(q): Load.position_terms
    extra, position = load.position_terms(q[0], q[1], q[2])
    inertial = load.inertia * q[2] + extra
    largest = load.inertia
    table = load.inertia_table
    if table is not None and table.active:
        largest = load.inertia + table.largest(float(np.min(q[0])), float(np.max(q[0])))
    damping = load.damping * q[1]
    steady = load.friction * sense + load.torque + position
    hold = float(load.torque + load.position_torque(np.array([start + h]))[0])
    kinks = None if crossings is None else np.isin(u, crossings)
    return PositionProfile(u, weights, q[0], np.ones_like(u), q[0], q[1], q[2], q[1], q[2],
                           q[3], inertial, damping, steady, hold, abs(h), load.inertia, load,
                           largest, (), jumps=jump_mask(law, u), kinks=kinks)


class PositionCalculator(LinkageCalculator):
    """One move and its dwell against position-dependent loads (module docs): the
    linkage engine's calculator with the load's own force reported and the dwell's
    held load the static load at the end position."""

    def dead_point_issues(self) -> None:  # type: ignore[override]  # CycleModel allows None
        return None  # no linkage: no dead-point check (as sizer.sizing.move)

    def segments(self, T: np.ndarray) -> list[LinkagePart]:
        p = self.profile
        move = PositionCalculator(p, Task(0.0, None), self.drive, self.motors,
                                  self.thermal_rule, self.law)
        out = [LinkagePart("move", "move", self.law, p, T, move)]
        if self.task.dwell > 0.0:
            out.append(LinkagePart("dwell", "dwell", None, HeldDwell(p.hold, abs(p.hold)),
                                   np.full_like(T, self.task.dwell), None))
        return out

    def search_start(self, limits: Limits) -> np.ndarray:
        """:meth:`LinkageCalculator.search_start` with the peak floor moved up to where
        the peak ratio as :meth:`sampled` reads it (refined between the samples) meets
        1 - torque margin (:func:`refined_floor`)."""
        if self._start is None or self._start[0] is not limits:
            floor = peak_floor(self, limits, self.speed_bound(limits))
            self._start = (limits, refined_floor(self, limits, floor))
        return self._start[1]

    def take(self, index: np.ndarray) -> PositionCalculator:
        return PositionCalculator(self.profile, self.task, self.drive.take(index),
                                  self.motors.subset(index), self.thermal_rule, self.law)

    def _sampled(self, duration: np.ndarray, state: tuple[np.ndarray, ...]
                 ) -> tuple[CycleMetrics, np.ndarray, np.ndarray]:
        """The linkage engine's figures, the load's torque (force) with its position terms
        and, with a dwell, the static load it holds."""
        metrics, speed, torque = super()._sampled(duration, state)
        p = self.profile
        T = np.broadcast_to(np.asarray(duration, dtype=float), (len(self.motors),))[:, None]
        force = p.inertial / T**2 + p.damping / T + p.steady
        load_torque = profile_max(np.abs(force), p, jumping=True)
        if self.task.dwell > 0.0:
            load_torque = np.maximum(load_torque, abs(p.hold))
        # the peak ratio refined as the peak torque is (the samples alone read a smooth
        # peak 1e-7 low: T_min would be that much short)
        with np.errstate(divide="ignore", invalid="ignore"):
            limit = self.motors.intermittent.limit_clipped(np.abs(speed))
            ratio = np.where(limit > 0.0, np.abs(torque) / limit,
                             np.where(torque == 0.0, 0.0, np.inf))
        ratio = np.where(np.isnan(ratio), np.inf, ratio)
        # (a position table's knots and the law's breakpoints: no parabola through them)
        peak_ratio = np.maximum(metrics.peak_ratio, profile_max(ratio, p, jumping=True))
        return replace(metrics, load_torque=load_torque, peak_ratio=peak_ratio), speed, \
            torque


FLOOR_WIDTH = 1e-14
"""The relative width to which :func:`refined_floor` brackets the crossing."""


def refined_floor(calculator: PositionCalculator, limits: Limits, floor: np.ndarray
                  ) -> np.ndarray:
    """The peak floor of :func:`peak_floor`, read on the samples (a smooth peak between
    two of them is read up to 1e-7 low), moved up where the refined peak ratio exceeds
    1 - torque margin there: to where it meets it, by the project's root finder
    (sizer.numerics.roots.bracketed_root) on T from the floor (the ratio falls with T
    past the floor). Where no bracket is found the floor stays (the engine's search goes
    on from it)."""
    grip = 1.0 - limits.torque_margin
    out = np.array(floor, dtype=float)
    rows = np.flatnonzero(np.isfinite(out) & (out > 0.0))
    if not rows.size:
        return out
    calc = calculator.take(rows)

    def excess(T: np.ndarray) -> np.ndarray:
        return calc.sampled(T)[0].peak_ratio - grip

    lo = out[rows]
    f_lo = excess(lo)
    open_ = f_lo > 0.0
    if not open_.any():
        return out
    hi, f_hi = lo.copy(), f_lo.copy()
    step = 1e-6
    for _ in range(6):  # a bracket: the ratio falls below the grip past the floor
        need = open_ & (f_hi > 0.0)
        if not need.any():
            break
        hi = np.where(need, lo * (1.0 + step), hi)
        f_hi = np.where(need, excess(hi), f_hi)
        step *= 10.0
    open_ &= f_hi <= 0.0
    index = np.flatnonzero(open_)
    if index.size:  # the crossing in u = T / floor (so that 1e-14 is relative to T)
        base = lo[index]

        def excess_at(u: np.ndarray, where: np.ndarray) -> np.ndarray:
            return calc.take(index[where]).sampled(u * base[where])[0].peak_ratio - grip

        _, top = bracketed_root(excess_at, np.ones(index.size), hi[index] / base,
                                f_lo[index], f_hi[index], xtol=FLOOR_WIDTH,
                                args=(np.arange(index.size),), bracket=True)
        out[rows[index]] = top * base
    return out


def check_position_drive(drive: Drive) -> None:
    """Refuse what the position-load engine does not model (module docs)."""
    if drive.steady_load_efficiency:
        raise UserError("load.gravity/load.spring: the steady-load efficiency rule is not "
                        "supported with position-dependent loads (use power_flow)")
    if any(bool(np.any(np.asarray(s.preload_torque) != 0.0)) for s in drive.stages):
        raise UserError("load.gravity/load.spring: a stage's preload torque is not "
                        "supported with position-dependent loads yet")


def position_calculator(task: Task, law: MotionLaw, load: Load, drive: Drive,
                        motors: MotorArrays, thermal_rule: str = "max") -> PositionCalculator:
    """The calculator the engine sizes a one-move task against position-dependent loads
    with (a sizer.sizing.evaluation.CycleModel)."""
    if task.return_move:
        raise UserError("load.gravity/load.spring: a task with a return move is not "
                        "supported with position-dependent loads yet (one move and its dwell)")
    check_position_drive(drive)
    profile = position_profile(load, task.displacement, law, task.linear)
    if profile.max_inertia != drive.load.inertia:  # an inertia table: the ratio check and
        # the inertia figures read the largest inertia over the move
        drive = Drive(replace(drive.load, inertia=profile.max_inertia), drive.transmissions,
                      drive.option)
    return PositionCalculator(profile, task, drive, motors, thermal_rule, law)


class PositionCycle(LinkageCycle):
    """A cycle of segments (or a task with a return move, the cycle it means) against
    position-dependent loads: the linkage engine's cycle with the identity as the
    linkage. Each move or run starts at the cycle's running position (the sum of the
    displacements before it: a return starts at h and goes back to 0), its profile the
    load's terms at its true positions (:func:`position_profile`); a dwell holds the
    static load at the position where it rests, tau_ext + g(x) without friction. The
    segments' own loads (a picked-up part) add as in any cycle (segment_load)."""

    def __init__(self, cycle: Cycle, law: MotionLaw | None, load: Load, drive: Drive,
                 motors: MotorArrays, thermal_rule: str) -> None:
        self._setup(cycle, law, motors, thermal_rule)
        position = 0.0
        for i, (segment, own) in enumerate(zip(cycle.segments, self.laws, strict=True)):
            here = segment_load(load, segment)
            if isinstance(segment, Move | Run):
                duration = None if np.isnan(self.fixed[i]) else float(self.fixed[i])
                self.parts.append(position_profile(here, segment.displacement,
                                                   _shape(segment, own, duration),
                                                   cycle.linear, position))
                position += segment.displacement
            else:
                hold = float(here.torque + here.position_torque(np.array([position]))[0])
                self.parts.append(HeldDwell(hold, abs(hold)))
        largest = max(p.max_inertia for p in self.parts if isinstance(p, LinkageProfile))
        if largest != drive.load.inertia:  # a picked-up part, an inertia table: the ratio
            # check and the inertia figures read the largest inertia over the cycle
            drive = Drive(replace(drive.load, inertia=largest), drive.transmissions,
                          drive.option)
        self.drive = drive

    def dead_point_issues(self) -> None:  # type: ignore[override]  # CycleModel allows None
        return None  # no linkage: no dead-point check

    def pieces(self, s: np.ndarray, samples: int | None = None) -> list[CyclePiece]:
        """:func:`linkage_pieces`, each dwell's torque with the sign of the static load it
        holds (gravity may hold either way)."""
        out = linkage_pieces(self, s, samples)
        return [replace(p, torque=p.torque * np.sign(part.hold))
                if isinstance(part, HeldDwell) else p
                for p, part in zip(out, self.parts, strict=True)]


def position_model(cycle: Cycle, law: MotionLaw, load: Load, drive: Drive,
                   motors: MotorArrays, thermal_rule: str = "max"
                   ) -> PositionCalculator | PositionCycle:
    """The model the engine sizes a design with position-dependent loads on (a
    sizer.sizing.evaluation.CycleModel): one move and its dwell
    (:func:`position_calculator`), else the cycle of segments, or the cycle a task with a
    return move means (:class:`PositionCycle`)."""
    task = shorthand_task(cycle)
    if task is not None and not task.return_move:
        return position_calculator(task, law, load, drive, motors, thermal_rule)
    check_position_drive(drive)
    return PositionCycle(cycle if task is None else from_task(task), law, load, drive,
                         motors, thermal_rule)
