"""A plain scalar evaluation of ONE candidate, for tests only (book sec. 6.1.1).

One motor, one law, one transmission (its stage list, so one total ratio), one task
and one duration T: the requirements (peak and RMS torque, max speed...), the checks with
their margins and, by a bracketed root search, the shortest feasible duration. It is
written from the definitions, not from sizer's engine (it calls nothing in sizer.sizing
or sizer.mechanics), so that the engine's vectorized paths can be compared with it:

- the move: load speed v = h/T v_N(t/T), acceleration a = h/T^2 a_N(t/T), along the
  motion (the return move has direction -1: the constant load torque changes sign);
- the load torque u = J_l a + B_l v + F + direction*tau_ext; each stage, from the load to
  the motor, needs at its input J_s k_in a + preload + x/(k eta) while its output torque x
  drives (x >= 0) and x eta/k while the load drives (x < 0), k_in the speed of its input
  over the load's (sizer/mechanics/drive.py, ``power_flow``); the motor adds
  J_m K a + B_m K v;
- at rest (the dwell) the motor holds |tau_ext| / prod(k eta) (holding counts as driving);
- peaks: every law piece is cut where a stage's output torque changes sign or the motor
  speed crosses a corner speed of the intermittent region (there the torque, or the
  torque limit, has a kink); each part is sampled densely and its best samples refined
  with scipy.optimize.minimize_scalar;
- RMS: scipy.integrate.quad over the same parts (smooth there), plus the dwells;
- regions: the corner points of sizer.envelope (the catalog's curves or the completion
  rule), linear between corners; a speed past the last corner reads the last corner's
  torque (the speed itself is checked apart);
- checks: margin = 1 - value/limit, passed when margin >= required - 1e-9.

Slow (tens of milliseconds per duration) and simple on purpose.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from functools import cache, cached_property
from itertools import pairwise

import numpy as np
from scipy import integrate, optimize

from sizer.envelope import continuous_region, intermittent_region
from sizer.laws import MotionLaw, make_law
from sizer.model import Limits, Load, Motor, Stage, Task

TOLERANCE = 1e-9
"""A check passes when margin >= required - TOLERANCE (the verdict's documented rule)."""

SAMPLES = 129
"""Samples per part of a piece for the peak searches."""

KEEP = 1e-3
"""Sampled local maxima within this share of the best sample are refined."""


@dataclass(frozen=True)
class Candidate:
    """Everything one candidate is: motor, law, task, load, stages (motor to load), limits."""

    motor: Motor
    law: MotionLaw
    task: Task
    load: Load
    stages: tuple[Stage, ...]
    limits: Limits

    @property
    def ratio(self) -> float:
        """Total ratio K: motor speed over load speed."""
        return math.prod(s.ratio for s in self.stages)

    @property
    def h(self) -> float:
        return abs(self.task.displacement)

    @property
    def directions(self) -> tuple[float, ...]:
        sign = 1.0 if self.task.displacement >= 0 else -1.0
        return (sign, -sign) if self.task.return_move else (sign,)

    @cached_property
    def intermittent(self) -> tuple[np.ndarray, np.ndarray]:
        """The intermittent region's corner speeds and torques."""
        return _corners(intermittent_region(self.motor, self.limits.envelope))

    @cached_property
    def continuous(self) -> tuple[np.ndarray, np.ndarray]:
        """The continuous region's corner speeds and torques."""
        return _corners(continuous_region(self.motor, self.limits.envelope))

    @cached_property
    def input_ratios(self) -> list[float]:
        """Speed of each stage's input over the load speed."""
        return [math.prod(s.ratio for s in self.stages[i:]) for i in range(len(self.stages))]


@dataclass
class Evaluation:
    """The requirements of a candidate at one duration, and its checks."""

    duration: float
    max_speed: float
    peak_torque: float
    peak_ratio: float
    rms_torque: float
    thermal_speed: float
    checks: dict[str, tuple[float, float, float]] = field(default_factory=dict)
    """name -> (value, limit, required margin)."""

    def margin(self, name: str) -> float:
        value, limit, _ = self.checks[name]
        return margin(value, limit)

    @property
    def worst_slack(self) -> float:
        return min(margin(v, lim) - req for v, lim, req in self.checks.values())

    @property
    def feasible(self) -> bool:
        return self.worst_slack >= -TOLERANCE


def margin(value: float, limit: float) -> float:
    """1 - value/limit; where the limit is 0: 1 when nothing is needed, else -inf."""
    if limit > 0.0:
        return 1.0 - value / limit
    return -math.inf if value > 0.0 else 1.0


# ------------------------------------------------------------------ regions
def _corners(curve) -> tuple[np.ndarray, np.ndarray]:
    return np.array([p[0] for p in curve]), np.array([p[1] for p in curve])


def region_torque(region: tuple[np.ndarray, np.ndarray], speed):
    """Torque of a region (corners, linear between) at |speed|, clipped to its end."""
    speeds, torques = region
    return np.interp(np.minimum(np.abs(speed), speeds[-1]), speeds, torques)


# ------------------------------------------------------------- the transmission
def torques(c: Candidate, a_l, v_l, direction: float):
    """Motor torque and each stage's output torque at load acceleration a_l, speed v_l."""
    load = c.load
    x = load.inertia * a_l + load.damping * v_l + load.friction + direction * load.torque
    k_in = c.input_ratios
    outputs = [x] * len(c.stages)
    for i in reversed(range(len(c.stages))):
        s = c.stages[i]
        outputs[i] = x
        reflected = np.where(x >= 0.0, x / (s.ratio * s.efficiency), x * s.efficiency / s.ratio)
        x = s.inertia * k_in[i] * a_l + s.preload_torque + reflected
    K = c.ratio
    motor = c.motor.inertia * K * a_l + c.motor.damping * K * v_l + x
    return motor, outputs


def holding_torques(c: Candidate) -> tuple[float, list[float]]:
    """|torque| at the motor and at each stage output holding the constant load at rest."""
    outputs = []
    for i in range(len(c.stages)):
        outputs.append(abs(c.load.torque)
                       / math.prod(s.ratio * s.efficiency for s in c.stages[i + 1:]))
    motor = abs(c.load.torque) / math.prod(s.ratio * s.efficiency for s in c.stages)
    return motor, outputs


def inertia_ratio(c: Candidate) -> float:
    """Driven inertia (stages and load, reflected) or the load alone, over the rotor's."""
    K = c.ratio
    load = c.load.inertia / K**2
    upstream, stages = 1.0, 0.0
    for s in c.stages:
        stages += s.inertia / upstream**2
        upstream *= s.ratio
    numerator = load if c.limits.inertia_ratio_of == "load" else load + stages
    return numerator / c.motor.inertia if c.motor.inertia > 0 else math.inf


# ---------------------------------------------------------- peaks and integrals
def _maximum(f, a: float, b: float) -> float:
    """max of f on [a, b] (f smooth there): dense samples, the best ones refined."""
    if b <= a:
        return float(f(np.array([a]))[0])
    tau = np.linspace(a, b, SAMPLES)
    values = f(tau)
    best = float(values.max())
    if not math.isfinite(best):
        return best
    floor = best - KEEP * abs(best)
    for i in range(SAMPLES):
        left, right = max(i - 1, 0), min(i + 1, SAMPLES - 1)
        local = values[i] >= values[left] and values[i] >= values[right]
        flat = values[i] == values[left] and values[i] == values[right] and 0 < i < SAMPLES - 1
        if values[i] >= floor and local and not flat:
            # a sampled local maximum, the ends included: the peak lies between its
            # neighbours (at an end, between it and the next sample, unless f falls
            # right away from the end)
            if i in (0, SAMPLES - 1):
                inward = tau[i] + (1e-6 if i == 0 else -1e-6) * (tau[1] - tau[0])
                if float(f(np.array([inward]))[0]) <= values[i]:
                    continue
            found = optimize.minimize_scalar(
                lambda x: -float(f(np.array([x]))[0]), bounds=(tau[left], tau[right]),
                method="bounded", options={"xatol": 1e-14})
            best = max(best, -float(found.fun))
    return best


def _roots(g, a: float, b: float) -> list[float]:
    """Sign changes of g on [a, b] (dense samples, then brentq); g identically 0 has none."""
    tau = np.linspace(a, b, SAMPLES)
    values = g(tau)
    out = []
    for i in range(SAMPLES - 1):
        if values[i] == 0.0 and i > 0 and values[i - 1] * values[i + 1] < 0.0:
            out.append(float(tau[i]))  # a sign change exactly on a sample
        elif values[i] * values[i + 1] < 0.0:
            out.append(optimize.brentq(lambda x: float(g(np.array([x]))[0]), tau[i], tau[i + 1],
                                       xtol=1e-15, rtol=1e-15))
    return out


def law_maximum(law: MotionLaw, order: int) -> float:
    """max over the pieces of |d^order q_N / d tau^order| (C_v, C_a, C_j by sampling)."""
    return _law_maxima(law.spec)[order]


@cache
def _law_maxima(spec: str) -> dict[int, float]:
    law = make_law(spec)
    out = {}
    for order in (1, 2, 3):
        out[order] = max(
            _maximum(lambda t, i=i, order=order: np.abs(law.piece_derivative(i, t, order)),
                     p.start, p.end)
            for i, p in enumerate(law.pieces))
    return out


@cache
def jerk_bounded(spec: str) -> bool:
    """No step of the acceleration between pieces nor against rest at the ends."""
    law = make_law(spec)
    scale = _law_maxima(spec)[2]
    ends = [float(law.piece_derivative(0, law.pieces[0].start, 2)),
            float(law.piece_derivative(len(law.pieces) - 1, law.pieces[-1].end, 2))]
    steps = [float(law.piece_derivative(i + 1, law.pieces[i + 1].start, 2)
                   - law.piece_derivative(i, law.pieces[i].end, 2))
             for i in range(len(law.pieces) - 1)]
    return all(abs(x) <= 1e-9 * scale for x in ends + steps)


@cache
def speed_square_integral(spec: str) -> float:
    """int_0^1 v_N^2 d tau (C_v_rms^2), by quad per piece."""
    law = make_law(spec)
    return sum(integrate.quad(lambda t, i=i: float(law.piece_derivative(i, t, 1)) ** 2,
                              p.start, p.end, epsabs=0.0, epsrel=1e-13, limit=200)[0]
               for i, p in enumerate(law.pieces))


class Move:
    """One move of the cycle at duration T in one direction: its torques against tau."""

    def __init__(self, c: Candidate, T: float, direction: float) -> None:
        self.c, self.T, self.direction = c, T, direction

    def motion(self, piece: int, tau):
        """Load acceleration and speed (along the motion) at tau of one piece."""
        law, h, T = self.c.law, self.c.h, self.T
        return (h / T**2 * law.piece_derivative(piece, tau, 2),
                h / T * law.piece_derivative(piece, tau, 1))

    def motor_torque(self, piece: int, tau):
        return torques(self.c, *self.motion(piece, tau), self.direction)[0]

    def stage_output(self, piece: int, tau, stage: int):
        return torques(self.c, *self.motion(piece, tau), self.direction)[1][stage]

    def abs_torque(self, piece: int, tau):
        return np.abs(self.motor_torque(piece, tau))

    def output(self, stage: int):
        """The output torque of one stage as a function of (piece, tau)."""
        return lambda piece, tau: self.stage_output(piece, tau, stage)

    def abs_output(self, stage: int):
        return lambda piece, tau: np.abs(self.stage_output(piece, tau, stage))

    def motor_speed(self, piece: int, tau):
        return self.c.ratio * self.motion(piece, tau)[1]

    def peak_ratio(self, piece: int, tau):
        """|torque| over the intermittent limit at the motor speed (clipped to the region)."""
        torque = np.abs(self.motor_torque(piece, tau))
        limit = region_torque(self.c.intermittent, self.motor_speed(piece, tau))
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(limit > 0.0, torque / limit, np.where(torque > 0.0, np.inf, 0.0))

    def parts(self, piece: int) -> list[tuple[float, float]]:
        """The piece cut where a stage output changes sign or the speed crosses a corner."""
        p = self.c.law.pieces[piece]
        cuts = {p.start, p.end}
        for stage in range(len(self.c.stages)):
            cuts.update(_roots(lambda t, s=stage: self.stage_output(piece, t, s),
                               p.start, p.end))
        for corner in self.c.intermittent[0][1:]:
            cuts.update(_roots(lambda t, w=corner: self.motor_speed(piece, t) - w,
                               p.start, p.end))
        edges = sorted(cuts)
        return list(pairwise(edges))

    def peak(self, f) -> float:
        """max over the move of f(piece, tau), part by part."""
        return max(_maximum(lambda t, i=i: f(i, t), a, b)
                   for i in range(len(self.c.law.pieces)) for a, b in self._parts(i))

    def integral(self, f) -> float:
        """int_0^T f(piece, t/T)^2 dt, by quad over the parts."""
        total = error = 0.0
        for i in range(len(self.c.law.pieces)):
            for a, b in self._parts(i):
                with warnings.catch_warnings():  # roundoff near 1e-13: its estimate is checked
                    warnings.simplefilter("ignore", integrate.IntegrationWarning)
                    value, bound = integrate.quad(
                        lambda t, i=i: float(f(i, np.array([t]))[0]) ** 2,
                        a, b, epsabs=0.0, epsrel=1e-13, limit=200)
                total, error = total + value, error + bound
        if error > 1e-11 * total:
            raise ArithmeticError(f"quad's error estimate {error:.3g} of {total:.3g}")
        return self.T * total

    def _parts(self, piece: int):
        cache = self.__dict__.setdefault("_cache", {})
        if piece not in cache:
            cache[piece] = self.parts(piece)
        return cache[piece]


# -------------------------------------------------------------- one duration
def evaluate(c: Candidate, T: float) -> Evaluation:
    """Requirements and checks of the candidate at duration T (sec. 6.1.1)."""
    law, h, K, limits, task = c.law, c.h, c.ratio, c.limits, c.task
    n = len(c.directions)
    load_speed = h / T * law_maximum(law, 1)
    max_speed = K * load_speed
    peak = ratio = square = 0.0
    stage_peak = [0.0] * len(c.stages)
    stage_square = [0.0] * len(c.stages)
    for direction in c.directions:
        move = Move(c, T, direction)
        peak = max(peak, move.peak(move.abs_torque))
        if np.all(c.intermittent[1] == c.intermittent[1][0]):  # a flat limit: the
            ratio = peak / c.intermittent[1][0]  # ratio peaks with the torque
        else:
            ratio = max(ratio, move.peak(move.peak_ratio))
        square += move.integral(move.motor_torque)
        for s, stage in enumerate(c.stages):
            if stage.peak_output_torque is not None:
                stage_peak[s] = max(stage_peak[s], move.peak(move.abs_output(s)))
            if stage.rated_output_torque is not None:
                stage_square[s] += move.integral(move.output(s))
    hold, stage_hold = holding_torques(c)
    if task.dwell > 0.0 and hold > 0.0:
        peak = max(peak, hold)
        at_rest = float(region_torque(c.intermittent, 0.0))
        ratio = max(ratio, hold / at_rest if at_rest > 0 else math.inf)
        stage_peak = [max(p, q) for p, q in zip(stage_peak, stage_hold, strict=True)]
    cycle = n * (T + task.dwell)
    rms = math.sqrt((square + n * task.dwell * hold**2) / cycle)
    stage_rms = [math.sqrt((sq + n * task.dwell * q**2) / cycle)
                 for sq, q in zip(stage_square, stage_hold, strict=True)]
    thermal = thermal_speed(c, T, max_speed)
    ev = Evaluation(T, max_speed, peak, ratio, rms, thermal)
    cont, inter = c.continuous, c.intermittent
    ev.checks["speed"] = (max_speed, float(inter[0][-1]), limits.speed_margin)
    ev.checks["peak"] = (ratio, 1.0, limits.torque_margin)
    ev.checks["rms"] = (rms, float(region_torque(cont, thermal)), limits.torque_margin)
    ev.checks["thermal_speed"] = (thermal, float(cont[0][-1]), limits.speed_margin)
    if limits.inertia_ratio is not None:
        ev.checks["inertia_ratio"] = (inertia_ratio(c), limits.inertia_ratio, 0.0)
    if limits.max_speed is not None:
        ev.checks["load_speed"] = (load_speed, limits.max_speed, 0.0)
    if limits.max_acceleration is not None:
        ev.checks["acceleration"] = (h / T**2 * law_maximum(law, 2), limits.max_acceleration,
                                     0.0)
    if limits.max_jerk is not None:
        jerk = h / T**3 * law_maximum(law, 3) if jerk_bounded(law.spec) else math.inf
        ev.checks["jerk"] = (jerk, limits.max_jerk, 0.0)
    k_in = c.input_ratios
    for s, (stage, label) in enumerate(zip(c.stages, stage_labels(c.stages), strict=True)):
        if stage.max_input_speed is not None:
            ev.checks[f"{label}_speed"] = (k_in[s] * load_speed, stage.max_input_speed,
                                           limits.speed_margin)
        if stage.rated_output_torque is not None:
            ev.checks[f"{label}_rms"] = (stage_rms[s], stage.rated_output_torque,
                                         limits.torque_margin)
        if stage.peak_output_torque is not None:
            ev.checks[f"{label}_peak"] = (stage_peak[s], stage.peak_output_torque,
                                          limits.torque_margin)
    return ev


def thermal_speed(c: Candidate, T: float, max_speed: float) -> float:
    """Speed of the RMS check: the max speed, the cycle's RMS speed or its mean speed."""
    rule, n = c.limits.thermal_speed, len(c.directions)
    cycle = n * (T + c.task.dwell)
    if rule == "max":
        return max_speed
    if rule == "rms":  # sqrt(n int_0^T (K v)^2 dt / cycle)
        return math.sqrt(n * T * (c.ratio * c.h / T) ** 2 * speed_square_integral(c.law.spec)
                         / cycle)
    return n * c.ratio * c.h / cycle  # mean |speed|: the law is monotone


def stage_labels(stages: tuple[Stage, ...]) -> list[str]:
    """A stage's name, else its kind, numbered when kinds repeat (the checks' names)."""
    kinds = [s.name or s.kind for s in stages]
    return [k if kinds.count(k) == 1 else f"{k}{i + 1}" for i, k in enumerate(kinds)]


# ----------------------------------------------------------- the shortest move
def initial_duration(c: Candidate) -> float:
    """A duration near T_min: the speed and inertial bounds of eq. (6.2), unloaded."""
    K, h = c.ratio, c.h
    J_t = c.motor.inertia + c.load.inertia / K**2 + sum(
        s.inertia * (k / K) ** 2 for s, k in zip(c.stages, c.input_ratios, strict=True))
    speeds, torques_ = c.intermittent
    tau_max = float(torques_.max())
    return max(law_maximum(c.law, 1) * K * h / float(speeds[-1]),
               math.sqrt(law_maximum(c.law, 2) * K * h * J_t / tau_max), 1e-6)


def minimum_duration(c: Candidate) -> float | None:
    """T_min to 1e-13 relative; None where no duration is feasible.

    T_min is where the worst slack reaches 0 (only where no duration reaches 0 but some
    are within the tolerance, where it reaches -TOLERANCE). A bracket first: from a
    duration near T_min, halve while feasible, else walk by factors of 2 up the slack
    until feasible; where the slack stops rising before, its maximum between the last
    steps (minimize_scalar on log T) decides.
    """
    def slack(x: float) -> float:
        return evaluate(c, math.exp(x)).worst_slack

    step = math.log(2.0)

    def descend(hi: float) -> tuple[float, float] | None:
        """From a feasible log T down to an infeasible one: (lo, hi)."""
        for _ in range(80):
            if slack(hi - step) < 0.0:
                return hi - step, hi
            hi -= step
        return None

    x0 = math.log(initial_duration(c))
    first = evaluate(c, math.exp(x0))
    if "inertia_ratio" in first.checks:  # no duration changes it
        value, limit, required = first.checks["inertia_ratio"]
        if margin(value, limit) - required < -TOLERANCE:
            return None
    f0 = first.worst_slack
    target = 0.0
    if f0 >= 0.0:
        bracket = descend(x0)
    else:
        f1 = slack(x0 + step)
        d = step if f1 > f0 else -step
        (prev, _), (cur, f_cur) = ((x0, f0), (x0 + step, f1))[:: 1 if d > 0 else -1]
        bracket = None
        for _ in range(80):
            if f_cur >= 0.0:
                bracket = (prev, cur) if d > 0 else descend(cur)
                break
            nxt = cur + d
            g = slack(nxt)
            if g <= f_cur and g < 0.0:  # the slack stopped rising: its top is in [prev, nxt]
                lo, hi = min(prev, nxt), max(prev, nxt)
                top = optimize.minimize_scalar(lambda y: -slack(y), bounds=(lo, hi),
                                               method="bounded", options={"xatol": 1e-10})
                if -top.fun < -TOLERANCE:
                    return None
                target = 0.0 if -top.fun >= 0.0 else -TOLERANCE
                bracket = (lo, float(top.x))
                break
            prev, cur, f_cur = cur, nxt, g
    if bracket is None:
        return None
    lo, hi = bracket
    root = optimize.brentq(lambda y: slack(y) - target, lo, hi, xtol=1e-13, rtol=1e-15)
    return math.exp(root)
