"""Loads of the load's position in a cycle (issue 38, book sec. 5.2.2): a task with a return
move (move h, dwell, move back, dwell) and a ``cycle:`` of segments, sized by the linkage
engine's cycle with the identity as the linkage (sizer.sizing.linkage_move.PositionCycle).

Each move's terms are evaluated at the load's true position (the return starts at h and
goes back to 0; a segment starts at the cycle's running position), each dwell holds the
static load where the load rests. Every figure is checked against an independent numpy
evaluation written here: the position sampled from the law's closed form, the motor torque
built by hand, tau = (J_m + J_g) N q'' + tau_l / (N eta^{+-1}), tau_l = J_l q'' + B_l q'
+ F sgn(q') + tau_ext + m g r cos(q + q0) + k (q - q_free) + preload + tau_table(q + x0);
the peak by dense sampling refined by scipy's bounded search, the RMS by scipy's quad over
the whole cycle (the dwells' holding included), cut at the table's knots and where the
power flow reverses; T_min by brentq on those checks."""

from __future__ import annotations

import math
from itertools import pairwise

import numpy as np
import pytest
from bad_input_cases import edited
from position_reference import ROTOR_GEAR, falling
from test_position_loads import G, _motor  # shared motors

from sizer.errors import UserError
from sizer.laws import law_choice
from sizer.mechanics.drive import Drive
from sizer.model.cycle import Cycle, Dwell, Move, ShareRule, Task, from_task
from sizer.model.domain import (
    GravityLoad,
    Limits,
    Load,
    Motor,
    SpringLoad,
    Stage,
    TableLoad,
    Transmission,
)
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.linkage_move import PositionCycle, position_model
from sizer.sizing.shortest_duration import answer

N = 5.0


ARM = Load(inertia=0.05, damping=0.01, friction=0.2,
           gravity=GravityLoad(moment=2.0 * 0.25, offset=math.radians(-30.0)))
SPRING = Load(inertia=0.02, friction=0.1, torque=0.3,
              spring=SpringLoad(stiffness=3.0, preload=-1.5, free_position=0.4))
TABLE = TableLoad((-0.2, 0.3, 0.7, 1.1, 1.6), (0.4, 1.8, -0.6, 0.9, 0.2), offset=0.1)
MIXED = Load(inertia=0.03, damping=0.02, friction=0.15,
             gravity=GravityLoad(moment=0.3, offset=0.2),
             spring=SpringLoad(stiffness=0.8, preload=0.2), table=TABLE)


