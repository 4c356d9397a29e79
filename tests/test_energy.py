"""Energy at the shaft and the bus, braking, several axes on one bus (issue 16).

Numbers come from closed forms (kinetic energy, integrals of linear powers, the vendor
formula E = J n^2/182) or scipy quadrature in the test, never from the code's output."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sizer.energy import (
    BusAxis,
    axis_power,
    braking,
    capacitor_energy,
    copper_loss,
    shared_bus,
)
from sizer.errors import UserError

J_M, J_L, K, ETA = 2.0e-4, 0.05, 10.0, 0.9  # rotor, load (kg*m^2), ratio, efficiency
W_M = 3000.0 * math.pi / 30.0  # 3000 rpm at the motor
T_A, T_C, T_D, T_W = 0.1, 0.2, 0.05, 0.3


def trapezoid(w=W_M, t_a=T_A, t_c=T_C, t_d=T_D, t_w=T_W, eta=ETA):
    """A rest-to-rest move at constant accelerations: sample times (torque steps as
    repeated times), motor torque (the load's torque through the stage by power flow:
    x/(K eta) accelerating, x eta/K decelerating) and motor speed."""
    alpha_a, alpha_d = w / t_a, -w / t_d  # motor accelerations
    tau_a = (J_M + J_L / (K * K * eta)) * alpha_a
    tau_d = (J_M + eta * J_L / (K * K)) * alpha_d
    e = [0.0, t_a, t_a + t_c, t_a + t_c + t_d, t_a + t_c + t_d + t_w]
    time = np.array([e[0], e[1], e[1], e[2], e[2], e[3], e[3], e[4]])
    torque = np.array([tau_a, tau_a, 0.0, 0.0, tau_d, tau_d, 0.0, 0.0])
    speed = np.array([0.0, w, w, w, w, 0.0, 0.0, 0.0])
    return time, torque, speed, tau_a, tau_d


def test_regenerated_energy_of_a_pure_inertia_stop_is_the_vendor_formula() -> None:
    time, torque, speed, _, _ = trapezoid()
    bus = axis_power(time, torque, speed).bus
    result = braking(time, bus)
    J = J_M + ETA * J_L / K**2  # J_M + J_L with the load's inertia seen braking
    n = 3000.0
    exact = 0.5 * J * W_M**2
    assert result.stops[0] == 1
    assert result.worst_stop_energy[0] == pytest.approx(exact, rel=1e-12)
    assert exact == pytest.approx(J * n * n / (2.0 * (30.0 / math.pi) ** 2), rel=1e-14)
    assert result.worst_stop_energy[0] == pytest.approx(J * n * n / 182.0, rel=3e-3)
    assert result.regenerated_energy[0] == pytest.approx(exact, rel=1e-12)
    # without losses (eta = 1) the whole kinetic energy comes back
    time, torque, speed, _, _ = trapezoid(eta=1.0)
    lossless = braking(time, axis_power(time, torque, speed).bus)
    assert lossless.worst_stop_energy[0] == pytest.approx(
        0.5 * (J_M + J_L / K**2) * W_M**2, rel=1e-12)


def test_copper_losses_are_taken_off_the_returned_energy() -> None:
    time, torque, speed, _, tau_d = trapezoid()
    R, k_t = 1.2, 0.5  # ohm line to line, N*m/A_rms
    power = axis_power(time, torque, speed, torque_constant=k_t, winding_resistance=R)
    loss = 1.5 * R * (tau_d / k_t) ** 2
    returned = -tau_d * W_M  # at the start of the stop, falling linearly to 0
    assert loss < returned
    # the bus power tau_d w(t) + loss is negative until w = loss/|tau_d|
    exact = (returned - loss) ** 2 * T_D / (2.0 * returned)
    result = braking(time, power.bus)
    assert result.worst_stop_energy[0] == pytest.approx(exact, rel=1e-12)
    kinetic = 0.5 * (J_M + ETA * J_L / K**2) * W_M**2
    assert kinetic - loss * T_D < result.worst_stop_energy[0] < kinetic  # vendors' bound
    figures = power.figures()
    tau_a = torque[0]
    copper = 1.5 * R * ((tau_a / k_t) ** 2 * T_A + (tau_d / k_t) ** 2 * T_D)
    assert figures.copper_energy[0] == pytest.approx(copper, rel=1e-12)
    assert np.allclose(copper_loss(torque, k_t, R, "phase"), 2.0 * power.copper[0])
    # one move, a resistance per candidate
    rows = axis_power(time, torque, speed, torque_constant=k_t, winding_resistance=[0.0, R])
    assert np.allclose(rows.figures().copper_energy, [0.0, copper], rtol=1e-12)


def test_a_smooth_stop_against_quadrature() -> None:
    from scipy.integrate import quad
    from scipy.optimize import brentq

    R, k_t, t_d, w = 0.3, 0.3, 0.08, W_M
    J = J_M + ETA * J_L / K**2

    def speed_of(t):
        s = t / t_d
        return w * (1.0 - s + np.sin(2.0 * np.pi * s) / (2.0 * np.pi))

    def torque_of(t):
        return -J * w / t_d * (1.0 - np.cos(2.0 * np.pi * t / t_d))

    def bus_of(t):
        tau = torque_of(t)
        return tau * speed_of(t) + 1.5 * R * (tau / k_t) ** 2

    grid = np.linspace(0.0, t_d, 4001)[1:-1]
    change = np.nonzero(np.diff(np.sign(bus_of(grid))))[0]
    assert change.size == 1  # negative, then the loss overtakes once
    end = brentq(bus_of, grid[change[0]], grid[change[0] + 1], xtol=1e-15)
    exact = -quad(bus_of, 0.0, end, epsabs=0.0, epsrel=1e-13)[0]
    time = np.linspace(0.0, t_d, 20001)
    result = braking(time, axis_power(time, torque_of(time), speed_of(time),
                                      torque_constant=k_t, winding_resistance=R).bus)
    assert result.stops[0] == 1
    assert result.worst_stop_energy[0] == pytest.approx(exact, rel=1e-7)


def test_the_drive_loss_share_acts_by_power_flow() -> None:
    time, torque, speed, tau_a, _ = trapezoid()
    plain = axis_power(time, torque, speed)
    lossy = axis_power(time, torque, speed, drive_loss=0.1)
    assert braking(time, lossy.bus).worst_stop_energy[0] == pytest.approx(
        0.9 * braking(time, plain.bus).worst_stop_energy[0], rel=1e-12)
    assert lossy.figures().peak_bus_power[0] == pytest.approx(1.1 * tau_a * W_M, rel=1e-12)


def test_shaft_figures_of_the_move() -> None:
    time, torque, speed, tau_a, tau_d = trapezoid()
    figures = axis_power(time, torque, speed).figures()
    cycle = T_A + T_C + T_D + T_W
    into = 0.5 * (J_M + J_L / (K * K * ETA)) * W_M**2
    back = 0.5 * (J_M + ETA * J_L / K**2) * W_M**2
    assert figures.cycle_time == pytest.approx(cycle)
    assert figures.peak_motoring_power[0] == pytest.approx(tau_a * W_M, rel=1e-12)
    assert figures.mean_motoring_power[0] == pytest.approx(into / cycle, rel=1e-12)
    assert figures.mean_shaft_power[0] == pytest.approx((into - back) / cycle, rel=1e-12)
    assert figures.peak_regenerative_power[0] == pytest.approx(-tau_d * W_M, rel=1e-12)
    assert figures.net_energy[0] == pytest.approx(into - back, rel=1e-12)


def test_capacitors_take_part_and_the_resistor_the_rest() -> None:
    time, torque, speed, _, tau_d = trapezoid()
    bus = axis_power(time, torque, speed).bus
    stop = 0.5 * (J_M + ETA * J_L / K**2) * W_M**2
    E_c = float(capacitor_energy(470e-6, 390.0, 325.0))
    assert E_c == pytest.approx(0.5 * 470e-6 * (390.0**2 - 325.0**2), rel=1e-15)
    assert E_c < stop
    result = braking(time, bus, absorbable_energy=E_c)
    cycle = T_A + T_C + T_D + T_W
    assert result.capacitor_energy[0] == pytest.approx(E_c, rel=1e-12)
    assert result.resistor_energy[0] == pytest.approx(stop - E_c, rel=1e-12)
    assert result.resistor_continuous_power[0] == pytest.approx((stop - E_c) / cycle,
                                                                rel=1e-12)
    assert result.resistor_peak_power[0] == pytest.approx(-tau_d * W_M, rel=1e-12)
    # a larger capacitor bank takes the whole stop: no resistor
    big = braking(time, bus, absorbable_energy=2.0 * stop)
    assert big.capacitor_energy[0] == pytest.approx(stop, rel=1e-12)
    assert big.resistor_energy[0] == 0.0 and big.resistor_peak_power[0] == 0.0
    # per candidate: one bank for each
    both = braking(time, np.vstack([bus, bus]), absorbable_energy=[E_c, 2.0 * stop])
    assert np.allclose(both.resistor_energy, [stop - E_c, 0.0], rtol=1e-12)


def test_a_stop_through_the_cycle_end_is_one_stop_when_periodic() -> None:
    time, torque, speed, _, _ = trapezoid()
    stop = 0.5 * (J_M + ETA * J_L / K**2) * W_M**2
    bus = axis_power(time, torque, speed).bus[0]
    # start the cycle in the middle of the stop: sample the same periodic power there
    cut = T_A + T_C + 0.4 * T_D
    period = time[-1]
    shifted, total = shared_bus([BusAxis(time, bus, phase=-cut)], period)
    periodic = braking(shifted, total)
    assert periodic.stops[0] == 1
    assert periodic.worst_stop_energy[0] == pytest.approx(stop, rel=1e-12)
    once = braking(shifted, total, periodic=False)
    assert once.stops[0] == 2
    assert once.regenerated_energy[0] == pytest.approx(stop, rel=1e-12)


def _periodic_interp(t, p, phase, period, x):
    """The axis's power at machine times x (a reference for the shared bus)."""
    return np.interp(np.mod(x - phase, period) + t[0], t, p)


