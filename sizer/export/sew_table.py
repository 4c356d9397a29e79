"""A SEW-EURODRIVE MOVI-C cam point file: the first line the number of pairs n, then n
lines 'master;slave' (decimal point). Source: ../shared/reference/controller-cams.md,
"SEW MOVI-C" (files stored in /DATA/Camming/<axis>; point interpolation)."""

from __future__ import annotations

from sizer.export.numbers import pairs
from sizer.export.sampling import PointTable


def write(table: PointTable) -> str:
    return "\n".join([str(table.points), *pairs(table.master, table.slave, ";")]) + "\n"
