"""The law curve's convex hull (sizer.laws.linear_peaks._convex_hull) against a plain
monotone chain (Andrew's algorithm, written here as the textbook gives it) on point sets
with repeated, collinear and vertical runs, and on the curves of real laws."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sizer.laws import make_law
from sizer.laws.linear_peaks import LinearPeaks, _convex_hull


def monotone_chain(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    order = np.lexsort((y, x))
    xs, ys = x[order].tolist(), y[order].tolist()

    def chain(indices) -> list[int]:
        hull: list[int] = []
        for i in indices:
            while len(hull) >= 2:
                a, b = hull[-2], hull[-1]
                if (xs[b] - xs[a]) * (ys[i] - ys[a]) - (ys[b] - ys[a]) * (xs[i] - xs[a]) > 0:
                    break
                hull.pop()
            hull.append(i)
        return hull

    lower, upper = chain(range(len(xs))), chain(range(len(xs) - 1, -1, -1))
    return order[np.array(lower[:-1] + upper[:-1], dtype=np.intp)]


small = st.integers(min_value=-4, max_value=4).map(float)


@settings(max_examples=300, deadline=None)
@given(st.lists(st.tuples(small, small), min_size=1, max_size=40))
def test_the_same_vertices_as_the_plain_chain_on_a_lattice(points):
    """Integer points on a small lattice: many repeats, collinear and vertical runs."""
    x, y = (np.array(c) for c in zip(*points, strict=True))
    np.testing.assert_array_equal(_convex_hull(x, y), monotone_chain(x, y))


@pytest.mark.parametrize("seed", range(5))
def test_the_same_vertices_on_a_noisy_loop(seed):
    rng = np.random.default_rng(seed)
    t = np.sort(rng.uniform(0.0, 2.0 * np.pi, 2000))
    r = 1.0 + 0.05 * rng.standard_normal(len(t))
    x, y = r * np.cos(t), r * np.sin(3.0 * t) * 0.5
    np.testing.assert_array_equal(_convex_hull(x, y), monotone_chain(x, y))


@pytest.mark.parametrize("spec", ["cycloidal", "poly5", "modified_trapezoidal",
                                  "trapezoidal(alpha=1/3)", "double_s(alpha=1/3, beta=1/4)"])
def test_the_same_vertices_on_laws(spec):
    peaks = LinearPeaks(make_law(spec))
    np.testing.assert_array_equal(peaks.hull, monotone_chain(peaks.v, peaks.a))
