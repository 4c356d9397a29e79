"""T_min in closed form with constant torques: Coulomb friction and a constant load (issue 34).

With an ideal gearbox and no damping the motor torque along each move is J_t K h q_N''/T^2
plus a constant (sizer.sizing.shortest_duration, module docs). Every reference here is
test-only and independent of that derivation: the law sampled densely piece by piece
(its peak q_N'', q_N', q_N''' from the samples, int q_N'' and int q_N''^2 by Gauss-Legendre
on each piece), the torques written from the physics (forward (F + G)/K, return (F - G)/K,
the hold |G|/K in the dwells), every check evaluated at T and T_min found by bisection to
1e-13. The auto shapes are checked against a grid of the engine's own T_min of fixed laws,
refined by a shrinking pattern search on the test's evaluation with the book's
coefficients of the trapezoid and the double S (sec. 3.2, 3.4, 6.2.1).
"""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest

from sizer.laws import law_choice, resolve
from sizer.laws.piecewise_polynomial import DoubleS, Trapezoidal
from sizer.model import Design, Limits, Load, Motor, Stage, Task, Transmission
from sizer.sizing.candidates import Candidates, MotorArrays
from sizer.sizing.choices import choose_shape
from sizer.sizing.cycle import single_task
from sizer.sizing.move import CycleCalculator
from sizer.sizing.optimal_shapes import rms_time
from sizer.sizing.shortest_duration import (
    bisect_duration,
    closed_form_duration,
    has_constant_torques,
    is_purely_inertial,
    minimum_duration,
    rms_duration,
)

H = math.pi / 2
RATIO, J_GEAR, J_LOAD = 10.0, 1.2e-4, 0.35
MARGIN, SPEED_MARGIN = 0.1, 0.05
RATED = 3000 * math.pi / 30


def rectangular_motors(count: int, low: float = 0.08, span: float = 400.0) -> tuple[Motor, ...]:
    out = []
    for i in range(count):
        torque = low * span ** (i / max(count - 1, 1))
        out.append(Motor(id=f"m{i}", inertia=2e-5 * torque**1.3, continuous_torque=torque,
                         peak_torque=3.0 * torque, rated_speed=RATED))
    return tuple(out)


MOTORS = rectangular_motors(8)


def make_design(spec: str, friction: float, torque: float, back: bool, dwell: float,
                motors=MOTORS, jerk: float | None = None, transmission=None) -> Design:
    transmission = Transmission((Stage("gearbox", RATIO, 1.0, J_GEAR),)) \
        if transmission is None else transmission
    return Design(Task(H, None, dwell=dwell, return_move=back),
                  Load(J_LOAD, friction=friction, torque=torque), transmission, laws=(spec,),
                  motors=motors, limits=Limits(torque_margin=MARGIN, speed_margin=SPEED_MARGIN,
                                               max_jerk=jerk))


def calculator_of(design: Design, law, motors=None) -> CycleCalculator:
    motors = design.motors if motors is None else motors
    candidates = Candidates.single(MotorArrays.of(motors), design.load, design.transmission)
    return CycleCalculator(None, single_task(design), candidates.drive, candidates.motors,
                           design.limits.thermal_speed, law=law)


# ------------------------------------------------------------ test-only reference
@functools.cache
def law_stats_of(spec: str) -> dict[str, float]:
    return law_stats(law_choice(spec).law)


def law_stats(law, samples: int = 200_001) -> dict[str, float]:
    """max q_N'', -min q_N'', max q_N', max |q_N'''| from dense samples of each piece (both
    ends, so jumps count on both sides), int q_N'' and int q_N''^2 by Gauss-Legendre."""
    nodes, weights = np.polynomial.legendre.leggauss(64)
    a_hi = a_lo = v_hi = j_hi = 0.0
    integral = square = 0.0
    for index, piece in enumerate(law.pieces):
        u = np.linspace(piece.start, piece.end, samples)
        a = law.piece_derivative(index, u, 2)
        a_hi, a_lo = max(a_hi, float(a.max())), max(a_lo, float(-a.min()))
        v_hi = max(v_hi, float(law.piece_derivative(index, u, 1).max()))
        j_hi = max(j_hi, float(np.abs(law.piece_derivative(index, u, 3)).max()))
        half = 0.5 * (piece.end - piece.start)
        g = law.piece_derivative(index, piece.start + half * (nodes + 1.0), 2)
        integral += half * float(weights @ g)
        square += half * float(weights @ (g * g))
    return {"a_max": a_hi, "a_min": a_lo, "v_max": v_hi, "j_max": j_hi, "int_a": integral,
            "int_a2": square}


