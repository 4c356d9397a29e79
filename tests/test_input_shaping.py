"""Input shaping (book sec. 7.4.2): the shapers, the shaped law, its residual vibration.

Reference numbers: the book's Example 7.4 (omega_n = 10 rad/s, delta = 0.1), the closed
forms of the shapers (K = exp(-delta pi / sqrt(1 - delta^2))), the undamped sensitivity
curves |cos(pi r / 2)|^n of ZV, ZVD, ZVDD, and independent computations in this file:
the ODE of the elastic load z'' + 2 delta w z' + w^2 z = -y'' (eq. 7.2) by
scipy.integrate.solve_ivp, the convolution sum_i A_i q(t - t_i) evaluated densely from
the base law, and integrals by scipy.integrate.quad.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from sizer.errors import UserError
from sizer.laws.base import MotionLaw
from sizer.laws.data_spec import canonical_data_spec
from sizer.laws.pieces import Piece
from sizer.laws.registry import make_law
from sizer.vibration.elastic_load import ElasticLoad
from sizer.vibration.shaped_law import ShapedLaw, shaped_for_duration
from sizer.vibration.shapers import (
    SHAPER_KINDS,
    Shaper,
    make_shaper,
    residual_vibration,
    shaper_length,
)
from sizer.vibration.transform import law_transform
from tests.cli_run import assert_user_error, run_cli

EXAMPLE_7_4 = ElasticLoad(10.0 / (2.0 * math.pi), 0.1)
"""omega_n = 10 rad/s, delta = 0.1 (m = 1 kg, d = 2 Ns/m, k = 100 N/m)."""


def kappa(delta: float) -> float:
    return math.exp(-delta * math.pi / math.sqrt(1.0 - delta**2))


def book_z(times: np.ndarray, amplitudes: np.ndarray, w: float, delta: float) -> float:
    """The book's Z(omega_n, delta) of sec. 7.4.2, written out here."""
    wd = w * math.sqrt(1.0 - delta**2)
    grow = amplitudes * np.exp(delta * w * times)
    c, s = np.sum(grow * np.cos(wd * times)), np.sum(grow * np.sin(wd * times))
    return float(math.exp(-delta * w * times[-1]) * math.hypot(c, s))


# ------------------------------------------------------------------ shapers
@pytest.mark.parametrize(("kind", "times", "amplitudes"), [
    ("zv", [0, 0.3157], [0.5783, 0.4217]),
    ("zvd", [0, 0.3157, 0.6315], [0.3344, 0.4877, 0.1778]),
    ("zvdd", [0, 0.3157, 0.6315, 0.9472], [0.1934, 0.4231, 0.3085, 0.0750]),
])
def test_example_7_4_shapers(kind: str, times: list[float], amplitudes: list[float]) -> None:
    """The impulses printed in Example 7.4 (four decimals)."""
    shaper = make_shaper(kind, EXAMPLE_7_4)
    assert np.allclose(shaper.times, times, rtol=0, atol=5.1e-5)
    assert np.allclose(shaper.amplitudes, amplitudes, rtol=0, atol=5.1e-5)
    assert math.fsum(shaper.amplitudes) == pytest.approx(1.0, abs=1e-15)


def test_zvd_digital_zeros_cancel_the_poles() -> None:
    """Example 7.4: G_ZVD(z) = s0 + s1/z + s2/z^2 has the double zero z = -0.7292."""
    shaper = make_shaper("zvd", EXAMPLE_7_4)
    zeros = np.roots(shaper.amplitudes)
    assert np.allclose(zeros, [-0.7292, -0.7292], atol=5e-5)
    assert np.allclose(zeros, -kappa(0.1), atol=1e-7)


