"""Convert a vendor's spreadsheet (CSV) into a motor catalog, with a unit per column.

    maps = [parse_column_map("Model=id"),
            parse_column_map("Rated torque (Nm)=continuous_torque:N*m"),
            parse_column_map("J (kgcm2)=inertia:kg*cm^2"), ...]
    catalog = import_csv("vendor.csv", maps, source="Vendor datasheet, https://...")
    catalog.yaml()     -> the catalog text (deterministic)

A mapped column's cells are numbers; each is written with the column's unit
('0.637 N*m'), so the catalog keeps the datasheet's figures as printed. A column mapped
without a unit is copied as it reads (a text field, or a quantity that carries its own
unit; a bare number means SI). Empty cells stay absent. Every row is validated like a
catalog motor (schema and sanity checks); all problems are collected and raised together
as a CatalogImportError, each located at the CSV file and line.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from pydantic import ValidationError

from sizer.catalog_tools.catalog_yaml import render_catalog
from sizer.errors import UserError
from sizer.input_limits import MAX_CATALOG_BYTES
from sizer.io.csv_rows import NUMBER, csv_delimiter, csv_records, decimal_point
from sizer.io.files import decode_text, read_user_bytes
from sizer.io.motor_rules import check_motor, motor_of
from sizer.io.schema.inputs import MotorInput
from sizer.io.validation import all_problems
from sizer.io.yaml_source import YamlSource
from sizer.units import KINDS, to_si

FIELD_KINDS: dict[str, str | None] = {
    "id": None,
    "part_number": None,
    "manufacturer": None,
    "inertia": "inertia",
    "continuous_torque": "torque",
    "peak_torque": "torque",
    "rated_speed": "angular_speed",
    "max_speed": "angular_speed",
    "damping": "rotary_damping",
    "mass": "mass",
    "price": "money",
    "source": None,
    "notes": None,
}
"""The motor fields a column can fill, in the order they are written, and their kinds
(None: text). Speed-torque curves are not imported (one row, one motor)."""

REQUIRED_FIELDS = ("id", "inertia", "continuous_torque", "peak_torque", "rated_speed")


@dataclass(frozen=True)
class ColumnMap:
    """``column=field[:unit]``: a CSV column fills a motor field, its numbers in ``unit``."""

    column: str
    field: str
    unit: str | None = None

    @property
    def text(self) -> str:
        return f"{self.column}={self.field}" + (f":{self.unit}" if self.unit else "")


class CatalogImportError(UserError):
    """Rows that do not make valid motors: ``problems`` holds each, located."""

    def __init__(self, problems: Sequence[UserError]) -> None:
        first = problems[0]
        more = len(problems) - 1
        message = first.message + (f" (and {more} more problem{'s' * (more > 1)})"
                                   if more else "")
        super().__init__(message, file=first.file, line=first.line, field=first.field)
        self.problems = list(problems)


def parse_column_map(text: str) -> ColumnMap:
    """Parse ``column=field[:unit]`` (the column is all before the last '=')."""
    column, equals, target = text.rpartition("=")
    if not equals or not column.strip():
        raise UserError(f"expected COLUMN=FIELD[:UNIT], got {text!r}", field="--map")
    name, _, unit = target.partition(":")
    name, unit = name.strip(), unit.strip()
    if name not in FIELD_KINDS:
        raise UserError(f"unknown field {name!r} in {text!r}; fields: "
                        f"{', '.join(FIELD_KINDS)}", field="--map")
    kind = FIELD_KINDS[name]
    if unit:
        if kind is None or kind == "money":
            raise UserError(f"{name} takes no unit, got {text!r}", field="--map")
        try:
            to_si(f"1 {unit}", kind)
        except UserError:
            raise UserError(f"{unit!r} is not a unit of {kind.replace('_', ' ')} (like "
                            f"{KINDS[kind].example!r}) in {text!r}", field="--map") from None
    return ColumnMap(column=column.strip(), field=name, unit=unit or None)


@dataclass(frozen=True)
class ImportedCatalog:
    """The catalog made from a CSV file: header fields and motors as texts with units."""

    name: str
    manufacturer: str | None
    source: str | None
    csv_name: str
    maps: tuple[ColumnMap, ...]
    motors: tuple[dict[str, str], ...] = field(default_factory=tuple)
    warnings: tuple[str, ...] = ()
    """Located warnings about rows that are valid but implausible (``file.csv:line: field
    (column ...): text``); the catalog is still written."""

    def yaml(self) -> str:
        """The catalog file's text: the same input gives the same text, byte for byte."""
        comments = [f"Motor catalog imported by 'sizer catalog import' from {self.csv_name}.",
                    "Each figure is the spreadsheet's, with the unit of its column:"]
        comments += [f"  {m.column!r} -> {m.field}" + (f" [{m.unit}]" if m.unit else "")
                     for m in self.maps]
        comments.append("Check it with 'sizer catalog validate'.")
        header = {"catalog": self.name, "manufacturer": self.manufacturer,
                  "source": self.source}
        return render_catalog(header, self.motors, comments)


