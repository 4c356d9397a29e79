"""The requirements of a machine cycle of several segments, for many candidates at once.

A cycle (sizer.model.cycle) is a list of moves, constant-speed runs and dwells, each with
its own load (the design's plus the segment's added inertia and external torque). For a
scale s of the free durations (book sec. 5.2: T_i = w_i s, the fixed ones stay) every
segment is evaluated exactly and the cycle's requirements combine them (DESIGN.md):

- peaks (torque, ratio to the intermittent region, speeds, stage outputs) are the
  maxima over the segments;
- the RMS torque is the square root of the sum of the segments' integrals of tau^2 over
  the cycle time (the same for each stage output and for the RMS speed).

The weights w_i may be each candidate's own (an array (candidates, segments)): with
``share: {optimize: rms | energy}`` and a cycle time, the split that minimizes the goal
for each motor (sizer.allocation, from this module's figures of each free move).

A rest-to-rest move is one move of the single-law engine (sizer.sizing.move); a move
with boundary speeds is a piecewise polynomial of each candidate's duration
(sizer.laws.boundary_speeds), evaluated exactly by sizer.sizing.move.polynomial_move; a
move between boundary speeds by a law of fixed shape (a table's span, at its fixed
duration: :meth:`SegmentCycle._shaped_move`) is the law's own pieces scaled by h/T^k,
through polynomial_move where they are polynomials. A run
has a constant torque; a dwell holds its constant load (holding counts as driving, as
in the single-law engine).

What shape a machine cycle has, for the engine (issue 12): the task shorthand or not
(:func:`shorthand_task`: the engine's closed-form path), the scale of its free durations
(:func:`given_scale`), and the laws that are ranked over it (:func:`ranked_laws`).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, TypeVar

import numpy as np

from sizer.errors import UserError
from sizer.laws import LawChoice, MotionLaw, law_choice, make_law
from sizer.laws.per_move import LawsPerMove, PerMoveChoice, RankedLaw
from sizer.laws.row_laws import RowLaws
from sizer.mechanics import Drive
from sizer.mechanics.loads import linear_load
from sizer.model.cycle import (
    Cycle,
    Dwell,
    Move,
    Run,
    Segment,
    ShareRule,
    boundary_laws,
    fixed_shape,
    shorthand_task,
)
from sizer.model.domain import Design, Limits, Load, Task, ThermalSpeedRule
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.checks import TOLERANCE, evaluate_checks, worst_slack
from sizer.sizing.evaluation import (
    SAMPLES,
    CycleMetrics,
    CyclePiece,
    RmsCurve,
    SegmentPart,
    held_piece,
)
from sizer.sizing.move import (
    CycleCalculator,
    MoveFigures,
    RmsModel,
    _safe_ratio,
    law_samples,
    polynomial_move,
    rule_speed,
)

if TYPE_CHECKING:
    from sizer.allocation import LawSplit


def single_task(design: Design) -> Task:
    """The task of a design the single-law engine sizes: laws chosen per duration (`auto`
    shapes, shaped laws without f_T) are sized for it only (sizer.io refuses them in
    other cycles, at their line)."""
    task = shorthand_task(design.machine_cycle)
    if task is None:
        raise UserError("`auto` shape parameters and shaped laws without f_T are chosen for "
                        "the task shorthand only, not yet for a cycle of segments",
                        field="laws")
    return task


def given_scale(cycle: Cycle) -> float:
    """The scale s of the free durations when it is not minimized: from the cycle time
    target (T_i = w_i s fill what the fixed durations leave), or 1 when nothing is free."""
    weights = math.fsum(cycle.weights())
    if cycle.cycle_time is None or weights == 0.0:
        return 1.0
    return (cycle.cycle_time - cycle.fixed_time) / weights


def ranked_laws(design: Design) -> tuple[LawChoice | PerMoveChoice, ...]:
    """The law choices the ranking runs over: the design's laws (those that can meet the
    boundary speeds of every move that names no law of its own), or with ``share:
    {optimize: GOAL, laws: per_move}`` one choice of a law of theirs per move; with a
    cycle whose every move names its law, that cycle once, labelled by its first move's
    law."""
    cycle = design.machine_cycle
    open_moves = [m for m in cycle.moves if m.law is None]
    if not open_moves:
        first = cycle.moves[0].law if cycle.moves else None
        return (first or law_choice("cycloidal"),)
    offered = _offered_laws(design)  # fixed laws: sizer.io refuses others in a cycle
    return (PerMoveChoice(offered),) if cycle.share.per_move else offered


def _offered_laws(design: Design) -> tuple[LawChoice, ...]:
    """The design's laws that can meet the boundary speeds of every move that names no
    law of its own."""
    cycle = design.machine_cycle
    if not design.laws:
        raise UserError("no motion laws to consider" + (
            "" if cycle.shorthand else " for the moves that name none"), field="laws")
    try:
        return boundary_laws(cycle, design.laws)
    except ValueError as error:  # sizer.io refuses it at the design's `laws:`
        raise UserError(str(error), field="laws") from None


def left_out_laws(design: Design) -> tuple[str, ...]:
    """The texts of the design's laws the ranking leaves out (no form with the moves'
    boundary speeds or accelerations), for the notes."""
    if not any(m.law is None for m in design.machine_cycle.moves):
        return ()
    kept = set(_offered_laws(design))
    return tuple(spec.text for spec in design.laws if spec not in kept)


@dataclass(frozen=True)
class SegmentFigures(MoveFigures):
    """One segment's requirements per candidate (arrays, SI): a move's figures
    (sizer.sizing.move.MoveFigures: the peaks and the integrals over the
    segment of tau^2, each stage's output^2, omega^2, |omega|, tau*omega), its duration
    and, for a rest-to-rest move when asked for, its RMS model
    (sizer.sizing.move.RmsModel)."""

    duration: np.ndarray
    rms_model: RmsModel | None = None
    end_accelerations: tuple[np.ndarray, np.ndarray] | None = None
    """A move's load acceleration at its start and at its end (signed; None: 0, a run or a
    dwell): where a join's two sides differ, the jerk there is an impulse."""


BOUND_SPAN = 16
"""The grid of scales a move with boundary speeds is first read at: 2 BOUND_SPAN + 1
points, factors of sqrt 2 apart, centred on the search's start."""

BOUND_CHUNKS = ((0, BOUND_SPAN + 1), (BOUND_SPAN + 1, BOUND_SPAN + 7),
                (BOUND_SPAN + 7, 2 * BOUND_SPAN + 1))
"""The grid is read in these slices from below, each for the candidates that have not
passed yet (only the first passing point and the one below it are used): most pass within
a factor 2 of the start."""

JOIN_TOLERANCE = 1e-9
"""A step of the acceleration at a join counts when it exceeds this share of the cycle's
acceleration scale (the largest |h|/T^2 of its moves)."""


@dataclass(frozen=True)
class CycleRmsModel:
    """The cycle's RMS torque near the scales s0 it was built at: each free rest-to-rest
    move's RMS model (exact at s0, second-order near: sizer.sizing.move.RmsModel), the
    fixed segments' integrals (constant) and the free dwells' (linear in s). With it
    sizer.sizing.shortest_duration.rms_crossing finds where the RMS check binds in a few
    rounds, as for a single law."""

    moves: tuple[tuple[RmsCurve, float], ...]
    constant: np.ndarray
    hold_rate: np.ndarray
    fixed_time: float
    weight_sum: float

    def rms(self, s: np.ndarray, index: np.ndarray | None = None) -> np.ndarray:
        def pick(x):
            return x if index is None else x[index]

        square = pick(self.constant) + pick(self.hold_rate) * s
        with np.errstate(over="ignore", invalid="ignore"):
            for model, w in self.moves:
                square = square + np.square(model.rms(w * s, index)) * (w * s)
            mean = square / (self.fixed_time + self.weight_sum * s)
        return np.sqrt(np.where(np.isnan(mean), np.inf, mean))


