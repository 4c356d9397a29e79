"""The linkage calculators' shortcuts (issue 34): the peak ratio read only at the samples
that may hold it, the fixed moves' figures computed once per search, and the speed
bound a shortest-cycle search starts from.

Each is checked against the plain computation written out here: the ratio over every
sample, a calculator evaluated afresh, the speed check's own definition."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np

from sizer.io.loader import load_design
from sizer.laws import law_choice
from sizer.mechanics.drive import Drive
from sizer.model.domain import Motor
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.linkage_move import LinkageCycle, linkage_calculator, peak_ratio
from sizer.sizing.shortest_duration import bisect_duration

ROOT = Path(__file__).resolve().parent.parent


def _motors(count: int) -> tuple[Motor, ...]:
    """Motors with falling speed-torque curves (the limit depends on the speed); in the
    press cycle the first is bound by its torque, the others by their speed."""
    out = []
    for k in range(count):
        tau_p, v_n = 1.0 + 4.0 * k, 150.0 + 25.0 * k
        out.append(Motor(id=f"m{k}", inertia=1e-4, continuous_torque=tau_p / 2,
                         peak_torque=tau_p, rated_speed=v_n, max_speed=2 * v_n,
                         intermittent_curve=((0.0, tau_p), (0.8 * v_n, tau_p),
                                             (1.4 * v_n, 0.7 * tau_p), (2 * v_n, 0.35 * tau_p)),
                         continuous_curve=((0.0, tau_p / 2), (2 * v_n, tau_p / 4))))
    return tuple(out)


def test_peak_ratio_is_the_largest_over_every_sample():
    rng = np.random.default_rng(34)
    motors = MotorArrays.of(_motors(6), "book")
    u = np.linspace(0.0, 1.0, 2001)
    speed = np.outer(450.0 + 100.0 * rng.random(6), np.sin(np.pi * u))
    torque = np.outer(1.0 + rng.random(6), np.sin(2 * np.pi * u) ** 7 + 0.1 * np.cos(5 * u))
    torque[2] = 0.2 * np.sin(7 * u)  # a flat torque: many samples near its largest
    speed[3] *= 3.0  # past the end of the region: the limit clipped there
    limit = motors.intermittent.limit_clipped(speed)
    expected = np.max(np.abs(torque) / limit, axis=1)
    assert np.array_equal(peak_ratio(motors, torque, speed), expected)


def _press(count: int) -> tuple[LinkageCycle, object]:
    design = load_design(ROOT / "examples" / "press-slider-crank-cycle.yaml")
    design = replace(design, motors=_motors(count))
    motors = MotorArrays.of(design.motors, design.limits.envelope)
    calculator = linkage_calculator(design, law_choice("poly7").law, motors,
                                    Drive(design.load, design.transmission))
    assert isinstance(calculator, LinkageCycle)
    return calculator, design


def test_fixed_moves_are_the_same_at_every_scale_and_in_every_subset():
    calculator, _ = _press(5)
    s = np.linspace(0.2, 0.6, 5)
    calculator.evaluate(s[::-1])  # the fixed move's figures kept from another scale
    again = calculator.evaluate(s)
    fresh, _ = _press(5)
    whole = fresh.evaluate(s)
    index = np.array([4, 1])
    part = calculator.take(index).evaluate(s[index])
    for name in ("peak_torque", "peak_ratio", "rms_torque", "max_speed", "load_torque"):
        assert np.array_equal(getattr(again, name), getattr(whole, name))
        assert np.array_equal(getattr(part, name), getattr(whole, name)[index])


def test_speed_bound_is_where_the_speed_check_reaches_its_limit():
    calculator, design = _press(4)
    bound = calculator.speed_bound(design.limits)
    wanted = (1.0 - design.limits.speed_margin) * calculator.motors.speed_limit
    at = calculator.evaluate(bound).max_speed
    assert np.allclose(at, wanted, rtol=1e-12, atol=0.0)
    below = calculator.evaluate(bound * (1.0 - 1e-6)).max_speed
    assert np.all(below > wanted)


def test_peak_bound_is_the_searched_shortest_scale_where_it_is_given():
    calculator, design = _press(8)
    bound = calculator.peak_bound(design.limits)
    searched = bisect_duration(calculator, design.limits)
    given = bound > 0.0
    assert given.any() and not given.all()  # speed binds for some motors, not all
    assert np.allclose(bound[given], searched[given], rtol=1e-12, atol=0.0)
