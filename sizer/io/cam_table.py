"""Reading a cam table: a CSV file of samples (time or master angle, position).

The file is what ``sizer law ... --format csv`` prints, or any table like it::

    t [s],q [rad],v [rad/s],a [rad/s^2],j [rad/s^3]
    0.0,0.0,0.0,0.0,7751.57
    ...

A header row is optional; its cells are names with an optional unit in brackets
(``angle [deg]``, ``position [mm]``). Blank lines and lines starting with ``#`` are
skipped. Cells are separated by ``,`` ``;`` a tab or ``|`` (sniffed, sizer.io.csv_rows);
with a separator other than ``,`` a decimal comma is read too (``0,5;1,25``). The file is
read by the bounded reader (a regular file of at most MAX_CAM_TABLE_BYTES), its rows
counted as they are read (at most MAX_CAM_TABLE_ROWS). The numbers
are returned as written: the units are the caller's business (:class:`CamTableData`
carries their texts).

Messages: a mistake in the file names the file, its line and the column; a mistake in the
mapping's fields (``file`` not found, ``columns``, ``order``...) names the field only, for
the design loader to put at its line (or the command line at its option).
"""

from __future__ import annotations

import itertools
import math
import re
from array import array
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from sizer.errors import UserError
from sizer.input_limits import MAX_CAM_TABLE_BYTES, MAX_CAM_TABLE_ROWS
from sizer.io.csv_rows import NUMBER, comma_is_decimal, csv_delimiter, csv_records
from sizer.io.files import decode_text, read_user_bytes

if TYPE_CHECKING:
    from sizer.laws.cam_interpolation import RestEnds
    from sizer.laws.multipoint.sample_fit import SampleFit

CAM_TABLE_FIELDS = ("file", "columns", "span")
"""The YAML fields that locate the samples (``span``: the rows of the law, read by
sizer.io.cam_table_law); the fitting fields are sample_fit.FIT_FIELDS."""

_NON_FINITE = ("nan", "inf", "infinity")
_SEPARATORS = {",": "','", ";": "';'", "\t": "tabs", "|": "'|'"}
_HEADER_CELL = re.compile(r"^\s*(?P<name>[^\[\]]*?)\s*(?:\[(?P<unit>[^\[\]]*)\])?\s*$")


@dataclass(frozen=True, eq=False)
class CamTableData:
    """The two chosen columns of a cam table, as written.

    ``names`` and ``units`` come from the header (None without a header, or a unit None
    when the header cell has no brackets); ``lines`` is each row's line number in the
    file (1-based) and ``header_line`` the header's, for messages.
    """

    path: Path
    x: np.ndarray
    q: np.ndarray
    names: tuple[str | None, str | None]
    units: tuple[str | None, str | None]
    lines: np.ndarray
    columns: tuple[int, int]
    header_line: int | None = None
    derivatives: tuple[np.ndarray, np.ndarray] | None = None
    """The velocity and acceleration columns of an XYVA table (``interpolation:
    quintic_hermite``), in the table's units (q's unit per x's unit, per its square)."""

    def column_name(self, i: int) -> str:
        """How messages name the x (``i`` = 0) or q (1) column: ``column 0 (t [s])``."""
        column = self.columns[i]
        name = self.names[i]
        unit = self.units[i]
        if name is None:
            return f"column {column}"
        return f"column {column} ({name}" + (f" [{unit}]" if unit is not None else "") + ")"


