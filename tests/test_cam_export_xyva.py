"""sizer cam --to codesys-xyva (issue 37): XYVA tables, their certificate of position,
velocity and acceleration errors, and the torques re-computed on the table read back.

Each written file is parsed back here and interpolated independently (scipy's
BPoly.from_derivatives, quintic Hermite); the reference errors come from a grid of 10^6
points, the laws' one-sided values at their breakpoints, and a brentq extremum near the
grid's largest error. The torques are checked against sizing the re-read table with
sizer.api.size on the design file itself.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from scipy.interpolate import BPoly
from scipy.optimize import brentq

from sizer import api
from sizer.cli.app import run
from sizer.export import codesys_xyva
from sizer.export.hermite_certificate import table_for_tolerance, table_of
from sizer.export.profile import CamProfile
from sizer.laws import make_law

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
DESIGN = EXAMPLES / "indexing-table.yaml"
LAWS = ("cycloidal", "poly5", "modified_sinusoidal", "trapezoidal(alpha=1/3)",
        "double_s(alpha=1/3, beta=1/4)", "harmonic",
        "{kind: cubic_spline, points: [[0, 0], [0.3, 0.15], [0.55, 0.8], [1, 1]]}")
DENSE = 1_000_001


def read_back(text: str) -> tuple[np.ndarray, ...]:
    """(X, Y, V, A) of a written XYVA file: '#' comments, a header, then X,Y,V,A rows."""
    lines = [line for line in text.splitlines() if not line.startswith("#")]
    assert lines[0].startswith("X [") and ",V [" in lines[0] and ",A [" in lines[0]
    data = np.array([line.split(",") for line in lines[1:]], dtype=float)
    assert data.shape[1] == 4
    return data[:, 0], data[:, 1], data[:, 2], data[:, 3]


def reference_errors(law, stroke: float, span: float, x, y, v, a) -> list[tuple[float, float]]:
    """(dense, true) largest |error| of position, velocity and acceleration of the
    quintic Hermite through the file's points against the law scaled to stroke/span."""
    curve = BPoly.from_derivatives(x, np.stack([y, v, a], axis=1), orders=5)

    def law_at(t, order):
        return stroke / span ** order * law.derivative(np.asarray(t) / span, order)

    grid = np.linspace(0.0, span, DENSE)
    # the law's one-sided values at its breakpoints (a step of acceleration)
    sides = []
    for j, piece in enumerate(law.pieces):
        for tau in (piece.start, piece.end):
            sides.append((tau * span, j))
    out = []
    for order in range(3):
        error = law_at(grid, order) - curve.derivative(order)(grid) if order else \
            law_at(grid, 0) - curve(grid)
        dense = float(np.max(np.abs(error)))
        true = dense
        for t, j in sides:
            one_sided = stroke / span ** order * law.piece_derivative(j, t / span, order)
            true = max(true, abs(float(one_sided - curve.derivative(order)(t))
                                 if order else float(one_sided - curve(t))))
        k = int(np.argmax(np.abs(error)))

        def rate(t: float, order: int = order) -> float:
            return float(law_at(np.array([t]), order + 1)[0]
                         - curve.derivative(order + 1)(t))

        lo, hi = grid[max(k - 2, 0)], grid[min(k + 2, DENSE - 1)]
        if rate(lo) * rate(hi) < 0.0:
            r = brentq(rate, lo, hi, xtol=1e-15, rtol=4 * np.finfo(float).eps)
            at_r = float(law_at(np.array([r]), order)[0] - curve.derivative(order)(r))
            true = max(true, abs(at_r))
        out.append((dense, true))
    return out


def assert_certified(certified: float, dense: float, true: float, scale: float) -> None:
    assert certified >= dense * (1 - 1e-12) - 1e-13 * scale
    assert certified == pytest.approx(true, rel=1e-9, abs=1e-11 * scale)


@pytest.mark.parametrize("spec", LAWS)
def test_certificate_matches_the_file_read_back(spec: str) -> None:
    law = make_law(spec)
    stroke, span = 90.0, 0.25
    table = table_for_tolerance(CamProfile(law, stroke, span), 1e-6, 128)
    x, y, v, a = read_back(codesys_xyva.write(table))
    assert np.array_equal(x, table.master) and np.array_equal(a, table.acceleration)
    assert x[0] == 0.0 and x[-1] == span and len(x) <= 128
    # the law's breakpoints are among the points
    for piece in law.pieces:
        assert np.min(np.abs(x - piece.start * span)) < 1e-12 * span
    refs = reference_errors(law, stroke, span, x, y, v, a)
    peaks = (stroke, stroke / span * 10, stroke / span ** 2 * 100)
    for got, (dense, true), scale in zip(
            (table.errors.position, table.errors.velocity, table.errors.acceleration),
            refs, peaks, strict=True):
        assert_certified(got.max, dense, true, scale)
    if table.clipped:
        assert not table.met
    else:
        assert table.met and table.errors.position.max <= 1e-6 * stroke
        if table.points > len(np.unique(table.profile.breakpoints)):
            fewer = table_of(table.profile, table.points - 1)
            assert fewer.errors.position.max > 1e-6 * stroke


