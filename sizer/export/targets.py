"""The cam targets: each a writer, its limit on points, whether its master values may be
unevenly spaced, and how its controller interpolates the table (what the certificate
re-evaluates)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from sizer.export import codesys_xy, csv_table, sew_table
from sizer.export.sampling import MAX_POINTS, PointTable


@dataclass(frozen=True)
class Target:
    """A point-table target."""

    name: str
    title: str
    limit: int
    interpolation: str
    source: str
    write: Callable[[PointTable], str]
    per_segment: bool = True
    """The table's master values may be any increasing ones: a machine cycle's dwells get
    their ends only (sizer.export.sampling.master_values). False: equidistant."""


LINEAR = "linear"

TARGETS: dict[str, Target] = {t.name: t for t in (
    Target("csv", "CSV point table", MAX_POINTS, LINEAR,
           "a plain table; linear interpolation assumed (numpy.interp)", csv_table.write),
    Target("codesys-xy", "CODESYS SoftMotion ASCII X/Y cam table", codesys_xy.MAX_ELEMENTS,
           LINEAR,
           "controller-cams.md line 45 (CODESYS SoftMotion SM3_Basic: MC_CAM_REF."
           "byInterpolationQuality 1 linear, 3 cubic; the default file limit "
           "gc_SMC_FILE_MAXCAMEL = 128 elements): load it with byInterpolationQuality := 1",
           codesys_xy.write, per_segment=False),
    Target("sew", "SEW MOVI-C cam point file", MAX_POINTS, LINEAR,
           "controller-cams.md line 48 (SEW MOVI-C: 'Point interpolation', taken as "
           "linear between the points)", sew_table.write),
)}