def read_cam_table(path: Path, *, columns: Sequence[str | int] | None = None,
                   derivatives: bool = False) -> CamTableData:
    """Read the samples of ``path``: columns ``columns`` = [x, q] chosen by header name
    (with or without its unit, e.g. ``t`` or ``t [s]``) or 0-based index; default the
    first two. A mistake in the file is a UserError at its file, line and column; a
    ``columns`` that does not fit the file names the field ``columns[i]`` (the caller
    locates it where ``columns`` is written). With ``derivatives`` the table has four
    columns [x, q, v, a] (default the first four), v and a read into ``derivatives``."""
    file = str(path)
    text = _text(path)
    delimiter = csv_delimiter(text, comment="#")
    decimal_comma = comma_is_decimal(delimiter)
    records = ((line, [c.strip() for c in cells])
               for line, cells in csv_records(text, file, delimiter, comment="#")
               if any(c.strip() for c in cells))
    first = next(records, None)
    if first is None:
        raise UserError("has no rows: a cam table needs at least 2 samples", file=file)
    header = None
    if not any(_number(cell, decimal_comma) is not None for cell in first[1]):
        header, first = first, next(records, None)  # a data row with a typo has numbers
        if first is None:                            # too: _cell reports it
            raise UserError(f"{path.name} has a header but no rows", file=file,
                            line=header[0])
    chosen = _columns(columns, header, first, path, 4 if derivatives else 2)
    values = [array("d") for _ in chosen]
    x, q, lines = values[0], values[1], array("q")
    for line, cells in itertools.chain((first,), records):
        if len(cells) <= max(chosen):
            raise UserError(f"the row has {len(cells)} cells, column {max(chosen)} is needed "
                            f"(cells separated by {_SEPARATORS.get(delimiter, delimiter)})",
                            file=file, line=line, field=_column_name(max(chosen), header))
        if len(x) == MAX_CAM_TABLE_ROWS:
            raise UserError(f"more than {MAX_CAM_TABLE_ROWS:,} rows: the limit is "
                            f"{MAX_CAM_TABLE_ROWS:,} (MAX_CAM_TABLE_ROWS); resample the "
                            f"table more coarsely", file=file, line=line)
        for column, read in zip(chosen, values, strict=True):
            read.append(_cell(cells, column, line, header, file, decimal_comma))
        lines.append(line)
    if len(x) < 2:
        raise UserError(f"has {len(x)} row: a cam table needs at least 2 samples",
                        file=file, line=lines[0])
    names: list[str | None] = [None, None]
    units: list[str | None] = [None, None]
    if header is not None:
        for i, column in enumerate(chosen[:2]):
            names[i], units[i] = _name_unit(header[1][column])
    return CamTableData(path=path, x=np.array(x, dtype=float),
                        q=np.array(q, dtype=float), names=(names[0], names[1]),
                        units=(units[0], units[1]), lines=np.array(lines, dtype=np.int64),
                        columns=(chosen[0], chosen[1]), header_line=(
                            header[0] if header is not None else None),
                        derivatives=(np.array(values[2], dtype=float),
                                     np.array(values[3], dtype=float)) if derivatives
                        else None)


def build_cam_table(fields: Mapping[str, Any], base_dir: Path) -> SampleFit:
    """A cam table's YAML mapping: ``file`` (CSV, relative to ``base_dir``), ``columns``
    ([x, q] by header name or 0-based index, default the first two) and the fitting
    fields ``order``, ``smoothing``, ``periodic`` (sample_fit.build_cam_table_samples)."""
    return load_cam_table(fields, base_dir)[1]


def load_cam_table(fields: Mapping[str, Any], base_dir: Path
                   ) -> tuple[CamTableData, SampleFit, RestEnds | None]:
    """The table a cam table's mapping names, its fit (see :func:`build_cam_table`) and
    which of its ends are at rest (sizer.laws.cam_interpolation)."""
    from sizer.laws.cam_interpolation import INTERPOLATION_FIELDS, cam_table_fit
    from sizer.laws.multipoint.fields import refuse_unknown
    from sizer.laws.multipoint.sample_fit import FIT_FIELDS

    refuse_unknown(fields, CAM_TABLE_FIELDS + FIT_FIELDS + INTERPOLATION_FIELDS,
                   "cam_table")
    raw = fields.get("file")
    if not isinstance(raw, str) or not raw.strip():
        raise UserError(f"must be the path of a CSV file, got {raw!r}", field="file")
    columns = fields.get("columns")
    hermite = fields.get("interpolation") == "quintic_hermite"
    count = 4 if hermite else 2
    if columns is not None and not (
            isinstance(columns, list | tuple) and len(columns) == count
            and all(isinstance(c, str) or (isinstance(c, int) and not isinstance(c, bool))
                    for c in columns)):
        raise UserError(f"must be two column names or 0-based indices, e.g. [t, q] or "
                        f"[0, 1], got {columns!r}" if not hermite else
                        f"must be four column names or 0-based indices (x, q, v, a) for "
                        f"interpolation quintic_hermite, e.g. [t, q, v, a], got "
                        f"{columns!r}", field="columns")
    path = Path(raw)
    if not path.is_absolute():
        path = base_dir / path
    table = read_cam_table(path, columns=columns, derivatives=hermite)
    _increasing(table)
    # the fitting fields (order, smoothing, periodic, interpolation) are the mapping's: their
    # errors stay unlocated, for the design loader (its line) or the command line (its
    # option)
    v, a = table.derivatives if table.derivatives is not None else (None, None)
    fit, rest = cam_table_fit(fields, table.x, table.q, v, a)
    return table, fit, rest


