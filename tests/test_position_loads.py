"""Loads of the load's position (issue 38, book sec. 5.2.2, eqs. 5.13-5.19): gravity on an
arm and a spring, in a single move with its dwell (sizer.sizing.linkage_move).

Every figure is checked against an independent computation written here: the motor
torque from its closed form, tau = (J_m + J_g) N q''
+ tau_l / (N eta^{+-1}), tau_l = J_l q'' + B_l q' + F + m g r cos(q + q0) + k (q - q_free)
+ preload; its peak on a dense grid refined by scipy's bounded search, its RMS by
scipy.integrate.quad, T_min by scipy's brentq on those checks. The position terms do not
scale with the duration (eq. 5.15): T_min is not where the whole torque scaled by
(T/T')^2 meets the limit, and without a dwell the RMS never falls below the position
terms' own RMS over the move."""

from __future__ import annotations

import math
from dataclasses import replace
from itertools import pairwise

import numpy as np
import pytest
from bad_input_cases import Case, edited
from bad_input_cases import run_case as run
from position_reference import ROTOR_GEAR, falling

from sizer.errors import UserError
from sizer.laws import law_choice
from sizer.mechanics.drive import Drive
from sizer.model.cycle import Task
from sizer.model.domain import GravityLoad, Limits, Load, Motor, SpringLoad, Stage, Transmission
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.linkage_move import position_calculator
from sizer.sizing.move import CycleCalculator
from sizer.sizing.shortest_duration import answer

G = 9.80665


def _motor(k: int, peak: float, continuous: float, speed: float = 300.0,
           inertia: float = 1e-4) -> Motor:
    """A flat (rectangular) region when ``speed`` is its end, else a falling corner."""
    return Motor(id=f"m{k}", inertia=inertia, continuous_torque=continuous, peak_torque=peak,
                 rated_speed=speed, max_speed=speed,
                 intermittent_curve=((0.0, peak), (speed, peak)),
                 continuous_curve=((0.0, continuous), (speed, continuous)))


ARM = Load(inertia=0.05, damping=0.01, friction=0.2,
           gravity=GravityLoad(moment=2.0 * 0.25, offset=math.radians(-30.0)))
SPRING = Load(inertia=0.02, damping=0.0, friction=0.1,
              spring=SpringLoad(stiffness=3.0, preload=-1.5, free_position=0.4))


