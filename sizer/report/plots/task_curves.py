"""The task curve of a sizing result: the core's ``task_curve`` with the result's own
law, duration and (when the solver chose it) transmission ratio or catalog gearbox."""

from __future__ import annotations

from typing import TYPE_CHECKING

from sizer.errors import UserError
from sizer.laws.data_spec import law_label

if TYPE_CHECKING:
    from sizer.model.domain import Design, Transmission
    from sizer.sizing import CandidateResult
    from sizer.sizing.samples import TaskCurve


def transmission_for(design: Design, result: CandidateResult) -> Transmission:
    """The transmission the result was sized with (its chosen ratio or gearbox in place)."""
    return result.transmission


def curve_for(design: Design, result: CandidateResult, samples: int = 401) -> TaskCurve:
    """One machine cycle of the result's motor and law at its duration (T_min in minimize
    mode), ``samples`` per move. A result without a feasible duration has no curve: a
    UserError saying why."""
    from sizer.sizing.samples import task_curve

    if result.duration is None:
        raise UserError(f"{result.motor} with {law_label(result.spec)} has no feasible duration "
                        f"({result.reason}): no task curve to draw")
    return task_curve(design, result.motor_object, result.law_object, result.duration,
                      transmission=result.transmission, samples=samples)
