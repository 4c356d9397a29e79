"""The RMS bound of eq. (6.2) with a dwell: the smallest T with T^3 (T + dwell) >= scale^2
(sizer.sizing.minimum_duration.rms_duration), against an independent root of the quartic
T^4 + dwell T^3 - scale^2 (numpy.roots, the eigenvalues of its companion matrix)."""

import numpy as np
import pytest

from sizer.sizing.shortest_duration import rms_duration


def _companion_root(scale: float, dwell: float) -> float:
    roots = np.roots([1.0, dwell, 0.0, 0.0, -scale * scale])
    real = roots[np.abs(roots.imag) <= 1e-9 * np.abs(roots)].real
    return float(real[real > 0.0].max())


@pytest.mark.parametrize("dwell", [1e-6, 0.15, 2.0, 100.0])
def test_root_of_the_quartic(dwell):
    scale = np.geomspace(1e-4, 1e4, 41)
    found = rms_duration(scale, dwell)
    expected = np.array([_companion_root(s, dwell) for s in scale])
    np.testing.assert_allclose(found, expected, rtol=1e-10)


def test_smallest_feasible_to_rounding():
    """T^3 (T + dwell) reaches scale^2 at the answer (to rounding) and not a few ulps below."""
    rng = np.random.default_rng(7)
    scale, dwell = 10.0 ** rng.uniform(-6, 6, 5000), 0.15
    T = rms_duration(scale, dwell)
    excess = (T**3 * (T + dwell)) / scale**2 - 1.0
    assert np.all(excess >= -1e-13)
    below = T * (1.0 - 1e-12)
    assert np.all(below**3 * (below + dwell) < scale**2)


def test_limits_of_the_float_range():
    T = rms_duration(np.array([1e308, 1e-300, 0.0, np.inf]), 0.15)
    assert T[0] == pytest.approx(1e154, rel=1e-12)  # sqrt(scale): the dwell is negligible
    # the dwell dominates: T = cbrt(scale^2 / dwell), on logarithms (scale^2 underflows)
    assert T[1] == pytest.approx(np.exp((2.0 * np.log(1e-300) - np.log(0.15)) / 3.0), rel=1e-12)
    assert T[2] == 0.0 and T[3] == np.inf


def test_no_dwell_is_the_square_root():
    scale = np.array([0.5, 2.0, 9.0])
    np.testing.assert_array_equal(rms_duration(scale, 0.0), np.sqrt(scale))
