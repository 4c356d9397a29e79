"""`sizer cam` for every target x a set of laws, checked from the written file alone
(issue 37, "Tests must show").

Each case runs the CLI in this process, parses the written file with an independent
reader (tests/cam_readers.py, no sizer import), interpolates it as the target does
(numpy.interp / chord slopes, scipy BPoly.from_derivatives on X, [Y, V, A], the TwinCAT
function types' closed forms or, between boundary speeds, the polynomial its written end
conditions fix, the Siemens segments' formula in absolute X) and measures the largest
position, velocity (and acceleration where the interpolation keeps it finite) error
against the law written here in closed form (cycloid, poly5, modified sine, trapezoid,
double S by exact integration of its jerk, the cubic spline by scipy's clamped
CubicSpline, poly7): on a dense grid over every cell between the file's knots and the
law's breakpoints (both one-sided values at every breakpoint), refined by
scipy.optimize.minimize_scalar (bounded) around every grid local maximum near the
largest. The certificate must equal these maxima (1e-9 relative; where they are zero to
rounding, at most 1e-12 of the stroke / the peak, 1e-11 of the peak for a table's
acceleration, and for a file of coefficients COEFFICIENT_ROUNDING eps times its terms)
and never be below a grid value (but for 1e-13 of the stroke / peak). The references
are closed forms; sizer's law objects are used only to check that they are the laws
sizer sizes (the first test).

Also: siemens-tcpu fitting poly7 (no polynomial of degree <= 6) within --tolerance, and
a cycle with boundary speeds, examples/flying-saw.yaml (moves to and from the line's
speed, a run at it, a dwell), whole, for every target over time and over a master range,
against tests/flying_saw_reference.py (independent of sizer, at the cycle time the
certificate reports).

Adding a target: a reader in tests/cam_readers.py and a row in TARGETS (``names``: the
laws it writes segment-exact, refusing the others; None: a table or a file of
coefficients, any law; ``exact``: the laws it reproduces to rounding) and in SAW_PLAN.
Adding a motion (e.g. a ``cycle:`` of segments): a row in MOTIONS, i.e. the CLI arguments
and a function from the normalized law to its segments (moves and dwells), see "cycle".
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import flying_saw_reference as saw
import numpy as np
import pytest
from cam_readers import (
    Curve,
    read_codesys_xy,
    read_codesys_xyva,
    read_csv,
    read_sew,
    read_siemens_tcpu,
    read_twincat_mc3,
    siemens_segments,
    twincat_points,
)
from cli_run import assert_user_error, run_cli

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
DESIGN = EXAMPLES / "indexing-table.yaml"
PI = math.pi
Q = Callable[[np.ndarray, int], np.ndarray]


# ------------------------------------------------- the laws, normalized, closed form
@dataclass(frozen=True)
class NormalizedLaw:
    """q(t) from 0 to 1 over t in [0, 1] as pieces: ``breaks`` (0 ... 1) and one
    analytic function per piece, evaluated on its own piece (one-sided at its ends)."""

    breaks: tuple[float, ...]
    pieces: tuple[Q, ...]


def one_piece(q: Q) -> NormalizedLaw:
    return NormalizedLaw((0.0, 1.0), (q,))


def polynomial(coefficients: dict[int, float]) -> Q:
    def q(t: np.ndarray, order: int) -> np.ndarray:
        out = np.zeros_like(t)
        for power, c in coefficients.items():
            if power >= order:
                out = out + c * math.perm(power, order) * t ** (power - order)
        return out
    return q


def line_and_sine(c0: float, c1: float, amplitude: float, w: float, phase: float) -> Q:
    """c0 + c1 t + amplitude sin(w t + phase)."""
    def q(t: np.ndarray, order: int) -> np.ndarray:
        out = amplitude * w ** order * np.sin(w * t + phase + order * PI / 2)
        return out + (c0 + c1 * t if order == 0 else c1 if order == 1 else 0.0)
    return q


def constant_jerk(segments: list[tuple[float, float | None, float]]) -> NormalizedLaw:
    """Exact integration from rest of pieces (start, acceleration at start or None to
    continue it, jerk): q = q0 + v0 s + a0 s^2/2 + j s^3/6 on each."""
    starts = [s[0] for s in segments]
    ends = [*starts[1:], 1.0]
    pieces, q0, v0, a0 = [], 0.0, 0.0, 0.0
    for (start, acc, jerk), end in zip(segments, ends, strict=True):
        a0 = a0 if acc is None else acc

        def q(t: np.ndarray, order: int, t0=start, c=(q0, v0, a0, jerk)) -> np.ndarray:
            s = t - t0
            terms = [c[0] + c[1] * s + c[2] * s ** 2 / 2 + c[3] * s ** 3 / 6,
                     c[1] + c[2] * s + c[3] * s ** 2 / 2, c[2] + c[3] * s]
            return terms[order] if order < 3 else np.full_like(t, c[3])
        pieces.append(q)
        d = end - start
        q0, v0, a0 = (q0 + v0 * d + a0 * d ** 2 / 2 + jerk * d ** 3 / 6,
                      v0 + a0 * d + jerk * d ** 2 / 2, a0 + jerk * d)
    assert abs(q0 - 1.0) < 1e-13 and abs(v0) < 1e-12
    return NormalizedLaw((*starts, 1.0), tuple(pieces))


def trapezoidal(alpha: float) -> NormalizedLaw:
    """Trapezoidal velocity: acceleration 1/(alpha (1 - alpha)) on [0, alpha], its
    negative on [1 - alpha, 1] (book sec. 3.2)."""
    a = 1.0 / (alpha * (1.0 - alpha))
    return constant_jerk([(0.0, a, 0.0), (alpha, 0.0, 0.0), (1.0 - alpha, -a, 0.0)])


def double_s(alpha: float, beta: float) -> NormalizedLaw:
    """Double S (book sec. 3.4, v0 = v1 = 0, symmetric): T_a = alpha, T_j = beta T_a,
    cruise 1/(1 - alpha), peak acceleration cruise / (T_a - T_j), jerk a / T_j."""
    ta, tj = alpha, beta * alpha
    a = 1.0 / ((1.0 - alpha) * (ta - tj))
    j = a / tj
    return constant_jerk([(0.0, 0.0, j), (tj, None, 0.0), (ta - tj, None, -j),
                          (ta, None, 0.0), (1 - ta, None, -j), (1 - ta + tj, None, 0.0),
                          (1 - tj, None, j)])


def modified_sine() -> NormalizedLaw:
    """Norton's modified sine: sine quarter waves of period 1/2 on [0, 1/8], [7/8, 1]
    and of period 3/2 between."""
    k = 1.0 / (4.0 + PI)
    return NormalizedLaw((0.0, 0.125, 0.875, 1.0), (
        line_and_sine(0.0, PI * k, -k / 4, 4 * PI, 0.0),
        line_and_sine(2 * k, PI * k, -9 * k / 4, 4 * PI / 3, PI / 3),
        line_and_sine(4 * k, PI * k, -k / 4, 4 * PI, 0.0)))


def clamped_spline(times: list[float], positions: list[float]) -> NormalizedLaw:
    """The C2 cubic spline through the points, end velocities 0 (data-laws.md,
    `cubic_spline`: start/end velocity default 0), by scipy's CubicSpline."""
    from scipy.interpolate import CubicSpline

    spline = CubicSpline(times, positions, bc_type=((1, 0.0), (1, 0.0)))

    def q(t: np.ndarray, order: int) -> np.ndarray:
        return spline(t, order)
    return NormalizedLaw(tuple(times), (q,) * (len(times) - 1))


