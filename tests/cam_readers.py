"""Independent readers of the files `sizer cam` writes, and the curve each controller runs
through them (issue 37). Written from docs/cam-export.md and the writers' docstrings
(sizer/export/*.py), without importing sizer: the tests compare these curves with closed
forms of the laws (tests/test_cam_matrix.py).

A reader turns the file's text into a :class:`Curve`: the master values where the
controller's interpolant changes piece (``knots``), the derivatives it keeps finite
(``orders``) and ``evaluate(x, order, interval)``, the ``order``-th derivative on the
given knot interval (one-sided at the knots: a linear table's velocity steps there).
To add a target, write ``read_<target>(text) -> Curve`` here and add a row to
``TARGETS`` in tests/test_cam_matrix.py.
"""

from __future__ import annotations

import itertools
import math
import re
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

Evaluate = Callable[[np.ndarray, int, np.ndarray], np.ndarray]


@dataclass(frozen=True)
class Curve:
    """What the controller runs: its pieces between ``knots``, and the derivatives its
    interpolation keeps finite (a linear table: position and velocity)."""

    interpolation: str
    knots: np.ndarray
    orders: tuple[int, ...]
    evaluate: Evaluate
    slave: np.ndarray
    """The slave position at each knot, as written."""
    terms: Callable[[int], float] | None = None
    """For a file of coefficients: the largest sum of the magnitudes of the terms of the
    ``order``-th derivative over a segment (at its ends), what double-precision rounding
    of the coefficients and of their evaluation is relative to (None: a table)."""


# ----------------------------------------------------------------- linear tables
def linear(x: np.ndarray, y: np.ndarray) -> Curve:
    """A table run linearly (as numpy.interp): the chord on each interval."""
    assert np.all(np.diff(x) > 0.0), "master values must increase"
    slope = np.diff(y) / np.diff(x)

    def evaluate(t: np.ndarray, order: int, interval: np.ndarray) -> np.ndarray:
        if order == 0:
            # numpy.interp is the controller's curve; on a knot interval it is the chord
            inside = np.interp(t, x, y)
            chord = y[interval] + slope[interval] * (t - x[interval])
            assert np.allclose(inside, chord, rtol=0.0, atol=1e-12 * np.ptp(y))
            return chord
        if order == 1:
            return slope[interval]
        raise ValueError("a linear table's acceleration is a train of impulses")

    return Curve("linear", x, (0, 1), evaluate, y)


def _columns(rows: list[list[str]], count: int) -> list[np.ndarray]:
    assert rows and all(len(r) == count for r in rows), rows[:3]
    data = np.array([[float(cell) for cell in r] for r in rows])
    assert np.all(np.isfinite(data))
    return [data[:, k] for k in range(count)]


HEADER = re.compile(r"^(time \[s\]|master \[deg\]),position \[(deg|mm)\]$")


def read_csv(text: str) -> Curve:
    """`csv`: a header `time [s],position [deg]` (or master [deg], [mm]), then x,y."""
    lines = text.splitlines()
    assert HEADER.match(lines[0]), lines[0]
    x, y = _columns([line.split(",") for line in lines[1:]], 2)
    return linear(x, y)


def read_codesys_xy(text: str) -> Curve:
    """`codesys-xy`: X<TAB>Y a line, no header, X equidistant, at most 128 elements."""
    lines = text.splitlines()
    assert len(lines) <= 128
    x, y = _columns([line.split("\t") for line in lines], 2)
    step = np.diff(x)
    assert np.allclose(step, (x[-1] - x[0]) / (len(x) - 1), rtol=1e-12, atol=0.0)
    return linear(x, y)


def read_sew(text: str) -> Curve:
    """`sew`: the first line n, then n lines master;slave (decimal point)."""
    lines = text.splitlines()
    count = int(lines[0])
    assert len(lines) == count + 1
    x, y = _columns([line.split(";") for line in lines[1:]], 2)
    return linear(x, y)


# ------------------------------------------------------------ XYVA: quintic Hermite
XYVA_HEADER = re.compile(
    r"^X \[(s|deg)\],Y \[(deg|mm)\],V \[\2/\1\],A \[\2/\1\^2\]$")


