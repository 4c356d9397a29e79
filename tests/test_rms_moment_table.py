"""The RMS torques of a cycle from the law's prefix-sum moment table (sizer.sizing.cycle:
moment_table, CycleCalculator._flow_sums) against an independent scalar integration.

The reference integrates the squared torques of the book's sec. 6.1.1 with
scipy.integrate.quad, written out here: the load torque J_l a + B_l v + friction + the
constant load (in the move's direction), each stage reflecting its output torque x to
its input as x/(k eta) while power flows to the load (x >= 0) and x eta/k when it flows
back, plus the stage's own inertia; the motor adds J_m K a + B_m K v. The integration is
cut at the law's piece ends and at every power-flow reversal (roots by brentq), so quad
sees smooth integrands only. The dwells hold the constant load (holding counts as
driving). Two stages, so that both reverse, and laws with jumps of a_N (trapezoid) and
without.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from sizer.laws import make_law
from sizer.mechanics import Drive
from sizer.model import Load, Motor, Stage, Task, Transmission
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.move import CycleCalculator, law_grid, moment_table

H, DWELL = 1.5, 0.2
LOAD = Load(0.05, damping=0.02, friction=0.3, torque=0.4)
STAGES = ((8.0, 0.9, 2e-5), (3.0, 0.95, 1e-4))  # motor side first: ratio, efficiency, inertia
MOTORS = [Motor(f"m{i}", 1e-4 * (i + 1), 1.0 + i, 3.0 + 3 * i, 300.0, damping=1e-3 * i)
          for i in range(3)]


def reflect(x: float, ratio: float, efficiency: float) -> float:
    """A stage's input torque from its output torque, efficiency in the power's direction."""
    return x / (ratio * efficiency) if x >= 0.0 else x * efficiency / ratio


def torques(law, T: float, direction: float, motor: Motor, tau: float):
    """(motor torque, output torque of stage 0, output torque of stage 1) at tau = t/T."""
    a = H / T**2 * float(law.acceleration(tau))
    v = H / T * float(law.velocity(tau))
    (k0, e0, j0), (k1, e1, j1) = STAGES
    x1 = LOAD.inertia * a + LOAD.damping * v + LOAD.friction + direction * LOAD.torque
    x0 = j1 * k1 * a + reflect(x1, k1, e1)
    shaft = j0 * k0 * k1 * a + reflect(x0, k0, e0)
    K = k0 * k1
    return motor.inertia * K * a + motor.damping * K * v + shaft, x0, x1


def reference_rms(law, T: float, motor: Motor) -> np.ndarray:
    """RMS of the motor torque and of the two stage outputs over move, dwell, return, dwell."""
    from scipy import integrate, optimize

    ends = sorted({p.start for p in law.pieces} | {p.end for p in law.pieces} | {0.0, 1.0})
    squares = np.zeros(3)
    known: dict[tuple[float, float], tuple[float, float, float]] = {}

    def torques(law, T, direction, motor, tau):
        """The module's torques, each (direction, tau) computed once: the scans of channels
        1 and 2 and the three channels' quads ask for the same points (same values)."""
        key = (direction, float(tau))
        if key not in known:
            known[key] = globals()["torques"](law, T, direction, motor, tau)
        return known[key]

    for direction in (1.0, -1.0):
        cuts = set(ends)
        for lo, hi in itertools.pairwise(ends):
            # the ends nudged inside: one piece throughout (its one-sided values there)
            inner = np.linspace(lo + 1e-13, hi - 1e-13, 401)
            for channel in (1, 2):
                f = [torques(law, T, direction, motor, t)[channel] for t in inner]
                for i in range(len(inner) - 1):
                    if f[i] * f[i + 1] < 0.0:
                        cuts.add(optimize.brentq(
                            lambda t, c=channel, d=direction: torques(law, T, d, motor, t)[c],
                            inner[i], inner[i + 1], xtol=1e-15, rtol=1e-15))
        cuts_sorted = sorted(cuts)
        for channel in range(3):
            for lo, hi in itertools.pairwise(cuts_sorted):
                def square(t, c=channel, lo=lo, hi=hi, d=direction):
                    # strictly inside (lo, hi): one piece and one flow direction (no kink)
                    t = min(max(t, lo + 1e-15), hi - 1e-15)
                    return torques(law, T, d, motor, t)[c] ** 2

                value, _ = integrate.quad(square, lo, hi, epsabs=0.0, epsrel=1e-13, limit=200)
                squares[channel] += T * value
    (k0, e0, _), (k1, e1, _) = STAGES
    hold = abs(LOAD.torque)
    holds = np.array([hold / (k0 * e0 * k1 * e1), hold / (k1 * e1), hold])
    return np.sqrt((squares + 2 * DWELL * holds**2) / (2 * (T + DWELL)))


def calculator(law) -> CycleCalculator:
    drive = Drive(LOAD, Transmission(tuple(Stage(f"s{i}", k, e, j)
                                           for i, (k, e, j) in enumerate(STAGES))))
    return CycleCalculator(None, Task(H, None, dwell=DWELL, return_move=True), drive,
                           MotorArrays.of(MOTORS, "book"), law=law)


@pytest.mark.parametrize("spec", ["cycloidal", "trapezoidal(alpha=1/3)", "poly5",
                                  "double_s(alpha=1/3, beta=1/4)"])
def test_rms_from_the_moment_table_equals_quad_with_the_power_flow_rule(spec):
    law = make_law(spec)
    calc = calculator(law)
    # short moves: inertia dominates and every stage reverses while decelerating; long
    # ones: friction and the constant load keep the flow one way through most of a move
    T = np.array([0.08, 0.3, 2.5])
    metrics = calc.evaluate(T, peaks=False)
    reversed_somewhere = False
    for i, t in enumerate(T):
        want = reference_rms(law, float(t), MOTORS[i])
        got = np.array([metrics.rms_torque[i], metrics.stage_rms[0][i], metrics.stage_rms[1][i]])
        np.testing.assert_allclose(got, want, rtol=1e-9, err_msg=f"{spec} T={t}")
        signs = {np.sign(torques(law, float(t), 1.0, MOTORS[i], x)[2])
                 for x in np.linspace(0.01, 0.99, 99)}
        reversed_somewhere |= signs == {-1.0, 1.0}
    assert reversed_somewhere  # the case the split points are for


def test_the_table_is_the_running_integral_of_the_law_moments():
    """Its rows are the integrals from 0 to each grid edge (quad of a_N^2, ..., v_N)."""
    from scipy import integrate

    law = make_law("modified_trapezoidal")
    table = moment_table(law)
    edges = np.append(law_grid(law).left, 1.0)
    assert table.shape == (len(edges), 6) and not table[0].any()
    functions = [lambda t: law.acceleration(t) ** 2, lambda t: law.velocity(t) ** 2,
                 lambda t: 1.0, lambda t: law.acceleration(t) * law.velocity(t),
                 lambda t: law.acceleration(t), lambda t: law.velocity(t)]
    breaks = sorted({p.end for p in law.pieces})
    for row in (len(edges) // 3, len(edges) // 2, len(edges) - 1):
        for column, f in enumerate(functions):
            stops = [0.0] + [b for b in breaks if b < edges[row]] + [edges[row]]
            want = sum(integrate.quad(lambda t, f=f: float(f(t)), lo, hi, epsabs=1e-14,
                                      epsrel=1e-13, limit=200)[0]
                       for lo, hi in itertools.pairwise(stops) if hi > lo)
            assert table[row, column] == pytest.approx(want, rel=1e-11, abs=1e-13)
