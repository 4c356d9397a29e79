"""The stage lives over the cycle with loads of the position (issue 38, docs/ball-screws.md,
docs/shaft-loads.md, docs/position-loads.md): a ball screw's L10 life and a gearbox's
output bearing life read the load's force with its terms of the position at each sample
(a force table, gravity on an arm, a mass table's m(s) s'' + 1/2 m'(s) s'^2), not its
constant part alone.

The references are computed here, apart from sizer: the laws in closed form (poly5,
cycloidal), the force by the docs' model (the screw is the last stage, its axial force is
the load's force, F = m a + F_c sgn(v) + F_table(x); the belt's radial load by the sharing
rule of docs/shaft-loads.md), the table by numpy's interp, a mass table by
scipy.interpolate.PchipInterpolator, and the integrals by scipy's adaptive quadrature
split at the table knots' crossings, the power flow's and the force's sign changes and the
slack strand's kinks (roots found by brentq)."""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.interpolate import PchipInterpolator
from scipy.optimize import brentq
from test_ball_screw_checks import LIFE, SHAFT, design

import sizer
from sizer.io.loader import load_design_data
from sizer.mechanics.drive import Drive
from sizer.model.domain import Load, Stage, Transmission
from sizer.sizing.engine import size_design

# the screw design of tests/test_ball_screw_checks.py
H, T, DWELL = 0.3, 0.6, 0.4  # m, s, s: out, dwell, back, dwell
MASS, FRICTION = 80.0, 150.0  # kg, N
LEAD, C_A, F_W, REQUIRED = 0.01, 9000.0, 1.2, 20000 * 3600.0


def _life(row) -> float:
    return row.check("ball_screw_life").limit


def _size(d: dict):
    return sizer.size(d, motors=["SGM7J-08A"]).results[0]


def _with_table(d: dict, points: list[list[str]]) -> dict:
    out = copy.deepcopy(d)
    del out["load"]["force"]
    out["load"]["force_table"] = {"points": points}
    return out


# ----------------------------------------------- (a) a table equal to a constant force
def test_a_constant_table_gives_the_constant_force_life():
    # the same force by two engines: the constant load by the law move's closed forms and
    # samples (1001 per move), the table by the position engine's uniform grid (4001 per
    # move); with a smooth law both trapezoidal sums of F^3 |v| are within ~1e-12 of
    # each other here (the difference is the two grids' O(dt^2) errors' difference)
    base = design(law="poly5", **LIFE, **SHAFT)
    table = _with_table(base, [["0 mm", "200 N"], ["300 mm", "200 N"]])
    expected, got = _size(base), _size(table)
    assert _life(got) == pytest.approx(_life(expected), rel=1e-9)
    # the buckling check's peak |F|: the law move's in closed form, the position
    # engine's its samples refined by a parabola (dt = T/4000: a smooth peak is then read
    # to about the third derivative times dt^3, 3e-11 here)
    assert got.check("ball_screw_buckling").value == pytest.approx(
        expected.check("ball_screw_buckling").value, rel=1e-10)
    # the motor's RMS, not this change's: the position engine's Gauss-Legendre sum is
    # not split where the power flow turns (a kink of tau^2), the law move's is exact
    assert got.rms_torque == pytest.approx(expected.rms_torque, rel=1e-8)


def test_the_reported_case_no_longer_reads_the_life_without_the_force():
    # the report: the trapezoid 1/4 and a table 199.999 N .. 200.001 N gave the life of
    # no force at all (2.04 times the constant-force life). The table differs from 200 N
    # by up to 5e-6 of it: the life by 3e-6 (the second comparison, same engine, same
    # grid). The bound of the first: the law move's samples repeat the time at each of
    # the trapezoid's acceleration jumps (u = 1/4, 3/4), exact for this piecewise-constant
    # force; where the position engine's grid holds a single sample at a jump (one side's
    # value), its trapezoidal sum errs by about dt/2 times the jump of F^3 |v| there
    # (dt = T/4000): 5e-4 of the life here. With samples either side of the breakpoint the
    # two engines agree to rounding.
    base = design(**LIFE, **SHAFT)
    table = _with_table(base, [["0 mm", "199.999 N"], ["300 mm", "200.001 N"]])
    constant = _with_table(base, [["0 mm", "200 N"], ["300 mm", "200 N"]])
    expected = _life(_size(base))
    assert _life(_size(table)) == pytest.approx(expected, rel=1e-3)
    assert _life(_size(table)) == pytest.approx(_life(_size(constant)), rel=2e-5)


