"""A torque table of the load's position (issue 38, book sec. 5.2.2): points (x, tau)
linear between them, tau(q + x0) at the load's position q from the start of the move,
sized by the position-load engine (sizer.sizing.linkage_move) with the table's knot
crossings as breakpoints of its grid.

Every figure is checked against an independent computation written here: the motor torque
from its closed form with numpy's interp for the table, its peak on a dense grid refined by
scipy's bounded search on each smooth piece (between knot crossings found by brentq), its
RMS by scipy.integrate.quad split at those crossings, T_min by brentq on those checks."""

from __future__ import annotations

import math

import numpy as np
import pytest
from bad_input_cases import Case, edited
from bad_input_cases import run_case as run
from position_reference import N_GEAR, ROTOR_GEAR, PiecewiseReference, calculator, falling, flat

from sizer.errors import UserError
from sizer.laws import law_choice
from sizer.mechanics.drive import Drive
from sizer.model.cycle import Task
from sizer.model.domain import GravityLoad, Limits, Load, Motor, Stage, TableLoad, Transmission
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.linkage_move import position_calculator
from sizer.sizing.shortest_duration import answer

G = 9.80665

# a measured process torque: rises, a sharp peak at 0.7 rad, falls, turns over
X = (-0.2, 0.1, 0.45, 0.7, 0.95, 1.3, 1.8)
TAU = (0.5, 0.8, 2.6, 4.1, 1.2, -0.6, 0.3)
TABLE = Load(inertia=0.03, damping=0.01, friction=0.15, table=TableLoad(X, TAU, offset=0.1))


class Independent(PiecewiseReference):
    """The move's torques from their closed forms, with numpy's interp and scipy."""

    def __init__(self, x, tau, offset: float, load: Load, h: float, law_name: str,
                 eta: float) -> None:
        self.x, self.tau, self.offset = np.asarray(x), np.asarray(tau), offset
        self.knots = self.x - offset
        self.load, self.h, self.law, self.eta = load, h, law_choice(law_name).law, eta

    def position_torque(self, q):
        return np.interp(np.asarray(q) + self.offset, self.x, self.tau)

    def load_torque(self, t, T: float):
        q, v, a = self.motion(t, T)
        sense = np.where(v > 0.0, 1.0, np.where(v < 0.0, -1.0, math.copysign(1.0, self.h)))
        L = self.load
        return L.inertia * a + L.damping * v + L.friction * sense + self.position_torque(q)

    def torque(self, t, T: float, rotor: float):
        _, v, a = self.motion(t, T)
        tl = self.load_torque(t, T)
        through = np.where(tl * v >= 0.0, 1.0 / (N_GEAR * self.eta), self.eta / N_GEAR)
        return (rotor + ROTOR_GEAR) * N_GEAR * a + tl * through

    def hold(self) -> float:
        return abs(float(self.position_torque(self.h))) / (N_GEAR * self.eta)

@pytest.mark.parametrize("h, law, eta", [
    (1.5, "cycloidal", 1.0),   # every knot crossed, the peak at the table's sharp knot
    (1.5, "poly5", 0.9),
    (-0.25, "poly7", 1.0),     # backwards: the load drives part of the move
])
def test_peak_and_rms_against_independent_evaluations(h, law, eta):
    motors = tuple(falling(k) for k in range(3))
    T, dwell = 0.5, 0.3
    calc = calculator(TABLE, h, law, motors, eta, T, dwell)
    metrics = calc.evaluate(np.full(len(motors), T))
    ref = Independent(X, TAU, 0.1, TABLE, h, law, eta)
    for k, motor in enumerate(motors):
        assert metrics.peak_torque[k] == pytest.approx(ref.peak(T, motor.inertia, dwell),
                                                       rel=1e-9)
        assert metrics.rms_torque[k] == pytest.approx(ref.rms(T, motor.inertia, dwell),
                                                      rel=1e-9)


