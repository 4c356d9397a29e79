"""The ratio column as the user wrote it (issue 36): a linear axis with a gearbox of 3, 5
or 7 before a 20 mm-lead ball screw shows 3/5/7, not the total 2*pi/0.02 x 3/5/7 rad/m."""

from __future__ import annotations

import math

import pytest

from sizer.io.loader import load_design_data
from sizer.report.transmission_text import listed_ratio_text, ratio_header
from sizer.sizing.engine import size_design

MOTOR = {"id": "M", "inertia": "0.5 kg*cm^2", "continuous_torque": "1.3 N*m",
         "peak_torque": "4.5 N*m", "rated_speed": "3000 rpm", "max_speed": "6000 rpm"}


def screw_axis(ratio) -> dict:
    return {"task": {"displacement": "0.2 m", "duration": "0.5 s", "dwell": "0.5 s"},
            "load": {"mass": "5 kg"},
            "transmission": [{"type": "gearbox", "ratio": ratio},
                             {"type": "ball_screw", "lead": "20 mm", "inertia": 0}],
            "laws": ["cycloidal"], "motors": [MOTOR]}


def test_a_listed_gearbox_before_a_screw_shows_its_own_ratio() -> None:
    design = load_design_data(screw_axis([3, 5, 7]))
    results = size_design(design).results
    assert ratio_header(design) == "gearbox ratio"
    for result in results:
        stage = listed_ratio_text(design, result)
        assert stage in {"3", "5", "7"}
        # the total, SI, is the stage's times the screw's 2*pi/lead (rad/m)
        assert result.ratio == pytest.approx(float(stage) * 2.0 * math.pi / 0.02, rel=1e-12)


def test_without_a_free_stage_the_total_ratio_is_shown() -> None:
    design = load_design_data(screw_axis(4))
    (result,) = size_design(design).results
    assert ratio_header(design) == "ratio"
    assert float(listed_ratio_text(design, result)) == pytest.approx(
        4.0 * 2.0 * math.pi / 0.02, rel=1e-4)
