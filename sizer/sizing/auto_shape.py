"""Shape parameters written ``auto``: chosen per motor by the solver.

In minimize mode the parameters minimize T_min; with a given duration they maximize the
smallest margin (ties broken by the next smallest). The trapezoid and the double S in
the book's case (rectangular regions, purely inertial load, ideal transmission) have
their time-optimal shape computed exactly (sizer.sizing.time_optimal_shape, sec. 3.2-3.4
and 6.2); every other case is searched to tolerance (sizer.sizing.auto_shape_search). The
chosen parameters are kept at full precision: the duration and margins reported are
those of the law with exactly these parameters.

A parameter is searched over its admissible range. The exact optimum approaches an open
end to within OPEN_INSET of the range (the infimum is not attained there: T_min at the
inset point is within about 1e-10 of it, e.g. beta -> 0 of a double S without a jerk
limit); the search keeps SEARCH_INSET away. A parameter without a finite range cannot
be searched.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np

from sizer.errors import UserError
from sizer.laws import AUTO, MotionLaw
from sizer.laws.base import Parameter
from sizer.laws.piecewise_polynomial import DoubleS, Trapezoidal
from sizer.model.domain import Design
from sizer.sizing.auto_shape_search import search_shape
from sizer.sizing.candidates import Candidates
from sizer.sizing.cycle import CycleCalculator
from sizer.sizing.minimum_duration import beyond_flat_part, is_purely_inertial
from sizer.sizing.time_optimal_shape import bound_scales, optimal_double_s, optimal_trapezoid

OPEN_INSET = 1e-10
SEARCH_INSET = 1e-3
"""The searched laws are built and sampled at each point; next to an open end their
shapes get steep (e.g. kappa -> -1 of the modified cycloidal) and their numerics are
not reliable there, so the search keeps 1e-3 of the range away from open ends."""


def choose_shape(family: type[MotionLaw], values: dict[str, Fraction | str], design: Design,
                 candidates: Candidates) -> list[MotionLaw]:
    """The best law of the family for each candidate, its auto parameters optimized."""
    motors = candidates.motors
    free = [p for p in family.parameters if values.get(p.name) == AUTO]
    fixed = {k: float(v) for k, v in values.items() if v != AUTO}
    ranges = {p.name: search_range(family.law_id, p, OPEN_INSET) for p in free}
    exact = exact_time_optimal(family, fixed, ranges, design, candidates)
    params, search = (None, np.ones(len(motors), dtype=bool)) if exact is None else exact
    if search.any():
        ranges = {p.name: search_range(family.law_id, p, SEARCH_INSET) for p in free}
        index = np.flatnonzero(search)
        found = search_shape(family, fixed, ranges, design, candidates.take(index))
        if params is None:
            params = found
        else:
            for name, values in found.items():
                params[name] = params[name].astype(float).copy()
                params[name][index] = values
    return [family(**fixed, **{name: float(v[i]) for name, v in params.items()})
            for i in range(len(motors))]


def search_range(law_id: str, p: Parameter, inset: float) -> tuple[float, float]:
    """The closed interval searched for an auto parameter: its ``auto_range`` (sizer.laws),
    open ends inset by ``inset`` times the range."""
    refusal = p.auto_refusal(law_id)
    if refusal is not None:
        raise UserError(refusal)
    low, high = p.auto_range  # type: ignore[misc]
    span = high - low
    return (low + (inset * span if p.low_open and low == p.low else 0.0),
            high - (inset * span if p.high_open and high == p.high else 0.0))


def exact_time_optimal(family: type[MotionLaw], fixed: dict[str, float],
                       ranges: dict[str, tuple[float, float]], design: Design,
                       candidates: Candidates) -> tuple[dict[str, np.ndarray], np.ndarray] | None:
    """The exact optimum where it is known (minimize mode, book's case), else None.

    With it, the mask of the motors left to the search: those whose region goes on past
    the flat part the exact optimum sees, where the optimum reaches the end of it
    (sizer.sizing.minimum_duration.beyond_flat_part).
    """
    if not design.task.minimize or family not in (Trapezoidal, DoubleS) \
            or design.transmission.linkage is not None:  # the book's case has no linkage
        return None
    if "alpha_d" in fixed or "beta_d" in fixed:  # the closed form is the symmetric law's
        return None
    motors = candidates.motors
    calculator = CycleCalculator(None, design.task, candidates.drive, motors,
                                 design.limits.thermal_speed)
    if not is_purely_inertial(calculator):
        return None
    scales = bound_scales(calculator, design.limits)
    if family is Trapezoidal:
        if design.limits.max_jerk is not None:  # infinite jerk: no alpha is feasible
            return {"alpha": np.full(len(motors), 1.0 / 3.0)}, np.zeros(len(motors), bool)
        solution = optimal_trapezoid(scales, *ranges["alpha"])
    else:
        given = {p.name: float(p.default) for p in family.parameters} | fixed
        a = ranges.get("alpha", (given["alpha"],) * 2)
        b = ranges.get("beta", (given["beta"],) * 2)
        solution = optimal_double_s(scales, a[0], b[0], a[1], b[1])
    alpha = solution.params.get("alpha", np.full(len(motors), fixed.get("alpha", 0.0)))
    # C_v = 1/(1 - alpha) for both families (sec. 3.2, 3.4)
    beyond = beyond_flat_part(calculator, design.limits, solution.duration, 1.0 / (1.0 - alpha))
    return {name: solution.params[name] for name in ranges}, beyond
