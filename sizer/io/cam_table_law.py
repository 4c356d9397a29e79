"""The builder of ``kind: cam_table`` laws: the CSV read, fitted, with its units and report.

The law layer (sizer.laws.data_law) imports this on first use of a cam table: reading
the file is I/O, kept out of the core. A relative ``file`` is taken from the working
directory (the design loader has already made a design's own paths absolute).
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from sizer.io.cam_table import load_cam_table
from sizer.laws.multipoint import FittedCurve

FIT_REPORT = ("max_residual", "rms_residual", "noise_sigma")
"""The fit's figures reported by name (position units of the table)."""
NOISE_ORDERS = ("velocity", "acceleration", "jerk")


def build_cam_table_law(fields: Mapping[str, Any]) -> FittedCurve:
    """The fitted curve of a cam table, the units of its columns and its fit report:
    residuals at the samples and the noise the fit puts in v, a and j (relative to
    their RMS; sizer.laws.multipoint.sample_fit)."""
    table, fit = load_cam_table(fields, Path.cwd())
    report: dict[str, float] = {k: float(getattr(fit, k)) for k in FIT_REPORT
                                if getattr(fit, k) is not None}
    for name, values in (("noise_rms", fit.noise_rms), ("noise_peak", fit.noise_peak)):
        if values is not None:
            report.update({f"{name}_{order}": float(v)
                           for order, v in zip(NOISE_ORDERS, values, strict=True)})
    report["samples"] = float(len(table.x))
    return FittedCurve(fit.curve, report, table.units)
