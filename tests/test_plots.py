"""Figures: the data drawn (read back from the matplotlib artists) is the core's envelope,
task curve and law profiles; files have the requested size and format."""

from __future__ import annotations

import dataclasses
import math
import struct
import xml.etree.ElementTree as ET

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from sizer.envelope import continuous_region, intermittent_region
from sizer.errors import UserError
from sizer.io import load_design
from sizer.laws import make_law
from sizer.model.domain import (
    Design,
    GearboxOption,
    Load,
    Motor,
    RatioChoice,
    Stage,
    Task,
    Transmission,
)
from sizer.report.plots import (
    curve_for,
    law_profiles_figure,
    save_figure,
    speed_torque_figure,
    transmission_for,
)
from sizer.report.plots.figure_files import figure_bytes
from sizer.report.plots.law_profiles import (
    GID_IMPULSE,
    GID_IMPULSE_LABEL,
    GID_PROFILE,
    REST_PAD,
)
from sizer.report.plots.speed_torque import (
    GID_CONTINUOUS,
    GID_INTERMITTENT,
    GID_RMS,
    GID_TASK,
    region_outline,
)
from sizer.sizing import size_design
from sizer.sizing.samples import task_curve

RPM = 30.0 / math.pi
SAMPLES = 41
SMALL = (4.0, 3.0)
DPI = 50

BOOK_6_1 = """\
name: Book 6.1
task: {displacement: 15 rad, duration: 3 s}
load: {inertia: 1 kg*m^2, damping: 0.3 N*m*s/rad}
transmission: {type: direct}
laws: [cycloidal, "trapezoidal(alpha=0.12732200375003505)"]
motors: book-examples
check: {motor: ex6_1, law: cycloidal}
"""

RETURN_MOVE = """\
name: Return move
task: {displacement: 90 deg, duration: 0.3 s, dwell: 0.1 s, return: true}
load: {inertia: 0.02 kg*m^2, friction: 0.2 N*m, torque: 0.1 N*m}
transmission: {type: gearbox, ratio: 5, efficiency: 0.9, inertia: 0.2 kg*cm^2}
laws: [cycloidal, "trapezoidal(alpha=1/3)"]
motors:
  - id: curvy
    inertia: 1 kg*cm^2
    continuous_torque: 1.0 N*m
    peak_torque: 3 N*m
    rated_speed: 3000 rpm
    max_speed: 5000 rpm
    continuous_curve: [[0 rpm, 1.0 N*m], [3000 rpm, 0.9 N*m], [5000 rpm, 0.5 N*m]]
    intermittent_curve: [[1000 rpm, 3 N*m], [3000 rpm, 3 N*m], [5000 rpm, 1.5 N*m]]
"""


@pytest.fixture(scope="module")
def book(tmp_path_factory):
    path = tmp_path_factory.mktemp("book") / "book.yaml"
    path.write_text(BOOK_6_1)
    design = load_design(path)
    return design, size_design(design)


@pytest.fixture(scope="module")
def round_trip(tmp_path_factory):
    path = tmp_path_factory.mktemp("ret") / "ret.yaml"
    path.write_text(RETURN_MOVE)
    design = load_design(path)
    return design, size_design(design)


def artists(figure, gid):
    """Every artist of the figure with this gid, in drawing order."""
    return [a for a in figure.findobj() if a.get_gid() == gid]


def png_size(data: bytes) -> tuple[int, int]:
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    assert data[12:16] == b"IHDR"
    return struct.unpack(">II", data[16:24])


def motor(design, motor_id):
    return next(m for m in design.motors if m.id == motor_id)


