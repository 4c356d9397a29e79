"""A machine cycle of segments (issue 12): the segment engine against the single-law
engine on the task shorthand, closed forms of the RMS over segments, time scaling."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from sizer.laws import make_law
from sizer.mechanics import Drive
from sizer.model.cycle import Cycle, Dwell, Move, Run, SegmentLoad, ShareRule, from_task
from sizer.model.domain import (
    Design,
    Limits,
    Load,
    Motor,
    RatioChoice,
    Stage,
    Task,
    Transmission,
)
from sizer.sizing import size_design
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.cycle import SegmentCycle, shorthand_task
from sizer.sizing.move import CycleCalculator

RPM = math.pi / 30.0
FIELDS = ("max_speed", "peak_torque", "peak_ratio", "rms_torque", "thermal_speed",
          "load_speed", "load_acceleration", "load_torque")


def curved_motors(count: int) -> tuple[Motor, ...]:
    out = []
    for i in range(count):
        tau = 0.5 * 40.0 ** (i / max(count - 1, 1))
        v_n = 3000.0 * RPM
        out.append(Motor(f"m{i}", 2e-5 * tau**1.3, tau, 3.0 * tau, v_n, max_speed=2 * v_n,
                         intermittent_curve=((0.0, 3 * tau), (0.8 * v_n, 3 * tau),
                                             (1.4 * v_n, 2.1 * tau), (2 * v_n, tau)),
                         continuous_curve=((0.0, 1.05 * tau), (v_n, tau), (2 * v_n, 0.5 * tau))))
    return tuple(out)


def real_design(**task) -> Design:
    """Friction, damping, a constant load, an efficiency of 0.9 and a ratio choice."""
    return Design(Task(1.2, **task), Load(0.3, damping=0.02, friction=0.3, torque=0.8),
                  Transmission((Stage("gearbox", 5.0, 0.9, 1e-4),)),
                  laws=("cycloidal", "trapezoidal(alpha=1/3)", "poly5"),
                  motors=curved_motors(5), limits=Limits(torque_margin=0.1),
                  ratio_choice=RatioChoice(ratios=(3.0, 5.0, 8.0)))


@pytest.mark.parametrize("spec", ["cycloidal", "trapezoidal(alpha=1/4)", "poly7",
                                  "modified_sinusoidal", "double_s(alpha=1/3, beta=1/4)"])
@pytest.mark.parametrize("rule", ["max", "rms", "mean"])
def test_segments_of_the_shorthand_equal_the_single_law_engine(spec, rule):
    task = Task(1.2, None, dwell=0.2, return_move=True)
    design = real_design(duration=None, dwell=0.2, return_move=True)
    motors = MotorArrays.of(design.motors, design.limits.envelope)
    drive = Drive(design.load, design.transmission)
    law = make_law(spec)
    single = CycleCalculator(None, task, drive, motors, rule, law=law)
    segments = SegmentCycle(from_task(task), law, drive, motors, rule)
    T = np.linspace(0.15, 1.5, len(design.motors))
    a, b = single.evaluate(T), segments.evaluate(T)
    for name in FIELDS:
        np.testing.assert_allclose(getattr(b, name), getattr(a, name), rtol=1e-12,
                                   err_msg=name)
    np.testing.assert_allclose(b.duration, 2 * (T + 0.2), rtol=1e-15)


@pytest.mark.parametrize("duration", [None, 0.6])
def test_a_dwell_split_in_two_changes_nothing(duration):
    """Sized through the segment engine (the split dwell is no shorthand) and through the
    single-law engine: the same verdicts, T_min (as cycle times) and torques."""
    design = real_design(duration=duration, dwell=0.3, return_move=True)
    h = design.task.displacement
    split = Cycle((Move(h, duration), Dwell(0.1), Dwell(0.2), Move(-h, duration), Dwell(0.3)),
                  closed=True)
    assert shorthand_task(split) is None
    plain, cycled = size_design(design), size_design(replace(design, cycle=split))
    by_key = {(r.motor, r.law): r for r in plain.results}
    assert len(by_key) == len(cycled.results) == 15
    for r in cycled.results:
        x = by_key[(r.motor, r.law)]
        assert r.feasible == x.feasible
        if not x.feasible:
            continue
        assert r.duration == pytest.approx(2 * (x.duration + 0.3), rel=1e-9)
        assert r.peak_torque == pytest.approx(x.peak_torque, rel=1e-9)
        assert r.rms_torque == pytest.approx(x.rms_torque, rel=1e-9)


def test_the_expanded_task_is_sized_as_the_task():
    design = real_design(duration=None, dwell=0.3, return_move=True)
    expanded = replace(from_task(design.task), shorthand=None)
    assert shorthand_task(expanded) == design.task
    a, b = size_design(design), size_design(replace(design, cycle=expanded))
    assert [(r.motor, r.law, r.duration, r.rms_torque) for r in a.results] == \
        [(r.motor, r.law, r.duration, r.rms_torque) for r in b.results]


def inertial_cycle_parts():
    """Two moves of different laws and a payload, a dwell holding a torque: ideal gearbox,
    rectangular regions."""
    motor = Motor("m", 1e-3, 5.0, 15.0, 300.0)
    load = Load(0.2)
    transmission = Transmission((Stage("gearbox", 10.0, 1.0, 2e-4),))
    cycle = Cycle((Move(1.0, 0.5, law="cycloidal"),
                   Dwell(0.25, load=SegmentLoad(torque=4.0)),
                   Move(-1.0, None, law="poly5", load=SegmentLoad(inertia=0.1)),
                   Dwell(0.25)), share=ShareRule.EQUAL)
    return motor, load, transmission, cycle


def test_rms_over_a_cycle_is_the_sum_of_the_segments_integrals():
    motor, load, transmission, cycle = inertial_cycle_parts()
    motors = MotorArrays.of([motor], "book")
    calc = SegmentCycle(cycle, None, Drive(load, transmission), motors)
    s = np.array([0.4])
    m = calc.evaluate(s)
    K = 10.0

    def j_t(inertia):
        return 1e-3 + 2e-4 + inertia / K**2

    c1, c2 = make_law("cycloidal").coefficients, make_law("poly5").coefficients
    assert c1.C_a_rms == pytest.approx(math.sqrt(2 * math.pi**2))  # (2 pi)^2 / 2
    first = (j_t(0.2) * K * 1.0 * c1.C_a_rms / 0.5**2) ** 2 * 0.5
    second = (j_t(0.3) * K * 1.0 * c2.C_a_rms / 0.4**2) ** 2 * 0.4
    hold = (4.0 / K) ** 2 * 0.25
    total = 0.5 + 0.25 + 0.4 + 0.25
    assert m.duration[0] == pytest.approx(total, rel=1e-15)
    assert m.rms_torque[0] == pytest.approx(math.sqrt((first + second + hold) / total), rel=1e-12)
    peak = max(j_t(0.2) * K * c1.C_a / 0.25, j_t(0.3) * K * c2.C_a / 0.16, 4.0 / K)
    assert m.peak_torque[0] == pytest.approx(peak, rel=1e-12)


def test_doubling_the_free_durations_divides_the_inertial_torques_by_four():
    motor, load, transmission, _ = inertial_cycle_parts()
    cycle = Cycle((Move(1.0, None, law="cycloidal"), Dwell(0.25),
                   Move(-0.5, None, law="poly5"), Dwell(0.25)), share=ShareRule.DISPLACEMENT)
    calc = SegmentCycle(cycle, None, Drive(load, transmission), MotorArrays.of([motor], "book"))
    a, b = calc.figures(np.array([0.3])), calc.figures(np.array([0.6]))
    for x, y in zip(a, b, strict=True):
        if x.duration[0] != y.duration[0]:
            assert y.duration[0] == pytest.approx(2 * x.duration[0], rel=1e-15)
            assert y.peak_torque[0] == pytest.approx(x.peak_torque[0] / 4, rel=1e-12)
    assert a[2].duration[0] == pytest.approx(0.5 * a[0].duration[0], rel=1e-15)


def test_a_run_has_the_closed_form_torque_of_its_constant_speed():
    motor = Motor("m", 1e-3, 5.0, 15.0, 300.0, damping=1e-4)
    load = Load(0.2, damping=0.05, friction=0.4, torque=1.0)
    transmission = Transmission((Stage("gearbox", 10.0, 0.8, 2e-4),))
    cycle = Cycle((Run(2.0, 0.5, load=SegmentLoad(torque=3.0)),))
    calc = SegmentCycle(cycle, None, Drive(load, transmission), MotorArrays.of([motor], "book"))
    f = calc.figures(np.array([1.0]))[0]
    u = 0.05 * 2.0 + 0.4 + 4.0  # the load's torque along the motion (opposes it)
    torque = 1e-4 * 10.0 * 2.0 + u / (10.0 * 0.8)
    assert f.peak_torque[0] == pytest.approx(torque, rel=1e-13)
    assert f.torque_square[0] == pytest.approx(torque**2 * 0.5, rel=1e-13)
    assert f.energy[0] == pytest.approx(torque * 20.0 * 0.5, rel=1e-13)
    assert f.max_speed[0] == pytest.approx(20.0)


def test_the_minimized_cycle_is_feasible_at_t_min_and_not_just_below():
    _, _, transmission, cycle = inertial_cycle_parts()
    free = Cycle(tuple(replace(s, duration=None) if isinstance(s, Move) else s
                       for s in cycle.segments), share=ShareRule.DISPLACEMENT)
    design = Design(Task(1.0, None), Load(0.2, friction=0.2), transmission,
                    laws=("cycloidal",), motors=curved_motors(4), cycle=free)
    result = size_design(design)
    feasible = [r for r in result.results if r.feasible]
    assert feasible
    from sizer.sizing.checks import evaluate_checks, worst_slack

    motors = MotorArrays.of(design.motors, design.limits.envelope)
    drive = Drive(design.load, transmission)
    calc = SegmentCycle(free, make_law("cycloidal"), drive, motors)
    durations = {r.motor: r.duration for r in feasible}
    index = np.array([i for i, m in enumerate(design.motors) if m.id in durations])
    sub = calc.take(index)
    T = np.array([durations[design.motors[i].id] for i in index])
    s = (T - 0.5) / 2.0  # free moves of weights 1 and 1 (|h| = 1 each); dwells 0.25 + 0.25
    at = worst_slack(evaluate_checks(sub.evaluate(s), sub.motors, sub.drive, design.limits))
    below = worst_slack(evaluate_checks(sub.evaluate(s * (1 - 1e-7)), sub.motors, sub.drive,
                                        design.limits))
    assert np.all(at >= -1e-9)
    assert np.all(below < 0.0)


def test_the_breakdown_of_a_cycle_per_segment():
    """Ideal gearbox, Coulomb friction only: over a rest-to-rest move the motor's work is
    the friction's, F |h| (the kinetic energy returns); shares of tau^2 sum to one; the
    times add up; the cycloidal law joins a dwell without an acceleration step, the
    trapezoid with one of its acceleration h C_a / T^2."""
    from sizer.sizing.samples import segment_breakdown

    motor = Motor("m", 1e-3, 5.0, 15.0, 300.0)
    design = Design(Task(1.0, None), Load(0.2, friction=0.5),
                    Transmission((Stage("gearbox", 10.0, 1.0, 2e-4),)), laws=("cycloidal",),
                    motors=(motor,),
                    cycle=Cycle((Move(1.0, 0.5, law="cycloidal", name="out"), Dwell(0.25),
                                 Move(-1.0, 0.4, law="trapezoidal(alpha=1/4)", name="back"),
                                 Dwell(0.3, load=SegmentLoad(torque=2.0)))))
    b = segment_breakdown(design, motor, "cycloidal", 1.45)
    assert [r.name for r in b.rows] == ["out", "dwell", "back", "dwell"]
    assert [t for r in b.rows for t in (r.start, r.end)] == pytest.approx(
        [0, 0.5, 0.5, 0.75, 0.75, 1.15, 1.15, 1.45], abs=1e-15)
    assert b.rows[0].energy == pytest.approx(0.5 * 1.0, rel=1e-12)
    assert b.rows[2].energy == pytest.approx(0.5 * 1.0, rel=1e-12)
    assert b.rows[1].energy == 0.0
    assert sum(r.rms_share for r in b.rows) == pytest.approx(1.0, rel=1e-14)
    assert b.rows[3].peak_torque == pytest.approx(2.0 / 10.0, rel=1e-15)
    assert b.rows[0].acceleration_step == 0.0 and b.rows[1].acceleration_step == 0.0
    C_a = 1.0 / (0.25 * 0.75)
    assert b.rows[2].acceleration_step == pytest.approx(-C_a / 0.4**2, rel=1e-12)
    assert b.rows[3].acceleration_step == pytest.approx(-C_a / 0.4**2, rel=1e-12)


def test_minimizing_one_named_segment_keeps_the_others():
    """The press dwell's neighbours fixed; the return move minimized: its T_min is the
    eq. (6.2) peak bound of poly5 alone (ideal gearbox, inertial load, rectangular regions,
    the peak binds: a large continuous torque)."""
    motor = Motor("m", 1e-3, 14.0, 15.0, 300.0)
    transmission = Transmission((Stage("gearbox", 10.0, 1.0, 2e-4),))
    cycle = Cycle((Move(1.0, 0.5, law="cycloidal"), Dwell(0.25),
                   Move(-1.0, 0.3, law="poly5", name="back"), Dwell(0.25)),
                  minimize_segment="back")
    design = Design(Task(1.0, None), Load(0.2), transmission, laws=("cycloidal",),
                    motors=(motor,), limits=Limits(envelope="book"), cycle=cycle)
    (result,) = size_design(design).results
    J_t = 1e-3 + 2e-4 + 0.2 / 100.0
    C_a = make_law("poly5").coefficients.C_a  # 10 / sqrt(3)
    assert C_a == pytest.approx(10 / math.sqrt(3), rel=1e-12)
    T_back = math.sqrt(J_t * 10.0 * 1.0 * C_a / 15.0)
    assert result.feasible
    assert result.duration == pytest.approx(0.5 + 0.25 + T_back + 0.25, rel=1e-9)


FLYING_SAW = Path(__file__).resolve().parent.parent / "examples" / "flying-saw.yaml"


def test_the_flying_saw_meets_the_line_speed_and_its_t_min():
    """examples/flying-saw.yaml: moves between boundary speeds sized exactly. The best
    pair's curve reaches the line's 0.5 m/s at the cut's start and leaves it at its end
    (to 1e-12), the cut's torque is its closed form, and the minimized cycle is feasible
    at T_min and not 1e-7 below it."""
    from sizer.api import load
    from sizer.sizing.checks import evaluate_checks, worst_slack
    from sizer.sizing.samples import scale_of, task_curve

    design = load(FLYING_SAW)
    best = size_design(design).results[0]
    assert best.feasible
    curve = task_curve(design, best.motor_object, best.law_object, best.duration)
    (_, _, end), (_, cut_start, cut_end) = curve.segments[0], curve.segments[1]
    assert end == cut_start
    for t in (cut_start, cut_end):
        at = np.flatnonzero(np.isclose(curve.time, t, rtol=0, atol=1e-15))
        assert np.allclose(curve.load_speed[at], 0.5, rtol=1e-12, atol=0)
    K = 3.0 / 0.03
    cut = (30.0 + 120.0) / (K * 0.95 * 0.95)  # friction and cut force through two stages
    assert np.allclose(curve.motor_torque[(curve.time > cut_start) & (curve.time < cut_end)],
                       cut, rtol=1e-12)
    motors = MotorArrays.of([best.motor_object], design.limits.envelope)
    calc = SegmentCycle(design.cycle, best.law_object, Drive(design.load, design.transmission),
                        motors)
    s = np.array([scale_of(design, best.duration)])
    at = worst_slack(evaluate_checks(calc.evaluate(s), calc.motors, calc.drive, design.limits,
                                     True))
    below = worst_slack(evaluate_checks(calc.evaluate(s * (1 - 1e-7)), calc.motors,
                                        calc.drive, design.limits, True))
    assert at[0] >= -1e-9 and below[0] < 0.0


def test_moves_meet_their_boundary_accelerations_and_joins_without_a_step():
    """Two poly5 moves joined at 60 deg/s and 200 deg/s^2: the curve reaches both at the
    join (to 1e-12 of the scale) and the breakdown marks no step there; the move back
    (cycloidal, from rest to rest) marks none either."""
    from sizer.sizing.samples import segment_breakdown, task_curve

    deg = math.pi / 180
    cycle = Cycle((Move(90 * deg, 0.3, law="poly5", end_speed=60 * deg,
                        end_acceleration=200 * deg, name="a"),
                   Move(30 * deg, 0.2, law="poly5", start_speed=60 * deg,
                        start_acceleration=200 * deg, name="b"),
                   Move(-120 * deg, 0.4, law="cycloidal", name="back"), Dwell(0.2)))
    motor = curved_motors(1)[0]
    design = Design(Task(1.0, None), Load(0.05, friction=0.3),
                    Transmission((Stage("gearbox", 10.0, 0.9, 0.0),)), laws=("cycloidal",),
                    motors=(motor,), cycle=cycle)
    curve = task_curve(design, motor, "cycloidal", 1.1)
    join = np.flatnonzero(np.isclose(curve.time, 0.3, rtol=0, atol=1e-15))
    assert len(join) == 2  # the end of a, the start of b
    assert np.allclose(curve.load_speed[join], 60 * deg, rtol=1e-12)
    assert np.allclose(curve.load_acceleration[join], 200 * deg, rtol=1e-12)
    rows = segment_breakdown(design, motor, "cycloidal", 1.1).rows
    assert [r.acceleration_step for r in rows] == [0.0, 0.0, 0.0, 0.0]
    steps = Cycle((replace(cycle.segments[0], end_acceleration=0.0),
                   replace(cycle.segments[1], start_acceleration=200 * deg),
                   *cycle.segments[2:]))
    rows = segment_breakdown(replace(design, cycle=steps), motor, "cycloidal", 1.1).rows
    assert rows[1].acceleration_step == pytest.approx(200 * deg, rel=1e-12)


def test_a_step_of_the_acceleration_at_a_join_makes_the_jerk_unbounded():
    """poly5 moves are jerk-bounded (C_j = 60): joined at the same acceleration the cycle's
    jerk is finite, 60 h/T^3 at most; with a step at the join it is an impulse (inf)."""
    deg = math.pi / 180
    first = Move(90 * deg, 0.3, law="poly5", end_speed=60 * deg, end_acceleration=200 * deg)
    second = Move(30 * deg, 0.2, law="poly5", start_speed=60 * deg,
                  start_acceleration=200 * deg)
    back = Move(-120 * deg, 0.4, law="poly5")
    motors = MotorArrays.of(curved_motors(1), "linear")
    drive = Drive(Load(0.05), Transmission((Stage("gearbox", 10.0, 1.0, 0.0),)))
    smooth = SegmentCycle(Cycle((first, second, back, Dwell(0.2))), None, drive, motors)
    jerk = smooth.evaluate(np.array([1.0])).load_jerk[0]
    assert np.isfinite(jerk) and jerk >= 60 * 120 * deg / 0.4**3 * (1 - 1e-12)
    stepped = SegmentCycle(Cycle((first, replace(second, start_acceleration=0.0), back,
                                  Dwell(0.2))), None, drive, motors)
    assert stepped.evaluate(np.array([1.0])).load_jerk[0] == np.inf


def test_the_bound_of_moves_with_boundary_speeds_is_the_closed_form_of_the_cubic():
    """Two cubic moves meet a run at speed v (inertial load, ideal gearbox, rectangular
    region). On a cubic from rest to s1 = v T / h, q'' is 6 - 2 s1 at its start and
    -6 + 4 s1 at its end, so J_t K |a| <= A' (A' the torque limit) holds for 1/T up to
    (2 v + sqrt(4 v^2 + 24 h A)) / (12 h), A = A' / (J_t K), where A >= 2 v^2 / (3 h);
    the move leaving the run is its mirror. The segment engine's bound on the scale (the
    moves' duration) is that threshold (the rest-to-rest return, twice as long, binds
    less), and T_min is the bound."""
    from sizer.sizing.shortest_duration import minimum_duration

    h, v, K, J_m, J_l, tau_p = 0.2, 0.5, 10.0, 1e-3, 0.2, 15.0
    cycle = Cycle((Move(h, None, law="poly3", end_speed=v), Run(v, 0.2),
                   Move(h, None, law="poly3", start_speed=v),
                   Move(-(2 * h + 0.1), None, law="poly5", weight=2.0), Dwell(0.1)),
                  share=ShareRule.WEIGHTS, closed=True)
    motor = Motor("m", J_m, 5.0, tau_p, 3000.0)
    drive = Drive(Load(J_l), Transmission((Stage("gearbox", K, 1.0, 0.0),)))
    limits = Limits(torque_margin=0.1)
    calc = SegmentCycle(cycle, None, drive, MotorArrays.of([motor], "book"))
    a_max = 0.9 * tau_p / ((J_m + J_l / K**2) * K)
    assert a_max >= 2 * v * v / (3 * h)
    T = 12 * h / (2 * v + math.sqrt(4 * v * v + 24 * h * a_max))
    c = make_law("poly5").coefficients
    assert c.C_a * (2 * h + 0.1) / (2 * T) ** 2 < a_max  # the return (weight 2) does not bind
    bound = calc.peak_bound(limits)
    assert bound[0] == pytest.approx(T, rel=1e-12)
    solution = minimum_duration(calc, limits)
    assert solution.feasible[0] and solution.duration[0] == pytest.approx(T, rel=1e-12)
    peak = calc.evaluate(np.array([T])).peak_torque[0]
    assert peak == pytest.approx(0.9 * tau_p, rel=1e-12)


def test_first_crossing_brackets_the_first_sign_change_to_its_width():
    """Rows of cubics: the returned end is where f >= 0, within 1e-13 of the root
    (closed forms), and of three sign changes in the bracket the first is kept."""
    from sizer.sizing.cycle import first_crossing

    c = np.array([2.0, 3.0, 10.0])

    def f(x, rows):
        return np.where(rows == 2, (x - 1.5) * (x - 2.5) * (x - 3.2), x**3 - c[rows])

    lo, hi = np.array([0.5, 1.0, 1.0]), np.array([2.0, 2.0, 4.0])
    rows = np.arange(3)
    x = first_crossing(f, lo, hi, f(lo, rows), f(hi, rows), xtol=1e-13)
    roots = np.array([2.0 ** (1 / 3), 3.0 ** (1 / 3), 1.5])
    assert np.all(f(x, rows) >= 0.0)
    assert np.allclose(x, roots, rtol=0, atol=2e-13)


def test_a_fixed_segment_kept_from_a_parent_equals_its_own_evaluation():
    """The figures of a fixed-duration move are kept per set of candidates; a subset made
    by take() reads its parent's, and they equal those of a fresh calculator on the
    subset's motors (friction, an efficiency, curved regions)."""
    cycle = Cycle((Move(0.5, 0.3, law="cycloidal"), Dwell(0.1),
                   Move(-0.5, None, law="poly5"), Dwell(0.2)), share=ShareRule.EQUAL)
    drive = Drive(Load(0.2, friction=0.3, torque=0.5),
                  Transmission((Stage("gearbox", 8.0, 0.9, 1e-4),)))
    motors = MotorArrays.of(curved_motors(5), "linear")
    calc = SegmentCycle(cycle, make_law("cycloidal"), drive, motors)
    s = np.linspace(0.2, 0.6, 5)
    calc.evaluate(s)  # keeps the fixed move's figures
    index = np.array([4, 1, 3])
    kept = calc.take(index).figures(s[index])[0]
    fresh = SegmentCycle(cycle, make_law("cycloidal"), drive,
                         motors.subset(index)).figures(s[index])[0]
    for name in ("peak_torque", "peak_ratio", "torque_square", "max_speed", "energy"):
        assert np.allclose(getattr(kept, name), getattr(fresh, name), rtol=1e-14, atol=0)


