"""The exact requirements of piecewise-polynomial moves (sizer.sizing.polynomial_move):
rest-to-rest moves against the engine (sizer.sizing.cycle), moves with boundary speeds and
a reversing move against a plain scalar evaluation integrated by scipy's quad and
maximized by dense sampling and scipy's minimize_scalar, and the kinetic energy of a pure
inertia."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sizer.laws import make_law
from sizer.mechanics import Drive
from sizer.model.domain import Load, Motor, Stage, Task, Transmission
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.move import CycleCalculator, polynomial_move

RPM = math.pi / 30.0
RATED = 3000.0 * RPM


def curve(peak: float) -> tuple[tuple[float, float], ...]:
    """A falling intermittent curve: flat to 0.8 v_n, then down to 0.35 of the peak at 2 v_n."""
    return ((0.0, peak), (0.8 * RATED, peak), (1.4 * RATED, 0.7 * peak),
            (2.0 * RATED, 0.35 * peak))


def curved_motors(count: int) -> MotorArrays:
    motors = []
    for i in range(count):
        torque = 0.5 * 3.0**i
        motors.append(Motor(f"m{i}", 2e-5 * torque**1.3, torque, 3.0 * torque, RATED,
                            max_speed=2.0 * RATED, intermittent_curve=curve(3.0 * torque),
                            continuous_curve=((0.0, 1.05 * torque), (RATED, torque),
                                              (2.0 * RATED, 0.5 * torque)),
                            damping=1e-4 * torque))
    return MotorArrays.of(motors)


STAGES = (Stage("gearbox", 5.0, 0.9, 2e-5, preload_torque=0.02, rated_output_torque=30.0,
                peak_output_torque=80.0),
          Stage("belt", 2.0, 0.85, 1e-5, rated_output_torque=60.0))
LOAD = Load(0.05, damping=0.02, friction=0.3, torque=0.4)


def real_drive(rule: str = "power_flow", count: int | None = None) -> Drive:
    """The drive; with ``count``, two transmission options (the second with other ratios
    and efficiencies) alternating over ``count`` candidates."""
    if count is None:
        return Drive(LOAD, Transmission(STAGES, efficiency_applies_to=rule))
    other = (Stage("gearbox", 7.0, 0.8, 3e-5, preload_torque=0.01, rated_output_torque=40.0,
                   peak_output_torque=90.0),
             Stage("belt", 1.5, 0.95, 2e-5, rated_output_torque=50.0))
    options = [Transmission(STAGES, efficiency_applies_to=rule),
               Transmission(other, efficiency_applies_to=rule)]
    return Drive(LOAD, options, option=np.arange(count) % 2)


def poly5(h: float, T: np.ndarray):
    """h (10 u^3 - 15 u^4 + 6 u^5), u = t/T: one piece."""
    breaks = np.column_stack((np.zeros_like(T), T))
    coefficients = np.zeros((len(T), 1, 6))
    coefficients[:, 0, 3] = 10.0 * h / T**3
    coefficients[:, 0, 4] = -15.0 * h / T**4
    coefficients[:, 0, 5] = 6.0 * h / T**5
    return breaks, coefficients


def trapezoid(h: float, T: np.ndarray, alpha: float):
    """Trapezoidal speed, T_a = alpha T: three pieces."""
    Ta = alpha * T
    top = h / (T * (1.0 - alpha))
    acc = top / Ta
    breaks = np.column_stack((np.zeros_like(T), Ta, T - Ta, T))
    coefficients = np.zeros((len(T), 3, 3))
    coefficients[:, 0, 2] = 0.5 * acc
    coefficients[:, 1, 0] = 0.5 * acc * Ta**2
    coefficients[:, 1, 1] = top
    coefficients[:, 2, 0] = h - 0.5 * acc * Ta**2
    coefficients[:, 2, 1] = top
    coefficients[:, 2, 2] = -0.5 * acc
    return breaks, coefficients


# durations: speeds on the flat part, on each falling segment and past the region's end
DURATIONS = np.array([0.02, 0.025, 0.03, 0.04, 0.05, 0.06, 0.12, 0.5])


@pytest.mark.parametrize("options", [False, True])
@pytest.mark.parametrize("rule", ["power_flow", "steady_load"])
@pytest.mark.parametrize("h", [1.0, -1.0])
@pytest.mark.parametrize("law", ["poly5", "trapezoidal(alpha=1/4)"])
def test_rest_to_rest_moves_equal_the_engine(law, h, rule, options):
    n = len(DURATIONS)
    motors = curved_motors(4).subset(np.arange(n) % 4)
    drive = real_drive(rule, n if options else None)
    T = DURATIONS
    engine = CycleCalculator(None, Task(h, 0.1, 0.0, False), drive, motors,
                             law=make_law(law)).evaluate(T)
    shape = poly5(h, T) if law == "poly5" else trapezoid(h, T, 0.25)
    mine = polynomial_move(*shape, drive, motors, math.copysign(1.0, h))
    assert np.any(engine.max_speed > 0.8 * RATED)  # the falling region is reached
    assert np.any(engine.max_speed > 2.0 * RATED)  # and left
    assert np.any(engine.stage_peak[0] > 0.0)
    close = {"rtol": 1e-9, "atol": 0.0}
    np.testing.assert_allclose(mine.peak_torque, engine.peak_torque, **close)
    np.testing.assert_allclose(mine.peak_ratio, engine.peak_ratio, **close)
    np.testing.assert_allclose(mine.torque_square, engine.rms_torque**2 * T, **close)
    np.testing.assert_allclose(mine.load_torque, engine.load_torque, **close)
    np.testing.assert_allclose(mine.max_speed, engine.max_speed, **close)
    np.testing.assert_allclose(mine.load_speed, engine.load_speed, **close)
    np.testing.assert_allclose(mine.load_acceleration, engine.load_acceleration, **close)
    for i in range(len(STAGES)):
        np.testing.assert_allclose(mine.stage_peak[i], engine.stage_peak[i], **close)
        np.testing.assert_allclose(mine.stage_square[i], engine.stage_rms[i] ** 2 * T, **close)
        np.testing.assert_allclose(mine.stage_speed[i], engine.stage_speed[i], **close)
    if law == "poly5":  # jerk 60 h / T^3 at the ends
        np.testing.assert_allclose(mine.load_jerk, 60.0 * abs(h) / T**3, **close)
    else:  # the acceleration jumps inside the move
        assert np.all(np.isinf(mine.load_jerk))


# ------------------------------------------------------- a plain scalar reference
def hermite(x0: float, x1: float, v0: float, v1: float, T: float) -> np.ndarray:
    """Ascending coefficients of the cubic from (x0, v0) to (x1, v1) in T."""
    h = x1 - x0
    return np.array([x0, v0, 3.0 * h / T**2 - (2.0 * v0 + v1) / T,
                     (v0 + v1) / T**2 - 2.0 * h / T**3])


class Scalar:
    """One candidate's move evaluated plainly at a time t (no vectorization)."""

    def __init__(self, breaks, coefficients, motor: Motor, direction: float) -> None:
        self.breaks, self.coefficients = breaks, coefficients
        self.motor, self.direction = motor, direction
        self.K = math.prod(s.ratio for s in STAGES)
        self.speeds = np.array([p[0] for p in motor.intermittent_curve])
        self.torques = np.array([p[1] for p in motor.intermittent_curve])

    def motion(self, t: float):
        p = min(max(int(np.searchsorted(self.breaks, t, side="right")) - 1, 0),
                len(self.coefficients) - 1)
        c = self.coefficients[p]
        s = t - self.breaks[p]
        x = sum(c[k] * s**k for k in range(len(c)))
        v = sum(k * c[k] * s ** (k - 1) for k in range(1, len(c)))
        a = sum(k * (k - 1) * c[k] * s ** (k - 2) for k in range(2, len(c)))
        return x, v, a

    def channels(self, t: float):
        """(motor torque, motor speed, [stage output torques], load torque) at t."""
        _, v, a = self.motion(t)
        sense = 1.0 if v > 0 else (-1.0 if v < 0 else self.direction)
        a_l, v_l = sense * a, sense * v
        u = (LOAD.inertia * a_l + LOAD.damping * v_l + LOAD.friction + sense * LOAD.torque)
        x, outputs = u, [u]
        k_in = 1.0
        inputs = []
        for stage in reversed(STAGES):
            k_in *= stage.ratio
            inputs.append(k_in)
        for stage, k in zip(reversed(STAGES), inputs, strict=True):
            reflected = (x / (stage.ratio * stage.efficiency) if x >= 0
                         else x * stage.efficiency / stage.ratio)
            x = stage.inertia * k * a_l + stage.preload_torque + reflected
            outputs.append(x)
        shaft = outputs.pop()
        along = (self.motor.inertia * self.K * a_l + self.motor.damping * self.K * v_l
                 + shaft)
        return sense * along, self.K * v, outputs[::-1], u

    def ratio(self, torque: float, speed: float) -> float:
        """|tau| / tau_int(|omega|), the speed clipped into the region."""
        limit = np.interp(min(abs(speed), self.speeds[-1]), self.speeds, self.torques)
        return abs(torque) / limit

    def speed_roots(self) -> list[float]:
        """Where v = 0 inside the move (friction turns there)."""
        out = []
        for p, c in enumerate(self.coefficients):
            for r in np.roots((np.arange(1, len(c)) * c[1:])[::-1]):
                width = self.breaks[p + 1] - self.breaks[p]
                if abs(r.imag) < 1e-12 and 0.0 < r.real < width:
                    out.append(self.breaks[p] + r.real)
        return out


