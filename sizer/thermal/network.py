"""Winding temperature rise of a motor as a sum of first-order modes (issue 16).

First-order model (book sec. 6.1.1, footnote: the thermal time constant is the time to
reach 63.2 % of the final rise): C dT/dt = P(t) - T/R_th, tau_th = R_th C, T the rise
above ambient. Two-node model (winding and housing, as maxon's datasheets give it:
R_th1 winding-housing, R_th2 housing-ambient, tau_w winding, tau_s stator/motor time
constants, C_w = tau_w/R_th1, C_h = tau_s/R_th2):

    C_w dT_w/dt = P - (T_w - T_h)/R_th1,   C_h dT_h/dt = (T_w - T_h)/R_th1 - T_h/R_th2.

Both are, seen from the winding, a sum of modes z_i' = (g_i P - z_i)/tau_i with
T = sum z_i (partial fractions of the transfer function; the two-node gains are positive
and add to R_th1 + R_th2). The loss P(t) is piecewise linear in time between samples (a
repeated time is a step: piecewise-constant losses are exact). On an interval of length
h from P0 to P1 each mode moves exactly to

    z1 = a z0 + g ((b - a) P0 + (1 - b) P1),   a = exp(-h/tau),  b = (tau/h)(1 - a),

(weights by power series where h/tau is small, :func:`_weights`) and the intervals
compose by an associative scan (no time stepping). The periodic steady state of a
repeated cycle solves z(0) = z(period): z0 = c/(1 - A) per mode. Peaks are exact: the
samples and the interior maxima (T' = 0, found by Chandrupatla's method on each interval,
split where T'' changes sign). Means are exact integrals.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from sizer.energy.inputs import finite, nonnegative, positive, samples, span, times
from sizer.errors import UserError
from sizer.numerics.roots import bracketed_root

SERIES_BELOW = 0.5
"""Below this h/tau the weights are summed from their power series (no cancellation)."""
_TERMS = 16
_FACT = np.cumprod(np.concatenate([[1.0], np.arange(1.0, _TERMS + 4.0)]))  # 0! .. (T+3)!


_SERIES = {  # coefficients of (-x)^k, k = 0 .. _TERMS - 1
    "b": 1.0 / _FACT[1:_TERMS + 1],
    "c1": 1.0 / _FACT[2:_TERMS + 2],
    "c2": np.arange(1.0, _TERMS + 1.0) / _FACT[2:_TERMS + 2],
    "d1": 1.0 / _FACT[3:_TERMS + 3],
    "d2": np.arange(2.0, _TERMS + 2.0) / _FACT[3:_TERMS + 3],
}


X_MAX = 1e150
"""h/tau beyond this is taken as this (the weights are then 0, 1/x, ... to rounding)."""


def _ratio(h, tau) -> np.ndarray:
    """x = h/tau, at most X_MAX (so that x^2 stays finite)."""
    with np.errstate(over="ignore"):
        return np.minimum(h / tau, X_MAX)


def _weights(x: np.ndarray, names: tuple[str, ...] = ("b", "c1", "c2", "d1", "d2")
             ) -> dict[str, np.ndarray]:
    """Weights of the exact response over an interval with x = h/tau >= 0:
    a = e^-x, b = (1 - a)/x, c1 = (x - 1 + a)/x^2, c2 = (1 - (1 + x) a)/x^2,
    d1 = (1/2 - c1)/x, d2 = (1/2 - c2)/x (power series for small x, exact at 0)."""
    x = np.minimum(x, X_MAX)
    a = np.exp(-x)
    out = {"a": a}
    small = x < SERIES_BELOW
    y = -x[small]
    big, ab = x[~small], a[~small]
    direct = {
        "b": lambda: -np.expm1(-big) / big,
        "c1": lambda: (big - 1.0 + ab) / (big * big),
        "c2": lambda: (1.0 - (1.0 + big) * ab) / (big * big),
        "d1": lambda: (0.5 - (big - 1.0 + ab) / (big * big)) / big,
        "d2": lambda: (0.5 - (1.0 - (1.0 + big) * ab) / (big * big)) / big,
    }
    for name in names:
        value = np.empty_like(x)
        coefficients = _SERIES[name]
        total = np.full_like(y, coefficients[-1])
        for c in coefficients[-2::-1]:  # Horner
            total = total * y + c
        value[small] = total
        with np.errstate(over="ignore", under="ignore"):
            value[~small] = direct[name]()
        out[name] = value
    return out


def _state(z0, g, P0, P1, x):
    """A mode's state after x = s/tau of an interval where the loss runs linearly from P0
    to P1 (at s): z = a z0 + g x (c2 P0 + c1 P1)."""
    w = _weights(x, ("c1", "c2"))
    return w["a"] * z0 + g * x * (w["c2"] * P0 + w["c1"] * P1)


def _scan(a: np.ndarray, c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Prefix compositions of z -> a z + c along the last axis: (A_k, C_k) with
    z_{k+1} = A_k z_0 + C_k (a doubling scan: log2(n) vector steps)."""
    A, C = a.copy(), c.copy()
    shift = 1
    n = a.shape[-1]
    while shift < n:
        C[..., shift:] = A[..., shift:] * C[..., :-shift] + C[..., shift:]
        A[..., shift:] = A[..., shift:] * A[..., :-shift]
        shift *= 2
    return A, C