def test_a_cycle_no_scale_passes_is_infeasible_with_boundary_speeds_and_no_warning():
    """Friction above the motor's peak torque: the rest-to-rest move's bound is
    inf (no duration passes), the boundary moves' bound is not sought there (no
    evaluation at an infinite scale), and no scale is feasible."""
    import warnings

    from sizer.sizing.shortest_duration import minimum_duration

    cycle = Cycle((Move(0.2, None, law="poly3", end_speed=0.5), Run(0.5, 0.2),
                   Move(0.2, None, law="poly3", start_speed=0.5),
                   Move(-0.5, None, law="poly5"), Dwell(0.1)), share=ShareRule.EQUAL,
                  closed=True)
    drive = Drive(Load(0.2, friction=1000.0),
                  Transmission((Stage("gearbox", 10.0, 1.0, 0.0),)))
    calc = SegmentCycle(cycle, None, drive, MotorArrays.of([Motor("m", 1e-3, 5.0, 15.0,
                                                                  3000.0)], "book"))
    limits = Limits(torque_margin=0.1)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        bound = calc.peak_bound(limits)
        solution = minimum_duration(calc, limits)
    assert np.isinf(bound[0])
    assert not solution.feasible[0]


@pytest.mark.parametrize(("rule", "limit"), [("max", 300.0), ("mean", 600.0), ("rms", 600.0)])
def test_the_peak_bound_reads_the_thermal_speed_only_by_the_max_rule(rule, limit):
    """A cycloid through 5:1 (C_v = 2) on a motor whose continuous curve ends at 300 rad/s
    and intermittent curve at 600 rad/s, nothing else binding: T_min = C_v K h / limit,
    with limit the continuous end where the thermal speed is the peak speed ("max") and
    the intermittent end otherwise (the mean or RMS speed over the cycle stays far below
    300). The cycle (move, dwell split in two, return, dwell) lasts 2 (T_min + 0.5 s); its
    peak bound once read the continuous end whatever the rule."""
    motor = Motor("m", 2e-5, 1.0, 3.0, 300.0, max_speed=600.0,
                  intermittent_curve=((0.0, 3.0), (600.0, 2.0)),
                  continuous_curve=((0.0, 1.0), (300.0, 0.8)))
    design = Design(Task(1.0, None, dwell=0.5, return_move=True), Load(1e-5),
                    Transmission((Stage("gearbox", 5.0, 1.0, 0.0),)), laws=("cycloidal",),
                    motors=(motor,), limits=Limits(thermal_speed=rule))
    cycle = Cycle((Move(1.0, None), Dwell(0.1), Dwell(0.4), Move(-1.0, None), Dwell(0.5)))
    T_min = 2.0 * 5.0 * 1.0 / limit
    task, = size_design(design).results
    cycled, = size_design(replace(design, cycle=cycle)).results
    assert task.feasible and cycled.feasible
    assert task.duration == pytest.approx(T_min, rel=1e-12)
    assert cycled.duration == pytest.approx(2.0 * (T_min + 0.5), rel=1e-12)