# --------------------------------------------------------------- speed-torque
def test_regions_drawn_are_the_motor_envelope_in_rpm(round_trip):
    design, sizing = round_trip
    results = list(sizing.results)
    curves = [curve_for(design, r, samples=SAMPLES) for r in results]
    figure = speed_torque_figure(curves, results, size=SMALL, dpi=DPI)
    m = motor(design, "curvy")
    for gid, region in ((GID_CONTINUOUS, continuous_region(m)),
                        (GID_INTERMITTENT, intermittent_region(m))):
        (polygon,) = artists(figure, gid)
        drawn = polygon.get_xy()
        # the return move has negative speeds: the region is drawn in four quadrants
        expected = region_outline(region, both_directions=True) * (RPM, 1.0)
        np.testing.assert_allclose(drawn[: len(expected)], expected, rtol=1e-12)
        corners = {(round(s * RPM, 9), round(t, 9)) for s, t in region}
        assert corners <= {(round(x, 9), round(y, 9)) for x, y in drawn}
        # every corner mirrored: |torque| <= limit(|speed|) in all four quadrants
        for sx, sy in ((1, 1), (1, -1), (-1, 1), (-1, -1)):
            mirrored = {(round(sx * s * RPM, 9), round(sy * t, 9)) for s, t in region}
            assert mirrored <= {(round(x, 9), round(y, 9)) for x, y in drawn}
    # the first intermittent point (1000 rpm) holds down to standstill
    (polygon,) = artists(figure, GID_INTERMITTENT)
    assert (0.0, 3.0) in {(round(x, 9), round(y, 9)) for x, y in polygon.get_xy()}


def test_one_way_move_draws_the_positive_speed_half(book):
    design, sizing = book
    result = next(r for r in sizing.results if r.motor == "ex6_1")
    figure = speed_torque_figure([curve_for(design, result, samples=SAMPLES)], [result],
                                 speed_unit="rad/s", size=SMALL, dpi=DPI)
    (polygon,) = artists(figure, GID_INTERMITTENT)
    xy = polygon.get_xy()
    assert xy[:, 0].min() == 0.0
    assert {(round(x, 12), round(y, 12)) for x, y in xy} == {
        (0.0, 20.0), (10.0, 20.0), (10.0, -20.0), (0.0, -20.0)}
    (polygon,) = artists(figure, GID_CONTINUOUS)
    assert {(round(x, 12), round(y, 12)) for x, y in polygon.get_xy()} == {
        (0.0, 8.0), (10.0, 8.0), (10.0, -8.0), (0.0, -8.0)}


def test_task_curves_and_rms_points_drawn_are_the_core_task_curves(round_trip):
    design, sizing = round_trip
    results = list(sizing.results)
    curves = [curve_for(design, r, samples=SAMPLES) for r in results]
    figure = speed_torque_figure(curves, results, size=SMALL, dpi=DPI)
    lines = artists(figure, GID_TASK)
    points = artists(figure, GID_RMS)
    assert len(lines) == len(points) == len(results) == 2
    for line, point, result in zip(lines, points, results, strict=True):
        core = task_curve(design, motor(design, result.motor), result.spec, result.duration,
                          samples=SAMPLES)
        np.testing.assert_allclose(line.get_xydata(),
                                   np.column_stack((core.motor_speed * RPM, core.motor_torque)),
                                   rtol=1e-12, atol=1e-15)
        np.testing.assert_allclose(point.get_xydata(),
                                   [[core.thermal_speed * RPM, core.rms_torque]], rtol=1e-12)
        # the curve is the sized pair: its RMS and peak are the result's
        assert core.rms_torque == pytest.approx(result.rms_torque, rel=1e-12)
        assert core.peak_torque == pytest.approx(result.peak_torque, rel=1e-12)
        assert result.spec in line.get_label()


