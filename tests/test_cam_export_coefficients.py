"""``sizer cam --to siemens-tcpu`` (issue 37): coefficient segments Y = sum A_i X^i +
B0 sin(B1 X + B2), exact where the law's pieces are such, fitted within the tolerance
elsewhere; the certificate against an independent re-evaluation of the written file (parsed
here, evaluated here, against closed forms), and the torques against sizing the file read
back as a ``cam_segments`` law."""

from __future__ import annotations

import itertools
import json
import math
from pathlib import Path

import numpy as np
import pytest

from sizer import api
from sizer.cli.app import run
from sizer.laws import make_law

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
DESIGN = EXAMPLES / "indexing-table.yaml"
STROKE, T = 90.0, 0.25
PI = math.pi


def read_segments(text: str) -> list[tuple[float, ...]]:
    """The 16 numbers of each segment line (comments and the header skipped)."""
    lines = [line for line in text.splitlines() if line and not line.startswith("#")]
    assert lines[0] == "Type;Reserve;X1;Y1;X2;Y2;A0;A1;A2;A3;A4;A5;A6;B0;B1;B2"
    rows = [tuple(float(c) for c in line.split(";")) for line in lines[1:]]
    assert all(len(r) == 16 and r[0] == 0 and r[1] == 0 for r in rows)
    return rows


def evaluate(row: tuple[float, ...], x: np.ndarray, order: int = 0) -> np.ndarray:
    """d^order/dX^order of sum A_i X^i + B0 sin(B1 X + B2), as the manual writes it."""
    a, (b0, b1, b2) = np.array(row[6:13]), row[13:16]
    coef = np.polynomial.polynomial.polyder(a, order) if order else a
    return (np.polynomial.polynomial.polyval(x, coef)
            + b0 * b1 ** order * np.sin(b1 * x + b2 + order * PI / 2))


def file_curve(rows, x: np.ndarray, order: int = 0) -> np.ndarray:
    starts = np.array([r[2] for r in rows])
    which = np.clip(np.searchsorted(starts, x, side="right") - 1, 0, len(rows) - 1)
    out = np.empty_like(x)
    for k in range(len(rows)):
        mask = which == k
        out[mask] = evaluate(rows[k], x[mask], order)
    return out


def cycloidal(t):
    return t - np.sin(2 * PI * t) / (2 * PI)


def poly5(t):
    return 10 * t**3 - 15 * t**4 + 6 * t**5


def trapezoid(t):  # alpha = 1/3: v_max 1.5, a 4.5
    return np.where(t < 1 / 3, 2.25 * t**2,
                    np.where(t < 2 / 3, 0.25 + 1.5 * (t - 1 / 3), 1 - 2.25 * (1 - t) ** 2))


def poly7(t):
    return 35 * t**4 - 84 * t**5 + 70 * t**6 - 20 * t**7


SPLINE = "{kind: cubic_spline, points: [[0, 0], [0.3, 0.15], [0.55, 0.8], [1, 1]]}"
LAWS = [("cycloidal", cycloidal), ("poly5", poly5), ("trapezoidal(alpha=1/3)", trapezoid),
        ("modified_sinusoidal", None), ("double_s(alpha=1/3, beta=1/4)", None),
        (SPLINE, None)]


def run_cam(args: list[str], capsys) -> tuple[int, str, str]:
    code = run(["cam", *args])
    out, err = capsys.readouterr()
    return code, out, err


def export(tmp_path: Path, capsys, spec: str, *extra: str) -> tuple[list, dict]:
    out_file, cert = tmp_path / "cam.txt", tmp_path / "cam.json"
    code, out, err = run_cam([spec, "--displacement", "90 deg", "--duration", "0.25 s",
                              "--to", "siemens-tcpu", "-o", str(out_file),
                              "--certificate", str(cert), *extra], capsys)
    record = json.loads(cert.read_text())
    # exit 1 only where the single-precision estimate is over the tolerance (REAL data)
    assert code == (0 if record["single_precision_estimate"]["within_tolerance"] else 1), \
        out + err
    return read_segments(out_file.read_text()), record


@pytest.mark.parametrize(("spec", "closed"), LAWS)
@pytest.mark.parametrize("master", [None, "360"])
def test_exact_laws_are_written_exactly(tmp_path: Path, capsys, spec, closed, master) -> None:
    extra = [] if master is None else ["--master-range", master]
    rows, record = export(tmp_path, capsys, spec, *extra)
    span = T if master is None else float(master)
    law = make_law(spec)
    breaks = sorted({p.start for p in law.pieces} | {1.0})
    assert len(rows) == len(law.pieces)  # split at the law's natural points, no more
    assert [r[2] for r in rows] == pytest.approx([b * span for b in breaks[:-1]], abs=1e-12)
    x = np.linspace(0.0, span, 20001)
    for order in range(3):
        want = STROKE / span ** order * law.derivative(x / span, order)
        if order == 0 and closed is not None:
            assert np.allclose(want, STROKE * closed(x / span), atol=1e-12)
        got = file_curve(rows, x, order)
        scale = STROKE / span ** order * max(1.0, np.max(np.abs(law.derivative(x / span,
                                                                               order))))
        assert np.max(np.abs(got - want)) <= 1e-12 * scale
        name = ("position", "velocity", "acceleration")[order]
        assert record["errors"][name]["max"] <= 1e-12 * scale
    assert record["tolerance_met"] and record["fitted_pieces"] == 0
    assert record["split"].get("fitted") is None