def read_codesys_xyva(text: str) -> Curve:
    """`codesys-xyva`: '#' comments, the header `X [s],Y [deg],V [deg/s],A [deg/s^2]`,
    then X,Y,V,A rows (SMC_CAMXYVA); run as the quintic Hermite matching Y, V and A at
    both ends of each interval (scipy BPoly.from_derivatives)."""
    from scipy.interpolate import BPoly

    lines = [line for line in text.splitlines() if not line.startswith("#")]
    assert XYVA_HEADER.match(lines[0]), lines[0]
    x, y, v, a = _columns([line.split(",") for line in lines[1:]], 4)
    assert len(x) <= 128 and np.all(np.diff(x) > 0.0)
    curve = BPoly.from_derivatives(x, np.column_stack([y, v, a]))
    derivatives = [curve, curve.derivative(1), curve.derivative(2)]

    def evaluate(t: np.ndarray, order: int, interval: np.ndarray) -> np.ndarray:
        # C2 by construction: which side of a knot scipy takes does not matter
        return derivatives[order](t)

    return Curve("quintic_hermite", x, (0, 1, 2), evaluate, y)


# ------------------------------------------------- TwinCAT 3 MC3 motion functions
def _poly(coefficients: dict[int, float]) -> Callable[[np.ndarray, int], np.ndarray]:
    def q(t: np.ndarray, order: int) -> np.ndarray:
        out = np.zeros_like(t)
        for power, c in coefficients.items():
            if power >= order:
                out = out + c * math.perm(power, order) * t ** (power - order)
        return out
    return q


def _line_and_sine(c0: float, c1: float, amplitude: float, w: float, phase: float
                   ) -> Callable[[np.ndarray, int], np.ndarray]:
    """c0 + c1 t + amplitude sin(w t + phase) and its derivatives."""
    def q(t: np.ndarray, order: int) -> np.ndarray:
        out = amplitude * w ** order * np.sin(w * t + phase + order * math.pi / 2)
        if order == 0:
            return out + c0 + c1 * t
        return out + c1 if order == 1 else out
    return q


_K = 1.0 / (4.0 + math.pi)
_MODSINE = (_line_and_sine(0.0, math.pi * _K, -_K / 4, 4 * math.pi, 0.0),
            _line_and_sine(2 * _K, math.pi * _K, -9 * _K / 4, 4 * math.pi / 3, math.pi / 3),
            _line_and_sine(4 * _K, math.pi * _K, -_K / 4, 4 * math.pi, 0.0))


def _modified_sine(t: np.ndarray, order: int) -> np.ndarray:
    """VDI 2143 modified sine, inflection point 1/2: sine quarter waves of period 1/2 on
    [0, 1/8] and [7/8, 1], a half wave of period 3/2 between (Norton's three pieces)."""
    out = np.empty_like(t)
    for piece, (lo, hi) in zip(_MODSINE, ((-np.inf, 0.125), (0.125, 0.875),
                                          (0.875, np.inf)), strict=True):
        mask = (t >= lo) & (t <= hi)
        out[mask] = piece(t[mask], order)
    return out


FUNCTION_TYPES: dict[str, Callable[[np.ndarray, int], np.ndarray]] = {
    "Linear": _poly({1: 1.0}),
    "Polynomial3": _poly({2: 3.0, 3: -2.0}),
    "Polynomial5": _poly({3: 10.0, 4: -15.0, 5: 6.0}),
    "Polynomial7": _poly({4: 35.0, 5: -84.0, 6: 70.0, 7: -20.0}),
    "Sinusoid": _line_and_sine(0.0, 1.0, -1.0 / (2 * math.pi), 2 * math.pi, 0.0),
    "ModifiedSinusoid": _modified_sine,
}
"""The rest-to-rest function types as sizer.export.twincat_mc3's docstring defines them,
q(t) from 0 to 1 over t in [0, 1]: the polynomials fixed by their rests, the cycloid
(VDI 2143 Sinuslinie) and the modified sine (inflection point 1/2); Linear q = t."""

