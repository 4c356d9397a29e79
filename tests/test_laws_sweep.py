"""Coefficient studies (issue 36; book sec. 6.2.1, Figs. 6.10 and 6.14): `sizer laws
--sweep` against closed forms of the book."""

from __future__ import annotations

import csv
import io
import json
import math
import subprocess
import sys

import numpy as np
import pytest

from sizer.errors import UserError
from sizer.laws.sweep import DEFAULT_POINTS, parse_sweep, sweep_coefficients


def run(*args: str, cwd=None) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "sizer", *args], capture_output=True,
                          text=True, cwd=cwd, check=False)


def test_trapezoid_against_the_closed_forms_of_sec_6_2_1() -> None:
    result = sweep_coefficients("trapezoidal(alpha=0.05..0.5)")
    alpha = np.array([p.values[0] for p in result.points])
    assert len(alpha) == DEFAULT_POINTS and alpha[0] == 0.05 and alpha[-1] == 0.5
    np.testing.assert_allclose(result.column("C_v"), 1 / (1 - alpha), rtol=1e-12)
    np.testing.assert_allclose(result.column("C_a"), 1 / (alpha * (1 - alpha)), rtol=1e-12)
    # two constant-acceleration phases of alpha*T each (footnote 4 of sec. 6.2.1)
    np.testing.assert_allclose(result.column("C_a_rms"),
                               np.sqrt(2 * alpha) / (alpha * (1 - alpha)), rtol=1e-9)
    # v ramps over alpha at both ends: integral of v^2 = C_v^2 (1 - 4 alpha / 3)
    np.testing.assert_allclose(result.column("C_v_rms"),
                               np.sqrt(1 - 4 * alpha / 3) / (1 - alpha), rtol=1e-9)
    assert all(p.jerk_bounded is False for p in result.points)


def test_double_s_over_beta_against_fig_6_14() -> None:
    """C_a^ss = C_a^tr / (1 - beta), C_a_rms^ss = C_a_rms^tr sqrt((3 - 4 beta)/3)/(1 - beta)."""
    alpha = 1 / 3
    result = sweep_coefficients("double_s(alpha=1/3, beta=0.05..0.5:10)")
    beta = np.array([p.values[0] for p in result.points])
    c_a_tr = 1 / (alpha * (1 - alpha))
    c_a_rms_tr = math.sqrt(2 * alpha) * c_a_tr
    np.testing.assert_allclose(result.column("C_a"), c_a_tr / (1 - beta), rtol=1e-9)
    np.testing.assert_allclose(result.column("C_a_rms"),
                               c_a_rms_tr * np.sqrt((3 - 4 * beta) / 3) / (1 - beta),
                               rtol=1e-9)
    np.testing.assert_allclose(result.column("C_v"), 1 / (1 - alpha), rtol=1e-12)


def test_two_parameters_make_a_grid_and_invalid_points_keep_their_reason() -> None:
    result = sweep_coefficients("double_s(alpha=0.25..0.75:3, beta=1/4..1/2:2)")
    assert [p.values for p in result.points] == [
        (0.25, 0.25), (0.5, 0.25), (0.75, 0.25), (0.25, 0.5), (0.5, 0.5), (0.75, 0.5)]
    bad = [p for p in result.points if p.coefficients is None]
    assert [p.values[0] for p in bad] == [0.75, 0.75] and all("alpha" in p.reason for p in bad)
    # book Table 6.7: alpha = 1/2, beta = 1/2 gives C_a_rms = 4.6188
    assert result.points[4].coefficients["C_a_rms"] == pytest.approx(4.6188, abs=1e-4)


@pytest.mark.parametrize("text, words", [
    ("trapezoidal", "write a law with a range"),
    ("trapezoidal(alpha=1/4)", "no range"),
    ("trapezoidal(alpha=0.1..0.5:1)", "at least 2 points"),
    ("trapezoidal(alpha=0.1..0.5:x)", "whole number"),
    ("trapezoidal(alpha=a..0.5)", "not a number"),
    ("trapezoidal(alpha=0.2..0.2)", "empty"),
    ("trapezoidal(0.1..0.4)", "parameter's name"),
    ("double_s(alpha=0.1..0.4:50, beta=0.1..0.4:50)", "the limit is"),
    ("poly5(a=0..1, b=0..1, c=0..1)", "one or two"),
])
def test_sweeps_that_cannot_be_read(text: str, words: str) -> None:
    with pytest.raises(UserError, match=words):
        parse_sweep(text)


def test_a_law_that_exists_nowhere_in_the_range() -> None:
    with pytest.raises(UserError, match="at no point"):
        sweep_coefficients("trapezoidal(alpha=0.6..0.9:3)")


