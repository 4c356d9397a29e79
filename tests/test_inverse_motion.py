"""The crank motion from the output motion through dead points, and the paper's
feasibility rules (seed 003 secs. 4-5, its slider-crank r = 0.75 m, l = 1.25 m, Table 1
with eq. 63, t0 = 0 at the top dead centre)."""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest

from sizer.errors import UserError
from sizer.mechanics.linkages.inverse_motion import (
    dead_point_crossings,
    input_motion,
    output_motion,
)
from sizer.mechanics.linkages.slider_crank import SliderCrank

R, L = 0.75, 1.25
PAPER = SliderCrank(R, L)
DT = 1e-3
T = np.round(np.arange(-500, 501) * DT, 12)  # t0 = 0 is sample 500
I0 = 500


def eq63(c2: float, c3: float, c4: float, t: np.ndarray = T, c0: float = 2.0):
    """Eq. 63 (c1 = 0) and its derivatives, with the one-sided values at t0 = 0."""
    sg = np.where(t < 0, 1.0, -1.0)
    s = -c4 * t ** 4 + sg * c3 * t ** 3 - c2 * t ** 2 + c0
    s1 = -4 * c4 * t ** 3 + 3 * sg * c3 * t ** 2 - 2 * c2 * t
    s2 = -12 * c4 * t ** 2 + 6 * sg * c3 * t - 2 * c2
    s3 = -24 * c4 * t + 6 * sg * c3
    left = (-12 * c4 * t ** 2 + 6 * c3 * t - 2 * c2, -24 * c4 * t + 6 * c3)
    right = (-12 * c4 * t ** 2 - 6 * c3 * t - 2 * c2, -24 * c4 * t - 6 * c3)
    return s, s1, s2, s3, left, right


def start_angle(s0: float) -> float:
    """The crank below the top dead centre before it, turning +: theta < 0, ds/dtheta > 0."""
    return float(PAPER.input_of(np.array([s0]), 1)[0])


def test_table1_feasibility() -> None:
    """Sec. 5.1: the c3 case reaches the dead point with s_ddot = 0 and a jerk (Fig. 5,
    infinite crank acceleration); the c4 case with s_ddot = s_dddot = 0 (Fig. 6) and the
    c2, c3 case with s_ddot != 0 (sec. 5.2, Fig. 7) are feasible."""
    for c2, c3, c4, bad in [(0, 0.5, 0, True), (0, 0, 0.5, False), (0.5, 0.5, 0, False)]:
        s, s1, s2, s3, left, right = eq63(c2, c3, c4)
        for one_sided in ({}, {"left": left, "right": right}):
            issues = dead_point_crossings(PAPER, T, s, s1, s2, s3, **one_sided)
            if not bad:
                assert issues == []
                continue
            assert len(issues) == 1
            issue = issues[0]
            assert (issue.kind, issue.time) == ("jerk", 0.0)
            assert abs(6 * c3) == pytest.approx(3.0)
            assert issue.message.startswith("acceleration 0 with jerk ")
            assert "at the dead point at t = 0 s" in issue.message
            assert "the jerk must be 0 too (C3)" in issue.message
            jerk = float(issue.message.split("jerk ")[1].split(" ")[0])
            assert abs(jerk) == pytest.approx(6 * c3, rel=1e-3)


