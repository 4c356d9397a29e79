"""Catalog listings (``sizer catalog list`` and ``show``): tables, CSV and JSON.

Tables are for people: torques in N*m, speeds in rpm, inertia in kg*cm^2. CSV and JSON
are SI (N*m, rad/s, kg*m^2) with the units named, like the other reports. Nothing is
computed here beyond unit conversion for display.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from sizer.catalog_tools.listing import CatalogSummary, MotorEntry
from sizer.io.schema.provenance import ROW_ALIASES
from sizer.model.domain import Curve, Motor
from sizer.report.csv_text import render_csv
from sizer.report.figure_grades import SourceIndex, grade_counts, provenance_json
from sizer.report.json_text import render_json
from sizer.report.numbers import full, short
from sizer.report.table import Column, Table, make_table

RPM_PER_RAD_S = 30.0 / math.pi
KG_CM2_PER_KG_M2 = 1e4

SI_UNITS = {"inertia": "kg*m^2", "continuous_torque": "N*m", "peak_torque": "N*m",
            "rated_speed": "rad/s", "max_speed": "rad/s", "damping": "N*m*s/rad",
            "mass": "kg", "price": "1", "region_speed": "rad/s", "region_torque": "N*m"}


def _opt(value: float | None, scale: float = 1.0) -> str:
    return "" if value is None else short(value * scale)


def _opt_full(value: float | None) -> str:
    return "" if value is None else full(value)


# ------------------------------------------------------------------ list of catalogs


class CatalogsDocument:
    """The catalogs (bundled ones by default): name, motors, manufacturers, file."""

    title = "Motor catalogs"
    columns = (Column("catalog", "left"), Column("motors"), Column("manufacturers", "left"),
               Column("default", "left"), Column("file", "left"))
    csv_headers = ("catalog", "title", "motors", "manufacturers", "default", "file")

    def __init__(self, summaries: Sequence[CatalogSummary]) -> None:
        self.summaries = list(summaries)

    def table(self) -> Table:
        rows = [(s.name, str(s.motors), ", ".join(s.manufacturers),
                 "yes" if s.default else "no", str(s.path)) for s in self.summaries]
        return make_table(self.columns, rows, title=self.title)

    def csv(self) -> str:
        return render_csv(self.csv_headers, (
            (s.name, s.title or "", str(s.motors), ";".join(s.manufacturers),
             "true" if s.default else "false", str(s.path)) for s in self.summaries))

    def json(self) -> str:
        return render_json([{"catalog": s.name, "title": s.title, "motors": s.motors,
                             "manufacturers": list(s.manufacturers), "default": s.default,
                             "file": str(s.path)} for s in self.summaries])


# ------------------------------------------------------------------ motors of one catalog


class MotorsDocument:
    """The motors of one catalog, one row each."""

    columns = (Column("id", "left"), Column("manufacturer", "left"),
               Column("cont. torque [N*m]"), Column("peak torque [N*m]"),
               Column("rated speed [rpm]"), Column("max speed [rpm]"),
               Column("inertia [kg*cm^2]"), Column("curves", "left"))
    csv_headers = ("id", "manufacturer", "part_number", "continuous_torque [N*m]",
                   "peak_torque [N*m]", "rated_speed [rad/s]", "max_speed [rad/s]",
                   "inertia [kg*m^2]", "curves", "source")

    def __init__(self, entries: Sequence[MotorEntry], title: str = "") -> None:
        self.entries = list(entries)
        self.title = title

    def table(self) -> Table:
        rows = []
        for e in self.entries:
            m = e.motor
            rows.append((m.id, m.manufacturer or "", short(m.continuous_torque),
                         short(m.peak_torque), short(m.rated_speed * RPM_PER_RAD_S),
                         _opt(m.max_speed, RPM_PER_RAD_S), short(m.inertia * KG_CM2_PER_KG_M2),
                         "yes" if e.has_curves else "no"))
        return make_table(self.columns, rows, title=self.title)

    def csv(self) -> str:
        return render_csv(self.csv_headers, (
            (e.motor.id, e.motor.manufacturer or "", e.motor.part_number or "",
             full(e.motor.continuous_torque), full(e.motor.peak_torque),
             full(e.motor.rated_speed), _opt_full(e.motor.max_speed), full(e.motor.inertia),
             "true" if e.has_curves else "false", e.motor.source or "")
            for e in self.entries))

    def json(self) -> str:
        return render_json({
            "catalog": self.entries[0].catalog if self.entries else None,
            "file": str(self.entries[0].path) if self.entries else None,
            "units": {k: SI_UNITS[k] for k in ("inertia", "continuous_torque", "peak_torque",
                                               "rated_speed", "max_speed")},
            "motors": [{"id": e.motor.id, "manufacturer": e.motor.manufacturer,
                        "part_number": e.motor.part_number,
                        "continuous_torque": e.motor.continuous_torque,
                        "peak_torque": e.motor.peak_torque,
                        "rated_speed": e.motor.rated_speed, "max_speed": e.motor.max_speed,
                        "inertia": e.motor.inertia, "curves": e.has_curves,
                        "source": e.motor.source, "grades": grade_counts(e.motor)}
                       for e in self.entries],
        })


# ------------------------------------------------------------------ one motor


def _given_text(value: Any) -> str:
    """A field as written in the file; a curve as '[0 rpm, 0.3 N*m]; [3000 rpm, ...]'."""
    if isinstance(value, list):
        return "; ".join(_point_text(v) for v in value)
    return str(value)


def _point_text(value: Any) -> str:
    if isinstance(value, list):
        return "[" + ", ".join(str(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k}: {v}" for k, v in value.items()) + "}"
    return str(value)


def _point(speed: float, torque: float) -> str:
    return f"{short(speed * RPM_PER_RAD_S)} rpm, {short(torque)} N*m"


SHOWN_ELSEWHERE = frozenset({"id", "manufacturer", "part_number", "source", "notes",
                             "figure_sources", "continuous_curve", "intermittent_curve"})
"""Fields of a motor row the table shows in rows of their own."""


class MotorDocument:
    """One motor: every field as written and in display units, with its grade (A1: grade
    A, source 1 of the list below the figures; '-' ungraded), its regions, its sources."""

    columns = (Column("field", "left"), Column("as written", "left"), Column("value", "left"),
               Column("grade", "left"))
    csv_headers = ("field", "as written", "SI value", "SI unit")

    def __init__(self, entry: MotorEntry) -> None:
        self.entry = entry

    def _values(self) -> list[tuple[str, float | None, float, str]]:
        """(field, SI value, display scale, display unit) of the numeric fields."""
        m = self.entry.motor
        return [
            ("inertia", m.inertia, KG_CM2_PER_KG_M2, "kg*cm^2"),
            ("continuous_torque", m.continuous_torque, 1.0, "N*m"),
            ("peak_torque", m.peak_torque, 1.0, "N*m"),
            ("rated_speed", m.rated_speed, RPM_PER_RAD_S, "rpm"),
            ("max_speed", m.max_speed, RPM_PER_RAD_S, "rpm"),
            ("damping", m.damping, 1.0, "N*m*s/rad"),
            ("mass", m.mass, 1.0, "kg"),
            ("price", m.price, 1.0, ""),
        ]

    def _regions(self) -> list[tuple[str, Curve]]:
        return [("continuous region", self.entry.continuous_region),
                ("intermittent region", self.entry.intermittent_region)]

    @property
    def title(self) -> str:
        e = self.entry
        where = f"{e.path}" + (f":{e.line}" if e.line is not None else "")
        return f"Motor {e.motor.id} (catalog {e.catalog}, {where})"

    def table(self) -> Table:
        e, given, m = self.entry, self.entry.given, self.entry.motor
        index = SourceIndex()

        def grade(key: str) -> str:
            name = ROW_ALIASES.get(key, key)
            return index.label(None if m.provenance is None else m.provenance.of(name))

        rows: list[tuple[str, str, str, str]] = [
            ("id", str(given.get("id", m.id)), m.id, "")]
        for key in ("manufacturer", "part_number"):
            if key in given:
                rows.append((key, str(given[key]), "", ""))
        values = self._values()
        for key, value, scale, unit in values:
            if key in given or (value is not None and key != "damping"):
                shown = "" if value is None else f"{short(value * scale)} {unit}".strip()
                rows.append((key, _given_text(given.get(key, "")), shown, grade(key)))
        listed = {key for key, *_ in values} | SHOWN_ELSEWHERE
        for key in given:
            if key not in listed:
                rows.append((key, _given_text(given[key]), "", grade(key)))
        for key in ("continuous_curve", "intermittent_curve"):
            if key in given:
                rows.append((key, _given_text(given[key]), "", grade(key)))
        for name, region in self._regions():
            for index_, (speed, torque) in enumerate(region):
                rows.append((f"{name} [{index_}]", "", _point(speed, torque), ""))
        rows.append(("source", str(given.get("source", m.source or "")), "", ""))
        rows.append(("grades", grade_counts(m), "", ""))
        for provenance, number in index.sources.items():
            rows.append((f"source {number}", f"grade {provenance.grade}: {provenance.text}",
                         "", ""))
        if e.notes:
            rows.append(("notes", e.notes, "", ""))
        return make_table(self.columns, rows, title=self.title)

    def csv(self) -> str:
        e, given = self.entry, self.entry.given
        rows: list[tuple[str, str, str, str]] = [("id", str(given.get("id", "")), e.motor.id, "")]
        for key in ("manufacturer", "part_number"):
            rows.append((key, str(given.get(key, "")), getattr(e.motor, key) or "", ""))
        for key, value, _, _ in self._values():
            rows.append((key, _given_text(given.get(key, "")), _opt_full(value), SI_UNITS[key]))
        for key in ("continuous_curve", "intermittent_curve"):
            rows.append((key, _given_text(given.get(key, "")), "", ""))
        for name, region in self._regions():
            label = name.split()[0]
            for index, (speed, torque) in enumerate(region):
                rows.append((f"{label}_region[{index}].speed", "", full(speed), "rad/s"))
                rows.append((f"{label}_region[{index}].torque", "", full(torque), "N*m"))
        rows.append(("source", str(given.get("source", "")), e.motor.source or "", ""))
        rows.append(("notes", e.notes or "", "", ""))
        return render_csv(self.csv_headers, rows)

    def json(self) -> str:
        e, m = self.entry, self.entry.motor
        return render_json({
            "id": m.id,
            "catalog": e.catalog,
            "file": str(e.path),
            "line": e.line,
            "manufacturer": m.manufacturer,
            "part_number": m.part_number,
            "given": {k: v for k, v in e.given.items()},
            "si": {key: value for key, value, _, _ in self._values()},
            "units": {**{key: SI_UNITS[key] for key, *_ in self._values()},
                      "regions": "[rad/s, N*m]"},
            "continuous_region": [[s, t] for s, t in e.continuous_region],
            "intermittent_region": [[s, t] for s, t in e.intermittent_region],
            "source": m.source,
            "figure_sources": _provenance(m),
            "notes": e.notes,
        })


def _provenance(motor: Motor) -> dict[str, Any]:
    """The motor's figures' grades and the sources they cite (JSON)."""
    shown = provenance_json([motor])
    return {"sources": shown["sources"], **shown["motors"][motor.id]}
