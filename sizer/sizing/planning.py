"""Planning without a motor: each law's shortest duration under the load's own limits
(book sec. 5.2.1, eq. 5.4, Table 5.1).

With only the load's maximum speed, acceleration and jerk (``limits.max_speed``,
``max_acceleration``, ``max_jerk``), a rest-to-rest move of h by a law with shape
coefficients C_v, C_a, C_j (sizer.laws.coefficients) needs at least

    T_min = max(C_v h / v_max, sqrt(C_a h / a_max), cbrt(C_j h / j_max))

(eq. 5.6 at the limits; a limit not given is no bound). The largest term is the binding
limit. For a given duration T the book's scaling factor (eq. 5.4, t = lambda t') is

    lambda = min(v_max / (C_v h / T), sqrt(a_max / (C_a h / T^2)), cbrt(j_max / (C_j h / T^3)))

so lambda = T / T_min: the move is feasible when lambda >= 1, and T / lambda is the
shortest duration of the same shape. A law whose acceleration jumps (jerk impulses,
``jerk_bounded`` false) cannot meet a jerk limit: T_min is infinite and lambda 0.

A machine cycle is planned segment by segment: its rest-to-rest moves and dwells (runs
and moves that start or end moving change shape with the duration: refused). With
``minimize`` the free durations T_i = w_i s share one scale s (sizer.model.cycle), the
smallest s meeting every free move's T_min; fixed moves must meet their own. With given
durations lambda is the smallest of the moves' lambdas.

Vectorized over the laws with numpy; pure (no printing, no files).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from sizer.errors import UserError
from sizer.laws import LawChoice
from sizer.model.cycle import Cycle, Move, Run
from sizer.model.domain import Design, Limits

LIMIT_NAMES = ("speed", "acceleration", "jerk")
"""The load's limits, in the order of the terms of T_min and lambda."""

TOLERANCE = 1e-9
"""Relative tolerance of lambda >= 1 (a duration exactly at T_min is feasible), as the
sizing checks (sizer.sizing.checks.TOLERANCE)."""


@dataclass(frozen=True)
class LoadLimits:
    """The load's maximum speed, acceleration and jerk (SI at the load; None: no limit)."""

    max_speed: float | None = None
    max_acceleration: float | None = None
    max_jerk: float | None = None

    @classmethod
    def of(cls, limits: Limits) -> LoadLimits:
        return cls(limits.max_speed, limits.max_acceleration, limits.max_jerk)

    @property
    def given(self) -> bool:
        return any(v is not None for v in self.values)

    @property
    def values(self) -> tuple[float | None, float | None, float | None]:
        return (self.max_speed, self.max_acceleration, self.max_jerk)


@dataclass(frozen=True)
class Shapes:
    """The coefficients of L laws as arrays; C_j is inf where the jerk has impulses."""

    C_v: np.ndarray
    C_a: np.ndarray
    C_j: np.ndarray

    @classmethod
    def of(cls, laws: Sequence[LawChoice]) -> Shapes:
        rows = []
        for choice in laws:
            c = choice.law.coefficients
            rows.append((c.C_v, c.C_a, c.C_j if c.jerk_bounded else math.inf))
        array = np.array(rows, dtype=float).reshape(-1, 3)
        return cls(array[:, 0], array[:, 1], array[:, 2])


def minimum_durations(h: float, shapes: Shapes, limits: LoadLimits) -> np.ndarray:
    """The three terms of T_min per law, shape (3, L): C_v h / v_max, sqrt(C_a h /
    a_max), cbrt(C_j h / j_max); 0 for a limit not given, inf for C_j = inf."""
    h = abs(h)
    v, a, j = limits.values
    zeros = np.zeros_like(shapes.C_v)
    with np.errstate(invalid="ignore"):
        terms = np.stack([
            zeros if v is None else shapes.C_v * h / v,
            zeros if a is None else np.sqrt(shapes.C_a * h / a),
            zeros if j is None else np.cbrt(shapes.C_j * h / j),
        ])
    return np.where(np.isnan(terms), 0.0, terms)  # h = 0: nothing to bound


def scaling_factors(h: float, T: float | np.ndarray, shapes: Shapes,
                    limits: LoadLimits) -> np.ndarray:
    """The three terms of the book's lambda (eq. 5.4) per law, shape (3, L): v_max /
    |q'|_max, sqrt(a_max / |q''|_max), cbrt(j_max / |q'''|_max) with |q^(n)|_max =
    C_n h / T^n (eq. 5.6); inf for a limit not given, 0 for C_j = inf."""
    h = abs(h)
    v, a, j = limits.values
    infinite = np.full_like(shapes.C_v, np.inf)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.stack([
            infinite if v is None else v / (shapes.C_v * h / T),
            infinite if a is None else np.sqrt(a / (shapes.C_a * h / T**2)),
            infinite if j is None else np.cbrt(j / (shapes.C_j * h / T**3)),
        ])


