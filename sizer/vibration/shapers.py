"""Input shapers of sec. 7.4.2: impulse sequences convolved with a motion law.

A shaper is a train of impulses A_i at times t_i (t_0 = 0, sum A_i = 1); the shaped input
y(t) = sum A_i q(t - t_i) moves the load of eq. (7.21) without residual vibration at the
design mode. With T_0 = 2 pi / omega_d the damped period and
K = exp(-delta pi / sqrt(1 - delta^2)) (the book's kappa):

- ``zv``, ``zvd``, ``zvdd``: n + 1 impulses at i T_0 / 2, amplitudes C(n, i) K^i / (1 + K)^n
  with n = 1, 2, 3 (Z = 0, then dZ/domega = 0, then d2Z/domega2 = 0);
- ``ei``: the one-hump extra-insensitive shaper (the book gives it for undamped loads
  only): (1 + z)/4, (1 - z)/2, (1 + z)/4 at 0, T_0/2, T_0, z the vibration limit;
- ``ei2``, ``ei3``: the two- and three-hump EI shapers for z = 5 %, times and amplitudes
  the book's cubic fits in delta (footnote 6); the fitted amplitudes sum to 1 within
  3e-4 and are divided by their sum. Used for delta <= EI_FIT_DAMPING_MAX.

:func:`residual_vibration` is the book's Z(omega_n, delta) of a shaper, the sensitivity
curve of Figs. 7.46, 7.47 and 7.52 when omega_n is varied against the design value.
Pure numpy.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np

from sizer.errors import UserError
from sizer.vibration.elastic_load import ElasticLoad

SUM_TOLERANCE = 1e-12
"""Largest |sum A_i - 1| of a shaper's amplitudes."""

EI_FIT_DAMPING_MAX = 0.3
"""Largest damping ratio for the fitted two- and three-hump EI shapers: past it the
three-hump fit's amplitudes turn negative (delta = 0.35: s_2 = -0.024)."""

EI_FIT_LIMIT = 0.05
"""The vibration limit z of the book's fitted multi-hump EI shapers."""

DEFAULT_VIBRATION_LIMIT = 0.05
"""The vibration limit z of the one-hump EI shaper when none is given."""


@dataclass(frozen=True)
class Shaper:
    """Impulses at ``times`` [s] (from 0, increasing) with ``amplitudes`` (positive,
    summing to 1): y(t) = sum A_i q(t - t_i) (sec. 7.4.2)."""

    times: tuple[float, ...]
    amplitudes: tuple[float, ...]

    def __post_init__(self) -> None:
        t = np.asarray(self.times, dtype=float)
        a = np.asarray(self.amplitudes, dtype=float)
        if t.ndim != 1 or t.size == 0 or t.size != a.size:
            raise UserError("a shaper needs one amplitude per impulse time", field="shaper")
        if not (np.all(np.isfinite(t)) and np.all(np.isfinite(a))):
            raise UserError("shaper times and amplitudes must be finite", field="shaper")
        if t[0] != 0.0 or np.any(np.diff(t) <= 0.0):
            raise UserError("shaper times must start at 0 and increase", field="shaper")
        if np.any(a <= 0.0) or abs(float(a.sum()) - 1.0) > SUM_TOLERANCE:
            raise UserError("shaper amplitudes must be positive and sum to 1",
                            field="shaper")

    @property
    def length(self) -> float:
        """t_n, the delay the shaper adds to a move [s]."""
        return float(self.times[-1])


def residual_vibration(shaper: Shaper, omega_n: np.ndarray | float,
                       damping_ratio: float) -> np.ndarray:
    """The book's Z(omega_n, delta) of sec. 7.4.2 (refs. [70, 71]), vectorized over
    omega_n [rad/s]: the residual amplitude relative to one unit impulse."""
    w = np.asarray(omega_n, dtype=float)[..., None]
    t = np.asarray(shaper.times)
    a = np.asarray(shaper.amplitudes)
    decay = damping_ratio * w
    phase = w * math.sqrt(1.0 - damping_ratio**2) * t
    grow = a * np.exp(decay * (t - t[-1]))  # e^(-delta w t_n) inside, no overflow
    out: np.ndarray = np.hypot((grow * np.cos(phase)).sum(axis=-1),
                               (grow * np.sin(phase)).sum(axis=-1))
    return out


def _kappa(damping_ratio: float) -> float:
    """K = exp(-delta pi / sqrt(1 - delta^2)) (sec. 7.4.2)."""
    return math.exp(-damping_ratio * math.pi / math.sqrt(1.0 - damping_ratio**2))


def zv_family(load: ElasticLoad, n: int) -> Shaper:
    """ZV (n = 1), ZVD (n = 2), ZVDD (n = 3): n + 1 impulses at i T_0 / 2 with
    amplitudes C(n, i) K^i / (1 + K)^n (sec. 7.4.2)."""
    k = _kappa(load.damping_ratio)
    weights = np.array([math.comb(n, i) * k**i for i in range(n + 1)])
    amplitudes = weights / weights.sum()
    half = load.damped_period / 2.0
    return Shaper(tuple(i * half for i in range(n + 1)), tuple(float(x) for x in amplitudes))


def one_hump_ei(load: ElasticLoad, vibration_limit: float) -> Shaper:
    """The one-hump EI shaper of sec. 7.4.2 (ref. [72]) for an undamped load:
    (1 + z)/4, (1 - z)/2, (1 + z)/4 at 0, T_0/2, T_0."""
    if load.damping_ratio != 0.0:
        raise UserError(f"the book gives the one-hump EI shaper for undamped loads only "
                        f"(damping_ratio 0, not {load.damping_ratio:g}); for a damped load "
                        f"use ei2 or ei3 (fitted in the damping ratio) or zvd",
                        field="damping_ratio")
    z = vibration_limit
    side = (1.0 + z) / 4.0
    middle = 1.0 - 2.0 * side  # (1 - z) / 2, written so that the sum is 1 exactly
    half = load.damped_period / 2.0
    return Shaper((0.0, half, 2.0 * half), (side, middle, side))


