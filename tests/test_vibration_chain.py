"""The n-DOF chain load of sec. 7.1.2 (sizer.vibration.chain_load), against solve_ivp on
the chain's own equations in the masses' positions x_i (the first system of sec. 7.1.2,
x_0 = y), independent of eq. 7.3's matrices, and the book's 5-DOF example of sec. 7.2."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import minimize_scalar

from sizer.errors import UserError
from sizer.laws import make_law
from sizer.vibration.chain_load import ChainLoad, chain_move_response, chain_vibration
from sizer.vibration.response import residual_amplitude, tracking_error

BOOK = ChainLoad((0.2,) * 5, (10.0,) * 5, (500.0,) * 5)
"""Sec. 7.2: m_i = 0.2, d_i = 10, k_i = 500."""


def _by_ivp(law_spec: str, T: float, h: float, chain: ChainLoad, until: float
            ) -> tuple[np.ndarray, float, object]:
    """x_i by solve_ivp from rest: the state [z, z'] at T, max |x_n - y| on [0, T], and
    the dense solution of the free motion after T (x_n - y from it)."""
    law = make_law(law_spec)
    m = np.array(chain.masses)
    d = np.array(chain.dampings)
    k = np.array(chain.stiffnesses)
    n = m.size

    def inputs(t: float) -> tuple[float, float]:
        tau = np.array([min(max(t / T, 0.0), 1.0)])
        return (h * float(law.position(tau)[0]), h / T * float(law.velocity(tau)[0]) *
                (0.0 <= t <= T))

    def rhs(t: float, state: np.ndarray) -> np.ndarray:
        x, v = state[:n], state[n:]
        y, yd = inputs(t)
        xm = np.concatenate([[y], x[:-1]])  # x_{i-1}
        vm = np.concatenate([[yd], v[:-1]])
        force = -d * (v - vm) - k * (x - xm)
        force[:-1] += d[1:] * (v[1:] - v[:-1]) + k[1:] * (x[1:] - x[:-1])
        return np.concatenate([v, force / m])

    cuts = [0.0] + [T * float(b) for b in law.breakpoints if 0 < b < 1] + [T]
    state = np.zeros(2 * n)
    peak = 0.0
    for a, b in itertools.pairwise(cuts):
        sol = solve_ivp(rhs, (a, b), state, method="DOP853", rtol=1e-12, atol=1e-15,
                        dense_output=True)
        state = sol.y[:, -1]

        def error(t: float, s=sol) -> float:
            return float(s.sol(t)[n - 1] - inputs(t)[0])

        grid = np.linspace(a, b, 3000)
        values = np.abs([error(t) for t in grid])
        i = int(np.argmax(values))
        best = minimize_scalar(lambda t: -abs(error(t)), method="bounded",
                               bounds=(grid[max(i - 1, 0)], grid[min(i + 1, 2999)]),
                               options={"xatol": 1e-14})
        peak = max(peak, float(values[i]), -float(best.fun))
    after = solve_ivp(rhs, (T, until), state, method="DOP853", rtol=1e-12, atol=1e-15,
                      dense_output=True)
    x, v = state[:n], state[n:]
    z = np.diff(np.concatenate([[h], x]))  # z_1 = x_1 - y(T), z_i = x_i - x_{i-1}
    zd = np.diff(np.concatenate([[0.0], v]))
    return np.concatenate([z, zd]), peak, after


@pytest.mark.parametrize("law", ["trapezoidal(alpha=1/3)", "cycloidal", "harmonic"])
def test_book_chain_move_matches_solve_ivp(law: str) -> None:
    T, h = 1.2, 0.4
    end, peak, after = _by_ivp(law, T, h, BOOK, T + 0.5)
    result = chain_vibration(law, T, h, BOOK)
    scale = np.abs(end).max()
    np.testing.assert_allclose(result.end_state, end, rtol=1e-8, atol=1e-10 * scale)
    assert result.peak_error == pytest.approx(peak, rel=1e-8)
    free = np.linspace(T, T + 0.5, 400)
    error = np.abs(after.sol(free)[4] - h)
    assert error.max() <= result.residual * (1 + 1e-9)  # the modes' envelopes bound it
    times = np.array([-0.1, 0.3, 0.77, T, T + 0.21])
    states = chain_move_response(law, T, h, BOOK, times)
    assert states.shape == (5, 10)
    np.testing.assert_allclose(states[0], 0.0)
    np.testing.assert_allclose(states[3], end, rtol=1e-8, atol=1e-10 * scale)
    later = after.sol(T + 0.21)
    z = np.diff(np.concatenate([[h], later[:5]]))
    np.testing.assert_allclose(states[4, :5], z, rtol=1e-8, atol=1e-10 * np.abs(z).max())


def test_one_element_chain_is_the_one_dof_load() -> None:
    """m = 1, d = 2, k = 100 (sec. 7.2's 1-DOF case): omega_n = 10, delta = 0.1."""
    chain = ChainLoad((1.0,), (2.0,), (100.0,))
    assert chain.natural_frequencies()[0] * 2 * math.pi == pytest.approx(10.0)
    assert chain.damping_ratios()[0] == pytest.approx(0.1)
    T, h = 1.3, 0.7
    fT = 10 / (2 * math.pi) * T
    result = chain_vibration("harmonic", T, h, chain)
    assert result.residual == pytest.approx(h * float(residual_amplitude("harmonic", fT, 0.1)),
                                            rel=1e-10)
    assert result.peak_error == pytest.approx(h * float(tracking_error("harmonic", fT, 0.1)),
                                              rel=1e-10)


def test_book_five_dof_modes_and_the_claims_of_section_7_2() -> None:
    """The uniform chain fixed at the input: omega_r = 2 sqrt(k / m) sin((2r - 1) pi /
    (2 (2n + 1))); D = (d / k) K, so delta_r = (d / k) omega_r / 2. The book: same total
    mass, stiffness (in series) and damping as the 1-DOF case; its oscillations are faster
    and damped sooner (lowest mode 14.2 rad/s, delta 0.142 against 10 rad/s, 0.1)."""
    r = np.arange(1, 6)
    omega = 2 * math.sqrt(500 / 0.2) * np.sin((2 * r - 1) * math.pi / 22)
    np.testing.assert_allclose(BOOK.natural_frequencies() * 2 * math.pi, omega, rtol=1e-12)
    np.testing.assert_allclose(BOOK.damping_ratios(), 0.01 * omega, rtol=1e-12)
    assert sum(BOOK.masses) == pytest.approx(1.0)
    assert 1 / sum(1 / k for k in BOOK.stiffnesses) == pytest.approx(100.0)
    assert 1 / sum(1 / d for d in BOOK.dampings) == pytest.approx(2.0)
    assert omega[0] > 10.0 and BOOK.damping_ratios()[0] > 0.1
    # q1 = 15, T = 30: discontinuous accelerations leave larger residual vibrations
    smooth = max(chain_vibration(law, 30.0, 15.0, BOOK).residual
                 for law in ("cycloidal", "polynomial(degree=5)", "modified_trapezoidal"))
    for law in ("constant_acceleration", "harmonic", "trapezoidal"):
        assert chain_vibration(law, 30.0, 15.0, BOOK).residual > 5 * smooth


def test_matrices_of_eq_7_3() -> None:
    chain = ChainLoad((1.0, 2.0, 3.0), (0.1, 0.2, 0.3), (10.0, 20.0, 30.0))
    M, D, K, m = chain.matrices()
    np.testing.assert_array_equal(M, [[1, 0, 0], [2, 2, 0], [3, 3, 3]])
    np.testing.assert_array_equal(K, [[10, -20, 0], [0, 20, -30], [0, 0, 30]])
    np.testing.assert_array_equal(D, [[0.1, -0.2, 0], [0, 0.2, -0.3], [0, 0, 0.3]])
    np.testing.assert_array_equal(m, [1, 2, 3])


@pytest.mark.parametrize("kwargs,field", [
    ({"masses": (1.0, -1.0), "dampings": (0.0, 0.0), "stiffnesses": (1.0, 1.0)}, "load.masses"),
    ({"masses": (1.0,), "dampings": (-0.1,), "stiffnesses": (1.0,)}, "load.dampings"),
    ({"masses": (1.0,), "dampings": (0.1,), "stiffnesses": (0.0,)}, "load.stiffnesses"),
    ({"masses": (1.0, 1.0), "dampings": (0.1,), "stiffnesses": (1.0, 1.0)}, "load"),
])
def test_bad_chains_are_user_errors(kwargs: dict, field: str) -> None:
    with pytest.raises(UserError) as info:
        ChainLoad(**kwargs)
    assert info.value.field == field


def test_critically_damped_chain_is_a_user_error() -> None:
    chain = ChainLoad((1.0,), (20.0,), (100.0,))  # d = 2 sqrt(k m): delta = 1
    with pytest.raises(UserError, match="critically damped"):
        chain_vibration("cycloidal", 1.0, 1.0, chain)


def test_periodic_cycle_of_the_book_chain_matches_solve_ivp() -> None:
    """Two moves (out and back) repeated every 1.2 s on the 5-DOF chain: the periodic
    state returned comes back after one period of the chain's equations in x_i, and each
    move's end state and peak |x_5 - y| agree with them."""
    from sizer.vibration.response import Segment, cycle_response

    segments = [Segment("cycloidal", 0.0, 0.4, 0.3),
                Segment("trapezoidal(alpha=1/4)", 0.6, 0.3, -0.3)]
    period = 1.2
    result = cycle_response(segments, BOOK, period=period)
    m, d, k = (np.array(v) for v in (BOOK.masses, BOOK.dampings, BOOK.stiffnesses))
    laws = [make_law(seg.law) for seg in segments]

    def inputs(t: float) -> tuple[float, float]:
        y, yd = 0.0, 0.0
        for law, seg in zip(laws, segments, strict=True):
            tau = np.array([min(max((t - seg.start) / seg.duration, 0.0), 1.0)])
            y += seg.displacement * float(law.position(tau)[0])
            if seg.start <= t <= seg.start + seg.duration:
                yd += seg.displacement / seg.duration * float(law.velocity(tau)[0])
        return y, yd

    def rhs(t: float, state: np.ndarray) -> np.ndarray:
        x, v = state[:5], state[5:]
        y, yd = inputs(t)
        force = -d * (v - np.concatenate([[yd], v[:-1]])) - k * (x - np.concatenate([[y], x[:-1]]))
        force[:-1] += d[1:] * (v[1:] - v[:-1]) + k[1:] * (x[1:] - x[:-1])
        return np.concatenate([v, force / m])

    def to_z(state: np.ndarray, t: float) -> np.ndarray:
        y, yd = inputs(t)
        return np.concatenate([np.diff(np.concatenate([[y], state[:5]])),
                               np.diff(np.concatenate([[yd], state[5:]]))])

    z0 = np.array(result.moves[0].start_state)
    assert np.abs(z0[:5]).max() > 1e-6  # the previous cycle's vibration is carried in
    state = np.concatenate([np.cumsum(z0[:5]), np.cumsum(z0[5:])])  # y = y' = 0 at t = 0
    cuts = sorted({0.0, period, *(seg.start + seg.duration * float(b) for law, seg in
                                  zip(laws, segments, strict=True) for b in law.breakpoints)})
    ends = {seg.start + seg.duration: i for i, seg in enumerate(segments)}
    peaks = [0.0, 0.0]
    checked = 0
    for a, b in itertools.pairwise(cuts):
        sol = solve_ivp(rhs, (a, b), state, method="DOP853", rtol=1e-12, atol=1e-15,
                        dense_output=True)
        state = sol.y[:, -1]
        for i, seg in enumerate(segments):
            if seg.start <= a and b <= seg.start + seg.duration + 1e-12:
                grid = np.linspace(a, b, 1500)
                error = np.abs([sol.sol(t)[4] - inputs(t)[0] for t in grid])
                j = int(np.argmax(error))
                best = minimize_scalar(
                    lambda t, s=sol: -abs(s.sol(t)[4] - inputs(t)[0]), method="bounded",
                    bounds=(grid[max(j - 1, 0)], grid[min(j + 1, 1499)]),
                    options={"xatol": 1e-14})
                peaks[i] = max(peaks[i], float(error[j]), -float(best.fun))
        if b in ends:
            np.testing.assert_allclose(result.moves[ends[b]].end_state, to_z(state, b),
                                       rtol=1e-7, atol=1e-11)
            checked += 1
    assert checked == 2
    np.testing.assert_allclose(to_z(state, period), z0, rtol=1e-7, atol=1e-11)
    for move, peak in zip(result.moves, peaks, strict=True):
        assert move.peak_error == pytest.approx(peak, rel=1e-8)