def test_table1_crank_speed_and_acceleration() -> None:
    """Sec. 5.2 (c2 = c3 = 0.5): the crank speed continuous and equal to eq. 33 at t0,
    the acceleration equal to eq. 53 with the jerk of each side (+3 before, -3 after);
    the rod's eqs. 34, 54 from q2 = asin(r sin q1 / l)."""
    s, s1, s2, s3, _, _ = eq63(0.5, 0.5, 0.0)
    theta, w1, w2, _ = input_motion(PAPER, s, s1, s2, s3, start_angle(s[0]))
    acc = -1.0
    speed = math.sqrt(-L * acc / (R * (R + L)))  # eq. 33
    assert theta[I0] == pytest.approx(0.0, abs=1e-12)
    assert w1[I0] == pytest.approx(speed, rel=1e-12)
    assert np.max(np.abs(np.diff(w1[I0 - 20:I0 + 21]))) < 2 * DT * np.max(np.abs(w2))
    root = math.sqrt(-acc * R * L * (R + L))
    for jerk, value in ((+3.0, 2 * w2[I0 - 1] - w2[I0 - 2]), (-3.0, w2[I0])):
        # extrapolated from the samples beside t0: within the limit forms' error there
        assert value == pytest.approx(-L * jerk / (3 * root), rel=1e-3)  # eq. 53
        assert R / L * value == pytest.approx(-R * jerk / (3 * root), rel=1e-3)  # eq. 54
    assert R / L * w1[I0] == pytest.approx(math.sqrt(-R * acc / (L * (R + L))))  # eq. 34
    # q2 from the crank's samples, differentiated: eq. 34 again
    q2 = np.arcsin(R * np.sin(theta) / L)
    assert (q2[I0 + 1] - q2[I0 - 1]) / (2 * DT) == pytest.approx(R / L * speed, rel=1e-3)


def test_smooth_law_through_the_dead_point() -> None:
    """s = 2 - 0.5 t^2 - 0.5 t^3 for all t (C3, s_ddot = -1, jerk -3 at t0): the crank
    acceleration continuous through t0 and equal to eq. 53."""
    t = T
    s = 2 - 0.5 * t ** 2 - 0.5 * t ** 3
    s1, s2, s3 = -t - 1.5 * t ** 2, -1 - 3 * t, -3 + 0 * t
    assert dead_point_crossings(PAPER, t, s, s1, s2, s3) == []
    _, _, w2, _ = input_motion(PAPER, s, s1, s2, s3, start_angle(s[0]))
    closed = -L * -3.0 / (3 * math.sqrt(R * L * (R + L)))
    assert w2[I0] == pytest.approx(closed, rel=1e-6)
    assert 2 * w2[I0 - 1] - w2[I0 - 2] == pytest.approx(closed, rel=1e-3)
    assert 2 * w2[I0 + 1] - w2[I0 + 2] == pytest.approx(closed, rel=1e-3)
    assert np.max(np.abs(np.diff(w2[I0 - 20:I0 + 21]))) < 0.02


def test_table1_at_rest_at_the_dead_point() -> None:
    """Sec. 5.1, Fig. 6 (c4 = 0.5): the crank stops at the dead point (speed 0, eq. 33
    with s_ddot = 0) with the acceleration of eq. 61 (s'''' = -12), decelerating before
    and accelerating after as it keeps turning; the rod's eq. 62."""
    s, s1, s2, s3, _, _ = eq63(0.0, 0.0, 0.5)
    closed = math.sqrt(-L * -12.0 / (3 * R * (R + L)))  # eq. 61
    for s4 in (None, np.full(T.size, -12.0)):
        theta, w1, w2, _ = input_motion(PAPER, s, s1, s2, s3, start_angle(s[0]), s4=s4)
        assert w1[I0] == 0.0
        assert np.all(w1[:I0] > 0) and np.all(w1[I0 + 1:] > 0)  # keeps turning +
        assert np.all(np.diff(theta) > 0)
        assert w2[I0] == pytest.approx(closed, rel=1e-9)
        assert 2 * w2[I0 - 1] - w2[I0 - 2] == pytest.approx(-closed, rel=1e-3)
        assert 2 * w2[I0 + 1] - w2[I0 + 2] == pytest.approx(closed, rel=1e-3)
        assert R / L * w2[I0] == pytest.approx(math.sqrt(-R * -12.0 / (3 * L * (R + L))))


def test_table1_infeasible_gets_infinite_acceleration() -> None:
    s, s1, s2, s3, _, _ = eq63(0.0, 0.5, 0.0)
    _, w1, w2, _ = input_motion(PAPER, s, s1, s2, s3, start_angle(s[0]))
    assert w1[I0] == 0.0 and math.isinf(w2[I0])
    assert abs(w2[I0 - 1]) > abs(w2[I0 - 5]) > abs(w2[I0 - 50])  # grows like |t|^-1/2


