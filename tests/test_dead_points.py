"""The paper's general dead-point results (seed 003 eqs. 22-27, 48-50, 60) on its
slider-crank (eqs. 28-32): the closed forms (33-34, 51-54, 61-62) and the numeric
inverse kinematics just beside the dead point (mpmath, 50 digits, the constraint
equations solved with findroot and differentiated in time)."""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest

from sizer.mechanics.linkages import dead_points as dp
from sizer.mechanics.linkages.slider_crank import SliderCrank

CASES = [(0.75, 1.25), (0.1, 0.35), (1.0, 1.5), (0.02, 0.2)]


def slider_crank_arrays(r: float, rod: float, q1: float, q2: float) -> dict:
    """phi_q^d, phi_q^i and their partial derivatives for eq. 28 (by hand)."""
    c1, s1, c2, s2 = math.cos(q1), math.sin(q1), math.cos(q2), math.sin(q2)
    phi_d = np.array([[r * c1, -rod * c2], [r * s1, rod * s2]])
    dphi_d = np.array([[[-r * s1, 0.0], [r * c1, 0.0]],
                       [[0.0, rod * s2], [0.0, rod * c2]]])
    d2 = np.zeros((2, 2, 2, 2))
    d2[0, 0] = [[-r * c1, 0.0], [-r * s1, 0.0]]
    d2[1, 1] = [[0.0, rod * c2], [0.0, -rod * s2]]
    return dict(phi_d=phi_d, phi_i=np.array([0.0, 1.0]), dphi_d=dphi_d, d2phi_d=d2,
                dphi_i_d=np.zeros((2, 2)), dphi_d_i=np.zeros((2, 2)))


def general(arrays: dict) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    m = dp.m_vector(arrays["phi_d"], arrays["phi_i"])
    k = dp.k_vector(arrays["phi_d"], arrays["dphi_d"])
    s = dp.s_matrix(arrays["phi_d"], arrays["dphi_d"], m, k)
    r = dp.r_vector(arrays["phi_d"], arrays["phi_i"], arrays["dphi_d"], arrays["d2phi_d"],
                    arrays["dphi_i_d"], arrays["dphi_d_i"], m, k)
    return m, k, s, r


@pytest.mark.parametrize(("r", "rod"), CASES)
def test_slider_crank_m_k_s_r(r: float, rod: float) -> None:
    m, k, s, rr = general(slider_crank_arrays(r, rod, 0.0, 0.0))
    np.testing.assert_allclose(m, [rod, r], rtol=1e-14)  # eq. 31
    np.testing.assert_allclose(k, [r * rod, r * rod], rtol=1e-14)  # eq. 32
    np.testing.assert_allclose(s, [[r * r * rod + 3 * r * rod ** 2, 2 * r * rod ** 2],
                                   [2 * r * r * rod, 3 * r * r * rod + r * rod ** 2]],
                               rtol=1e-14)  # eq. 51
    np.testing.assert_allclose(rr, [0.0, 0.0], atol=1e-14)  # eq. 52


@pytest.mark.parametrize(("r", "rod"), CASES)
@pytest.mark.parametrize(("acc", "jerk"), [(-1.0, 0.0), (-3.5, 2.0), (-0.2, -7.0)])
def test_slider_crank_closed_forms(r: float, rod: float, acc: float, jerk: float) -> None:
    m, k, s, rr = general(slider_crank_arrays(r, rod, 0.0, 0.0))
    v = dp.velocities(m, k, acc)
    assert v[0] == pytest.approx(math.sqrt(-rod * acc / (r * (r + rod))), rel=1e-13)  # 33
    assert v[1] == pytest.approx(math.sqrt(-r * acc / (rod * (r + rod))), rel=1e-13)  # 34
    a = dp.accelerations(s, rr, m, k, acc, jerk)
    root = math.sqrt(-acc * r * rod * (r + rod))
    # eqs. 53-54 with the jerk in the numerator (errata)
    assert a[0] == pytest.approx(-rod * jerk / (3 * root), rel=1e-12, abs=1e-14)
    assert a[1] == pytest.approx(-r * jerk / (3 * root), rel=1e-12, abs=1e-14)
    snap = 12.0 * acc  # any negative fourth derivative
    a0 = dp.accelerations_at_rest(slider_crank_arrays(r, rod, 0, 0)["phi_d"],
                                  slider_crank_arrays(r, rod, 0, 0)["dphi_d"], m, k, snap)
    assert a0[0] == pytest.approx(math.sqrt(-rod * snap / (3 * r * (r + rod))), rel=1e-13)  # 61
    assert a0[1] == pytest.approx(math.sqrt(-r * snap / (3 * rod * (r + rod))), rel=1e-13)  # 62


