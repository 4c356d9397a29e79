"""The candidates of a design as one flat axis: motors x drives x transmission options.

A candidate is a motor with one transmission (the design's, or it with a listed ratio, a
catalog gearbox or a lattice point of a continuous ratio in place). Its figures are the
rows of ``motors`` (:class:`MotorArrays`: motors as arrays, so that every check runs for
all of them at once) and ``drive`` (sizer.mechanics.drive), whatever mixes motors and
options.

Motors with drives (issue 16): a candidate is a motor x a compatible drive. The drive's
current limits become torque limits through the motor's torque constant k_t (or its
torque-current curve, which gives saturation): the intermittent region is clipped at
T(I_peak), the continuous one at T(I_cont), i.e. the motor and drive region is
min(motor curve, drive torque) at every speed. The clipped regions are exact: each segment
crossing the drive's torque gets the crossing as a corner. The checks
``drive_peak_current`` and ``drive_rms_current`` (sizer.sizing.checks) name the drive when
it binds. A drive suits a motor when its ``motors`` list names the motor (an id or an
fnmatch pattern), or, without a list, by rule: the motor gives k_t and the drive's
continuous current covers the motor's (continuous_torque / k_t through the curve).

What the motors of a catalog give is read once per catalog (:func:`catalog_facts`): the
candidate arrays share one tuple of the distinct motors, their ``catalog``, across every
subset, chunk and transmission option. The energy and heat checks read per-motor ratings
from it (thermal time constant, allowed rise, k_t, R) and the motors' own continuous
regions: a Python pass over the catalog, once per evaluation, where a 10,000-motor
catalog is evaluated hundreds of times. Each such column is built on first use and kept
with the catalog (keyed by the tuple's identity, the tuple held so that the identity stays
its own; the last few catalogs).
"""

from __future__ import annotations

import fnmatch
from collections import OrderedDict
from collections.abc import Sequence
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np

from sizer.envelope import RegionTable, continuous_region, intermittent_region
from sizer.envelope.electrical import on_supply
from sizer.errors import UserError
from sizer.mechanics import Drive
from sizer.mechanics.load_figures import LoadFigures
from sizer.model.domain import (
    Curve,
    Design,
    EnvelopeRule,
    Load,
    Motor,
    ServoDrive,
    Transmission,
)
from sizer.numerics.arrays import sorted_unique
from sizer.vibration.elastic_load import ElasticLoad

KEPT = 8
"""Catalogs whose facts are kept (a design has one; tests and loops make more)."""


class CatalogFacts:
    """Columns of one catalog's motors, each built on first use."""

    def __init__(self, catalog: tuple[Motor, ...]) -> None:
        self.catalog = catalog
        self._columns: dict[str, np.ndarray] = {}
        self._regions: dict[str, RegionTable] = {}
        self.heated = any(m.thermal_time_constant is not None
                          and m.max_winding_temperature_rise is not None for m in catalog)
        """Some motor gives its thermal time constant and allowed rise (a heat check)."""

    def column(self, name: str) -> np.ndarray:
        """The motors' rating ``name`` as floats, NaN where a motor leaves it out (read
        only: shared by every caller)."""
        found = self._columns.get(name)
        if found is None:
            found = np.array([np.nan if getattr(m, name) is None else float(getattr(m, name))
                              for m in self.catalog], dtype=float)
            found.setflags(write=False)
            self._columns[name] = found
        return found

    def continuous(self, envelope: EnvelopeRule) -> RegionTable:
        """The motors' own continuous regions (not clipped by a drive), by ``envelope``."""
        found = self._regions.get(envelope)
        if found is None:
            found = self._regions[envelope] = RegionTable(
                [continuous_region(m, envelope) for m in self.catalog])
        return found


_KEPT: OrderedDict[int, CatalogFacts] = OrderedDict()


def catalog_facts(catalog: tuple[Motor, ...]) -> CatalogFacts:
    """The facts of ``catalog`` (a tuple: a list could change; it gets fresh facts)."""
    if not isinstance(catalog, tuple):
        return CatalogFacts(tuple(catalog))
    key = id(catalog)
    found = _KEPT.get(key)
    if found is None or found.catalog is not catalog:
        found = _KEPT[key] = CatalogFacts(catalog)
        while len(_KEPT) > KEPT:
            _KEPT.popitem(last=False)
    else:
        _KEPT.move_to_end(key)
    return found