def test_acceleration_panel_is_the_regions_over_total_inertia(round_trip):
    design, sizing = round_trip
    result = sizing.results[0]
    curve = curve_for(design, result, samples=SAMPLES)
    figure = speed_torque_figure([curve], [result], acceleration=True, speed_unit="rad/s",
                                 size=(6.0, 3.0), dpi=DPI)
    assert len(figure.axes) == 2
    torque_axes, acceleration_axes = figure.axes
    assert "rad/s^2" in acceleration_axes.get_ylabel()
    assert "[rad/s]" in acceleration_axes.get_xlabel()
    continuous, intermittent = curve.acceleration_regions
    for gid, region in ((GID_CONTINUOUS, continuous), (GID_INTERMITTENT, intermittent)):
        polygons = artists(figure, gid)
        assert [p.axes for p in polygons] == [torque_axes, acceleration_axes]
        expected = region_outline(region, both_directions=True)
        np.testing.assert_allclose(polygons[1].get_xy()[: len(expected)], expected,
                                   rtol=1e-12)
    line = artists(figure, GID_TASK)[1]
    assert line.axes is acceleration_axes
    np.testing.assert_allclose(line.get_xydata(),
                               np.column_stack((curve.motor_speed, curve.motor_acceleration)),
                               rtol=1e-12, atol=1e-12)
    point = artists(figure, GID_RMS)[1]
    np.testing.assert_allclose(point.get_xydata(),
                               [[curve.thermal_speed, curve.rms_torque / curve.total_inertia]],
                               rtol=1e-12)


def test_title_names_the_motor_and_the_margins(book):
    design, sizing = book
    result = next(r for r in sizing.results if r.motor == "ex6_1" and r.law == "cycloidal")
    figure = speed_torque_figure([curve_for(design, result, samples=SAMPLES)], [result],
                                 size=SMALL, dpi=DPI, title=design.name)
    title = figure.get_suptitle()
    assert "motor ex6_1" in title and "Book 6.1" in title
    for name in ("peak", "rms", "speed"):
        assert f"{name} {100 * result.margin(name):.1f} %" in title
    axes = figure.axes[0]
    assert axes.get_xlabel() == "motor speed [rpm]"
    assert axes.get_ylabel() == "motor torque [N*m]"
    labels = axes.get_legend_handles_labels()[1]
    assert "intermittent region" in labels and "continuous region" in labels


def test_curves_of_different_motors_are_refused(book):
    design, sizing = book
    results = [next(r for r in sizing.results if r.motor == m) for m in ("ex6_1", "ex6_3")]
    curves = [curve_for(design, r, samples=SAMPLES) for r in results]
    with pytest.raises(ValueError, match="several motors"):
        speed_torque_figure(curves, results)


# ---------------------------------------------------------------- law profiles
def _interior(law, tau):
    """Samples strictly inside a piece (one value there, whichever side)."""
    return ~np.isin(np.round(tau, 12), np.round(law.breakpoints, 12))


@pytest.mark.parametrize("scaled", [False, True])
def test_law_profiles_drawn_are_the_law_derivatives(scaled):
    laws = [make_law("cycloidal"), make_law("trapezoidal(alpha=1/4)"), make_law("poly5")]
    h, T = (1.2, 0.5) if scaled else (1.0, 1.0)
    kwargs = {"displacement": h, "duration": T} if scaled else {}
    figure = law_profiles_figure(laws, samples=SAMPLES, size=(4.0, 6.0), dpi=DPI, **kwargs)
    assert len(figure.axes) == 4
    lines = artists(figure, GID_PROFILE)
    assert len(lines) == 4 * len(laws)
    for order, ax in enumerate(figure.axes):
        for law, line in zip(laws, [x for x in lines if x.axes is ax], strict=True):
            t, y = line.get_xdata(), line.get_ydata()
            tau = t / T
            inside = (tau > 0) & (tau < 1) & _interior(law, tau)
            expected = law.derivative(tau[inside], order) * h / T**order
            np.testing.assert_allclose(y[inside], expected, rtol=1e-12, atol=1e-12)
            # at rest before and after the move
            assert t[0] == pytest.approx(-REST_PAD * T) and y[0] == 0.0
            assert t[-1] == pytest.approx((1 + REST_PAD) * T)
            assert y[-1] == (h if order == 0 else 0.0)
    assert figure.axes[0].get_legend_handles_labels()[1] == [law.spec for law in laws]
    if scaled:
        assert figure.axes[1].get_ylabel() == "velocity [rad/s]"
        assert figure.axes[3].get_xlabel() == "time t [s]"
    else:
        assert figure.axes[3].get_xlabel() == "tau = t/T [-]"


