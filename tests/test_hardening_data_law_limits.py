"""Laws defined by data in bounded memory and time: row and point limits refused at once,
a mid-size cam table answered under a 2 GiB address-space limit, and data that overflow
refused at the field without a leaked warning (issue 32)."""

from __future__ import annotations

import csv
import io
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from sizer.input_limits import (
    MAX_AUTO_TIMES_POINTS,
    MAX_CAM_TABLE_ROWS,
    MAX_VIA_POINTS,
)
from tests.cli_run import assert_user_error, run_cli


def _cycloidal_table(path: Path, rows: int) -> Path:
    """A cam table of the cycloidal law q = t - sin(2 pi t) / (2 pi), t in [0, 1]."""
    t = np.linspace(0.0, 1.0, rows)
    q = t - np.sin(2.0 * np.pi * t) / (2.0 * np.pi)
    with path.open("w") as out:
        out.write("t,q\n")
        np.savetxt(out, np.column_stack((t, q)), delimiter=",", fmt="%.17g")
    return path


def test_a_cam_table_over_the_row_limit_is_refused_naming_it(tmp_path: Path) -> None:
    path = _cycloidal_table(tmp_path / "big.csv", MAX_CAM_TABLE_ROWS + 1)
    result = run_cli("law", f"{{kind: cam_table, file: {path}}}", "--duration", "0.5 s",
                     "--displacement", "1 rad")
    assert_user_error(result, "MAX_CAM_TABLE_ROWS", f"{MAX_CAM_TABLE_ROWS:,}")


GIB = 1 << 30

_UNDER_2_GIB = textwrap.dedent("""
    import resource, sys
    resource.setrlimit(resource.RLIMIT_AS, (2 << 30, 2 << 30))
    from sizer.cli.app import main
    main(sys.argv[1:])
""")


def _limited(*args: str) -> subprocess.CompletedProcess[str]:
    """``sizer ARGS`` in a subprocess whose address space is limited to 2 GiB."""
    return subprocess.run([sys.executable, "-c", _UNDER_2_GIB, *args], capture_output=True,
                          text=True, timeout=120, check=False)


def test_a_mid_size_cam_table_is_answered_under_2_gib(tmp_path: Path) -> None:
    """2,000 rows of the cycloidal law: its coefficients are the closed form's, C_v = 2 and
    C_a = 2 pi (Table 2.2), with no warning, under a 2 GiB address space."""
    path = _cycloidal_table(tmp_path / "mid.csv", 2_000)
    result = _limited("laws", "--law", f"{{kind: cam_table, file: {path}}}",
                      "--format", "csv")
    assert result.returncode == 0, result.stderr
    assert "Warning" not in result.stderr
    values = next(csv.DictReader(io.StringIO(result.stdout)))
    assert float(values["C_v"]) == pytest.approx(2.0, rel=1e-6)
    assert float(values["C_a"]) == pytest.approx(2.0 * np.pi, rel=1e-4)


def _points(count: int) -> str:
    t = np.linspace(0.0, 1.0, count)
    return "[" + ", ".join(f"[{a!r}, {b!r}]" for a, b in zip(t.tolist(), t.tolist(),
                                                            strict=True)) + "]"


@pytest.mark.parametrize("kind", ["cubic_spline", "smoothing_spline", "via_trapezoid"])
def test_too_many_via_points_are_refused_naming_the_limit(kind: str) -> None:
    law = f"{{kind: {kind}, points: {_points(MAX_VIA_POINTS + 1)}}}"
    result = run_cli("laws", "--law", law)
    assert_user_error(result, "points", "MAX_VIA_POINTS", f"{MAX_VIA_POINTS + 1:,}")


def test_too_many_positions_for_times_auto_are_refused_naming_the_limit() -> None:
    positions = ", ".join(str(i) for i in range(MAX_AUTO_TIMES_POINTS + 1))
    result = run_cli("laws", "--law", f"{{kind: cubic_spline, times: auto, "
                                      f"positions: [{positions}]}}")
    assert_user_error(result, "positions", "MAX_AUTO_TIMES_POINTS")


@pytest.mark.parametrize(("law", "field"), [
    ("{kind: cubic_spline, times: auto, positions: [0, 0.15, 1.0e+308, 1]}", "positions[2]"),
    ("{kind: cubic_spline, points: [[0, 0], [0.5, 1.0e+308], [1, 1]]}", "points[1]"),
    ("{kind: cubic_spline, points: [[0, 0], [1.0e+308, 1]]}", "points[1]"),
    ("{kind: poly_spline, order: 4, points: [[0, 0], [0.5, 1.0e+308], [1, 1]], "
     "start: {velocity: 0}, end: {velocity: 0}}", "points[1]"),
    ("{kind: bspline, order: 4, points: [[0, 0], [0.5, 1.0e+308], [1, 1]], "
     "start: {velocity: 0}, end: {velocity: 0}}", "points[1]"),
    ("{kind: via_trapezoid, points: [[0, 0], [0.5, 1.0e+308], [1, 1]]}", "points[1]"),
    ("{kind: cubic_spline, points: [[0, 0], [0.5, 0.5], [1, 1]], "
     "start: {velocity: 1.0e+308}}", "start.velocity"),
])
def test_data_that_overflow_are_refused_at_the_value(law: str, field: str) -> None:
    result = run_cli("laws", "--law", law)
    line = assert_user_error(result, field, "not finite")
    assert "Warning" not in result.stderr, line


def test_a_curve_that_swings_far_beyond_its_displacement_is_refused() -> None:
    """Via-points 0, 1e11, 1: the curve reaches 1e11, 1e11 times its displacement 1."""
    result = run_cli("laws", "--law",
                     "{kind: cubic_spline, points: [[0, 0], [0.5, 1.0e+11], [1, 1]]}")
    assert_user_error(result, "points[1]", "MAX_DATA_LAW_EXCURSION")


@pytest.mark.parametrize("law", [
    "{kind: cubic_spline, times: auto, positions: [0, 0.15, 8.0e+299, 1]}",
    "{kind: cubic_spline, points: [[0, 1.0e-308], [1, 2.0e-308]]}",
    "{kind: cubic_spline, points: [[0, -0.0], [1, 1]]}",
    "{kind: nurbs, order: 4, points: [[0, 0], [0.5, 0.5], [1, 1]], "
    "weights: [1, 1.0e-308, 1, 1, 1], start: {velocity: 0}, end: {velocity: 0}}",
])
def test_extreme_but_finite_data_give_a_finite_law_or_an_error(law: str) -> None:
    """Exit 0 with finite numbers, or one user error; never an internal error, a warning,
    nan or inf."""
    result = run_cli("laws", "--law", law)
    assert result.returncode in (0, 2), result.stderr
    assert "Warning" not in result.stderr
    assert "nan" not in result.stdout.lower() and "inf" not in result.stdout.lower()
