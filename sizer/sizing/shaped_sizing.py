"""A law shaped for the load's mode at each candidate's own duration (book sec. 7.4.2).

``{kind: shaped, law: L, shaper: zv}`` without ``f_T`` in a design with
``load.natural_frequency``: the shaper's impulses are set by the mode (their times are
multiples of its damped period), so the normalized shaped law depends on the move's
duration T through f_T = f_n T (sizer.vibration.shaped_law). The shaped move keeps the
whole duration T, its base law taking T - t_n.

- A given duration: one law, f_T = f_n T, sized like any other.
- ``minimize``: the shortest T at which the law shaped for T is feasible, per candidate:
  T = T_min(L(f_n T)), solved by a secant iteration from T_0 = T_min(base) + t_n (the
  base move at its own T_min convolved with the shaper: its peaks are convex
  combinations of the base's, sec. 7.4.2). Each step sizes every candidate with the law
  shaped for its own T (one law per distinct T, as for ``auto`` shapes); the result is
  the law shaped for the last T, sized in minimize mode, so its verdict and figures are
  the engine's own.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from sizer.errors import UserError
from sizer.laws import make_law
from sizer.laws.base import MotionLaw
from sizer.laws.data_spec import data_spec_text, read_data_spec
from sizer.model.domain import Design
from sizer.sizing.candidates import Candidates
from sizer.sizing.table import CandidateTable, concatenate
from sizer.vibration.elastic_load import ElasticLoad

ROUNDS = 12
"""Most secant steps of the minimize iteration."""

RTOL = 1e-9
"""Relative change of T at which the iteration stops."""


def _mode(design: Design, fields: dict[str, Any]) -> ElasticLoad:
    elastic = design.load.elastic
    if elastic is None:
        raise UserError("a shaped law without f_T is shaped for the load's mode: give "
                        "load.natural_frequency (or f_T)", field="laws")
    return ElasticLoad(elastic.natural_frequency,
                       float(fields.get("damping_ratio", elastic.damping_ratio)))


def _shaped(fields: dict[str, Any], mode: ElasticLoad, T: float) -> MotionLaw:
    return make_law(data_spec_text({**fields, "f_T": mode.natural_frequency * T,
                                    "damping_ratio": mode.damping_ratio}))


def evaluate_shaped(design: Design, spec: str, candidates: Candidates) -> CandidateTable:
    """The open shaped law ``spec`` for every candidate, in their order."""
    from sizer.sizing.engine import evaluate_fixed_law
    from sizer.vibration.shapers import shaper_length

    fields = dict(read_data_spec(spec))
    mode = _mode(design, fields)
    if design.cycle is not None:
        raise UserError(f"{spec}: a shaped law without f_T is shaped for one duration, "
                        "and the moves of a cycle have their own: give f_T",
                        field="laws")
    if not design.task.minimize:
        assert design.task.duration is not None
        return evaluate_fixed_law(design, _shaped(fields, mode, design.task.duration),
                                  candidates)
    # the rounds size the torques alone: the law shaped for T leaves no residual at T, a
    # residual limit is checked once T is found (moving T inside the rounds would break the
    # shaping's timing)
    limit = design.limits.residual_vibration
    plain = replace(design, limits=replace(design.limits, residual_vibration=None))
    base = fields["law"] if isinstance(fields["law"], str) else data_spec_text(fields["law"])
    start = evaluate_fixed_law(plain, make_law(base), candidates).figures["duration"]
    t_n = shaper_length(fields["shaper"], mode, fields.get("vibration_limit"))
    known = np.isfinite(start)
    fallback = float(np.nanmax(start)) if known.any() else 4.0 * t_n
    T = np.where(known, start, fallback) + t_n
    table, h = _round(plain, fields, mode, T, candidates)
    previous_T, previous_h = T, h
    for _ in range(ROUNDS):
        moving = np.isfinite(h) & (np.abs(h) > RTOL * T)
        if not moving.any():
            break
        slope = np.where(np.isfinite(previous_h) & (previous_T != T),
                         (h - previous_h) / np.where(previous_T != T, T - previous_T, 1.0),
                         0.0)
        # the secant of h(T) = T_min(L(f_n T)) - T, whose slope is about -1 (a plain
        # fixed-point step T + h where there is no slope yet or it is unusable)
        usable = (slope < -0.05) & (slope > -20.0)
        step = np.where(usable, -h / np.where(usable, slope, -1.0), h)
        nxt = np.where(moving, np.maximum(T + step, t_n * (1.0 + 1e-6)), T)
        previous_T, previous_h = T, h
        T = nxt
        table, h = _round(plain, fields, mode, T, candidates)
    if limit is None:
        return table
    return _round(design, fields, mode, T, candidates)[0]


def _round(design: Design, fields: dict[str, Any], mode: ElasticLoad, T: np.ndarray,
           candidates: Candidates) -> tuple[CandidateTable, np.ndarray]:
    """Every candidate sized (minimize) with the law shaped for its own T; the table in
    the candidates' order and h = T_min - T (nan where infeasible)."""
    from sizer.sizing.engine import evaluate_fixed_law

    keys = np.round(T, 15)
    distinct, group = np.unique(keys, return_inverse=True)
    parts, positions = [], []
    for k in range(len(distinct)):
        index = np.flatnonzero(group == k)
        law = _shaped(fields, mode, float(T[index[0]]))
        parts.append(evaluate_fixed_law(design, law, candidates.take(index)))
        positions.append(index)
    joined = concatenate(parts)
    inverse = np.empty(len(candidates), dtype=np.intp)
    inverse[np.concatenate(positions)] = np.arange(len(candidates))
    table = joined.take(inverse)
    return table, table.figures["duration"] - T
