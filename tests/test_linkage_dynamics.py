"""The torque at the crank of a linkage (Lagrange): energy balance over moves through dead
points, the d(J_eq)/dtheta term alone at constant speed, the scotch-yoke limit of a long
rod, a constant-ratio rocker, time scaling and bad input.

The reference numbers come from the slider-crank's closed forms written here (not from
sizer's geometry) and from energy: the motor's work equals the change of kinetic energy
plus the work against the load, friction and damping.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from functools import partial

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from sizer.errors import UserError
from sizer.mechanics.linkages.dynamics import LinkageDynamics, LinkageMasses
from sizer.mechanics.linkages.slider_crank import SliderCrank

MASSES = LinkageMasses(crank_inertia=0.03, output_inertia=2.5, link_mass_at_crank=0.8,
                       link_mass_at_output=0.6, load=40.0, friction=15.0, damping=3.0)


def slider(theta, r, rod, e):
    """s and ds/dtheta of the offset slider-crank, written independently of sizer."""
    u = r * np.sin(theta) - e
    w = np.sqrt(rod * rod - u * u)
    return r * np.cos(theta) + w, -r * np.sin(theta) - u * r * np.cos(theta) / w


def cycloidal(t, T, start=0.3, end=2.8):
    """A cycloidal crank motion (book eq. 3.4) from ``start`` to ``end`` rad in T."""
    h, x = end - start, 2.0 * math.pi * t / T
    return (start + h * (t / T - np.sin(x) / (2.0 * math.pi)), h / T * (1.0 - np.cos(x)),
            2.0 * math.pi * h / T**2 * np.sin(x))


def turn_and_sine(t, T, a=0.8):
    """A full turn at constant speed plus a half sine: theta(T) = 2 pi, end speeds differ."""
    x = math.pi * t / T
    return (2.0 * math.pi * t / T + a * np.sin(x),
            (2.0 * math.pi + a * math.pi * np.cos(x)) / T,
            -a * (math.pi / T) ** 2 * np.sin(x))


GEOMETRIES = {"paper": (0.75, 1.25, 0.0), "offset": (0.1, 0.25, -0.1)}
"""(r, l, e): the paper's slider-crank (dead points 0 and pi) and an offset one whose
bottom dead centre is at pi - atan(0.1 / sqrt(0.0125)) = 2.41 rad."""
MOVES = {
    # through the offset one's bottom dead centre (2.41 rad), rest to rest
    ("offset", "cycloidal 0.3..2.8 rad"): (partial(cycloidal, start=0.3, end=2.8), 0.4),
    # away from the paper's top dead centre (0) and through its bottom one (pi)
    ("paper", "cycloidal 0..3.6 rad"): (partial(cycloidal, start=0.0, end=3.6), 0.4),
    ("offset", "turn + sine"): (turn_and_sine, 0.5),
    ("paper", "turn + sine"): (turn_and_sine, 0.5),
}


@pytest.mark.parametrize(("geometry", "law_name"), MOVES)
def test_motor_work_is_kinetic_energy_plus_losses(geometry: str, law_name: str) -> None:
    r, rod, e = GEOMETRIES[geometry]
    law, T = MOVES[geometry, law_name]
    m = MASSES
    dynamics = LinkageDynamics(SliderCrank(r, rod, e), m)

    def ratio(t):
        return slider(law(t, T)[0], r, rod, e)[1]

    def s_dot(t):
        return ratio(t) * law(t, T)[1]

    # the dead points passed (ds/dtheta = 0): the kinks of |friction * s_dot|
    grid = np.linspace(0.0, T, 2001)
    v = np.array([ratio(t) for t in grid])
    kinks = [brentq(ratio, grid[i], grid[i + 1], xtol=1e-15)
             for i in range(len(grid) - 1) if v[i] * v[i + 1] < 0.0]
    kinks += [grid[i] for i in range(len(grid)) if abs(v[i]) < 1e-15]
    assert kinks, "the motion must pass a dead point"
    bounds = sorted({0.0, T, *kinks})
    pieces = list(itertools.pairwise(bounds))

    def power(t):
        theta, speed, acceleration = law(t, T)
        return float(dynamics.crank_torque(theta, speed, acceleration)) * speed

    work = sum(quad(power, a, b, epsabs=0.0, epsrel=1e-12, limit=200)[0] for a, b in pieces)

    def kinetic(t):
        speed = law(t, T)[1]
        crank = m.crank_inertia + m.link_mass_at_crank * r * r
        return 0.5 * crank * speed**2 + 0.5 * (m.output_inertia + m.link_mass_at_output) \
            * s_dot(t) ** 2

    position = [slider(law(t, T)[0], r, rod, e)[0] for t in bounds]
    load_work = m.load * (position[-1] - position[0])
    friction_work = m.friction * sum(abs(b - a) for a, b in itertools.pairwise(position))
    damping_work = sum(quad(lambda t: m.damping * s_dot(t) ** 2, a, b, epsabs=0.0,
                            epsrel=1e-12, limit=200)[0] for a, b in pieces)
    change = kinetic(T) - kinetic(0.0)
    for t in (0.0, 0.3 * T, T):
        theta, speed, _ = law(t, T)
        assert float(dynamics.kinetic_energy(theta, speed)) == pytest.approx(kinetic(t),
                                                                            rel=1e-13)
    expected = change + load_work + friction_work + damping_work
    scale = abs(change) + abs(load_work) + friction_work + damping_work
    assert friction_work > 0.0 and damping_work > 0.0
    assert work == pytest.approx(expected, rel=0.0, abs=1e-9 * scale)
    if law_name == "turn + sine":
        assert abs(change) > 0.1 * scale  # the kinetic energy does change


def test_constant_speed_torque_is_the_inertia_derivative_term() -> None:
    """At constant crank speed omega, tau = (1/2) dJ/dtheta omega^2 = M s' s'' omega^2;
    the crank's inertia and the pin's mass add nothing."""
    r, rod, M, omega = 0.75, 1.25, 3.0, 30.0
    theta = np.linspace(-math.pi, math.pi, 721)
    masses = LinkageMasses(crank_inertia=0.5, output_inertia=M, link_mass_at_crank=2.0)
    tau = LinkageDynamics(SliderCrank(r, rod), masses).crank_torque(theta, omega, 0.0)
    w = np.sqrt(rod**2 - (r * np.sin(theta)) ** 2)
    s1 = -r * np.sin(theta) - r * r * np.sin(theta) * np.cos(theta) / w
    s2 = (-r * np.cos(theta) - r * r * np.cos(2.0 * theta) / w
          - r**4 * np.sin(theta) ** 2 * np.cos(theta) ** 2 / w**3)
    expected = M * s1 * s2 * omega**2
    np.testing.assert_allclose(tau, expected, rtol=0.0, atol=1e-12 * np.max(np.abs(expected)))
    assert np.max(np.abs(tau)) > 0.1 * M * r * r * omega**2
    # zero at the dead points (s' = 0) and where s'' = 0
    dead = LinkageDynamics(SliderCrank(r, rod), masses).crank_torque(
        np.array([0.0, math.pi]), omega, 0.0)
    np.testing.assert_allclose(dead, 0.0, atol=1e-12 * M * r * r * omega**2)


def test_long_rod_approaches_the_scotch_yoke() -> None:
    """l >> r: s' -> -r sin theta, so tau -> M r^2 (sin^2 theta theta_ddot +
    sin theta cos theta theta_dot^2), with an error of order r/l."""
    r, M = 0.05, 4.0
    rng = np.random.default_rng(14)
    theta = rng.uniform(-math.pi, math.pi, 200)
    speed, acceleration = rng.uniform(-40.0, 40.0, 200), rng.uniform(-900.0, 900.0, 200)
    yoke = M * r * r * (np.sin(theta) ** 2 * acceleration
                        + np.sin(theta) * np.cos(theta) * speed**2)
    scale = M * r * r * (np.max(np.abs(acceleration)) + np.max(speed**2))
    errors = []
    for ratio in (1e3, 1e4, 1e5):
        dynamics = LinkageDynamics(SliderCrank(r, ratio * r), LinkageMasses(output_inertia=M))
        errors.append(np.max(np.abs(dynamics.crank_torque(theta, speed, acceleration) - yoke)))
    assert errors[-1] < 1e-4 * scale
    assert 5.0 < errors[0] / errors[1] < 20.0 and 5.0 < errors[1] / errors[2] < 20.0


@dataclass(frozen=True)
class ConstantRocker:
    """A rocker turning k times the crank (s = k theta): a stand-in with a constant ratio."""

    k: float
    output_linear: bool = False

    def output(self, theta, order=0):
        theta = np.asarray(theta, dtype=float)
        return {0: self.k * theta, 1: np.full_like(theta, self.k)}.get(
            order, np.zeros_like(theta))


def test_rocker_masses_and_loads_with_a_constant_ratio() -> None:
    """J = J_c + m_pin r^2 + (I + m_out l^2) k^2 constant; tau = J theta_ddot
    + k (T_load + f sign(k theta_dot) + c k theta_dot)."""
    k, r, lr = 0.4, 0.06, 0.12
    m = LinkageMasses(crank_inertia=0.01, output_inertia=0.2, link_mass_at_crank=0.5,
                      link_mass_at_output=0.7, load=-3.0, friction=1.5, damping=0.25)
    dynamics = LinkageDynamics(ConstantRocker(k), m, crank_radius=r, rocker_length=lr)
    J = 0.01 + 0.5 * r * r + (0.2 + 0.7 * lr * lr) * k * k
    theta, speed, acceleration = np.array([0.3, 1.0, 2.0]), np.array([5.0, 0.0, -2.0]), \
        np.array([100.0, -50.0, 7.0])
    expected = J * acceleration + k * (-3.0 + 1.5 * np.sign(speed) + 0.25 * k * speed)
    np.testing.assert_allclose(dynamics.crank_torque(theta, speed, acceleration), expected,
                               rtol=1e-14)
    np.testing.assert_allclose(dynamics.inertia(theta), J, rtol=1e-15)
    np.testing.assert_allclose(dynamics.inertia_derivative(theta), 0.0, atol=0.0)


def test_motor_torque_broadcasts_over_candidates_and_a_ratio() -> None:
    """J_m k theta_ddot + tau/k: the power balance tau_m k theta_dot = J_m (k theta_ddot)
    (k theta_dot) + tau theta_dot, one row per candidate."""
    dynamics = LinkageDynamics(SliderCrank(0.1, 0.3, 0.02), MASSES)
    theta = np.linspace(0.0, 2.0 * math.pi, 50)
    speed, acceleration = 10.0 + np.sin(theta), 200.0 * np.cos(theta)
    J_m, k = np.array([1e-4, 5e-4, 2e-3]), np.array([1.0, 5.0, 10.0])
    tau = dynamics.crank_torque(theta, speed, acceleration)
    motor = dynamics.motor_torque(theta, speed, acceleration, J_m, k)
    assert motor.shape == (3, 50)
    for i in range(3):
        power = J_m[i] * k[i] * acceleration * k[i] * speed + tau * speed
        np.testing.assert_allclose(motor[i] * k[i] * speed, power, rtol=1e-13)


def test_time_scaling_parts() -> None:
    """tau(u; T) = A/T^2 + D/T + B equals the torque of theta(t) = theta_N(t/T) at each T."""
    dynamics = LinkageDynamics(SliderCrank(0.1, 0.25, -0.1), MASSES)
    u = np.linspace(0.0, 1.0, 101)
    theta, prime, second = cycloidal(u, 1.0)
    parts = dynamics.time_scaling_parts(theta, prime, second)
    durations, J_m = np.array([0.05, 0.4, 3.0]), np.array([1e-3, 0.0, 0.02])
    scaled = parts.crank_torque(durations)
    motor = parts.motor_torque(durations, J_m)
    assert scaled.shape == motor.shape == (3, 101)
    for i, T in enumerate(durations):
        direct = dynamics.crank_torque(theta, prime / T, second / T**2)
        np.testing.assert_allclose(scaled[i], direct, rtol=1e-13, atol=1e-12)
        np.testing.assert_allclose(motor[i], direct + J_m[i] * second / T**2, rtol=1e-13,
                                   atol=1e-12)
    # B is what is left for a very slow move: the load and friction through s'
    s1 = slider(theta, 0.1, 0.25, -0.1)[1]
    np.testing.assert_allclose(parts.steady, s1 * (40.0 + 15.0 * np.sign(s1 * prime)),
                               rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize(("kwargs", "field"), [
    ({"output_inertia": -1.0}, "output_inertia"),
    ({"crank_inertia": -1e-6}, "crank_inertia"),
    ({"link_mass_at_crank": -0.1}, "link_mass_at_crank"),
    ({"link_mass_at_output": float("nan")}, "link_mass_at_output"),
    ({"friction": -2.0}, "friction"),
    ({"damping": float("inf")}, "damping"),
    ({"load": float("nan")}, "load"),
    ({"load": "heavy"}, "load"),
    ({"output_inertia": True}, "output_inertia"),
])
def test_bad_masses(kwargs: dict, field: str) -> None:
    with pytest.raises(UserError) as error:
        LinkageMasses(**kwargs)
    assert error.value.field == field


def test_bad_geometry_for_the_masses() -> None:
    with pytest.raises(UserError) as error:
        LinkageDynamics(ConstantRocker(0.5), LinkageMasses(link_mass_at_output=1.0))
    assert error.value.field == "rocker_length"
    with pytest.raises(UserError) as error:
        LinkageDynamics(ConstantRocker(0.5), LinkageMasses(link_mass_at_crank=1.0))
    assert error.value.field == "crank_radius"
    with pytest.raises(UserError) as error:
        LinkageDynamics(ConstantRocker(0.5), LinkageMasses(), crank_radius=-0.1)
    assert error.value.field == "crank_radius"
    with pytest.raises(UserError) as error:
        LinkageDynamics(ConstantRocker(0.5), LinkageMasses(), rocker_length=float("nan"))
    assert error.value.field == "rocker_length"
    # the slider-crank gives its crank radius itself
    dynamics = LinkageDynamics(SliderCrank(0.1, 0.3), LinkageMasses(link_mass_at_crank=2.0))
    assert dynamics.crank_side_inertia == pytest.approx(2.0 * 0.01, rel=1e-15)
