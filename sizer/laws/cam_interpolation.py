"""A cam table's curve: its ends at rest within its resolution, and the controllers'
interpolations (linear, cubic spline, quintic Hermite) beside the fitted orders.

**Ends at rest.** A table sampled from a law that starts (or ends) at rest does not make a
fit whose end velocity is exactly zero: the fit's truncation error (and the samples'
rounding or noise) leaves a small speed, e.g. v_N(0) = 1e-8 for sizer's own export of a
cycloidal law fitted with order 6. What a table can resolve at an end is measured on its
own samples: the m-th difference of a window of m + 1 samples, m the fit's order
(degree + 1), estimates h^m q^(m), and the velocity error a fit of that order makes there
is of the size of that difference over h (h the window's largest spacing). The error a
fit makes at a kink inside the table spreads to the end, decayed by DECAY per sample, so
every window from the end counts, decayed by its distance:

    at rest at the start  if  |v_fit(x_0)| <= REST_FACTOR * max_i DECAY^i |Delta^m q_i| / h_i
                                             + rounding

with ``rounding`` = 8 * 2^m ulp of the end window's positions over h (what the difference
itself cannot tell from zero). A table that truly starts moving (an electronic cam's
period) has an end speed far above that bound and is kept as fitted. A table at rest at an
end is fitted again with that end clamped: v = 0 there replaces one of the fit's
not-a-knot conditions at that end (make_interp_spline with the knot it had dropped given
back and ``bc_type`` derivative (1, 0.0)), so that the curve still interpolates every
sample and its end velocity is zero by construction, not by editing a coefficient.

**Interpolations** (``interpolation:``), the way controllers run a point table:

- ``linear``: position piecewise linear between the points (CODESYS
  byInterpolationQuality 1, Rockwell linear, SEW's linear table). Its velocity steps at
  every point and its acceleration is a train of impulses: a motor cannot be sized on it
  (torque would be infinite in theory, set by the drive's bandwidth in practice), so a
  linear table is refused with that message. Certify it as a table (sizer cam), size on
  a smooth interpolation.
- ``cubic_spline``: the C2 cubic spline through the points (scipy CubicSpline). At an end
  at rest (criterion above) the end slope is clamped to 0, the Rockwell MCCP form with
  Start/End Slope 0; at an end that moves, not-a-knot (no assumption on the derivatives,
  which a "natural" end would make by forcing the acceleration to 0); ``periodic: true``
  joins the ends (bc_type "periodic"). CODESYS's cubic interpolation
  (byInterpolationQuality 3) does not document its end conditions: the clamped/not-a-knot
  spline is the one that reproduces a rest-to-rest law's points best.
- ``quintic_hermite``: a quintic through each pair of points matching position, velocity
  and acceleration at both (CODESYS XYVA, TwinCAT MC3 points with velocity and
  acceleration; scipy BPoly.from_derivatives): the table then carries v and a columns.

Every curve is a scipy PPoly, so the law's coefficients C_v, C_a, ... follow from its
pieces exactly (sizer.laws.data_law).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from sizer.errors import UserError

if TYPE_CHECKING:
    from scipy.interpolate import PPoly

    from sizer.laws.multipoint.sample_fit import SampleFit

INTERPOLATIONS = ("linear", "cubic_spline", "quintic_hermite")
"""The values of a cam table's ``interpolation`` field (absent: fitted by ``order``)."""

REST_FACTOR = 4.0
"""Safety factor of the rest criterion over the end difference's estimate of the fit's
velocity error (the module docstring)."""

_ROUNDING_ULPS = 8.0

DECAY = 0.7
"""How much less an error of the fit weighs one sample further from the end: a spline
interpolant spreads a local error by a factor below 0.6 per knot for degrees up to 9."""

MAX_WINDOWS = 256
"""Windows of samples read from each end for the bound (DECAY^256 ~ 1e-40)."""


@dataclass(frozen=True)
class RestEnds:
    """Whether a table is at rest at its start and end, with the figures that decided:
    the fit's end speeds and the bounds (position units per x unit)."""

    start: bool
    end: bool
    speeds: tuple[float, float]
    bounds: tuple[float, float]