class Independent:
    """The move's torques from their closed forms, with scipy."""

    def __init__(self, load: Load, h: float, law_name: str, N: float, eta: float) -> None:
        self.load, self.h, self.law = load, h, law_choice(law_name).law
        self.N, self.eta = N, eta

    def motion(self, t, T: float):
        u = np.clip(np.atleast_1d(np.asarray(t, dtype=float)) / T, 0.0, 1.0)
        q, v, a = (self.law.derivative(u, k) for k in range(3))
        return self.h * q, self.h * v / T, self.h * a / T**2

    def position_torque(self, q):
        out = np.zeros(np.shape(q))
        if self.load.gravity is not None:
            g = self.load.gravity
            out += g.moment * G * np.cos(q + g.offset)  # m g r cos(q + q0)
        if self.load.spring is not None:
            s = self.load.spring
            out += s.stiffness * (q - s.free_position) + s.preload
        return out

    def load_torque(self, t, T: float):
        q, v, a = self.motion(t, T)
        sense = np.where(v > 0.0, 1.0, np.where(v < 0.0, -1.0, math.copysign(1.0, self.h)))
        L = self.load
        return L.inertia * a + L.damping * v + L.friction * sense + self.position_torque(q)

    def torque(self, t, T: float, rotor: float):
        """The motor torque at the times t (an array)."""
        _, v, a = self.motion(t, T)
        tl = self.load_torque(t, T)
        through = np.where(tl * v >= 0.0, 1.0 / (self.N * self.eta), self.eta / self.N)
        return (rotor + ROTOR_GEAR) * self.N * a + tl * through

    def hold(self) -> float:
        return abs(float(self.position_torque(self.h))) / (self.N * self.eta)

    def peak(self, T: float, rotor: float, dwell: float) -> float:
        from scipy.optimize import minimize_scalar

        t = np.linspace(0.0, T, 4001)
        values = np.abs(self.torque(t, T, rotor))
        best = float(values.max())
        for b in self.law.breakpoints:  # a jump's larger side: the value just beside it
            for side in (np.nextafter(b * T, 0.0), np.nextafter(b * T, T)):
                best = max(best, float(np.abs(self.torque(np.array([side]), T, rotor))[0]))
        for i in np.argsort(values)[-6:]:  # the largest samples, each refined
            lo, hi = t[max(i - 1, 0)], t[min(i + 1, len(t) - 1)]
            found = minimize_scalar(lambda x: -abs(self.torque(x, T, rotor)[0]), bounds=(lo, hi),
                                    method="bounded", options={"xatol": 1e-14 * T})
            best = max(best, -float(found.fun))
        return max(best, self.hold()) if dwell > 0.0 else best

    def rms(self, T: float, rotor: float, dwell: float) -> float:
        """By quad, the move cut where the power flow reverses (the torque's kinks)."""
        from scipy.integrate import quad
        from scipy.optimize import brentq

        t = np.linspace(0.0, T, 2001)
        _, v, _ = self.motion(t, T)
        flow = self.load_torque(t, T) * v
        kinks = [brentq(lambda x: float((self.load_torque(x, T) * self.motion(x, T)[1])[0]),
                        t[i], t[i + 1], xtol=1e-15 * T)
                 for i in np.flatnonzero(flow[:-1] * flow[1:] < 0.0)]
        breaks = [b * T for b in self.law.breakpoints if 0.0 < b < 1.0]  # jumps
        # a sign change of the flow across a jump is the jump, not a root: kept once
        kinks = [k for k in kinks if min((abs(k - b) for b in breaks), default=T) > 1e-9 * T]
        edges = [0.0, *sorted([*kinks, *breaks]), T]
        square = sum(quad(lambda x: self.torque(x, T, rotor)[0] ** 2, lo, hi, limit=200,
                          epsabs=0.0, epsrel=1e-13)[0] for lo, hi in pairwise(edges))
        return math.sqrt((square + dwell * self.hold() ** 2) / (T + dwell))


def _calculator(load: Load, h: float, law: str, motors: tuple[Motor, ...], eta: float,
                duration: float | None, dwell: float):
    drive = Drive(load, Transmission(stages=(Stage(ratio=5.0, efficiency=eta,
                                                   inertia=ROTOR_GEAR),)))
    return position_calculator(Task(h, duration, dwell=dwell), law_choice(law).law, load,
                               drive, MotorArrays.of(motors, "electrical"))


@pytest.mark.parametrize("load, h, law, eta, rms_tolerance", [
    (ARM, math.pi / 2, "cycloidal", 0.9, 1e-9),  # gravity opposes the whole move
    (ARM, -math.pi / 2, "poly5", 1.0, 1e-9),  # lowered: gravity drives, the flow reverses
    (SPRING, 1.2, "poly7", 1.0, 1e-9),  # the spring helps, then holds back
    (SPRING, 0.6, "cycloidal", 0.85, 1e-9),
    # a lossy stage whose flow reverses inside a quadrature interval: the torque has a
    # kink there and the composite Gauss rule loses its order (1e-9 to 5e-8 here; the
    # linkage engine's rule, docs/position-loads.md)
    (ARM, -math.pi / 2, "poly5", 0.8, 1e-7),
    # the acceleration jumps at the law's breakpoints: the peak is the larger side's
    # value there, the top speed a kink (no parabola through either)
    (ARM, math.pi / 2, "trapezoidal(alpha=1/4)", 0.9, 1e-9),
    (SPRING, 1.2, "trapezoidal(alpha=1/3)", 1.0, 1e-9),
    (ARM, -math.pi / 2, "constant_acceleration", 0.9, 1e-7),
    # a slow move: the start's static torque is the peak, the torque falls from it
    (ARM, math.pi / 2, "poly7", 0.9, 1e-9),
])
def test_peak_and_rms_against_independent_evaluations(load, h, law, eta, rms_tolerance):
    motors = tuple(falling(k) for k in range(3))
    T, dwell = (3.0 if law == "poly7" and eta == 0.9 else 0.45), 0.3
    calc = _calculator(load, h, law, motors, eta, T, dwell)
    metrics = calc.evaluate(np.full(len(motors), T))
    ref = Independent(load, h, law, 5.0, eta)
    for k, motor in enumerate(motors):
        assert metrics.peak_torque[k] == pytest.approx(ref.peak(T, motor.inertia, dwell),
                                                       rel=1e-9)
        assert metrics.rms_torque[k] == pytest.approx(ref.rms(T, motor.inertia, dwell),
                                                      rel=rms_tolerance)


