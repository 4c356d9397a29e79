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

The law's grid (:func:`law_grid`): its fixed sampling and quadrature grid on [0, 1],
computed once per law. A move with boundary speeds (:func:`polynomial_move`): the exact
requirements of a piecewise-polynomial move per candidate (issue 12). The move's peak
bound (:func:`peak_duration`): the largest duration below which a peak or speed check
fails, a lower bound on T_min found without a search (eq. 6.2 in the rectangular case).

Law grid: A law's fixed sampling and quadrature grid on [0, 1], computed once per law.

The intervals and nodes are the law's one integration scheme (sizer.laws.quadrature) at
the engine's resolution (ENGINE_RESOLUTION); each interval carries Gauss-Legendre nodes
and weights and the one-sided values of the normalized velocity and acceleration at its
ends. Polynomial pieces (trapezoid, double S, polynomial laws) are integrated exactly
with few nodes (their degree plus one), the other pieces to machine
precision; all intervals of a law carry the same count (the largest its pieces need:
arrays are rectangular).

Moves with boundary speeds (issue 12). The exact requirements of a piecewise-polynomial
move, per candidate (book sec. 6.1.1).

A move with boundary speeds has a shape that depends on its duration, so each candidate
carries its own piecewise polynomial: ``breaks`` (n, P+1) and ``coefficients``
(n, P, d+1), the load's position relative to the move's start in ascending powers of
t - breaks[:, p]. The physics is the engine's (:class:`CycleCalculator`):

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
  intervals and each sign change is found by Newton steps kept in its bracket
  (:func:`_bracketed`), all rows at once);
- the peak ratio |tau| / tau_int(|omega|) (the speed clipped into the region, as in the
  engine) at the ends, at the torque's stationary points, where |omega| crosses a corner of
  the region and at the stationary points of tau / (c0 + c1 |omega|) on each of its
  segments (the roots of tau' L - tau L'); every point is evaluated with the true region.

Arrays are (candidates, sub-pieces); loops run over degrees, stages and region segments
only.

Peak bound: A lower bound on T_min from the checks that only grow stricter as the move gets faster.

The speed check, the load's speed, acceleration and jerk limits and the peak torque
checks (motor against its intermittent region, stage outputs against their peak ratings)
each hold for every duration from a threshold on (book sec. 6.1.1, eq. 6.2 in the
rectangular case). Their largest threshold is a lower bound on T_min: where the cycle is
feasible there, it is T_min, found without a search (sizer.sizing.shortest_duration).

The peak check in u = 1/T. Every torque is a maximum of linear functions of the load's
(a, v) (sizer.mechanics.drive.Drive.linear_pieces), a = h u^2 a_N, v = h u v_N, so one of
its functions under one line of the region, alpha + sigma * omega with omega = K v, reads

    F(u) = max over tau of (P a_N u^2 + Q v_N u)  <=  D,
    P = A h,  Q = (B - c sigma K) h,  D = c alpha - C,

with c = 1 - torque margin. For a rest-to-rest law (v_N >= 0) F(u) = u g(u) with g a
maximum of linear functions of u, nondecreasing from u = 0: F is convex and increasing,
so the condition holds on [0, u*]. From a point x where F(x) > D each step takes the
quadratic of the maximizer there, q(u) = P a_N u^2 + Q v_N u at its tau (the law's exact
linear peak, sizer.laws.linear_peaks): q <= F everywhere and q(x) = F(x), so the
positive root of q = D lies in [u*, x); the iterates fall monotonically to u*, as
Newton's method would, but faster, the step's quadratic being exact for a fixed tau
(F - q is of second order in u - x, with the maximizer's drift as its only cause;
Newton's step where rounding leaves q no root). Stopped anywhere, the iterate is
>= u*, so 1/u is a valid bound. The condition is necessary where the line lies on or
above the region at every speed the move may reach: true of every segment's line of a
concave region (a flat part, then falling segments that fall faster and faster), and of
the flat line at the region's largest torque for any region. Only the motoring side
(torque >= 0) is bounded: -tau is a minimum of the functions, for which a single
function gives no necessary condition.
"""

from __future__ import annotations

import copy
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import cached_property, lru_cache

import numpy as np

from sizer.errors import UserError
from sizer.laws import MotionLaw
from sizer.laws.linear_peaks import LinearPeak, piece_values
from sizer.laws.piece_forms import PieceForms
from sizer.laws.quadrature import PieceIntervals, Resolution, gauss_legendre, law_intervals
from sizer.laws.row_laws import RowLaws
from sizer.mechanics import Drive
from sizer.model.cycle import Dwell, from_task
from sizer.model.domain import Limits, Task, ThermalSpeedRule
from sizer.numerics.arrays import sorted_unique, spread
from sizer.numerics.golden import golden_step, interior_points
from sizer.numerics.hermite import hermite_root
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.evaluation import (
    SAMPLES,
    CycleMetrics,
    CyclePiece,
    held_piece,
    rms_of_powers,
    thermal_speed_of,
)

POLYNOMIAL_INTERVALS = 16
"""Uniform intervals per polynomial piece. One would be exact for the integrals, but the
engine needs more (sizer.sizing.move): it finds the power-flow reversals of a stage
inside a move from the signs of the output torque at interval ends (a reversal and its
return within one interval go unseen: with one interval per piece the RMS torque of
3-4-5 and 4-5-6-7 laws through a reversing stage was 5e-4 low against
tests/scalar_reference.py), and it samples the load's torque at the nodes without
refinement (then 4.5e-3 below its peak on a 3-4-5 law, tests/test_exact_peaks.py
allows 1e-3)."""

SMOOTH_INTERVALS = 16
"""Uniform base intervals per non-polynomial piece (before grading and halving), for
the same reasons."""

ENGINE_RESOLUTION = Resolution(POLYNOMIAL_INTERVALS, SMOOTH_INTERVALS)
"""Node counts as the laws' own rule: d + 1 on a polynomial piece of degree d, exact for
q_N^2 and up (d would do for the torques' squares, but the load's torque sampled at the
nodes of a 3-4-5 law then misses its peak by 1.3e-3, 6.8e-4 with d + 1)."""


@dataclass(frozen=True)
class LawGrid:
    """Base intervals of a law with nodes, weights and normalized v, a (arrays are (G, n));
    v, a and j at both ends of each interval, one-sided on its piece ((G, 2))."""

    law: MotionLaw
    left: np.ndarray
    right: np.ndarray
    piece: np.ndarray
    nodes: np.ndarray
    weights: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    end_velocity: np.ndarray
    end_acceleration: np.ndarray
    end_jerk: np.ndarray

    @property
    def size(self) -> int:
        return len(self.left)


class GridRows:
    """The law grid each candidate row reads: one law's for every row, or (several laws
    as the rows of one model: sizer.laws.row_laws.RowLaws) row i the grid of
    ``laws[which[i]]``, the laws' arrays padded to the longest grid (a padded interval
    repeats the last one's right end and is marked invalid). Interval indices are each
    row's own grid's; pieces, for the laws' pieces as data, are numbered across the laws
    (sizer.laws.piece_forms.PieceForms.stacked)."""

    def __init__(self, laws: Sequence[MotionLaw], several: bool = False) -> None:
        self.laws = tuple(laws)
        self.which: np.ndarray | None = None  # per row its law (:meth:`for_rows`)
        grids = [law_grid(law) for law in self.laws]
        tables = [moment_table(law) for law in self.laws]
        if not several:  # one law: its own arrays, shared by every row
            (g,), (table,) = grids, tables
            self.size = np.full(1, float(g.size))
            self.table, self.piece, self.left, self.right = table, g.piece, g.left, g.right
            self.end_velocity, self.end_acceleration = g.end_velocity, g.end_acceleration
            self.end_jerk = g.end_jerk
            self.forms: PieceForms | None = self.laws[0].piece_forms()
            self.node_count = np.full(1, g.nodes.shape[1])
            return
        sizes = np.array([g.size for g in grids])
        width = int(sizes.max())
        forms = [law.piece_forms() for law in self.laws]
        if any(f is None for f in forms):  # their pieces are numbered across the laws
            raise ValueError("several laws' grids need every law's pieces as data")
        self.forms = PieceForms.stacked(
            [f for f in forms if f is not None])
        first = np.concatenate(([0], np.cumsum([len(law.pieces) for law in self.laws])))

        def padded(arrays: Sequence[np.ndarray], length: int) -> np.ndarray:
            out = np.empty((len(arrays), length, *arrays[0].shape[1:]), arrays[0].dtype)
            for k, x in enumerate(arrays):
                out[k, :len(x)] = x
                out[k, len(x):] = x[-1]
            return out

        def ends(arrays: Sequence[np.ndarray]) -> np.ndarray:
            out = padded(arrays, width)
            for k, x in enumerate(arrays):
                out[k, len(x):] = x[-1, 1]  # a padded interval: the last right end
            return out

        self.size = sizes.astype(float)
        self.table = padded(tables, width + 1)
        self.piece = padded([g.piece + first[k] for k, g in enumerate(grids)], width)
        self.left, self.right = (padded([getattr(g, name) for g in grids], width)
                                 for name in ("left", "right"))
        self.end_velocity, self.end_acceleration, self.end_jerk = (
            ends([getattr(g, name) for g in grids])
            for name in ("end_velocity", "end_acceleration", "end_jerk"))
        self.node_count = np.array([g.nodes.shape[1] for g in grids])
        self.valid = np.arange(width)[None, :] < sizes[:, None]

    def for_rows(self, which: np.ndarray) -> GridRows:
        """These laws' grids read by rows each of its own law, ``laws[which[i]]``."""
        view = copy.copy(self)
        view.which = which
        return view

    def law_of(self, cand: np.ndarray) -> np.ndarray | int:
        """The law (index into the padded arrays) of each row at ``cand``; 0 for one law."""
        return 0 if self.which is None else self.which[cand]

    def at(self, array: np.ndarray, cand: np.ndarray, interval: np.ndarray) -> np.ndarray:
        """``array``'s entries of each (row, interval) pair."""
        return array[interval] if self.which is None else array[self.which[cand], interval]


