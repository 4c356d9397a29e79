"""The checks of sec. 6.1.1 with their margins, for many candidates at once.

- speed: the peak speed against the highest speed of the intermittent region;
- peak: every point (|speed(t)|, |torque(t)|) inside the intermittent region;
- rms: the RMS torque against the continuous region at the thermal speed (max speed by
  default as in the book; rms or mean speed on request), and that speed inside it;
- inertia ratio (by default everything the motor drives, reflected to it, over the rotor
  inertia, as vendors define it; ``inertia_ratio_of: load`` for the load alone), load
  speed, load acceleration and load jerk against the user's limits.

Every verdict is decided here, with one tolerance: a check passes when
margin >= required - TOLERANCE, i.e. value <= (1 - required + TOLERANCE) * limit. A
requirement exactly equal to a rating (a motor run exactly at its rated speed) passes
although rounding leaves it one ulp above; a requirement 1e-6 (relative) above fails.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from sizer.mechanics import Drive
from sizer.model.domain import Limits
from sizer.sizing.cycle import CycleMetrics
from sizer.sizing.motors import MotorArrays

TOLERANCE = 1e-9
"""Relative tolerance of every check: value <= (1 - required + TOLERANCE) * limit passes."""


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
                           None if self.applies is None else _pick(self.applies, index))

    @property
    def passed(self) -> np.ndarray:
        """The verdict per candidate: slack >= -TOLERANCE."""
        return self.slack >= -TOLERANCE


def evaluate_checks(metrics: CycleMetrics, motors: MotorArrays, drive: Drive,
                    limits: Limits, linear: bool = False) -> list[CheckArrays]:
    """All checks for the candidates described by ``metrics``."""
    ones = np.ones_like(metrics.duration)
    checks = [
        CheckArrays("speed", metrics.max_speed, motors.speed_limit, "rad/s", limits.speed_margin),
        CheckArrays("peak", metrics.peak_ratio, ones, "", limits.torque_margin),
        CheckArrays("rms", metrics.rms_torque,
                    motors.continuous.limit_clipped(metrics.thermal_speed), "N*m",
                    limits.torque_margin),
        CheckArrays("thermal_speed", metrics.thermal_speed, motors.continuous.max_speed,
                    "rad/s", limits.speed_margin),
    ]
    if limits.inertia_ratio is not None:
        with np.errstate(divide="ignore"):
            ratio = drive.inertia_ratio_numerator(limits.inertia_ratio_of) / motors.inertia
        checks.append(CheckArrays("inertia_ratio", ratio, limits.inertia_ratio * ones, "", 0.0))
    unit = "m" if linear else "rad"
    if limits.max_speed is not None:
        checks.append(CheckArrays("load_speed", metrics.load_speed,
                                  limits.max_speed * ones, f"{unit}/s", 0.0))
    if limits.max_acceleration is not None:
        checks.append(CheckArrays("acceleration", metrics.load_acceleration,
                                  limits.max_acceleration * ones, f"{unit}/s^2", 0.0))
    if limits.max_jerk is not None:
        checks.append(CheckArrays("jerk", metrics.load_jerk, limits.max_jerk * ones,
                                  f"{unit}/s^3", 0.0))
    checks.extend(stage_checks(metrics, drive, limits, linear))
    return checks


def stage_labels(drive: Drive) -> list[str]:
    """A name per stage: its own name, else its kind (numbered when kinds repeat)."""
    kinds = [s.name or s.kind for s in drive.stages]
    return [k if kinds.count(k) == 1 else f"{k}{i + 1}" for i, k in enumerate(kinds)]


def stage_checks(metrics: CycleMetrics, drive: Drive, limits: Limits,
                 linear: bool) -> list[CheckArrays]:
    """Limits of the transmission stages: input speed, RMS and peak output torque."""
    ones = np.ones_like(metrics.duration)
    checks = []
    last = len(drive.stages) - 1
    for i, (stage, label) in enumerate(zip(drive.stages, stage_labels(drive), strict=True)):
        torque_unit = "N" if linear and i == last else "N*m"
        rated = stage.rated
        if stage.max_input_speed is not None:
            checks.append(CheckArrays(f"{label}_speed", metrics.stage_speed[i],
                                      stage.max_input_speed * ones, "rad/s", limits.speed_margin,
                                      _applies(rated["max_input_speed"], ones)))
        if stage.rated_output_torque is not None:
            checks.append(CheckArrays(f"{label}_rms", metrics.stage_rms[i],
                                      stage.rated_output_torque * ones, torque_unit,
                                      limits.torque_margin,
                                      _applies(rated["rated_output_torque"], ones)))
        if stage.peak_output_torque is not None:
            checks.append(CheckArrays(f"{label}_peak", metrics.stage_peak[i],
                                      stage.peak_output_torque * ones, torque_unit,
                                      limits.torque_margin,
                                      _applies(rated["peak_output_torque"], ones)))
    return checks


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
    """Index of the binding check (smallest slack) per candidate."""
    return np.argmin(np.stack([c.slack for c in checks]), axis=0)