# --------------------------------------------- (b) a force table that varies strongly
POINTS = [(0.0, 0.0), (0.12, 400.0), (0.3, 100.0)]  # m, N: a rise and a fall


def _poly5(u: float) -> tuple[float, float, float]:
    """q_N, q_N', q_N'' of the 3-4-5 polynomial (book eq. 2.9's 5th-degree form)."""
    return (10 * u**3 - 15 * u**4 + 6 * u**5, 30 * u**2 - 60 * u**3 + 30 * u**4,
            60 * u - 180 * u**2 + 120 * u**3)


def _roots(f, lo: float = 0.0, hi: float = 1.0, n: int = 20001) -> list[float]:
    """The sign changes of f on [lo, hi], each refined by brentq."""
    u = np.linspace(lo, hi, n)
    y = np.array([f(x) for x in u])
    out = []
    for i in np.flatnonzero(np.sign(y[:-1]) * np.sign(y[1:]) < 0.0):
        out.append(brentq(f, u[i], u[i + 1], xtol=1e-15, rtol=1e-15))
    return out


def _screw_reference(force, knots: list[float], peak_out: bool = False
                     ) -> tuple[float, float]:
    """(F_m, peak |F|) over the cycle: out by poly5 from 0 to H, back from H to 0, F the
    axial force ``force(x, v, a)`` (signed, positive opposing a positive move); the
    quadrature split where x crosses a table's inner ``knots`` and where F changes sign."""
    cube, travel, peak = 0.0, 0.0, 0.0
    for start, h in ((0.0, H), (H, -H)):
        def state(u: float, start=start, h=h) -> tuple[float, float, float]:
            q, q1, q2 = _poly5(u)
            return start + h * q, h * q1 / T, h * q2 / T**2

        def signed(u: float, state=state) -> float:
            return force(*state(u))

        cuts = [*_roots(signed)]
        for knot in knots:
            cuts += _roots(lambda u, state=state, knot=knot: state(u)[0] - knot)
        cube += T * quad(lambda u, state=state, signed=signed:
                         abs(signed(u))**3 * abs(state(u)[1]), 0.0, 1.0,
                         points=sorted(cuts), epsabs=0.0, epsrel=1e-13, limit=400)[0]
        travel += T * quad(lambda u, state=state: abs(state(u)[1]), 0.0, 1.0,
                           epsabs=0.0, epsrel=1e-13)[0]
        if peak_out:
            u = np.linspace(0.0, 1.0, 200001)
            peak = max(peak, max(abs(signed(x)) for x in u[::50]))
    assert travel == pytest.approx(2 * H, rel=1e-12)
    return (cube / travel) ** (1.0 / 3.0), peak


def _rated_life(f_m: float) -> float:
    """L10 in seconds: (C_a / (f_w F_m))^3 1e6 revolutions at the cycle's mean speed."""
    revolutions = 2 * H / LEAD
    return (C_A / (F_W * f_m)) ** 3 * 1e6 * 2 * (T + DWELL) / revolutions


REL = 1e-6
"""The position engine's samples are a uniform grid of 4001 per move with the table's
knot crossings (its kinks); the trapezoidal rule's O(dt^2) error, ~1e-8 of the
integrals here; the life is the cube of F_m (three times its relative error)."""


