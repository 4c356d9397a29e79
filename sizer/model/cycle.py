"""A machine cycle of several segments, in SI units (issue 12; book sec. 5.2).

A cycle is an ordered list of segments: moves (a displacement by a motion law, from a
start speed to an end speed), constant-speed runs and dwells. Each segment may change
the load while it lasts: an added inertia (or mass, on a linear axis: a part picked up)
and an external torque (or force: pressing, cutting, gravity on a vertical leg), on top
of the design's load. The design's ``task`` (move, dwell, move back, dwell) is the
shorthand :func:`from_task` expands.

Durations: a segment's duration is fixed (``duration``) or free (None). Free durations
are one scale s times each segment's weight, T_i = w_i * s (book sec. 5.2: time scaling
keeps the shape of every free segment); the weights come from ``ShareRule``. Minimize
is the smallest s; a cycle time target fixes s. An optimized rule (``optimize: rms`` or
``energy``, a cycle time given) gives each candidate motor its own weights
(sizer.allocation); :meth:`Cycle.weights` is then the sqrt_displacement rule's (the
optimum of purely inertial moves by one law), their start.
"""

from __future__ import annotations

import enum
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from sizer.laws.base import MotionLaw
    from sizer.laws.choice import LawChoice


@dataclass(frozen=True)
class Task:
    """A rest-to-rest move of h in T (None = as fast as possible), then a dwell.

    With ``return_move`` the machine cycle is: move, dwell, move back, dwell.
    ``displacement`` is at the load: rad for a rotary axis, m for a linear one.
    """

    displacement: float
    duration: float | None = None
    dwell: float = 0.0
    return_move: bool = False
    linear: bool = False

    @property
    def minimize(self) -> bool:
        return self.duration is None

    @property
    def moves_per_cycle(self) -> int:
        return 2 if self.return_move else 1


class ShareRule(enum.Enum):
    """How free durations share the time: the weight w_i of each free segment."""

    EQUAL = "equal"
    """Every free segment takes the same time (the task shorthand: move and return)."""
    DISPLACEMENT = "displacement"
    """In proportion to |h| (the same mean speed)."""
    SQRT_DISPLACEMENT = "sqrt_displacement"
    """In proportion to sqrt(|h|): with the same law, the same peak acceleration."""
    WEIGHTS = "weights"
    """The ``weight`` each free segment gives."""
    OPTIMIZE_RMS = "optimize: rms"
    """Chosen per candidate motor to minimize the cycle's RMS motor torque at the given
    cycle time (sizer.allocation; the engine's figures): no weights shared by all."""
    OPTIMIZE_ENERGY = "optimize: energy"
    """Chosen per candidate motor to minimize the electrical energy per cycle (shaft work
    plus copper loss; the RMS goal where a motor lacks k_t or R): sizer.allocation."""
    OPTIMIZE_VIBRATION = "optimize: vibration"
    """Chosen to minimize the largest residual vibration over the moves (the load's mode,
    ``load.natural_frequency``): one split for every motor, the residual depends on the
    laws and durations only (sizer.allocation.minimax_split)."""
    OPTIMIZE_RMS_PER_MOVE = "optimize: rms, laws: per_move"
    """As OPTIMIZE_RMS, with a law per free move chosen with the split from the design's
    ``laws:`` (sizer.allocation.allocate_laws): each motor its own combination."""
    OPTIMIZE_ENERGY_PER_MOVE = "optimize: energy, laws: per_move"
    """As OPTIMIZE_ENERGY, with a law per free move chosen with the split."""

    @property
    def goal(self) -> str | None:
        """What an optimized split minimizes ("rms", "energy", "vibration"), None for a
        fixed rule."""
        return self.value.partition(": ")[2].partition(",")[0] or None

    @property
    def per_move(self) -> bool:
        """Whether each move that names no law takes its own of the design's laws, chosen
        with the split (``share: {optimize: GOAL, laws: per_move}``)."""
        return self.value.endswith("laws: per_move")