def end_bound(x: np.ndarray, q: np.ndarray, order: int) -> tuple[float, float]:
    """The speed a table cannot tell from rest at its start and at its end, for a fit of
    ``order`` (module docstring): the m-th differences of its windows over their spacing,
    m = ``order`` (at most the samples - 1), each decayed by DECAY per window away from
    the end, their largest times REST_FACTOR, plus the rounding of the end window."""
    m = max(1, min(order, len(x) - 1))
    bounds = []
    for xs, qs in ((x, q), (x[::-1], q[::-1])):
        count = min(len(xs) - m, MAX_WINDOWS)
        reach = xs[:count + m]
        steps = np.abs(np.diff(reach))
        h = np.array([np.max(steps[i:i + m]) for i in range(count)])
        differences = _differences(reach, qs[:count + m], m)
        decayed = np.abs(differences) / h * DECAY ** np.arange(count)
        rounding = _ROUNDING_ULPS * 2.0 ** m * float(np.spacing(np.max(np.abs(qs[:m + 1])))
                                                    ) / h[0]
        bounds.append(REST_FACTOR * float(np.max(decayed)) + rounding)
    return bounds[0], bounds[1]


def _differences(xs: np.ndarray, qs: np.ndarray, m: int) -> np.ndarray:
    """m! h^m times the m-th divided differences of consecutive windows of m + 1 samples
    (h the mean spacing): the m-th forward differences of uniform samples."""
    h = float(np.mean(np.abs(np.diff(xs))))
    values = qs.astype(float)
    for level in range(1, m + 1):
        values = (values[1:] - values[:-1]) / ((xs[level:] - xs[:-level]) / h) * level
    return values


def rest_ends(curve: PPoly, x: np.ndarray, q: np.ndarray, order: int,
              periodic: bool = False) -> RestEnds:
    """Which ends of the fitted ``curve`` of samples (x, q) are at rest within the
    table's resolution (never for a periodic fit: its ends join each other)."""
    speeds = (float(curve(x[0], 1)), float(curve(x[-1], 1)))
    bounds = end_bound(x, q, order)
    if periodic:
        return RestEnds(False, False, speeds, bounds)
    return RestEnds(abs(speeds[0]) <= bounds[0], abs(speeds[1]) <= bounds[1], speeds,
                    bounds)


def clamped_interpolant(x: np.ndarray, q: np.ndarray, order: int, rest: RestEnds
                        ) -> PPoly | None:
    """The interpolating spline of ``order`` with v = 0 at the ends at rest, each in place
    of one not-a-knot condition there; None when the degree has none to give (order 2,
    a broken line: its velocity steps at every sample, at the ends too)."""
    from scipy.interpolate import make_interp_spline

    k = order - 1
    if k < 2 or not (rest.start or rest.end):
        return None
    # scipy's not-a-knot knots (make_interp_spline's default): the samples for an odd
    # degree, the midpoints for an even one, without the `half` next to each end
    half = (k + 1) // 2 if k % 2 else k // 2
    sites = x if k % 2 else (x[1:] + x[:-1]) / 2.0
    interior = sites[half:len(sites) - half]
    left = [sites[half - 1]] if rest.start else []  # the knot not-a-knot dropped last
    right = [sites[len(sites) - half]] if rest.end else []
    knots = np.concatenate(([x[0]] * (k + 1), left, interior, right, [x[-1]] * (k + 1)))
    try:
        spline = make_interp_spline(x, q, k=k, t=knots,
                                    bc_type=([(1, 0.0)] if rest.start else None,
                                             [(1, 0.0)] if rest.end else None))
    except (ValueError, np.linalg.LinAlgError) as exc:
        raise UserError(f"cannot fit a spline of order {order} at rest at its ends to "
                        f"these samples: {exc}", field="order") from None
    return _as_ppoly(spline, x[0], x[-1])


def _as_ppoly(spline: Any, a: float, b: float) -> PPoly:
    from sizer.laws.multipoint.sample_fit import _trimmed

    return _trimmed(spline, a, b)


