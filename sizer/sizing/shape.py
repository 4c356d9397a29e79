"""Shape parameters written ``auto``: chosen per motor by the solver.

In minimize mode the parameter minimizes T_min; with a given duration it maximizes the
smallest margin. The search is a grid over the parameter's range refined twice around
each motor's best point (vectorized over the motors that share a neighbourhood), halving
the spacing each round, so the chosen value is within about 1e-3 of the range of the
true optimum; the chosen value is rounded to 4 significant digits, and the duration or
margins reported are exact for it.
"""

from __future__ import annotations

import itertools
from fractions import Fraction

import numpy as np

from sizer.laws import AUTO, MotionLaw
from sizer.mechanics import Drive
from sizer.model.domain import Design
from sizer.sizing.checks import evaluate_checks
from sizer.sizing.cycle import CycleCalculator
from sizer.sizing.duration import minimum_duration
from sizer.sizing.motors import MotorArrays

COARSE = {1: 13, 2: 7}
FINE = {1: 5, 2: 5}
REFINEMENTS = 7
INSET = 1e-3  # keep open interval ends out of the grid


def choose_shape(family: type[MotionLaw], values: dict[str, Fraction | str], design: Design,
                 drive: Drive, motors: MotorArrays) -> list[MotionLaw]:
    """The best law of the family for each motor, its auto parameters optimized."""
    free = [p for p in family.parameters if values.get(p.name) == AUTO]
    fixed = {k: float(v) for k, v in values.items() if v != AUTO}
    bounds = []
    for p in free:
        span = p.high - p.low
        bounds.append((p.low + (INSET * span if p.low_open else 0.0),
                       p.high - (INSET * span if p.high_open else 0.0)))
    dims = len(free)
    steps = [(hi - lo) / (COARSE[dims] - 1) for lo, hi in bounds]
    grids = [np.linspace(lo, hi, COARSE[dims]) for lo, hi in bounds]
    best_point = [None] * len(motors)
    best_score: list[np.ndarray | None] = [None] * len(motors)
    everyone = np.arange(len(motors))
    _search(family, free, fixed, grids, everyone, design, drive, motors, best_point, best_score)
    for _ in range(REFINEMENTS):
        steps = [2.0 * s / (FINE[dims] - 1) for s in steps]
        groups: dict[tuple, list[int]] = {}
        for i, point in enumerate(best_point):
            groups.setdefault(point, []).append(i)
        for point, members in groups.items():
            local = [np.clip(np.linspace(c - s * (FINE[dims] - 1) / 2, c + s * (FINE[dims] - 1) / 2,
                                         FINE[dims]), lo, hi)
                     for c, s, (lo, hi) in zip(point, steps, bounds, strict=True)]
            _search(family, free, fixed, local, np.array(members), design, drive, motors,
                    best_point, best_score)
    names = [p.name for p in free]
    return [family(**fixed, **dict(zip(names, _rounded(point, bounds), strict=True)))
            for point in best_point]


def _rounded(point: tuple[float, ...], bounds) -> tuple[float, ...]:
    """4 significant digits (the search is no finer), kept inside the bounds."""
    return tuple(min(max(float(f"{x:.4g}"), lo), hi)
                 for x, (lo, hi) in zip(point, bounds, strict=True))


def _search(family, free, fixed, grids, members, design, drive, motors, best_point, best_score):
    """Evaluate every grid point for the member motors and keep improvements."""
    subset = motors.subset(members)
    names = [p.name for p in free]
    for point in itertools.product(*(np.unique(g) for g in grids)):
        point = tuple(float(x) for x in point)
        law = family(**fixed, **dict(zip(names, point, strict=True)))
        score = _score(law, design, drive, subset)
        for j, i in enumerate(members):
            if best_score[i] is None or _better(score[j], best_score[i]):
                best_point[i] = point
                best_score[i] = score[j]
    for i in members:
        if best_point[i] is None:  # nothing feasible: keep the middle point for reporting
            best_point[i] = tuple(float(g[len(g) // 2]) for g in grids)


def _score(law: MotionLaw, design: Design, drive: Drive, motors: MotorArrays) -> np.ndarray:
    """Rows compared lexicographically, higher is better: (-T_min,) in minimize mode, the
    slacks of all checks smallest first otherwise (ties on the worst check, e.g. one
    that does not depend on the law, are broken by the next one)."""
    calculator = CycleCalculator(None, design.task, drive, motors,
                                 design.limits.thermal_speed, law=law)
    if design.task.minimize:
        solution = minimum_duration(calculator, design.limits)
        return np.where(solution.feasible, -solution.duration, -np.inf)[:, None]
    metrics = calculator.evaluate(np.full(len(motors), design.task.duration))
    checks = evaluate_checks(metrics, motors, drive, design.limits, design.task.linear)
    return np.sort(np.stack([c.slack for c in checks], axis=1), axis=1)


def _better(new: np.ndarray, old: np.ndarray) -> bool:
    """new beats old at the first entry where they differ beyond rounding."""
    with np.errstate(invalid="ignore"):
        differs = ~np.isclose(new, old, rtol=1e-12, atol=1e-12) & ~(new == old)
    if not differs.any():
        return False
    first = int(np.argmax(differs))
    return bool(new[first] > old[first])