@dataclass(frozen=True)
class SegmentLoad:
    """What a segment adds to the design's load while it lasts (SI, at the load).

    ``inertia``: added inertia (kg*m^2) or mass (kg, linear axis), >= 0. ``torque``:
    added external torque (N*m) or force (N), signed like ``Load.torque`` (positive
    opposes a positive move).

    On a linear axis an added mass rides the design's guides: ``friction_coefficient``
    and ``incline`` are the design's (``load:``; the reader copies them in), and the
    part's weight adds mu m g cos(incline) of Coulomb friction and m g sin(incline) of
    gravity along the axis (sizer.mechanics.loads.linear_load, as for the design's own
    mass). Both are 0 on a rotary axis: an added inertia changes nothing else. They
    describe the axis, not what the segment adds, so equality ignores them.
    """

    inertia: float = 0.0
    torque: float = 0.0
    friction_coefficient: float = field(default=0.0, compare=False)
    incline: float = field(default=0.0, compare=False)

    @property
    def is_zero(self) -> bool:
        return self.inertia == 0.0 and self.torque == 0.0


@dataclass(frozen=True)
class Move:
    """A move of ``displacement`` (signed) from ``start_speed`` to ``end_speed`` (signed,
    at the load), by ``law`` (a law choice, a spec text read here; None: each of the
    design's laws in turn)."""

    displacement: float
    duration: float | None = None
    law: LawChoice | None = None
    start_speed: float = 0.0
    end_speed: float = 0.0
    weight: float = 1.0
    load: SegmentLoad = field(default_factory=SegmentLoad)
    name: str = ""
    start_acceleration: float = 0.0
    end_acceleration: float = 0.0
    """Boundary accelerations (signed, at the load), for the laws that can meet them
    (polynomials of degree 5 and 7, sizer.laws.boundary_speeds); 0 by default."""

    def __post_init__(self) -> None:
        if isinstance(self.law, str):
            from sizer.laws.choice import law_choice  # lazy: the law families load with a law

            object.__setattr__(self, "law", law_choice(self.law))

    @property
    def rest_to_rest(self) -> bool:
        return (self.start_speed == 0.0 and self.end_speed == 0.0
                and self.start_acceleration == 0.0 and self.end_acceleration == 0.0)


@dataclass(frozen=True)
class Run:
    """A constant-speed run: ``speed`` (signed, nonzero) for ``duration`` (fixed: a
    process speed and time, e.g. a flying saw synchronous with the line)."""

    speed: float
    duration: float
    load: SegmentLoad = field(default_factory=SegmentLoad)
    name: str = ""

    @property
    def displacement(self) -> float:
        return self.speed * self.duration

    @property
    def start_speed(self) -> float:
        return self.speed

    @property
    def end_speed(self) -> float:
        return self.speed


@dataclass(frozen=True)
class Dwell:
    """A rest of ``duration`` (None: free, scaled with the moves), holding the design's
    constant load plus the segment's own torque or force."""

    duration: float | None
    weight: float = 1.0
    load: SegmentLoad = field(default_factory=SegmentLoad)
    name: str = ""

    displacement = 0.0
    start_speed = 0.0
    end_speed = 0.0


Segment = Move | Run | Dwell