class Independent:
    """The cycle's motor torque by hand: ``segments`` are ("move", h, T, law name) or
    ("dwell", T), each move starting where the one before ended (from 0)."""

    def __init__(self, load: Load, segments: list[tuple], eta: float) -> None:
        self.load, self.eta = load, eta
        self.parts = []
        x = 0.0
        for seg in segments:
            if seg[0] == "move":
                _, h, T, law = seg
                self.parts.append(("move", x, h, T, law_choice(law).law))
                x += h
            else:
                self.parts.append(("dwell", x, 0.0, seg[1], None))

    def position_torque(self, q):
        L = self.load
        out = np.full(np.shape(q), L.torque)
        if L.gravity is not None:
            out = out + L.gravity.moment * G * np.cos(q + L.gravity.offset)
        if L.spring is not None:
            s = L.spring
            out = out + s.stiffness * (q - s.free_position) + s.preload
        if L.table is not None:
            out = out + np.interp(np.asarray(q) + L.table.offset, L.table.x, L.table.tau)
        return out

    @staticmethod
    def motion(part, t):
        _, x0, h, T, law = part
        u = np.clip(np.atleast_1d(np.asarray(t, dtype=float)) / T, 0.0, 1.0)
        return x0 + h * law.derivative(u, 0), h * law.derivative(u, 1) / T, \
            h * law.derivative(u, 2) / T**2

    def load_torque(self, part, t):
        q, v, a = self.motion(part, t)
        h = part[2]
        sense = np.where(v > 0.0, 1.0, np.where(v < 0.0, -1.0, math.copysign(1.0, h)))
        L = self.load
        return L.inertia * a + L.damping * v + L.friction * sense + self.position_torque(q)

    def torque(self, part, t, rotor: float):
        _, v, a = self.motion(part, t)
        tl = self.load_torque(part, t)
        through = np.where(tl * v >= 0.0, 1.0 / (N * self.eta), self.eta / N)
        return (rotor + ROTOR_GEAR) * N * a + tl * through

    def hold(self, part) -> float:
        return abs(float(self.position_torque(np.array(part[1]))) / (N * self.eta))

    def peak(self, rotor: float) -> float:
        from scipy.optimize import minimize_scalar

        best = 0.0
        for part in self.parts:
            if part[0] == "dwell":
                best = max(best, self.hold(part))
                continue
            T = part[3]
            t = np.linspace(0.0, T, 4001)
            values = np.abs(self.torque(part, t, rotor))
            best = max(best, float(values.max()))
            for i in np.argsort(values)[-8:]:
                lo, hi = t[max(i - 1, 0)], t[min(i + 1, len(t) - 1)]
                found = minimize_scalar(lambda x, p=part: -abs(self.torque(p, x, rotor)[0]),
                                        bounds=(lo, hi), method="bounded",
                                        options={"xatol": 1e-14 * T})
                best = max(best, -float(found.fun))
        return best

    def _cuts(self, part) -> list[float]:
        """Where the move's torque has a kink: the power flow reverses, the position
        crosses a table's knot."""
        from scipy.optimize import brentq

        T = part[3]
        t = np.linspace(0.0, T, 4001)
        cuts = [0.0, T]

        def flow(x):
            return float((self.load_torque(part, x) * self.motion(part, x)[1])[0])

        values = self.load_torque(part, t) * self.motion(part, t)[1]
        cuts += [brentq(flow, t[i], t[i + 1], xtol=1e-15 * T)
                 for i in np.flatnonzero(values[:-1] * values[1:] < 0.0)]
        if self.load.table is not None:
            q = self.motion(part, t)[0]
            for knot in np.asarray(self.load.table.x) - self.load.table.offset:
                def off(x, k=knot):
                    return float(self.motion(part, x)[0][0] - k)

                cuts += [brentq(off, t[i], t[i + 1], xtol=1e-15 * T)
                         for i in np.flatnonzero((q[:-1] - knot) * (q[1:] - knot) < 0.0)]
        cuts = sorted(cuts)
        return [cuts[0], *(b for a, b in pairwise(cuts) if b - a > 1e-12 * T)]

    def rms(self, rotor: float) -> float:
        from scipy.integrate import quad

        square, time = 0.0, 0.0
        for part in self.parts:
            T = part[3]
            time += T
            if part[0] == "dwell":
                square += T * self.hold(part) ** 2
                continue
            square += sum(quad(lambda x, p=part: self.torque(p, x, rotor)[0] ** 2, lo, hi,
                               limit=200, epsabs=0.0, epsrel=1e-12)[0]
                          for lo, hi in pairwise(self._cuts(part)))
        return math.sqrt(square / time)


def _drive(load: Load, eta: float) -> Drive:
    return Drive(load, Transmission(stages=(Stage(ratio=N, efficiency=eta,
                                                  inertia=ROTOR_GEAR),)))


def _return_segments(h: float, T: float, dwell: float, law: str) -> list[tuple]:
    return [("move", h, T, law), ("dwell", dwell), ("move", -h, T, law), ("dwell", dwell)]


@pytest.mark.parametrize("load, h, law", [
    (ARM, math.pi / 2, "cycloidal"),  # up against gravity, down helped by it
    (ARM, -math.pi / 3, "poly5"),  # lowered first
    (MIXED, 1.3, "cycloidal"),  # the table's knots crossed on the way out and back
])
def test_a_return_move_at_its_true_positions(load, h, law):
    motors = (falling(1),)
    T, dwell = 0.45, 0.3
    task = Task(h, T, dwell=dwell, return_move=True)
    calc = position_model(from_task(task), law_choice(law).law, load, _drive(load, 1.0),
                          MotorArrays.of(motors, "electrical"))
    assert isinstance(calc, PositionCycle)
    metrics = calc.evaluate(np.full(len(motors), T))
    assert np.all(calc.reported(metrics) == T)  # a task's result reports each move's T
    assert metrics.duration == pytest.approx(2 * (T + dwell), rel=1e-15)
    ref = Independent(load, _return_segments(h, T, dwell, law), 1.0)
    for k, motor in enumerate(motors):
        assert metrics.peak_torque[k] == pytest.approx(ref.peak(motor.inertia), rel=1e-9)
        assert metrics.rms_torque[k] == pytest.approx(ref.rms(motor.inertia), rel=1e-9)