def test_a_quintic_law_is_reproduced_exactly() -> None:
    """poly5 is one quintic: two XYVA points give it back, to rounding."""
    table = table_for_tolerance(CamProfile(make_law("poly5"), 90.0, 0.25), 1e-9, 128)
    assert table.points == 2
    assert table.errors.position.max <= 1e-12 * 90.0
    assert table.errors.velocity.max <= 1e-12 * 90.0 / 0.25
    assert table.errors.acceleration.max <= 1e-11 * 90.0 / 0.25 ** 2


def run_cam(args: list[str], capsys) -> tuple[int, str, str]:
    code = run(["cam", *args])
    out, err = capsys.readouterr()
    return code, out, err


def resized_independently(out_file: Path, motor: str):
    """The written file read back as a user would, sized on the design file itself (its
    duration and ratio are fixed) for the motor."""
    spec = f"{{kind: cam_table, file: {json.dumps(str(out_file))}, " \
           "interpolation: quintic_hermite}"
    make_law(spec)
    return api.size(DESIGN, motors=[motor], laws=[spec]).results[0]


@pytest.mark.parametrize("extra", [[], ["--master-range", "360", "--points", "128"]])
def test_torques_equal_sizing_the_table_read_back(tmp_path: Path, capsys, extra) -> None:
    out_file, cert_file = tmp_path / "cam.txt", tmp_path / "cam.json"
    code, out, err = run_cam([str(DESIGN), "--to", "codesys-xyva", "-o", str(out_file),
                              "--certificate", str(cert_file), *extra], capsys)
    assert code == 0, out + err
    record = json.loads(cert_file.read_text())
    assert record["motor"] == "HG-KN43J" and record["law"] == "modified_sinusoidal"
    torques = record["torques"]
    assert torques["computed"] and torques["newly_failed"] == []
    again = resized_independently(out_file, "HG-KN43J")
    exported = torques["exported"]
    assert exported["peak_torque_Nm"] == pytest.approx(again.peak_torque, rel=1e-9)
    assert exported["rms_torque_Nm"] == pytest.approx(again.rms_torque, rel=1e-9)
    for check in again.checks:
        assert exported["margins"][str(check.name)]["margin"] == pytest.approx(
            check.margin, rel=1e-9, abs=1e-12)
    law = api.size(DESIGN, motors=["HG-KN43J"], laws=["modified_sinusoidal"]).results[0]
    assert torques["law"]["peak_torque_Nm"] == pytest.approx(law.peak_torque, rel=1e-12)
    assert torques["law"]["rms_torque_Nm"] == pytest.approx(law.rms_torque, rel=1e-12)
    assert "exported table: peak torque" in out and "acceleration error" in out
    if extra:  # a fine table: the torques approach the law's
        assert record["points"] == 128
        assert again.peak_torque == pytest.approx(law.peak_torque, rel=1e-6)
        assert again.rms_torque == pytest.approx(law.rms_torque, rel=1e-6)


def test_clipped_to_128_points_exits_1(tmp_path: Path, capsys) -> None:
    out_file, cert_file = tmp_path / "cam.txt", tmp_path / "cam.json"
    code, out, err = run_cam([str(DESIGN), "--to", "codesys-xyva", "-o", str(out_file),
                              "--law", "trapezoidal(alpha=1/3)", "--tolerance", "1e-9",
                              "--certificate", str(cert_file)], capsys)
    assert code == 1
    assert "clipped to 128 points" in out and "not met" in err
    record = json.loads(cert_file.read_text())
    assert record["points"] == 128 and record["clipped"] and not record["tolerance_met"]
    assert len(read_back(out_file.read_text())[0]) == 128


def test_a_check_the_exported_table_fails_exits_1(tmp_path: Path, capsys) -> None:
    """The trapezoid's acceleration steps: a C2 curve through them overshoots the peak
    torque. With a peak margin required between the law's and the table's, the law passes
    and the exported table fails: exit 1, said."""
    text = DESIGN.read_text().replace("catalogs/", str(EXAMPLES / "catalogs") + "/")
    text = text.replace("torque_margin: 10 %", "torque_margin: 83 %")
    design = tmp_path / "design.yaml"
    design.write_text(text)
    out_file, cert_file = tmp_path / "cam.txt", tmp_path / "cam.json"
    code, out, err = run_cam([str(design), "--to", "codesys-xyva", "-o", str(out_file),
                              "--motor", "HG-KN43J", "--law", "trapezoidal(alpha=1/3)",
                              "--certificate", str(cert_file)], capsys)
    record = json.loads(cert_file.read_text())
    assert code == 1, out + err
    assert record["torques"]["newly_failed"] == ["peak"]
    assert "fails peak, which the sized law passed" in err
    assert record["torques"]["law"]["margins"]["peak"]["passed"]
    assert not record["torques"]["exported"]["margins"]["peak"]["passed"]


def test_a_law_alone_has_no_torques(tmp_path: Path, capsys) -> None:
    out_file = tmp_path / "c.txt"
    code, out, _ = run_cam(["cycloidal", "--displacement", "90 deg", "--duration", "0.25 s",
                            "--to", "codesys-xyva", "-o", str(out_file)], capsys)
    assert code == 0
    assert "torques: not re-computed (a law alone" in out
    _, y, v, _ = read_back(out_file.read_text())
    assert y[-1] == pytest.approx(90.0) and v[0] == pytest.approx(0.0, abs=1e-9)