@pytest.mark.parametrize("delta", [0.0, 0.05, 0.1, 0.3])
@pytest.mark.parametrize("kind", ["zv", "zvd", "zvdd"])
def test_zv_family_closed_forms(kind: str, delta: float) -> None:
    """n + 1 impulses at i T_0 / 2, amplitudes C(n, i) K^i / (1 + K)^n; Z = 0 at the design
    frequency, and for ZVD/ZVDD dZ/domega = 0 there too."""
    n = {"zv": 1, "zvd": 2, "zvdd": 3}[kind]
    load = ElasticLoad(3.0, delta)
    period = 2.0 * math.pi / (load.omega_n * math.sqrt(1.0 - delta**2))
    k = kappa(delta)
    shaper = make_shaper(kind, load)
    assert np.allclose(shaper.times, [i * period / 2 for i in range(n + 1)], rtol=1e-15)
    expected = [math.comb(n, i) * k**i / (1 + k) ** n for i in range(n + 1)]
    assert np.allclose(shaper.amplitudes, expected, rtol=1e-14)
    t, a = np.asarray(shaper.times), np.asarray(shaper.amplitudes)
    w = load.omega_n
    assert book_z(t, a, w, delta) < 1e-15
    assert float(residual_vibration(shaper, w, delta)) < 1e-15
    eps = 1e-4  # Z(w (1 +- eps)) / eps: about pi/2 at a simple zero, ~eps at a double one
    for side in (-1.0, 1.0):
        growth = book_z(t, a, w * (1 + side * eps), delta) / eps
        assert (growth < 1e-3) if n >= 2 else (growth > 0.5)


@pytest.mark.parametrize(("kind", "n"), [("zv", 1), ("zvd", 2), ("zvdd", 3)])
def test_undamped_sensitivity_curves(kind: str, n: int) -> None:
    """Fig. 7.46: for delta = 0, Z(r omega_n) = |cos(pi r / 2)|^n."""
    load = ElasticLoad(2.0, 0.0)
    ratios = np.linspace(0.2, 2.0, 181)
    z = residual_vibration(make_shaper(kind, load), ratios * load.omega_n, 0.0)
    assert np.allclose(z, np.abs(np.cos(np.pi * ratios / 2)) ** n, rtol=0, atol=1e-14)


@pytest.mark.parametrize("delta", [0.0, 0.1, 0.2])
def test_residual_vibration_is_the_books_z(delta: float) -> None:
    load = ElasticLoad(1.5, delta)
    for kind in SHAPER_KINDS:
        if kind == "ei" and delta > 0:
            continue
        shaper = make_shaper(kind, load)
        t, a = np.asarray(shaper.times), np.asarray(shaper.amplitudes)
        for w in load.omega_n * np.array([0.5, 0.9, 1.0, 1.3, 2.0]):
            assert float(residual_vibration(shaper, w, delta)) == pytest.approx(
                book_z(t, a, w, delta), rel=1e-12, abs=1e-15)


@pytest.mark.parametrize("limit", [0.0, 0.05, 0.1])
def test_one_hump_ei_undamped(limit: float) -> None:
    """(1 + z)/4, (1 - z)/2, (1 + z)/4 at 0, T_0/2, T_0: Z = z at the design frequency and
    zero where cos(omega T_0 / 2) = -(1 - z)/(1 + z), one frequency below, one above."""
    load = ElasticLoad(4.0, 0.0)
    shaper = make_shaper("ei", load, vibration_limit=limit)
    period = 1.0 / 4.0
    assert np.allclose(shaper.times, [0, period / 2, period], rtol=1e-15)
    assert np.allclose(shaper.amplitudes, [(1 + limit) / 4, (1 - limit) / 2, (1 + limit) / 4],
                       rtol=1e-15)
    w = load.omega_n
    assert float(residual_vibration(shaper, w, 0.0)) == pytest.approx(limit, abs=1e-15)
    x = math.acos(-(1 - limit) / (1 + limit))  # omega T_0 / 2 at the zeros: pi -+ (pi - x)
    for half_phase in (x, 2 * math.pi - x):
        zero = half_phase / math.pi * w
        assert float(residual_vibration(shaper, zero, 0.0)) < 1e-15
    between = np.linspace(x, 2 * math.pi - x, 201) / math.pi * w
    assert np.max(residual_vibration(shaper, between, 0.0)) <= limit + 1e-15


