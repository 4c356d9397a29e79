"""sizer cam --to twincat-mc3 (issue 37): the law itself as TwinCAT 3 MC3 motion functions.

The written IEC 61131-3 code is parsed back with regular expressions, the profile rebuilt
from each point's FunctionType with formulas written here independently of
sizer.export.twincat_mc3 (poly3/5/7 by their rest boundary conditions, the cycloid
t - sin(2 pi t)/(2 pi), the VDI 2143 modified sine), and compared with sizer's law to
1e-12 of the stroke (and of the peak velocity and acceleration).
"""

from __future__ import annotations

import itertools
import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

from sizer.cli.app import run
from sizer.laws import make_law

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
PI = math.pi
POINT = re.compile(r"\(([^()]*)\)")
FIELD = re.compile(r"(\w+) := ([^,]+)")


def read_back(text: str) -> list[dict[str, object]]:
    """The MotionFunctionPoints of the ARRAY initialisation, as dicts."""
    body = re.search(r"ARRAY\[0\.\.(\d+)\] OF MotionFunctionPoint := \[(.*?)\];", text,
                     re.S)
    assert body is not None
    points = []
    for match in POINT.finditer(body.group(2)):
        fields = dict(FIELD.findall(match.group(1)))
        kind = fields.pop("FunctionType")
        assert kind.startswith("EMotionFunctionType.")
        point: dict[str, object] = {k: float(v) for k, v in fields.items()}
        point["FunctionType"] = kind.split(".", 1)[1]
        points.append(point)
    assert len(points) == int(body.group(1)) + 1
    assert f"NumberOfPoints := {len(points)};" in text
    return points


def q(kind: str, t: np.ndarray, order: int) -> np.ndarray:
    """Normalized rest-to-rest function types (q(0) = 0, q(1) = 1), by hand."""
    if kind == "Linear":
        return [t, np.ones_like(t), np.zeros_like(t)][order]
    if kind == "Polynomial3":
        return [3 * t**2 - 2 * t**3, 6 * t - 6 * t**2, 6 - 12 * t][order]
    if kind == "Polynomial5":
        return [10 * t**3 - 15 * t**4 + 6 * t**5, 30 * t**2 - 60 * t**3 + 30 * t**4,
                60 * t - 180 * t**2 + 120 * t**3][order]
    if kind == "Polynomial7":
        return [35 * t**4 - 84 * t**5 + 70 * t**6 - 20 * t**7,
                140 * t**3 - 420 * t**4 + 420 * t**5 - 140 * t**6,
                420 * t**2 - 1680 * t**3 + 2100 * t**4 - 840 * t**5][order]
    if kind == "Sinusoid":
        return [t - np.sin(2 * PI * t) / (2 * PI), 1 - np.cos(2 * PI * t),
                2 * PI * np.sin(2 * PI * t)][order]
    assert kind == "ModifiedSinusoid"
    # Norton, "Cam design and manufacturing handbook", modified sine (VDI 2143 modifizierte
    # Sinuslinie with its inflection point at 1/2)
    c = 1 / (4 + PI)
    ends = (t <= 1 / 8) | (t >= 7 / 8)
    base = np.where(t >= 7 / 8, 4 * c, 0.0)
    s, w, p = np.where(ends, c / 4, 9 * c / 4), np.where(ends, 4 * PI, 4 * PI / 3), \
        np.where(ends, 0.0, PI / 3)
    base = np.where(ends, base, 2 * c)
    return [base + PI * c * t - s * np.sin(w * t + p),
            PI * c - s * w * np.cos(w * t + p),
            s * w**2 * np.sin(w * t + p)][order]


def rebuilt(points: list[dict[str, object]], x: np.ndarray, order: int) -> np.ndarray:
    masters = np.array([p["MasterPosition"] for p in points], dtype=float)
    out = np.empty_like(x)
    k = np.clip(np.searchsorted(masters, x, side="right") - 1, 0, len(points) - 2)
    for i in np.unique(k):
        a, b = points[i], points[i + 1]
        span = float(b["MasterPosition"]) - float(a["MasterPosition"])  # type: ignore[arg-type]
        rise = float(b["SlavePosition"]) - float(a["SlavePosition"])  # type: ignore[arg-type]
        t = (x[k == i] - float(a["MasterPosition"])) / span  # type: ignore[arg-type]
        out[k == i] = rise / span**order * q(str(a["FunctionType"]), t, order)
        if order == 0:
            out[k == i] += float(a["SlavePosition"])  # type: ignore[arg-type]
    return out


