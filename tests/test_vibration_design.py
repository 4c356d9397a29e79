"""The residual vibration of a design's moves (sizer.sizing.vibration_check, issue 15).

Every reference here is independent of sizer's transform: the mode's ODE (eq. 7.2,
z'' + 2 delta w z' + w^2 z = -y'') integrated by scipy's DOP853 over repeated cycles, or
the undamped residual |int a_N exp(-i w T tau)| / (w T) by scipy.integrate.quad.
"""

from __future__ import annotations

import json
import math
from dataclasses import replace

import numpy as np
import pytest
from cli_run import assert_user_error, run_cli
from scipy.integrate import quad, solve_ivp

from sizer.io import load_design
from sizer.laws import make_law
from sizer.sizing.engine import size_design
from sizer.vibration.elastic_load import ElasticLoad

ROOT = __import__("pathlib").Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "indexing-table-vibration.yaml"
ARCSEC = math.pi / 180.0 / 3600.0


def simulated_residuals(spec: str, h: float, T: float, dwell: float, load: ElasticLoad,
                        back: bool, cycles: int) -> list[float]:
    """The amplitude at the end of each move of the last of ``cycles`` repeated cycles
    (move, dwell[, move back, dwell]), by integrating eq. 7.2 piece by piece.

    Eq. 7.2 is linear: a move's end state is the free response from its start state plus
    the forced response from rest. The forced one (the law evaluated at every step, most
    of the time) is the same every cycle: integrated once a direction, piece by piece of
    the law (no kink inside a step), with the same DOP853 tolerances; the free one each
    cycle."""
    law = make_law(spec)
    w, d, wd = load.omega_n, load.damping_ratio, load.omega_d
    moves = [h, -h] if back else [h]
    forced: dict[float, np.ndarray] = {}

    def move(x, sign):
        if sign not in forced:
            forced[sign] = np.zeros(2)
            for i, piece in enumerate(law.pieces):  # piece by piece: no kink inside a step
                if piece.end <= piece.start:
                    continue

                def f(t, y, i=i):
                    a = sign * h * law.piece_derivative(i, np.array([t / T]), 2)[0] / T**2
                    return [y[1], -w * w * y[0] - 2 * d * w * y[1] - a]
                forced[sign] = solve_ivp(f, (piece.start * T, piece.end * T), forced[sign],
                                         method="DOP853", rtol=1e-12, atol=1e-18).y[:, -1]
        return free(x, T) + forced[sign]

    def free(x, span):
        f = lambda t, y: [y[1], -w * w * y[0] - 2 * d * w * y[1]]  # noqa: E731
        return solve_ivp(f, (0.0, span), x, method="DOP853", rtol=1e-12, atol=1e-18).y[:, -1]

    def rest(x):
        return free(x, dwell)

    x = np.zeros(2)
    out = []
    for _ in range(cycles):
        out = []
        for m in moves:
            x = move(x, np.sign(m))
            out.append(math.hypot(x[0], (x[1] + d * w * x[0]) / wd))
            if dwell > 0:
                x = rest(x)
    return out


def task_design(spec: str, T: float | None, dwell: float, load: ElasticLoad,
                back: bool = False, limit: float | None = None):
    base = load_design(EXAMPLE)
    task = replace(base.task, duration=T, dwell=dwell, return_move=back)
    return replace(base, task=task, laws=(spec,), load=replace(base.load, elastic=load),
                   limits=replace(base.limits, residual_vibration=limit),
                   motors=base.motors[:1])


@pytest.mark.parametrize("spec, back", [("cycloidal", True), ("harmonic", False),
                                        ("trapezoidal(alpha=1/3)", False),
                                        ("polynomial(degree=5)", True)])
def test_steady_state_residual_equals_the_integrated_ode(spec, back):
    load = ElasticLoad(10.0, 0.1)  # decays by exp(-pi) a cycle: 8 cycles are steady to 1e-10
    T, dwell, h = 0.23, 0.27, math.pi / 2
    result = size_design(task_design(spec, T, dwell, load, back)).results[0]
    expected = max(simulated_residuals(spec, h, T, dwell, load, back, cycles=8))
    assert result.residual_vibration == pytest.approx(expected, rel=1e-8)


def _undamped_residual(spec: str, fT: float) -> float:
    law = make_law(spec)
    x = 2 * math.pi * fT
    a = lambda t: law.derivative(np.array([t]), 2)[0]  # noqa: E731
    points = list(law.breakpoints[1:-1])
    re = quad(lambda t: a(t) * math.cos(x * t), 0, 1, points=points or None, limit=500)[0]
    im = quad(lambda t: a(t) * math.sin(x * t), 0, 1, points=points or None, limit=500)[0]
    return math.hypot(re, im) / x


@pytest.mark.parametrize("fT", [2.0, 3.0, 4.0])
def test_an_undamped_cycloidal_index_leaves_nothing_at_integer_fT(fT):
    load = ElasticLoad(fT / 0.25, 0.0)
    result = size_design(task_design("cycloidal", 0.25, 0.3, load)).results[0]
    assert result.residual_vibration < 1e-12


