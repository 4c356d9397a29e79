"""A rest-to-rest cam table (sizer's own ``sizer law ... --format csv``) read back is at
rest at its ends within its resolution: a task with a dwell sizes it (issue 37)."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from sizer.cli.app import app
from sizer.laws import make_law
from sizer.laws.cam_interpolation import end_bound, rest_ends
from sizer.laws.data_spec import data_spec_text
from sizer.laws.multipoint.sample_fit import fit_samples

ROOT = Path(__file__).resolve().parents[1]
LAWS = ("cycloidal", "poly5", "modified_sinusoidal")
ORDERS = (4, 6, 8)


def export(law: str, folder: Path) -> Path:
    """sizer's own export of ``law``: 90 deg in 0.25 s, 101 samples."""
    path = folder / f"{law}.csv"
    result = CliRunner().invoke(app, ["law", law, "--displacement", "90 deg", "--duration",
                                      "0.25 s", "--format", "csv", "-o", str(path)])
    assert result.exit_code == 0, result.output
    return path


def dwell_design(folder: Path, law: str) -> Path:
    """examples/indexing-table.yaml (a 0.35 s dwell) with ``law`` as its only law."""
    text = (ROOT / "examples" / "indexing-table.yaml").read_text()
    text = re.sub(r"laws:\n(  - .*\n)+", f"laws:\n  - {law}\n", text)
    text = re.sub(r"check:\n(  .*\n?)+", "", text)
    text = text.replace("motors: catalogs/", f"motors: {ROOT / 'examples' / 'catalogs'}/")
    path = folder / "design.yaml"
    path.write_text(text)
    return path


def size(design: Path) -> dict:
    result = CliRunner().invoke(app, ["size", str(design), "--all", "--format", "json"])
    assert result.exit_code == 0, result.output
    return json.loads(result.output)


def table_law(path: Path, **fields):
    return make_law(data_spec_text({"kind": "cam_table", "file": str(path), **fields}))


@pytest.mark.parametrize("law", LAWS)
@pytest.mark.parametrize("order", ORDERS)
def test_the_exported_law_is_at_rest_at_its_ends(tmp_path, law, order):
    table = table_law(export(law, tmp_path), order=order)
    assert table.end_speeds == (0.0, 0.0)
    assert table.rest_to_rest
    # clamped: the fitted curve itself starts and ends at rest
    assert table.piece_derivative(0, 0.0, 1) == pytest.approx(0.0, abs=1e-12)
    last = len(table.pieces) - 1
    assert table.piece_derivative(last, 1.0, 1) == pytest.approx(0.0, abs=1e-12)


def test_a_broken_line_is_refused_for_sizing(tmp_path):
    """Order 2 fits a broken line: its acceleration is a train of impulses, so no torque
    follows from it (it sized with zero acceleration before: refused, as linear is)."""
    from sizer.errors import UserError

    with pytest.raises(UserError, match="broken line"):
        table_law(export(LAWS[0], tmp_path), order=2)


@pytest.mark.parametrize("law", LAWS)
def test_a_task_with_a_dwell_sizes_the_exported_table(tmp_path, law):
    path = export(law, tmp_path)
    table = size(dwell_design(tmp_path, f"{{kind: cam_table, file: {path}}}"))
    exact = size(dwell_design(tmp_path, law))
    pairs = {r["motor"]: r for r in table["results"]}
    # same motors, same verdicts, torques to 1e-4 (the modified sine's C_a, below)
    for result in exact["results"]:
        other = pairs[result["motor"]]
        assert other["feasible"] == result["feasible"]
        for key in ("peak_torque", "rms_torque"):
            if isinstance(result.get(key), float):
                assert other[key] == pytest.approx(result[key], rel=1e-4)


# order 6 (the default) of 101 samples: C_v, C_v_rms, C_a_rms to 1e-9; C_a to 1e-4 (the
# modified sine's jerk steps, which a quintic fit rounds over one sample spacing)
@pytest.mark.parametrize("law", LAWS)
def test_the_coefficients_of_the_read_back_law(tmp_path, law):
    exact = make_law(law).coefficients.as_dict()
    read = table_law(export(law, tmp_path)).coefficients.as_dict()
    for name, rel in (("C_v", 1e-9), ("C_v_rms", 1e-9), ("C_a_rms", 1e-8), ("C_a", 1e-4)):
        assert read[name] == pytest.approx(exact[name], rel=rel), name


def test_a_table_that_starts_moving_still_moves(tmp_path):
    """v_N(0) = 0.01 plus a poly5: far above what 101 samples leave unresolved."""
    x = np.linspace(0.0, 1.0, 101)
    q = 0.01 * x + x ** 3 * (10 - 15 * x + 6 * x ** 2)
    path = tmp_path / "moving.csv"
    path.write_text("t,q\n" + "".join(f"{float(a)!r},{float(b)!r}\n"
                                      for a, b in zip(x, q, strict=True)))
    for order in (4, 6, 8):
        law = table_law(path, order=order)
        assert not law.rest_to_rest
        # a cubic (order 4) is off by h^3-ish on a quintic, the higher orders exact
        assert law.end_speeds[0] == pytest.approx(0.01 / 1.01, rel=1e-2 if order == 4
                                                  else 1e-9)


def test_the_bound_is_the_end_difference():
    """Uniform samples of q = x^m: the m-th difference is m! h^m at every window, the
    bound REST_FACTOR m! h^(m-1) (+ rounding) at both ends."""
    from sizer.laws.cam_interpolation import REST_FACTOR

    x = np.linspace(0.0, 1.0, 11)
    h = 0.1
    start, end = end_bound(x, x ** 4, 4)
    assert start == pytest.approx(REST_FACTOR * 24 * h ** 3, rel=1e-9)
    assert end == pytest.approx(REST_FACTOR * 24 * h ** 3, rel=1e-9)


def test_rest_ends_of_a_clean_fit():
    x = np.linspace(0.0, 1.0, 101)
    q = x - np.sin(2 * np.pi * x) / (2 * np.pi)
    fit = fit_samples(x, q, order=6)
    rest = rest_ends(fit.curve, x, q, 6)
    assert rest.start and rest.end
    assert abs(rest.speeds[0]) < rest.bounds[0]
