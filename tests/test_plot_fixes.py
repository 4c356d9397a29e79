"""Issue 36, plots: the vibration sweep shows its limit and the passing region below it;
a periodic cam is drawn over several periods without jumps; the report reads rpm."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from sizer.laws import make_law
from sizer.report.design_report import display_check
from sizer.report.plots.law_profiles import GID_PROFILE, PERIODS, law_profiles_figure
from sizer.report.plots.vibration_plot import (
    GID_LIMIT,
    GID_PASSING,
    vibration_figure,
    y_range,
)
from sizer.sizing.results import Check
from sizer.sizing.vibration_check import VibrationSweep

ARCSEC_PER_RAD = 180.0 / math.pi * 3600.0


def _artists(figure, gid):
    return [a for ax in figure.axes for a in (*ax.lines, *ax.patches, *ax.collections)
            if a.get_gid() == gid]


# ------------------------------------------------------------------ vibration sweep
def _sweep(residual_arcsec: list[list[float]], limit_arcsec: float | None) -> VibrationSweep:
    scales = np.linspace(0.1, 0.3, len(residual_arcsec[0]))
    laws = tuple(make_law(spec) for spec in ("cycloidal", "poly5")[:len(residual_arcsec)])
    residual = tuple(np.array(r) / ARCSEC_PER_RAD for r in residual_arcsec)
    limit = None if limit_arcsec is None else limit_arcsec / ARCSEC_PER_RAD
    return VibrationSweep(scales, laws, residual, limit)


def test_the_limit_below_every_residual_is_inside_the_axes_with_the_passing_region():
    # every sample is above the limit (50..10000 arcsec against 20): the old figure set
    # its y-range from the samples only, and the limit line fell below the axes
    sweep = _sweep([[10000.0, 50.0, 400.0], [2000.0, 80.0, 60.0]], 20.0)
    figure = vibration_figure(sweep, linear=False, cycle=False)
    ax = figure.axes[0]
    bottom, top = ax.get_ylim()
    (line,) = _artists(figure, GID_LIMIT)
    limit = line.get_ydata()[0]
    assert limit == pytest.approx(20.0)
    assert bottom < limit < top
    assert bottom <= limit / 10.0 * (1 + 1e-12)  # a decade of the passing region shown
    assert top >= 10000.0
    (region,) = _artists(figure, GID_PASSING)
    # a Rectangle from the axes' bottom up to the limit (data coordinates)
    assert region.get_y() == pytest.approx(bottom)
    assert region.get_y() + region.get_height() == pytest.approx(limit)
    assert "limit 20 arcsec" in ax.get_legend_handles_labels()[1]


def test_the_limit_above_every_residual_is_inside_the_axes():
    sweep = _sweep([[1.0, 5.0, 2.0]], 100.0)
    bottom, top = vibration_figure(sweep, linear=False, cycle=False).axes[0].get_ylim()
    assert bottom <= 1.0 and top > 100.0


def test_y_range_rules():
    assert y_range(np.array([[0.0, 0.0]]), None) is None
    assert y_range(np.array([[0.0, 0.0]]), 10.0) == pytest.approx((1.0, 20.0))
    assert y_range(np.array([[1e-3, 1e3]]), None) == pytest.approx((1e-3, 2e3))
    assert y_range(np.array([[1e-30, 1.0]]), None) == pytest.approx((1e-8, 2.0))


# --------------------------------------------------------------------- periodic cams
def _cam(tmp_path: Path, name: str, q_deg, periodic: bool = True):
    theta = np.arange(0.0, 361.0, 5.0)
    rows = "".join(f"{a:g},{b:.9f}\n" for a, b in zip(theta, q_deg(theta), strict=True))
    path = tmp_path / f"{name}.csv"
    path.write_text("theta [deg],q [deg]\n" + rows)
    return make_law(f"{{kind: cam_table, file: {path}, periodic: {str(periodic).lower()}}}")


def _position_line(figure, index=0):
    ax = figure.axes[0]
    lines = [line for line in ax.lines if line.get_gid() == GID_PROFILE]
    return lines[index].get_xdata(), lines[index].get_ydata()


def test_a_knife_cam_is_drawn_over_several_periods_unwrapped(tmp_path):
    # q = theta + 0.3 rad sin(theta): one turn per period, the ends move and join
    law = _cam(tmp_path, "knife", lambda t: t + math.degrees(0.3) * np.sin(np.radians(t)))
    assert law.periodic
    figure = law_profiles_figure([law], samples=400)
    tau, q = _position_line(figure)
    assert tau[0] == pytest.approx(0.0) and tau[-1] == pytest.approx(PERIODS)
    # unwrapped: q_N(tau + k) = q_N(tau) + k, so the last point is PERIODS strokes up
    assert q[-1] == pytest.approx(PERIODS, abs=1e-9)
    for k in range(1, PERIODS):
        at = np.isclose(tau, k)
        assert np.allclose(q[at], k, atol=1e-9)  # both sides of the join: no jump
    # continuous: no step larger than the largest slope times the sample spacing allows
    steps = np.abs(np.diff(q))
    assert steps.max() < 0.02
    # the velocity is periodic, never the rest of a move
    velocity = next(line for line in figure.axes[1].lines if line.get_gid() == GID_PROFILE)
    assert velocity.get_ydata().min() > 0.5


def test_a_cam_that_returns_rests_at_its_start_not_at_the_top(tmp_path):
    # rise and return, at rest at both ends: q_N(1) = 0. The old plot drew q_N = 1 after
    # the move: a jump to the top of the stroke.
    law = _cam(tmp_path, "rise-return", lambda t: 10.0 * (1.0 - np.cos(np.radians(t))))
    figure = law_profiles_figure([law], samples=400)
    tau, q = _position_line(figure)
    after = tau > 1.0
    assert after.any() and np.allclose(q[after], 0.0, atol=1e-9)
    assert np.abs(np.diff(q)).max() < 0.05


def test_a_swinging_periodic_cam_returns_each_period(tmp_path):
    # q = 10 deg sin(theta): ends move, join, and q(1) = q(0): no stroke per period
    law = _cam(tmp_path, "swing", lambda t: 10.0 * np.sin(np.radians(t)))
    assert law.periodic
    tau, q = _position_line(law_profiles_figure([law], samples=400))
    assert tau[-1] == pytest.approx(PERIODS)
    assert np.abs(np.diff(q)).max() < 0.1
    one = q[(tau >= 0) & (tau <= 1)]
    assert np.max(np.abs(q)) == pytest.approx(np.max(np.abs(one)))


def test_a_move_beside_a_periodic_cam_rests_to_the_end_of_the_axis(tmp_path):
    law = _cam(tmp_path, "knife", lambda t: t + math.degrees(0.3) * np.sin(np.radians(t)))
    figure = law_profiles_figure([law, make_law("cycloidal")], samples=200)
    tau, q = _position_line(figure, 1)
    assert tau[-1] >= PERIODS and q[-1] == 1.0
    assert figure.axes[3].get_xlim()[1] >= PERIODS


# ------------------------------------------------------------------ report units
def test_report_checks_show_speeds_in_rpm_and_torques_in_n_m():
    speed = display_check(Check("speed", 100.0, 2.0 * math.pi * 50.0, "rad/s", 0.68))
    assert speed.unit == "rpm"
    assert speed.value == pytest.approx(100.0 * 30.0 / math.pi)
    assert speed.limit == pytest.approx(3000.0)
    assert speed.margin == 0.68
    assert "rpm against 3000 rpm" in speed.describe()
    torque = Check("peak_torque", 2.0, 4.0, "N*m", 0.5)
    assert display_check(torque) is torque


def test_the_report_has_no_rad_per_second(tmp_path):
    from typer.testing import CliRunner

    from sizer.cli.app import app

    example = Path(__file__).resolve().parents[1] / "examples" / "indexing-table.yaml"
    result = CliRunner().invoke(app, ["report", str(example), "-o", str(tmp_path / "r")])
    assert result.exit_code == 0, result.output
    text = (tmp_path / "r" / "report.md").read_text()
    import re

    assert not re.search(r"\brad/s\b(?!\^)", text)
    assert " rpm against " in text
