"""The exact response of an elastic load (sec. 7.1.1, 7.2): sizer.vibration.response.

Every value is checked against an independent integration of eq. 7.2 by
scipy.integrate.solve_ivp (DOP853, rtol 1e-12, restarted at the law's breakpoints where
the acceleration may jump), or against closed forms derived here:

- cycloidal, q_N'' = 2 pi sin(2 pi tau): int_0^1 q_N'' e^{-i Omega tau} dtau =
  (2 pi)^2 (1 - e^{-i Omega}) / ((2 pi)^2 - Omega^2), so the undamped residual per unit h
  is |F| / Omega = (2 pi)^2 2 |sin(Omega / 2)| / (Omega |(2 pi)^2 - Omega^2|), zero at
  f_n T = 2, 3, 4, ...;
- trapezoid(alpha), q_N'' = +-A on [0, alpha] and [1 - alpha, 1], A = 1 / (alpha (1 - alpha)):
  F(s) = (A / s)(1 - e^{-s alpha})(1 - e^{-s (1 - alpha)}), so the undamped residual is
  4 A |sin(pi fT alpha) sin(pi fT (1 - alpha))| / (2 pi fT)^2, zero where fT alpha or
  fT (1 - alpha) is an integer.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import minimize_scalar

from sizer.errors import UserError
from sizer.laws import make_law
from sizer.vibration.elastic_load import ElasticLoad
from sizer.vibration.response import (
    Segment,
    cycle_response,
    move_response,
    residual_amplitude,
    tracking_error,
)

LAWS = ("cycloidal", "trapezoidal(alpha=1/3)", "harmonic", "polynomial(degree=5)",
        "modified_trapezoidal", "double_s(alpha=1/3, beta=1/4)", "exponential",
        "freudenstein_1_3_5", "elliptic")


def _integrate(law_spec: str, fT: float, delta: float, x0: tuple[float, float] = (0.0, 0.0),
               dense: int = 4000) -> tuple[np.ndarray, float]:
    """Normalized eq. 7.2 (zeta'' + 2 delta Omega zeta' + Omega^2 zeta = -q_N'') over the
    move by solve_ivp, piece by piece: the end state and the peak |zeta| (dense output on
    a fine grid, refined by a bounded scalar search around the best sample)."""
    law = make_law(law_spec)
    omega = 2.0 * math.pi * fT

    def rhs(t: float, x: np.ndarray) -> list[float]:
        return [x[1], -omega**2 * x[0] - 2 * delta * omega * x[1]
                - float(law.acceleration(np.array([t]))[0])]

    cuts = [0.0] + [float(b) for b in law.breakpoints if 0.0 < b < 1.0] + [1.0]
    x = np.array(x0, dtype=float)
    peak = 0.0
    for a, b in itertools.pairwise(cuts):
        sol = solve_ivp(rhs, (a, b), x, method="DOP853", rtol=1e-12, atol=1e-15,
                        dense_output=True)
        x = sol.y[:, -1]
        grid = np.linspace(a, b, max(50, int(dense * (b - a))))
        values = np.abs(sol.sol(grid)[0])
        i = int(np.argmax(values))
        lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
        best = minimize_scalar(lambda t, s=sol: -abs(s.sol(t)[0]), bounds=(lo, hi),
                               method="bounded", options={"xatol": 1e-13})
        peak = max(peak, float(values[i]), -float(best.fun))
    return x, peak


def _envelope(x: np.ndarray, fT: float, delta: float) -> float:
    """A of zeta = A e^{-delta Omega t} cos(Omega_d t + phi) from a state (zeta, zeta')."""
    omega = 2.0 * math.pi * fT
    omega_d = omega * math.sqrt(1.0 - delta**2)
    z, zd = x
    return math.hypot(z, (zd + delta * omega * z) / omega_d)


CASES = [(law, fT, delta) for law in LAWS for fT, delta in ((0.7, 0.0), (2.3, 0.05),
                                                            (5.4, 0.3), (11.1, 0.0))]


@pytest.mark.parametrize("law,fT,delta", CASES)
def test_residual_and_peak_match_solve_ivp(law: str, fT: float, delta: float) -> None:
    state, peak = _integrate(law, fT, delta)
    residual = float(residual_amplitude(law, fT, delta))
    assert residual == pytest.approx(_envelope(state, fT, delta), rel=1e-9, abs=1e-13)
    assert float(tracking_error(law, fT, delta)) == pytest.approx(peak, rel=1e-9, abs=1e-13)


def test_residual_vectorized_over_fT_agrees_with_one_at_a_time() -> None:
    fT = np.array([[0.4, 3.3, 17.0], [60.0, 1.0, 2.5]])
    together = residual_amplitude("trapezoidal(alpha=1/4)", fT, 0.1)
    assert together.shape == fT.shape
    alone = [float(residual_amplitude("trapezoidal(alpha=1/4)", v, 0.1)) for v in fT.ravel()]
    np.testing.assert_allclose(together.ravel(), alone, rtol=1e-12)


def test_cycloidal_undamped_residual_vanishes_at_integer_fT_from_two() -> None:
    fT = np.array([2.0, 3.0, 4.0, 7.0])
    assert np.all(residual_amplitude("cycloidal", fT, 0.0) < 1e-12)
    omega = 2.0 * math.pi * np.array([2.5, 1.0, 1.5, 6.25])
    closed = np.where(np.isclose(omega, 2 * math.pi), 0.5,  # the limit at fT = 1: |F| = pi
                      (2 * math.pi) ** 2 * 2 * np.abs(np.sin(omega / 2))
                      / (omega * np.abs((2 * math.pi) ** 2 - omega**2) + 1e-300))
    got = residual_amplitude("cycloidal", omega / (2 * math.pi), 0.0)
    np.testing.assert_allclose(got, closed, rtol=1e-12)
    assert got[0] > 0.02  # fT = 2.5: far from zero


@pytest.mark.parametrize("alpha", [1 / 3, 1 / 4, 0.4])
def test_trapezoid_residual_follows_its_closed_form_and_zeros(alpha: float) -> None:
    a = 1.0 / (alpha * (1.0 - alpha))
    fT = np.concatenate([np.linspace(0.3, 25.0, 997), [123.45, 311.7, 1000.3]])
    closed = 4 * a * np.abs(np.sin(math.pi * fT * alpha) * np.sin(math.pi * fT * (1 - alpha))
                            ) / (2 * math.pi * fT) ** 2
    spec = f"trapezoidal(alpha={alpha!r})"
    np.testing.assert_allclose(residual_amplitude(spec, fT, 0.0), closed, rtol=1e-11,
                               atol=1e-15)
    zeros = np.concatenate([np.arange(1, 6) / alpha, np.arange(1, 6) / (1 - alpha)])
    assert np.all(residual_amplitude(spec, zeros, 0.0) < 1e-13)


def test_residual_at_large_fT_and_heavy_damping_is_finite_and_exact() -> None:
    """delta omega_n T = 2 pi 0.9 400 ~ 2262: e^{+2262} would overflow a plain transform.
    With delta > 0 the trapezoid's last jump (-A -> 0 at tau = 1) dominates: the free
    response after a step -J of q'' ends at zeta = J / Omega^2, zeta' = 0 from 1 - alpha
    on (the earlier jumps have decayed by e^{-delta Omega alpha})."""
    fT, delta = 400.0, 0.9
    omega = 2 * math.pi * fT
    a = 4.5
    # last step of q'' at tau = 1 is +A (from -A to 0): zeta jumps to equilibrium 0 from
    # the quasi-static A / Omega^2 (the deceleration phase's), with zeta' = 0
    expected = _envelope(np.array([a / omega**2, 0.0]), fT, delta)
    got = float(residual_amplitude("trapezoidal(alpha=1/3)", fT, delta))
    assert got == pytest.approx(expected, rel=1e-12)


def test_peak_error_scales_as_quasi_static_for_large_fT() -> None:
    """z ~ -y'' / omega_n^2 for a slow move: peak * (2 pi fT)^2 -> C_a = 2 pi for the
    cycloidal law (continuous acceleration; the jerk jump adds O(1 / fT))."""
    fT = np.array([20.0, 40.0, 80.0, 160.0])
    scaled = tracking_error("cycloidal", fT, 0.0) * (2 * math.pi * fT) ** 2
    gap = np.abs(scaled - 2 * math.pi)
    assert np.all(gap[1:] < gap[:-1])  # tends to C_a
    assert gap[-1] < 2 * math.pi * 0.02
    assert np.all(gap * fT < 2 * math.pi * 2)  # O(1 / fT)


@pytest.mark.parametrize("fT", [4.0, 8.0, 12.0])
def test_trapezoid_peak_is_twice_the_quasi_static_at_synchronous_fT(fT: float) -> None:
    """trapezoid(1/4) with fT alpha an integer: every jump of q'' falls on a multiple of
    the period, so zeta(tau) = -(q_N''(tau) / Omega^2)(1 - cos Omega tau), peak 2 A / Omega^2
    (A = 16/3): the step response's doubling, exactly."""
    omega = 2 * math.pi * fT
    got = float(tracking_error("trapezoidal(alpha=1/4)", fT, 0.0))
    assert got == pytest.approx(2 * (16 / 3) / omega**2, rel=1e-12)


def test_move_response_matches_solve_ivp_during_and_after() -> None:
    load = ElasticLoad(3.0, 0.08)
    T, h = 0.8, 0.25
    law = make_law("modified_trapezoidal")
    times = np.array([-0.1, 0.0, 0.13, 0.4, 0.77, 0.8, 0.95, 1.6])
    z, zd = move_response(law, T, h, load, times, initial=(0.001, -0.02))
    wn, d = load.omega_n, load.damping_ratio

    def rhs(t: float, x: np.ndarray) -> list[float]:
        acc = h / T**2 * float(law.acceleration(np.array([t / T]))[0])
        return [x[1], -wn**2 * x[0] - 2 * d * wn * x[1] - acc]

    cuts = [0.0, *[T * float(b) for b in law.breakpoints if 0 < b < 1], T, 1.6]
    x = np.array([0.001, -0.02])
    for a, b in itertools.pairwise(cuts):
        sol = solve_ivp(rhs, (a, b), x, method="DOP853", rtol=1e-12, atol=1e-16,
                        dense_output=True)
        x = sol.y[:, -1]
        inside = (times >= a) & (times <= b)
        if not inside.any():
            continue
        ref = sol.sol(times[inside])
        np.testing.assert_allclose(z[inside], ref[0], rtol=1e-9, atol=1e-14)
        np.testing.assert_allclose(zd[inside], ref[1], rtol=1e-9, atol=1e-13)
    assert (z[0], zd[0]) == (0.001, -0.02)


def _cycle_by_ivp(segments: list[Segment], load: ElasticLoad, x0: np.ndarray, until: float
                  ) -> tuple[list[tuple[np.ndarray, np.ndarray, float]], np.ndarray]:
    """(start state, end state, peak |z|) per move and the state at ``until``, solve_ivp."""
    wn, d = load.omega_n, load.damping_ratio
    x = np.array(x0, dtype=float)
    t = segments[0].start
    out = []

    def free(t0: float, t1: float, x: np.ndarray) -> np.ndarray:
        if t1 <= t0:
            return x
        return solve_ivp(lambda _t, v: [v[1], -wn**2 * v[0] - 2 * d * wn * v[1]], (t0, t1),
                         x, method="DOP853", rtol=1e-12, atol=1e-16).y[:, -1]

    for seg in segments:
        x = free(t, seg.start, x)
        start = x.copy()
        # normalized: zeta = z (units of z), tau = (t - start) / T, q'' scaled by h
        fT = load.natural_frequency * seg.duration
        omega = 2 * math.pi * fT
        norm = np.array([x[0], x[1] * seg.duration])
        law = make_law(seg.law)

        def rhs(tau: float, v: np.ndarray, law=law, omega=omega, h=seg.displacement
                ) -> list[float]:
            return [v[1], -omega**2 * v[0] - 2 * d * omega * v[1]
                    - h * float(law.acceleration(np.array([tau]))[0])]

        cuts = [0.0] + [float(b) for b in law.breakpoints if 0 < b < 1] + [1.0]
        peak = 0.0
        for a, b in itertools.pairwise(cuts):
            sol = solve_ivp(rhs, (a, b), norm, method="DOP853", rtol=1e-12, atol=1e-16,
                            dense_output=True)
            norm = sol.y[:, -1]
            grid = np.linspace(a, b, 3000)
            values = np.abs(sol.sol(grid)[0])
            i = int(np.argmax(values))
            best = minimize_scalar(lambda u, s=sol: -abs(s.sol(u)[0]),
                                   bounds=(grid[max(i - 1, 0)], grid[min(i + 1, 2999)]),
                                   method="bounded", options={"xatol": 1e-13})
            peak = max(peak, float(values[i]), -float(best.fun))
        x = np.array([norm[0], norm[1] / seg.duration])
        out.append((start, x.copy(), peak))
        t = seg.start + seg.duration
    return out, free(t, until, x)


def _segments() -> list[Segment]:
    return [Segment("cycloidal", 0.1, 0.5, 0.2),
            Segment("trapezoidal(alpha=1/3)", 0.75, 0.3, -0.05),
            Segment("polynomial(degree=5)", 1.05, 0.45, -0.15)]


def test_cycle_carries_the_state_from_move_to_move() -> None:
    load = ElasticLoad(2.7, 0.04)
    segments = _segments()
    result = cycle_response(segments, load)
    assert not result.periodic
    reference, _ = _cycle_by_ivp(segments, load, np.zeros(2), 1.5)
    for move, (start, end, peak) in zip(result.moves, reference, strict=True):
        np.testing.assert_allclose(move.start_state, start, rtol=1e-9, atol=1e-14)
        np.testing.assert_allclose(move.end_state, end, rtol=1e-9, atol=1e-13)
        assert move.peak_error == pytest.approx(peak, rel=1e-9, abs=1e-14)
        omega_d = load.omega_d
        z, zd = end
        envelope = math.hypot(z, (zd + load.damping_ratio * load.omega_n * z) / omega_d)
        assert move.residual == pytest.approx(envelope, rel=1e-9)


def test_periodic_cycle_returns_to_its_state_after_one_period() -> None:
    load = ElasticLoad(2.7, 0.04)
    segments = _segments()
    period = 2.0
    result = cycle_response(segments, load, period=period)
    assert result.periodic
    first = np.array(result.moves[0].start_state)
    assert np.abs(first).max() > 1e-5  # the previous cycle's vibration is carried in
    reference, back = _cycle_by_ivp(segments, load, first, segments[0].start + period)
    np.testing.assert_allclose(back, first, rtol=1e-8, atol=1e-14)
    for move, (_start, end, peak) in zip(result.moves, reference, strict=True):
        np.testing.assert_allclose(move.end_state, end, rtol=1e-8, atol=1e-13)
        assert move.peak_error == pytest.approx(peak, rel=1e-8)


def test_one_move_cycle_from_rest_is_the_residual_per_unit_h() -> None:
    load = ElasticLoad(5.0, 0.1)
    move = cycle_response([Segment("harmonic", 0.0, 0.37, 0.3)], load).moves[0]
    fT = 5.0 * 0.37
    assert move.residual == pytest.approx(0.3 * float(residual_amplitude("harmonic", fT, 0.1)),
                                          rel=1e-12)
    assert move.peak_error == pytest.approx(0.3 * float(tracking_error("harmonic", fT, 0.1)),
                                            rel=1e-12)


# ------------------------------------------------------------------ sec. 7.2's 1-DOF case
def test_book_section_7_2_one_dof_parameters() -> None:
    """m = 1, d = 2, k = 100 -> omega_n = 10, delta = 0.1 (the book prints no response
    values for its Figs. 7.6-7.17: only the plots)."""
    m, d, k = 1.0, 2.0, 100.0
    omega_n = math.sqrt(k / m)
    load = ElasticLoad(omega_n / (2 * math.pi), d / (2 * m * omega_n))
    assert load.omega_n == pytest.approx(10.0)
    assert load.damping_ratio == pytest.approx(0.1)


DISCONTINUOUS = ("constant_acceleration", "harmonic", "elliptic", "polynomial(degree=3)",
                 "circular_blends", "trapezoidal")
CONTINUOUS = ("cycloidal", "polynomial(degree=5)", "modified_trapezoidal",
              "modified_cycloidal", "gutman_1_3", "freudenstein_1_3", "freudenstein_1_3_5")


def test_book_section_7_2_discontinuous_accelerations_vibrate_more() -> None:
    """Sec. 7.2, 'Some considerations': the laws with discontinuous accelerations leave
    larger oscillations than those with continuous ones, in proportion to the jump. The
    book's case: q1 - q0 = 15, T = 30, omega_n = 10, delta = 0.1 (Omega = 300): the last
    jump dominates, residual ~ |q_N''(1-)| h / (Omega |s|)... = |jump| h / Omega^2 /
    sqrt(1 - delta^2) to O(1 / Omega)."""
    fT, delta, h = 30 * 10 / (2 * math.pi), 0.1, 15.0
    worst_smooth = max(float(residual_amplitude(law, fT, delta)) for law in CONTINUOUS)
    omega = 2 * math.pi * fT
    for spec in DISCONTINUOUS:
        law = make_law(spec)
        residual = float(residual_amplitude(law, fT, delta))
        assert residual > 5 * worst_smooth
        jump = abs(float(law.acceleration(np.array([1.0]))[0]))
        assert h * residual == pytest.approx(h * jump / omega**2 / math.sqrt(1 - delta**2),
                                             rel=3 / omega)


# ------------------------------------------------------------------ bad input
@pytest.mark.parametrize("fT", [-1.0, 0.0, math.nan, math.inf])
def test_bad_fT_is_a_user_error(fT: float) -> None:
    with pytest.raises(UserError, match="f_n T") as info:
        residual_amplitude("cycloidal", np.array([1.0, fT]), 0.0)
    assert info.value.field == "load.natural_frequency"


@pytest.mark.parametrize("delta", [1.0, -0.1, 1.5, math.nan])
def test_damping_outside_under_damped_range_is_a_user_error(delta: float) -> None:
    for call in (residual_amplitude, tracking_error):
        with pytest.raises(UserError, match=r"\[0, 1\)") as info:
            call("cycloidal", 2.0, delta)
        assert info.value.field == "load.damping_ratio"


def test_negative_natural_frequency_is_a_user_error() -> None:
    with pytest.raises(UserError, match="positive") as info:
        ElasticLoad(-3.0, 0.1)
    assert info.value.field == "load.natural_frequency"


def test_bad_samples_and_moves_are_user_errors() -> None:
    with pytest.raises(UserError, match="samples") as info:
        tracking_error("cycloidal", 2.0, 0.0, samples=1)
    assert info.value.field == "samples"
    load = ElasticLoad(2.0, 0.1)
    with pytest.raises(UserError, match="duration must be positive") as info:
        move_response("cycloidal", 0.0, 1.0, load, np.array([0.1]))
    assert info.value.field == "duration"
    with pytest.raises(UserError, match="displacement must be finite"):
        move_response("cycloidal", 1.0, math.inf, load, np.array([0.1]))
    with pytest.raises(UserError, match="initial state") as info:
        cycle_response([Segment("cycloidal", 0.0, 1.0, 1.0)], load, initial=(0.0,))
    assert info.value.field == "initial"


def test_bad_cycles_are_user_errors() -> None:
    load = ElasticLoad(2.0, 0.0)
    with pytest.raises(UserError, match="before the previous one ends") as info:
        cycle_response([Segment("cycloidal", 0.0, 1.0, 1.0),
                        Segment("cycloidal", 0.5, 1.0, -1.0)], load)
    assert info.value.field == "segments[1].start"
    with pytest.raises(UserError, match="duration") as info:
        cycle_response([Segment("cycloidal", 0.0, -1.0, 1.0)], load)
    assert info.value.field == "segments[0].duration"
    with pytest.raises(UserError, match="shorter than the moves"):
        cycle_response([Segment("cycloidal", 0.0, 1.0, 1.0)], load, period=0.5)
    # undamped, f_n P = 2 * 1.5 = 3: resonant, no periodic state
    with pytest.raises(UserError, match="no steady periodic state") as info:
        cycle_response([Segment("cycloidal", 0.0, 1.0, 1.0)], load, period=1.5)
    assert info.value.field == "period"
    with pytest.raises(UserError, match="at least one move"):
        cycle_response([], load)
