"""Choosing the free ratio of a transmission stage for each motor and law.

The options are a list of ratios, catalog gearboxes (each ratio with its own efficiency,
inertia and limits), or a continuous range searched on a logarithmic grid refined around
each motor's best point down to 0.25 % steps. Per motor the best option is the feasible
one with the shortest T_min (minimize mode) or the smallest RMS torque (duration given);
when none is feasible, the one closest to feasible.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

import numpy as np

from sizer.model.domain import Design, Stage
from sizer.sizing.motors import MotorArrays
from sizer.sizing.results import CandidateResult

COARSE = 9
FINE = 5
LOG_STEP = 2.5e-3
"""Final spacing of the search in log(ratio): the chosen ratio is within ~0.25 %."""

Evaluate = Callable[[Design, str, MotorArrays], list[CandidateResult]]


def _key(result: CandidateResult, minimize: bool) -> tuple[float, float]:
    """Smaller is better."""
    if not result.feasible:
        return (1.0, -result.worst_slack)
    value = result.duration if minimize else result.rms_torque
    return (0.0, math.inf if value is None else value)


def _with_stage(design: Design, stage: Stage) -> Design:
    choice = design.ratio_choice
    transmission = design.transmission.with_stage(choice.stage, stage)
    return dataclasses.replace(design, transmission=transmission, ratio_choice=None)


def choose_ratio(design: Design, spec: str, motors: MotorArrays,
                 evaluate: Evaluate) -> list[CandidateResult]:
    """The best option for each motor (results carry the ratio and the gearbox)."""
    choice = design.ratio_choice
    base = design.transmission.stages[choice.stage]
    minimize = design.task.minimize
    best: list[CandidateResult | None] = [None] * len(motors)

    def consider(stage: Stage, gearbox: str | None, members: np.ndarray) -> None:
        results = evaluate(_with_stage(design, stage), spec, motors.subset(members))
        for i, result in zip(members, results, strict=True):
            result = dataclasses.replace(result, gearbox=gearbox,
                                         extra={**result.extra, "stage_ratio": stage.ratio})
            if best[i] is None or _key(result, minimize) < _key(best[i], minimize):
                best[i] = result

    everyone = np.arange(len(motors))
    for option in choice.gearboxes:
        consider(option.stage, option.gearbox, everyone)
    for ratio in choice.ratios:
        consider(dataclasses.replace(base, ratio=ratio), None, everyone)
    if choice.bounds is not None:
        _continuous(choice.bounds, base, consider, best, everyone)
    return [r for r in best if r is not None]


def _continuous(bounds, base: Stage, consider, best, everyone) -> None:
    """Log-spaced grid over the bounds, then halving steps around each motor's best.

    All points lie on one lattice in log(ratio), so each round evaluates every needed
    point once, for all the motors whose neighbourhood contains it.
    """
    lo, hi = math.log(bounds[0]), math.log(bounds[1])
    step = (hi - lo) / (COARSE - 1)
    for x in np.linspace(lo, hi, COARSE):
        consider(dataclasses.replace(base, ratio=math.exp(x)), None, everyone)
    last = COARSE - 1
    while step > LOG_STEP:
        step /= 2.0
        last *= 2
        needed: dict[int, list[int]] = {}
        for i in everyone:
            centre = round((math.log(best[i].extra["stage_ratio"]) - lo) / step)
            for k in (-2, -1, 1, 2):
                if 0 <= centre + k <= last:
                    needed.setdefault(centre + k, []).append(int(i))
        for key, members in sorted(needed.items()):
            consider(dataclasses.replace(base, ratio=math.exp(lo + key * step)), None,
                     np.array(members))