@lru_cache(maxsize=256)
def engine_intervals(law: MotionLaw) -> tuple[PieceIntervals, ...]:
    """The intervals and node counts of the law's grid (cached: laws hash by their
    canonical spec; read by :func:`law_grid` and :func:`grid_samples`)."""
    return tuple(law_intervals(law, ENGINE_RESOLUTION))


def grid_samples(law: MotionLaw) -> int:
    """The samples of one candidate on the law's grid, its nodes and both ends of each
    interval (``grid.nodes.size + 2 * grid.size`` of :func:`law_grid`), from its intervals
    alone: the memory of an evaluation is known without computing the law's values there
    (a law move through an ideal drive never reads them unless its exact peaks fail)."""
    parts = engine_intervals(law)
    count = max(part.nodes for part in parts)
    return sum(len(part.edges) - 1 for part in parts) * (count + 2)


CHUNK_SAMPLES = 2**21
"""Candidates x law samples evaluated at once (each array of that size is 16 MiB): larger
candidate sets are evaluated in chunks, so memory stays bounded whatever the catalog."""
MIN_CHUNK = 64
"""The smallest chunk (the per-evaluation overhead stays small against the work) while
its samples stay within MAX_CHUNK_SAMPLES."""
MAX_CHUNK_SAMPLES = 8 * CHUNK_SAMPLES
"""Candidates x samples never exceeded by a chunk: a cycle of many moves (each candidate
already holds millions of samples) is evaluated a few candidates, or one, at a time."""