SPLINE = "{kind: cubic_spline, points: [[0, 0], [0.3, 0.15], [0.55, 0.8], [1, 1]]}"


@dataclass(frozen=True)
class LawRow:
    id: str
    spec: str
    law: NormalizedLaw


LAWS = (
    LawRow("cycloidal", "cycloidal", one_piece(line_and_sine(0.0, 1.0, -1 / (2 * PI),
                                                                 2 * PI, 0.0))),
    LawRow("poly5", "polynomial(degree=5)", one_piece(polynomial({3: 10.0, 4: -15.0,
                                                                   5: 6.0}))),
    LawRow("modified_sinusoidal", "modified_sinusoidal", modified_sine()),
    LawRow("trapezoidal", "trapezoidal(alpha=1/3)", trapezoidal(1 / 3)),
    LawRow("double_s", "double_s(alpha=0.3, beta=0.2)", double_s(0.3, 0.2)),
    LawRow("cubic_spline", SPLINE, clamped_spline([0, 0.3, 0.55, 1], [0, 0.15, 0.8, 1])),
)


# ------------------------------------------------------- the motion over the master
@dataclass(frozen=True)
class Reference:
    """The motion the export must reproduce, over the master: pieces between
    ``breaks`` (master units), each evaluated on its own piece."""

    breaks: np.ndarray
    evaluate: Callable[[np.ndarray, int, np.ndarray], np.ndarray]


