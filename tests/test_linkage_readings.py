"""Other outputs of a linkage (the coupler's, the crank's, the rod's angle) and a four-bar
driven from its rocker (issue 14): the geometry of each coordinate.

The expected values come from this test's own geometry (two circles meet: the rocker pin
B of a four-bar; the rod's inclination asin((r sin q - e) / l) of a slider-crank), the
velocity analysis dq2/dq1 = -l1 sin(q1 + q3) / (l2 sin(q2 + q3)) and high-order central
differences, not from sizer's formulas."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from scipy.optimize import brentq

from sizer.errors import UserError
from sizer.mechanics.linkages.four_bar import FourBar, paper_four_bar
from sizer.mechanics.linkages.inverse_motion import input_motion, output_motion
from sizer.mechanics.linkages.slider_crank import SliderCrank

GEOMETRIES = [(0.075, 0.175, 0.100, 0.175), (0.05, 0.2, 0.15, 0.18), (0.04, 0.12, 0.1, 0.13)]


def pins(lengths: tuple[float, ...], branch: int, q1: np.ndarray):
    """A and B of the four-bar at crank angles q1: B where |B - A| = l2, |B - O4| = l3,
    on the left of A->O4 for the open assembly (branch +1)."""
    l1, l2, l3, l4 = lengths
    a = l1 * np.exp(1j * q1)
    d = l4 - a
    dist = np.abs(d)
    along = (dist**2 + l2**2 - l3**2) / (2 * dist)
    across = np.sqrt(l2**2 - along**2)
    b = a + d / dist * (along + 1j * branch * across)
    return a, b


def angles(lengths, branch, q1):
    """(q2, q3): the coupler's direction A->B and the rocker's inner angle at O4."""
    a, b = pins(lengths, branch, q1)
    l4 = lengths[3]
    return np.angle(b - a), np.arctan2(b.imag, l4 - b.real)


def derivative(f, x: np.ndarray, h: float = 1e-3) -> np.ndarray:
    """d f / dx by the eighth-order central difference."""
    c = (4 / 5, -1 / 5, 4 / 105, -1 / 280)
    return sum(ck * (f(x + (k + 1) * h) - f(x - (k + 1) * h)) for k, ck in enumerate(c)) / h


THETA = np.linspace(-3.1, 3.1, 41)


@pytest.mark.parametrize("lengths", GEOMETRIES)
@pytest.mark.parametrize("branch", [1, -1])
def test_coupler_angle_and_its_derivatives(lengths, branch) -> None:
    bar = FourBar(*lengths, branch=branch, coordinate="coupler_angle")
    q2, q3 = angles(lengths, branch, THETA)
    got = bar.output(THETA)
    assert np.allclose(np.angle(np.exp(1j * (got - q2))), 0.0, atol=1e-12)
    l1, l2 = lengths[:2]
    velocity = -l1 * np.sin(THETA + q3) / (l2 * np.sin(q2 + q3))
    assert np.allclose(bar.output(THETA, 1), velocity, rtol=1e-10, atol=1e-12)
    for k in range(1, 5):  # each order against the differences of the one below
        fd = derivative(lambda x, k=k: bar.output(x, k - 1), THETA)
        scale = np.max(np.abs(fd))
        assert np.allclose(bar.output(THETA, k), fd, atol=1e-8 * scale), k
    # continuous over the turn (no branch cut inside the coupler's swing)
    dense = bar.output(np.linspace(-np.pi, np.pi, 20001))
    assert np.max(np.abs(np.diff(dense))) < 1e-2


@pytest.mark.parametrize("lengths", GEOMETRIES)
@pytest.mark.parametrize("branch", [1, -1])
def test_coupler_dead_points_are_where_crank_and_rocker_are_parallel(lengths, branch):
    bar = FourBar(*lengths, branch=branch, coordinate="coupler_angle")
    l1, l2 = lengths[:2]

    def velocity(q1: float) -> float:
        q2, q3 = angles(lengths, branch, np.array([q1]))
        return float(-l1 * np.sin(q1 + q3[0]) / (l2 * np.sin(q2[0] + q3[0])))

    grid = np.linspace(-np.pi, np.pi, 721)
    values = np.array([velocity(x) for x in grid])
    roots = [brentq(velocity, grid[i], grid[i + 1], xtol=1e-14)
             for i in np.flatnonzero(np.sign(values[:-1]) * np.sign(values[1:]) < 0)]
    assert len(roots) == 2
    dead = bar.dead_points()
    assert sorted(dead) == pytest.approx(sorted(roots), abs=1e-10)
    low, high = bar.output_range()
    dense = bar.output(np.linspace(-np.pi, np.pi, 200001))
    assert (low, high) == pytest.approx((dense.min(), dense.max()), abs=1e-9)
    assert float(bar.output(dead[0:1])[0]) == pytest.approx(high, abs=1e-12)
    assert bar.output(dead, 2)[0] < 0 < bar.output(dead, 2)[1]


@pytest.mark.parametrize("coordinate", ["coupler_angle", "rocker_angle"])
@pytest.mark.parametrize("branch", [1, -1])
def test_input_of_inverts_each_coordinate(coordinate, branch) -> None:
    bar = FourBar(*GEOMETRIES[1], branch=branch, coordinate=coordinate)
    s, slope = bar.output(THETA), bar.output(THETA, 1)
    back = bar.input_of(s, np.where(slope > 0, 1, -1))
    assert np.allclose(np.angle(np.exp(1j * (back - THETA))), 0.0, atol=1e-9)
    with pytest.raises(UserError) as caught:
        bar.input_of(np.array([bar.output_range()[1] + 0.1]), 1)
    assert caught.value.field == "output"


def test_the_crank_angle_reading_is_the_identity() -> None:
    bar = replace(paper_four_bar(), coordinate="crank_angle")
    assert np.array_equal(bar.output(THETA), THETA)
    assert np.all(bar.output(THETA, 1) == 1.0) and np.all(bar.output(THETA, 3) == 0.0)
    assert bar.dead_points().size == 0


@pytest.mark.parametrize("offset", [0.0, 0.02, -0.01])
def test_rod_angle_and_its_derivatives(offset) -> None:
    r, rod = 0.05, 0.2
    crank = SliderCrank(r, rod, offset, coordinate="rod_angle")
    assert not crank.output_linear
    v = np.arcsin((r * np.sin(THETA) - offset) / rod)
    assert np.allclose(crank.output(THETA), v, atol=1e-14)
    assert np.allclose(crank.output(THETA, 1), r * np.cos(THETA) / (rod * np.cos(v)),
                       atol=1e-14)
    for k in range(1, 5):
        fd = derivative(lambda x, k=k: crank.output(x, k - 1), THETA)
        assert np.allclose(crank.output(THETA, k), fd, atol=1e-8 * np.max(np.abs(fd))), k
    low, high = crank.output_range()
    assert (low, high) == pytest.approx((np.arcsin((-r - offset) / rod),
                                         np.arcsin((r - offset) / rod)))
    assert crank.output(crank.dead_points()) == pytest.approx([high, low])
    back = crank.input_of(v, np.where(np.cos(THETA) > 0, 1, -1))
    assert np.allclose(np.angle(np.exp(1j * (back - THETA))), 0.0, atol=1e-9)


def test_inverse_motion_through_a_dead_point_of_the_coupler() -> None:
    # the crank turns at 3 rad/s through the coupler's largest angle: from the coupler's
    # motion alone the inverse kinematics gives the crank's speed back, 3 rad/s, at the
    # dead point too (the paper's limit theta_dot^2 = s_ddot / f'', eq. 27)
    bar = FourBar(*GEOMETRIES[0], coordinate="coupler_angle")
    top = float(bar.dead_points()[0])
    t = np.linspace(-0.2, 0.2, 4001)
    theta = top + 3.0 * t
    s = output_motion(bar, theta, np.full_like(t, 3.0), np.zeros_like(t), np.zeros_like(t))
    back, w1, w2, _ = input_motion(bar, *s, start_theta=float(theta[0]))
    assert np.allclose(back, theta, atol=1e-7)
    assert np.allclose(w1, 3.0, rtol=1e-4)
    assert np.max(np.abs(w2)) < 1e-2 * 9.0 / 0.2


def test_the_rocker_drive_inverse_motion_is_the_paper_s_with_input_and_output_swapped():
    # the law on the rocker (the motor's link) through its largest angle: the crank's speed
    # at the dead point is sqrt(q3_ddot / q3''), as for a law on the rocker driven by the
    # crank; the crank keeps turning (crank and coupler in line)
    bar = paper_four_bar()
    top = float(bar.dead_points()[0])
    f2 = float(bar.output(np.array([top]), 2)[0])
    t = np.linspace(-0.1, 0.1, 2001)
    high = bar.output_range()[1]
    s = [high - 2.0 * t**2, -4.0 * t, np.full_like(t, -4.0), np.zeros_like(t)]
    theta, w1, _, _ = input_motion(bar, *s, start_theta=float(
        bar.input_of(s[0][:1], 1)[0]))
    middle = np.argmin(np.abs(t))
    assert theta[middle] == pytest.approx(top, abs=1e-6)
    assert w1[middle] == pytest.approx(np.sqrt(-4.0 / f2), rel=1e-6)
