"""A sized machine cycle of segments as the profile a cam exports (issue 37).

Each segment at the duration the sizing used for the chosen pair: the cycle's scale s at
the result (sizer.sizing.samples.scale_of: the result reports the cycle time, the fixed
segments keep their durations, the free ones last w_i s, as
sizer.sizing.cycle.SegmentCycle.durations). Over time the master is t (s); over a master
range the whole cycle time maps onto it (proportionally).

- a move from rest to rest: its own ``law:`` or the ranked law, scaled to its stroke;
- a move between boundary speeds (or accelerations): EXACTLY the shape the sizing
  evaluated, q_N(u) = B_h + s0 B_0 + s1 B_1 (+ r0 B_a0 + r1 B_a1) of the law's
  boundary-speed form (sizer.laws.boundary_speeds) at s0 = v0 T/h, s1 = v1 T/h (r = a
  T^2/h), built by sizer.sizing.cycle.normalized_move, frozen as a :class:`FrozenShape`
  whose ends are not at rest (q_N(0) = 0, q_N(1) = 1, q_N'(0) = s0, q_N'(1) = s1);
- a constant-speed run: a linear segment (q_N = u) of its stroke v T;
- a dwell: holds.

Zero-displacement moves cannot occur: the design reader refuses them at their line
("a segment without motion is a `dwell:`").

Pure numpy: no files, no printing.
"""

from __future__ import annotations

import math
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np

from sizer.export.profile import CamProfile, CamSegment
from sizer.laws.base import MotionLaw
from sizer.laws.per_move import RankedLaw
from sizer.laws.pieces import trig_poly_piece

if TYPE_CHECKING:
    from sizer.model.domain import Design
    from sizer.sizing.results import CandidateResult


class FrozenShape(MotionLaw):
    """A normalized shape on [0, 1] of fixed polynomial pieces, not necessarily at rest
    at its ends: ``coefficients[p, k]`` of (u - breaks[p])^k on piece p. ``source`` is
    the law (family) whose boundary-speed form it is (None: a run, q_N = u); ``speeds``
    (s0, s1) and ``accelerations`` (r0, r1) its normalized boundary values."""

    law_id = "frozen"
    title = "A move between boundary speeds, frozen at its duration"

    def __init__(self, label: str, breaks: np.ndarray, coefficients: np.ndarray,
                 source: MotionLaw | None, speeds: tuple[float, float],
                 accelerations: tuple[float, float] = (0.0, 0.0)) -> None:
        self._label = label
        self._breaks = np.asarray(breaks, dtype=float)
        self._coefficients = np.asarray(coefficients, dtype=float)
        self.source = source
        self.speeds = (float(speeds[0]), float(speeds[1]))
        self.accelerations = (float(accelerations[0]), float(accelerations[1]))
        super().__init__()

    def _build(self):
        pieces = [trig_poly_piece(float(a), float(b), tuple(c), origin=float(a))
                  for a, b, c in zip(self._breaks[:-1], self._breaks[1:],
                                     self._coefficients, strict=True)]
        return pieces, 1

    @cached_property
    def spec(self) -> str:
        return self._label

    @property
    def is_run(self) -> bool:
        return self.source is None

    def outside(self, order: int) -> tuple[float, float]:
        """Its neighbours in the cycle continue its position and speed."""
        if order == 0:
            return 0.0, 1.0
        if order == 1:
            return self.speeds
        return 0.0, 0.0

    def __reduce__(self):  # a frozen shape is not a registry law: pickled as itself
        return (FrozenShape, (self._label, self._breaks, self._coefficients, self.source,
                              self.speeds, self.accelerations))


def run_shape() -> FrozenShape:
    """q_N = u: a constant-speed run."""
    return FrozenShape("linear (constant speed)", np.array([0.0, 1.0]),
                       np.array([[0.0, 1.0]]), None, (1.0, 1.0))


