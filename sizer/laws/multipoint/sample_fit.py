"""Cam tables: a smooth spline through (or near) sampled positions, with a fit report.

A cam table is a list of samples (x_i, q_i), x a time or a master angle, q the follower's
position. :func:`fit_samples` turns it into a piecewise polynomial q(x) of a chosen
*order* (degree + 1, as in the slides on polynomial splines, seed 002) and reports how far
the curve is from the samples and how much of its velocity, acceleration and jerk is
noise that the samples carry.

Fitting (all scipy.interpolate):

- ``smoothing`` None or 0: the interpolating spline of degree k = ``order - 1``
  (make_interp_spline). Its k - 1 = ``order - 2`` extra conditions are scipy's
  *not-a-knot* ones at both ends, for every degree, odd or even: the breakpoints are the
  samples without the (k - 1) / 2 next to each end for an odd degree, the midpoints
  between samples without the k / 2 next to each end for an even one, so that the pieces
  near the ends extend one polynomial over several samples. It assumes nothing about
  the end derivatives (a "natural" end, zero high derivatives, would bend a cam that
  starts with a jerk or an acceleration) and reproduces any polynomial of degree k.
- ``smoothing`` > 0: a smoothing spline of the same degree (make_splrep, FITPACK's
  algorithm) whose RMS residual at the samples is at most ``smoothing`` (position units):
  ``sum (g(x_i) - q_i)^2 <= m * smoothing^2``. It takes fewer knots where the data
  allow. (make_smoothing_spline would fix the degree at 3, so jerk would jump.)
- ``periodic``: the spline's first ``order - 2`` derivatives take the same values at
  both ends (bc_type "periodic"). The position may rise by a whole stroke per period (a
  rotary knife turns once per cycle): the fit is periodic on q minus the line from the
  first sample to the last, added back after, so an out-and-back table and a rotary
  one are both periodic.

The default order 6 (quintic, C4) keeps the jerk continuous and its derivative too, so
that a sized drive sees no jerk steps that the table does not contain.

Derivative noise. Interpolating noisy samples amplifies their scatter in the k-th
derivative by about sigma / dx^k. The report estimates it in two steps:

1. The noise level sigma of the samples, from pseudo-residuals (Gasser, Sroka and
   Jennen-Steinmetz 1986; Hall, Kay and Titterington 1990 for higher orders): on every
   window of d + 1 = 7 consecutive samples, the normalized divided difference
   r_i = sum_j w_j q_{i+j} (w annihilates polynomials of degree < d, sum w_j^2 = 1) is
   pure noise of variance sigma^2 plus a smooth part of size dx^d q^(d), negligible for a
   sampled law; sigma^2 = median(r_i^2) / 0.4549 (the median of chi^2_1), robust to the
   few windows across a kink of the table.
2. The fit is linear in the samples (for a smoothing spline: with its knots fixed), so
   white noise of that sigma gives the k-th derivative a variance sigma^2 var_k(x) that
   depends only on the abscissas and the method: var_k is computed by fitting a fixed set
   of 64 standard-normal sample vectors (seed 0) with the same method.

For k = 1, 2, 3 the report gives the RMS over [x_0, x_n] (over 2,048 evenly spread
pieces of a longer table) and the peak of that standard deviation, sigma sqrt(var_k(x)),
divided by the RMS of the fitted k-th derivative: the share of the fitted velocity,
acceleration and jerk that is noise. Clean samples of a smooth law give nearly zero; the
numbers grow in proportion to the noise.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from sizer.errors import UserError
from sizer.input_limits import MAX_CAM_TABLE_ROWS
from sizer.laws.multipoint.fields import boolean, integer, number
from sizer.laws.quadrature import gauss
from sizer.numerics.arrays import sorted_unique

if TYPE_CHECKING:
    from scipy.interpolate import BSpline, PPoly

FIT_FIELDS = ("order", "smoothing", "periodic")
"""The YAML fields of a cam table that choose the fit (read by build_cam_table_samples)."""

DEFAULT_ORDER = 6
"""Degree 5: a C4 curve, jerk continuous."""

MIN_ORDER, MAX_ORDER = 2, 10
_DIFFERENCE_ORDER = 6
"""d of the pseudo-residuals (module docstring)."""
_NOISE_MIN_SAMPLES = _DIFFERENCE_ORDER + 3
"""With fewer samples (fewer than 3 pseudo-residuals) there is no noise report."""
_NOISE_DRAWS = 64
_CHI2_MEDIAN = 0.454936423119572
"""Median of the chi-square distribution with one degree of freedom."""
_GAUSS_NODES = 9
"""Gauss-Legendre nodes per piece for the RMS integrals: exact up to degree 17, so for
the squared derivatives (degree <= 2 (k - 1) = 16) of every allowed degree k <= 9."""
_PEAK_POINTS = 24
"""Points per piece (ends included) for the peaks of the derivative noise."""


@dataclass(frozen=True, eq=False)
class SampleFit:
    """A fitted cam table: the curve and its report.

    ``noise_rms[k-1]`` and ``noise_peak[k-1]`` (k = 1, 2, 3: velocity, acceleration,
    jerk) are relative to ``derivative_rms[k-1]`` (0.0 where that derivative is
    identically zero); they and ``noise_sigma`` (the samples' estimated noise, position
    units) are None with fewer than 9 samples or for a periodic smoothing fit.
    """

    curve: PPoly
    x: np.ndarray
    q: np.ndarray
    order: int
    smoothing: float | None
    periodic: bool
    max_residual: float
    rms_residual: float
    derivative_rms: tuple[float, float, float]
    noise_sigma: float | None
    noise_rms: tuple[float, float, float] | None
    noise_peak: tuple[float, float, float] | None

    @property
    def degree(self) -> int:
        return self.order - 1


def fit_samples(x: np.ndarray, q: np.ndarray, *, order: int = DEFAULT_ORDER,
                smoothing: float | None = None, periodic: bool = False) -> SampleFit:
    """Fit the samples (x_i, q_i) with a spline of ``order`` (degree ``order - 1``).

    See the module docstring for the conditions, the smoothing and the noise measure.
    UserError (field ``x``, ``q``, ``order``, ``smoothing``, ``periodic``) on bad input.
    """
    x, q = _checked_samples(x, q, order, smoothing, periodic)
    slope = (q[-1] - q[0]) / (x[-1] - x[0]) if periodic else 0.0
    wrapped = q - slope * (x - x[0])
    if periodic:
        wrapped[-1] = wrapped[0]  # equal but for rounding
    spline = _fit(x, wrapped, order, smoothing, periodic)
    curve = _with_line(_trimmed(spline, x[0], x[-1]), slope, x[0])
    residual = curve(x) - q
    rms = _derivative_rms(curve)
    sigma = noise_rms = noise_peak = None
    if len(x) >= _NOISE_MIN_SAMPLES and not (smoothing and periodic):
        sigma = _noise_sigma(x, q)
        noise_rms, noise_peak = _derivative_noise(x, spline, curve, order, smoothing,
                                                  periodic, sigma, rms)
    return SampleFit(curve=curve, x=x, q=q, order=order, smoothing=smoothing,
                     periodic=periodic, max_residual=float(np.max(np.abs(residual))),
                     rms_residual=float(np.sqrt(np.mean(residual ** 2))),
                     derivative_rms=rms, noise_sigma=sigma, noise_rms=noise_rms,
                     noise_peak=noise_peak)


def build_cam_table_samples(fields: Mapping[str, Any], x: np.ndarray, q: np.ndarray
                            ) -> SampleFit:
    """fit_samples with the fitting fields of a cam table's YAML mapping.

    ``order`` (integer 2..10, default 6), ``smoothing`` (RMS residual allowed, position
    units, >= 0; absent or 0: interpolation), ``periodic`` (bool, default false). Other
    keys are not read here (the caller refuses the unknown ones).
    """
    order = integer(fields, "order", DEFAULT_ORDER, low=MIN_ORDER, high=MAX_ORDER)
    smoothing = number(fields, "smoothing", 0.0, low=0.0)
    periodic = boolean(fields, "periodic", False)
    return fit_samples(x, q, order=order, smoothing=smoothing or None, periodic=periodic)


def _checked_samples(x: np.ndarray, q: np.ndarray, order: int, smoothing: float | None,
                     periodic: bool) -> tuple[np.ndarray, np.ndarray]:
    if isinstance(order, bool) or not isinstance(order, int | np.integer) or not (
            MIN_ORDER <= order <= MAX_ORDER):
        raise UserError(f"must be an integer between {MIN_ORDER} and {MAX_ORDER}, got "
                        f"{order!r}", field="order")
    if smoothing is not None and not (np.isfinite(smoothing) and smoothing >= 0.0):
        raise UserError(f"must be a finite number >= 0, got {smoothing!r}",
                        field="smoothing")
    x = np.asarray(x, dtype=float)
    q = np.asarray(q, dtype=float)
    if len(x) > MAX_CAM_TABLE_ROWS:
        raise UserError(f"a cam table of {len(x):,} rows: the limit is "
                        f"{MAX_CAM_TABLE_ROWS:,} (MAX_CAM_TABLE_ROWS); resample the table "
                        f"more coarsely", field="file")
    if x.ndim != 1 or q.shape != x.shape:
        raise UserError(f"x and q must be two lists of the same length, got shapes "
                        f"{x.shape} and {q.shape}", field="q")
    for name, values in (("x", x), ("q", q)):
        bad = np.flatnonzero(~np.isfinite(values))
        if bad.size:
            i = int(bad[0])
            raise UserError(f"sample {i} has {name} = {values[i]!r}: samples must be finite "
                            f"numbers", field=name)
    needed = order + 1 if periodic else order
    if len(x) < needed:
        raise UserError(f"order {order} needs at least {needed} samples"
                        f"{' (periodic)' if periodic else ''}, got {len(x)}", field="order")
    bad = np.flatnonzero(np.diff(x) <= 0.0)
    if bad.size:
        i = int(bad[0]) + 1
        raise UserError(f"x must increase strictly: sample {i} has x = {x[i]:g} after "
                        f"x = {x[i - 1]:g}", field="x")
    return x, q


def _fit(x: np.ndarray, q: np.ndarray, order: int, smoothing: float | None,
         periodic: bool) -> BSpline:
    """The spline of degree order - 1 (module docstring), as scipy builds it."""
    from scipy.interpolate import make_interp_spline, make_splrep

    k = order - 1
    with warnings.catch_warnings():
        # FITPACK warns when it cannot meet s exactly and returns its best approximation:
        # that is fine here, the report gives the residual the fit reached.
        warnings.simplefilter("ignore" if smoothing else "error")
        try:
            if smoothing:
                return make_splrep(x, q, k=k, s=len(x) * smoothing ** 2,
                                   bc_type="periodic" if periodic else None)
            return make_interp_spline(x, q, k=k, bc_type="periodic" if periodic else None)
        except (ValueError, np.linalg.LinAlgError, RuntimeWarning, UserWarning) as exc:
            raise UserError(f"cannot fit a spline of order {order} to these samples: "
                            f"{exc}", field="order") from None


def _trimmed(spline: BSpline, a: float, b: float) -> PPoly:
    """``spline`` as a PPoly over [a, b], one piece per knot span inside it.

    Written out rather than PPoly.from_spline, which keeps the repeated end knots, reaches
    beyond the ends for a periodic spline and crashes the interpreter for degree >= 8 in
    scipy 1.17 (it goes through FITPACK's splev). The Taylor coefficients of each piece
    are the spline's own derivatives at its left end (BSpline evaluates the piece to the
    right of a knot).
    """
    from scipy.interpolate import PPoly

    k = spline.k
    knots = sorted_unique(spline.t)
    span = b - a
    inside = knots[(knots > a + 1e-12 * span) & (knots < b - 1e-12 * span)]
    breaks = np.concatenate(([a], inside, [b]))
    left = breaks[:-1]
    coefficients = np.array([spline(left, nu=k - m) / math.factorial(k - m)
                             for m in range(k + 1)])
    return PPoly(coefficients, breaks, extrapolate=False)


def _with_line(curve: PPoly, slope: float, start: float) -> PPoly:
    """``curve`` plus slope * (x - start): a periodic fit's rise per period put back."""
    if slope == 0.0:
        return curve
    from scipy.interpolate import PPoly

    c = curve.c.copy()
    c[-2] += slope
    c[-1] += slope * (curve.x[:-1] - start)
    return PPoly(c, curve.x, extrapolate=False)


