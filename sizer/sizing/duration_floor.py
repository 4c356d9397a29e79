"""Below which duration can no candidate be feasible? A floor under the T_min it reports.

The peak and speed bound of sizer.sizing.peak_duration (book sec. 6.1.1, eq. 6.2 in the
rectangular case) holds for the checks as they are decided, tolerance included, when
every limit it reads is relaxed by the checks' tolerance: a check passes where value <=
(1 - required + TOLERANCE) * limit (sizer.sizing.checks), so a torque margin m reads as
m - TOLERANCE, a speed margin likewise, a load limit as (1 + TOLERANCE) times itself.
Every duration a candidate reports as feasible passes those checks, so it is at least
the floor; the searches that move T_min up afterwards (the residual vibration, braking
and heat) keep it so. The ratio search (sizer.sizing.ratio_choice) leaves out an option
whose floor lies above a motor's best T_min: it cannot beat it.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from sizer.laws import AUTO, make_law, resolve
from sizer.laws.open_shaped import is_open_shaped
from sizer.model.domain import Design, Limits
from sizer.sizing.candidates import Candidates
from sizer.sizing.checks import TOLERANCE
from sizer.sizing.cycle import CycleCalculator
from sizer.sizing.minimum_duration import is_purely_inertial
from sizer.sizing.peak_duration import peak_queries, speed_bounds

CHUNK = 1 << 14
"""Candidates bounded at once (the peak queries of each are a few dozen numbers)."""


def relaxed(limits: Limits) -> Limits:
    """The limits as the checks apply them at the edge of their tolerance."""
    def wider(limit: float | None) -> float | None:
        return None if limit is None else limit * (1.0 + TOLERANCE)

    return dataclasses.replace(
        limits, torque_margin=limits.torque_margin - TOLERANCE,
        speed_margin=limits.speed_margin - TOLERANCE, max_speed=wider(limits.max_speed),
        max_acceleration=wider(limits.max_acceleration), max_jerk=wider(limits.max_jerk))


@dataclass(frozen=True)
class PeakScales:
    """What the floor's peak part takes from the candidates, for every law at once.

    Each peak query F(u) <= D of sizer.sizing.peak_duration has its lower bracket 1/u =
    max(sqrt(C_a P / D), C_v Q / D) where D > 0 and P, Q >= 0 (0 where P or Q < 0, no
    duration where D <= 0): the law enters by C_a and C_v only, so a candidate's largest
    bracket is max(sqrt(C_a) root, C_v ratio) with ``root`` its largest sqrt(P / D) and
    ``ratio`` its largest Q / D, and ``blocked`` where some D <= 0."""

    root: np.ndarray
    ratio: np.ndarray
    blocked: np.ndarray


def peak_scales(design: Design, candidates: Candidates) -> PeakScales:
    """The :class:`PeakScales` of the candidates, limits relaxed (module docs)."""
    limits, n = relaxed(design.limits), len(candidates)
    root, ratio, blocked = np.zeros(n), np.zeros(n), np.zeros(n, dtype=bool)
    for start in range(0, n, CHUNK):
        rows = np.arange(start, min(start + CHUNK, n))
        part = candidates if n <= CHUNK else candidates.take(rows)
        calculator = CycleCalculator(None, design.task, part.drive, part.motors,
                                     design.limits.thermal_speed)
        queries = peak_queries(calculator, limits)
        if queries is None:
            continue
        who, P, Q, D = queries
        usable = (D > 0.0) & (P >= 0.0) & (Q >= 0.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            np.maximum.at(root, rows[who[usable]], np.sqrt(P[usable] / D[usable]))
            np.maximum.at(ratio, rows[who[usable]], Q[usable] / D[usable])
        blocked[rows[who[D <= 0.0]]] = True
    return PeakScales(root, ratio, blocked)


def duration_floor(design: Design, spec: str, candidates: Candidates,
                   scales: PeakScales | None = None) -> np.ndarray | None:
    """Per candidate a duration below which the law ``spec`` is infeasible, in minimize
    mode for the task shorthand (a move, its dwell and return) with a fixed law; None
    where there is no such floor (a given duration, a linkage, a law shaped per
    candidate, a law that moves backwards) or no need of one (the closed form of eq. 6.2
    sizes every option at the cost of one evaluation). ``scales``: the candidates'
    :func:`peak_scales` where known (the same for every law). A cycle of segments has
    its own floor: :func:`_cycle_floor`."""
    minimize = design.task.minimize if design.cycle is None else design.cycle.minimize
    if not minimize or design.transmission.linkage is not None or is_open_shaped(spec):
        return None
    _, values = resolve(spec)
    if any(v == AUTO for v in values.values()):
        return None
    law, limits = make_law(spec), relaxed(design.limits)
    if design.cycle is not None:
        return _cycle_floor(design, law, candidates, limits)
    calculator = CycleCalculator(None, design.task, candidates.drive, candidates.motors,
                                 design.limits.thermal_speed, law=law)
    if is_purely_inertial(calculator):  # eq. (6.2): every option is cheap as it is
        return None
    if float(law.linear_peaks.minimum(0.0, 1.0).value) < -1e-12:
        return None  # it moves backwards: no peak bound (sizer.sizing.peak_duration)
    if calculator.h == 0.0:
        return np.zeros(len(candidates))
    scales = peak_scales(design, candidates) if scales is None else scales
    c = law.coefficients
    peak = np.where(scales.blocked, np.inf,
                    np.maximum(math.sqrt(c.C_a) * scales.root, c.C_v * scales.ratio))
    return np.maximum(speed_bounds(calculator, limits), peak)


def _cycle_floor(design: Design, law, candidates: Candidates,
                 limits: Limits) -> np.ndarray | None:
    """The floor of a cycle of segments in minimize mode: its time at the lower bound on
    the scale of its free durations from the free moves' peak checks (SegmentCycle.
    peak_bound, the limits relaxed), below which no scale passes them; the cycle time
    grows with the scale. None where a law moves backwards (no bound)."""
    from sizer.sizing.segment_cycle import SegmentCycle  # only designs with a cycle need it

    cycle = design.cycle
    assert cycle is not None
    n = len(candidates)
    out = np.zeros(n)
    for start in range(0, n, CHUNK):
        rows = np.arange(start, min(start + CHUNK, n))
        part = candidates if n <= CHUNK else candidates.take(rows)
        calculator = SegmentCycle(cycle, law, part.drive, part.motors,
                                  design.limits.thermal_speed)
        bound = calculator.peak_bound(limits)
        if bound is None:
            return None
        out[rows] = calculator.cycle_time(bound)
    return out