def rms_floor(rates: list[np.ndarray], fixed: np.ndarray, weights: np.ndarray,
              n: int) -> np.ndarray | None:
    """A torque the RMS over a cycle exceeds at every scale s, from each segment's lower
    bound on its mean square (``rates``), its fixed duration (nan: free) and its weight:
    the mean square is at least (a + b s)/(F + W s) (F, a the fixed segments' time and
    integral, W, b the free ones' weights and theirs), monotone in s, so never below its
    smaller limit (s -> 0 or s -> inf); None where no segment has a positive time."""
    fixed_time, fixed_sum = 0.0, np.zeros(n)
    free_weight, free_sum = 0.0, np.zeros(n)
    for rate, duration, w in zip(rates, fixed, weights, strict=True):
        if np.isfinite(duration):
            fixed_time, fixed_sum = fixed_time + duration, fixed_sum + rate * duration
        else:
            free_weight, free_sum = free_weight + w, free_sum + rate * w
    limits = [x / t for x, t in ((fixed_sum, fixed_time), (free_sum, free_weight)) if t > 0.0]
    return np.sqrt(np.minimum.reduce(limits)) if limits else None


def segment_load(base: Load, segment: Segment) -> Load:
    """The design's load with the segment's added inertia (or mass) and torque (force).

    The added load is built as the design's own linear load is (one formula,
    :func:`sizer.mechanics.loads.linear_load`): on a linear axis a picked-up part's
    weight adds mu m g cos(incline) of friction and m g sin(incline) of gravity, with the
    design's coefficient and incline (the segment's ``SegmentLoad``); on a rotary axis
    both are 0 and only the inertia and torque add.
    """
    added = segment.load
    if added.is_zero:
        return base
    extra = linear_load(added.inertia, incline=added.incline,
                        friction_coefficient=added.friction_coefficient, force=added.torque)
    return replace(base, inertia=base.inertia + extra.inertia,
                   friction=base.friction + extra.friction,
                   torque=base.torque + extra.torque)


def normalized_move(basis, move: Move, T: np.ndarray) -> np.ndarray:
    """The normalized shape q_N(u) of a move between boundary conditions for durations T,
    as piece coefficients (n, P, d+1) (sizer.laws.boundary_speeds): s = v T / h and, where
    the move gives boundary accelerations, r = a T^2 / h."""
    h = move.displacement
    T = np.asarray(T, dtype=float)
    s0, s1 = move.start_speed * T / h, move.end_speed * T / h
    if move.start_acceleration == 0.0 and move.end_acceleration == 0.0:
        return basis.combine(s0, s1)
    return basis.combine(s0, s1, r0=move.start_acceleration * T * T / h,
                         r1=move.end_acceleration * T * T / h)


def cycle_laws(cycle: Cycle, law: RankedLaw | None) -> tuple[MotionLaw | None, ...]:
    """The law of each segment: a move's own law, else ``law`` (the one being ranked; a
    law per move, sizer.laws.per_move, gives the moves that name none theirs in order)."""
    if isinstance(law, LawsPerMove):
        open_moves = sum(1 for s in cycle.segments if isinstance(s, Move) and not s.law)
        if open_moves != len(law.laws):
            raise ValueError(f"{law.spec} gives {len(law.laws)} laws for {open_moves} moves "
                             "that name none")
        spread = iter(law.laws)
        return tuple((make_law(s.law) if s.law else next(spread)) if isinstance(s, Move)
                     else None for s in cycle.segments)
    return _moves_with(cycle, law)


def segment_laws(cycle: Cycle, law: RankedLaw | RowLaws | None
                 ) -> tuple[MotionLaw | RowLaws | None, ...]:
    """:func:`cycle_laws` where several laws may stand for one over the candidates' rows
    (RowLaws, in a cycle whose moves are all rest to rest: sizer.sizing.engine.rows_cycle):
    the moves that name no law move with each row's own."""
    return _moves_with(cycle, law) if isinstance(law, RowLaws) else cycle_laws(cycle, law)


_Law = TypeVar("_Law", MotionLaw, RowLaws)


def _moves_with(cycle: Cycle, law: _Law | None) -> tuple[MotionLaw | _Law | None, ...]:
    """Each move's own law, else ``law``; None for the other segments."""
    return tuple((make_law(s.law) if s.law else law) if isinstance(s, Move) else None
                 for s in cycle.segments)


def single_law(law: MotionLaw | RowLaws | None) -> MotionLaw | None:
    """``law``, one law for every row: several laws over the rows (RowLaws) are sized only
    where every move is rest to rest and the split is the rule's
    (sizer.sizing.engine.rows_cycle), through the rest-to-rest moves' engine; a path
    that reads one law's shape (a move with boundary speeds, an optimized share, the
    samples of the cycle, its breakdown) never sees them."""
    if isinstance(law, RowLaws):
        raise TypeError("several laws over the rows reach only the rest-to-rest moves' "
                        "engine (sizer.sizing.engine.rows_cycle)")
    return law


def with_move_laws(design: Design, law: LawsPerMove) -> Design:
    """``design`` with a sized pair's law per move written in: each move that names no law
    names its law of ``law``, the share minimizes the same goal with those laws (no law
    choice left). Sized, its pair is the one ``law`` was chosen for (the same laws and
    split): what a sensitivity or another build of that pair keeps fixed."""
    cycle = design.machine_cycle
    laws = cycle_laws(cycle, law)
    segments = tuple(replace(s, law=law_choice(one.spec))
                     if isinstance(s, Move) and not s.law and one is not None else s
                     for s, one in zip(cycle.segments, laws, strict=True))
    share = ShareRule(f"optimize: {cycle.share.goal}")
    return replace(design, machine_cycle=replace(cycle, segments=segments, share=share))


