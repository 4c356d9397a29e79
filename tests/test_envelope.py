"""Completion of the speed-torque regions of motors given by their ratings only.

The expected values are the rules written out by hand (straight lines through the rated
point and the max-speed point) and closed forms of the trapezoid, not the code's output.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from scipy.optimize import brentq

from sizer.envelope import (
    DEFAULT_ENVELOPE,
    ENVELOPE_RULES,
    RegionTable,
    continuous_region,
    intermittent_region,
)
from sizer.io import bundled_catalogs, load_catalog
from sizer.model.domain import Design, Limits, Load, Motor, Task
from sizer.sizing import size_design
from sizer.sizing.candidates import MotorArrays

RPM = 2 * math.pi / 60
RULES = tuple(ENVELOPE_RULES)

# a motor given by its ratings only: tau_c = 1, tau_p = 3, v_n = 100, v_max = 200 (SI)
PLAIN = Motor(id="plain", inertia=1e-4, continuous_torque=1.0, peak_torque=3.0,
              rated_speed=100.0, max_speed=200.0)


def test_the_rules_are_named_and_electrical_is_the_default():
    assert RULES == ("book", "linear", "linear_intermittent", "electrical")
    assert DEFAULT_ENVELOPE == "electrical"
    assert Design(task=Task(1.0, 1.0), load=Load(1.0)).limits.envelope == "electrical"
    # a motor without its winding's data is completed as by `linear` (issue 35)
    assert continuous_region(PLAIN, "electrical") == continuous_region(PLAIN, "linear")
    assert intermittent_region(PLAIN, "electrical") == intermittent_region(PLAIN, "linear")


def test_book_keeps_the_rectangles_up_to_the_rated_speed():
    assert continuous_region(PLAIN, "book") == ((0.0, 1.0), (100.0, 1.0))
    assert intermittent_region(PLAIN, "book") == ((0.0, 3.0), (100.0, 3.0))
    assert continuous_region(PLAIN) == continuous_region(PLAIN, "book")  # no rule: no completion


def test_linear_falls_from_the_rated_corner_to_max_speed():
    # intermittent: tau_p at v_n down to tau_c at v_max; continuous: tau_c down to
    # tau_c v_n / v_max = 0.5 (the rated power 100 W at 200 rad/s)
    assert intermittent_region(PLAIN, "linear") == ((0.0, 3.0), (100.0, 3.0), (200.0, 1.0))
    assert continuous_region(PLAIN, "linear") == ((0.0, 1.0), (100.0, 1.0), (200.0, 0.5))
    assert continuous_region(PLAIN, "linear_intermittent") == ((0.0, 1.0), (100.0, 1.0))
    assert intermittent_region(PLAIN, "linear_intermittent") == intermittent_region(
        PLAIN, "linear")


def test_region_values_between_the_corners():
    arrays = MotorArrays.of([PLAIN], "linear")
    speed = np.array([[0.0, 50.0, 100.0, 150.0, 200.0, 201.0]])
    assert arrays.intermittent.limit(speed)[0] == pytest.approx([3, 3, 3, 2, 1, 0])
    assert arrays.continuous.limit(speed)[0] == pytest.approx([1, 1, 1, 0.75, 0.5, 0])
    assert arrays.speed_limit == pytest.approx([200.0])
    assert arrays.continuous.max_speed == pytest.approx([200.0])


@pytest.mark.parametrize("rule", RULES)
def test_without_max_speed_every_rule_keeps_the_rectangles(rule):
    for motor in (replace(PLAIN, max_speed=None), replace(PLAIN, max_speed=100.0)):
        assert continuous_region(motor, rule) == ((0.0, 1.0), (100.0, 1.0))
        assert intermittent_region(motor, rule) == ((0.0, 3.0), (100.0, 3.0))
        assert bool(MotorArrays.of([motor], rule).is_rectangular[0])


@pytest.mark.parametrize("rule", RULES)
def test_a_catalog_curve_is_never_completed(rule):
    motor = replace(PLAIN, continuous_curve=((0.0, 1.2), (150.0, 0.8)),
                    intermittent_curve=((10.0, 2.5), (120.0, 2.0)))
    assert continuous_region(motor, rule) == ((0.0, 1.2), (150.0, 0.8))
    assert intermittent_region(motor, rule) == ((0.0, 2.5), (10.0, 2.5), (120.0, 2.0))


def test_only_the_missing_region_is_completed():
    motor = replace(PLAIN, continuous_curve=((0.0, 1.2), (150.0, 0.8)))
    assert intermittent_region(motor, "linear") == ((0.0, 3.0), (100.0, 3.0), (200.0, 1.0))


def test_an_unknown_rule_is_refused():
    with pytest.raises(ValueError, match="linear_intermittent"):
        continuous_region(PLAIN, "flat")  # type: ignore[arg-type]


def test_completed_regions_are_not_rectangles_so_eq_6_2_is_not_used():
    book, linear = MotorArrays.of([PLAIN], "book"), MotorArrays.of([PLAIN], "linear")
    assert book.is_rectangular.tolist() == [True]
    assert linear.is_rectangular.tolist() == [False]
    half = MotorArrays.of([PLAIN], "linear_intermittent")
    assert half.is_rectangular.tolist() == [False]  # the regions end at different speeds
    assert linear.subset(np.array([0])).envelope == "linear"


def _all_bundled_motors():
    return [m for name in bundled_catalogs() for m in load_catalog(name)]


@pytest.mark.parametrize("rule", RULES)
def test_bundled_regions_fall_with_speed_and_continuous_stays_under_intermittent(rule):
    motors = _all_bundled_motors()
    arrays = MotorArrays.of(motors, rule)
    for motor in motors:
        for region in (continuous_region(motor, rule), intermittent_region(motor, rule)):
            speeds, torques = np.array(region).T
            assert np.all(np.diff(speeds) > 0), motor.id
            assert np.all(np.diff(torques) <= 0), motor.id  # never rising with speed
    top = np.maximum(arrays.intermittent.max_speed, arrays.continuous.max_speed)
    speed = top[:, None] * np.linspace(0.0, 1.0, 201)[None, :]
    assert np.all(arrays.continuous.limit(speed) <= arrays.intermittent.limit(speed) + 1e-12)


def test_linear_reaches_max_speed_for_every_servo_with_a_max_speed_above_rated():
    for motor in _all_bundled_motors():
        arrays = MotorArrays.of([motor], "linear")
        if motor.intermittent_curve is None and motor.max_speed is not None:
            assert arrays.speed_limit[0] == pytest.approx(motor.max_speed), motor.id
        if motor.id == "1FT7044-AK7":  # a written curve: 9000 rpm is mechanical only
            assert arrays.speed_limit[0] == pytest.approx(6000 * RPM)


# ------------------------------------------------------------------ sizing above v_n

SGM7J_04A = {m.id: m for m in load_catalog("yaskawa-sgm7j")}["SGM7J-04A"]
J_LOAD = 1.0e-4           # kg*m^2, direct drive
T_MOVE, DWELL = 0.1, 0.3  # s
V_PEAK = 4000 * RPM       # the trapezoid's top speed, above the rated 3000 rpm
H = V_PEAK * T_MOVE / 1.5  # trapezoid alpha = 1/3: C_v = 1.5


def _design(envelope, thermal_speed="max", duration=T_MOVE):
    return Design(task=Task(H, duration, dwell=DWELL), load=Load(J_LOAD),
                  laws=("trapezoidal(alpha=1/3)",), motors=(SGM7J_04A,),
                  limits=Limits(thermal_speed=thermal_speed, envelope=envelope))


def _linear_limits(speed):
    """SGM7J-04A under 'linear', by hand: 4.46 -> 1.27 N*m and 1.27 -> 0.635 N*m."""
    share = (speed - 3000 * RPM) / (3000 * RPM)
    return 4.46 - (4.46 - 1.27) * share, 1.27 - (1.27 - 1.27 / 2) * share


def test_a_yaskawa_motor_at_4000_rpm_is_feasible_with_linear_and_not_with_book():
    J_t = SGM7J_04A.inertia + J_LOAD
    torque = J_t * 4.5 * H / T_MOVE**2          # C_a = 4.5, flat during the acceleration
    rms = J_t * 4.5 * math.sqrt(2 / 3) * H / T_MOVE**2 * math.sqrt(T_MOVE / (T_MOVE + DWELL))
    peak_limit, continuous_limit = _linear_limits(V_PEAK)

    result = size_design(_design("linear")).results[0]
    assert result.feasible, result.reason
    checks = {c.name: c for c in result.checks}
    assert checks["speed"].value == pytest.approx(V_PEAK, rel=1e-9)
    assert checks["speed"].limit == pytest.approx(6000 * RPM)
    # the worst point of the acceleration is its end, at the top speed
    assert checks["peak"].value == pytest.approx(torque / peak_limit, rel=1e-6)
    assert checks["rms"].value == pytest.approx(rms, rel=1e-9)
    assert checks["rms"].limit == pytest.approx(continuous_limit, rel=1e-9)

    book = size_design(_design("book")).results[0]
    assert not book.feasible
    assert "speed" in book.reason and "thermal_speed" in book.reason

    # only the intermittent region extended: the RMS point at the top speed is outside
    # the continuous region, but at the cycle's mean speed it is inside
    half = size_design(_design("linear_intermittent")).results[0]
    assert not half.feasible and "thermal_speed" in half.reason and "peak" not in half.reason
    assert size_design(_design("linear_intermittent", "mean")).results[0].feasible


def test_the_rule_is_stated_in_the_notes():
    for rule in RULES:
        notes = size_design(_design(rule)).notes
        assert [n for n in notes if n.startswith(f"envelope {rule}:")], notes
    assert any("rectangular" in n for n in size_design(_design("book")).notes)


def test_shortest_move_with_a_falling_region_matches_an_independent_root():
    """T_min by the engine (bisection) against the roots of each limit, found here."""
    J_t = SGM7J_04A.inertia + 4.0e-4  # heavier load: the peak torque binds above v_n
    h = 40.0

    def peak_slack(T):
        speed = 1.5 * h / T
        if speed > 6000 * RPM:
            return -1.0
        return _linear_limits(max(speed, 3000 * RPM))[0] - J_t * 4.5 * h / T**2

    def rms_slack(T):
        speed = 1.5 * h / T
        rms = J_t * 4.5 * math.sqrt(2 / 3) * h / T**2 * math.sqrt(T / (T + DWELL))
        return _linear_limits(max(speed, 3000 * RPM))[1] - rms

    speed_bound = 1.5 * h / (6000 * RPM)
    peak_bound = brentq(peak_slack, speed_bound * (1 + 1e-12), 10.0, xtol=1e-15)
    rms_bound = brentq(rms_slack, speed_bound * (1 + 1e-12), 10.0, xtol=1e-15)
    expected = max(speed_bound, peak_bound, rms_bound)
    assert 1.5 * h / expected > 3000 * RPM  # the binding point is on the falling line

    design = Design(task=Task(h, None, dwell=DWELL), load=Load(4.0e-4),
                    laws=("trapezoidal(alpha=1/3)",), motors=(SGM7J_04A,),
                    limits=Limits(envelope="linear"))
    result = size_design(design).results[0]
    assert result.feasible
    assert result.duration == pytest.approx(expected, rel=1e-9)

    def book_rms_slack(T):
        return 1.27 - J_t * 4.5 * math.sqrt(2 / 3) * h / T**2 * math.sqrt(T / (T + DWELL))

    book_expected = max(1.5 * h / (3000 * RPM), math.sqrt(J_t * 4.5 * h / 4.46),
                        brentq(book_rms_slack, 1e-3, 10.0, xtol=1e-15))
    book = size_design(replace(design, limits=Limits(envelope="book"))).results[0]
    assert book.duration == pytest.approx(book_expected, rel=1e-9)
    assert book.duration > expected


def test_region_table_of_completed_and_written_curves_together():
    motors = [PLAIN, replace(PLAIN, id="curve", intermittent_curve=((0.0, 2.0), (50.0, 1.0)))]
    table = RegionTable([intermittent_region(m, "linear") for m in motors])
    assert table.limit(np.array([[150.0], [25.0]]))[:, 0] == pytest.approx([2.0, 1.5])
    assert table.max_speed == pytest.approx([200.0, 50.0])


def test_the_speed_torque_diagram_draws_the_completed_regions():
    from sizer.sizing.samples import task_curve

    curve = task_curve(_design("linear"), SGM7J_04A, "trapezoidal(alpha=1/3)", T_MOVE)
    assert curve.intermittent_region == ((0.0, 4.46), (3000 * RPM, 4.46), (6000 * RPM, 1.27))
    assert curve.continuous_region[-1] == pytest.approx((6000 * RPM, 1.27 / 2))
    book = task_curve(_design("book"), SGM7J_04A, "trapezoidal(alpha=1/3)", T_MOVE)
    assert book.intermittent_region == ((0.0, 4.46), (3000 * RPM, 4.46))


def test_region_lookup_is_exact_at_corners_and_bounded_in_memory():
    """The segment of every speed equals the brute-force count of corner speeds <= it
    (corners included), and the lookup needs memory motors x samples, not x curve points
    (the brute force would take 150 MB here)."""
    import tracemalloc

    from sizer.envelope.region import RegionTable

    rng = np.random.default_rng(7)
    curves = []
    for _ in range(1000):
        speeds = np.unique(np.concatenate(([0.0], rng.uniform(0.0, 600.0, 299))))
        curves.append(tuple(zip(speeds, rng.uniform(0.1, 5.0, len(speeds)), strict=True)))
    table = RegionTable(curves)
    speed = rng.uniform(0.0, 700.0, (1000, 500))
    speed[:, :10] = table.speeds[:, :10]  # exactly on corners
    expected = (table.speeds[:100, None, 1:-1] <= speed[:100, :, None]).sum(axis=-1)
    tracemalloc.start()
    index = table._segment(speed)
    limit = table.limit(speed)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    assert np.array_equal(index[:100], expected)
    assert peak < 60e6, peak
    rows = np.arange(1000)[:, None]
    s0, s1 = table.speeds[rows, index], table.speeds[rows, index + 1]
    inside = speed <= table.max_speed[:, None]
    assert np.all((s0 <= speed) | ~inside) and np.all((speed <= s1) | ~inside)
    assert np.all(limit[~inside] == 0.0)


def test_a_held_segment_gives_the_limit_of_the_table_to_the_bit():
    """HeldSegments (the root finders' lookup near a speed) against the table's own
    limit_clipped of the same rows: equal to the bit at speeds on the held segment, off it
    (the search again), exactly at corners, past the region's end and below zero speed;
    curves of different lengths (padded rows) and rectangles together."""
    from sizer.envelope.region import RegionTable

    rng = np.random.default_rng(11)
    curves = [((0.0, 2.0), (300.0, 2.0))]
    for count in (2, 3, 5, 40):
        for _ in range(20):
            speeds = np.unique(np.concatenate(([0.0], rng.uniform(1.0, 600.0, count - 1))))
            curves.append(tuple(zip(speeds, rng.uniform(0.1, 5.0, len(speeds)), strict=True)))
    table = RegionTable(curves)
    n = len(table)
    start = rng.uniform(0.0, 1.1, n) * table.max_speed
    held = table.held_at(start)
    for factor in (1.0, 1.0 + 1e-9, 0.97, 1.3, 0.2, 3.0, -1.0):
        rows = np.flatnonzero(rng.uniform(size=n) < 0.7)
        speed = start[rows] * factor
        speed[:3] = table.speeds[rows[:3], 1]  # exactly on a corner
        np.testing.assert_array_equal(held.limit_clipped(speed, rows),
                                      table.take(rows).limit_clipped(speed))
