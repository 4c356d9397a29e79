"""A sampled motion t, q, v, a, j (``sizer law``): CSV with units, JSON, display table."""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING

import numpy as np

from sizer.laws.data_spec import law_label
from sizer.report.csv_text import render_csv
from sizer.report.json_text import render_json_flat_arrays
from sizer.report.numbers import full, short, short_column
from sizer.report.table import Column, Table, make_table
from sizer.units import KINDS

if TYPE_CHECKING:
    from sizer.laws import ScaledMotion

SERIES = ("t", "q", "v", "a", "j")

_ROTARY_KINDS = ("time", "angle", "angular_speed", "angular_acceleration", "angular_jerk")
_LINEAR_KINDS = ("time", "length", "linear_speed", "linear_acceleration", "linear_jerk")


def series_units(linear: bool) -> dict[str, str]:
    """SI unit of each series: rad-based for a rotary axis, m-based for a linear one."""
    kinds = _LINEAR_KINDS if linear else _ROTARY_KINDS
    return {name: KINDS[kind].si_unit for name, kind in zip(SERIES, kinds, strict=True)}


class SeriesDocument:
    """Samples of one move, with the move's data, in every format."""

    def __init__(self, motion: ScaledMotion, series: Mapping[str, np.ndarray], *,
                 linear: bool) -> None:
        self.motion = motion
        self.series = {name: np.asarray(series[name], dtype=float) for name in SERIES}
        self.units = series_units(linear)

    @property
    def headers(self) -> tuple[str, ...]:
        return tuple(f"{name} [{self.units[name]}]" for name in SERIES)

    def _columns(self) -> list[np.ndarray]:
        return [self.series[name] for name in SERIES]

    def table(self) -> Table:
        columns = [short_column(values) for values in self._columns()]
        rows = list(zip(*columns, strict=True))
        title = (f"{law_label(self.motion.law.spec)}: h = {short(self.motion.displacement)} "
                 f"{self.units['q']}, T = {short(self.motion.duration)} s")
        fit = fit_text(self.motion.law)
        if fit:
            title += f"\n{fit}"
        return make_table([Column(h) for h in self.headers], rows, title=title)

    def csv(self) -> str:
        rows = ([full(x) for x in row] for row in zip(*self._columns(), strict=True))
        return render_csv(self.headers, rows)

    def json(self) -> str:
        motion = self.motion
        document = {
            "law": motion.law.law_id,
            "spec": motion.law.spec,
            "displacement": float(motion.displacement),
            "duration": float(motion.duration),
            "start_time": float(motion.start_time),
            "start_position": float(motion.start_position),
            "samples": len(self.series["t"]),
            "units": self.units,
        }
        fit = getattr(motion.law, "report", None)
        if fit:
            document["fit"] = dict(fit)
        document.update({name: self.series[name].tolist() for name in SERIES})
        return render_json_flat_arrays(document)


def fit_text(law: object) -> str:
    """One line on a fitted law's fit (a cam table): the residuals at the samples, in the
    table's position units, and the noise the fit puts in v, a and j (% of their RMS)."""
    report = getattr(law, "report", None)
    if not report or "max_residual" not in report:
        return ""
    text = (f"fit of {int(report.get('samples', 0))} samples: residual max "
            f"{short(report['max_residual'])}, RMS {short(report['rms_residual'])}")
    noise = [(name, report.get(f"noise_rms_{name}")) for name in ("velocity", "acceleration",
                                                                  "jerk")]
    if all(value is not None for _, value in noise):
        text += "; noise the fit puts in " + ", ".join(
            f"{name[0]} {100 * value:.3g} %" for name, value in noise) + " of their RMS"
    return text
