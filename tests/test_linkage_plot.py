"""The linkage figure: ratio and motor torque over the crank angle, dead points marked.

What is drawn is read back from the matplotlib artists and compared with the arrays given
(in degrees); the files are real PNG and SVG.
"""

from __future__ import annotations

import math
import struct
import xml.etree.ElementTree as ET

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from sizer.mechanics.linkages.dynamics import LinkageDynamics, LinkageMasses
from sizer.mechanics.linkages.slider_crank import SliderCrank
from sizer.report.plots import linkage_figure, save_figure
from sizer.report.plots.linkage_curves import (
    GID_DEAD_POINT,
    GID_DEAD_POINT_LABEL,
    GID_RATIO,
    GID_TORQUE,
    dead_point_angles,
)

SMALL = (5.0, 4.0)
DPI = 50


def _slider_crank_data(theta: np.ndarray):
    linkage = SliderCrank(0.75, 1.25)
    dynamics = LinkageDynamics(linkage, LinkageMasses(crank_inertia=0.1, output_inertia=2.0))
    omega = 10.0
    torques = {name: dynamics.motor_torque(theta, omega, 0.0, J_m)
               for name, J_m in (("motor A", 1e-3), ("motor B", 5e-3))}
    return linkage, linkage.output(theta, 1), torques


def _lines(ax, gid):
    return [line for line in ax.get_lines() if line.get_gid() == gid]


def test_two_axes_labels_curves_and_dead_points() -> None:
    theta = np.linspace(-math.pi, 3.0 * math.pi, 801)  # two turns
    _, ratio, torques = _slider_crank_data(theta)
    dead = {"top dead centre": 0.0, "bottom dead centre": math.pi}
    figure = linkage_figure(theta, ratio, torques, dead, linear=True, size=SMALL, dpi=DPI)
    ratio_axes, torque_axes = figure.axes
    assert len(figure.axes) == 2
    assert ratio_axes.get_ylabel() == "transmission ratio ds/dθ [m/rad]"
    assert torque_axes.get_ylabel() == "motor torque [N*m]"
    assert torque_axes.get_xlabel() == "crank angle [deg]"
    assert ratio_axes.get_shared_x_axes().joined(ratio_axes, torque_axes)

    (drawn,) = _lines(ratio_axes, GID_RATIO)
    np.testing.assert_allclose(drawn.get_xdata(), theta * 180.0 / math.pi, rtol=1e-15)
    # the ratio of the paper's slider-crank: -r sin(theta) (1 + r cos(theta) / w)
    w = np.sqrt(1.25**2 - (0.75 * np.sin(theta)) ** 2)
    np.testing.assert_allclose(drawn.get_ydata(), -0.75 * np.sin(theta)
                               * (1.0 + 0.75 * np.cos(theta) / w), atol=1e-14)
    curves = _lines(torque_axes, GID_TORQUE)
    assert [c.get_label() for c in curves] == ["motor A", "motor B"]
    np.testing.assert_array_equal(curves[1].get_ydata(), torques["motor B"])

    # every turn's dead points, on both panels, at -180, 0, 180, 360, 540 deg
    expected = [-180.0, 0.0, 180.0, 360.0, 540.0]
    for ax in (ratio_axes, torque_axes):
        at = sorted(line.get_xdata()[0] for line in _lines(ax, GID_DEAD_POINT))
        np.testing.assert_allclose(at, expected, atol=1e-9)
    labels = sorted((t.get_position()[0], t.get_text()) for t in ratio_axes.texts
                    if t.get_gid() == GID_DEAD_POINT_LABEL)
    assert [text for _, text in labels] == [
        "bottom dead centre -180°", "top dead centre 0°", "bottom dead centre 180°",
        "top dead centre 360°", "bottom dead centre 540°"]
    assert np.allclose([x for x, _ in labels], expected, atol=1e-9)
    assert torque_axes.get_xlim() == pytest.approx((-180.0, 540.0))


def test_rocker_units_and_unnamed_dead_points() -> None:
    theta = np.linspace(0.0, 2.0 * math.pi, 100)
    ratio = 0.5 * np.sin(theta)  # rad/rad, zero at 0 and 180 deg
    dead = [0.0, -math.pi]  # as Linkage.dead_points() gives them, in [-pi, pi)
    figure = linkage_figure(theta, ratio, {"m": np.cos(theta)}, dead, linear=False,
                            size=SMALL, dpi=DPI)
    ratio_axes, torque_axes = figure.axes
    assert ratio_axes.get_ylabel() == "transmission ratio ds/dθ [rad/rad]"
    at = sorted(line.get_xdata()[0] for line in _lines(torque_axes, GID_DEAD_POINT))
    np.testing.assert_allclose(at, [0.0, 180.0, 360.0], atol=1e-9)
    texts = sorted(t.get_text() for t in ratio_axes.texts if t.get_gid() == GID_DEAD_POINT_LABEL)
    assert texts == ["dead point 1 0°", "dead point 1 360°", "dead point 2 180°"]


def test_dead_point_angles() -> None:
    assert dead_point_angles(90.0, 0.0, 720.0) == [90.0, 450.0]
    assert dead_point_angles(-180.0, -180.0, 180.0) == [-180.0, 180.0]
    assert dead_point_angles(10.0, 20.0, 300.0) == []


def test_saves_png_and_svg(tmp_path) -> None:
    theta = np.linspace(-math.pi, math.pi, 361)
    linkage, ratio, torques = _slider_crank_data(theta)
    figure = linkage_figure(theta, ratio, torques, linkage.dead_points(), linear=True,
                            size=SMALL, dpi=DPI)
    png = save_figure(figure, tmp_path / "linkage.png")
    data = png.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    width, height = struct.unpack(">II", data[16:24])
    assert (width, height) == (SMALL[0] * DPI, SMALL[1] * DPI)
    svg = save_figure(figure, tmp_path / "linkage.svg")
    root = ET.fromstring(svg.read_bytes())
    assert root.tag.endswith("svg") and len(svg.read_bytes()) > 1000
    assert any(e.get("id") == GID_RATIO for e in root.iter())


def test_bad_arrays() -> None:
    theta = np.linspace(0.0, 1.0, 10)
    with pytest.raises(ValueError, match="ratio"):
        linkage_figure(theta, theta[:5], {"m": theta}, [], linear=True)
    with pytest.raises(ValueError, match="'m'"):
        linkage_figure(theta, theta, {"m": theta[:3]}, [], linear=True)
    with pytest.raises(ValueError, match="no motor torque"):
        linkage_figure(theta, theta, {}, [], linear=True)
