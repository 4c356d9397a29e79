"""``sizer plot`` and ``sizer plot-law``: files written, the pair chosen, errors; and no
matplotlib import where it is not needed (``sizer size`` stays fast to start)."""

from __future__ import annotations

import math
import os
import struct
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
import typer
from typer.testing import CliRunner

pytest.importorskip("matplotlib")

from sizer.cli import plot_command, report_command
from sizer.cli.plot_command import parse_size, plot_pairs
from sizer.errors import UserError
from sizer.io import load_design
from sizer.report.numbers import short
from sizer.report.plots import curve_for, speed_torque_figure
from sizer.sizing import size_design

ROOT = Path(__file__).resolve().parents[1]

DESIGN = """\
name: Book 6.1
task: {displacement: 15 rad, duration: 3 s}
load: {inertia: 1 kg*m^2, damping: 0.3 N*m*s/rad}
transmission: {type: direct}
laws: [cycloidal, "trapezoidal(alpha=0.12732200375003505)", harmonic]
motors: book-examples
"""

CHECKED = DESIGN + "check: {motor: ex6_1, law: cycloidal}\n"

FAST = ["--dpi", "40", "--size", "4x3", "--samples", "21"]


def app() -> typer.Typer:
    """The commands of this module on their own app (sizer.cli.app registers them too)."""
    application = typer.Typer()
    plot_command.register(application)
    report_command.register(application)
    return application


def run(*args: str) -> tuple[int, str]:
    """Exit code and output; a UserError counts as exit code 2, as in sizer.cli.app.main."""
    result = CliRunner().invoke(app(), [str(a) for a in args])
    if isinstance(result.exception, UserError):
        return 2, str(result.exception)
    if result.exception and not isinstance(result.exception, SystemExit):
        raise result.exception
    return result.exit_code, result.output


def png_size(path: Path) -> tuple[int, int]:
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    return struct.unpack(">II", data[16:24])


@pytest.fixture
def design_file(tmp_path):
    path = tmp_path / "design.yaml"
    path.write_text(DESIGN)
    return path


@pytest.fixture
def checked_file(tmp_path):
    path = tmp_path / "checked.yaml"
    path.write_text(CHECKED)
    return path


# -------------------------------------------------------------------- sizer plot
def test_plot_draws_the_check_pair_by_default(tmp_path, checked_file):
    out = tmp_path / "plot.png"
    code, output = run("plot", checked_file, "-o", out, *FAST)
    assert code == 0, output
    assert png_size(out) == (160, 120)
    assert output.strip() == f"{out}: speed-torque diagram of ex6_1 with cycloidal"


def test_plot_without_check_draws_the_best_ranked_feasible_pair(tmp_path, design_file):
    design = load_design(design_file)
    best = next(r for r in size_design(design).results if r.feasible)
    out = tmp_path / "plot.svg"
    code, output = run("plot", design_file, "-o", out, *FAST, "--acceleration")
    assert code == 0, output
    assert f"of {best.motor} with {best.spec}" in output
    root = ET.fromstring(out.read_bytes())
    assert root.tag.endswith("svg") and root.get("width") == "288pt"


def test_plot_with_motor_and_laws(tmp_path, checked_file):
    out = tmp_path / "two.png"
    code, output = run("plot", checked_file, "-o", out, "--motor", "ex6_1", "--law",
                       "harmonic", "--law", "poly5", "--speed-unit", "rad/s", *FAST)
    assert code == 0, output
    assert "of ex6_1 with harmonic, polynomial(degree=5)" in output
    assert out.stat().st_size > 1000


def test_plot_pairs_rules(design_file, checked_file):
    design, checked = load_design(design_file), load_design(checked_file)
    ranked = size_design(design).results
    best = next(r for r in ranked if r.feasible)
    assert [(r.motor, r.spec) for r in plot_pairs(design)] == [(best.motor, best.spec)]
    assert [(r.motor, r.spec) for r in plot_pairs(checked)] == [("ex6_1", "cycloidal")]
    # a motor alone: its best-ranked law
    ex6_4 = next(r for r in ranked if r.motor == "ex6_4")
    assert [(r.motor, r.spec) for r in plot_pairs(design, "ex6_4")] == [
        ("ex6_4", ex6_4.spec)]
    # laws alone: the check motor, in the order asked
    pairs = plot_pairs(checked, laws=["harmonic", "cycloidal", "harmonic"])
    assert [(r.motor, r.spec) for r in pairs] == [("ex6_1", "harmonic"),
                                                  ("ex6_1", "cycloidal")]
    # laws alone, no check: the motor of the best-ranked feasible pair of those laws
    pairs = plot_pairs(design, laws=["harmonic"])
    best_harmonic = next(r for r in ranked if r.spec == "harmonic" and r.feasible)
    assert [r.motor for r in pairs] == [best_harmonic.motor]
    # the pair drawn is the sized one
    pair = plot_pairs(design, "ex6_1", ["cycloidal"])[0]
    assert pair == next(r for r in ranked if r.motor == "ex6_1" and r.spec == "cycloidal")