@pytest.mark.parametrize("delta", [0.0, 0.1, 0.2])
@pytest.mark.parametrize(("kind", "impulses"), [("ei2", 4), ("ei3", 5)])
def test_fitted_multi_hump_ei(kind: str, impulses: int, delta: float) -> None:
    """The book's cubic fits in delta (z = 5 %): first impulse times against the printed
    polynomials, and a sensitivity curve held near z = 5 % over a wide notch
    (Fig. 7.52: from about -30 % to +30 % of the design frequency)."""
    load = ElasticLoad(1.0, delta)
    shaper = make_shaper(kind, load)
    assert len(shaper.times) == impulses
    period = 1.0 / math.sqrt(1 - delta**2)
    fits = {"ei2": ((0.4989, 0.1627, -0.5426, 6.1618), (0.1605, 0.7669, 2.2656, -1.2275)),
            "ei3": ((0.4997, 0.2383, 0.4455, 12.4720), (0.1127, 0.7663, 3.2916, -1.4438))}
    t1, s0 = (sum(c * delta**k for k, c in enumerate(fit)) for fit in fits[kind])
    assert shaper.times[1] == pytest.approx(t1 * period, rel=1e-12)
    # amplitudes divided by their sum (1 within 3e-4)
    assert shaper.amplitudes[0] == pytest.approx(s0, abs=4e-4)
    ratios = np.linspace(0.7, 1.3, 601)
    z = residual_vibration(shaper, ratios * load.omega_n, delta)
    assert np.max(z) < 0.055
    zv = residual_vibration(make_shaper("zv", load), ratios * load.omega_n, delta)
    assert np.max(zv) > 0.3


# ----------------------------------------------------------- residual vibration
def residual_by_ode(law: MotionLaw, duration: float, w: float, delta: float) -> float:
    """Amplitude of the free vibration left after a move of unit displacement over
    ``duration``, from solve_ivp of z'' + 2 delta w z' + w^2 z = -y''(t) (eq. 7.2), one
    solve per piece of the law (its acceleration read on the piece's own side)."""
    from scipy.integrate import solve_ivp

    wd = w * math.sqrt(1 - delta**2)
    state = np.zeros(2)
    for piece in law.pieces:
        def rhs(t: float, x: np.ndarray, piece: Piece = piece) -> list[float]:
            tau = piece.clamp(np.array([t / duration]))
            a = float(piece.evaluate(tau, 2)[0]) / duration**2
            return [x[1], -a - 2 * delta * w * x[1] - w * w * x[0]]

        solution = solve_ivp(rhs, (piece.start * duration, piece.end * duration), state,
                             method="DOP853", rtol=1e-13, atol=1e-16)
        state = solution.y[:, -1]
    z, v = state
    return math.hypot(z, (v + delta * w * z) / wd)


def residual_by_transform(law: MotionLaw, duration: float, w: float, delta: float) -> float:
    """The same amplitude in closed form: for t >= T, z(t) = -Im(e^(lambda t) I) / w_d with
    lambda = -delta w + i w_d and I = int_0^T y''(s) e^(-lambda s) ds = F(lambda T) / T
    (F the transform of q_N'', unit displacement): amplitude e^(-delta w T) |F| / (w_d T)."""
    wd = w * math.sqrt(1 - delta**2)
    lam = complex(-delta * w, wd)
    f = complex(law_transform(law, lam * duration)[()])
    return math.exp(-delta * w * duration) * abs(f) / (wd * duration)


@pytest.mark.parametrize("delta", [0.0, 0.05])
@pytest.mark.parametrize("base_spec", ["cycloidal", "trapezoidal(alpha=1/3)"])
def test_zv_leaves_no_residual_vibration(base_spec: str, delta: float) -> None:
    """A ZV-shaped move leaves no residual vibration at the design frequency (1e-9 of the
    unit displacement) where the base move alone leaves some; the move grows by T_0/2."""
    base = make_law(base_spec)
    load = ElasticLoad(2.7, delta)  # f T = 2.7: far from a zero of either law's spectrum
    law, total = shaped_for_duration(base, "zv", load, 1.0, keep="base")
    half_period = math.pi / (load.omega_n * math.sqrt(1 - delta**2))
    assert total - 1.0 == pytest.approx(half_period, rel=1e-13)
    w = load.omega_n
    unshaped = residual_by_ode(base, 1.0, w, delta)
    assert unshaped > 1e-3
    assert residual_by_transform(base, 1.0, w, delta) == pytest.approx(unshaped, rel=1e-9)
    assert residual_by_ode(law, total, w, delta) < 1e-9
    assert residual_by_transform(law, total, w, delta) < 1e-12