@dataclass(frozen=True)
class SegmentPlan:
    """One move of a law's plan: its duration (given, or planned with minimize), its
    T_min terms, lambda = duration / T_min, and the limit that binds it."""

    name: str
    displacement: float
    law: str
    duration: float
    T_vel: float
    T_acc: float
    T_jerk: float
    lam: float
    binding: str | None
    """'speed', 'acceleration' or 'jerk'; None when no limit bounds the move."""
    free: bool = False
    """Its duration is one of the free ones (scaled with minimize)."""

    @property
    def T_min(self) -> float:
        return max(self.T_vel, self.T_acc, self.T_jerk)


@dataclass(frozen=True)
class LawPlan:
    """A law's answer with no motor.

    minimize: ``T_min`` the shortest move duration (the task) or cycle time (a cycle),
    ``scale`` the free durations' scale s. Given durations: ``lam`` the book's lambda,
    ``T_min`` = duration / lambda. ``binding`` and ``segment``: the limit and the move
    that decide; ``reason`` why an infeasible law is infeasible ("" when feasible).
    """

    law: str
    feasible: bool
    reason: str
    T_min: float
    duration: float | None
    """The given move duration (task) or cycle time (cycle); None with minimize."""
    lam: float | None
    scale: float | None
    binding: str | None
    segment: str | None
    segments: tuple[SegmentPlan, ...]


@dataclass(frozen=True)
class PlanningResult:
    """Every law's plan, ranked: feasible first, by T_min (minimize) or by lambda
    (largest first), then in the design's order."""

    name: str
    minimize: bool
    linear: bool
    task: bool
    """True for the task shorthand (T is the move's duration), False for a cycle."""
    limits: LoadLimits
    plans: tuple[LawPlan, ...]

    @property
    def any_feasible(self) -> bool:
        return any(p.feasible for p in self.plans)


def plans_without_motor(design: Design) -> bool:
    """A design to plan: no motors, and the load's limits give something to plan with."""
    return not design.motors and LoadLimits.of(design.limits).given


def plan(design: Design) -> PlanningResult:
    """Each of the design's laws planned against the load's limits (module docstring);
    a UserError for a design that cannot be planned this way."""
    limits = LoadLimits.of(design.limits)
    if not limits.given:
        raise UserError("nothing to plan without a motor: give limits.max_speed, "
                        "max_acceleration or max_jerk", field="limits")
    cycle = design.machine_cycle
    _check_plannable(cycle)
    laws = tuple(design.laws)
    usable = [choice for choice in laws if choice.is_fixed]
    plans = {choice.text: _not_fixed(choice) for choice in laws if not choice.is_fixed}
    if usable:
        for law_plan in _plan_laws(cycle, usable, limits):
            plans[law_plan.law] = law_plan
    ordered = [plans[choice.text] for choice in laws]
    minimize = cycle.minimize
    ranked = sorted(range(len(ordered)), key=lambda i: (
        not ordered[i].feasible,
        ordered[i].T_min if minimize else -(ordered[i].lam or 0.0), i))
    return PlanningResult(design.name, minimize, cycle.linear, cycle.shorthand is not None,
                          limits, tuple(ordered[i] for i in ranked))


def _check_plannable(cycle: Cycle) -> None:
    if not cycle.moves:
        raise UserError("nothing to plan without a motor: the cycle has no move",
                        field="cycle")
    if cycle.share.goal is not None:
        raise UserError(f"share: {{{cycle.share.value}}} splits the cycle time for each "
                        "motor (its RMS torque or energy): without motors give a share rule "
                        "(equal, displacement, sqrt_displacement or weights)",
                        field="cycle.share")
    for index, segment in enumerate(cycle.segments):
        name = segment.name or f"segment {index + 1}"
        if isinstance(segment, Run):
            raise UserError(f"{name}: a run cannot be planned without a motor (only "
                            "rest-to-rest moves and dwells); give motors to size it",
                            field="cycle")
        if isinstance(segment, Move) and not segment.rest_to_rest:
            raise UserError(f"{name}: a move that starts or ends moving cannot be planned "
                            "without a motor (its shape changes with its duration); give "
                            "motors to size it", field="cycle")


def _not_fixed(choice: LawChoice) -> LawPlan:
    what = "shaped for the load's mode at each duration" if choice.open_shaped else \
        f"its {', '.join(choice.auto)} chosen against a motor (auto)"
    return LawPlan(choice.text, False, f"not planned: {what}; give its parameters",
                   math.inf, None, None, None, None, None, ())


def _move_laws(move: Move, laws: Sequence[LawChoice]) -> list[LawChoice]:
    """The law of a move per row: its own, or each row's."""
    return [move.law] * len(laws) if move.law is not None else list(laws)


