"""Reading a cam table: a CSV file of samples (time or master angle, position).

The file is what ``sizer law ... --format csv`` prints, or any table like it::

    t [s],q [rad],v [rad/s],a [rad/s^2],j [rad/s^3]
    0.0,0.0,0.0,0.0,7751.57
    ...

A header row is optional; its cells are names with an optional unit in brackets
(``angle [deg]``, ``position [mm]``). Blank lines and lines starting with ``#`` are
skipped. The numbers are returned as written: the units are the caller's business
(:class:`CamTableData` carries their texts).
"""

from __future__ import annotations

import csv
import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from sizer.errors import UserError

if TYPE_CHECKING:
    from sizer.laws.multipoint.sample_fit import SampleFit

CAM_TABLE_FIELDS = ("file", "columns")
"""The YAML fields that locate the samples; the fitting fields are sample_fit.FIT_FIELDS."""

_HEADER_CELL = re.compile(r"^\s*(?P<name>[^\[\]]*?)\s*(?:\[(?P<unit>[^\[\]]*)\])?\s*$")


@dataclass(frozen=True, eq=False)
class CamTableData:
    """The two chosen columns of a cam table, as written.

    ``names`` and ``units`` come from the header (None without a header, or a unit None
    when the header cell has no brackets); ``lines`` is each row's line number in the
    file (1-based), for messages.
    """

    path: Path
    x: np.ndarray
    q: np.ndarray
    names: tuple[str | None, str | None]
    units: tuple[str | None, str | None]
    lines: np.ndarray
    columns: tuple[int, int]


def read_cam_table(path: Path, *, columns: Sequence[str | int] | None = None
                   ) -> CamTableData:
    """Read the samples of ``path``: columns ``columns`` = [x, q] chosen by header name
    (with or without its unit, e.g. ``t`` or ``t [s]``) or 0-based index; default the
    first two. UserError with the file, the line and the field on every mistake."""
    file = str(path)
    rows = _rows(path)
    if not rows:
        raise UserError("has no rows: a cam table needs at least 2 samples", file=file,
                        field="file")
    header = None
    if not any(_is_number(cell) for cell in rows[0][1]):  # a data row with a typo has
        header = rows.pop(0)                                # numbers too: _cell reports it
        if not rows:
            raise UserError(f"{path.name} has a header but no rows", file=file,
                            line=header[0], field="file")
    chosen = _columns(columns, header, rows, file)
    x, q = [], []
    for line, cells in rows:
        if len(cells) <= max(chosen):
            raise UserError(f"row has {len(cells)} cells, column {max(chosen)} is needed",
                            file=file, line=line, field="file")
        x.append(_cell(cells, chosen[0], line, header, file))
        q.append(_cell(cells, chosen[1], line, header, file))
    if len(rows) < 2:
        raise UserError(f"has {len(rows)} row: a cam table needs at least 2 samples",
                        file=file, line=rows[0][0], field="file")
    names: list[str | None] = [None, None]
    units: list[str | None] = [None, None]
    if header is not None:
        for i, column in enumerate(chosen):
            names[i], units[i] = _name_unit(header[1][column])
    return CamTableData(path=path, x=np.array(x), q=np.array(q), names=tuple(names),
                        units=tuple(units), lines=np.array([r[0] for r in rows]),
                        columns=(chosen[0], chosen[1]))


def build_cam_table(fields: Mapping[str, Any], base_dir: Path) -> SampleFit:
    """A cam table's YAML mapping: ``file`` (CSV, relative to ``base_dir``), ``columns``
    ([x, q] by header name or 0-based index, default the first two) and the fitting
    fields ``order``, ``smoothing``, ``periodic`` (sample_fit.build_cam_table_samples)."""
    return load_cam_table(fields, base_dir)[1]


def load_cam_table(fields: Mapping[str, Any], base_dir: Path
                   ) -> tuple[CamTableData, SampleFit]:
    """The table a cam table's mapping names and its fit (see :func:`build_cam_table`)."""
    from sizer.laws.multipoint.fields import refuse_unknown
    from sizer.laws.multipoint.sample_fit import FIT_FIELDS, build_cam_table_samples

    refuse_unknown(fields, CAM_TABLE_FIELDS + FIT_FIELDS, "cam_table")
    raw = fields.get("file")
    if not isinstance(raw, str) or not raw.strip():
        raise UserError(f"must be the path of a CSV file, got {raw!r}", field="file")
    columns = fields.get("columns")
    if columns is not None and not (
            isinstance(columns, list | tuple) and len(columns) == 2
            and all(isinstance(c, str) or (isinstance(c, int) and not isinstance(c, bool))
                    for c in columns)):
        raise UserError(f"must be two column names or 0-based indices, e.g. [t, q] or "
                        f"[0, 1], got {columns!r}", field="columns")
    path = Path(raw)
    if not path.is_absolute():
        path = base_dir / path
    table = read_cam_table(path, columns=columns)
    _increasing(table)
    try:
        return table, build_cam_table_samples(fields, table.x, table.q)
    except UserError as exc:
        raise exc.located(file=str(path)) from None


