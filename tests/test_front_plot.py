"""``sizer plot DESIGN --front``: the feasible pairs, the front, the chord and the knee."""

from __future__ import annotations

import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from cli_run import assert_user_error
from cli_run import run_cli as run

from sizer import api
from sizer.report.plots.front_plot import (
    GID_CANDIDATES,
    GID_CHORD,
    GID_FRONT,
    GID_KNEE,
    front_figure,
)
from sizer.sizing.front import trade_off

ROOT = Path(__file__).resolve().parent.parent
GEARBOXES = str(ROOT / "examples" / "indexing-table-gearboxes.yaml")
INDEXING = str(ROOT / "examples" / "indexing-table.yaml")


def gids(path: Path) -> set[str]:
    return {e.get("id") or "" for e in ET.parse(path).getroot().iter()} - {""}


def test_plot_front_writes_the_figure_with_its_parts(tmp_path: Path) -> None:
    out = tmp_path / "front.svg"
    result = run("plot", GEARBOXES, "--front", "-o", str(out))
    assert result.returncode == 0, result.stderr
    from test_front import knee_by_hand

    knee, on, feasible = knee_by_hand(api.size(GEARBOXES))
    assert f"trade-off front of {on} of {feasible} feasible pairs, knee {knee.motor}" \
        in result.stdout
    assert {GID_CANDIDATES, GID_FRONT, GID_CHORD, GID_KNEE} <= gids(out)
    png = tmp_path / "front.png"
    assert run("plot", GEARBOXES, "--front", "-o", str(png)).returncode == 0
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_the_figure_draws_the_cores_front() -> None:
    sizing = api.size(GEARBOXES)
    front = trade_off(sizing)
    figure = front_figure(sizing, front, title="t")
    ax = figure.axes[0]
    lines = {line.get_gid(): line for line in ax.get_lines()}
    drawn = lines[GID_FRONT]
    assert np.allclose(drawn.get_xdata(), front.size[front.members])  # W
    assert np.allclose(drawn.get_ydata(), front.time[front.members] * 1000.0)  # ms
    assert front.knee is not None
    knee = lines[GID_KNEE]
    assert knee.get_xdata()[0] == pytest.approx(front.size[front.knee])
    chord = lines[GID_CHORD]  # through the two ends of the front
    assert list(chord.get_xdata()) == list(drawn.get_xdata()[[0, -1]])
    scatter = next(c for c in ax.collections if c.get_gid() == GID_CANDIDATES)
    assert len(scatter.get_offsets()) == len(sizing.feasible)


def test_a_given_duration_draws_the_margin(tmp_path: Path) -> None:
    out = tmp_path / "margin.png"
    result = run("plot", INDEXING, "--front", "--law", "cycloidal", "-o", str(out))
    assert result.returncode == 0, result.stderr
    assert "of 2 of 2 feasible pairs" in result.stdout and out.exists()


@pytest.mark.parametrize(("args", "option"), [
    (["--front", "--time"], "--time"), (["--front", "--acceleration"], "--acceleration"),
    (["--front", "--motor", "HG-KN43J"], "--motor"), (["--front-by", "mass"], "--front"),
    (["--front", "--front-by", "volume"], "--front-by"),
    (["--front", "--law", "nope"], "--law")])
def test_plot_front_user_errors(tmp_path: Path, args: list[str], option: str) -> None:
    out = tmp_path / "x.png"
    assert_user_error(run("plot", GEARBOXES, *args, "-o", str(out)), option)
    assert not out.exists()


def test_sizer_plot_front_imports_matplotlib_only_when_drawing(tmp_path: Path) -> None:
    code = ("import sys\nimport sizer.report.plots.front_plot, sizer.sizing.front\n"
            "print('matplotlib' in sys.modules)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, cwd=tmp_path)
    assert out.stdout.strip() == "False"