@dataclass(frozen=True)
class Response:
    """The winding's temperature rise (K) at the sample times, per candidate and mode.

    ``modes`` (candidates, modes, samples); ``rise`` their sum; ``peak`` and ``mean`` over
    the samples' span, exact for the piecewise-linear loss.
    """

    time: np.ndarray
    loss: np.ndarray
    time_constants: np.ndarray
    gains: np.ndarray
    modes: np.ndarray

    @property
    def rise(self) -> np.ndarray:
        return self.modes.sum(axis=1)

    @property
    def final(self) -> np.ndarray:
        """The mode states at the last sample (candidates, modes): the start of what follows."""
        return self.modes[:, :, -1]

    def _pieces(self):
        h = np.diff(self.time, axis=1)[:, None, :]
        tau, g = self.time_constants[:, :, None], self.gains[:, :, None]
        P0, P1 = self.loss[:, None, :-1], self.loss[:, None, 1:]
        return h, tau, g, P0, P1, self.modes[:, :, :-1]

    @property
    def mean(self) -> np.ndarray:
        """The mean rise over the span: the exact integral over the span's length,
        per interval h (z0 b + g x (d2 P0 + d1 P1))."""
        h, tau, g, P0, P1, z0 = self._pieces()
        x = _ratio(h, tau)
        w = _weights(x, ("b", "d1", "d2"))
        integral = h * (z0 * w["b"] + g * x * (w["d2"] * P0 + w["d1"] * P1))
        return integral.sum(axis=(1, 2)) / span(self.time)

    @property
    def peak(self) -> np.ndarray:
        """The largest rise over the span (samples and interior maxima)."""
        best = self.rise.max(axis=1)
        h, tau, g, P0, P1, z0 = self._pieces()
        n, k, m = z0.shape
        hh = np.broadcast_to(h[:, 0, :], (n, m))
        with np.errstate(divide="ignore", invalid="ignore"):
            slope = np.where(h > 0.0, (P1 - P0) / h, 0.0)
        split = hh
        if k == 2:  # T''(s) = sum E_i e^(-s/tau_i) is zero at most once
            E = (g * slope - (g * P0 - z0) / tau) / tau  # (g_i P' - z_i'(0)) / tau_i
            with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
                ratio = -E[:, 0] / E[:, 1]
                s0 = np.log(ratio) / (1.0 / tau[:, 0] - 1.0 / tau[:, 1])
            inside = np.isfinite(s0) & (ratio > 0.0) & (s0 > 0.0) & (s0 < hh)
            split = np.where(inside, s0, hh)

        def at(s, rows, cols):  # (T'(s) * scale, T(s)) of the intervals (rows, cols)
            tk, gk, zk = tau[rows, :, 0], g[rows, :, 0], z0[rows, :, cols]
            p0 = P0[rows, 0, cols][:, None]
            p = p0 + slope[rows, 0, cols][:, None] * s[:, None]
            z = _state(zk, gk, p0, p, _ratio(s[:, None], tk))
            return np.sum((gk * p - z) / tk, axis=1), np.sum(z, axis=1)

        # a mode stays within its start and the range of g P: an interval whose bound
        # is below the samples' best cannot hold the peak
        bound = np.sum(np.maximum(z0, g * np.maximum(P0, P1)), axis=1)
        hopeful = bound > best[:, None]
        for lo_all, hi_all in ((np.zeros_like(hh), split), (split, hh)):
            rows, cols = np.nonzero(hopeful & (hi_all > lo_all))
            lo, hi = lo_all[rows, cols], hi_all[rows, cols]
            d_lo, d_hi = at(lo, rows, cols)[0], at(hi, rows, cols)[0]
            keep = (d_lo > 0.0) & (d_hi < 0.0)
            rows, cols = rows[keep], cols[keep]
            if rows.size == 0:
                continue
            root = bracketed_root(lambda s, r, c: at(s, r, c)[0], lo[keep], hi[keep], d_lo[keep],
                                  d_hi[keep], args=(rows, cols))
            np.maximum.at(best, rows, at(root, rows, cols)[1])
        return best


