"""What every cycle model answers, and the one evaluation it returns (book sec. 6.1.1).

A cycle model is one law (or a cycle's laws) for many candidates at once: a single move
rest-to-rest (sizer.sizing.move.CycleCalculator), a cycle of segments
(sizer.sizing.cycle.SegmentCycle), a move or a cycle through a linkage
(sizer.sizing.linkage_move.LinkageCalculator, sizer.sizing.linkage_move.LinkageCycle).
Each satisfies :class:`CycleModel` structurally; the search for the shortest duration, the
checks and the later limits (residual vibration, energy and heat) ask only what it
declares. Each evaluation is one
:class:`CycleMetrics`: arrays over candidates, SI. Each model samples itself piece by piece
(:class:`CyclePiece`, for sizer.sizing.samples); a cycle of segments also gives each
segment's figures (:class:`SegmentedModel`, :class:`SegmentPart`).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any, Protocol, Self

import numpy as np

if TYPE_CHECKING:
    from sizer.laws import MotionLaw
    from sizer.mechanics import Drive
    from sizer.model.domain import Limits, Load, Task
    from sizer.sizing.candidates import MotorArrays
    from sizer.sizing.move import CycleCalculator


@dataclass(frozen=True)
class CycleMetrics:
    """Requirements of one law for each candidate (arrays over candidates, SI).

    Motor side: max_speed, peak_torque, peak_ratio (worst |tau|/tau_int(|speed|)),
    rms_torque, thermal_speed. Load side: load_speed, load_acceleration, load_jerk (peaks)
    and load_torque (peak |u|). Per stage: stage_peak and stage_rms output torques and
    stage_speed (peak input speed), lists over the stages.
    """

    duration: np.ndarray
    max_speed: np.ndarray
    peak_torque: np.ndarray
    peak_ratio: np.ndarray
    rms_torque: np.ndarray
    thermal_speed: np.ndarray
    load_speed: np.ndarray
    load_acceleration: np.ndarray
    load_jerk: np.ndarray
    load_torque: np.ndarray
    stage_peak: list[np.ndarray]
    stage_rms: list[np.ndarray]
    stage_speed: list[np.ndarray]
    rms_model: RmsCurve | None = None


SAMPLES = 1001
"""Samples of the normalized law per move for energy and heat (spread over its pieces by
their lengths)."""


@dataclass(frozen=True)
class CyclePiece:
    """One segment of a sampled cycle: (candidates, samples) arrays, or (samples,) where
    the same for every candidate (the load's position); ``theta`` and ``ratio`` through a
    linkage only. Times from the cycle's start (a repeated time is a jump), the load's
    position, speed and acceleration, the motor's speed and acceleration, the motor torque
    signed like the motion (SI). ``load``: the load the piece moves where it is not the
    model's drive's (whose load is the heaviest of the cycle, for the inertia ratio): a
    segment's own (a picked-up part's mass while it is carried), or a load of the
    position whose terms act at the piece's positions; None: the drive's."""

    name: str
    time: np.ndarray
    position: np.ndarray
    load_speed: np.ndarray
    load_acceleration: np.ndarray
    motor_speed: np.ndarray
    motor_acceleration: np.ndarray
    torque: np.ndarray
    theta: np.ndarray | None = None
    ratio: np.ndarray | None = None
    load: Load | None = None


def held_piece(name: str, start: np.ndarray, T: np.ndarray, position: float,
               torque: np.ndarray) -> CyclePiece:
    """A dwell of T (candidates, 1) from ``start`` holding ``torque`` (candidates,)."""
    zeros = np.zeros((len(start), 2))
    return CyclePiece(name, np.concatenate([start, start + T], axis=1), np.full(2, position),
                      zeros, zeros, zeros, zeros,
                      np.repeat(np.asarray(torque)[:, None], 2, axis=1))


@dataclass(frozen=True)
class SegmentPart:
    """One segment of a cycle for its breakdown (sizer.sizing.samples.segment_breakdown):
    its name, kind (move, run, dwell) and law, and per candidate its duration, peak motor
    torque, integral of tau^2 (``square``), peak motor speed, work at the motor shaft, the
    load's acceleration at its start and end, and for a move its acceleration scale (the
    largest |h|/T^2 the join tolerance is a share of; None for a run or a dwell)."""

    name: str
    kind: str
    law: MotionLaw | None
    duration: np.ndarray
    peak_torque: np.ndarray
    square: np.ndarray
    max_speed: np.ndarray
    energy: np.ndarray
    start_acceleration: np.ndarray
    end_acceleration: np.ndarray
    acceleration_scale: np.ndarray | None


def singular_metrics(metrics: CycleMetrics) -> CycleMetrics:
    """The metrics of a law that breaks the dead-point rule: its peak and RMS torques are
    not numbers (NaN, so results hold None and reports a verdict, never inf); the peak
    ratio is unbounded (its check fails, :func:`unbounded`)."""
    n = len(metrics.peak_torque)
    return replace(metrics, peak_torque=np.full(n, np.nan), peak_ratio=np.full(n, np.inf),
                   rms_torque=np.full(n, np.nan))


class RmsCurve(Protocol):
    """The RMS torque as a function of the duration near where it was built: a law's
    :class:`RmsModel`, or a cycle's (sizer.sizing.cycle.CycleRmsModel)."""

    def rms(self, T: np.ndarray, index: np.ndarray | None = None) -> np.ndarray: ...