def test_two_axes_on_one_bus_add_their_regeneration_only_in_phase() -> None:
    time, torque, speed, _, tau_d = trapezoid()
    bus = axis_power(time, torque, speed).bus[0]
    period = float(time[-1])
    stop = 0.5 * (J_M + ETA * J_L / K**2) * W_M**2
    peak = -tau_d * W_M
    E_c = 0.5 * stop
    same_t, same = shared_bus([BusAxis(time, bus), BusAxis(time, bus)], period)
    in_phase = braking(same_t, same, absorbable_energy=E_c)
    assert in_phase.stops[0] == 1
    assert in_phase.worst_stop_energy[0] == pytest.approx(2.0 * stop, rel=1e-12)
    assert in_phase.resistor_peak_power[0] == pytest.approx(2.0 * peak, rel=1e-12)
    assert in_phase.resistor_energy[0] == pytest.approx(2.0 * stop - E_c, rel=1e-12)
    # the second axis 0.1 s later: its stop falls in the first's dwell, and each one's
    # stop while the other cruises (no torque)
    off_t, off = shared_bus([BusAxis(time, bus), BusAxis(time, bus, phase=0.1)], period)
    apart = braking(off_t, off, absorbable_energy=E_c)
    assert apart.stops[0] == 2
    assert apart.worst_stop_energy[0] == pytest.approx(stop, rel=1e-12)
    assert apart.resistor_peak_power[0] == pytest.approx(peak, rel=1e-12)
    assert apart.resistor_cycle_energy[0] == pytest.approx(2.0 * (stop - E_c), rel=1e-12)
    # the sum is the sum of the interpolants wherever it is read
    x = np.random.default_rng(1).uniform(0.0, period, 200)
    reference = (_periodic_interp(time, bus, 0.0, period, x)
                 + _periodic_interp(time, bus, 0.1, period, x))
    assert np.allclose(np.interp(x, off_t[0], off[0]), reference, rtol=1e-12, atol=1e-9)


