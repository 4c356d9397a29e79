"""The task curve of a sizing result: the core's ``task_curve`` with the result's own
law, duration and (when the solver chose it) transmission ratio or catalog gearbox."""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

from sizer.errors import UserError

if TYPE_CHECKING:
    from sizer.model.domain import Design, Motor, Transmission
    from sizer.sizing import CandidateResult
    from sizer.sizing.profile import TaskCurve


def transmission_for(design: Design, result: CandidateResult) -> Transmission:
    """The transmission the result was sized with.

    Without a free ratio it is the design's. With one, stage ``ratio_choice.stage`` is the
    catalog gearbox the result names (its ratio, efficiency, inertia and limits), or the
    design's stage with the ratio ``result.extra["stage_ratio"]``.
    """
    choice = design.ratio_choice
    if choice is None:
        return design.transmission
    ratio = result.extra.get("stage_ratio")
    if ratio is None:
        raise ValueError(f"{result.motor}, {result.spec}: no stage_ratio for the free ratio")
    if result.gearbox is not None:
        stage = next((o.stage for o in choice.gearboxes
                      if o.gearbox == result.gearbox and o.stage.ratio == ratio), None)
        if stage is None:
            raise ValueError(f"{result.motor}, {result.spec}: gearbox {result.gearbox!r} "
                             f"with ratio {ratio!r} is not among the design's options")
    else:
        stage = dataclasses.replace(design.transmission.stages[choice.stage], ratio=ratio)
    return design.transmission.with_stage(choice.stage, stage)


def motor_of(design: Design, result: CandidateResult) -> Motor:
    """The design's motor the result is about."""
    motor = next((m for m in design.motors if m.id == result.motor), None)
    if motor is None:
        raise ValueError(f"motor {result.motor!r} is not among the design's motors")
    return motor


def curve_for(design: Design, result: CandidateResult, samples: int = 401) -> TaskCurve:
    """One machine cycle of the result's motor and law at its duration (T_min in minimize
    mode), ``samples`` per move. A result without a feasible duration has no curve: a
    UserError saying why."""
    from sizer.sizing.profile import task_curve

    if result.duration is None:
        raise UserError(f"{result.motor} with {result.spec} has no feasible duration "
                        f"({result.reason}): no task curve to draw")
    return task_curve(design, motor_of(design, result), result.spec, result.duration,
                      transmission=transmission_for(design, result), samples=samples)