def test_wrong_sign_is_refused() -> None:
    m, k, _, _ = general(slider_crank_arrays(0.75, 1.25, 0.0, 0.0))
    with pytest.raises(ValueError):
        dp.velocities(m, k, +1.0)  # at the top dead centre the slider must decelerate


def test_one_dof_form() -> None:
    """n = 1, phi = s - f(theta): m = 1, k = -f'', S = -3 f'', R = -f'''/f''."""
    f2, f3 = -2.5, 0.7
    arrays = dict(phi_d=np.array([[0.0]]), phi_i=np.array([1.0]),
                  dphi_d=np.array([[[-f2]]]), d2phi_d=np.array([[[[-f3]]]]),
                  dphi_i_d=np.zeros((1, 1)), dphi_d_i=np.zeros((1, 1)))
    m, k, s, r = general(arrays)
    assert (m[0], k[0], s[0, 0], r[0]) == pytest.approx((1.0, -f2, -3 * f2, -f3 / f2))
    acc, jerk = -1.3, 0.4
    theta1 = math.sqrt(acc / f2)
    assert dp.velocities(m, k, acc)[0] == pytest.approx(theta1)
    assert dp.accelerations(s, r, m, k, acc, jerk)[0] == pytest.approx(
        (jerk - f3 * theta1 ** 3) / (3 * f2 * theta1))


# -- numeric inverse kinematics beside the dead point ---------------------------------

def numeric_dependent(r: float, rod: float, e: float, law, t: mp.mpf, guess) -> mp.matrix:
    """q1, q2 solving eq. 28 (slider line at height e) for q3 = law(t), near ``guess``."""
    def eqs(q1, q2):
        return [r * mp.sin(q1) - rod * mp.sin(q2) - e,
                -r * mp.cos(q1) - rod * mp.cos(q2) + law(t)]
    return mp.findroot(eqs, guess)


def numeric_limits(r: float, rod: float, e: float, coefficients, side: int):
    """q_dot^d, q_ddot^d at t = side * 1e-12 (the crank turning +) for q3 = top -
    c2 t^2 - c3 t^3 (top: the dead point's, in 60 digits), by differentiating the
    solved coordinates in time (mpmath.diff)."""
    mp.mp.dps = 60
    r, rod, e = mp.mpf(r), mp.mpf(rod), mp.mpf(e)
    alpha = mp.asin(e / (r + rod))
    top = (r + rod) * mp.cos(alpha)
    c2, c3 = (mp.mpf(c) for c in coefficients)

    def law(t):
        return top - c2 * t ** 2 - c3 * t ** 3

    def q(t, j):
        # first-order guess for the passing branch: q1 = alpha + delta, q2 = -alpha - ...
        s2 = -(r * (r + rod) / rod)  # d^2 s / dtheta^2 at the zero-offset top dead centre
        gap = max(top - law(t), mp.mpf(0))
        delta = (1 if t > 0 else -1) * mp.sqrt(2 * gap / -s2)
        sol = numeric_dependent(r, rod, e, law, t, [alpha + delta, -alpha - r * delta / rod])
        return sol[j]

    t0 = side * mp.mpf("1e-12")
    out = []
    for j in range(2):
        out.append((float(mp.diff(lambda t, j=j: q(t, j), t0, 1)),
                    float(mp.diff(lambda t, j=j: q(t, j), t0, 2))))
    mp.mp.dps = 15
    return out


@pytest.mark.parametrize(("r", "rod", "e"), [(0.75, 1.25, 0.0), (0.1, 0.35, 0.0),
                                             (0.75, 1.25, 0.3), (0.1, 0.35, -0.05)])
@pytest.mark.parametrize("side", [-1, 1])
def test_against_numeric_inverse_kinematics(r: float, rod: float, e: float,
                                            side: int) -> None:
    """q3 = top - 0.5 t^2 - 0.4 t^3 through the top dead centre at t = 0: eqs. 27 and 49
    (with the offset R != 0) against the solved constraint equations at t = +-1e-12."""
    alpha = math.asin(e / (r + rod))
    c2, c3 = 0.5, 0.4
    m, k, s, rr = general(slider_crank_arrays(r, rod, alpha, -alpha))
    acc, jerk = -2 * c2, -6 * c3
    v = dp.velocities(m, k, acc)
    a = dp.accelerations(s, rr, m, k, acc, jerk)
    numeric = numeric_limits(r, rod, e, (c2, c3), side)
    for j in range(2):
        assert numeric[j][0] == pytest.approx(v[j], rel=1e-8)
        assert numeric[j][1] == pytest.approx(a[j], rel=1e-7)
    if e != 0.0:
        assert np.max(np.abs(rr)) > 1e-3  # the offset case exercises R (eq. 48)
    # the same with the 1-DOF form of the crank angle of sizer's SliderCrank
    link = SliderCrank(r, rod, e)
    theta = np.array([alpha])
    f2, f3 = float(link.output(theta, 2)[0]), float(link.output(theta, 3)[0])
    theta1 = math.sqrt(acc / f2)
    assert theta1 == pytest.approx(v[0], rel=1e-12)
    assert (jerk - f3 * theta1 ** 3) / (3 * f2 * theta1) == pytest.approx(a[0], rel=1e-10)


