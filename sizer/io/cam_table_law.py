"""The builder of ``kind: cam_table`` laws: the CSV read, fitted, with its units and report.

The law layer (sizer.laws.data_law) imports this on first use of a cam table: reading
the file is I/O, kept out of the core. A relative ``file`` is taken from the working
directory (the design loader has already made a design's own paths absolute).

The units of the columns come from the header (``t [s]``); each is a :class:`HeaderUnit`,
a text that knows where it is written, so that a unit sizer cannot read is reported at
the CSV's header line and column (sizer.laws.data_law), not at a design field.

``span: [x0, x1]`` (master units of the file; both must be rows of the table, within
SPAN_TOLERANCE of its x range) makes the law of the rows between them: the curve of the
WHOLE table (its interpolation or fit, and its ends at rest as the table's rest criterion
decides, sizer.laws.cam_interpolation) restricted to [x0, x1], normalized to its own
stroke and duration. A span's end that is not an end of the table is at rest only where
its normalized speed is (|v_N| < sizer.laws.data_law.REST_TOLERANCE): the table's rest
criterion measures the table's own ends. Such a law may start or end moving: a move of a
cycle between boundary speeds takes it (sizer.io.cycle), as ``sizer cam`` writes a cycle.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np

from sizer.errors import UserError
from sizer.io.cam_table import CamTableData, load_cam_table
from sizer.laws.multipoint import FittedCurve

FIT_REPORT = ("max_residual", "rms_residual", "noise_sigma")
"""The fit's figures reported by name (position units of the table)."""
NOISE_ORDERS = ("velocity", "acceleration", "jerk")

SPAN_TOLERANCE = 1e-9
"""A ``span`` end names the row within this share of the file's master range (the
export writes every segment end as a row, by repr: the same number)."""


class HeaderUnit(str):
    """A unit text read from a cam table's header; ``where`` (file, line, field) is the
    place a message about it names."""

    where: dict[str, Any]

    def __new__(cls, text: str, where: dict[str, Any]) -> HeaderUnit:
        unit = super().__new__(cls, text)
        unit.where = where
        return unit

    def __reduce__(self) -> tuple[Any, ...]:
        return HeaderUnit, (str(self), self.where)


def header_units(table: CamTableData) -> tuple[str | None, str | None]:
    """The units of the table's x and q columns, each located at the header's cell."""
    x, q = (None if unit is None else HeaderUnit(unit, {
        "file": str(table.path), "line": table.header_line, "field": table.column_name(i)})
        for i, unit in enumerate(table.units))
    return x, q


def build_cam_table_law(fields: Mapping[str, Any]) -> FittedCurve:
    """The fitted curve of a cam table, the units of its columns and its fit report:
    residuals at the samples and the noise the fit puts in v, a and j (relative to
    their RMS; sizer.laws.multipoint.sample_fit)."""
    span = fields.get("span")
    table, fit, rest = load_cam_table({k: v for k, v in fields.items() if k != "span"},
                                      Path.cwd())
    curve = fit.curve
    samples = len(table.x)
    if span is not None:
        from sizer.laws.cam_interpolation import restricted_curve

        i0, i1 = span_rows(span, table.x, str(table.path), "row")
        curve = restricted_curve(curve, float(table.x[i0]), float(table.x[i1]))
        samples = i1 - i0 + 1
        if rest is not None:  # the table's rest criterion decides at the table's ends only
            rest = replace(rest, start=rest.start and i0 == 0,
                           end=rest.end and i1 == len(table.x) - 1)
    report: dict[str, float] = {k: float(getattr(fit, k)) for k in FIT_REPORT
                                if getattr(fit, k) is not None}
    for name, values in (("noise_rms", fit.noise_rms), ("noise_peak", fit.noise_peak)):
        if values is not None:
            report.update({f"{name}_{order}": float(v)
                           for order, v in zip(NOISE_ORDERS, values, strict=True)})
    report["samples"] = float(samples)
    if rest is not None:  # ends at rest within the table's resolution (DataLaw.end_speeds)
        report["rest_start"] = float(rest.start)
        report["rest_end"] = float(rest.end)
    return FittedCurve(curve, report, header_units(table))


def span_rows(span: Any, x: np.ndarray, file: str, what: str) -> tuple[int, int]:
    """The indices (i0, i1) of the rows ``span`` = [x0, x1] names in the increasing
    master values ``x`` (each within SPAN_TOLERANCE of the range); UserError at the field
    ``span`` saying the nearest rows when it names none, or when x0 >= x1."""
    if not (isinstance(span, list | tuple) and len(span) == 2
            and all(isinstance(v, int | float) and not isinstance(v, bool)
                    and math.isfinite(v) for v in span)):
        raise UserError(f"must be two master values [x0, x1] (rows of the file), got "
                        f"{span!r}", field="span")
    x0, x1 = float(span[0]), float(span[1])
    if not x0 < x1:
        raise UserError(f"x0 ({x0!r}) must be less than x1 ({x1!r})", field="span")
    reach = SPAN_TOLERANCE * max(float(x[-1] - x[0]), float(np.max(np.abs(x[[0, -1]]))))
    found = []
    for i, value in enumerate((x0, x1)):
        k = int(np.argmin(np.abs(x - value)))
        if abs(float(x[k]) - value) > reach:
            near = sorted({max(k - 1, 0), k, min(k + 1, len(x) - 1)})
            raise UserError(f"{value!r} is not a {what} of {file}: the span's ends must be "
                            f"{what}s of the file (the nearest: "
                            f"{', '.join(repr(float(x[j])) for j in near)})",
                            field=f"span[{i}]")
        found.append(k)
    return found[0], found[1]
