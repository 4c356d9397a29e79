"""A piece of constant acceleration (zero jerk) is a straight segment of the (v_N, a_N)
curve: LinearPeaks keeps only its two ends, and its peaks stay the closed forms."""

from __future__ import annotations

import numpy as np

from sizer.laws.linear_peaks import LinearPeaks
from sizer.laws.piecewise_polynomial import Trapezoidal


def test_trapezoid_keeps_the_piece_ends_only():
    alpha = 0.2
    law = Trapezoidal(alpha=alpha)
    peaks = LinearPeaks(law)
    ends = np.array([[p.start, p.end] for p in law.pieces]).ravel()
    assert np.array_equal(peaks.tau, ends)
    assert np.array_equal(peaks.piece, np.repeat(np.arange(len(law.pieces)), 2))
    assert not peaks.j.any()
    # book sec. 6.2.1: C_a = 1/(alpha (1 - alpha)), C_v = 1/(1 - alpha)
    c_a, c_v = 1.0 / (alpha * (1.0 - alpha)), 1.0 / (1.0 - alpha)
    assert np.isclose(peaks.maximum(1.0, 0.0).value, c_a, rtol=1e-14)
    assert np.isclose(peaks.minimum(1.0, 0.0).value, -c_a, rtol=1e-14)
    assert np.isclose(peaks.maximum(0.0, 1.0).value, c_v, rtol=1e-14)
