"""The trade-off front of a sizing: which feasible candidates no other one beats on both
speed and motor size, and the knee among them (issue 36).

Two objectives, both read so that smaller is better:

- the **time**: with ``duration: minimize`` the candidate's shortest duration (T_min of
  the move, or the shortest cycle time of a cycle of segments: ``CandidateResult.duration``);
  with a given duration every feasible candidate takes the same time, so the question
  becomes how much room a bigger motor buys: the candidate's **smallest margin beyond the
  required one** over all its checks (the key of ``--rank-by margin``), larger better;
- the **size** (:class:`FrontBy`): the motor's rated power tau_c*v_n (``power``, the
  default), its ``price`` or ``mass`` (catalog figures), or the net ``energy`` drawn from
  the DC bus per machine cycle (``cycle_energy``, designs with energy or heat checks).

A candidate is **on the front** when it is feasible, both its figures are known, and no
other such candidate is at least as good in both and strictly better in one (Pareto
dominance; the figures compared to 12 significant digits, a margin to 1e-12, so that the
engine's rounding noise splits no tie: two candidates with the same two figures are both
on the front). Feasible candidates whose size figure is unknown (a motor without a
price) are left out of the front and counted (:attr:`Front.left_out`).

The **knee** (:data:`KNEE_RULE`): both objectives scaled to [0, 1] over the front
(0 the best value on the front, 1 the worst), the front point farthest from the straight
line through the front's two ends (the smallest motor and the fastest candidate), on the
side of the ideal point (0, 0): the largest 1 - t - s. None when the front has fewer than
three distinct points or no point lies strictly on that side (a straight or concave front
has no best compromise); ties go to the smaller motor.

Pure numpy: the dominance test and the knee are vectorized over the candidates.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum
from functools import cached_property

import numpy as np

from sizer.errors import UserError
from sizer.sizing.ranking import margin_columns, rated_power_column
from sizer.sizing.results import CandidateResult, Mode, Rows, SizingResult


class FrontBy(StrEnum):
    """The size objective of a front (``--front-by``)."""

    POWER = "power"
    PRICE = "price"
    MASS = "mass"
    ENERGY = "energy"


FRONT_ALIASES: dict[str, FrontBy] = {"size": FrontBy.POWER, "rated_power": FrontBy.POWER}
"""Other names accepted for a size objective."""

FRONT_CHOICES = ", ".join(k.value for k in FrontBy)
"""The size objectives, in words."""

@dataclass(frozen=True)
class SizeObjective:
    """A size objective: the result field (record key) it reads, what it is in words,
    its short name and unit in tables and plots, and its SI unit in JSON."""

    field: str
    text: str
    name: str
    unit: str
    json_unit: str


SIZE_OBJECTIVES: dict[FrontBy, SizeObjective] = {
    FrontBy.POWER: SizeObjective("rated_power", "the motor's rated power tau_c*v_n",
                                 "rated power", "W", "W (tau_c*v_n)"),
    FrontBy.PRICE: SizeObjective("price", "the motor's catalog price", "price", "",
                                 "as in the catalog"),
    FrontBy.MASS: SizeObjective("mass", "the motor's mass", "mass", "kg", "kg"),
    FrontBy.ENERGY: SizeObjective(
        "cycle_energy", "the net energy drawn from the DC bus per machine cycle",
        "energy per cycle", "J", "J per machine cycle drawn from the DC bus (net)"),
}
"""Each size objective, listed once."""

KNEE_RULE = ("knee: with both objectives scaled to [0, 1] over the front, the front point "
             "farthest from the straight line through the front's two ends (its smallest "
             "motor and its best time, or margin), on the side of the ideal point; none "
             "with fewer than 3 distinct points or a front that does not bulge towards the "
             "ideal point")
"""The rule of the knee, in words."""

MARGIN = "margin"
DURATION = "duration"
"""The names of the time objective: ``duration`` (minimize mode, smaller better) or
``margin`` (a given duration: the smallest margin beyond the required one, larger
better)."""

KNEE = "knee"
ON_FRONT = "front"
"""The front status of a row: ``knee``, ``front``, or '' (not on the front)."""


def front_by(text: str | FrontBy | None) -> FrontBy:
    """The size objective a text names (None: power); UserError (``field="front_by"``)
    naming the choices when it names none."""
    if text is None:
        return FrontBy.POWER
    name = str(text).strip().lower()
    found = FRONT_ALIASES.get(name, next((k for k in FrontBy if k == name), None))
    if found is None:
        raise UserError(f"unknown size objective {str(text)!r}; choose one of "
                        f"{FRONT_CHOICES}", field="front_by")
    return found


def non_dominated(time: np.ndarray, size: np.ndarray) -> np.ndarray:
    """True where a point is on the front of (time, size), both minimized.

    Points with a NaN or infinite coordinate are on no front and dominate nothing. A point
    is dominated when another is no worse in both coordinates and better in one; equal
    points do not dominate each other. Sorted by (time, size), a point is dominated exactly
    when an earlier point of strictly smaller time has a size no larger, or an earlier point
    of equal time a smaller size: two cumulative minima, no loop over the points.
    """
    t = np.asarray(time, dtype=float)
    s = np.asarray(size, dtype=float)
    known = np.isfinite(t) & np.isfinite(s)
    index = np.flatnonzero(known)
    out = np.zeros(t.shape, dtype=bool)
    if index.size == 0:
        return out
    order = index[np.lexsort((s[index], t[index]))]
    ts, ss = t[order], s[order]
    starts = np.r_[True, ts[1:] != ts[:-1]]  # the first of each group of equal times
    group = np.cumsum(starts) - 1
    first = np.flatnonzero(starts)
    running = np.minimum.accumulate(ss)
    # the smallest size among strictly faster points: the running minimum before the group
    before = np.r_[np.inf, running][first][group]
    group_best = ss[first][group]  # the smallest size at the same time (sorted by size)
    out[order] = (before > ss) & (group_best >= ss)
    return out


def knee_of(time: np.ndarray, size: np.ndarray) -> int | None:
    """The index of the knee among front points (time, size), both minimized (see
    :data:`KNEE_RULE`); None when there is none. Ties: the smaller size, then the first."""
    t = np.asarray(time, dtype=float)
    s = np.asarray(size, dtype=float)
    if t.size < 3:
        return None
    span_t, span_s = np.ptp(t), np.ptp(s)
    if not (span_t > 0.0 and span_s > 0.0):
        return None
    # scaled to [0, 1]: the ends of a front are (t, s) = (1, 0), the smallest motor, and
    # (0, 1), the fastest; the line through them is t + s = 1, the ideal point (0, 0)
    bulge = 1.0 - (t - t.min()) / span_t - (s - s.min()) / span_s
    order = np.lexsort((t, s))  # ties to the smaller motor, then the faster
    best = order[int(np.argmax(bulge[order]))]
    if not bulge[best] > 1e-12:
        return None
    return int(best)


@dataclass(frozen=True, eq=False)
class Front:
    """The front of a sizing's ranked results (positions are indices into
    ``SizingResult.results``).

    ``time`` and ``size`` hold each result's objectives as reported (SI; ``time`` is the
    duration in s, or with ``time_name == "margin"`` the smallest margin beyond the
    required one as a fraction; NaN where the result is infeasible or the figure unknown).
    ``members`` are the front's positions sorted by size, then time; ``knee`` the knee's
    position or None; ``left_out`` the feasible results without a size figure.
    """

    by: FrontBy
    time_name: str
    time: np.ndarray
    size: np.ndarray
    members: np.ndarray
    knee: int | None
    left_out: int = 0

    @property
    def size_field(self) -> str:
        return SIZE_OBJECTIVES[self.by].field

    @cached_property
    def statuses(self) -> tuple[str, ...]:
        """Per result (ranked order): ``knee``, ``front`` or ''."""
        out = np.full(len(self.time), "", dtype=object)
        out[self.members] = ON_FRONT
        if self.knee is not None:
            out[self.knee] = KNEE
        return tuple(str(x) for x in out)

    @property
    def rule(self) -> str:
        """The front in words: its objectives, the dominance and the knee."""
        time = ("the duration (T_min, or the shortest cycle time)"
                if self.time_name == DURATION else
                "the smallest margin beyond the required one over all checks (larger "
                "better: the duration is given)")
        return (f"front: the feasible pairs that no other pair beats in both {time} and "
                f"{SIZE_OBJECTIVES[self.by].text} (each smaller better unless said); {KNEE_RULE}")


def objectives(sizing: SizingResult, by: FrontBy | str | None = None
               ) -> tuple[np.ndarray, np.ndarray, str]:
    """(time, size, time name) per ranked result, both to minimize: the duration, or
    minus the smallest slack with a given duration; NaN where infeasible or unknown."""
    key = front_by(by)
    field = SIZE_OBJECTIVES[key].field
    results = sizing.results
    table = sizing.table
    if table is not None and isinstance(results, Rows) and results.table is table:
        order = results.order
        feasible = np.asarray(table.feasible, dtype=bool)[order]
        if sizing.mode is Mode.MINIMIZE:
            time = np.asarray(table.figures["duration"], dtype=float)[order]
        else:  # the smallest margin, negated: the ranking's own key (--rank-by margin)
            time = margin_columns(table)[0][order]
        if key is FrontBy.POWER:
            size = rated_power_column(table)[0][order]
        elif key is FrontBy.ENERGY:
            size = (np.asarray(table.figures[field], dtype=float)[order]
                    if field in table.figures else np.full(len(order), np.nan))
        else:
            size = table.motor_column(field)[order]
    else:
        feasible = np.array([r.feasible for r in results], dtype=bool)
        time = np.array([_time_of(r, sizing.mode) for r in results], dtype=float)
        size = np.array([_float(getattr(r, field)) for r in results], dtype=float)
    time = np.where(feasible & np.isfinite(time), time, np.nan)
    size = np.where(feasible & np.isfinite(size), size, np.nan)
    return time, size, DURATION if sizing.mode is Mode.MINIMIZE else MARGIN


def trade_off(sizing: SizingResult, by: FrontBy | str | None = None) -> Front:
    """The front of ``sizing``'s feasible candidates in time and ``by`` (power by default),
    with its knee (module docstring). A UserError (``field="front_by"``) when no feasible
    candidate has the size figure while some is feasible."""
    key = front_by(by)
    time, size, name = objectives(sizing, key)
    feasible_time = np.isfinite(time)
    known = feasible_time & np.isfinite(size)
    left_out = int(np.count_nonzero(feasible_time & ~known))
    if left_out and not np.any(known):
        objective = SIZE_OBJECTIVES[key]
        raise UserError(f"no feasible pair has {objective.text} ({objective.field}): "
                        f"the front by {key.value} needs it; choose one of {FRONT_CHOICES}",
                        field="front_by")
    on = non_dominated(_compared(time, name), _compared(size, None))
    members = np.flatnonzero(on)
    members = members[np.lexsort((time[members], size[members]))]
    knee = knee_of(time[members], size[members])
    signed = -time if name == MARGIN else time
    return Front(key, name, signed, size, members,
                 None if knee is None else int(members[knee]), left_out)


def _compared(values: np.ndarray, name: str | None) -> np.ndarray:
    """The figures as compared: a margin (a fraction) to 1e-12, other figures to 12
    significant digits, so that rounding noise of the engine does not split a tie."""
    if name == MARGIN:
        return np.round(values, 12)
    with np.errstate(invalid="ignore"):
        mantissa, exponent = np.frexp(values)
        return np.where(np.isfinite(values),
                        np.ldexp(np.round(mantissa * 2.0**40) / 2.0**40, exponent), values)


def _time_of(result: CandidateResult, mode: Mode) -> float:
    if mode is Mode.MINIMIZE:
        return _float(result.duration)
    return -min((-np.inf if np.isnan(s) else s for s in result.slacks), default=np.inf)


def _float(value: float | None) -> float:
    return np.nan if value is None else float(value)