NUMBER = r"(-?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?)"
POINT = re.compile(r"\(FunctionType := EMotionFunctionType\.(\w+), "
                   rf"MasterPosition := {NUMBER}, SlavePosition := {NUMBER}(.*?)\)")
FIELD = re.compile(rf"(\w+) := {NUMBER}")


@dataclass(frozen=True)
class MotionFunctionPoint:
    function_type: str
    master: float
    slave: float
    fields: dict[str, float]


def twincat_points(text: str) -> list[MotionFunctionPoint]:
    """The ARRAY OF MotionFunctionPoint initialiser of the VAR block, in order."""
    block = re.search(r"aCamPoints : ARRAY\[0\.\.(\d+)\] OF MotionFunctionPoint := "
                      r"\[(.*?)\n    \];", text, re.S)
    assert block, text[:400]
    points = [MotionFunctionPoint(m[1], float(m[2]), float(m[3]),
                                  {f[1]: float(f[2]) for f in FIELD.finditer(m[4])})
              for m in POINT.finditer(block[2])]
    assert len(points) == int(block[1]) + 1
    assert "stCamRef : MC_CAM_REF;" in text
    assert f"stCamRef.NumberOfPoints := {len(points)};" in text
    return points


END_CONDITIONS = ("SlaveVelocity", "SlaveAcceleration", "SlaveJerk")
"""The derivatives of orders 1, 2, 3 a MotionFunctionPoint may give (slave units per
master unit^k); left out: 0."""


def hermite_polynomial(start: MotionFunctionPoint, end: MotionFunctionPoint, degree: int
                       ) -> Callable[[np.ndarray, int], np.ndarray]:
    """PolynomialN (N = 2m + 1) between end conditions: the one polynomial with the two
    points' positions and derivatives of orders 1..m (END_CONDITIONS, 0 where left out),
    solved by numpy in u = (X - X_start) / span in [0, 1] (conditioned: the derivatives
    scaled by span^k); returns (u, order) -> d^order Y / du^order."""
    m = (degree - 1) // 2
    span = end.master - start.master
    rows, rhs = [], []
    for point, u in ((start, 0.0), (end, 1.0)):
        for k in range(m + 1):
            rows.append([math.perm(j, k) * u ** (j - k) if j >= k else 0.0
                         for j in range(degree + 1)])
            value = point.slave if k == 0 else point.fields.get(END_CONDITIONS[k - 1], 0.0)
            rhs.append(value * span ** k)
    c = np.linalg.solve(np.array(rows), np.array(rhs))
    return _poly(dict(enumerate(float(v) for v in c)))


def read_twincat_mc3(text: str) -> Curve:
    """`twincat-mc3`: each segment [point i, point i+1] runs point i's FunctionType,
    scaled to its rise over its master span; a Polynomial3/5/7 whose points write a
    non-zero end condition (a move between boundary speeds) is the polynomial those
    conditions fix (:func:`hermite_polynomial`), else the rest-to-rest closed form."""
    points = twincat_points(text)
    x = np.array([p.master for p in points])
    y = np.array([p.slave for p in points])
    assert np.all(np.diff(x) > 0.0)
    types = [p.function_type for p in points[:-1]]
    between: dict[int, Callable[[np.ndarray, int], np.ndarray]] = {}
    for k, kind in enumerate(types):
        if kind.startswith("Polynomial") and any(
                p.fields.get(name, 0.0) != 0.0 for p in points[k:k + 2]
                for name in END_CONDITIONS):
            between[k] = hermite_polynomial(points[k], points[k + 1], int(kind[-1]))

    def evaluate(t: np.ndarray, order: int, interval: np.ndarray) -> np.ndarray:
        out = np.empty_like(t)
        for k in np.unique(interval):
            mask = interval == k
            span, rise = x[k + 1] - x[k], y[k + 1] - y[k]
            u = (t[mask] - x[k]) / span
            if k in between:
                out[mask] = between[k](u, order) / span ** order
                continue
            q = FUNCTION_TYPES[types[k]](u, order)
            out[mask] = rise / span ** order * q + (y[k] if order == 0 else 0.0)
        return out

    return Curve("segment-exact", x, (0, 1, 2), evaluate, y)