def test_a_table_of_gravity_approaches_gravity():
    arm = GravityLoad(moment=0.5, offset=-0.3)
    motors = tuple(falling(k) for k in range(2))
    base = Load(inertia=0.05, friction=0.2, gravity=arm)
    exact = calculator(base, math.pi / 2, "cycloidal", motors, 1.0, 0.45, 0.3)
    reference = exact.evaluate(np.full(2, 0.45))
    errors = []
    for n in (9, 33, 129):
        x = np.linspace(-0.01, math.pi / 2 + 0.01, n)
        table = TableLoad(tuple(x), tuple(0.5 * G * np.cos(x - 0.3)))
        calc = calculator(Load(inertia=0.05, friction=0.2, table=table), math.pi / 2,
                           "cycloidal", motors, 1.0, 0.45, 0.3)
        got = calc.evaluate(np.full(2, 0.45))
        errors.append(max(np.max(np.abs(got.peak_torque / reference.peak_torque - 1.0)),
                          np.max(np.abs(got.rms_torque / reference.rms_torque - 1.0))))
    # linear interpolation of a cosine: the error falls as the knots' spacing squared
    assert errors[0] > errors[1] > errors[2]
    assert errors[2] < 1e-4
    assert errors[1] / errors[2] > 10.0


def _t_min(motor: Motor, check: str, h: float, law: str, dwell: float, grip: float) -> float:
    from scipy.optimize import brentq

    ref = Independent(X, TAU, 0.1, TABLE, h, law, 0.9)
    if check == "peak":
        def excess(T):
            return ref.peak(T, motor.inertia, dwell) - grip * motor.peak_torque
    else:
        def excess(T):
            return ref.rms(T, motor.inertia, dwell) - grip * motor.continuous_torque
    return brentq(excess, 0.12, 0.6, xtol=1e-15, rtol=1e-13)


def test_t_min_where_the_position_terms_do_not_scale():
    motors = (flat(0, peak=1.6, continuous=100.0), flat(1, peak=100.0, continuous=1.0))
    h, law, dwell, grip = 1.5, "cycloidal", 0.3, 0.9
    calc = calculator(TABLE, h, law, motors, 0.9, None, dwell)
    settled = answer(calc, Limits(torque_margin=0.1), [], True)
    assert settled.feasible.all()
    assert settled.scale[0] == pytest.approx(_t_min(motors[0], "peak", h, law, dwell, grip),
                                             rel=1e-9)
    assert settled.scale[1] == pytest.approx(_t_min(motors[1], "rms", h, law, dwell, grip),
                                             rel=1e-9)


@pytest.mark.parametrize("h, law", [(0.12, "cycloidal"), (-0.08, "poly5")])
def test_a_force_table_on_a_linear_axis(h, law):
    # a linear axis (s in m, F in N) through a stage of ratio N rad/m: the same engine
    x, force = (-0.1, -0.02, 0.03, 0.07, 0.15), (40.0, 120.0, 310.0, -60.0, 90.0)
    load = Load(inertia=8.0, damping=3.0, friction=25.0, table=TableLoad(x, force))
    motors = tuple(falling(k) for k in range(2))
    drive = Drive(load, Transmission(stages=(Stage(ratio=N_GEAR, efficiency=0.9,
                                                   inertia=ROTOR_GEAR),)))
    T, dwell = 0.4, 0.2
    calc = position_calculator(Task(h, T, dwell=dwell, linear=True), law_choice(law).law,
                               load, drive, MotorArrays.of(motors, "electrical"))
    metrics = calc.evaluate(np.full(len(motors), T))
    ref = Independent(x, force, 0.0, load, h, law, 0.9)
    for k, motor in enumerate(motors):
        assert metrics.peak_torque[k] == pytest.approx(ref.peak(T, motor.inertia, dwell),
                                                       rel=1e-9)
        assert metrics.rms_torque[k] == pytest.approx(ref.rms(T, motor.inertia, dwell),
                                                      rel=1e-9)