class CycleModel(Protocol):
    """A cycle (or move) of one law evaluated for many candidates at a duration each: the
    move's duration T, or for a cycle the scale s of its free durations."""

    segmented: bool
    """A cycle of segments (time-scaled by s) rather than one law move rest-to-rest."""

    @property
    def task(self) -> Task:
        """The move (or the cycle's first move) as a task: displacement, linear or not."""
        ...

    @property
    def drive(self) -> Drive:
        """The drive the checks read (a cycle's: its heaviest segment's load)."""
        ...

    @property
    def motors(self) -> MotorArrays:
        """The candidates' motors."""
        ...

    def take(self, index: np.ndarray) -> Self:
        """The same model for the candidates at ``index``."""
        ...

    def evaluate(self, duration: np.ndarray, peaks: bool = True, model: bool = False,
                 rms: np.ndarray | None = None) -> CycleMetrics:
        """The requirements at ``duration``; without ``peaks`` the peak torques and ratios
        left at zero; with ``model`` the RMS model there where the model has one; ``rms``:
        the motor's RMS torque there where known (a model may skip computing it)."""
        ...

    def thermal_speed(self, T: np.ndarray) -> np.ndarray:
        """The speed at which the continuous torque limit is read (sec. 6.1.1)."""
        ...

    def peak_bound(self, limits: Limits) -> np.ndarray | None:
        """The largest duration below which a peak or speed check fails, or None where no
        such bound holds."""
        ...

    def search_start(self, limits: Limits) -> np.ndarray | None:
        """Where the searches start for the candidates whose peak bound is 0 (no answer
        there): a duration below which a check fails and from which on the peak check
        passes (through a linkage the larger of the speed bound and the peak floor; inf:
        no duration passes them); None: from a usable peak bound or the initial guess."""
        ...

    def initial_guess(self) -> np.ndarray:
        """A duration scale to start a search from (never zero)."""
        ...

    def rms_lower_bound(self) -> np.ndarray | None:
        """A torque the motor's RMS exceeds at every duration, or None where none holds."""
        ...

    def reported(self, metrics: CycleMetrics) -> np.ndarray:
        """The duration a result reports from the metrics at a scale: the move's T, the
        cycle time, or each move's T of a task with a return through a linkage."""
        ...

    def dead_point_issues(self) -> tuple[str, ...] | None:
        """The dead-point rules the law breaks through a linkage (book sec. 3: the paper
        on linkages at dead points), () where it breaks none; None without a linkage (no
        dead-point check)."""
        ...

    def given_scale(self) -> float:
        """The scale of the design's given durations (not minimized): the move's T, or
        the scale of a cycle's free durations."""
        ...

    def law_move(self) -> CycleCalculator | None:
        """The law move rest-to-rest this model is (its closed forms: book eq. 6.2), or
        None."""
        ...

    def cycle_time(self, s: np.ndarray) -> np.ndarray:
        """The machine cycle's time at durations (or scales) s."""
        ...

    def scale_of(self, duration: np.ndarray) -> np.ndarray:
        """The durations (or scales) s at which :meth:`evaluate` reports ``duration``."""
        ...

    def pieces(self, s: np.ndarray, samples: int | None = None) -> list[CyclePiece]:
        """The machine cycle at durations (or scales) s (one per candidate), piece by
        piece: each move on ``samples`` points (None: the model's own for energy and heat,
        SAMPLES of a law, a linkage profile's whole uniform grid), each dwell holding its
        torque."""
        ...


class SegmentedModel(CycleModel, Protocol):
    """A cycle of segments (``segmented``): also each segment's figures."""

    def breakdown(self, s: np.ndarray) -> list[SegmentPart]:
        """Each segment's figures at scales s (sizer.sizing.samples.segment_breakdown)."""
        ...


def rms_of_powers(c: np.ndarray, T: np.ndarray, n: int, dwell: float,
                  hold: np.ndarray) -> np.ndarray:
    """The RMS torque at durations T of n moves whose summed int tau^2 dt is
    c_3/T^3 + c_2/T^2 + c_1/T + c_0 + c_(-1) T (rows of ``c``: :attr:`RmsModel.powers`),
    each followed by a dwell holding ``hold``."""
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        u = 1.0 / T
        square = ((c[0] * u + c[1]) * u + c[2]) * u + c[3] + c[4] * T
        mean = (square + n * dwell * np.square(hold)) / (n * (T + dwell))
    return np.sqrt(np.where(np.isnan(mean), np.inf, mean))


def thermal_speed_of(rule: str, K: float | np.ndarray, h: float, dwell: float, n: int,
                     C_v: float | np.ndarray, C_v_rms: float | np.ndarray,
                     T: np.ndarray) -> np.ndarray:
    """The speed the continuous region is read at (the thermal rule, book sec. 6.1.1) of n
    moves of h at durations T with dwells, ratio K and the law's C_v, C_v_rms (one per row
    where the rows' laws differ): the peak speed as in the book, or the RMS or mean speed
    over the cycle (sizer.sizing.move.CycleCalculator.thermal_speed)."""
    cycle = n * (T + dwell)
    if rule == "max":
        return K * C_v * h / T
    if rule == "rms":
        return K * h * C_v_rms * np.sqrt(n * T / cycle) / T
    return n * K * h / cycle


def combined_metrics(found: Sequence[CycleMetrics],
                     combine: Callable[[list[np.ndarray]], np.ndarray]) -> dict[str, Any]:
    """The fields of one CycleMetrics from several, each array (and each stage's) the
    ``combine`` of theirs; the RMS model left out."""
    fields: dict[str, Any] = {}
    for field in dataclasses.fields(CycleMetrics):
        if field.name == "rms_model":
            continue
        values = [getattr(m, field.name) for m in found]
        fields[field.name] = [combine(list(stage)) for stage in zip(*values, strict=True)] \
            if isinstance(values[0], list) else combine(values)
    return fields