def test_a_strongly_varying_table_against_a_quadrature():
    d = _with_table(design(law="poly5", **LIFE, **SHAFT),
                    [[f"{x * 1e3:g} mm", f"{f:g} N"] for x, f in POINTS])
    row = _size(d)
    xs, fs = [p[0] for p in POINTS], [p[1] for p in POINTS]

    def force(x: float, v: float, a: float) -> float:
        return MASS * a + FRICTION * math.copysign(1.0, v) + float(np.interp(x, xs, fs))

    f_m, peak = _screw_reference(force, xs[1:-1], peak_out=True)
    # the table matters: its F_m is far from the one without it
    free, _ = _screw_reference(lambda x, v, a: MASS * a + FRICTION * math.copysign(1.0, v),
                               [])
    assert f_m > 1.05 * free
    assert _life(row) == pytest.approx(_rated_life(f_m), rel=REL)
    assert row.check("ball_screw_life").value == REQUIRED
    # the buckling check's peak |F| (the engine's refined peak; the dwells hold the
    # table's force at the ends, 100 N and 0 N, below it)
    assert row.check("ball_screw_buckling").value == pytest.approx(peak, rel=1e-6)


def test_a_mass_table_adds_its_inertial_terms_once():
    # m(s) by PCHIP (scipy's, an implementation apart from sizer's numpy one): the force
    # (m_0 + m(x)) a + 1/2 m'(x) v^2 + F_c sgn(v) + 200 N (the design's constant force,
    # opposing the move out, helping it back). The engine's drive holds the largest mass
    # over the cycle (for the inertia ratio): that one must not be counted as well.
    mass_points = [(0.0, 10.0), (0.1, 40.0), (0.3, 20.0)]
    d = design(law="poly5", **LIFE, **SHAFT)
    d["load"]["mass_table"] = {"points": [[f"{x * 1e3:g} mm", f"{m:g} kg"]
                                          for x, m in mass_points]}
    row = _size(d)
    pchip = PchipInterpolator([p[0] for p in mass_points], [p[1] for p in mass_points])
    slope = pchip.derivative()

    def force(x: float, v: float, a: float) -> float:
        return ((MASS + float(pchip(x))) * a + 0.5 * float(slope(x)) * v * v
                + FRICTION * math.copysign(1.0, v) + 200.0)

    f_m, _ = _screw_reference(force, [0.1])  # the inner knot: m'' jumps there
    assert _life(row) == pytest.approx(_rated_life(f_m), rel=REL)


# ------------------------------------------ (c) gravity on an arm, a gearbox's output life
H_ARM, T_ARM, DWELL_ARM = 2.0, 0.4, 0.3  # rad, s, s: one move and its dwell
J_ARM = 0.05  # kg*m^2
ARM_MASS, ARM_RADIUS, ARM_OFFSET, G = 2.0, 0.25, math.radians(-120.0), 9.80665
K_GEAR = 5.0
D_DRIVER, D_DRIVEN = 0.04, 0.08  # m
K_BELT = D_DRIVEN / D_DRIVER
J_DRIVER, J_DRIVEN = 2e-5, 1e-4  # kg*m^2
ETA_BELT = 0.9
PRETENSION, WRAP = 30.0, math.radians(160.0)


def _arm_design(rating: float = 1000.0) -> dict:
    return {"task": {"displacement": f"{H_ARM} rad", "duration": f"{T_ARM} s",
                     "dwell": f"{DWELL_ARM} s"},
            "load": {"inertia": f"{J_ARM} kg*m^2",
                     "gravity": {"mass": f"{ARM_MASS} kg", "radius": f"{ARM_RADIUS} m",
                                 "offset": f"{math.degrees(ARM_OFFSET)!r} deg"}},
            "transmission": [
                {"type": "gearbox", "ratio": K_GEAR, "inertia": "1 kg*cm^2",
                 "peak_output_torque": "100 N*m",
                 "output_radial_load_life": f"{rating!r} N", "output_load_life": "20000 h"},
                {"type": "belt", "driver_diameter": f"{D_DRIVER} m",
                 "driven_diameter": f"{D_DRIVEN} m", "driver_inertia": f"{J_DRIVER} kg*m^2",
                 "driven_inertia": f"{J_DRIVEN} kg*m^2", "efficiency": ETA_BELT,
                 "on_gearbox_output": True, "pretension": f"{PRETENSION} N",
                 "wrap_angle": "160 deg"}],
            "laws": ["cycloidal"],
            "motors": [{"id": "M", "inertia": "0.2 kg*cm^2", "continuous_torque": "50 N*m",
                        "peak_torque": "100 N*m", "rated_speed": "30000 rpm"}]}


