"""The exported profile sized again: the motor's torques on what the controller will run.

For a C1-or-smoother export the written table, read back as a ``cam_table`` law with the
target's interpolation (the caller makes the law of the file's spec, as a user would),
is sized through the engine (sizer.sizing.size_design) for the same motor, drive,
transmission (the ratio or gearbox the sizing chose, fixed) and the same duration (the
sized one, fixed also when the design minimizes it): the same computation as
``sizer size`` of the design with ``laws: [that spec]``. No files here: the caller reads
the law.

A design's cycle of segments (:func:`resize_cycle`): the design's cycle with each move's
law replaced by the written file's span of that move (``{kind: cam_table, file: F,
interpolation: ..., span: [x0, x1]}`` or ``{kind: cam_segments, file: F, span: [x0,
x1]}``, normalized to its own stroke and duration), every move and dwell at the duration
the sizing gave it (fixed; runs unchanged), sized for the pair: the same computation as
``sizer size`` of that cycle written out. A move between boundary speeds takes its span at
that fixed duration, its end slopes checked against the move's speeds
(sizer.model.cycle.shape_mismatch) and evaluated exactly (sizer.sizing.cycle).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from collections.abc import Sequence

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
    return result.fixed_in(replace(design, machine_cycle=from_task(task)))


def resize(design: Design, result: CandidateResult, spec: str) -> Resized:
    """The law ``spec`` (the exported table read back) sized for ``result``'s pair."""
    from sizer.laws.choice import law_choice
    from sizer.sizing import size_design

    fixed = replace(fixed_design(design, result), laws=(law_choice(spec),))
    exported = size_design(fixed).results[0]
    return Resized(result, exported)


def cycle_design(design: Design, result: CandidateResult, specs: Sequence[str | None]
                 ) -> Design:
    """``design`` with the pair fixed (:func:`fixed_design`) and its cycle's moves by the
    laws ``specs`` (one per segment, None for a run or a dwell), each move and dwell at
    the duration the sizing gave it (sizer.export.cycle_profile.segment_durations), no
    duration free and no cycle-time target. ValueError where a move's law does not meet
    its boundary speeds at that duration (the message says the numbers)."""
    from sizer.export.cycle_profile import segment_durations
    from sizer.laws.choice import law_choice
    from sizer.model.cycle import Dwell, Move, Segment, fixed_shape, shape_mismatch

    cycle = design.machine_cycle
    if result.duration is None:
        raise ValueError("the pair has no sized duration")
    durations = segment_durations(design, result.duration, result)
    segments: list[Segment] = []
    for segment, duration, spec in zip(cycle.segments, durations, specs, strict=True):
        if isinstance(segment, Move):
            if spec is None:
                raise ValueError(f"no law for move {segment.name!r}")
            choice = law_choice(spec)
            moved = replace(segment, duration=duration, law=choice)
            if not moved.rest_to_rest and fixed_shape(choice.law):
                reason = shape_mismatch(moved, choice.law, duration, cycle.linear)
                if reason is not None:
                    raise ValueError(f"move {segment.name!r}: {reason}")
            segments.append(moved)
        elif isinstance(segment, Dwell):
            segments.append(replace(segment, duration=duration))
        else:
            segments.append(segment)
    fixed = replace(cycle, segments=tuple(segments), cycle_time=None,
                    minimize_segment=None, shorthand=None)
    return result.fixed_in(replace(design, machine_cycle=fixed))


def resize_cycle(design: Design, result: CandidateResult, specs: Sequence[str | None]
                 ) -> Resized:
    """The design's cycle with each move's law ``specs[i]`` (the exported file's span of
    that move), sized for ``result``'s pair at the sized durations (:func:`cycle_design`)."""
    from sizer.sizing import size_design

    exported = size_design(cycle_design(design, result, specs)).results[0]
    return Resized(result, exported)