def quintic(x0: float, x1: float, v0: float, v1: float, T: float) -> np.ndarray:
    """Ascending coefficients of the quintic from (x0, v0) to (x1, v1) in T, at rest
    in acceleration at both ends (a linear system solved here)."""
    rows = []
    for t in (0.0, T):
        rows.append([t**k for k in range(6)])
        rows.append([k * t ** (k - 1) if k else 0.0 for k in range(6)])
        rows.append([k * (k - 1) * t ** (k - 2) if k > 1 else 0.0 for k in range(6)])
    return np.linalg.solve(np.array(rows), np.array([x0, v0, 0.0, x1, v1, 0.0]))


def boundary_moves():
    """Four candidates with boundary speeds: a cubic (two pieces of one polynomial), a
    quintic, a move of two quintics that starts forward, reverses and ends forward, and a
    cubic whose speed k (t - t0)^2 stops for an instant and goes on."""
    T = np.array([0.05, 0.08, 0.11, 0.09])
    breaks = np.zeros((4, 3))
    coefficients = np.zeros((4, 2, 6))
    c = hermite(0.0, 0.9, 10.0, 35.0, T[0])
    cut = 0.4 * T[0]
    breaks[0] = (0.0, cut, T[0])
    coefficients[0, 0, :4] = c
    coefficients[0, 1, :4] = np.polynomial.Polynomial(c)(
        np.polynomial.Polynomial([cut, 1.0])).coef
    breaks[1] = (0.0, 0.5 * T[1], T[1])
    c = quintic(0.0, 1.2, 30.0, 5.0, T[1])
    coefficients[1, 0] = c
    coefficients[1, 1] = np.polynomial.Polynomial(c)(
        np.polynomial.Polynomial([0.5 * T[1], 1.0])).coef
    half = 0.5 * T[2]
    breaks[2] = (0.0, half, T[2])
    coefficients[2, 0] = quintic(0.0, 0.1, 20.0, -8.0, half)
    coefficients[2, 1] = quintic(0.1, 0.3, -8.0, 28.0, half)
    t0 = 0.4 * T[3]
    k = 30.0 / (T[3] - t0) ** 2
    breaks[3] = (0.0, 0.5 * T[3], T[3])
    coefficients[3, 0, :4] = (0.0, k * t0**2, -k * t0, k / 3.0)
    coefficients[3, 1, :4] = np.polynomial.Polynomial(coefficients[3, 0, :4])(
        np.polynomial.Polynomial([0.5 * T[3], 1.0])).coef
    return breaks, coefficients