def _plan_laws(cycle: Cycle, laws: Sequence[LawChoice],
               limits: LoadLimits) -> list[LawPlan]:
    """The plans of fixed laws, vectorized over them (one pass per move)."""
    n = len(laws)
    free = set(cycle.free)
    weights = cycle.weights()
    moves = [(i, s) for i, s in enumerate(cycle.segments) if isinstance(s, Move)]
    terms, shapes = {}, {}
    for i, move in moves:
        own = _move_laws(move, laws)
        if move.law is not None and not move.law.is_fixed:
            raise UserError(f"{move.name or f'segment {i + 1}'}: its law {move.law.text} has "
                            "auto parameters, chosen against a motor; give their values",
                            field="cycle")
        shapes[i] = Shapes.of(own)
        terms[i] = minimum_durations(move.displacement, shapes[i], limits)
    if cycle.minimize:
        scale = np.zeros(n)
        for i, _ in moves:
            if i in free and weights[i] > 0.0:
                scale = np.maximum(scale, terms[i].max(axis=0) / weights[i])
        cycle_time = cycle.fixed_time + scale * math.fsum(weights)
    else:
        given = cycle.cycle_time
        scale = np.full(n, 0.0 if given is None else
                        (given - cycle.fixed_time) / math.fsum(weights))
        cycle_time = np.full(n, math.fsum(s.duration or 0.0 for s in cycle.segments)
                             if given is None else given)
    durations = {i: np.where(i in free, weights[i] * scale, move.duration or 0.0)
                 for i, move in moves}
    lams = {i: scaling_factors(move.displacement, durations[i], shapes[i], limits)
            for i, move in moves}
    plans = []
    names = [s.name or f"segment {i + 1}" for i, s in enumerate(cycle.segments)]
    for k, choice in enumerate(laws):
        segs = []
        for i, move in moves:
            t = terms[i][:, k]
            lam = lams[i][:, k]
            bound = bool(np.any(t > 0.0))
            segs.append(SegmentPlan(
                names[i], move.displacement, (move.law or choice).text, float(durations[i][k]),
                float(t[0]), float(t[1]), float(t[2]),
                float(np.nan_to_num(lam.min(), nan=0.0, posinf=np.inf)),
                LIMIT_NAMES[int(np.argmax(t))] if bound else None, i in free))
        plans.append(_law_plan(choice.text, cycle, segs, float(scale[k]),
                               float(cycle_time[k])))
    return plans


def _law_plan(law: str, cycle: Cycle, segs: list[SegmentPlan], scale: float,
              cycle_time: float) -> LawPlan:
    task = cycle.shorthand is not None
    jerk_blocked = [s for s in segs if math.isinf(s.T_jerk)]
    if jerk_blocked:
        seg = jerk_blocked[0]
        own = "" if seg.law == law else f" ({seg.law}, its own law)"
        return LawPlan(law, False, f"{seg.name}: the law's acceleration jumps{own} (jerk "
                       "impulses): no duration meets limits.max_jerk",
                       math.inf, None if cycle.minimize else _duration(task, segs, cycle_time),
                       None if cycle.minimize else 0.0, None, "jerk", jerk_blocked[0].name,
                       tuple(segs))
    if cycle.minimize:
        fixed_short = [s for s in segs if not s.free and s.lam < 1.0 - TOLERANCE]
        # the free move that sets the scale is at its T_min: the smallest lambda, 1
        deciding = min((s for s in segs if s.free and s.binding is not None),
                       key=lambda s: s.lam, default=None)
        if fixed_short:
            s = fixed_short[0]
            return LawPlan(law, False, f"{s.name}: its fixed duration {s.duration:.6g} s is "
                           f"below its T_min {s.T_min:.6g} s ({s.binding} limit)",
                           math.inf, None, None, scale, s.binding, s.name, tuple(segs))
        T_min = segs[0].duration if task else cycle_time
        binding = deciding.binding if deciding is not None else None
        segment = deciding.name if deciding is not None else None
        return LawPlan(law, True, "", T_min, None, None, scale, binding, segment, tuple(segs))
    tightest = min(segs, key=lambda s: s.lam)
    feasible = tightest.lam >= 1.0 - TOLERANCE
    duration = _duration(task, segs, cycle_time)
    reason = "" if feasible else (
        f"{tightest.name}: lambda {tightest.lam:.6g} < 1: the {tightest.binding} limit is "
        f"exceeded (T_min {tightest.T_min:.6g} s > {tightest.duration:.6g} s)")
    return LawPlan(law, feasible, reason, duration / tightest.lam, duration, tightest.lam,
                   None, tightest.binding, tightest.name, tuple(segs))


def _duration(task: bool, segs: list[SegmentPlan], cycle_time: float) -> float:
    return segs[0].duration if task else cycle_time