def book_stats(C_v, C_a, C_a_rms, C_j=np.inf) -> dict:
    """The stats of a symmetric law from its coefficients (max q_N'' = -min q_N'' = C_a)."""
    return {"a_max": C_a, "a_min": C_a, "v_max": C_v, "j_max": C_j, "int_a": 0.0,
            "int_a2": C_a_rms**2}


def physics(motors, friction: float, torque: float, back: bool, dwell: float):
    """Per motor J_t, and the constants of the moves, from the load written out."""
    J_m = np.array([m.inertia for m in motors])
    J_t = J_m + J_GEAR + J_LOAD / RATIO**2
    constants = [(friction + torque) / RATIO]  # along the forward move
    if back:  # along the return's own motion: friction opposes it, the load now helps
        constants.append((friction - torque) / RATIO)
    hold = abs(torque) / RATIO if dwell > 0.0 else 0.0
    tau_p = np.array([m.peak_torque for m in motors]) * (1.0 - MARGIN)
    tau_c = np.array([m.continuous_torque for m in motors]) * (1.0 - MARGIN)
    return J_t, constants, hold, tau_p, tau_c


def passes(T, stats, J_t, constants, hold, tau_p, tau_c, dwell, jerk=None):
    """Every check at durations T (arrays broadcast with the motors' figures), exactly."""
    P = J_t * RATIO * H / T**2
    peak = np.full(np.shape(P), hold)
    square = 0.0
    for c in constants:
        peak = np.maximum(peak, np.maximum(P * stats["a_max"] + c, P * stats["a_min"] - c))
        square = square + T * (P**2 * stats["int_a2"] + 2.0 * P * c * stats["int_a"] + c * c)
    n = len(constants)
    rms = np.sqrt((square + n * dwell * hold**2) / (n * (T + dwell)))
    ok = (peak <= tau_p) & (rms <= tau_c)
    ok &= RATIO * stats["v_max"] * H / T <= (1.0 - SPEED_MARGIN) * RATED
    if jerk is not None:
        ok &= stats["j_max"] * H / T**3 <= jerk
    return ok


def reference_duration(stats, figures, dwell, jerk=None, shape=None) -> np.ndarray:
    """T_min by bisection in log T to 1e-13 (nan where even 1e3 s fails)."""
    J_t, constants, hold, tau_p, tau_c = figures
    shape = np.shape(J_t) if shape is None else shape
    extra = (1,) * (len(shape) - 1)
    J_t, tau_p, tau_c = (np.reshape(x, (-1, *extra)) for x in (J_t, tau_p, tau_c))
    lo, hi = np.full(shape, math.log(1e-5)), np.full(shape, math.log(1e3))
    top = passes(np.exp(hi), stats, J_t, constants, hold, tau_p, tau_c, dwell, jerk)
    assert not passes(np.exp(lo), stats, J_t, constants, hold, tau_p, tau_c, dwell, jerk).any()
    for _ in range(70):
        mid = 0.5 * (lo + hi)
        ok = passes(np.exp(mid), stats, J_t, constants, hold, tau_p, tau_c, dwell, jerk)
        hi, lo = np.where(ok, mid, hi), np.where(ok, lo, mid)
    return np.where(top, np.exp(hi), np.nan)


def test_rms_duration_with_a_dwell_per_candidate_and_negative_dwells():
    """T^3 (T + d) = s^2 with d per element, negative ones included (then T > -d): the
    root checked by the quartic itself and by bisection between -d (or 0) and 1e3."""
    rng = np.random.default_rng(3)
    scale = 10 ** rng.uniform(-4, 1, 200)
    dwell = rng.uniform(-2.0, 2.0, 200)
    dwell[:20] = 0.0
    T = rms_duration(scale, dwell)
    lo, hi = np.maximum(-dwell, 0.0), np.full(200, 1e3)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        above = mid**3 * (mid + dwell) >= scale**2
        hi, lo = np.where(above, mid, hi), np.where(above, lo, mid)
    np.testing.assert_allclose(T, hi, rtol=1e-13)
    np.testing.assert_allclose(rms_time(scale.reshape(20, 10), dwell.reshape(20, 10)),
                               hi.reshape(20, 10), rtol=1e-13)
    assert rms_duration(np.array([0.0]), np.array([-0.5]))[0] == 0.5  # T + d >= 0 still