def _noise_sigma(x: np.ndarray, q: np.ndarray) -> float:
    """The samples' noise level from normalized divided differences (module docstring)."""
    d = _DIFFERENCE_ORDER
    windows = np.lib.stride_tricks.sliding_window_view(x, d + 1)
    gaps = windows[:, :, None] - windows[:, None, :]
    gaps[:, np.arange(d + 1), np.arange(d + 1)] = 1.0
    # Divided-difference weights, scaled per window first (gaps / their mean) to keep
    # the products of d gaps in range.
    scale = np.mean(np.abs(gaps), axis=(1, 2), keepdims=True)
    weights = 1.0 / np.prod(gaps / scale, axis=2)
    weights /= np.linalg.norm(weights, axis=1, keepdims=True)
    residuals = np.sum(weights * np.lib.stride_tricks.sliding_window_view(q, d + 1), axis=1)
    return float(np.sqrt(np.median(residuals ** 2) / _CHI2_MEDIAN))


def _derivative_rms(curve: PPoly) -> tuple[float, float, float]:
    t, w = (a.ravel() for a in gauss(curve.x, _GAUSS_NODES))
    span = curve.x[-1] - curve.x[0]
    return _three([float(np.sqrt(np.sum(w * curve(t, nu) ** 2) / span)) for nu in (1, 2, 3)])