@dataclass(frozen=True)
class CurrentCurves:
    """Per candidate, torque vs current (A rms -> N*m) as padded piecewise-linear rows,
    extrapolated past both ends along the end segments; a motor without a curve has the
    line torque = k_t * current (the points (0, 0) and (1 A, k_t))."""

    currents: np.ndarray
    torques: np.ndarray

    @classmethod
    def of(cls, motors: Sequence[Motor]) -> CurrentCurves:
        curves = [motor_curve(m) for m in motors]
        width = max(len(c) for c in curves)
        currents = np.empty((len(curves), width))
        torques = np.empty((len(curves), width))
        for row, curve in enumerate(curves):  # per catalog motor, not per candidate
            i = np.array([p[0] for p in curve])
            t = np.array([p[1] for p in curve])
            pad = width - len(curve)
            step = i[-1] - i[-2]
            currents[row] = np.concatenate((i, i[-1] + step * (1.0 + np.arange(pad))))
            slope = (t[-1] - t[-2]) / step
            torques[row] = np.concatenate((t, t[-1] + slope * step * (1.0 + np.arange(pad))))
        return cls(currents, torques)

    def take(self, index: np.ndarray) -> CurrentCurves:
        return CurrentCurves(self.currents[index], self.torques[index])

    def torque(self, current: np.ndarray) -> np.ndarray:
        """The torque of each candidate's motor at ``current`` (one per candidate)."""
        return _interpolate(self.currents, self.torques, np.asarray(current, dtype=float))

    def current(self, torque: np.ndarray) -> np.ndarray:
        """The current each candidate's motor needs for ``torque`` (one per candidate)."""
        return _interpolate(self.torques, self.currents, np.abs(np.asarray(torque, float)))


def motor_curve(motor: Motor) -> tuple[tuple[float, float], ...]:
    """A motor's torque-current curve: its own, or the line of its k_t."""
    if motor.torque_current_curve is not None:
        return motor.torque_current_curve
    if motor.torque_constant is None:
        raise UserError(f"motor {motor.id!r} is paired with a drive but gives no "
                        "torque_constant (N*m/A): the drive's currents become torques "
                        "through it", field="torque_constant")
    return ((0.0, 0.0), (1.0, motor.torque_constant))


