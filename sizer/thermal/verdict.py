"""Which heat check applies, and its margin (issue 16; book sec. 6.1.1 and its footnote).

The book's RMS check (tau_rms <= tau_c at the thermal speed) assumes a cycle much shorter
than the thermal time constant: the winding then only sees the mean loss, and with
R_th from the continuous torque (dT_max = R_th P_cu(tau_c)) the mean rise is
dT_max (tau_rms/tau_c)^2 exactly. When the cycle is shorter than ``share`` * tau_th
(1/10 by default) the RMS check applies; otherwise the thermal model's peak rise does.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from sizer.energy.inputs import nonnegative, positive

RMS_SHARE = 0.1
"""The RMS check applies when the cycle is shorter than this share of tau_th."""


@dataclass(frozen=True)
class ThermalVerdict:
    """Per candidate: ``applied`` ("rms" or "thermal"), the rise the RMS torque implies
    (dT_max (tau_rms/tau_c)^2) and the thermal model's peak rise, the ``rise`` of the check
    that applies, the allowed rise, margin = 1 - rise/allowed and ``feasible`` (margin >= 0).
    """

    applied: np.ndarray
    rms_rise: np.ndarray
    peak_rise: np.ndarray
    rise: np.ndarray
    allowed_rise: np.ndarray
    margin: np.ndarray
    feasible: np.ndarray


def applied_check(cycle_time: ArrayLike, time_constant: ArrayLike,
                  share: float = RMS_SHARE) -> np.ndarray:
    """"rms" where the cycle is shorter than ``share`` * tau_th, else "thermal"."""
    T = positive(cycle_time, "cycle_time")
    tau = positive(time_constant, "thermal_time_constant")
    positive(share, "share")
    return np.where(share * tau > T, "rms", "thermal")


def thermal_verdict(cycle_time: ArrayLike, time_constant: ArrayLike, rms_torque: ArrayLike,
                    continuous_torque: ArrayLike, peak_rise: ArrayLike,
                    allowed_rise: ArrayLike, share: float = RMS_SHARE) -> ThermalVerdict:
    """The verdict of the heat check for each candidate (module docstring)."""
    applied = applied_check(cycle_time, time_constant, share)
    tau_rms = nonnegative(rms_torque, "rms_torque")
    tau_c = positive(continuous_torque, "continuous_torque")
    allowed = positive(allowed_rise, "allowed_rise")
    peak = nonnegative(peak_rise, "peak_rise")
    rms_rise = allowed * (tau_rms / tau_c) ** 2
    applied, rms_rise, peak, allowed = np.broadcast_arrays(applied, rms_rise, peak, allowed)
    rise = np.where(applied == "rms", rms_rise, peak)
    margin = 1.0 - rise / allowed
    return ThermalVerdict(applied, rms_rise, peak, rise, allowed, margin, margin >= 0.0)