def _integral(f, scalar: Scalar, T: float) -> float:
    from scipy.integrate import quad

    points = sorted({*scalar.breaks[1:-1], *scalar.speed_roots()})
    value, _ = quad(f, 0.0, T, points=points or None, limit=400, epsabs=0.0, epsrel=1e-13)
    return value


def _refined(f, t: np.ndarray, values: np.ndarray) -> tuple[float, float]:
    """max of f from its dense samples ``values`` at ``t``, then by minimize_scalar
    between the best sample's neighbours (in the offset from the left one, so that its
    relative tolerance reaches a peak at a jump of the friction): (sampled, refined)."""
    from scipy.optimize import minimize_scalar

    best = int(np.argmax(values))
    lo, hi = t[max(best - 1, 0)], t[min(best + 1, len(t) - 1)]
    found = minimize_scalar(lambda x: -f(lo + x), bounds=(0.0, hi - lo), method="bounded",
                            options={"xatol": 1e-16 * t[-1]})
    return values[best], max(values[best], -found.fun)


@pytest.fixture(scope="module")
def boundary_case():
    breaks, coefficients = boundary_moves()
    motors = curved_motors(4)
    figures = polynomial_move(breaks, coefficients, real_drive(), motors, 1.0)
    scalars = [Scalar(breaks[i], coefficients[i], motors.motors[i], 1.0) for i in range(4)]
    return figures, scalars, breaks[:, -1]