def import_csv(path: str | Path, maps: Sequence[ColumnMap], *, catalog_name: str | None = None,
               manufacturer: str | None = None, source: str | None = None,
               delimiter: str | None = None, decimal_comma: bool = False,
               encoding: str = "utf-8") -> ImportedCatalog:
    """Read a CSV file into an ImportedCatalog; UserError for bad maps or an unreadable
    file, CatalogImportError (every problem) for rows that are not valid motors."""
    path = Path(path)
    maps = tuple(maps)
    _check_maps(maps, source)
    rows = _read_rows(path, encoding, delimiter)
    header, body = rows[0][1], rows[1:]
    index = _column_indices(path, header, maps)
    problems: list[UserError] = []
    warnings: list[str] = []
    motors: list[dict[str, str]] = []
    first_line: dict[str, int] = {}
    for line, cells in body:
        if not any(c.strip() for c in cells):
            continue
        motor, row_problems = _row(path, line, cells, maps, index, decimal_comma)
        problems += row_problems
        if row_problems:
            continue
        errors, row_warnings = _validate(path, line, motor, maps, manufacturer, source)
        problems += errors
        warnings += [str(w) for w in row_warnings]
        motor_id = motor.get("id", "").strip()
        if motor_id in first_line:
            problems.append(UserError(
                f"duplicate motor id {motor_id!r} (first on line {first_line[motor_id]})",
                file=str(path), line=line, field=_field_text("id", maps)))
        first_line.setdefault(motor_id, line)
        motors.append(motor)
    if problems:
        raise CatalogImportError(problems)
    if not motors:
        raise UserError("no motor rows under the header line", file=str(path), line=rows[0][0])
    return ImportedCatalog(name=catalog_name or path.stem, manufacturer=manufacturer,
                           source=source, csv_name=path.name, maps=maps, motors=tuple(motors),
                           warnings=tuple(warnings))


def _check_maps(maps: Sequence[ColumnMap], source: str | None) -> None:
    seen: dict[str, ColumnMap] = {}
    for item in maps:
        if item.field in seen:
            raise UserError(f"field {item.field!r} is mapped twice: {seen[item.field].text!r} "
                            f"and {item.text!r}", field="--map")
        seen[item.field] = item
    missing = [f for f in REQUIRED_FIELDS if f not in seen]
    if missing:
        raise UserError(f"no column maps to the required field(s) {', '.join(missing)}: add "
                        f"--map 'COLUMN={missing[0]}[:UNIT]'", field="--map")
    if "source" not in seen and not (source or "").strip():
        raise UserError("no source: give --source 'datasheet title, https://...' or map a "
                        "column to source", field="--source")


