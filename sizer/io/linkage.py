"""A linkage stage of a design's transmission (seed 003): read, its geometry checked.

The linkage must be the transmission's last stage: the stages before it turn its crank
(their ratio is motor speed over crank speed), its output is the load. Its geometry is
checked by building it (sizer.mechanics.linkages): a rod not longer than the crank plus
the offset, a four-bar that cannot close or whose crank cannot turn fully, are errors at
the stage's line.
"""

from __future__ import annotations

from typing import Any

from sizer.errors import UserError
from sizer.io.yaml_source import YamlSource
from sizer.model.domain import LinkageStage
from sizer.model.transmission_inputs import FourBarInput, SliderCrankInput


def linkage_stage(item: SliderCrankInput | FourBarInput, source: YamlSource,
                  at: tuple[Any, ...]) -> LinkageStage:
    """The LinkageStage of a ``slider_crank`` or ``four_bar`` item, its geometry built."""
    common = {"law_on": item.law_on, "start_angle": item.start_angle,
              "direction": 1 if item.direction == "positive" else -1,
              "crank_inertia": item.crank_inertia, "name": item.name or ""}
    if isinstance(item, SliderCrankInput):
        stage = LinkageStage("slider_crank", (item.crank_radius, item.rod_length, item.offset),
                             link_mass_at_crank=item.rod_mass_at_crank,
                             link_mass_at_output=item.rod_mass_at_slider, **common)
    else:
        stage = LinkageStage("four_bar", (item.crank, item.coupler, item.rocker, item.ground),
                             branch=item.branch, link_mass_at_crank=item.coupler_mass_at_crank,
                             link_mass_at_output=item.coupler_mass_at_rocker, **common)
    try:
        linkage_of(stage)
    except UserError as error:
        raise source.relocate(error, (*at, error.field) if error.field else at) from None
    return stage


def linkage_of(stage: LinkageStage) -> Any:
    """The mechanism of a LinkageStage (a sizer.mechanics.linkages.Linkage)."""
    if stage.kind == "slider_crank":
        from sizer.mechanics.linkages.slider_crank import SliderCrank

        r, rod, e = stage.lengths
        return SliderCrank(r, rod, e)
    from sizer.mechanics.linkages.four_bar import FourBar

    crank, coupler, rocker, ground = stage.lengths
    return FourBar(crank=crank, coupler=coupler, rocker=rocker, ground=ground,
                   branch=stage.branch)


def linkage_task(task: Any, stage: LinkageStage, cycle: Any, model: Any,
                 source: YamlSource) -> tuple[Any, bool]:
    """The task of a design whose transmission ends in a linkage, and its axis (the
    linkage's output: a slider is linear, a rocker rotary).

    With ``law_on: crank`` the task's displacement is the crank's turn, an angle; with
    ``law_on: output`` it is the output's travel, of the output's kind. The shorthand
    task only: a cycle of segments, a return move through a linkage are not sized yet.
    """
    from dataclasses import replace

    at = ("task", "displacement")
    if cycle is not None:
        raise source.error("a linkage (slider_crank, four_bar) is sized with the task "
                           "shorthand only, not yet in a cycle of segments", ("cycle",))
    if task.return_move:
        raise source.error("a linkage turns its crank on; a return move through it is not "
                           "sized yet: write the way back as the crank's turn", ("task",
                                                                                 "return"))
    output = "a length (the slider's travel)" if stage.output_linear else \
        "an angle (the rocker's swing)"
    if stage.law_on == "crank" and task.linear:
        raise source.error("with law_on: crank the displacement is the crank's turn, an "
                           "angle like '180 deg'", at)
    if stage.law_on == "output" and task.linear != stage.output_linear:
        raise source.error(f"with law_on: output the displacement is {output}", at)
    if stage.law_on == "output":
        _check_stroke(stage, task.displacement, source, at)
    return replace(task, linear=stage.output_linear), stage.output_linear


def _check_stroke(stage: LinkageStage, h: float, source: YamlSource,
                  at: tuple[Any, ...]) -> None:
    """The output's move from where the crank starts stays within the linkage's range."""
    import numpy as np

    linkage = linkage_of(stage)
    start = float(linkage.output(np.array([stage.start_angle]))[0])
    low, high = linkage.output_range()
    end = start + h
    tolerance = 1e-9 * (high - low)
    if not low - tolerance <= end <= high + tolerance:
        unit = "m" if stage.output_linear else "rad"
        raise source.error(f"the output would move from {start:.6g} {unit} (the crank at "
                           f"start_angle) to {end:.6g} {unit}, beyond its range "
                           f"[{low:.6g}, {high:.6g}] {unit} (the stroke between the dead "
                           f"points)", at)


def output_linear(items: Any, linear: bool) -> bool:
    """Whether the load is linear: the displacement's kind, or, when the transmission
    ends in a linkage, its output's (a slider is linear, a rocker is not)."""
    items = items if isinstance(items, list) else [items] if items is not None else []
    for item in reversed(items):
        kind = getattr(item, "type", None)
        if kind in ("slider_crank", "four_bar"):
            return kind == "slider_crank"
        if kind not in (None, "direct"):
            break
    return linear
