"""The heat check of sampled motor torques (issue 16): the first-order winding model with
R_th from the continuous torque, and the verdict of sizer.thermal.verdict.

With dT_max = R_th P_cu(tau_c) and P_cu = f R (tau/k_t)^2 the rise is driven by
dT_max (tau/tau_c)^2 / tau_th: the resistance, the torque constant and the winding
convention cancel, so the datasheet's thermal time constant, continuous torque and allowed
rise are all the model needs. The loss is the piecewise-linear interpolant of the samples
of (tau/tau_c)^2 (a repeated time is a step), and the RMS torque is taken from the same
interpolant, so that over a periodic cycle the model's mean rise is dT_max (tau_rms/tau_c)^2
exactly.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from sizer.energy.inputs import finite, per_candidate, positive, samples, span, times
from sizer.energy.power import integral
from sizer.errors import UserError
from sizer.thermal.network import Response, first_order
from sizer.thermal.verdict import RMS_SHARE, ThermalVerdict, thermal_verdict


@dataclass(frozen=True)
class WindingCheck:
    """The model's response (K), the RMS torque of the samples and the verdict."""

    response: Response
    rms_torque: np.ndarray
    verdict: ThermalVerdict


def winding_check(time: ArrayLike, torque: ArrayLike, continuous_torque: ArrayLike,
                  allowed_rise: ArrayLike, time_constant: ArrayLike,
                  periodic: bool = True, share: float = RMS_SHARE,
                  initial_rise: ArrayLike = 0.0) -> WindingCheck:
    """The heat check of motor torques (N*m) sampled at ``time`` (s), (samples,) or
    (candidates, samples): the periodic steady state of the repeated cycle, or with
    ``periodic`` False a one-off sequence from ``initial_rise`` (K above ambient).
    ``continuous_torque`` tau_c (N*m), ``allowed_rise`` dT_max (K) and ``time_constant``
    tau_th (s) are scalars or one per candidate."""
    t = times(time)
    tau = samples(torque, t, "torque")
    given = {"continuous_torque": positive(continuous_torque, "continuous_torque"),
             "allowed_rise": positive(allowed_rise, "allowed_rise"),
             "thermal_time_constant": positive(time_constant, "thermal_time_constant")}
    n = max([t.shape[0], tau.shape[0]] + [v.size for v in given.values()])
    if tau.shape[0] not in (1, n):
        raise UserError(f"has {tau.shape[0]} candidates (rows), the figures {n}",
                        field="torque")
    tau_c, allowed, tau_th = (per_candidate(v, n, k) for k, v in given.items())
    model = first_order(np.broadcast_to(allowed, (n, 1))[:, 0],
                        np.broadcast_to(tau_th, (n, 1))[:, 0])
    loss = np.broadcast_to((tau / tau_c) ** 2, (n, t.shape[1]))
    if periodic:
        response = model.periodic(t, loss)
    else:
        start = per_candidate(finite(initial_rise, "initial_rise"), n, "initial_rise")
        response = model.response(t, loss, initial=np.broadcast_to(start, (n, 1)))
    cycle = np.broadcast_to(span(t), (n,))
    rms = np.sqrt(np.broadcast_to(integral(t, tau * tau), (n,)) / cycle)
    verdict = thermal_verdict(cycle, tau_th[:, 0], rms, tau_c[:, 0], response.peak,
                              allowed[:, 0], share)
    return WindingCheck(response, rms, verdict)
