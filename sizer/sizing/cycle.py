"""The machine cycle of one law for many candidates at once (book sec. 6.1.1).

For each candidate (a motor with its own duration T) the cycle is: move |h| in T, dwell,
and with a return move the same back and a second dwell. Along each move the motor torque
is

    tau(t) = J_m K a(t) + B_m K v(t) + chain(a, v)

with a, v the load's acceleration and speed, K the total ratio and chain() the torque
the transmission and the load need at the motor shaft, efficiencies applied in the
direction of power flow (sizer.mechanics.drive). During a dwell the motor holds the
constant external load. The RMS torque covers the whole cycle; so do the RMS torques at
the outputs of transmission stages that have torque ratings.

Integrals are exact: quadratic forms of the law's moments (Gauss-Legendre on its grid,
summed into a prefix-sum table once per law: :func:`moment_table`) over the stretches
between the power-flow reversals of the stages, each reversal a root; with ideal stages
the RMS is the closed form in C_v_rms, C_a_rms. Peaks are exact where they can be
(:meth:`CycleCalculator._exact_peaks`: the law's linear peaks, and against a concave
speed-torque region the linear-fractional peaks of Dinkelbach's method, restricted to the
parts of the move below and above the region's top speed where the move leaves it);
elsewhere they are found on the grid (piece ends and the ends of the move included) and
the largest local maxima of the samples, in whatever interval or piece, are refined by
golden-section search.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property, lru_cache
from typing import Protocol

import numpy as np

from sizer.laws.linear_peaks import LinearPeak, piece_values
from sizer.laws.quadrature import gauss_legendre
from sizer.mechanics import Drive
from sizer.model.domain import Task, ThermalSpeedRule
from sizer.numerics.arrays import spread
from sizer.numerics.hermite import hermite_root
from sizer.sizing.golden import golden_step, interior_points
from sizer.sizing.grid import LawGrid, PieceEvaluator, law_grid
from sizer.sizing.motors import MotorArrays

GOLDEN_STEPS = 40
FLOW_ROOT_STEP = 1e-6
"""A power-flow root's Newton step (in the grid interval's coordinate) that ends its
search (:meth:`CycleCalculator._flow_root`): the root is then within about the step's
square times the torque's relative curvature over the interval, and an integral moves
with the square of a root's error (the two reflections agree at the root): far below
rounding."""
REFINED = 6
"""Local maxima of the samples refined per candidate (the largest ones)."""
REFINE_SHARE = 0.5
"""Samples below this share of the best sample are no candidate peaks."""


@dataclass(frozen=True)
class CycleMetrics:
    """Requirements of one law for each candidate (arrays over candidates, SI).

    Motor side: max_speed, peak_torque, peak_ratio (worst |tau|/tau_int(|speed|)),
    rms_torque, thermal_speed. Load side: load_speed, load_acceleration, load_jerk (peaks)
    and load_torque (peak |u|). Per stage: stage_peak and stage_rms output torques and
    stage_speed (peak input speed), lists over the stages.
    """

    duration: np.ndarray
    max_speed: np.ndarray
    peak_torque: np.ndarray
    peak_ratio: np.ndarray
    rms_torque: np.ndarray
    thermal_speed: np.ndarray
    load_speed: np.ndarray
    load_acceleration: np.ndarray
    load_jerk: np.ndarray
    load_torque: np.ndarray
    stage_peak: list[np.ndarray]
    stage_rms: list[np.ndarray]
    stage_speed: list[np.ndarray]
    rms_model: RmsCurve | None = None


def rule_speed(rule: str, peak: np.ndarray, square: np.ndarray, travel: np.ndarray,
               cycle_time: np.ndarray) -> np.ndarray:
    """The thermal speed of a cycle from its statistics (sec. 6.1.1): the peak speed (the
    book's rule, ``max``), the RMS speed sqrt(int w^2 dt / T_c) or the mean speed
    int |w| dt / T_c, from the peak, int w^2 dt, int |w| dt and the cycle time T_c."""
    if rule == "max":
        return peak
    if rule == "rms":
        return np.sqrt(square / cycle_time)
    return travel / cycle_time


class RmsCurve(Protocol):
    """The RMS torque as a function of the duration near where it was built: a law's
    :class:`RmsModel`, or a cycle's (sizer.sizing.segment_cycle.CycleRmsModel)."""

    def rms(self, T: np.ndarray, index: np.ndarray | None = None) -> np.ndarray: ...


@dataclass(frozen=True)
class RmsModel:
    """The motor's RMS torque near the durations it was built at, T0, with the power
    flow's split points held (book sec. 6.1.1; :meth:`CycleCalculator.evaluate` with
    ``model``): per move the motor's linear functions at T0 and the law's moments where
    each is the torque. At T the coefficient of a_N scales as (T0/T)^2, that of v_N as
    T0/T. Exact at T0 (and for an ideal drive at every T); elsewhere off by O((T - T0)^2),
    as the torque is continuous across a split point, so moving it changes the integral
    to second order only.
    """

    duration: np.ndarray
    moves: list[list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]]
    dwell: float
    hold: np.ndarray

    @cached_property
    def powers(self) -> np.ndarray:
        """The summed integrals T int (P s^2 a_N + Q s v_N + C)^2 (s = T0/T, each function
        over its moments M) as c_3/T^3 + c_2/T^2 + c_1/T + c_0 + c_(-1) T: rows (c_3, c_2,
        c_1, c_0, c_(-1)) over the candidates, summed over the moves once, so that each
        value of the model costs a polynomial in 1/T."""
        T0 = self.duration
        out = np.zeros((5, len(T0)))
        with np.errstate(over="ignore", invalid="ignore"):
            for move in self.moves:
                for P, Q, C, M in move:
                    p, q = P * T0 * T0, Q * T0  # the torque scales of a_N and v_N at T0
                    out[0] += p * p * M[0]
                    out[1] += 2.0 * p * q * M[3]
                    out[2] += q * q * M[1] + 2.0 * p * C * M[4]
                    out[3] += 2.0 * q * C * M[5]
                    out[4] += C * C * M[2]
        return out

    def rms(self, T: np.ndarray, index: np.ndarray | None = None) -> np.ndarray:
        """RMS torque at durations T (of the candidates at ``index``, default all)."""
        c = self.powers if index is None else self.powers[:, index]
        hold = self.hold if index is None else self.hold[index]
        n = len(self.moves)
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            u = 1.0 / T
            square = ((c[0] * u + c[1]) * u + c[2]) * u + c[3] + c[4] * T
            mean = (square + n * self.dwell * np.square(hold)) / (n * (T + self.dwell))
        return np.sqrt(np.where(np.isnan(mean), np.inf, mean))


Objective = Callable[[np.ndarray, np.ndarray], np.ndarray]
"""A channel's value at normalized (a_N, v_N) arrays of shape (candidates, k)."""


@dataclass(frozen=True)
class MoveScales:
    """Per-candidate scales of one move: load a = acc*a_N, v = vel*v_N."""

    acc: np.ndarray
    vel: np.ndarray
    direction: float | np.ndarray
    """+1 or -1 (per candidate where several moves are stacked: CycleCalculator._exact_moves)."""


