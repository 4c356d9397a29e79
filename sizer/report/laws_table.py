"""The shape-coefficient table of motion laws (``sizer laws``): rows, CSV, JSON, display."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from sizer.laws.data_spec import data_law_label, is_data_spec
from sizer.report.csv_text import render_csv
from sizer.report.json_text import render_json
from sizer.report.numbers import (
    continuity_text,
    continuity_value,
    fraction_or_short,
    full,
    short,
)
from sizer.report.table import Column, Table, make_table

if TYPE_CHECKING:
    from sizer.laws import MotionLaw

COEFFICIENTS = ("C_v", "C_a", "C_j", "C_v_rms", "C_a_rms")

CSV_HEADERS = ("law", "spec", "continuity", "C_v", "C_a", "C_j", "jerk_bounded",
               "C_v_rms", "C_a_rms", "acceleration_jump_tau")
"""CSV columns; jump positions are separated by ';' in one cell."""

TABLE_COLUMNS = (
    Column("law", "left"), Column("continuity", "left"), Column("C_v"), Column("C_a"),
    Column("C_j"), Column("C_v_rms"), Column("C_a_rms"), Column("jerk", "left"),
)
"""Display columns; 'jerk' says 'bounded', or where the acceleration jumps (impulses)."""


@dataclass(frozen=True)
class LawRow:
    """The numbers of one law, as plain Python values (floats, not numpy scalars)."""

    law_id: str
    spec: str
    params: dict[str, float]
    continuity: float
    C_v: float
    C_a: float
    C_j: float
    jerk_bounded: bool
    C_v_rms: float
    C_a_rms: float
    jumps: tuple[tuple[float, float], ...]
    """(tau, jump) where the normalized acceleration steps."""

    @classmethod
    def of(cls, law: MotionLaw) -> LawRow:
        c = law.coefficients
        return cls(
            law_id=law.law_id,
            spec=law.spec,
            params={name: float(value) for name, value in law.params.items()},
            continuity=float(law.continuity),
            **{name: float(getattr(c, name)) for name in COEFFICIENTS},
            jerk_bounded=bool(c.jerk_bounded),
            jumps=tuple((float(j.tau), float(j.jump)) for j in c.acceleration_jumps),
        )

    def as_json(self) -> dict[str, Any]:
        """The JSON object of this law, keys in a fixed order."""
        return {
            "law": self.law_id,
            "spec": self.spec,
            "params": self.params,
            "continuity": continuity_value(self.continuity),
            "C_v": self.C_v,
            "C_a": self.C_a,
            "C_j": self.C_j,
            "jerk_bounded": self.jerk_bounded,
            "C_v_rms": self.C_v_rms,
            "C_a_rms": self.C_a_rms,
            "acceleration_jumps": [{"tau": tau, "jump": jump} for tau, jump in self.jumps],
        }

    def csv_cells(self) -> tuple[str, ...]:
        """CSV cells at full precision."""
        return (
            self.law_id, self.spec, str(continuity_value(self.continuity)),
            full(self.C_v), full(self.C_a), full(self.C_j),
            "true" if self.jerk_bounded else "false",
            full(self.C_v_rms), full(self.C_a_rms),
            ";".join(full(tau) for tau, _ in self.jumps),
        )

    def jerk_text(self) -> str:
        """'bounded', or 'impulses at 0, 1/2, 1' (tau where the acceleration jumps)."""
        if self.jerk_bounded:
            return "bounded"
        return "impulses at " + ", ".join(fraction_or_short(tau) for tau, _ in self.jumps)

    def table_cells(self, *, unicode: bool = False) -> tuple[str, ...]:
        """Display cells: short numbers, jump positions as fractions where they are."""
        return (
            data_law_label(self.spec) if is_data_spec(self.spec) else self.spec,
            continuity_text(self.continuity, unicode=unicode),
            short(self.C_v), short(self.C_a), short(self.C_j),
            short(self.C_v_rms), short(self.C_a_rms), self.jerk_text(),
        )


class LawsDocument:
    """The coefficient table of a list of laws, in every format."""

    title = "Motion-law shape coefficients (dimensionless)"

    def __init__(self, laws: Sequence[MotionLaw]) -> None:
        self.rows = [LawRow.of(law) for law in laws]

    def table(self) -> Table:
        return make_table(
            TABLE_COLUMNS,
            [row.table_cells() for row in self.rows],
            title=self.title,
            unicode_rows=[row.table_cells(unicode=True) for row in self.rows],
        )

    def csv(self) -> str:
        return render_csv(CSV_HEADERS, (row.csv_cells() for row in self.rows))

    def json(self) -> str:
        return render_json([row.as_json() for row in self.rows])
