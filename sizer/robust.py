"""Robust sizing: every candidate at the corners of the design's tolerances and, with
samples, at Monte Carlo builds drawn from them (``sizer size --robust``, docs/robust.md).

With k tolerances of half-widths w_i on inputs x_i (relative: x_i (1 +- w_i); absolute:
x_i +- w_i), a corner sets each input to an end of its range: 2^k corners. A pair's
worst-case margin of a check is the least margin over the corners, with the corner that
gives it; the pair is robustly feasible when it is feasible at every corner (and every
sample). Where a margin is monotone in each input (most are: more inertia, friction or
load torque, or less motor torque, never helps) the corners give its exact worst case over
the whole box. A sample is a build drawn from the tolerances' distributions (uniform, or
normal truncated at its corners); N samples give each pair's share of builds that pass,
with a 95 % Wilson interval, and a margin that is worse at a sample than at every corner
(not monotone) takes the sample's value. With more than MAX_TOLERANCES tolerances there
are no corners: the samples alone give the worst case seen.

A ratio choice (a free ratio, catalog gearboxes) is made at the nominal design, as the
engineer buys one gearbox: each pair's builds are sized with the transmission its nominal
sizing chose, fixed. In minimize mode each build is sized for its own T_min, and a pair's
worst-case T_min is the largest over the corners (:class:`WorstDuration`).

Every build (a corner or a sample) is a change of each input in its tolerance's terms (a
fraction, or SI for an absolute tolerance). Builds are candidate rows of one sizing where
the engine has an axis for them: the motor's figures (perturbed Motor copies, as in
sizer.sensitivity) and the load's J, B, F and tau_ext (each copy driving its own build of
the load: sizer.mechanics.load_figures; not through a linkage or with loads of the
position, whose engines read the design's load), at most MAX_MOTOR_ROWS rows a sizing.
The transmission's efficiency and the load's mode are rows too (sizer.sizing.candidates.
Builds), the mode except where a law or the split is made for the design's mode
(sizer.sizing.engine.reads_builds): such builds are sizings of their own, one per change
(2^j at the corners for j such tolerances). The
design is never re-read, the catalogs never re-loaded: each build is the loaded design
with dataclasses.replace. Pure: sizer.api, the engine, the model objects and numpy.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from copy import copy
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from sizer.errors import UserError
from sizer.model.tolerance import Tolerance, tolerance_of
from sizer.sensitivity import design_inputs, row_input

if TYPE_CHECKING:
    from sizer.model.domain import Design, Motor
    from sizer.sizing import SizingResult
    from sizer.sizing.results import CandidateResult

MAX_TOLERANCES = 10
"""At most this many tolerances for corners (2^10 = 1024); more are sampled."""

MAX_MOTOR_ROWS = 512

"""At most this many motor rows (perturbed copies) in one sizing, unless one build has
more motors. The engine's work is per row: on examples/pick-and-place.yaml (ratio 2, 4
laws) 512 rows in one sizing took 0.8 times the CPU of 8 sizings of 64, 1280 rows 1.15
times that of 20 sizings; batching beyond this gains nothing."""

MAX_SAMPLES = 100_000
"""At most this many samples (``--samples``)."""

DEFAULT_SEED = 0
"""The seed of the samples unless one is given: the same builds, the same output."""

Z95 = 1.959963984540054
"""The standard normal's 97.5 % quantile: a two-sided 95 % interval."""

MOTOR = "motor."

Corner = tuple[tuple[str, float], ...]
"""A build: each input's name and its change in its tolerance's terms (a fraction, +0.2 =
20 % more, for a relative tolerance; the change in SI for an absolute one)."""

CORNERS, SAMPLES, NOMINAL = "corners", "samples", "nominal"
"""Where a worst-case margin comes from: the corners, a sample, the nominal machine."""


def wilson_interval(passed: int, n: int, z: float = Z95) -> tuple[float, float]:
    """The Wilson score interval of a share ``passed``/``n`` (95 % by default)."""
    if n <= 0:
        return (math.nan, math.nan)
    p = passed / n
    denominator = 1.0 + z * z / n
    center = (p + z * z / (2.0 * n)) / denominator
    half = z * math.sqrt(p * (1.0 - p) / n + z * z / (4.0 * n * n)) / denominator
    return (0.0 if passed == 0 else max(0.0, center - half),
            1.0 if passed == n else min(1.0, center + half))