def cam(args: list[str], capsys) -> tuple[int, str, str]:
    code = run(["cam", *args])
    out, err = capsys.readouterr()
    return code, out, err


CASES = [("poly3", "Polynomial3"), ("poly5", "Polynomial5"),
         ("polynomial(degree=7)", "Polynomial7"), ("cycloidal", "Sinusoid"),
         ("modified_sinusoidal", "ModifiedSinusoid")]


@pytest.mark.parametrize(("spec", "kind"), CASES)
def test_one_segment_is_the_law(spec: str, kind: str, tmp_path: Path, capsys) -> None:
    out_file, cert_file = tmp_path / "cam.st", tmp_path / "cam.json"
    code, out, err = cam([spec, "--displacement", "90 deg", "--duration", "0.25 s", "--to",
                          "twincat-mc3", "-o", str(out_file), "--certificate",
                          str(cert_file)], capsys)
    assert code == 0, err
    assert "exact (the law the controller names)" in out
    points = read_back(out_file.read_text())
    assert [p["FunctionType"] for p in points] == [kind, kind]
    assert [p["MasterPosition"] for p in points] == [0.0, 0.25]
    assert [p["SlavePosition"] for p in points] == [0.0, 90.0]
    assert all(p["SlaveVelocity"] == 0.0 for p in points)
    law, h, T = make_law(spec), 90.0, 0.25
    x = np.concatenate([np.linspace(0.0, T, 100_001), T * np.array([1 / 8, 7 / 8, 0.5])])
    scale = [h, h / T * law.coefficients.C_v, h / T**2 * law.coefficients.C_a]
    for order in range(3):
        error = np.abs(rebuilt(points, x, order) - h / T**order * law.derivative(x / T, order))
        assert error.max() <= 1e-12 * scale[order], (order, error.max())
    record = json.loads(cert_file.read_text())
    assert record["function_type"] == kind
    for name, k in (("position", 0), ("velocity", 1), ("acceleration", 2)):
        assert record["errors"][name]["max"] <= 1e-12 * scale[k]
    assert record["expected_characteristics"]["peak_acceleration"] == pytest.approx(
        h / T**2 * law.coefficients.C_a, rel=1e-12)
    assert record["identification"]["confirmed"] is kind.startswith("Polynomial")


def test_the_cycle_dwells_are_linear_with_zero_slope(tmp_path: Path, capsys) -> None:
    out_file = tmp_path / "index.st"
    code, _, err = cam([str(EXAMPLES / "indexing-table.yaml"), "--to", "twincat-mc3",
                          "--cycle", "--master-range", "360", "-o", str(out_file)], capsys)
    assert code == 0, err
    points = read_back(out_file.read_text())
    kinds = [p["FunctionType"] for p in points]
    assert kinds[0] == "ModifiedSinusoid" and "Linear" in kinds
    assert points[0]["MasterPosition"] == 0.0 and points[-1]["MasterPosition"] == 360.0
    for a, b in itertools.pairwise(points):
        if a["FunctionType"] == "Linear":
            assert a["SlavePosition"] == b["SlavePosition"]
    # the move: the sized law over its share of the master range
    move_span = float(points[1]["MasterPosition"])  # type: ignore[arg-type]
    law = make_law("modified_sinusoidal")
    x = np.linspace(0.0, move_span, 10_001)
    error = np.abs(rebuilt(points, x, 0) - 90.0 * law.derivative(x / move_span, 0))
    assert error.max() <= 1e-12 * 90.0


@pytest.mark.parametrize("spec", ["trapezoidal(alpha=1/3)", "harmonic",
                                  "double_s(alpha=1/3, beta=1/4)",
                                  "polynomial(degree=9)"])
def test_a_law_twincat_does_not_name_is_refused(spec: str, tmp_path: Path, capsys) -> None:
    out_file = tmp_path / "x.st"
    code, _, err = cam([spec, "--displacement", "90 deg", "--duration", "0.25 s", "--to",
                        "twincat-mc3", "-o", str(out_file)], capsys)
    assert code == 2
    assert "not a law TwinCAT MC3 names" in err and "poly5" in err
    assert "Traceback" not in err and not out_file.exists()


def test_points_are_refused(tmp_path: Path, capsys) -> None:
    code, _, err = cam(["poly5", "--displacement", "90 deg", "--duration", "0.25 s", "--to",
                        "twincat-mc3", "--points", "5", "-o", str(tmp_path / "x.st")], capsys)
    assert code == 2 and "--points" in err