def test_acceleration_discontinuous() -> None:
    """C1 law: s_ddot = -1 before the top dead centre, -2 after."""
    a = np.where(T < 0, 1.0, 2.0)
    s, s1, s2, s3 = 2 - a * T ** 2 / 2, -a * T, -a, 0 * T
    left, right = (-np.ones_like(T), 0 * T), (-2 * np.ones_like(T), 0 * T)
    for one_sided in ({}, {"left": left, "right": right}):
        issues = dead_point_crossings(PAPER, T, s, s1, s2, s3, **one_sided)
        assert [(i.kind, i.time) for i in issues] == [("discontinuous", 0.0)]
        assert issues[0].message.startswith(
            "acceleration discontinuous at the dead point at t = 0 s")


def test_acceleration_of_the_wrong_sign() -> None:
    """At the bottom dead centre the geometry needs s_ddot > 0."""
    low = PAPER.output_range()[0]
    t = np.array([-DT, 0.0, DT])
    s, s1 = np.array([low + 1e-9, low, low + 1e-9]), np.array([-1e-3, 0.0, 1e-3])
    s2, s3 = np.full(3, -3.2), np.zeros(3)
    issues = dead_point_crossings(PAPER, t, s, s1, s2, s3, left=(s2, s3), right=(s2, s3))
    assert [(i.kind, i.time) for i in issues] == [("sign", 0.0)]
    assert issues[0].message == ("acceleration -3.2 m/s^2 at the dead point at t = 0 s: "
                                 "the geometry needs it above 0")


def test_away_from_dead_points_no_issue_and_crank_reverses() -> None:
    """The crank swinging 0.8 +- 0.5 rad (no dead point): the output reverses inside its
    range, the crank with it, recovered exactly; no issue."""
    t = np.linspace(0, 10, 4001)
    th, w1, w2, w3 = 0.8 + 0.5 * np.sin(t), 0.5 * np.cos(t), -0.5 * np.sin(t), -0.5 * np.cos(t)
    s = output_motion(PAPER, th, w1, w2, w3)
    assert dead_point_crossings(PAPER, t, *s) == []
    got = input_motion(PAPER, *s, 0.8)
    for a, b, tol in zip(got, (th, w1, w2, w3), (1e-12, 1e-9, 1e-7, 1e-5), strict=True):
        assert np.max(np.abs(a - b)) < tol


@pytest.mark.parametrize("linkage", [PAPER, SliderCrank(0.1, 0.35, 0.03)],
                         ids=["paper", "offset"])
@pytest.mark.parametrize("dt", [1e-3, 1.2345e-5])
def test_round_trip_through_many_dead_points(linkage: SliderCrank, dt: float) -> None:
    """A crank law over several turns (through both dead points many times): the output
    from it, then the crank from the output, against the law itself."""
    t = np.arange(0, 4, dt)
    th = 0.3 + 2 * t + 0.7 * t ** 2 + 0.2 * t ** 3
    law = (th, 2 + 1.4 * t + 0.6 * t ** 2, 1.4 + 1.2 * t, 1.2 + 0.5 * t)
    s = output_motion(linkage, *law)
    assert dead_point_crossings(linkage, t, *s) == []
    got = input_motion(linkage, *s, 0.3)
    for a, b, tol in zip(got, law, (1e-11, 1e-8, 1e-4, 1e-4), strict=True):
        assert np.max(np.abs(a - b)) / np.max(np.abs(b)) < tol


def test_output_motion_against_mpmath() -> None:
    """The chain rule against mpmath's derivatives of s(theta(t)) written out."""
    r, rod, e = 0.1, 0.35, 0.03
    link = SliderCrank(r, rod, e)

    def s_of_t(t):
        th = 0.3 + 2 * t + 0.7 * t ** 2
        return r * mp.cos(th) + mp.sqrt(rod ** 2 - (r * mp.sin(th) - e) ** 2)

    t = 0.37
    th = np.array([0.3 + 2 * t + 0.7 * t ** 2])
    got = output_motion(link, th, np.array([2 + 1.4 * t]), np.array([1.4]), np.array([0.0]))
    for k in range(4):
        assert float(got[k][0]) == pytest.approx(float(mp.diff(s_of_t, t, k)), rel=1e-10)