@dataclass(frozen=True)
class WorstDuration:
    """In minimize mode, a pair's shortest duration T_min over the builds: ``worst`` the
    largest (inf where some build has no T_min: a check fails at every duration), at
    ``corner`` (``by``: the corners, a sample larger than every corner, or the nominal
    machine); ``p95`` the samples' T_min's 95th percentile (nearest rank: the least T_min
    that 95 % of the samples reach; nan without samples) and ``sampled_max`` their
    largest."""

    worst: float
    corner: Corner
    by: str
    p95: float = math.nan
    sampled_max: float = math.nan


@dataclass(frozen=True)
class RobustResult:
    """One pair: its nominal result, and per check its worst-case margin and the build
    that gives it (``by``: from the corners, or from a sample worse than every corner);
    ``feasible`` when every corner and sample passes, ``failing`` the number of corners
    that fail (of ``corners``), ``passing`` the samples that pass (of ``samples``)."""

    nominal: CandidateResult
    worst: dict[str, float]
    corner: dict[str, Corner]
    feasible: bool
    failing: int
    corners: int
    passing: int = 0
    samples: int = 0
    by: dict[str, str] | None = None
    duration: WorstDuration | None = None

    @property
    def margin(self) -> float:
        """The least worst-case margin over the checks (nan without checks)."""
        return min(self.worst.values(), default=math.nan)

    @property
    def limiting(self) -> str | None:
        """The check of the least worst-case margin."""
        return min(self.worst, key=lambda k: self.worst[k]) if self.worst else None

    @property
    def share(self) -> float:
        """The share of the samples that pass (nan without samples)."""
        return self.passing / self.samples if self.samples else math.nan

    @property
    def interval(self) -> tuple[float, float]:
        """The 95 % Wilson interval of :attr:`share`."""
        return wilson_interval(self.passing, self.samples)

    @property
    def sampled_checks(self) -> tuple[str, ...]:
        """The checks whose worst case is not a corner's but a sample's or the nominal
        machine's (not monotone, or no corners)."""
        return tuple(n for n, b in (self.by or {}).items() if b != CORNERS)


@dataclass(frozen=True)
class RobustSizing:
    """The nominal sizing re-ranked: the pairs feasible at every build first (each group
    in the nominal order, or by the worst-case margin with ``rank_by`` worst_margin), and
    each pair's robust result by its nominal result's id. ``corners`` is False where
    there were too many tolerances for corners (the samples alone); ``samples`` the
    number of samples (0: corners only) and ``seed`` their seed. ``fixed_ratio``: the
    design chooses the ratio; each pair's is the nominal sizing's, fixed at every build.
    ``minimize``: each build sized for its T_min (:class:`WorstDuration`);
    ``by_worst_duration``: each group ranked by the largest T_min, least first."""

    sizing: SizingResult
    tolerances: tuple[Tolerance, ...]
    results: tuple[RobustResult, ...]
    corners: bool = True
    samples: int = 0
    seed: int = DEFAULT_SEED
    by_worst_margin: bool = False
    fixed_ratio: bool = False
    minimize: bool = False
    by_worst_duration: bool = False

    def of(self, result: CandidateResult) -> RobustResult:
        return self._by_id[id(result)]

    @property
    def _by_id(self) -> dict[int, RobustResult]:
        return {id(r.nominal): r for r in self.results}


def check_tolerances(design: Design, samples: int = 0) -> None:
    """UserError where ``design`` cannot be sized robustly: no tolerances, too many for
    corners without ``samples``, a tolerance on an input the design does not have (or has
    as zero) or an absolute one as wide as the value, two laws of one family chosen at
    each build."""
    given = [tolerance_of(t) for t in design.tolerances]
    if not given:
        raise UserError("the design gives no tolerances: add a 'tolerances:' section "
                        "(e.g. tolerances: {load.inertia: 20 %}, docs/robust.md) or leave "
                        "out --robust", field="--robust")
    if not 0 <= samples <= MAX_SAMPLES:
        raise UserError(f"the number of samples must be in [0, {MAX_SAMPLES}], got "
                        f"{samples}", field="--samples")
    if len(given) > MAX_TOLERANCES and samples == 0:
        raise UserError(f"{len(given)} tolerances make 2^{len(given)} corners; give at most "
                        f"{MAX_TOLERANCES} (keep the inputs the margins depend on most: "
                        f"sizer sensitivity), or sample them instead (--samples N)",
                        field="tolerances")
    chosen = [c.family for c in design.laws if not c.is_fixed]
    if len(chosen) != len(set(chosen)):
        raise UserError("not yet with two laws of one family chosen at each duration "
                        "('auto' parameters): keep one of them", field="--robust")
    present = {i.name: i.value for i in design_inputs(design) if i.build is not None}
    for t in given:
        field = f"tolerances['{t.name}']"
        if not t.name.startswith(MOTOR) and t.name not in present:
            raise UserError(f"the design has no {t.name} (or it is zero, or the transmission "
                            f"has several stages): a relative tolerance changes nothing",
                            field=field)
        if not t.absolute:
            continue
        values = ([(t.name, present[t.name])] if not t.name.startswith(MOTOR) else
                  [(f"motor {m.id}'s {t.input.removeprefix(MOTOR)}",
                    float(getattr(m, t.input.removeprefix(MOTOR)))) for m in design.motors
                   if t.motor in (None, m.id)])
        for what, value in values:
            if not t.width < abs(value):
                raise UserError(f"the tolerance's range +-{t.width:g} (SI) reaches zero: "
                                f"{what} is {value:g}; give a smaller one", field=field)