class SegmentCycle:
    """Evaluates a cycle of segments for candidate motors at candidate scales s.

    Has the interface of :class:`sizer.sizing.move.CycleCalculator` that the checks and
    the T_min search use (``evaluate``, ``take``, ``motors``, ``drive``, ``task``); the
    duration the search varies is the scale s of the free durations.
    """

    segmented = True

    def __init__(self, cycle: Cycle, law: RankedLaw | RowLaws | None, drive: Drive,
                 motors: MotorArrays, thermal_speed: ThermalSpeedRule = "max",
                 weights: np.ndarray | None = None) -> None:
        self.cycle = cycle
        self.law = law
        self.laws = segment_laws(cycle, law)
        self.motors = motors
        self.thermal_rule = thermal_speed
        self.weights = np.array(cycle.weights())
        self.split: np.ndarray | None = None
        """Each candidate's own weights (candidates, segments), or None: ``weights`` (the
        rule's, shared by all). Rows sum as the rule's weights do, so a scale gives every
        candidate the same cycle time; an optimized share (``share: {optimize: ...}``)
        computes them (:meth:`_optimized_split`)."""
        free = cycle.free
        self.fixed = np.array([np.nan if s.duration is None or i in free else s.duration
                               for i, s in enumerate(cycle.segments)], dtype=float)
        self.drives = tuple(drive.with_load(segment_load(drive.load, s))
                            if not s.load.is_zero else drive for s in cycle.segments)
        heaviest = max(cycle.segments, key=lambda s: s.load.inertia)
        self.drive = (drive.with_load(segment_load(drive.load, heaviest))
                      if heaviest.load.inertia > 0.0 else drive)
        """The drive the checks read (the inertia ratio): the largest load of the cycle."""
        self.task = Task(cycle.moves[0].displacement if cycle.moves else 0.0, None,
                         linear=cycle.linear)
        self._base = drive
        self._fixed: dict[tuple[int, bool], SegmentFigures] = {}
        self._parent: tuple[SegmentCycle, np.ndarray] | None = None
        if weights is not None:
            split = np.array(np.broadcast_to(weights, (len(motors), len(cycle.segments))),
                             dtype=float)
            if not np.allclose(split.sum(axis=1), self.weights.sum(), rtol=1e-12, atol=0.0):
                raise ValueError("each candidate's weights must sum as the cycle's do")
            self.split = split
        elif cycle.share.goal is not None and cycle.cycle_time is not None:
            self.split = self._optimized_split(cycle.share.goal)

    # ------------------------------------------------------------------ public
    def durations(self, s: np.ndarray) -> list[np.ndarray]:
        """Each segment's duration per candidate at scales s (each candidate's own
        weights where it has them: :attr:`split`)."""
        weights = self.weights if self.split is None else self.split.T
        return [np.full_like(s, fixed) if np.isfinite(fixed) else w * s
                for fixed, w in zip(self.fixed, weights, strict=True)]

    def _optimized_split(self, goal: str) -> np.ndarray:
        """Each candidate's weights (candidates, segments) whose durations at the given
        cycle time minimize ``goal`` ("rms": the integral of tau^2 over the free moves;
        "energy": their shaft work plus copper loss, the RMS goal where the motor lacks
        k_t or R), found by sizer.allocation from each free move's figures for any
        candidates at any durations; each move by its own law or the ranked one."""
        from sizer.allocation import allocate  # lazy: the cycle-time allocation

        free = [i for i, w in enumerate(self.weights) if w > 0.0]
        n, s = len(self.motors), given_scale(self.cycle)
        split = np.tile(self.weights, (n, 1))
        if len(free) < 2 or n == 0:
            return split
        if not all(isinstance(self.cycle.segments[i], Move) for i in free):
            raise ValueError("an optimized share splits the time among free moves only")
        if goal == "vibration":
            split[:, free] = self._vibration_split(free, s * float(np.sum(self.weights))) / s
            return split
        move_cost = self._move_cost(goal, free)

        def cost(j: int, T: np.ndarray, rows: np.ndarray) -> np.ndarray:
            return move_cost(j, single_law(self.laws[free[j]]), T, rows)

        found = allocate(cost, np.full(n, s * float(np.sum(self.weights))),
                         np.tile(self.weights[free], (n, 1)))  # from sqrt_displacement
        split[:, free] = found.durations / s
        return split

    def _move_cost(self, goal: str, free: list[int]
                   ) -> Callable[[int, MotionLaw | None, np.ndarray, np.ndarray], np.ndarray]:
        """``cost(j, law, T, rows)``: free move j's term of ``goal`` ("rms" or "energy")
        by ``law`` at durations T for the candidates ``rows`` (the engine's figures)."""
        copper = (self._copper_factor() if goal == "energy"
                  else np.full(len(self.motors), np.nan))

        def cost(j: int, law: MotionLaw | None, T: np.ndarray, rows: np.ndarray
                 ) -> np.ndarray:
            i = free[j]
            move = self.cycle.segments[i]
            assert isinstance(move, Move)
            sub = self.take(rows)
            f = sub._move(move, law, sub.drives[i], np.asarray(T, dtype=float),
                          peaks=False, model=False)
            k = copper[rows]
            return np.where(np.isfinite(k), f.energy + k * f.torque_square, f.torque_square)

        return cost

    def law_split(self, laws: tuple[MotionLaw, ...]) -> LawSplit:
        """Each candidate's law per free move (of ``laws``, for the free moves that name
        none, whose indices the result gives; a move's own law is kept, its index then
        means nothing: the design's laws meet every move's boundary speeds,
        sizer.sizing.cycle.ranked_laws) and its split of the cycle time that minimize the
        share's goal ("rms" or "energy"): sizer.allocation.allocate_laws, every law
        combination a row of one search where they are few. The law choice per move of
        ``share: {optimize: ..., laws: per_move}``; the engine does not rank by it yet
        (it needs the laws per row in every figure: see docs/allocation.md)."""
        from sizer.allocation import allocate_laws

        goal = self.cycle.share.goal
        if goal not in ("rms", "energy") or self.cycle.cycle_time is None:
            raise ValueError("a law per move is chosen for the rms or energy goal of a "
                             "given cycle time")
        free = [i for i, w in enumerate(self.weights) if w > 0.0]
        if not all(isinstance(self.cycle.segments[i], Move) for i in free):
            raise ValueError("an optimized share splits the time among free moves only")
        n, s = len(self.motors), given_scale(self.cycle)
        move_cost = self._move_cost(goal, free)
        own = [getattr(self.cycle.segments[i], "law", None) for i in free]

        def cost(j: int, k: int, T: np.ndarray, rows: np.ndarray) -> np.ndarray:
            return move_cost(j, laws[k] if own[j] is None else single_law(self.laws[free[j]]),
                             T, rows)

        return allocate_laws(cost, len(laws), np.full(n, s * float(np.sum(self.weights))),
                             np.tile(self.weights[free], (n, 1)))

    def move_laws(self, laws: tuple[MotionLaw, ...]) -> np.ndarray:
        """Per candidate the law (an index into ``laws``) of each move that names none, in
        the cycle's order (candidates, moves): the free ones' with the split
        (:meth:`law_split`), a move of fixed duration's the law of least goal at its
        duration (its term does not depend on the split)."""
        goal = self.cycle.share.goal
        free = [i for i, w in enumerate(self.weights) if w > 0.0]
        split = self.law_split(laws) if free else None
        out = []
        for i, segment in enumerate(self.cycle.segments):
            if not isinstance(segment, Move) or segment.law:
                continue
            if split is not None and i in free:
                out.append(split.laws[:, free.index(i)])
                continue
            cost = self._move_cost(str(goal), [i])
            T, rows = np.full(len(self.motors), self.fixed[i]), np.arange(len(self.motors))
            every = np.stack([cost(0, law, T, rows) for law in laws], axis=1)
            out.append(np.argmin(np.where(np.isnan(every), np.inf, every), axis=1))
        return np.stack(out, axis=1)

    def _vibration_split(self, free: list[int], free_time: float) -> np.ndarray:
        """The free moves' durations (moves,) that minimize the largest residual vibration
        over the cycle's moves (sizer.vibration.cycle_residual.CycleVibration: the load's
        mode, the laws of :attr:`laws`): one split for all candidates, the residual
        depends on the laws and durations only (sizer.allocation.minimax_split)."""
        elastic = self._base.load.elastic
        if elastic is None:  # sizer.io refuses it at the share's line
            raise UserError("`share: {optimize: vibration}` needs the load's mode: give "
                            "load.natural_frequency", field="cycle.share")
        return _vibration_split(elastic, self.cycle, self.laws, tuple(free), free_time)

    def _copper_factor(self) -> np.ndarray:
        """f R / k_t^2 per candidate (the copper loss per N^2 m^2 of torque squared, W, as
        the energy check reads it: sizer.energy.copper_loss, R line to line); NaN where the
        motor lacks k_t or R."""
        from sizer.energy import copper_loss
        from sizer.sizing.candidates import catalog_facts

        facts = catalog_facts(self.motors.catalog)
        k_t = facts.column("torque_constant")[self.motors.index]
        R = facts.column("winding_resistance")[self.motors.index]
        known = np.isfinite(k_t) & np.isfinite(R) & (k_t > 0.0)
        out = np.full(len(k_t), np.nan)
        out[known] = copper_loss(1.0, k_t[known], R[known])
        return out

    def reported(self, metrics: CycleMetrics) -> np.ndarray:
        """The duration a result reports: the one :meth:`evaluate` gives."""
        return metrics.duration

    def dead_point_issues(self) -> None:
        return None  # no linkage

    def given_scale(self) -> float:
        return given_scale(self.cycle)

    def law_move(self) -> None:
        return None  # no closed form (sizer.sizing.evaluation.CycleModel)

    def cycle_time(self, s: np.ndarray) -> np.ndarray:
        return sum(self.durations(np.asarray(s, dtype=float)), np.zeros_like(s))

    def scale_of(self, cycle_time: np.ndarray) -> np.ndarray:
        """The scale s of the free durations at which the cycle lasts ``cycle_time``
        (the inverse of :meth:`cycle_time`: fixed durations plus weights times s)."""
        fixed = float(np.sum(self.fixed[np.isfinite(self.fixed)]))
        return (np.asarray(cycle_time, dtype=float) - fixed) / float(np.sum(self.weights))

    def take(self, index: np.ndarray) -> SegmentCycle:
        out = object.__new__(SegmentCycle)
        out.__dict__.update(self.__dict__)
        if isinstance(self.law, RowLaws):  # each row's law goes with it
            out.law = self.law.take(index)
            out.laws = tuple(law.take(index) if isinstance(law, RowLaws) else law
                             for law in self.laws)
        out.motors = self.motors.subset(index)
        out.drives = tuple(d.take(index) for d in self.drives)
        out.drive = self.drive.take(index)
        out._base = self._base.take(index)
        out._fixed = {}
        out._parent = (self, np.asarray(index))
        if self.split is not None:
            out.split = self.split[np.asarray(index)]
        return out

    def by_law(self, rows: np.ndarray) -> list[tuple[int, np.ndarray, SegmentCycle]]:
        """The rows ``rows`` law by law (RowLaws), else all at once (law 0): per law its
        index, the positions ``at`` in ``rows`` of its rows and the cycle of the rows
        ``rows[at]`` with that law alone (its fixed segments' figures read from this
        cycle's, row by row)."""
        if not isinstance(self.law, RowLaws):
            return [(0, np.arange(len(rows)), self.take(rows))]
        out = []
        for k, at in self.law.groups(rows):
            one = self.take(rows[at])
            one.law = self.law.laws[k]
            one.laws = segment_laws(self.cycle, one.law)
            out.append((k, at, one))
        return out

    def initial_guess(self) -> np.ndarray:
        """A scale to start the search from: the free moves' speed and inertial bounds."""
        n = len(self.motors)
        guess = np.full(n, 1e-3)
        tau_p = np.maximum(self.motors.intermittent.torques.max(axis=1), 1e-300)
        for segment, law, drive, w in zip(self.cycle.segments, self.laws, self.drives,
                                          self.weights, strict=True):
            if not isinstance(segment, Move) or w == 0.0 or law is None:
                continue
            c, k, h = law.coefficients, drive.ratio, abs(segment.displacement)
            J_t = self.motors.inertia + drive.transmission_inertia + drive.reflected_load_inertia
            T = np.maximum(c.C_v * k * h / self.motors.speed_limit,
                           np.sqrt(c.C_a * k * h * J_t / tau_p))
            guess = np.maximum(guess, np.broadcast_to(T / w, (n,)))
        return np.where(np.isfinite(guess) & (guess > 0.0), guess, 1.0)

    def search_start(self, limits: Limits) -> None:
        """None: the peak bound is a bound wherever it is usable (CycleModel)."""
        return None

    def peak_bound(self, limits: Limits) -> np.ndarray | None:
        """A lower bound on the minimized scale s: each free rest-to-rest move's bound on
        its duration from its speed, load-limit and peak checks
        (CycleCalculator.peak_bound), over its weight; the cycle's peaks are the maxima
        over its segments, so below the largest of these no scale is feasible. None where
        a law moves backwards (the bound does not hold)."""
        bound = np.zeros(len(self.motors))
        boundary = []
        for i, (segment, law, drive, w) in enumerate(zip(
                self.cycle.segments, self.laws, self.drives, self.weights, strict=True)):
            if not isinstance(segment, Move) or w == 0.0:
                continue
            if not segment.rest_to_rest:
                boundary.append(i)
                continue
            task = Task(segment.displacement, None, linear=self.cycle.linear)
            # the thermal speed is this move's peak speed only by the "max" rule (then
            # the cycle's is the largest of its moves'): another rule reads no bound here
            found = CycleCalculator(None, task, drive, self.motors, self.thermal_rule,
                                    law=law).peak_bound(limits)
            if found is None:
                return None
            bound = np.maximum(bound, found / w)
        if boundary:
            start = np.where(bound > 0.0, bound, self.initial_guess())
            for i in boundary:
                bound = np.maximum(bound, self._boundary_bound(i, limits, start))
        return bound

    def rms_lower_bound(self) -> np.ndarray | None:
        """Per candidate a torque the motor's RMS over the cycle exceeds at every scale;
        None where a rest-to-rest move has none (a negative damping term).

        Segment by segment a lower bound on the mean square of the motor torque over it:
        a rest-to-rest move's (CycleCalculator.rms_lower_bound, squared: the
        square of its largest positive constant torque), a dwell's holding torque and a
        run's constant torque squared (exact), 0 for a move with boundary speeds; the
        cycle's from them (:func:`rms_floor`)."""
        if self.split is not None:
            return None  # the floor reads one rule's weights (each candidate has its own)
        n = len(self.motors)
        ones = np.ones(n)
        rates = []
        for segment, law, drive in zip(self.cycle.segments, self.laws, self.drives,
                                       strict=True):
            if isinstance(segment, Move):
                if not segment.rest_to_rest or law is None:
                    rate = np.zeros(n)
                else:
                    task = Task(segment.displacement, None, linear=self.cycle.linear)
                    bound = CycleCalculator(None, task, drive, self.motors, "max",
                                            law=law).rms_lower_bound()
                    if bound is None:
                        return None
                    rate = np.square(bound)
            elif isinstance(segment, Run):
                rate = self._run(segment, drive, ones).torque_square
            else:
                rate = self._dwell(drive, ones).torque_square
            rates.append(rate)
        return rms_floor(rates, self.fixed, self.weights, n)

    def _boundary_slack(self, i: int, limits: Limits, s: np.ndarray,
                        rows: np.ndarray) -> np.ndarray:
        """The worst slack of the peak checks of one free move with boundary speeds alone
        (speed, peak ratio, load limits, stage speeds and peaks; the thermal speed where it
        is the peak speed) at scales s for the candidates ``rows`` (repeats allowed): those
        checks of the cycle that read only this move's peaks."""
        sub = self.take(rows)
        w = float(self.weights[i])
        move = self.cycle.segments[i]
        assert isinstance(move, Move)
        f = sub._boundary_move(move, single_law(self.laws[i]), sub.drives[i], w * s)
        zero = np.zeros(len(rows))
        metrics = CycleMetrics(
            duration=w * s, max_speed=f.max_speed, peak_torque=f.peak_torque,
            peak_ratio=f.peak_ratio, rms_torque=zero,
            thermal_speed=f.max_speed if self.thermal_rule == "max" else zero,
            load_speed=f.load_speed, load_acceleration=f.load_acceleration,
            load_jerk=f.load_jerk, load_torque=f.load_torque, stage_peak=f.stage_peak,
            stage_rms=[zero for _ in f.stage_peak], stage_speed=f.stage_speed)
        checks = [c for c in evaluate_checks(metrics, sub.motors, sub.drive, limits,
                                             self.cycle.linear)
                  if c.name != "inertia_ratio"]
        return worst_slack(checks)

    def _boundary_bound(self, i: int, limits: Limits, start: np.ndarray) -> np.ndarray:
        """A lower bound on the minimized scale from the free move with boundary speeds at
        segment ``i``:
        the smallest scale at which its peak checks pass (the cycle's peaks are maxima over
        its segments, so no smaller scale is feasible).

        The move's shape changes with its duration, so no closed form bounds it; its
        figures are exact (sizer.sizing.move), so every candidate's slack is read on a
        log grid of scales around ``start`` (factors of sqrt 2 over 2^-8 to 2^8; in
        BOUND_CHUNKS from below, up to the first feasible point), and the crossing below
        its first feasible point is refined (:func:`first_crossing`) to the engine's width
        (1e-13 in log s, the feasible end kept). 0 (no bound) where the
        grid's lowest point already passes or none does: the search of the whole cycle
        then decides, as without the bound."""
        out = np.zeros(len(self.motors))
        where = np.flatnonzero(np.isfinite(start) & (start > 0.0))  # inf: already no scale
        if not len(where):
            return out
        steps = np.arange(-BOUND_SPAN, BOUND_SPAN + 1) * (0.5 * np.log(2.0))
        x = np.log(start[where])[:, None] + steps[None, :]  # (candidates, G)
        f = np.full(x.shape, np.nan)
        for a, b in BOUND_CHUNKS:  # from below, only the candidates with no pass yet
            rest = np.flatnonzero(~(f >= -TOLERANCE).any(axis=1))
            if len(rest):
                f[rest, a:b] = self._boundary_slack(
                    i, limits, np.exp(x[rest, a:b].ravel()),
                    np.repeat(where[rest], b - a)).reshape(len(rest), b - a)
        good = f >= -TOLERANCE
        first = np.argmax(good, axis=1)
        found = np.flatnonzero(good.any(axis=1) & (first > 0))
        if not len(found):
            return out
        index = where[found]
        k = first[found]
        x_lo, x_hi = x[found, k - 1], x[found, k]
        f_lo, f_hi = f[found, k - 1], f[found, k]
        offset = np.where(f_hi >= 0.0, 0.0, TOLERANCE)

        def slack(z: np.ndarray, where: np.ndarray) -> np.ndarray:
            return self._boundary_slack(i, limits, np.exp(z), index[where]) \
                + offset[where]

        # 3 even points a round, not 7: each row costs its own polynomial move, and the
        # secant with its offsets does the narrowing (a quarter a round at worst)
        hi = first_crossing(slack, x_lo, x_hi, f_lo + offset, f_hi + offset, xtol=1e-13,
                            points=3)
        out[index] = np.exp(hi)
        return out

    def figures(self, s: np.ndarray, peaks: bool = True,
                model: bool = False) -> list[SegmentFigures]:
        """Each segment's requirements at scales s (with ``model``, the rest-to-rest
        moves' RMS models)."""
        s = np.broadcast_to(np.asarray(s, dtype=float), (len(self.motors),)).copy()
        out = []
        for i, (segment, law, drive, T) in enumerate(zip(
                self.cycle.segments, self.laws, self.drives, self.durations(s), strict=True)):
            if np.isfinite(self.fixed[i]):
                out.append(self._fixed_figures(i, segment, law, drive, T, peaks))
            elif isinstance(segment, Move):
                out.append(self._move(segment, law, drive, T, peaks, model))
            elif isinstance(segment, Run):
                out.append(self._run(segment, drive, T))
            else:
                out.append(self._dwell(drive, T))
        return out

    def _fixed_figures(self, i: int, segment: Segment, law: MotionLaw | RowLaws | None,
                       drive: Drive,
                       T: np.ndarray, peaks: bool) -> SegmentFigures:
        """A segment of fixed duration: its figures do not depend on the scale, so they
        are evaluated once per set of candidates (and ``peaks``) and kept; a subset made
        by :meth:`take` reads its parent's. Without an RMS model (a fixed segment enters
        the cycle's model as a constant)."""
        key = (i, peaks)
        found = self._fixed_lookup(key)
        if found is None:
            if isinstance(segment, Move):
                found = self._move(segment, law, drive, T, peaks, False)
            elif isinstance(segment, Run):
                found = self._run(segment, drive, T)
            else:
                found = self._dwell(drive, T)
        self._fixed[key] = found
        return found

    def _fixed_lookup(self, key: tuple[int, bool]) -> SegmentFigures | None:
        """The kept figures of a fixed segment, here or (subset) in a parent's."""
        found = self._fixed.get(key)
        if found is None and self._parent is not None:
            parent, index = self._parent
            kept = parent._fixed_lookup(key)
            if kept is not None:
                found = self._fixed[key] = _take_figures(kept, index)
        return found

    def thermal_speed(self, s: np.ndarray) -> np.ndarray:
        """The speed the continuous region is read at (the thermal rule) at scales s, in
        closed form over rest-to-rest moves, runs and dwells (a move with boundary speeds
        is evaluated)."""
        s = np.asarray(s, dtype=float)
        T = self.durations(s)
        cycle_time = sum(T, np.zeros_like(s))
        peak, square, travel = np.zeros_like(s), np.zeros_like(s), np.zeros_like(s)
        for segment, law, drive, t in zip(self.cycle.segments, self.laws, self.drives, T,
                                          strict=True):
            if isinstance(segment, Move) and not segment.rest_to_rest:
                return self.evaluate(s, peaks=False).thermal_speed
            K = drive.ratio
            if isinstance(segment, Move):
                assert law is not None
                c, h = law.coefficients, abs(segment.displacement)
                with np.errstate(divide="ignore", over="ignore"):
                    peak = np.maximum(peak, K * h * c.C_v / t)
                    square = square + np.square(K * h * c.C_v_rms) / t
                travel = travel + K * h
            elif isinstance(segment, Run):
                speed = K * abs(segment.speed)
                peak = np.maximum(peak, speed)
                square = square + speed * speed * t
                travel = travel + speed * t
        return rule_speed(self.thermal_rule, peak, square, travel, cycle_time)

    def evaluate(self, duration: np.ndarray, peaks: bool = True, model: bool = False,
                 rms: np.ndarray | None = None) -> CycleMetrics:
        """The cycle's requirements at scales s = ``duration``; with ``model`` the RMS
        model of the cycle (:class:`CycleRmsModel`; None with a free move that has
        boundary speeds). ``rms`` (a known RMS torque) is not used: each segment computes
        its own."""
        parts = self.figures(duration, peaks, model)
        T = parts[0].duration * 0.0 + self.cycle_time(np.broadcast_to(
            np.asarray(duration, dtype=float), (len(self.motors),)))
        n_stages = len(self._base.stages)

        def most(name: str) -> np.ndarray:
            return np.max(np.stack([getattr(p, name) for p in parts]), axis=0)

        def total(name: str) -> np.ndarray:
            return np.sum(np.stack([getattr(p, name) for p in parts]), axis=0)

        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            rms = np.sqrt(total("torque_square") / T)
            stage_rms = [np.sqrt(np.sum(np.stack([p.stage_square[i] for p in parts]), axis=0)
                                 / T) for i in range(n_stages)]
            thermal = rule_speed(self.thermal_rule, most("max_speed"), total("speed_square"),
                                 total("speed_abs"), T)
        return CycleMetrics(
            duration=T, max_speed=most("max_speed"), peak_torque=most("peak_torque"),
            peak_ratio=most("peak_ratio"), rms_torque=_finite_or_inf(rms),
            thermal_speed=_finite_or_inf(thermal), load_speed=most("load_speed"),
            load_acceleration=most("load_acceleration"),
            load_jerk=np.where(self._join_steps(parts), np.inf, most("load_jerk")),
            load_torque=most("load_torque"),
            stage_peak=[np.max(np.stack([p.stage_peak[i] for p in parts]), axis=0)
                        for i in range(n_stages)],
            stage_rms=[_finite_or_inf(x) for x in stage_rms],
            stage_speed=[np.max(np.stack([p.stage_speed[i] for p in parts]), axis=0)
                         for i in range(n_stages)],
            rms_model=self._rms_model(parts) if model else None,
        )

    def _join_steps(self, parts: list[SegmentFigures]) -> np.ndarray:
        """Per candidate: does the acceleration step at a join (the cycle repeats, so the
        last segment joins the first)? A jerk impulse: no jerk limit is met there."""
        n = len(self.motors)
        zero = np.zeros(n)
        ends = [p.end_accelerations or (zero, zero) for p in parts]
        reference = np.zeros(n)
        for segment, p in zip(self.cycle.segments, parts, strict=True):
            if isinstance(segment, Move):
                with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
                    reference = np.fmax(reference, abs(segment.displacement) / p.duration ** 2)
        steps = np.zeros(n, dtype=bool)
        for before, after in zip(ends[-1:] + ends[:-1], ends, strict=True):
            steps |= np.abs(after[0] - before[1]) > JOIN_TOLERANCE * reference
        return steps

    def _rms_model(self, parts: list[SegmentFigures]):
        if self.split is not None:
            return None  # the model scales one rule's weights (each candidate has its own)
        moves, n = [], len(self.motors)
        constant, hold_rate = np.zeros(n), np.zeros(n)
        for segment, w, f in zip(self.cycle.segments, self.weights, parts, strict=True):
            if w == 0.0:
                constant = constant + f.torque_square
            elif isinstance(segment, Move):
                if f.rms_model is None:
                    return None
                moves.append((f.rms_model, float(w)))
            else:  # a free dwell: hold^2 * w * s
                hold = f.peak_torque
                hold_rate = hold_rate + hold * hold * w
        return CycleRmsModel(tuple(moves), constant, hold_rate, self.cycle.fixed_time,
                             float(np.sum(self.weights)))

    # ------------------------------------------------------------- segments
    def _move(self, move: Move, law: MotionLaw | RowLaws | None, drive: Drive,
              T: np.ndarray, peaks: bool, model: bool) -> SegmentFigures:
        if move.rest_to_rest:
            assert law is not None, "segment_laws gives a move one"
            return self._rest_move(move, law, drive, T, peaks, model)
        law = single_law(law)
        if law is not None and fixed_shape(law):
            return self._shaped_move(move, law, drive, T, peaks)
        return self._boundary_move(move, law, drive, T)

    def _shaped_move(self, move: Move, law: MotionLaw, drive: Drive, T: np.ndarray,
                     peaks: bool) -> SegmentFigures:
        """A move between boundary speeds by a law of fixed shape at its fixed duration
        (sizer.io.cycle: a cam table's span whose end slopes are v T/h): the law's figures
        scale with h/T^k. Polynomial pieces (a PieceTable: a quintic Hermite table, a
        spline, a fitted table) exactly by polynomial_move on the law's own coefficients
        scaled by h/T^k, as a move with a boundary form; another curve (coefficient
        segments with sines) as the rest-to-rest path evaluates a law (the single-law
        engine on its grid), its jerk bounded unless the acceleration jumps inside (its
        ends join its neighbours: :meth:`_join_steps`)."""
        h = move.displacement
        table = law.piece_table()
        last = len(law.pieces) - 1
        with np.errstate(over="ignore", invalid="ignore"):
            ends = (h * law.piece_derivative(0, 0.0, 2) / T / T,
                    h * law.piece_derivative(last, 1.0, 2) / T / T)
        if table is None:
            grid = self._rest_move(move, law, drive, T, peaks)
            c = law.coefficients
            inside = any(0.0 < jump.tau < 1.0 for jump in c.acceleration_jumps)
            with np.errstate(over="ignore", invalid="ignore"):
                jerk = (np.full_like(T, np.inf) if inside or not math.isfinite(c.C_j)
                        else c.C_j * abs(h) / T / T / T)
            return replace(grid, load_jerk=jerk, rms_model=None, end_accelerations=ends)
        local = table.rows[0] / table.size  # (P, d+1) in u = tau - start
        local[:, 0] -= table.offset / table.size
        powers = np.arange(local.shape[1])
        with np.errstate(over="ignore", invalid="ignore"):
            coefficients = h * local[None] / T[:, None, None] ** powers
            breaks = T[:, None] * np.append(table.starts, 1.0)[None, :]
        exact = polynomial_move(breaks, coefficients, drive, self.motors,
                                1.0 if h >= 0 else -1.0)
        return SegmentFigures(**vars(exact), duration=T, end_accelerations=ends)

    def _rest_move(self, move: Move, law: MotionLaw | RowLaws, drive: Drive, T: np.ndarray,
                   peaks: bool, model: bool = False) -> SegmentFigures:
        """A rest-to-rest move: the law move's engine for a one-move task (each row's own
        law with RowLaws)."""
        task = Task(move.displacement, None, linear=self.cycle.linear)
        calc = CycleCalculator(None, task, drive, self.motors, "max", law=law)
        m = calc.evaluate(T, peaks, model)
        c, K, h = law.coefficients, np.broadcast_to(drive.ratio, T.shape), abs(move.displacement)
        start, end = _end_accelerations(law)
        with np.errstate(over="ignore", invalid="ignore"):
            rms_speed = K * h * c.C_v_rms / T
            energy = calc.shaft_work(T)
            return SegmentFigures(
                duration=T, peak_torque=m.peak_torque, peak_ratio=m.peak_ratio,
                load_torque=m.load_torque, max_speed=m.max_speed, load_speed=m.load_speed,
                load_acceleration=m.load_acceleration, load_jerk=m.load_jerk,
                stage_peak=m.stage_peak, stage_speed=m.stage_speed,
                torque_square=np.square(m.rms_torque) * T,
                stage_square=[np.square(x) * T for x in m.stage_rms],
                speed_square=np.square(rms_speed) * T, speed_abs=K * h, energy=energy,
                rms_model=m.rms_model if isinstance(m.rms_model, RmsModel) else None,
                end_accelerations=(  # a law move's model is an RmsModel (or None)
                    move.displacement * start / T / T, move.displacement * end / T / T))

    def _boundary_move(self, move: Move, law: MotionLaw | None, drive: Drive,
                       T: np.ndarray) -> SegmentFigures:
        """A move with boundary speeds: each candidate's piecewise polynomial, exactly."""
        from sizer.laws.boundary_speeds import boundary_form

        spec = law.spec if law is not None else None
        basis = boundary_form(spec) if spec is not None else None
        if basis is None:
            raise ValueError(f"{spec} has no form with boundary speeds")
        h = move.displacement
        with np.errstate(over="ignore", invalid="ignore"):
            normalized = normalized_move(basis, move, T)  # (n, P, d+1) in u
            powers = np.arange(normalized.shape[2])
            coefficients = h * normalized / T[:, None, None] ** powers
            breaks = T[:, None] * basis.breaks[None, :]
        f = polynomial_move(breaks, coefficients, drive, self.motors,
                            1.0 if h >= 0 else -1.0)
        jerk = f.load_jerk if basis.jerk_bounded else np.full_like(T, np.inf)
        width = basis.breaks[-1] - basis.breaks[-2]
        k = powers[2:]
        with np.errstate(over="ignore", invalid="ignore"):
            first = 2.0 * normalized[:, 0, 2] * h / T / T
            last = np.sum(normalized[:, -1, 2:] * k * (k - 1) * width ** (k - 2), axis=1) \
                * h / T / T
        return SegmentFigures(**{**vars(f), "load_jerk": jerk}, duration=T,
                              end_accelerations=(first, last))

    def _run(self, run: Run, drive: Drive, T: np.ndarray) -> SegmentFigures:
        """A constant-speed run: a = 0, the torque constant over T."""
        n = len(T)
        direction = 1.0 if run.speed > 0 else -1.0
        v = np.full((n, 1), run.speed * direction)  # along the motion
        shaft, outputs = drive.chain(np.zeros((n, 1)), v, direction)
        K = np.broadcast_to(drive.ratio, (n,))
        torque = (self.motors.damping * K * v[:, 0] + shaft[:, 0])
        speed = K * abs(run.speed)
        limit = self.motors.intermittent.limit(speed)
        stage_out = [np.abs(x[:, 0]) for x in outputs]
        u = np.abs(drive.load_torque(np.zeros(n), v[:, 0], direction))
        return SegmentFigures(
            duration=T, peak_torque=np.abs(torque), peak_ratio=_safe_ratio(np.abs(torque), limit),
            load_torque=u, max_speed=speed, load_speed=np.full(n, abs(run.speed)),
            load_acceleration=np.zeros(n), load_jerk=np.zeros(n), stage_peak=stage_out,
            stage_speed=[np.broadcast_to(k * abs(run.speed), (n,)) for k in drive.input_ratios],
            torque_square=np.square(torque) * T, stage_square=[x * x * T for x in stage_out],
            speed_square=speed * speed * T, speed_abs=speed * T, energy=torque * speed * T)

    def _dwell(self, drive: Drive, T: np.ndarray) -> SegmentFigures:
        """A dwell holding the segment's constant load (counts as driving)."""
        n = len(T)
        hold, stage_hold = drive.holding_torques()
        hold = np.broadcast_to(hold, (n,))
        stage_hold = [np.broadcast_to(x, (n,)) for x in stage_hold]
        held = hold > 0.0
        ratio = np.where(held, _safe_ratio(hold, self.motors.intermittent.limit(np.zeros(n))),
                         0.0)
        zero = np.zeros(n)
        return SegmentFigures(
            duration=T, peak_torque=hold.copy(), peak_ratio=ratio,
            load_torque=np.abs(drive.figures.column("torque", n)), max_speed=zero,
            load_speed=zero,
            load_acceleration=zero, load_jerk=zero,
            stage_peak=[x.copy() for x in stage_hold],
            stage_speed=[zero for _ in drive.stages], torque_square=hold * hold * T,
            stage_square=[x * x * T for x in stage_hold], speed_square=zero, speed_abs=zero,
            energy=zero)

    # ------------------------------------------------------------- samples
    def pieces(self, s: np.ndarray, samples: int | None = None) -> list[CyclePiece]:
        """The cycle at scales s, segment by segment: a move from rest on its law's grid
        (``samples`` per move), a move with boundary speeds on each candidate's own
        polynomial, a run at its constant speed, a dwell holding its constant load."""
        samples = SAMPLES if samples is None else samples
        n = len(self.motors)
        out, start, position = [], np.zeros((n, 1)), 0.0
        for segment, law, drive, T in zip(self.cycle.segments, self.laws, self.drives,
                                          self.durations(s), strict=True):
            K = np.broadcast_to(np.asarray(drive.ratio, dtype=float), (n,))[:, None]
            Tc = np.asarray(T, dtype=float)[:, None]
            name = segment.name or type(segment).__name__.lower()
            if isinstance(segment, Dwell):
                hold = np.broadcast_to(np.asarray(drive.holding_torque, dtype=float), (n,))
                out.append(held_piece(name, start, Tc, position,
                                      hold * np.sign(drive.figures.torque)))
            else:
                if isinstance(segment, Move):
                    one = single_law(law)
                    assert one is not None, "segment_laws gives a move one"
                    u, q, v, a = _move_samples(segment, one, np.asarray(T, dtype=float),
                                               samples)
                    rest = 1.0 if segment.displacement >= 0.0 else -1.0
                else:
                    assert isinstance(segment, Run)
                    u, rest = np.array([0.0, 1.0]), 1.0
                    v, a = np.full((n, 2), segment.speed), np.zeros((n, 2))
                    q = segment.speed * (Tc * u[None])
                out.append(CyclePiece(name, start + Tc * u[None], position + q, v, a, K * v,
                                      K * a, signed_torque(drive, self.motors, a, v, rest),
                                      load=drive.load))
            start, position = start + Tc, position + segment.displacement
        return out

    def breakdown(self, s: np.ndarray) -> list[SegmentPart]:
        """Each segment's figures at scales s (:meth:`figures`)."""
        out = []
        for segment, law, g in zip(self.cycle.segments, self.laws, self.figures(s),
                                   strict=True):
            zero = np.zeros_like(g.duration)
            start, end = g.end_accelerations or (zero, zero)
            kind = type(segment).__name__.lower()
            scale = abs(segment.displacement) / g.duration ** 2 \
                if isinstance(segment, Move) else None
            out.append(SegmentPart(segment.name or kind, kind, single_law(law), g.duration,
                                   g.peak_torque, g.torque_square, g.max_speed, g.energy,
                                   start, end, scale))
        return out


