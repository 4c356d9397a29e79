"""Winding heat models (issue 16): first-order and two-node, one-off and periodic.

References: closed forms of the first-order response to steps, the energy balance of the
periodic steady state, and scipy.integrate.solve_ivp on the physical ODEs in the test."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sizer.energy import copper_loss
from sizer.errors import UserError
from sizer.thermal import (
    applied_check,
    first_order,
    thermal_resistance,
    thermal_verdict,
    two_node,
    winding_check,
)

K_T, R_W = 0.6, 2.0  # N*m/A_rms, ohm line to line
TAU_C, RISE = 2.0, 100.0  # continuous torque (N*m), allowed rise (K)


def _loss(torque):
    return 1.5 * R_W * (np.asarray(torque, dtype=float) / K_T) ** 2


R_TH = RISE / float(_loss(TAU_C))


def steps(levels, durations):
    """Piecewise-constant samples: times with a repeated time at each step."""
    edges = np.concatenate([[0.0], np.cumsum(durations)])
    time = np.repeat(edges, 2)[1:-1]
    return time, np.repeat(np.asarray(levels, dtype=float), 2)


def test_thermal_resistance_from_the_continuous_torque() -> None:
    assert float(thermal_resistance(RISE, copper_loss(TAU_C, K_T, R_W))) == pytest.approx(
        RISE / (1.5 * R_W * (TAU_C / K_T) ** 2), rel=1e-15)


@pytest.mark.parametrize("tau_th", [1e-6, 0.05, 1.0, 30.0, 2000.0, 1e9])
def test_periodic_mean_is_the_rms_torque_loss(tau_th) -> None:
    torques = [5.0, 0.4, -3.0, 0.1]  # accelerate, run, brake, hold
    durations = [0.1, 0.25, 0.08, 0.37]
    time, torque = steps(torques, durations)
    rms = math.sqrt(sum(t * t * d for t, d in zip(torques, durations, strict=True))
                    / sum(durations))
    exact = R_TH * 1.5 * R_W * (rms / K_T) ** 2
    periodic = first_order(R_TH, tau_th).periodic(time, _loss(torque))
    assert periodic.mean[0] == pytest.approx(exact, rel=1e-11)
    assert periodic.rise[0, -1] == pytest.approx(periodic.rise[0, 0], rel=1e-11)
    assert periodic.peak[0] >= periodic.mean[0]
    # the rise the RMS torque implies, as the verdict has it, is the same number
    verdict = thermal_verdict(sum(durations), tau_th, rms, TAU_C, periodic.peak, RISE)
    assert verdict.rms_rise[0] == pytest.approx(exact, rel=1e-12)
    # two nodes: the mean is the total resistance times the mean loss
    model = two_node(0.4 * R_TH, 0.6 * R_TH, tau_th / 20.0, tau_th)
    assert model.thermal_resistance[0] == pytest.approx(R_TH, rel=1e-12)
    assert model.periodic(time, _loss(torque)).mean[0] == pytest.approx(exact, rel=1e-10)


def test_ripple_shrinks_with_the_cycle() -> None:
    tau, share, P = 10.0, 0.3, 50.0
    periods = np.array([40.0, 20.0, 10.0, 3.0, 1.0, 0.3, 0.1, 0.01])
    model = first_order(R_TH, tau)
    found = []
    for T in periods:
        time, loss = steps([P, 0.0], [share * T, (1.0 - share) * T])
        response = model.periodic(time, loss)
        # the square wave's steady state in closed form
        top = R_TH * P * -math.expm1(-share * T / tau) / -math.expm1(-T / tau)
        bottom = top * math.exp(-(1.0 - share) * T / tau)
        assert response.peak[0] == pytest.approx(top, rel=1e-11)
        assert response.rise[0].min() == pytest.approx(bottom, rel=1e-11)
        found.append(response.peak[0] - response.rise[0].min())
    ripples = np.array(found)
    assert np.all(np.diff(ripples) < 0.0)
    # for short cycles: ripple ~ R_th P share (1 - share) T / tau
    slope = R_TH * P * share * (1.0 - share) / tau
    assert ripples[-1] / periods[-1] == pytest.approx(slope, rel=1e-3)
    assert ripples[-2] / periods[-2] == pytest.approx(slope, rel=1e-2)


def _first_failures(tau_th, moves, dwell, torque):
    """The shortest one-off move (from cold, then a dwell) failing each check."""
    model = first_order(R_TH, tau_th)
    thermal = rms = None
    for t_m in moves:
        time, tq = steps([torque, 0.0], [t_m, dwell])
        peak = model.response(time, _loss(tq)).peak[0]
        tau_rms = torque * math.sqrt(t_m / (t_m + dwell))
        if thermal is None and peak > RISE:
            thermal = t_m
        if rms is None and tau_rms > TAU_C:
            rms = t_m
    return thermal, rms


def test_a_long_move_fails_by_heat_first_with_a_short_time_constant() -> None:
    torque, dwell = 2.0 * TAU_C, 3.0  # the RMS check fails beyond t_m = dwell/3 = 1 s
    rms_limit = dwell / 3.0
    coarse = np.arange(0.02, 40.0, 0.25)
    for tau_th, heat_first in ((0.5, True), (100.0, False)):
        # from cold: rise 4 dT_max (1 - exp(-t/tau)) passes dT_max at tau ln(4/3)
        heat_limit = tau_th * math.log(4.0 / 3.0)
        near = np.array([heat_limit - 1e-3, heat_limit + 1e-3, rms_limit - 1e-3,
                         rms_limit + 1e-3])
        moves = np.sort(np.concatenate([coarse, near]))
        thermal, rms = _first_failures(tau_th, moves, dwell, torque)
        assert rms == pytest.approx(rms_limit + 1e-3, abs=1e-12)
        assert thermal == pytest.approx(heat_limit + 1e-3, abs=1e-12)
        assert bool(thermal < rms) == heat_first
    # which check applies: the cycle against tau_th / 10
    cycle = 1.0 + dwell
    assert applied_check(cycle, 0.5)[()] == "thermal"
    assert applied_check(cycle, 100.0)[()] == "rms"
    verdict = thermal_verdict(cycle, [0.5, 100.0], torque * math.sqrt(1.0 / cycle), TAU_C,
                              [4.0 * RISE * -math.expm1(-1.0 / 0.5), 50.0], RISE)
    assert list(verdict.applied) == ["thermal", "rms"]
    assert verdict.margin[0] == pytest.approx(1.0 - 4.0 * -math.expm1(-2.0), rel=1e-12)
    assert verdict.margin[1] == pytest.approx(1.0 - 4.0 / cycle, rel=1e-12)
    assert list(verdict.feasible) == [False, True]


def _profile():
    """An arbitrary loss: linear pieces with steps (repeated times) and a ramp down."""
    time = np.array([0.0, 0.3, 0.3, 1.1, 1.7, 1.7, 2.6, 3.2, 4.0])
    loss = np.array([0.0, 80.0, 20.0, 140.0, 10.0, 60.0, 60.0, 0.0, 5.0])
    return time, loss


def _reference(rhs, time, loss, y0, dense=8):
    """solve_ivp piece by piece (the loss is linear on each piece, steps between)."""
    from scipy.integrate import solve_ivp

    y = np.array(y0, dtype=float)
    at, fine = [y.copy()], []
    for k in range(time.size - 1):
        t0, t1, p0, p1 = time[k], time[k + 1], loss[k], loss[k + 1]
        if t1 == t0:
            at.append(y.copy())
            continue

        def power(t, t0=t0, t1=t1, p0=p0, p1=p1):
            return p0 + (p1 - p0) * (t - t0) / (t1 - t0)

        s = np.linspace(t0, t1, dense)
        sol = solve_ivp(lambda t, x, power=power: rhs(x, power(t)), (t0, t1), y,
                        method="DOP853", rtol=1e-12, atol=1e-12, t_eval=s)
        y = sol.y[:, -1]
        at.append(y.copy())
        fine.append(sol.y[0])
    return np.array(at), np.concatenate(fine)


def test_first_order_against_solve_ivp() -> None:
    time, loss = _profile()
    R, tau = 0.8, 0.7
    C = tau / R
    response = first_order(R, tau).response(time, loss, initial=[[3.0]])
    at, fine = _reference(lambda x, p: [(p - x[0] / R) / C], time, loss, [3.0], dense=400)
    assert np.allclose(response.rise[0], at[:, 0], rtol=1e-9, atol=1e-9)
    assert response.peak[0] == pytest.approx(fine.max(), rel=1e-6)
    assert response.peak[0] >= fine.max() - 1e-9
    # periodic: one cycle from the periodic start comes back to it
    periodic = first_order(R, tau).periodic(time, loss)
    again, _ = _reference(lambda x, p: [(p - x[0] / R) / C], time, loss,
                          [periodic.rise[0, 0]])
    assert again[-1, 0] == pytest.approx(periodic.rise[0, 0], rel=1e-9)


def test_two_node_against_solve_ivp() -> None:
    time, loss = _profile()
    R1, R2, tau_w, tau_h = 0.5, 1.2, 0.4, 6.0  # maxon-style figures
    Cw, Ch = tau_w / R1, tau_h / R2

    def rhs(x, p):
        w, h = x
        return [(p - (w - h) / R1) / Cw, ((w - h) / R1 - h / R2) / Ch]

    response = two_node(R1, R2, tau_w, tau_h).response(time, loss)
    at, fine = _reference(rhs, time, loss, [0.0, 0.0], dense=400)
    assert np.allclose(response.rise[0], at[:, 0], rtol=1e-9, atol=1e-9)
    assert response.peak[0] == pytest.approx(fine.max(), rel=1e-6)
    # the datasheet of maxon EC 45 flat: tau_w 11.5 s, tau_s 251 s, 3.96 and 5.7 K/W
    maxon = two_node(3.96, 5.7, 11.5, 251.0)
    assert maxon.thermal_resistance[0] == pytest.approx(9.66, rel=1e-12)
    assert maxon.time_constant[0] > 251.0


def test_candidates_are_rows() -> None:
    time, loss = _profile()
    models = first_order([0.8, 1.6], [0.7, 0.7])
    both = models.response(time, np.vstack([loss, 0.5 * loss]))
    single = first_order(0.8, 0.7).response(time, loss)
    assert both.rise.shape == (2, time.size)
    assert np.allclose(both.rise[0], single.rise[0], rtol=1e-14)
    assert np.allclose(both.rise[1], single.rise[0], rtol=1e-14)  # 2R * P/2
    assert np.allclose(both.peak, single.peak[0], rtol=1e-12)
    # two-node models per candidate, each as on its own
    params = [(0.5, 1.2, 0.4, 6.0), (0.3, 2.0, 1.5, 40.0), (1.0, 0.2, 0.05, 3.0)]
    together = two_node(*np.array(params).T).response(time, loss)
    for row, p in enumerate(params):
        alone = two_node(*p).response(time, loss)
        assert np.allclose(together.rise[row], alone.rise[0], rtol=1e-13)
        assert together.peak[row] == pytest.approx(alone.peak[0], rel=1e-12)
        assert together.mean[row] == pytest.approx(alone.mean[0], rel=1e-12)


def test_continuing_from_a_final_state() -> None:
    time, loss = _profile()
    model = two_node(0.5, 1.2, 0.4, 6.0)
    first = model.response(time, loss)
    second = model.response(time, loss, initial=first.final)
    doubled_time = np.concatenate([time, time + time[-1]])  # a step at the join
    doubled_loss = np.concatenate([loss, loss])
    whole = model.response(doubled_time, doubled_loss)
    assert whole.rise[0, -1] == pytest.approx(second.rise[0, -1], rel=1e-12)


@pytest.mark.parametrize("call,field", [
    (lambda: first_order(1.0, 0.0), "thermal_time_constant"),
    (lambda: first_order(1.0, -3.0), "thermal_time_constant"),
    (lambda: first_order(-1.0, 3.0), "thermal_resistance"),
    (lambda: first_order(1.0, np.inf), "thermal_time_constant"),
    (lambda: two_node(0.5, 1.2, 0.0, 6.0), "winding_time_constant"),
    (lambda: two_node(-0.5, 1.2, 0.4, 6.0), "winding_housing_resistance"),
    (lambda: two_node(0.5, 1.2, 0.4, -6.0), "housing_time_constant"),
    (lambda: thermal_resistance(0.0, 10.0), "allowed_rise"),
    (lambda: thermal_resistance(100.0, 0.0), "continuous_loss"),
    (lambda: first_order(1.0, 1.0).response([0.0, 1.0], [1.0, -2.0]), "loss"),
    (lambda: first_order(1.0, 1.0).periodic([0.0, 1.0], [1.0]), "loss"),
    (lambda: first_order(1.0, 1.0).periodic([1.0, 0.0], [1.0, 1.0]), "time"),
    (lambda: applied_check(0.0, 1.0), "cycle_time"),
    (lambda: first_order([1.0, 2.0], [1.0, 2.0, 3.0]), "thermal_resistance"),
    (lambda: first_order([1.0, 2.0], 1.0).response([0.0, 1.0], np.ones((3, 2))), "loss"),
    (lambda: thermal_verdict(1.0, 1.0, 1.0, 0.0, 1.0, 100.0), "continuous_torque"),
    (lambda: thermal_verdict(1.0, 1.0, -1.0, 1.0, 1.0, 100.0), "rms_torque"),
])
def test_bad_inputs_name_their_field(call, field) -> None:
    with pytest.raises(UserError) as error:
        call()
    assert error.value.field == field


def test_winding_check_of_sampled_torques() -> None:
    torques = [5.0, 0.4, -3.0, 0.1]
    durations = [0.1, 0.25, 0.08, 0.37]
    time, torque = steps(torques, durations)
    cycle = sum(durations)
    rms = math.sqrt(sum(t * t * d for t, d in zip(torques, durations, strict=True)) / cycle)
    check = winding_check(time, torque, TAU_C, RISE, [100.0, 2.0])
    assert np.allclose(check.rms_torque, rms, rtol=1e-13)
    assert np.allclose(check.response.mean, RISE * (rms / TAU_C) ** 2, rtol=1e-11)
    assert list(check.verdict.applied) == ["rms", "thermal"]
    # the same as the model with R_th from the continuous torque's copper loss
    model = first_order(R_TH, 2.0).periodic(time, _loss(torque))
    assert check.verdict.peak_rise[1] == pytest.approx(model.peak[0], rel=1e-12)
    assert check.verdict.margin[0] == pytest.approx(1.0 - (rms / TAU_C) ** 2, rel=1e-12)
    # a one-off sequence from a warm start
    once = winding_check(time, torque, TAU_C, RISE, 2.0, periodic=False, initial_rise=20.0)
    warm = first_order(R_TH, 2.0).response(time, _loss(torque), initial=[[20.0]])
    assert once.response.rise[0] == pytest.approx(warm.rise[0], rel=1e-12)
    with pytest.raises(UserError) as error:
        winding_check(time, torque, TAU_C, RISE, 0.0)
    assert error.value.field == "thermal_time_constant"


def test_each_candidate_with_its_own_cycle() -> None:
    cycles = [([5.0, 0.4, -3.0, 0.1], [0.1, 0.25, 0.08, 0.37]),
              ([4.0, 0.0, -4.0, 0.0], [0.2, 0.5, 0.2, 1.1]),
              ([2.5, 1.0, -1.0, 0.5], [0.05, 0.1, 0.05, 0.2])]
    samples = [steps(levels, durations) for levels, durations in cycles]
    time = np.vstack([s[0] for s in samples])
    torque = np.vstack([s[1] for s in samples])
    model = two_node(0.5, 1.2, 0.4, 6.0)
    together = model.periodic(time, _loss(torque))
    check = winding_check(time, torque, TAU_C, RISE, 3.0)
    for row, (t, tq) in enumerate(samples):
        alone = model.periodic(t, _loss(tq))
        assert np.allclose(together.rise[row], alone.rise[0], rtol=1e-13)
        assert together.peak[row] == pytest.approx(alone.peak[0], rel=1e-13)
        assert together.mean[row] == pytest.approx(alone.mean[0], rel=1e-13)
        one = winding_check(t, tq, TAU_C, RISE, 3.0)
        assert check.verdict.rise[row] == pytest.approx(one.verdict.rise[0], rel=1e-13)
        assert check.verdict.applied[row] == one.verdict.applied[0]


@pytest.mark.parametrize("share_of_limit,feasible", [(0.999, True), (1.001, False)])
def test_a_short_cycle_agrees_with_the_rms_check(share_of_limit, feasible) -> None:
    levels = np.array([5.0, 0.4, -3.0, 0.1])
    durations = [0.1, 0.25, 0.08, 0.37]
    cycle = sum(durations)
    rms = math.sqrt(float(np.sum(levels**2 * durations)) / cycle)
    levels = levels * share_of_limit * TAU_C / rms  # tau_rms = share * tau_c
    time, torque = steps(levels, durations)
    check = winding_check(time, torque, TAU_C, RISE, 1e4 * cycle)
    assert check.verdict.applied[0] == "rms"
    rms_rise = RISE * share_of_limit**2
    assert check.verdict.rms_rise[0] == pytest.approx(rms_rise, rel=1e-12)
    # the model's peak is the RMS rise to within the ripple, ~ cycle / tau_th
    assert abs(check.verdict.peak_rise[0] / rms_rise - 1.0) < 1e-4
    assert bool(check.verdict.peak_rise[0] <= RISE) == feasible
    assert bool(check.verdict.feasible[0]) == feasible
