"""``sizer cam`` of a design's cycle of segments (issue 37): the motor's torques re-sized on
the written file. Each move's law is the file's span of that move (``span: [x0, x1]``), at
the duration the sizing gave it; a move between boundary speeds takes its span at that
fixed duration when its end slopes are the move's speeds (v T/h).

The certificate's torques are checked against ``sizer size`` of a design written here with
those laws and durations (the same computation, to 1e-9), against the sized law's own
torques (poly5 and double S are exactly reproduced by a quintic Hermite table and by
polynomial segments: 1e-9), and against an independent computation: the XYVA file parsed
here, its quintic Hermite pieces solved here, the flying saw's torque written out by hand
(mass, friction, the cut force, a belt and a rack with their efficiencies in the
direction of the power flow, the rotor) and integrated by Gauss-Legendre rules exact for
its polynomial pieces.
"""

from __future__ import annotations

import itertools
import json
import math
from pathlib import Path

import numpy as np
import pytest
import yaml

from sizer.cli.app import run
from sizer.laws import make_law

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
SAW = EXAMPLES / "flying-saw.yaml"
MASS, FRICTION, CUT = 25.0, 30.0, 120.0  # kg, N, N (examples/flying-saw.yaml)
RATIO, RADIUS, ETA = 3.0, 0.030, 0.95  # belt 3:1, pinion radius, each stage's efficiency
J_MOTOR = 0.00123  # SGM7A-70A rotor inertia, kg m^2 (the bundled Yaskawa catalog)
K = RATIO / RADIUS  # motor rad per m of the carriage


def cam(args: list[str], capsys) -> tuple[int, str]:
    code = run(["cam", *args])
    out, err = capsys.readouterr()
    return code, out + err


def export(tmp_path: Path, capsys, target: str, law: str, name: str) -> dict:
    out_file, cert = tmp_path / name, tmp_path / f"{name}.json"
    code, text = cam([str(SAW), "--to", target, "--law", law, "-o", str(out_file),
                      "--certificate", str(cert)], capsys)
    record = json.loads(cert.read_text())
    real = record.get("single_precision_estimate", {"within_tolerance": True})
    assert code == (0 if real["within_tolerance"] else 1), text  # REAL data: exit 1
    assert record["torques"]["computed"], record["torques"]
    return record


@pytest.fixture(scope="module")
def xyva_poly5(tmp_path_factory) -> dict:
    """One XYVA export of the flying saw by poly5 (read by several tests)."""
    folder = tmp_path_factory.mktemp("xyva")
    cert = folder / "saw.json"
    assert run(["cam", str(SAW), "--to", "codesys-xyva", "--law", "poly5", "-o",
                str(folder / "saw.csv"), "--certificate", str(cert)]) == 0
    return json.loads(cert.read_text())


def written_design(record: dict, folder: Path) -> Path:
    """The flying saw with each move's law the file's span (the certificate's specs) and
    every move and dwell at its exported duration (the segment's span, master = time)."""
    design = yaml.safe_load(SAW.read_text())
    specs = record["torques"]["exported_specs"]
    segments = design["cycle"]["segments"]
    assert len(segments) == len(record["segments"]) == len(specs)
    for segment, exported, spec in zip(segments, record["segments"], specs, strict=True):
        kind, fields = next(iter(segment.items()))
        if kind == "move":
            fields["law"] = yaml.safe_load(spec)
            fields["duration"] = exported["span"]
        elif kind == "dwell":
            fields["duration"] = exported["span"]
        else:
            assert spec is None
    design.pop("laws")
    path = folder / "written.yaml"
    path.write_text(yaml.safe_dump(design))
    return path


def size_json(path: Path, motor: str, capsys) -> dict:
    capsys.readouterr()
    assert run(["size", str(path), "--format", "json"]) == 0
    results = json.loads(capsys.readouterr().out)["results"]
    return next(r for r in results if r["motor"] == motor)


