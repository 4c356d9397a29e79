"""The task curve of a sizing result: the core's ``task_curve`` with the result's own
law, duration and (when the solver chose it) transmission ratio or catalog gearbox."""

from __future__ import annotations

from typing import TYPE_CHECKING

from sizer.errors import UserError
from sizer.laws.data_spec import law_label

if TYPE_CHECKING:
    from sizer.model.domain import Design, Motor, Transmission
    from sizer.sizing import CandidateResult
    from sizer.sizing.samples import TaskCurve


def transmission_for(design: Design, result: CandidateResult) -> Transmission:
    """The transmission the result was sized with (its chosen ratio or gearbox in place)."""
    return result.transmission or design.transmission


def motor_of(design: Design, result: CandidateResult) -> Motor:
    """The motor the result is about (the object the engine sized; for a hand-made result
    the design's motor of that id)."""
    if result.motor_object is not None:
        return result.motor_object
    motor = next((m for m in design.motors if m.id == result.motor), None)
    if motor is None:
        raise ValueError(f"motor {result.motor!r} is not among the design's motors")
    return motor


def curve_for(design: Design, result: CandidateResult, samples: int = 401) -> TaskCurve:
    """One machine cycle of the result's motor and law at its duration (T_min in minimize
    mode), ``samples`` per move. A result without a feasible duration has no curve: a
    UserError saying why."""
    from sizer.sizing.samples import task_curve

    if result.duration is None:
        raise UserError(f"{result.motor} with {law_label(result.spec)} has no feasible duration "
                        f"({result.reason}): no task curve to draw")
    law = result.law_object if result.law_object is not None else result.spec
    return task_curve(design, motor_of(design, result), law, result.duration,
                      transmission=transmission_for(design, result), samples=samples)