@pytest.mark.parametrize("spec", ["cycloidal", "trapezoidal(alpha=1/3)", "harmonic"])
def test_undamped_residual_of_a_single_move_is_the_transform_over_wT(spec):
    load = ElasticLoad(2.5 / 0.25, 0.0)  # f_n T = 2.5, undamped: the cycle run once
    h = math.pi / 2
    result = size_design(task_design(spec, 0.25, 0.3, load)).results[0]
    assert result.residual_vibration == pytest.approx(h * _undamped_residual(spec, 2.5),
                                                      rel=1e-9)


def test_minimize_moves_T_to_the_first_duration_meeting_the_limit():
    load = ElasticLoad(25.0, 0.02)
    limit = 20 * ARCSEC
    specs = ("double_s(alpha=1/3, beta=1/4)", "cycloidal")
    base = load_design(EXAMPLE)
    base = replace(base, motors=base.motors[2:3])
    free = size_design(replace(base, laws=specs,
                               limits=replace(base.limits, residual_vibration=None)))
    bound = size_design(replace(base, laws=specs))
    t_min = {(r.motor, r.spec): r.duration for r in free.results if r.feasible}
    checked: set[str] = set()
    for r in bound.results:
        if not r.feasible:
            continue
        assert r.residual_vibration <= limit * (1 + 1e-9)
        assert r.duration >= t_min[(r.motor, r.spec)] * (1 - 1e-12)
        if r.duration > t_min[(r.motor, r.spec)] * (1 + 1e-9) and not checked \
                and r.spec.startswith("double_s"):
            # the limit binds: just below T the steady residual is above it (one motor a
            # law: the residual does not depend on the motor)
            T = r.duration
            at = max(simulated_residuals(r.spec, math.pi / 2, T, 0.35, load, False, 7))
            before = max(simulated_residuals(r.spec, math.pi / 2, T * (1 - 1e-4), 0.35, load,
                                             False, 7))
            assert at == pytest.approx(limit, rel=1e-6)
            assert before > limit
            assert r.limiting == "residual_vibration"
            checked.add(r.spec)
    assert checked == {"double_s(alpha=1/3, beta=1/4)"}


def test_ranking_by_vibration_puts_the_smallest_residual_first():
    design = load_design(EXAMPLE)
    design = replace(design, task=replace(design.task, duration=0.6),
                     limits=replace(design.limits, residual_vibration=None))
    results = [r for r in size_design(design, rank_by="vibration").results if r.feasible]
    residuals = [r.residual_vibration for r in results]
    assert residuals == sorted(residuals)
    assert len(set(residuals)) > 1


def test_designs_without_a_mode_have_no_residual_column():
    plain = str(ROOT / "examples" / "book" / "ex6_4.yaml")
    result = run_cli("size", plain, "-f", "csv")
    assert result.returncode == 0
    assert "residual" not in result.stdout.splitlines()[0]
    assert_user_error(run_cli("size", plain, "--rank-by", "vibration"), "natural_frequency")


def test_size_exports_the_residual_in_si():
    csv = run_cli("size", str(EXAMPLE), "-f", "csv")
    header = csv.stdout.splitlines()[0].split(",")
    assert header[-1] == "residual_vibration [rad]"
    document = json.loads(run_cli("size", str(EXAMPLE), "-f", "json").stdout)
    first = next(r for r in document["results"] if r["limiting"] == "residual_vibration")
    assert first["residual_vibration"] == pytest.approx(20 * ARCSEC, rel=1e-9)
    assert any(c["name"] == "residual_vibration" for c in first["checks"])


def test_frequency_units_as_datasheets_write_them(tmp_path):
    text = EXAMPLE.read_text().replace("natural_frequency: 25 Hz", "natural_frequency: 1500 1/min")
    path = tmp_path / "d.yaml"
    path.write_text(text.replace("motors: catalogs/", f"motors: {EXAMPLE.parent}/catalogs/"))
    assert load_design(path).load.elastic == ElasticLoad(25.0, 0.02)
    path.write_text(path.read_text().replace("1500 1/min", "25"))  # a bare number is Hz
    assert load_design(path).load.elastic.natural_frequency == 25.0