_EI2_TIMES = ((0.4989, 0.1627, -0.5426, 6.1618),
              (0.9974, 0.1838, -1.5827, 8.1712),
              (1.4992, -0.0929, -0.2833, 1.8571))
_EI2_AMPLITUDES = ((0.1605, 0.7669, 2.2656, -1.2275),
                   (0.3391, 0.4508, -2.5808, 1.7365),
                   (0.3408, -0.6153, -0.6876, 0.4226),
                   (0.1599, -0.6024, 1.0028, -0.9314))
_EI3_TIMES = ((0.4997, 0.2383, 0.4455, 12.4720),
              (0.9984, 0.2980, -2.3646, 23.3999),
              (1.4987, 0.1030, -2.0139, 17.0320),
              (1.9960, -0.2823, 0.6153, 5.4045))
_EI3_AMPLITUDES = ((0.1127, 0.7663, 3.2916, -1.4438),
                   (0.2369, 0.6116, -2.5785, 4.8522),
                   (0.3000, -0.1906, -2.1456, 0.1374),
                   (0.2377, -0.7329, 0.4688, -2.0865),
                   (0.1124, -0.4543, 0.9638, -1.4600))


def _fitted_ei(load: ElasticLoad, name: str, times: tuple[tuple[float, ...], ...],
               amplitudes: tuple[tuple[float, ...], ...]) -> Shaper:
    """A multi-hump EI shaper from the book's cubic fits in delta (z = 5 %)."""
    delta = load.damping_ratio
    if delta > EI_FIT_DAMPING_MAX:
        raise UserError(f"the book's {name} shaper is fitted in the damping ratio; sizer "
                        f"uses it up to {EI_FIT_DAMPING_MAX:g} (past it the fitted "
                        f"amplitudes turn negative), not {delta:g}; use zvd or zvdd",
                        field="damping_ratio")
    powers = delta ** np.arange(4)
    t = np.concatenate(([0.0], np.asarray(times) @ powers)) * load.damped_period
    a = np.asarray(amplitudes) @ powers
    return Shaper(tuple(float(x) for x in t), tuple(float(x) for x in a / a.sum()))


@dataclass(frozen=True)
class ShaperKind:
    """A kind of shaper by name: its builder from a load and a vibration limit z (only
    the one-hump EI reads z), and a title citing the book."""

    name: str
    title: str
    builder: Callable[[ElasticLoad, float], Shaper]
    reads_limit: bool = False

    def build(self, load: ElasticLoad, vibration_limit: float | None = None) -> Shaper:
        if vibration_limit is not None and not self.reads_limit:
            raise UserError(f"the {self.name} shaper has no vibration_limit (only ei "
                            f"reads it; ei2 and ei3 are the book's fits for 5 %)",
                            field="vibration_limit")
        z = DEFAULT_VIBRATION_LIMIT if vibration_limit is None else float(vibration_limit)
        if not (math.isfinite(z) and 0.0 <= z < 1.0):
            raise UserError(f"the vibration limit z must be in [0, 1), not {z:g}",
                            field="vibration_limit")
        return self.builder(load, z)


SHAPER_KINDS: Mapping[str, ShaperKind] = {k.name: k for k in (
    ShaperKind("zv", "Zero Vibration: 2 impulses over T_0/2 (sec. 7.4.2)",
               lambda load, z: zv_family(load, 1)),
    ShaperKind("zvd", "Zero Vibration and Derivative: 3 impulses over T_0 (sec. 7.4.2)",
               lambda load, z: zv_family(load, 2)),
    ShaperKind("zvdd", "ZV and two derivatives: 4 impulses over 3 T_0/2 (sec. 7.4.2)",
               lambda load, z: zv_family(load, 3)),
    ShaperKind("ei", "One-hump extra-insensitive, undamped: 3 impulses over T_0 "
               "(sec. 7.4.2)", one_hump_ei, reads_limit=True),
    ShaperKind("ei2", "Two-hump extra-insensitive, z = 5 %: 4 impulses, fitted in delta "
               "(sec. 7.4.2)",
               lambda load, z: _fitted_ei(load, "ei2", _EI2_TIMES, _EI2_AMPLITUDES)),
    ShaperKind("ei3", "Three-hump extra-insensitive, z = 5 %: 5 impulses, fitted in delta "
               "(sec. 7.4.2)",
               lambda load, z: _fitted_ei(load, "ei3", _EI3_TIMES, _EI3_AMPLITUDES)),
)}
"""Shaper kinds by name (sec. 7.4.2)."""


def kind_of_shaper(name: object) -> ShaperKind:
    """The kind of a shaper name; UserError listing the kinds."""
    if not isinstance(name, str) or name not in SHAPER_KINDS:
        raise UserError(f"unknown shaper {name!r}; shapers: {', '.join(SHAPER_KINDS)}",
                        field="shaper")
    return SHAPER_KINDS[name]


def make_shaper(name: str, load: ElasticLoad, vibration_limit: float | None = None) -> Shaper:
    """The shaper of kind ``name`` designed for ``load`` (times in s)."""
    return kind_of_shaper(name).build(load, vibration_limit)


def shaper_length(shaper_kind: str, load: ElasticLoad,
                  vibration_limit: float | None = None) -> float:
    """t_n: how much a shaper of this kind lengthens a move on this load [s]."""
    return make_shaper(shaper_kind, load, vibration_limit).length
