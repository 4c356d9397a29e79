"""The transmission of a result as the user wrote it (issue 36: a linear axis showed its
total ratio, 150/250/350 rad/m, where the user listed gearboxes 3/5/7).

A design chooses at most one stage's ratio (sizer.model.domain.RatioChoice: a list, bounds
or catalog gearboxes), always a gearbox or a belt: its ratio is rad/rad, as listed. The
tables show that stage's ratio; the total ratio K (rad/rad, or rad/m on a linear axis,
motor speed over load speed) stays in CSV and JSON, SI, with its unit said.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from sizer.report.numbers import short, short_or_na

if TYPE_CHECKING:
    from sizer.model.domain import Design, Stage
    from sizer.sizing import CandidateResult


def free_stage(design: Design, result: CandidateResult) -> Stage | None:
    """The stage whose ratio the design leaves to the solver, as the result chose it
    (None: no free stage, or the result has no such stage)."""
    choice = design.ratio_choice
    transmission = result.transmission
    if choice is None or transmission is None or choice.stage >= len(transmission.stages):
        return None
    return transmission.stages[choice.stage]


def ratio_header(design: Design) -> str:
    """'gearbox ratio', 'belt ratio' (the free stage's kind), else 'ratio'."""
    choice = design.ratio_choice
    stages = design.transmission.stages
    if choice is None or choice.stage >= len(stages):
        return "ratio"
    return f"{stages[choice.stage].kind.replace('_', ' ')} ratio"


def listed_ratio_text(design: Design, result: CandidateResult) -> str:
    """The free stage's ratio as listed ('5'), with the catalog gearbox chosen
    ('10 (PG60 i=10)'); the total ratio where the design has no free stage."""
    stage = free_stage(design, result)
    text = short_or_na(result.ratio) if stage is None else short(stage.ratio)
    return f"{text} ({result.gearbox})" if result.gearbox else text
