"""Spectra of laws (``sizer spectrum``): one frequency column and one column per law, as
a display table, CSV with units, or JSON; and the harmonics of a repeated move (sec. 7.3.3)
with their phases. The numbers come from sizer.vibration; this module only formats them.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from sizer.report.csv_text import render_csv
from sizer.report.json_text import render_json_flat_arrays
from sizer.report.numbers import full, short_column
from sizer.report.table import Column, Table, make_table


@dataclass(frozen=True)
class SpectrumSeries:
    """One law's values at the document's frequencies (and phases for harmonics)."""

    label: str
    spec: str
    closed_form: bool
    values: np.ndarray
    phases: np.ndarray | None = None


@dataclass(frozen=True)
class SpectrumDocument:
    """A spectrum (``k`` None) or harmonic content (``k`` the harmonic numbers).

    ``frequency_name`` heads the frequency column ('fT' or 'f [Hz]'), ``value_name`` and
    ``value_unit`` the value columns ('|A_N|' and '' normalized, '|A|' and 'rad/s'
    scaled...); ``meta`` goes into the JSON before the arrays."""

    frequency: np.ndarray
    series: tuple[SpectrumSeries, ...]
    frequency_name: str
    value_name: str
    value_unit: str
    title: str
    k: np.ndarray | None = None
    meta: Mapping[str, Any] = field(default_factory=dict)

    def _value_header(self, series: SpectrumSeries) -> str:
        unit = f" [{self.value_unit}]" if self.value_unit else ""
        return f"{self.value_name} {series.label}{unit}"

    def _columns(self, with_phases: bool) -> tuple[list[str], list[np.ndarray]]:
        headers, columns = [], []
        if self.k is not None:
            headers.append("k")
            columns.append(np.asarray(self.k))
        headers.append(self.frequency_name)
        columns.append(self.frequency)
        for series in self.series:
            headers.append(self._value_header(series))
            columns.append(series.values)
            if with_phases and series.phases is not None:
                headers.append(f"phi {series.label} [rad]")
                columns.append(series.phases)
        return headers, columns

    def table(self) -> Table:
        headers, columns = self._columns(with_phases=False)
        texts = [[str(int(v)) for v in column] if self.k is not None and i == 0
                 else short_column(column) for i, column in enumerate(columns)]
        rows = list(zip(*texts, strict=True))
        return make_table([Column(h) for h in headers], rows, title=self.title)

    def csv(self) -> str:
        headers, columns = self._columns(with_phases=True)
        integer = 0 if self.k is not None else -1
        rows = ([str(int(v)) if i == integer else full(v) for i, v in enumerate(row)]
                for row in zip(*columns, strict=True))
        return render_csv(headers, rows)

    def json(self) -> str:
        document: dict[str, Any] = dict(self.meta)
        document["laws"] = [s.spec for s in self.series]
        document["closed_form"] = [s.closed_form for s in self.series]
        if self.k is not None:
            document["k"] = [int(v) for v in self.k]
        document["frequency"] = [float(v) for v in self.frequency]
        document["values"] = [[float(v) for v in s.values] for s in self.series]
        if any(s.phases is not None for s in self.series):
            document["phases"] = [[float(v) for v in s.phases] if s.phases is not None
                                  else None for s in self.series]
        return render_json_flat_arrays(document)


def spectrum_title(lines: Sequence[str]) -> str:
    """The table's title: its lines joined."""
    return "\n".join(line for line in lines if line)