def test_gravity_term_is_m_g_r_cos():
    arm = GravityLoad(moment=0.5, offset=0.3, g=1.62)
    q = np.linspace(-1.0, 2.0, 7)
    assert np.allclose(arm.torque(q), 0.5 * 1.62 * np.cos(q + 0.3), rtol=1e-15, atol=0.0)
    spring = SpringLoad(stiffness=2.0, preload=0.5, free_position=0.25)
    assert np.allclose(spring.torque(q), 2.0 * (q - 0.25) + 0.5, rtol=1e-15, atol=1e-15)
    assert Load(1.0, gravity=arm, spring=spring).position_torque(0.4) == pytest.approx(
        0.5 * 1.62 * math.cos(0.7) + 2.0 * 0.15 + 0.5, rel=1e-15)


def _t_min(load: Load, h: float, law: str, motor: Motor, check: str, grip: float,
           dwell: float) -> float:
    """The duration where the peak (or RMS) check meets its limit: brentq on the
    independent evaluations, from a duration that passes to one that fails."""
    from scipy.optimize import brentq

    ref = Independent(load, h, law, 5.0, 0.9)
    if check == "peak":
        def excess(T):
            return ref.peak(T, motor.inertia, dwell) - grip * motor.peak_torque
    else:
        def excess(T):
            return ref.rms(T, motor.inertia, dwell) - grip * motor.continuous_torque
    lo, hi = 0.15, 0.4  # fails at lo, passes at hi (asserted by brentq's signs)
    return brentq(excess, lo, hi, xtol=1e-15, rtol=1e-13)


def test_t_min_where_the_position_terms_do_not_scale():
    # a peak-bound motor (its continuous torque is ample) and an RMS-bound one
    motors = (_motor(0, peak=3.0, continuous=100.0), _motor(1, peak=100.0, continuous=1.5))
    h, law, dwell, grip = math.pi / 2, "cycloidal", 0.3, 0.9
    calc = _calculator(ARM, h, law, motors, 0.9, None, dwell)
    settled = answer(calc, Limits(torque_margin=0.1), [], True)
    assert settled.feasible.all()
    peak_bound = _t_min(ARM, h, law, motors[0], "peak", grip, dwell)
    rms_bound = _t_min(ARM, h, law, motors[1], "rms", grip, dwell)
    assert settled.scale[0] == pytest.approx(peak_bound, rel=1e-9)
    assert settled.scale[1] == pytest.approx(rms_bound, rel=1e-9)
    # eq. 5.18: scaling the whole torque by (T/T')^2 is wrong for a position term; the
    # shortest duration is where only tau_s scales
    ref = Independent(ARM, h, law, 5.0, 0.9)
    T0 = 1.0
    naive = T0 * math.sqrt(ref.peak(T0, motors[0].inertia, dwell) / (grip * 3.0))
    assert abs(naive / peak_bound - 1.0) > 0.05


def test_a_static_load_beyond_the_continuous_torque_is_infeasible():
    # without a dwell the RMS falls with T towards the position terms' own RMS over the
    # move, which no duration lowers: above the continuous torque, no T passes
    motors = (_motor(0, peak=100.0, continuous=1.0),)
    calc = _calculator(ARM, math.pi / 2, "cycloidal", motors, 0.9, None, 0.0)
    ref = Independent(ARM, math.pi / 2, "cycloidal", 5.0, 0.9)
    assert min(ref.rms(T, motors[0].inertia, 0.0) for T in np.geomspace(0.1, 1e4, 25)) > 0.9
    assert not answer(calc, Limits(torque_margin=0.1), [], True).feasible[0]


def test_zero_terms_are_no_terms():
    zero = replace(ARM, gravity=GravityLoad(moment=0.0), spring=SpringLoad(stiffness=0.0))
    assert not zero.position_dependent
    assert not replace(ARM, gravity=None).position_dependent
    assert ARM.position_dependent and SPRING.position_dependent
    assert np.all(zero.position_torque(np.linspace(0.0, 3.0, 5)) == 0.0)