def reference(segments: list[tuple[float, float, float, float, NormalizedLaw | None]]
              ) -> Reference:
    """Moves (start, span, origin, stroke, law) and dwells (law None) in order: y =
    origin + stroke q((x - start)/span), its k-th derivative stroke/span^k q^(k)."""
    breaks, funcs = [], []
    for start, span, origin, stroke, law in segments:
        if law is None:
            breaks.append(start)
            funcs.append((start, span, origin, 0.0, polynomial({})))
            continue
        for b, q in zip(law.breaks[:-1], law.pieces, strict=True):
            breaks.append(start + b * span)
            funcs.append((start, span, origin, stroke, q))
    last = segments[-1]
    breaks.append(last[0] + last[1])

    def evaluate(x: np.ndarray, order: int, piece: np.ndarray) -> np.ndarray:
        out = np.empty_like(x)
        for k in np.unique(piece):
            start, span, origin, stroke, q = funcs[k]
            mask = piece == k
            out[mask] = stroke / span ** order * q((x[mask] - start) / span, order)
            if order == 0:
                out[mask] += origin
        return out

    return Reference(np.array(breaks), evaluate)


Segment = tuple[float, float, float, float, "NormalizedLaw | None"]


@dataclass(frozen=True)
class Motion:
    """How a law is exported: the CLI arguments given its spec, the option a refusal
    names, the master span and the stroke, and the motion's segments (start, span,
    origin, stroke, law or None for a dwell) given the normalized law."""

    id: str
    args: Callable[[str], tuple[str, ...]]
    option: str
    span: float
    stroke: float
    segments: Callable[[NormalizedLaw], list[Segment]]
    laws: frozenset[str] | None = None
    """The laws it is run with (None: all of LAWS)."""


ALONE = ("--displacement", "90 deg", "--duration", "0.25 s")
CYCLE_MOVE = 360.0 * 0.25 / (0.25 + 0.35)
"""The indexing table's cycle over 360 deg of master: the 0.25 s move, the 0.35 s dwell."""

MOTIONS = (
    Motion("time", lambda spec: (spec, *ALONE), "SPEC", 0.25, 90.0,
           lambda law: [(0.0, 0.25, 0.0, 90.0, law)]),
    Motion("master", lambda spec: (spec, *ALONE, "--master-range", "360"), "SPEC",
           360.0, 90.0, lambda law: [(0.0, 360.0, 0.0, 90.0, law)]),
    Motion("cycle", lambda spec: (str(DESIGN), "--law", spec, "--cycle",
                                  "--master-range", "360"), "--law", 360.0, 90.0,
           lambda law: [(0.0, CYCLE_MOVE, 0.0, 90.0, law),
                        (CYCLE_MOVE, 360.0 - CYCLE_MOVE, 90.0, 0.0, None)],
           laws=frozenset({"modified_sinusoidal"})),
)


# ------------------------------------------------------------------- the targets
@dataclass(frozen=True)
class TargetRow:
    name: str
    read: Callable[[str], Curve]
    names: frozenset[str] | None = None
    """The laws the target names, written segment-exact (others refused, exit 2);
    None: a table, any law."""
    exact: frozenset[str] = frozenset()
    """Laws a table target reproduces exactly, to rounding (XYVA: poly5 is one quintic;
    double S and the cubic spline are cubics between breakpoints that are points)."""


TWINCAT_NAMES = frozenset({"cycloidal", "poly5", "modified_sinusoidal"})
TARGETS = (
    TargetRow("csv", read_csv),
    TargetRow("codesys-xy", read_codesys_xy),
    TargetRow("sew", read_sew),
    TargetRow("codesys-xyva", read_codesys_xyva,
              exact=frozenset({"poly5", "double_s", "cubic_spline"})),
    TargetRow("twincat-mc3", read_twincat_mc3, names=TWINCAT_NAMES),
    TargetRow("siemens-tcpu", read_siemens_tcpu, exact=frozenset(row.id for row in LAWS)),
)

KNOWN_DISAGREEMENTS: dict[tuple[str, str, str], str] = {}
"""(target, law, motion) -> why: certificates found to disagree with the file (xfail)."""


# ------------------------------------------------------------ the true largest errors
GRID = 40_000
REFINE = 24


@dataclass(frozen=True)
class Measured:
    grid: float
    true: float
    at: float


