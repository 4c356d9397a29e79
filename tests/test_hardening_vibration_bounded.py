"""Vibration and spectra in bounded memory and time (issue 32): a 1e6 s move on a 25 Hz
mode, high f T, many harmonics; refusals name the option and the limit at once."""

from __future__ import annotations

import math
import resource
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from sizer.input_limits import MAX_SPECTRUM_LINES, MAX_VIBRATION_POINTS
from sizer.laws import make_law
from sizer.vibration.response import residual_amplitude, tracking_error
from sizer.vibration.spectrum import numerical_spectrum, spectrum

ROOT = Path(__file__).resolve().parents[1]
GIB = 1 << 30


def _limited() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (2 * GIB, 2 * GIB))


HANG = 120.0
"""Seconds after which a run is a hang (subprocess.TimeoutExpired fails the test): far
above any run, so that a loaded machine never fails a test for being slow; the speed of
these runs is measured in benchmarks/README.md (issue 32), not asserted here."""


def run_limited(*args: str, timeout: float = HANG) -> subprocess.CompletedProcess[str]:
    """``sizer ARGS`` in a subprocess limited to 2 GiB of address space, a hang after
    ``timeout`` seconds."""
    return subprocess.run([sys.executable, "-m", "sizer", *args], cwd=ROOT, text=True,
                          capture_output=True, timeout=timeout, preexec_fn=_limited,
                          check=False)


@pytest.fixture(scope="module")
def long_design(tmp_path_factory: pytest.TempPathFactory) -> Path:
    text = (ROOT / "examples/indexing-table-vibration.yaml").read_text()
    text = text.replace("duration: minimize", "duration: 1e6 s").replace(
        "motors: catalogs/", f"motors: {ROOT}/examples/catalogs/")
    path = tmp_path_factory.mktemp("long") / "long.yaml"
    path.write_text(text)
    return path


@pytest.mark.parametrize("command", [["size"], ["vibration", "--points", "21"],
                                     ["segments"]])
def test_a_1e6_s_move_on_a_25_hz_mode_runs_in_2_gib(long_design: Path,
                                                     command: list[str]) -> None:
    # f_n T = 2.5e7: sampling it (16 points a period) took 24 GB before
    done = run_limited(command[0], str(long_design), *command[1:])
    assert done.returncode == 0, done.stderr
    assert "Traceback" not in done.stderr and "Warning" not in done.stderr


@pytest.mark.parametrize("fT", [2.5e7 + 0.5, 1e5 + 0.3, 1234.567])
def test_undamped_residual_is_the_spectrum_over_2_pi_f_T(fT: float) -> None:
    # sec. 7.3: A / h = |A_N(fT)| / (2 pi fT), cycloidal |A_N| = 2 pi |sinc(fT - 1) / (1 + fT)|
    closed = 2 * math.pi * abs(np.sinc(fT - 1.0) / (1.0 + fT)) / (2 * math.pi * fT)
    got = residual_amplitude("cycloidal", fT)
    assert got == pytest.approx(closed, rel=1e-6)


def test_damped_trapezoid_residual_far_and_near_agree_with_the_jumps() -> None:
    # trapezoid(alpha = 1/2) = constant acceleration: q_N'' = 4, -4 on the halves; the
    # exact w(1) = (4 / s) (e^s - 2 e^{s/2} + 1) (three steps); A / h = |w| / Omega_d
    delta = 0.02
    for fT in (700.3, 3.3e6 + 0.1):
        omega = 2 * math.pi * fT
        s = omega * complex(-delta, math.sqrt(1 - delta**2))
        w = 4.0 / s * (np.exp(s) - 2.0 * np.exp(s / 2) + 1.0)
        expected = abs(w) / (omega * math.sqrt(1 - delta**2))
        assert residual_amplitude("constant_acceleration", fT, delta) == pytest.approx(
            expected, rel=1e-8)


