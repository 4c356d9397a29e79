"""Exact response of an elastic load to a law: residual vibration and tracking error (sec. 7.2).

The 1-DOF load of sec. 7.1.1, z = x - y, z'' + 2 delta omega_n z' + omega_n^2 z = -y''
(eq. 7.2). With lambda = omega_n (-delta + i sqrt(1 - delta^2)) and omega_d = Im lambda,
the state is carried by one complex mode coordinate W:

    z = -Im(W) / omega_d,  z' = -Im(lambda W) / omega_d,  W' = lambda W + y''

(the state-transition matrix exp(A t) of sec. 7.1.1 is W -> e^{lambda t} W). A move of law
q_N, duration T and displacement h from W0 ends at W = e^{lambda T} W0 + (h / T) w(1), with
w the exact convolution of sizer.vibration.convolution at s = lambda T; after it the load
vibrates freely, z(t) = A e^{-delta omega_n (t - T)} cos(omega_d (t - T) + phi) with the
residual amplitude A = |W| / omega_d. In normalized time (tau = t / T, zeta = z / h) only
f_n T and delta matter: zeta'' + 2 delta Omega zeta' + Omega^2 zeta = -q_N'', Omega = 2 pi f_n T.
No time stepping anywhere: every value is exact to rounding.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from sizer.errors import UserError
from sizer.laws.base import MotionLaw
from sizer.laws.registry import make_law
from sizer.numerics.arrays import sorted_unique
from sizer.vibration import convolution as cv
from sizer.vibration import far_field as far
from sizer.vibration.elastic_load import ElasticLoad

TRACK_STEP = 2.0 * math.pi / 16.0
"""Phase of one part of the tracking grid [rad]: 16 samples a period of the mode."""

TRACK_SAMPLES = 64
"""Fewest parts of the move in the tracking grid (slow modes)."""

RESIDUAL_STEP = 4.0
"""Largest |s| times a part's width in the residual's grid: 20 Gauss nodes integrate the
kernel over it to far below rounding (2^40 / 40! ~ 1e-36), and its series about the
part's middle converges in sizer.vibration.convolution.TAYLOR terms."""

CANDIDATES = 8
"""Highest sampled local maxima of |z| refined to the exact ones."""

NEWTON_STEPS = 6
"""Newton iterations refining the peak of |z| from the grid's best sample."""


def _check_damping(damping_ratio: float) -> float:
    """delta in [0, 1): the under-damped mode the residual formulas need."""
    return ElasticLoad(1.0, float(damping_ratio)).damping_ratio


def _check_fT(fT: np.ndarray | float) -> np.ndarray:
    values = np.asarray(fT, dtype=float)
    if values.size == 0 or not np.all(np.isfinite(values) & (values > 0.0)):
        bad = values[~(np.isfinite(values) & (values > 0.0))] if values.size else values
        shown = f"{bad.flat[0]:g}" if bad.size else "no value"
        raise UserError(f"f_n T (natural frequency times duration) must be positive and "
                        f"finite, not {shown}", field="load.natural_frequency")
    return values


def _mode(fT: np.ndarray, delta: float) -> tuple[np.ndarray, np.ndarray]:
    """s = lambda T and Omega_d = omega_d T for every f_n T."""
    omega = 2.0 * math.pi * fT
    root = math.sqrt(1.0 - delta * delta)
    return omega * complex(-delta, root), omega * root


def _law(law: MotionLaw | str) -> MotionLaw:
    return law if isinstance(law, MotionLaw) else make_law(law)


GRID_S_MAX = float(2 ** 20)
"""Largest |s| = 2 pi f_n T of the grids (their cost grows with it: 2^20 is ~0.4 GB at
most); beyond it the end series of sizer.vibration.far_field, whose cost does not grow."""

TRACK_GRID_S_MAX = float(2 ** 16)
"""Largest |s| of the tracking error's grid (16 samples a period); beyond, the end series."""


def _far_rows(law: MotionLaw, s: np.ndarray, grid_max: float) -> np.ndarray:
    """Where the end series is used: above its s_min, and above grid_max in any case
    (a UserError where the law's acceleration cannot be interpolated there)."""
    size = np.abs(s)
    series = far.end_series(law)
    if not math.isfinite(series.s_min) and np.any(size > grid_max):
        raise UserError(f"f_n T up to {float(np.max(size)) / (2.0 * math.pi):.4g} is beyond "
                        f"the {grid_max / (2.0 * math.pi):.4g} that {law.spec}'s vibration "
                        f"is sampled to (its acceleration has no polynomial interpolation "
                        f"to rounding): lower the natural frequency or the duration",
                        field="load.natural_frequency")
    return (size >= series.s_min) | (size > grid_max)


