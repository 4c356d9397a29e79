"""The four-bar crank-rocker (seed 003, Figure 2, Tables 1-2, section 6)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sizer.errors import UserError
from sizer.mechanics.linkages.four_bar import FourBar, paper_four_bar

PAPER = (0.075, 0.175, 0.100, 0.175)
GEOMETRIES = [PAPER, (1.0, 3.5, 2.5, 3.0), (0.5, 2.0, 1.8, 2.5), (1.0, 2.5, 3.2, 2.8)]
CASES = [(lengths, branch) for lengths in GEOMETRIES for branch in (1, -1)]
THETA = np.linspace(-math.pi, math.pi, 37)[:-1] + 0.013


def make(lengths: tuple[float, ...], branch: int = 1) -> FourBar:
    crank, coupler, rocker, ground = lengths
    return FourBar(crank=crank, coupler=coupler, rocker=rocker, ground=ground, branch=branch)


def pins(lengths: tuple[float, ...], theta: np.ndarray, s: np.ndarray):
    """A and B from the module's conventions: A = l1 e^{i theta}, B = (l4 - l3 cos s, l3 sin s)."""
    l1, _, l3, l4 = lengths
    return l1 * np.exp(1j * theta), (l4 - l3 * np.cos(s)) + 1j * l3 * np.sin(s)


def stencil(f, x: np.ndarray, h: float) -> np.ndarray:
    """Five-point central difference of f at x (error O(h^4))."""
    return (-f(x + 2 * h) + 8 * f(x + h) - 8 * f(x - h) + f(x - 2 * h)) / (12 * h)


@pytest.mark.parametrize(("lengths", "branch"), CASES)
def test_position_closes_the_loop_on_its_branch(lengths, branch):
    linkage = make(lengths, branch)
    s = linkage.output(THETA)
    a, b = pins(lengths, THETA, s)
    assert np.allclose(np.abs(b - a), lengths[1], rtol=1e-13)
    # the branch: B on the left (+1) or right (-1) of the line from A to O4
    cross = np.imag(np.conj(lengths[3] - a) * (b - a))
    assert np.all(np.sign(cross) == branch)
    phi = linkage.coupler_angle(THETA)
    assert np.allclose(a + lengths[1] * np.exp(1j * phi), b, atol=1e-13 * lengths[1])
    # s stays inside (0, pi) on the open branch, (-pi, 0) on the crossed one
    assert np.all(branch * s > 0) and np.all(branch * s < math.pi)


@pytest.mark.parametrize("lengths", GEOMETRIES)
def test_crossed_branch_is_the_open_one_mirrored(lengths):
    assert np.allclose(make(lengths, -1).output(THETA), -make(lengths, 1).output(-THETA),
                       atol=1e-14)


def test_open_branch_is_convex_at_a_quarter_turn():
    a, b = pins(PAPER, np.array(math.pi / 2), paper_four_bar().output(math.pi / 2))
    corners = [0j, complex(a), complex(b), PAPER[3] + 0j]
    turns = [np.imag(np.conj(corners[i] - corners[i - 1]) * (corners[(i + 1) % 4] - corners[i]))
             for i in range(4)]
    assert all(t < 0 for t in turns) or all(t > 0 for t in turns)