def _text(path: Path) -> str:
    """The text of a cam table file: regular, at most MAX_CAM_TABLE_BYTES, UTF-8."""
    file = str(path)
    try:
        missing = not path.exists()
        folder = path.is_dir()
    except (OSError, ValueError):
        missing = folder = False  # a name too long...: read_user_bytes says what
    if missing or folder:  # the mapping's field is wrong, not a file: located there
        raise UserError(f"cam table file {'not found' if missing else 'is a folder'}: "
                        f"{file}", field="file")
    raw = read_user_bytes(path, limit=MAX_CAM_TABLE_BYTES, what="CSV")
    try:
        return decode_text(raw, file)
    except UserError as error:
        raise UserError(f"is not a CSV file ({error.message})", file=file,
                        line=error.line) from None


def _number(cell: str, decimal_comma: bool) -> float | None:
    """The number a cell writes (``0,5`` too where the comma is decimal), else None."""
    if decimal_comma and "," in cell and "." not in cell and cell.count(",") == 1:
        cell = cell.replace(",", ".")
    if not NUMBER.match(cell):
        return None
    return float(cell)


def _name_unit(cell: str) -> tuple[str, str | None]:
    match = _HEADER_CELL.match(cell)
    if match is None:
        return cell.strip(), None
    unit = match.group("unit")
    return match.group("name"), unit.strip() if unit is not None else None


def _column_name(column: int, header: tuple[int, list[str]] | None) -> str:
    name = header[1][column] if header is not None and column < len(header[1]) else None
    return f"column {column}" + (f" ({name})" if name else "")


def _columns(columns: Sequence[str | int] | None, header: tuple[int, list[str]] | None,
             first: tuple[int, list[str]], path: Path, count: int = 2) -> list[int]:
    """The 0-based [x, q] (or [x, q, v, a], ``count`` 4) columns: the first ``count``, or
    those ``columns`` names."""
    width = len(header[1]) if header is not None else len(first[1])
    if columns is None:
        if width < 2:
            raise UserError("has one column: a cam table needs two (x and q), separated by "
                            "',', ';', a tab or '|'", file=str(path),
                            line=(header or first)[0])
        if width < count:
            raise UserError(f"has {width} columns: a quintic_hermite table needs four (x, "
                            f"q, v and a)", file=str(path), line=(header or first)[0])
        return list(range(count))
    chosen = []
    for i, column in enumerate(columns):
        if isinstance(column, int):
            if not 0 <= column < width:
                raise UserError(f"column index {column} is out of range: {path.name} has "
                                f"{width} columns (0 to {width - 1})", field=f"columns[{i}]")
            chosen.append(column)
            continue
        if header is None:
            raise UserError(f"{path.name} has no header: choose column {column!r} by its "
                            f"0-based index", field=f"columns[{i}]")
        cells = header[1]
        found = [j for j, cell in enumerate(cells)
                 if cell == column.strip() or _name_unit(cell)[0] == column.strip()]
        if not found:
            raise UserError(f"no column {column!r} in {path.name}; its header (line "
                            f"{header[0]}) has: {', '.join(cells)}", field=f"columns[{i}]")
        chosen.append(found[0])
    if len(set(chosen)) < len(chosen):
        raise UserError("x and q must be two different columns" if count == 2 else
                        "x, q, v and a must be four different columns", field="columns")
    return chosen


def _cell(cells: list[str], column: int, line: int, header: tuple[int, list[str]] | None,
          file: str, decimal_comma: bool) -> float:
    text = cells[column]
    value = _number(text, decimal_comma)
    if value is None and text.strip().lstrip("+-").lower() not in _NON_FINITE:
        raise UserError(f"{text!r} is not a number", file=file, line=line,
                        field=_column_name(column, header))
    if value is None or not math.isfinite(value):
        raise UserError(f"{text!r} is not a finite number", file=file, line=line,
                        field=_column_name(column, header))
    return value


def _increasing(table: CamTableData) -> None:
    """x must increase strictly: UserError at the line of the first row that does not."""
    bad = np.flatnonzero(np.diff(table.x) <= 0.0)
    if bad.size:
        i = int(bad[0]) + 1
        name = table.names[0] or f"column {table.columns[0]}"
        raise UserError(f"{name} must increase strictly: {table.x[i]:g} follows "
                        f"{table.x[i - 1]:g}", file=str(table.path),
                        line=int(table.lines[i]), field=table.column_name(0))