def candidates_per_chunk(samples: int) -> int:
    """How many candidates of ``samples`` samples each one evaluation takes: CHUNK_SAMPLES
    worth, at least MIN_CHUNK, at most MAX_CHUNK_SAMPLES worth, at least one."""
    samples = max(samples, 1)
    return max(1, min(max(MIN_CHUNK, CHUNK_SAMPLES // samples), MAX_CHUNK_SAMPLES // samples))


def acceleration_range(law: MotionLaw | RowLaws):
    """(least a_N, largest a_N) of the law (each row's: RowLaws, arrays over the rows)
    where its acceleration is linear on every piece (MotionLaw.linear_acceleration),
    else None."""
    if isinstance(law, RowLaws):
        return law.acceleration_range
    linear = law.linear_acceleration
    return None if linear is None else (linear.lowest, linear.highest)


@lru_cache(maxsize=256)
def law_grid(law: MotionLaw) -> LawGrid:
    """The grid of a law (cached: laws hash by their canonical spec)."""
    parts = engine_intervals(law)
    count = max(part.nodes for part in parts)
    rules = [part.gauss(count) for part in parts]
    left = np.concatenate([part.edges[:-1] for part in parts])
    right = np.concatenate([part.edges[1:] for part in parts])
    piece = np.concatenate([np.full(len(part.edges) - 1, part.index) for part in parts])
    nodes = np.concatenate([tau for tau, _ in rules])
    weights = np.concatenate([weight for _, weight in rules])
    # nodes are evaluated on their interval's piece: in an interval a few ulps wide a node
    # may round onto the next piece's start, where law.derivative would switch pieces
    taus = [tau for tau, _ in rules]
    forms = law.piece_forms()
    on_pieces = ([_edge_and_node_values(law, part, tau)
                  for part, tau in zip(parts, taus, strict=True)] if forms is None
                 else _edge_and_node_values_at_once(forms, parts, taus))
    end_v, end_a, end_j, velocity, acceleration = (
        np.concatenate(columns) for columns in zip(*on_pieces, strict=True))
    return LawGrid(law, left, right, piece, nodes, weights, velocity, acceleration,
                   end_v, end_a, end_j)


def _edge_and_node_values(law: MotionLaw, part: PieceIntervals, tau: np.ndarray
                          ) -> tuple[np.ndarray, ...]:
    """v_N, a_N and j_N of one piece (one-sided at its ends) at its intervals' ends,
    (intervals, 2) arrays, and v_N, a_N at their nodes ``tau``, (intervals, nodes)."""
    edges = len(part.edges)
    at = np.concatenate((part.edges, tau.ravel()))
    v, a = (law.piece_derivative(part.index, at, order) for order in (1, 2))
    j = law.piece_derivative(part.index, part.edges, 3)
    return (np.stack((v[:edges - 1], v[1:edges]), axis=1),
            np.stack((a[:edges - 1], a[1:edges]), axis=1),
            np.stack((j[:-1], j[1:]), axis=1),
            v[edges:].reshape(tau.shape), a[edges:].reshape(tau.shape))


def _edge_and_node_values_at_once(forms: PieceForms, parts: Sequence[PieceIntervals],
                                  taus: Sequence[np.ndarray]) -> list[tuple[np.ndarray, ...]]:
    """:func:`_edge_and_node_values` of every part, each piece's points evaluated in one
    pass of the law's pieces as data (the same values)."""
    at = [np.concatenate((part.edges, tau.ravel())) for part, tau in zip(parts, taus,
                                                                         strict=True)]
    sizes = [len(x) for x in at]
    edge_sizes = [len(part.edges) for part in parts]
    v, a = forms.values(np.repeat([part.index for part in parts], sizes), np.concatenate(at),
                        (1, 2))
    (j,) = forms.values(np.repeat([part.index for part in parts], edge_sizes),
                        np.concatenate([part.edges for part in parts]), (3,))
    out: list[tuple[np.ndarray, ...]] = []
    start = edge_start = 0
    for size, edges, tau in zip(sizes, edge_sizes, taus, strict=True):
        vp, ap = v[start:start + size], a[start:start + size]
        jp = j[edge_start:edge_start + edges]
        start, edge_start = start + size, edge_start + edges
        out.append((np.stack((vp[:edges - 1], vp[1:edges]), axis=1),
                    np.stack((ap[:edges - 1], ap[1:edges]), axis=1),
                    np.stack((jp[:-1], jp[1:]), axis=1),
                    vp[edges:].reshape(tau.shape), ap[edges:].reshape(tau.shape)))
    return out


class PieceEvaluator:
    """Evaluates a law at points each bound to its own piece (one-sided at piece ends).

    The grouping of points by piece is computed once, for repeated evaluations at moving
    points that stay in their pieces (root and peak searches). Each point is clamped into
    its piece's interval: a search point a rounding error outside reads the end's
    one-sided value, never the piece's extrapolation (with a steep double S that overshoot
    exceeded C_a and put a check's slack below zero).
    """

    def __init__(self, law: MotionLaw, piece: np.ndarray) -> None:
        self.law = law
        self.shape = piece.shape
        flat = piece.ravel()
        self.groups = [(int(i), np.nonzero(flat == i)[0]) for i in sorted_unique(flat)]
        self._piece = flat.astype(np.intp, copy=False)  # for the law's pieces as data

    def __call__(self, tau: np.ndarray, order: int) -> np.ndarray:
        return self.orders(tau, (order,))[0]

    def orders(self, tau: np.ndarray, orders: tuple[int, ...]) -> tuple[np.ndarray, ...]:
        """The derivatives of the given orders at tau, each point clamped into its piece
        once for all of them (MotionLaw.piece_derivative of each)."""
        flat = tau.ravel()
        if len(self.groups) == 1:  # every point on one piece: no gathering
            piece = self.law.pieces[self.groups[0][0]]
            at = piece.clamp(flat)
            out = [np.empty(flat.shape) for _ in orders]
            for values, k in zip(out, orders, strict=True):
                values[:] = piece.evaluate(at, k)
            return tuple(values.reshape(self.shape) for values in out)
        forms = self.law.piece_forms()
        if forms is not None:  # every piece at once, the same values
            return tuple(values.reshape(self.shape)
                         for values in forms.values(self._piece, flat, orders))
        out = [np.empty(flat.shape) for _ in orders]
        for index, where in self.groups:
            piece = self.law.pieces[index]
            at = piece.clamp(flat[where])
            for values, k in zip(out, orders, strict=True):
                values[where] = piece.evaluate(at, k)
        return tuple(values.reshape(self.shape) for values in out)


def piecewise(law: MotionLaw, tau: np.ndarray, piece: np.ndarray, order: int) -> np.ndarray:
    """Derivative of the given order at tau, each point evaluated on its own piece index."""
    return PieceEvaluator(law, piece)(tau, order)


_DEGREE_TOLERANCE = 1e-12
"""Coefficients below this share of a row's largest (on the unit interval) are zero."""
_IMAGINARY_TOLERANCE = 1e-7
"""Complex roots of a quadratic this close to the real axis (the unit interval's scale)
are kept as roots: a spurious cut costs nothing, a missed pair of close crossings would."""
_NEWTON_STEPS = 3
"""Newton steps polishing the closed-form roots of degree 1 and 2 (each taken only where
it lowers |c(u)|)."""
_BRACKET_STEPS = 60
_BRACKET_TOLERANCE = 1e-14
"""The bracketed roots' steps at most and their end (:func:`_bracketed`)."""
_RATIO_MARGIN = 1e-9
"""The share by which a sub-piece's bound of the peak ratio (:func:`_peak_ratio`) is
widened (its speeds' range too) against the rounding of the points it is read at."""
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
        f = drive.figures
        self.load = both([(f.inertia, f.damping, f.friction + f.torque)],
                         [(f.inertia, f.damping, f.friction - f.torque)])
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
        roots = _unit_roots(poly, self.hi > self.lo)
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

    along = kin.sigma[..., None] * kin.V  # |v| on each sub-piece
    motor_points, *stage_points, load_points, speed_points, a_points, j_points = \
        _critical_points([motor, *stages, load, along, kin.A, kin.J], valid)
    top = _most(np.abs(_polyval(motor, motor_points)))  # max |tau| per sub-piece
    peak_torque = _most(np.where(valid, top, 0.0))
    stage_peak = [_peak(x, p, valid) for x, p in zip(stages, stage_points, strict=True)]
    load_torque = _peak(load, load_points, valid)
    speed_values = _polyval(along, speed_points)
    fastest = np.where(valid, _most(speed_values), -np.inf)
    slowest = np.where(valid, _most(speed_values, np.minimum), np.inf)
    load_speed = _most(np.where(valid, np.abs(fastest), 0.0))
    load_acceleration = _peak(kin.A, a_points, valid)
    load_jerk = _peak(kin.J, j_points, valid)
    load_jerk = np.where(_acceleration_jumps(breaks, coefficients), np.inf, load_jerk)
    peak_ratio = _peak_ratio(motor, motor_points, top, kin, K, motors.intermittent,
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


def _critical_points(polys: list[np.ndarray], valid: np.ndarray) -> list[np.ndarray]:
    """For each of the polynomials (n, M, .) the unit variable's ends and the roots of its
    derivative inside (NaN ones and those of the shorter polynomials' padding at 0), all
    solved at once on the ``valid`` sub-pieces only (0 on the others)."""
    width = max(p.shape[-1] for p in polys)
    stack = _derivative(np.stack([_pad(p, width) for p in polys]))
    roots = np.nan_to_num(_unit_roots(stack, np.broadcast_to(valid, stack.shape[:-1])), nan=0.0)
    ends = np.broadcast_to(np.array([0.0, 1.0]), (*stack.shape[:-1], 2))
    return list(np.concatenate((ends, roots), axis=-1))


def _peak(poly: np.ndarray, points: np.ndarray, valid: np.ndarray) -> np.ndarray:
    """max |poly| over the valid sub-pieces, from its values at ``points``."""
    return _most(np.where(valid, _most(np.abs(_polyval(poly, points))), 0.0))


def _peak_ratio(motor: np.ndarray, points: np.ndarray, top: np.ndarray, kin: _Kinematics,
                K: np.ndarray, region, slowest: np.ndarray, fastest: np.ndarray) -> np.ndarray:
    """max |tau| / tau_int(|omega|) over the move (the speed clipped into the region).

    On the speeds of one segment of the region the limit is a line L = c0 + c1 |omega|, so
    the maximum is at a sub-piece's end, where |omega| crosses a corner, at a stationary
    point of tau (a flat limit) or at a root of tau' L - tau L'. ``slowest`` and
    ``fastest`` bound |omega| on each sub-piece: only the corners and segments they reach
    are solved for, and only on the sub-pieces where ``top`` (max |tau| there) over the
    smallest limit at those speeds may exceed the ratio found so far (elsewhere no point
    can: the maximum is the same).
    """
    n = len(K)
    valid = kin.valid
    omega = (kin.sigma * K[:, None])[..., None] * kin.V  # |omega| on each sub-piece
    ratio = np.zeros(n)

    def raised(rows, cols, u):  # the ratio with the points u of the sub-pieces (rows, cols)
        if not len(rows):
            return ratio
        torque = np.abs(_polyval(motor[rows, cols], u))
        limit = region.take(rows).limit_clipped(_polyval(omega[rows, cols], u))
        out = ratio.copy()
        np.maximum.at(out, rows, _most(_safe_ratio(torque, limit)))
        return out

    def solved(found):  # the ratio with the roots of the polynomials (rows, cols, poly)
        if not found:
            return ratio
        rows, cols, polys = (np.concatenate(x) for x in zip(*found, strict=True))
        return raised(rows, cols, np.nan_to_num(_unit_roots(polys), nan=0.0))

    rows, cols = np.nonzero(valid)
    ratio = raised(rows, cols, points[rows, cols])
    speeds, torques, limit_top = region.speeds, region.torques, region.max_speed
    derivative = _pad(_derivative(motor), motor.shape[-1])
    widened = top * (1.0 + _RATIO_MARGIN)  # against the rounding of the points read

    def may_exceed(limit):  # where max |tau| over ``limit`` may exceed the ratio found
        return _safe_ratio(widened, limit) >= ratio[:, None]

    found = []  # the corners at once: |omega| = s_j, the limit t_j there
    for j in range(1, speeds.shape[1]):
        corner = speeds[:, j]
        rows, cols = np.nonzero(
            valid & (corner <= limit_top)[:, None] & (slowest < corner[:, None])
            & (fastest > corner[:, None]) & may_exceed(torques[:, j, None]))
        crossing = omega[rows, cols].copy()
        crossing[:, 0] -= corner[rows]
        found.append((rows, cols, crossing))
    ratio = solved(found)
    found = []  # then the segments at once: L = t_j + slope (|omega| - s_j)
    for j in range(speeds.shape[1] - 1):
        start, end = speeds[:, j], speeds[:, j + 1]
        slope = (torques[:, j + 1] - torques[:, j]) / (end - start)
        # the line's smallest value over the speeds of the sub-piece on the segment
        ends = [np.clip(x, start[:, None], np.minimum(end, limit_top)[:, None])
                * (1.0 + sign * _RATIO_MARGIN) for x, sign in ((slowest, -1.0), (fastest, 1.0))]
        least = np.minimum(*(torques[:, j, None] + slope[:, None] * (x - start[:, None])
                             for x in ends))
        rows, cols = np.nonzero(
            valid & ((start < limit_top) & (slope != 0.0))[:, None] & (fastest > start[:, None])
            & (slowest < end[:, None]) & may_exceed(least))
        line = slope[rows, None] * omega[rows, cols]
        line[:, 0] += torques[rows, j] - slope[rows] * start[rows]
        first = _multiply(derivative[rows, cols], line)  # tau' L - tau L'
        found.append((rows, cols, first - _pad(_multiply(motor[rows, cols], _derivative(line)),
                                               first.shape[-1])))
    return solved(found)


def _load_jerk(c, h: float, T: np.ndarray) -> np.ndarray:
    """The load's peak jerk C_j h / T^3 where the law's acceleration is continuous (each
    row's law's: RowLaws), else inf (a jump: an impulse of jerk)."""
    with np.errstate(invalid="ignore", over="ignore"):
        return np.where(c.jerk_bounded, c.C_j * h / T / T / T, np.inf)


def _stacked_grids(law: RowLaws, k: int | None = None) -> GridRows:
    """The laws' grids padded into one (GridRows; with ``k``, law k's alone), built once
    for the rows of these laws and every take of them."""
    key = "grids" if k is None else f"grid {k}"
    grids = law.shared.get(key)
    if grids is None:
        grids = law.shared[key] = (GridRows(law.laws, several=True) if k is None
                                   else GridRows((law.laws[k],)))
    assert isinstance(grids, GridRows)
    return grids


def _jerk_bound(c, h: float, max_jerk: float) -> np.ndarray | float:
    """The duration below which the load's jerk exceeds ``max_jerk``: cbrt(C_j h / j_max)
    where the law's (each row's law's) acceleration is continuous, else inf."""
    with np.errstate(invalid="ignore"):
        return np.where(c.jerk_bounded, np.cbrt(c.C_j * h / max_jerk), np.inf)


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


def _most(a: np.ndarray, pick=np.maximum) -> np.ndarray:
    """The largest (``pick`` np.minimum: smallest) entry over the last axis, taken column
    by column: numpy reduces a short last axis many times slower. Needs one entry."""
    out = a[..., 0].copy()
    for k in range(1, a.shape[-1]):
        pick(out, a[..., k], out=out)
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


def _unit_roots(c: np.ndarray, where: np.ndarray | None = None) -> np.ndarray:
    """The real roots inside [0, 1] of polynomials c (..., m+1), the ends aside (every use
    has them already): (..., m), NaN for none (and where ``where`` (...) is False: those
    polynomials are not solved).

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
    if where is not None:
        out = np.full((*shape[:-1], width), np.nan)
        out[where] = _unit_roots(c[where])
        return out
    flat = np.array(c.reshape(-1, m + 1), dtype=float)  # a copy: rows are deflated in place
    out = np.full((len(flat), width), np.nan)
    if m == 0 or not len(flat):
        return out.reshape((*shape[:-1], width))
    flat = _deflate(flat)
    size = np.abs(flat)
    ends = np.flatnonzero(np.abs(flat.sum(axis=1))
                          <= _DEGREE_TOLERANCE * _most(size))  # c(1) = 0
    if len(ends):
        ones = np.ones(len(ends))
        flat[ends] = _compose(_deflate(_compose(flat[ends], ones, -ones)), ones, -ones)
    size = np.abs(flat)
    big = size > _DEGREE_TOLERANCE * _most(size)[:, None]
    degree = np.where(big.any(axis=1), m - np.argmax(big[:, ::-1], axis=1), 0)
    for k in range(1, m + 1):
        rows = np.flatnonzero(degree == k)
        if len(rows):
            out[rows, :k] = _real_roots(flat[rows, :k + 1])
    found = np.nonzero(~np.isnan(out))  # polished, each root with its row
    c, u = flat[found[0]], out[found]
    slope, value = _derivative(c), _horner(c, u)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for _ in range(_NEWTON_STEPS):
            step = np.clip(u - value / _horner(slope, u), 0.0, 1.0)
            new = _horner(c, step)
            better = np.isfinite(new) & (np.abs(new) < np.abs(value))
            u = np.where(better, step, u)
            value = np.where(better, new, value)
    out[found] = u
    return out.reshape((*shape[:-1], width))


def _deflate(flat: np.ndarray) -> np.ndarray:
    """Rows c (rows, m+1) with their roots at u = 0 divided out: the low coefficients
    below _DEGREE_TOLERANCE of the row's largest dropped, the rest shifted down."""
    size = np.abs(flat)
    small = size <= _DEGREE_TOLERANCE * _most(size)[:, None]
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
    found by Newton steps kept in it (:func:`_bracketed`). A root where the sign does
    not change (even multiplicity) is of no use: it cuts no sign of speed or flow, and the
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
    """The root of each row c in [a, b], where c changes sign once (f_a = c(a)): Newton's
    steps kept inside the bracket (bisection where a step leaves it), the bracket shrunk
    at every point, the rows still open only, until a step or the bracket is below
    _BRACKET_TOLERANCE of [0, 1] or c's value is within its rounding there (a cut's error
    moves an integral by its square, a stationary point's a peak by its square too;
    :func:`_unit_roots` polishes the roots after)."""
    slope, size = _derivative(c), np.abs(c)
    x, out = 0.5 * (a + b), np.empty(len(a))
    rows = np.arange(len(a))
    a, b, up = a.copy(), b.copy(), f_a < 0.0  # up: c rises through the root
    for _ in range(_BRACKET_STEPS):
        value, change = _horner(c[rows], x), _horner(slope[rows], x)
        low = (value < 0.0) == up
        a, b = np.where(low, x, a), np.where(low, b, x)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = x - value / change
        inside = (step > a) & (step < b)
        new = np.where(inside, step, 0.5 * (a + b))
        settled = np.abs(value) <= 8.0 * np.finfo(float).eps * _horner(size[rows], x)
        done = settled | (inside & (np.abs(new - x) <= _BRACKET_TOLERANCE)) \
            | (b - a <= _BRACKET_TOLERANCE)
        out[rows[done]] = np.where(settled[done], x[done], new[done])
        keep = ~done
        if not keep.any():
            return out
        rows, x, a, b, up = rows[keep], new[keep], a[keep], b[keep], up[keep]
    out[rows] = x
    return out


def _horner(c: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Rows c (rows, m+1) ascending at one point x (rows,) each."""
    out = c[:, -1].copy()
    for k in range(c.shape[1] - 2, -1, -1):
        out = out * x + c[:, k]
    return out


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
        return rms_of_powers(c, T, len(self.moves), self.dwell, hold)


Objective = Callable[[np.ndarray, np.ndarray], np.ndarray]
"""A channel's value at normalized (a_N, v_N) arrays of shape (candidates, k)."""


def law_samples(law: MotionLaw, samples: int = SAMPLES) -> tuple[np.ndarray, ...]:
    """u, q_N, v_N, a_N on [0, 1], piece by piece with both ends of each piece (book ch.
    2-3: the law's normalized form; a step of the acceleration is a repeated u)."""
    parts: list[list[np.ndarray]] = [[], [], [], []]
    for index, piece in enumerate(law.pieces):
        u = np.linspace(piece.start, piece.end, max(2, round(samples * (piece.end -
                                                                         piece.start))))
        parts[0].append(u)
        for order in range(3):
            parts[order + 1].append(law.piece_derivative(index, u, order))
    return tuple(np.concatenate(p) for p in parts)


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
    """A cycle of segments (sizer.sizing.cycle.SegmentCycle) says True: the T_min
    search then varies the scale of its free durations, without the closed forms."""

    def __init__(self, grid: LawGrid | None, task: Task, drive: Drive, motors: MotorArrays,
                 thermal_speed: ThermalSpeedRule = "max", law=None) -> None:
        if drive.load.position_dependent:  # never sized as if the terms were absent
            raise UserError("load.gravity and load.spring (loads of the position) are "
                            "sized in one move with its dwell and a given transmission "
                            "(sizer.sizing.linkage_move; docs/position-loads.md), not in "
                            "this case (a cycle, a return or a ratio search)", field="load")
        self._grid = grid
        self._grid_rows: GridRows | None = None  # the law's grid as the rows read it
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
        known to pass: sizer.sizing.shortest_duration); with ``model`` the metrics carry
        the RMS model at these durations (:class:`RmsModel`). ``rms``: the motor's RMS
        torque at these durations, known (an RMS model's value within CONVERGED of where
        it was built: sizer.sizing.shortest_duration.rms_crossing_with_rms); the power-flow
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
            load_torque = np.maximum(load_torque, np.abs(self.drive.figures.torque))
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
        jerk = _load_jerk(c, h, T)
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
        return thermal_speed_of(self.thermal_rule, self.drive.ratio, self.h, self.task.dwell,
                                len(self.directions), c.C_v, c.C_v_rms, T)

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

    def _mean_squares(self, scales: MoveScales, model: list | None = None) -> list[np.ndarray]:
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
        moments = np.stack([np.broadcast_to(np.asarray(x, dtype=float), (n,)) for x in
                            (c.C_a_rms**2, c.C_v_rms**2, 1.0, 0.0, 0.0, 1.0)])
        return [(spread((self.motors.inertia * K + a_part) * scales.acc, n),
                 spread((self.motors.damping * K + v_part) * scales.vel, n),
                 spread(np.asarray(const, dtype=float), n), moments)]

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
        of the move where that function is the torque (:func:`flow_sums`)."""
        n = len(self.motors)
        law = self.law
        if not isinstance(law, RowLaws):
            if self._grid_rows is None:
                self._grid_rows = GridRows((law,))
            return flow_sums(self._grid_rows, terms, n)
        if all(one.piece_forms() is not None for one in law.laws):  # every row at once
            return flow_sums(_stacked_grids(law).for_rows(law.index), terms, n)
        # law by law: each law's rows summed on its own grid, as its calculator does
        out: list[list[np.ndarray]] | None = None
        for k, at in law.groups():
            part = [[tuple(spread(x, n)[at] for x in f) for f in channel] for channel in terms]
            found = flow_sums(_stacked_grids(law, k), part, len(at))
            if out is None:
                out = [[np.empty((6, n)) for _ in channel] for channel in found]
            for mine, theirs in zip(out, found, strict=True):
                for whole, one in zip(mine, theirs, strict=True):
                    whole[:, at] = one
        assert out is not None
        return out

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
                rows = np.flatnonzero(~exact)
                for _, at, sub in self.by_law(rows):
                    index = rows[at]
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

    def by_law(self, rows: np.ndarray) -> list[tuple[int, np.ndarray, CycleCalculator]]:
        """The rows ``rows`` law by law (RowLaws), else all at once (law 0): per law its
        index, the positions ``at`` in ``rows`` of its rows and the calculator of the rows
        ``rows[at]`` with that law alone."""
        if not isinstance(self.law, RowLaws):
            return [(0, np.arange(len(rows)), self.take(rows))]
        out = []
        for k, at in self.law.groups(rows):
            index = rows[at]
            out.append((k, at, CycleCalculator(None, self.task, self.drive.take(index),
                                               self.motors.subset(index), self.thermal_rule,
                                               law=self.law.laws[k])))
        return out

    def shaft_work(self, T: np.ndarray) -> np.ndarray:
        """Work at the motor shaft over the move, the integral of tau*omega (signed along
        the move), by the law grid's Gauss-Legendre rule (exact for polynomial pieces of
        an ideal drive; to the grid's accuracy where a stage's power flow reverses); each
        row on its own law's grid (RowLaws: law by law)."""
        if isinstance(self.law, RowLaws):
            out = np.empty(len(T))
            for _, at, calc in self.by_law(np.arange(len(T))):
                out[at] = calc.shaft_work(T[at])
            return out
        grid = self.grid
        sign = 1.0 if self.task.displacement >= 0 else -1.0
        scales = MoveScales(self.h / T / T, self.h / T, sign)
        torque, _ = self.channels(grid.acceleration[None], grid.velocity[None], scales)
        K = np.broadcast_to(self.drive.ratio, T.shape)
        omega = (K * self.h / T)[:, None, None] * grid.velocity[None]
        return np.sum(grid.weights[None] * torque * omega, axis=(1, 2)) * T

    def _law_view(self, k: int) -> CycleCalculator:
        """This calculator's rows, every one read with the law ``self.law.laws[k]``
        (RowLaws: the rows of that law take its own steps through it)."""
        assert isinstance(self.law, RowLaws)
        return CycleCalculator(None, self.task, self.drive, self.motors, self.thermal_rule,
                               law=self.law.laws[k])

    def _each_law(self, rows: np.ndarray,
                  step: Callable[[CycleCalculator, np.ndarray], np.ndarray]) -> np.ndarray:
        """``step(calculator, rows)`` over the rows ``rows``: this calculator with all of
        them, or (RowLaws) law by law, a view of its rows read with that law
        (:meth:`_law_view`) with that law's rows; the results joined."""
        if not isinstance(self.law, RowLaws):
            return step(self, rows)
        out: np.ndarray | None = None
        for k, at in self.law.groups(rows):
            found = step(self._law_view(k), rows[at])
            if out is None:
                out = np.empty(len(rows), dtype=found.dtype)
            out[at] = found
        assert out is not None
        return out

    def _linear_peaks(self, rows: np.ndarray):
        """The linear peaks of queries asked for the rows ``rows``: the law's, or each
        row's own law's (RowLaws)."""
        if isinstance(self.law, RowLaws):
            return self.law.peaks(rows)
        return self.law.linear_peaks

    def _acceleration_range(self):
        """:func:`acceleration_range` of the calculator's law."""
        return acceleration_range(self.law)

    def _values(self, rows: np.ndarray, tau: np.ndarray, piece: np.ndarray, order):
        """piece_values of points of the rows ``rows`` on the law (each row's: RowLaws)."""
        if isinstance(self.law, RowLaws):
            return self.law.values(rows, tau, piece, order)
        return piece_values(self.law, tau, piece, order)

    def _exact_moves(self, moves: list[MoveScales]):
        """:meth:`_exact_peaks` of every move, the moves' candidates stacked into one run
        (the same linear functions per candidate in every move, their coefficients and
        the direction per row): each query elementwise, so the answers are those of one
        run per move, at the cost of one."""
        figures = self.drive.figures
        terms = [self.channel_terms(scales) for scales in moves]
        n = len(self.motors)
        joined = None
        if len(moves) > 1 and not (_inertial(terms[0][0])
                                   and figures.none("damping", "friction", "torque")):
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

    def reported(self, metrics: CycleMetrics) -> np.ndarray:
        """The duration a result reports: the move's T."""
        return metrics.duration

    def dead_point_issues(self) -> None:
        return None  # no linkage

    def given_scale(self) -> float:
        assert self.task.duration is not None, "a given duration"
        return self.task.duration

    def law_move(self) -> CycleCalculator:
        """Itself: a law move rest-to-rest, with the closed forms of eq. (6.2)."""
        return self

    def cycle_time(self, T: np.ndarray) -> np.ndarray:
        return self.task.moves_per_cycle * (np.asarray(T, dtype=float) + self.task.dwell)

    def scale_of(self, duration: np.ndarray) -> np.ndarray:
        """The move durations T themselves (:meth:`evaluate` reports T)."""
        return np.asarray(duration, dtype=float)

    def pieces(self, s: np.ndarray, samples: int | None = None) -> list[CyclePiece]:
        """The task shorthand at move durations T = s: move, dwell and with a return the
        move back and a dwell, each move on the law's normalized grid scaled by T (time
        t0 + T u, speed h v_N(u) / T, acceleration h a_N(u) / T^2, book sec. 6.1.1)."""
        if isinstance(self.law, RowLaws):  # the engine samples each chosen law's own model
            raise TypeError("a calculator of several laws' rows has no one law to sample")
        T = s
        n = len(self.motors)
        u, q_n, v_n, a_n = law_samples(self.law, SAMPLES if samples is None else samples)
        h, Tc = self.h, T[:, None]
        K = np.broadcast_to(np.asarray(self.drive.ratio, dtype=float), (n,))[:, None]
        hold = np.broadcast_to(np.asarray(self.drive.holding_torque, dtype=float), (n,))
        hold = hold * np.sign(self.drive.figures.torque)
        directions = iter(self.directions)
        out, start, position = [], np.zeros((n, 1)), 0.0
        for segment in from_task(self.task).segments:  # named move, dwell, return, dwell 2
            name = segment.name or ""
            if isinstance(segment, Dwell):
                out.append(held_piece(name, start, np.full((n, 1), self.task.dwell), position,
                                      hold))
                start = start + self.task.dwell
                continue
            direction = next(directions)
            torque, _ = self.channels(a_n[None], v_n[None],
                                      MoveScales(h / T / T, h / T, direction))
            speed = direction * h * v_n[None] / Tc
            acceleration = direction * h * a_n[None] / Tc / Tc
            out.append(CyclePiece(name, start + Tc * u[None], position + direction * h * q_n,
                                  speed, acceleration, K * speed, K * acceleration,
                                  direction * np.broadcast_to(torque, (n, u.size))))
            start, position = start + Tc, position + direction * h
        return out

    def take(self, index: np.ndarray) -> CycleCalculator:
        """The calculator of the candidates at ``index`` (same law and grid)."""
        law = self.law.take(index) if isinstance(self.law, RowLaws) else self.law
        return CycleCalculator(self._grid, self.task, self.drive.take(index),
                               self.motors.subset(index), self.thermal_rule, law=law)

    def peak_bound(self, limits: Limits) -> np.ndarray | None:
        """The peak and speed bound on T_min (:func:`peak_duration`)."""
        return peak_duration(self, limits)

    def search_start(self, limits: Limits) -> None:
        """None: the peak bound is a bound wherever it is usable (CycleModel)."""
        return None

    def initial_guess(self) -> np.ndarray:
        """A duration scale from the speed and inertial bounds (never zero)."""
        c = self.law.coefficients
        drive, motors = self.drive, self.motors
        k, h = drive.ratio, self.h
        J_t = motors.inertia + drive.transmission_inertia + drive.reflected_load_inertia
        tau_p = np.maximum(motors.intermittent.torques.max(axis=1), 1e-300)
        guess = np.maximum(c.C_v * k * h / motors.speed_limit,
                           np.sqrt(c.C_a * k * h * J_t / tau_p))
        return np.where(np.isfinite(guess) & (guess > 0.0), guess, 1.0)

    def rms_lower_bound(self) -> np.ndarray | None:
        """Per candidate a torque the motor's RMS over the cycle exceeds at every duration
        (book sec. 6.1.1); None where a damping term is negative (the bound needs them
        >= 0).

        Over a rest-to-rest move int a dt = 0 and int v dt = h, and the motor torque is at
        least each of its linear functions P a + Q v + C (Drive.linear_pieces, the rotor
        added), so int tau dt >= (damping terms) h + C_k T >= C_k T. By Cauchy-Schwarz
        int tau^2 dt >= (int tau dt)^2 / T >= (C+)^2 T, C+ the largest C_k if positive.
        With n moves, dwells t_d and the holding torque: RMS^2 >= (S T + n t_d hold^2) /
        (n (T + t_d)), S the sum of (C+)^2 over the moves: a weighted mean of S/n and
        hold^2, so RMS >= sqrt(min(S/n, hold^2)) at every T (sqrt(S/n) without a dwell).
        """
        drive, motors = self.drive, self.motors
        n = len(motors)
        total = np.zeros(n)
        for direction in self.directions:
            shaft, _ = drive.linear_pieces(direction)
            for _, B, _ in shaft:
                if bool(np.any(np.broadcast_to(B, (n,)) + motors.damping * drive.ratio < 0.0)):
                    return None
            top = np.max([np.broadcast_to(np.asarray(C, dtype=float), (n,))
                          for _, _, C in shaft], axis=0)
            total += np.square(np.maximum(top, 0.0))
        least = total / len(self.directions)
        if self.task.dwell > 0.0:
            hold = np.broadcast_to(drive.holding_torques()[0], (n,))
            least = np.minimum(least, np.square(hold))
        return np.sqrt(least)

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
        certified = np.ones(n, dtype=bool)
        speed = K * scales.vel * c.C_v
        # speeds past the region are clipped into it for the ratio (the speed check covers
        # them): a region flat to its end is flat at every speed
        flat = np.broadcast_to((speed <= motors.flat_speed)
                               | (motors.flat_speed >= motors.speed_limit), (n,))
        # where every region is flat no ratio reads where the peak is: a channel affine
        # in the acceleration (its functions P a_N + C, no speed term) peaks from the
        # law's least and largest a_N where its acceleration is linear on every piece
        # (the values its linear peaks give, without their hull: :func:`affine`)
        extremes = self._acceleration_range() if flat.all() else None

        def without_hull(coefficients) -> bool:
            """A channel read without linear-peak queries: proportional to the
            acceleration (C_a), or affine in it where ``extremes`` are known."""
            return _inertial(coefficients) or (extremes is not None and not any(
                np.any(Q) for _, Q, _ in coefficients))

        def channel(coefficients, highs, lows):
            """max |value| of a maximum of linear functions of (a_N, v_N), from each
            function's linear peaks (``highs``) and lowest points (``lows``); clears
            ``certified`` where the minimum could not be certified."""
            if _inertial(coefficients):
                places.append(None)
                return np.broadcast_to(np.abs(coefficients[0][0]) * c.C_a, (n,)).copy()
            if without_hull(coefficients):  # affine in the acceleration: from ``extremes``
                return affine(coefficients)
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
                v_n, a_n = self._values(np.arange(n), tau, piece, (1, 2))
                values = np.stack([P * a_n + Q * v_n + C for P, Q, C in coefficients])
                scale = np.max(np.abs(values), axis=0) + np.abs(bottom)
                certified[:] &= values.max(axis=0) <= bottom + 1e-12 * scale
            upper = top >= -bottom
            places.append((np.where(upper, top_tau, tau), np.where(upper, top_piece, piece)))
            return np.maximum(top, -bottom)

        def affine(coefficients):
            """:func:`channel` of functions P a_N + C (no speed term) from the law's least
            and largest a_N (``extremes``): each function's highest and lowest values are
            P times one of them, plus C, the floats its linear peaks give; the minimum
            certified as there, at the a_N of its function's minimizer."""
            assert extremes is not None
            places.append(None)
            lowest, highest = extremes
            top = np.full(n, -np.inf)
            floors, minimizers = [], []
            for P, _, C in coefficients:
                rising = P >= 0.0
                value = np.where(rising, P * highest, P * lowest) + C
                top = np.where(value > top, value, top)
                floors.append(np.broadcast_to(np.where(rising, P * lowest, P * highest) + C,
                                              (n,)))
                minimizers.append(np.broadcast_to(np.where(rising, lowest, highest), (n,)))
            lows = np.stack(floors)
            best = np.argmax(lows, axis=0)
            bottom = lows[best, np.arange(n)]
            if len(coefficients) > 1:
                a_n = np.choose(best, minimizers)
                values = np.stack([P * a_n + C for P, _, C in coefficients])
                scale = np.max(np.abs(values), axis=0) + np.abs(bottom)
                certified[:] &= values.max(axis=0) <= bottom + 1e-12 * scale
            return np.maximum(top, -bottom)

        places: list[tuple[np.ndarray, np.ndarray] | None] = []  # where each |peak| is
        motor_terms, *stage_terms = self.channel_terms(scales) if terms is None else terms
        f = drive.figures
        load_terms = [(spread(f.inertia * scales.acc, n), spread(f.damping * scales.vel, n),
                       f.column("friction", n) + scales.direction * f.column("torque", n))]
        channels = [motor_terms, load_terms] + (stage_terms if self.stage_checks else [])
        # every function's highest and lowest point, all channels in one query
        functions = [f for co in channels if not without_hull(co) for f in co]
        # the law's linear peaks (its hull) only where a channel needs them: purely
        # inertial channels read C_a alone, affine ones the law's extremes
        solved = self._linear_peaks(np.tile(np.arange(n), 2 * len(functions))).maximum(
            np.concatenate([sign * spread(P, n) for sign in (1.0, -1.0)
                            for P, _, _ in functions]),
            np.concatenate([sign * spread(Q, n) for sign in (1.0, -1.0)
                            for _, Q, _ in functions])) if functions else None
        results, start = [], 0
        for co in channels:
            if without_hull(co):
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
        ratio = _safe_ratio(peak, motors.intermittent.torques[:, 0])
        exact = certified & flat
        curved = np.flatnonzero(certified & ~flat)
        speed_scale = spread(K * scales.vel, n)
        if len(curved):
            exact[curved] = self._each_law(curved, lambda calc, rows: calc._curve_ratio(
                motor_terms, rows, speed_scale[rows], calc.law.coefficients.C_v, ratio))
        beyond = np.flatnonzero(certified & ~exact & (spread(speed, n)
                                                      > motors.speed_limit))
        if len(beyond) and peak_place is not None:
            place = peak_place
            exact[beyond] = self._each_law(beyond, lambda calc, rows: calc._beyond_ratio(
                peak, place, rows, speed_scale[rows], ratio))
        leaving = np.flatnonzero(certified & ~exact & (spread(speed, n)
                                                       > motors.speed_limit))
        if len(leaving):
            exact[leaving] = self._each_law(leaving, lambda calc, rows: calc._leaving_ratio(
                motor_terms, rows, speed_scale[rows], ratio))
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


def flow_sums(rows: GridRows, terms, n: int) -> list[list[np.ndarray]]:
    """Per channel and per function of it, the law's moments summed over the stretches
    of the move where that function is the torque: (6, candidates) arrays; each row
    reads its own law's grid (``rows``).

    Between two power-flow reversals of the stages every channel is one of its linear
    functions (the reflections switch only where a stage's output torque is zero), so
    a stretch's moments are a difference of the law's prefix-sum moment table
    (:func:`moment_table`) and the work per candidate is per reversal, not per grid
    interval. The reversals: a stage's output torque (a maximum of linear functions)
    is read at the ends of every grid interval; where it changes sign inside an
    interval the root is found (Newton in a bracket, in the interval's own coordinate:
    the two reflections agree at the root, so a root error dz changes an integral by
    O(dz^2)) and the table read there by Gauss-Legendre on the part of the interval
    before it; where its sign class changes across a grid edge (a jump of a_N) the
    edge is a split. Each stretch's function is the one with the largest integral
    over it (the torque is the maximum of the functions).
    """
    several = rows.which is not None
    size = rows.end_velocity.shape[-2]
    end_a, end_v = rows.end_acceleration, rows.end_velocity
    if several:
        end_a, end_v = end_a[rows.which], end_v[rows.which]
    edge = np.zeros((n, max(size - 1, 0)), dtype=bool)
    roots: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []  # (cand, interval, z)
    for pieces in terms[1:]:  # each stage's output at the ends of every interval
        x = _linear_maximum(pieces, end_a, end_v, rows_first=several)
        lo, hi = x[..., 0], x[..., 1]
        # sign classes as booleans (NaN, a move of 1e-200 s, counts as zero): an end
        # at zero takes the class of the interval's other end
        pos_lo, neg_lo, pos_hi, neg_hi = lo > 0.0, lo < 0.0, hi > 0.0, hi < 0.0
        left_pos = pos_lo | (pos_hi & ~neg_lo)
        left_neg = neg_lo | (neg_hi & ~pos_lo)
        right_pos = pos_hi | (pos_lo & ~neg_hi)
        right_neg = neg_hi | (neg_lo & ~pos_hi)
        edge |= (right_pos[:, :-1] != left_pos[:, 1:]) | (right_neg[:, :-1] != left_neg[:, 1:])
        crossing = (pos_lo & neg_hi) | (neg_lo & pos_hi)
        if several:  # a padded interval neither crosses nor splits
            valid = rows.valid[rows.which]
            crossing &= valid
            edge &= valid[:, 1:]
        cand, interval = np.nonzero(crossing)
        if len(cand):
            roots.append((cand, interval, _flow_root(rows, pieces, n, cand, interval,
                                                     lo[cand, interval],
                                                     hi[cand, interval])))
    # every split point: (candidate, position along the grid, prefix moments there)
    table = rows.table
    totals = table[-1] if not several else table[rows.which, -1]
    e_cand, e_index = np.nonzero(edge)
    cands = [np.arange(n), np.arange(n), e_cand]
    keys = [np.zeros(n), np.full(n, rows.size[0]) if not several
            else rows.size[rows.which], (e_index + 1).astype(float)]
    values = [np.zeros((n, 6)), np.broadcast_to(totals, (n, 6)),
              rows.at(table, e_cand, e_index + 1)]
    for cand, interval, z in roots:
        cands.append(cand)
        keys.append(interval + z)
        values.append(rows.at(table, cand, interval)
                      + _partial_moments(rows, cand, interval, z))
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
            sums.append([np.repeat(totals[:, None], n, axis=1) if not several
                         else np.ascontiguousarray(totals.T)])
            continue
        best = _largest_integral([tuple(spread(x, n)[run_cand] for x in f)
                                  for f in channel], run)
        mine = []
        columns = np.arange(6)
        for k in range(len(channel)):
            chosen = best == k
            # one bincount over (candidate, moment) bins: each bin's terms summed in
            # the runs' order, as six bincounts of one column each would
            bins = (run_cand[chosen][:, None] * 6 + columns).ravel()
            mine.append(np.bincount(bins, weights=run[chosen].ravel(),
                                    minlength=6 * n).reshape(n, 6).T.copy())
        sums.append(mine)
    return sums


def _flow_root(rows: GridRows, pieces, n: int, cand: np.ndarray, interval: np.ndarray,
               f_lo: np.ndarray, f_hi: np.ndarray) -> np.ndarray:
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
    count = len(cand)
    on_piece = rows.at(rows.piece, cand, interval)
    by_piece = np.argsort(on_piece, kind="stable")
    piece = on_piece[by_piece]
    lo_edge = rows.at(rows.left, cand, interval)[by_piece]
    width = rows.at(rows.right, cand, interval)[by_piece] - lo_edge
    chosen = [tuple(spread(x, n)[cand[by_piece]] for x in part)
              for part in pieces]
    sign_lo = np.sign(f_lo[by_piece])
    lo, hi = np.zeros(count), np.ones(count)
    f0, f1 = f_lo[by_piece], f_hi[by_piece]
    if len(chosen) == 1:  # one function: its cubic Hermite model on the interval
        (P, Q, _), = chosen
        a, j = (rows.at(x, cand[by_piece], interval[by_piece])
                for x in (rows.end_acceleration, rows.end_jerk))
        z = hermite_root(f0, f1, (P * j[:, 0] + Q * a[:, 0]) * width,
                         (P * j[:, 1] + Q * a[:, 1]) * width, xtol=0.1 * FLOW_ROOT_STEP)
    else:
        z = np.clip(f0 / (f0 - f1), 0.0, 1.0)
    forms = rows.forms
    law = rows.laws[0]  # (without forms: one law, evaluated piece by piece)
    bounds_of = np.arange(len(law.pieces) + 1)
    open_ = np.arange(count)
    for _ in range(60):
        if not len(open_):
            break
        tau = lo_edge[open_] + z[open_] * width[open_]
        mine = piece[open_]
        if forms is not None:  # every piece at once, the same values
            v_n, a_n, j_n = forms.values(mine, tau, (1, 2, 3))
        else:
            bounds = np.searchsorted(mine, bounds_of)
            v_n, a_n, j_n = (np.empty(len(open_)) for _ in range(3))
            for index in np.flatnonzero(np.diff(bounds)):
                part = slice(bounds[index], bounds[index + 1])
                at = law.pieces[index].clamp(tau[part])
                for out, order in ((v_n, 1), (a_n, 2), (j_n, 3)):
                    out[part] = law.pieces[index].evaluate(at, order)
        values = np.stack([P[open_] * a_n + Q[open_] * v_n + C[open_] for P, Q, C in chosen])
        k = np.argmax(values, axis=0)
        f = values[k, np.arange(len(open_))]
        slope = np.choose(k, [P[open_] * j_n + Q[open_] * a_n for P, Q, _ in chosen])
        below = np.sign(f) == sign_lo[open_]
        lo[open_] = np.where(below, z[open_], lo[open_])
        hi[open_] = np.where(below, hi[open_], z[open_])
        with np.errstate(divide="ignore", invalid="ignore"):
            step = z[open_] - f / (slope * width[open_])
        inside = (step > lo[open_]) & (step < hi[open_])
        new = np.where(inside, step, 0.5 * (lo[open_] + hi[open_]))
        done = (np.abs(new - z[open_]) <= FLOW_ROOT_STEP) | (f == 0.0) \
            | (hi[open_] - lo[open_] <= 1e-10)
        z[open_] = np.where(f == 0.0, z[open_], new)
        open_ = open_[~done]
    out = np.empty(count)
    out[by_piece] = np.minimum(np.maximum(z, 0.0), 1.0)
    return out


def _partial_moments(rows: GridRows, cand: np.ndarray, interval: np.ndarray,
                     z: np.ndarray) -> np.ndarray:
    """The law's moments over the first part [left, left + z width] of each grid
    interval at ``interval`` (Gauss-Legendre with the grid's node count, on the
    interval's piece): (len(interval), 6), columns as :func:`interval_moments`. Rows of
    laws with different node counts are integrated in groups of one count."""
    counts = rows.node_count[rows.law_of(cand)]  # one count for one law
    out = np.empty((len(cand), 6))
    for count in sorted_unique(counts):
        at = np.flatnonzero(counts == count) if np.ndim(counts) else slice(None)
        c, i = cand[at], interval[at]
        lo_edge = rows.at(rows.left, c, i)
        half = 0.5 * z[at] * (rows.at(rows.right, c, i) - lo_edge)
        x, w = gauss_legendre(int(count))
        tau = (lo_edge + half)[:, None] + half[:, None] * x
        piece = np.broadcast_to(rows.at(rows.piece, c, i)[:, None], tau.shape)
        if rows.forms is not None:
            a_n, v_n = (v.reshape(tau.shape) for v in rows.forms.values(
                piece.ravel(), tau.ravel(), (2, 1)))
        else:
            a_n, v_n = PieceEvaluator(rows.laws[0], piece).orders(tau, (2, 1))
        weight = half[:, None] * w
        out[at] = np.column_stack([(weight * a_n * a_n).sum(axis=1),
                                   (weight * v_n * v_n).sum(axis=1), weight.sum(axis=1),
                                   (weight * a_n * v_n).sum(axis=1),
                                   (weight * a_n).sum(axis=1), (weight * v_n).sum(axis=1)])
    return out


def _linear_maximum(pieces, a_n: np.ndarray, v_n: np.ndarray,
                    rows_first: bool = False) -> np.ndarray:
    """max_k P_k a_N + Q_k v_N + C_k for (P, Q, C) arrays over candidates and a_N, v_N
    arrays shared by all of them: shape (candidates, *a_n.shape); with ``rows_first``
    a_N, v_N have the candidates as their first axis already (each its own law's)."""
    shape = (-1,) + (1,) * (np.ndim(a_n) - (1 if rows_first else 0))
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


NEWTON_STEPS = 40
"""Steps at most (quadratic convergence: about 3 from the start used here)."""

SETTLED = 1e-8
"""A relative step of :func:`_largest_u` that ends its row: the step after it would be
of about its square times the maximizer's drift, below rounding."""


def peak_duration(calculator: CycleCalculator, limits: Limits,
                  prune: bool = True) -> np.ndarray | None:
    """A lower bound on T_min per candidate (inf where no duration passes a peak or speed
    check; None where the law may move backwards, v_N < 0, and the bound does not hold).
    ``prune=False`` solves every query (the reference the pruned result equals)."""
    law = calculator.law
    if law.moves_backwards():  # one law or each row's (RowLaws)
        return None
    c = law.coefficients
    n, h = len(calculator.motors), calculator.h
    if h == 0.0:  # no move: nothing bounds the duration
        return np.zeros(n)
    bounds = [speed_bounds(calculator, limits)]
    queries = peak_queries(calculator, limits)
    if queries is not None:
        who, P, Q, D = queries
        bounds.append(_largest_duration(calculator, n, who, P, Q, D, spread(c.C_a, n)[who],
                                        spread(c.C_v, n)[who], prune))
    return np.max(np.stack(bounds), axis=0)


def peak_queries(calculator: CycleCalculator, limits: Limits):
    """The peak conditions F(u) <= D of the module docs, one per candidate x torque
    function x region line (or stage rating) x direction: (candidate, P, Q, D) arrays,
    or None where there are none."""
    motors, drive, h = calculator.motors, calculator.drive, calculator.h
    n = len(motors)
    K = np.broadcast_to(drive.ratio, (n,))
    grip = 1.0 - limits.torque_margin
    alpha, sigma, _ = motors.intermittent.lines()
    rows, cols = np.nonzero(np.isfinite(alpha))
    queries: list[tuple[np.ndarray, ...]] = []
    for direction in calculator.directions:
        shaft, outputs = drive.linear_pieces(direction)
        for A, B, C in shaft:
            A = np.broadcast_to(A + motors.inertia * K, (n,))
            B = np.broadcast_to(B + motors.damping * K, (n,))
            C = np.broadcast_to(C, (n,))
            queries.append((rows, A[rows] * h, (B[rows] - grip * sigma[rows, cols] * K[rows]) * h,
                            grip * alpha[rows, cols] - C[rows]))
        for stage, pieces in zip(drive.stages, outputs, strict=True):
            if stage.peak_output_torque is None:
                continue
            rated = np.flatnonzero(np.broadcast_to(stage.rated["peak_output_torque"], (n,)))
            rating = np.broadcast_to(stage.peak_output_torque, (n,))[rated]
            for A, B, C in pieces:
                queries.append((rated, np.broadcast_to(A, (n,))[rated] * h,
                                np.broadcast_to(B, (n,))[rated] * h,
                                grip * rating - np.broadcast_to(C, (n,))[rated]))
    if not queries:
        return None
    who = np.concatenate([q[0] for q in queries])
    P, Q, D = (np.concatenate([q[i] for q in queries]) for i in (1, 2, 3))
    return who, P, Q, D


PRUNE_MARGIN = 1e-9
"""Relative gap by which a query's upper bracket must lie below another query's lower
bracket to be left out (far above the rounding of either)."""


def _largest_duration(calculator: CycleCalculator, n: int, who: np.ndarray, P: np.ndarray,
                      Q: np.ndarray, D: np.ndarray, C_a: np.ndarray, C_v: np.ndarray,
                      prune: bool) -> np.ndarray:
    """Per candidate the largest of its queries' bounds 1/u (:func:`_largest_u`).

    Only the largest counts, so a query is solved only where it may be the largest: each
    query's bound lies in a bracket from closed forms (:func:`_brackets`), and a query
    whose upper end is below the largest lower end of its candidate's queries is left
    out. Where the solved queries do not reach that lower end after all (a Newton run
    that never got to the right of u*), the candidate's other queries are solved too, so
    the result is the largest over all queries, as without pruning."""
    keep = np.ones(len(who), dtype=bool)
    if prune:
        low, high = _brackets(P, Q, D, C_a, C_v)
        floor = np.zeros(n)
        np.maximum.at(floor, who, low)
        keep = ~(high * (1.0 + PRUNE_MARGIN) < floor[who] * (1.0 - PRUNE_MARGIN))
    worst = np.zeros(n)
    solved = np.zeros(len(who), dtype=bool)
    for _ in range(2):
        todo = keep & ~solved
        if todo.any():
            u = _largest_u(calculator, who[todo], P[todo], Q[todo], D[todo], C_a[todo],
                           C_v[todo])
            with np.errstate(divide="ignore"):
                np.maximum.at(worst, who[todo], np.where(u > 0.0, 1.0 / u, np.inf))
            solved |= todo
        if keep.all():
            break
        short = worst < floor * (1.0 - PRUNE_MARGIN)
        keep |= short[who]
    return worst


def _brackets(P: np.ndarray, Q: np.ndarray, D: np.ndarray, C_a: np.ndarray,
              C_v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per query a lower and an upper end of its bound 1/u* (module docs: F(u) <= D).

    Lower: 1/u at the start of :func:`_largest_u` (the Newton iterates stay at or below
    it, so the bound computed is at least this). Upper: where P, Q >= 0, F(u) <= P C_a u^2
    + Q C_v u (a_N <= C_a, 0 <= v_N <= C_v), so u* is at least that quadratic's root and
    1/u* at most (Q C_v + sqrt((Q C_v)^2 + 4 P C_a D)) / (2 D); inf elsewhere (and where
    D <= 0: no duration passes)."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        start = np.minimum(np.sqrt(D / (P * C_a)), D / (Q * C_v))
        low = np.where((D > 0.0) & np.isfinite(start) & (start > 0.0), 1.0 / start, 0.0)
        a, b = P * C_a, Q * C_v
        high = (b + np.sqrt(b * b + 4.0 * a * D)) / (2.0 * D)
    high = np.where((D > 0.0) & (P >= 0.0) & (Q >= 0.0) & np.isfinite(high), high, np.inf)
    low = np.where(D > 0.0, low, np.inf)
    return low, high


def speed_bounds(calculator: CycleCalculator, limits: Limits) -> np.ndarray:
    """The durations below which the speed check or a load limit fails (closed forms)."""
    c = calculator.law.coefficients
    h, motors = calculator.h, calculator.motors
    K = np.broadcast_to(calculator.drive.ratio, (len(motors),))
    with np.errstate(divide="ignore", invalid="ignore"):
        T = c.C_v * K * h / (motors.speed_limit * (1.0 - limits.speed_margin))
        T = np.where(np.isnan(T), np.inf, T)
    if calculator.thermal_rule == "max":  # the thermal speed is the peak speed
        with np.errstate(divide="ignore", invalid="ignore"):
            thermal = c.C_v * K * h / (motors.continuous.max_speed * (1.0 - limits.speed_margin))
        T = np.maximum(T, np.where(np.isnan(thermal), np.inf, thermal))
    if limits.max_speed is not None:
        T = np.maximum(T, c.C_v * h / limits.max_speed)
    if limits.max_acceleration is not None:
        T = np.maximum(T, np.sqrt(c.C_a * h / limits.max_acceleration))
    if limits.max_jerk is not None:
        T = np.maximum(T, _jerk_bound(c, h, limits.max_jerk))
    for k, stage in zip(calculator.drive.input_ratios, calculator.drive.stages, strict=True):
        if stage.max_input_speed is not None:
            rated = np.broadcast_to(stage.rated["max_input_speed"], T.shape)
            with np.errstate(divide="ignore", invalid="ignore"):
                bound = c.C_v * k * h / (stage.max_input_speed * (1.0 - limits.speed_margin))
            T = np.where(rated, np.maximum(T, bound), T)
    return T


def _largest_u(calculator: CycleCalculator, who: np.ndarray, P: np.ndarray, Q: np.ndarray,
               D: np.ndarray, C_a: np.ndarray, C_v: np.ndarray) -> np.ndarray:
    """Per query the largest u with max_tau (P a_N u^2 + Q v_N u) <= D (0 where D <= 0,
    inf where nothing limits u): the maximizer's quadratic from the right (module docs)."""
    u = np.full(P.shape, np.inf)
    u[D <= 0.0] = 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        # F(u) >= max(P C_a u^2, Q C_v u) (v_N >= 0, a_N >= 0 at the peaks), so the smaller
        # of these two roots has F >= D: a start on the right of u*
        start = np.minimum(np.sqrt(D / (P * C_a)), D / (Q * C_v))
    open_ = (D > 0.0) & np.isfinite(start)
    index = np.flatnonzero(open_)
    x = start[index]
    P, Q, D = P[index], Q[index], D[index]
    # no speed term: the peak is at the law's least or largest a_N where its acceleration
    # is linear on every piece (the values of its linear peaks: CycleCalculator._exact_peaks)
    extremes = None if np.any(Q) else calculator._acceleration_range()
    if extremes is not None:  # per candidate
        lowest, highest = (np.broadcast_to(e, (len(calculator.motors),)) for e in extremes)
    for _ in range(NEWTON_STEPS):
        if len(index) == 0:
            break
        rows = who[index]  # each query's candidate (its law's peaks and pieces)
        if extremes is None:
            peak = calculator._linear_peaks(rows).maximum(P * x * x, Q * x)
            v, a = calculator._values(rows, peak.tau, peak.piece, (1, 2))
            value = peak.value
        else:
            scale = P * x * x
            a = np.where(scale >= 0.0, highest[rows], lowest[rows])
            v, value = np.zeros(len(rows)), scale * a
        excess = value - D
        # the maximizer's quadratic A u^2 + b u <= F(u), equal at x with the same slope:
        # its positive root, in the stable form, lies in (u*, x) where F(x) > D
        A, b = P * a, Q * v
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            root = 2.0 * D / (b + np.sqrt(b * b + 4.0 * A * D))
            newton = x - excess / (2.0 * A * x + b)  # where rounding leaves no root
        root = np.where((root > 0.0) & (root < x), root, newton)
        nxt = np.where((excess > 0.0) & (root < x) & (root > 0.0), root, x)
        # a point where F >= D is on the right of u* (to rounding: F is exact to a few ulps)
        right = excess >= -1e-14 * np.abs(D)
        u[index] = np.minimum(u[index], np.where(right, x, u[index]))
        # a step this small leaves the next of about its square: the step's end, right of
        # u* by construction, is the answer without evaluating F there
        settled = (nxt < x) & (x - nxt <= SETTLED * x)
        u[index] = np.where(settled, np.minimum(u[index], nxt), u[index])
        moving = (nxt < x) & (x - nxt > 1e-15 * x) & ~settled
        x = nxt
        index, x, P, Q, D = (z[moving] for z in (index, x, P, Q, D))
    return u
