"""``sizer plot --cam``: the follower over the cam angle, the cam's profile, and the profile
exported as points (``--points FILE.csv``; issue 38, docs/disc-cams.md).

Every expected number is computed here from closed forms: the cycloidal lift written out,
the translating offset roller follower's pitch curve x = (s0 + s) sin th + e cos th,
y = (s0 + s) cos th - e sin th (s0 = sqrt(R_p^2 - e^2); Norton ch. 7, the cam turning
counterclockwise), its tangent by the derivative of that form, the profile R_f along the
inward normal, the pressure angle atan((s' - e) / (s0 + s)); never sizer's own formulas.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import yaml
from cli_run import assert_user_error, run_cli
from test_cam_follower import _lift  # the lift written out: the same cam cycle

pytest.importorskip("matplotlib")

H = 0.02
RISE, TOP, BACK, BOTTOM = 0.1, 0.05, 0.1, 0.05
CYCLE = RISE + TOP + BACK + BOTTOM
OMEGA = 2.0 * math.pi / CYCLE
BETA = 2.0 * math.pi * RISE / CYCLE
DWELL = 2.0 * math.pi * TOP / CYCLE
E, R_F = 0.005, 0.010
SMALL = ("--size", "7x4", "--dpi", "50")
"""A small figure: the tests read the points, the figure need only be written."""
MOTOR = {"id": "m1", "inertia": "1 kg*cm^2", "continuous_torque": "50 N*m",
         "peak_torque": "150 N*m", "rated_speed": "3000 rpm"}


def _design(base_radius: str = "40 mm", laws: tuple[str, ...] = ("cycloidal",)) -> dict:
    stage = {"type": "disc_cam", "base_radius": base_radius, "roller_radius": "10 mm",
             "offset": "5 mm", "follower_mass": "0.5 kg", "spring_preload": "100 N",
             "spring_force_at_top": "140 N"}
    return {
        "name": "disc cam plot",
        "cycle": {"segments": [
            {"move": {"displacement": "20 mm", "duration": f"{RISE} s", "name": "rise"}},
            {"dwell": {"duration": f"{TOP} s", "name": "top"}},
            {"move": {"displacement": "-20 mm", "duration": f"{BACK} s", "name": "return"}},
            {"dwell": {"duration": f"{BOTTOM} s", "name": "bottom"}}]},
        "load": {"mass": "2 kg", "force": "50 N"},
        "transmission": [{"type": "gearbox", "ratio": 5, "efficiency": "95 %"}, stage],
        "laws": list(laws), "motors": [MOTOR]}


def _write(folder: Path, design: dict) -> Path:
    path = folder / "cam.yaml"
    path.write_text(yaml.safe_dump(design, sort_keys=False), encoding="utf-8")
    return path


def _read_csv(path: Path) -> tuple[dict[str, str], list[str], np.ndarray]:
    """(the '#' lines as 'key: value', the header's columns, the numbers)."""
    lines = path.read_text(encoding="utf-8").splitlines()
    notes = {}
    for line in lines:
        if line.startswith("# ") and ": " in line:
            key, _, value = line[2:].partition(": ")
            notes[key] = value
    body = [line for line in lines if not line.startswith("#")]
    table = np.array([[float(x) for x in line.split(",")] for line in body[1:]])
    return notes, body[0].split(","), table


@pytest.fixture(scope="module")
def exported(tmp_path_factory) -> tuple[Path, Path]:
    folder = tmp_path_factory.mktemp("cam")
    design = _write(folder, _design())
    figure, points = folder / "cam.png", folder / "cam.csv"
    result = run_cli("plot", str(design), "--cam", "-o", str(figure), "--points", str(points),
                     *SMALL)
    assert result.returncode == 0, result.stderr
    assert "cam angle" in result.stdout and str(points) in result.stdout
    return figure, points


def test_the_figure_is_written(exported) -> None:
    figure, _ = exported
    data = figure.read_bytes()
    assert data.startswith(b"\x89PNG\r\n\x1a\n") and len(data) > 5_000


def test_the_points_are_the_closed_form_pitch_curve(exported) -> None:
    _, points = exported
    notes, columns, table = _read_csv(points)
    assert columns == ["cam angle [deg]", "lift [mm]", "pitch x [mm]", "pitch y [mm]",
                       "profile x [mm]", "profile y [mm]"]
    assert float(notes["base radius R_b [mm]"]) == pytest.approx(40.0, abs=1e-12)
    assert float(notes["roller radius R_f [mm]"]) == pytest.approx(10.0, abs=1e-12)
    theta = np.radians(table[:, 0])
    assert table[0, 0] == 0.0 and table[-1, 0] == pytest.approx(360.0, abs=1e-12)
    assert np.all(np.diff(table[:, 0]) == pytest.approx(0.1, abs=1e-9))
    s = _lift(theta)
    s0 = math.sqrt((0.040 + R_F) ** 2 - E**2)
    x = (s0 + s) * np.sin(theta) + E * np.cos(theta)
    y = (s0 + s) * np.cos(theta) - E * np.sin(theta)
    np.testing.assert_allclose(table[:, 1], s * 1e3, rtol=0, atol=1e-9)
    np.testing.assert_allclose(table[:, 2], x * 1e3, rtol=0, atol=1e-9)
    np.testing.assert_allclose(table[:, 3], y * 1e3, rtol=0, atol=1e-9)


def test_the_profile_is_the_pitch_curve_moved_by_the_roller_inward(exported) -> None:
    _, points = exported
    _, _, table = _read_csv(points)
    theta = np.radians(table[:, 0])
    s, s1 = _lift(theta), _lift(theta, 1)
    s0 = math.sqrt((0.040 + R_F) ** 2 - E**2)
    # the closed form's derivative in theta: the pitch curve's tangent
    dx = s1 * np.sin(theta) + (s0 + s) * np.cos(theta) - E * np.sin(theta)
    dy = s1 * np.cos(theta) - (s0 + s) * np.sin(theta) - E * np.cos(theta)
    norm = np.hypot(dx, dy)
    inward = np.stack([dy / norm, -dx / norm])  # the curve turns clockwise as theta grows
    moved = np.stack([table[:, 4] - table[:, 2], table[:, 5] - table[:, 3]]) / 1e3
    np.testing.assert_allclose(moved, R_F * inward, rtol=0, atol=1e-12)
    # toward the cam's centre, and on the bottom dwell the base circle itself
    pitch = np.stack([table[:, 2], table[:, 3]])
    assert np.all(np.sum(inward * pitch, axis=0) < 0.0)
    bottom = theta > 2 * BETA + DWELL + 1e-9
    radius = np.hypot(table[bottom, 4], table[bottom, 5])
    np.testing.assert_allclose(radius, 40.0, rtol=0, atol=1e-9)


def test_auto_writes_the_base_radius_the_sizing_chose(tmp_path) -> None:
    design = _write(tmp_path, _design("auto"))
    points = tmp_path / "auto.csv"
    result = run_cli("plot", str(design), "--cam", "-o", str(tmp_path / "auto.svg"),
                     "--points", str(points), *SMALL)
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "auto.svg").read_bytes().startswith(b"<?xml")
    notes, _, table = _read_csv(points)
    base = float(notes["base radius R_b [mm]"]) / 1e3
    s0 = math.sqrt((base + R_F) ** 2 - E**2)
    theta = np.linspace(0.0, 2.0 * math.pi, 200_001)
    phi = np.abs(np.arctan((_lift(theta, 1) - E) / (s0 + _lift(theta))))
    # the smallest radius within 30 deg: the limit binds (cycloidal: the pressure angle)
    assert float(np.max(phi)) <= math.radians(30.0) + 1e-9
    assert float(np.max(phi)) == pytest.approx(math.radians(30.0), abs=1e-6)
    x = (s0 + _lift(np.radians(table[:, 0]))) * np.sin(np.radians(table[:, 0])) \
        + E * np.cos(np.radians(table[:, 0]))
    np.testing.assert_allclose(table[:, 2], x * 1e3, rtol=0, atol=1e-9)


