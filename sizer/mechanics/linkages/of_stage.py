"""The mechanism of a design's linkage stage (sizer.model.domain.LinkageStage)."""

from __future__ import annotations

from sizer.mechanics.linkages import Linkage
from sizer.model.domain import LinkageStage


def linkage_of(stage: LinkageStage) -> Linkage:
    """The slider-crank or four-bar of a LinkageStage; UserError for bad geometry."""
    if stage.kind == "slider_crank":
        from sizer.mechanics.linkages.slider_crank import SliderCrank

        r, rod, e = stage.lengths
        return SliderCrank(r, rod, e)
    from sizer.mechanics.linkages.four_bar import FourBar

    crank, coupler, rocker, ground = stage.lengths
    return FourBar(crank=crank, coupler=coupler, rocker=rocker, ground=ground,
                   branch=stage.branch)