# ------------------------------------------------------------------- fixed laws
LOADS = [(0.5, 0.0, True, 0.15), (0.5, 0.0, False, 0.0), (0.0, 2.0, True, 0.15),
         (0.0, 2.0, False, 0.2), (0.6, -1.5, True, 0.1), (0.6, 1.5, False, 0.0),
         # the hold (0.15 N*m at the motor) above the smallest motor's continuous rating
         # (0.072): t_d' < 0, the RMS still falls to its limit as T grows
         (1.0, -1.5, False, 0.2)]
LAWS = ["trapezoidal(alpha=1/3)", "cycloidal", "poly5", "trapezoidal(alpha=0.2, alpha_d=0.4)"]


@pytest.mark.parametrize("spec", LAWS)
@pytest.mark.parametrize("load", LOADS)
def test_closed_form_equals_numeric_reference(spec, load):
    friction, torque, back, dwell = load
    design = make_design(spec, friction, torque, back, dwell)
    law = law_choice(spec).law
    calculator = calculator_of(design, law)
    assert has_constant_torques(calculator) and not is_purely_inertial(calculator)
    reference = reference_duration(law_stats_of(spec), physics(MOTORS, *load), dwell)
    assert np.isfinite(reference).sum() >= 4  # most motors feasible, some constrained
    closed = closed_form_duration(calculator, design.limits)
    np.testing.assert_allclose(closed[np.isfinite(reference)],
                               reference[np.isfinite(reference)], rtol=1e-9)
    solution = minimum_duration(calculator, design.limits)
    assert solution.method == "closed form (eq. 6.2)"
    np.testing.assert_array_equal(solution.feasible, np.isfinite(reference))
    np.testing.assert_allclose(solution.duration, reference, rtol=1e-9)


def test_steady_load_efficiency_reflects_the_constants_by_their_sign():
    """Yaskawa's rule (efficiency on the steady load only, Drive.is_ideal): a constant
    that opposes the motion needs 1/eta more, one that drives gives back eta times it;
    holding counts as driving the load (divided by eta)."""
    eta, friction, torque, dwell = 0.8, 0.5, 1.0, 0.15
    design = make_design("poly5", friction, torque, True, dwell, transmission=Transmission(
        (Stage("gearbox", RATIO, eta, J_GEAR),), efficiency_applies_to="steady_load"))
    calculator = calculator_of(design, law_choice("poly5").law)
    assert has_constant_torques(calculator)
    J_t, _, _, tau_p, tau_c = physics(MOTORS, friction, torque, True, dwell)
    forward, back = friction + torque, friction - torque  # 1.5 opposes, -0.5 drives
    constants = [forward / (RATIO * eta), back * eta / RATIO]
    figures = (J_t, constants, abs(torque) / (RATIO * eta), tau_p, tau_c)
    reference = reference_duration(law_stats_of("poly5"), figures, dwell)
    solution = minimum_duration(calculator, design.limits)
    assert solution.method == "closed form (eq. 6.2)"
    np.testing.assert_allclose(solution.duration, reference, rtol=1e-9)


@pytest.mark.parametrize("load", [LOADS[0], LOADS[3], LOADS[6]])
def test_closed_form_agrees_with_the_engines_search(load):
    friction, torque, back, dwell = load
    design = make_design("cycloidal", friction, torque, back, dwell)
    calculator = calculator_of(design, law_choice("cycloidal").law)
    closed = minimum_duration(calculator, design.limits).duration
    searched = bisect_duration(calculator, design.limits)
    searched = np.where(np.isfinite(searched), searched, np.nan)
    # the search ends within the checks' tolerance (1e-9) of the binding limit
    np.testing.assert_allclose(searched, closed, rtol=2e-9)


def test_hold_beyond_the_peak_rating_is_infeasible_at_every_duration():
    design = make_design("cycloidal", 0.0, 3.0, False, 0.2, motors=rectangular_motors(3))
    calculator = calculator_of(design, law_choice("cycloidal").law)
    # 0.3 N*m held against 0.216, 0.648 * 0.9 ... of peak: the first motor fails
    solution = minimum_duration(calculator, design.limits)
    assert np.isinf(closed_form_duration(calculator, design.limits)[0])
    assert not solution.feasible[0] and solution.feasible[1:].all()


