"""The exact requirements of a piecewise-polynomial move, per candidate (book sec. 6.1.1;
issue 12).

A move with boundary speeds has a shape that depends on its duration, so each candidate
carries its own piecewise polynomial: ``breaks`` (n, P+1) and ``coefficients``
(n, P, d+1), the load's position relative to the move's start in ascending powers of
t - breaks[:, p]. The physics is the engine's (sizer.sizing.cycle.CycleCalculator):

    tau = J_m K a_l + B_m K v_l + shaft(a_l, v_l),   (a_l, v_l) = s (a, v)

along the motion, with s the sign of the load's speed, pointwise (a move with boundary
speeds may reverse; ``direction`` where the speed is zero, and on a sub-piece where it
stays within rounding of zero, such as one cut off next to a rest end by a root that
rounding moved) and shaft() the drive's chain (sizer.mechanics.drive.Drive), efficiencies
in the direction of power flow.

Every piece is cut at the real roots of v and, stage by stage from the load up, at the
roots of each stage's output torque (where its power flow reverses), so that on every
sub-piece each channel (motor torque, stage outputs, the load's torque) is one
polynomial: the one of Drive.linear_pieces' linear functions that is the channel there
(the one with the largest integral over the sub-piece, as in the engine: each function
is at most the channel, equal where its choice of flow directions holds). Then:

- integrals by Gauss-Legendre with enough nodes for the degree (exact);
- peaks at the sub-pieces' ends and the real roots of the derivative (:func:`_unit_roots`:
  closed forms to degree 2; above, the derivative's roots cut [0, 1] into monotone
  intervals and each sign change is found by the project's root finder, all rows at
  once);
- the peak ratio |tau| / tau_int(|omega|) (the speed clipped into the region, as in the
  engine) at the ends, at the torque's stationary points, where |omega| crosses a corner of
  the region and at the stationary points of tau / (c0 + c1 |omega|) on each of its
  segments (the roots of tau' L - tau L'); every point is evaluated with the true region.

Arrays are (candidates, sub-pieces); loops run over degrees, stages and region segments
only.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from sizer.laws.quadrature import gauss_legendre
from sizer.mechanics import Drive
from sizer.numerics.roots import illinois
from sizer.sizing.motors import MotorArrays

_DEGREE_TOLERANCE = 1e-12
"""Coefficients below this share of a row's largest (on the unit interval) are zero."""
_IMAGINARY_TOLERANCE = 1e-7
"""Complex roots of a quadratic this close to the real axis (the unit interval's scale)
are kept as roots: a spurious cut costs nothing, a missed pair of close crossings would."""
_NEWTON_STEPS = 3
"""Newton steps polishing the closed-form roots of degree 1 and 2 (each taken only where
it lowers |c(u)|)."""
_SPEED_NOISE = 1e-12
"""Speeds below this share of the piece's largest possible speed have no sign."""


@dataclass(frozen=True)
class MoveFigures:
    """Requirements of one move for each candidate (arrays over candidates (n,), SI).

    Peaks: peak_torque (max |tau| at the motor), peak_ratio (max |tau|/tau_int(|omega|)),
    load_torque (max |u|), max_speed (max |omega| at the motor), load_speed,
    load_acceleration, load_jerk (max |.| at the load; inf where the acceleration jumps at
    an interior break: the jumps at the move's ends depend on its neighbours); per stage
    stage_peak (max |output torque|) and stage_speed (max input speed). Integrals over the
    move: torque_square (int tau^2 dt), stage_square (int x_i^2 dt per stage), speed_square
    (int omega^2 dt), speed_abs (int |omega| dt) and energy (int tau omega dt at the motor
    shaft, J, signed: negative when the load drives).
    """

    peak_torque: np.ndarray
    peak_ratio: np.ndarray
    load_torque: np.ndarray
    max_speed: np.ndarray
    load_speed: np.ndarray
    load_acceleration: np.ndarray
    load_jerk: np.ndarray
    stage_peak: list[np.ndarray]
    stage_speed: list[np.ndarray]
    torque_square: np.ndarray
    stage_square: list[np.ndarray]
    speed_square: np.ndarray
    speed_abs: np.ndarray
    energy: np.ndarray