SECANT_OFFSETS = (1e-2, 1e-4, 1e-6, 1e-8)
"""Where :func:`first_crossing` reads its points beside each round's secant point (shares
of the bracket's width, on both sides)."""
CROSSING_ROUNDS = 40


def first_crossing(f, lo: np.ndarray, hi: np.ndarray, f_lo: np.ndarray, f_hi: np.ndarray,
                   xtol: float = 1e-13, points: int = 7) -> np.ndarray:
    """Per row the upper end of a bracket of width <= xtol (relative to max(1, |lo|)) of
    the first sign change of f in [lo, hi], from f_lo < 0 <= f_hi: the end where f >= 0.

    For functions whose evaluation costs about as much for a few rows as for many (an
    exact polynomial move, sizer.sizing.move) several points per row are read
    in one call ``f(x, rows)``: ``points`` evenly spaced across the bracket, the foretold
    crossing (:func:`_crossing_guess`: the inverse quadratic through the bracket's ends
    and the last round's nearest point beside it; in the first round the secant) and
    points beside it at SECANT_OFFSETS of the width. The
    new bracket is the first adjacent pair whose signs differ, so the bracket always
    holds the first sign change it held; where f is smooth the quadratic's zero is
    accurate to the cube of the width, which the offsets then bracket (four rounds from
    a width of 0.35 to 1e-13 on the flying saw's moves, five with the secant alone; the
    project's root finder, sizer.numerics.roots.bracketed_root, takes one call per
    step and about ten).
    """
    lo, hi, f_lo, f_hi = (np.array(x, dtype=float) for x in (lo, hi, f_lo, f_hi))
    share = np.arange(1, points + 1) / (points + 1.0)
    offsets = np.concatenate((-np.array(SECANT_OFFSETS), [0.0], SECANT_OFFSETS))
    # a third point beside the bracket (the last round's nearest outside it), for the
    # inverse quadratic through three points: NaN until a round has read one
    x_c, f_c = np.full(len(lo), np.nan), np.full(len(lo), np.nan)
    for _ in range(CROSSING_ROUNDS):
        width = hi - lo
        open_ = width > np.maximum(xtol * np.maximum(1.0, np.abs(lo)),
                                   2.0 * np.spacing(np.abs(hi)))
        rows = np.flatnonzero(open_)
        if not len(rows):
            break
        a, b, fa, fb, w = lo[rows], hi[rows], f_lo[rows], f_hi[rows], width[rows]
        guess = _crossing_guess(a, b, fa, fb, x_c[rows], f_c[rows])
        x = np.concatenate((a[:, None] + w[:, None] * share[None, :],
                            guess[:, None] + w[:, None] * offsets[None, :]), axis=1)
        x = np.sort(np.clip(x, a[:, None], b[:, None]), axis=1)
        m = x.shape[1]
        fx = f(x.ravel(), np.repeat(rows, m)).reshape(x.shape)
        xs = np.concatenate((a[:, None], x, b[:, None]), axis=1)
        fs = np.concatenate((fa[:, None], fx, fb[:, None]), axis=1)
        k = np.argmax(fs >= 0.0, axis=1)  # the first point on f_hi's side (>= 1)
        j = np.arange(len(rows))
        lo[rows], f_lo[rows] = xs[j, k - 1], fs[j, k - 1]
        hi[rows], f_hi[rows] = xs[j, k], fs[j, k]
        outside = np.where(k >= 2, k - 2, np.minimum(k + 1, m + 1))  # the nearest beside
        x_c[rows], f_c[rows] = xs[j, outside], fs[j, outside]
    return hi