def test_the_return_is_not_the_way_out_mirrored():
    """The return starts at h: its position terms differ from a second move from 0 (the
    old one-move engine would have evaluated them at 0 ... -h)."""
    h, T, dwell = math.pi / 2, 0.45, 0.3
    motors = (falling(0),)
    calc = position_model(from_task(Task(h, T, dwell=dwell, return_move=True)),
                          law_choice("cycloidal").law, ARM, _drive(ARM, 1.0),
                          MotorArrays.of(motors, "electrical"))
    parts = calc.parts
    assert parts[2].s[0] == pytest.approx(h, abs=1e-15) and abs(parts[2].s[-1]) < 1e-15
    # the first dwell holds gravity at h (arm at 60 deg), the second at 0 (-30 deg)
    assert parts[1].hold == pytest.approx(0.5 * G * math.cos(h - math.radians(30.0)), 1e-15)
    assert parts[3].hold == pytest.approx(0.5 * G * math.cos(-math.radians(30.0)), 1e-15)
    wrong = Independent(ARM, [("move", h, T, "cycloidal"), ("dwell", dwell)], 1.0)
    ref = Independent(ARM, _return_segments(h, T, dwell, "cycloidal"), 1.0)
    rms = calc.evaluate(np.array([T])).rms_torque[0]
    assert rms == pytest.approx(ref.rms(motors[0].inertia), rel=1e-9)
    assert abs(rms / wrong.rms(motors[0].inertia) - 1.0) > 1e-3


CYCLE = [("move", 0.9, 0.3, "cycloidal"), ("dwell", 0.15), ("move", 0.5, 0.25, "poly5"),
         ("dwell", 0.1), ("move", -1.4, 0.4, "poly7"), ("dwell", 0.2)]


def _cycle(segments: list[tuple], free: bool = False) -> Cycle:
    out: list = []
    for i, seg in enumerate(segments):
        if seg[0] == "move":
            out.append(Move(seg[1], None if free else seg[2], law=law_choice(seg[3]),
                            name=f"s{i}"))
        else:
            out.append(Dwell(seg[1], name=f"s{i}"))
    return Cycle(tuple(out), share=ShareRule.EQUAL)


@pytest.mark.parametrize("load", [SPRING, MIXED])
def test_a_cycle_of_segments_from_its_running_position(load):
    motors = (falling(1),)
    calc = position_model(_cycle(CYCLE), law_choice("cycloidal").law, load, _drive(load, 1.0),
                          MotorArrays.of(motors, "electrical"))
    metrics = calc.evaluate(np.ones(len(motors)))
    ref = Independent(load, CYCLE, 1.0)
    assert metrics.duration == pytest.approx(1.4, rel=1e-15)
    for k, motor in enumerate(motors):
        assert metrics.peak_torque[k] == pytest.approx(ref.peak(motor.inertia), rel=1e-9)
        assert metrics.rms_torque[k] == pytest.approx(ref.rms(motor.inertia), rel=1e-9)


def test_a_lossy_stage_in_a_cycle():
    """eta < 1 where the power flow reverses: the kink inside a quadrature interval costs
    the composite rule its order (docs/position-loads.md, the known limit): 1e-7."""
    motors = (falling(1),)
    calc = position_model(_cycle(CYCLE), law_choice("cycloidal").law, ARM, _drive(ARM, 0.85),
                          MotorArrays.of(motors, "electrical"))
    metrics = calc.evaluate(np.ones(1))
    ref = Independent(ARM, CYCLE, 0.85)
    assert metrics.peak_torque[0] == pytest.approx(ref.peak(motors[0].inertia), rel=1e-9)
    assert metrics.rms_torque[0] == pytest.approx(ref.rms(motors[0].inertia), rel=1e-7)