def forced_end(law: MotionLaw, s: np.ndarray) -> np.ndarray:
    """w(1) = int_0^1 q_N''(u) e^{s (1 - u)} du for every s (1-D complex), grouped by |s|:
    the grids for small |s|, the end series (cost free of |s|) for large."""
    out = np.empty(s.shape, dtype=complex)
    is_far = _far_rows(law, s, GRID_S_MAX)
    if is_far.any():
        out[is_far] = far.end_values(law, s[is_far])
    caps = cv.s_cap_of(np.abs(s))
    for cap in sorted_unique(caps[~is_far]):
        rows = np.flatnonzero((caps == cap) & ~is_far)
        grid = cv.law_grid(law, float(cap), RESIDUAL_STEP)
        size = max(1, cv.CHUNK // (grid.edges.size + grid.xi.size))
        for i in range(0, rows.size, size):
            part = rows[i:i + size]
            out[part] = cv.end_values(grid, s[part])
    return out


def residual_amplitude(law: MotionLaw | str, fT: np.ndarray | float,
                       damping_ratio: float = 0.0) -> np.ndarray:
    """Residual vibration amplitude per unit displacement after a rest-to-rest move.

    The load starts at rest; after the move (t > T) z(t) = A e^{-delta omega_n (t - T)}
    cos(omega_d (t - T) + phi), and this returns A / h for every f_n T (same shape). With
    delta = 0, A = sqrt(z^2 + (z' / omega_n)^2) at t = T = |F(i 2 pi f_n T)| / (2 pi f_n T),
    F the transform of q_N'' (sec. 7.3); in general A / h = |w(1)| / (2 pi f_n T
    sqrt(1 - delta^2)), w(1) = int_0^1 q_N''(u) e^{lambda T (1 - u)} du.
    """
    delta = _check_damping(damping_ratio)
    values = _check_fT(fT)
    s, omega_d = _mode(values.ravel(), delta)
    return (np.abs(forced_end(_law(law), s)) / omega_d).reshape(values.shape)


# ------------------------------------------------------------------ peaks during a move
def _combination(total: np.ndarray, c: np.ndarray) -> np.ndarray:
    """Re sum over modes of c * total, (rows,)."""
    return np.sum(c * total, axis=1).real


def peak_output(law: MotionLaw, s: np.ndarray, c: np.ndarray, w0: np.ndarray,
                scale: np.ndarray, samples: int = TRACK_SAMPLES) -> np.ndarray:
    """max over tau in [0, 1] of |Re sum_j c_j m_j(tau)|, m_j = e^{s_j tau} w0_j + scale_j
    w(tau; s_j), for rows of modes (arrays (rows, modes)); the output is C^1 in tau
    (its c . B term is zero). Exact on a grid (16 samples a period, at least ``samples``
    over the move), its CANDIDATES highest local maxima refined by Newton on the
    output's derivative."""
    rows, modes = s.shape
    flat = s.ravel()
    cap = float(cv.s_cap_of(np.array([np.max(np.abs(flat), initial=0.0)]))[0])
    grid = cv.law_grid(law, cap, TRACK_STEP, samples)
    at_edges = cv.edge_values(grid, flat)  # (rows * modes, K + 1)
    total = (np.exp(np.multiply.outer(flat, grid.edges)) * w0.ravel()[:, None]
             + scale.ravel()[:, None] * at_edges).reshape(rows, modes, -1)
    out = np.abs(np.einsum("rm,rmk->rk", c, total).real)  # (rows, K + 1)
    # the CANDIDATES highest local maxima of the samples are refined: two humps of
    # nearly equal height may swap places between the samples and the exact values
    padded = np.pad(out, ((0, 0), (1, 1)), constant_values=-1.0)
    humps = np.where((out >= padded[:, :-2]) & (out >= padded[:, 2:]), out, -1.0)
    count = min(CANDIDATES, out.shape[1])
    k = np.argpartition(-humps, count - 1, axis=1)[:, :count].ravel()
    row = np.repeat(np.arange(rows), count)
    best = out[row, k]
    low = grid.edges[np.maximum(k - 1, 0)]
    high = grid.edges[np.minimum(k + 1, grid.edges.size - 1)]
    tau = grid.edges[k].copy()
    inside = np.ones(tau.size, dtype=bool)
    pick = (row[:, None] * modes + np.arange(modes)).ravel()  # flattened (row, mode)
    s_c, c_c, w0_c, scale_c = (a[row] for a in (s, c, w0, scale))
    flat_c, w0_f, scale_f = s_c.ravel(), w0_c.ravel(), scale_c.ravel()

    def modes_at(tau: np.ndarray) -> np.ndarray:
        return _modes_at(grid, flat_c, at_edges, np.repeat(tau, modes), w0_f, scale_f,
                         pick).reshape(tau.size, modes)

    for _ in range(NEWTON_STEPS):
        m = modes_at(tau)
        acc = grid.law.derivative(tau, 2)[:, None]
        d1 = _combination(s_c * m + scale_c * acc, c_c)
        d2 = _combination(s_c * s_c * m + s_c * scale_c * acc, c_c)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = np.where(d2 != 0.0, d1 / d2, 0.0)
        tau = tau - np.where(inside, step, 0.0)
        inside &= (tau >= low) & (tau <= high)
        tau = np.clip(tau, low, high)
    refined = np.abs(_combination(modes_at(tau), c_c))
    return np.maximum(best, refined).reshape(rows, count).max(axis=1)


def _modes_at(grid: cv.Grid, s: np.ndarray, at_edges: np.ndarray, tau: np.ndarray,
              w0: np.ndarray, scale: np.ndarray, row: np.ndarray) -> np.ndarray:
    """e^{s tau} w0 + scale w(tau; s), per flattened (candidate, mode)."""
    return np.exp(s * tau) * w0 + scale * cv.values_at(grid, s, at_edges, tau, row)


def tracking_error(law: MotionLaw | str, fT: np.ndarray | float, damping_ratio: float = 0.0,
                   samples: int = TRACK_SAMPLES) -> np.ndarray:
    """Peak tracking error max |z(t)| / h over the move 0 <= t <= T from rest (sec. 7.2).

    z is exact on a grid of 16 samples a damped period (at least ``samples`` over the
    move), and the best sample is refined to the exact local maximum (Newton on z' = 0);
    the value returned is |z| at a point of the move, never below the grid's best. It
    scales as 1 / (f_n T)^2 for large f_n T: the quasi-static C_a / (2 pi f_n T)^2
    (z ~ -y'' / omega_n^2) for a continuous acceleration, plus the free vibration each
    jump of q_N'' starts (the trapezoid's first step doubles it).
    Values sharing a grid (f_n T within a factor 2) are computed together.
    """
    delta = _check_damping(damping_ratio)
    values = _check_fT(fT)
    if int(samples) < 2:
        raise UserError(f"samples must be at least 2, not {samples}", field="samples")
    the_law = _law(law)
    s, omega_d = _mode(values.ravel(), delta)
    out = np.empty(s.shape)
    is_far = _far_rows(the_law, s, TRACK_GRID_S_MAX)
    far_rows, block = np.flatnonzero(is_far), cv.CHUNK // far.SAMPLES
    for i in range(0, far_rows.size, block):
        part = far_rows[i:i + block]
        out[part] = far.peak_error(the_law, s[part]) / omega_d[part]
    caps = cv.s_cap_of(np.abs(s))
    for cap in sorted_unique(caps[~is_far]):
        rows = np.flatnonzero((caps == cap) & ~is_far)
        grid = cv.law_grid(the_law, float(cap), TRACK_STEP, int(samples))
        size = max(1, cv.CHUNK // (grid.edges.size + CANDIDATES * grid.xi.size) // 2)
        for i in range(0, rows.size, size):
            part = rows[i:i + size]
            n = part.size
            peak = peak_output(the_law, s[part, None], np.full((n, 1), 1j),
                               np.zeros((n, 1), complex), np.ones((n, 1)), int(samples))
            out[part] = peak / omega_d[part]
    return out.reshape(values.shape)


# ------------------------------------------------------------------ one move, any times
def _coordinate(z: float, z_dot: float, lam: complex, omega_d: float) -> complex:
    """The mode coordinate W of a state (z, z'): -Im W = omega_d z, -Im(lambda W) = omega_d z'."""
    return complex(-(z_dot - lam.real * z), -omega_d * z)


def checked_move(duration: float, displacement: float) -> tuple[float, float]:
    """(T, h) as floats; UserError unless T > 0 and h are finite."""
    T, h = float(duration), float(displacement)
    if not (math.isfinite(T) and T > 0.0):
        raise UserError(f"duration must be positive, not {T:g} s", field="duration")
    if not math.isfinite(h):
        raise UserError(f"displacement must be finite, not {h:g}", field="displacement")
    return T, h


def modal_move(law: MotionLaw | str, duration: float, displacement: float,
               model: ModalModel, times: np.ndarray,
               initial: Sequence[float] | None = None) -> np.ndarray:
    """The load's state at the given times [s] of a move starting at t = 0, shape
    times.shape + (states,): exact during the move, free vibration after it; times
    before 0 read the state ``initial`` the move starts from (rest by default)."""
    T, h = checked_move(duration, displacement)
    the_law = _law(law)
    size = model.vectors.shape[0]
    W0 = model.coordinates(np.zeros(size) if initial is None else initial)
    t = np.asarray(times, dtype=float).ravel()
    tau = np.clip(t / T, 0.0, 1.0)
    s = model.lam * T
    grid = cv.law_grid(the_law, float(cv.s_cap_of(np.array([np.max(np.abs(s))]))[0]),
                       TRACK_STEP, TRACK_SAMPLES)
    at_edges = cv.edge_values(grid, s)  # (modes, K + 1)
    count = s.size
    row = np.tile(np.arange(count), tau.size)
    forced = cv.values_at(grid, np.tile(s, tau.size), at_edges, np.repeat(tau, count),
                          row).reshape(tau.size, count)
    W = np.exp(np.multiply.outer(tau, s)) * W0 + (h / T) * model.beta * forced
    after = t > T
    W[after] *= np.exp(np.multiply.outer(t[after] - T, model.lam))
    x = (W @ model.vectors.T).real
    x[t < 0.0] = 0.0 if initial is None else np.asarray(initial, dtype=float)
    return x.reshape((*np.shape(times), size))


def move_response(law: MotionLaw | str, duration: float, displacement: float,
                  load: ElasticLoad, times: np.ndarray,
                  initial: tuple[float, float] = (0.0, 0.0)
                  ) -> tuple[np.ndarray, np.ndarray]:
    """z(t) = x - y and z'(t) at the given times [s] of a move starting at t = 0 (eq. 7.2).

    The load is in state ``initial`` (z, z') when the move starts (rest by default; times
    before 0 read that state); during the move the exact forced response, after it the
    exact free vibration (x = y + z, y = h q_N(t / T)).
    """
    x = modal_move(law, duration, displacement, ModalModel.of(load), times, initial)
    return x[..., 0], x[..., 1]


# ------------------------------------------------------------------ cycles of moves
@dataclass(frozen=True)
class Segment:
    """One move of a cycle: law, start time [s], duration [s], displacement (signed)."""

    law: MotionLaw | str
    start: float
    duration: float
    displacement: float


@dataclass(frozen=True)
class MoveVibration:
    """The load during and after one move of a cycle (units of the displacement).

    ``residual``: amplitude A of the free vibration at the move's end (A = |W| / omega_d,
    the envelope of z after it; for a chain the sum of its modes' envelopes);
    ``peak_error``: max |z| during the move; ``start_state`` and ``end_state``: (z, z')
    at its start and end ([z_1 .. z_n, z_1' .. z_n'] for a chain)."""

    residual: float
    peak_error: float
    start_state: tuple[float, ...]
    end_state: tuple[float, ...]


@dataclass(frozen=True)
class CycleResponse:
    """Per move of the cycle, in order; ``periodic`` when it is the steady periodic state."""

    moves: tuple[MoveVibration, ...]
    periodic: bool


def _check_segments(segments: Sequence[Segment], period: float | None) -> None:
    if not segments:
        raise UserError("a cycle needs at least one move", field="segments")
    end = -math.inf
    for i, seg in enumerate(segments):
        field = f"segments[{i}]"
        if not (math.isfinite(seg.start) and math.isfinite(seg.displacement)):
            raise UserError("start and displacement must be finite", field=field)
        if not (math.isfinite(seg.duration) and seg.duration > 0.0):
            raise UserError(f"duration must be positive, not {seg.duration:g} s",
                            field=f"{field}.duration")
        if seg.start < end - 1e-12 * max(1.0, abs(end)):
            raise UserError(f"move starts at {seg.start:g} s, before the previous one ends "
                            f"({end:g} s)", field=f"{field}.start")
        end = seg.start + seg.duration
    if period is not None:
        span = end - segments[0].start
        if not (math.isfinite(period) and period >= span * (1.0 - 1e-12)):
            raise UserError(f"period {period:g} s is shorter than the moves "
                            f"({span:g} s from the first start to the last end)",
                            field="period")


@dataclass(frozen=True)
class ModalModel:
    """A linear load by its modes: coordinates W_j' = lam_j W_j + beta_j y''; output
    (the error of the load's last mass) Re sum_j c_j W_j; state = Re(vectors @ W)."""

    lam: np.ndarray
    beta: np.ndarray
    c: np.ndarray
    vectors: np.ndarray

    @classmethod
    def of(cls, load: ElasticLoad | ModalLoad) -> ModalModel:
        """The 1-DOF load (z = -Im W / omega_d, z' = -Im(lambda W) / omega_d) or a chain."""
        if isinstance(load, ElasticLoad):
            lam = load.omega_n * complex(-load.damping_ratio,
                                         math.sqrt(1.0 - load.damping_ratio**2))
            vectors = np.array([[1j], [1j * lam]]) / load.omega_d
            return cls(np.array([lam]), np.ones(1, dtype=complex),
                       np.array([1j / load.omega_d]), vectors)
        return load.modes

    def coordinates(self, state: Sequence[float] | np.ndarray) -> np.ndarray:
        """W of a real state (for the 1-DOF load, (z, z'))."""
        x = np.asarray(state, dtype=float)
        if x.shape != (self.vectors.shape[0],) or not np.all(np.isfinite(x)):
            raise UserError(f"initial state must be {self.vectors.shape[0]} finite numbers",
                            field="initial")
        if self.lam.size == 1:
            return np.array([_coordinate(x[0], x[1], complex(self.lam[0]),
                                         float(self.lam[0].imag))])
        return np.linalg.solve(self.vectors, x.astype(complex))

    def state(self, W: np.ndarray) -> tuple[float, ...]:
        return tuple(float(v) for v in (self.vectors @ W).real)


class ModalLoad(Protocol):
    """A load known by its modes (the chain of sec. 7.1.2: sizer.vibration.chain_load)."""

    @property
    def modes(self) -> ModalModel: ...


def cycle_response(segments: Sequence[Segment], load: ElasticLoad | ModalLoad,
                   period: float | None = None,
                   initial: Sequence[float] | None = None) -> CycleResponse:
    """The load through a cycle of moves with dwells between them, the state carried
    exactly from one to the next (the state-transition e^{lambda t} of each mode).

    ``load``: the 1-DOF ElasticLoad (states (z, z')) or a ChainLoad of sec. 7.1.2 (states
    [z_1 .. z_n, z_1' .. z_n'], residual and peak of the last mass's error x_n - y; its
    residual is the sum of the modes' envelopes, sizer.vibration.chain_load). Without
    ``period`` the load starts from ``initial`` (rest by default) at the first move. With
    it the cycle repeats every ``period`` seconds and the steady periodic state is
    returned: W = e^{lambda P} W + r solved for the state at the first start (a
    UserError for an undamped mode with f_n P an integer: no periodic state exists).
    """
    _check_segments(segments, period)
    model = ModalModel.of(load)
    lam, c = model.lam, model.c
    prepared = [(_law(seg.law), seg) for seg in segments]

    def run(W: np.ndarray, keep: bool) -> tuple[np.ndarray, list[MoveVibration]]:
        t = segments[0].start
        out: list[MoveVibration] = []
        for law, seg in prepared:
            W = W * np.exp(lam * (seg.start - t))
            T, h = seg.duration, seg.displacement
            s = lam * T
            scale = model.beta * (h / T)
            end = np.exp(s) * W + scale * forced_end(law, s)
            if keep:
                peak = float(peak_output(law, s[None, :], c[None, :], W[None, :],
                                         scale[None, :])[0])
                out.append(MoveVibration(float(np.sum(np.abs(c * end))), peak,
                                         model.state(W), model.state(end)))
            W = end
            t = seg.start + T
        return W, out

    size = model.vectors.shape[0]
    W0 = model.coordinates(np.zeros(size) if initial is None else initial)
    if period is not None:
        span_end = segments[0].start + period
        last = segments[-1].start + segments[-1].duration
        r, _ = run(np.zeros(lam.size, dtype=complex), keep=False)
        r = r * np.exp(lam * (span_end - last))
        phi = np.exp(lam * period)
        if np.any(np.abs(1.0 - phi) < 1e-9):
            f = float(np.abs(lam[np.argmin(np.abs(1.0 - phi))])) / (2.0 * math.pi)
            raise UserError(f"an undamped mode with f_n x period = {f * period:g} (an "
                            f"integer) has no steady periodic state: it resonates with the "
                            f"cycle", field="period")
        W0 = r / (1.0 - phi)
    _, moves = run(W0, keep=True)
    return CycleResponse(tuple(moves), period is not None)