def largest_errors(curve: Curve, ref: Reference, order: int) -> Measured:
    """max |curve^(k) - law^(k)| over every cell between the curve's knots and the
    law's breakpoints: a grid with both ends of each cell (one-sided values at every
    breakpoint), then minimize_scalar (bounded) around every grid local maximum near the
    largest (at most REFINE of them)."""
    from scipy.optimize import minimize_scalar

    cuts = np.unique(np.concatenate([curve.knots, ref.breaks]))
    lo, hi = cuts[:-1], cuts[1:]
    keep = hi - lo > 1e-13 * (cuts[-1] - cuts[0])
    lo, hi = lo[keep], hi[keep]
    mid = (lo + hi) / 2
    interval = np.clip(np.searchsorted(curve.knots, mid) - 1, 0, len(curve.knots) - 2)
    piece = np.clip(np.searchsorted(ref.breaks, mid) - 1, 0, len(ref.breaks) - 2)
    m = max(17, GRID // len(lo))
    s = np.linspace(0.0, 1.0, m)
    x = lo[:, None] + (hi - lo)[:, None] * s[None, :]
    x[:, -1] = hi
    cells = np.repeat(np.arange(len(lo)), m)

    def error(xs: np.ndarray, cell: np.ndarray) -> np.ndarray:
        return np.abs(curve.evaluate(xs, order, interval[cell])
                      - ref.evaluate(xs, order, piece[cell]))

    e = error(x.ravel(), cells).reshape(x.shape)
    best = float(e.max())
    at = float(x.ravel()[int(np.argmax(e))])
    # every grid local maximum within 1e-4 of the largest (the ends of a cell included:
    # the extremum may lie just inside a breakpoint), refined between its neighbours
    padded = np.pad(e, ((0, 0), (1, 1)), constant_values=-1.0)
    local = (e >= padded[:, :-2]) & (e >= padded[:, 2:]) & (e >= best * (1 - 1e-4))
    rows, cols = np.nonzero(local)
    true = best
    for r in np.argsort(e[rows, cols])[::-1][:REFINE]:
        c, j = rows[r], cols[r]
        a, b = x[c, max(j - 1, 0)], x[c, min(j + 1, m - 1)]
        found = minimize_scalar(
            lambda t, c=c: -float(error(np.array([t]), np.array([c]))[0]),
            bounds=(a, b), method="bounded",
            options={"xatol": 1e-15 * max(abs(a), abs(b), 1.0)})
        if -found.fun > true:
            true, at = float(-found.fun), float(found.x)
    return Measured(best, true, at)


def peak(ref: Reference, span: float, order: int) -> float:
    x = np.linspace(0.0, span, 20_001)
    piece = np.clip(np.searchsorted(ref.breaks, x, side="right") - 1, 0,
                    len(ref.breaks) - 2)
    return float(np.max(np.abs(ref.evaluate(x, order, piece))))


# ------------------------------------------------------------------------- tests
def test_closed_forms_are_the_laws_sizer_sizes() -> None:
    """The reference laws here are sizer's (so a disagreement below is the export's)."""
    from sizer.laws import make_law

    t = np.linspace(0.0, 1.0, 2001)
    for row in LAWS:
        law = make_law(row.spec)
        ref = reference([(0.0, 1.0, 0.0, 1.0, row.law)])
        piece = np.clip(np.searchsorted(ref.breaks, t, side="right") - 1, 0,
                        len(ref.breaks) - 2)
        for order in range(3):
            mine = ref.evaluate(t, order, piece)
            theirs = law.derivative(t, order)
            scale = max(1.0, float(np.max(np.abs(mine))))
            assert np.max(np.abs(mine - theirs)) < 1e-12 * scale, (row.id, order)


CASES = [pytest.param(target, law, motion, id=f"{target.name}-{law.id}-{motion.id}",
                      marks=[pytest.mark.xfail(strict=True, reason=why)] if (
                          why := KNOWN_DISAGREEMENTS.get((target.name, law.id, motion.id)))
                      else [])
         for target in TARGETS for law in LAWS for motion in MOTIONS
         if motion.laws is None or law.id in motion.laws]


@pytest.mark.parametrize(("target", "law", "motion"), CASES)
def test_certificate_equals_the_file_read_back(tmp_path: Path, target: TargetRow,
                                               law: LawRow, motion: Motion) -> None:
    out, cert = tmp_path / "cam.out", tmp_path / "cam.json"
    result = run_cli("cam", *motion.args(law.spec), "--to", target.name, "-o", str(out),
                     "--certificate", str(cert))
    if target.names is not None and law.id not in target.names:
        assert_user_error(result, motion.option, target.name)
        assert not out.exists() and not cert.exists()
        return
    record = written(result, cert, target)
    assert record["stroke"] == motion.stroke and record["master"]["span"] == motion.span
    curve = target.read(out.read_text())
    ref = reference(motion.segments(law.law))
    for segment, mine in zip(record["segments"], motion.segments(law.law), strict=True):
        assert segment["start"] == pytest.approx(mine[0], rel=1e-15, abs=0.0)
        assert segment["span"] == pytest.approx(mine[1], rel=1e-15)
    exact = target.names is not None or law.id in target.exact
    assert_certificate_is_the_file(record, curve, ref, motion.span, motion.stroke, target,
                                   exact)


def written(result, cert: Path, target: TargetRow) -> dict:
    """The certificate of a file written (exit 0; exit 1 only when clipped to the
    target's limit, the tolerance not met, by design)."""
    assert result.returncode in (0, 1), result.stdout + result.stderr
    record = json.loads(cert.read_text())
    assert record["target"] == target.name
    single = record.get("single_precision_estimate", {"within_tolerance": True})
    assert (result.returncode == 1) == (record.get("clipped") is True
                                        or not single["within_tolerance"]), result.stdout
    if record.get("clipped"):
        assert not record["tolerance_met"] and "NOT met" in result.stdout
        assert record["points"] == record["limit"] < record["points_needed"]
    return record


COEFFICIENT_ROUNDING = 8.0
"""A file of coefficients (siemens-tcpu) reproduces a law that is its form to rounding:
at most COEFFICIENT_ROUNDING * eps * (the largest sum of the magnitudes of the terms of
the derivative over a segment, Curve.terms), not a fraction of the stroke. Absolute X
makes the terms of a segment far from X = 0 large and cancelling, and their rounding, in
sizer's binomial expansion, in the file's 17 digits and in the evaluation, is relative
to them (the sine's argument: relative to |B1 X| + |B2|). Measured (this reader against
the closed forms, and the certificates): at most 1.2 eps * terms over the six laws x
time, master and cycle and the flying saw's three laws both ways, where the terms reach
1.8e6 strokes (poly5: its return, late in the cycle, 9.8e-8 mm of 450 mm, exact to
rounding in double; the certificate's single-precision estimate of it is 15-20 mm). 8
leaves a margin of rounding order, not of error; a fraction of the stroke would be either
loose (cycloid: terms 1.2 strokes) or false (the saw)."""


def rounding(target: TargetRow, curve: Curve, order: int, scale: float) -> tuple[float,
                                                                               float]:
    """(the reader's, the certificate's) bounds of 'zero to rounding' for ``order``:
    a file of coefficients COEFFICIENT_ROUNDING eps terms; otherwise 1e-12 of the stroke
    / the peak, a table's acceleration 1e-11 of its peak for the certificate (it evaluates
    the law's pieces at their ends: 2.5e-12 of the peak acceleration for XYVA double_s at
    its breakpoint 0.19 s)."""
    if curve.terms is not None:
        bound = COEFFICIENT_ROUNDING * EPS * curve.terms(order)
        return bound, bound
    return 1e-12 * scale, (1e-12 if target.names is not None or order < 2
                           else 1e-11) * scale


EPS = float(np.finfo(float).eps)
NAMES = ("position", "velocity", "acceleration")


def assert_certificate_is_the_file(record: dict, curve: Curve, ref: Reference, span: float,
                                   stroke: float, target: TargetRow, exact: bool) -> None:
    """The certificate's errors are the largest errors of the file read back (``curve``)
    against the reference: zero to rounding where the target writes the law ``exact``ly,
    else equal to 1e-9 relative and never below a grid value."""
    ends = ref.evaluate(np.array([0.0, span]), 0, np.array([0, len(ref.breaks) - 2]))
    assert curve.knots[0] == 0.0 and curve.knots[-1] == pytest.approx(span, rel=1e-15)
    assert curve.slave[0] == ends[0]
    assert curve.slave[-1] == pytest.approx(ends[1], rel=1e-15, abs=1e-13 * stroke)
    if curve.terms is not None:  # each segment's formula at its ends: its Y1 and Y2
        inner = np.arange(len(curve.knots) - 1)
        floor = COEFFICIENT_ROUNDING * EPS * curve.terms(0)
        for at, y in ((curve.knots[:-1], curve.slave[:-1]),
                      (curve.knots[1:], curve.slave[1:])):
            assert np.max(np.abs(curve.evaluate(at, 0, inner) - y)) <= floor
    scales = [stroke, *(peak(ref, span, k) for k in (1, 2))]
    for order in curve.orders:
        measured = largest_errors(curve, ref, order)
        entry = record["errors"][NAMES[order]]
        certified, scale = entry["max"], scales[order]
        mine, theirs = rounding(target, curve, order, scale)
        if exact:
            assert measured.true <= mine, (NAMES[order], measured, mine)
            assert certified <= theirs, (NAMES[order], certified, theirs)
        elif measured.true <= mine:
            assert certified <= theirs, (NAMES[order], certified, measured)
        else:
            # never below a grid value (but for rounding: 1e-13 of the scale); equal to
            # 1e-9 relative, but for a file of coefficients' rounding floor (both
            # evaluations of the file are double: poly7 over time, 4.7e-12 deg apart,
            # the certificate 1e-12 deg from the file evaluated in rationals)
            floor = 0.0 if curve.terms is None else mine
            assert certified >= measured.grid - 1e-13 * scale - floor, (
                NAMES[order], certified, measured)
            assert abs(certified - measured.true) <= 1e-9 * measured.true + floor, (
                NAMES[order], certified, measured, floor)
        if order == 0 and record.get("tolerance_met"):  # the file meets the tolerance
            assert measured.true <= record["tolerance"] * stroke
        if order == 0:
            assert entry["of_stroke"] == pytest.approx(certified / stroke, rel=1e-12)
        else:
            assert entry["of_peak"] == pytest.approx(certified / scale, rel=1e-6)
    if curve.orders == (0, 1):
        # a linear table: its acceleration is impulses, the largest the largest step of
        # the chord slopes, the law's own velocities at the ends counted
        acceleration = record["errors"]["acceleration"]
        assert acceleration["finite"] is False
        x, y = curve.knots, curve.slave
        slopes = np.diff(y) / np.diff(x)
        law_v = ref.evaluate(np.array([0.0, span]), 1, np.array([0, len(ref.breaks) - 2]))
        steps = np.abs(np.diff(np.concatenate([[law_v[0]], slopes, [law_v[1]]])))
        assert acceleration["largest_velocity_step"] == pytest.approx(steps.max(),
                                                                      rel=1e-9)


# ------------------------------------------- a cycle with boundary speeds: the flying saw
SAW = EXAMPLES / "flying-saw.yaml"
SAW_MOTOR = "SGM7A-70A"
"""Feasible with each of SAW_LAWS; naming it sizes one motor, not the catalog (faster)."""
SAW_LAWS = {"poly5": "poly5", "trapezoidal": saw.TRAPEZOID, "double_s": saw.DOUBLE_S}
"""The saw's moves between boundary speeds by these laws (the ids of LAWS: a table target
writes poly5 and double S exactly where its ``exact`` says so)."""
SAW_RUNS = {
    "A": (("poly5", "time"), ("trapezoidal", "master"), ("double_s", "time")),
    "B": (("poly5", "master"), ("trapezoidal", "time"), ("double_s", "master")),
    "twincat-mc3": (("poly5", "time"), ("poly5", "master"), ("trapezoidal", "time"),
                    ("double_s", "master")),
}
SAW_PLAN = {"csv": "B", "codesys-xy": "B", "sew": "A", "codesys-xyva": "A",
            "siemens-tcpu": "B", "twincat-mc3": "twincat-mc3"}
"""Every target over time and over 360 deg of master, every law with both masters across
the targets, each case ~0.3 s (the cycle is sized again for each): siemens-tcpu poly5 and
double S over the master (the largest absolute-X terms), codesys-xyva poly5 and double S
(written exactly) over time, the trapezoid over the master (clipped to 128 points);
twincat-mc3 poly5 both ways and the trapezoid and double S refused."""
TWINCAT_BETWEEN_SPEEDS = frozenset({"poly5"})
"""The laws twincat-mc3 writes between boundary speeds (poly3/5/7 with their end
conditions); the others are refused, exit 2."""


def saw_reference(law: str, cycle_time: float, scale: float) -> Reference:
    """tests/flying_saw_reference.py's cycle over the master x = scale t."""
    _, pieces = saw.cycle(SAW_LAWS[law], cycle_time)
    breaks = np.array([scale * p.t0 for p in pieces] + [scale * pieces[-1].t1])

    def evaluate(x: np.ndarray, order: int, piece: np.ndarray) -> np.ndarray:
        out = np.empty_like(x)
        for k in np.unique(piece):
            mask = piece == k
            out[mask] = pieces[int(k)].at(x[mask] / scale, order) / scale ** order
        return out
    return Reference(breaks, evaluate)


SAW_CASES = [pytest.param(target, law, master, id=f"{target.name}-{law}-{master}")
             for target in TARGETS for law, master in SAW_RUNS[SAW_PLAN[target.name]]]


@pytest.mark.parametrize(("target", "law", "master"), SAW_CASES)
def test_a_cycle_with_boundary_speeds(tmp_path: Path, target: TargetRow, law: str,
                                      master: str) -> None:
    """The flying saw's whole cycle (accelerate to the line's speed, cut at it, stop,
    return, wait) against tests/flying_saw_reference.py, at the cycle time the
    certificate reports."""
    out, cert = tmp_path / "cam.out", tmp_path / "cam.json"
    extra = () if master == "time" else ("--master-range", "360")
    result = run_cli("cam", str(SAW), "--to", target.name, "-o", str(out), "--certificate",
                     str(cert), "--law", SAW_LAWS[law], "--motor", SAW_MOTOR, *extra)
    if target.names is not None and law not in TWINCAT_BETWEEN_SPEEDS:
        assert_user_error(result, "--law", "'accelerate'", target.name)
        assert not out.exists() and not cert.exists()
        return
    record = written(result, cert, target)
    info = record["master"]
    cycle_time = info["cycle_time_s"]  # every target names it so
    assert "move_duration_s" not in info
    span = cycle_time if master == "time" else 360.0
    scale = span / cycle_time
    assert info["span"] == pytest.approx(span, rel=1e-15)
    assert record["stroke"] == 450.0  # the cycle's travel
    durations = saw.durations(cycle_time)
    starts = np.cumsum([0.0, *durations])[:-1]
    line = saw.LINE / scale  # the line's speed, mm per master unit
    speeds = [(0.0, line), (line, line), (line, 0.0), (0.0, 0.0), (0.0, 0.0)]
    assert [s["name"] for s in record["segments"]] == list(saw.NAMES)
    for segment, start, duration, (v0, v1) in zip(record["segments"], starts, durations,
                                                  speeds, strict=True):
        assert segment["start"] == pytest.approx(scale * start, rel=1e-12, abs=1e-12)
        assert segment["span"] == pytest.approx(scale * duration, rel=1e-12)
        assert segment["start_velocity"] == pytest.approx(v0, rel=1e-12)
        assert segment["end_velocity"] == pytest.approx(v1, rel=1e-12)
    curve = target.read(out.read_text())
    ref = saw_reference(law, cycle_time, scale)
    assert_certificate_is_the_file(record, curve, ref, span, 450.0, target,
                                   target.names is not None or law in target.exact)


# ------------------------------------------------------- a law siemens-tcpu fits: poly7
POLY7 = one_piece(polynomial({4: 35.0, 5: -84.0, 6: 70.0, 7: -20.0}))


@pytest.mark.parametrize(("extra", "tolerance"), [((), "1e-4"),
                                                  (("--master-range", "360"), "1e-6")],
                         ids=["time", "master"])
def test_siemens_fits_poly7_within_the_tolerance(tmp_path: Path, extra, tolerance) -> None:
    """poly7 is no polynomial of degree <= 6: fitted segments, whose certificate is the
    file's errors against the closed form (1e-9 relative, but for the rounding floor of
    evaluating the file in double: see assert_certificate_is_the_file) and meets
    --tolerance."""
    out, cert = tmp_path / "cam.txt", tmp_path / "cam.json"
    result = run_cli("cam", "polynomial(degree=7)", *ALONE, *extra, "--to", "siemens-tcpu",
                     "-o", str(out), "--certificate", str(cert), "--tolerance", tolerance)
    target = next(t for t in TARGETS if t.name == "siemens-tcpu")
    record = written(result, cert, target)
    single = record["single_precision_estimate"]["within_tolerance"]
    assert result.returncode == (0 if single else 1) and record["tolerance_met"] is True
    assert record["split"] == {"fitted": record["coefficient_segments"]}
    span = 0.25 if not extra else 360.0
    units, _ = siemens_segments(out.read_text())
    assert units == {"master_unit": "deg" if extra else "s", "slave_unit": "deg"}
    curve = target.read(out.read_text())
    assert len(curve.knots) == record["coefficient_segments"] + 1 > 2
    ref = reference([(0.0, span, 0.0, 90.0, POLY7)])
    assert_certificate_is_the_file(record, curve, ref, span, 90.0, target, exact=False)
    measured = largest_errors(curve, ref, 0)
    assert 0.0 < measured.true <= float(tolerance) * 90.0


# ------------------------------------------------------------------ the refusals
def test_twincat_refuses_the_points_and_the_tolerance(tmp_path: Path) -> None:
    for option in (("--points", "10"), ("--tolerance", "1e-6")):
        out = tmp_path / "cam.st"
        result = run_cli("cam", "poly5", *ALONE, "--to", "twincat-mc3",
                         "-o", str(out), *option)
        assert_user_error(result, option[0])
        assert not out.exists()


@pytest.mark.parametrize("target", ["codesys-xy", "codesys-xyva"])
def test_more_than_128_elements_is_refused(tmp_path: Path, target: str) -> None:
    out = tmp_path / "cam.txt"
    result = run_cli("cam", "cycloidal", *ALONE, "--to", target,
                     "-o", str(out), "--points", "129")
    assert_user_error(result, "--points")
    assert not out.exists()


def test_twincat_points_are_rests_with_the_symmetry_ratio(tmp_path: Path) -> None:
    out = tmp_path / "cam.st"
    result = run_cli("cam", "modified_sinusoidal", *ALONE, "--master-range", "360", "--to",
                     "twincat-mc3", "-o", str(out))
    assert result.returncode == 0, result.stderr
    points = twincat_points(out.read_text())
    assert [p.function_type for p in points] == ["ModifiedSinusoid"] * 2
    assert [p.master for p in points] == [0.0, 360.0]
    assert [p.slave for p in points] == [0.0, 90.0]
    assert all(p.fields["SlaveVelocity"] == 0.0 for p in points)
    assert points[0].fields["SymmetryRatio"] == 0.5 and "SymmetryRatio" not in points[1].fields


# -------------------------------------------------------------------- the torques
def size_json(design: Path) -> dict:
    result = run_cli("size", str(design), "--format", "json")
    assert result.returncode in (0, 1), result.stderr
    return json.loads(result.stdout)


def design_with_law(tmp_path: Path, law: str | dict, motor: str) -> Path:
    """The indexing table with one law and the check pair (motor, that law), its
    catalog path made absolute: the design a user would write to size the file."""
    import yaml

    design = yaml.safe_load(DESIGN.read_text())
    design["motors"] = str(EXAMPLES / design["motors"])
    design["laws"] = [law]
    design["check"] = {"motor": motor, "law": law}
    path = tmp_path / "resized.yaml"
    path.write_text(yaml.safe_dump(design, sort_keys=False))
    return path


def result_of(record: dict, motor: str) -> dict:
    (found,) = [r for r in record["results"] if r["motor"] == motor]
    return found


@pytest.mark.parametrize("extra", [(), ("--master-range", "360")], ids=["time", "master"])
def test_xyva_torques_equal_sizing_the_written_table(tmp_path: Path, extra) -> None:
    out, cert = tmp_path / "cam.txt", tmp_path / "cam.json"
    result = run_cli("cam", str(DESIGN), "--to", "codesys-xyva", "-o", str(out),
                     "--certificate", str(cert), *extra)
    assert result.returncode == 0, result.stdout + result.stderr
    record = json.loads(cert.read_text())
    motor = record["motor"]
    assert (motor, record["law"]) == ("HG-KN43J", "modified_sinusoidal")
    torques = record["torques"]
    assert torques["computed"]
    spec = {"kind": "cam_table", "file": str(out), "interpolation": "quintic_hermite"}
    again = result_of(size_json(design_with_law(tmp_path, spec, motor)), motor)
    exported = torques["exported"]
    assert exported["peak_torque_Nm"] == pytest.approx(again["peak_torque"], rel=1e-9)
    assert exported["rms_torque_Nm"] == pytest.approx(again["rms_torque"], rel=1e-9)
    # and the sized law's torques are those `sizer size` reports for the check pair
    sized = result_of(size_json(design_with_law(tmp_path, "modified_sinusoidal", motor)),
                      motor)
    assert torques["law"]["peak_torque_Nm"] == pytest.approx(sized["peak_torque"],
                                                             rel=1e-9)
    assert torques["law"]["rms_torque_Nm"] == pytest.approx(sized["rms_torque"], rel=1e-9)


def test_twincat_torques_are_the_sized_laws(tmp_path: Path) -> None:
    """Segment-exact: the controller runs the sized law, whose torques are the sizing's;
    sizing the named law alone gives what `sizer size` reports for the check pair."""
    out, cert = tmp_path / "cam.st", tmp_path / "cam.json"
    result = run_cli("cam", str(DESIGN), "--to", "twincat-mc3", "-o", str(out),
                     "--certificate", str(cert))
    assert result.returncode == 0, result.stdout + result.stderr
    record = json.loads(cert.read_text())
    assert "the sizing's" in record["torques"]
    motor, law = record["motor"], record["law"]
    assert twincat_points(out.read_text())[0].function_type == "ModifiedSinusoid"
    reported = [r for r in size_json(DESIGN)["results"]
                if r["motor"] == motor and r["law"] == law]
    alone = result_of(size_json(design_with_law(tmp_path, law, motor)), motor)
    assert len(reported) == 1
    assert alone["peak_torque"] == pytest.approx(reported[0]["peak_torque"], rel=1e-9)
    assert alone["rms_torque"] == pytest.approx(reported[0]["rms_torque"], rel=1e-9)