def test_start_at_the_dead_point_with_direction() -> None:
    """From rest at the top dead centre, s = 2 - 0.3 (1 - cos t): the crank turns the
    way asked, with theta_dot^2 = s_ddot / f'' at t = 0 (eq. 27: 0.3 l / (r (r + l)))."""
    t = np.linspace(0, 2, 2001)
    s, s1, s2, s3 = 2 - 0.3 * (1 - np.cos(t)), -0.3 * np.sin(t), -0.3 * np.cos(t), \
        0.3 * np.sin(t)
    # from rest the acceleration jumps to -0.3 at the dead point: the paper's rule fails
    issues = dead_point_crossings(PAPER, t, s, s1, s2, s3)
    assert [(i.kind, i.time) for i in issues] == [("discontinuous", 0.0)]
    for direction in (1, -1):
        theta, w1, _, _ = input_motion(PAPER, s, s1, s2, s3, 0.0, direction=direction)
        assert np.all(np.sign(w1) == direction)
        assert w1[0] == pytest.approx(direction * math.sqrt(0.3 * L / (R * (R + L))))
        assert np.all(direction * np.diff(theta) > 0)


def test_bad_input() -> None:
    t = np.array([0.0, 0.1])
    s = np.array([1.9, 2.05])
    z = np.zeros(2)
    with pytest.raises(UserError) as err:
        dead_point_crossings(PAPER, t, s, z, z, z)
    assert err.value.field == "output"
    with pytest.raises(UserError) as err:
        input_motion(PAPER, s, z, z, z, 0.3)
    assert err.value.field == "output"
    with pytest.raises(UserError) as err:
        input_motion(PAPER, np.array([1.9, 1.8]), z, z, z, 0.0)
    assert err.value.field == "start_theta"


def test_dead_point_between_samples() -> None:
    """Table 1 on a grid that misses t0 (shifted by 0.37 ms): the same verdicts, the
    issue's time within a sample interval of t0; the c2, c3 crank speed still eq. 33."""
    t = np.arange(-500, 501) * DT + 0.37e-3
    for c2, c3, c4, kind in [(0, 0.5, 0, "jerk"), (0, 0, 0.5, None), (0.5, 0.5, 0, None)]:
        s, s1, s2, s3, _, _ = eq63(c2, c3, c4, t=t)
        issues = dead_point_crossings(PAPER, t, s, s1, s2, s3)
        assert [i.kind for i in issues] == ([kind] if kind else [])
        if kind:
            assert abs(issues[0].time) < DT
    s, s1, s2, s3, _, _ = eq63(0.5, 0.5, 0.0, t=t)
    _, w1, _, _ = input_motion(PAPER, s, s1, s2, s3, start_angle(s[0]))
    i = int(np.argmin(np.abs(t)))
    assert min(w1[i - 1:i + 2]) == pytest.approx(math.sqrt(L / (R * (R + L))), rel=1e-3)
    a = np.where(t < 0, 1.0, 2.0)
    issues = dead_point_crossings(PAPER, t, 2 - a * t ** 2 / 2, -a * t, -a, 0 * t)
    assert [i.kind for i in issues] == ["discontinuous"] and abs(issues[0].time) < DT


@pytest.mark.parametrize("noise", [-1e-17, 1e-17])
def test_round_off_speed_at_the_dead_point(noise: float) -> None:
    """A law whose s_dot at the dead point is round-off of either sign (a spline's knot):
    the crank still passes turning +, theta_dot = eq. 33 there."""
    s, s1, s2, s3, _, _ = eq63(0.5, 0.5, 0.0)
    s1 = s1.copy()
    s1[I0] = noise
    _, w1, _, _ = input_motion(PAPER, s, s1, s2, s3, start_angle(s[0]))
    assert np.all(w1 > 0)
    assert w1[I0] == pytest.approx(math.sqrt(L / (R * (R + L))), rel=1e-12)
    assert dead_point_crossings(PAPER, T, s, s1, s2, s3) == []