def test_zero_terms_give_identical_results(tmp_path):
    import sizer

    base = edited("book/ex6_1-6_2.yaml")
    with_terms = edited("book/ex6_1-6_2.yaml", set={
        "load.gravity": {"mass": "0 kg", "radius": "0.2 m", "offset": "10 deg"},
        "load.spring": {"stiffness": "0 N*m/rad", "preload": "0 N*m"}})
    results = []
    for name, text in (("base.yaml", base), ("zero.yaml", with_terms)):
        path = tmp_path / name
        path.write_text(text, encoding="utf-8")
        result = sizer.size(path)
        results.append([repr(r) for r in result.results])
    assert results[0] == results[1]


def test_sizer_sizes_a_gravity_arm_end_to_end(tmp_path):
    import sizer

    text = edited("book/ex6_1-6_2.yaml", set={
        "task.displacement": "90 deg", "task.duration": "0.45 s", "task.dwell": "0.3 s",
        "load": {"inertia": "0.05 kg*m^2", "damping": "0.01 N*m*s/rad", "friction": "0.2 N*m",
                 "gravity": {"mass": "2 kg", "radius": "250 mm", "offset": "-30 deg"}},
        "transmission": {"type": "gearbox", "ratio": 5, "efficiency": 0.9,
                         "inertia": f"{ROTOR_GEAR} kg*m^2"},
        "laws": ["cycloidal"]})
    path = tmp_path / "arm.yaml"
    path.write_text(text, encoding="utf-8")
    motor = falling(1)
    row = sizer.size(path, motors=[motor]).results[0]
    ref = Independent(ARM, math.pi / 2, "cycloidal", 5.0, 0.9)
    assert row.peak_torque == pytest.approx(ref.peak(0.45, motor.inertia, 0.3), rel=1e-9)
    assert row.rms_torque == pytest.approx(ref.rms(0.45, motor.inertia, 0.3), rel=1e-9)


def test_the_segment_breakdown_of_a_gravity_arm(tmp_path):
    """sizer segments of a gravity arm goes through the position engine (its cycle RMS is
    the sizing's): the move and the dwell, and the same RMS torque as sizer size."""
    import json

    from cli_run import run_cli

    text = edited("book/ex6_1-6_2.yaml", set={
        "task.displacement": "90 deg", "task.duration": "0.45 s", "task.dwell": "0.3 s",
        "load": {"inertia": "0.05 kg*m^2", "friction": "0.2 N*m",
                 "gravity": {"mass": "2 kg", "radius": "250 mm", "offset": "-30 deg"}},
        "transmission": {"type": "gearbox", "ratio": 10, "efficiency": 0.9},
        "laws": ["cycloidal"], "check": {"motor": "ex6_3", "law": "cycloidal"}})
    path = tmp_path / "arm.yaml"
    path.write_text(text, encoding="utf-8")
    result = run_cli("segments", str(path))
    assert result.returncode == 0, result.stderr
    sized = json.loads(run_cli("size", str(path), "--all", "--format", "json").stdout)
    row = next(r for r in sized["results"] if r["motor"] == "ex6_3")
    assert f"cycle rms torque {row['rms_torque']:.4g} N*m" in result.stdout


def test_the_law_move_engine_never_ignores_a_position_term():
    drive = Drive(ARM, Transmission())
    motors = MotorArrays.of((_motor(0, 3.0, 1.0),), "electrical")
    with pytest.raises(UserError, match=r"load\.gravity"):
        CycleCalculator(None, Task(1.0, 0.5), drive, motors, law=law_choice("cycloidal").law)


def test_position_engine_refuses_what_it_does_not_model():
    motors = MotorArrays.of((_motor(0, 3.0, 1.0),), "electrical")
    law = law_choice("cycloidal").law
    screw = Drive(ARM, Transmission(stages=(Stage(ratio=5.0, preload_torque=0.1),)))
    with pytest.raises(UserError, match="preload"):
        position_calculator(Task(1.0, 0.5), law, ARM, screw, motors)
    with pytest.raises(UserError, match="return"):
        position_calculator(Task(1.0, 0.5, return_move=True), law, ARM,
                            Drive(ARM, Transmission()), motors)