def signs(k: int) -> list[tuple[int, ...]]:
    """The 2^k corners as signs (-1: the low end, +1: the high end), all -1 first."""
    return list(itertools.product((-1, 1), repeat=k))


def draw(tolerances: Sequence[Tolerance | tuple[str, float]], n: int, seed: int = DEFAULT_SEED
         ) -> np.ndarray:
    """``n`` builds (rows) drawn from the tolerances (columns, in their order): each
    change uniform over +-width, or normal with sigma width / sigmas truncated at +-width
    (by rejection); the same ``seed``, the same builds."""
    rng = np.random.default_rng(seed)
    out = np.empty((n, len(tolerances)))
    for j, t in enumerate(tolerance_of(p) for p in tolerances):
        if t.distribution == "uniform":
            out[:, j] = rng.uniform(-t.width, t.width, n)
            continue
        assert t.sigmas is not None
        z = rng.standard_normal(n)
        bad = np.abs(z) > t.sigmas
        while bad.any():
            z[bad] = rng.standard_normal(int(bad.sum()))
            bad = np.abs(z) > t.sigmas
        out[:, j] = z * (t.width / t.sigmas)
    return out


def corner_changes(tolerances: Sequence[Tolerance | tuple[str, float]]) -> np.ndarray:
    """The 2^k corners (rows, all low first) as changes +-width per tolerance (columns)."""
    widths = np.array([tolerance_of(t).width for t in tolerances], dtype=float)
    return np.array(signs(len(widths)), dtype=float).reshape(-1, len(widths)) * widths


def _factor(t: Tolerance, change: float, value: float) -> float:
    """The factor on ``value`` of a change in ``t``'s terms."""
    return 1.0 + change / value if t.absolute else 1.0 + change


def perturbed_design(design: Design, changes: Sequence[tuple[str, float]]) -> Design:
    """``design`` with each named non-motor input times (1 + change) (relative changes;
    :func:`build_design` for a build of the design's own tolerances)."""
    for name, change in changes:
        inputs = {i.name: i for i in design_inputs(design)}
        build = inputs[name].build
        assert build is not None
        design = build(1.0 + change)
    return design


def build_design(design: Design, tolerances: Sequence[Tolerance],
                 changes: Sequence[float]) -> Design:
    """``design`` at one build of its non-motor ``tolerances`` (each changed by its own
    change: a fraction, or SI when absolute)."""
    values = {i.name: i.value for i in design_inputs(design)}
    relative = [(t.name, _factor(t, c, values[t.name]) - 1.0)
                for t, c in zip(tolerances, changes, strict=True)]
    return perturbed_design(design, relative)


def perturbed_motor(motor: Motor, changes: Sequence[tuple[str, float]]) -> Motor:
    """``motor`` with each named figure (``motor.<field>``) times (1 + change), or changed
    by it where ``changes`` holds absolute Tolerance-keyed pairs (:func:`build_motor`)."""
    for name, change in changes:
        field = name.removeprefix(MOTOR)
        motor = replace(motor, **{field: getattr(motor, field) * (1.0 + change)})
    return motor


def build_motor(motor: Motor, tolerances: Sequence[Tolerance],
                changes: Sequence[float]) -> Motor:
    """``motor`` at one build of the motor ``tolerances`` (one limited to another motor
    changes nothing)."""
    for t, change in zip(tolerances, changes, strict=True):
        if t.motor not in (None, motor.id):
            continue
        field = t.input.removeprefix(MOTOR)
        value = float(getattr(motor, field))
        changed: dict[str, Any] = {field: value * _factor(t, float(change), value)}
        motor = replace(motor, **changed)
    return motor