def _interpolate(x: np.ndarray, y: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Row-wise piecewise-linear y(q) through (x, y), extrapolated along the end segments."""
    rows = np.arange(len(x))
    k = np.clip((x[:, 1:-1] <= q[:, None]).sum(axis=1), 0, x.shape[1] - 2)
    x0, x1, y0, y1 = x[rows, k], x[rows, k + 1], y[rows, k], y[rows, k + 1]
    return y0 + (y1 - y0) * (q - x0) / (x1 - x0)


def suits(drive: ServoDrive, motor: Motor) -> bool:
    """Whether ``drive`` is a drive for ``motor`` (its list, else the rule)."""
    return bool(compatibility([motor], [drive])[0, 0])


def compatibility(motors: Sequence[Motor], drives: Sequence[ServoDrive]) -> np.ndarray:
    """(motors, drives): whether each drive suits each motor. A listed drive suits the
    motors its patterns match; a drive without a list those with a torque constant whose
    continuous current (tau_c through the motor's curve) its continuous current covers."""
    ids = [m.id for m in motors]
    known = np.array([m.torque_constant is not None or m.torque_current_curve is not None
                      for m in motors], dtype=bool)
    rated = np.full(len(motors), np.inf)
    if known.any():
        which = np.flatnonzero(known)
        chosen = [motors[int(i)] for i in which]
        rated[which] = CurrentCurves.of(chosen).current(
            np.array([m.continuous_torque for m in chosen]))
    out = np.zeros((len(motors), len(drives)), dtype=bool)
    for d, drive in enumerate(drives):  # a loop over the drives, the motors as arrays
        if drive.motors is None:
            out[:, d] = known & (drive.continuous_current >= rated * (1.0 - 1e-12))
        else:
            names = {i for pattern in drive.motors for i in fnmatch.filter(ids, pattern)}
            out[:, d] = np.isin(np.array(ids, dtype=object), list(names))
    return out


def pairs(motors: Sequence[Motor], drives: Sequence[ServoDrive]) -> tuple[np.ndarray,
                                                                         np.ndarray]:
    """(motor index, drive index) of every compatible pair, motor by motor, drives in their
    order; a UserError if there is none."""
    motor, drive = np.nonzero(compatibility(motors, drives))
    if motor.size == 0:
        raise UserError("no motor has a compatible drive: a drive suits the motors its "
                        "`motors:` list names, or (without a list) those with a "
                        "torque_constant whose continuous current it covers",
                        field="drives")
    return motor.astype(np.intp), drive.astype(np.intp)


def clip_region(table: RegionTable, cap: np.ndarray) -> RegionTable:
    """min(region, cap) per row, exactly: every segment gets one more corner, where it
    crosses the cap (or its midpoint, where it does not: the clipped segment is then
    straight)."""
    s, t = table.speeds, table.torques
    c = np.asarray(cap, dtype=float)[:, None]
    s0, s1, t0, t1 = s[:, :-1], s[:, 1:], t[:, :-1], t[:, 1:]
    crosses = (t0 - c) * (t1 - c) < 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        at = s0 + (c - t0) * (s1 - s0) / (t1 - t0)
    middle = np.where(crosses, at, 0.5 * (s0 + s1))
    torque_middle = np.where(crosses, c, t0 + (t1 - t0) * (middle - s0) / (s1 - s0))
    n, width = s.shape
    speeds = np.empty((n, 2 * width - 1))
    torques = np.empty((n, 2 * width - 1))
    speeds[:, 0::2], speeds[:, 1::2] = s, middle
    torques[:, 0::2], torques[:, 1::2] = t, torque_middle
    out = object.__new__(RegionTable)
    out.speeds = speeds
    out.torques = np.minimum(torques, c)
    out.max_speed = table.max_speed.copy()
    return out


@dataclass(frozen=True, eq=False)
class Builds:
    """Each candidate's build of the machine (robust sizing and sensitivities, sizer.robust:
    the builds are rows of one sizing): the load's figures (sizer.mechanics.load_figures;
    None: the design's); where the builds change a stage's figures (a ratio, an
    efficiency) the transmissions and each candidate's (``option``); where they change the
    load's mode, the modes and each candidate's (``mode``: the residual vibration's,
    sizer.sizing.vibration_check.ResidualLimit)."""

    figures: LoadFigures | None = None
    transmissions: tuple[Transmission, ...] = ()
    option: np.ndarray | None = None
    modes: tuple[ElasticLoad | None, ...] = ()
    mode: np.ndarray | None = None

    @classmethod
    def of(cls, builds: Sequence[Design], design: Design) -> Builds:
        """The builds of ``design`` (one per candidate): their loads' figures, and their
        transmissions and modes where one differs from the design's."""
        transmissions, option = _distinct([b.transmission for b in builds],
                                          design.transmission)
        modes, mode = _distinct([b.load.elastic for b in builds], design.load.elastic)
        return cls(LoadFigures.builds([b.load for b in builds]), transmissions, option,
                   modes, mode)

    def take(self, index: np.ndarray) -> Builds:
        return Builds(None if self.figures is None else self.figures.take(index),
                      self.transmissions,
                      None if self.option is None else self.option[index], self.modes,
                      None if self.mode is None else self.mode[index])

    def drive(self, load: Load, transmission: Transmission) -> Drive:
        """The candidates' drive: ``load`` with their figures, through ``transmission``
        (the design's) or their builds' transmissions."""
        if self.transmissions:
            return Drive(load, self.transmissions, self.option, figures=self.figures)
        return Drive(load, transmission, figures=self.figures)


def _distinct(values: list, design_value: object) -> tuple[tuple, np.ndarray | None]:
    """The distinct ``values`` and each one's index among them; nothing where every one is
    the design's own."""
    place = {v: k for k, v in enumerate(dict.fromkeys(values))}
    if list(place) == [design_value]:
        return (), None
    return tuple(place), np.array([place[v] for v in values], dtype=np.intp)


@dataclass(frozen=True)
class MotorArrays:
    """Rotor inertia, damping and speed-torque regions of the candidates' motors.

    ``catalog`` are the distinct motors, ``index`` the motor of each candidate (a motor
    repeats once per transmission option); the arrays are per candidate.

    ``envelope`` is the rule that completed the regions without curves
    (sizer.envelope.completion); ``book`` keeps the book's rectangles.

    With ``drives`` a candidate is a motor with one drive (sizer.sizing.candidates): ``drive``
    indexes ``drives`` per candidate, ``currents`` is each candidate's torque-current
    curve, and the regions are clipped at the drive's torques.

    ``builds``: where each candidate is sized in its own build of the machine (robust
    sizing, sizer.robust): its load's figures and transmission (:class:`Builds`); None:
    the design's for all.

    ``axis``: per candidate its place on an axis its caller laid the motors out along
    (the law of each row where several laws' candidates are sized as one axis:
    sizer.sizing.engine), carried through :meth:`subset`; None: none.
    """

    catalog: tuple[Motor, ...]
    index: np.ndarray
    inertia: np.ndarray
    damping: np.ndarray
    intermittent: RegionTable
    continuous: RegionTable
    envelope: EnvelopeRule = "book"
    drives: tuple[ServoDrive, ...] = ()
    drive: np.ndarray | None = None
    currents: CurrentCurves | None = None
    builds: Builds | None = None
    axis: np.ndarray | None = None

    @classmethod
    def of(cls, motors: Sequence[Motor], envelope: EnvelopeRule = "book",
           drives: Sequence[ServoDrive] = (),
           builds: Builds | None = None) -> MotorArrays:
        """The motors' arrays; with ``drives``, one candidate per compatible motor-drive
        pair, the regions clipped at the drive's torques; ``builds``: per motor its build
        of the machine."""
        alone = cls._alone(tuple(motors), envelope)
        if builds is not None:
            alone = replace(alone, builds=builds)
        if not drives:
            return alone
        return alone.with_drives(tuple(drives))

    @classmethod
    def _alone(cls, motors: tuple[Motor, ...], envelope: EnvelopeRule) -> MotorArrays:
        return cls(
            motors,
            np.arange(len(motors)),
            np.array([m.inertia + m.brake_inertia for m in motors], dtype=float),
            np.array([m.damping for m in motors], dtype=float),
            RegionTable([intermittent_region(m, envelope) for m in motors]),
            RegionTable([continuous_region(m, envelope) for m in motors]),
            envelope,
        )

    def with_drives(self, drives: tuple[ServoDrive, ...]) -> MotorArrays:
        """Every compatible (motor, drive) pair of these motors (one per motor: the
        catalog) as candidates, the regions clipped at T(I_peak) and T(I_cont)."""
        motor, drive = pairs(self.catalog, drives)
        paired = self.subset(motor)
        distinct = sorted_unique(motor)  # the curves once per paired motor, then per pair
        currents = CurrentCurves.of([self.catalog[int(m)] for m in distinct]).take(
            np.searchsorted(distinct, motor))
        peak = np.array([d.peak_current for d in drives])[drive]
        continuous = np.array([d.continuous_current for d in drives])[drive]
        intermittent_table, continuous_table = paired.intermittent, paired.continuous
        if self.envelope == "electrical":
            intermittent_table, continuous_table = self._on_drive_buses(
                drives, motor, drive, paired)
        return MotorArrays(self.catalog, paired.index, paired.inertia, paired.damping,
                           clip_region(intermittent_table, currents.torque(peak)),
                           clip_region(continuous_table, currents.torque(continuous)),
                           self.envelope, drives, drive, currents, paired.builds)

    def _on_drive_buses(self, drives: tuple[ServoDrive, ...], motor: np.ndarray,
                        drive: np.ndarray, paired: MotorArrays
                        ) -> tuple[RegionTable, RegionTable]:
        """The pairs' regions under ``electrical`` with the drive's DC link as the motor's
        supply, where the drive gives one (sizer.envelope.electrical.on_supply); the
        motor's own regions elsewhere."""
        buses = [drives[int(d)].dc_bus_voltage for d in drive]
        if all(bus is None for bus in buses):
            return paired.intermittent, paired.continuous
        found: dict[tuple[int, float | None], tuple[Curve, Curve]] = {}
        for m, bus in zip(motor.tolist(), buses, strict=True):
            if (m, bus) not in found:
                on_bus = on_supply(self.catalog[m], bus)
                found[(m, bus)] = (intermittent_region(on_bus, self.envelope),
                                   continuous_region(on_bus, self.envelope))
        rows = [found[(m, bus)] for m, bus in zip(motor.tolist(), buses, strict=True)]
        return RegionTable([r[0] for r in rows]), RegionTable([r[1] for r in rows])

    @property
    def peak_current(self) -> np.ndarray:
        """Each candidate's drive peak current (A rms)."""
        assert self.drive is not None
        return np.array([d.peak_current for d in self.drives])[self.drive]

    @property
    def continuous_current(self) -> np.ndarray:
        """Each candidate's drive continuous current (A rms)."""
        assert self.drive is not None
        return np.array([d.continuous_current for d in self.drives])[self.drive]

    def __len__(self) -> int:
        return len(self.index)

    @property
    def brake_torque(self) -> np.ndarray:
        """Each candidate's holding-brake torque (N*m; NaN: the motor has no brake)."""
        return catalog_facts(self.catalog).column("brake_holding_torque")[self.index]

    @property
    def motors(self) -> tuple[Motor, ...]:
        """The motor of each candidate."""
        return tuple(self.catalog[int(i)] for i in self.index)


    @property
    def speed_limit(self) -> np.ndarray:
        """Highest speed of the intermittent region (rated speed for the book's rectangles)."""
        return self.intermittent.max_speed

    @cached_property
    def is_rectangular(self) -> np.ndarray:
        """True where both regions are flat up to one common speed (the book's case).

        Read from the regions as completed, so a motor whose regions were extended past
        the rated speed by a falling line is not rectangular (eq. 6.2 does not apply).
        """
        flat_i = np.all(self.intermittent.torques == self.intermittent.torques[:, :1], axis=1)
        flat_c = np.all(self.continuous.torques == self.continuous.torques[:, :1], axis=1)
        return flat_i & flat_c & (self.intermittent.max_speed == self.continuous.max_speed)

    @cached_property
    def flat_speed(self) -> np.ndarray:
        """Speed up to which both regions keep their standstill torque: the rectangle that
        eq. (6.2) sees (the rated speed for a motor whose regions the envelope rule
        extended, the whole region for the book's rectangles)."""
        return np.minimum(_flat_end(self.intermittent), _flat_end(self.continuous))

    @cached_property
    def all_rectangular(self) -> bool:
        return bool(np.all(self.is_rectangular))

    def subset(self, index: np.ndarray) -> MotorArrays:
        """The candidates at the given positions, in that order (repeats allowed)."""
        index = np.asarray(index, dtype=np.intp)
        return MotorArrays(self.catalog, self.index[index], self.inertia[index],
                           self.damping[index], self.intermittent.take(index),
                           self.continuous.take(index), self.envelope, self.drives,
                           None if self.drive is None else self.drive[index],
                           None if self.currents is None else self.currents.take(index),
                           None if self.builds is None else self.builds.take(index),
                           None if self.axis is None else self.axis[index])


def _flat_end(table: RegionTable) -> np.ndarray:
    """Per motor, the speed where the region's torque first leaves its value at rest."""
    same = table.torques == table.torques[:, :1]
    first_change = np.argmin(same, axis=1)  # 0 only where every point is the same
    end = table.speeds[np.arange(len(table)), np.maximum(first_change - 1, 0)]
    return np.where(same.all(axis=1), table.max_speed, np.minimum(end, table.max_speed))


@dataclass(frozen=True)
class Candidates:
    """Per candidate: its motor's figures and its drive's (arrays over candidates)."""

    motors: MotorArrays
    drive: Drive
    gearboxes: tuple[str | None, ...] | None = None
    """The catalog gearbox of each transmission option (None: no names)."""

    def __len__(self) -> int:
        return len(self.motors)

    @classmethod
    def single(cls, motors: MotorArrays, load: Load, transmission: Transmission) -> Candidates:
        """Every motor with the same transmission."""
        if motors.builds is not None:
            return cls(motors, motors.builds.drive(load, transmission))
        return cls(motors, Drive(load, transmission))

    @classmethod
    def pairs(cls, motors: MotorArrays, load: Load, transmissions: Sequence[Transmission],
              motor: np.ndarray, option: np.ndarray,
              gearboxes: tuple[str | None, ...] | None = None) -> Candidates:
        """The candidates (motor[i], transmissions[option[i]]): ``motor`` indexes the
        rows of ``motors``."""
        chosen = motors.subset(motor)
        if chosen.builds is None:
            return cls(chosen, Drive(load, transmissions, option), gearboxes)
        if chosen.builds.transmissions:
            raise ValueError("builds of the transmission are not sized with a ratio choice")
        return cls(chosen, Drive(load, transmissions, option, figures=chosen.builds.figures),
                   gearboxes)

    def take(self, index: np.ndarray) -> Candidates:
        """The candidates at ``index`` (repeats allowed), in that order."""
        index = np.asarray(index, dtype=np.intp)
        return Candidates(self.motors.subset(index), self.drive.take(index), self.gearboxes)

    @property
    def gearbox_names(self) -> tuple[str | None, ...]:
        return self.gearboxes or (None,) * len(self.drive.transmissions)

    @property
    def option(self) -> np.ndarray:
        """The transmission option of each candidate."""
        if self.drive.option is None:
            return np.zeros(len(self), dtype=np.intp)
        return self.drive.option
