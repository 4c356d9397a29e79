"""A stage's checks over the machine cycle, as later limits of the search: a ball screw's
critical speed, buckling and L10 life; a gearbox's output bearing life.

Both read the cycle the same way (:func:`mean_cubic_load`): on the samples of one machine
cycle (the engine's own sampling for energy and heat,
sizer.sizing.evaluation.CycleModel.pieces: every move on its law's grid, each dwell holding
its load) each stage's output torque (force) is as the engine computes it
(sizer.mechanics.Drive.chain, along the motion), a load's terms of its position included
(gravity on an arm, a spring, a torque or force table: g(q); an inertia or mass table:
J(q) q'' + 1/2 J'(q) q'^2; sizer.model.domain.Load.position_terms at each sample's
position, speed and acceleration, added to the load's torque as the position engine adds
them, sizer.sizing.linkage_move.position_profile, each move with the load it moves:
:class:`sizer.sizing.evaluation.CyclePiece`'s ``load``); with v the load's speed, the mean cubic
load weighted by revolutions F_m = (int |F|^3 |v| dt / int |v| dt)^(1/3) (the shaft's speed
is k |v| with k constant per candidate: it cancels), each integral by the trapezoidal rule
on the samples (a repeated time, a jump, adds nothing; a dwell, where nothing turns,
nothing).

The ball screw's checks (sizer.sizing.checks.SCREW_CHECKS; their limits from the makers'
formulas, sizer.mechanics.stages.ScrewRatings, docs/ball-screws.md), for each ball screw
that has ratings, for every candidate at its scale:

- ``<stage>_critical_speed``: the screw's peak speed (the cycle's ``stage_speed``);
- ``<stage>_buckling``: the peak |axial force|; the ball screw is the last stage, so its
  axial force is the load's force u (the cycle's ``load_torque``, the dwells holding the
  load included), taken as compressive (the direction the load pushes is not known);
- ``<stage>_life``: F the screw's axial force (its output force); revolutions
  N = k_in int |v| dt / (2 pi) (k_in = 2 pi / lead); F_m as above (THK, General Catalog,
  Ball Screw, "Studying the Service Life": F_m = (sum F_i^3 l_i / sum l_i)^(1/3) over the
  distances l_i travelled under F_i); the mean speed n_m = N / t_cycle; the rated life
  L_10 = (C_a / (f_w F_m))^3 1e6 revolutions, in time L_10 / n_m.

The gearbox's output bearing checks (sizer.sizing.checks.GEARBOX_LIFE_RATINGS,
docs/shaft-loads.md): for a stage on the output shaft of the gearbox right before it
(``on_gearbox_output``), ``gearbox_radial_life`` (a belt's pulley, a pinion) or
``gearbox_axial_life`` (a ball screw): the equivalent force on the output F_eq = F_m with F
the force the stage puts on the shaft at each sample (sizer.mechanics.shaft_loads.
shaft_forces, from the gearbox's output torque there; a screw's axial force is its own
output force), against the force the gearbox's maker rates for a stated bearing life
(``output_radial_load_life``, ``output_axial_load_life``; Stober's "equivalent values"
F_2rad,eq = (sum n_2m,i t_i F_2rad,i^3 / sum n_2m,i t_i)^(1/3), likewise axial).

No further margin (the makers' safety factors are in the limits). In minimize mode a
failing candidate is moved to the shortest scale at which all of the limit's checks pass
(each slack grows with the scale: the shafts turn slower and less often, the inertial
forces fall), found by doubling the scale and the project's root finder; where none is
found within 2^DOUBLINGS the checks fail there with their margins.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from sizer.mechanics import Drive
from sizer.mechanics.shaft_loads import shaft_forces
from sizer.mechanics.stages import ScrewRatings, screw_rated_life
from sizer.model.domain import ShaftLoad
from sizer.numerics.roots import first_passing
from sizer.sizing.checks import (
    TOLERANCE,
    CheckArrays,
    gearbox_life_check,
    gearbox_life_kind,
    gearbox_life_rating,
    gearbox_output_loads,
    screw_checks,
    screw_ratings,
    stage_labels,
)
from sizer.sizing.evaluation import CycleMetrics, CycleModel
from sizer.sizing.shortest_duration import LaterChecks

DOUBLINGS = 30
"""The scale is doubled at most this many times looking for passing checks."""
XTOL = 1e-12
"""Relative width of the final bracket of the passing scale."""

StageForce = Callable[[list[np.ndarray]], np.ndarray]
"""The force (N, >= 0) of interest from every stage's output torque (force) along the
motion, at the samples (sizer.mechanics.Drive.chain's second answer)."""


@dataclass(frozen=True)
class MeanCubicLoad:
    """Per candidate over one machine cycle: the load's travel int |v| dt (m or rad), the
    mean cubic load weighted by it (N; 0 where nothing moves) and the cycle time (s)."""

    travel: np.ndarray
    mean: np.ndarray
    cycle_time: np.ndarray


def mean_cubic_load(calculator: CycleModel, s: np.ndarray, force: StageForce
                    ) -> MeanCubicLoad:
    """F_m = (int F^3 |v| dt / int |v| dt)^(1/3) of the ``force`` over one machine cycle of
    every candidate of ``calculator`` at its scale ``s`` (module docstring)."""
    s = np.broadcast_to(np.asarray(s, dtype=float), (len(calculator.motors),))
    n = len(s)
    travel, cube, end = np.zeros(n), np.zeros(n), np.zeros(n)
    for piece in calculator.pieces(s):
        time = np.broadcast_to(piece.time, (n, np.shape(piece.time)[-1]))
        v = np.broadcast_to(piece.load_speed, time.shape)
        a = np.broadcast_to(piece.load_acceleration, time.shape)
        end = np.maximum(end, time[:, -1])
        if not np.any(v):
            continue  # a dwell: nothing turns
        moved = piece.load
        drive = calculator.drive if moved is None else calculator.drive.with_load(moved)
        sense = np.where(v < 0.0, -1.0, 1.0)  # along the motion, as the engine's chain
        extra = None
        if moved is not None and moved.position_dependent:  # along the motion
            inertial, steady = moved.position_terms(piece.position, v, a)
            extra = (sense * inertial, sense * steady)
        _, outputs = drive.chain(sense * a, sense * v, sense, extra=extra)
        f = np.broadcast_to(force(outputs), time.shape)
        speed = np.abs(v)
        travel += _trapezoid(speed, time)
        cube += _trapezoid(f**3 * speed, time)
    with np.errstate(divide="ignore", invalid="ignore"):
        mean = np.where(travel > 0.0, np.cbrt(cube / travel), 0.0)
    return MeanCubicLoad(travel, mean, end)


@dataclass(frozen=True)
class ScrewCycle:
    """Per candidate over one machine cycle: the screw's revolutions, the mean cubic axial
    load F_m (N; 0 where the screw does not turn) and the cycle time (s)."""

    revolutions: np.ndarray
    mean_load: np.ndarray
    cycle_time: np.ndarray


def screw_cycle(calculator: CycleModel, s: np.ndarray, stage: int) -> ScrewCycle:
    """The screw of stage ``stage`` over one machine cycle of every candidate of
    ``calculator`` at its scale ``s`` (module docstring)."""
    cycle = mean_cubic_load(calculator, s, lambda outputs: np.abs(outputs[stage]))
    k_in = np.broadcast_to(np.asarray(calculator.drive.input_ratios[stage], dtype=float),
                           cycle.travel.shape)
    return ScrewCycle(k_in * cycle.travel / (2.0 * math.pi), cycle.mean, cycle.cycle_time)


def _trapezoid(y: np.ndarray, t: np.ndarray) -> np.ndarray:
    """int y dt per row by the trapezoidal rule on the samples."""
    return 0.5 * ((y[:, 1:] + y[:, :-1]) * np.diff(t, axis=1)).sum(axis=1)


def rated_life_time(screw: ScrewRatings, cycle: ScrewCycle) -> np.ndarray:
    """L_10 in seconds per candidate: (C_a / (f_w F_m))^3 1e6 revolutions at the cycle's
    mean speed; inf where the screw carries no load or does not turn."""
    assert screw.dynamic_load_rating is not None
    revolutions = screw_rated_life(screw.dynamic_load_rating, cycle.mean_load,
                                   screw.load_factor)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        life = revolutions * cycle.cycle_time / cycle.revolutions
    return np.where((cycle.mean_load > 0.0) & (cycle.revolutions > 0.0), life, np.inf)


class CycleLimit:
    """A later limit of the search (sizer.sizing.shortest_duration.LaterLimit) made of a
    stage's checks over the cycle (:meth:`checks`): they pass where every one does, and a
    failing candidate's passing scale is found by doubling and the root finder."""

    def checks(self, calculator: CycleModel, s: np.ndarray, metrics: CycleMetrics,
               known: np.ndarray) -> list[CheckArrays]:
        """The checks at scales ``s`` where ``known`` (elsewhere they pass, value 0)."""
        raise NotImplementedError

    def at(self, calculator: CycleModel, s: np.ndarray, metrics: CycleMetrics,
           known: np.ndarray) -> LaterChecks:
        checks = self.checks(calculator, np.asarray(s, dtype=float), metrics, known)
        passed = np.logical_and.reduce([c.passed for c in checks])
        return LaterChecks(checks, passed, {})

    def passing_scale(self, calculator: CycleModel, rows: np.ndarray, s: np.ndarray,
                      found: LaterChecks) -> np.ndarray:
        model = calculator.take(rows)

        def slack(x: np.ndarray, index: np.ndarray) -> np.ndarray:
            sub = model.take(index)
            checks = self.checks(sub, x, sub.evaluate(x), np.ones(len(index), dtype=bool))
            return np.min([c.slack for c in checks], axis=0) + TOLERANCE

        f_lo = np.min([c.slack[rows] for c in found.checks], axis=0) + TOLERANCE
        return first_passing(slack, s, f_lo, DOUBLINGS, XTOL)


@dataclass(frozen=True)
class ScrewLimit(CycleLimit):
    """The checks of the ball screw at stage ``stage`` (label ``label``) as a later limit
    of the search."""

    screw: ScrewRatings
    stage: int
    label: str

    def checks(self, calculator: CycleModel, s: np.ndarray, metrics: CycleMetrics,
               known: np.ndarray) -> list[CheckArrays]:
        life = None
        if self.screw.has_life_check:
            life = np.full(len(s), np.inf)
            rows = np.flatnonzero(known)
            if rows.size:
                cycle = screw_cycle(calculator.take(rows), s[rows], self.stage)
                life[rows] = rated_life_time(self.screw, cycle)
        n = len(s)
        speed = np.broadcast_to(metrics.stage_speed[self.stage], (n,))
        force = np.broadcast_to(metrics.load_torque, (n,))
        return screw_checks(self.screw, self.label, speed, force, life, known)


def screw_limits(drive: Drive) -> list[ScrewLimit]:
    """The later limits of the drive's ball screws that have ratings (none otherwise)."""
    labels = stage_labels(drive)
    out = []
    for i in range(len(drive.stages)):
        screw = screw_ratings(drive, i)
        if screw is not None and (screw.has_shaft_checks or screw.has_life_check):
            out.append(ScrewLimit(screw, i, labels[i]))
    return out


@dataclass(frozen=True)
class GearboxLifeLimit(CycleLimit):
    """The output bearing life check of the gearbox at stage ``stage - 1``, loaded by the
    stage ``stage`` on its output shaft (its ``load``), as a later limit of the search."""

    load: ShaftLoad
    stage: int

    def force(self, outputs: list[np.ndarray]) -> np.ndarray:
        """The force on the gearbox's output (N) at the samples: from its output torque,
        or a screw's axial force (module docstring)."""
        forces = shaft_forces(self.load, outputs[self.stage - 1], outputs[self.stage])
        figure = forces.axial if self.load.kind == "screw" else forces.radial
        assert figure is not None
        return figure

    def checks(self, calculator: CycleModel, s: np.ndarray, metrics: CycleMetrics,
               known: np.ndarray) -> list[CheckArrays]:
        n = len(s)
        limit = np.broadcast_to(gearbox_life_rating(calculator.drive, self.stage, self.load),
                                (n,))
        value = np.zeros(n)
        rows = np.flatnonzero(known & np.isfinite(limit))
        if rows.size:
            value[rows] = mean_cubic_load(calculator.take(rows), s[rows], self.force).mean
        return [gearbox_life_check(self.load, value, limit)]


def gearbox_life_limits(drive: Drive) -> list[GearboxLifeLimit]:
    """The later limits of the gearboxes' output bearing lives: one per stage on a
    gearbox's output shaft where some candidate's gearbox rates the force it puts there
    for a bearing life (none otherwise; sizer.sizing.checks.shaft_notes says which)."""
    out = []
    for i, load in gearbox_output_loads(drive):
        _, rating = gearbox_life_kind(load)
        if any(getattr(t.stages[i - 1], rating) is not None for t in drive.transmissions):
            out.append(GearboxLifeLimit(load, i))
    return out
