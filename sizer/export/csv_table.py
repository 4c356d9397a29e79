"""A plain CSV point table: a header naming the columns with their units, then one
'master,slave' line per point (time or master position, slave position)."""

from __future__ import annotations

from sizer.export.numbers import pairs
from sizer.export.sampling import PointTable


def write(table: PointTable) -> str:
    profile = table.profile
    master = "time" if profile.over_time else "master"
    header = f"{master} [{profile.master_unit}],position [{profile.slave_unit}]"
    return "\n".join([header, *pairs(table.master, table.slave, ",")]) + "\n"