@pytest.mark.parametrize("delta", [0.0, 0.05])
def test_zv_residual_at_a_fixed_total_duration(delta: float) -> None:
    """Keeping the total duration: the base gets T - T_0/2, the residual is still null."""
    load = ElasticLoad(3.1, delta)
    law, total = shaped_for_duration(make_law("cycloidal"), "zv", load, 0.8, keep="total")
    assert total == 0.8
    assert law.base_fraction * total == pytest.approx(0.8 - load.damped_period / 2, rel=1e-13)
    assert residual_by_ode(law, total, load.omega_n, delta) < 1e-9


@pytest.mark.parametrize(("kind", "periods"), [("zv", 0.5), ("zvd", 1.0), ("zvdd", 1.5),
                                                ("ei", 1.0)])
def test_duration_grows_by_the_shaper_length(kind: str, periods: float) -> None:
    load = ElasticLoad(5.0, 0.0 if kind == "ei" else 0.08)
    expected = periods * 2 * math.pi / (load.omega_n * math.sqrt(1 - load.damping_ratio**2))
    assert shaper_length(kind, load) == pytest.approx(expected, rel=1e-14)
    _, total = shaped_for_duration(make_law("poly5"), kind, load, 0.6, keep="base")
    assert total == pytest.approx(0.6 + expected, rel=1e-14)


@pytest.mark.parametrize("delta", [0.0, 0.05])
def test_zvd_is_robust_to_a_frequency_error(delta: float) -> None:
    """Over +-10 % of the design frequency the ZVD-shaped move leaves a residual below 3 %
    of the unshaped move's, and less than the ZV-shaped one everywhere off the design
    frequency; the ratio to the base's residual is the book's Z (the sensitivity curve)."""
    load = ElasticLoad(2.7, delta)
    base = make_law("cycloidal")
    shaped = {kind: shaped_for_duration(base, kind, load, 1.0, keep="base")
              for kind in ("zv", "zvd")}
    ratios = {kind: [] for kind in shaped}
    for r in np.linspace(0.9, 1.1, 21):
        w = r * load.omega_n
        unshaped = residual_by_transform(base, 1.0, w, delta)
        for kind, (law, total) in shaped.items():
            ratio = residual_by_transform(law, total, w, delta) / unshaped
            shaper = make_shaper(kind, load)
            z = book_z(np.asarray(shaper.times), np.asarray(shaper.amplitudes), w, delta)
            assert ratio == pytest.approx(z, rel=1e-7, abs=1e-12)
            ratios[kind].append(ratio)
    zv, zvd = np.array(ratios["zv"]), np.array(ratios["zvd"])
    assert np.max(zvd) < 0.03
    assert np.max(zv) > 0.12
    off = np.abs(np.linspace(0.9, 1.1, 21) - 1.0) > 1e-9
    assert np.all(zvd[off] < zv[off])
    # at the end points, one check by the ODE
    w = 1.1 * load.omega_n
    law, total = shaped["zvd"]
    assert residual_by_ode(law, total, w, delta) / residual_by_ode(base, 1.0, w, delta) < 0.03


def test_cascade_of_two_shapers_cancels_two_modes() -> None:
    """Example 7.6 in spirit: a law shaped for one mode, then for another, written as a
    nested mapping, leaves neither mode vibrating."""
    first, second = ElasticLoad(2.0, 0.1), ElasticLoad(3.2, 0.0)
    total = 1.5
    inner_duration = total - second.damped_period / 2
    text = (f"{{kind: shaped, shaper: zv, f_T: {second.natural_frequency * total!r}, "
            f"law: {{kind: shaped, law: cycloidal, shaper: zvdd, damping_ratio: 0.1, "
            f"f_T: {first.natural_frequency * inner_duration!r}}}}}")
    law = make_law(text)
    for mode in (first, second):
        before = residual_by_transform(make_law("cycloidal"), 1.0, mode.omega_n,
                                       mode.damping_ratio)
        after = residual_by_transform(law, total, mode.omega_n, mode.damping_ratio)
        assert before > 1e-3
        assert after < 1e-12


