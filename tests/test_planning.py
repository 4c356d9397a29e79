"""Planning without a motor (book sec. 5.2.1, eq. 5.4, Table 5.1; docs/planning.md).

Expected numbers come from the book's printed values and from closed forms evaluated here
with numpy alone (the polynomials' own coefficients), never from sizer's output.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from cli_run import assert_user_error, run_cli

from sizer.errors import UserError
from sizer.laws import law_choice
from sizer.model.cycle import Cycle, Dwell, Move, Run, ShareRule, Task
from sizer.model.domain import Design, Limits, Load
from sizer.sizing.planning import LoadLimits, Shapes, minimum_durations, plan, scaling_factors

# the normalized polynomials of degree 3, 5, 7 (book eqs. 5.7, 5.9, 5.11), highest power first
POLYNOMIALS = {
    "polynomial(degree=3)": np.poly1d([-2, 3, 0, 0]),
    "polynomial(degree=5)": np.poly1d([6, -15, 10, 0, 0, 0]),
    "polynomial(degree=7)": np.poly1d([-20, 70, -84, 35, 0, 0, 0, 0]),
}

TABLE_5_1 = {  # book Table 5.1: h = 40, v_max = 30, a_max = 80; (T_vel, T_acc) as printed
    "polynomial(degree=3)": (2.0000, 1.7321),
    "polynomial(degree=5)": (2.5000, 1.6990),
    "polynomial(degree=7)": (2.9167, 1.9382),
}


def independent_peaks(name: str) -> tuple[float, float, float]:
    """max |q_N^(n)| for n = 1, 2, 3: at the roots of the next derivative and the ends."""
    q = POLYNOMIALS[name]
    peaks = []
    for order in (1, 2, 3):
        d = q.deriv(order)
        roots = [r.real for r in d.deriv().roots if abs(r.imag) < 1e-12 and 0 <= r.real <= 1]
        peaks.append(max(abs(d(t)) for t in [0.0, 1.0, *roots]))
    return peaks[0], peaks[1], peaks[2]


def shapes(*names: str) -> Shapes:
    return Shapes.of([law_choice(n) for n in names])


def test_table_5_1_to_its_printed_digits() -> None:
    names = list(TABLE_5_1)
    terms = minimum_durations(40.0, shapes(*names), LoadLimits(30.0, 80.0))
    for k, name in enumerate(names):
        T_vel, T_acc = TABLE_5_1[name]
        assert round(float(terms[0, k]), 4) == T_vel
        assert round(float(terms[1, k]), 4) == T_acc
        C_v, C_a, _ = independent_peaks(name)  # and to 1e-12 against the closed forms
        assert terms[0, k] == pytest.approx(C_v * 40 / 30, rel=1e-12)
        assert terms[1, k] == pytest.approx(math.sqrt(C_a * 40 / 80), rel=1e-12)
    assert not terms[2].any()  # no jerk limit: no bound


def test_example_5_3_durations_and_binding_limits() -> None:
    # poly3 with 30/80: T = 2 (speed); poly5 with 37.5/60: 2 and 1.962 (speed);
    # poly7 with 45/50: 1.944 and 2.4516 (acceleration)
    cases = [("polynomial(degree=3)", 30.0, 80.0, (2.0, 1.732), "speed"),
             ("polynomial(degree=5)", 37.5, 60.0, (2.0, 1.962), "speed"),
             ("polynomial(degree=7)", 45.0, 50.0, (1.944, 2.4516), "acceleration")]
    for name, v, a, printed, binds in cases:
        design = task_design(40.0, None, [name], Limits(max_speed=v, max_acceleration=a))
        row = plan(design).plans[0]
        T_vel, T_acc = row.segments[0].T_vel, row.segments[0].T_acc
        digits = len(str(printed[1]).split(".")[1])
        assert (round(T_vel, 3), round(T_acc, digits)) == (round(printed[0], 3), printed[1])
        assert row.binding == binds
        assert row.T_min == pytest.approx(max(T_vel, T_acc), rel=1e-15)


def test_eq_5_4_lambda_as_the_book_defines_it() -> None:
    h, T, v, a, j = 40.0, 3.0, 30.0, 80.0, 100.0
    name = "polynomial(degree=5)"
    C_v, C_a, C_j = independent_peaks(name)
    book = min(v / (C_v * h / T), math.sqrt(a / (C_a * h / T**2)),
               (j / (C_j * h / T**3)) ** (1 / 3))
    terms = scaling_factors(h, T, shapes(name), LoadLimits(v, a, j))
    assert float(terms.min()) == pytest.approx(book, rel=1e-12)
    # t = lambda t' (eq. 5.4): derivatives scale by lambda^n; at T / lambda the binding
    # limit is met exactly and none is exceeded (evaluated on the polynomial itself)
    lam = float(terms.min())
    tau = np.linspace(0.0, 1.0, 200001)
    q = POLYNOMIALS[name]
    peaks = [np.abs(q.deriv(n)(tau)).max() * h / (T / lam) ** n for n in (1, 2, 3)]
    ratios = [peaks[0] / v, peaks[1] / a, peaks[2] / j]
    assert max(ratios) == pytest.approx(1.0, rel=1e-9)
    design = task_design(h, T, [name], Limits(max_speed=v, max_acceleration=a, max_jerk=j))
    row = plan(design).plans[0]
    assert row.lam == pytest.approx(book, rel=1e-12)
    assert row.T_min == pytest.approx(T / book, rel=1e-12)
    assert row.binding == ("speed", "acceleration", "jerk")[int(np.argmax(ratios))]
    assert row.feasible  # lambda > 1: T could shrink to T / lambda


def test_a_duration_below_t_min_is_infeasible_and_exactly_t_min_is_feasible() -> None:
    limits = Limits(max_speed=30.0, max_acceleration=80.0)
    at = plan(task_design(40.0, 2.0, ["polynomial(degree=3)"], limits)).plans[0]
    assert at.feasible and at.lam == pytest.approx(1.0, rel=1e-15)
    below = plan(task_design(40.0, 1.9, ["polynomial(degree=3)"], limits)).plans[0]
    assert not below.feasible and below.lam == pytest.approx(1.9 / 2.0, rel=1e-12)
    assert "speed" in below.reason


def test_each_limit_can_bind() -> None:
    h = 1.0  # cycloidal: C_v = 2, C_a = 2 pi, C_j = 4 pi^2
    cases = [(Limits(max_speed=1.0, max_acceleration=1e3, max_jerk=1e6), "speed", 2.0),
             (Limits(max_speed=1e3, max_acceleration=2.0, max_jerk=1e6), "acceleration",
              math.sqrt(2 * math.pi / 2.0)),
             (Limits(max_speed=1e3, max_acceleration=1e3, max_jerk=1.0), "jerk",
              (4 * math.pi**2) ** (1 / 3))]
    for limits, binds, T_min in cases:
        row = plan(task_design(h, None, ["cycloidal"], limits)).plans[0]
        assert row.binding == binds
        assert row.T_min == pytest.approx(T_min, rel=1e-12)


def test_a_jerk_limit_makes_laws_with_jerk_impulses_infeasible() -> None:
    limits = Limits(max_speed=30.0, max_acceleration=80.0, max_jerk=500.0)
    laws = ["trapezoidal(alpha=1/3)", "polynomial(degree=3)", "polynomial(degree=5)"]
    for T in (None, 3.0):
        result = plan(task_design(40.0, T, laws, limits))
        by_law = {p.law: p for p in result.plans}
        for name in laws[:2]:
            row = by_law[name]
            assert not row.feasible and row.binding == "jerk"
            assert "jerk" in row.reason and math.isinf(row.T_min)
            if T is not None:
                assert row.lam == 0.0
        assert by_law[laws[2]].feasible
        assert result.plans[0].law == laws[2]  # feasible ranked first


def test_ranked_by_t_min_or_by_lambda() -> None:
    limits = Limits(max_speed=30.0, max_acceleration=80.0)
    laws = ["polynomial(degree=7)", "polynomial(degree=3)", "polynomial(degree=5)"]
    minimize = plan(task_design(40.0, None, laws, limits))
    assert [p.law for p in minimize.plans] == [laws[1], laws[2], laws[0]]
    given = plan(task_design(40.0, 3.5, laws, limits))
    lams = [p.lam for p in given.plans]
    assert lams == sorted(lams, reverse=True)
    assert [p.law for p in given.plans] == [laws[1], laws[2], laws[0]]


def test_a_cycle_scales_its_free_moves_together() -> None:
    h1, h2 = math.pi / 2, math.pi
    cycle = Cycle((Move(h1, None, name="index 1"), Dwell(0.3, name="check"),
                   Move(h2, None, name="index 2"), Dwell(0.4, name="press")),
                  share=ShareRule.SQRT_DISPLACEMENT)
    limits = Limits(max_speed=2 * math.pi, max_acceleration=20.0)
    design = Design(load=Load(inertia=1.0), laws=("cycloidal",), limits=limits, cycle=cycle)
    row = plan(design).plans[0]
    need = [max(2 * h / limits.max_speed, math.sqrt(2 * math.pi * h / limits.max_acceleration))
            for h in (h1, h2)]
    weights = [math.sqrt(h1), math.sqrt(h2)]
    s = max(n / w for n, w in zip(need, weights, strict=True))
    assert row.scale == pytest.approx(s, rel=1e-12)
    assert row.T_min == pytest.approx(0.7 + s * sum(weights), rel=1e-12)
    assert row.segment == "index 2" and row.binding == "speed"


def test_a_run_is_refused() -> None:
    cycle = Cycle((Move(1.0, None, end_speed=1.0), Run(1.0, 1.0), Move(1.0, None,
                                                                      start_speed=1.0)))
    design = Design(load=Load(inertia=1.0), laws=("poly5",),
                    limits=Limits(max_speed=3.0), cycle=cycle)
    with pytest.raises(UserError, match="without a motor"):
        plan(design)


def task_design(h: float, T: float | None, laws: list[str], limits: Limits) -> Design:
    return Design(Task(h, T), Load(inertia=1.0), laws=tuple(laws), limits=limits)


# ------------------------------------------------------------------ end to end (CLI)

DESIGN = """\
name: belt axis
task: {{displacement: 300 mm, duration: {duration}, return: true, dwell: 0.1 s}}
load: {{mass: 3 kg}}
laws: [cycloidal, poly5, "trapezoidal(alpha=1/3)"]
motors: []
limits: {{max_speed: 2 m/s, max_acceleration: 20 m/s^2{jerk}}}
"""


def run(tmp_path: Path, *args: str, duration: str = "minimize", jerk: str = "",
        text: str | None = None) -> tuple[int, str, str]:
    design = tmp_path / "axis.yaml"
    design.write_text(text if text is not None else
                      DESIGN.format(duration=duration, jerk=jerk))
    result = run_cli("size", str(design), *args)
    return result.returncode, result.stdout, result.stderr


def test_cli_minimize_json(tmp_path: Path) -> None:
    code, out, _ = run(tmp_path, "--format", "json")
    assert code == 0
    data = json.loads(out)
    assert data["mode"] == "minimize" and data["axis"] == "linear"
    assert data["limits"] == {"max_speed": 2.0, "max_acceleration": 20.0, "max_jerk": None}
    rows = {r["law"]: r for r in data["laws"]}
    h = 0.3  # trapezoidal(1/3): C_v = 3/2, C_a = 9/2
    T_trap = max(1.5 * h / 2.0, math.sqrt(4.5 * h / 20.0))
    assert rows["trapezoidal(alpha=1/3)"]["T_min"] == pytest.approx(T_trap, rel=1e-12)
    assert rows["trapezoidal(alpha=1/3)"]["binding"] == "acceleration"
    T_cyc = max(2 * h / 2.0, math.sqrt(2 * math.pi * h / 20.0))
    assert rows["cycloidal"]["T_min"] == pytest.approx(T_cyc, rel=1e-12)
    assert data["laws"][0]["rank"] == 1 and data["laws"][0]["law"] == "trapezoidal(alpha=1/3)"
    assert rows["cycloidal"]["segments"][0]["T_jerk"] is None  # no jerk limit given


def test_cli_given_duration_and_the_jerk_limit(tmp_path: Path) -> None:
    code, out, _ = run(tmp_path, "--format", "json", duration="0.4 s", jerk=", max_jerk: 500 m/s^3")
    assert code == 0
    rows = {r["law"]: r for r in json.loads(out)["laws"]}
    trap = rows["trapezoidal(alpha=1/3)"]
    assert not trap["feasible"] and trap["lambda"] == 0.0 and trap["T_min"] is None
    cyc = rows["cycloidal"]  # lambda = min(v T / (C_v h), sqrt(a T^2 / (C_a h)), ...)
    h, T = 0.3, 0.4
    lam = min(2.0 * T / (2 * h), math.sqrt(20.0 * T**2 / (2 * math.pi * h)),
              (500.0 * T**3 / (4 * math.pi**2 * h)) ** (1 / 3))
    assert cyc["lambda"] == pytest.approx(lam, rel=1e-12) and cyc["feasible"]
    code, csv, _ = run(tmp_path, "--format", "csv", duration="0.4 s")
    assert code == 0 and csv.splitlines()[0].startswith("rank,law,feasible,T_min")
    code, table, _ = run(tmp_path, duration="0.4 s")
    assert code == 0 and "lambda" in table and "cycloidal" in table


def test_cli_no_feasible_law_and_user_errors(tmp_path: Path) -> None:
    code, out, err = run(tmp_path, "--format", "json", duration="0.05 s")
    assert code == 0 and not json.loads(out)["any_feasible"]  # as sizing: the report says so
    assert "no feasible law" in err
    design = tmp_path / "axis.yaml"
    assert_user_error(run_cli("size", str(design), "--rank-by", "price"), "--rank-by")
    assert_user_error(run_cli("size", str(design), "--front"), "--front")
    no_limits = DESIGN.format(duration="minimize", jerk="").replace(
        "max_speed: 2 m/s, max_acceleration: 20 m/s^2", "torque_margin: 10 %")
    design.write_text(no_limits)
    assert_user_error(run_cli("size", str(design)), "motors", "no motors to size",
                      "plan without a motor")


CYCLE = """\
name: two indexes
cycle:
  share: sqrt_displacement
  segments:
    - move: {{displacement: 90 deg, duration: {first}, name: index 1}}
    - dwell: {{duration: 0.3 s, name: check}}
    - move: {{displacement: 180 deg, duration: {second}, name: index 2}}
    - dwell: {{duration: 0.4 s, name: press}}
