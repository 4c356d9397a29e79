"""What the catalogs hold: summaries of catalog files, their motors, one motor in full.

    catalog_summaries()                 -> [CatalogSummary] of the bundled catalogs
    catalog_entries("yaskawa-sgm7j")    -> [MotorEntry] of one catalog (name or file)
    find_motor("SGM7J-02A")             -> MotorEntry, searched in the bundled catalogs
    find_motor("X", ["my-motors.yaml"]) -> ... or in the given ones

A MotorEntry holds the SI motor that the sizing uses, its speed-torque regions as the
sizing sees them (``sizer.envelope``), and the fields as written in the file (units
included, catalog-level defaults filled in), with the file and line.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from sizer.envelope import continuous_region, intermittent_region
from sizer.errors import UserError
from sizer.io.loader import bundled_catalogs, default_catalogs, load_catalog, resolve_catalog
from sizer.io.yaml_source import read_yaml
from sizer.model.domain import Curve, Motor

CATALOG_DEFAULTS = ("manufacturer", "source")
"""Catalog-level fields that motors without their own inherit."""


@dataclass(frozen=True)
class CatalogSummary:
    """One catalog file: its name, title, motors and manufacturers."""

    name: str
    path: Path
    title: str | None
    motors: int
    manufacturers: tuple[str, ...]
    default: bool
    """True when a design that names no catalog is sized against it."""


@dataclass(frozen=True)
class MotorEntry:
    """One motor of a catalog, as loaded (SI) and as written."""

    motor: Motor
    catalog: str
    """The catalog's name: the bundled name, or the file's stem."""
    path: Path
    line: int | None
    given: dict[str, Any]
    """The motor's fields as written (texts with units), catalog defaults filled in."""
    notes: str | None

    @property
    def has_curves(self) -> bool:
        return bool(self.motor.continuous_curve or self.motor.intermittent_curve)

    @property
    def continuous_region(self) -> Curve:
        """(rad/s, N*m) corner points of the continuous region used by the sizing."""
        return continuous_region(self.motor)

    @property
    def intermittent_region(self) -> Curve:
        """(rad/s, N*m) corner points of the intermittent region used by the sizing."""
        return intermittent_region(self.motor)


def catalog_summaries(names: Iterable[str] | None = None) -> list[CatalogSummary]:
    """Summaries of the bundled catalogs (or of the given names or files), in name order."""
    if names is None:
        return [summarize_catalog(path) for path in bundled_catalogs().values()]
    return [summarize_catalog(name) for name in names]


def summarize_catalog(reference: str | Path) -> CatalogSummary:
    """A summary of one catalog (a bundled name or a file); UserError if it does not load."""
    path = resolve_catalog(reference, Path.cwd())
    entries = catalog_entries(path)
    data = read_yaml(path).data
    title = data.get("catalog") if isinstance(data.get("catalog"), str) else None
    makers = tuple(dict.fromkeys(e.motor.manufacturer for e in entries if e.motor.manufacturer))
    return CatalogSummary(name=_name(path), path=path, title=title, motors=len(entries),
                          manufacturers=makers, default=_is_default(path))


def catalog_entries(reference: str | Path) -> list[MotorEntry]:
    """The motors of one catalog (a bundled name or a file), in file order."""
    path = resolve_catalog(reference, Path.cwd())
    motors = load_catalog(path)  # raises UserError, located, on any mistake
    source = read_yaml(path)
    data = source.data
    defaults = {key: data[key] for key in CATALOG_DEFAULTS if data.get(key) is not None}
    entries = []
    for index, (motor, raw) in enumerate(zip(motors, data["motors"], strict=True)):
        given = dict(raw)
        for key, value in defaults.items():
            given.setdefault(key, value)
        notes = given.pop("notes", None)
        entries.append(MotorEntry(motor=motor, catalog=_name(path), path=path,
                                  line=source.line_of(("motors", index)), given=given,
                                  notes=str(notes) if notes is not None else None))
    return entries


def find_motor(motor_id: str, catalogs: Sequence[str | Path] | None = None) -> MotorEntry:
    """The motor with this id, from the given catalogs or else from every bundled one.

    The first match in catalog order wins; an unknown id is a UserError naming close ids.
    """
    references: Sequence[str | Path] = catalogs or list(bundled_catalogs().values())
    known: list[str] = []
    for reference in references:
        for entry in catalog_entries(reference):
            if entry.motor.id == motor_id:
                return entry
            known.append(entry.motor.id)
    close = difflib.get_close_matches(motor_id, known, n=3)
    hint = f"; did you mean {', '.join(repr(c) for c in close)}?" if close else ""
    where = "the given catalogs" if catalogs else "the bundled catalogs"
    raise UserError(f"no motor {motor_id!r} in {where}{hint} ('sizer catalog list NAME' "
                    f"lists a catalog's motors)", field="ID")


def _name(path: Path) -> str:
    for name, bundled in bundled_catalogs().items():
        if _same(bundled, path):
            return name
    return path.stem


def _is_default(path: Path) -> bool:
    return any(_same(p, path) for p in default_catalogs().values())


def _same(a: Path, b: Path) -> bool:
    try:
        return a.resolve() == b.resolve()
    except OSError:
        return False