# --------------------------------------------------------------- the law
def dense_convolution(base: MotionLaw, shaper_kind: str, f_T: float, delta: float,
                      tau: np.ndarray, order: int) -> np.ndarray:
    """q_s^(k)(tau) = sum A_i r^-k q_N^(k)((tau - tau_i)/r) from the book's formulas."""
    k = kappa(delta)
    n = {"zv": 1, "zvd": 2}[shaper_kind]
    amplitudes = [math.comb(n, i) * k**i / (1 + k) ** n for i in range(n + 1)]
    half = 0.5 / (f_T * math.sqrt(1 - delta**2))  # T_0 / 2 over T_s
    r = 1 - n * half
    out = np.zeros_like(tau)
    for i, a in enumerate(amplitudes):
        out += a * r**-order * base.derivative((tau - i * half) / r, order)
    return out


@pytest.mark.parametrize(("base_spec", "kind", "f_T", "delta"), [
    ("cycloidal", "zv", 4.0, 0.02),
    ("trapezoidal(alpha=1/3)", "zvd", 3.0, 0.05),
    ("poly5", "zv", 1.7, 0.0),
    ("modified_sinusoidal", "zvd", 6.5, 0.1),
])
def test_coefficients_match_a_dense_convolution(base_spec: str, kind: str, f_T: float,
                                                 delta: float) -> None:
    from scipy.integrate import quad

    base = make_law(base_spec)
    law = ShapedLaw(base, kind, f_T, delta)
    n = {"zv": 1, "zvd": 2}[kind]
    half = 0.5 / (f_T * math.sqrt(1 - delta**2))
    kinks = np.concatenate([i * half + (1 - n * half) * base.breakpoints for i in range(n + 1)])
    tau = np.unique(np.concatenate([np.linspace(0.0, 1.0, 400_001), kinks]))
    # off the kinks (where one side or the other is a rounding away); the same points for
    # every order, and the dense curves of orders 1 and 2 are v and a below
    gap = np.min(np.abs(tau[:, None] - np.unique(kinks)[None, :]), axis=1)
    inside = gap > 1e-9
    denses = []
    for order in range(4):
        dense = dense_convolution(base, kind, f_T, delta, tau, order)
        denses.append(dense)
        assert np.allclose(law.derivative(tau[inside], order), dense[inside],
                           rtol=1e-12, atol=1e-11 * max(1.0, np.max(np.abs(dense))))
    v, a = denses[1], denses[2]
    edges = list(np.unique(kinks))
    a2 = sum(quad(lambda x: dense_convolution(base, kind, f_T, delta, np.array([x]), 2)[0]
                  ** 2, lo, hi, epsabs=1e-14, epsrel=1e-13)[0]
             for lo, hi in itertools.pairwise(edges))
    v2 = sum(quad(lambda x: dense_convolution(base, kind, f_T, delta, np.array([x]), 1)[0]
                  ** 2, lo, hi, epsabs=1e-14, epsrel=1e-13)[0]
             for lo, hi in itertools.pairwise(edges))
    for candidate in (law, make_law(law.spec)):
        c = candidate.coefficients
        assert c.C_v == pytest.approx(np.max(np.abs(v)), rel=1e-9)
        assert c.C_a == pytest.approx(np.max(np.abs(a)), rel=1e-8)
        assert c.C_a >= np.max(np.abs(a))  # the exact peak is at least any sample
        assert c.C_v_rms == pytest.approx(math.sqrt(v2), rel=1e-10)
        assert c.C_a_rms == pytest.approx(math.sqrt(a2), rel=1e-10)
    assert law.position(np.array([0.0, 1.0])).tolist() == pytest.approx([0.0, 1.0], abs=1e-15)


@pytest.mark.parametrize("base_spec", ["cycloidal", "trapezoidal(alpha=1/3)",
                                       "double_s(alpha=1/3, beta=1/4)", "poly5", "harmonic"])
