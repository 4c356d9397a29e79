"""Coefficient segments (issue 37): a cam as consecutive segments, each
Y = A0 + A1 X + ... + A6 X^6 + B0 sin(B1 X + B2) over [X1, X2] of the master, the form a
Siemens Technology CPU takes (MC_CamSectorAdd, Type 0 = polynomial; docs/cam-coefficients.md).

Pure: the text of a segment file parsed (:func:`parse_segments`), each segment evaluated
to any derivative order in the absolute master coordinate X, and the segments as one
curve (:class:`SegmentCurve`, a sizer.laws.multipoint.Curve) that a ``cam_segments`` law
reads back (its builder, which reads the file, is sizer.io.segment_table_law).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from sizer.errors import UserError
from sizer.numerics.arrays import sorted_unique

COLUMNS = ("Type", "Reserve", "X1", "Y1", "X2", "Y2", "A0", "A1", "A2", "A3", "A4", "A5",
           "A6", "B0", "B1", "B2")
"""The columns of a segment line: the fields of the manual's data block, in its order."""
POLYNOMIAL_TYPE = 0
DEGREE = 6


@dataclass(frozen=True)
class CoefficientSegment:
    """Y(X) = sum a[i] X^i + b[0] sin(b[1] X + b[2]) on [x1, x2] (X absolute)."""

    x1: float
    y1: float
    x2: float
    y2: float
    a: tuple[float, ...]
    b: tuple[float, float, float] = (0.0, 0.0, 0.0)

    def derivative(self, x: np.ndarray, order: int = 0) -> np.ndarray:
        """d^order Y / dX^order at x (Horner on the differentiated coefficients)."""
        x = np.asarray(x, dtype=float)
        coef = list(self.a)
        for _ in range(order):
            coef = [k * c for k, c in enumerate(coef[1:], start=1)] or [0.0]
        out = coef[-1] + x * 0.0
        for c in coef[-2::-1]:
            out = c + out * x
        b0, b1, b2 = self.b
        if b0 != 0.0:
            out = out + b0 * b1 ** order * np.sin(b1 * x + b2 + order * math.pi / 2)
        return out

    @property
    def fields(self) -> tuple[float, ...]:
        """The line's numbers after Type and Reserve: X1, Y1, X2, Y2, A0..A6, B0..B2."""
        a = tuple(self.a) + (0.0,) * (DEGREE + 1 - len(self.a))
        return (self.x1, self.y1, self.x2, self.y2, *a, *self.b)


@dataclass(frozen=True)
class SegmentFile:
    """The segments of a file, with the units its comments name (None if not)."""

    segments: tuple[CoefficientSegment, ...]
    master_unit: str | None = None
    slave_unit: str | None = None


def format_segments(segments: Sequence[CoefficientSegment], comments: Sequence[str],
                    master_unit: str, slave_unit: str) -> str:
    """The file's text: comment lines, the units, the header, one line per segment with
    every number written by repr (it parses back to the same double)."""
    lines = [f"# {c}" for c in comments]
    lines += [f"# master_unit: {master_unit}", f"# slave_unit: {slave_unit}",
              ";".join(COLUMNS)]
    for s in segments:
        lines.append(";".join([str(POLYNOMIAL_TYPE), "0", *(repr(float(v)) for v in s.fields)]))
    return "\n".join(lines) + "\n"


def parse_segments(text: str, file: str | None = None) -> SegmentFile:
    """The segments of a file's text; UserError (with the file and line) when it is not
    a segment file sizer can run."""
    units: dict[str, str] = {}
    segments: list[CoefficientSegment] = []
    header = False
    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.strip()
        if not line:
            continue
        if line.startswith("#"):
            key, colon, value = line[1:].partition(":")
            if colon and key.strip() in ("master_unit", "slave_unit"):
                units[key.strip()] = value.strip()
            continue
        cells = [c.strip() for c in line.split(";")]
        if not header:
            if tuple(cells) != COLUMNS:
                raise UserError(f"expected the header {';'.join(COLUMNS)}", file=file,
                                line=number)
            header = True
            continue
        if len(cells) != len(COLUMNS):
            raise UserError(f"expected {len(COLUMNS)} fields separated by ';', got "
                            f"{len(cells)}", file=file, line=number)
        try:
            values = [float(c) for c in cells]
        except ValueError:
            raise UserError("every field must be a number", file=file, line=number) from None
        if not all(math.isfinite(v) for v in values):
            raise UserError("every field must be a finite number", file=file, line=number)
        if values[0] != POLYNOMIAL_TYPE:
            raise UserError(f"only Type 0 (polynomial) segments are read, got "
                            f"{cells[0]}", file=file, line=number, field="Type")
        x1, y1, x2, y2 = values[2:6]
        if not x2 > x1:
            raise UserError(f"X2 ({x2:g}) must exceed X1 ({x1:g})", file=file, line=number,
                            field="X2")
        if segments and x1 != segments[-1].x2:
            raise UserError(f"X1 ({x1:g}) must be the previous segment's X2 "
                            f"({segments[-1].x2:g}): gaps and overlaps are interpolated "
                            f"by the controller, not by sizer", file=file, line=number,
                            field="X1")
        segments.append(CoefficientSegment(x1, y1, x2, y2, tuple(values[6:13]),
                                           (values[13], values[14], values[15])))
    if not segments:
        raise UserError("no segment lines", file=file)
    return SegmentFile(tuple(segments), units.get("master_unit"), units.get("slave_unit"))


class SegmentCurve:
    """The segments as one curve over [X1 of the first, X2 of the last]: a point at a
    join takes the segment on its right, the last end the last segment."""

    def __init__(self, segments: Sequence[CoefficientSegment]) -> None:
        self.segments = tuple(segments)
        self.x = np.array([s.x1 for s in self.segments] + [self.segments[-1].x2])

    def locate(self, t: np.ndarray) -> np.ndarray:
        index = np.searchsorted(self.x[:-1], t, side="right") - 1
        return np.clip(index, 0, len(self.segments) - 1)

    def __call__(self, t: np.ndarray, nu: int = 0) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        index = self.locate(t)
        out = np.zeros(t.shape)
        for k in sorted_unique(index):
            mask = index == k
            out[mask] = self.segments[int(k)].derivative(t[mask], nu)
        return out