def _peak_error(spec: str, h: float, T: float, load: ElasticLoad) -> float:
    """max |z| over the move from rest: the ODE's dense solution on 20,001 points."""
    law = make_law(spec)
    w, d = load.omega_n, load.damping_ratio

    def f(t, y):
        return [y[1], -w * w * y[0] - 2 * d * w * y[1]
                - h * law.derivative(np.array([t / T]), 2)[0] / T**2]
    sol = solve_ivp(f, (0.0, T), [0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-18,
                    dense_output=True)
    return float(np.max(np.abs(sol.sol(np.linspace(0.0, T, 20001))[0])))


def test_vibration_command_sweeps_the_durations(tmp_path):
    csv = run_cli("vibration", str(EXAMPLE), "--from", "0.2 s", "--to", "0.6", "-n", "5",
                  "-l", "cycloidal", "-f", "csv")
    assert csv.returncode == 0, csv.stderr
    lines = csv.stdout.splitlines()
    assert lines[0] == "T [s],cycloidal [rad],tracking error cycloidal [rad]"
    assert [float(line.split(",")[0]) for line in lines[1:]] == pytest.approx(
        [0.2, 0.3, 0.4, 0.5, 0.6])
    load = ElasticLoad(25.0, 0.02)
    T, value, tracking = (float(x) for x in lines[2].split(","))
    assert value == pytest.approx(max(simulated_residuals("cycloidal", math.pi / 2, T, 0.35,
                                                          load, False, 8)), rel=1e-7)
    assert tracking == pytest.approx(_peak_error("cycloidal", math.pi / 2, T, load), rel=1e-6)
    plot = tmp_path / "r.png"
    first = run_cli("vibration", str(EXAMPLE), "-n", "7", "-f", "json", "--plot", str(plot),
                    "--from", "0.3", "--to", "0.9")
    again = run_cli("vibration", str(EXAMPLE), "-n", "7", "-f", "json", "--from", "0.3",
                    "--to", "0.9")
    assert first.returncode == 0 and first.stdout == again.stdout
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert_user_error(run_cli("vibration", str(EXAMPLE), "--from", "0.5", "--to", "0.2"),
                      "--to")
    assert_user_error(run_cli("vibration", str(ROOT / "examples" / "book" / "ex6_4.yaml")),
                      "natural_frequency")


def test_a_cycle_with_runs_and_boundary_speeds_against_the_integrated_ode(tmp_path):
    """The flying saw: accelerate to the line speed, run, stop, return, dwell; each move's
    residual in the repeated cycle's steady state, the ODE driven by the moves' own
    accelerations (their polynomial shapes between boundary speeds)."""
    from sizer.laws.boundary_speeds import boundary_form

    text = (ROOT / "examples" / "flying-saw.yaml").read_text()
    text = text.replace("  closed: true\n", "  closed: true\n  cycle_time: 2 s\n")
    text = text.replace("  friction: 30 N\n",
                        "  friction: 30 N\n  natural_frequency: 8 Hz\n  damping_ratio: 0.05\n")
    path = tmp_path / "saw.yaml"
    path.write_text(text)
    design = load_design(path)
    design = replace(design, laws=("poly5",), motors=design.motors[-1:])
    result = size_design(design).results[0]
    load = ElasticLoad(8.0, 0.05)
    w, d, wd = load.omega_n, load.damping_ratio, load.omega_d
    # the free durations share 2 s - 0.4 s - 0.1 s by displacement (150, 100, 450 mm)
    s = (2.0 - 0.5) / 0.7
    basis = boundary_form(make_law("poly5"))
    segments = [("move", 0.15, 0.0, 0.5), ("run", 0.4), ("move", 0.10, 0.5, 0.0),
                ("move", -0.45, 0.0, 0.0), ("dwell", 0.1)]

    forced: dict[tuple[float, ...], np.ndarray] = {}

    def move(x, h, v0, v1, T):
        # the ODE is linear: the free response from x plus the forced response from rest,
        # the same every cycle (integrated once a move; see simulated_residuals)
        if (h, v0, v1, T) not in forced:
            s0, s1 = v0 * T / h, v1 * T / h
            f = lambda t, y: [y[1], -w * w * y[0] - 2 * d * w * y[1]  # noqa: E731
                              - h * basis.derivative(np.array([t / T]), 2, s0, s1)[0, 0] / T**2]
            forced[h, v0, v1, T] = solve_ivp(f, (0.0, T), [0.0, 0.0], method="DOP853",
                                             rtol=1e-12, atol=1e-18).y[:, -1]
        return rest(x, T) + forced[h, v0, v1, T]

    def rest(x, T):
        f = lambda t, y: [y[1], -w * w * y[0] - 2 * d * w * y[1]]  # noqa: E731
        return solve_ivp(f, (0.0, T), x, method="DOP853", rtol=1e-12, atol=1e-18).y[:, -1]

    x = np.zeros(2)
    for _ in range(7):
        ends = []
        for seg in segments:
            if seg[0] == "move":
                _, h, v0, v1 = seg
                x = move(x, h, v0, v1, abs(h) * s)
                ends.append(math.hypot(x[0], (x[1] + d * w * x[0]) / wd))
            else:
                x = rest(x, seg[1])
    assert result.residual_vibration == pytest.approx(max(ends), rel=1e-7)


def test_a_limit_no_duration_meets_is_named_as_the_reason():
    load = ElasticLoad(25.0, 0.02)
    design = task_design("harmonic", None, 0.35, load, limit=1e-15)
    design = replace(design, limits=replace(design.limits, inertia_ratio=None))
    result = size_design(design).results[0]
    assert not result.feasible and result.duration is None
    assert result.limiting == "residual_vibration"
    assert "residual_vibration" in result.reason