def test_friction_above_the_continuous_rating():
    """mean c^2 > tau_c'^2: the RMS tends to sqrt(mean c^2) above the limit, but a long
    dwell lowers it, so a window of durations may pass. Where even the least RMS any
    rest-to-rest law could have (C_a_rms^2 = 12, the cubic's) misses it, no duration
    (inf); else the closed form leaves the motor to the search, which finds the window's
    start: the RMS check at its limit there and failing just below."""
    friction, dwell = 2.0, 5.0  # c = 0.2 N*m at the motor, both ways
    design = make_design("cycloidal", friction, 0.0, True, dwell)
    law = law_choice("cycloidal").law
    calculator = calculator_of(design, law)
    closed = closed_form_duration(calculator, design.limits)
    assert np.isinf(closed[0]) and np.isnan(closed[1]) and np.isfinite(closed[2:]).all()
    solution = minimum_duration(calculator, design.limits)
    assert not solution.feasible[0] and solution.feasible[1:].all()
    figures = physics(MOTORS, friction, 0.0, True, dwell)
    stats = law_stats_of("cycloidal")
    T = solution.duration[1]
    one = [figures[0][1:2], figures[1], figures[2], figures[3][1:2], figures[4][1:2]]
    assert passes(np.array([T * (1.0 + 1e-9)]), stats, *one, dwell).all()
    assert not passes(np.array([T * (1.0 - 1e-8)]), stats, *one, dwell).any()
    assert not passes(np.array([1e3]), stats, *one, dwell).any()  # a window, not a tail
    reference = reference_duration(stats, figures, dwell)
    np.testing.assert_allclose(solution.duration[2:], reference[2:], rtol=1e-9)


# ------------------------------------------------------------------- auto shapes
def trapezoid_book(a):
    return book_stats(1.0 / (1.0 - a), 1.0 / (a * (1.0 - a)), np.sqrt(2.0 / a) / (1.0 - a))


def double_s_book(a, b):
    c_a = 1.0 / (a * (1.0 - a) * (1.0 - b))
    c_a_rms = np.sqrt((6.0 - 8.0 * b) / (3.0 * a)) / ((1.0 - a) * (1.0 - b))
    return book_stats(1.0 / (1.0 - a), c_a, c_a_rms, c_a / (a * b))


def engine_duration(design: Design, law, rows=None) -> np.ndarray:
    motors = design.motors if rows is None else tuple(design.motors[i] for i in rows)
    calculator = calculator_of(design, law, motors)
    return minimum_duration(calculator, design.limits).duration


def bound_durations(stats, figures, dwell, jerk=None) -> np.ndarray:
    """T_min from each check on its own, arrays (motors, k): the speed, the peaks (each
    move's P a_max + c <= tau_p' and P |a_min| - c <= tau_p', P = J_t K h / T^2, solved
    for T), the jerk, and the RMS by bisection in log T; their largest. The same checks
    as :func:`passes` (compared on samples in the test), cheap enough for a search."""
    J_t, constants, hold, tau_p, tau_c = (np.reshape(x, (-1, 1)) if np.ndim(x) else x
                                          for x in figures)
    T_V = RATIO * stats["v_max"] * H / ((1.0 - SPEED_MARGIN) * RATED)
    grip = np.inf
    for c in constants:
        grip = np.minimum(grip, np.minimum((tau_p - c) / stats["a_max"],
                                           (tau_p + c) / stats["a_min"]))
    T_A = np.sqrt(J_t * RATIO * H / grip)
    T_J = 0.0 if jerk is None else np.cbrt(stats["j_max"] * H / jerk)
    n, c2 = len(constants), sum(c * c for c in constants)
    X, held, limit = n * (J_t * RATIO * H) ** 2 * stats["int_a2"], n * dwell * hold**2, \
        n * tau_c**2
    lo, hi = np.full(np.shape(T_A), math.log(1e-5)), np.full(np.shape(T_A), math.log(1e3))
    for _ in range(56):  # mean square over the cycle <= tau_c'^2
        mid = 0.5 * (lo + hi)
        T = np.exp(mid)
        ok = X / T**3 + c2 * T + held <= limit * (T + dwell)
        hi, lo = np.where(ok, mid, hi), np.where(ok, lo, mid)
    return np.maximum(np.maximum(T_V, T_A), np.maximum(np.exp(hi), T_J))