def test_discontinuities_are_vertical_steps():
    law = make_law("trapezoidal(alpha=1/3)")
    figure = law_profiles_figure([law], samples=SAMPLES, size=(4.0, 6.0), dpi=DPI)
    acceleration = artists(figure, GID_PROFILE)[2].get_xydata()
    # at tau = 1/3 the acceleration steps from +4.5 to 0: two points at the same tau
    at = acceleration[np.isclose(acceleration[:, 0], 1 / 3, atol=1e-12)]
    assert sorted(np.round(at[:, 1], 9)) == [0.0, 4.5]


@pytest.mark.parametrize("spec", ["trapezoidal(alpha=1/3)", "constant_acceleration"])
def test_jerk_impulses_are_marked_where_the_acceleration_jumps(spec):
    law = make_law(spec)
    h, T = 2.0, 0.5
    figure = law_profiles_figure([law, make_law("cycloidal")], displacement=h, duration=T,
                                 samples=SAMPLES, size=(4.0, 6.0), dpi=DPI)
    arrows = artists(figure, GID_IMPULSE)
    labels = artists(figure, GID_IMPULSE_LABEL)
    jumps = law.coefficients.acceleration_jumps
    assert len(arrows) == len(labels) == len(jumps) > 0
    for arrow, label, jump in zip(arrows, labels, jumps, strict=True):
        assert arrow.axes is figure.axes[3]
        x, tip = arrow.xy
        assert x == pytest.approx(jump.tau * T)
        assert math.copysign(1.0, tip) == math.copysign(1.0, jump.jump)
        assert arrow.xyann == (x, 0.0)
        size = jump.jump * h / T**2
        assert f"{size:+.5g} rad/s^2" in label.get_text()


def test_smooth_laws_have_no_impulse_markers():
    figure = law_profiles_figure([make_law("cycloidal"), make_law("double_s")],
                                 samples=SAMPLES, size=(4.0, 6.0), dpi=DPI)
    assert artists(figure, GID_IMPULSE) == []


def test_law_profiles_need_both_h_and_T():
    with pytest.raises(ValueError, match="both"):
        law_profiles_figure([make_law("cycloidal")], displacement=1.0)


# ------------------------------------------------------------------ files
def test_png_has_the_requested_size(tmp_path, book):
    design, sizing = book
    result = sizing.results[0]
    figure = speed_torque_figure([curve_for(design, result, samples=SAMPLES)], [result],
                                 size=(4.0, 3.0), dpi=DPI)
    path = save_figure(figure, tmp_path / "diagram.PNG", dpi=DPI)
    data = path.read_bytes()
    assert png_size(data) == (200, 150)
    assert len(data) > 2000
    import matplotlib.image

    pixels = matplotlib.image.imread(path, format="png")
    assert pixels.shape[:2] == (150, 200)
    assert pixels.std() > 0.01  # not a blank image


def test_svg_has_the_requested_size_and_is_deterministic(tmp_path):
    figure = law_profiles_figure([make_law("cycloidal")], samples=SAMPLES, size=(3.0, 5.0),
                                 dpi=DPI)
    path = save_figure(figure, tmp_path / "law.svg")
    root = ET.fromstring(path.read_bytes())
    assert root.tag == "{http://www.w3.org/2000/svg}svg"
    assert root.get("width") == "216pt" and root.get("height") == "360pt"
    assert len(root.findall(".//{http://www.w3.org/2000/svg}path")) > 10
    again = law_profiles_figure([make_law("cycloidal")], samples=SAMPLES, size=(3.0, 5.0),
                                dpi=DPI)
    assert figure_bytes(again, "svg") == path.read_bytes()
    assert figure_bytes(again, "png") == figure_bytes(figure, "png")


@pytest.mark.parametrize("name", ["figure.pdf", "figure", "figure.png.txt"])
def test_unknown_suffix_is_a_user_error(tmp_path, name):
    figure = law_profiles_figure([make_law("cycloidal")], samples=SAMPLES, size=SMALL,
                                 dpi=DPI)
    with pytest.raises(UserError, match=r"\*.png or \*.svg"):
        save_figure(figure, tmp_path / name)
    assert list(tmp_path.iterdir()) == []


