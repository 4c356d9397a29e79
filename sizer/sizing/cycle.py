"""The machine cycle of one law for many candidates at once (book sec. 6.1.1).

For each candidate (a motor with its own duration T) the cycle is: move |h| in T, dwell,
and with a return move the same back and a second dwell. Per move the motor torque is

    tau(t) = (J_m + J_gear) k a(t) + B_m k v(t) + reflect(J_l a + B_l v + F +- tau_ext)

with a, v the load's acceleration and speed, k the ratio and reflect() applying the
efficiency in the direction of power flow (sizer.mechanics.drive). During a dwell the
motor holds the constant external load. The RMS torque covers the whole cycle.

Integrals are exact: Gauss-Legendre on the law's grid, each interval split where the
power flow reverses; with eta = 1 the RMS is the closed form in C_v_rms, C_a_rms.
Peaks are found on the grid and refined by golden-section search.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.polynomial.legendre import leggauss

from sizer.mechanics import Drive
from sizer.model.domain import Task, ThermalSpeedRule
from sizer.sizing.grid import LawGrid, PieceEvaluator, law_grid
from sizer.sizing.motors import MotorArrays

GOLDEN_STEPS = 40
ROOT_STEPS = 60
INV_PHI = (math.sqrt(5.0) - 1.0) / 2.0


@dataclass(frozen=True)
class CycleMetrics:
    """Requirements of one law for each candidate (arrays over candidates, SI, motor side)."""

    duration: np.ndarray
    max_speed: np.ndarray
    peak_torque: np.ndarray
    peak_ratio: np.ndarray
    rms_torque: np.ndarray
    thermal_speed: np.ndarray
    load_speed: np.ndarray
    load_acceleration: np.ndarray
    load_jerk: np.ndarray


class CycleCalculator:
    """Evaluates the cycle of one law for candidate motors at candidate durations."""

    def __init__(self, grid: LawGrid | None, task: Task, drive: Drive, motors: MotorArrays,
                 thermal_speed: ThermalSpeedRule = "max", law=None) -> None:
        self._grid = grid
        self.law = grid.law if grid is not None else law
        self.task = task
        self.drive = drive
        self.motors = motors
        self.thermal_rule = thermal_speed
        self.h = abs(task.displacement)
        sign = 1.0 if task.displacement >= 0 else -1.0
        self.directions = (sign, -sign) if task.return_move else (sign,)

    @property
    def grid(self) -> LawGrid:
        """The law's sampling grid, built on first use (the closed forms need none)."""
        if self._grid is None:
            self._grid = law_grid(self.law)
        return self._grid

    # ------------------------------------------------------------------ public
    def evaluate(self, duration: np.ndarray) -> CycleMetrics:
        T = np.broadcast_to(np.asarray(duration, dtype=float), (len(self.motors),)).copy()
        c = self.law.coefficients
        k, h = self.drive.ratio, self.h
        load_speed = c.C_v * h / T
        max_speed = k * load_speed
        peak_torque = np.zeros_like(T)
        peak_ratio = np.zeros_like(T)
        move_square = np.zeros_like(T)
        for direction in self.directions:
            torque, ratio = self._peaks(T, direction)
            peak_torque = np.maximum(peak_torque, torque)
            peak_ratio = np.maximum(peak_ratio, ratio)
            move_square += T * self._mean_square(T, direction)
        dwell = self.task.dwell
        n = len(self.directions)
        hold = self.drive.holding_torque
        if dwell > 0.0 and hold > 0.0:
            peak_torque = np.maximum(peak_torque, hold)
            hold_limit = self.motors.intermittent.limit(np.zeros_like(T))
            peak_ratio = np.maximum(peak_ratio, _safe_ratio(np.full_like(T, hold), hold_limit))
        cycle = n * (T + dwell)
        rms = np.sqrt((move_square + n * dwell * hold**2) / cycle)
        if self.thermal_rule == "max":
            thermal = max_speed
        elif self.thermal_rule == "rms":
            thermal = k * h * c.C_v_rms * np.sqrt(n * T / cycle) / T
        else:
            thermal = n * k * h / cycle
        jerk = c.C_j * h / T**3 if c.jerk_bounded else np.full_like(T, np.inf)
        return CycleMetrics(T, max_speed, peak_torque, peak_ratio, rms, thermal, load_speed,
                            c.C_a * h / T**2, jerk)

    # ---------------------------------------------------------------- torques
    def _coefficients(self, T: np.ndarray, direction: float):
        """Per-candidate factors: motor part P*a_N + Q*v_N and load part alpha*a_N + ..."""
        drive, h, k = self.drive, self.h, self.drive.ratio
        rotor = self.motors.inertia + drive.transmission_inertia
        p = rotor * k * h / T**2
        q = self.motors.damping * k * h / T
        load = drive.load
        alpha = load.inertia * h / T**2
        beta = load.damping * h / T
        gamma = load.friction + direction * load.torque
        return p, q, alpha, beta, gamma

    def _torque(self, a_n, v_n, factors, index=None):
        """Motor torque at normalized a_N, v_N (candidate-major arrays)."""
        p, q, alpha, beta, gamma = factors
        if index is not None:
            p, q, alpha, beta = p[index], q[index], alpha[index], beta[index]
        shape = (-1,) + (1,) * (np.ndim(a_n) - 1)
        p, q, alpha, beta = (np.reshape(x, shape) for x in (p, q, alpha, beta))
        u = alpha * a_n + beta * v_n + gamma
        return p * a_n + q * v_n + self.drive.reflect(u)

    def _mean_square(self, T: np.ndarray, direction: float) -> np.ndarray:
        """(1/T) * integral of tau^2 over one move, for each candidate."""
        factors = self._coefficients(T, direction)
        p, q, alpha, beta, gamma = factors
        c = self.law.coefficients
        if self.drive.efficiency == 1.0:
            k = self.drive.ratio
            a_part, v_part, const = p + alpha / k, q + beta / k, gamma / k
            # int a_N = 0, int a_N v_N = 0 and int v_N = 1 over a rest-to-rest move
            return (a_part * c.C_a_rms) ** 2 + (v_part * c.C_v_rms) ** 2 + const**2 \
                + 2.0 * v_part * const
        g = self.grid
        a_n, v_n = g.acceleration[None], g.velocity[None]
        torque = self._torque(a_n, v_n, factors)
        u_ends = (alpha[:, None, None] * g.end_acceleration[None]
                  + beta[:, None, None] * g.end_velocity[None] + gamma)
        crossing = u_ends[..., 0] * u_ends[..., 1] < 0.0
        plain = np.where(crossing[..., None], 0.0, g.weights[None] * torque**2)
        total = plain.sum(axis=(1, 2))
        if crossing.any():
            total += self._split_integrals(np.nonzero(crossing), factors)
        return total

    def _split_integrals(self, where, factors) -> np.ndarray:
        """Integrals of tau^2 over base intervals where the power flow reverses.

        The interval is cut at the root of the load torque (bisection), and each side is
        integrated with Gauss-Legendre, so the kink of reflect() is never inside a rule.
        """
        cand, interval = where
        g = self.grid
        law = self.law
        piece = g.piece[interval]
        _, _, alpha, beta, gamma = factors
        at = PieceEvaluator(law, piece)

        def load_torque(tau):
            return alpha[cand] * at(tau, 2) + beta[cand] * at(tau, 1) + gamma

        lo, hi = g.left[interval].copy(), g.right[interval].copy()
        f_lo = load_torque(lo)
        for _ in range(ROOT_STEPS):
            mid = 0.5 * (lo + hi)
            f_mid = load_torque(mid)
            same = np.sign(f_mid) == np.sign(f_lo)
            lo, f_lo = np.where(same, mid, lo), np.where(same, f_mid, f_lo)
            hi = np.where(same, hi, mid)
        root = 0.5 * (lo + hi)
        x, w = leggauss(self.grid.nodes.shape[1])
        total = np.zeros(len(self.motors))
        for a, b in ((g.left[interval], root), (root, g.right[interval])):
            half = 0.5 * (b - a)
            tau = (0.5 * (a + b))[:, None] + half[:, None] * x
            on_pieces = PieceEvaluator(law, np.broadcast_to(piece[:, None], tau.shape))
            a_n, v_n = on_pieces(tau, 2), on_pieces(tau, 1)
            torque = self._torque(a_n, v_n, factors, index=cand)
            np.add.at(total, cand, (half[:, None] * w * torque**2).sum(axis=1))
        return total

    # ------------------------------------------------------------------ peaks
    def _peaks(self, T: np.ndarray, direction: float) -> tuple[np.ndarray, np.ndarray]:
        """max |tau| and max |tau|/tau_int(|omega|) over one move, for each candidate."""
        g = self.grid
        factors = self._coefficients(T, direction)
        speed_scale = self.drive.ratio * self.h / T
        # samples: the nodes, and both one-sided ends of every interval
        tau = np.concatenate((g.left[:, None], g.nodes, g.right[:, None]), axis=1)
        a_n = np.concatenate((g.end_acceleration[:, :1], g.acceleration,
                              g.end_acceleration[:, 1:]), axis=1)
        v_n = np.concatenate((g.end_velocity[:, :1], g.velocity, g.end_velocity[:, 1:]), axis=1)
        torque = np.abs(self._torque(a_n[None], v_n[None], factors))
        peak = self._refine(torque, tau, factors, speed_scale, by_ratio=False)
        if self.motors.all_rectangular:  # flat limit: the ratio peaks with the torque
            return peak, _safe_ratio(peak, self.motors.intermittent.torques[:, 0])
        speed = speed_scale[:, None, None] * v_n[None]
        ratio = _safe_ratio(torque, self.motors.intermittent.limit_clipped(speed))
        return peak, self._refine(ratio, tau, factors, speed_scale, by_ratio=True)

    def _refine(self, values, tau, factors, speed_scale, by_ratio: bool) -> np.ndarray:
        """Golden-section refinement of the best sample of each candidate."""
        g = self.grid
        count = len(values)
        flat = values.reshape(count, -1)
        best = np.argmax(flat, axis=1)
        best_value = flat[np.arange(count), best]
        interval, column = np.divmod(best, tau.shape[1])
        lo = tau[interval, np.maximum(column - 1, 0)]
        hi = tau[interval, np.minimum(column + 1, tau.shape[1] - 1)]
        at = PieceEvaluator(self.law, g.piece[interval])

        def objective(x):
            a_n, v_n = at(x, 2), at(x, 1)
            torque = np.abs(self._torque(a_n, v_n, factors))
            if not by_ratio:
                return torque
            limit = self.motors.intermittent.limit_clipped(speed_scale * v_n)
            return _safe_ratio(torque, limit)

        x1 = hi - INV_PHI * (hi - lo)
        x2 = lo + INV_PHI * (hi - lo)
        f1, f2 = objective(x1), objective(x2)
        for _ in range(GOLDEN_STEPS):
            left = f1 >= f2  # the maximum lies in [lo, x2]
            hi, lo = np.where(left, x2, hi), np.where(left, lo, x1)
            new_x1 = np.where(left, hi - INV_PHI * (hi - lo), x2)
            new_x2 = np.where(left, x1, lo + INV_PHI * (hi - lo))
            f_new = objective(np.where(left, new_x1, new_x2))
            f1, f2 = np.where(left, f_new, f2), np.where(left, f1, f_new)
            x1, x2 = new_x1, new_x2
        return np.maximum(best_value, np.maximum(f1, f2))


def _safe_ratio(torque: np.ndarray, limit: np.ndarray) -> np.ndarray:
    """torque/limit, infinite where a positive torque meets a zero limit."""
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = torque / limit
    return np.where(limit > 0.0, ratio, np.where(torque > 0.0, np.inf, 0.0))

