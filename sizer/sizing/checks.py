"""The checks of sec. 6.1.1 with their margins, for many candidates at once.

- speed: the peak speed against the highest speed of the intermittent region;
- peak: every point (|speed(t)|, |torque(t)|) inside the intermittent region;
- rms: the RMS torque against the continuous region at the thermal speed (max speed by
  default as in the book; rms or mean speed on request), and that speed inside it;
- inertia ratio (by default everything the motor drives, reflected to it, over the rotor
  inertia, as vendors define it; ``inertia_ratio_of: load`` for the load alone), load
  speed, load acceleration and load jerk against the user's limits.

Every check's name is listed once (:class:`CheckName`); the kinds evaluated here from a
cycle model's metrics are :data:`CHECKS` and :data:`STAGE_CHECKS`, those evaluated by their
own code (catalog figures, whole-cycle figures, a linkage's rules) are :data:`OWN_CHECKS`.
Every verdict is decided here, with one tolerance: a check passes when
margin >= required - TOLERANCE, i.e. value <= (1 - required + TOLERANCE) * limit. A
requirement exactly equal to a rating (a motor run exactly at its rated speed) passes
although rounding leaves it one ulp above; a requirement 1e-6 (relative) above fails.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from enum import StrEnum
from functools import cached_property
from typing import Any

import numpy as np

from sizer.mechanics import Drive
from sizer.mechanics.stages import BallScrewStage, ScrewRatings
from sizer.model.domain import Limits, Motor, RatioChoice, ShaftLoad, Transmission
from sizer.sizing.candidates import MotorArrays
from sizer.sizing.evaluation import CycleMetrics

TOLERANCE = 1e-9
"""Relative tolerance of every check: value <= (1 - required + TOLERANCE) * limit passes."""


class CheckName(StrEnum):
    """The name of every check but the stages' (``<stage>_<suffix>``: :data:`STAGE_CHECKS`),
    as results and reports show it."""

    SPEED = "speed"
    PEAK = "peak"
    RMS = "rms"
    THERMAL_SPEED = "thermal_speed"
    INERTIA_RATIO = "inertia_ratio"
    LOAD_SPEED = "load_speed"
    ACCELERATION = "acceleration"
    JERK = "jerk"
    HOLDING_BRAKE = "holding_brake"
    DRIVE_PEAK_CURRENT = "drive_peak_current"
    DRIVE_RMS_CURRENT = "drive_rms_current"
    RESIDUAL_VIBRATION = "residual_vibration"
    BRAKING_RESISTOR_POWER = "braking_resistor_power"
    WINDING_TEMPERATURE_RISE = "winding_temperature_rise"
    DEAD_POINT = "dead_point"
    PRESSURE_ANGLE = "pressure_angle"
    CAM_CURVATURE = "cam_curvature"
    CAM_CONTACT = "cam_contact"
    SHAFT_RADIAL = "shaft_radial"
    SHAFT_AXIAL = "shaft_axial"
    GEARBOX_RADIAL = "gearbox_radial"
    GEARBOX_AXIAL = "gearbox_axial"
    GEARBOX_RADIAL_LIFE = "gearbox_radial_life"
    GEARBOX_AXIAL_LIFE = "gearbox_axial_life"


@dataclass(frozen=True, eq=False)
class CheckArrays:
    """One check for all candidates: value, limit, margin = 1 - value/limit, required.

    ``applies`` (None: everywhere) marks the candidates the check is part of: a catalog
    gearbox without a torque rating has no rating check. Where it does not apply the
    slack is +inf (it never binds) and the result rows omit it.
    """

    name: str
    value: np.ndarray
    limit: np.ndarray
    unit: str
    required: float
    applies: np.ndarray | None = None
    notes: np.ndarray | None = None
    """Per candidate, why the check fails when a number does not say it (a law that
    breaks a linkage's dead-point rule: which rule, and when); None: no notes."""

    @cached_property
    def margin(self) -> np.ndarray:
        with np.errstate(divide="ignore", invalid="ignore"):
            margin = 1.0 - self.value / self.limit
        return np.where(self.limit > 0.0, margin, np.where(self.value > 0.0, -np.inf, 1.0))

    @cached_property
    def slack(self) -> np.ndarray:
        slack = self.margin - self.required
        if self.applies is not None:
            slack = np.where(self.applies, slack, np.inf)
        return slack

    def take(self, index: np.ndarray) -> CheckArrays:
        """The check of the candidates at ``index``."""
        return CheckArrays(self.name, _pick(self.value, index), _pick(self.limit, index),
                           self.unit, self.required,
                           None if self.applies is None else _pick(self.applies, index),
                           None if self.notes is None else _pick(self.notes, index))

    @property
    def passed(self) -> np.ndarray:
        """The verdict per candidate: slack >= -TOLERANCE."""
        return self.slack >= -TOLERANCE


@dataclass(frozen=True)
class CheckInput:
    """What a check reads: the candidates' requirements, motors, drive and the limits."""

    metrics: CycleMetrics
    motors: MotorArrays
    drive: Drive
    limits: Limits
    linear: bool

    @cached_property
    def ones(self) -> np.ndarray:
        return np.ones_like(self.metrics.duration)

    @property
    def axis_unit(self) -> str:
        return "m" if self.linear else "rad"


@dataclass(frozen=True)
class CheckKind:
    """A check of the registry: its name, unit, value, limit and required margin.

    ``given`` says whether a design has the check at all (a user limit left out, no
    inertia ratio bound); value and limit are arrays over the candidates.
    """

    name: CheckName
    unit: Callable[[CheckInput], str]
    value: Callable[[CheckInput], np.ndarray]
    limit: Callable[[CheckInput], np.ndarray]
    required: Callable[[Limits], float]
    given: Callable[[Limits], bool] = lambda limits: True

    def evaluate(self, x: CheckInput) -> CheckArrays:
        return CheckArrays(self.name, self.value(x), self.limit(x), self.unit(x),
                           self.required(x.limits))


def _inertia_ratio(x: CheckInput) -> np.ndarray:
    with np.errstate(divide="ignore"):
        return x.drive.inertia_ratio_numerator(x.limits.inertia_ratio_of) / x.motors.inertia


def _speed_margin(limits: Limits) -> float:
    return limits.speed_margin


def _torque_margin(limits: Limits) -> float:
    return limits.torque_margin


def _none(limits: Limits) -> float:
    return 0.0


CHECKS: tuple[CheckKind, ...] = (
    CheckKind(CheckName.SPEED, lambda x: "rad/s", lambda x: x.metrics.max_speed,
              lambda x: x.motors.speed_limit, _speed_margin),
    CheckKind(CheckName.PEAK, lambda x: "", lambda x: x.metrics.peak_ratio, lambda x: x.ones,
              _torque_margin),
    CheckKind(CheckName.RMS, lambda x: "N*m", lambda x: x.metrics.rms_torque,
              lambda x: x.motors.continuous.limit_clipped(x.metrics.thermal_speed),
              _torque_margin),
    CheckKind(CheckName.THERMAL_SPEED, lambda x: "rad/s", lambda x: x.metrics.thermal_speed,
              lambda x: x.motors.continuous.max_speed, _speed_margin),
    CheckKind(CheckName.INERTIA_RATIO, lambda x: "", _inertia_ratio,
              lambda x: x.limits.inertia_ratio * x.ones, _none,
              lambda limits: limits.inertia_ratio is not None),
    CheckKind(CheckName.LOAD_SPEED, lambda x: f"{x.axis_unit}/s",
              lambda x: x.metrics.load_speed,
              lambda x: x.limits.max_speed * x.ones, _none,
              lambda limits: limits.max_speed is not None),
    CheckKind(CheckName.ACCELERATION, lambda x: f"{x.axis_unit}/s^2",
              lambda x: x.metrics.load_acceleration,
              lambda x: x.limits.max_acceleration * x.ones, _none,
              lambda limits: limits.max_acceleration is not None),
    CheckKind(CheckName.JERK, lambda x: f"{x.axis_unit}/s^3", lambda x: x.metrics.load_jerk,
              lambda x: x.limits.max_jerk * x.ones, _none,
              lambda limits: limits.max_jerk is not None),
)
"""The checks of sec. 6.1.1 and the user's load limits, in the order results list them;
then the stage checks (:data:`STAGE_CHECKS`), per stage."""


@dataclass(frozen=True)
class StageCheckKind:
    """A rating of a transmission stage checked like the motor's: ``rating`` names the
    Stage field, ``metric`` the CycleMetrics list of per-stage values."""

    suffix: str
    rating: str
    metric: str
    torque: bool
    required: Callable[[Limits], float]


STAGE_CHECKS: tuple[StageCheckKind, ...] = (
    StageCheckKind("speed", "max_input_speed", "stage_speed", False, _speed_margin),
    StageCheckKind("rms", "rated_output_torque", "stage_rms", True, _torque_margin),
    StageCheckKind("peak", "peak_output_torque", "stage_peak", True, _torque_margin),
)
"""Per stage: input speed, RMS and peak output torque against its ratings."""

SCREW_CRITICAL_SPEED = "critical_speed"
SCREW_BUCKLING = "buckling"
SCREW_AXIAL_LOAD = "axial_load"
SCREW_LIFE = "life"
SCREW_CHECKS: tuple[str, ...] = (SCREW_CRITICAL_SPEED, SCREW_BUCKLING, SCREW_AXIAL_LOAD,
                                 SCREW_LIFE)
"""The suffixes of a ball screw's own checks (``<stage>_<suffix>``), where its ratings
give them (sizer.mechanics.stages.ScrewRatings, docs/ball-screws.md), with no further
margin (the makers' safety factors are in the limits):

- ``critical_speed``: the screw's peak speed against speed_factor x its critical speed
  (rad/s);
- ``buckling``: the peak |axial force| (the load's force u, the screw being the last stage;
  dwells holding the load included) against buckling_factor x its Euler buckling load (N);
- ``axial_load``: the same force against the root section's permissible tensile-compressive
  load (THK's P_2 = 116 d_1^2 N);
- ``life``: the required life against the L10 life from the cycle's mean cubic axial load
  and mean speed (s).

They are made by :func:`screw_checks` and evaluated as a later limit of the search
(sizer.sizing.stage_life), after the checks of the cycle."""


@dataclass(frozen=True)
class OwnCheckKind:
    """A kind of the registry whose value and limit its own code computes: its name and
    unit (``linear_unit`` where a linear axis has another); :meth:`arrays` makes the
    check of its value, limit and required margin, as every kind's (slack, verdict)."""

    name: CheckName
    unit: str
    linear_unit: str | None = None

    def arrays(self, value: np.ndarray, limit: np.ndarray, required: float,
               applies: np.ndarray | None = None, notes: np.ndarray | None = None,
               linear: bool = False) -> CheckArrays:
        unit = self.linear_unit if linear and self.linear_unit is not None else self.unit
        return CheckArrays(self.name, value, limit, unit, required, applies, notes)


HOLDING_BRAKE = OwnCheckKind(CheckName.HOLDING_BRAKE, "N*m")
"""A brake variant's holding torque (:func:`holding_brake_check`)."""
DRIVE_PEAK_CURRENT = OwnCheckKind(CheckName.DRIVE_PEAK_CURRENT, "A")
DRIVE_RMS_CURRENT = OwnCheckKind(CheckName.DRIVE_RMS_CURRENT, "A")
"""A drive's peak and continuous currents (:func:`drive_checks`)."""
RESIDUAL_VIBRATION = OwnCheckKind(CheckName.RESIDUAL_VIBRATION, "rad", "m")
"""The worst residual vibration at the load (sizer.sizing.vibration_check)."""
BRAKING_RESISTOR_POWER = OwnCheckKind(CheckName.BRAKING_RESISTOR_POWER, "W")
"""The braking resistor's mean power (sizer.sizing.energy_check)."""
WINDING_TEMPERATURE_RISE = OwnCheckKind(CheckName.WINDING_TEMPERATURE_RISE, "K")
"""The winding's temperature rise (sizer.sizing.energy_check)."""
DEAD_POINT = OwnCheckKind(CheckName.DEAD_POINT, "")
"""A linkage's dead-point rules (sizer.sizing.linkage_move)."""
PRESSURE_ANGLE = OwnCheckKind(CheckName.PRESSURE_ANGLE, "rad")
CAM_CURVATURE = OwnCheckKind(CheckName.CAM_CURVATURE, "m")
CAM_CONTACT = OwnCheckKind(CheckName.CAM_CONTACT, "N")
"""A disc cam's checks (:func:`cam_checks`, docs/disc-cams.md)."""
SHAFT_RADIAL = OwnCheckKind(CheckName.SHAFT_RADIAL, "N")
SHAFT_AXIAL = OwnCheckKind(CheckName.SHAFT_AXIAL, "N")
"""The loads on the motor's shaft against its catalog ratings (:func:`shaft_checks`)."""
GEARBOX_RADIAL = OwnCheckKind(CheckName.GEARBOX_RADIAL, "N")
GEARBOX_AXIAL = OwnCheckKind(CheckName.GEARBOX_AXIAL, "N")
"""The loads on a gearbox's output shaft against its ratings (:func:`shaft_checks`)."""
GEARBOX_RADIAL_LIFE = OwnCheckKind(CheckName.GEARBOX_RADIAL_LIFE, "N")
GEARBOX_AXIAL_LIFE = OwnCheckKind(CheckName.GEARBOX_AXIAL_LIFE, "N")
"""The equivalent (mean cubic) load on a gearbox's output shaft over the cycle against the
force its maker rates for a bearing life (:func:`gearbox_life_check`,
sizer.sizing.stage_life)."""
OWN_CHECKS = (HOLDING_BRAKE, DRIVE_PEAK_CURRENT, DRIVE_RMS_CURRENT, RESIDUAL_VIBRATION,
              BRAKING_RESISTOR_POWER, WINDING_TEMPERATURE_RISE, DEAD_POINT, PRESSURE_ANGLE,
              CAM_CURVATURE, CAM_CONTACT, SHAFT_RADIAL, SHAFT_AXIAL, GEARBOX_RADIAL,
              GEARBOX_AXIAL, GEARBOX_RADIAL_LIFE, GEARBOX_AXIAL_LIFE)
"""The kinds evaluated by their own code, in the order results list them."""


def evaluate_checks(metrics: CycleMetrics, motors: MotorArrays, drive: Drive,
                    limits: Limits, linear: bool = False) -> list[CheckArrays]:
    """All checks of the registry that the design has, for the candidates of ``metrics``."""
    x = CheckInput(metrics, motors, drive, limits, linear)
    checks = [kind.evaluate(x) for kind in CHECKS if kind.given(limits)]
    checks.extend(stage_checks(x))
    checks.extend(drive_checks(x))
    brake = holding_brake_check(x)
    if brake is not None:
        checks.append(brake)
    checks.extend(cam_checks(x))
    checks.extend(shaft_checks(x))
    return checks


SHAFT_RATINGS = ((SHAFT_RADIAL, "radial_load", "radial"), (SHAFT_AXIAL, "axial_load", "axial"))
"""Each shaft check, the Motor rating it reads and the ShaftForces figure it checks."""
GEARBOX_RATINGS = ((GEARBOX_RADIAL, "output_radial_load", "radial"),
                   (GEARBOX_AXIAL, "output_axial_load", "axial"))
"""Each gearbox output shaft check, the gearbox Stage rating it reads and the ShaftForces
figure it checks."""
GEARBOX_LIFE_RATINGS = ((GEARBOX_RADIAL_LIFE, "output_radial_load_life", "radial"),
                        (GEARBOX_AXIAL_LIFE, "output_axial_load_life", "axial"))
"""Each gearbox output bearing life check, the rating it reads (the force the maker rates
for the bearing life ``output_load_life``) and the figure it checks."""


def shaft_checks(x: CheckInput) -> list[CheckArrays]:
    """The loads a stage puts on the shaft it sits on (its ``shaft_load``: a belt's
    pretension and pull, a pinion's tooth force, a directly coupled ball screw's axial
    force; sizer.mechanics.shaft_loads) against that shaft's ratings, with no further
    margin (the makers' ratings are the limits):

    - ``shaft_radial``, ``shaft_axial``: the first stage on the motor's shaft, against the
      motor's catalog ``radial_load`` and ``axial_load`` (N), for the motor's peak |torque|
      of the cycle;
    - ``gearbox_radial``, ``gearbox_axial``: a stage on the output shaft of the gearbox
      right before it, against that gearbox's ``output_radial_load`` and
      ``output_axial_load`` (N), for the gearbox's peak |output torque| of the cycle
      (their bearing life checks over the whole cycle: sizer.sizing.stage_life).

    A screw's force is the load's peak |force| (the screw being the last stage). A check
    applies to the candidates whose motor (gearbox) gives the rating; none where none
    gives it or no stage loads the shaft (:func:`shaft_notes` says which)."""
    from sizer.mechanics.shaft_loads import shaft_forces

    out = []
    load = first_shaft_load(x.drive)
    if load is not None:
        forces = shaft_forces(load, x.metrics.peak_torque, x.metrics.load_torque)
        for kind, rating, figure in SHAFT_RATINGS:
            out.extend(_rated(kind, getattr(forces, figure), _motor_rating(x.motors, rating),
                              x.ones))
    for i, load in gearbox_output_loads(x.drive):
        forces = shaft_forces(load, x.metrics.stage_peak[i - 1], x.metrics.load_torque)
        for kind, rating, figure in GEARBOX_RATINGS:
            out.extend(_rated(kind, getattr(forces, figure),
                              _gearbox_rating(x.drive, i - 1, rating), x.ones))
    return out


def gearbox_output_loads(drive: Drive) -> list[tuple[int, ShaftLoad]]:
    """Each stage ``i`` on the output shaft of the gearbox ``i - 1`` and its load, where the
    engine computes the stages' output torques (:func:`stage_peaks_computed`)."""
    if not stage_peaks_computed(drive.stages):
        return []
    return [(i, s.shaft_load) for i, s in enumerate(drive.transmission.stages)
            if i > 0 and s.shaft_load is not None and s.shaft_load.shaft == "gearbox"]


def gearbox_life_kind(load: ShaftLoad) -> tuple[OwnCheckKind, str]:
    """The bearing life check a stage's ``load`` on a gearbox's output shaft makes
    (``gearbox_axial_life`` for a ball screw's thrust, else ``gearbox_radial_life``) and the
    gearbox rating it reads."""
    kind, rating, _ = GEARBOX_LIFE_RATINGS[1 if load.kind == "screw" else 0]
    return kind, rating


def gearbox_life_rating(drive: Drive, i: int, load: ShaftLoad) -> np.ndarray:
    """The force the gearbox before stage ``i`` (loaded by ``load``) is rated for over its
    bearing life, per candidate (N; NaN: not rated)."""
    return _gearbox_rating(drive, i - 1, gearbox_life_kind(load)[1])


def gearbox_life_check(load: ShaftLoad, value: np.ndarray, limit: np.ndarray) -> CheckArrays:
    """``gearbox_radial_life`` or ``gearbox_axial_life``: the cycle's equivalent force on the
    gearbox's output ``value`` (N, sizer.sizing.stage_life) against the rated ``limit``
    (NaN: not rated, the check does not apply), with no further margin."""
    kind, _ = gearbox_life_kind(load)
    has = np.isfinite(limit)
    return kind.arrays(value, np.where(has, limit, 1.0), 0.0, None if has.all() else has.copy())


def stage_peaks_computed(stages: Sequence[Any]) -> bool:
    """Whether the engine computes the stages' peak output torques: where a stage has a
    torque rating (sizer.sizing.move.CycleCalculator.stage_checks, the same rule), else
    they are left at zero and no gearbox output shaft check is made (:func:`shaft_notes`
    says so)."""
    return any(s.rated_output_torque is not None or s.peak_output_torque is not None
               for s in stages)


def _rated(kind: OwnCheckKind, force: np.ndarray | None, limit: np.ndarray,
           ones: np.ndarray) -> list[CheckArrays]:
    """The check of ``force`` against the rating ``limit`` (NaN: not rated) where a
    candidate is rated; none without a force or a rated candidate."""
    limit = np.broadcast_to(limit, ones.shape)
    has = np.isfinite(limit)
    if force is None or not has.any():
        return []
    return [kind.arrays(np.broadcast_to(force, ones.shape).copy(), np.where(has, limit, 1.0),
                        0.0, None if has.all() else has)]


def first_shaft_load(drive: Drive) -> ShaftLoad | None:
    """The first stage's load on the motor's shaft (None: none known)."""
    return first_shaft_load_of(drive.transmission)


def _motor_rating(motors: MotorArrays, name: str) -> np.ndarray:
    """A motor rating per candidate, NaN where its catalog leaves it out."""
    column = np.array([np.nan if (v := getattr(m, name)) is None else v
                       for m in motors.catalog], dtype=float)
    return column[motors.index]


def _gearbox_rating(drive: Drive, i: int, name: str) -> np.ndarray:
    """The rating ``name`` of stage ``i`` (a gearbox) per candidate (each candidate's
    transmission option: a catalog gearbox), NaN where it is not rated."""
    column = np.array([np.nan if (v := getattr(t.stages[i], name)) is None else v
                       for t in drive.transmissions], dtype=float)
    return column if drive.option is None else column[drive.option]


def _listed(names: Sequence[str]) -> str:
    return ", ".join(names[:5]) + (f" and {len(names) - 5} more" if len(names) > 5 else "")


def shaft_notes(motors: Sequence[Motor], transmission: Transmission,
                choice: RatioChoice | None = None, sampled: bool = True) -> list[str]:
    """What the shaft checks left out: the motors (gearboxes: the design's, or with
    ``choice`` its catalog's) whose catalogs give no rating for a load a stage puts on the
    shaft (no guessed limit: no check); without ``sampled`` (a design through a linkage:
    sizer.sizing.stage_life does not sample its cycle's stage forces, its samples are the
    output's) the gearbox output bearing life checks."""
    stages = transmission.stages
    out: list[str] = []
    load = first_shaft_load_of(transmission)
    if load is not None:
        for _, rating, figure in SHAFT_RATINGS:
            if (figure == "axial") != (load.kind == "screw"):
                continue
            missing = [m.id for m in motors if getattr(m, rating) is None]
            if missing:
                out.append(f"no shaft_{figure} check for {_listed(missing)}: the catalog "
                           f"gives no {rating}")
    for i, stage in enumerate(stages):
        load = stage.shaft_load
        if load is None or load.shaft != "gearbox" or i == 0:
            continue
        if choice is not None and choice.stage == i - 1 and choice.gearboxes:
            boxes = [(g.gearbox, g.stage) for g in choice.gearboxes]
        else:
            boxes = [(stages[i - 1].name or "the gearbox", stages[i - 1])]
        options = [*stages, *(box for _, box in boxes)]
        if not stage_peaks_computed(options):
            out.append("no gearbox_radial or gearbox_axial check: the gearbox's output "
                       "torque is computed where a stage has a torque rating (give the "
                       "gearbox its rated_output_torque or peak_output_torque)")
            continue
        for kind, rating, figure in (*GEARBOX_RATINGS, *GEARBOX_LIFE_RATINGS):
            if (figure == "axial") != (load.kind == "screw"):
                continue
            if kind in (GEARBOX_RADIAL_LIFE, GEARBOX_AXIAL_LIFE) and not sampled:
                if any(getattr(box, rating) is not None for _, box in boxes):
                    out.append(f"no {kind.name} check: the cycle's forces on the gearbox's "
                               f"output are not sampled through a linkage")
                continue
            missing = list(dict.fromkeys(
                name.split(" i=")[0] for name, box in boxes if getattr(box, rating) is None))
            if missing:
                out.append(f"no {kind.name} check for {_listed(missing)}: its ratings "
                           f"give no {rating}")
    return out


def first_shaft_load_of(transmission: Transmission) -> ShaftLoad | None:
    """The first stage's load on the motor's shaft of ``transmission`` (None: none)."""
    stages = transmission.stages
    load = stages[0].shaft_load if stages else None
    return load if load is not None and load.shaft == "motor" else None


def cam_checks(x: CheckInput) -> list[CheckArrays]:
    """A disc cam's checks (sizer.mechanics.disc_cam), the same for every candidate (the
    cam's geometry and speed are the design's, per law), with no further margin:

    - ``pressure_angle``: the largest |phi| over the turn against the design's limit (rad);
    - ``cam_curvature``: the roller's radius against the pitch curve's smallest radius of
      curvature where convex (m): the roller does not undercut the cam when it is smaller;
    - ``cam_contact`` (a force-closed follower): the spring preload the contact needs at
      the design speed (the follower never leaves the cam) against the given preload (N).

    None for a design without a cam."""
    stage = x.drive.transmission.linkage
    if stage is None:  # no linkage: the cam's module is not even imported
        return []
    from sizer.mechanics.disc_cam import CamStage

    if not isinstance(stage, CamStage) or stage.figures is None:
        return []
    f, ones = stage.figures, x.ones
    out = [PRESSURE_ANGLE.arrays(f.max_pressure_angle * ones, stage.pressure_angle * ones,
                                 0.0),
           CAM_CURVATURE.arrays(stage.roller_radius * ones, f.min_convex_radius * ones, 0.0)]
    if stage.force_closed:
        out.append(CAM_CONTACT.arrays(max(f.needed_preload, 0.0) * ones,
                                      stage.spring_preload * ones, 0.0))
    return out


def holding_brake_check(x: CheckInput) -> CheckArrays | None:
    """A brake variant's holding torque against the torque that holds the constant load at
    rest (a vertical axis, a constant force), at the motor shaft through the transmission
    and counted as driving (divided by the efficiencies: conservative), with the torque
    margin. None where no candidate's motor has a brake or nothing is held."""
    brake = x.motors.brake_torque
    has = np.isfinite(brake)
    if not has.any() or x.drive.figures.none("torque"):
        return None
    hold = np.broadcast_to(x.drive.holding_torque, x.ones.shape)
    return HOLDING_BRAKE.arrays(hold, np.where(has, brake, 1.0), x.limits.torque_margin,
                                None if has.all() else has.copy())


DRIVE_CHECKS = (CheckName.DRIVE_PEAK_CURRENT, CheckName.DRIVE_RMS_CURRENT)
"""The checks of a candidate's drive (sizer.sizing.candidates): the current its peak and its
RMS torque need (through the motor's k_t or torque-current curve) against the drive's peak
and continuous currents, with the margin ``limits.drive_current_margin``."""


def drive_checks(x: CheckInput) -> list[CheckArrays]:
    """The drive's current checks, for candidates with drives (none without)."""
    motors = x.motors
    if motors.drive is None or motors.currents is None:
        return []
    required = x.limits.drive_current_margin
    peak = motors.currents.current(np.broadcast_to(x.metrics.peak_torque, x.ones.shape))
    rms = motors.currents.current(np.broadcast_to(x.metrics.rms_torque, x.ones.shape))
    return [DRIVE_PEAK_CURRENT.arrays(peak, motors.peak_current, required),
            DRIVE_RMS_CURRENT.arrays(rms, motors.continuous_current, required)]


def stage_labels(drive: Drive) -> list[str]:
    """A name per stage: its own name, else its kind (numbered when kinds repeat)."""
    kinds = [s.name or s.kind for s in drive.stages]
    return [k if kinds.count(k) == 1 else f"{k}{i + 1}" for i, k in enumerate(kinds)]


def stage_checks(x: CheckInput) -> list[CheckArrays]:
    """The ratings of the transmission stages (:data:`STAGE_CHECKS`) that are given."""
    checks = []
    last = len(x.drive.stages) - 1
    for i, (stage, label) in enumerate(zip(x.drive.stages, stage_labels(x.drive), strict=True)):
        for kind in STAGE_CHECKS:
            rating = getattr(stage, kind.rating)
            if rating is None:
                continue
            unit = ("N" if x.linear and i == last else "N*m") if kind.torque else "rad/s"
            checks.append(CheckArrays(f"{label}_{kind.suffix}", getattr(x.metrics, kind.metric)[i],
                                      rating * x.ones, unit, kind.required(x.limits),
                                      _applies(stage.rated[kind.rating], x.ones)))
    return checks


def screw_checks(screw: ScrewRatings, label: str, speed: np.ndarray, force: np.ndarray,
                 life: np.ndarray | None, known: np.ndarray) -> list[CheckArrays]:
    """The checks of a ball screw with its ratings (:data:`SCREW_CHECKS`, those it has), for
    the candidates' peak screw ``speed`` (rad/s), peak |axial ``force``| (N) and L10
    ``life`` (s); where not ``known`` (no scale) they pass with value 0."""
    checks = []
    if screw.has_shaft_checks:
        checks += [CheckArrays(f"{label}_{SCREW_CRITICAL_SPEED}", np.where(known, speed, 0.0),
                               np.full(known.shape, screw.permissible_speed), "rad/s", 0.0),
                   CheckArrays(f"{label}_{SCREW_BUCKLING}", np.where(known, force, 0.0),
                               np.full(known.shape, screw.permissible_buckling_load), "N", 0.0),
                   CheckArrays(f"{label}_{SCREW_AXIAL_LOAD}", np.where(known, force, 0.0),
                               np.full(known.shape, screw.permissible_tensile_compressive_load),
                               "N", 0.0)]
    if screw.has_life_check:
        assert life is not None and screw.required_life is not None
        checks.append(CheckArrays(f"{label}_{SCREW_LIFE}",
                                  np.where(known, screw.required_life, 0.0),
                                  np.where(known, life, np.inf), "s", 0.0))
    return checks


def screw_ratings(drive: Drive, i: int) -> ScrewRatings | None:
    """The ratings of stage ``i`` if it is a ball screw that has them (a screw is never a
    free-ratio stage: every transmission option has the same one)."""
    stage = drive.transmission.stages[i]
    return stage.screw if isinstance(stage, BallScrewStage) else None


def _applies(rated: np.ndarray, ones: np.ndarray) -> np.ndarray | None:
    """None where every candidate is rated, else the mask broadcast over candidates."""
    if bool(np.all(rated)):
        return None
    return np.broadcast_to(rated, ones.shape).copy()


def _pick(x: np.ndarray, index: np.ndarray) -> np.ndarray:
    return x if np.ndim(x) == 0 or len(x) == 1 else x[index]


def worst_slack(checks: list[CheckArrays]) -> np.ndarray:
    """min over checks of margin - required, per candidate (see :func:`feasible`)."""
    return np.min(np.stack([c.slack for c in checks]), axis=0)


def feasible(checks: list[CheckArrays]) -> np.ndarray:
    """Every check passes, per candidate: worst slack >= -TOLERANCE."""
    return worst_slack(checks) >= -TOLERANCE


def limiting_index(checks: list[CheckArrays]) -> np.ndarray:
    """Index of the binding check (smallest slack) per candidate.

    A drive check within TOLERANCE of the smallest slack is named before the motor check
    it ties with: the drive's torque clips the motor's region, so the peak (or RMS) check
    and the drive's current check then bind together, and the drive is the cause.
    """
    slack = np.stack([c.slack for c in checks])
    best = np.argmin(slack, axis=0)
    for k, check in enumerate(checks):
        if check.name in DRIVE_CHECKS:
            lowest = slack[best, np.arange(slack.shape[1])]
            tie = slack[k] <= lowest + TOLERANCE * np.maximum(1.0, np.abs(lowest))
            best = np.where(tie & (slack[best, np.arange(slack.shape[1])] < np.inf)
                            & ~np.isin(best, _drive_positions(checks)), k, best)
    return best


def _drive_positions(checks: list[CheckArrays]) -> np.ndarray:
    return np.array([k for k, c in enumerate(checks) if c.name in DRIVE_CHECKS], dtype=np.intp)


def dead_point_check(issues: tuple[str, ...], n: int) -> CheckArrays:
    """``dead_point``: passes when the law meets the paper's rule at every dead point
    the output reaches; else fails for every candidate with the reasons as its note."""
    notes = np.full(n, "; ".join(issues), dtype=object) if issues else None
    return DEAD_POINT.arrays(np.full(n, np.inf if issues else 0.0), np.ones(n), 0.0,
                             None, notes)


UNBOUNDED_NOTE = ("unbounded: the crank's acceleration is infinite at the dead point (see "
                  "dead_point)")


def unbounded(check: CheckArrays) -> CheckArrays:
    """A torque check of a law that breaks the dead-point rule: unbounded, saying why."""
    n = len(check.value)
    return replace(check, value=np.full(n, np.inf),
                   notes=np.full(n, UNBOUNDED_NOTE, dtype=object))


UNBOUNDED_CHECKS = ("peak", "rms", "drive_peak_current", "drive_rms_current")
"""The checks of the peak and RMS torques (and the drive's currents they need): unbounded
where a law breaks the dead-point rule."""


def unbounded_checks(checks: list[CheckArrays]) -> list[CheckArrays]:
    """``checks`` with those of the torques unbounded (:func:`unbounded`)."""
    return [unbounded(c) if c.name in UNBOUNDED_CHECKS else c for c in checks]