def test_at_rest_against_numeric() -> None:
    """q3 = 2 - 0.5 t^4 (Table 1, slider-crank, c4 = 0.5): the crank at rest at t0 with
    the acceleration of eq. 61; beside the dead point the solved q1 has q1_ddot -> that
    value, of opposite signs either side when the crank keeps turning."""
    r, rod = 0.75, 1.25

    def law(t):
        return mp.mpf(2) - mp.mpf("0.5") * t ** 4

    snap = -12.0
    closed = math.sqrt(-rod * snap / (3 * r * (r + rod)))
    for side in (-1, 1):
        mp.mp.dps = 60

        def q1(t):
            gap = max(2 - law(t), mp.mpf(0))
            delta = (1 if t > 0 else -1) * mp.sqrt(2 * gap * rod / (r * (r + rod)))
            return numeric_dependent(r, rod, 0.0, law, t, [delta, -r * delta / rod])[0]

        acc = float(mp.diff(q1, side * mp.mpf("1e-9"), 2))
        mp.mp.dps = 15
        assert acc == pytest.approx(side * closed, rel=1e-6)


def test_four_bar_against_numeric_inverse_kinematics() -> None:
    """A four-bar with the paper's link lengths (l1 crank 0.075, l2 coupler 0.175, l3
    rocker 0.1, l4 ground 0.175 m): l1 e^{i q1} + l2 e^{i q2} = l4 + l3 e^{i q3}, the
    rocker q3 at a dead point when crank and coupler are in line (q1 = q2). Eqs. 27 and
    49 (R from eq. 48 non-zero here) against the solved loop equations at t = +-1e-12."""
    l1, l2, l3, l4 = 0.075, 0.175, 0.1, 0.175
    q3 = math.acos(((l1 + l2) ** 2 - l4 ** 2 - l3 ** 2) / (2 * l4 * l3))
    alpha = math.atan2(l3 * math.sin(q3), l4 + l3 * math.cos(q3))
    c1 = math.cos(alpha)
    s1 = math.sin(alpha)
    arrays = dict(
        phi_d=np.array([[-l1 * s1, -l2 * s1], [l1 * c1, l2 * c1]]),
        phi_i=np.array([l3 * math.sin(q3), -l3 * math.cos(q3)]),
        dphi_d=np.array([[[-l1 * c1, 0.0], [-l1 * s1, 0.0]],
                         [[0.0, -l2 * c1], [0.0, -l2 * s1]]]),
        d2phi_d=np.zeros((2, 2, 2, 2)), dphi_i_d=np.zeros((2, 2)), dphi_d_i=np.zeros((2, 2)))
    arrays["d2phi_d"][0, 0] = [[l1 * s1, 0.0], [-l1 * c1, 0.0]]
    arrays["d2phi_d"][1, 1] = [[0.0, l2 * s1], [0.0, -l2 * c1]]
    m, k, s, rr = general(arrays)
    assert np.max(np.abs(rr)) > 1e-6
    acc = -math.copysign(0.8, float(np.dot(k, m)))  # the sign the geometry needs
    jerk = 1.7
    v = dp.velocities(m, k, acc)
    a = dp.accelerations(s, rr, m, k, acc, jerk)
    mp.mp.dps = 60
    q3_dead = mp.acos(((mp.mpf(l1) + l2) ** 2 - mp.mpf(l4) ** 2 - mp.mpf(l3) ** 2)
                      / (2 * mp.mpf(l4) * l3))
    alpha_mp = mp.atan2(l3 * mp.sin(q3_dead), l4 + l3 * mp.cos(q3_dead))

    def solved(t, j):
        law = q3_dead + acc * t ** 2 / 2 + jerk * t ** 3 / 6

        def eqs(x1, x2):
            return [l1 * mp.cos(x1) + l2 * mp.cos(x2) - l4 - l3 * mp.cos(law),
                    l1 * mp.sin(x1) + l2 * mp.sin(x2) - l3 * mp.sin(law)]
        guess = [alpha_mp + v[0] * t, alpha_mp + v[1] * t]  # the branch passing +
        return mp.findroot(eqs, guess)[j]

    for side in (-1, 1):
        t0 = side * mp.mpf("1e-12")
        for j in range(2):
            speed = float(mp.diff(lambda t, j=j: solved(t, j), t0, 1))
            accel = float(mp.diff(lambda t, j=j: solved(t, j), t0, 2))
            assert speed == pytest.approx(v[j], rel=1e-8)
            assert accel == pytest.approx(a[j], rel=1e-7)
    mp.mp.dps = 15