@pytest.mark.parametrize("target", ["codesys-xyva", "siemens-tcpu"])
def test_certificate_equals_sizing_the_written_spans(tmp_path: Path, capsys,
                                                     target: str) -> None:
    record = export(tmp_path, capsys, target, "poly5", "saw.cam")
    torques = record["torques"]
    again = size_json(written_design(record, tmp_path), record["motor"], capsys)
    exported = torques["exported"]
    assert exported["peak_torque_Nm"] == pytest.approx(again["peak_torque"], rel=1e-9)
    assert exported["rms_torque_Nm"] == pytest.approx(again["rms_torque"], rel=1e-9)
    assert again["feasible"] == exported["feasible"]
    # poly5 is a quintic: the XYVA table and the segments reproduce it (errors ~1e-11 of
    # the stroke), so the torques are the sized law's to 1e-9
    law = torques["law"]
    assert exported["peak_torque_Nm"] == pytest.approx(law["peak_torque_Nm"], rel=1e-9)
    assert exported["rms_torque_Nm"] == pytest.approx(law["rms_torque_Nm"], rel=1e-9)
    assert torques["newly_failed"] == []
    # the run and the dwell keep no law; every move reads its span of the file
    kinds = [s["kind"] for s in record["segments"]]
    assert [spec is None for spec in torques["exported_specs"]] == \
        [k != "move" for k in kinds]


def test_double_s_table_keeps_the_law_torques(tmp_path: Path, capsys) -> None:
    """Double S pieces are cubics: its XYVA table is the law, its torques the law's."""
    record = export(tmp_path, capsys, "codesys-xyva", "double_s(alpha=1/3, beta=1/4)",
                    "ds.csv")
    law, exported = record["torques"]["law"], record["torques"]["exported"]
    assert exported["peak_torque_Nm"] == pytest.approx(law["peak_torque_Nm"], rel=1e-9)
    assert exported["rms_torque_Nm"] == pytest.approx(law["rms_torque_Nm"], rel=1e-9)


def test_coarse_table_of_a_trapezoid_is_sized_on_what_it_runs(tmp_path: Path,
                                                             capsys) -> None:
    """The trapezoid's acceleration steps; a 128-point XYVA table smooths them into
    larger peaks: the exported torque is not the law's, and the check it fails exits 1."""
    out_file, cert = tmp_path / "t.csv", tmp_path / "t.json"
    code, text = cam([str(SAW), "--to", "codesys-xyva", "--law", "trapezoidal(alpha=1/3)",
                      "-o", str(out_file), "--certificate", str(cert)], capsys)
    record = json.loads(cert.read_text())
    torques = record["torques"]
    assert code == 1 and "fails peak" in text
    assert torques["newly_failed"] == ["peak"]
    assert torques["exported"]["peak_torque_Nm"] > 1.1 * torques["law"]["peak_torque_Nm"]


# ----------------------------------------------------------------- independent
def hermite(y0, v0, a0, y1, v1, a1, w) -> np.ndarray:
    """Ascending coefficients of the quintic with these values at 0 and w."""
    d = y1 - y0
    return np.array([
        y0, v0, a0 / 2,
        (20 * d - (8 * v1 + 12 * v0) * w - (3 * a0 - a1) * w * w) / (2 * w ** 3),
        (-30 * d + (14 * v1 + 16 * v0) * w + (3 * a0 - 2 * a1) * w * w) / (2 * w ** 4),
        (12 * d - 6 * (v1 + v0) * w - (a0 - a1) * w * w) / (2 * w ** 5)])


def motor_torque(a: np.ndarray, v: np.ndarray, rest_sign: float, force: float) -> np.ndarray:
    """The motor's torque (signed) at the carriage's a and v (SI): along the motion
    (sign of v, ``rest_sign`` at rest) the force m a + friction + the external force,
    through the pinion and the belt, divided by both efficiencies where it drives the load,
    times them where the load drives back, plus the rotor's J K a."""
    s = np.where(v > 0, 1.0, np.where(v < 0, -1.0, rest_sign))
    along = s * a
    f = MASS * along + FRICTION + force
    shaft = f * RADIUS / RATIO * np.where(f >= 0.0, 1.0 / ETA ** 2, ETA ** 2)
    return s * (J_MOTOR * K * along + shaft)