def test_plot_minimize_uses_t_min(tmp_path):
    path = tmp_path / "fast.yaml"
    path.write_text(DESIGN.replace("duration: 3 s", "duration: minimize"))
    design = load_design(path)
    (pair,) = plot_pairs(design, "ex6_1", ["harmonic"])
    assert pair.feasible
    assert pair.duration >= math.pi / 2 * 15 / 10  # at least C_v h / v_n
    assert pair.duration != pytest.approx(3.0)  # T_min, not the 3 s of the other mode
    assert curve_for(design, pair, samples=11).duration == pair.duration
    figure = speed_torque_figure([curve_for(design, pair, samples=11)], [pair],
                                 duration_name="T_min", size=(4, 3), dpi=40)
    assert figure.axes[0].get_legend_handles_labels()[1][2] == (
        f"harmonic, T_min = {short(pair.duration * 1000)} ms")
    out = tmp_path / "fast.png"
    code, output = run("plot", path, "-o", out, "--motor", "ex6_1", "--law", "harmonic",
                       *FAST)
    assert code == 0, output


@pytest.mark.parametrize(("args", "message"), [
    (["--motor", "nope"], "--motor: unknown motor 'nope'"),
    (["--law", "nolaw"], "nolaw"),
    (["--speed-unit", "deg/s"], "--speed-unit: expected one of rpm, rad/s"),
    (["--size", "4"], "--size: expected WIDTHxHEIGHT"),
    (["--size", "400x3"], "between 0.5 and 100 inches"),
])
def test_plot_user_errors(tmp_path, design_file, args, message):
    out = tmp_path / "x.png"
    code, output = run("plot", design_file, "-o", out, *args)
    assert code == 2
    assert message in output
    assert not out.exists()


def test_plot_output_suffix_is_checked_before_any_work(tmp_path):
    code, output = run("plot", tmp_path / "missing.yaml", "-o", tmp_path / "x.jpg")
    assert code == 2
    assert "*.png or *.svg" in output


def test_plot_of_a_pair_without_duration_says_so(tmp_path):
    path = tmp_path / "hopeless.yaml"
    path.write_text(DESIGN.replace("duration: 3 s", "duration: minimize")
                    .replace("inertia: 1 kg*m^2", "inertia: 1 kg*m^2, torque: 50 N*m"))
    code, output = run("plot", path, "-o", tmp_path / "x.png", "--motor", "ex6_1", *FAST)
    assert code == 2
    assert "no law with a feasible duration" in output


def test_parse_size():
    assert parse_size("8x6") == (8.0, 6.0)
    assert parse_size(" 3.5 X 2 ") == (3.5, 2.0)
    assert parse_size(None) is None
    with pytest.raises(UserError):
        parse_size("8 by 6")


# ---------------------------------------------------------------- sizer plot-law
def test_plot_law_normalized(tmp_path):
    out = tmp_path / "laws.png"
    code, output = run("plot-law", "cycloidal", "trapezoidal", "-o", out, *FAST)
    assert code == 0, output
    assert png_size(out) == (160, 120)
    assert "cycloidal, trapezoidal(alpha=1/3)" in output


def test_plot_law_scaled(tmp_path):
    out = tmp_path / "laws.svg"
    code, output = run("plot-law", "double_s", "-o", out, "--displacement", "200 mm",
                       "--duration", "0.5 s", "--size", "3x5")
    assert code == 0, output
    root = ET.fromstring(out.read_bytes())
    assert root.get("width") == "216pt" and root.get("height") == "360pt"


@pytest.mark.parametrize(("args", "message"), [
    (["--duration", "1 s"], "--displacement: --duration needs --displacement too"),
    (["--displacement", "1 rad"], "--duration: --displacement needs --duration too"),
    (["--displacement", "1 rad", "--duration", "0 s"], "--duration: must be positive"),
    (["--displacement", "2 kg", "--duration", "1 s"], "--displacement"),
])
def test_plot_law_user_errors(tmp_path, args, message):
    code, output = run("plot-law", "cycloidal", "-o", tmp_path / "x.png", *args)
    assert code == 2
    assert message in output


def test_plot_law_unknown_law(tmp_path):
    code, output = run("plot-law", "nolaw", "-o", tmp_path / "x.png")
    assert code == 2
    assert "nolaw" in output


# ------------------------------------------------------------ lazy matplotlib
def _python(code: str, cwd: Path) -> str:
    env = dict(os.environ, PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    done = subprocess.run([sys.executable, "-c", code], cwd=cwd, env=env, capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_sizer_size_does_not_import_matplotlib(tmp_path, design_file):
    code = (
        "import sys\n"
        "from sizer.cli import app as cli\n"
        "from sizer.cli import plot_command, report_command\n"
        "plot_command.register(cli.app); report_command.register(cli.app)\n"
        "try:\n"
        f"    cli.main(['size', {str(design_file)!r}, '--format', 'csv'])\n"
        "except SystemExit as stop:\n"
        "    assert not stop.code, stop.code\n"
        "print('matplotlib' in sys.modules, 'matplotlib.pyplot' in sys.modules)\n"
    )
    out = _python(code, tmp_path)
    assert out.strip().splitlines()[-1] == "False False"


def test_importing_the_plot_and_report_modules_does_not_import_matplotlib(tmp_path):
    code = (
        "import sys\n"
        "import sizer.cli.plot_command, sizer.cli.report_command\n"
        "import sizer.report.plots, sizer.report.design_report\n"
        "import sizer.laws, sizer.sizing, sizer.envelope, sizer.mechanics\n"
        "print(sorted(m for m in sys.modules if m.split('.')[0] == 'matplotlib'))\n"
    )
    assert _python(code, tmp_path).strip() == "[]"