def test_the_reversing_move_reverses(boundary_case):
    _, scalars, _ = boundary_case
    assert len(scalars[2].speed_roots()) == 2
    assert not scalars[0].speed_roots() and not scalars[1].speed_roots()
    t0 = 0.4 * scalars[3].breaks[-1]
    assert scalars[3].motion(t0)[1] == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize("row", range(4))
def test_integrals_with_boundary_speeds_equal_quad(boundary_case, row):
    figures, scalars, T = boundary_case
    s, duration = scalars[row], T[row]
    close = {"rtol": 1e-9, "atol": 0.0}
    np.testing.assert_allclose(
        figures.torque_square[row], _integral(lambda t: s.channels(t)[0] ** 2, s, duration),
        **close)
    for i in range(len(STAGES)):
        np.testing.assert_allclose(
            figures.stage_square[i][row],
            _integral(lambda t, i=i: s.channels(t)[2][i] ** 2, s, duration), **close)
    np.testing.assert_allclose(
        figures.speed_square[row], _integral(lambda t: s.channels(t)[1] ** 2, s, duration),
        **close)
    np.testing.assert_allclose(
        figures.speed_abs[row], _integral(lambda t: abs(s.channels(t)[1]), s, duration),
        **close)
    energy = _integral(lambda t: s.channels(t)[0] * s.channels(t)[1], s, duration)
    np.testing.assert_allclose(figures.energy[row], energy, **close)


@pytest.mark.parametrize("row", range(4))
def test_peaks_with_boundary_speeds_equal_sampling_and_refinement(boundary_case, row):
    figures, scalars, T = boundary_case
    s, duration = scalars[row], T[row]
    exact = [figures.peak_torque[row], figures.peak_ratio[row], figures.load_torque[row],
             figures.max_speed[row], figures.load_acceleration[row],
             *(figures.stage_peak[i][row] for i in range(len(STAGES)))]

    def plain(t: float) -> list[float]:
        """|tau|, the ratio, |u|, |omega|, |a| and each |stage output| at t."""
        torque, speed, stages, load = s.channels(t)
        return [abs(torque), s.ratio(torque, speed), abs(load), abs(speed), abs(s.motion(t)[2]),
                *(abs(x) for x in stages)]

    t = np.linspace(0.0, duration, 20001)
    samples = np.array([plain(x) for x in t])
    for k, value in enumerate(exact):
        sampled, refined = _refined(lambda x, k=k: plain(x)[k], t, samples[:, k])
        assert sampled <= value * (1.0 + 1e-12)
        assert value <= sampled * (1.0 + 1e-3)  # the sampling's resolution
        np.testing.assert_allclose(value, refined, rtol=1e-9)
    assert figures.max_speed[row] == pytest.approx(s.K * figures.load_speed[row], rel=1e-15)


def test_the_figures_see_the_falling_region(boundary_case):
    """The boundary moves reach the curve's falling part (the ratio is not peak/flat)."""
    figures, _, _ = boundary_case
    assert np.all(figures.max_speed > 0.8 * RATED)


def test_energy_of_a_pure_inertia_is_its_kinetic_energy():
    """From rest to speed w through an ideal gearbox: 1/2 J omega^2 at the motor."""
    J_load, J_gear, ratio, w = 0.3, 4e-5, 6.0, 20.0
    motors = MotorArrays.of([Motor("a", 2e-4, 5.0, 15.0, 1e4), Motor("b", 7e-4, 9.0, 30.0, 1e4)])
    drive = Drive(Load(J_load), Transmission((Stage("gearbox", ratio, 1.0, J_gear),)))
    T = np.array([0.2, 0.35])
    breaks = np.column_stack((np.zeros(2), T))
    coefficients = np.stack([hermite(0.0, 0.55 * w * t, 0.0, w, t) for t in T])[:, None, :]
    figures = polynomial_move(breaks, coefficients, drive, motors, 1.0)
    J = motors.inertia + J_gear + J_load / ratio**2
    np.testing.assert_allclose(figures.energy, 0.5 * J * (ratio * w) ** 2, rtol=1e-12)