def _t_min(load: Load, build, motor: Motor, check: str, grip: float, near: float) -> float:
    """Where the independent peak (or RMS) check meets its limit: a secant step from
    ``near`` (the engine's answer) and a point 1e-7 beyond, whose error is of the order of
    their distance to the root squared (brentq over a wide bracket gives the same to
    rounding, at many evaluations' cost)."""
    def excess(s):
        ref = Independent(load, build(s), 1.0)
        if check == "peak":
            return ref.peak(motor.inertia) - grip * motor.peak_torque
        return ref.rms(motor.inertia) - grip * motor.continuous_torque

    far = near * (1.0 + 1e-7)
    f0, f1 = excess(near), excess(far)
    assert f0 * f1 <= 0.0 or abs(f0) < 1e-9 * grip  # the engine's answer is that close
    return near - f0 * (far - near) / (f1 - f0)


def test_t_min_of_a_return_where_the_position_terms_do_not_scale():
    motors = (_motor(0, peak=3.0, continuous=100.0), _motor(1, peak=100.0, continuous=1.2))
    h, law, dwell, grip = math.pi / 2, "cycloidal", 0.3, 0.9
    calc = position_model(from_task(Task(h, None, dwell=dwell, return_move=True)),
                          law_choice(law).law, ARM, _drive(ARM, 1.0),
                          MotorArrays.of(motors, "electrical"))
    settled = answer(calc, Limits(torque_margin=0.1), [], True)
    assert settled.feasible.all()
    found = calc.reported(settled.metrics)

    def build(T):
        return _return_segments(h, T, dwell, law)

    peak_bound = _t_min(ARM, build, motors[0], "peak", grip, float(found[0]))
    rms_bound = _t_min(ARM, build, motors[1], "rms", grip, float(found[1]))
    assert found[0] == pytest.approx(peak_bound, rel=1e-9)
    assert found[1] == pytest.approx(rms_bound, rel=1e-9)
    # scaling the whole torque by (T/T')^2 (eq. 5.18 applied to everything) misses it
    T0 = 1.0
    naive = T0 * math.sqrt(Independent(ARM, build(T0), 1.0).peak(motors[0].inertia)
                           / (grip * 3.0))
    assert abs(naive / peak_bound - 1.0) > 0.05


def test_t_min_of_a_free_cycle():
    motors = (_motor(0, peak=2.5, continuous=100.0),)
    grip = 0.9
    calc = position_model(_cycle(CYCLE, free=True), law_choice("cycloidal").law, MIXED,
                          _drive(MIXED, 1.0), MotorArrays.of(motors, "electrical"))
    settled = answer(calc, Limits(torque_margin=0.1), [], True)
    assert settled.feasible.all()

    def build(s):  # every move of duration s (equal shares), the dwells fixed
        return [(seg[0], seg[1], s, seg[3]) if seg[0] == "move" else seg for seg in CYCLE]

    fixed = sum(seg[1] for seg in CYCLE if seg[0] == "dwell")
    bound = _t_min(MIXED, build, motors[0], "peak", grip,
                   float(settled.metrics.duration[0] - fixed) / 3)
    assert settled.metrics.duration[0] == pytest.approx(3 * bound + fixed, rel=1e-9)


def test_a_cycle_that_leaves_the_table_is_refused():
    # 0.9 + 0.5 = 1.4 rad, + 0.1 offset = 1.5 within the table; one more 0.2 rad is not
    segments = [*CYCLE[:4], ("move", 0.2, 0.2, "poly5"), ("move", -1.6, 0.4, "poly5")]
    with pytest.raises(UserError, match=r"table covers"):
        position_model(_cycle(segments), law_choice("cycloidal").law, MIXED,
                       _drive(MIXED, 1.0), MotorArrays.of((falling(0),), "electrical"))


