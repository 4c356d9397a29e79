"""What the laws of one sizing share: built once, for every law (sizer.sizing.engine, and
each worker process of sizer.sizing.law_processes)."""

from __future__ import annotations

from functools import cached_property
from typing import TYPE_CHECKING

from sizer.model.domain import Design
from sizer.sizing.motors import MotorArrays

if TYPE_CHECKING:
    from sizer.sizing.duration_floor import PeakScales
    from sizer.sizing.ratio_choice import ListedPairs


class SharedByLaws:
    """What every law of one sizing of a free stage shares, each part built on first use:
    every motor with every listed option (sizer.sizing.ratio_choice.listed_pairs) and
    their peak scales (sizer.sizing.duration_floor.peak_scales)."""

    def __init__(self, design: Design, motors: MotorArrays) -> None:
        self.design, self.motors = design, motors

    @cached_property
    def pairs(self) -> ListedPairs:
        from sizer.sizing.ratio_choice import listed_pairs

        return listed_pairs(self.design, self.motors)

    @cached_property
    def scales(self) -> PeakScales:
        from sizer.sizing.duration_floor import peak_scales

        assert self.pairs.candidates is not None  # asked for the listed pairs' floors only
        return peak_scales(self.design, self.pairs.candidates)
