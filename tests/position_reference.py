"""An independent reference for the position-load tests (issue 38, book sec. 5.2.2): a
move's torques from their closed forms, each test's subclass giving the load's torque and
the knots of its table; the peak on a dense grid refined by scipy's bounded search on each
smooth piece (between knot crossings and power-flow reversals found by brentq), the RMS by
scipy.integrate.quad split there. No sizer code computes any of it."""

from __future__ import annotations

import math
from itertools import pairwise

import numpy as np

from sizer.laws import law_choice
from sizer.mechanics.drive import Drive
from sizer.model.cycle import Task
from sizer.model.domain import Load, Motor, Stage, Transmission
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.linkage_move import position_calculator

ROTOR_GEAR = 5e-6
N_GEAR = 5.0


def falling(k: int) -> Motor:
    tp, vn = 2.0 + 3.0 * k, 150.0 + 25.0 * k
    return Motor(id=f"f{k}", inertia=1e-4 * (1 + k), continuous_torque=tp / 3, peak_torque=tp,
                 rated_speed=vn, max_speed=2 * vn,
                 intermittent_curve=((0.0, tp), (0.8 * vn, tp), (1.4 * vn, 0.7 * tp),
                                     (2 * vn, 0.35 * tp)),
                 continuous_curve=((0.0, tp / 3), (2 * vn, tp / 5)))


def flat(k: int, peak: float, continuous: float, speed: float = 300.0) -> Motor:
    return Motor(id=f"m{k}", inertia=1e-4, continuous_torque=continuous, peak_torque=peak,
                 rated_speed=speed, max_speed=speed,
                 intermittent_curve=((0.0, peak), (speed, peak)),
                 continuous_curve=((0.0, continuous), (speed, continuous)))


class PiecewiseReference:
    """A move by ``law`` over ``h`` (rad) through a gearbox N_GEAR of efficiency ``eta``;
    subclasses give ``load_torque(t, T)``, ``torque(t, T, rotor)``, ``hold()`` and
    ``knots`` (the positions from the move's start where the load's torque has a kink)."""

    knots: np.ndarray
    h: float
    law: object

    def motion(self, t, T: float):
        u = np.clip(np.atleast_1d(np.asarray(t, dtype=float)) / T, 0.0, 1.0)
        q, v, a = (self.law.derivative(u, k) for k in range(3))
        return self.h * q, self.h * v / T, self.h * a / T**2

    def load_torque(self, t, T: float):
        raise NotImplementedError

    def torque(self, t, T: float, rotor: float):
        raise NotImplementedError

    def hold(self) -> float:
        raise NotImplementedError

    def edges(self, T: float) -> list[float]:
        """0, every time the position crosses a knot or the power flow reverses, T."""
        from scipy.optimize import brentq

        t = np.linspace(0.0, T, 4001)
        cuts = []
        for knot in self.knots:
            f = self.motion(t, T)[0] - knot
            cuts += [brentq(lambda s, k=knot: float(self.motion(s, T)[0][0] - k), t[i], t[i + 1],
                            xtol=1e-16, rtol=1e-15)
                     for i in np.flatnonzero(f[:-1] * f[1:] < 0.0)]
        flow = self.load_torque(t, T) * self.motion(t, T)[1]
        cuts += [brentq(lambda s: float((self.load_torque(s, T) * self.motion(s, T)[1])[0]),
                        t[i], t[i + 1], xtol=1e-16, rtol=1e-15)
                 for i in np.flatnonzero(flow[:-1] * flow[1:] < 0.0)]
        return [0.0, *sorted(cuts), T]

    def peak(self, T: float, rotor: float, dwell: float) -> float:
        from scipy.optimize import minimize_scalar

        best = 0.0
        for lo, hi in pairwise(self.edges(T)):  # smooth on each piece
            t = np.linspace(lo, hi, 401)
            values = np.abs(self.torque(t, T, rotor))
            best = max(best, float(values.max()))
            i = int(np.argmax(values))
            a, b = t[max(i - 1, 0)], t[min(i + 1, len(t) - 1)]
            found = minimize_scalar(lambda s: -abs(self.torque(s, T, rotor)[0]), bounds=(a, b),
                                    method="bounded", options={"xatol": 1e-15 * T})
            best = max(best, -float(found.fun))
        return max(best, self.hold()) if dwell > 0.0 else best

    def rms(self, T: float, rotor: float, dwell: float) -> float:
        from scipy.integrate import quad

        square = sum(quad(lambda s: self.torque(s, T, rotor)[0] ** 2, lo, hi, limit=200,
                          epsabs=0.0, epsrel=1e-13)[0] for lo, hi in pairwise(self.edges(T)))
        return math.sqrt((square + dwell * self.hold() ** 2) / (T + dwell))


def calculator(load: Load, h: float, law: str, motors, eta: float, duration, dwell: float):
    drive = Drive(load, Transmission(stages=(Stage(ratio=N_GEAR, efficiency=eta,
                                                   inertia=ROTOR_GEAR),)))
    return position_calculator(Task(h, duration, dwell=dwell), law_choice(law).law, load,
                               drive, MotorArrays.of(motors, "electrical"))
