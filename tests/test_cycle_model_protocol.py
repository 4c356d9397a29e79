"""The cycle model's one declared interface (sizer.sizing.evaluation.CycleModel), the mode
of a sizing and the check names as types (issue 33)."""

from __future__ import annotations

import json

from sizer.sizing.checks import CHECKS, OWN_CHECKS, CheckName, OwnCheckKind
from sizer.sizing.cycle import SegmentCycle
from sizer.sizing.evaluation import CycleModel, SegmentedModel
from sizer.sizing.linkage_move import LinkageCalculator, LinkageCycle
from sizer.sizing.move import CycleCalculator
from sizer.sizing.results import Mode, SizingResult

MEMBERS = ("segmented", "task", "drive", "motors", "take", "evaluate", "thermal_speed",
           "peak_bound", "search_start", "initial_guess", "rms_lower_bound", "cycle_time",
           "scale_of", "pieces", "reported", "law_move", "dead_point_issues", "given_scale")
ATTRIBUTES = ("segmented", "task", "drive", "motors")
"""Members a calculator sets per instance (``segmented`` on the class)."""
SEGMENTED = ("breakdown",)
"""What a cycle of segments adds (sizer.sizing.evaluation.SegmentedModel)."""


def declared(protocol: type) -> set[str]:
    return {n for n in vars(protocol) if not n.startswith("_")} | \
        set(protocol.__annotations__)


def test_the_protocol_declares_what_the_search_and_the_sampler_ask():
    assert declared(CycleModel) == set(MEMBERS)
    assert declared(SegmentedModel) == set(SEGMENTED)


def test_every_calculator_implements_every_member():
    for cls in (CycleCalculator, SegmentCycle, LinkageCalculator, LinkageCycle):
        for name in MEMBERS + SEGMENTED * cls.segmented:
            if name not in ATTRIBUTES:
                assert callable(getattr(cls, name, None)), (cls.__name__, name)
        assert isinstance(cls.segmented, bool)


def test_the_mode_is_an_enum_and_its_json_the_text():
    result = SizingResult("minimize", [], "demo")
    assert result.mode is Mode.MINIMIZE
    assert json.dumps(result.to_dict()["mode"]) == '"minimize"'


def test_each_check_name_is_listed_once():
    names = [k.name for k in CHECKS] + [k.name for k in OWN_CHECKS]
    assert len(names) == len(set(names))
    assert set(names) == set(CheckName)
    assert json.dumps(CheckName.DEAD_POINT) == '"dead_point"'


def test_an_own_kind_makes_its_check_with_its_unit():
    import numpy as np

    kind = OwnCheckKind(CheckName.RESIDUAL_VIBRATION, "rad", "m")
    rotary = kind.arrays(np.array([1.0]), np.array([4.0]), 0.0)
    linear = kind.arrays(np.array([5.0]), np.array([4.0]), 0.0, linear=True)
    assert (rotary.unit, linear.unit) == ("rad", "m")
    assert rotary.slack[0] == 0.75 and linear.slack[0] == -0.25  # 1 - value/limit
