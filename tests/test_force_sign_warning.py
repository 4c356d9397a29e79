"""The sign of a process force (issue 36): a positive force (torque) opposes a positive
move; one that helps the motion through a whole move or run is warned about, located (a
sign mistake gave an 18 % lower RMS torque on a press). The RMS torques of the press of
docs/process-forces.md are checked against an independent model (the figure's script)."""

from __future__ import annotations

import importlib.util
import math
import subprocess
import sys
from pathlib import Path

import pytest

from sizer.io import load_design
from sizer.io.force_sign import aids_the_whole_segment
from sizer.sizing.engine import size_design

ROOT = Path(__file__).resolve().parent.parent
MOTOR = ("{id: M, inertia: 1 kg*cm^2, continuous_torque: 3 N*m, peak_torque: 9 N*m, "
         "rated_speed: 3000 rpm, max_speed: 5000 rpm}")


def press(force: str, extra: str = "") -> str:
    return f"""name: Press
cycle:
  closed: true
  segments:
    - move: {{displacement: 80 mm, duration: 0.2 s, name: approach}}
    - move: {{displacement: 20 mm, duration: 0.3 s, force: {force}, name: press}}
    - move: {{displacement: -100 mm, duration: 0.25 s, name: return}}
    - dwell: {{duration: 0.25 s, force: -500 N, name: unload}}
{extra}load: {{mass: 30 kg}}
transmission:
  - {{type: ball_screw, lead: 10 mm, inertia: 0}}
laws: [cycloidal]
motors:
  - {MOTOR}
"""


def design_of(tmp_path: Path, text: str, name: str = "press.yaml"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path, load_design(path)


@pytest.mark.parametrize("force, h, v0, v1, warned", [
    (-1.0, 1.0, 0.0, 0.0, True), (1.0, 1.0, 0.0, 0.0, False), (1.0, -1.0, 0.0, 0.0, True),
    (-1.0, -1.0, 0.0, 0.0, False), (0.0, 1.0, 0.0, 0.0, False),
    (-1.0, 1.0, -0.5, 0.0, False),  # starts backwards: not helped all along
    (-1.0, 1.0, 0.5, 0.5, True)])
def test_a_force_against_the_displacement_helps_the_whole_segment(
        force: float, h: float, v0: float, v1: float, warned: bool) -> None:
    assert aids_the_whole_segment(force, h, v0, v1) is warned


def test_the_wrong_sign_is_warned_with_its_place(tmp_path: Path) -> None:
    path, design = design_of(tmp_path, press("-2000 N"))
    (warning,) = [w for w in design.warnings if "helps the motion" in w]
    assert warning.startswith(f"{path}:6: cycle.segments[1].move.force: -2000 N helps")
    assert "docs/process-forces.md" in warning
    _, right = design_of(tmp_path, press("2000 N"), "right.yaml")
    assert not [w for w in right.warnings if "helps the motion" in w]  # nor the dwell's


def test_a_run_against_its_force_is_warned(tmp_path: Path) -> None:
    text = """cycle:
  closed: true
  share: displacement
  segments:
    - move: {displacement: 150 mm, end_speed: 0.5 m/s}
    - run: {speed: 0.5 m/s, duration: 0.4 s, force: -120 N, name: cut}
    - move: {displacement: 100 mm, start_speed: 0.5 m/s}
    - move: {displacement: -450 mm}
    - dwell: {duration: 0.1 s}
load: {mass: 25 kg}
transmission:
  - {type: rack_pinion, pitch_radius: 30 mm}
laws: [poly5]
"""
    _, design = design_of(tmp_path, text + f"motors:\n  - {MOTOR}\n")
    (warning,) = [w for w in design.warnings if "helps the motion" in w]
    assert "cycle.segments[1].run.force: -120 N" in warning and "0.5 m/s" in warning


def _model():
    spec = importlib.util.spec_from_file_location(
        "process_force_figure", ROOT / "tools" / "process_force_figure.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_press_rms_torques_of_the_page(tmp_path: Path) -> None:
    """+2000 N: 2.03 N*m; -2000 N back-drives the 90 % screw: 1.68 N*m (17 % lower)."""
    model = _model()
    for force in (2000.0, -2000.0):
        _, design = design_of(tmp_path, press(f"{force:g} N"), f"p{force:g}.yaml")
        (row,) = size_design(design).results
        # the dwell's 500 N held at rest counts as driving: 500 N / K / 0.9 either way
        hold = 500.0 * 0.01 / (2.0 * math.pi) / 0.9
        held = math.sqrt(model.rms(force) ** 2 + hold**2 * 0.25 / 1.0)
        assert row.rms_torque == pytest.approx(held, rel=1e-4)


def test_the_cli_prints_the_warning_on_stderr(tmp_path: Path) -> None:
    path, _ = design_of(tmp_path, press("-2000 N"))
    result = subprocess.run([sys.executable, "-m", "sizer", "size", str(path), "--format",
                             "csv"], capture_output=True, text=True, timeout=120)
    assert result.returncode == 0
    assert "warning: " in result.stderr and "helps the motion" in result.stderr
    assert "helps" not in result.stdout
