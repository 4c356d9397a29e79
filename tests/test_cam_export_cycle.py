"""sizer cam of a design with a `cycle:` of segments (issue 37): the flying saw (accelerate
150 mm to the line's 0.5 m/s, run 0.4 s with it, stop over 100 mm, return 450 mm, wait
0.1 s) exported to every target.

The reference motion is built here, independently of sizer.export and of
sizer.laws.boundary_speeds: the segment durations from the cycle time the sizing reports
(the run and the wait fixed, the moves sharing the rest in proportion to their lengths),
the trapezoid between boundary speeds by the book's eqs. 3.13 (Biagiotti & Melchiorri),
the quintic between boundary speeds as the solution of its six end conditions. Each
written file is parsed back and interpolated as its controller does (linear; quintic
Hermite by scipy's BPoly; TwinCAT's polynomials solved from the written end conditions),
and its errors against the reference equal the certificate's.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

from sizer.cli.app import run

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
SAW = str(EXAMPLES / "flying-saw.yaml")
MOTOR = "SGM7A-70A"
LINE = 500.0  # the line's 0.5 m/s in mm/s
TRAPEZOID = "trapezoidal(alpha=1/3)"


# ------------------------------------------------------------- the reference motion
def durations(cycle_time: float) -> list[float]:
    """accelerate, cut, stop, return, wait: the run 0.4 s and the wait 0.1 s fixed, the
    moves in proportion to 150 : 100 : 450 mm."""
    free = cycle_time - 0.5
    return [free * 150 / 700, 0.4, free * 100 / 700, free * 450 / 700, 0.1]


def trapezoid(h: float, T: float, v0: float, v1: float, alpha: float = 1 / 3):
    """Eqs. 3.13a-c: q(t) and its derivatives on [0, T], T_a = T_d = alpha T."""
    ta = td = alpha * T
    vv = (h - (v0 * ta + v1 * td) / 2) / (T - ta / 2 - td / 2)

    def f(t: np.ndarray, order: int) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        s = T - t
        first = [v0 * t + (vv - v0) * t * t / (2 * ta), v0 + (vv - v0) * t / ta,
                 np.full_like(t, (vv - v0) / ta)]
        q_a = v0 * ta + (vv - v0) * ta / 2
        middle = [q_a + vv * (t - ta), np.full_like(t, vv), np.zeros_like(t)]
        last = [h - v1 * s - (vv - v1) * s * s / (2 * td), v1 + (vv - v1) * s / td,
                np.full_like(t, -(vv - v1) / td)]
        return np.where(t < ta, first[order], np.where(t < T - td, middle[order],
                                                       last[order]))
    return f


def polynomial(h: float, T: float, v0: float, v1: float, degree: int = 5):
    """The polynomial of degree 2m+1 with q(0) = 0, q(T) = h, q'(0) = v0, q'(T) = v1 and
    its derivatives of orders 2..m null at both ends (2m+2 conditions: numpy solves
    them)."""
    m = (degree - 1) // 2
    rows = [[math.perm(j, k) * t ** (j - k) if j >= k else 0.0 for j in range(degree + 1)]
            for t in (0.0, T) for k in range(m + 1)]
    rhs = [0.0, v0] + [0.0] * (m - 1) + [h, v1] + [0.0] * (m - 1)
    c = np.linalg.solve(np.array(rows), rhs)

    def f(t: np.ndarray, order: int) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        return sum(c[j] * math.perm(j, order) * t ** (j - order)
                   for j in range(order, degree + 1))
    return f


def motion(law: str, cycle_time: float, scale: float = 1.0):
    """The cycle by ``law`` (TRAPEZOID, poly3, poly5, poly7) as (x, order) ->
    d^order y/dx^order (mm, x = scale * t), and its segment ends in x."""
    T = durations(cycle_time)
    degree = {"poly3": 3, "poly5": 5, "poly7": 7}.get(law, 5)

    def shape(h: float, T: float, v0: float, v1: float):
        if law == TRAPEZOID:
            return trapezoid(h, T, v0, v1)
        return polynomial(h, T, v0, v1, degree)
    parts = [(shape(150.0, T[0], 0.0, LINE), 0.0),
             (lambda t, k: [LINE * t, np.full_like(t, LINE), np.zeros_like(t)][k], 150.0),
             (shape(100.0, T[2], LINE, 0.0), 350.0),
             (shape(-450.0, T[3], 0.0, 0.0), 450.0),
             (lambda t, k: np.zeros_like(t), 0.0)]
    ends = np.concatenate([[0.0], np.cumsum(T)])

    def y(x: np.ndarray, order: int, side: str = "right") -> np.ndarray:
        t = np.asarray(x, dtype=float) / scale
        k = np.clip(np.searchsorted(ends, t, side=side) - 1, 0, 4)
        out = np.zeros_like(t)
        for i, (f, origin) in enumerate(parts):
            m = k == i
            if m.any():
                out[m] = f(t[m] - ends[i], order) / scale ** order \
                    + (origin if order == 0 else 0.0)
        return out
    return y, ends * scale


# ------------------------------------------------------------------------ helpers
def export(tmp_path: Path, capsys, target: str, law: str, *extra: str):
    out_file = tmp_path / f"cam.{target}"
    cert_file = tmp_path / "cam.json"
    code = run(["cam", SAW, "--to", target, "-o", str(out_file), "--certificate",
                str(cert_file), "-m", MOTOR, "-l", law, *extra])
    out, err = capsys.readouterr()
    cert = json.loads(cert_file.read_text()) if cert_file.exists() else None
    return code, out, err, out_file, cert


def read_table(target: str, text: str) -> np.ndarray:
    lines = text.splitlines()
    if target == "csv":
        assert lines[0] in ("time [s],position [mm]", "master [deg],position [mm]")
        rows = [line.split(",") for line in lines[1:]]
    elif target == "sew":
        rows = [line.split(";") for line in lines[1:]]
        assert len(rows) == int(lines[0])
    elif target == "codesys-xy":
        rows = [line.split("\t") for line in lines]
    else:  # codesys-xyva
        body = [line for line in lines if not line.startswith("#")]
        assert body[0].startswith("X [")
        rows = [line.split(",") for line in body[1:]]
    return np.array(rows, dtype=float)


def linear_reference(y, ends: np.ndarray, x: np.ndarray, s: np.ndarray
                     ) -> tuple[float, float]:
    """The largest position error (dense grid) and velocity error (one-sided at every
    table point and segment end: the reference's velocity is piecewise linear or
    polynomial, the chord constant, so the extreme is at a cell end for the trapezoid
    and close to one for the quintic) of the linear table (x, s)."""
    dense = np.linspace(x[0], x[-1], 400_001)
    position = float(np.max(np.abs(y(dense, 0) - np.interp(dense, x, s))))
    slope = np.diff(s) / np.diff(x)
    cuts = np.unique(np.concatenate([x, ends]))
    eps = 1e-11 * x[-1]
    left, right = cuts[1:] - eps, cuts[:-1] + eps
    velocity = 0.0
    for t, side in ((left, "left"), (right, "right")):
        i = np.clip(np.searchsorted(x, t, side="right") - 1, 0, len(slope) - 1)
        velocity = max(velocity, float(np.max(np.abs(y(t, 1, side) - slope[i]))))
    return position, velocity


# -------------------------------------------------------------------------- tests
@pytest.mark.parametrize("target", ["csv", "sew", "codesys-xy"])
def test_point_tables_of_the_cycle_equal_an_independent_re_evaluation(
        tmp_path: Path, capsys, target: str) -> None:
    code, out, err, path, cert = export(tmp_path, capsys, target, TRAPEZOID)
    assert code in (0, 1), err
    cycle_time = cert["master"]["cycle_time_s"]
    assert cert["master"]["span"] == pytest.approx(cycle_time, rel=1e-12)
    y, ends = motion(TRAPEZOID, cycle_time)
    table = read_table(target, path.read_text())
    x, s = table[:, 0], table[:, 1]
    assert x[0] == 0.0 and x[-1] == pytest.approx(cycle_time, rel=1e-12)
    assert np.allclose(s, y(x, 0), rtol=0, atol=1e-9)
    position, velocity = linear_reference(y, ends, x, s)
    errors = cert["errors"]
    assert errors["position"]["max"] >= position * (1 - 1e-12)
    assert errors["position"]["max"] == pytest.approx(position, rel=1e-6)
    assert errors["velocity"]["max"] == pytest.approx(velocity, rel=1e-6)
    assert cert["stroke"] == 450.0  # the cycle's travel
    assert "whole cycle of 5 segments" in out
    if target != "codesys-xy":  # tables whose master values may be uneven
        # every segment end is a point; the run is its two ends, the line's speed
        for e in ends:
            assert np.min(np.abs(x - e)) <= 1e-12 * cycle_time
        run = (x >= ends[1] - 1e-12) & (x <= ends[2] + 1e-12)
        assert run.sum() == 2
        assert np.diff(s[run]) / np.diff(x[run]) == pytest.approx(LINE, rel=1e-12)


def test_the_boundary_speeds_meet_the_run_without_a_step(tmp_path: Path, capsys) -> None:
    """The velocity steps of a linear table: the chord slopes' differences with the
    law's speed at the ends (0 at rest); at the run's ends the move meets the run at the
    line's speed (no step of the law), so the step there is only the chords'."""
    code, _, err, path, cert = export(tmp_path, capsys, "csv", TRAPEZOID)
    assert code == 0, err
    y, ends = motion(TRAPEZOID, cert["master"]["cycle_time_s"])
    for e in ends[1:3]:
        before, after = y(np.array([e]), 1, "left"), y(np.array([e]), 1, "right")
        assert before == pytest.approx(LINE, rel=1e-12) and after == pytest.approx(LINE)
    table = read_table("csv", path.read_text())
    slope = np.diff(table[:, 1]) / np.diff(table[:, 0])
    steps = np.abs(np.diff(np.concatenate([[0.0], slope, [0.0]])))
    step = cert["errors"]["acceleration"]["largest_velocity_step"]
    assert step == pytest.approx(float(np.max(steps)), rel=1e-12)
    segments = {s["name"]: s for s in cert["segments"]}
    assert segments["cut"]["kind"] == "run"
    assert segments["accelerate"]["end_velocity"] == LINE
    assert segments["stop"]["start_velocity"] == LINE
    assert segments["cut"]["span"] == pytest.approx(0.4, rel=1e-12)
    assert segments["wait"]["span"] == pytest.approx(0.1, rel=1e-12)


def test_over_a_master_range_the_cycle_spans_it(tmp_path: Path, capsys) -> None:
    code, _, err, path, cert = export(tmp_path, capsys, "csv", TRAPEZOID,
                                      "--master-range", "360")
    assert code == 0, err
    cycle_time = cert["master"]["cycle_time_s"]
    scale = 360.0 / cycle_time
    y, ends = motion(TRAPEZOID, cycle_time, scale)
    table = read_table("csv", path.read_text())
    x, s = table[:, 0], table[:, 1]
    assert x[-1] == pytest.approx(360.0, rel=1e-12)
    assert np.allclose(s, y(x, 0), rtol=0, atol=1e-9)
    run = (x >= ends[1] - 1e-9) & (x <= ends[2] + 1e-9)
    assert np.diff(s[run]) / np.diff(x[run]) == pytest.approx(LINE / scale, rel=1e-12)
    position, velocity = linear_reference(y, ends, x, s)
    assert cert["errors"]["position"]["max"] == pytest.approx(position, rel=1e-6)
    assert cert["errors"]["velocity"]["max"] == pytest.approx(velocity, rel=1e-6)


@pytest.mark.parametrize("law", [TRAPEZOID, "poly5"])
def test_xyva_of_the_cycle_equals_a_quintic_hermite_re_evaluation(
        tmp_path: Path, capsys, law: str) -> None:
    from scipy.interpolate import BPoly

    code, _out, err, path, cert = export(tmp_path, capsys, "codesys-xyva", law,
                                        "--tolerance", "1e-3")
    assert code in (0, 1), err
    y, ends = motion(law, cert["master"]["cycle_time_s"])
    table = read_table("codesys-xyva", path.read_text())
    x = table[:, 0]
    # the written values are the reference's (right-sided; the end's left-sided)
    side = np.where(np.arange(len(x)) == len(x) - 1, 0, 1)
    for k in range(3):
        expected = np.where(side == 1, y(x, k, "right"), y(x, k, "left"))
        assert np.allclose(table[:, 1 + k], expected, rtol=0,
                           atol=1e-9 * max(1.0, float(np.max(np.abs(expected)))))
    for e in ends[1:3]:  # the boundary speeds at the run's ends: the line's
        i = int(np.argmin(np.abs(x - e)))
        assert abs(x[i] - e) < 1e-12 and table[i, 2] == pytest.approx(LINE, rel=1e-12)
    curve = BPoly.from_derivatives(x, table[:, 1:4])
    dense = np.linspace(0.0, x[-1], 400_001)
    for k, key in enumerate(("position", "velocity", "acceleration")):
        reference = float(np.max(np.abs(y(dense, k) - curve(dense, k))))
        for t in (x[1:] - 1e-12 * x[-1], x[:-1] + 1e-12 * x[-1]):  # one-sided at points
            reference = max(reference, float(np.max(np.abs(y(t, k) - curve(t, k)))))
        rounding = 1e-9 * float(np.max(np.abs(y(dense, k))))
        if reference < rounding:  # a quintic reproduced exactly: both at rounding
            assert cert["errors"][key]["max"] < rounding
            continue
        assert cert["errors"][key]["max"] >= reference * (1 - 1e-9)
        assert cert["errors"][key]["max"] == pytest.approx(reference, rel=1e-4)
    torques = cert["torques"]  # re-sized on the file's spans (test_cam_cycle_torques.py)
    assert torques["computed"] is True
    assert torques["exported_specs"][1] is None  # the run: no law of the file


def parse_twincat(text: str) -> list[dict[str, float | str]]:
    points = []
    for row in re.findall(r"\((FunctionType := [^)]*)\)", text):
        fields = dict(f.split(" := ") for f in row.split(", "))
        point: dict[str, float | str] = {"type": fields.pop("FunctionType").split(".")[1]}
        point.update({k: float(v) for k, v in fields.items()})
        points.append(point)
    return points


def twincat_curve(points, x: np.ndarray, order: int) -> np.ndarray:
    """Each segment by its type: Linear, or PolynomialN from its written end conditions
    (2m+2 conditions for degree 2m+1, a condition left out read as 0)."""
    masters = np.array([p["MasterPosition"] for p in points])
    k = np.clip(np.searchsorted(masters, x, side="right") - 1, 0, len(points) - 2)
    out = np.zeros_like(x)
    for i in np.unique(k):
        a, b = points[i], points[i + 1]
        X = b["MasterPosition"] - a["MasterPosition"]
        u = x[k == i] - a["MasterPosition"]
        if a["type"] == "Linear":
            slope = (b["SlavePosition"] - a["SlavePosition"]) / X
            out[k == i] = [a["SlavePosition"] + slope * u, slope + 0 * u, 0 * u][order]
            continue
        degree = int(str(a["type"])[-1])
        m = (degree - 1) // 2
        names = ("SlavePosition", "SlaveVelocity", "SlaveAcceleration", "SlaveJerk")
        rows, rhs = [], []
        for p, t in ((a, 0.0), (b, X)):
            for j in range(m + 1):
                rows.append([math.perm(n, j) * t ** (n - j) if n >= j else 0.0
                             for n in range(degree + 1)])
                rhs.append(float(p.get(names[j], 0.0)))
        c = np.linalg.solve(np.array(rows), rhs)
        out[k == i] = sum(c[n] * math.perm(n, order) * u ** (n - order)
                          for n in range(order, degree + 1))
    return out


@pytest.mark.parametrize(("law", "master_range"), [("poly5", None), ("poly5", "360"),
                                                   ("poly3", None), ("poly7", None)])
def test_twincat_writes_the_boundary_polynomials_exactly(
        tmp_path: Path, capsys, law: str, master_range: str | None) -> None:
    extra = () if master_range is None else ("--master-range", master_range)
    code, _, err, path, cert = export(tmp_path, capsys, "twincat-mc3", law, *extra)
    assert code == 0, err
    cycle_time = cert["master"]["cycle_time_s"]
    scale = 1.0 if master_range is None else 360.0 / cycle_time
    y, ends = motion(law, cycle_time, scale)
    points = parse_twincat(path.read_text())
    kind = f"Polynomial{law[-1]}"
    assert [p["type"] for p in points] == [kind, "Linear", kind, kind, "Linear", "Linear"]
    assert np.allclose([p["MasterPosition"] for p in points], ends, rtol=1e-14, atol=0)
    assert [p["SlavePosition"] for p in points] == [0.0, 150.0, 350.0, 450.0, 0.0, 0.0]
    # the boundary speeds: the line's 500 mm/s, at the run's two ends
    assert points[1]["SlaveVelocity"] == pytest.approx(LINE / scale, rel=1e-15)
    assert points[2]["SlaveVelocity"] == pytest.approx(LINE / scale, rel=1e-15)
    if law != "poly3":  # fixed by the form: null at every end of a poly5 or poly7
        assert all(p["SlaveAcceleration"] == 0.0 for p in points)
    if law == "poly7":
        assert all(p["SlaveJerk"] == 0.0 for p in points[:4])
    dense = np.linspace(0.0, ends[-1], 200_001)
    for order in range(3):
        peak = float(np.max(np.abs(y(dense, order))))
        error = float(np.max(np.abs(twincat_curve(points, dense, order) - y(dense, order))))
        assert error <= 1e-11 * peak
        certified = cert["errors"][("position", "velocity", "acceleration")[order]]["max"]
        assert certified <= 1e-11 * peak
    assert cert["segments"][1]["function_type"] == "Linear"


def test_twincat_refuses_a_boundary_law_it_cannot_name(tmp_path: Path, capsys) -> None:
    code, _, err, path, _ = export(tmp_path, capsys, "twincat-mc3", TRAPEZOID)
    assert code == 2 and not path.exists()
    assert "segment 'accelerate'" in err and "polynomial(degree=5)" in err
    assert "Traceback" not in err


def test_the_cycle_is_the_one_the_sizing_evaluated() -> None:
    """The exported profile against the sizing's own samples of the same pair
    (sizer.sizing.samples.task_curve: SegmentCycle.pieces) at the reported cycle time."""
    from sizer import api
    from sizer.export.cycle_profile import cycle_profile
    from sizer.sizing.samples import task_curve

    design = api.override(api.load(SAW, ()), motors=[MOTOR], laws=["poly5"])
    result = api.size(design).results[0]
    profile = cycle_profile(design, result.law_object, result.duration)
    curve = task_curve(design, result.motor_object, result.law_object, result.duration)
    inside = curve.time < curve.time[-1]
    t = curve.time[inside]
    assert np.allclose(profile.position(t), 1000 * curve.position[inside], rtol=0,
                       atol=1e-9)
    assert np.allclose(profile.derivative(t, 1), 1000 * curve.load_speed[inside], rtol=0,
                       atol=1e-7)
    assert profile.span == pytest.approx(result.duration, rel=1e-14)
    assert [s.span for s in profile.segments] == pytest.approx(
        durations(result.duration), rel=1e-12)


@pytest.mark.parametrize("degree", [3, 5, 7])
def test_a_boundary_polynomial_is_the_unique_one(degree: int) -> None:
    """The sizing's boundary polynomial (sizer.laws.boundary_speeds, frozen) IS the
    polynomial of its degree fixed by its 2m+2 end conditions (numpy's solution)."""
    from sizer import api
    from sizer.export.cycle_profile import FrozenShape, cycle_profile

    law = f"poly{degree}"
    design = api.override(api.load(SAW, ()), motors=[MOTOR], laws=[law])
    result = api.size(design).results[0]
    profile = cycle_profile(design, result.law_object, result.duration)
    T = durations(result.duration)
    for index, (h, v0, v1) in ((0, (150.0, 0.0, LINE)), (2, (100.0, LINE, 0.0))):
        move = profile.segments[index]
        assert isinstance(move.law, FrozenShape)
        reference = polynomial(h, T[index], v0, v1, degree)
        t = np.linspace(0.0, T[index], 1001)
        piece = np.full(t.shape, index)  # one piece per segment before it (dwell-free)
        for order in range(3):
            expected = reference(t, order)
            got = profile.derivative(move.start + t, order, piece) - (
                move.origin if order == 0 else 0.0)
            assert np.allclose(got, expected, rtol=0,
                               atol=1e-10 * float(np.max(np.abs(expected))))