def test_a_constant_force_table_sizes_as_the_constant_force(tmp_path):
    import sizer

    rows = []
    for name, extra in (("force", {"force": "300 N"}),
                        ("table", {"force_table": {"file": "f.csv", "offset": "-5 mm"}})):
        load = {"mass": "250 kg", "friction": "490 N", **extra}
        text = edited("vendor-ballscrew.yaml", set={"load": load, "laws": ["cycloidal"],
                                                    **POWER_FLOW})
        path = tmp_path / f"{name}.yaml"
        path.write_text(text, encoding="utf-8")
        (tmp_path / "f.csv").write_text("s [mm],F [kN]\n-10,0.3\n500,0.3\n", encoding="utf-8")
        rows.append(sizer.size(path).results)
    assert len(rows[0]) == len(rows[1]) > 0
    for a, b in zip(*rows, strict=True):
        assert (a.motor, a.law, a.feasible) == (b.motor, b.law, b.feasible)
        assert b.peak_torque == pytest.approx(a.peak_torque, rel=1e-9)
        assert b.rms_torque == pytest.approx(a.rms_torque, rel=1e-9)


def test_no_output_is_written_over_the_table_file(tmp_path):
    """The table's CSV is an input of the design: an output naming it is refused (exit 2)
    and the file is left as it was."""
    from cli_run import run_cli

    load = {"mass": "250 kg", "friction": "490 N",
            "force_table": {"file": "f.csv", "offset": "-5 mm"}}
    path = tmp_path / "design.yaml"
    path.write_text(edited("vendor-ballscrew.yaml", set={"load": load, **POWER_FLOW}),
                    encoding="utf-8")
    table = tmp_path / "f.csv"
    table.write_text("s [mm],F [kN]\n-10,0.3\n500,0.3\n", encoding="utf-8")
    result = run_cli("size", str(path), "--format", "csv", "-o", str(table))
    assert result.returncode == 2 and "f.csv" in result.stderr
    assert table.read_text(encoding="utf-8") == "s [mm],F [kN]\n-10,0.3\n500,0.3\n"


def test_a_move_beyond_the_table_is_refused():
    motors = MotorArrays.of((falling(0),), "electrical")
    law = law_choice("cycloidal").law
    with pytest.raises(UserError, match="table covers"):
        position_calculator(Task(2.0, 0.5), law, TABLE, Drive(TABLE, Transmission()), motors)


def test_table_term_is_linear_between_points():
    table = TableLoad((0.0, 1.0, 3.0), (1.0, 3.0, -1.0), offset=0.5)
    q = np.array([-0.5, 0.0, 0.5, 1.5, 2.5])
    assert np.allclose(table.torque(q), [1.0, 2.0, 3.0, 1.0, -1.0], rtol=1e-15, atol=1e-15)
    assert table.knots == (-0.5, 0.5, 2.5)
    assert not TableLoad((0.0, 1.0), (0.0, 0.0)).active
    assert Load(1.0, table=table).position_dependent


# ------------------------------------------------------------ bad fields, located
ROTARY = "book/ex6_1-6_2.yaml"
LINEAR = "vendor-ballscrew.yaml"
D = "design.yaml:"
POINTS = [["0 deg", "1 N*m"], ["60 deg", "3 N*m"], ["120 deg", "0.5 N*m"]]


def case(id: str, value: dict, words: tuple[str, ...], fields: tuple[str, ...],
         example: str = ROTARY, files: dict[str, str] | None = None,
         where: str = D) -> Case:
    return Case(id, design=edited(example, set=value), words=(where, *words), fields=fields,
                extra_files=files or {})


def table(**fields) -> dict:
    return {"load.torque_table": fields}


def forces(**fields) -> dict:
    return {"load.force_table": fields}


FORCES = [["0 mm", "100 N"], ["150 mm", "900 N"], ["300 mm", "-200 N"]]
POWER_FLOW = {"efficiency_applies_to": "power_flow"}


