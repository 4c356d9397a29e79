"""sizer cam (issue 37): point-table exports and their certificates.

Each written file is parsed back here and interpolated independently (numpy.interp, the
chord slopes); the reference errors come from a very dense grid plus a brentq extremum
near the grid's largest error. The certificate must be at least the dense grid's maximum
and within 1e-9 (relative) of the true one.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

from sizer.cli.app import run
from sizer.export.profile import CamProfile
from sizer.export.sampling import table_for_tolerance, table_of
from sizer.export.targets import TARGETS
from sizer.laws import make_law

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
LAWS = ("cycloidal", "poly5", "modified_sinusoidal", "trapezoidal(alpha=1/3)",
        "double_s(alpha=1/3, beta=1/4)", "harmonic", "exponential(sigma=7.1, lam=1/5)",
        "{kind: cubic_spline, points: [[0, 0], [0.3, 0.15], [0.55, 0.8], [1, 1]]}")
DENSE = 1_000_001


def read_back(target: str, text: str) -> tuple[np.ndarray, np.ndarray]:
    """The (master, slave) columns of a written file, parsed as its controller would."""
    lines = text.splitlines()
    if target == "csv":
        assert lines[0] in ("time [s],position [deg]", "time [s],position [mm]",
                            "master [deg],position [deg]", "master [deg],position [mm]")
        rows = [line.split(",") for line in lines[1:]]
    elif target == "sew":
        count = int(lines[0])
        rows = [line.split(";") for line in lines[1:]]
        assert len(rows) == count
    else:
        rows = [line.split() for line in lines]
    data = np.array(rows, dtype=float)
    return data[:, 0], data[:, 1]


def law_at(law, stroke: float, span: float, x: np.ndarray, order: int) -> np.ndarray:
    """The scaled law, independently of sizer.export: stroke/span^k q_N^(k)(x/span)."""
    return stroke / span ** order * law.derivative(np.asarray(x) / span, order)


def reference_errors(law, stroke: float, span: float, x: np.ndarray, y: np.ndarray,
                     motion=None) -> tuple[float, float, float, float]:
    """(dense position, true position, dense velocity, true velocity) errors of the table
    (x, y) against the law scaled to stroke and span (or ``motion(x, order)`` over span)."""
    if motion is None:
        def motion(t, order):
            return law_at(law, stroke, span, t, order)
    grid = np.linspace(0.0, span, DENSE)
    slope = np.diff(y) / np.diff(x)
    interval = np.clip(np.searchsorted(x, grid, side="right") - 1, 0, len(slope) - 1)
    position = np.abs(motion(grid, 0) - np.interp(grid, x, y))
    velocity = np.abs(motion(grid, 1) - slope[interval])
    k = int(np.argmax(position))
    i = interval[k]

    def chord(t: float) -> float:
        return float(motion(np.array([t]), 1)[0] - slope[i])

    a, b = max(grid[max(k - 2, 0)], x[i]), min(grid[min(k + 2, DENSE - 1)], x[i + 1])
    true_position = float(position[k])
    if chord(a) * chord(b) < 0.0:
        r = brentq(chord, a, b, xtol=1e-15, rtol=4 * np.finfo(float).eps)
        at_r = abs(float(motion(np.array([r]), 0)[0])
                   - float(np.interp(r, x, y)))
        true_position = max(true_position, at_r)
    # the velocity error's largest on an interval is at its ends (one-sided) or where the
    # law's acceleration is zero (resolved by the dense grid to far below 1e-9)
    ends = np.max(np.abs(np.concatenate([motion(x[:-1], 1) - slope,
                                         motion(x[1:], 1) - slope])))
    return float(position.max()), true_position, float(velocity.max()), \
        max(float(velocity.max()), float(ends))


def assert_certified(certified: float, dense: float, true: float) -> None:
    assert certified >= dense * (1 - 1e-12)
    assert certified == pytest.approx(true, rel=1e-9, abs=1e-12)


@pytest.mark.parametrize("spec", LAWS)
def test_certificate_matches_the_file_read_back(spec: str) -> None:
    law = make_law(spec)
    profile = CamProfile(law, 90.0, 0.25)
    table = table_for_tolerance(profile, 1e-4)
    reference = reference_errors(law, 90.0, 0.25, table.master, table.slave)
    for target in sorted(TARGETS):
        x, y = read_back(target, TARGETS[target].write(table))
        assert np.array_equal(x, table.master) and np.array_equal(y, table.slave), target
    assert x[0] == 0.0 and x[-1] == 0.25 and y[0] == 0.0 and y[-1] == pytest.approx(90.0)
    dense_p, true_p, dense_v, true_v = reference
    assert_certified(table.errors.position, dense_p, true_p)
    assert_certified(table.errors.velocity, dense_v, true_v)
    assert table.met and table.errors.position <= 1e-4 * 90.0
    # the fewest points: one fewer misses the budget
    assert not table_of(profile, table.points - 1).errors.position <= 1e-4 * 90.0


def test_the_error_of_a_fine_table_nears_the_classic_bound() -> None:
    """On a fine equidistant table the error of a C2 law tends to max|y''| dx^2 / 8 (a
    bound): 2 pi * 0.01^2 / 8 for the cycloidal law (C_a = 2 pi) with 101 points."""
    law = make_law("cycloidal")
    profile = CamProfile(law, 1.0, 1.0)
    table = table_of(profile, 101)
    bound = 2 * math.pi * 0.01 ** 2 / 8
    assert table.errors.position <= bound
    assert table.errors.position == pytest.approx(bound, rel=1e-3)


def run_cam(args: list[str], capsys) -> tuple[int, str, str]:
    code = run(["cam", *args])
    out, err = capsys.readouterr()
    return code, out, err


def test_codesys_clips_to_128_points_and_says_so(tmp_path: Path, capsys) -> None:
    out_file, cert_file = tmp_path / "cam.txt", tmp_path / "cam.json"
    code, out, err = run_cam([str(EXAMPLES / "indexing-table.yaml"), "--to", "codesys-xy",
                              "-o", str(out_file), "--tolerance", "1e-6",
                              "--certificate", str(cert_file)], capsys)
    assert code == 1
    assert "clipped to 128 points" in out and "NOT met" in out and "not met" in err
    record = json.loads(cert_file.read_text())
    assert record["points"] == 128 and record["clipped"] and not record["tolerance_met"]
    assert record["points_needed"] > 128
    x, y = read_back("codesys-xy", out_file.read_text())
    assert len(x) == 128
    law = make_law(record["law"])
    T = record["master"]["span"]
    dense_p, true_p, dense_v, true_v = reference_errors(law, 90.0, T, x, y)
    assert_certified(record["errors"]["position"]["max"], dense_p, true_p)
    assert_certified(record["errors"]["velocity"]["max"], dense_v, true_v)
    assert record["errors"]["position"]["of_stroke"] > 1e-6


def test_the_design_check_pair_over_a_master_range(tmp_path: Path, capsys) -> None:
    out_file, cert_file = tmp_path / "cam.txt", tmp_path / "cam.json"
    code, out, _ = run_cam([str(EXAMPLES / "indexing-table.yaml"), "--to", "sew",
                            "-o", str(out_file), "--master-range", "360",
                            "--certificate", str(cert_file)], capsys)
    assert code == 0, out
    record = json.loads(cert_file.read_text())
    # the design's check: pair
    assert record["motor"] == "HG-KN43J" and record["law"] == "modified_sinusoidal"
    assert record["master"] == {"kind": "master position", "span": 360.0, "unit": "deg",
                                "move_duration_s": 0.25}
    x, y = read_back("sew", out_file.read_text())
    assert x[0] == 0.0 and x[-1] == 360.0 and y[-1] == pytest.approx(90.0)
    dense_p, true_p, dense_v, true_v = reference_errors(make_law("modified_sinusoidal"),
                                                        90.0, 360.0, x, y)
    assert_certified(record["errors"]["position"]["max"], dense_p, true_p)
    assert_certified(record["errors"]["velocity"]["max"], dense_v, true_v)
    assert record["errors"]["velocity"]["unit"] == "deg/deg"
    assert record["errors"]["acceleration"]["finite"] is False
    # over a master range the errors in slave units are those over time: the same table
    time_table = table_for_tolerance(CamProfile(make_law("modified_sinusoidal"), 90.0,
                                                0.25), 1e-4)
    assert record["points"] == time_table.points
    assert record["errors"]["position"]["max"] == pytest.approx(time_table.errors.position,
                                                                rel=1e-9)


def task_motion(law, h: float, T: float, D: float):
    """Move h in T, dwell D, move back in T, dwell D: y(x) and its derivatives."""
    def motion(x: np.ndarray, order: int) -> np.ndarray:
        forward = h / T ** order * law.derivative(x / T, order)
        back = h / T ** order * law.derivative((x - T - D) / T, order)
        return np.where(x < T + D, forward, (h if order == 0 else 0.0) - back)
    return motion


def test_the_machine_cycle_of_a_task_with_return(tmp_path: Path, capsys) -> None:
    out_file, cert_file = tmp_path / "cam.csv", tmp_path / "cam.json"
    code, out, _ = run_cam([str(EXAMPLES / "pick-and-place.yaml"), "--to", "csv", "--cycle",
                            "-o", str(out_file), "--certificate", str(cert_file)], capsys)
    assert code == 0, out
    record = json.loads(cert_file.read_text())
    assert [s["name"] for s in record["segments"]] == ["move", "dwell", "return", "dwell 2"]
    T = record["master"]["move_duration_s"]
    D = record["segments"][1]["span"]
    h = record["stroke"]
    assert record["master"]["span"] == pytest.approx(2 * (T + D))
    x, y = read_back("csv", out_file.read_text())
    assert y[0] == 0.0 and y[-1] == pytest.approx(0.0, abs=1e-12)
    motion = task_motion(make_law(record["law"]), h, T, D)
    dense_p, true_p, dense_v, true_v = reference_errors(None, h, 2 * (T + D), x, y, motion)
    assert_certified(record["errors"]["position"]["max"], dense_p, true_p)
    assert_certified(record["errors"]["velocity"]["max"], dense_v, true_v)
    assert record["tolerance_met"] and record["errors"]["position"]["of_stroke"] <= 1e-4
    # a dwell gets its ends only; the two moves the same points
    for dwell in (record["segments"][1], record["segments"][3]):
        start, end = dwell["start"], dwell["start"] + dwell["span"]
        assert start in x and end in x and not np.any((x > start) & (x < end))
    assert np.sum(x <= T) == np.sum((x >= T + D) & (x <= 2 * T + D))


def test_an_equidistant_cycle_over_a_master_range(tmp_path: Path, capsys) -> None:
    """CODESYS's ASCII table is equidistant: the dwell costs points, and 128 points miss
    1e-4 of the stroke for the indexing table's move and dwell (exit 1); SEW's pairs give
    the dwell its ends only."""
    code, out, _ = run_cam([str(EXAMPLES / "indexing-table.yaml"), "--to", "codesys-xy",
                            "--cycle", "--master-range", "360", "-o",
                            str(tmp_path / "c.txt")], capsys)
    assert code == 1 and "clipped to 128 points" in out
    x, _ = read_back("codesys-xy", (tmp_path / "c.txt").read_text())
    assert np.allclose(np.diff(x), 360.0 / 127)
    code, out, _ = run_cam([str(EXAMPLES / "indexing-table.yaml"), "--to", "sew", "--cycle",
                            "--master-range", "360", "-o", str(tmp_path / "s.txt"),
                            "--certificate", str(tmp_path / "s.json")], capsys)
    assert code == 0
    x, y = read_back("sew", (tmp_path / "s.txt").read_text())
    record = json.loads((tmp_path / "s.json").read_text())
    move_end = 360.0 * 0.25 / 0.6
    assert x[-2] == pytest.approx(move_end) and y[-1] == y[-2] == pytest.approx(90.0)
    motion = task_motion(make_law(record["law"]), 90.0, move_end, 360.0 - move_end)
    dense_p, true_p, dense_v, true_v = reference_errors(None, 90.0, 360.0, x, y, motion)
    assert_certified(record["errors"]["position"]["max"], dense_p, true_p)
    assert_certified(record["errors"]["velocity"]["max"], dense_v, true_v)


def test_a_law_alone_in_mm(tmp_path: Path, capsys) -> None:
    out_file, cert_file = tmp_path / "c.csv", tmp_path / "c.json"
    code, out, _ = run_cam(["cycloidal", "--displacement", "200 mm", "--duration", "0.5 s",
                            "--to", "csv", "-o", str(out_file), "--points", "50",
                            "--certificate", str(cert_file)], capsys)
    assert code == 0, out
    record = json.loads(cert_file.read_text())
    assert record["motor"] is None and record["tolerance"] is None
    assert record["points"] == 50 and record["slave_unit"] == "mm"
    x, y = read_back("csv", out_file.read_text())
    assert out_file.read_text().startswith("time [s],position [mm]\n")
    assert len(x) == 50 and x[-1] == 0.5 and y[-1] == pytest.approx(200.0)
    dense_p, true_p, dense_v, true_v = reference_errors(make_law("cycloidal"), 200.0, 0.5,
                                                        x, y)
    assert_certified(record["errors"]["position"]["max"], dense_p, true_p)
    assert_certified(record["errors"]["velocity"]["max"], dense_v, true_v)


def test_a_law_alone_over_a_master_range(tmp_path: Path, capsys) -> None:
    out_file, cert_file = tmp_path / "c.txt", tmp_path / "c.json"
    code, out, _ = run_cam(["poly5", "--displacement", "1 rev", "--duration", "2 s",
                            "--master-range", "2 rev", "--to", "codesys-xy", "-o",
                            str(out_file), "--certificate", str(cert_file)], capsys)
    assert code == 0, out
    record = json.loads(cert_file.read_text())
    assert record["stroke"] == pytest.approx(360.0) and record["master"]["span"] == 720.0
    x, y = read_back("codesys-xy", out_file.read_text())
    assert len(x) == record["points"] <= 128 and x[-1] == 720.0
    dense_p, true_p, dense_v, true_v = reference_errors(make_law("poly5"), 360.0, 720.0,
                                                        x, y)
    assert_certified(record["errors"]["position"]["max"], dense_p, true_p)
    assert_certified(record["errors"]["velocity"]["max"], dense_v, true_v)
    assert record["errors"]["position"]["of_stroke"] <= 1e-4


def test_another_pair_by_motor_and_law(tmp_path: Path, capsys) -> None:
    out_file = tmp_path / "c.csv"
    code, out, _ = run_cam([str(EXAMPLES / "indexing-table.yaml"), "--to", "csv", "-o",
                            str(out_file), "--motor", "HG-KN73J", "--law", "poly5"], capsys)
    assert code == 0 and "sized for HG-KN73J" in out and "polynomial(degree=5)" in out


@pytest.mark.parametrize(("args", "field"), [
    (["--to", "foo"], "--to"),
    (["--to", "codesys-xy", "--points", "200"], "--points"),
    (["--to", "csv", "--points", "20", "--tolerance", "1e-3"], "--points"),
    (["--to", "csv", "--tolerance", "0"], "--tolerance"),
    (["--to", "csv", "--master-range", "-5"], "--master-range"),
])
def test_user_errors(tmp_path: Path, capsys, args: list[str], field: str) -> None:
    code, _, err = run_cam([str(EXAMPLES / "indexing-table.yaml"), "-o",
                            str(tmp_path / "x.txt"), *args], capsys)
    assert code == 2 and err.startswith("error:") and field in err
    assert not (tmp_path / "x.txt").exists()


def test_a_cycle_of_segments_through_a_linkage_is_refused(tmp_path: Path, capsys) -> None:
    """A cycle of segments is exported (tests/test_cam_export_cycle.py), but not one
    through a linkage: its laws are at the linkage's output."""
    code, _, err = run_cam([str(EXAMPLES / "press-slider-crank-cycle.yaml"), "--to", "csv",
                            "-o", str(tmp_path / "x.csv")], capsys)
    assert code == 2 and "cycle of segments through a linkage is not exported" in err


def test_the_export_core_imports_no_surface_and_scipy_lazily() -> None:
    """sizer.export is core: no CLI, report or plotting import, and scipy only when a
    certificate is computed (start-up time)."""
    import subprocess
    import sys

    code = ("import sys, sizer.export.targets, sizer.export.linear_certificate, "
            "sizer.cli.cam_command\n"
            "bad = [m for m in sys.modules if m.startswith(('scipy', 'matplotlib', 'pandas'))]\n"
            "assert not bad, bad\n")
    subprocess.run([sys.executable, "-c", code], check=True)
    import ast

    for path in (Path(__file__).resolve().parents[1] / "sizer" / "export").glob("*.py"):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.module:
                assert not node.module.startswith(("sizer.cli", "sizer.report", "typer",
                                                   "rich", "matplotlib")), path