def test_pieces_keep_the_base_degree_and_continuity(base_spec: str) -> None:
    base = make_law(base_spec)
    law = ShapedLaw(base, "zvd", 3.3, 0.05)
    assert law.continuity == base.continuity
    assert make_law(law.spec).continuity == base.continuity  # measured on the data kind
    base_degrees = {p.degree for p in base.pieces}
    if None in base_degrees:
        assert all(p.degree is None for p in law.pieces)
    else:
        assert {p.degree for p in law.pieces} <= base_degrees | {0}
    # the pieces are cut at every shifted breakpoint: 3 impulses x base breakpoints
    r, half = law.base_fraction, (1 - law.base_fraction) / 2
    shifted = np.unique(np.concatenate([i * half + r * base.breakpoints for i in range(3)]))
    assert np.allclose(law.breakpoints, shifted, atol=1e-13)


@pytest.mark.parametrize("base_spec", ["cycloidal", "trapezoidal(alpha=1/3)", "poly7",
                                       "modified_trapezoidal"])
@pytest.mark.parametrize("kind", ["zv", "zvd", "zvdd", "ei2", "ei3"])
def test_peaks_at_the_same_base_duration_are_at_most_the_base(base_spec: str,
                                                              kind: str) -> None:
    """Positive amplitudes summing to 1: y^(k) is a convex combination of q^(k), so the
    peak speed and acceleration (inertia torque) of the shaped move over T_s = T_b + t_n
    are at most the base's over T_b: C_s / T_s^k <= C_b / T_b^k."""
    base = make_law(base_spec)
    load = ElasticLoad(1.8, 0.1)
    law, total = shaped_for_duration(base, kind, load, 1.0, keep="base")
    shaped, plain = law.coefficients, base.coefficients
    assert shaped.C_v / total <= plain.C_v * (1 + 1e-12)
    assert shaped.C_a / total**2 <= plain.C_a * (1 + 1e-12)
    assert shaped.C_a_rms / total**2 <= plain.C_a_rms * (1 + 1e-12)
    # keeping the total duration instead, the base gets r = 1 - t_n / T: C_s <= C_b / r^2
    compressed, _ = shaped_for_duration(base, kind, load, 2.0, keep="total")
    r = 1 - shaper_length(kind, load) / 2.0
    assert compressed.base_fraction == pytest.approx(r, rel=1e-13)
    assert compressed.coefficients.C_a * r**2 <= plain.C_a * (1 + 1e-12)


# ------------------------------------------------------------------ spec
def test_spec_round_trip() -> None:
    law = ShapedLaw(make_law("cycloidal"), "zv", 4.0, 0.02)
    assert law.spec == "{kind: shaped, damping_ratio: 0.02, f_T: 4, law: cycloidal, shaper: zv}"
    again = make_law(law.spec)
    assert again == law and again.spec == law.spec
    assert canonical_data_spec(law.spec) == law.spec
    written = "{ shaper: zv,  law: cycloidal, f_T: 4.0, damping_ratio: 0.02, kind: shaped }"
    assert make_law(written) == law
    odd, _ = shaped_for_duration(make_law("double_s(alpha=1/3, beta=1/4)"), "ei2",
                                     ElasticLoad(7.3, 0.03), 0.37, keep="base")
    assert make_law(odd.spec) == odd
    assert make_law(odd.spec).coefficients.C_a == pytest.approx(odd.coefficients.C_a,
                                                                rel=1e-12)
    ei = ShapedLaw(make_law("poly5"), "ei", 2.5, vibration_limit=0.1)
    assert "vibration_limit: 0.1" in ei.spec and make_law(ei.spec) == ei
    nested = ShapedLaw(make_law("{kind: cubic_spline, points: [[0, 0], [0.5, 0.4], [1, 1]]}"),
                       "zv", 3.0)
    assert nested.spec.startswith("{kind: shaped, f_T: 3, law: {kind: cubic_spline")
    assert make_law(nested.spec) == nested


def test_sizer_law_prints_a_shaped_law() -> None:
    result = run_cli("law", "{kind: shaped, law: cycloidal, shaper: zvd, f_T: 4, "
                     "damping_ratio: 0.02}", "--displacement", "1 rad", "--duration", "1 s")
    assert result.returncode == 0, result.stderr
    assert "a [rad/s^2]" in result.stdout