def test_tracking_error_of_constant_acceleration_from_its_two_steps() -> None:
    # undamped, q_N'' = 4 then -4: z = -(4 / W^2)(1 - cos W tau) to the middle (W = 2 pi
    # f T); after it z = 4 / W^2 + A cos(...), A = |(z_m - 4 / W^2, z'_m / W)|; with many
    # periods left the peak is max(8 / W^2, 4 / W^2 + A)
    for fT in (2.5e7 + 0.1, 1.0e5 + 0.3):
        W = 2 * math.pi * fT
        z_m = -4.0 / W**2 * (1.0 - math.cos(W / 2))
        v_m = -4.0 / W * math.sin(W / 2)
        A = math.hypot(z_m - 4.0 / W**2, v_m / W)
        expected = max(8.0 / W**2, 4.0 / W**2 + A)
        assert float(tracking_error("constant_acceleration", fT)) == pytest.approx(
            expected, rel=1e-6)


def test_tracking_error_of_the_cycloid_is_quasi_static_at_high_f_T() -> None:
    # q_N'' = 2 pi sin(2 pi tau) is C^0 with zero ends: z ~ -q_N'' / Omega^2, peak 2 pi /
    # Omega^2 (+ the residual, O(1 / Omega^3))
    fT = 3.0e7
    omega = 2 * math.pi * fT
    assert float(tracking_error("cycloidal", fT)) * omega**2 == pytest.approx(
        2 * math.pi, rel=1e-6)


def test_high_f_T_spectrum_matches_closed_forms() -> None:
    fT = np.linspace(1000.0, 1e5, 2001)
    for spec in ("cycloidal", "double_s(alpha=1/3, beta=1/4)", "gutman_1_3"):
        law = make_law(spec)
        exact = spectrum(law, fT)  # closed form
        numeric = numerical_spectrum(law, fT)
        scale = float(numerical_spectrum(law, np.array([0.5]))[0])
        assert np.max(np.abs(numeric - exact)) <= 1e-11 * scale


def test_many_harmonics_are_answered_in_2_gib() -> None:
    done = run_limited("spectrum", "cycloidal", "--max-ft", "1000", "--period", "20",
                       "--format", "csv")
    assert done.returncode == 0, done.stderr
    assert len(done.stdout.splitlines()) > 20_000


@pytest.mark.parametrize(("args", "field", "words"), [
    (["--max-ft", "1000", "--period", "1000"], "--max-ft", "MAX_SPECTRUM_LINES"),
    (["--max-ft", "1000", "--period", "1e308"], "--max-ft", "MAX_SPECTRUM_LINES"),
    (["--points", str(MAX_SPECTRUM_LINES + 1)], "--points", "MAX_SPECTRUM_LINES"),
    (["--displacement", "1e308", "--duration", "1e-308"], "--duration", "float range"),
    (["--displacement", "1", "--duration", "1e308", "--period", "1e308"], "--duration",
     "float range"),
])
def test_spectrum_refusals_are_immediate_and_located(args: list[str], field: str,
                                                     words: str) -> None:
    done = run_limited("spectrum", "cycloidal", *args)
    assert done.returncode == 2
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"error: {field}:") and words in lines[0]


def test_vibration_points_limit_is_named(long_design: Path) -> None:
    done = run_limited("vibration", str(long_design), "--points",
                       str(MAX_VIBRATION_POINTS + 1))
    assert done.returncode == 2
    assert "error: --points:" in done.stderr and "MAX_VIBRATION_POINTS" in done.stderr


@pytest.mark.parametrize("spec", ["poly5", "poly7", "cycloidal", "trapezoidal(alpha=1/3)"])
def test_the_spectrum_at_a_tiny_f_T_is_2_pi_f_T(spec: str) -> None:
    # |A_N(fT)| = |int q_N'' e^{-i 2 pi fT tau}| = 2 pi fT |int q_N'| (1 + O(fT)) for a
    # rest-to-rest law (by parts); scipy's spherical_jn gave nan at subnormal arguments
    # (found by the options fuzz: --max-ft 1e-320)
    law = make_law(spec)
    for fT in (1e-200, 1e-90):
        assert float(spectrum(law, np.array([fT]))[0]) == pytest.approx(2 * math.pi * fT,
                                                                          rel=1e-9, abs=0.0)
    tiny = float(spectrum(law, np.array([1e-320]))[0])  # subnormal: few significant bits
    assert tiny == pytest.approx(2 * math.pi * 1e-320, rel=1e-2, abs=0.0)