@dataclass(frozen=True)
class Cycle:
    """The segments of one machine cycle, repeated.

    ``cycle_time``: a target (s) that fixes the scale of the free durations; None with
    free segments means minimize. ``minimize_segment``: the name of the one segment to
    minimize (the others must be fixed). ``closed``: the cycle must end where it starts.
    ``shorthand``: the task it was expanded from, if any (results then report the move
    duration T, as always; otherwise the cycle time).
    """

    segments: tuple[Segment, ...]
    share: ShareRule = ShareRule.EQUAL
    cycle_time: float | None = None
    minimize_segment: str | None = None
    closed: bool = False
    linear: bool = False
    shorthand: Task | None = None

    @property
    def moves(self) -> tuple[Move, ...]:
        return tuple(s for s in self.segments if isinstance(s, Move))

    @property
    def free(self) -> tuple[int, ...]:
        """Indices of the segments with free durations (with ``minimize_segment``, that
        segment alone)."""
        if self.minimize_segment is not None:
            return tuple(i for i, s in enumerate(self.segments)
                         if s.name == self.minimize_segment)
        return tuple(i for i, s in enumerate(self.segments)
                     if not isinstance(s, Run) and s.duration is None)

    @property
    def minimize(self) -> bool:
        return bool(self.free) and self.cycle_time is None

    @property
    def fixed_time(self) -> float:
        """The sum of the fixed durations."""
        free = self.free
        return math.fsum(s.duration for i, s in enumerate(self.segments)
                         if s.duration is not None and i not in free)

    @property
    def net_displacement(self) -> float:
        return math.fsum(s.displacement for s in self.segments)

    def weights(self) -> tuple[float, ...]:
        """w_i of every segment (0 for fixed ones): T_i = w_i * s for the free ones."""
        out = []
        for i, s in enumerate(self.segments):
            if i not in self.free:
                out.append(0.0)
            elif self.share is ShareRule.EQUAL:
                out.append(1.0)
            elif self.share is ShareRule.WEIGHTS:
                assert not isinstance(s, Run)  # a run has its duration: never free
                out.append(s.weight)
            elif isinstance(s, Dwell):
                raise ValueError("a free dwell needs the `weights` share rule")
            elif self.share is ShareRule.DISPLACEMENT:
                out.append(abs(s.displacement))
            else:  # an optimized split starts from it (each candidate has its own)
                out.append(math.sqrt(abs(s.displacement)))
        return tuple(out)


def from_task(task: Task) -> Cycle:
    """The cycle the task shorthand means: move, dwell (and move back, dwell)."""
    segments: list[Segment] = [Move(task.displacement, task.duration, name="move")]
    if task.dwell > 0.0:
        segments.append(Dwell(task.dwell, name="dwell"))
    if task.return_move:
        segments.append(Move(-task.displacement, task.duration, name="return"))
        if task.dwell > 0.0:
            segments.append(Dwell(task.dwell, name="dwell 2"))
    return Cycle(tuple(segments), linear=task.linear, closed=task.return_move,
                 shorthand=task)


def boundary_laws(cycle: Cycle, laws: Sequence[LawChoice]) -> tuple[LawChoice, ...]:
    """The laws that can size the cycle's moves that name none: every one where those
    moves start and end at rest, else those with a form that meets their boundary speeds
    and accelerations (sizer.laws.boundary_speeds); ValueError where none can."""
    moving = [m for m in cycle.moves if m.law is None and not m.rest_to_rest]
    if not moving:
        return tuple(laws)
    from sizer.laws.boundary_speeds import boundary_form

    accelerated = any(m.start_acceleration or m.end_acceleration for m in moving)

    def usable(spec: LawChoice) -> bool:
        basis = None if spec.auto else boundary_form(spec.text)
        return basis is not None and (not accelerated or basis.meets_accelerations)

    kept = tuple(spec for spec in laws if usable(spec))
    if not kept:
        raise ValueError("none of the laws can start or end a move at a non-zero speed" + (
            " or acceleration (polynomials of degree 5 and 7 can)" if accelerated else
            " (those that can: trapezoidal, double_s, polynomial of degree 3, 5 or 7, "
            "constant_acceleration)") + "; name one in `laws:` or give the move its own "
            "`law:`")
    return kept


def shorthand_task(cycle: Cycle) -> Task | None:
    """The task whose expansion is ``cycle`` (:func:`from_task`: move, dwell, move back,
    dwell, equal durations, no load changes), else None: the engine sizes it by its
    closed-form single-law path (sizer.sizing.move.CycleCalculator)."""
    if cycle.shorthand is not None:
        return cycle.shorthand
    if (cycle.minimize_segment is not None or cycle.cycle_time is not None
            or cycle.share.goal):
        return None
    segments = cycle.segments
    moves = [s for s in segments if isinstance(s, Move)]
    dwells = [s for s in segments if isinstance(s, Dwell)]
    if len(moves) + len(dwells) != len(segments) or not 1 <= len(moves) <= 2:
        return None
    if any(m.law is not None or not m.rest_to_rest or not m.load.is_zero for m in moves):
        return None
    if any(d.duration is None or not d.load.is_zero for d in dwells):
        return None
    first = moves[0]
    if len(moves) == 2:
        back = moves[1]
        if back.displacement != -first.displacement or back.duration != first.duration:
            return None
        if first.duration is None and len(set(cycle.weights())) > 2:  # unequal free shares
            return None
        expected: list[type] = [Move, Dwell, Move, Dwell] if dwells else [Move, Move]
    else:
        expected = [Move, Dwell] if dwells else [Move]
    if [type(s) for s in segments] != expected:
        return None
    dwell = dwells[0].duration if dwells else 0.0
    if any(d.duration != dwell for d in dwells) or (dwells and not dwell):
        return None
    return Task(first.displacement, first.duration, dwell=dwell or 0.0,
                return_move=len(moves) == 2, linear=cycle.linear)


