"""The builder of ``kind: cam_table`` laws: the CSV read, fitted, with its units and report.

The law layer (sizer.laws.data_law) imports this on first use of a cam table: reading
the file is I/O, kept out of the core. A relative ``file`` is taken from the working
directory (the design loader has already made a design's own paths absolute).

The units of the columns come from the header (``t [s]``); each is a :class:`HeaderUnit`,
a text that knows where it is written, so that a unit sizer cannot read is reported at
the CSV's header line and column (sizer.laws.data_law), not at a design field.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from sizer.io.cam_table import CamTableData, load_cam_table
from sizer.laws.multipoint import FittedCurve

FIT_REPORT = ("max_residual", "rms_residual", "noise_sigma")
"""The fit's figures reported by name (position units of the table)."""
NOISE_ORDERS = ("velocity", "acceleration", "jerk")


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
    table, fit, rest = load_cam_table(fields, Path.cwd())
    report: dict[str, float] = {k: float(getattr(fit, k)) for k in FIT_REPORT
                                if getattr(fit, k) is not None}
    for name, values in (("noise_rms", fit.noise_rms), ("noise_peak", fit.noise_peak)):
        if values is not None:
            report.update({f"{name}_{order}": float(v)
                           for order, v in zip(NOISE_ORDERS, values, strict=True)})
    report["samples"] = float(len(table.x))
    if rest is not None:  # ends at rest within the table's resolution (DataLaw.end_speeds)
        report["rest_start"] = float(rest.start)
        report["rest_end"] = float(rest.end)
    return FittedCurve(fit.curve, report, header_units(table))