def test_without_a_disc_cam_the_option_is_named(tmp_path) -> None:
    design = _write(tmp_path, {"name": "no cam", "task": {"displacement": "1 rad",
                                                          "duration": "0.5 s"},
                               "load": {"inertia": "0.01 kg*m^2"},
                               "transmission": {"type": "direct"}, "laws": ["cycloidal"],
                               "motors": [MOTOR]})
    result = run_cli("plot", str(design), "--cam", "-o", str(tmp_path / "x.png"))
    assert_user_error(result, "--cam", "disc_cam")
    assert not (tmp_path / "x.png").exists()


@pytest.mark.parametrize(("args", "words"), [
    (["--points", "{tmp}/p.csv"], ("--points", "--cam")),
    (["--cam", "--time"], ("--cam", "--time")),
    (["--cam", "--linkage"], ("--cam", "--linkage")),
    (["--cam", "--points", "{tmp}/p.txt"], ("--points", "*.csv")),
    (["--cam", "--points", "{tmp}/p.csv", "--law", "cycloidal", "--law", "poly5"],
     ("--points", "one --law")),
    (["--front", "--points", "{tmp}/p.csv"], ("--points",)),
])
def test_option_mistakes_exit_2(tmp_path, args, words) -> None:
    design = _write(tmp_path, _design())
    before = design.read_bytes()
    result = run_cli("plot", str(design), "-o", str(tmp_path / "x.png"),
                     *(a.format(tmp=tmp_path) for a in args))
    assert_user_error(result, *words)
    assert design.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cam.yaml"]