def _read_rows(path: Path, encoding: str, delimiter: str | None) -> list[tuple[int, list[str]]]:
    """(line, cells) of every record, header first; line = where the record starts."""
    try:
        "".encode(encoding)
    except LookupError:
        raise UserError(f"unknown encoding {encoding!r}", field="--encoding") from None
    raw = read_user_bytes(path, limit=MAX_CATALOG_BYTES, what="CSV")
    try:
        text = decode_text(raw, str(path), encoding=encoding)
    except UserError as error:
        raise UserError(f"{error.message} (save the spreadsheet as UTF-8 CSV, or give "
                        f"--encoding, e.g. cp1252)", file=error.file, line=error.line) from None
    if not text.strip():
        raise UserError("the file is empty", file=str(path))
    delimiter = csv_delimiter(text, delimiter)
    rows: list[tuple[int, list[str]]] = []
    for start, cells in csv_records(text, str(path), delimiter):
        if cells or rows:  # blank lines before the header are skipped
            rows.append((start, cells))
    while rows and not any(c.strip() for c in rows[0][1]):
        rows.pop(0)
    if not rows:
        raise UserError("the file is empty", file=str(path))
    return rows


def _column_indices(path: Path, header: list[str], maps: Sequence[ColumnMap]) -> dict[str, int]:
    names = [h.strip() for h in header]
    index = {}
    for item in maps:
        if item.column in header:
            index[item.column] = header.index(item.column)
        elif item.column.strip() in names:
            index[item.column] = names.index(item.column.strip())
        else:
            shown = ", ".join(repr(n) for n in names)
            raise UserError(f"no column {item.column!r} in the header line; columns: {shown}",
                            file=str(path), line=1, field="--map")
    return index


def _field_text(name: str, maps: Sequence[ColumnMap]) -> str:
    for item in maps:
        if item.field == name:
            return f"{name} (column {item.column!r})"
    return name


def _row(path: Path, line: int, cells: list[str], maps: Sequence[ColumnMap],
         index: dict[str, int], decimal_comma: bool
         ) -> tuple[dict[str, str], list[UserError]]:
    """The motor fields of one row, in FIELD_KINDS order, and the cells that are not numbers."""
    values: dict[str, str] = {}
    problems = []
    for item in maps:
        position = index[item.column]
        cell = cells[position].strip() if position < len(cells) else ""
        if not cell:
            continue
        kind = FIELD_KINDS[item.field]
        if kind is not None and decimal_comma:
            cell = decimal_point(cell)
        if item.unit is not None:
            if not NUMBER.match(cell):
                hint = (" (a decimal comma? give --decimal-comma)"
                        if not decimal_comma and NUMBER.match(decimal_point(cell)) else "")
                problems.append(UserError(
                    f"expected a number (the unit {item.unit} comes from --map), got "
                    f"{cell!r}{hint}", file=str(path), line=line,
                    field=_field_text(item.field, maps)))
                continue
            cell = f"{cell} {item.unit}"
        values[item.field] = cell
    ordered = {name: values[name] for name in FIELD_KINDS if name in values}
    return ordered, problems


def _validate(path: Path, line: int, motor: dict[str, str], maps: Sequence[ColumnMap],
              manufacturer: str | None, source: str | None
              ) -> tuple[list[UserError], list[UserError]]:
    """Schema and sanity problems of one row's motor, at the row's line: the errors, and
    the warnings (implausible figures) that do not stop the import."""
    where = YamlSource(data=motor, file=str(path), lines={(): line})
    for name in motor:
        where.lines[(name,)] = line
    try:
        item = MotorInput.model_validate(motor)
    except ValidationError as error:
        return [_renamed(p, maps) for p in all_problems(error, MotorInput, where)], []
    found: dict[str, list[UserError]] = {"error": [], "warning": []}
    for p in check_motor(motor_of(item), manufacturer=manufacturer, source=source, given=motor):
        found[p.severity].append(UserError(p.message, file=str(path), line=line,
                                           field=_field_text(str(p.path[0]), maps)))
    return found["error"], found["warning"]


def _renamed(problem: UserError, maps: Sequence[ColumnMap]) -> UserError:
    name: Any = problem.field or ""
    head = str(name).split(".")[0].split("[")[0]
    field_text = _field_text(head, maps) if head in FIELD_KINDS else problem.field
    return UserError(problem.message, file=problem.file, line=problem.line, field=field_text)