def test_independent_torques_of_the_xyva_file(xyva_poly5: dict) -> None:
    record = xyva_poly5
    rows = np.loadtxt(record["file"], delimiter=",", comments="#", skiprows=3)
    x, y, v, a = (rows[:, i] for i in range(4))
    y, v, a = y / 1000.0, v / 1000.0, a / 1000.0  # mm -> m
    nodes, weights = np.polynomial.legendre.leggauss(8)  # exact to degree 15
    peak, square = 0.0, 0.0
    for seg in record["segments"]:
        lo, hi = seg["start"], seg["start"] + seg["span"]
        if seg["kind"] == "dwell":
            continue  # holds no load: the axis is horizontal, no force at rest
        force = CUT if seg["kind"] == "run" else 0.0
        rest_sign = 1.0 if seg["stroke"] >= 0 else -1.0
        for i in np.flatnonzero((x[:-1] >= lo - 1e-12) & (x[1:] <= hi + 1e-12)):
            w = x[i + 1] - x[i]
            c = hermite(y[i], v[i], a[i], y[i + 1], v[i + 1], a[i + 1], w)
            assert np.polynomial.polynomial.polyval(w, c) == pytest.approx(y[i + 1], abs=1e-12)
            vc = np.polynomial.polynomial.polyder(c)
            ac = np.polynomial.polynomial.polyder(c, 2)
            jc = np.polynomial.polynomial.polyder(c, 3)
            # extremes: the ends and where the jerk vanishes (torque rises with |a| on
            # either side of the efficiency's switch, where it is continuous)
            cand = [0.0, w] + [r.real for r in np.roots(jc[::-1])
                               if abs(r.imag) < 1e-12 and 0.0 < r.real < w]
            t = np.array(cand)
            tau = motor_torque(np.polynomial.polynomial.polyval(t, ac),
                               np.polynomial.polynomial.polyval(t, vc), rest_sign, force)
            peak = max(peak, float(np.max(np.abs(tau))))
            # the integral of tau^2, split where the force along the motion changes sign
            f_along = rest_sign * MASS * ac  # + FRICTION, v keeps the move's sign inside
            f_along[0] += FRICTION + force
            cuts = sorted({0.0, w, *[r.real for r in np.roots(f_along[::-1])
                                     if abs(r.imag) < 1e-12 and 0.0 < r.real < w]})
            for t0, t1 in itertools.pairwise(cuts):
                t = t0 + (t1 - t0) * (nodes + 1.0) / 2.0
                tau = motor_torque(np.polynomial.polynomial.polyval(t, ac),
                                   np.polynomial.polynomial.polyval(t, vc), rest_sign, force)
                square += (t1 - t0) / 2.0 * float(np.sum(weights * tau * tau))
    cycle_time = record["master"]["cycle_time_s"]
    exported = record["torques"]["exported"]
    assert exported["peak_torque_Nm"] == pytest.approx(peak, rel=1e-9)
    assert exported["rms_torque_Nm"] == pytest.approx(math.sqrt(square / cycle_time),
                                                      rel=1e-9)