# ------------------------------------------------------------ the interpolations
def interpolated_curve(interpolation: str, x: np.ndarray, q: np.ndarray,
                       v: np.ndarray | None = None, a: np.ndarray | None = None,
                       periodic: bool = False) -> PPoly:
    """The curve a controller runs through the points (module docstring), a PPoly.
    UserError (field ``interpolation``) for a value sizer does not know, for a linear
    table (not sizable) or a quintic Hermite one without velocities and accelerations."""
    from scipy.interpolate import BPoly, CubicSpline, PPoly

    if interpolation not in INTERPOLATIONS:
        raise UserError(f"unknown interpolation {interpolation!r}; interpolations: "
                        f"{', '.join(INTERPOLATIONS)} (or none: a spline fitted by "
                        f"order)", field="interpolation")
    if interpolation == "linear":
        raise UserError("a linear cam table cannot size a motor: its velocity steps at "
                        "every point, so its acceleration (and the torque) is a train of "
                        "impulses; give the table the interpolation the controller "
                        "smooths it with (cubic_spline, quintic_hermite) or fit it by "
                        "order", field="interpolation")
    if interpolation == "cubic_spline":
        if len(x) < 3 + periodic:
            raise UserError(f"a cubic spline needs at least {3 + periodic} points, got "
                            f"{len(x)}", field="interpolation")
        if periodic:
            wrapped = q.copy()
            slope = (q[-1] - q[0]) / (x[-1] - x[0])
            wrapped = q - slope * (x - x[0])
            wrapped[-1] = wrapped[0]
            spline = CubicSpline(x, wrapped, bc_type="periodic")
            c = spline.c.copy()
            c[-2] += slope
            c[-1] += slope * (x[:-1] - x[0])
            return PPoly(c, x, extrapolate=False)
        rest = cubic_rest(x, q)
        bc = (((1, 0.0) if rest.start else "not-a-knot"),
              ((1, 0.0) if rest.end else "not-a-knot"))
        spline = CubicSpline(x, q, bc_type=bc)
        return PPoly(spline.c, spline.x, extrapolate=False)
    if v is None or a is None:
        raise UserError("a quintic_hermite table needs velocity and acceleration columns: "
                        "name them with columns: [x, q, v, a]", field="columns")
    y = np.stack([q, v, a], axis=1)
    bpoly = BPoly.from_derivatives(x, y, orders=5)
    curve = PPoly.from_bernstein_basis(bpoly)
    return PPoly(curve.c, curve.x, extrapolate=False)


def cubic_rest(x: np.ndarray, q: np.ndarray) -> RestEnds:
    """The rest criterion of a cubic spline table: its not-a-knot spline's end speeds
    against the bound of order 4."""
    from scipy.interpolate import CubicSpline

    return rest_ends(CubicSpline(x, q, bc_type="not-a-knot"), x, q, 4)



# ------------------------------------------------------------ a table's fit
INTERPOLATION_FIELDS = ("interpolation",)
"""The cam table field that names a controller's interpolation."""