@pytest.mark.parametrize(("lengths", "branch"), CASES)
@pytest.mark.parametrize("order", [1, 2, 3, 4])
def test_derivatives_match_finite_differences(lengths, branch, order):
    linkage = make(lengths, branch)
    exact = linkage.output(THETA, order)
    scale = max(1.0, float(np.max(np.abs(exact))))
    # of the order below (exact), tight
    fd = stencil(lambda x: linkage.output(x, order - 1), THETA, 1e-3)
    assert np.allclose(exact, fd, rtol=0, atol=1e-7 * scale)
    # of the position alone, looser
    h = {1: 2e-3, 2: 2e-3, 3: 5e-3, 4: 1e-2}[order]   # round-off against truncation
    s = [linkage.output(THETA + j * h) for j in range(-3, 4)]
    weights = {1: [-1, 9, -45, 0, 45, -9, 1], 2: [2, -27, 270, -490, 270, -27, 2],
               3: [1, -8, 13, 0, -13, 8, -1], 4: [-1, 12, -39, 56, -39, 12, -1]}
    divisor = {1: 60 * h, 2: 180 * h**2, 3: 8 * h**3, 4: 6 * h**4}
    fd0 = sum(w * v for w, v in zip(weights[order], s, strict=True)) / divisor[order]
    assert np.allclose(exact, fd0, rtol=0, atol=1e-4 * scale)


@pytest.mark.parametrize(("lengths", "branch"), CASES)
@pytest.mark.parametrize("order", [1, 2, 3, 4])
def test_coupler_derivatives_match_finite_differences(lengths, branch, order):
    linkage = make(lengths, branch)
    exact = linkage.coupler_angle(THETA, order)
    if order == 1:   # the angle itself, unwrapped about its value at THETA
        base = linkage.coupler_angle(THETA)
        fd = stencil(lambda x: np.angle(np.exp(1j * (linkage.coupler_angle(x) - base))),
                     THETA, 1e-3)
    else:
        fd = stencil(lambda x: linkage.coupler_angle(x, order - 1), THETA, 1e-3)
    scale = max(1.0, float(np.max(np.abs(exact))))
    assert np.allclose(exact, fd, rtol=0, atol=1e-7 * scale)


def test_order_out_of_range_is_a_programming_error():
    with pytest.raises(ValueError):
        paper_four_bar().output(0.0, 5)


@pytest.mark.parametrize(("lengths", "branch"), CASES)
@pytest.mark.parametrize("half", [1, -1])
def test_input_of_inverts_output_on_both_halves(lengths, branch, half):
    linkage = make(lengths, branch)
    theta = np.linspace(-math.pi, math.pi, 721)[:-1]
    slope = linkage.output(theta, 1)
    pick = np.sign(slope) == half
    pick &= np.abs(slope) > 1e-2 * np.max(np.abs(slope))   # away from the dead points
    back = linkage.input_of(linkage.output(theta[pick]), half)
    assert np.allclose(np.angle(np.exp(1j * (back - theta[pick]))), 0.0, atol=1e-9)
    assert np.all((back >= -math.pi) & (back < math.pi))


@pytest.mark.parametrize(("lengths", "branch"), CASES)
def test_dead_points_are_the_output_extremes(lengths, branch):
    linkage = make(lengths, branch)
    l1, l2, l3, l4 = lengths
    dead = linkage.dead_points()
    assert np.all(np.abs(linkage.output(dead, 1)) < 1e-12)
    # crank and coupler in line: extended (same angle) at one, folded (pi apart) at the other
    gap = np.angle(np.exp(1j * (linkage.coupler_angle(dead) - dead)))
    assert sorted(np.round(np.abs(gap), 12)) == [0.0, round(math.pi, 12)]
    # the rocker's inner angle at O4 from the triangles O2-O4-B, |O2 B| = l2 +- l1
    extended = math.acos((l4**2 + l3**2 - (l1 + l2) ** 2) / (2 * l3 * l4))
    folded = math.acos((l4**2 + l3**2 - (l2 - l1) ** 2) / (2 * l3 * l4))
    low, high = linkage.output_range()
    expected = (folded, extended) if branch == 1 else (-extended, -folded)
    assert (low, high) == pytest.approx(expected, abs=1e-14)
    assert linkage.output(dead) == pytest.approx([high, low], abs=1e-14)
    s = linkage.output(np.linspace(-math.pi, math.pi, 200_001))
    assert s.max() <= high + 1e-13 and s.max() > high - 1e-8
    assert s.min() >= low - 1e-13 and s.min() < low + 1e-8


