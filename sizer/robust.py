"""Robust sizing: every candidate at the corners of the design's tolerances
(``sizer size --robust``, docs/robust.md).

With k relative tolerances t_i on inputs x_i, a corner sets each input to x_i (1 - t_i)
or x_i (1 + t_i): 2^k corners. A pair's worst-case margin of a check is the least margin
over the corners, with the corner that gives it; the pair is robustly feasible when it is
feasible at every corner. Where a margin is monotone in each input (most are: more
inertia, friction or load torque, or less motor torque, never helps) the corners give its
exact worst case over the whole box; a margin that is not monotone may be worse inside
the box, which corners do not see.

The motor's tolerances are candidate rows of one sizing (perturbed Motor copies, as in
sizer.sensitivity); the other inputs' corners are separate sizings of perturbed designs
(2^j of them for j such inputs). Pure: sizer.api and the model objects.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

from sizer.errors import UserError
from sizer.sensitivity import design_inputs

if TYPE_CHECKING:
    from sizer.model.domain import Design, Motor
    from sizer.sizing import SizingResult
    from sizer.sizing.results import CandidateResult

MAX_TOLERANCES = 10
"""At most this many tolerances (2^10 = 1024 corners)."""

MOTOR = "motor."

Corner = tuple[tuple[str, float], ...]
"""A corner: each input's name and its relative change (+0.2 = 20 % more)."""


@dataclass(frozen=True)
class RobustResult:
    """One pair: its nominal result, and per check its worst-case margin over the corners
    and the corner that gives it; ``feasible`` when every corner passes, ``failing`` the
    number of corners that fail (of ``corners``)."""

    nominal: CandidateResult
    worst: dict[str, float]
    corner: dict[str, Corner]
    feasible: bool
    failing: int
    corners: int

    @property
    def margin(self) -> float:
        """The least worst-case margin over the checks (nan without checks)."""
        return min(self.worst.values(), default=math.nan)

    @property
    def limiting(self) -> str | None:
        """The check of the least worst-case margin."""
        return min(self.worst, key=lambda k: self.worst[k]) if self.worst else None


@dataclass(frozen=True)
class RobustSizing:
    """The nominal sizing re-ranked: the pairs feasible at every corner first (each group
    in the nominal order), and each pair's robust result by its nominal result's id."""

    sizing: SizingResult
    tolerances: tuple[tuple[str, float], ...]
    results: tuple[RobustResult, ...]

    def of(self, result: CandidateResult) -> RobustResult:
        return self._by_id[id(result)]

    @property
    def _by_id(self) -> dict[int, RobustResult]:
        return {id(r.nominal): r for r in self.results}


def check_tolerances(design: Design) -> None:
    """UserError where ``design`` cannot be sized robustly: no tolerances, too many, a
    tolerance on an input the design does not have (or has as zero), ``minimize`` or a
    ratio choice (not in this version)."""
    given = design.tolerances
    if not given:
        raise UserError("the design gives no tolerances: add a 'tolerances:' section "
                        "(e.g. tolerances: {load.inertia: 20 %}, docs/robust.md) or leave "
                        "out --robust", field="--robust")
    if len(given) > MAX_TOLERANCES:
        raise UserError(f"{len(given)} tolerances make 2^{len(given)} corners; give at most "
                        f"{MAX_TOLERANCES} (keep the inputs the margins depend on most: "
                        f"sizer sensitivity)", field="tolerances")
    if design.machine_cycle.minimize:
        raise UserError("not yet with 'duration: minimize': give the duration to size at",
                        field="--robust")
    if design.ratio_choice is not None:
        raise UserError("not yet with a ratio choice (a free ratio or a gearbox catalog): "
                        "give the ratio", field="--robust")
    chosen = [c.family for c in design.laws if not c.is_fixed]
    if len(chosen) != len(set(chosen)):
        raise UserError("not yet with two laws of one family chosen at each duration "
                        "('auto' parameters): keep one of them", field="--robust")
    present = {i.name for i in design_inputs(design) if i.build is not None}
    for name, _ in given:
        if not name.startswith(MOTOR) and name not in present:
            raise UserError(f"the design has no {name} (or it is zero, or the transmission "
                            f"has several stages): a relative tolerance changes nothing",
                            field=f"tolerances['{name}']")


