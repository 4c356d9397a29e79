"""``sizer spectrum``: table, CSV, Markdown and JSON outputs against the book's closed forms,
the physical scaling, the harmonics of a repeated move, determinism, the plot file, and
bad input (exit code 2, one line naming the option)."""

from __future__ import annotations

import csv
import io
import json
import math
import struct
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from cli_run import assert_user_error, run_cli

PI = math.pi


def cycloidal_book(omega: np.ndarray) -> np.ndarray:
    """|A_N| = pi V'_N = 2 |sin(pi Omega)| / |1 - Omega^2| (sec. 7.3.1), 2 pi/2 at 1."""
    omega = np.asarray(omega, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        value = 2 * np.abs(np.sin(PI * omega)) / np.abs(1 - omega**2)
    return np.where(np.isclose(omega, 1.0), PI, value)


def trapezoid_book(omega: np.ndarray, alpha: float) -> np.ndarray:
    omega = np.asarray(omega, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        value = (2 / ((1 - alpha) * alpha * PI * omega)
                 * np.abs(np.sin((1 - alpha) * PI * omega) * np.sin(alpha * PI * omega)))
    return np.where(omega == 0.0, 0.0, value)


def read_csv(text: str) -> tuple[list[str], np.ndarray]:
    rows = list(csv.reader(io.StringIO(text)))
    return rows[0], np.array([[float(x) for x in row] for row in rows[1:]])


def test_csv_normalized() -> None:
    result = run_cli("spectrum", "cycloidal", "trapezoidal(alpha=1/3)", "--max-ft", "8",
                     "--points", "33", "--format", "csv")
    assert result.returncode == 0, result.stderr
    headers, data = read_csv(result.stdout)
    assert headers == ["fT", "|A_N| cycloidal", "|A_N| trapezoidal(alpha=1/3)"]
    np.testing.assert_allclose(data[:, 0], np.linspace(0, 8, 33))
    np.testing.assert_allclose(data[:, 1], cycloidal_book(data[:, 0]), rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(data[:, 2], trapezoid_book(data[:, 0], 1 / 3), rtol=1e-12,
                               atol=1e-14)


def test_book_scale_and_physical_units() -> None:
    """--scale book divides by pi; --displacement/--duration: f = fT/T [Hz], (h/T)|A_N|."""
    result = run_cli("spectrum", "cycloidal", "--max-ft", "4", "--points", "9", "--scale",
                     "book", "--displacement", "90 deg", "--duration", "0.2 s", "-f", "csv")
    assert result.returncode == 0, result.stderr
    headers, data = read_csv(result.stdout)
    assert headers == ["f [Hz]", "V cycloidal [rad/s]"]
    fT = np.linspace(0, 4, 9)
    np.testing.assert_allclose(data[:, 0], fT / 0.2)
    h, T = PI / 2, 0.2
    np.testing.assert_allclose(data[:, 1], h / T * cycloidal_book(fT) / PI, rtol=1e-12,
                               atol=1e-14)
    linear = run_cli("spectrum", "cycloidal", "--points", "3", "--displacement", "200 mm",
                     "--duration", "1 s", "-f", "csv")
    assert read_csv(linear.stdout)[0] == ["f [Hz]", "|A| cycloidal [m/s]"]


def test_velocity_and_jerk_orders() -> None:
    """--order 3 of the trapezoid: four jerk impulses of a = 1/(alpha (1 - alpha)) at 0,
    alpha, 1 - alpha, 1; --order 1 scaled: |V(0)| = h (the area under the velocity)."""
    result = run_cli("spectrum", "trapezoidal(alpha=1/3)", "--order", "3", "--max-ft", "4",
                     "--points", "9", "-f", "csv")
    headers, data = read_csv(result.stdout)
    assert headers == ["fT", "|J_N| trapezoidal(alpha=1/3)"]
    s = 2j * PI * data[:, 0]
    alpha, a = 1 / 3, 4.5
    impulses = a * np.abs(1 - np.exp(-s * alpha) - np.exp(-s * (1 - alpha)) + np.exp(-s))
    np.testing.assert_allclose(data[:, 1], impulses, rtol=1e-10, atol=1e-12)
    velocity = run_cli("spectrum", "cycloidal", "--order", "1", "--points", "2",
                       "--displacement", "2 rad", "--duration", "0.5 s", "-f", "csv")
    headers, data = read_csv(velocity.stdout)
    assert headers == ["f [Hz]", "|V| cycloidal [rad]"]
    assert data[0, 1] == pytest.approx(2.0, rel=1e-14)


def test_json_and_table_and_md() -> None:
    result = run_cli("spectrum", "cycloidal", "modified_sinusoidal", "--max-ft", "3",
                     "--points", "7", "-f", "json")
    assert result.returncode == 0, result.stderr
    document = json.loads(result.stdout)
    assert document["kind"] == "spectrum" and document["order"] == 2
    assert document["laws"] == ["cycloidal", "modified_sinusoidal"]
    assert document["closed_form"] == [True, False]  # no closed form: the transform
    np.testing.assert_allclose(document["values"][0], cycloidal_book(document["frequency"]),
                               rtol=1e-12, atol=1e-14)
    table = run_cli("spectrum", "cycloidal", "--max-ft", "3", "--points", "7")
    assert table.returncode == 0
    lines = table.stdout.splitlines()
    assert lines[0].split() == ["fT", "|A_N|", "cycloidal"]
    assert lines[2 + 2].split() == ["1", "3.1416"]  # fT = 1: pi
    assert lines[2 + 4].split() == ["2", "0"]  # a zero of the cycloidal spectrum
    md = run_cli("spectrum", "cycloidal", "--points", "3", "-f", "md")
    assert md.stdout.startswith("|") and "cycloidal" in md.stdout


def test_harmonics() -> None:
    """--period 1: the book's repetition; the cycloidal law has only v_1 = 2 pi (phase
    -pi/2: 2 pi sin(2 pi t)); Gutman 1-3 has v_1 and v_3; a dwell (T_c = 2 T) puts the
    harmonics at fT = k/2, where they sample 2 (T/T_c) |A_N|."""
    result = run_cli("spectrum", "cycloidal", "gutman_1_3", "--period", "1", "--max-ft",
                     "6", "-f", "csv")
    assert result.returncode == 0, result.stderr
    headers, data = read_csv(result.stdout)
    assert headers == ["k", "fT", "v_Nk cycloidal", "phi cycloidal [rad]",
                       "v_Nk gutman_1_3", "phi gutman_1_3 [rad]"]
    assert list(data[:, 0]) == [1, 2, 3, 4, 5, 6]
    assert data[0, 2] == pytest.approx(2 * PI) and data[0, 3] == pytest.approx(-PI / 2)
    assert np.all(data[1:, 2] < 1e-12)
    # Gutman 1-3: q_N'' = 2 pi (15/16) sin(2 pi tau) + 6 pi (1/16) sin(6 pi tau)
    np.testing.assert_allclose(data[[0, 2], 4], [2 * PI * 15 / 16, 6 * PI / 16], rtol=1e-12)
    assert np.all(data[[1, 3, 4, 5], 4] < 1e-12)
    dwell = run_cli("spectrum", "trapezoidal(alpha=1/3)", "--period", "2", "--max-ft", "3",
                    "-f", "json")
    document = json.loads(dwell.stdout)
    assert document["kind"] == "harmonics" and document["k"] == [1, 2, 3, 4, 5, 6]
    fT = np.array(document["frequency"])
    np.testing.assert_allclose(fT, np.arange(1, 7) / 2)
    np.testing.assert_allclose(document["values"][0], 2 / 2 * trapezoid_book(fT, 1 / 3),
                               rtol=1e-10, atol=1e-12)


def test_harmonics_with_return_and_units() -> None:
    """Rise, dwell, return at T_c/2: even harmonics vanish, odd ones double; in physical
    units v_k = (h/T^2) v_Nk at f = k/T_c."""
    result = run_cli("spectrum", "cycloidal", "--period", "0.8 s", "--return",
                     "--displacement", "2 rad", "--duration", "0.2 s", "--max-ft", "1",
                     "-f", "csv")
    assert result.returncode == 0, result.stderr
    headers, data = read_csv(result.stdout)
    assert headers[:3] == ["k", "f [Hz]", "v_k cycloidal [rad/s^2]"]
    k = data[:, 0]
    assert list(k) == [1, 2, 3, 4]
    np.testing.assert_allclose(data[:, 1], k / 0.8)
    fT = k * 0.2 / 0.8
    expected = np.where(k % 2 == 1, 2.0, 0.0) * 2 * (0.2 / 0.8) * cycloidal_book(fT)
    np.testing.assert_allclose(data[:, 2], 2.0 / 0.2**2 * expected, rtol=1e-10, atol=1e-9)


def test_deterministic_and_output_file(tmp_path: Path) -> None:
    args = ("spectrum", "elliptic(n=2)", "poly5", "--max-ft", "5", "--points", "51",
            "-f", "csv")
    first, second = run_cli(*args), run_cli(*args)
    assert first.returncode == 0 and first.stdout == second.stdout
    out = tmp_path / "s.csv"
    written = run_cli(*args, "-o", str(out))
    assert written.returncode == 0 and written.stdout == ""
    assert out.read_text() == first.stdout


def test_plot_files(tmp_path: Path) -> None:
    png = tmp_path / "spectra.png"
    result = run_cli("spectrum", "cycloidal", "poly5", "--points", "101", "--plot", str(png),
                     "--size", "4x3", "--dpi", "50", "-f", "csv")
    assert result.returncode == 0, result.stderr
    data = png.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    assert struct.unpack(">II", data[16:24]) == (200, 150)
    assert result.stdout.startswith("fT,")  # the table is still printed
    svg = tmp_path / "harmonics.svg"
    again = run_cli("spectrum", "cycloidal", "poly5", "--period", "1.5", "--plot", str(svg))
    assert again.returncode == 0, again.stderr
    root = ET.fromstring(svg.read_text())
    ids = [e.get("id", "") for e in root.iter()]
    assert sum(i.startswith("harmonic") for i in ids) == 2  # one stem set per law
    assert sum(i.startswith("envelope") for i in ids) == 2
    first = svg.read_bytes()
    run_cli("spectrum", "cycloidal", "poly5", "--period", "1.5", "--plot", str(svg))
    assert svg.read_bytes() == first


@pytest.mark.parametrize(("args", "fragments"), [
    (("nosuch",), ("SPEC", "unknown law")),
    (("trapezoidal(alpha=2)",), ("SPEC", "alpha")),
    (("cycloidal", "--max-ft", "0"), ("--max-ft",)),
    (("cycloidal", "--max-ft", "nan"), ("--max-ft",)),
    (("cycloidal", "--points", "1"), ("--points",)),
    (("cycloidal", "--points", "100000", "--max-ft", "100"), ("--points",)),
    (("cycloidal", "--order", "4"), ("--order",)),
    (("cycloidal", "--period", "0.5"), ("--period", "at least")),
    (("cycloidal", "--period", "1 s"), ("--period", "bare number")),
    (("cycloidal", "--period", "1.5", "--return"), ("--period", "twice")),
    (("cycloidal", "--return"), ("--return", "--period")),
    (("cycloidal", "--period", "1", "--order", "3"), ("--order",)),
    (("cycloidal", "--period", "2", "--max-ft", "0.1"), ("--max-ft", "no harmonic")),
    (("cycloidal", "--duration", "1 s"), ("--displacement",)),
    (("cycloidal", "--displacement", "1", "--duration", "0"), ("--duration",)),
    (("cycloidal", "--displacement", "3 kg", "--duration", "1"), ("--displacement",)),
    (("cycloidal", "--scale", "foo"), ("--scale",)),
    (("cycloidal", "--plot", "x.txt"), ("--plot", "*.png")),
    (("cycloidal", "--size", "0x3", "--plot", "x.png"), ("--size",)),
])
def test_bad_input(args: tuple[str, ...], fragments: tuple[str, ...]) -> None:
    assert_user_error(run_cli("spectrum", *args), *fragments)


def test_plot_and_output_the_same_file(tmp_path: Path) -> None:
    target = tmp_path / "a.png"
    assert_user_error(run_cli("spectrum", "cycloidal", "--plot", str(target), "-o",
                              str(target)), "--plot")
    assert not target.exists()