def _rows(path: Path) -> list[tuple[int, list[str]]]:
    """(line number, cells) of the non-blank, non-comment rows."""
    file = str(path)
    try:
        text = path.read_text(encoding="utf-8-sig")
    except FileNotFoundError:
        raise UserError("cam table file not found", file=file, field="file") from None
    except IsADirectoryError:
        raise UserError("is a directory, not a CSV file", file=file, field="file") from None
    except UnicodeDecodeError:
        raise UserError("is not a CSV file (not UTF-8 text)", file=file,
                        field="file") from None
    except OSError as exc:
        raise UserError(f"cannot be read: {exc.strerror}", file=file, field="file") from None
    if "\x00" in text:
        raise UserError("is not a CSV file (binary content)", file=file, field="file")
    rows = []
    reader = csv.reader(text.splitlines())
    try:
        for cells in reader:
            line = reader.line_num
            if not cells or all(not c.strip() for c in cells) or cells[0].lstrip(
                    ).startswith("#"):
                continue
            rows.append((line, [c.strip() for c in cells]))
    except csv.Error as exc:
        raise UserError(f"is not a CSV file: {exc}", file=file, line=reader.line_num,
                        field="file") from None
    return rows


def _is_number(cell: str) -> bool:
    try:
        float(cell)
    except ValueError:
        return False
    return True


def _name_unit(cell: str) -> tuple[str, str | None]:
    match = _HEADER_CELL.match(cell)
    if match is None:
        return cell.strip(), None
    unit = match.group("unit")
    return match.group("name"), unit.strip() if unit is not None else None


def _columns(columns: Sequence[str | int] | None, header: tuple[int, list[str]] | None,
             rows: list[tuple[int, list[str]]], file: str) -> tuple[int, int]:
    width = len(header[1]) if header is not None else len(rows[0][1])
    if columns is None:
        if width < 2:
            raise UserError("has one column: a cam table needs two (x and q)", file=file,
                            line=(header or rows[0])[0], field="columns")
        return 0, 1
    chosen = []
    for i, column in enumerate(columns):
        if isinstance(column, int):
            if not 0 <= column < width:
                raise UserError(f"column index {column} is out of range: the table has "
                                f"{width} columns (0 to {width - 1})", file=file,
                                field=f"columns[{i}]")
            chosen.append(column)
            continue
        if header is None:
            raise UserError(f"the table has no header: choose column {column!r} by its "
                            f"0-based index", file=file, field=f"columns[{i}]")
        cells = header[1]
        found = [j for j, cell in enumerate(cells)
                 if cell == column.strip() or _name_unit(cell)[0] == column.strip()]
        if not found:
            raise UserError(f"no column {column!r}; the header has: {', '.join(cells)}",
                            file=file, line=header[0], field=f"columns[{i}]")
        chosen.append(found[0])
    if chosen[0] == chosen[1]:
        raise UserError("x and q must be two different columns", file=file,
                        field="columns")
    return chosen[0], chosen[1]


def _cell(cells: list[str], column: int, line: int, header: tuple[int, list[str]] | None,
          file: str) -> float:
    text = cells[column]
    name = header[1][column] if header is not None and column < len(header[1]) else None
    where = f"column {column}" + (f" ({name})" if name else "")
    try:
        value = float(text)
    except ValueError:
        raise UserError(f"{where}: {text!r} is not a number", file=file, line=line,
                        field="file") from None
    if not math.isfinite(value):
        raise UserError(f"{where}: {text!r} is not a finite number", file=file, line=line,
                        field="file")
    return value


def _increasing(table: CamTableData) -> None:
    """x must increase strictly: UserError at the line of the first row that does not."""
    bad = np.flatnonzero(np.diff(table.x) <= 0.0)
    if bad.size:
        i = int(bad[0]) + 1
        name = table.names[0] or f"column {table.columns[0]}"
        raise UserError(f"{name} must increase strictly: {table.x[i]:g} follows "
                        f"{table.x[i - 1]:g}", file=str(table.path),
                        line=int(table.lines[i]), field="file")