def _cycloidal(u: float) -> tuple[float, float, float]:
    """q, q', q'' of the cycloidal law over the arm's move (closed forms)."""
    q = H_ARM * (u - math.sin(2 * math.pi * u) / (2 * math.pi))
    speed = H_ARM / T_ARM * (1.0 - math.cos(2 * math.pi * u))
    acceleration = 2 * math.pi * H_ARM / T_ARM**2 * math.sin(2 * math.pi * u)
    return q, speed, acceleration


def _load_torque(u: float) -> float:
    """The arm's torque, positive opposing the (positive) move: J q'' + m g r cos(q + q0)."""
    q, _, acceleration = _cycloidal(u)
    return J_ARM * acceleration + ARM_MASS * G * ARM_RADIUS * math.cos(q + ARM_OFFSET)


def _gearbox_output_torque(u: float) -> float:
    """The belt's input torque: its pulleys reflected to the driver (J_driver +
    J_driven / k^2) at the driver's acceleration k q'', plus the load's torque through the
    belt in the direction of power flow (/ (k eta) while it flows to the load, eta / k
    while the load drives)."""
    tau = _load_torque(u)
    through = tau / (K_BELT * ETA_BELT) if tau >= 0.0 else tau * ETA_BELT / K_BELT
    return (J_DRIVER + J_DRIVEN / K_BELT**2) * K_BELT * _cycloidal(u)[2] + through


def _belt_radial(torque: float) -> float:
    """docs/shaft-loads.md: the pull tau / (d/2) raises the tight strand and lowers the
    slack one by half of it (no lower than 0), the strands' vector sum over the wrap."""
    pull = abs(torque) / (D_DRIVER / 2.0)
    slack = max(PRETENSION - pull / 2.0, 0.0)
    tight = slack + pull
    return math.sqrt(tight**2 + slack**2 - 2.0 * tight * slack * math.cos(WRAP))


def _arm_equivalent_force() -> float:
    """F_eq = (int |n_2| F^3 dt / int |n_2| dt)^(1/3) over the move (the dwell turns
    nothing), split where the power flow turns, the torque changes sign, the slack strand
    goes slack."""
    cuts = [*_roots(_load_torque), *_roots(_gearbox_output_torque),
            *_roots(lambda u: abs(_gearbox_output_torque(u)) - PRETENSION * D_DRIVER)]
    assert len(cuts) >= 3  # each regime is crossed

    def weighted(u: float) -> float:
        return abs(_cycloidal(u)[1]) * _belt_radial(_gearbox_output_torque(u)) ** 3

    cube = quad(weighted, 0.0, 1.0, points=sorted(cuts), epsabs=0.0, epsrel=1e-13,
                limit=400)[0]
    turned = quad(lambda u: abs(_cycloidal(u)[1]), 0.0, 1.0, epsabs=0.0, epsrel=1e-13)[0]
    assert turned * T_ARM == pytest.approx(H_ARM, rel=1e-12)
    return (cube / turned) ** (1.0 / 3.0)


def test_gravity_on_an_arm_gets_the_gearbox_output_life_check():
    result = size_design(load_design_data(_arm_design()))
    row = result.results[0]
    found = [c for c in row.checks if c.name == "gearbox_radial_life"]
    assert found, [c.name for c in row.checks]
    check = found[0]
    f_eq = _arm_equivalent_force()
    # without gravity's terms the value would be another: the check reads them
    assert abs(f_eq / _arm_equivalent_force_without_gravity() - 1.0) > 0.05
    assert check.value == pytest.approx(f_eq, rel=REL)
    assert check.limit == 1000.0
    assert not any("not sampled" in n for n in result.notes), result.notes


def _arm_equivalent_force_without_gravity() -> float:
    global ARM_MASS
    saved, ARM_MASS = ARM_MASS, 0.0
    try:
        return _arm_equivalent_force()
    finally:
        ARM_MASS = saved