class CycleCalculator:
    """Evaluates the cycle of one law for candidate motors at candidate durations."""

    segmented = False
    """A cycle of segments (sizer.sizing.segment_cycle.SegmentCycle) says True: the T_min
    search then varies the scale of its free durations, without the closed forms."""

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
        self.stage_checks = any(s.rated_output_torque is not None
                                or s.peak_output_torque is not None for s in drive.stages)

    @property
    def grid(self) -> LawGrid:
        """The law's sampling grid, built on first use (the closed forms need none)."""
        if self._grid is None:
            self._grid = law_grid(self.law)
        return self._grid

    # ------------------------------------------------------------------ public
    def evaluate(self, duration: np.ndarray, peaks: bool = True,
                 model: bool = False, rms: np.ndarray | None = None) -> CycleMetrics:
        """The requirements at the given durations. Without ``peaks`` the peak torques
        and ratios are left at zero (a search on the other checks, where the peaks are
        known to pass: sizer.sizing.minimum_duration); with ``model`` the metrics carry
        the RMS model at these durations (:class:`RmsModel`). ``rms``: the motor's RMS
        torque at these durations, known (an RMS model's value within CONVERGED of where
        it was built: sizer.sizing.minimum_duration.rms_crossing_with_rms); the power-flow
        integrals are then not computed where no stage has an RMS rating to check (the
        stages' RMS is then left at zero, as nothing reads it)."""
        if rms is not None and (model or self.stage_checks or self.drive.is_ideal):
            rms = None  # wanted, or as cheap as the known values
        T = np.broadcast_to(np.asarray(duration, dtype=float), (len(self.motors),)).copy()
        c = self.law.coefficients
        K, h = self.drive.ratio, self.h
        n_stages = len(self.drive.stages)
        load_speed = c.C_v * h / T
        peak_torque = np.zeros_like(T)
        peak_ratio = np.zeros_like(T)
        load_torque = np.zeros_like(T)
        square = np.zeros_like(T)
        stage_peak = [np.zeros_like(T) for _ in range(n_stages)]
        stage_square = [np.zeros_like(T) for _ in range(n_stages)]
        # no T**2: T may be 1e300
        moves = [MoveScales(h / T / T, h / T, d) for d in self.directions]
        found = self._peaks(moves) if peaks else [
            (np.zeros_like(T), np.zeros_like(T), np.zeros_like(T),
             [np.zeros_like(T) for _ in range(n_stages)]) for _ in moves]
        parts: list | None = [] if model else None
        for scales, (torque, ratio, load, stages) in zip(moves, found, strict=True):
            peak_torque = np.maximum(peak_torque, torque)
            peak_ratio = np.maximum(peak_ratio, ratio)
            load_torque = np.maximum(load_torque, load)
            for i in range(n_stages):
                stage_peak[i] = np.maximum(stage_peak[i], stages[i])
            if rms is not None:
                continue
            means = self._mean_squares(scales, parts)
            square += T * means[0]
            for i in range(n_stages):
                stage_square[i] += T * means[1 + i]
        dwell = self.task.dwell
        n = len(self.directions)
        hold, stage_hold = self.drive.holding_torques()
        hold = np.broadcast_to(hold, T.shape)
        if dwell > 0.0 and bool(np.any(hold > 0.0)):
            peak_torque = np.maximum(peak_torque, hold)
            hold_limit = self.motors.intermittent.limit(np.zeros_like(T))
            peak_ratio = np.maximum(peak_ratio, _safe_ratio(hold, hold_limit))
            load_torque = np.maximum(load_torque, abs(self.drive.load.torque))
            for i in range(n_stages):
                stage_peak[i] = np.maximum(stage_peak[i], stage_hold[i])
        cycle = n * (T + dwell)
        with np.errstate(over="ignore"):  # beyond the float range: inf, reported unbounded
            rms = (np.sqrt((square + n * dwell * np.square(np.float64(hold))) / cycle)
                   if rms is None else np.asarray(rms, dtype=float).copy())
            stage_rms = [np.sqrt((stage_square[i] + n * dwell
                                  * np.square(np.float64(stage_hold[i]))) / cycle)
                         for i in range(n_stages)]
        thermal = self.thermal_speed(T)
        jerk = c.C_j * h / T / T / T if c.jerk_bounded else np.full_like(T, np.inf)
        return CycleMetrics(
            duration=T, max_speed=K * load_speed, peak_torque=peak_torque,
            peak_ratio=peak_ratio, rms_torque=rms, thermal_speed=thermal,
            load_speed=load_speed, load_acceleration=c.C_a * h / T / T, load_jerk=jerk,
            load_torque=load_torque, stage_peak=stage_peak, stage_rms=stage_rms,
            stage_speed=[k * load_speed for k in self.drive.input_ratios],
            rms_model=None if parts is None else RmsModel(T, parts, dwell, hold),
        )

    def thermal_speed(self, T: np.ndarray) -> np.ndarray:
        """The speed the continuous region is read at (the thermal rule): the peak speed
        as in the book, or the RMS or mean speed over the cycle."""
        c = self.law.coefficients
        K, h, dwell = self.drive.ratio, self.h, self.task.dwell
        n = len(self.directions)
        cycle = n * (T + dwell)
        if self.thermal_rule == "max":
            return K * c.C_v * h / T
        if self.thermal_rule == "rms":
            return K * h * c.C_v_rms * np.sqrt(n * T / cycle) / T
        return n * K * h / cycle

    # ---------------------------------------------------------------- torques
    def channels(self, a_n: np.ndarray, v_n: np.ndarray, scales: MoveScales,
                  index: np.ndarray | None = None) -> tuple[np.ndarray, list[np.ndarray]]:
        """Motor torque and stage output torques at normalized a_N, v_N.

        Arrays are candidate-major; ``index`` selects the candidates of the rows.
        """
        acc, vel = scales.acc, scales.vel
        rotor, damping = self.motors.inertia, self.motors.damping
        if index is not None:
            acc, vel, rotor, damping = acc[index], vel[index], rotor[index], damping[index]
        shape = (-1,) + (1,) * (np.ndim(a_n) - 1)
        acc, vel, rotor, damping = (np.reshape(x, shape) for x in (acc, vel, rotor, damping))
        a_l, v_l = acc * a_n, vel * v_n
        shaft, outputs = self.drive.chain(a_l, v_l, scales.direction, index)
        K = self.drive.ratio
        if index is not None and len(K) > 1:
            K = K[index]
        K = np.reshape(K, (-1,) + (1,) * (np.ndim(a_l) - 1)) if np.ndim(a_l) > 1 else K
        return rotor * K * a_l + damping * K * v_l + shaft, outputs

    def _mean_squares(self, scales: MoveScales,
                      model: list | None = None) -> list[np.ndarray]:
        """(1/T) * integral of the squared motor torque (then of each stage output) per move.

        Each torque is a maximum of linear functions L_k = P a_N + Q v_N + C of the law
        (Drive.linear_pieces); on an interval of the law's grid where no stage's power flow
        reverses one of them is the torque throughout (the one with the largest integral
        there), so its integral is the quadratic form of (P, Q, C) with the law's moments
        (int a_N^2, v_N^2, 1, a_N v_N, a_N, v_N) over the stretch: differences of the law's
        prefix-sum moment table (:func:`moment_table`, once per law) between the power-flow
        reversals (:meth:`_flow_sums`). With ``model`` the motor's functions and their
        summed moments are appended to it (:class:`RmsModel`; moments as (6, candidates)
        arrays, each moment's row contiguous).
        """
        drive = self.drive
        if drive.is_ideal:
            if model is not None:
                model.append(self._ideal_motor_terms(scales))
            return self._ideal_mean_squares(scales)
        terms = self.channel_terms(scales)
        sums = self._flow_sums(terms)
        if model is not None:
            model.append([(*piece, m) for piece, m in zip(terms[0], sums[0], strict=True)])
        with np.errstate(over="ignore", invalid="ignore"):
            totals = [sum(_form(P, Q, C, m) for (P, Q, C), m in zip(channel, sum_k, strict=True))
                      for channel, sum_k in zip(terms, sums, strict=True)]
        return [np.where(np.isnan(total), np.inf, total) for total in totals]

    def _ideal_motor_terms(self, scales: MoveScales):
        """The motor's one linear function with an ideal drive, and the law's moments over
        the move (int a_N^2 = C_a_rms^2, int v_N^2 = C_v_rms^2, int a_N = int a_N v_N = 0,
        int v_N = 1)."""
        n = len(self.motors)
        c = self.law.coefficients
        K = self.drive.ratio
        a_part, v_part, const = self.drive.linear_chain(float(scales.direction))
        moments = np.array([c.C_a_rms**2, c.C_v_rms**2, 1.0, 0.0, 0.0, 1.0])
        return [(spread((self.motors.inertia * K + a_part) * scales.acc, n),
                 spread((self.motors.damping * K + v_part) * scales.vel, n),
                 spread(np.asarray(const, dtype=float), n),
                 np.broadcast_to(moments[:, None], (6, n)))]

    def channel_terms(self, scales: MoveScales) -> list[list[tuple[np.ndarray, ...]]]:
        """Per channel (the motor, then each stage's output) its linear functions of the
        normalized law, (P, Q, C) arrays over the candidates: value = max_k P a_N + Q v_N + C."""
        n = len(self.motors)
        shaft, outputs = self.drive.linear_pieces(float(scales.direction))
        K = self.drive.ratio
        rotor = (self.motors.inertia * K, self.motors.damping * K)

        def scaled(pieces, with_rotor):
            return [(spread((A + rotor[0] if with_rotor else A) * scales.acc, n),
                     spread((B + rotor[1] if with_rotor else B) * scales.vel, n),
                     spread(np.asarray(C, dtype=float), n))
                    for A, B, C in pieces]

        return [scaled(shaft, True)] + [scaled(pieces, False) for pieces in outputs]

    def _ideal_mean_squares(self, scales: MoveScales) -> list[np.ndarray]:
        """Closed forms: int a_N = 0, int a_N v_N = 0, int v_N = 1 over a rest-to-rest move."""
        c = self.law.coefficients
        K = self.drive.ratio
        a_part, v_part, const = self.drive.linear_chain(float(scales.direction))
        p = (self.motors.inertia * K + a_part) * scales.acc
        q = (self.motors.damping * K + v_part) * scales.vel
        out = [_square_mean(p, q, const, c.C_a_rms, c.C_v_rms)]
        if self.stage_checks:
            out += self._stage_ideal_mean_squares(scales)
        else:
            out += [np.zeros_like(p) for _ in self.drive.stages]
        return out

    def _stage_ideal_mean_squares(self, scales: MoveScales) -> list[np.ndarray]:
        """Each stage output torque is linear too: its coefficients from the chain."""
        c = self.law.coefficients
        zero, one = np.zeros(1), np.ones(1)
        _, out_a = self.drive.chain(one, zero, scales.direction)
        _, out_v = self.drive.chain(zero, one, scales.direction)
        _, out_0 = self.drive.chain(zero, zero, scales.direction)
        result = []
        for xa, xv, x0 in zip(out_a, out_v, out_0, strict=True):
            a_coef, v_coef, const = xa - x0, xv - x0, x0
            result.append(_square_mean(a_coef * scales.acc, v_coef * scales.vel, const,
                                       c.C_a_rms, c.C_v_rms))
        return result

    def _flow_sums(self, terms) -> list[list[np.ndarray]]:
        """Per channel and per function of it, the law's moments summed over the stretches
        of the move where that function is the torque: (6, candidates) arrays.

        Between two power-flow reversals of the stages every channel is one of its linear
        functions (the reflections switch only where a stage's output torque is zero), so
        a stretch's moments are a difference of the law's prefix-sum moment table
        (:func:`moment_table`) and the work per candidate is per reversal, not per grid
        interval. The reversals: a stage's output torque (a maximum of linear functions)
        is read at the ends of every grid interval; where it changes sign inside an
        interval the root is found (Illinois, in the interval's own coordinate, to 1e-9:
        the two reflections agree at the root, so a root error dz changes an integral by
        O(dz^2)) and the table read there by Gauss-Legendre on the part of the interval
        before it; where its sign class changes across a grid edge (a jump of a_N) the
        edge is a split. Each stretch's function is the one with the largest integral
        over it (the torque is the maximum of the functions).
        """
        g, law = self.grid, self.law
        n, size = len(self.motors), g.size
        table = moment_table(law)
        edge = np.zeros((n, max(size - 1, 0)), dtype=bool)
        roots: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []  # (cand, interval, z)
        for pieces in terms[1:]:  # each stage's output at the ends of every interval
            x = _linear_maximum(pieces, g.end_acceleration, g.end_velocity)
            lo, hi = x[..., 0], x[..., 1]
            # sign classes as booleans (NaN, a move of 1e-200 s, counts as zero): an end
            # at zero takes the class of the interval's other end
            pos_lo, neg_lo, pos_hi, neg_hi = lo > 0.0, lo < 0.0, hi > 0.0, hi < 0.0
            left_pos = pos_lo | (pos_hi & ~neg_lo)
            left_neg = neg_lo | (neg_hi & ~pos_lo)
            right_pos = pos_hi | (pos_lo & ~neg_hi)
            right_neg = neg_hi | (neg_lo & ~pos_hi)
            edge |= (right_pos[:, :-1] != left_pos[:, 1:]) | (right_neg[:, :-1] != left_neg[:, 1:])
            cand, interval = np.nonzero((pos_lo & neg_hi) | (neg_lo & pos_hi))
            if len(cand):
                roots.append((cand, interval, self._flow_root(pieces, cand, interval,
                                                              lo[cand, interval],
                                                              hi[cand, interval])))
        # every split point: (candidate, position along the grid, prefix moments there)
        e_cand, e_index = np.nonzero(edge)
        cands = [np.arange(n), np.arange(n), e_cand]
        keys = [np.zeros(n), np.full(n, float(size)), (e_index + 1).astype(float)]
        values = [np.zeros((n, 6)), np.broadcast_to(table[-1], (n, 6)), table[e_index + 1]]
        for cand, interval, z in roots:
            cands.append(cand)
            keys.append(interval + z)
            values.append(table[interval] + self._partial_moments(interval, z))
        cand = np.concatenate(cands)
        key = np.concatenate(keys)
        value = np.concatenate(values)
        order = np.lexsort((key, cand))
        cand, value = cand[order], value[order]
        same = cand[1:] == cand[:-1]
        run_cand = cand[:-1][same]
        run = (value[1:] - value[:-1])[same]
        sums = []
        for channel in terms:
            if len(channel) == 1:
                sums.append([np.repeat(table[-1][:, None], n, axis=1)])
                continue
            best = _largest_integral([tuple(spread(x, n)[run_cand] for x in f)
                                      for f in channel], run)
            mine = []
            columns = np.arange(6)
            for k in range(len(channel)):
                rows = best == k
                # one bincount over (candidate, moment) bins: each bin's terms summed in
                # the runs' order, as six bincounts of one column each would
                bins = (run_cand[rows][:, None] * 6 + columns).ravel()
                mine.append(np.bincount(bins, weights=run[rows].ravel(),
                                        minlength=6 * n).reshape(n, 6).T.copy())
            sums.append(mine)
        return sums

    def _flow_root(self, pieces, cand: np.ndarray, interval: np.ndarray, f_lo: np.ndarray,
                   f_hi: np.ndarray) -> np.ndarray:
        """Where a stage's output torque (its linear ``pieces``) is zero inside the grid
        intervals at ``interval`` of the candidates at ``cand``: the coordinate z in [0, 1]
        of each interval (f_lo, f_hi: the torque at its ends, of opposite signs).

        Newton's method on the function that is the torque (its derivative P j_N + Q a_N),
        kept inside the shrinking sign bracket (bisection where a step would leave it),
        from the regula falsi point; each step evaluates only the roots still open, the
        points sorted by piece once so that a subset needs no regrouping, until a step
        is below FLOW_ROOT_STEP (or the bracket below 1e-10). Where the torque is one
        linear function the root of its cubic Hermite model on the interval (values and
        slopes at the ends, from the grid) starts the steps instead: one or two
        evaluations of the law per root.
        """
        g, law = self.grid, self.law
        count = len(cand)
        by_piece = np.argsort(g.piece[interval], kind="stable")
        piece = g.piece[interval][by_piece]
        lo_edge = g.left[interval][by_piece]
        width = g.right[interval][by_piece] - lo_edge
        n = len(self.motors)
        chosen = [tuple(spread(x, n)[cand[by_piece]] for x in part)
                  for part in pieces]
        sign_lo = np.sign(f_lo[by_piece])
        lo, hi = np.zeros(count), np.ones(count)
        f0, f1 = f_lo[by_piece], f_hi[by_piece]
        if len(chosen) == 1:  # one function: its cubic Hermite model on the interval
            (P, Q, _), = chosen
            ends = interval[by_piece]
            a, j = (x[ends] for x in (g.end_acceleration, g.end_jerk))
            z = hermite_root(f0, f1, (P * j[:, 0] + Q * a[:, 0]) * width,
                             (P * j[:, 1] + Q * a[:, 1]) * width, xtol=0.1 * FLOW_ROOT_STEP)
        else:
            z = np.clip(f0 / (f0 - f1), 0.0, 1.0)
        rows = np.arange(count)
        bounds_of = np.arange(len(law.pieces) + 1)
        for _ in range(60):
            if not len(rows):
                break
            tau = lo_edge[rows] + z[rows] * width[rows]
            mine = piece[rows]
            bounds = np.searchsorted(mine, bounds_of)
            v_n, a_n, j_n = (np.empty(len(rows)) for _ in range(3))
            for index in np.flatnonzero(np.diff(bounds)):
                part = slice(bounds[index], bounds[index + 1])
                at = law.pieces[index].clamp(tau[part])
                for out, order in ((v_n, 1), (a_n, 2), (j_n, 3)):
                    out[part] = law.pieces[index].evaluate(at, order)
            values = np.stack([P[rows] * a_n + Q[rows] * v_n + C[rows] for P, Q, C in chosen])
            k = np.argmax(values, axis=0)
            f = values[k, np.arange(len(rows))]
            slope = np.choose(k, [P[rows] * j_n + Q[rows] * a_n for P, Q, _ in chosen])
            below = np.sign(f) == sign_lo[rows]
            lo[rows] = np.where(below, z[rows], lo[rows])
            hi[rows] = np.where(below, hi[rows], z[rows])
            with np.errstate(divide="ignore", invalid="ignore"):
                step = z[rows] - f / (slope * width[rows])
            inside = (step > lo[rows]) & (step < hi[rows])
            new = np.where(inside, step, 0.5 * (lo[rows] + hi[rows]))
            done = (np.abs(new - z[rows]) <= FLOW_ROOT_STEP) | (f == 0.0) \
                | (hi[rows] - lo[rows] <= 1e-10)
            z[rows] = np.where(f == 0.0, z[rows], new)
            rows = rows[~done]
        out = np.empty(count)
        out[by_piece] = np.minimum(np.maximum(z, 0.0), 1.0)
        return out

    def _partial_moments(self, interval: np.ndarray, z: np.ndarray) -> np.ndarray:
        """The law's moments over the first part [left, left + z width] of each grid
        interval at ``interval`` (Gauss-Legendre with the grid's node count, on the
        interval's piece): (len(interval), 6), columns as :func:`interval_moments`."""
        g = self.grid
        lo_edge = g.left[interval]
        half = 0.5 * z * (g.right[interval] - lo_edge)
        x, w = gauss_legendre(g.nodes.shape[1])
        tau = (lo_edge + half)[:, None] + half[:, None] * x
        on_pieces = PieceEvaluator(self.law, np.broadcast_to(g.piece[interval][:, None],
                                                             tau.shape))
        a_n, v_n = on_pieces.orders(tau, (2, 1))
        weight = half[:, None] * w
        return np.column_stack([(weight * a_n * a_n).sum(axis=1),
                                (weight * v_n * v_n).sum(axis=1), weight.sum(axis=1),
                                (weight * a_n * v_n).sum(axis=1), (weight * a_n).sum(axis=1),
                                (weight * v_n).sum(axis=1)])

    # ------------------------------------------------------------------ peaks
    def _peaks(self, moves: list[MoveScales]):
        """Per move: max |tau|, max |tau|/tau_int(|speed|), max |u| and stage output peaks.

        Exact by the law's linear peaks (:meth:`_exact_peaks`) wherever their conditions
        hold (moves that leave the region included: :meth:`_leaving_ratio`); the grid
        search (:meth:`_sampled_peaks`) for the other candidates (a torque minimum or a
        ratio that could not be certified, a region that is not concave, a law whose speed
        changes sign).
        """
        out = []
        for scales, found_exactly in zip(moves, self._exact_moves(moves), strict=True):
            (peak, ratio, load, stages), exact, certified = found_exactly
            if not exact.all():
                index = np.flatnonzero(~exact)
                sub = self.take(index)
                move = MoveScales(scales.acc[index], scales.vel[index], scales.direction)
                if bool(np.all(certified[index])):
                    # only the ratio against a falling region is left to the grid search
                    ratio[index] = sub._sampled_peaks([move], ratio_only=True)[0][1]
                else:
                    found = sub._sampled_peaks([move])[0]
                    for mine, theirs in zip((peak, ratio, load, *stages),
                                            (found[0], found[1], found[2], *found[3]),
                                            strict=True):
                        mine[index] = theirs
            out.append((peak, ratio, load, stages))
        return out

    def _exact_moves(self, moves: list[MoveScales]):
        """:meth:`_exact_peaks` of every move, the moves' candidates stacked into one run
        (the same linear functions per candidate in every move, their coefficients and
        the direction per row): each query elementwise, so the answers are those of one
        run per move, at the cost of one."""
        load = self.drive.load
        terms = [self.channel_terms(scales) for scales in moves]
        n = len(self.motors)
        joined = None
        if len(moves) > 1 and not (_inertial(terms[0][0]) and load.damping == 0.0
                                   and load.friction == 0.0 and load.torque == 0.0):
            joined = _stacked_terms(terms, n)
        if joined is None:
            # no linear-peak query to share (the book's inertial case), or a single move
            return [self._exact_peaks(scales, t) for scales, t in zip(moves, terms, strict=True)]

        def stack(values):
            return np.concatenate([spread(x, n) for x in values])

        scales = MoveScales(stack([s.acc for s in moves]), stack([s.vel for s in moves]),
                            np.repeat([s.direction for s in moves], n))
        big = self.take(np.tile(np.arange(n), len(moves)))
        (peak, ratio, load, stages), exact, certified = big._exact_peaks(scales, joined)
        parts = [slice(i * n, (i + 1) * n) for i in range(len(moves))]
        return [((peak[at].copy(), ratio[at].copy(), load[at].copy(),
                  [x[at].copy() for x in stages]), exact[at].copy(), certified[at].copy())
                for at in parts]

    def take(self, index: np.ndarray) -> CycleCalculator:
        """The calculator of the candidates at ``index`` (same law and grid)."""
        return CycleCalculator(self._grid, self.task, self.drive.take(index),
                               self.motors.subset(index), self.thermal_rule, law=self.law)

    def _exact_peaks(self, scales: MoveScales, terms=None):
        """Exact peaks of a move from the law's linear peaks (sizer.laws.linear_peaks).

        Every torque is a maximum of linear functions of the load's (a, v): the motor
        torque and each stage's output torque (sizer.mechanics.drive.Drive.linear_pieces:
        one function per choice of power-flow direction in the stages, their maximum
        because each stage's reflection max(x/(k eta), x eta/k) is increasing in x). So
        max tau = max_j max_t L_j: one support query per function. For min tau, the
        largest of the functions' own minima is a lower bound, reached where that
        function is the active one at its own minimizer (checked at that point): then it
        is exact; elsewhere the candidate is left to the grid search. The peak ratio is
        the peak over the intermittent torque at rest where the move's speed stays on the
        flat part of the region. Returns the peaks, the mask of the exact candidates and that of
        those whose torques are exact (their ratio may still need the grid search).
        ``terms``: the channels' linear functions when the caller has them
        (:meth:`_exact_moves`: several moves stacked; ``scales.direction`` per row).
        """
        n = len(self.motors)
        c = self.law.coefficients
        motors, drive = self.motors, self.drive
        K = drive.ratio
        peaks = self.law.linear_peaks
        certified = np.ones(n, dtype=bool)

        inertial = _inertial

        def channel(coefficients, highs, lows):
            """max |value| of a maximum of linear functions of (a_N, v_N), from each
            function's linear peaks (``highs``) and lowest points (``lows``); clears
            ``certified`` where the minimum could not be certified."""
            if inertial(coefficients):
                places.append(None)
                return np.broadcast_to(np.abs(coefficients[0][0]) * c.C_a, (n,)).copy()
            top = np.full(n, -np.inf)
            top_tau, top_piece = np.zeros(n), np.zeros(n, dtype=np.intp)
            for high, (_, _, C) in zip(highs, coefficients, strict=True):
                value = high.value + C
                better = value > top
                top = np.where(better, value, top)
                top_tau = np.where(better, high.tau, top_tau)
                top_piece = np.where(better, high.piece, top_piece)
            floors = np.stack([low.value + C for low, (_, _, C) in zip(lows, coefficients,
                                                                       strict=True)])
            best = np.argmax(floors, axis=0)
            bottom = floors[best, np.arange(n)]
            tau = np.choose(best, [low.tau for low in lows])
            piece = np.choose(best, [low.piece for low in lows])
            if len(coefficients) > 1:
                v_n, a_n = piece_values(self.law, tau, piece, (1, 2))
                values = np.stack([P * a_n + Q * v_n + C for P, Q, C in coefficients])
                scale = np.max(np.abs(values), axis=0) + np.abs(bottom)
                certified[:] &= values.max(axis=0) <= bottom + 1e-12 * scale
            upper = top >= -bottom
            places.append((np.where(upper, top_tau, tau), np.where(upper, top_piece, piece)))
            return np.maximum(top, -bottom)

        places: list[tuple[np.ndarray, np.ndarray] | None] = []  # where each |peak| is
        motor_terms, *stage_terms = self.channel_terms(scales) if terms is None else terms
        load_terms = [(spread(drive.load.inertia * scales.acc, n),
                       spread(drive.load.damping * scales.vel, n),
                       np.full(n, drive.load.friction + scales.direction * drive.load.torque))]
        channels = [motor_terms, load_terms] + (stage_terms if self.stage_checks else [])
        # every function's highest and lowest point, all channels in one query
        functions = [f for co in channels if not inertial(co) for f in co]
        solved = peaks.maximum(
            np.concatenate([sign * spread(P, n) for sign in (1.0, -1.0)
                            for P, _, _ in functions]),
            np.concatenate([sign * spread(Q, n) for sign in (1.0, -1.0)
                            for _, Q, _ in functions])) if functions else None
        results, start = [], 0
        for co in channels:
            if inertial(co):
                results.append(channel(co, [], []))
                continue
            size = len(co)
            at = [slice((start + i) * n, (start + i + 1) * n) for i in range(size)]
            low_at = [slice((len(functions) + start + i) * n,
                            (len(functions) + start + i + 1) * n) for i in range(size)]
            start += size
            assert solved is not None  # a channel that is not inertial has functions
            highs = [LinearPeak(solved.value[t], solved.tau[t], solved.piece[t]) for t in at]
            lows = [LinearPeak(-solved.value[t], solved.tau[t], solved.piece[t])
                    for t in low_at]
            results.append(channel(co, highs, lows))
        peak, load = results[0], results[1]
        peak_place = places[0]
        stages = results[2:] if self.stage_checks else [np.zeros(n) for _ in drive.stages]
        speed = K * scales.vel * c.C_v
        # speeds past the region are clipped into it for the ratio (the speed check covers
        # them): a region flat to its end is flat at every speed
        flat = np.broadcast_to((speed <= motors.flat_speed)
                               | (motors.flat_speed >= motors.speed_limit), (n,))
        ratio = _safe_ratio(peak, motors.intermittent.torques[:, 0])
        exact = certified & flat
        curved = np.flatnonzero(certified & ~flat)
        speed_scale = spread(K * scales.vel, n)
        if len(curved):
            exact[curved] = self._curve_ratio(motor_terms, curved, speed_scale[curved], c.C_v,
                                              ratio)
        beyond = np.flatnonzero(certified & ~exact & (spread(speed, n)
                                                      > motors.speed_limit))
        if len(beyond) and peak_place is not None:
            exact[beyond] = self._beyond_ratio(peak, peak_place, beyond, speed_scale[beyond],
                                               ratio)
        leaving = np.flatnonzero(certified & ~exact & (spread(speed, n)
                                                       > motors.speed_limit))
        if len(leaving):
            exact[leaving] = self._leaving_ratio(motor_terms, leaving, speed_scale[leaving],
                                                 ratio)
        return (peak, ratio, load, stages), exact, certified

    def _beyond_ratio(self, peak: np.ndarray, place, rows: np.ndarray,
                      speed_scale: np.ndarray, ratio: np.ndarray) -> np.ndarray:
        """The peak ratio of moves that leave the region (the speed check fails them),
        where it is the torque peak over the region's lowest torque: past its end the
        region is read at its end (clipped), so |tau|/limit <= peak/lowest everywhere, with
        equality at the torque's peak when that lies past the end and the end is the
        lowest point. Returns where that holds (written into ``ratio``)."""
        region = self.motors.intermittent.take(rows)
        tau, piece = place[0][rows], place[1][rows]
        at_peak = speed_scale * piece_values(self.law, tau, piece, 1)
        end = region.limit(region.max_speed)
        done = (at_peak >= region.max_speed) & (end <= region.torques.min(axis=1))
        ratio[rows[done]] = _safe_ratio(peak[rows[done]], end[done])
        return done

    def _leaving_ratio(self, terms, rows: np.ndarray, speed_scale: np.ndarray,
                       ratio: np.ndarray) -> np.ndarray:
        """The peak ratio |tau|/tau_int(min(|speed|, v_max)) of moves that leave a concave
        region (the speed check fails them; the ratio is read with the speed clipped to
        the region's end), exactly; returns where it was found (written into ``ratio``).

        With u = v_max/(K vel) the move splits into the part above the top speed, v_N >= u,
        where the limit is the region's end torque e: there the ratio is max |tau| / e,
        from linear peaks restricted to that part (LinearPeaks.maximum_within); and the
        part below, v_N <= u, where the limit is the minimum of the segments' lines (all
        positive there when e > 0), so the ratio is the largest over the lines of |tau|
        over the line: linear-fractional peaks restricted to that part
        (LinearPeaks.ratio_maximum_within). Both parts include their ends, the points where
        v_N = u. For -tau = min_k(-L_k) the smallest of the -L_k peaks, exact where its
        function is the torque at its maximizer (as in :meth:`_curve_ratio`). A flat
        first segment (the standstill torque t0, the region falling from it) gives at most
        peak/t0, which ``ratio`` holds already. Candidates whose region is not concave or
        whose law's speed changes sign are left to the grid search.
        """
        peaks = self.law.linear_peaks
        if not peaks.speeds_nonnegative:
            return np.zeros(len(rows), dtype=bool)
        region = self.motors.intermittent.take(rows)
        alpha, sigma, concave = region.lines()
        end = region.limit(region.max_speed)
        ok = concave & (speed_scale > 0.0) & (region.max_speed > 0.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            bound = region.max_speed / speed_scale
        n = len(self.motors)
        parts = [tuple(spread(x, n)[rows] for x in part) for part in terms]
        count = len(parts)

        def certify(sel, k, solved_tau, solved_piece):
            """Where the function k (per row) is the torque at the found points."""
            v_n, a_n = piece_values(self.law, solved_tau, solved_piece, (1, 2))
            torques = np.stack([P[sel] * a_n + Q[sel] * v_n + C[sel] for P, Q, C in parts])
            mine = torques[k, np.arange(len(sel))]
            scale = np.max(np.abs(torques), axis=0)
            return mine >= torques.max(axis=0) - 1e-12 * scale

        found = np.where(sigma[:, 0] == 0.0, ratio[rows], -np.inf)
        # above the top speed: max |tau| over v_N >= u, against the end torque
        sel = np.flatnonzero(ok)
        m = len(sel)
        below = None
        if m:
            below, band = peaks.bands(bound[sel])
            tile = np.tile(np.arange(m), 2 * count)
            solved = peaks.maximum_within(
                np.concatenate([sign * P[sel] for sign in (1.0, -1.0) for P, _, _ in parts]),
                np.concatenate([sign * Q[sel] for sign in (1.0, -1.0) for _, Q, _ in parts]),
                band.take(tile))
            take = [slice(i * m, (i + 1) * m) for i in range(2 * count)]
            tops = np.stack([solved.value[t] + C[sel]
                             for t, (_, _, C) in zip(take[:count], parts, strict=True)])
            lows = np.stack([solved.value[t] - C[sel]
                             for t, (_, _, C) in zip(take[count:], parts, strict=True)])
            k = np.argmin(lows, axis=0)
            bottom = lows[k, np.arange(m)]
            if count > 1:
                tau = np.choose(k, [solved.tau[t] for t in take[count:]])
                piece = np.choose(k, [solved.piece[t] for t in take[count:]])
                ok[sel] &= ~np.isfinite(bottom) | certify(sel, k, tau, piece)
            top = np.maximum(tops.max(axis=0), bottom)
            inside = np.isfinite(top)
            found[sel[inside]] = np.maximum(found[sel[inside]],
                                            _safe_ratio(np.maximum(top[inside], 0.0),
                                                        end[sel][inside]))
        banded = sel  # the rows of the bands (those below are among them)
        # below the top speed: |tau| over each line of the region, where the lines are
        # positive (e > 0; where e = 0 the part above gave inf, or the row is left)
        positive = end > 0.0
        ok &= positive | (found == np.inf)
        sel = np.flatnonzero(ok & positive)
        if len(sel) and below is not None:
            band = below.take(np.searchsorted(banded, sel))
            blocks, queries, band_rows, floors = [], [], [], []
            for column in range(alpha.shape[1]):
                use = np.isfinite(alpha[sel, column])
                if column == 0:
                    use &= sigma[sel, 0] != 0.0
                mine = np.flatnonzero(use)
                if not len(mine):
                    continue
                at = sel[mine]
                blocks.append(at)
                line = (alpha[at, column], sigma[at, column] * speed_scale[at])
                for sign in (1.0, -1.0):
                    for P, Q, C in parts:
                        queries.append((sign * P[at], sign * Q[at], sign * C[at], *line))
                        band_rows.append(mine)
                        floors.append(found[at])
            if blocks:
                # each query starts at the ratio found so far: most stop after one step
                num_a, num_v, num_c, den_c, den_v = (
                    np.concatenate([query[i] for query in queries]) for i in range(5))
                solved = peaks.ratio_maximum_within(num_a, num_v, num_c, den_c, den_v,
                                                    band.take(np.concatenate(band_rows)),
                                                    floor=np.concatenate(floors))
                start = 0
                for at in blocks:
                    size = len(at)
                    take = [slice(start + i * size, start + (i + 1) * size)
                            for i in range(2 * count)]
                    start += 2 * count * size
                    tops = np.stack([solved.value[t] for t in take[:count]])
                    lows = np.stack([solved.value[t] for t in take[count:]])
                    k = np.argmin(lows, axis=0)
                    bottom = lows[k, np.arange(size)]
                    if count > 1:  # needed only where every -L_k beat the floor
                        tau = np.choose(k, [solved.tau[t] for t in take[count:]])
                        piece = np.choose(k, [solved.piece[t] for t in take[count:]])
                        ok[at] &= (bottom <= found[at]) | certify(at, k, tau, piece)
                    found[at] = np.maximum(found[at], np.maximum(tops.max(axis=0), bottom))
        ok &= np.isfinite(found) | (found == np.inf)
        ratio[rows[ok]] = found[ok]
        return ok

    def _curve_ratio(self, terms, rows: np.ndarray, speed_scale: np.ndarray, C_v: float,
                     ratio: np.ndarray) -> np.ndarray:
        """The peak ratio |tau|/tau_int(speed) of the candidates at ``rows`` against a
        concave region, exactly; returns where it was found (written into ``ratio``).

        A concave region is the minimum of its segments' lines (RegionTable.lines), so
        the ratio is the largest over the lines the move reaches of |tau| over the line:
        for the torque's functions L_k a linear-fractional peak each
        (LinearPeaks.ratio_maximum); for -tau = min_k(-L_k) the smallest of the -L_k
        peaks, exact where its function is the torque at its maximizer (as for the torque
        minimum in :meth:`_exact_peaks`). The first line too where it is not flat (a
        region falling from standstill, as a published speed-torque line); where it is
        flat, the torque peak over it, which ``ratio`` holds. Candidates whose region is
        not concave, whose move leaves the region or reaches a line's zero are left to
        the grid search.
        """
        region = self.motors.intermittent.take(rows)
        alpha, sigma, concave = region.lines()
        rate = sigma * speed_scale[:, None]  # the line over v_N: alpha + sigma K vel v_N
        peak_speed = speed_scale * C_v
        starts = region.speeds[:, :-1]
        used = (starts < peak_speed[:, None]) & np.isfinite(alpha)
        # a flat first line gives the torque peak over the standstill torque (``ratio``
        # holds it); a first line that is not flat is queried like the others
        used[:, 0] = sigma[:, 0] != 0.0
        ok = concave & (peak_speed <= region.max_speed)
        ok &= np.all(~used | (alpha + sigma * peak_speed[:, None] > 0.0), axis=1)
        n = len(self.motors)
        parts = [tuple(spread(x, n)[rows] for x in part) for part in terms]
        # every (line, function, side) problem in one Dinkelbach run: blocks per line of
        # the functions' +L_k, then their -L_k, over the candidates that reach the line
        blocks, queries, floors = [], [], []
        # the peak over the standstill torque is reached where the region does not rise
        # above it (its first line flat or falling); elsewhere no floor
        found = np.where(sigma[:, 0] <= 0.0, ratio[rows], -np.inf)
        for column in range(alpha.shape[1]):
            sel = np.flatnonzero(ok & used[:, column])
            if len(sel):
                blocks.append(sel)
                line = (alpha[sel, column], rate[sel, column])
                for sign in (1.0, -1.0):
                    queries += [(sign * P[sel], sign * Q[sel], sign * C[sel], *line)
                                for P, Q, C in parts]
                    floors += [found[sel]] * len(parts)
        if not blocks:
            ratio[rows[ok]] = found[ok]
            return ok
        # each query starts at the ratio known already (peak over the standstill torque):
        # where the line cannot beat it, one step
        num_a, num_v, num_c, den_c, den_v = (
            np.concatenate([query[i] for query in queries]) for i in range(5))
        solved = self.law.linear_peaks.ratio_maximum(num_a, num_v, num_c, den_c, den_v,
                                                     floor=np.concatenate(floors))
        start, count = 0, len(parts)
        for sel in blocks:
            m = len(sel)
            take = [slice(start + i * m, start + (i + 1) * m) for i in range(2 * count)]
            start += 2 * count * m
            tops = np.stack([solved.value[t] for t in take[:count]])
            lows = np.stack([solved.value[t] for t in take[count:]])
            k = np.argmin(lows, axis=0)
            bottom = lows[k, np.arange(m)]
            if count > 1:  # -tau = min_k(-L_k): exact where L_k is the torque there
                # (needed only where every -L_k beat the floor)
                tau = np.choose(k, [solved.tau[t] for t in take[count:]])
                piece = np.choose(k, [solved.piece[t] for t in take[count:]])
                v_n, a_n = piece_values(self.law, tau, piece, (1, 2))
                torques = np.stack([P[sel] * a_n + Q[sel] * v_n + C[sel] for P, Q, C in parts])
                mine = torques[k, np.arange(m)]
                scale = np.max(np.abs(torques), axis=0)
                ok[sel] &= (bottom <= found[sel]) | (mine >= torques.max(axis=0) - 1e-12 * scale)
            found[sel] = np.maximum(found[sel], np.maximum(tops.max(axis=0), bottom))
        done = ok
        ratio[rows[done]] = found[done]
        return done

    def _sampled_peaks(self, moves: list[MoveScales], ratio_only: bool = False):
        """Peaks on the law's grid, the largest samples of every channel and move refined
        together (:meth:`_refine`: one golden-section search for all of them). With
        ``ratio_only`` only the peak ratio is searched (the torques known exactly)."""
        g = self.grid
        tau = np.concatenate((g.left[:, None], g.nodes, g.right[:, None]), axis=1)
        a_n = np.concatenate((g.end_acceleration[:, :1], g.acceleration,
                              g.end_acceleration[:, 1:]), axis=1)
        v_n = np.concatenate((g.end_velocity[:, :1], g.velocity, g.end_velocity[:, 1:]), axis=1)
        n_stages = len(self.drive.stages)
        searches: list[tuple[np.ndarray, Objective]] = []
        plans = []
        for scales in moves:
            motor, outputs = self.channels(a_n[None], v_n[None], scales)
            speed_scale = self.drive.ratio * scales.vel

            def channel(which, by_ratio=False, scales=scales, speed_scale=speed_scale):
                def objective(a, v):
                    motor_torque, stage_torques = self.channels(a, v, scales)
                    torque = np.abs(motor_torque if which < 0 else stage_torques[which])
                    if by_ratio:
                        speed = np.reshape(speed_scale, (-1,) + (1,) * (np.ndim(v) - 1)) * v
                        return _safe_ratio(torque, self.motors.intermittent.limit_clipped(speed))
                    return torque
                return objective

            plan = {}
            if not ratio_only or self.motors.all_rectangular:
                plan["peak"] = len(searches)
                searches.append((np.abs(motor), channel(-1)))
            if not self.motors.all_rectangular:
                speed = speed_scale[:, None, None] * v_n[None]
                limit = self.motors.intermittent.limit_clipped(speed)
                plan["ratio"] = len(searches)
                searches.append((_safe_ratio(np.abs(motor), limit), channel(-1, True)))
            if self.stage_checks and not ratio_only:
                plan["stages"] = len(searches)
                searches.extend((np.abs(outputs[i]), channel(i)) for i in range(n_stages))
            # the load's torque is reported, not checked: its sampled peak (grid of 14
            # points per interval) is enough
            a_l = scales.acc[:, None, None] * a_n[None]
            v_l = scales.vel[:, None, None] * v_n[None]
            plan["load"] = np.abs(self.drive.load_torque(a_l, v_l, scales.direction)).max(
                axis=(1, 2))
            plans.append(plan)
        found = self._refine(searches, tau)
        out = []
        for plan in plans:
            peak = found[plan["peak"]] if "peak" in plan else np.full(len(self.motors), np.nan)
            if "ratio" in plan:
                ratio = found[plan["ratio"]]
            else:  # flat limit: the ratio peaks with the torque
                ratio = _safe_ratio(peak, self.motors.intermittent.torques[:, 0])
            if "stages" in plan:
                stages = found[plan["stages"]:plan["stages"] + n_stages]
            else:
                stages = [np.zeros_like(peak) for _ in range(n_stages)]
            out.append((peak, ratio, plan["load"], stages))
        return out

    def _refine(self, searches: list[tuple[np.ndarray, Objective]],
                tau: np.ndarray) -> list[np.ndarray]:
        """The maximum over the move of each search: the best samples, refined by golden
        section, all searches in one pass (the law is evaluated once per step).

        Each search is (samples, objective): the samples (candidates, intervals, columns)
        at ``tau`` (intervals, columns: each interval's left end, nodes, right end, so
        breakpoints and the ends of the move are samples, one-sided) and the objective at
        (a_N, v_N) of shape (candidates, k). Every sample that is a local maximum of the
        samples of its piece and within REFINE_SHARE of the best is a candidate peak (the
        REFINED largest of them); each is refined between its neighbours in its interval.
        A peak on a sample is that sample; one between samples is found in whichever
        interval or piece it lies, not only next to the best sample.
        """
        starts = [self._candidate_peaks(values, tau) for values, _ in searches]
        shape = starts[0][0].shape  # (candidates, keep)
        lo = np.concatenate([s[0] for s in starts], axis=1)
        hi = np.concatenate([s[1] for s in starts], axis=1)
        piece = np.concatenate([s[2] for s in starts], axis=1)
        at = PieceEvaluator(self.law, piece)
        width = shape[1]

        def objective(x):
            a, v = at.orders(x, (2, 1))
            return np.concatenate([f(a[:, k * width:(k + 1) * width],
                                     v[:, k * width:(k + 1) * width])
                                   for k, (_, f) in enumerate(searches)], axis=1)

        x1, x2 = interior_points(lo, hi)
        bracket = (lo, hi, x1, x2, objective(x1), objective(x2))
        for _ in range(GOLDEN_STEPS):
            bracket = golden_step(objective, bracket, bracket[4] >= bracket[5])  # max in [lo, x2]
        best = np.maximum(bracket[4], bracket[5])
        out = []
        for k, (valid, best_value) in enumerate((s[3], s[4]) for s in starts):
            part = best[:, k * width:(k + 1) * width]
            refined = np.where(valid, part, -np.inf).max(axis=1)
            out.append(np.maximum(best_value, refined))
        return out

    def _candidate_peaks(self, values: np.ndarray, tau: np.ndarray):
        """(lo, hi, piece, valid, best) of :meth:`_refine`'s candidate peaks of one search."""
        g = self.grid
        count, columns = len(values), tau.shape[1]
        best_value = values.reshape(count, -1).max(axis=1)
        # neighbours of each sample; at an interval's end, the sample across the end when
        # the next interval is on the same piece (else none: a breakpoint or an end)
        same = g.piece[1:] == g.piece[:-1]
        before = np.where(same[None, :], values[:, :-1, -2], -np.inf)
        after = np.where(same[None, :], values[:, 1:, 1], -np.inf)
        edge = np.full((count, 1), -np.inf)
        before = np.concatenate((edge, before), axis=1)[..., None]
        after = np.concatenate((after, edge), axis=1)[..., None]
        left = np.concatenate((before, values[..., :-1]), axis=2)
        right = np.concatenate((values[..., 1:], after), axis=2)
        floor = (REFINE_SHARE * best_value)[:, None, None]
        local = (values >= left) & (values >= right) & (values >= floor)
        score = np.where(local, values, -np.inf).reshape(count, -1)
        keep = min(REFINED, score.shape[1])
        chosen = np.argpartition(-score, keep - 1, axis=1)[:, :keep]  # (count, keep)
        valid = np.isfinite(np.take_along_axis(score, chosen, axis=1))
        interval, column = np.divmod(chosen, columns)
        lo = tau[interval, np.maximum(column - 1, 0)]
        hi = tau[interval, np.minimum(column + 1, columns - 1)]
        return lo, hi, g.piece[interval], valid, best_value


def _inertial(coefficients) -> bool:
    """A channel proportional to the acceleration (the book's inertial case): its peak is
    |P| C_a, no linear-peak query."""
    return len(coefficients) == 1 and not np.any(coefficients[0][1]) \
        and not np.any(coefficients[0][2])


def _stacked_terms(terms: list, n: int):
    """The channels' linear functions of several moves (:meth:`CycleCalculator.channel_terms`
    each) stacked along the candidates, move after move; None where the moves' channels
    have different numbers of functions."""
    counts = [[len(channel) for channel in t] for t in terms]
    if any(c != counts[0] for c in counts):
        return None

    def stack(values):
        return np.concatenate([spread(x, n) for x in values])

    return [[tuple(stack([t[c][k][i] for t in terms]) for i in range(3))
             for k in range(len(terms[0][c]))] for c in range(len(terms[0]))]


def _linear_maximum(pieces, a_n: np.ndarray, v_n: np.ndarray) -> np.ndarray:
    """max_k P_k a_N + Q_k v_N + C_k for (P, Q, C) arrays over candidates and a_N, v_N
    arrays shared by all of them: shape (candidates, *a_n.shape)."""
    shape = (-1,) + (1,) * np.ndim(a_n)
    out = None
    for P, Q, C in pieces:
        value = np.reshape(P, shape) * a_n + np.reshape(Q, shape) * v_n + np.reshape(C, shape)
        out = value if out is None else np.maximum(out, value)
    assert out is not None  # at least one function
    return out


def _form(P, Q, C, m: np.ndarray) -> np.ndarray:
    """int (P a + Q v + C)^2 from the moments m (6, rows: a^2, v^2, 1, a v, a, v)."""
    return (P * P * m[0] + Q * Q * m[1] + C * C * m[2]
            + 2.0 * (P * Q * m[3] + P * C * m[4] + Q * C * m[5]))


def _largest_integral(pieces, moments: np.ndarray) -> np.ndarray:
    """Per row the index of the function of ``pieces`` ((P, Q, C) arrays over rows, or
    over rows x columns of ``moments`` (..., 6)) with the largest integral: where no flow
    reverses, the one that is the torque."""
    if len(pieces) == 1:
        return np.zeros(moments.shape[:-1], dtype=np.intp)
    shape = (-1,) + (1,) * (moments.ndim - 2)
    return np.argmax(np.stack([np.reshape(P, shape) * moments[..., 4]
                               + np.reshape(Q, shape) * moments[..., 5]
                               + np.reshape(C, shape) * moments[..., 2]
                               for P, Q, C in pieces]), axis=0)


@lru_cache(maxsize=256)
def interval_moments(law) -> np.ndarray:
    """Per interval of the law's grid the Gauss-Legendre integrals of a_N^2, v_N^2, 1,
    a_N v_N, a_N and v_N (columns in that order), shape (intervals, 6)."""
    g = law_grid(law)
    a, v, w = g.acceleration, g.velocity, g.weights
    return np.column_stack([(w * a * a).sum(axis=1), (w * v * v).sum(axis=1), w.sum(axis=1),
                            (w * a * v).sum(axis=1), (w * a).sum(axis=1), (w * v).sum(axis=1)])


@lru_cache(maxsize=256)
def moment_table(law) -> np.ndarray:
    """The law's moments (columns as :func:`interval_moments`) integrated from 0 to each
    edge of its grid: prefix sums, shape (intervals + 1, 6), first row zero. The moments
    over a stretch of grid edges are a difference of two rows."""
    moments = interval_moments(law)
    table = np.zeros((len(moments) + 1, 6))
    np.cumsum(moments, axis=0, out=table[1:])
    table.setflags(write=False)
    return table


def _square_mean(p, q, const, c_a_rms: float, c_v_rms: float):
    """int_0^1 (p a_N + q v_N + const)^2 d tau for a rest-to-rest law.

    A torque beyond 1e154 N*m (a move of 1e-100 s) squares past the float range: the mean
    is then inf, which the checks report as unbounded (Check.undefined_reason), never a
    warning.
    """
    with np.errstate(over="ignore", invalid="ignore"):
        const = np.float64(const)  # a Python float would raise OverflowError
        mean = (p * c_a_rms) ** 2 + (q * c_v_rms) ** 2 + const**2 + 2.0 * q * const
    return np.where(np.isnan(mean), np.inf, mean)


def _safe_ratio(torque: np.ndarray, limit: np.ndarray) -> np.ndarray:
    """torque/limit, infinite where a positive torque meets a zero limit."""
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = torque / limit
    return np.where(limit > 0.0, ratio, np.where(torque > 0.0, np.inf, 0.0))