@dataclass(frozen=True)
class ThermalModel:
    """A winding seen as modes: time constants and gains (candidates, modes), s and K/W."""

    time_constants: np.ndarray
    gains: np.ndarray

    @property
    def thermal_resistance(self) -> np.ndarray:
        """The steady rise per watt (K/W), per candidate."""
        return self.gains.sum(axis=1)

    @property
    def time_constant(self) -> np.ndarray:
        """The slowest mode's time constant, per candidate."""
        return self.time_constants.max(axis=1)

    def _steps(self, time, loss):
        t = times(time)
        P = samples(loss, t, "loss")
        nonnegative(P, "loss")
        n = max(t.shape[0], P.shape[0], self.gains.shape[0])
        for name, rows in (("loss", P.shape[0]), ("time", t.shape[0])):
            if rows not in (1, n) or self.gains.shape[0] not in (1, n):
                raise UserError(f"has {rows} candidates (rows), the model "
                                f"{self.gains.shape[0]}", field=name)
        P = np.broadcast_to(P, (n, t.shape[1]))
        tau = np.broadcast_to(self.time_constants, (n, self.gains.shape[1]))[:, :, None]
        g = np.broadcast_to(self.gains, (n, self.gains.shape[1]))[:, :, None]
        x = _ratio(np.diff(t, axis=1)[:, None, :], tau)
        w = _weights(x, ("c1", "c2"))
        c = g * x * (w["c2"] * P[:, None, :-1] + w["c1"] * P[:, None, 1:])
        return t, P, tau, g, w["a"], c

    def _response(self, t, P, tau, g, z0, A, C) -> Response:
        modes = np.concatenate([z0[:, :, None], A * z0[:, :, None] + C], axis=2)
        return Response(t, P, tau[:, :, 0], g[:, :, 0], modes)

    def response(self, time: ArrayLike, loss: ArrayLike,
                 initial: ArrayLike | None = None) -> Response:
        """A one-off sequence from ``initial`` mode states (candidates, modes) or, by
        default, from ambient (zero rise): loss (W) sampled at ``time``."""
        t, P, tau, g, a, c = self._steps(time, loss)
        A, C = _scan(a, c)
        z0 = np.zeros(A.shape[:2]) if initial is None else np.broadcast_to(
            finite(initial, "initial"), A.shape[:2])
        return self._response(t, P, tau, g, z0, A, C)

    def periodic(self, time: ArrayLike, loss: ArrayLike) -> Response:
        """The periodic steady state of the cycle ``loss`` sampled at ``time`` repeated
        forever: the rise at the cycle's start equals the rise at its end."""
        t, P, tau, g, a, c = self._steps(time, loss)
        A, C = _scan(a, c)
        period = span(t)[:, None]
        z0 = C[:, :, -1] / -np.expm1(-period / tau[:, :, 0])
        return self._response(t, P, tau, g, z0, A, C)