# ------------------------------------------- Siemens Technology CPU: coefficient segments
SIEMENS_HEADER = "Type;Reserve;X1;Y1;X2;Y2;A0;A1;A2;A3;A4;A5;A6;B0;B1;B2"


@dataclass(frozen=True)
class CoefficientSegment:
    """One MC_CamSectorAdd polynomial data block: Y = sum a[i] X^i + b0 sin(b1 X + b2)
    on [x1, x2], X the absolute master coordinate."""

    x1: float
    y1: float
    x2: float
    y2: float
    a: tuple[float, ...]
    b: tuple[float, float, float]

    def derivative(self, x: np.ndarray, order: int) -> np.ndarray:
        """d^order Y / dX^order: the powers summed term by term, the sine's derivative
        sin(b1 X + b2 + order pi/2) times b0 b1^order."""
        out = np.zeros_like(x)
        for power, c in enumerate(self.a):
            if power >= order and c != 0.0:
                out = out + c * math.perm(power, order) * x ** (power - order)
        b0, b1, b2 = self.b
        if b0 != 0.0:
            out = out + b0 * b1 ** order * np.sin(b1 * x + b2 + order * math.pi / 2)
        return out

    def terms(self, x: np.ndarray, order: int) -> np.ndarray:
        """sum |a[i] d^order X^i/dX^order| + |b0 b1^order| (1 + |b1 x| + |b2|) at x: the
        scale of the rounding of ``derivative`` (absolute X: the terms cancel far from
        X = 0; the sine's argument is rounded relative to its size)."""
        b0, b1, b2 = self.b
        out = abs(b0 * b1 ** order) * (1.0 + np.abs(b1 * x) + abs(b2))
        for power, c in enumerate(self.a):
            if power >= order:
                out = out + abs(c) * math.perm(power, order) * np.abs(x) ** (power - order)
        return out


def siemens_segments(text: str) -> tuple[dict[str, str], list[CoefficientSegment]]:
    """`siemens-tcpu`: '#' comments (among them `# master_unit: U`, `# slave_unit: U`),
    the header Type;Reserve;X1;Y1;X2;Y2;A0..A6;B0;B1;B2, then one line per segment
    (Type 0, polynomial; Reserve 0), numbers with a decimal point."""
    lines = text.splitlines()
    units = dict(re.findall(r"^# (master_unit|slave_unit): (\S+)$", text, re.M))
    body = [line for line in lines if not line.startswith("#")]
    assert body[0] == SIEMENS_HEADER, body[0]
    rows = [line.split(";") for line in body[1:]]
    assert rows and all(len(r) == 16 and r[0] == "0" and r[1] == "0" for r in rows), rows[:2]
    segments = []
    for r in rows:
        v = [float(cell) for cell in r[2:]]
        assert all(math.isfinite(c) for c in v)
        segments.append(CoefficientSegment(v[0], v[1], v[2], v[3], tuple(v[4:11]),
                                           (v[11], v[12], v[13])))
    return units, segments


def read_siemens_tcpu(text: str) -> Curve:
    """`siemens-tcpu`: the segments run as their formula says, in the absolute X (the
    docs' inference; B1 in rad per master unit); they join end to end (each X1 the
    previous X2: no gap for MC_CamInterpolate to close)."""
    _, segments = siemens_segments(text)
    x = np.array([s.x1 for s in segments] + [segments[-1].x2])
    assert all(a.x2 == b.x1 for a, b in itertools.pairwise(segments))
    assert np.all(np.diff(x) > 0.0)

    def evaluate(t: np.ndarray, order: int, interval: np.ndarray) -> np.ndarray:
        out = np.empty_like(t)
        for k in np.unique(interval):
            mask = interval == k
            out[mask] = segments[int(k)].derivative(t[mask], order)
        return out

    def terms(order: int) -> float:
        return max(float(np.max(s.terms(np.array([s.x1, s.x2]), order)))
                   for s in segments)

    y = np.array([s.y1 for s in segments] + [segments[-1].y2])
    return Curve("coefficient-segments", x, (0, 1, 2), evaluate, y, terms)