load: {{inertia: 0.034 kg*m^2}}
laws: [cycloidal, poly5]
motors: []
limits: {{max_speed: 60 rpm, max_acceleration: 20 rad/s^2}}
"""


def test_cli_cycle_minimize_and_given(tmp_path: Path) -> None:
    v, a = 2 * math.pi, 20.0  # 60 rpm
    h1, h2 = math.pi / 2, math.pi
    code, out, _ = run(tmp_path, "--format", "json",
                       text=CYCLE.format(first="free", second="free"))
    assert code == 0
    rows = {r["law"]: r for r in json.loads(out)["laws"]}
    need = [max(2 * h / v, math.sqrt(2 * math.pi * h / a)) for h in (h1, h2)]
    weights = [math.sqrt(h1), math.sqrt(h2)]
    s = max(n / w for n, w in zip(need, weights, strict=True))
    assert rows["cycloidal"]["scale"] == pytest.approx(s, rel=1e-12)
    assert rows["cycloidal"]["T_min"] == pytest.approx(0.7 + s * sum(weights), rel=1e-12)
    code, out, _ = run(tmp_path, "--format", "json",
                       text=CYCLE.format(first="0.8 s", second="1.2 s"))
    assert code == 0
    row = {r["law"]: r for r in json.loads(out)["laws"]}["cycloidal"]
    lams = [min(v * T / (2 * h), math.sqrt(a * T**2 / (2 * math.pi * h)))
            for h, T in ((h1, 0.8), (h2, 1.2))]
    assert row["lambda"] == pytest.approx(min(lams), rel=1e-12)
    assert row["segment"] == ("index 1", "index 2")[int(np.argmin(lams))]
    assert row["T_min"] == pytest.approx(2.7 / min(lams), rel=1e-12)


def test_a_fixed_move_shorter_than_its_t_min_fails_the_minimized_cycle() -> None:
    cycle = Cycle((Move(1.0, None, name="free one"), Move(-1.0, 0.5, name="fixed one")))
    design = Design(load=Load(inertia=1.0), laws=("cycloidal",),
                    limits=Limits(max_speed=2.0), cycle=cycle)  # T_min = 2 h / v = 1 s
    row = plan(design).plans[0]
    assert not row.feasible and "fixed one" in row.reason and row.binding == "speed"
    design = Design(load=Load(inertia=1.0), laws=("cycloidal",),
                    limits=Limits(max_speed=4.0), cycle=cycle)  # T_min = 0.5 s: just met
    row = plan(design).plans[0]
    assert row.feasible and row.T_min == pytest.approx(0.5 + 0.5, rel=1e-12)


def test_the_python_api_plans_as_the_command(tmp_path: Path) -> None:
    """sizer.plan gives the laws' T_min of Table 5.1 (poly5: max(C_v h/v, sqrt(C_a h/a))
    with C_v = 15/8, C_a = 10/sqrt(3), h = 40, v = 30, a = 80)."""
    import sizer

    design = tmp_path / "plan.yaml"
    design.write_text("name: api plan\ntask: {displacement: 40 rad, duration: minimize}\n"
                      "load: {inertia: 1 kg*m^2}\nlaws: [poly3, poly5]\nmotors: []\n"
                      "limits: {max_speed: 30 rad/s, max_acceleration: 80 rad/s^2}\n")
    result = sizer.plan(design, laws=["poly5"])
    assert [p.law for p in result.plans] == ["poly5"]
    expected = max(15 / 8 * 40 / 30, math.sqrt(10 / math.sqrt(3) * 40 / 80))
    assert result.plans[0].T_min == pytest.approx(expected, rel=1e-12)
    assert result.plans[0].binding == "speed"


def test_motors_left_out_with_the_load_limits_is_a_plan_and_needs_no_load(
        tmp_path: Path) -> None:
    """Issue 38: `motors:` may be left out when the load's limits are given (and then the
    load too); without the limits a design naming no motors is sized against the bundled
    catalogs, and with `--catalog` (or named motors) its load is required as always.
    Table 5.1's poly3 row: T_vel = 3/2 h / v = 2, T_acc = sqrt(6 h / a) = 1.7321."""
    design = tmp_path / "table51.yaml"
    design.write_text("name: table 5.1\ntask: {displacement: 40 rad, duration: minimize}\n"
                      "laws: [poly3]\n"
                      "limits: {max_speed: 30 rad/s, max_acceleration: 80 rad/s^2}\n")
    result = run_cli("size", str(design), "--format", "json")
    assert result.returncode == 0, result.stderr
    row = json.loads(result.stdout)["laws"][0]
    assert row["T_min"] == pytest.approx(1.5 * 40 / 30, rel=1e-12)
    assert row["binding"] == "speed"
    assert_user_error(run_cli("size", str(design), "--catalog", "siemens-1ft7"),
                      "load.inertia", "required field is missing")
    # the commands about motors say why there are none
    assert_user_error(run_cli("report", str(design), "-o", str(tmp_path / "r.md")),
                      "no motors to size", "is a plan")
    named = design.read_text() + "motors: [siemens-1ft7]\n"
    design.write_text(named)
    assert_user_error(run_cli("size", str(design)), "load.inertia")
    sized = named.replace("laws:", "load: {inertia: 0.01 kg*m^2}\nlaws:")
    design.write_text(sized.replace("motors: [siemens-1ft7]\n", ""))  # a load: still a plan
    out = run_cli("size", str(design), "--format", "json")
    assert out.returncode == 0 and "laws" in json.loads(out.stdout)
    design.write_text(sized)  # named motors: sized
    out = run_cli("size", str(design), "--format", "json")
    assert out.returncode == 0 and "results" in json.loads(out.stdout)
    catalogs = tmp_path / "catalogs.yaml"  # no load limits: the bundled catalogs
    catalogs.write_text("name: bundled\ntask: {displacement: 40 rad, duration: 2 s}\n"
                        "load: {inertia: 0.01 kg*m^2}\nlaws: [poly3]\n")
    out = run_cli("size", str(catalogs), "--format", "json")
    assert out.returncode == 0 and len(json.loads(out.stdout)["results"]) > 10


def test_a_machine_axis_without_motors_is_sized_against_the_bundled_catalogs() -> None:
    """A machine is sized, never planned: an axis naming no motors gets the bundled
    catalogs even where it gives the load's limits (as a design without those limits)."""
    import yaml

    from sizer.io.loader import default_catalogs, load_catalog
    from sizer.io.machine_loader import load_machine_data

    root = Path(__file__).resolve().parents[1] / "examples" / "machines"
    data = yaml.safe_load((root / "two-axis-packer.yaml").read_text())
    axis = data["axes"][0]
    del axis["motors"]
    axis["limits"]["max_speed"] = "300 rpm"
    machine = load_machine_data(data, base=root)
    bundled = sum(len(load_catalog(path)) for path in default_catalogs().values())
    assert len(machine.axes[0].design.motors) == bundled