def _crossing_guess(a: np.ndarray, b: np.ndarray, fa: np.ndarray, fb: np.ndarray,
                    c: np.ndarray, fc: np.ndarray) -> np.ndarray:
    """Where f crosses zero in [a, b] (fa < 0 <= fb), foretold: the inverse quadratic
    through (a, b, c) where a third point c is known and the quadratic's zero lies
    inside, else the secant, else the midpoint."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        secant = (a * fb - b * fa) / (fb - fa)
        quadratic = (a * fb * fc / ((fa - fb) * (fa - fc))
                     + b * fa * fc / ((fb - fa) * (fb - fc))
                     + c * fa * fb / ((fc - fa) * (fc - fb)))
    inside_q = np.isfinite(quadratic) & (quadratic > a) & (quadratic < b)
    inside_s = np.isfinite(secant) & (secant > a) & (secant < b)
    return np.where(inside_q, quadratic, np.where(inside_s, secant, 0.5 * (a + b)))


@functools.lru_cache(maxsize=32)
def _vibration_split(elastic, cycle: Cycle, laws: tuple[MotionLaw | None, ...],
                     free: tuple[int, ...], free_time: float) -> np.ndarray:
    """:meth:`SegmentCycle._vibration_split`, kept: the same for every part of the
    candidates and every evaluator the engine builds for one law (read only)."""
    from sizer.allocation import minimax_split
    from sizer.vibration.cycle_residual import CycleVibration

    vibration = CycleVibration(elastic, cycle, laws)
    fixed = [None if i in free else float(s.duration or 0.0)
             for i, s in enumerate(cycle.segments)]
    column = {i: j for j, i in enumerate(free)}

    def worst(D: np.ndarray) -> np.ndarray:
        k = len(D)
        durations = [D[:, column[i]] if t is None else np.full(k, t)
                     for i, t in enumerate(fixed)]
        return vibration.worst(np.ones(k), durations)

    found = minimax_split(worst, free_time, len(free))
    found.setflags(write=False)
    return found


def _take_figures(f: SegmentFigures, index: np.ndarray) -> SegmentFigures:
    """The figures of the candidates at ``index`` (without an RMS model)."""
    def pick(x):
        if x is None:
            return None
        if isinstance(x, list | tuple):
            return type(x)(pick(y) for y in x)
        return np.asarray(x)[index]

    return SegmentFigures(**{k: pick(v) for k, v in vars(f).items() if k != "rms_model"})


def _finite_or_inf(x: np.ndarray) -> np.ndarray:
    return np.where(np.isnan(x), np.inf, x)


def signed_torque(drive: Drive, motors: MotorArrays, a: np.ndarray, v: np.ndarray,
                  rest_sign: float) -> np.ndarray:
    """The motor torque (signed like the motion) at the load's acceleration ``a`` and speed
    ``v`` (candidates, samples): s (J_m K a_l + B_m K v_l + shaft(a_l, v_l)) with
    (a_l, v_l) = s (a, v), s the sign of v (``rest_sign`` where v is 0) and shaft() the
    drive's chain with the efficiencies in the direction of power flow."""
    n = a.shape[0]
    K = np.broadcast_to(np.asarray(drive.ratio, dtype=float), (n,))[:, None]
    J = np.asarray(motors.inertia, dtype=float)[:, None]
    B = np.asarray(motors.damping, dtype=float)[:, None]
    sign = np.where(v > 0.0, 1.0, np.where(v < 0.0, -1.0, rest_sign))
    out = np.zeros_like(a)
    for s in (1.0, -1.0):
        if not (sign == s).any():
            continue
        shaft, _ = drive.chain(s * a, s * v, s)
        along = J * K * s * a + B * K * s * v + shaft
        out = np.where(sign == s, s * along, out)
    return out