FIELD_CASES = [
    case("load-torque-table-unsorted",
         table(points=[POINTS[0], POINTS[2], POINTS[1]]),
         ("load.torque_table.points", "increase strictly"), ("load.torque_table.points",)),
    case("load-torque-table-one-point", table(points=[POINTS[0]]),
         ("load.torque_table.points", "at least 2"), ("load.torque_table.points",)),
    case("load-torque-table-torque-a-force", table(points=[POINTS[0], ["60 deg", "3 N"]]),
         ("load.torque_table.points",), ("load.torque_table.points",)),
    case("load-torque-table-offset-a-length", table(points=POINTS, offset="10 mm"),
         ("load.torque_table.offset",), ("load.torque_table.offset",)),
    case("load-torque-table-points-and-file", table(points=POINTS, file="t.csv"),
         ("load.torque_table", "one of them"), ("load.torque_table",)),
    case("load-torque-table-file-missing", table(file="missing.csv"),
         ("load.torque_table.file", "not found"), ("load.torque_table.file",)),
    case("load-torque-table-file-bad-unit", table(file="t.csv"),
         ("t.csv:1", "column 1"), ("load.torque_table.file",),
         files={"t.csv": "q [deg],tau [N]\n0,1\n120,2\n"}, where="t.csv"),
    case("load-torque-table-file-no-units", table(file="t.csv"),
         ("t.csv:1", "no unit"), ("load.torque_table.file",),
         files={"t.csv": "q,tau\n0,1\n120,2\n"}, where="t.csv"),
    case("load-torque-table-file-unsorted", table(file="t.csv"),
         ("t.csv:4", "increase strictly"), ("load.torque_table.file",),
         files={"t.csv": "q [deg],tau [N*m]\n0,1\n120,2\n60,3\n"}, where="t.csv"),
    case("load-torque-table-too-short", table(points=POINTS[:2]),
         ("load.torque_table", "table covers"), ("load.torque_table",)),
    case("load-torque-table-on-a-linear-axis", table(points=POINTS),
         ("load.torque_table", "takes 'force_table'"), ("load.torque_table",), LINEAR),
    case("load-force-table-on-a-rotary-axis", forces(points=FORCES),
         ("load.force_table", "takes 'torque_table'"), ("load.force_table",)),
    case("load-force-table-force-a-torque", {**forces(points=[FORCES[0], ["0.3 m", "2 N*m"]]),
                                             **POWER_FLOW},
         ("load.force_table.points",), ("load.force_table.points",), LINEAR),
    case("load-force-table-unsorted", {**forces(points=FORCES[::-1]), **POWER_FLOW},
         ("load.force_table.points", "increase strictly"), ("load.force_table.points",),
         LINEAR),
    case("load-force-table-offset-an-angle", {**forces(points=FORCES, offset="5 deg"),
                                              **POWER_FLOW},
         ("load.force_table.offset",), ("load.force_table.offset",), LINEAR),
    case("load-force-table-file-angle-unit", {**forces(file="f.csv"), **POWER_FLOW},
         ("f.csv:1", "is not a length unit"), ("load.force_table.file",), LINEAR,
         files={"f.csv": "s [deg],F [N]\n0,1\n400,2\n"}, where="f.csv"),
    case("load-force-table-short", {**forces(points=FORCES[:2]), **POWER_FLOW},
         ("load.force_table", "table covers"), ("load.force_table",), LINEAR),
]


@pytest.mark.parametrize("case", FIELD_CASES, ids=str)
def test_bad_torque_table_field(case, tmp_path):
    run(case, tmp_path)


def _position_cases() -> list[Case]:
    """Every position term's field cases (tests/test_bad_inputs_fields.py reads them)."""
    from test_position_inertia import FIELD_CASES as INERTIA
    from test_position_loads import FIELD_CASES as TERMS

    return [*TERMS, *FIELD_CASES, *INERTIA]


POSITION_FIELD_CASES = _position_cases()
"""Gravity's and the spring's cases (tests/test_position_loads.py) and the table's."""