def signs(k: int) -> list[tuple[int, ...]]:
    """The 2^k corners as signs (-1: x (1 - t), +1: x (1 + t)), all -1 first."""
    return list(itertools.product((-1, 1), repeat=k))


def perturbed_design(design: Design, changes: Sequence[tuple[str, float]]) -> Design:
    """``design`` with each named non-motor input times (1 + change)."""
    for name, change in changes:
        inputs = {i.name: i for i in design_inputs(design)}
        build = inputs[name].build
        assert build is not None
        design = build(1.0 + change)
    return design


def perturbed_motor(motor: Motor, changes: Sequence[tuple[str, float]]) -> Motor:
    """``motor`` with each named figure (``motor.<field>``) times (1 + change)."""
    for name, change in changes:
        field = name.removeprefix(MOTOR)
        motor = replace(motor, **{field: getattr(motor, field) * (1.0 + change)})
    return motor


def robust_sizing(design: Design, nominal: SizingResult, *, rank_by: str | None = None,
                  workers: int | None = 1) -> RobustSizing:
    """Every pair of ``nominal`` (the sizing of ``design``) at the corners of the
    design's tolerances (:func:`check_tolerances` first)."""
    from sizer import api

    check_tolerances(design)
    motor_tol = [(n, t) for n, t in design.tolerances if n.startswith(MOTOR)]
    other_tol = [(n, t) for n, t in design.tolerances if not n.startswith(MOTOR)]
    motor_corners = [tuple((n, s * t) for (n, t), s in zip(motor_tol, sg, strict=True))
                     for sg in signs(len(motor_tol))]
    copies = [(i, c, perturbed_motor(m, corner)) for i, m in enumerate(design.motors)
              for c, corner in enumerate(motor_corners)]
    slot = {id(p): (i, c) for i, c, p in copies}
    motors = [p for _, _, p in copies]

    fixed = {c.text for c in design.laws if c.is_fixed}

    def key(r: CandidateResult, motor: int) -> tuple[object, ...]:
        # a law chosen at each corner (an 'auto' parameter) is known by its family
        law = r.spec if r.spec in fixed else f"{r.law} (chosen)"
        return (motor, r.drive_object.id if r.drive_object is not None else None, law,
                r.gearbox)

    index = {}
    for r in nominal.results:
        i = next(n for n, m in enumerate(design.motors) if m == r.motor_object)
        index[key(r, i)] = r
    seen: dict[tuple[object, ...], list[tuple[Corner, CandidateResult]]] = {
        k: [] for k in index}
    for sg in signs(len(other_tol)):
        changes = tuple((n, s * t) for (n, t), s in zip(other_tol, sg, strict=True))
        corner_design = perturbed_design(design, changes)
        sized = api.size(corner_design, motors=motors, rank_by=rank_by, workers=workers)
        for r in sized.results:
            found = slot.get(id(r.motor_object))
            if found is None:  # the engine copied the motor: find it by value
                found = next((i, c) for i, c, p in copies if p == r.motor_object)
            i, c = found
            k = key(r, i)
            if k in seen:
                seen[k].append((changes + motor_corners[c], r))
    results = []
    for k, nominal_result in index.items():
        results.append(_robust(nominal_result, seen[k], len(signs(len(design.tolerances)))))
    by_id = {id(r.nominal): r for r in results}
    order = sorted(nominal.results, key=lambda r: not by_id[id(r)].feasible)  # stable
    reranked = replace(nominal, results=tuple(order), table=None)
    return RobustSizing(reranked, design.tolerances,
                        tuple(by_id[id(r)] for r in order))


def _robust(nominal: CandidateResult, at: list[tuple[Corner, CandidateResult]],
            corners: int) -> RobustResult:
    worst: dict[str, float] = {}
    where: dict[str, Corner] = {}
    for corner, r in at:
        for check in r.checks:
            name, margin = str(check.name), float(check.margin)
            if name not in worst or margin < worst[name] or math.isnan(margin):
                if name in worst and math.isnan(worst[name]):
                    continue
                worst[name], where[name] = margin, corner
    failing = sum(not r.feasible for _, r in at) + (corners - len(at))
    return RobustResult(nominal, worst, where, failing == 0, failing, corners)