# ------------------------------------------------------------------ bad input
@pytest.mark.parametrize(("text", "field", "fragment"), [
    ("{kind: shaped, law: cycloidal, shaper: zx, f_T: 4}", "shaper", "unknown shaper"),
    ("{kind: shaped, law: cycloidal, shaper: zv, f_T: 0.5}", "f_T", "too small"),
    ("{kind: shaped, law: cycloidal, shaper: zvdd, f_T: 1.5}", "f_T", "exceed 1.5"),
    ("{kind: shaped, law: cycloidal, shaper: zv, f_T: -1}", "f_T", "positive"),
    ("{kind: shaped, law: cycloidal, shaper: zv, f_T: 4, damping_ratio: 1}",
     "damping_ratio", "[0, 1)"),
    ("{kind: shaped, law: cycloidal, shaper: zv, f_T: 4, damping_ratio: -0.1}",
     "damping_ratio", "[0, 1)"),
    ("{kind: shaped, law: cycloidal, shaper: ei, f_T: 4, damping_ratio: 0.1}",
     "damping_ratio", "undamped"),
    ("{kind: shaped, law: cycloidal, shaper: ei3, f_T: 4, damping_ratio: 0.4}",
     "damping_ratio", "0.3"),
    ("{kind: shaped, law: cycloidal, shaper: zv, f_T: 4, vibration_limit: 0.1}",
     "vibration_limit", "only ei"),
    ("{kind: shaped, law: cycloidal, shaper: ei, f_T: 4, vibration_limit: 1.5}",
     "vibration_limit", "[0, 1)"),
    ("{kind: shaped, law: nonsense, shaper: zv, f_T: 4}", "law", "unknown law"),
    ("{kind: shaped, shaper: zv, f_T: 4}", "law", "required"),
    ("{kind: shaped, law: cycloidal, f_T: 4}", "shaper", "required"),
    ("{kind: shaped, law: cycloidal, shaper: zv}", "f_T", "required"),
    ("{kind: shaped, law: cycloidal, shaper: zv, f_T: yes}", "f_T", "number"),
    ("{kind: shaped, law: cycloidal, shaper: zv, f_T: 4, delay: 1}", "delay", "no field"),
    ("{kind: shaped, law: [1, 2], shaper: zv, f_T: 4}", "law", "name or a mapping"),
    ("{kind: shaped, shaper: zv, f_T: 4, law: {kind: cubic_spline, periodic: true, "
     "points: [[0, 0], [0.5, 1], [1, 0]]}}", "law", "at rest"),
])
def test_bad_inputs(text: str, field: str, fragment: str) -> None:
    with pytest.raises(UserError) as error:
        make_law(text)
    assert error.value.field == field
    assert fragment in error.value.message


def test_bad_inputs_of_the_helpers() -> None:
    load = ElasticLoad(2.0, 0.0)
    base = make_law("cycloidal")
    with pytest.raises(UserError) as error:
        shaped_for_duration(base, "zvd", load, 0.5, keep="total")  # t_n = 0.5 s
    assert error.value.field == "duration"
    with pytest.raises(UserError) as error:
        shaped_for_duration(base, "zv", load, 1.0, keep="middle")  # type: ignore[arg-type]
    assert error.value.field == "keep"
    with pytest.raises(UserError) as error:
        shaped_for_duration(base, "zv", load, -1.0)
    assert error.value.field == "duration"
    with pytest.raises(UserError) as error:
        shaper_length("zw", load)
    assert error.value.field == "shaper"
    for times, amplitudes in (((0.0, 1.0), (0.5, 0.6)), ((0.1, 1.0), (0.5, 0.5)),
                              ((0.0, 0.0), (0.5, 0.5)), ((0.0,), (0.5, 0.5)),
                              ((0.0, 1.0), (1.5, -0.5))):
        with pytest.raises(UserError):
            Shaper(times, amplitudes)


def test_bad_input_on_the_command_line() -> None:
    result = run_cli("law", "{kind: shaped, law: cycloidal, shaper: zv, f_T: 0.4}",
                     "--displacement", "1 rad", "--duration", "1 s")
    assert_user_error(result, "f_T", "too small")
