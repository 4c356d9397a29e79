"""Motors with drives: a candidate is a motor x a compatible drive (issue 16).

The drive's current limits become torque limits through the motor's torque constant k_t
(or its torque-current curve, which gives saturation): the intermittent region is clipped
at T(I_peak), the continuous one at T(I_cont), i.e. the motor and drive region is
min(motor curve, drive torque) at every speed. The clipped regions are exact: each segment
crossing the drive's torque gets the crossing as a corner. The checks
``drive_peak_current`` and ``drive_rms_current`` (sizer.sizing.checks) name the drive when
it binds.

A drive suits a motor when its ``motors`` list names the motor (an id or an fnmatch
pattern), or, without a list, by rule: the motor gives k_t and the drive's continuous
current covers the motor's (continuous_torque / k_t through the curve).
"""

from __future__ import annotations

import fnmatch
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from sizer.envelope import RegionTable
from sizer.errors import UserError
from sizer.model.domain import Motor, ServoDrive


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