def test_poly7_is_fitted_within_the_tolerance_c2(tmp_path: Path, capsys) -> None:
    rows, record = export(tmp_path, capsys, "poly7", "--tolerance", "1e-6")
    assert record["fitted_pieces"] == 1 and len(rows) > 1
    x = np.linspace(0.0, T, 400001)
    x = np.unique(np.concatenate([x, [r[2] for r in rows]]))
    for order, name in enumerate(("position", "velocity", "acceleration")):
        law = STROKE / T ** order * make_law("poly7").derivative(x / T, order)
        dense = np.max(np.abs(file_curve(rows, x, order) - law))
        certified = record["errors"][name]["max"]
        # rounding: the absolute-X coefficients cancel (amplification ~1e3 strokes)
        assert dense <= certified + 1e-10 * STROKE / T ** order
        assert certified == pytest.approx(dense, rel=1e-3)  # the true max, not a bound
    assert record["errors"]["position"]["max"] <= 1e-6 * STROKE
    np.testing.assert_allclose(
        STROKE * poly7(x / T), STROKE / T ** 0 * make_law("poly7").derivative(x / T),
        atol=1e-12)
    for left, right in itertools.pairwise(rows):  # C2 joins
        x0 = np.array([right[2]])
        for order in range(3):
            assert evaluate(left, x0, order) == pytest.approx(evaluate(right, x0, order),
                                                              rel=1e-9, abs=1e-9)


def test_torques_equal_sizing_the_segments_read_back(tmp_path: Path, capsys) -> None:
    out_file, cert = tmp_path / "cam.txt", tmp_path / "cam.json"
    code, out, err = run_cam([str(DESIGN), "--to", "siemens-tcpu", "-o", str(out_file),
                              "--certificate", str(cert)], capsys)
    assert code == 0, out + err
    record = json.loads(cert.read_text())
    assert record["motor"] == "HG-KN43J" and record["law"] == "modified_sinusoidal"
    torques = record["torques"]
    assert torques["computed"] and torques["newly_failed"] == []
    spec = f"{{kind: cam_segments, file: {json.dumps(str(out_file))}}}"
    again = api.size(DESIGN, motors=["HG-KN43J"], laws=[spec]).results[0]
    exported = torques["exported"]
    assert exported["peak_torque_Nm"] == pytest.approx(again.peak_torque, rel=1e-9)
    assert exported["rms_torque_Nm"] == pytest.approx(again.rms_torque, rel=1e-9)
    law = api.size(DESIGN, motors=["HG-KN43J"], laws=["modified_sinusoidal"]).results[0]
    # the exported segments are the law: the same torques to rounding
    assert again.peak_torque == pytest.approx(law.peak_torque, rel=1e-9)
    assert again.rms_torque == pytest.approx(law.rms_torque, rel=1e-9)
    assert "exported segments: peak torque" in out and "REAL" in out


def test_user_errors_exit_2(tmp_path: Path, capsys) -> None:
    out_file = tmp_path / "cam.txt"
    base = ["cycloidal", "--displacement", "90 deg", "--duration", "0.25 s", "--to",
            "siemens-tcpu", "-o", str(out_file)]
    code, _, err = run_cam([*base, "--points", "5"], capsys)
    assert code == 2 and "--points" in err and "Traceback" not in err
    code, _, err = run_cam([*base, "--tolerance", "2"], capsys)
    assert code == 2 and "--tolerance" in err
    bad = tmp_path / "bad.txt"
    bad.write_text("Type;Reserve;X1;Y1;X2;Y2;A0;A1;A2;A3;A4;A5;A6;B0;B1;B2\n"
                   "0;0;0;0;1;1;0;1;0;0;0;0;0;0;0\n")
    code = run(["law", f"{{kind: cam_segments, file: {json.dumps(str(bad))}}}"])
    _, err = capsys.readouterr()
    assert code == 2 and "bad.txt:2:" in err and "16 fields" in err and "Traceback" not in err
    assert not out_file.exists()


def test_splitting_stops_at_the_cap_and_says_not_met() -> None:
    from sizer.export.coefficient_segments import export_segments
    from sizer.export.profile import CamProfile

    profile = CamProfile(make_law("poly7"), STROKE, T)
    export = export_segments(profile, 1e-12, limit=2)
    assert export.capped and not export.met and len(export.segments) == 2
    again = export_segments(profile, 1e-4)
    assert again.met and not again.capped