# ----------------------------------------------------------------- the span law
def test_span_law_ends_and_slopes_against_the_file(xyva_poly5: dict) -> None:
    record = xyva_poly5
    rows = np.loadtxt(record["file"], delimiter=",", comments="#", skiprows=3)
    x, y, v = rows[:, 0], rows[:, 1], rows[:, 2]
    for seg, spec in zip(record["segments"], record["torques"]["exported_specs"],
                         strict=True):
        if spec is None:
            continue
        law = make_law(spec)
        i0 = int(np.argmin(abs(x - seg["start"])))
        i1 = int(np.argmin(abs(x - (seg["start"] + seg["span"]))))
        T, h = x[i1] - x[i0], y[i1] - y[i0]
        ends = law.derivative(np.array([0.0, 1.0]), 0)
        assert ends == pytest.approx([0.0, 1.0], abs=1e-12)
        slopes = [law.piece_derivative(0, 0.0, 1), law.piece_derivative(len(law.pieces) - 1,
                                                                       1.0, 1)]
        assert slopes == pytest.approx([v[i0] * T / h, v[i1] * T / h], abs=1e-12)
        # inside: the normalized law is the file's rows
        inside = (x[i0:i1 + 1] - x[i0]) / T
        assert law.derivative(inside, 0) == pytest.approx((y[i0:i1 + 1] - y[i0]) / h,
                                                          abs=1e-12)


def test_span_must_name_rows(xyva_poly5: dict) -> None:
    from sizer.errors import UserError

    file = json.dumps(record_file := xyva_poly5["file"])
    assert Path(record_file).exists()
    with pytest.raises(UserError, match="span") as error:
        make_law(f"{{kind: cam_table, file: {file}, interpolation: quintic_hermite, "
                 f"span: [0.0, 0.0123]}}")
    assert "nearest" in error.value.message


def test_mismatched_boundary_slope_is_a_located_error(xyva_poly5: dict, tmp_path: Path,
                                                      capsys) -> None:
    """The accelerate move's span at a duration 10 % off: its end slope is no longer
    v T/h, an error at the move's law with the numbers (exit 2)."""
    path = written_design(xyva_poly5, tmp_path)
    design = yaml.safe_load(path.read_text())
    move = design["cycle"]["segments"][0]["move"]
    move["duration"] = move["duration"] * 1.1
    path.write_text(yaml.safe_dump(design))
    capsys.readouterr()
    assert run(["size", str(path)]) == 2
    err = capsys.readouterr().err
    assert "cycle.segments[0].move.law" in err and "end slope" in err
    assert "v T/h" in err


def test_span_is_the_whole_tables_curve_restricted(tmp_path: Path) -> None:
    """A cubic spline span is the spline through ALL the rows (scipy's CubicSpline built
    here, not-a-knot: the table's ends move), restricted and normalized; a span starting
    inside a fitted spline's piece too (order 6 drops knots: re-expanded there)."""
    from scipy.interpolate import CubicSpline

    x = np.linspace(0.0, 1.0, 41)
    q = np.sin(3 * x) + x
    table = tmp_path / "sin.csv"
    table.write_text("t [s],q [m]\n" + "".join(f"{a!r},{b!r}\n" for a, b in zip(
        x.tolist(), q.tolist(), strict=True)))
    a, b = float(x[1]), float(x[30])
    t = np.linspace(0.0, 1.0, 1001)
    spline = CubicSpline(x, q)
    law = make_law(f"{{kind: cam_table, file: {json.dumps(str(table))}, interpolation: "
                   f"cubic_spline, span: [{a!r}, {b!r}]}}")
    h = spline(b) - spline(a)
    for k in range(3):
        expected = spline(a + t * (b - a), k) * (b - a) ** k / h - (spline(a) / h if k == 0
                                                                    else 0.0)
        assert law.derivative(t, k) == pytest.approx(expected, abs=1e-12 * np.max(
            np.abs(expected)))
    whole = make_law(f"{{kind: cam_table, file: {json.dumps(str(table))}, order: 6}}")
    fitted = make_law(f"{{kind: cam_table, file: {json.dumps(str(table))}, order: 6, "
                      f"span: [{a!r}, {b!r}]}}")
    curve = whole.curve
    assert a not in curve.x  # inside a piece of the fit
    h = curve(b) - curve(a)
    for k in range(3):
        expected = (curve(a + t * (b - a), k) - (curve(a) if k == 0 else 0.0)) \
            * (b - a) ** k / h
        assert fitted.derivative(t, k) == pytest.approx(expected, abs=1e-10 * np.max(
            np.abs(expected)))


