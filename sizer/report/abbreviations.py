"""Short forms of the ``sizer size`` terminal table's headers and cells, for a terminal too
narrow for the full ones (80 columns): the motor, the law, the duration, the peak, RMS and
speed margins and the limiting check stay, abbreviated rather than cut or dropped.

Only the rich table on a terminal is abbreviated, and only when it would not fit
otherwise (sizer.report.rich_table.fit_table); Markdown, CSV, JSON and piped text keep the
full words. ``LEGEND`` is the sentence that says so (``sizer size --help``, docs/tables.md).
"""

from __future__ import annotations

import re

from sizer.report.table import Column, Table

HEADERS = {
    "peak margin [%]": "pk mrg [%]",
    "rms margin [%]": "rms mrg [%]",
    "speed margin [%]": "spd mrg [%]",
    "speed [rpm]": "spd [rpm]",
    "max speed [rpm]": "spd [rpm]",
    "limiting": "limit",
}
"""Column headers: margin -> mrg, peak -> pk, speed -> spd, limiting -> limit."""

CHECKS = {
    "thermal_speed": "therm_spd",
    "inertia_ratio": "J_ratio",
    "load_speed": "load_spd",
    "acceleration": "accel",
    "holding_brake": "brake",
    "drive_peak_current": "drv_pk_I",
    "drive_rms_current": "drv_rms_I",
    "residual_vibration": "residual",
    "braking_resistor_power": "brake_R",
    "winding_temperature_rise": "winding_dT",
    "dead_point": "dead_pt",
}
"""Limiting checks (the stages' ``<stage>_speed`` become ``<stage>_spd``)."""

LAWS = {
    "constant_acceleration": "const_acc",
    "trapezoidal": "trap",
    "modified_trapezoidal": "mod_trap",
    "modified_sinusoidal": "mod_sine",
    "modified_cycloidal": "mod_cycl",
    "polynomial": "poly",
    "cycloidal": "cycl",
}
"""Law names; their parameters are given by position: trap(1/3) = trapezoidal(alpha=1/3)."""

LEGEND = ("On a terminal too narrow for the table (80 columns), sizer size abbreviates "
          "rather than cuts: mrg = margin, pk = peak, spd = speed, limit = the limiting "
          "check (J_ratio = inertia_ratio, winding_dT = winding_temperature_rise, "
          "drv_pk_I/drv_rms_I = the drive's currents, ...), and laws with their parameters "
          "by position (trap(1/3) = trapezoidal(alpha=1/3), poly(5) = "
          "polynomial(degree=5), mod_sine = modified_sinusoidal, cycl = cycloidal); "
          "--format md, csv or json keep the full words.")
"""The sentence of ``sizer size --help`` and docs/tables.md."""

CAPTION = "abbreviated to fit: mrg margin, pk peak, spd speed (sizer size --help)"
"""The line under an abbreviated table."""

_PARAMETER_NAME = re.compile(r"(?<=[(,])\s*[A-Za-z_][A-Za-z_0-9]*\s*=\s*")
_NAME = re.compile(r"(?:^|(?<=\())[A-Za-z_][A-Za-z_0-9]*(?=\(|\)|$)")
"""A law's name: first, or inside a wrapper's parentheses ('zv(cycloidal)')."""


def short_law(label: str) -> str:
    """'trapezoidal(alpha=1/3)' -> 'trap(1/3)'; 'double_s(alpha=1/3, beta=1/4)' ->
    'double_s(1/3, 1/4)' (a space after each comma: the cell wraps there)."""
    text = _PARAMETER_NAME.sub(lambda m: " " if m.group(0)[0].isspace() else "", label)
    text = re.sub(r",(?=\S)", ", ", text)
    return _NAME.sub(lambda m: LAWS.get(m.group(0), m.group(0)), text)


def short_check(name: str) -> str:
    """A limiting check's short name ('inertia_ratio' -> 'J_ratio')."""
    if name in CHECKS:
        return CHECKS[name]
    return re.sub(r"_speed$", "_spd", name)


CELLS = {"law": short_law, "limiting": short_check}
"""The columns whose cells get short forms, by full header."""


def abbreviated(table: Table) -> Table:
    """The table with the short headers and cells; the same object when nothing is
    shortened."""
    columns = tuple(Column(HEADERS.get(c.header, c.header), c.align) for c in table.columns)
    shorten = [CELLS.get(c.header) for c in table.columns]

    def rows(cells: tuple[tuple[str, ...], ...]) -> tuple[tuple[str, ...], ...]:
        return tuple(tuple(cell if f is None else f(cell) for cell, f in zip(row, shorten,
                                                                           strict=True))
                     for row in cells)

    short = Table(columns, rows(table.rows), table.title,
                  None if table.unicode_rows is None else rows(table.unicode_rows))
    return table if short == table else short