def segment_durations(design: Design, duration: float,
                      pair: CandidateResult | None = None) -> list[float]:
    """Each segment's duration (s) at the result's reported ``duration``: the cycle time
    of a cycle of segments (the move duration T for the task shorthand), as the sizing
    scaled it (sizer.sizing.samples.scale_of, SegmentCycle.durations). A split chosen per
    motor (``share: {optimize: ...}``) is the sized ``pair``'s own
    (sizer.sizing.samples.pair_durations); ValueError without the pair."""
    from sizer.sizing.samples import pair_durations, scale_of

    cycle = design.machine_cycle
    if cycle.share.goal is not None:
        if pair is None:
            raise ValueError(f"share: {{{cycle.share.value}}} splits the cycle time for "
                             "each motor: export a sized pair")
        return pair_durations(design, pair.motor_object, pair.law_object, duration,
                              pair.transmission)
    s = scale_of(design, duration)
    free, weights = cycle.free, cycle.weights()
    out = []
    for i, segment in enumerate(cycle.segments):
        if i in free or segment.duration is None:
            out.append(weights[i] * s)
        else:
            out.append(float(segment.duration))
    return out


def cycle_profile(design: Design, law: RankedLaw | None, duration: float,
                  master_range: float | None = None,
                  pair: CandidateResult | None = None) -> CamProfile:
    """The design's whole machine cycle at the result's reported ``duration`` (s),
    moves by their own ``law:`` or ``law`` (the ranked one); the slave in mm (linear
    axis) or deg, the master in s or, with ``master_range`` (deg), spanning the cycle.

    The profile's ``law`` is ``law`` (or the first move's), its ``stroke`` the cycle's
    travel (the largest position less the smallest): the reference of the tolerance."""
    from sizer.laws.boundary_speeds import boundary_form
    from sizer.model.cycle import Dwell, Move, Run, fixed_shape
    from sizer.sizing.cycle import cycle_laws, normalized_move

    cycle = design.machine_cycle
    durations = segment_durations(design, duration, pair)
    total = math.fsum(durations)
    if not (math.isfinite(total) and total > 0.0):
        raise ValueError(f"the cycle has no positive duration (got {total!r} s)")
    scale = 1.0 if master_range is None else master_range / total
    factor = 1000.0 if cycle.linear else math.degrees(1.0)
    laws = cycle_laws(cycle, law)
    segments: list[CamSegment] = []
    y = 0.0
    for i, (segment, the_law, T) in enumerate(zip(cycle.segments, laws, durations,
                                                  strict=True)):
        name = segment.name or type(segment).__name__.lower()
        if T <= 0.0:
            raise ValueError(f"segment {name!r} lasts {T!r} s: nothing to export")
        x, span = math.fsum(durations[:i]) * scale, T * scale
        speeds: tuple[float, float] | None = None
        shape: MotionLaw | None
        if isinstance(segment, Dwell):
            shape, stroke = None, 0.0
        elif isinstance(segment, Run):
            shape, stroke = run_shape(), segment.speed * T * factor
            speeds = (segment.speed * factor / scale, segment.speed * factor / scale)
        else:
            assert isinstance(segment, Move) and the_law is not None
            stroke = segment.displacement * factor
            shape = the_law
            if not segment.rest_to_rest and fixed_shape(the_law):
                # a law of its own shape at the fixed duration (a span of an exported
                # file: sizer.model.cycle.shape_mismatch checked its end slopes)
                speeds = (segment.start_speed * factor / scale,
                          segment.end_speed * factor / scale)
            elif not segment.rest_to_rest:
                basis = boundary_form(the_law.spec)
                if basis is None:
                    raise ValueError(f"{the_law.spec} has no form between boundary speeds "
                                     f"(segment {name!r})")
                c = normalized_move(basis, segment, np.array([T]))[0]
                h = segment.displacement
                s01 = (segment.start_speed * T / h, segment.end_speed * T / h)
                acc = (segment.start_acceleration * T * T / h,
                       segment.end_acceleration * T * T / h)
                shape = FrozenShape(f"{the_law.spec} between boundary speeds "
                                    f"(s0 = {s01[0]:.6g}, s1 = {s01[1]:.6g})",
                                    basis.breaks, c, the_law, s01, acc)
                speeds = (segment.start_speed * factor / scale,
                          segment.end_speed * factor / scale)
        segments.append(CamSegment(x, span, y, stroke, shape, name, speeds))
        y = y + stroke
    positions = np.cumsum([0.0] + [s.stroke for s in segments])
    travel = float(np.max(positions) - np.min(positions))
    label = law if law is not None else next(s.law for s in segments if s.law is not None)
    assert label is not None
    return CamProfile(label, travel, total * scale, "mm" if cycle.linear else "deg",
                      "s" if master_range is None else "deg", tuple(segments))