def test_cli_csv_json_and_plot(tmp_path) -> None:
    done = run("laws", "--sweep", "trapezoidal(alpha=0.1..0.5:5)", "--format", "csv")
    assert done.returncode == 0, done.stderr
    rows = list(csv.DictReader(io.StringIO(done.stdout)))
    # five equidistant points 0.1 .. 0.5 (each exact to the float's rounding)
    assert [float(r["alpha"]) for r in rows] == pytest.approx([0.1, 0.2, 0.3, 0.4, 0.5],
                                                              rel=1e-15)
    assert float(rows[-1]["C_a"]) == pytest.approx(4.0, rel=1e-12)
    assert rows[0]["C_j"] == "" and rows[0]["jerk_bounded"] == "false"
    document = json.loads(run("laws", "--sweep", "trapezoidal(alpha=0.1..0.5:5)",
                              "--format", "json").stdout)
    assert document["ranges"] == [{"name": "alpha", "from": 0.1, "to": 0.5, "points": 5}]
    assert document["points"][0]["C_a"] == pytest.approx(1 / 0.09, rel=1e-12)
    figure = tmp_path / "sweep.svg"
    done = run("laws", "--sweep", "double_s(alpha=0.1..0.5:5, beta=0.1..0.5:3)",
               "--plot", str(figure), "--format", "md")
    assert done.returncode == 0, done.stderr
    assert figure.read_text().lstrip().startswith(("<?xml", "<svg"))
    assert "| alpha | beta |" in done.stdout.replace("  ", " ")


@pytest.mark.parametrize("args, words", [
    (["--plot", "x.png"], "--plot"),
    (["--sweep", "trapezoidal(alpha=0.1..0.5)", "--plot", "x.pdf"], "--plot"),
    (["--sweep", "trapezoidal(alpha=0.1..0.5)", "--law", "cycloidal"], "--sweep"),
    (["--sweep", "nolaw(alpha=0.1..0.5)"], "--sweep: unknown law"),
])
def test_cli_user_errors(args, words, tmp_path) -> None:
    done = run("laws", *args, cwd=tmp_path)
    assert done.returncode == 2 and "Traceback" not in done.stderr
    assert words in done.stderr


def test_t_min_of_a_design_against_eq_6_2(tmp_path) -> None:
    """Example 6.3 (h = 0.6 rad, J = 0.25 kg*m^2, tau_p = 30, tau_c = 14 N*m, v_n = 6
    rad/s): T_min = max(C_v h / v_n, sqrt(C_a h J / tau_p), sqrt(C_a_rms h J / tau_c))."""
    from pathlib import Path

    design = Path(__file__).resolve().parents[1] / "examples/book/ex6_3.yaml"
    done = run("laws", "--sweep", "trapezoidal(alpha=0.1..0.5:3)", "--design", str(design),
               "--format", "json")
    assert done.returncode == 0, done.stderr
    h, inertia, peak, rated, speed = 0.6, 0.25, 30.0, 14.0, 6.0
    for point in json.loads(done.stdout)["points"]:
        alpha = point["alpha"]
        c_v, c_a = 1 / (1 - alpha), 1 / (alpha * (1 - alpha))
        c_a_rms = math.sqrt(2 * alpha) * c_a
        expected = max(c_v * h / speed, math.sqrt(c_a * h * inertia / peak),
                       math.sqrt(c_a_rms * h * inertia / rated))
        assert point["T_min"] == pytest.approx(expected, rel=1e-6)
        assert point["motor"] == "ex6_3"


def test_t_min_needs_a_minimize_design() -> None:
    from pathlib import Path

    design = Path(__file__).resolve().parents[1] / "examples/rotary-knife.yaml"
    done = run("laws", "--sweep", "trapezoidal(alpha=0.1..0.5:3)", "--design", str(design))
    assert done.returncode == 2 and "duration: minimize" in done.stderr
    assert "--design" in done.stderr and "Traceback" not in done.stderr


def test_range_ends_are_read_within_the_spec_limits_and_written_back_exactly() -> None:
    """An end past the spec parser's limits is a user error, not a traceback; a tiny end
    is written 1e-20 (its own law, refused by its range), never rounded to 0."""
    huge = run("laws", "--sweep", "trapezoidal(alpha=1e999999..0.5)")
    assert huge.returncode == 2 and "Traceback" not in huge.stderr
    assert "out of range" in huge.stderr
    tiny = run("laws", "--sweep", "trapezoidal(alpha=1e-20..0.5:3)", "--format", "csv")
    assert tiny.returncode == 0, tiny.stderr
    first = next(csv.DictReader(io.StringIO(tiny.stdout)))
    assert first["spec"] == "trapezoidal(alpha=1e-20)" and first["C_a"] == ""


def test_fastest_by_law_equals_one_sizing_per_law() -> None:
    """sizer.api.fastest_by_law sizes the laws together; each law's answer is the one a
    sizing of that law alone gives (its fastest feasible motor)."""
    from pathlib import Path

    from sizer import api

    design = api.load(Path(__file__).resolve().parents[1] / "examples/book/ex6_3.yaml")
    laws = ["trapezoidal(alpha=0.2)", "cycloidal", "poly5"]
    together = api.fastest_by_law(design, laws)
    for spec, answer in zip(laws, together, strict=True):
        alone = api.size(api.override(design, laws=[spec]), rank_by="duration")
        best = alone.feasible[0]
        assert answer == (best.duration, best.motor)