def cam_table_fit(fields: Mapping[str, Any], x: np.ndarray, q: np.ndarray,
                  v: np.ndarray | None = None, a: np.ndarray | None = None
                  ) -> tuple[SampleFit, RestEnds | None]:
    """The curve of a cam table's samples: the controller's ``interpolation`` when the
    mapping names one, else the spline fitted by ``order`` (sample_fit), in both cases
    with its ends at rest where the table is (module docstring); and which ends are at
    rest (None for a periodic or smoothing fit, and a quintic Hermite one, whose ends are
    the table's own velocities)."""
    from sizer.laws.multipoint.fields import boolean
    from sizer.laws.multipoint.sample_fit import build_cam_table_samples

    interpolation = fields.get("interpolation")
    if interpolation is None:
        fit = build_cam_table_samples(fields, x, q)
        if fit.order <= 2:  # a broken line: as a linear table, not sizable
            raise UserError(f"a cam table fitted with order {fit.order} is a broken line: "
                            "its velocity steps at every point, so its acceleration (and "
                            "the torque) is a train of impulses; fit it with order 4 or "
                            "more, or give the interpolation the controller smooths it "
                            "with (cubic_spline, quintic_hermite)", field="order")
        if fit.smoothing or fit.periodic:
            return (fit, None)
        rest = rest_ends(fit.curve, fit.x, fit.q, fit.order)
        clamped = clamped_interpolant(fit.x, fit.q, fit.order, rest)
        return (fit if clamped is None else _refitted(fit, clamped)), rest
    if not isinstance(interpolation, str) or interpolation not in INTERPOLATIONS:
        raise UserError(f"unknown interpolation {interpolation!r}; interpolations: "
                        f"{', '.join(INTERPOLATIONS)} (or none: a spline fitted by "
                        f"order)", field="interpolation")
    clash = [k for k in ("order", "smoothing") if fields.get(k) is not None]
    if clash:
        raise UserError(f"interpolation {interpolation} is the controller's own curve "
                        f"through the points: it takes no {' or '.join(clash)} (those fit "
                        f"a spline of sizer's)", field=clash[0])
    periodic = boolean(fields, "periodic", False)
    curve = interpolated_curve(interpolation, x, q, v, a, periodic=periodic)
    ends = None if periodic or interpolation != "cubic_spline" else cubic_rest(x, q)
    return _interpolated_fit(curve, x, q, periodic), ends


def _refitted(fit: SampleFit, curve: PPoly) -> SampleFit:
    """``fit`` with its curve replaced by ``curve`` (the noise report kept: the clamp
    changes the curve within the table's resolution)."""
    from sizer.laws.multipoint.sample_fit import _derivative_rms

    residual = curve(fit.x) - fit.q
    return replace(fit, curve=curve, max_residual=float(np.max(np.abs(residual))),
                   rms_residual=float(np.sqrt(np.mean(residual ** 2))),
                   derivative_rms=_derivative_rms(curve))


def _interpolated_fit(curve: PPoly, x: np.ndarray, q: np.ndarray, periodic: bool
                      ) -> SampleFit:
    from sizer.laws.multipoint.sample_fit import SampleFit, _derivative_rms

    residual = curve(x) - q
    order = curve.c.shape[0]
    return SampleFit(curve=curve, x=x, q=q, order=order, smoothing=None, periodic=periodic,
                     max_residual=float(np.max(np.abs(residual))),
                     rms_residual=float(np.sqrt(np.mean(residual ** 2))),
                     derivative_rms=_derivative_rms(curve), noise_sigma=None,
                     noise_rms=None, noise_peak=None)


# ------------------------------------------------------------ a span of a table
def restricted_curve(curve: PPoly, x0: float, x1: float) -> PPoly:
    """``curve`` over [x0, x1] alone (inside its breakpoints): the pieces there as they
    are, the first one re-expanded about x0 where x0 is inside a piece (its Taylor
    coefficients are the curve's derivatives there), the last one ending at x1. The curve
    is the whole table's (its interpolation or fit, its ends clamped where the table is at
    rest), so the span is exactly what the controller runs between those points."""
    import math

    from scipy.interpolate import PPoly

    x = np.asarray(curve.x, dtype=float)
    c = np.asarray(curve.c, dtype=float)
    first = int(np.searchsorted(x, x0, side="right")) - 1
    last = int(np.searchsorted(x, x1, side="left"))  # x[last - 1] < x1 <= x[last]
    first = min(max(first, 0), len(x) - 2)
    last = min(max(last, first + 1), len(x) - 1)
    coefficients = c[:, first:last].copy()
    if x[first] != x0:  # inside a piece: its Taylor coefficients about x0
        m = c.shape[0] - 1
        inside = PPoly(c[:, first:first + 1], x[first:first + 2], extrapolate=True)
        coefficients[:, 0] = [float(inside(x0, nu=m - k)) / math.factorial(m - k)
                              for k in range(m + 1)]
    breaks = np.concatenate(([x0], x[first + 1:last], [x1]))
    return PPoly(coefficients, breaks, extrapolate=False)
