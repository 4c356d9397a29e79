"""Coefficient segments (issue 37): the profile as segments Y = A0 + A1 X + ... + A6 X^6
+ B0 sin(B1 X + B2), the form of a Siemens Technology CPU's MC_CamSectorAdd (Type 0,
"polynomial"; docs/cam-coefficients.md), and their certificate.

Splitting: the profile's natural points, its law's pieces (and its dwells). A piece that
is a polynomial of degree <= 6 plus at most one sine is written exactly, from its closed
form read without sampling:

- ``Piece.form`` (sizer.laws.pieces.TrigPolyForm: set by trig_poly_piece, carried through
  ``mirrored``): cycloidal, harmonic, modified sine and trapezoid, trapezoid, double S,
  fifteen segments...;
- the law's PieceTable (a cubic or quintic spline, a cam table fitted by a PPoly);
- a piece that declares its ``degree`` <= 6 and nothing else (poly3, poly5: Bernstein
  form): its Taylor coefficients at its start, q^(k)(start) / k!, k <= degree.

Any other piece (poly7, the exponential law, a Fourier law of several sines, a shaped
law, a NURBS) is fitted: on each sub-interval the polynomial of degree 6 matching the
position, velocity and acceleration of the law at both ends (C2 joins) and its position
at the middle; sub-intervals are halved until the position error (the certificate's true
maximum) is within the tolerance, at most MAX_SEGMENTS segments in all, none shorter
than MIN_SHARE of the span, and only while halving lowers the error (absolute-X
coefficients of a short segment far from X = 0 cancel: their rounding sets a floor).

Coordinates: X is the absolute master coordinate (time in s, or the master angle in
deg), B1 in rad per master unit: inferred from the manual (the docs say why), not stated.
A segment far from X = 0 has large, cancelling coefficients: ``amplification`` (the
largest sum |A_i X^i| over a segment, over the stroke) says how much of the stroke the
rounding of one coefficient in a given precision can move.

Certificate: the segments (the written file parsed back) evaluated as the formula says,
in double precision, against the profile: the largest errors of position, velocity and
acceleration at the segment ends and at the interior extrema of the difference (the
roots of its next derivative, bracketed on SAMPLES + 1 points per segment and refined,
as sizer.export.hermite_certificate does); and an estimate of the position error when
the coefficients, X and the evaluation are single precision (REAL), on a grid.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from sizer.export.extremes import Extreme, largest_difference
from sizer.export.profile import CamProfile
from sizer.laws.pieces import TrigPolyForm
from sizer.laws.segment_table import DEGREE, CoefficientSegment
from sizer.numerics.arrays import sorted_unique

MAX_SEGMENTS = 256
"""sizer's own cap on the segments of one export (not a controller limit: the manual
says several MC_CamSectorAdd calls add more than 4 polynomials; no maximum is stated)."""
MIN_SHARE = 1e-4
"""Fitted sub-intervals are not halved below this share of the span, nor when halving
does not lower the error (the rounding floor of the absolute-X coefficients)."""
SAMPLES = 32
"""Samples of e^(k+1) per segment (sign changes bracket the extrema of e^(k))."""
REAL_SAMPLES = 256
"""Grid points per segment of the single-precision estimate."""


@dataclass(frozen=True)
class SegmentErrors:
    """The largest errors of the segments against the profile (file units)."""

    position: Extreme
    velocity: Extreme
    acceleration: Extreme


@dataclass(frozen=True)
class Written:
    """One segment and how it was obtained."""

    segment: CoefficientSegment
    piece: int
    """The profile piece it lies on."""
    exact: bool
    how: str
    """'form', 'piece table', 'taylor', 'dwell' (exact) or 'fitted'."""


@dataclass(frozen=True)
class SegmentExport:
    """The segments of a profile, certified."""

    profile: CamProfile
    written: tuple[Written, ...]
    errors: SegmentErrors
    real_position: Extreme
    """Estimate: single-precision coefficients, X and evaluation (a grid, not a bound)."""
    amplification: float
    tolerance: float
    capped: bool
    """Splitting stopped at MAX_SEGMENTS or at MIN_SHARE: the tolerance is not met."""

    @property
    def segments(self) -> tuple[CoefficientSegment, ...]:
        return tuple(w.segment for w in self.written)

    @property
    def relative_position_error(self) -> float:
        return self.errors.position.max / abs(self.profile.stroke)

    @property
    def met(self) -> bool:
        return self.relative_position_error <= self.tolerance

    @property
    def met_in_single_precision(self) -> bool:
        """The single-precision estimate (the data block's REAL) within the tolerance."""
        return self.real_position.max / abs(self.profile.stroke) <= self.tolerance

    @property
    def fitted_pieces(self) -> int:
        return len({w.piece for w in self.written if not w.exact})


# ------------------------------------------------------------------ exact forms
def piece_form(profile: CamProfile, index: int) -> tuple[TrigPolyForm, str] | None:
    """The exact closed form of the profile's piece ``index`` in its law's tau (None: no
    polynomial of degree <= 6 plus one sine is known for it)."""
    _, segment_of, local_of = profile._pieces
    s = profile.segments[int(segment_of[index])]
    if s.law is None:
        return TrigPolyForm((0.0,)), "dwell"
    j = int(local_of[index])
    piece = s.law.pieces[j]
    form = piece.form
    if form is not None:
        poly = _trimmed(form.poly)
        if len(poly) - 1 <= DEGREE and len(form.sines) <= 1:
            return TrigPolyForm(poly, form.origin, form.sines), "form"
        return None
    table = s.law.piece_table()
    if table is not None:
        row = np.asarray(table.rows[0][j], dtype=float) / table.size
        row[0] -= table.offset / table.size
        poly = _trimmed(tuple(float(c) for c in row))
        if len(poly) - 1 <= DEGREE:
            return TrigPolyForm(poly, float(table.starts[j])), "piece table"
        return None
    if piece.degree is not None and piece.degree <= DEGREE:
        tau = np.array([piece.start])
        poly = tuple(float(s.law.piece_derivative(j, tau, k)[0]) / math.factorial(k)
                     for k in range(piece.degree + 1))
        return TrigPolyForm(poly, piece.start), "taylor"
    return None


def _trimmed(poly: Sequence[float]) -> tuple[float, ...]:
    poly = list(poly)
    while len(poly) > 1 and poly[-1] == 0.0:
        poly.pop()
    return tuple(poly)


def absolute(local: Sequence[float], x0: float) -> tuple[float, ...]:
    """The coefficients in X of sum local[k] (X - x0)^k (binomial expansion)."""
    out = [0.0] * (DEGREE + 1)
    for k, d in enumerate(local):
        for j in range(k + 1):
            out[j] += d * math.comb(k, j) * (-x0) ** (k - j)
    return tuple(out)


def exact_segment(profile: CamProfile, index: int, form: TrigPolyForm,
                  x1: float, x2: float) -> CoefficientSegment:
    """The piece's form in the master's X: y = y0 + H q((X - start) / span)."""
    _, segment_of, _ = profile._pieces
    s = profile.segments[int(segment_of[index])]
    H, span = s.stroke, s.span
    x_origin = s.start + form.origin * span
    local = [H * c / span ** k for k, c in enumerate(form.poly)]
    local[0] += s.origin
    b = (0.0, 0.0, 0.0)
    if form.sines:
        amplitude, omega, phase = form.sines[0]
        b = (H * amplitude, omega / span, phase - omega * s.start / span)
    return _with_ends(profile, index, x1, x2, absolute(local, x_origin), b)


def _with_ends(profile: CamProfile, index: int, x1: float, x2: float,
               a: tuple[float, ...], b: tuple[float, float, float]) -> CoefficientSegment:
    ends = profile.derivative(np.array([x1, x2]), 0, np.array([index, index]))
    return CoefficientSegment(x1, float(ends[0]), x2, float(ends[1]), a, b)


# ----------------------------------------------------------------- fitted pieces
def fitted_segment(profile: CamProfile, index: int, x1: float, x2: float
                   ) -> CoefficientSegment:
    """The degree-6 polynomial with the profile's y, v, a at both ends and its y at the
    middle; solved in s = (X - x1) / (x2 - x1) in [0, 1] (well conditioned)."""
    h = x2 - x1
    ends = np.array([x1, x2])
    piece = np.array([index, index])
    y = [profile.derivative(ends, k, piece) * h ** k for k in (0, 1, 2)]
    middle = float(profile.derivative(np.array([x1 + h / 2]), 0, np.array([index]))[0])
    rows, rhs = [], []
    for k in (0, 1, 2):
        for side, s in enumerate((0.0, 1.0)):
            rows.append([math.perm(p, k) * s ** (p - k) if p >= k else 0.0
                         for p in range(DEGREE + 1)])
            rhs.append(y[k][side])
    rows.append([0.5 ** p for p in range(DEGREE + 1)])
    rhs.append(middle)
    e = np.linalg.solve(np.array(rows), np.array(rhs))
    local = [float(c) / h ** p for p, c in enumerate(e)]
    return _with_ends(profile, index, x1, x2, absolute(local, x1), (0.0, 0.0, 0.0))


# ------------------------------------------------------------------- the export
def export_segments(profile: CamProfile, tolerance: float,
                    limit: int = MAX_SEGMENTS) -> SegmentExport:
    """The profile as coefficient segments, exact where its pieces allow, fitted within
    ``tolerance`` (a fraction of the stroke) elsewhere, certified (module docstring)."""
    if not (math.isfinite(tolerance) and tolerance > 0.0):
        raise ValueError(f"the tolerance must be positive, got {tolerance!r}")
    breaks = profile.breakpoints
    budget = abs(profile.stroke) * tolerance
    plan: list[list[Written]] = []
    fitted: list[int] = []
    for index in range(len(breaks) - 1):
        x1, x2 = float(breaks[index]), float(breaks[index + 1])
        if not x2 > x1:
            plan.append([])
            continue
        found = piece_form(profile, index)
        if found is None:
            plan.append([Written(fitted_segment(profile, index, x1, x2), index, False,
                                 "fitted")])
            fitted.append(index)
        else:
            form, how = found
            plan.append([Written(exact_segment(profile, index, form, x1, x2), index, True,
                                 how)])
    capped = False
    count = sum(len(p) for p in plan)
    for index in fitted:  # halve a fitted piece's worst sub-interval until within budget
        parts = plan[index]
        errors = [position_error(profile, parts)]
        while True:
            worst = int(np.argmax(errors))
            if errors[worst] <= budget:
                break
            s = parts[worst].segment
            if count + 1 > limit or s.x2 - s.x1 < MIN_SHARE * profile.span:
                capped = True  # the cap, or the rounding floor: halving cannot help
                break
            middle = 0.5 * (s.x1 + s.x2)
            halves = [Written(fitted_segment(profile, index, a, b), index, False, "fitted")
                      for a, b in ((s.x1, middle), (middle, s.x2))]
            half_errors = [position_error(profile, [h]) for h in halves]
            if max(half_errors) >= errors[worst]:
                capped = True  # no better: the rounding of the absolute-X coefficients
                break
            parts[worst:worst + 1] = halves
            errors[worst:worst + 1] = half_errors
            count += 1
    written = tuple(w for part in plan for w in part)
    return certified(profile, written, tolerance, capped)


def certified(profile: CamProfile, written: Sequence[Written], tolerance: float,
              capped: bool = False) -> SegmentExport:
    """The export of ``written`` with its certificate (the caller may pass the segments
    parsed back from the written file)."""
    written = tuple(written)
    errors = segment_errors(profile, written)
    return SegmentExport(profile, written, errors, real_position_estimate(profile, written),
                         amplification(profile, [w.segment for w in written]), tolerance,
                         capped)


def with_segments(export: SegmentExport, segments: Sequence[CoefficientSegment]
                  ) -> SegmentExport:
    """The export's certificate recomputed on ``segments`` (the file read back)."""
    if len(segments) != len(export.written):
        raise ValueError("the file holds another number of segments than was written")
    written = [Written(s, w.piece, w.exact, w.how)
               for s, w in zip(segments, export.written, strict=True)]
    return certified(export.profile, written, export.tolerance, export.capped)


# ------------------------------------------------------------------ certificate
def _difference(profile: CamProfile, written: Sequence[Written], x: np.ndarray,
                which: np.ndarray, order: int) -> np.ndarray:
    """e^(order) = profile - segment at x, x[i] on segment which[i]."""
    out = np.empty(x.shape)
    for k in sorted_unique(which):
        mask = which == k
        w = written[int(k)]
        out[mask] = (profile.derivative(x[mask], order, np.full(mask.sum(), w.piece))
                     - w.segment.derivative(x[mask], order))
    return out


def _extreme(profile: CamProfile, written: Sequence[Written], order: int) -> Extreme:
    lo = np.array([w.segment.x1 for w in written])
    hi = np.array([w.segment.x2 for w in written])

    def on_cells(t: np.ndarray, cell: np.ndarray, k: int) -> np.ndarray:
        return _difference(profile, written, t, cell, k)

    return largest_difference(on_cells, lo, hi, order, SAMPLES)


def segment_errors(profile: CamProfile, written: Sequence[Written]) -> SegmentErrors:
    """The certificate's true largest errors (module docstring)."""
    return SegmentErrors(*(_extreme(profile, written, k) for k in (0, 1, 2)))


def position_error(profile: CamProfile, written: Sequence[Written]) -> float:
    return _extreme(profile, written, 0).max


def amplification(profile: CamProfile, segments: Sequence[CoefficientSegment]) -> float:
    """max over segments and their ends of sum |A_i X^i| + |B0|, over |stroke|: the
    factor by which a relative rounding of the coefficients (or of the evaluation) can
    move the position, in strokes."""
    worst = 0.0
    for s in segments:
        for x in (s.x1, s.x2):
            worst = max(worst, sum(abs(c) * abs(x) ** i for i, c in enumerate(s.a))
                        + abs(s.b[0]))
    return worst / abs(profile.stroke)


def real_position_estimate(profile: CamProfile, written: Sequence[Written]) -> Extreme:
    """ESTIMATE, on REAL_SAMPLES + 1 points per segment: the position error when X, the
    coefficients and the evaluation (Horner, sin) are IEEE single precision, as a REAL
    data block suggests. Not a bound: the CPU recomputes the coefficients (manual)."""
    worst, at = 0.0, 0.0
    fractions = np.linspace(0.0, 1.0, REAL_SAMPLES + 1)
    for w in written:
        s = w.segment
        x = s.x1 + (s.x2 - s.x1) * fractions
        x32 = x.astype(np.float32)
        a32 = np.asarray(s.a, dtype=np.float32)
        y = np.full(x32.shape, a32[-1], dtype=np.float32)
        for c in a32[-2::-1]:
            y = (c + y * x32).astype(np.float32)
        b0, b1, b2 = (np.float32(v) for v in s.b)
        if b0 != 0.0:
            y = (y + b0 * np.sin((b1 * x32 + b2).astype(np.float32))).astype(np.float32)
        law = profile.derivative(x, 0, np.full(x.shape, w.piece))
        err = np.abs(y.astype(float) - law)
        k = int(np.argmax(err))
        if err[k] > worst:
            worst, at = float(err[k]), float(x[k])
    return Extreme(worst, at)