def test_an_axis_braking_while_the_other_accelerates() -> None:
    time, torque, speed, tau_a, tau_d = trapezoid()
    bus = axis_power(time, torque, speed).bus[0]
    period = float(time[-1])
    # B starts its acceleration when A starts its stop: B's motoring eats A's braking
    phase = T_A + T_C
    grid, total = shared_bus([BusAxis(time, bus), BusAxis(time, bus, phase=phase)], period)
    # over A's stop [0, T_D] (B's accel is T_A > T_D long):
    #   P(s) = tau_d W (1 - s/T_D) + tau_a W s/T_A, negative while s < s0
    a, b = -tau_d * W_M, tau_a * W_M
    s0 = a / (a / T_D + b / T_A)
    exact = 0.5 * a * s0
    stop = 0.5 * (J_M + ETA * J_L / K**2) * W_M**2  # B's own stop falls in A's dwell
    result = braking(grid, total)
    assert result.stops[0] == 2
    energies = np.sort(result.stop_energy[0][result.stop_energy[0] > 0.0])
    assert energies == pytest.approx([exact, stop], rel=1e-12)


@pytest.mark.parametrize("call,field", [
    (lambda: copper_loss(1.0, 0.5, -1.0), "winding_resistance"),
    (lambda: copper_loss(1.0, 0.0, 1.0), "torque_constant"),
    (lambda: copper_loss(1.0, -0.2, 1.0), "torque_constant"),
    (lambda: copper_loss(1.0, 0.5, 1.0, "delta"), "winding"),
    (lambda: axis_power([0.0, 1.0], [1.0, 1.0], [1.0, 1.0], torque_constant=0.5,
                        winding_resistance=-2.0), "winding_resistance"),
    (lambda: axis_power([0.0, 1.0], [1.0, 1.0], [1.0, 1.0], winding_resistance=2.0),
     "torque_constant"),
    (lambda: axis_power([1.0, 0.0], [1.0, 1.0], [1.0, 1.0]), "time"),
    (lambda: axis_power([0.0, 0.0], [1.0, 1.0], [1.0, 1.0]), "time"),
    (lambda: axis_power([0.0, 1.0], [1.0, 1.0, 1.0], [1.0, 1.0]), "torque"),
    (lambda: axis_power([0.0, 1.0], np.ones((2, 2)), np.ones((3, 2))), "torque"),
    (lambda: axis_power([0.0, 1.0], np.ones((3, 2)), np.ones((2, 2))), "speed"),
    (lambda: axis_power([0.0, 1.0], [1.0, np.nan], [1.0, 1.0]), "torque"),
    (lambda: axis_power([0.0, 1.0], [1.0, 1.0], [1.0, 1.0], drive_loss=1.5), "drive_loss"),
    (lambda: capacitor_energy(1e-3, 300.0, 325.0), "u_max"),
    (lambda: capacitor_energy(-1e-3, 390.0, 325.0), "capacitance"),
    (lambda: braking([0.0, 1.0], [-1.0, -1.0], absorbable_energy=-1.0), "absorbable_energy"),
    (lambda: shared_bus([BusAxis(np.array([0.0, 1.0]), np.array([1.0, 1.0]))], 2.0),
     "axes[0].time"),
    (lambda: shared_bus([], 2.0), "axes"),
    (lambda: shared_bus([BusAxis(np.array([0.0, 1.0]), np.array([1.0, 1.0]))], 0.0),
     "cycle_time"),
])
def test_bad_inputs_name_their_field(call, field) -> None:
    with pytest.raises(UserError) as error:
        call()
    assert error.value.field == field