def thermal_resistance(allowed_rise: ArrayLike, continuous_loss: ArrayLike) -> np.ndarray:
    """R_th = dT_max / P_cu(tau_c) (K/W): the winding reaches its allowed rise at the
    continuous torque's copper loss (sizer.energy.copper_loss of tau_c)."""
    return positive(allowed_rise, "allowed_rise") / positive(continuous_loss, "continuous_loss")


def _together(values: dict[str, np.ndarray]) -> list[np.ndarray]:
    """Scalars or one value per candidate, all of one length: 1-D float arrays."""
    arrays = [np.atleast_1d(v).astype(float) for v in values.values()]
    sizes = {a.size for a in arrays} - {1}
    if len(sizes) > 1 or any(a.ndim != 1 for a in arrays):
        raise UserError("must be one number or one per candidate, as the other figures",
                        field=next(iter(values)))
    n = max(a.size for a in arrays)
    return [np.broadcast_to(a, (n,)).copy() for a in arrays]


def first_order(thermal_resistance: ArrayLike, time_constant: ArrayLike) -> ThermalModel:
    """The one-node winding model: R_th (K/W) and tau_th (s), scalars or per candidate."""
    R = positive(thermal_resistance, "thermal_resistance")
    tau = positive(time_constant, "thermal_time_constant", " (a time constant of zero "
                   "would make the winding follow its loss without delay)")
    R, tau = _together({"thermal_resistance": R, "thermal_time_constant": tau})
    return ThermalModel(tau.reshape(-1, 1).astype(float), R.reshape(-1, 1).astype(float))


def two_node(winding_housing_resistance: ArrayLike, housing_ambient_resistance: ArrayLike,
             winding_time_constant: ArrayLike, housing_time_constant: ArrayLike
             ) -> ThermalModel:
    """The winding-housing model from R_th1, R_th2 (K/W) and the winding's and the
    housing's time constants tau_w = R_th1 C_w, tau_s = R_th2 C_h (s)."""
    R1 = positive(winding_housing_resistance, "winding_housing_resistance")
    R2 = positive(housing_ambient_resistance, "housing_ambient_resistance")
    tw = positive(winding_time_constant, "winding_time_constant")
    th = positive(housing_time_constant, "housing_time_constant")
    R1, R2, tw, th = _together({"winding_housing_resistance": R1,
                                "housing_ambient_resistance": R2,
                                "winding_time_constant": tw, "housing_time_constant": th})
    Cw, Ch = tw / R1, th / R2
    m11, m12 = -1.0 / (R1 * Cw), 1.0 / (R1 * Cw)
    m21, m22 = 1.0 / (R1 * Ch), -(1.0 / (R1 * Ch) + 1.0 / (R2 * Ch))
    trace, det = m11 + m22, m11 * m22 - m12 * m21
    root = np.sqrt(np.maximum(0.25 * (m11 - m22) ** 2 + m12 * m21, 0.0))
    fast, slow = 0.5 * trace - root, 0.5 * trace + root  # real, distinct, negative
    if bool(np.any(~(root > 0.0) | ~(det > 0.0))):
        raise UserError("these figures give no two-node model", field="winding_time_constant")
    # residues of (s - m22) / (C_w (s - fast)(s - slow)); gain = residue * tau = -r/lambda
    r_fast = (fast - m22) / (Cw * (fast - slow))
    r_slow = (slow - m22) / (Cw * (slow - fast))
    tau = np.stack([-1.0 / fast, -1.0 / slow], axis=1)
    gains = np.stack([-r_fast / fast, -r_slow / slow], axis=1)
    return ThermalModel(tau, gains)