def test_through_a_linkage_the_note_stays():
    from sizer.sizing.checks import shaft_notes

    transmission = load_design_data(_arm_design()).transmission
    notes = shaft_notes([], transmission, None, sampled=False)
    assert ("no gearbox_radial_life check: the cycle's forces on the gearbox's output are "
            "not sampled through a linkage") in notes


# ------------------------------------------------ Drive.chain's extra terms, by hand
@pytest.mark.parametrize("rule", ["power_flow", "steady_load"])
def test_the_chain_takes_the_position_terms(rule):
    # one gearbox k = 4, eta = 0.8, input inertia J_g; the load J_l, friction F, no
    # constant torque; extra (inertial i, steady g) along the motion
    k, eta, J_g, J_l, F = 4.0, 0.8, 1e-3, 0.5, 1.0
    drive = Drive(Load(J_l, friction=F), Transmission(
        (Stage("gearbox", k, efficiency=eta, inertia=J_g),), efficiency_applies_to=rule))
    a, v = np.array([[2.0, 2.0, -3.0]]), np.array([[1.0, 1.0, 1.0]])
    i, g = np.array([[0.3, 0.3, 0.3]]), np.array([[0.5, -4.0, 0.0]])
    shaft, outputs = drive.chain(a, v, 1.0, extra=(i, g))
    u = J_l * a + F + i + g
    assert outputs[0] == pytest.approx(u, rel=1e-15)
    if rule == "power_flow":  # the whole torque in the power flow's direction
        through = np.where(u >= 0.0, u / (k * eta), u * eta / k)
    else:  # the inertial part without loss, the steady part (F + g) by its own sign
        steady = F + g
        through = (J_l * a + i) / k + np.where(steady >= 0.0, steady / (k * eta),
                                               steady * eta / k)
    assert shaft == pytest.approx(J_g * k * a + through, rel=1e-15)
    # no extra: as before
    _, plain = drive.chain(a, v, 1.0)
    assert plain[0] == pytest.approx(J_l * a + F, rel=1e-15)


def test_a_cycle_of_segments_reads_each_moves_own_load():
    """A part of 20 kg picked up for the way out of a cycle of segments: the screw's F_m
    weighs the way out with 100 kg and the way back with 80 kg (each segment's own load,
    not the heaviest for every move: that one is the inertia ratio's)."""
    screw = design(law="poly5", **LIFE, **SHAFT)["transmission"]
    d = {"name": "part out, back empty",
         "cycle": {"segments": [
             {"move": {"displacement": "300 mm", "duration": "0.6 s", "mass": "20 kg",
                       "name": "out"}},
             {"dwell": {"duration": "0.4 s"}},
             {"move": {"displacement": "-300 mm", "duration": "0.6 s", "name": "back"}},
             {"dwell": {"duration": "0.4 s"}}]},
         "load": {"mass": "80 kg", "friction": "150 N"}, "transmission": screw,
         "laws": ["poly5"], "motors": ["yaskawa-sgm7j"]}
    row = _size(d)

    def mean_cubic(masses: tuple[float, float]) -> float:
        cube = 0.0
        for h, mass in zip((H, -H), masses, strict=True):
            def integrand(u: float, h=h, mass=mass) -> float:
                _, q1, q2 = _poly5(u)
                v, a = h * q1 / T, h * q2 / T**2
                return abs(mass * a + FRICTION * math.copysign(1.0, v)) ** 3 * abs(v)

            cuts = _roots(lambda u, h=h, mass=mass: mass * h * _poly5(u)[2] / T**2
                          + FRICTION * math.copysign(1.0, h))
            cube += T * quad(integrand, 0.0, 1.0, points=cuts, epsabs=0.0, epsrel=1e-13,
                             limit=400)[0]
        return (cube / (2 * H)) ** (1.0 / 3.0)

    f_m = mean_cubic((MASS + 20.0, MASS))
    assert _rated_life(mean_cubic((MASS + 20.0, MASS + 20.0))) < 0.9 * _rated_life(f_m)
    assert _life(row) == pytest.approx(_rated_life(f_m), rel=REL)