def test_a_dwell_holds_with_the_sign_of_its_load():
    """Sampled for plots and energy, a dwell's motor torque has the static load's sign."""
    h, T, dwell = -math.pi / 2, 0.45, 0.3  # lowered to 120 deg below: gravity pulls down
    calc = position_model(from_task(Task(h, T, dwell=dwell, return_move=True)),
                          law_choice("cycloidal").law, ARM, _drive(ARM, 1.0),
                          MotorArrays.of((falling(0),), "electrical"))
    pieces = calc.pieces(np.array([T]), 11)
    held = 0.5 * G * math.cos(h - math.radians(30.0)) / N
    assert held < 0.0
    assert pieces[1].torque[0] == pytest.approx(np.full_like(pieces[1].torque[0], held),
                                                rel=1e-15)


# ------------------------------------------------------------ design files, end to end
def _design(tmp_path, set_: dict, name: str = "arm.yaml"):
    text = edited("book/ex6_1-6_2.yaml", set={
        "load": {"inertia": "0.05 kg*m^2", "damping": "0.01 N*m*s/rad", "friction": "0.2 N*m",
                 "gravity": {"mass": "2 kg", "radius": "250 mm", "offset": "-30 deg"}},
        "transmission": {"type": "gearbox", "ratio": 5, "efficiency": 1.0,
                         "inertia": f"{ROTOR_GEAR} kg*m^2"},
        "laws": ["cycloidal"], **set_})
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.filterwarnings("ignore::scipy.integrate.IntegrationWarning")
def test_a_knot_reached_at_a_moves_end_up_to_rounding():
    """60 + 40 - 100 deg: the last move ends on the table's first point up to rounding;
    no piece of zero width, no warning (the independent quad's own piece there, 2e-6 of
    the move long, warns of its rounding)."""
    import warnings

    load = Load(inertia=0.1, table=TableLoad((0.0, math.radians(50.0), math.radians(100.0)),
                                             (0.0, 1.0, 0.0)))
    segments = [("move", math.radians(60.0), 0.3, "poly5"), ("dwell", 0.2),
                ("move", math.radians(40.0), 0.2, "poly5"), ("dwell", 0.1),
                ("move", -math.radians(100.0), 0.3, "poly5"), ("dwell", 0.2)]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        calc = position_model(_cycle(segments), law_choice("poly5").law, load,
                              _drive(load, 1.0), MotorArrays.of((falling(0),), "electrical"))
        metrics = calc.evaluate(np.ones(1))
    assert all(np.all(np.diff(p.u) > 0.0) for p in calc.parts if hasattr(p, "u"))
    ref = Independent(load, segments, 1.0)
    assert metrics.rms_torque[0] == pytest.approx(ref.rms(falling(0).inertia), rel=1e-9)


# ------------------------------------------------------------ design files, located
def _case(id_: str, set_: dict, words: tuple[str, ...]):
    from bad_input_cases import Case

    return Case(id_, design=edited("book/ex6_1-6_2.yaml", set=set_, delete=("task",)),
                words=("design.yaml:", *words), fields=(words[0],))


ARM_YAML = {"inertia": "0.05 kg*m^2", "gravity": {"mass": "2 kg", "radius": "250 mm"}}
TABLE_YAML = {"inertia": "0.05 kg*m^2",
              "torque_table": {"points": [["0 deg", "1 N*m"], ["90 deg", "2 N*m"]]}}
CYCLE_CASES = [
    _case("table-short-for-the-cycle", {
        "load": TABLE_YAML,
        "cycle": {"segments": [{"move": {"displacement": "60 deg", "duration": "0.3 s"}},
                               {"move": {"displacement": "40 deg", "duration": "0.3 s"}},
                               {"move": {"displacement": "-100 deg", "duration": "0.3 s"}}]}},
          ("load.torque_table", "cycle covers", "table covers")),
    _case("free-move-with-a-boundary-speed", {
        "load": ARM_YAML, "laws": ["poly5"],
        "cycle": {"segments": [
            {"move": {"displacement": "60 deg", "end_speed": "2 rad/s"}},
            {"move": {"displacement": "30 deg", "start_speed": "2 rad/s",
                      "duration": "0.2 s"}}]}},
          ("cycle.segments[0]", "boundary speeds", "own duration")),
]


@pytest.mark.parametrize("case", CYCLE_CASES, ids=str)
def test_what_a_cycle_with_position_terms_refuses(case, tmp_path):
    from bad_input_cases import run_case

    run_case(case, tmp_path)
