"""A coefficient study (``sizer laws --sweep``): the table of the shape coefficients over a
law's swept parameters in every format, and its plot (book Figs. 6.10 and 6.14).

The numbers come from :func:`sizer.laws.sweep.sweep_coefficients`; this module lays
them out. A point where the law does not exist has empty cells (CSV), nulls and its
``reason`` (JSON), ``n/a`` (table) and a gap in the plot; so has C_j where the law has
jerk impulses (``jerk_bounded`` false: C_j is no bound there).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from sizer.laws.coefficients import COEFFICIENT_NAMES
from sizer.report.csv_text import render_csv
from sizer.report.json_text import render_json
from sizer.report.numbers import full_or_empty, short_or_na
from sizer.report.table import Column, Table, make_table

if TYPE_CHECKING:
    from sizer.laws.sweep import SweepPoint, SweepResult

PLOT_SIZE = (9.0, 5.5)
"""The plot's size in inches."""
MAX_CURVES = 8
"""Curves per panel for the second parameter of a two-parameter sweep (evenly picked)."""


def _value(point: SweepPoint, name: str) -> float | None:
    """A coefficient of a point; None where the law does not exist, or for C_j where the
    jerk is unbounded."""
    if point.coefficients is None or (name == "C_j" and point.jerk_bounded is False):
        return None
    value = point.coefficients[name]
    return value if math.isfinite(value) else None


class SweepDocument:
    """The coefficients of a sweep, one row per point (``sizer.report.document``)."""

    def __init__(self, result: SweepResult,
                 fastest: Sequence[tuple[float | None, str | None]] | None = None) -> None:
        self.result = result
        self.fastest = None if fastest is None else list(fastest)
        """Per point, a design's T_min (s) and its fastest feasible motor (None: none)."""
        self.title = (f"Shape coefficients of {result.sweep.law} against "
                      f"{' and '.join(result.names)} (dimensionless)")

    def table(self) -> Table:
        columns = [Column(name) for name in self.result.names]
        columns += [Column(name) for name in COEFFICIENT_NAMES]
        columns.append(Column("jerk", "left"))
        if self.fastest is not None:
            columns += [Column("T_min [ms]"), Column("motor", "left")]
        rows = []
        for k, p in enumerate(self.result.points):
            jerk = ("n/a" if p.jerk_bounded is None else
                    "bounded" if p.jerk_bounded else "impulses")
            row = [*(f"{v:.6g}" for v in p.values),
                   *(short_or_na(_value(p, name)) for name in COEFFICIENT_NAMES), jerk]
            if self.fastest is not None:
                t_min, motor = self.fastest[k]
                row += [short_or_na(t_min, 1e3), motor or "none feasible"
                        if p.coefficients is not None else "n/a"]
            rows.append(row)
        return make_table(columns, rows, title=self.title)

    def csv(self) -> str:
        design = () if self.fastest is None else ("T_min [s]", "motor")
        headers = (*self.result.names, "spec", *COEFFICIENT_NAMES, "jerk_bounded",
                   *design, "reason")
        rows = ((*(repr(float(v)) for v in p.values), p.spec,
                 *(full_or_empty(_value(p, name)) for name in COEFFICIENT_NAMES),
                 "" if p.jerk_bounded is None else str(p.jerk_bounded).lower(),
                 *(() if self.fastest is None else
                   (full_or_empty(self.fastest[k][0]), self.fastest[k][1] or "")),
                 p.reason)
                for k, p in enumerate(self.result.points))
        return render_csv(headers, rows)

    def as_json(self) -> dict[str, Any]:
        sweep = self.result.sweep
        return {
            "law": sweep.law,
            "ranges": [{"name": r.name, "from": r.start, "to": r.stop, "points": r.points}
                       for r in sweep.ranges],
            "fixed": list(sweep.fixed),
            "points": [{**dict(zip(self.result.names, p.values, strict=True)),
                        "spec": p.spec,
                        **{name: _value(p, name) for name in COEFFICIENT_NAMES},
                        "jerk_bounded": p.jerk_bounded,
                        **({} if self.fastest is None else
                           {"T_min": self.fastest[k][0], "motor": self.fastest[k][1]}),
                        "reason": p.reason or None}
                       for k, p in enumerate(self.result.points)],
        }

    def json(self) -> str:
        return render_json(self.as_json())


def plot_sweep(result: SweepResult, path: Path | str,
               fastest: Sequence[tuple[float | None, str | None]] | None = None) -> Path:
    """One panel per coefficient against the first swept parameter (a curve per value of
    the second, at most :data:`MAX_CURVES`), and a design's T_min in the sixth where
    given, written as PNG or SVG by ``path``'s suffix."""
    import numpy as np

    from sizer.report.plots.figure_files import figure_format, new_figure, save_figure

    figure_format(path, "--plot")  # the suffix checked before any drawing
    figure = new_figure(PLOT_SIZE)
    axes = figure.subplots(2, 3, sharex=True).ravel()
    first = result.sweep.ranges[0]
    x = first.values
    columns = {name: np.array([np.nan if v is None else v for v in
                               (_value(p, name) for p in result.points)], dtype=float)
               for name in COEFFICIENT_NAMES}
    curves: list[tuple[str, slice]] = [("", slice(None))]
    if len(result.sweep.ranges) == 2:
        second = result.sweep.ranges[1]
        n, m = first.points, second.points
        picked = sorted({round(k) for k in np.linspace(0, m - 1, min(m, MAX_CURVES))})
        curves = [(f"{second.name} = {second.values[k]:.4g}", slice(k * n, (k + 1) * n))
                  for k in picked]
    panels = list(COEFFICIENT_NAMES)
    if fastest is not None:
        columns["T_min [s]"] = np.array([np.nan if t is None else t for t, _ in fastest],
                                        dtype=float)
        panels.append("T_min [s]")
    for ax, name in zip(axes, panels, strict=False):
        for label, rows in curves:
            ax.plot(x, columns[name][rows], label=label or None)
        ax.set_title(name)
        ax.grid(True, alpha=0.3)
        if not np.isfinite(columns[name]).any():
            ax.text(0.5, 0.5, "jerk impulses: no bound" if name == "C_j" else "none",
                    transform=ax.transAxes, ha="center", va="center")
            ax.set_yticks([])
    for ax in axes[2:]:
        ax.set_xlabel(first.name)
        ax.tick_params(labelbottom=True)
    if fastest is None:
        axes[5].axis("off")
    if len(curves) > 1:
        handles, labels = axes[0].get_legend_handles_labels()
        where = axes[5] if fastest is None else axes[0]
        where.legend(handles, labels, loc="center" if fastest is None else "best",
                     title=None if fastest is not None else "curves", fontsize="small")
    figure.suptitle(f"{result.sweep.law}: shape coefficients (sec. 6.2)")
    return save_figure(figure, path)
