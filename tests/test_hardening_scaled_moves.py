"""A law scaled to a move on the command line (issue 32): a displacement and a duration
whose derivatives leave the float range are refused naming --duration, never printed as
inf nor raised as an internal error (found by the options fuzz: ``--duration 1e-200 s``)."""

from __future__ import annotations

import math

import pytest
from bad_input_cases import Case, run_case

from sizer.laws.motion import PEAK_HEADROOM, scale_fault


def test_the_first_order_out_of_range_is_named() -> None:
    # h / T^k: 0.02 / (1e-200)^k = 2e-2, 2e198, 2e398: the acceleration overflows
    assert scale_fault(0.02, 1e-200) is not None and "acceleration" in scale_fault(0.02, 1e-200)
    # 1e300 / 1e-5 = 1e305, beyond 1.8e308 / PEAK_HEADROOM = 1.8e302: the velocity
    assert "velocity" in scale_fault(1e300, 1e-5)
    # T^2 = 1e600 overflows though h / T^2 would underflow to 0
    assert "divides by T^2" in scale_fault(1e-300, 1e300)
    # the largest scale that passes: h / T^3 just under 1.8e308 / PEAK_HEADROOM
    top = 1.7976931348623157e308 / PEAK_HEADROOM
    assert scale_fault(top * 0.99 * 1e-9, 1e-3) is None
    assert scale_fault(top * 1.01 * 1e-9, 1e-3) is not None
    assert scale_fault(math.pi / 2, 0.25) is None
    assert scale_fault(0.0, 1e-300) is None  # no move: nothing scales


@pytest.mark.parametrize("args", [
    ("law", "cycloidal", "--displacement", "20mm", "--duration", "1e-200 s"),
    ("law", "cycloidal", "--displacement", "1e300", "--duration", "1e-5"),
    ("law", "cycloidal", "--displacement", "1e-300", "--duration", "1e300"),
    ("law", "{{kind: cubic_spline, times: auto, positions: [0, 0.3, 0.8, 1]}}",  # str.format
     "--displacement", "20 mm", "--duration", "1e-200 s", "--format", "csv"),
    ("plot-law", "cycloidal", "--displacement", "20mm", "--duration", "1e-200s", "-o",
     "{tmp}/p.png"),
    ("plot-law", "cycloidal", "--displacement", "1e300", "--duration", "1e-5", "-o",
     "{tmp}/p.png"),
    ("spectrum", "cycloidal", "--displacement", "1", "--duration", "1e200"),
], ids=lambda args: " ".join(args[:1] + args[3:6]))
def test_a_move_beyond_the_float_range_is_refused_naming_duration(args, tmp_path) -> None:
    run_case(Case("scaled", args=args, words=("--duration", "float range")), tmp_path)
