"""Brent's method for a maximum (sizer.numerics.golden.BrentMax), the step of the search
for a feasible duration where the slack peaks (sizer.sizing.shortest_duration._peak_search):
the maximizers of functions known in closed form, and how many points it reads."""

from __future__ import annotations

import numpy as np
import pytest

from sizer.numerics.golden import BrentMax, interior_points

CENTRES = np.array([0.3, -0.7, 0.05, 0.9, -0.999])
TOL = 2.5e-8


def search(f, lo, hi, steps=100):
    """The maximizer of f per element from [lo, hi] and the points read after the two
    golden ones, each element dropped once settled."""
    x1, x2 = interior_points(lo, hi)
    f1, f2 = f(x1, np.arange(len(lo))), f(x2, np.arange(len(lo)))
    best = f1 >= f2
    state = BrentMax(lo, hi, f(lo, np.arange(len(lo))), np.where(best, x1, x2),
                     np.where(best, f1, f2),
                     np.where(best, x2, x1), np.where(best, f2, f1), TOL)
    index = np.arange(len(lo))
    found, count = np.full(len(lo), np.nan), np.zeros(len(lo), dtype=int)
    for _ in range(steps):
        done = state.settled
        found[index[done]] = state.x[done]
        index, state = index[~done], state.take(~done)
        if not len(index):
            break
        u = state.point()
        state.update(u, f(u, index))
        count[index] += 1
    return found, count


@pytest.mark.parametrize(("name", "g", "most"), [
    ("smooth", lambda d: -d * d + 0.1 * d**3, 18),
    ("cosine", lambda d: np.cos(3.0 * d), 18),
    ("kink", lambda d: -np.abs(d), 40),
    ("two lines, uneven slopes", lambda d: np.minimum(2.0 * d, -0.5 * d), 45),
])
def test_the_maximum_of_known_functions_is_found_to_the_tolerance(name, g, most):
    found, count = search(lambda x, i: g(x - CENTRES[i]), np.full(5, -1.0), np.full(5, 1.0))
    assert np.all(np.abs(found - CENTRES) <= 4 * TOL), name
    assert count.max() <= most, (name, count)


def test_a_smooth_peak_takes_fewer_points_than_golden_section():
    # golden section shrinks the bracket by 0.618 a point: 2 -> 1e-7 takes 35 points;
    # a peak inside takes a third of that, one 1e-3 from an end (-0.999) half
    _, count = search(lambda x, i: -(x - CENTRES[i]) ** 2, np.full(5, -1.0), np.full(5, 1.0))
    assert count[:4].max() <= 12
    assert count[4] <= 18