def polynomial_move(breaks: np.ndarray, coefficients: np.ndarray, drive: Drive,
                    motors: MotorArrays, direction: float) -> MoveFigures:
    """The exact requirements of the piecewise-polynomial moves of n candidates.

    ``breaks`` (n, P+1): seconds from the move's start, each row increasing;
    ``coefficients`` (n, P, d+1): the load's position relative to the move's start in
    ascending powers of (t - breaks[:, p]) (rad or m); ``drive`` and ``motors`` per
    candidate (arrays of length n or 1); ``direction`` (+1/-1) the move's sign, used
    where the speed is exactly zero.
    """
    breaks = np.asarray(breaks, dtype=float)
    coefficients = np.asarray(coefficients, dtype=float)
    n, count, width = coefficients.shape
    if width < 4:  # at least a cubic, so that the jerk has a polynomial
        coefficients = np.concatenate(
            (coefficients, np.zeros((n, count, 4 - width))), axis=2)
    sign = 1.0 if direction >= 0 else -1.0
    channels = _Channels(drive, motors, n)
    piece = np.broadcast_to(np.arange(count), (n, count)).copy()
    widths = np.diff(breaks, axis=1)
    cuts = _Cuts(piece, np.zeros((n, count)), widths)
    # where the speed changes sign (Coulomb friction, the external load's sense)
    cuts = cuts.split(_Kinematics(coefficients, widths, cuts, sign).V)
    # where a stage's power flow reverses, from the load up: the output of stage i is
    # one function where the stages after it keep their flow
    if channels.reversing:
        for i in reversed(range(len(drive.stages))):
            if not np.all(drive.stages[i].efficiency == 1.0):
                kin = _Kinematics(coefficients, widths, cuts, sign)
                cuts = cuts.split(channels.polynomial(channels.stages[i], kin))
    kin = _Kinematics(coefficients, widths, cuts, sign)
    return _figures(kin, channels, drive, motors, breaks, coefficients)


# ---------------------------------------------------------------- the channels
class _Channels:
    """Each channel's linear functions of the load's (a_l, v_l) along the motion
    (Drive.linear_pieces, the motor's rotor added), for both senses of motion: lists of
    (A+, B+, C+, A-, B-, C-) arrays over the candidates."""

    def __init__(self, drive: Drive, motors: MotorArrays, n: int) -> None:
        plus, minus = drive.linear_pieces(1.0), drive.linear_pieces(-1.0)
        K = drive.ratio
        rotor = (motors.inertia * K, motors.damping * K)

        def both(first, second, extra=(0.0, 0.0)):
            return [tuple(np.broadcast_to(np.asarray(x, dtype=float), (n,))
                          for x in (A1 + extra[0], B1 + extra[1], C1,
                                    A2 + extra[0], B2 + extra[1], C2))
                    for (A1, B1, C1), (A2, B2, C2) in zip(first, second, strict=True)]

        self.motor = both(plus[0], minus[0], rotor)
        self.stages = [both(p, m) for p, m in zip(plus[1], minus[1], strict=True)]
        load = drive.load
        self.load = both([(np.full(1, float(load.inertia)), np.full(1, float(load.damping)),
                           np.full(1, load.friction + load.torque))],
                         [(np.full(1, float(load.inertia)), np.full(1, float(load.damping)),
                           np.full(1, load.friction - load.torque))])
        self.reversing = len(self.motor) > 1

    @staticmethod
    def polynomial(functions, kin: _Kinematics) -> np.ndarray:
        """The channel on each sub-piece as one polynomial of u (n, M, d): of its linear
        functions the one with the largest integral there, s (A a + B v) + C."""
        up = kin.sigma > 0.0
        chosen: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None
        best = None
        for A1, B1, C1, A2, B2, C2 in functions:
            A = np.where(up, A1[:, None], A2[:, None])
            B = np.where(up, B1[:, None], B2[:, None])
            C = np.where(up, C1[:, None], C2[:, None])
            integral = kin.sigma * (A * kin.dv + B * kin.dx) + C * kin.w
            if best is None:
                best, chosen = integral, (A, B, C)
            else:
                assert chosen is not None
                better = integral > best
                best = np.where(better, integral, best)
                A, B, C = (np.where(better, new, old)
                           for new, old in zip((A, B, C), chosen, strict=True))
                chosen = (A, B, C)
        assert chosen is not None  # at least one combination
        A, B, C = chosen
        out = kin.sigma[..., None] * (A[..., None] * kin.A_full + B[..., None] * kin.V)
        out[..., 0] += C
        return out


