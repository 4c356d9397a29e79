"""Exact peaks of p*a_N + q*v_N (sizer.laws.linear_peaks) against an independent brute
force (dense uniform samples of every piece refined by a bounded scalar search) and,
on the axes, against the closed-form C_a and C_v (book sec. 6.2, Table 6.2)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import optimize

from sizer.laws import DEFAULT_LAW_SPECS, make_law
from sizer.laws.linear_peaks import maximum, minimum, piece_values

VARIANTS = (
    "trapezoidal(alpha=0.1)", "double_s(alpha=0.2, beta=0.5)", "elliptic(n=5)",
    "modified_cycloidal(kappa=-0.5)", "polynomial(11)", "exponential(sigma=3, lam=0.5)",
)
SPECS = (*DEFAULT_LAW_SPECS, *VARIANTS)
BRUTE_SAMPLES = 200_000


def random_pairs(seed: int, count: int) -> tuple[np.ndarray, np.ndarray]:
    """Signs and magnitudes over 1e-6..1e6, with some p = 0 and some q = 0."""
    rng = np.random.default_rng(seed)
    p = rng.choice([-1.0, 1.0], count) * 10.0 ** rng.uniform(-6, 6, count)
    q = rng.choice([-1.0, 1.0], count) * 10.0 ** rng.uniform(-6, 6, count)
    p[:3], q[3:6] = 0.0, 0.0
    return p, q


def brute_force_maximum(law, p: float, q: float, samples: list) -> float:
    """max of p*a + q*v over 2e5 uniform samples per piece, the best refined by a
    bounded Brent search between its neighbouring samples."""
    best, where = -math.inf, None
    for index, (tau, v, a) in enumerate(samples):
        f = p * a + q * v
        k = int(np.argmax(f))
        if f[k] > best:
            best, where = float(f[k]), (index, tau, k)
    index, tau, k = where
    lo, hi = tau[max(k - 1, 0)], tau[min(k + 1, len(tau) - 1)]

    center = tau[k]

    def negative(u: float) -> float:  # tau = center + u: Brent's tolerance relative to u
        x = np.array([center + u])
        return -float(p * law.piece_derivative(index, x, 2)[0]
                      + q * law.piece_derivative(index, x, 1)[0])

    result = optimize.minimize_scalar(negative, bounds=(lo - center, hi - center),
                                      method="bounded", options={"xatol": 1e-16})
    return max(best, -float(result.fun))


def law_samples(law) -> list:
    out = []
    for index, piece in enumerate(law.pieces):
        tau = np.linspace(piece.start, piece.end, BRUTE_SAMPLES)
        out.append((tau, law.piece_derivative(index, tau, 1), law.piece_derivative(index, tau, 2)))
    return out


@pytest.mark.parametrize("spec", SPECS)
def test_maximum_against_brute_force(spec):
    law = make_law(spec)
    samples = law_samples(law)
    p, q = random_pairs(sum(map(ord, spec)), 24)
    peak = maximum(law, p, q)
    c = law.coefficients
    for i in range(len(p)):
        scale = abs(p[i]) * c.C_a + abs(q[i]) * c.C_v
        brute = brute_force_maximum(law, p[i], q[i], samples)
        assert peak.value[i] >= brute - 1e-12 * scale, (p[i], q[i])
        assert peak.value[i] <= brute + 1e-10 * scale, (p[i], q[i])
    # the value is the combination at the tau and piece reported
    at = (p * piece_values(law, peak.tau, peak.piece, 2)
          + q * piece_values(law, peak.tau, peak.piece, 1))
    assert np.array_equal(at, peak.value)
    starts = np.array([piece.start for piece in law.pieces])
    ends = np.array([piece.end for piece in law.pieces])
    assert np.all((peak.tau >= starts[peak.piece]) & (peak.tau <= ends[peak.piece]))


@pytest.mark.parametrize("spec", SPECS)
def test_minimum_against_brute_force(spec):
    law = make_law(spec)
    samples = law_samples(law)
    p, q = random_pairs(7 + len(spec), 6)
    low = minimum(law, p, q)
    c = law.coefficients
    for i in range(len(p)):
        scale = abs(p[i]) * c.C_a + abs(q[i]) * c.C_v
        brute = -brute_force_maximum(law, -p[i], -q[i], samples)
        assert low.value[i] <= brute + 1e-12 * scale
        assert low.value[i] >= brute - 1e-10 * scale


def closed_form(law, name: str) -> float:
    known = law.closed_form_coefficients()
    if name in known:
        return known[name]
    return getattr(law.numerical_coefficients, name)  # roots of the next derivative


@pytest.mark.parametrize("spec", SPECS)
@pytest.mark.parametrize("size", [1e-6, 1.0, 1e6])
def test_axes_give_the_peak_coefficients(spec, size):
    """q = 0 gives p*C_a (a_N is odd about tau = 1/2), p = 0 gives q*C_v; v_N >= 0
    (0 at the ends up to the rounding of the law's sums of cosines)."""
    law = make_law(spec)
    C_a, C_v = closed_form(law, "C_a"), closed_form(law, "C_v")
    p = np.array([size, -size, 0.0, 0.0])
    q = np.array([0.0, 0.0, size, -size])
    peak = maximum(law, p, q)
    expected = np.array([size * C_a, size * C_a, size * C_v, 0.0])
    assert peak.value == pytest.approx(expected, rel=1e-12, abs=1e-15 * size * C_v)
    low = minimum(law, p, q)
    expected_low = np.array([-size * C_a, -size * C_a, 0.0, -size * C_v])
    assert low.value == pytest.approx(expected_low, rel=1e-12, abs=1e-15 * size * C_v)


def test_broadcast_shapes():
    law = make_law("cycloidal")
    p = np.array([[1.0], [2.0], [-3.0]])
    q = np.array([[0.5, 1.0, -1.0, 0.0]])
    peak = maximum(law, p, q)
    assert peak.value.shape == peak.tau.shape == peak.piece.shape == (3, 4)
    for i in range(3):
        for k in range(4):
            assert peak.value[i, k] == maximum(law, p[i, 0], q[0, k]).value
    assert maximum(law, 2.0, 0.0).value == pytest.approx(4 * math.pi, rel=1e-14)
    assert maximum(law, 0.0, 0.0).value == 0.0


def test_cycloidal_combination_in_closed_form():
    """p*2 pi sin(2 pi t) + q*(1 - cos(2 pi t)) peaks at q + sqrt((2 pi p)^2 + q^2)."""
    law = make_law("cycloidal")
    p, q = random_pairs(3, 1000)
    expected = q + np.hypot(2 * math.pi * p, q)
    scale = np.abs(p) * 2 * math.pi + np.abs(q) * 2
    assert np.all(np.abs(maximum(law, p, q).value - expected) <= 1e-14 * scale)


def test_piece_values_match_the_law():
    law = make_law("double_s(alpha=1/3, beta=1/4)")
    rng = np.random.default_rng(5)
    piece = rng.integers(0, len(law.pieces), 500)
    starts = np.array([pc.start for pc in law.pieces])
    ends = np.array([pc.end for pc in law.pieces])
    tau = starts[piece] + rng.uniform(0, 1, 500) * (ends - starts)[piece]
    tau[:8], tau[8:16] = starts[piece[:8]], ends[piece[8:16]]  # one-sided ends
    for order in (1, 2, 3):
        expected = [law.piece_derivative(int(i), np.array([t]), order)[0]
                    for i, t in zip(piece, tau, strict=True)]
        assert np.array_equal(piece_values(law, tau, piece, order), expected)


@pytest.mark.parametrize("spec", ["elliptic(n=1000)", "modified_cycloidal(kappa=-0.99)",
                                  "modified_cycloidal(kappa=0.99)",
                                  "exponential(sigma=1, lam=0.15)"])
def test_steep_laws_against_a_graded_brute_force(spec):
    """At the ends of the parameter ranges the profile narrows to 1e-3 of the piece
    around tau = 1/2 or the ends: the brute force adds 2e4 points graded toward them."""
    law = make_law(spec)
    samples = []
    for index, piece in enumerate(law.pieces):
        graded = np.geomspace(1e-13, 0.5, 20_000)
        focus = [piece.start, piece.end, *law.fine_points()]
        tau = np.concatenate([np.linspace(piece.start, piece.end, BRUTE_SAMPLES)]
                             + [np.concatenate((x - graded, x + graded)) for x in focus])
        tau = np.unique(tau[(tau >= piece.start) & (tau <= piece.end)])
        samples.append((tau, law.piece_derivative(index, tau, 1),
                        law.piece_derivative(index, tau, 2)))
    p, q = random_pairs(11, 40)
    peak = maximum(law, p, q)
    c = law.coefficients
    for i in range(len(p)):
        scale = abs(p[i]) * c.C_a + abs(q[i]) * c.C_v
        brute = brute_force_maximum(law, p[i], q[i], samples)
        assert brute - 1e-12 * scale <= peak.value[i] <= brute + 1e-10 * scale, (p[i], q[i])