def _end_accelerations(law: MotionLaw | RowLaws) -> tuple[float | np.ndarray, ...]:
    """q_N'' at the start of the first piece and at the end of the last, one-sided: the
    law's, or each row's law's (RowLaws: arrays over the rows)."""
    if isinstance(law, RowLaws):
        ends = np.array([_end_accelerations(one) for one in law.laws], dtype=float)
        return ends[law.index, 0], ends[law.index, 1]
    return (law.piece_derivative(0, 0.0, 2),
            law.piece_derivative(len(law.pieces) - 1, 1.0, 2))


def _move_samples(move: Move, law: MotionLaw, T: np.ndarray, samples: int):
    """u (samples,), the load's position from the move's start (samples,) or (n, samples),
    speed and acceleration (n, samples) of a move in durations T: a move from rest on its
    law's grid, a move with boundary speeds on each candidate's own polynomial."""
    h, Tc = move.displacement, T[:, None]
    if move.rest_to_rest or fixed_shape(law):  # its own shape: on its grid, at its T
        u, q_n, v_n, a_n = law_samples(law, samples)
        return u, h * q_n, h * v_n[None] / Tc, h * a_n[None] / (Tc * Tc)
    from sizer.laws.boundary_speeds import boundary_form

    basis = boundary_form(law.spec)
    assert basis is not None, "sizer.io.cycle accepts only laws with a boundary form"
    c = normalized_move(basis, move, T)  # (n, P, d+1), ascending powers of u - break
    p = np.arange(c.shape[2])
    parts: list[list[np.ndarray]] = [[], [], [], []]
    for k in range(len(basis.breaks) - 1):
        lo, hi = float(basis.breaks[k]), float(basis.breaks[k + 1])
        u = np.linspace(lo, hi, max(2, round(samples * (hi - lo))))
        x = (u - lo)[:, None]
        dx = np.where(p >= 1, p * x ** np.maximum(p - 1, 0), 0.0)
        ddx = np.where(p >= 2, p * (p - 1) * x ** np.maximum(p - 2, 0), 0.0)
        for out, values in zip(parts, (u, c[:, k, :] @ (x ** p).T, c[:, k, :] @ dx.T,
                                       c[:, k, :] @ ddx.T), strict=True):
            out.append(values)
    u, q, v, a = (np.concatenate(x, axis=-1) for x in parts)
    return u, h * q, h * v / Tc, h * a / (Tc * Tc)
