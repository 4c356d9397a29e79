"""A cam table read with a controller's interpolation (``interpolation:`` linear,
cubic_spline, quintic_hermite): the round trip of sizer's own export (issue 37)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.interpolate import CubicSpline
from typer.testing import CliRunner

from sizer.cli.app import app
from sizer.errors import UserError
from sizer.laws import make_law
from sizer.laws.data_spec import data_spec_text
from tests.test_cam_table_rest import dwell_design, export

LAWS = ("cycloidal", "poly5", "modified_sinusoidal")
H, T = np.pi / 2, 0.25  # the export's displacement (rad) and duration (s)


def table(path: Path) -> np.ndarray:
    """The columns t, q, v, a, j of sizer's export."""
    return np.loadtxt(path, delimiter=",", skiprows=1)


def read(path: Path, **fields):
    return make_law(data_spec_text({"kind": "cam_table", "file": str(path), **fields}))


@pytest.mark.parametrize("law", LAWS)
@pytest.mark.parametrize("interpolation", ["cubic_spline", "quintic_hermite"])
def test_the_points_are_the_table_s(tmp_path, law, interpolation):
    path = export(law, tmp_path)
    t, q = table(path)[:, 0].copy(), table(path)[:, 1].copy()
    read_back = read(path, interpolation=interpolation)
    assert read_back.rest_to_rest
    position = read_back.derivative(t / T, 0) * H
    assert np.max(np.abs(position - q)) < 1e-14 * H


@pytest.mark.parametrize("law", LAWS)
def test_the_cubic_spline_is_scipy_s(tmp_path, law):
    """The law's C_v, C_a and its derivatives against scipy's CubicSpline with the ends
    clamped at rest (the table starts and ends at rest), built here independently."""
    path = export(law, tmp_path)
    t, q = table(path)[:, 0], table(path)[:, 1]
    spline = CubicSpline(t, q, bc_type=((1, 0.0), (1, 0.0)))
    law_read = read(path, interpolation="cubic_spline")
    fine = np.linspace(0.0, T, 5001)
    for order in (1, 2):
        np.testing.assert_allclose(law_read.derivative(fine / T, order) * H / T ** order,
                                   spline(fine, order), rtol=0, atol=1e-9 * H / T ** order)
    # C_a: the acceleration is piecewise linear, its peak at a knot
    c_a = np.max(np.abs(spline(t, 2))) * T ** 2 / H
    # C_v: the speed's peak at a root of the acceleration (or an end)
    roots = np.concatenate((spline.derivative(2).roots(extrapolate=False), t[[0, -1]]))
    c_v = np.max(np.abs(spline(roots, 1))) * T / H
    coefficients = law_read.coefficients.as_dict()
    assert coefficients["C_a"] == pytest.approx(c_a, rel=1e-12)
    assert coefficients["C_v"] == pytest.approx(c_v, rel=1e-12)


@pytest.mark.parametrize("law", LAWS)
def test_the_quintic_hermite_keeps_v_and_a_at_the_points(tmp_path, law):
    path = export(law, tmp_path)
    data = table(path)
    read_back = read(path, interpolation="quintic_hermite")
    tau = data[:, 0] / T
    for order in (1, 2):
        scale = H / T ** order
        got = read_back.derivative(tau, order) * scale
        np.testing.assert_allclose(got, data[:, 1 + order], rtol=0,
                                   atol=1e-9 * np.max(np.abs(data[:, 1 + order])))
    exact = make_law(law).coefficients.as_dict()
    assert read_back.coefficients.as_dict()["C_v"] == pytest.approx(exact["C_v"], rel=1e-12)


@pytest.mark.parametrize("interpolation", ["cubic_spline", "quintic_hermite"])
def test_a_task_with_a_dwell_sizes_an_interpolated_table(tmp_path, interpolation):
    path = export("cycloidal", tmp_path)
    design = dwell_design(tmp_path, f"{{kind: cam_table, file: {path}, "
                                    f"interpolation: {interpolation}}}")
    result = CliRunner().invoke(app, ["size", str(design)])
    assert result.exit_code == 0, result.output


def test_a_bad_interpolation_is_a_located_error(tmp_path):
    path = export("cycloidal", tmp_path)
    design = dwell_design(tmp_path, f"{{kind: cam_table, file: {path}, interpolation: cubic}}")
    code = f"from sizer.cli.app import main; main(['size', {str(design)!r}])"
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            timeout=120)
    assert result.returncode == 2
    assert "Traceback" not in result.stderr
    line = next(i for i, text in enumerate(design.read_text().splitlines(), 1)
                if "interpolation: cubic" in text)
    assert result.stderr.startswith(f"error: {design}:{line}: laws[0].interpolation: "
                                    f"unknown interpolation 'cubic'"), result.stderr


def test_a_linear_table_is_refused_for_sizing(tmp_path):
    path = export("cycloidal", tmp_path)
    with pytest.raises(UserError, match="train of") as error:
        read(path, interpolation="linear")
    assert error.value.field == "interpolation"


def test_an_interpolation_takes_no_order(tmp_path):
    path = export("cycloidal", tmp_path)
    with pytest.raises(UserError, match="takes no order") as error:
        read(path, interpolation="cubic_spline", order=6)
    assert error.value.field == "order"


def test_a_quintic_hermite_table_needs_four_columns(tmp_path):
    path = tmp_path / "two.csv"
    path.write_text("t,q\n0,0\n0.5,0.5\n1,1\n")
    with pytest.raises(UserError, match="needs four"):
        read(path, interpolation="quintic_hermite")


def test_a_periodic_cubic_spline_table(tmp_path):
    """A rotary cam: q = x + 0.1 sin(2 pi x) over one period, its ends joined."""
    x = np.linspace(0.0, 1.0, 41)
    q = x + 0.1 * np.sin(2 * np.pi * x)
    path = tmp_path / "rotary.csv"
    path.write_text("t,q\n" + "".join(f"{float(a)!r},{float(b)!r}\n"
                                      for a, b in zip(x, q, strict=True)))
    law = read(path, interpolation="cubic_spline", periodic=True)
    assert not law.rest_to_rest and law.periodic
    spline = CubicSpline(x, q - x, bc_type="periodic")
    fine = np.linspace(0.0, 1.0, 401)
    np.testing.assert_allclose(law.derivative(fine, 1), spline(fine, 1) + 1.0, atol=1e-12)
