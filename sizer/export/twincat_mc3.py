"""TwinCAT 3 MC3 motion functions: the law itself as the controller names it (segment-exact).

A TwinCAT 3 MC3 cam (TF5550 Tc3_Mc3Camming) is an ARRAY OF MotionFunctionPoint referenced
by MC_CAM_REF {PointsAddress, NumberOfPoints}. Each point carries the FunctionType
(EMotionFunctionType) of the segment that starts at it, its MasterPosition and
SlavePosition, optional boundary conditions (SlaveVelocity, SlaveAcceleration, SlaveJerk;
default #Ignore) and SymmetryRatio (the normalized inflection point of a rest-to-rest
motion function; default #Ignore). Sources (infosys.beckhoff.com, TF55xx TC3 MC3):
MotionFunctionPoint .../tf55xx_tc3_mc3/21872070667.html, EMotionFunctionType
.../21872045067.html, MC_CAM_REF .../21872066827.html.

A move exports as ONE segment (its start point and the next point) whose FunctionType IS
sizer's law; a dwell as a Linear segment of zero slope. Only laws whose definition is
that of a TwinCAT function type are mapped; any other law is refused
(:class:`UnnamedLawError`): no approximation is exported under a law's name.

The mapping and its basis:

- ``polynomial(degree=3|5|7)`` -> Polynomial3/5/7: the rest-to-rest polynomial of degree
  2m+1 is the ONLY polynomial of that degree with y' = ... = y^(m) = 0 at both ends, and
  these boundary conditions are written (SlaveVelocity, and SlaveAcceleration /
  SlaveJerk where the law's are zero): exact by construction.
- ``cycloidal`` -> Sinusoid and ``modified_sinusoidal`` -> ModifiedSinusoid
  (SymmetryRatio 0.5): MC3's page says only "Simple sinusoidal motion law" and "Modified
  sinusoidal motion law"; the identification with VDI 2143's Sinuslinie (the cycloid,
  acceleration one full sine wave) and modifizierte Sinuslinie (inflection point 0.5)
  follows the MC2 names of the same types (MOTIONFUNCTYPE_SINUSLINIE, _MODSINUSLINIE) and
  is INFERRED, not read: the certificate gives the peak velocity and acceleration that
  MC_CamObject.ComputeCharacteristics must return for the controller to agree
  (cycloid 2 h/T and 2 pi h/T^2; a harmonic would give pi/2 h/T and pi^2/2 h/T^2).

A ``cycle:`` of segments (sizer.export.cycle_profile): a run is Linear (its slope, with
SlaveVelocity at both ends); a move between boundary speeds only by
``polynomial(degree=3|5|7)`` -> Polynomial3/5/7 with its end conditions written at both
points (SlaveVelocity = the design's boundary speed; degree 5 and 7 SlaveAcceleration,
7 SlaveJerk, as the sizing's form fixes them). A polynomial of degree 2m+1 is ONE
polynomial once its positions and derivatives of orders 1..m are given at both ends (the
Hermite system is non-singular), and the sizing's boundary form meets exactly these
conditions: the controller's curve is evaluated from the WRITTEN conditions
(:func:`_hermite`, a dense solve independent of sizer.laws.boundary_speeds) and the
certificate finds it equal to the sized shape to rounding. Any other law between boundary
speeds is refused.

Pure numpy; no files.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from sizer.export.numbers import exact
from sizer.export.profile import CamProfile
from sizer.laws.base import MotionLaw
from sizer.laws.per_move import RankedLaw, one_law
from sizer.numerics.arrays import sorted_unique

PI = math.pi
LINEAR = "Linear"


class UnnamedLawError(ValueError):
    """The law is not one TwinCAT MC3 names: it has no exact motion function."""


@dataclass(frozen=True)
class NamedLaw:
    """A sizer law as a TwinCAT MC3 function type."""

    function_type: str
    formula: str
    basis: str
    confirmed: bool
    """True when the definition is certain (a polynomial fixed by its boundary
    conditions); False when the identification is inferred from names (see module)."""


POLYNOMIALS = {3: "Polynomial3", 5: "Polynomial5", 7: "Polynomial7"}
POLYNOMIAL_DEGREES = {name: degree for degree, name in POLYNOMIALS.items()}
"""The degree of each polynomial function type."""
SUPPORTED = ("polynomial(degree=3) (poly3)", "polynomial(degree=5) (poly5)",
             "polynomial(degree=7) (poly7)", "cycloidal", "modified_sinusoidal")


def named_law(ranked: RankedLaw) -> NamedLaw:
    """The TwinCAT function type that IS ``law``, or UnnamedLawError."""
    law = one_law(ranked)
    if law.law_id == "polynomial":
        degree = int(law.params["degree"])
        if degree in POLYNOMIALS:
            formula = {3: "3t^2 - 2t^3", 5: "10t^3 - 15t^4 + 6t^5",
                       7: "35t^4 - 84t^5 + 70t^6 - 20t^7"}[degree]
            return NamedLaw(POLYNOMIALS[degree], formula,
                            "the only polynomial of its degree with the written rest "
                            "boundary conditions", True)
    if law.law_id == "cycloidal":
        return NamedLaw("Sinusoid", "t - sin(2 pi t)/(2 pi)",
                        "VDI 2143 Sinuslinie (MC2 MOTIONFUNCTYPE_SINUSLINIE): inferred",
                        False)
    if law.law_id == "modified_sinusoidal":
        return NamedLaw("ModifiedSinusoid",
                        "VDI 2143 modified sine, inflection point 0.5 (sine quarter "
                        "waves of period 1/2 on [0, 1/8] and [7/8, 1], of period 3/2 "
                        "between)",
                        "VDI 2143 modifizierte Sinuslinie (MC2 "
                        "MOTIONFUNCTYPE_MODSINUSLINIE), SymmetryRatio 0.5: inferred",
                        False)
    raise UnnamedLawError(
        f"{law.spec} is not a law TwinCAT MC3 names (EMotionFunctionType); "
        f"twincat-mc3 exports only {', '.join(SUPPORTED)}: export this law as a point "
        "table (--to csv, sew, codesys-xy) instead")


@dataclass(frozen=True)
class MotionFunctionPoint:
    """One MotionFunctionPoint. None: the field is left out (its default #Ignore)."""

    function_type: str
    master: float
    slave: float
    velocity: float | None = None
    acceleration: float | None = None
    jerk: float | None = None
    symmetry_ratio: float | None = None


BOUNDARY_SUPPORTED = ("polynomial(degree=3) (poly3)", "polynomial(degree=5) (poly5)",
                      "polynomial(degree=7) (poly7)")
"""The laws twincat-mc3 exports for a move between boundary speeds (a run: Linear)."""


def segment_type(law: MotionLaw | None, name: str = "") -> str:
    """The function type of a profile segment: a dwell or a run Linear, a move its law's
    (:func:`named_law`); a move between boundary speeds (a frozen shape,
    sizer.export.cycle_profile) only as Polynomial3/5/7, whose boundary conditions the
    points carry: UnnamedLawError for any other law."""
    from sizer.export.cycle_profile import FrozenShape

    if law is None:
        return LINEAR
    if not isinstance(law, FrozenShape):
        return named_law(law).function_type
    if law.is_run:
        return LINEAR
    source = law.source
    if (source is not None and source.law_id == "polynomial"
            and int(source.params["degree"]) in POLYNOMIALS):
        return POLYNOMIALS[int(source.params["degree"])]
    raise UnnamedLawError(
        f"{'segment ' + repr(name) + ': ' if name else ''}{law.spec}: "
        f"twincat-mc3 exports a move between boundary speeds only as a "
        f"polynomial whose written end conditions fix it ({', '.join(BOUNDARY_SUPPORTED)});"
        f" give the move that `law:` or size with one of them (--law), or export a point "
        f"table (--to csv, sew, codesys-xy, codesys-xyva)")


Ends = tuple[tuple[float | None, float | None, float | None],
             tuple[float | None, float | None, float | None]]


def _segment_ends(segment, function_type: str) -> Ends:
    """((v, a, j) at the start, at the end) of a segment in file units, exact where the
    sizing's form fixes them (None: not fixed, left out unless zero to 1e-9)."""
    from sizer.export.cycle_profile import FrozenShape

    law = segment.law
    if law is None:
        return (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)
    X, H = segment.span, segment.stroke
    if isinstance(law, FrozenShape):
        v0, v1 = segment.end_speeds or tuple(H / X * s for s in law.speeds)
        if law.is_run:
            return (v0, 0.0, 0.0), (v1, 0.0, 0.0)
        degree = POLYNOMIAL_DEGREES[function_type]
        # degree 2m+1 fixes the derivatives of orders 1..m at both ends
        a0, a1 = ((H / X ** 2 * r for r in law.accelerations) if degree >= 5
                  else (None, None))
        j = 0.0 if degree == 7 else None
        return (v0, a0, j), (v1, a1, j)
    (za0, zj0), (za1, zj1) = _end_derivatives(law)
    return ((0.0, 0.0 if za0 else None, 0.0 if za0 and zj0 else None),
            (0.0, 0.0 if za1 else None, 0.0 if za1 and zj1 else None))


def _end_derivatives(law: MotionLaw | None) -> tuple[tuple[bool, bool], tuple[bool, bool]]:
    """((acceleration zero, jerk zero) at the start, at the end) of a law (a dwell: all)."""
    if law is None:
        return (True, True), (True, True)
    ends = np.array([0.0, 1.0])
    acc = np.abs(law.derivative(ends, 2)) < 1e-9
    jerk = np.abs(law.derivative(ends, 3)) < 1e-9
    return (bool(acc[0]), bool(jerk[0])), (bool(acc[1]), bool(jerk[1]))


def _agreed(values: list[float | None], scale: float) -> float | None:
    """The common value of both sides of a point (None if one side is not fixed or they
    differ by more than 1e-9 of ``scale``)."""
    if any(v is None for v in values):
        return None
    known = [float(v) for v in values if v is not None]
    if max(known) - min(known) > 1e-9 * scale:
        return None
    return known[-1]


def motion_functions(profile: CamProfile) -> tuple[MotionFunctionPoint, ...]:
    """The points of the profile's segments: a move's start point carries its function
    type (a move from rest also SymmetryRatio 0.5), a dwell's and a run's Linear. Each
    point carries the slave velocity there (the boundary speed the move was sized for;
    0 at a rest); SlaveAcceleration and SlaveJerk where every segment meeting there fixes
    the same value (a rest law's zero, a boundary polynomial's form). The last point
    repeats the last segment's type (no segment starts at it). A polynomial between
    boundary speeds needs its conditions written at both ends (UnnamedLawError where a
    join's two sides differ)."""
    from sizer.export.cycle_profile import FrozenShape

    segments = profile.segments
    types = [segment_type(s.law, s.name) for s in segments]
    ends = [_segment_ends(s, t) for s, t in zip(segments, types, strict=True)]
    scales = [max(profile.peak_velocity, 1e-300), max(profile.peak_acceleration, 1e-300)]
    points = []
    for i, segment in enumerate((*segments, segments[-1])):
        last = i == len(segments)
        master = segment.start + segment.span if last else segment.start
        slave = segment.origin + segment.stroke if last else segment.origin
        meeting = ([ends[i - 1][1]] if i > 0 else []) + ([] if last else [ends[i][0]])
        velocity = _agreed([m[0] for m in meeting], scales[0])
        if velocity is None:
            raise UnnamedLawError(
                f"the velocity steps at master {master:g}: motion functions meet with one "
                f"SlaveVelocity")
        acceleration = _agreed([m[1] for m in meeting],
                               scales[1] if np.isfinite(scales[1]) else 1.0)
        jerk = None if acceleration is None else _agreed([m[2] for m in meeting], 1.0)
        rest_move = (not last and segment.law is not None
                     and not isinstance(segment.law, FrozenShape))
        points.append(MotionFunctionPoint(
            types[-1] if last else types[i], float(master), float(slave), velocity,
            acceleration, jerk, 0.5 if rest_move else None))
    for k, segment in enumerate(segments):
        if not isinstance(segment.law, FrozenShape) or segment.law.is_run:
            continue
        degree = POLYNOMIAL_DEGREES[types[k]]
        for p, side in ((points[k], "start"), (points[k + 1], "end")):
            if (degree >= 5 and p.acceleration is None) or (degree == 7 and p.jerk is None):
                raise UnnamedLawError(
                    f"segment {segment.name!r}: its {side}'s acceleration (or jerk) differs "
                    f"from its neighbour's, and a MotionFunctionPoint carries one: "
                    f"{types[k]} is not fixed there")
    return tuple(points)


# --------------------------------------------------------- the controller's curve
def normalized(function_type: str, t: np.ndarray, order: int) -> np.ndarray:
    """d^order q/dt^order of a rest-to-rest function type over t in [0, 1], q from 0 to
    1, from its published definition (the polynomials by their boundary conditions,
    VDI 2143 for the sinusoids); Linear: q = t."""
    t = np.asarray(t, dtype=float)
    if function_type in POLYNOMIALS.values():
        coefficients = {"Polynomial3": {2: 3.0, 3: -2.0},
                        "Polynomial5": {3: 10.0, 4: -15.0, 5: 6.0},
                        "Polynomial7": {4: 35.0, 5: -84.0, 6: 70.0, 7: -20.0}}[function_type]
        out = np.zeros(t.shape)
        for power, c in coefficients.items():
            if power >= order:
                out += c * math.perm(power, order) * t ** (power - order)
        return out
    if function_type == "Sinusoid":
        w = 2.0 * PI
        return _trig(t, order, (0.0, 1.0), -1.0 / w, w, 0.0)
    if function_type == "ModifiedSinusoid":
        k = 1.0 / (4.0 + PI)
        out = np.empty(t.shape)
        first, last = t <= 0.125, t >= 0.875
        middle = ~(first | last)
        out[first] = _trig(t[first], order, (0.0, PI * k), -0.25 * k, 4 * PI, 0.0)
        out[middle] = _trig(t[middle], order, (2.0 * k, PI * k), -2.25 * k, 4 * PI / 3,
                            PI / 3)
        out[last] = _trig(t[last], order, (4.0 * k, PI * k), -0.25 * k, 4 * PI, 0.0)
        return out
    if function_type == LINEAR:
        return _trig(t, order, (0.0, 1.0), 0.0, 0.0, 0.0)
    raise ValueError(f"no definition of {function_type!r}")


def _trig(t: np.ndarray, order: int, line: tuple[float, float], a: float, w: float,
          phase: float) -> np.ndarray:
    """d^order/dt^order of line[0] + line[1] t + a sin(w t + phase)."""
    out = a * w ** order * np.sin(w * t + phase + order * PI / 2)
    if order == 0:
        out = out + line[0] + line[1] * t
    elif order == 1:
        out = out + line[1]
    return out


def curve(points: tuple[MotionFunctionPoint, ...], x: np.ndarray, order: int,
          segment: np.ndarray | None = None) -> np.ndarray:
    """The controller's curve: d^order slave / d master^order at x, each segment between
    consecutive points by its function type (on the given segments, else the one that
    holds x)."""
    x = np.asarray(x, dtype=float)
    masters = np.array([p.master for p in points])
    index = (np.clip(np.searchsorted(masters[:-1], x, side="right") - 1, 0,
                     len(points) - 2) if segment is None else np.asarray(segment))
    out = np.zeros(x.shape)
    for k in sorted_unique(index):
        mask = index == k
        a, b = points[k], points[k + 1]
        span, rise = b.master - a.master, b.slave - a.slave
        t = (x[mask] - a.master) / span
        if a.function_type in POLYNOMIALS.values() and not _at_rest(a, b):
            out[mask] = _hermite(a, b, a.function_type, t, order) / span ** order
            continue
        out[mask] = rise / span ** order * normalized(a.function_type, t, order)
        if order == 0:
            out[mask] += a.slave
    return out


def _at_rest(a: MotionFunctionPoint, b: MotionFunctionPoint) -> bool:
    """Both ends at rest with no other condition written but zeros: the published
    rest-to-rest polynomial."""
    return all(not v for p in (a, b) for v in (p.velocity, p.acceleration, p.jerk))


def _hermite(a: MotionFunctionPoint, b: MotionFunctionPoint, function_type: str,
             t: np.ndarray, order: int) -> np.ndarray:
    """d^order y/dt^order, t in [0, 1] over the segment, of THE polynomial of the type's
    degree 2m+1 with the points' positions and their written derivatives of orders 1..m
    (a condition left out read as 0) at both ends: the 2m+2 conditions fix it. In the
    segment's own variable t (d/dt = span d/dx), solved as a dense linear system in the
    monomial basis 1, t, ..., t^(2m+1) (independently of sizer.laws.boundary_speeds)."""
    degree = POLYNOMIAL_DEGREES[function_type]
    m = (degree - 1) // 2
    span = b.master - a.master
    rows, rhs = [], []
    for p, t_end in ((a, 0.0), (b, 1.0)):
        given = [p.slave, p.velocity, p.acceleration, p.jerk]
        for k in range(m + 1):
            rows.append([math.perm(j, k) * t_end ** (j - k) if j >= k else 0.0
                         for j in range(degree + 1)])
            rhs.append((given[k] or 0.0) * span ** k)
    c = np.linalg.solve(np.array(rows), np.array(rhs))
    out = np.zeros(t.shape)
    for j in range(degree, order - 1, -1):
        out = out * t + c[j] * math.perm(j, order)
    return out


@dataclass(frozen=True)
class ExactErrors:
    """The largest |controller curve - law| of position, velocity and acceleration (in
    the slave unit per master unit^k) over the checked abscissae, and where."""

    position: float
    velocity: float
    acceleration: float
    at: tuple[float, float, float]
    checked: int


CHECK_PER_SEGMENT = 1001
"""Equidistant abscissae per segment, beside the law's breakpoints and extrema."""


def exact_errors(profile: CamProfile, points: tuple[MotionFunctionPoint, ...]
                 ) -> ExactErrors:
    """The controller's curve against the law: zero to rounding for a named law. Checked
    at every segment's ends and the law's breakpoints, at the law's interior extrema of
    position, velocity and acceleration (tau = 1/2, where the acceleration is zero; the
    peaks of the acceleration: the jerk's zeros located on the grid), and on an
    equidistant grid, one-sided per segment."""
    xs, segments = [], []
    for k, s in enumerate(profile.segments):
        taus = [np.linspace(0.0, 1.0, CHECK_PER_SEGMENT)]
        if s.law is not None:
            taus.append(np.array([piece.start for piece in s.law.pieces] + [0.5]))
            taus.append(_extrema(s.law))
        tau = sorted_unique(np.concatenate(taus))
        xs.append(s.start + tau * s.span)
        segments.append(np.full(tau.shape, k))
    x, seg = np.concatenate(xs), np.concatenate(segments)
    piece = _law_piece(profile, x, seg)
    errors, where = [], []
    for order in range(3):
        e = np.abs(curve(points, x, order, seg) - profile.derivative(x, order, piece))
        i = int(np.argmax(e))
        errors.append(float(e[i]))
        where.append(float(x[i]))
    return ExactErrors(errors[0], errors[1], errors[2], (where[0], where[1], where[2]),
                       len(x))


def _extrema(law: MotionLaw) -> np.ndarray:
    """Where the law's velocity and acceleration peak (zeros of the acceleration and of
    the jerk, by sign changes on a fine grid refined by one secant step)."""
    grid = np.linspace(0.0, 1.0, 20001)
    found = []
    for order in (2, 3):
        f = law.derivative(grid, order)
        change = np.nonzero(f[:-1] * f[1:] < 0.0)[0]
        a, b = grid[change], grid[change + 1]
        fa, fb = f[change], f[change + 1]
        found.append(a - fa * (b - a) / (fb - fa))
    return np.clip(np.concatenate(found), 0.0, 1.0)


def _law_piece(profile: CamProfile, x: np.ndarray, segment: np.ndarray) -> np.ndarray:
    """The profile piece of each x within its own segment (one-sided at segment ends)."""
    breaks = profile.breakpoints
    piece = profile.piece_of(x)
    starts = np.searchsorted(breaks[:-1], [s.start for s in profile.segments], side="left")
    first = starts[segment]
    last = np.append(starts[1:], len(breaks) - 1)[segment] - 1
    return np.clip(piece, first, last)


# ------------------------------------------------------------------- the IEC text
def write(points: tuple[MotionFunctionPoint, ...], header: list[str],
          name: str = "aCamPoints") -> str:
    """IEC 61131-3 declarations: the ARRAY OF MotionFunctionPoint with its initial values
    (one structure initialisation per point; fields left out keep their defaults) and an
    MC_CAM_REF, with the lines that connect them as a comment."""
    last = len(points) - 1
    rows = []
    for i, p in enumerate(points):
        fields = [f"FunctionType := EMotionFunctionType.{p.function_type}",
                  f"MasterPosition := {exact(p.master)}",
                  f"SlavePosition := {exact(p.slave)}"]
        for label, v in (("SlaveVelocity", p.velocity), ("SlaveAcceleration", p.acceleration),
                         ("SlaveJerk", p.jerk), ("SymmetryRatio", p.symmetry_ratio)):
            if v is not None:
                fields.append(f"{label} := {exact(v)}")
        rows.append(f"        ({', '.join(fields)})" + ("," if i < last else ""))
    comment = ["(*", *(f"  {line.replace('*)', '* )')}" for line in header), "*)"]
    return "\n".join([
        *comment,
        "VAR",
        f"    {name} : ARRAY[0..{last}] OF MotionFunctionPoint := [",
        *rows,
        "    ];",
        "    stCamRef : MC_CAM_REF;",
        "END_VAR",
        "(* Setup (Tc3_Mc3Camming, TF5550):",
        f"    stCamRef.PointsAddress := ADR({name});",
        f"    stCamRef.NumberOfPoints := {len(points)};",
        "   then load it into the cam object (MC_CamObject.WriteData, see 'Create a cam "
        "plate', infosys .../tf55xx_tc3_mc3/19976940427.html) and couple with MC_CamIn. *)",
    ]) + "\n"


def not_a_table(table: object) -> str:
    """The point-table writer slot of the target registry: twincat-mc3 writes motion
    functions (sizer.cli.cam_segment_exact), never a point table."""
    raise TypeError("twincat-mc3 is segment-exact: it writes motion functions, not a table")
