"""The core on extreme but finite inputs: no warning, every figure finite or absent (issue 10).

Designs are built directly (no loader, so no plausible-range refusal): durations of 1 us
and 1e6 s, displacements of 1e-6 and 1e6 rad, inertias of 1e-12 and 1e6 kg*m^2, ratios of
1e-4 and 1e5, efficiency 0.01, friction or a constant load above the peak torque, a load
of almost nothing. Warnings are errors (``warnings.simplefilter('error')``), so any
RuntimeWarning of numpy (overflow, divide by zero, invalid value) fails the test.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import replace

import pytest

from sizer.model.domain import Design, Limits, Load, Motor, Stage, Task, Transmission
from sizer.sizing import check_design, size_design
from sizer.sizing.results import CandidateResult

MOTORS = (
    Motor("book", inertia=0.0, continuous_torque=14.0, peak_torque=30.0, rated_speed=6.0),
    Motor("servo", inertia=1.2e-4, continuous_torque=1.3, peak_torque=3.8, rated_speed=314.16,
          max_speed=628.3),
    Motor("tiny", inertia=1e-12, continuous_torque=1e-6, peak_torque=2e-6, rated_speed=1e-6),
    Motor("huge", inertia=1e6, continuous_torque=1e6, peak_torque=3e6, rated_speed=1e3),
)
LAWS = ("cycloidal", "double_s(alpha=1/3, beta=1/4)")  # smooth, and piecewise with flats


def design(*, h: float = 0.6, T: float | None = 0.2, dwell: float = 0.0,
           back: bool = False, J: float = 0.25, B: float = 0.0, friction: float = 0.0,
           torque: float = 0.0, ratio: float = 1.0, efficiency: float = 1.0,
           limits: Limits | None = None) -> Design:
    stages = (Stage("gearbox", ratio=ratio, efficiency=efficiency),)
    return Design(task=Task(h, T, dwell, back), load=Load(J, B, friction, torque),
                  transmission=Transmission(stages), laws=LAWS, motors=MOTORS,
                  limits=limits or Limits(), chosen_motor="servo", chosen_law="cycloidal")


EXTREMES = {
    "duration-1us": design(T=1e-6),
    "duration-1e6s": design(T=1e6),
    "minimize": design(T=None),
    "displacement-1e-6": design(h=1e-6, T=None),
    "displacement-1e6": design(h=1e6, T=None),
    "inertia-1e-12": design(J=1e-12, T=None),
    "inertia-1e6": design(J=1e6, T=None),
    "almost-no-load": design(J=1e-12, T=None, dwell=1e-6, back=True),
    "ratio-1e-4": design(ratio=1e-4, T=None),
    "ratio-1e5": design(ratio=1e5, T=None),
    "ratio-1e5-efficiency-0.01": design(ratio=1e5, efficiency=0.01, T=None),
    "efficiency-0.01": design(efficiency=0.01, friction=1.0, T=None),
    "friction-above-peak": design(friction=1e4, T=None),
    "friction-above-peak-fixed": design(friction=1e4),
    "constant-load-above-peak": design(torque=1e4, T=None, dwell=0.1),
    "damping-1e6": design(B=1e6, T=None),
    "dwell-1e6-return": design(dwell=1e6, back=True, T=None),
    "limits": design(T=None, limits=Limits(inertia_ratio=10.0, max_acceleration=1e-6,
                                          max_jerk=1e-6, max_speed=1e-6)),
    # beyond the plausible ranges (refused at load), still no warning in the core
    "duration-1e-100": design(T=1e-100),
    "duration-1e300": design(T=1e300),
    "displacement-1e200": design(h=1e200, T=None, dwell=1.0),
    "friction-1e300-dwell": design(friction=1e300, torque=1e300, T=1.0, dwell=1.0),
    "margins-99pc": design(T=None, limits=Limits(torque_margin=0.99, speed_margin=0.99)),
}


def finite_or_none(value: float | None) -> bool:
    return value is None or math.isfinite(value)


def assert_honest(result: CandidateResult) -> None:
    """Every summary figure finite or absent (None with a reason); no NaN anywhere."""
    for name in ("duration", "peak_torque", "rms_torque", "max_speed", "load_speed",
                 "load_torque"):
        value = getattr(result, name)
        if not finite_or_none(value):  # beyond the float range: infeasible, said so
            assert value > 0.0 and not result.feasible, (result.motor, result.spec, name)
            assert "unbounded" in result.reason, result.reason
    if result.duration is None:
        assert not result.feasible and result.reason
    for check in result.checks:
        assert not math.isnan(check.value) and not math.isnan(check.margin), check
        if not (math.isfinite(check.value) and math.isfinite(check.margin)):
            assert check.undefined_reason and not check.passed, check
    if not result.feasible:
        assert result.reason and result.limiting


@pytest.mark.parametrize("name", list(EXTREMES), ids=str)
def test_size_extreme_design_without_warnings(name: str) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        sized = size_design(EXTREMES[name])
        checked = check_design(EXTREMES[name])
    assert len(sized.results) == len(MOTORS) * len(LAWS)
    for result in (*sized.results, checked):
        assert_honest(result)


def test_friction_above_the_peak_torque_has_no_duration_and_says_which_limit() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        sized = size_design(EXTREMES["friction-above-peak"])
    weak = [r for r in sized.results if r.motor != "huge"]  # tau_p <= 30 N*m < 1e4 N*m
    for result in weak:
        assert result.duration is None and not result.feasible
        assert "no duration is feasible" in result.reason
    assert all(r.feasible for r in sized.results if r.motor == "huge")


def test_a_longer_move_never_needs_more_torque_at_the_extremes() -> None:
    """At T = 1e6 s the inertial torque J h C_a / T^2 is 1e-12 of the one at 1 s: the
    peak torque is that closed form (cycloidal C_a = 2 pi), finite and tiny."""
    base = replace(EXTREMES["duration-1e6s"], laws=("cycloidal",), chosen_motor="book")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        result = check_design(base)
    assert result.peak_torque == pytest.approx(0.25 * 0.6 * 2 * math.pi / 1e12, rel=1e-9)


def test_a_move_beyond_the_regions_says_the_motor_gives_no_torque_there(tmp_path):
    """Curves that end at 0 N*m at max speed, a move far beyond it: the peak ratio is
    unbounded and the RMS limit 0; the reasons say why, not 'beyond the range of a float'."""
    from sizer.io import load_design
    from sizer.sizing import size_design

    (tmp_path / "motors.yaml").write_text(
        "motors:\n  - id: C0\n    inertia: 0.5 kg*cm^2\n    continuous_torque: 1.3 N*m\n"
        "    peak_torque: 3.8 N*m\n    rated_speed: 3000 rpm\n    max_speed: 6000 rpm\n"
        "    continuous_curve: [[0 rpm, 1.3 N*m], [3000 rpm, 1.3 N*m], [6000 rpm, 0 N*m]]\n"
        "    intermittent_curve: [[0 rpm, 3.8 N*m], [3000 rpm, 3.8 N*m], [6000 rpm, 0 N*m]]\n",
        encoding="utf-8")
    (tmp_path / "d.yaml").write_text(
        "task: {displacement: 20 rev, duration: 0.1 s}\nload: {inertia: 1 kg*cm^2}\n"
        "transmission: {type: direct}\nlaws: [cycloidal]\nmotors: motors.yaml\n",
        encoding="utf-8")
    (result,) = size_design(load_design(tmp_path / "d.yaml")).results
    checks = {c.name: c for c in result.checks}
    assert not result.feasible
    assert "gives none" in checks["peak"].undefined_reason
    assert checks["rms"].limit == 0.0
    assert "needed where the motor gives none" in checks["rms"].undefined_reason
    assert "float" not in result.reason