def robust_sizing(design: Design, nominal: SizingResult, *, rank_by: str | None = None,
                  workers: int | None = 1, samples: int = 0,
                  seed: int = DEFAULT_SEED) -> RobustSizing:
    """Every pair of ``nominal`` (the sizing of ``design``) at the corners of the
    design's tolerances (when at most MAX_TOLERANCES) and at ``samples`` builds drawn from
    them with ``seed`` (:func:`check_tolerances` first). ``rank_by`` worst_margin orders
    each group (feasible at every build or not) by the worst-case margin."""
    from sizer import api
    from sizer.sizing.candidates import Builds
    from sizer.sizing.engine import size_design
    from sizer.sizing.ranking import is_robust_key, nominal_rank_by

    check_tolerances(design, samples)
    tolerances = tuple(tolerance_of(t) for t in design.tolerances)
    k = len(tolerances)
    with_corners = k <= MAX_TOLERANCES
    builds = np.concatenate(
        [corner_changes(tolerances) if with_corners else np.empty((0, k)),
         draw(tolerances, samples, seed) if samples else np.empty((0, k))]).reshape(-1, k)
    n_corners = 2 ** k if with_corners else 0
    is_motor = np.array([t.name.startswith(MOTOR) for t in tolerances], dtype=bool)
    is_row = np.array([row_input(design, t.name) for t in tolerances],
                      dtype=bool)  # the load's and the stages' figures, the mode: rows too
    is_other = ~is_motor & ~is_row
    motor_tol = [t for t, m in zip(tolerances, is_motor, strict=True) if m]
    row_tol = [t for t, m in zip(tolerances, is_row, strict=True) if m]
    other_tol = [t for t, m in zip(tolerances, is_other, strict=True) if m]
    names = [t.name for t in tolerances]

    fixed = {c.text for c in design.laws if c.is_fixed}
    per_move = design.machine_cycle.share.per_move

    def key(r: CandidateResult, motor: int) -> tuple[object, ...]:
        # a law chosen at each build (an 'auto' parameter, a law per move) is known by
        # its family
        law = "per_move (chosen)" if per_move else \
            r.spec if r.spec in fixed else f"{r.law} (chosen)"
        return (motor, r.drive_object.id if r.drive_object is not None else None, law,
                r.gearbox)

    index = {}
    for r in nominal.results:
        i = next(n for n, m in enumerate(design.motors) if m == r.motor_object)
        index[key(r, i)] = r
    minimize = bool(design.machine_cycle.minimize)
    seen = {k_: _Tally(n_corners, minimize) for k_ in index}
    groups: dict[tuple[float, ...], list[int]] = {}
    for b, row in enumerate(builds):
        groups.setdefault(tuple(row[is_other].tolist()), []).append(b)
    sizing_rank = nominal_rank_by(rank_by)
    fixed_ratio = design.ratio_choice is not None
    for part, wanted, motors in _fixed_ratio_parts(design, index) if fixed_ratio else [
            (design, None, list(range(len(design.motors))))]:
        per_sizing = max(1, MAX_MOTOR_ROWS // max(1, len(motors)))
        batches = [(other, members[s:s + per_sizing]) for other, members in groups.items()
                   for s in range(0, len(members), per_sizing)]
        designs: dict[tuple[float, ...], Design] = {}
        for other, members in batches:
            if other not in designs:
                designs[other] = build_design(part, other_tol, other)
            group_design = designs[other]
            copies = [(i, b, copy(build_motor(design.motors[i], motor_tol,
                                              builds[b, is_motor])))
                      for i in motors for b in members]  # each its own object: its row
            slot = {id(p): (i, b) for i, b, p in copies}
            built = {b: build_design(group_design, row_tol, builds[b, is_row])
                     for b in members} if row_tol else {}
            sized = size_design(
                api.override(group_design, motors=[p for _, _, p in copies]),
                rank_by=sizing_rank, workers=workers,
                builds=Builds.of([built[b] for _, b, _ in copies], group_design)
                if built else None)
            for r in sized.results:
                found = slot.get(id(r.motor_object))
                if found is None:  # the engine copied the motor: find it by value
                    found = next((i, b) for i, b, p in copies if p == r.motor_object)
                i, b = found
                k_: tuple[object, ...] | None = key(r, i)
                if wanted is not None:  # the nominal pair of this ratio (its gearbox's)
                    k_ = next((w for w in wanted if k_ is not None and w[:3] == k_[:3]),
                              None)
                if k_ in seen:
                    seen[k_].add(b, r)

    def corner(b: int) -> Corner:  # build -1: the nominal machine
        changes = builds[b] if b >= 0 else np.zeros(k)
        return tuple((n, float(c)) for n, c in zip(names, changes, strict=True))

    results = [seen[k_].result(nominal_result, samples, corner)
               for k_, nominal_result in index.items()]
    by_id = {id(r.nominal): r for r in results}
    by_duration = minimize and (rank_by is None or is_robust_key(rank_by))
    by_margin = rank_by is not None and is_robust_key(rank_by) and not by_duration

    def order_key(r: CandidateResult) -> tuple[bool, float]:
        robust = by_id[id(r)]
        if by_duration:
            worst = robust.duration.worst if robust.duration is not None else math.inf
            return (not robust.feasible, math.inf if math.isnan(worst) else worst)
        margin = robust.margin
        return (not robust.feasible,
                -margin if by_margin and not math.isnan(margin) else
                (math.inf if by_margin else 0.0))

    order = sorted(nominal.results, key=order_key)  # stable: the nominal order in ties
    reranked = replace(nominal, results=tuple(order), table=None)
    return RobustSizing(reranked, tolerances, tuple(by_id[id(r)] for r in order),
                        with_corners, samples, seed, by_margin, fixed_ratio, minimize,
                        by_duration)


def _fixed_ratio_parts(design: Design, index: dict[tuple[object, ...], CandidateResult]
                       ) -> list[tuple[Design, set[tuple[object, ...]], list[int]]]:
    """The design with each ratio the nominal sizing chose (a free ratio, a catalog
    gearbox) fixed: per transmission in place, that design (no ratio choice), the pairs'
    keys that have it and their motors' indices; laws of fixed parameters other pairs
    have are left out."""
    parts: dict[int, tuple[Design, set[tuple[object, ...]], list[int]]] = {}
    seen: list[Any] = []
    for k_, r in index.items():
        n = next((j for j, t in enumerate(seen) if t == r.transmission), None)
        if n is None:
            seen.append(r.transmission)
            n = len(seen) - 1
            parts[n] = (replace(design, ratio_choice=None, transmission=r.transmission),
                        set(), [])
        _, keys, motors = parts[n]
        keys.add(k_)
        i = k_[0]
        assert isinstance(i, int)
        if i not in motors:
            motors.append(i)
    out = []
    for part, keys, motors in parts.values():
        specs = {r.spec for k_, r in index.items() if k_ in keys}
        laws = part.laws if part.machine_cycle.share.per_move else \
            tuple(c for c in part.laws if not c.is_fixed or c.law.spec in specs)
        out.append((replace(part, laws=laws), keys, sorted(motors)))
    return out


SAMPLE_BELOW = 1e-9
"""A sample's margin counts as below the corners' (not monotone) by more than this."""


class _Least:
    """The least margin of each check over some builds and the build giving it, whatever
    the order the builds come in: a NaN margin (undecided) before any number, then the
    least margin, and of equals the lowest build."""

    def __init__(self) -> None:
        self.margin: dict[str, float] = {}
        self.build: dict[str, int] = {}

    def add(self, b: int, result: CandidateResult) -> None:
        for check in result.checks:
            name, margin = str(check.name), float(check.margin)
            if name not in self.margin or _order(margin, b) < _order(self.margin[name],
                                                                     self.build[name]):
                self.margin[name], self.build[name] = margin, b


def _order(margin: float, build: int) -> tuple[bool, float, int]:
    """The order of (margin, build) in :class:`_Least`: undecided first, then the least
    margin, then the lowest build."""
    undecided = math.isnan(margin)
    return (not undecided, 0.0 if undecided else margin, build)


class _Tally:
    """One pair's builds folded as they come (memory bounded by the pairs, not the
    builds): the least margins over the corners and over the samples apart, the corners
    that fail, the samples that pass."""

    def __init__(self, corners: int, minimize: bool = False) -> None:
        self.corners = corners
        self.at_corners, self.at_samples = _Least(), _Least()
        self.corners_seen = self.failing = self.samples_seen = self.passing = 0
        self.minimize = minimize
        self.corner_durations: dict[int, float] = {}  # minimize: T_min per build
        self.sample_durations: list[tuple[int, float]] = []

    def add(self, b: int, result: CandidateResult) -> None:
        if b < self.corners:
            self.at_corners.add(b, result)
            self.corners_seen += 1
            self.failing += not result.feasible
        else:
            self.at_samples.add(b, result)
            self.samples_seen += 1
            self.passing += bool(result.feasible)
        if self.minimize:
            t = _duration(result)
            if b < self.corners:
                self.corner_durations[b] = t
            else:
                self.sample_durations.append((b, t))

    def worst_duration(self, nominal: CandidateResult,
                       corner: Callable[[int], Corner]) -> WorstDuration:
        """The largest T_min over the corners (a corner not returned: none, inf), or a
        sample's or the nominal machine's where larger (not monotone), with the build."""
        at_corners = [(b, self.corner_durations.get(b, math.inf))
                      for b in range(self.corners)]
        sampled = sorted(self.sample_durations)
        others = [(SAMPLES, b, t) for b, t in sampled] + [(NOMINAL, -1, _duration(nominal))]
        if at_corners:
            b, t = max(at_corners, key=lambda bt: bt[1])  # the first of equals
            label, worst_b, worst = CORNERS, b, t
            others = [o for o in others if o[2] > t * (1.0 + 1e-9)]  # not monotone
        if others:
            label, worst_b, worst = max(others, key=lambda o: o[2])
        values = np.array([t for _, t in sampled], dtype=float)
        # the nearest-rank 95th percentile (a T_min of some sample; inf where it has none)
        p95 = (float(np.sort(values)[math.ceil(0.95 * values.size) - 1]) if values.size
               else math.nan)
        top = float(values.max()) if values.size else math.nan
        return WorstDuration(worst, corner(worst_b), label, p95, top)

    def result(self, nominal: CandidateResult, samples: int,
               corner: Callable[[int], Corner]) -> RobustResult:
        """The corners' least margin of each check, or, where lower by more than
        SAMPLE_BELOW (the margin is not monotone) or where there are no corners, the
        least of the samples' and the nominal machine's (the box's center, build -1,
        sized already); a corner the sizing did not return counts as failing."""
        center = _Least()
        center.add(-1, nominal)
        worst: dict[str, float] = {}
        where: dict[str, Corner] = {}
        by: dict[str, str] = {}
        parts = ((CORNERS, self.at_corners), (SAMPLES, self.at_samples), (NOMINAL, center))
        names = dict.fromkeys(n for _, part in parts for n in part.margin)
        for name in names:
            found = [(label, part) for label, part in parts if name in part.margin]
            label, part = found[0]
            if label == CORNERS and not math.isnan(part.margin[name]):
                least = part.margin[name] - SAMPLE_BELOW
                inside = [(lb, pt) for lb, pt in found[1:]
                          if not pt.margin[name] >= least]  # lower, or NaN
                if inside:
                    label, part = _lowest(inside, name)
            elif label != CORNERS:
                label, part = _lowest(found, name)
            worst[name], where[name], by[name] = (part.margin[name],
                                                  corner(part.build[name]), label)
        failing = self.failing + (self.corners - self.corners_seen)
        feasible = failing == 0 and self.passing == samples and bool(nominal.feasible)
        duration = self.worst_duration(nominal, corner) if self.minimize else None
        return RobustResult(nominal, worst, where, feasible, failing, self.corners,
                            self.passing, samples, by, duration)


def _duration(result: CandidateResult) -> float:
    """A build's T_min: inf where the pair has none (a check fails at every duration)."""
    t = result.duration
    return float(t) if result.feasible and t is not None and math.isfinite(t) else math.inf


def _lowest(found: list[tuple[str, _Least]], name: str) -> tuple[str, _Least]:
    """The first of ``found`` whose margin of ``name`` is NaN (undecided), else the
    least (the first of equals)."""
    undecided = [f for f in found if math.isnan(f[1].margin[name])]
    return undecided[0] if undecided else min(found, key=lambda f: f[1].margin[name])


def _robust(nominal: CandidateResult, at: list[tuple[int, CandidateResult]], corners: int,
            samples: int, corner: Callable[[int], Corner]) -> RobustResult:
    """The robust result of builds ``at`` ((build, result) pairs; builds below
    ``corners`` are corners)."""
    tally = _Tally(corners)
    for b, r in at:
        tally.add(b, r)
    return tally.result(nominal, samples, corner)


def tolerance_units(design: Design) -> dict[str, str]:
    """The SI unit of each input a tolerance of ``design`` can name (an absolute
    tolerance's width is in it)."""
    return {i.name: i.unit for i in design_inputs(design)}