def golden_min(f, lo: np.ndarray, hi: np.ndarray, width: float = 1e-11) -> np.ndarray:
    """Per element the minimum of a unimodal f on [lo, hi] by golden section."""
    g = (math.sqrt(5.0) - 1.0) / 2.0
    x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
    f1, f2 = f(x1), f(x2)
    while np.max(hi - lo) > width:
        left = f1 <= f2
        hi, lo = np.where(left, x2, hi), np.where(left, lo, x1)
        x2n, x1n = np.where(left, x1, lo + g * (hi - lo)), np.where(left, hi - g * (hi - lo), x2)
        fx = f(np.where(left, x1n, x2n))
        f1, f2 = np.where(left, fx, f2), np.where(left, f1, fx)
        x1, x2 = x1n, x2n
    return np.minimum(f1, f2)


def refine(g, start: np.ndarray, radius: float, low: float, high: float = 0.5,
           points: int = 81) -> np.ndarray:
    """Per motor the least g(a) (arrays (motors, k)) near ``start``: a sample of ``points``
    around the best so far, narrowed to two of its spacings each round."""
    best = start.astype(float).copy()
    while radius > 1e-13:
        a = np.clip(best[:, None] + radius * np.linspace(-1.0, 1.0, points), low, high)
        T = g(a)
        pick = np.argmin(np.where(np.isnan(T), np.inf, T), axis=1)
        best = a[np.arange(len(best)), pick]
        radius *= 4.0 / (points - 1)
    return np.nanmin(T, axis=1)


LOW = 1e-6
AUTO_MOTORS = rectangular_motors(5, low=0.3, span=100.0)


@pytest.mark.parametrize("family,spec", [
    (Trapezoidal, "trapezoidal(alpha=auto)"),
    (DoubleS, "double_s(alpha=auto, beta=auto)"),
])
def test_auto_shape_with_friction_beats_a_grid_of_fixed_laws(family, spec):
    jerk = 2e4 if family is DoubleS else None
    load = (0.5, 0.8, True, 0.15)
    design = make_design(spec, *load, motors=AUTO_MOTORS, jerk=jerk)
    n = len(AUTO_MOTORS)
    _, values = resolve(spec)
    candidates = Candidates.single(MotorArrays.of(design.motors), design.load,
                                   design.transmission)
    chosen = choose_shape(family, values, design, candidates)
    T = np.array([engine_duration(design, law, [i])[0] for i, law in enumerate(chosen)])
    figures = physics(AUTO_MOTORS, *load)
    if family is Trapezoidal:
        grid = np.linspace(0.02, 0.5, 49)[:, None]
        laws = [Trapezoidal(alpha=float(a)) for a in grid[:, 0]]

        def g(a):
            return bound_durations(trapezoid_book(a), figures, load[3])
    else:
        axis = np.linspace(0.05, 0.5, 8)
        grid = np.array([(a, b) for a in axis for b in axis])
        laws = [DoubleS(alpha=float(a), beta=float(b)) for a, b in grid]

        def g(a):  # T is unimodal in beta (T_A, T_R rise with it, T_J falls): golden
            return golden_min(lambda b: bound_durations(double_s_book(a, b), figures,
                                                        load[3], jerk),
                              np.full(a.shape, LOW), np.full(a.shape, 0.5))
    # the bounds' search function is the reference's checks (compared on samples)
    a = np.linspace(0.1, 0.45, 8)[None, :].repeat(len(AUTO_MOTORS), 0)
    stats = trapezoid_book(a) if family is Trapezoidal else double_s_book(a, a * 0.7)
    np.testing.assert_allclose(bound_durations(stats, figures, load[3], jerk),
                               reference_duration(stats, figures, load[3], jerk, a.shape),
                               rtol=1e-12)
    table = np.stack([engine_duration(design, law) for law in laws], axis=1)  # motors x grid
    assert np.isfinite(table).all()
    best = np.argmin(table, axis=1)
    assert np.all(table[np.arange(n), best] * (1.0 + 1e-12) >= T)
    refined = refine(g, grid[best, 0], radius=0.05, low=LOW)
    np.testing.assert_allclose(T, refined, rtol=1e-9)
