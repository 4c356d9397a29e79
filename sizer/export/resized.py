"""The exported profile sized again: the motor's torques on what the controller will run.

For a C1-or-smoother export the written table, read back as a ``cam_table`` law with the
target's interpolation (the caller makes the law of the file's spec, as a user would),
is sized through the engine (sizer.sizing.size_design) for the same motor, drive,
transmission (the ratio or gearbox the sizing chose, fixed) and the same duration (the
sized one, fixed also when the design minimizes it): the same computation as
``sizer size`` of the design with ``laws: [that spec]``. No files here: the caller reads
the law.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from sizer.model.domain import Design
    from sizer.sizing.results import CandidateResult


@dataclass(frozen=True)
class Resized:
    """The sized law's result and the exported profile's, for the same pair."""

    law: CandidateResult
    exported: CandidateResult

    @property
    def newly_failed(self) -> tuple[str, ...]:
        """The checks the exported profile fails that the law passed (and 'feasible'
        when the law was feasible and the profile is not, with no check named)."""
        passed = {c.name for c in self.law.checks if c.passed}
        failed = tuple(c.name for c in self.exported.checks
                       if not c.passed and c.name in passed)
        if not failed and self.law.feasible and not self.exported.feasible:
            return ("feasible",)
        return failed


def fixed_design(design: Design, result: CandidateResult) -> Design:
    """``design`` with the pair's motor, drive, transmission and duration fixed."""
    from sizer.model.cycle import from_task

    task = replace(design.task, duration=result.duration)
    fixed = replace(design, machine_cycle=from_task(task), motors=(result.motor_object,),
                    chosen_motor=None, chosen_law=None)
    if design.ratio_choice is not None:
        fixed = replace(fixed, ratio_choice=None, transmission=result.transmission)
    if result.drive_object is not None:
        fixed = replace(fixed, drives=(result.drive_object,))
    return fixed


def resize(design: Design, result: CandidateResult, spec: str) -> Resized:
    """The law ``spec`` (the exported table read back) sized for ``result``'s pair."""
    from sizer.laws.choice import law_choice
    from sizer.sizing import size_design

    fixed = replace(fixed_design(design, result), laws=(law_choice(spec),))
    exported = size_design(fixed).results[0]
    return Resized(result, exported)