def test_each_candidate_with_its_own_durations() -> None:
    """Sample times per candidate (rows): each row as on its own."""
    moves = [trapezoid(t_d=0.05, t_w=0.3), trapezoid(t_d=0.1, t_w=0.25),
             trapezoid(w=200.0, t_a=0.2, t_c=0.1, t_d=0.05, t_w=0.3)]
    time = np.vstack([m[0] for m in moves])
    torque = np.vstack([m[1] for m in moves])
    speed = np.vstack([m[2] for m in moves])
    together = axis_power(time, torque, speed, torque_constant=0.5, winding_resistance=1.0)
    stops = braking(time, together.bus, absorbable_energy=5.0)
    figures = together.figures()
    for row, (t, tq, w, _, _) in enumerate(moves):
        alone = axis_power(t, tq, w, torque_constant=0.5, winding_resistance=1.0)
        one = braking(t, alone.bus, absorbable_energy=5.0)
        assert stops.worst_stop_energy[row] == pytest.approx(one.worst_stop_energy[0],
                                                             rel=1e-14)
        assert stops.resistor_continuous_power[row] == pytest.approx(
            one.resistor_continuous_power[0], rel=1e-14)
        assert figures.mean_bus_power[row] == pytest.approx(
            alone.figures().mean_bus_power[0], rel=1e-14)
    # on a shared bus: a second axis (the same moves) with a phase per candidate
    phases = np.array([0.0, 0.1, 0.3])
    grid, total = shared_bus([BusAxis(time, together.bus),
                              BusAxis(time, together.bus, phase=phases)], 0.65)
    assert grid.shape == total.shape and grid.shape[0] == 3
    x = np.random.default_rng(2).uniform(0.0, 0.65, 100)
    for row in range(3):
        reference = (_periodic_interp(time[row], together.bus[row], 0.0, 0.65, x)
                     + _periodic_interp(time[row], together.bus[row], phases[row], 0.65, x))
        assert np.allclose(np.interp(x, grid[row], total[row]), reference, rtol=1e-12,
                           atol=1e-9)
        alone_t, alone_p = shared_bus([BusAxis(time[row], together.bus[row]),
                                       BusAxis(time[row], together.bus[row],
                                               phase=phases[row])], 0.65)
        assert braking(grid[row], total[row]).worst_stop_energy[0] == pytest.approx(
            braking(alone_t, alone_p).worst_stop_energy[0], rel=1e-12)


@pytest.mark.parametrize("side", ["left", "right"])
def test_the_counts_before_are_searchsorteds_for_one_row_and_several(side) -> None:
    """sizer.energy.bus._count_before: one row (a machine's own cycle) by searchsorted,
    several by one merge sort: both numpy's searchsorted row by row, ties included."""
    from sizer.energy.bus import _count_before

    rng = np.random.default_rng(3)
    t = np.sort(rng.choice(np.linspace(0.0, 1.0, 41), size=(3, 30)), axis=1)
    x = np.concatenate((rng.uniform(-0.1, 1.1, (3, 20)), t[:, ::3]), axis=1)  # ties
    expected = np.array([np.searchsorted(t[r], x[r], side=side) for r in range(3)])
    assert np.array_equal(_count_before(t, x, side), expected)
    for r in range(3):
        assert np.array_equal(_count_before(t[r:r + 1], x[r:r + 1], side), expected[r:r + 1])