def test_paper_experiment_dead_point():
    """Section 6: the test bed at rest at its dead point, q1 = 0.318 rad, q3 = 2.246 rad."""
    linkage = paper_four_bar()
    assert (linkage.crank, linkage.coupler, linkage.rocker, linkage.ground) == PAPER
    theta = linkage.dead_points()[0]
    assert round(float(theta), 3) == 0.318
    assert round(float(linkage.output(theta)), 3) == 2.246
    assert round(linkage.output_range()[1], 3) == 2.246


def paper_m_k(lengths, q1, q2, q3):
    """m = adj(phi_q^d) phi_q^i and k = d det(phi_q^d) / d q^d (eqs. 22-23) for the
    closure l1 cos q1 + l2 cos q2 + l3 cos q3 - l4 = 0, l1 sin q1 + l2 sin q2 - l3 sin q3 = 0."""
    l1, l2, l3, _ = lengths
    phi_d = np.array([[-l1 * math.sin(q1), -l2 * math.sin(q2)],
                      [l1 * math.cos(q1), l2 * math.cos(q2)]])
    phi_i = np.array([-l3 * math.sin(q3), -l3 * math.cos(q3)])
    adj = np.array([[phi_d[1, 1], -phi_d[0, 1]], [-phi_d[1, 0], phi_d[0, 0]]])
    k = l1 * l2 * math.cos(q2 - q1) * np.array([-1.0, 1.0])  # det = l1 l2 sin(q2 - q1)
    return adj @ phi_i, k


@pytest.mark.parametrize(("lengths", "branch"), CASES)
@pytest.mark.parametrize("which", [0, 1])
def test_dead_point_velocity_limit(lengths, branch, which):
    """theta_dot^2 = s_ddot / s''(theta_dp) (eqs. 26-27 in 1-DOF form) against the paper's
    m, k and against the numeric inverse kinematics just beside the dead point."""
    linkage = make(lengths, branch)
    theta_dp = float(linkage.dead_points()[which])
    s_dp = float(linkage.output(theta_dp))
    curvature = float(linkage.output(theta_dp, 2))
    # the paper's Table 1 third case (c1 = 0, c2 = 0.5, c3 = 0.563) through the dead point,
    # turned upwards at the least rocker angle; c0 the exact dead point (printed 2.25)
    sign = -1.0 if which == 0 else 1.0
    c2, c3 = 0.5, 0.563
    s_ddot = sign * 2 * c2
    assert s_ddot * curvature > 0
    limit = math.sqrt(s_ddot / curvature)
    # eq. (26) with the paper's m and k at the dead point
    phi_dp = float(linkage.coupler_angle(theta_dp))
    m, k = paper_m_k(lengths, theta_dp, phi_dp, s_dp)
    assert limit == pytest.approx(math.sqrt(-m[0] ** 2 * s_ddot / (k @ m)), rel=1e-10)
    # eq. (25): q2_dot / q1_dot = m2 / m1
    assert float(linkage.coupler_angle(theta_dp, 1)) == pytest.approx(m[1] / m[0], rel=1e-10)

    def law(t):
        sgn = np.sign(t)
        return (s_dp + sign * (c2 * t**2 - sgn * c3 * t**3),
                sign * (2 * c2 * t - sgn * 3 * c3 * t**2))

    errors = []
    for tau in (1e-3, 1e-4):
        for t in (-tau, tau):
            s, s_dot = law(t)
            # the crank turning forwards: s' has the sign of s_dot
            theta = linkage.input_of(np.array(s), int(np.sign(s_dot)))
            theta_dot = s_dot / float(linkage.output(theta, 1))
            errors.append(abs(theta_dot / limit - 1.0))
    assert max(errors[2:]) < 1e-3
    assert max(errors[2:]) < 0.2 * max(errors[:2])


