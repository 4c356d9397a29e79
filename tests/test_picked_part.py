"""A part picked up in a segment of a linear cycle (issue 38): its weight adds Coulomb
friction mu m g cos(incline) and gravity m g sin(incline) along the axis, with the
design's coefficient and incline, as the design's own mass does. Numbers from closed forms:
the trapezoidal law's torques are piecewise constant."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from sizer.io.cycle import weight_twice_warnings
from sizer.io.loader import load_design_data
from sizer.io.yaml_source import parse_mapping
from sizer.mechanics import Drive
from sizer.model.cycle import Cycle, Dwell, Move, SegmentLoad
from sizer.model.domain import Load, Motor, Stage, Transmission
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.cycle import SegmentCycle, segment_load

G = 9.80665
MU, INCLINE = 0.1, math.radians(30.0)
M, PART, F0 = 4.0, 2.0, 5.0  # carriage kg, part kg, the guides' given friction N
K, JM = 100.0, 1e-4  # an ideal stage of 100 rad/m, the motor's inertia kg*m^2
H, T1, T2, D1, D2 = 0.1, 0.5, 0.4, 0.2, 0.3
LAW = "trapezoidal(alpha=1/3)"
ALPHA = 1.0 / 3.0


def base_load() -> Load:
    """The carriage: friction F0 + mu M g cos(a), gravity M g sin(a) (written out)."""
    return Load(M, friction=F0 + MU * M * G * math.cos(INCLINE), torque=M * G * math.sin(INCLINE))


def part(mass: float = PART) -> SegmentLoad:
    return SegmentLoad(inertia=mass, friction_coefficient=MU, incline=INCLINE)


def cycle_of(load: SegmentLoad) -> Cycle:
    """Up 100 mm with the part in 0.5 s, rest, back empty in 0.4 s, rest."""
    return Cycle((Move(H, T1, law=LAW, load=load), Dwell(D1), Move(-H, T2, law=LAW),
                  Dwell(D2)), closed=True, linear=True)


def calculator(load: SegmentLoad) -> SegmentCycle:
    motor = Motor("m", JM, 5.0, 15.0, 600.0)
    drive = Drive(base_load(), Transmission((Stage("gearbox", K, 1.0, 0.0),)))
    return SegmentCycle(cycle_of(load), None, drive, MotorArrays.of([motor], "book"))


def test_the_segment_load_adds_the_parts_friction_and_weight():
    base = base_load()
    move = Move(H, T1, load=part())
    got = segment_load(base, move)
    assert got.inertia == M + PART
    assert got.friction == pytest.approx(base.friction + MU * PART * G * math.cos(INCLINE),
                                         rel=1e-15)
    assert got.torque == pytest.approx(base.torque + PART * G * math.sin(INCLINE), rel=1e-15)
    # the same as a carriage of M + m on the same guides
    assert got.friction == pytest.approx(F0 + MU * (M + PART) * G * math.cos(INCLINE), rel=1e-14)
    assert got.torque == pytest.approx((M + PART) * G * math.sin(INCLINE), rel=1e-14)
    # a given force adds on top; a segment without a part is the design's load itself
    pushed = segment_load(base, Move(H, T1, load=SegmentLoad(2.0, 7.0, MU, INCLINE)))
    assert pushed.torque == pytest.approx(got.torque + 7.0, rel=1e-15)
    assert segment_load(base, Move(H, T1)) is base


def test_a_rotary_segment_adds_its_inertia_and_torque_only():
    base = Load(0.02, damping=0.01, friction=0.3, torque=0.5)
    got = segment_load(base, Move(1.0, 0.3, load=SegmentLoad(inertia=0.01, torque=2.0)))
    assert (got.inertia, got.damping, got.friction, got.torque) == (0.03, 0.01, 0.3, 2.5)


def trapezoid(mass: float, force: float, h: float, T: float) -> tuple[float, float]:
    """Peak |tau| and int tau^2 dt of a trapezoidal move (alpha = 1/3): the load's
    acceleration is +-h / (alpha (1 - alpha) T^2) on the first and last thirds, 0 between;
    tau = (J_m K + mass / K) a + force / K with the constant force (friction and gravity,
    signed) over the move."""
    a = abs(h) / (ALPHA * (1.0 - ALPHA) * T * T)
    A = (JM * K + mass / K) * a * math.copysign(1.0, h)
    C = force / K
    values = (A + C, C, C - A)
    spans = (ALPHA * T, (1.0 - 2.0 * ALPHA) * T, ALPHA * T)
    return max(abs(v) for v in values), sum(v * v * d for v, d in zip(values, spans, strict=True))


def closed_form(mass: float) -> tuple[list[tuple[float, float]], float, float]:
    """Each segment's (peak, int tau^2), the cycle's peak and RMS, with a part of ``mass``
    on the way up (0: none)."""
    normal, weight = G * math.cos(INCLINE), G * math.sin(INCLINE)
    up = trapezoid(M + mass, F0 + MU * (M + mass) * normal + (M + mass) * weight, H, T1)
    down = trapezoid(M, -(F0 + MU * M * normal) + M * weight, -H, T2)
    hold = M * weight / K  # at rest the motor holds the carriage's weight, no friction
    rest1, rest2 = (hold, hold * hold * D1), (hold, hold * hold * D2)
    parts = [up, rest1, down, rest2]
    total = T1 + D1 + T2 + D2
    return parts, max(p for p, _ in parts), math.sqrt(sum(q for _, q in parts) / total)


@pytest.mark.parametrize("mass", [PART, 0.0])
def test_peak_and_rms_of_the_cycle_against_the_closed_form(mass):
    calc = calculator(part(mass) if mass else SegmentLoad())
    s = np.array([1.0])  # every duration is fixed
    parts, peak, rms = closed_form(mass)
    figures = calc.figures(s)
    for got, (p, q) in zip(figures, parts, strict=True):
        assert got.peak_torque[0] == pytest.approx(p, rel=1e-9)
        assert got.torque_square[0] == pytest.approx(q, rel=1e-9)
    metrics = calc.evaluate(s)
    assert metrics.peak_torque[0] == pytest.approx(peak, rel=1e-9)
    assert metrics.rms_torque[0] == pytest.approx(rms, rel=1e-9)


def test_the_segments_without_the_part_are_unchanged():
    loaded, empty = calculator(part()), calculator(SegmentLoad())
    s = np.array([1.0])
    a, b = loaded.figures(s), empty.figures(s)
    for i in (1, 2, 3):
        assert a[i].peak_torque[0] == b[i].peak_torque[0]
        assert a[i].torque_square[0] == b[i].torque_square[0]
    assert a[0].peak_torque[0] > b[0].peak_torque[0]


LINEAR: dict[str, Any] = {
    "name": "pick on an incline",
    "cycle": {"closed": True, "segments": [
        {"move": {"displacement": "100 mm", "duration": "0.5 s", "mass": "2 kg"}},
        {"dwell": {"duration": "0.2 s", "force": "3 N"}},
        {"move": {"displacement": "-100 mm", "duration": "0.4 s"}},
    ]},
    "load": {"mass": "4 kg", "friction": "5 N", "friction_coefficient": 0.1,
             "incline": "30 deg"},
    "motors": "book-examples",
}


def test_the_reader_gives_the_part_the_designs_guides():
    design = load_design_data(LINEAR)
    up, rest, down = design.cycle.segments
    assert up.load == SegmentLoad(inertia=2.0)
    assert (up.load.friction_coefficient, up.load.incline) == (0.1, pytest.approx(INCLINE))
    assert design.load.friction == pytest.approx(base_load().friction, rel=1e-14)
    lifted = segment_load(design.load, up)
    assert lifted.friction == pytest.approx(F0 + MU * (M + PART) * G * math.cos(INCLINE),
                                            rel=1e-14)
    assert lifted.torque == pytest.approx((M + PART) * G * math.sin(INCLINE), rel=1e-14)
    held = segment_load(design.load, rest)  # a force alone: no mass, nothing more
    assert held.friction == design.load.friction
    assert held.torque == pytest.approx(M * G * math.sin(INCLINE) + 3.0, rel=1e-14)
    assert segment_load(design.load, down) is design.load


def test_a_horizontal_axis_without_a_coefficient_adds_the_mass_only():
    data = {**LINEAR, "load": {"mass": "4 kg", "friction": "5 N"}}
    data["cycle"] = {"segments": [
        {"move": {"displacement": "100 mm", "duration": "0.5 s", "mass": "2 kg"}},
        {"dwell": {"duration": "0.2 s"}},
    ]}
    design = load_design_data(data)
    lifted = segment_load(design.load, design.cycle.segments[0])
    assert (lifted.inertia, lifted.friction, lifted.torque) == (6.0, 5.0, 0.0)


def test_a_rotary_design_reads_no_guides():
    data = {"name": "rotary", "cycle": {"segments": [
        {"move": {"displacement": "90 deg", "duration": "0.3 s", "inertia": "0.01 kg*m^2"}},
        {"dwell": {"duration": "0.2 s"}},
    ]}, "load": {"inertia": "0.02 kg*m^2", "friction": "0.3 N*m"}, "motors": "book-examples"}
    design = load_design_data(data)
    move = design.cycle.segments[0]
    assert (move.load.friction_coefficient, move.load.incline) == (0.0, 0.0)
    got = segment_load(design.load, move)
    assert (got.inertia, got.friction, got.torque) == (pytest.approx(0.03, rel=1e-15), 0.3, 0.0)


@pytest.mark.parametrize(("force", "warned"), [("9.8 N", True), ("30 N", False),
                                               ("-9.8 N", False)])
def test_a_force_equal_to_the_parts_weight_is_warned_about(force, warned):
    """On a 30 deg incline 2 kg weigh m g sin(a) = 9.80665 N along the axis: a force of
    that much on the same segment is likely the weight given twice."""
    data = {**LINEAR, "cycle": {"closed": True, "segments": [
        {"move": {"displacement": "100 mm", "duration": "0.5 s", "mass": "2 kg",
                  "force": force}},
        {"move": {"displacement": "-100 mm", "duration": "0.4 s"}},
    ]}}
    design = load_design_data(data)
    twice = weight_twice_warnings(design.cycle, parse_mapping(data, "design"))
    assert len(twice) == int(warned)
    if warned:
        assert "cycle.segments[0].move.force" in twice[0] and "9.80665 N" in twice[0]