def strokes(kind: str, n: int = 2001):
    """Rest-to-rest strokes from the bottom to the top dead centre in 1 s."""
    low, high = PAPER.output_range()
    h = high - low
    tau = np.linspace(0.0, 1.0, n)
    if kind == "poly7":  # s_ddot = s_dddot = 0 at both ends
        c = np.array([0, 0, 0, 0, 35, -84, 70, -20], dtype=float)
    else:  # poly5: s_ddot = 0, s_dddot = 60 h at the ends
        c = np.array([0, 0, 0, 10, -15, 6], dtype=float)
    p = np.polynomial.Polynomial(c)
    return tau, low + h * p(tau), h * p.deriv(1)(tau), h * p.deriv(2)(tau), \
        h * p.deriv(3)(tau)


def test_rest_to_rest_strokes_between_dead_points() -> None:
    """From the bottom dead centre to the top one: the 7th-degree polynomial (C3, s_ddot
    = s_dddot = 0 at the ends) is feasible; the 5th-degree one has s_ddot = 0 and a
    jerk 60 h at both ends (infeasible, C3 rule); the crank from rest to rest."""
    t, s, s1, s2, s3 = strokes("poly7")
    assert dead_point_crossings(PAPER, t, s, s1, s2, s3) == []
    theta, w1, w2, _ = input_motion(PAPER, s, s1, s2, s3, float(PAPER.dead_points()[1]))
    assert w1[0] == 0.0 and w1[-1] == pytest.approx(0.0, abs=1e-9)
    assert abs(theta[-1] - theta[0]) == pytest.approx(math.pi)
    assert np.all(np.isfinite(w2))
    t, s, s1, s2, s3 = strokes("poly5")
    issues = dead_point_crossings(PAPER, t, s, s1, s2, s3)
    h = np.ptp(s)
    assert [(i.kind, i.time) for i in issues] == [("jerk", 0.0), ("jerk", 1.0)]
    assert abs(float(issues[0].message.split("jerk ")[1].split(" ")[0])) == \
        pytest.approx(60 * h, rel=1e-3)


def test_periodic_harmonic_and_rest_at_a_dead_point() -> None:
    """The harmonic back-and-forth over the whole stroke (s_ddot = -+A w^2 at the ends,
    continuous from period to period) is feasible when periodic; arriving at a dead point
    with s_ddot != 0 and resting there breaks the C2 rule at the arrival."""
    low, high = PAPER.output_range()
    mid, amp, w = (low + high) / 2, (high - low) / 2, 2 * np.pi
    t = np.linspace(0.0, 1.0, 1001)
    s, s1 = mid + amp * np.cos(w * t), -amp * w * np.sin(w * t)
    s2, s3 = -amp * w * w * np.cos(w * t), amp * w ** 3 * np.sin(w * t)
    assert dead_point_crossings(PAPER, t, s, s1, s2, s3, periodic=True) == []
    assert [i.kind for i in dead_point_crossings(PAPER, t, s, s1, s2, s3)] == \
        ["discontinuous", "discontinuous"]  # from rest and back to rest at the top
    # a stroke to the top (s_ddot = -1 on arrival at t = 0), then rest there
    t = np.round(np.arange(-500, 1) * DT, 12)
    t = np.concatenate([t, [0.1, 0.2]])
    s = np.where(t < 0, 2 - 0.5 * t ** 2, 2.0)
    s1, s2, s3 = np.where(t < 0, -t, 0.0), np.where(t < 0, -1.0, 0.0), 0 * t
    issues = dead_point_crossings(PAPER, t, s, s1, s2, s3)
    assert [(i.kind, i.time) for i in issues] == [("discontinuous", 0.0)]