def test_the_points_never_go_over_an_input(tmp_path) -> None:
    design = _write(tmp_path, _design())
    table = tmp_path / "table.csv"
    table.write_text("x,y\n", encoding="utf-8")
    catalog = tmp_path / "motors.csv"
    catalog.write_text("id,inertia,continuous_torque,peak_torque,rated_speed\n"
                       "m1,1 kg*cm^2,50 N*m,150 N*m,3000 rpm\n", encoding="utf-8")
    result = run_cli("plot", str(design), "--cam", "-o", str(tmp_path / "x.png"),
                     "--catalog", str(catalog), "--points", str(catalog))
    assert_user_error(result, "--points")
    assert catalog.read_text(encoding="utf-8").startswith("id,")


def test_follower_motion_is_the_lift_at_the_cams_speed() -> None:
    from sizer.api import load
    from sizer.laws import make_law
    from sizer.mechanics.disc_cam import CamStage, follower_motion
    from sizer.sizing.linkage_move import cam_design

    design = load(_design())
    stage = cam_design(design, make_law("cycloidal")).transmission.linkage
    assert isinstance(stage, CamStage)
    motion = follower_motion(stage, 721)
    th = motion.theta
    assert motion.speed == pytest.approx(OMEGA, rel=1e-15)
    np.testing.assert_allclose(motion.position, _lift(th), rtol=0, atol=1e-15)
    ends = np.array([0.0, BETA, BETA + DWELL, 2 * BETA + DWELL, 2.0 * math.pi])
    inside = np.min(np.abs(th[:, None] - ends[None, :]), axis=1) > 1e-9  # jumps at ends
    assert np.count_nonzero(~inside) <= 10
    for k, values in enumerate((motion.velocity, motion.acceleration, motion.jerk), 1):
        expected = _lift(th, k) * OMEGA**k
        np.testing.assert_allclose(values[inside], expected[inside], rtol=1e-12,
                                   atol=1e-12 * float(np.max(np.abs(expected))))


def test_an_oscillating_followers_points_keep_the_arm(tmp_path) -> None:
    a, L, base = 0.100, 0.080, 0.025
    design = _design()
    design["cycle"]["segments"][0]["move"]["displacement"] = "20 deg"
    design["cycle"]["segments"][2]["move"]["displacement"] = "-20 deg"
    design["load"] = {"inertia": "0.001 kg*m^2"}
    design["transmission"][1] = {"type": "disc_cam", "follower": "oscillating_roller",
                                 "base_radius": "25 mm", "roller_radius": "10 mm",
                                 "pivot_distance": "100 mm", "arm_length": "80 mm"}
    path = _write(tmp_path, design)
    points = tmp_path / "osc.csv"
    result = run_cli("plot", str(path), "--cam", "-o", str(tmp_path / "osc.png"),
                     "--points", str(points), *SMALL)
    assert result.returncode == 0, result.stderr
    notes, columns, table = _read_csv(points)
    assert columns[1] == "swing [deg]"
    assert float(notes["base radius R_b [mm]"]) == pytest.approx(25.0, abs=1e-12)
    theta = np.radians(table[:, 0])
    swing = np.radians(table[:, 1])
    np.testing.assert_allclose(swing, _lift(theta) * math.radians(20.0) / H, rtol=0,
                               atol=1e-12)
    # the roller's centre back in the fixed frame (turned by +theta): on the arm's circle
    # about the pivot (a, 0), at psi_0 + swing from the line to the cam's centre
    cx, cy = table[:, 2] / 1e3, table[:, 3] / 1e3
    px = np.cos(theta) * cx - np.sin(theta) * cy
    py = np.sin(theta) * cx + np.cos(theta) * cy
    psi0 = math.acos((a * a + L * L - (base + R_F) ** 2) / (2.0 * a * L))
    np.testing.assert_allclose(px, a - L * np.cos(psi0 + swing), rtol=0, atol=1e-12)
    np.testing.assert_allclose(py, L * np.sin(psi0 + swing), rtol=0, atol=1e-12)
    gap = np.hypot(table[:, 4] - table[:, 2], table[:, 5] - table[:, 3])
    np.testing.assert_allclose(gap, 10.0, rtol=0, atol=1e-9)