def test_rest_is_decided_at_the_tables_ends_only(tmp_path: Path, capsys) -> None:
    """sizer's own cycloidal export read back (order 6): its ends are at rest by the
    table's criterion; a span keeps that decision at an end of the table, and is moving at
    an end inside it (the law's speed there, 1 - cos of the cycloid)."""
    capsys.readouterr()
    assert run(["law", "cycloidal", "--displacement", "90deg", "--duration", "0.25s",
                "--format", "csv"]) == 0
    table = tmp_path / "cyc.csv"
    table.write_text(capsys.readouterr().out)
    x = np.loadtxt(table, delimiter=",", skiprows=1)[:, 0]
    file = json.dumps(str(table))
    head = make_law(f"{{kind: cam_table, file: {file}, span: [0.0, {float(x[40])!r}]}}")
    tail = make_law(f"{{kind: cam_table, file: {file}, span: [{float(x[40])!r}, "
                    f"{float(x[-1])!r}]}}")
    assert head.report["rest_start"] == 1.0 and head.report["rest_end"] == 0.0
    assert tail.report["rest_start"] == 0.0 and tail.report["rest_end"] == 1.0
    tau = x[40] / x[-1]  # the cycloid's speed 1 - cos(2 pi tau), over the span's share
    q = tau - math.sin(2 * math.pi * tau) / (2 * math.pi)
    assert head.end_speeds[0] == 0.0 and tail.end_speeds[1] == 0.0
    assert head.end_speeds[1] == pytest.approx((1 - math.cos(2 * math.pi * tau)) * tau / q,
                                               rel=1e-6)
    assert tail.end_speeds[0] == pytest.approx(
        (1 - math.cos(2 * math.pi * tau)) * (1 - tau) / (1 - q), rel=1e-6)


def test_segment_span_names_segment_ends(tmp_path: Path) -> None:
    from sizer.errors import UserError

    text = ("# master_unit: s\n# slave_unit: mm\n"
            "Type;Reserve;X1;Y1;X2;Y2;A0;A1;A2;A3;A4;A5;A6;B0;B1;B2\n"
            "0;0;0.0;0.0;1.0;1.0;0;1;0;0;0;0;0;0;0;0\n"
            "0;0;1.0;1.0;2.0;3.0;-1;2;0;0;0;0;0;0;0;0\n")
    file = tmp_path / "seg.txt"
    file.write_text(text)
    law = make_law(f"{{kind: cam_segments, file: {json.dumps(str(file))}, span: [1.0, 2.0]}}")
    assert law.derivative(np.array([0.0, 0.5, 1.0]), 0) == pytest.approx([0.0, 0.5, 1.0])
    with pytest.raises(UserError, match="segment end") as error:
        make_law(f"{{kind: cam_segments, file: {json.dumps(str(file))}, span: [0.5, 2.0]}}")
    assert error.value.field == "span[0]"


def test_a_design_of_spans_exports_again(xyva_poly5: dict, tmp_path: Path, capsys) -> None:
    """The design read back from an export (each move its span of the file) is itself a
    cycle sizer cam exports: its spans are their own shapes at the fixed durations (the
    same segments, spans and travel)."""
    design = written_design(xyva_poly5, tmp_path)
    again = tmp_path / "again.csv"
    code, text = cam([str(design), "--to", "csv", "--motor", xyva_poly5["motor"], "-o",
                      str(again), "--certificate", str(tmp_path / "again.json")], capsys)
    assert code == 0, text
    record = json.loads((tmp_path / "again.json").read_text())
    assert [s["span"] for s in record["segments"]] == pytest.approx(
        [s["span"] for s in xyva_poly5["segments"]], rel=1e-12)
    assert record["stroke"] == pytest.approx(xyva_poly5["stroke"], rel=1e-12)