# ------------------------------------------------------------ bad fields, located
ROTARY = "book/ex6_1-6_2.yaml"
LINEAR = "vendor-ballscrew.yaml"
D = "design.yaml:"
ARM_FIELDS = {"mass": "2 kg", "radius": "0.25 m"}


def case(id: str, value: dict, words: tuple[str, ...], fields: tuple[str, ...],
         example: str = ROTARY) -> Case:
    return Case(id, design=edited(example, set=value), words=(D, *words), fields=fields)


FIELD_CASES = [
    case("load-gravity-mass-negative", {"load.gravity": {**ARM_FIELDS, "mass": "-2 kg"}},
         ("load.gravity.mass", "[1e-6, 1e7] kg"), ("load.gravity.mass",)),
    case("load-gravity-radius-a-torque", {"load.gravity": {**ARM_FIELDS, "radius": "5 N*m"}},
         ("load.gravity.radius",), ("load.gravity.radius",)),
    case("load-gravity-offset-400-deg", {"load.gravity": {**ARM_FIELDS, "offset": "400 deg"}},
         ("load.gravity.offset", "6.28319] rad"), ("load.gravity.offset",)),
    case("load-gravity-g-zero", {"load.gravity": {**ARM_FIELDS, "g": 0}},
         ("load.gravity.g", "[0.001, 1000] m/s^2"), ("load.gravity.g",)),
    case("load-gravity-without-radius", {"load.gravity": {"mass": "2 kg"}},
         ("load.gravity", "radius"), ("load.gravity",)),
    case("load-gravity-on-a-linear-axis", {"load.gravity": ARM_FIELDS},
         ("load.gravity", "incline"), ("load.gravity",), LINEAR),
    case("load-spring-stiffness-a-length", {"load.spring": {"stiffness": "2 m"}},
         ("load.spring.stiffness",), ("load.spring.stiffness",)),
    case("load-spring-preload-huge", {"load.spring": {"stiffness": 1, "preload": "1e9 N*m"}},
         ("load.spring.preload", "[1e-9, 1e8] N*m"), ("load.spring.preload",)),
    case("load-spring-free-position-a-length",
         {"load.spring": {"stiffness": 1, "free_position": "10 mm"}},
         ("load.spring.free_position",), ("load.spring.free_position",)),
    case("load-spring-unknown-field", {"load.spring": {"stiffness": 1, "rate": 2}},
         ("load.spring", "rate"), ("load.spring",)),
    case("load-spring-with-steady-load-efficiency",
         {"load.spring": {"stiffness": 1}, "efficiency_applies_to": "steady_load"},
         ("load.spring", "power_flow"), ()),
]


@pytest.mark.parametrize("case", FIELD_CASES, ids=str)
def test_bad_position_load_field(case, tmp_path):
    run(case, tmp_path)


def test_a_dwell_holding_more_than_the_move_sets_the_peaks():
    """An arm raised slowly to where gravity's moment is largest (no friction): holding it
    there through the dwell takes more torque than any instant of the move (the move
    decelerates into it). The motor's peak is the holding torque m g r / (N eta), the
    stage's (its output is the arm) the static torque m g r itself, as for an axis
    without position terms (sizer.sizing.move)."""
    arm = Load(inertia=0.05, gravity=GravityLoad(moment=0.5, offset=-math.pi / 3))
    h, law, eta, T, dwell = math.pi / 3, "constant_acceleration", 0.9, 3.0, 0.3
    motors = tuple(falling(k) for k in range(3))
    ref = Independent(arm, h, law, 5.0, eta)
    static = 0.5 * G
    t = np.linspace(0.0, T, 20001)
    assert static / (5.0 * eta) > np.abs(ref.torque(t, T, motors[-1].inertia)).max()
    assert static > np.abs(ref.load_torque(t, T)).max()
    metrics = _calculator(arm, h, law, motors, eta, T, dwell).evaluate(np.full(3, T))
    assert metrics.peak_torque == pytest.approx(static / (5.0 * eta), rel=1e-12)
    assert metrics.stage_peak[0] == pytest.approx(static, rel=1e-12)