SHAPE_TOLERANCE = 1e-6
"""A move between boundary speeds by a law of fixed shape (a law defined by data, e.g. the
span of a cam table: :func:`fixed_shape`): its normalized end slopes q_N'(0), q_N'(1) must
equal s0 = v0 T/h and s1 = v1 T/h (and its end accelerations q_N''(0), q_N''(1) the
boundary accelerations a T^2/h where the move gives them) within this share of
max(1, |s|): an exported table's ends are the sized move's to rounding."""


def fixed_shape(law: MotionLaw) -> bool:
    """Whether ``law`` (a MotionLaw) has no form between boundary speeds
    (sizer.laws.boundary_speeds): its shape is its own, not a function of the move's
    duration, so a move between boundary speeds takes it only at a fixed duration that
    its end slopes fit (:func:`shape_mismatch`)."""
    from sizer.laws.boundary_speeds import boundary_form

    # the law object first (its family: no spec to read), its spec where that says none
    return boundary_form(law) is None and boundary_form(law.spec) is None


def shape_ends(law: MotionLaw, order: int) -> tuple[float, float]:
    """q_N^(order) of ``law`` at tau = 0 (its first piece) and tau = 1 (its last)."""
    return (float(law.piece_derivative(0, 0.0, order)),
            float(law.piece_derivative(len(law.pieces) - 1, 1.0, order)))


def shape_mismatch(move: Move, law: MotionLaw, duration: float, linear: bool = True
                   ) -> str | None:
    """Why ``law`` (of fixed shape) cannot be ``move`` over ``duration`` (s), or None: its
    end position must be 1 (a displacement, not a curve that returns), its end slopes
    s0 = v0 T/h and s1 = v1 T/h, and its end accelerations a T^2/h where the move gives
    non-zero ones, each within SHAPE_TOLERANCE (the numbers said, in SI units of a
    ``linear`` axis or a rotary one)."""
    length = "m" if linear else "rad"
    h, T = move.displacement, duration
    end = shape_ends(law, 0)[1]
    if abs(end - 1.0) > SHAPE_TOLERANCE:
        return (f"the law returns to its start (q_N(1) = {end:.6g}): a move's law must end "
                f"at its displacement")
    wanted: list[tuple[str, int, tuple[float, float], str, tuple[float, float]]] = [
        ("slope", 1, (move.start_speed * T / h, move.end_speed * T / h),
               "v T/h", (move.start_speed, move.end_speed))]
    if move.start_acceleration or move.end_acceleration:
        wanted.append(("acceleration", 2, (move.start_acceleration * T * T / h,
                                           move.end_acceleration * T * T / h), "a T^2/h",
                       (move.start_acceleration, move.end_acceleration)))
    for what, order, expected, formula, given in wanted:
        ends = shape_ends(law, order)
        for i in [0, 1] if order == 1 else [i for i in (0, 1) if given[i] != 0.0]:
            if abs(ends[i] - expected[i]) > SHAPE_TOLERANCE * max(1.0, abs(expected[i])):
                side = ("start", "end")[i]
                return (f"the law's normalized {side} {what} q_N{chr(39) * order}({i}) = "
                        f"{ends[i]:.9g} must equal {formula} = {expected[i]:.9g} (the move's "
                        f"{side} {'speed' if order == 1 else 'acceleration'} {given[i]:.9g} "
                        f"{length}/s{'' if order == 1 else '^2'}, duration T = {T:.9g} s, "
                        f"displacement h = {h:.9g} {length}) within {SHAPE_TOLERANCE:g} of "
                        f"max(1, |{formula}|)")
    return None