def test_unwritable_figure_is_a_user_error(tmp_path):
    figure = law_profiles_figure([make_law("cycloidal")], samples=SAMPLES, size=SMALL,
                                 dpi=DPI)
    with pytest.raises(UserError, match="cannot write"):
        save_figure(figure, tmp_path / "missing" / "figure.png")


# -------------------------------------------------- results and transmissions
def test_plotting_never_changes_a_result(round_trip):
    design, before = round_trip
    for result in before.results:
        figure = speed_torque_figure([curve_for(design, result, samples=SAMPLES)], [result],
                                     acceleration=True, size=SMALL, dpi=DPI)
        figure_bytes(figure, "png")
    assert size_design(design) == before


MOTOR = Motor("m", inertia=1e-4, continuous_torque=3.0, peak_torque=9.0, rated_speed=400.0)


def _gearbox(ratio, efficiency=1.0, inertia=0.0, **limits):
    return Stage("gearbox", ratio, efficiency, inertia, **limits)


def test_task_curve_of_a_chosen_ratio_uses_that_ratio():
    design = Design(Task(1.0, 0.5, dwell=0.2), Load(0.5, friction=0.3),
                    Transmission((_gearbox(10.0, 0.9),)), laws=("cycloidal",),
                    motors=(MOTOR,), ratio_choice=RatioChoice(0, ratios=(5.0, 50.0, 100.0)))
    (result,) = size_design(design).results
    assert result.ratio in (50.0, 100.0) and result.gearbox is None
    transmission = transmission_for(design, result)
    assert transmission.ratio == result.ratio
    assert transmission.stages[0].efficiency == 0.9
    curve = curve_for(design, result, samples=SAMPLES)
    assert curve.ratio == result.ratio
    assert curve.rms_torque == pytest.approx(result.rms_torque, rel=1e-12)
    assert curve.peak_torque == pytest.approx(result.peak_torque, rel=1e-12)


def test_task_curve_of_a_catalog_gearbox_uses_its_efficiency_and_inertia():
    strong = GearboxOption("GB-big", _gearbox(20.0, 0.8, 1e-4, peak_output_torque=500.0))
    weak = GearboxOption("GB-small", _gearbox(50.0, 0.97, 2e-5, peak_output_torque=10.0))
    design = Design(Task(1.0, 0.5), Load(0.5), Transmission((_gearbox(10.0),)),
                    laws=("cycloidal",), motors=(MOTOR,),
                    ratio_choice=RatioChoice(0, gearboxes=(strong, weak)))
    (result,) = size_design(design).results
    assert result.gearbox == "GB-big"
    assert transmission_for(design, result).stages == (strong.stage,)
    curve = curve_for(design, result, samples=SAMPLES)
    assert curve.rms_torque == pytest.approx(result.rms_torque, rel=1e-12)
    assert curve.peak_torque == pytest.approx(result.peak_torque, rel=1e-12)
    # the design's stage with the ratio replaced would not be the sized transmission
    naive = design.transmission.with_stage(
        0, dataclasses.replace(design.transmission.stages[0], ratio=20.0))
    other = task_curve(design, MOTOR, result.spec, result.duration, transmission=naive,
                       samples=SAMPLES)
    assert other.rms_torque != pytest.approx(result.rms_torque, rel=1e-6)


def test_a_result_without_duration_has_no_curve():
    tiny = Motor("tiny", inertia=1e-5, continuous_torque=0.01, peak_torque=0.02,
                 rated_speed=10.0)
    design = Design(Task(1.0, None), Load(0.5, torque=1.0), Transmission(),
                    laws=("cycloidal",), motors=(tiny,))
    (result,) = size_design(design).results
    assert result.duration is None
    with pytest.raises(UserError, match="no feasible duration"):
        curve_for(design, result)
