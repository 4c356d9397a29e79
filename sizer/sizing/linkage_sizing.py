"""Sizing through a linkage at the load (issue 14, seed 003): a position-dependent ratio.

The motion of the move has a fixed shape over normalized time u = t/T (book sec. 5.2):
with the law on the crank, theta(u) = theta_0 + h q_N(u); with the law on the output,
s(u) = s_0 + h q_N(u) and the crank follows by inverse kinematics, through the dead
points by the paper's limits (sizer.mechanics.linkages.inverse_motion). The torque the
crank needs is tau_c(u; T) = A(u)/T^2 + D(u)/T + B(u) by Lagrange, with the d(J_eq)/dq
term (sizer.mechanics.linkages.dynamics). Computed once per law (:func:`linkage_profile`)
on a fixed grid: composite Gauss-Legendre nodes for the integrals (RMS), a uniform grid
of PEAK_POINTS points plus the law's breakpoints for the peaks.

Per candidate (:class:`LinkageCalculator`), the gear stages between motor and crank
(ratio N, efficiency eta in the direction of power flow, their inertia) give the motor's
speed N theta'(u)/T and torque (J_m + J_stages) N theta''(u)/T^2 + tau_c/(N eta^{+-1}):
peaks and the speed-torque envelope over the samples, the RMS over the cycle with the
dwell holding the output's static load. A law that breaks the paper's dead-point rule is
infeasible for every candidate, with its reason (check ``dead_point``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np

from sizer.errors import UserError
from sizer.laws import MotionLaw
from sizer.laws.quadrature import gauss_legendre
from sizer.mechanics.drive import Drive
from sizer.model.domain import Design, Limits, LinkageStage, Load, Task
from sizer.sizing.checks import CheckArrays, evaluate_checks
from sizer.sizing.cycle import CycleMetrics, rule_speed
from sizer.sizing.motors import MotorArrays

PEAK_POINTS = 4001
"""Uniform samples of u in [0, 1] where the peaks are read (with the law's breakpoints):
a smooth peak is read to about (1/4000)^2 of its curvature, 1e-7 relative."""
GAUSS_PIECES = 128
"""Composite Gauss-Legendre: sub-intervals of [0, 1] (split at the law's breakpoints)."""
GAUSS_NODES = 8
"""Nodes per sub-interval: exact for polynomials of degree 15 in each."""


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


def _grid(law: MotionLaw | FixedShape) -> tuple[np.ndarray, np.ndarray]:
    """Sample points of [0, 1] and their quadrature weights (0 for the peak-only ones)."""
    cuts = np.unique(np.concatenate((law.breakpoints, np.linspace(0.0, 1.0, GAUSS_PIECES + 1))))
    x, w = gauss_legendre(GAUSS_NODES)
    left, width = cuts[:-1, None], np.diff(cuts)[:, None]
    nodes = (left + 0.5 * width * (x + 1.0)).ravel()
    weights = (0.5 * width * w).ravel()
    peaks = np.unique(np.concatenate((np.linspace(0.0, 1.0, PEAK_POINTS), law.breakpoints)))
    u = np.concatenate((nodes, peaks))
    order = np.argsort(u, kind="stable")  # in time order, as the inverse kinematics needs
    return u[order], np.concatenate((weights, np.zeros(len(peaks))))[order]


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


def linkage_profile(design: Design, law: MotionLaw) -> LinkageProfile:
    """The profile of ``law`` through the design's linkage (cached per law and design)."""
    stage = design.transmission.linkage
    assert stage is not None
    return _profile(stage, design.load, design.task.displacement, design.task.duration, law)


def profile_of(stage: LinkageStage, load: Load, h: float, duration: float | None,
               law: MotionLaw | FixedShape) -> LinkageProfile:
    """The profile of a move of ``h`` by ``law`` from the stage's start angle (cached)."""
    return _profile(stage, load, h, duration, law)


@lru_cache(maxsize=256)
def _profile(stage: LinkageStage, load: Load, h: float, duration: float | None,
             law: MotionLaw | FixedShape) -> LinkageProfile:
    from sizer.mechanics.linkages.dynamics import LinkageDynamics, LinkageMasses
    from sizer.mechanics.linkages.inverse_motion import input_motion, output_motion
    from sizer.mechanics.linkages.of_stage import linkages_of

    views = linkages_of(stage)
    u, weights = _grid(law)
    q = [law.derivative(u, k) for k in range(4)]
    theta0 = stage.start_angle
    issues: tuple[str, ...] = ()
    # the coordinate the law is on: the driven link's (law_on: crank) or the load's
    given = views.motor if stage.law_on == "crank" else views.output
    x0 = float(given.output(np.array([theta0]))[0])
    x = [x0 + h * q[0], h * q[1], h * q[2], h * q[3]]
    if not given.dead_points().size:  # the law is on the crank angle itself
        theta = x
    else:
        issues = _issues(given, law, u, x, h, duration)
        with np.errstate(all="ignore"):
            theta = list(input_motion(given, *x, start_theta=theta0,
                                      direction=stage.direction))
    with np.errstate(all="ignore"):
        s = x if given is views.output else list(output_motion(views.output, *theta))
        motor = theta if views.crank_driven else list(output_motion(views.motor, *theta))
    masses = LinkageMasses(crank_inertia=stage.crank_inertia, output_inertia=load.inertia,
                           link_mass_at_crank=stage.link_mass_at_crank,
                           link_mass_at_output=stage.link_mass_at_output,
                           load=load.torque, friction=load.friction, damping=load.damping)
    crank_radius = stage.lengths[0]
    rocker_length = None if stage.kind == "slider_crank" else stage.lengths[2]
    joint = None if views.joint == views.output else views.joint
    dynamics = LinkageDynamics(views.output, masses, crank_radius=crank_radius,
                               rocker_length=rocker_length, joint=joint)
    with np.errstate(all="ignore"):
        parts = dynamics.time_scaling_parts(theta[0], theta[1], theta[2])
    inertial, damping, steady = parts.inertial, parts.damping, parts.steady
    end = theta[0][-1:]  # u is in time order
    hold = float(views.output.output(end, 1)[0] * load.torque)
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
        hold = static_torque(stage, load.torque, float(end[0]))
        hold = hold if math.isfinite(hold) else 0.0  # unbounded: the issue says so
        turn = float(np.sum(np.abs(np.diff(motor[0]))))
        ratio = _over(views.output.output(_finite(theta[0]), 1), g1)
        with np.errstate(all="ignore"):
            reflected = dynamics.inertia(theta[0]) / g1**2
        max_inertia = float(np.max(reflected[np.isfinite(reflected)], initial=0.0))
    return LinkageProfile(u, weights, _finite(theta[0]), _finite(ratio), s[0],
                          _finite(motor[1]), _finite(motor[2]), s[1], s[2], s[3],
                          _finite(inertial), _finite(damping), _finite(steady), hold, turn,
                          dynamics.output_side_inertia, load, max_inertia, issues)


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
               ) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """The output's (acceleration, jerk) just before and just after every sample: where
    the law's pieces join they differ; outside [0, 1] the law is at rest."""
    starts = np.array([piece.start for piece in law.pieces])
    last = len(law.pieces) - 1
    after = np.clip(np.searchsorted(starts, u, side="right") - 1, 0, last)
    before = np.clip(np.searchsorted(starts, u, side="left") - 1, 0, last)

    def values(index: np.ndarray, order: int) -> np.ndarray:
        out = np.empty(len(u))
        for i in np.unique(index):
            mask = index == i
            out[mask] = law.piece_derivative(int(i), u[mask], order)
        return h * out / T**order

    left = [values(before, k) for k in (2, 3)]
    right = [values(after, k) for k in (2, 3)]
    for k, (outside_before, outside_after) in enumerate(law.outside(order) for order in (2, 3)):
        left[k][0] = h * outside_before / T ** (k + 2)
        right[k][-1] = h * outside_after / T ** (k + 2)
    return {"left": (left[0], left[1]), "right": (right[0], right[1])}


def _issues(linkage, law: MotionLaw, u: np.ndarray, s: list,
            h: float, duration: float | None) -> tuple[str, ...]:
    """The paper's rule at every dead point the output reaches, in the move's own time
    and units (for a shortest-duration task, at T = 1 s: the verdict does not depend on
    T, the values scale with it)."""
    from sizer.mechanics.linkages.inverse_motion import dead_point_crossings

    T = duration or 1.0
    scaled = [s[0], *(x / T**k for k, x in enumerate(s[1:], start=1))]
    found = dead_point_crossings(linkage, u * T, *scaled, **_one_sided(law, u, h, T),
                                 units="m" if linkage.output_linear else "rad")
    suffix = "" if duration else " (for a move of 1 s; the values scale with its duration)"
    return tuple(issue.message + suffix for issue in found)


def _finite(x: np.ndarray) -> np.ndarray:
    """The samples where the motion is singular (a law that breaks the dead-point rule)
    read 0: the verdict is the dead-point check's, no inf or NaN reaches a result."""
    x = np.asarray(x, dtype=float)
    return np.where(np.isfinite(x), x, 0.0)


class LinkageCalculator:
    """The requirements of one law through a linkage for each candidate at durations T
    (the interface of sizer.sizing.cycle.CycleCalculator that minimum_duration uses)."""

    segmented = True

    def __init__(self, profile: LinkageProfile, task: Task, drive: Drive,
                 motors: MotorArrays, thermal_rule: str, law: MotionLaw) -> None:
        self.profile, self.task, self.drive, self.motors = profile, task, drive, motors
        self.thermal_rule, self.law = thermal_rule, law

    def take(self, index: np.ndarray) -> LinkageCalculator:
        return LinkageCalculator(self.profile, self.task, self.drive.take(index),
                                 self.motors.subset(index), self.thermal_rule, self.law)

    def peak_bound(self, limits: Limits) -> None:
        return None

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
        p, motors, drive = self.profile, self.motors, self.drive
        T = np.broadcast_to(np.asarray(duration, dtype=float), (len(motors),))[:, None]
        N, eta = drive.ratio[:, None], drive.efficiency[:, None]
        rotor = (motors.inertia + drive.transmission_inertia)[:, None]
        crank = p.inertial / T**2 + p.damping / T + p.steady
        driving = crank * p.theta1 >= 0.0
        torque = rotor * N * p.theta2 / T**2 + np.where(driving, crank / (N * eta),
                                                         crank * eta / N)
        return N * p.theta1 / T, torque, crank

    def evaluate(self, duration: np.ndarray, peaks: bool = True) -> CycleMetrics:
        p, motors, drive = self.profile, self.motors, self.drive
        T = np.broadcast_to(np.asarray(duration, dtype=float), (len(motors),))[:, None]
        N, eta = drive.ratio[:, None], drive.efficiency[:, None]
        speed, torque, crank = self.motor_samples(T[:, 0])
        dwell = self.task.dwell
        hold = abs(p.hold) / (N[:, 0] * eta[:, 0])
        cycle = T[:, 0] + dwell
        square = T[:, 0] * (torque**2 @ p.weights) + dwell * hold**2
        with np.errstate(divide="ignore", invalid="ignore"):
            limit = motors.intermittent.limit_clipped(speed)
            ratio = np.where(limit > 0.0, np.abs(torque) / limit,
                             np.where(torque == 0.0, 0.0, np.inf))
        load = p.load
        force = (p.output_mass * p.s2 / T**2 + load.damping * p.s1 / T + load.torque
                 + load.friction * np.sign(p.s1))
        stage_torque, stage_speed = self._stages(crank, T)
        return CycleMetrics(
            duration=T[:, 0], max_speed=refined_max(np.abs(speed), p.u),
            peak_torque=refined_max(np.abs(torque), p.u), peak_ratio=np.max(ratio, axis=1),
            rms_torque=np.sqrt(square / cycle), thermal_speed=self.thermal_speed(T[:, 0]),
            load_speed=np.max(np.abs(p.s1)) / T[:, 0],
            load_acceleration=np.max(np.abs(p.s2)) / T[:, 0] ** 2,
            load_jerk=np.max(np.abs(p.s3)) / T[:, 0] ** 3,
            load_torque=np.max(np.abs(force), axis=1),
            stage_peak=[np.max(np.abs(x), axis=1) for x in stage_torque],
            stage_rms=[np.sqrt(T[:, 0] * (x**2 @ p.weights) / cycle) for x in stage_torque],
            stage_speed=stage_speed)

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


UNBOUNDED_NOTE = ("unbounded: the crank's acceleration is infinite at the dead point (see "
                  "dead_point)")


def unbounded(check: CheckArrays) -> CheckArrays:
    """A torque check of a law that breaks the dead-point rule: unbounded, saying why."""
    n = len(check.value)
    return replace(check, value=np.full(n, np.inf),
                   notes=np.full(n, UNBOUNDED_NOTE, dtype=object))


UNBOUNDED_CHECKS = ("peak", "rms", "drive_peak_current", "drive_rms_current")
"""The checks of the peak and RMS torques (and the drive's currents they need): unbounded
where a law breaks the dead-point rule."""


def unbounded_checks(checks: list[CheckArrays]) -> list[CheckArrays]:
    """``checks`` with those of the torques unbounded (:func:`unbounded`)."""
    return [unbounded(c) if c.name in UNBOUNDED_CHECKS else c for c in checks]


def singular_metrics(metrics: CycleMetrics) -> CycleMetrics:
    """The metrics of a law that breaks the dead-point rule: its peak and RMS torques are
    not numbers (NaN, so results hold None and reports a verdict, never inf); the peak
    ratio is unbounded (its check fails, :func:`unbounded`)."""
    n = len(metrics.peak_torque)
    return replace(metrics, peak_torque=np.full(n, np.nan), peak_ratio=np.full(n, np.inf),
                   rms_torque=np.full(n, np.nan))


def refined_max(values: np.ndarray, u: np.ndarray) -> np.ndarray:
    """The largest value of each row of samples at the increasing points u, refined by
    the parabola through the largest sample and its two neighbours (a smooth peak between
    samples is then read to the third order of their spacing, not the second)."""
    m = values.shape[1]
    i = np.clip(np.argmax(values, axis=1), 1, m - 2)
    rows = np.arange(values.shape[0])
    x0, x1, x2 = u[i - 1], u[i], u[i + 1]
    f0, f1, f2 = values[rows, i - 1], values[rows, i], values[rows, i + 1]
    d01 = (f1 - f0) / (x1 - x0)
    curvature = ((f2 - f1) / (x2 - x1) - d01) / (x2 - x0)
    best = np.max(values, axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        # p(x) = f0 + d01 (x - x0) + c (x - x0)(x - x1): p'(x*) = 0
        vertex = 0.5 * (x0 + x1) - d01 / (2.0 * curvature)
        top = f0 + d01 * (vertex - x0) + curvature * (vertex - x0) * (vertex - x1)
    inside = (curvature < 0.0) & (vertex > x0) & (vertex < x2) & np.isfinite(top)
    return np.where(inside, np.maximum(best, top), best)


def dead_point_check(issues: tuple[str, ...], n: int) -> CheckArrays:
    """``dead_point``: passes when the law meets the paper's rule at every dead point
    the output reaches; else fails for every candidate with the reasons as its note."""
    notes = np.full(n, "; ".join(issues), dtype=object) if issues else None
    return CheckArrays("dead_point", np.full(n, np.inf if issues else 0.0), np.ones(n), "",
                       0.0, None, notes)


def crank_drive(design: Design, drive: Drive, profile: LinkageProfile) -> Drive:
    """The drive of the gear stages with the linkage's largest equivalent inertia at
    the crank as their load (for the inertia ratio: the worst over a turn)."""
    load = replace(design.load, inertia=profile.max_inertia, damping=0.0, friction=0.0,
                   torque=0.0)
    return Drive(load, drive.transmissions, drive.option)


def shorthand_cycle(design: Design) -> Design:
    """A task with a return move as the cycle it means (move, dwell, move back, dwell):
    through a linkage the way back starts where the way out stopped."""
    from sizer.model.cycle import from_task

    return replace(design, cycle=from_task(design.task))


def evaluate_linkage(design: Design, law: MotionLaw, motors: MotorArrays, drive: Drive):
    """(duration, metrics, checks, feasible) of one law through the design's linkage."""
    from sizer.sizing.checks import feasible as all_pass
    from sizer.sizing.minimum_duration import minimum_duration

    if design.task.return_move:  # the cycle it means; the task reports its moves' T
        from sizer.sizing.linkage_cycle import evaluate_linkage_cycle

        cyc = shorthand_cycle(design)
        assert cyc.cycle is not None
        cycle_time, metrics, checks, feasible = evaluate_linkage_cycle(cyc, law, motors, drive)
        if design.task.minimize:  # both moves free, one scale: T = s
            T = (cycle_time - cyc.cycle.fixed_time) / len(cyc.cycle.moves)
        else:
            T = np.full(len(motors), design.task.duration)
        return T, metrics, checks, feasible

    profile = linkage_profile(design, law)
    drive = crank_drive(design, drive, profile)
    calculator = LinkageCalculator(profile, design.task, drive, motors,
                                   design.limits.thermal_speed, law)
    n = len(motors)
    point = dead_point_check(profile.issues, n)
    if design.task.minimize and not profile.issues:
        solution = minimum_duration(calculator, design.limits)
        checks = [point, *solution.checks]
        return solution.duration, solution.metrics, checks, solution.feasible
    T = np.full(n, design.task.duration if design.task.duration is not None else np.nan)
    if design.task.minimize:  # the law is infeasible at any duration: show one
        T = calculator.initial_guess()
    metrics = calculator.evaluate(T)
    if profile.issues:  # the crank's motion is singular: no torque to report
        metrics = singular_metrics(metrics)
    checks = [point, *evaluate_checks(metrics, motors, drive, design.limits,
                                      design.task.linear)]
    if profile.issues:
        checks = unbounded_checks(checks)
    feasible = all_pass(checks)
    duration = np.where(feasible, T, np.nan) if design.task.minimize else T
    return duration, metrics, checks, feasible


def result_calculator(design: Design, motor, law: MotionLaw, transmission=None
                      ) -> tuple[LinkageProfile, Drive, LinkageCalculator]:
    """The profile, drive and calculator of one result (a motor, a law, the result's
    transmission) through the design's linkage."""
    profile = linkage_profile(design, law)
    drive = crank_drive(design, Drive(design.load, transmission or design.transmission),
                        profile)
    calculator = LinkageCalculator(profile, design.task, drive,
                                   MotorArrays.of([motor], design.limits.envelope),
                                   design.limits.thermal_speed, law)
    return profile, drive, calculator


def linkage_curve(design: Design, motor, law: MotionLaw, duration: float,
                  transmission=None, samples: int = 401):
    """The TaskCurve of one candidate through the linkage (for plots and reports): the
    move at ``samples`` instants and the dwell holding the output."""
    from sizer.sizing.profile import TaskCurve, continuous_region, intermittent_region

    if design.cycle is not None or design.task.return_move:
        cyc = design if design.cycle is not None else shorthand_cycle(design)
        return _cycle_curve(cyc, motor, law, duration, transmission, samples)
    profile, drive, calculator = result_calculator(design, motor, law, transmission)
    T = np.array([duration])
    metrics = calculator.evaluate(T)
    speed, torque, _ = calculator.motor_samples(T)
    pick = np.flatnonzero(profile.weights == 0.0)  # the uniform grid, in order
    pick = pick[np.linspace(0, len(pick) - 1, samples).round().astype(int)]
    u = profile.u[pick]
    times, position = [duration * u], [profile.s[pick]]
    load_speed, load_acceleration = [profile.s1[pick] / duration], \
        [profile.s2[pick] / duration**2]
    motor_speed, torques = [speed[0, pick]], [torque[0, pick]]
    motor_acceleration = [float(drive.ratio[0]) * profile.theta2[pick] / duration**2]
    if design.task.dwell > 0.0:
        hold = profile.hold / float(drive.ratio[0] * drive.efficiency[0])
        times.append(np.array([duration, duration + design.task.dwell]))
        position.append(np.full(2, profile.s[pick][-1]))
        for series in (load_speed, load_acceleration, motor_speed, motor_acceleration):
            series.append(np.zeros(2))
        torques.append(np.full(2, hold))
    total = motor.inertia + float(drive.driven_inertia[0])
    return TaskCurve(
        motor=motor.id, law=law.spec, duration=duration, ratio=float(drive.ratio[0]),
        time=np.concatenate(times), position=np.concatenate(position),
        load_speed=np.concatenate(load_speed),
        load_acceleration=np.concatenate(load_acceleration),
        motor_speed=np.concatenate(motor_speed),
        motor_acceleration=np.concatenate(motor_acceleration),
        motor_torque=np.concatenate(torques), rms_torque=float(metrics.rms_torque[0]),
        thermal_speed=float(metrics.thermal_speed[0]),
        peak_torque=float(metrics.peak_torque[0]), max_speed=float(metrics.max_speed[0]),
        continuous_region=continuous_region(motor, design.limits.envelope),
        intermittent_region=intermittent_region(motor, design.limits.envelope),
        total_inertia=total)


@dataclass(frozen=True)
class LinkageCurve:
    """One candidate through the linkage over the crank angle: the crank angle (rad,
    increasing or decreasing as the crank turns), the ratio ds/dtheta and the motor
    torque at the result's duration, and the linkage's dead points (name: angle)."""

    theta: np.ndarray
    ratio: np.ndarray
    motor_torque: np.ndarray
    dead_points: dict[str, float]
    linear: bool


def linkage_curve_of(design: Design, motor, law: MotionLaw, duration: float,
                     transmission=None) -> LinkageCurve:
    """The data of the ratio-and-torque plot of one result (sizer plot --linkage)."""

    stage = design.transmission.linkage
    assert stage is not None
    if design.cycle is not None or design.task.return_move:
        from sizer.sizing.linkage_cycle import cycle_samples

        cyc = design if design.cycle is not None else shorthand_cycle(design)
        parts = [p for p in cycle_samples(cyc, motor, law, duration, transmission)[0]
                 if np.all(np.isfinite(p["ratio"]))]  # the moves
        theta, ratio, torque = (np.concatenate([p[k] for p in parts])
                                for k in ("theta", "ratio", "motor_torque"))
        return LinkageCurve(theta, ratio, torque, _dead_points(stage), stage.output_linear)
    profile, _, calculator = result_calculator(design, motor, law, transmission)
    _, torque, _ = calculator.motor_samples(np.array([duration]))
    pick = np.flatnonzero(profile.weights == 0.0)
    return LinkageCurve(profile.theta[pick], profile.ratio[pick], torque[0, pick],
                        _dead_points(stage), stage.output_linear)


def _dead_points(stage: LinkageStage) -> dict[str, float]:
    """The linkage's dead points by name: crank angles (rad), the output's, and a driven
    rocker's (crank and coupler in line)."""
    from sizer.mechanics.linkages.of_stage import linkages_of, output_name

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


def _cycle_curve(design: Design, motor, law: MotionLaw, duration: float, transmission,
                 samples: int):
    """The TaskCurve of a cycle through the linkage (the moves and the dwells)."""
    from sizer.sizing.linkage_cycle import cycle_samples
    from sizer.sizing.profile import TaskCurve, continuous_region, intermittent_region
    parts, metrics, calculator = cycle_samples(design, motor, law, duration, transmission,
                                               samples)

    def joined(key: str) -> np.ndarray:
        return np.concatenate([p[key] for p in parts])

    segments, start = [], 0.0
    for segment, p in zip(design.cycle.segments, parts, strict=True):
        end = float(p["time"][-1])
        segments.append((segment.name or ("move" if p["ratio"].size > 2 or np.all(
            np.isfinite(p["ratio"])) else "dwell"), start, end))
        start = end
    return TaskCurve(
        motor=motor.id, law=law.spec, duration=duration,
        ratio=float(calculator.drive.ratio[0]), time=joined("time"),
        position=joined("position"), load_speed=joined("load_speed"),
        load_acceleration=joined("load_acceleration"), motor_speed=joined("motor_speed"),
        motor_acceleration=joined("motor_acceleration"), motor_torque=joined("motor_torque"),
        rms_torque=float(metrics.rms_torque[0]), thermal_speed=float(metrics.thermal_speed[0]),
        peak_torque=float(metrics.peak_torque[0]), max_speed=float(metrics.max_speed[0]),
        continuous_region=continuous_region(motor, design.limits.envelope),
        intermittent_region=intermittent_region(motor, design.limits.envelope),
        total_inertia=motor.inertia + float(calculator.drive.driven_inertia[0]),
        segments=tuple(segments))


def linkage_breakdown(design: Design, motor, law: MotionLaw, duration: float,
                      transmission=None):
    """The move and the dwell of a task through a linkage, for one result, as the
    segment table shows them (sizer.sizing.segment_breakdown's rows)."""
    from sizer.sizing.segment_breakdown import SegmentBreakdown, SegmentRow

    if design.cycle is not None or design.task.return_move:
        from sizer.sizing.linkage_cycle import cycle_breakdown

        cyc = design if design.cycle is not None else shorthand_cycle(design)
        return cycle_breakdown(cyc, motor, law, duration, transmission)
    profile, drive, calculator = result_calculator(design, motor, law, transmission)
    T = np.array([duration])
    metrics = calculator.evaluate(T)
    speed, torque, _ = calculator.motor_samples(T)
    move_square = duration * float(torque[0] ** 2 @ profile.weights)
    dwell = design.task.dwell
    hold = abs(profile.hold) / float(drive.ratio[0] * drive.efficiency[0])
    total = move_square + dwell * hold**2
    first = float(profile.s2[np.argmin(profile.u)]) / duration**2
    last = float(profile.s2[np.argmax(profile.u)]) / duration**2
    rows = [SegmentRow(
        name="move", kind="move", law=law.spec, start=0.0, end=duration,
        peak_torque=float(metrics.peak_torque[0]),
        rms_torque=math.sqrt(move_square / duration),
        rms_share=move_square / total if total > 0 else 0.0,
        peak_speed=float(metrics.max_speed[0]),
        energy=duration * float((torque[0] * speed[0]) @ profile.weights),
        acceleration_step=first)]
    if dwell > 0.0:
        rows.append(SegmentRow(
            name="dwell", kind="dwell", law=None, start=duration, end=duration + dwell,
            peak_torque=hold, rms_torque=hold,
            rms_share=dwell * hold**2 / total if total > 0 else 0.0, peak_speed=0.0,
            energy=0.0, acceleration_step=-last))
    return SegmentBreakdown(motor.id, law.spec, duration + dwell,
                            float(metrics.rms_torque[0]), tuple(rows))