def test_paper_table1_c0_is_just_beyond_the_swing():
    """Table 1 prints c0 = 2.25 for the four-bar, the dead point rounded up: beyond q3_max."""
    with pytest.raises(UserError) as caught:
        paper_four_bar().input_of(np.array([2.25]), -1)
    assert caught.value.field == "output"


@pytest.mark.parametrize("branch", [1, -1])
def test_output_out_of_range(branch):
    linkage = make(PAPER, branch)
    low, high = linkage.output_range()
    for bad in (high + 0.01, low - 0.01, math.nan):
        with pytest.raises(UserError) as caught:
            linkage.input_of(np.array([low, bad]), 1)
        assert caught.value.field == "output"
        assert "outside its swing" in caught.value.message
        assert f"[{low:g}, {high:g}] rad" in caught.value.message
    # the ends themselves are fine (to round-off)
    ends = linkage.input_of(np.array([low * (1 - 1e-15), high]), 1)
    assert np.all(np.isfinite(ends))


def test_cannot_close():
    with pytest.raises(UserError) as caught:
        FourBar(crank=0.1, coupler=0.2, rocker=0.3, ground=1.0)
    assert caught.value.field == "ground"
    message = caught.value.message
    assert "cannot close" in message and "(1 m)" in message and "(0.6 m)" in message
    with pytest.raises(UserError) as caught:
        FourBar(crank=0.1, coupler=0.5, rocker=0.2, ground=0.2)
    assert caught.value.field == "coupler" and "cannot close" in caught.value.message


def test_crank_not_the_shortest():
    with pytest.raises(UserError) as caught:
        FourBar(crank=0.2, coupler=0.1, rocker=0.3, ground=0.35)
    assert caught.value.field == "crank"
    message = caught.value.message
    assert "cannot turn fully" in message and "shortest" in message and "the coupler is" in message
    assert "crank 0.2 m, coupler 0.1 m, rocker 0.3 m, ground 0.35 m" in message
    with pytest.raises(UserError) as caught:
        FourBar(crank=0.2, coupler=0.3, rocker=0.2, ground=0.1)
    assert "the rocker and the ground are not longer" in caught.value.message


@pytest.mark.parametrize("ground", [0.45, 0.4])  # non-Grashof; the change point s + l = p + q
def test_not_grashof(ground):
    with pytest.raises(UserError) as caught:
        FourBar(crank=0.1, coupler=0.3, rocker=0.2, ground=ground)
    assert caught.value.field == "crank"
    message = caught.value.message
    assert "cannot turn fully" in message and "Grashof" in message
    assert f"(0.1 + {ground:g} m)" in message and "(0.5 m)" in message


@pytest.mark.parametrize("field", ["crank", "coupler", "rocker", "ground"])
@pytest.mark.parametrize("value", [0.0, -0.1, math.nan, math.inf, True, "0.1"])
def test_non_positive_length(field, value):
    lengths = dict(zip(["crank", "coupler", "rocker", "ground"], PAPER, strict=True))
    lengths[field] = value
    with pytest.raises(UserError) as caught:
        FourBar(**lengths)
    assert caught.value.field == field
    assert "must be a positive length" in caught.value.message


@pytest.mark.parametrize("branch", [0, 2, -2, 0.5, True, "open"])
def test_bad_branch(branch):
    with pytest.raises(UserError) as caught:
        make(PAPER, branch)
    assert caught.value.field == "branch"
    assert "+1 (open) or -1 (crossed)" in caught.value.message


def test_bad_coordinate():
    with pytest.raises(UserError) as caught:
        FourBar(*PAPER, coordinate="slider_position")
    assert caught.value.field == "coordinate"
    assert "rocker_angle, coupler_angle, crank_angle" in caught.value.message


def test_branch_accepts_float_one():
    assert make(PAPER, -1.0).output_range()[1] < 0   # type: ignore[arg-type]