def _three(values: Sequence[float]) -> tuple[float, float, float]:
    """The values of the orders 1, 2, 3 (velocity, acceleration, jerk) as a triple."""
    velocity, acceleration, jerk = values
    return velocity, acceleration, jerk


def _derivative_noise(x: np.ndarray, spline: BSpline, curve: PPoly, order: int,
                      smoothing: float | None, periodic: bool, sigma: float,
                      rms: tuple[float, float, float]
                      ) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
    """RMS and peak of the k-th derivative's noise deviation, k = 1..3, relative to
    rms[k-1] (module docstring, step 2)."""
    from scipy.interpolate import make_interp_spline, make_lsq_spline

    draws = np.random.default_rng(0).standard_normal((len(x), _NOISE_DRAWS))
    k = order - 1
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        if smoothing:  # linear once the knots are fixed: least squares on them
            response = make_lsq_spline(x, draws, spline.t, k=k)
        else:
            if periodic:
                draws[-1] = draws[0]
            response = make_interp_spline(x, draws, k=k,
                                          bc_type="periodic" if periodic else None)
    # on at most _NOISE_PIECES pieces spread evenly over the table (all of a shorter one)
    count = len(curve.x) - 1
    chosen = sorted_unique(np.linspace(0, count - 1, min(count, _NOISE_PIECES)).astype(int))
    left, width = curve.x[chosen], curve.x[chosen + 1] - curve.x[chosen]
    u, g = np.polynomial.legendre.leggauss(_GAUSS_NODES)
    t = (left[:, None] + 0.5 * width[:, None] * (u + 1.0)).ravel()
    w = (0.5 * width[:, None] * g).ravel()
    s = np.linspace(0.0, 1.0, _PEAK_POINTS)
    dense = (left[:, None] + width[:, None] * s).ravel()
    span = float(np.sum(width))
    noise_rms, noise_peak = [], []
    for nu, scale in zip((1, 2, 3), rms, strict=True):
        if scale == 0.0:
            noise_rms.append(0.0)
            noise_peak.append(0.0)
            continue
        integral = sum(float(np.sum(w[part] * _variance(response, t[part], nu)))
                       for part in _chunks(len(t)))
        noise_rms.append(sigma * float(np.sqrt(integral / span)) / scale)
        peak = math.sqrt(max(float(np.max(_variance(response, dense[part], nu)))
                             for part in _chunks(len(dense))))
        noise_peak.append(sigma * float(peak) / scale)
    return _three(noise_rms), _three(noise_peak)


_NOISE_PIECES = 2_048
"""Pieces of a long table on which the derivative noise is estimated (evenly spread; the
noise of an evenly sampled table is about the same on every piece): the report's cost
is bounded whatever the number of samples."""

_NOISE_CHUNK = 16_384
"""Points at which the noise response (64 draws each) is evaluated at once: the memory
of the noise report stays bounded (16 MB) whatever the number of samples."""


def _chunks(count: int) -> list[slice]:
    return [slice(i, i + _NOISE_CHUNK) for i in range(0, count, _NOISE_CHUNK)]


def _variance(response: BSpline, x: np.ndarray, nu: int) -> np.ndarray:
    """The mean over the draws of the squared nu-th derivative of the response at x."""
    return np.mean(response(x, nu) ** 2, axis=1)