# ------------------------------------------------------------------ sub-pieces
class _Cuts:
    """The sub-pieces: per candidate row, the piece of each and its interval [lo, hi] in
    the piece's own time (s = t - breaks[p]). Empty sub-pieces (lo == hi) pad the rows."""

    def __init__(self, piece: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> None:
        self.piece, self.lo, self.hi = piece, lo, hi

    def split(self, poly: np.ndarray) -> _Cuts:
        """Cut every sub-piece at the real roots of its polynomial ``poly`` (n, M, m+1) of
        the sub-piece's unit variable, then drop the empty ones (keeping the order)."""
        n = len(self.lo)
        roots = _unit_roots(poly)
        w = self.hi - self.lo
        at = self.lo[..., None] + w[..., None] * roots
        at = np.where(np.isnan(at), self.hi[..., None], np.minimum(at, self.hi[..., None]))
        edges = np.sort(np.concatenate((self.lo[..., None], at, self.hi[..., None]), axis=-1),
                        axis=-1)
        parts = edges.shape[-1] - 1
        lo = edges[..., :-1].reshape(n, self.lo.shape[1] * parts)
        hi = edges[..., 1:].reshape(n, self.lo.shape[1] * parts)
        piece = np.repeat(self.piece, parts, axis=1)
        empty = hi <= lo
        order = np.argsort(empty, axis=1, kind="stable")
        keep = max(int((~empty).sum(axis=1).max(initial=0)), 1)
        order = order[:, :keep]
        return _Cuts(*(np.take_along_axis(x, order, axis=1) for x in (piece, lo, hi)))


class _Kinematics:
    """The load's motion on every sub-piece as polynomials of the unit variable u in
    [0, 1] (t = breaks[p] + lo + w u): position X, speed V, acceleration A (also padded
    to V's length: A_full) and jerk J, coefficients (n, M, .); the sense of motion sigma,
    the width w, dx = int v dt and dv = int a dt over the sub-piece."""

    def __init__(self, coefficients: np.ndarray, widths: np.ndarray, cuts: _Cuts,
                 direction: float) -> None:
        own = np.take_along_axis(coefficients, cuts.piece[..., None], axis=1)
        self.w = cuts.hi - cuts.lo
        self.valid = self.w > 0.0
        w = np.where(self.valid, self.w, 1.0)[..., None]
        self.X = _compose(own, cuts.lo, self.w)
        self.V = _derivative(self.X) / w
        self.A = _derivative(self.V) / w
        self.J = _derivative(self.A) / w
        self.A_full = _pad(self.A, self.V.shape[-1])
        # the sense of motion: the sign of v inside, where it stands out of the rounding
        # of its piece (a sub-piece cut off by a root that rounding moved off an end or a
        # double root is at rest: ``direction``, as in the engine)
        mid = _polyval(self.V, np.full((*self.w.shape, 1), 0.5))[..., 0]
        noise = _SPEED_NOISE * np.take_along_axis(_speed_scale(coefficients, widths), cuts.piece,
                                                  axis=1)
        self.sigma = np.where(mid > noise, 1.0, np.where(mid < -noise, -1.0, direction))
        self.dx = self.X[..., 1:].sum(axis=-1)
        self.dv = self.V[..., 1:].sum(axis=-1)


# ---------------------------------------------------------------- the figures
def _figures(kin: _Kinematics, channels: _Channels, drive: Drive, motors: MotorArrays,
             breaks: np.ndarray, coefficients: np.ndarray) -> MoveFigures:
    n = len(kin.w)
    K = np.broadcast_to(np.asarray(drive.ratio, dtype=float), (n,))
    valid = kin.valid
    motor = channels.polynomial(channels.motor, kin)  # along the motion
    stages = [channels.polynomial(f, kin) for f in channels.stages]
    load = channels.polynomial(channels.load, kin)
    nodes, weights = gauss_legendre(kin.V.shape[-1])
    nodes = 0.5 * (nodes + 1.0)
    weights = np.where(valid, kin.w, 0.0)[..., None] * (0.5 * weights)

    def integral(values):
        return (weights * values).sum(axis=(1, 2))

    at = np.broadcast_to(nodes, kin.w.shape + nodes.shape)
    torque_nodes = _polyval(motor, at)
    speed_nodes = _polyval(kin.V, at)
    torque_square = integral(torque_nodes**2)
    stage_square = [integral(_polyval(x, at) ** 2) for x in stages]
    speed_square = K * K * integral(speed_nodes**2)
    # tau omega = (s tau_along)(K v) = tau_along K |v|
    energy = K * integral(torque_nodes * kin.sigma[..., None] * speed_nodes)
    speed_abs = K * np.where(valid, kin.sigma * kin.dx, 0.0).sum(axis=1)

    motor_points = _critical_points(motor)
    peak_torque = _peak(motor, motor_points, valid)
    stage_peak = [_peak(x, _critical_points(x), valid) for x in stages]
    load_torque = _peak(load, _critical_points(load), valid)
    along = kin.sigma[..., None] * kin.V  # |v| on each sub-piece
    speed_points = _critical_points(along)
    speed_values = _polyval(along, speed_points)
    fastest = np.where(valid, speed_values.max(axis=-1), -np.inf)
    slowest = np.where(valid, speed_values.min(axis=-1), np.inf)
    load_speed = np.where(valid, np.abs(fastest), 0.0).max(axis=1, initial=0.0)
    load_acceleration = _peak(kin.A, _critical_points(kin.A), valid)
    load_jerk = _peak(kin.J, _critical_points(kin.J), valid)
    load_jerk = np.where(_acceleration_jumps(breaks, coefficients), np.inf, load_jerk)
    peak_ratio = _peak_ratio(motor, motor_points, kin, K, motors.intermittent,
                             K[:, None] * slowest, K[:, None] * fastest)
    return MoveFigures(
        peak_torque=peak_torque, peak_ratio=peak_ratio, load_torque=load_torque,
        max_speed=K * load_speed, load_speed=load_speed,
        load_acceleration=load_acceleration, load_jerk=load_jerk, stage_peak=stage_peak,
        stage_speed=[np.broadcast_to(k, (n,)) * load_speed for k in drive.input_ratios],
        torque_square=torque_square, stage_square=stage_square, speed_square=speed_square,
        speed_abs=speed_abs, energy=energy)


def _speed_scale(coefficients: np.ndarray, widths: np.ndarray) -> np.ndarray:
    """Per piece a bound of |v| on it: sum_k k |c_k| width^(k-1), (n, P)."""
    speed = np.abs(_derivative(coefficients))
    powers = widths[..., None] ** np.arange(speed.shape[-1])
    return (speed * powers).sum(axis=-1)


def _acceleration_jumps(breaks: np.ndarray, coefficients: np.ndarray) -> np.ndarray:
    """Per candidate, whether the acceleration jumps at an interior break (infinite jerk)."""
    if coefficients.shape[1] < 2:
        return np.zeros(len(coefficients), dtype=bool)
    widths = np.diff(breaks, axis=1)
    acc = _derivative(_derivative(coefficients))
    end = _polyval(acc[:, :-1], widths[:, :-1, None])[..., 0]
    start = acc[:, 1:, 0]
    scale = np.maximum(np.abs(end), np.abs(start)).max(axis=1)
    real = (widths[:, :-1] > 0.0) & (widths[:, 1:] > 0.0)  # empty pieces pad rows
    return np.any(real & (np.abs(end - start) > 1e-9 * scale[:, None]), axis=1)


def _critical_points(poly: np.ndarray) -> np.ndarray:
    """The unit variable's ends and the roots of the derivative inside (NaN ones at 0)."""
    roots = np.nan_to_num(_unit_roots(_derivative(poly)), nan=0.0)
    ends = np.broadcast_to(np.array([0.0, 1.0]), (*poly.shape[:-1], 2))
    return np.concatenate((ends, roots), axis=-1)


def _peak(poly: np.ndarray, points: np.ndarray, valid: np.ndarray) -> np.ndarray:
    """max |poly| over the valid sub-pieces, from its values at ``points``."""
    values = np.abs(_polyval(poly, points)).max(axis=-1)
    return np.where(valid, values, 0.0).max(axis=1, initial=0.0)


def _peak_ratio(motor: np.ndarray, points: np.ndarray, kin: _Kinematics, K: np.ndarray,
                region, slowest: np.ndarray, fastest: np.ndarray) -> np.ndarray:
    """max |tau| / tau_int(|omega|) over the move (the speed clipped into the region).

    On the speeds of one segment of the region the limit is a line L = c0 + c1 |omega|, so
    the maximum is at a sub-piece's end, where |omega| crosses a corner, at a stationary
    point of tau (a flat limit) or at a root of tau' L - tau L'. ``slowest`` and
    ``fastest`` bound |omega| on each sub-piece: only the corners and segments they reach
    are solved for.
    """
    n = len(K)
    valid = kin.valid
    omega = (kin.sigma * K[:, None])[..., None] * kin.V  # |omega| on each sub-piece
    ratio = np.zeros(n)

    def evaluate(rows, cols, u):
        torque = np.abs(_polyval(motor[rows, cols], u))
        speed = _polyval(omega[rows, cols], u)
        limit = region.take(rows).limit_clipped(speed)
        return _safe_ratio(torque, limit).max(axis=-1)

    def gather(rows, cols, values):
        dense = np.zeros(valid.shape)
        dense[rows, cols] = values
        return dense.max(axis=1)

    rows, cols = np.nonzero(valid)
    if not len(rows):
        return ratio
    ratio = gather(rows, cols, evaluate(rows, cols, points[rows, cols]))
    speeds, torques, top = region.speeds, region.torques, region.max_speed
    derivative = _pad(_derivative(motor), motor.shape[-1])
    for j in range(1, speeds.shape[1]):  # corners: |omega| = s_j
        corner = speeds[:, j]
        reach = valid & (corner <= top)[:, None] & (slowest < corner[:, None]) \
            & (fastest > corner[:, None])
        rows, cols = np.nonzero(reach)
        if len(rows):
            crossing = omega[rows, cols].copy()
            crossing[:, 0] -= corner[rows]
            u = np.nan_to_num(_unit_roots(crossing), nan=0.0)
            ratio = np.maximum(ratio, gather(rows, cols, evaluate(rows, cols, u)))
    for j in range(speeds.shape[1] - 1):  # segments: L = t_j + slope (|omega| - s_j)
        start, end = speeds[:, j], speeds[:, j + 1]
        slope = (torques[:, j + 1] - torques[:, j]) / (end - start)
        reach = valid & ((start < top) & (slope != 0.0))[:, None] \
            & (fastest > start[:, None]) & (slowest < end[:, None])
        rows, cols = np.nonzero(reach)
        if len(rows):
            line = slope[rows, None] * omega[rows, cols]
            line[:, 0] += torques[rows, j] - slope[rows] * start[rows]
            tau = motor[rows, cols]
            first = _multiply(derivative[rows, cols], line)
            stationary = first - _pad(_multiply(tau, _derivative(line)), first.shape[-1])
            u = np.nan_to_num(_unit_roots(stationary), nan=0.0)
            ratio = np.maximum(ratio, gather(rows, cols, evaluate(rows, cols, u)))
    return ratio


def _safe_ratio(torque: np.ndarray, limit: np.ndarray) -> np.ndarray:
    """torque/limit, infinite where a positive torque meets a zero limit."""
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = torque / limit
    return np.where(limit > 0.0, ratio, np.where(torque > 0.0, np.inf, 0.0))


# ------------------------------------------------------------------ polynomials
def _polyval(c: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Horner: coefficients c (..., m+1) ascending, points u (..., k) -> (..., k)."""
    out = np.broadcast_to(c[..., -1:], np.broadcast_shapes((*c.shape[:-1], 1), u.shape))
    if c.shape[-1] == 1:
        return out.copy()
    for k in range(c.shape[-1] - 2, -1, -1):
        out = out * u + c[..., k:k + 1]
    return out


def _derivative(c: np.ndarray) -> np.ndarray:
    """d/du of ascending coefficients (at least one coefficient is kept)."""
    m = c.shape[-1] - 1
    if m == 0:
        return np.zeros_like(c)
    return c[..., 1:] * np.arange(1, m + 1)


def _pad(c: np.ndarray, length: int) -> np.ndarray:
    extra = length - c.shape[-1]
    if extra <= 0:
        return c
    return np.concatenate((c, np.zeros((*c.shape[:-1], extra))), axis=-1)


def _multiply(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The product of two polynomials, row by row."""
    rows = np.broadcast_shapes(a.shape[:-1], b.shape[:-1])
    out = np.zeros((*rows, a.shape[-1] + b.shape[-1] - 1))
    for i in range(a.shape[-1]):
        out[..., i:i + b.shape[-1]] += a[..., i:i + 1] * b
    return out


def _compose(c: np.ndarray, s0: np.ndarray, w: np.ndarray) -> np.ndarray:
    """Coefficients in u of c(s0 + w u) (Horner on polynomials)."""
    out = c[..., -1:]
    s0, w = s0[..., None], w[..., None]
    for k in range(c.shape[-1] - 2, -1, -1):
        new = np.zeros((*out.shape[:-1], out.shape[-1] + 1))
        new[..., :-1] = out * s0
        new[..., 1:] += out * w
        new[..., 0] += c[..., k]
        out = new
    return out


def _unit_roots(c: np.ndarray) -> np.ndarray:
    """The real roots inside [0, 1] of polynomials c (..., m+1), the ends aside (every use
    has them already): (..., m), NaN for none.

    Roots at the ends are divided out first (u^k, (1-u)^k where the low coefficients in
    u, or in 1-u, are below _DEGREE_TOLERANCE of the largest: a double root at a rest
    end would otherwise come back as two roots off the end by sqrt(eps)), then the
    negligible top coefficients are dropped (on [0, 1] either moves the polynomial by
    less than that share). The rows of each degree are solved together
    (:func:`_real_roots`), and Newton steps polish the roots (a step is taken only where
    it lowers |c(u)|).
    """
    shape = c.shape
    m = shape[-1] - 1
    width = max(m, 1)
    flat = np.array(c.reshape(-1, m + 1), dtype=float)  # a copy: rows are deflated in place
    out = np.full((len(flat), width), np.nan)
    if m == 0 or not len(flat):
        return out.reshape((*shape[:-1], width))
    flat = _deflate(flat)
    size = np.abs(flat)
    ends = np.flatnonzero(np.abs(flat.sum(axis=1))
                          <= _DEGREE_TOLERANCE * size.max(axis=1))  # c(1) = 0
    if len(ends):
        ones = np.ones(len(ends))
        flat[ends] = _compose(_deflate(_compose(flat[ends], ones, -ones)), ones, -ones)
    size = np.abs(flat)
    big = size > _DEGREE_TOLERANCE * size.max(axis=1, keepdims=True)
    degree = np.where(big.any(axis=1), m - np.argmax(big[:, ::-1], axis=1), 0)
    for k in range(1, m + 1):
        rows = np.flatnonzero(degree == k)
        if len(rows):
            out[rows, :k] = _real_roots(flat[rows, :k + 1])
    slope = _derivative(flat)
    u = np.nan_to_num(out, nan=0.5)
    value = _polyval(flat, u)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for _ in range(_NEWTON_STEPS):
            step = np.clip(u - value / _polyval(slope, u), 0.0, 1.0)
            new = _polyval(flat, step)
            better = np.isfinite(new) & (np.abs(new) < np.abs(value))
            u = np.where(better, step, u)
            value = np.where(better, new, value)
    out = np.where(np.isnan(out), np.nan, u)
    return out.reshape((*shape[:-1], width))


def _deflate(flat: np.ndarray) -> np.ndarray:
    """Rows c (rows, m+1) with their roots at u = 0 divided out: the low coefficients
    below _DEGREE_TOLERANCE of the row's largest dropped, the rest shifted down."""
    size = np.abs(flat)
    small = size <= _DEGREE_TOLERANCE * size.max(axis=1, keepdims=True)
    low = np.argmin(small, axis=1)  # 0 where none (or where all are: a zero row)
    if not low.any():
        return flat
    index = np.arange(flat.shape[1])[None, :] + low[:, None]
    inside = index < flat.shape[1]
    shifted = np.take_along_axis(flat, np.minimum(index, flat.shape[1] - 1), axis=1)
    return np.where(inside, shifted, 0.0)


def _real_roots(c: np.ndarray) -> np.ndarray:
    """Roots in (0, 1) of rows c (rows, k+1) of degree exactly k: (rows, k), NaN for none.

    Degrees 1 and 2 in closed form (a complex pair within _IMAGINARY_TOLERANCE of the
    axis counts as a root: a spurious cut costs nothing). Above, every root where the
    sign changes: the derivative's roots (recursively) cut [0, 1] into intervals where
    the polynomial is monotone, and each one that brackets a sign change holds one root,
    found by the project's root finder (Illinois). A root where the sign does not
    change (even multiplicity) is of no use: it cuts no sign of speed or flow, and the
    maxima of a smooth function are where its derivative changes sign.
    """
    k = c.shape[1] - 1
    if k <= 2:
        z = _roots_of_degree(c)
        keep = (np.abs(z.imag) <= _IMAGINARY_TOLERANCE) & (z.real > 0.0) & (z.real < 1.0)
        return np.where(keep, z.real, np.nan)
    count = len(c)
    turns = np.nan_to_num(_real_roots(_derivative(c)), nan=1.0)
    edges = np.sort(np.concatenate((np.zeros((count, 1)), turns, np.ones((count, 1))), axis=1),
                    axis=1)
    lo, hi = edges[:, :-1], edges[:, 1:]
    f_lo, f_hi = _polyval(c, lo), _polyval(c, hi)
    rows, cols = np.nonzero(f_lo * f_hi < 0.0)
    out = np.full((count, k), np.nan)
    if len(rows):
        out[rows, cols] = _bracketed(c[rows], lo[rows, cols], hi[rows, cols], f_lo[rows, cols])
    return out


def _bracketed(c: np.ndarray, a: np.ndarray, b: np.ndarray, f_a: np.ndarray) -> np.ndarray:
    """The root of each row c in [a, b], where c changes sign once (f_a = c(a)): the
    project's root finder (sizer.numerics.roots, Illinois), all rows together, to 1e-14
    of [0, 1] (a cut's error moves an integral by its square, a stationary point's a
    peak by its square too)."""
    f_b = _polyval(c, b[:, None])[:, 0]
    return illinois(lambda x: _polyval(c, x[:, None])[:, 0], a, b, f_a, f_b, xtol=1e-14)


def _roots_of_degree(c: np.ndarray) -> np.ndarray:
    """All complex roots of rows c (rows, k+1) of degree exactly k = 1 or 2: (rows, k)."""
    if c.shape[1] == 2:
        return (-c[:, :1] / c[:, 1:]).astype(complex)
    # the stable quadratic formula
    a, b, const = c[:, 2], c[:, 1], c[:, 0]
    disc = b * b - 4.0 * a * const
    root = np.sqrt(np.abs(disc))
    real_q = -0.5 * (b + np.copysign(root, b))
    with np.errstate(divide="ignore", invalid="ignore"):
        real = np.column_stack((real_q / a, const / real_q))
    pair = np.column_stack((-b / (2.0 * a), -b / (2.0 * a)))
    imag = (0.5 * root / np.abs(a))[:, None] * np.array([1.0, -1.0])
    return np.where((disc >= 0.0)[:, None], real + 0j, pair + 1j * imag)
