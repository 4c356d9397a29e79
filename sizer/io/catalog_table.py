"""A catalog's motors read as columns: checked and converted one column at a time.

A catalog in the common form (known fields, every required one given, text where text
goes, quantities that convert and lie in their ranges, curve points as ``[speed,
torque]`` or ``{speed: .., torque: ..}``) is read without a pydantic model per motor:
each quantity column is converted by :func:`sizer.units.column_to_si` (one unit
conversion per distinct unit of the column, bit for bit :func:`sizer.units.to_si`) and
checked against its range (:mod:`sizer.io.schema.ranges`) as an array, and the domain motors
are built from the columns. They are the motors the validation of
:class:`sizer.io.schema.inputs.CatalogFile` gives (tests/test_catalog_load_columns.py).

Anything else gives None: the loader then validates the file field by field, which words
its first problem with the file, the line and the field, exactly as before. So a value
refused here is never worded here.
"""

from __future__ import annotations

import types
import typing
from dataclasses import dataclass
from functools import cache
from typing import Any

import numpy as np
from pydantic import BaseModel, ValidationError

from sizer.io.motor_rules import (
    CurveColumns,
    Figures,
    MotorColumns,
    bus_voltage,
    is_idealized,
    line_to_line,
)
from sizer.io.schema.inputs import CatalogFile, CurvePointInput, MotorInput
from sizer.io.schema.inputs_base import RangeRef, field_markers
from sizer.io.schema.provenance import (
    catalog_source_text,
    common_sources,
    figure_names,
    file_sources,
    row_sources,
    sources_adapter,
)
from sizer.io.schema.ranges import RANGES
from sizer.model.domain import FigureSources, Motor
from sizer.units import column_to_si

CURVES = ("continuous_curve", "intermittent_curve")
TORQUE_CURRENT = "torque_current_curve"
FIGURE_SOURCES = "figure_sources"
"""A row naming its figures' sources: read here where every name is well formed (plain
keys of given figures and of the file's sources), else field by field (which words it)."""
PROVENANCE = ("sources", "default_source")
_CURRENT_KEYS = frozenset({"current", "torque"})
_POINT_KEYS = frozenset({"speed", "torque"})
_ONE_OF = (("winding_resistance", "phase_resistance"),
           ("winding_inductance", "phase_inductance"),
           ("dc_bus_voltage", "supply_voltage"))
"""Fields of which a motor gives one (MotorInput's validator words the other case)."""
_COMMUTATIONS = ("sinusoidal", "block")


def _consistent(columns: dict[str, Any]) -> bool:
    """The checks of MotorInput's validator across fields, on the columns: poles even and
    whole, the peak current not below the continuous one."""
    poles = columns["poles"]
    given = ~np.isnan(poles)
    if np.any(given & ((poles != np.round(poles)) | (np.round(poles) % 2 != 0))):
        return False
    with np.errstate(invalid="ignore"):
        return not np.any(columns["peak_current"] < columns["continuous_current"])


@dataclass(frozen=True)
class _Fields:
    """The fields of a motor by what they hold (from :class:`MotorInput`)."""

    quantities: dict[str, str]
    """Field -> range name."""
    texts: tuple[str, ...]
    nullable: frozenset[str]
    required: frozenset[str]
    allowed: frozenset[str]
    defaults: dict[str, Any]
    point: tuple[str, str]
    """The range names of a curve point's speed and torque."""
    catalog_texts: tuple[str, ...]
    catalog_keys: frozenset[str]


def _range_of(model: type[BaseModel], name: str) -> str | None:
    return next((m.name for m in field_markers(model, name) if isinstance(m, RangeRef)), None)


def _nullable(annotation: Any) -> bool:
    origin = typing.get_origin(annotation)
    return (origin is typing.Union or origin is types.UnionType) and \
        type(None) in typing.get_args(annotation)


@cache
def _fields() -> _Fields:
    motor = MotorInput.model_fields
    assert all(info.alias is None for info in motor.values())
    quantities = {name: found for name in motor if (found := _range_of(MotorInput, name))}
    texts = tuple(name for name in motor if name not in quantities and name not in CURVES
                  and name not in (TORQUE_CURRENT, FIGURE_SOURCES))
    speed, torque = _range_of(CurvePointInput, "speed"), _range_of(CurvePointInput, "torque")
    assert speed is not None and torque is not None and texts[0] == "id"
    catalog = CatalogFile.model_fields
    return _Fields(
        quantities=quantities, texts=texts,
        nullable=frozenset(n for n, info in motor.items() if _nullable(info.annotation)),
        required=frozenset(n for n, info in motor.items() if info.is_required()),
        allowed=frozenset(motor),
        defaults={n: info.default for n, info in motor.items() if not info.is_required()},
        point=(speed, torque),
        catalog_texts=tuple(n for n in catalog if n not in ("motors", "drives", *PROVENANCE)),
        catalog_keys=frozenset(catalog))


class _NotCommonError(Exception):
    """The catalog needs the field-by-field validation."""


@dataclass(frozen=True)
class CatalogTable:
    """The motors of a catalog, its texts, and the columns the rules' screens read."""

    motors: list[Motor]
    columns: MotorColumns
    manufacturer: str | None
    source: str | None


def read_table(data: Any) -> CatalogTable | None:
    """The motors of a catalog's data (a mapping from YAML), or None if it is not in the
    common form (then :func:`sizer.io.validation.validate` words what is wrong)."""
    fields = _fields()
    if type(data) is not dict or not data.keys() <= fields.catalog_keys or "drives" in data:
        return None
    rows = data.get("motors")
    if type(rows) is not list or not rows:
        return None
    allowed, required = fields.allowed, fields.required
    for row in rows:
        if type(row) is not dict or not row.keys() <= allowed or not required <= row.keys():
            return None
        if any(one in row and other in row for one, other in _ONE_OF):
            return None
        if row.get("commutation", "sinusoidal") not in _COMMUTATIONS:
            return None
    try:
        provenance = common_sources(data)
    except ValueError:
        return None
    row_provenance = _row_provenance(data, rows, provenance)
    if row_provenance is None:
        return None
    try:
        catalog = {key: _texts([data.get(key)], nullable=True)[0] for key in fields.catalog_texts}
        columns: dict[str, Any] = {}  # texts as lists, quantities as SI arrays
        for key in fields.texts:
            columns[key] = _texts(_column(rows, key, fields), nullable=key in fields.nullable)
        ids = [text.strip() for text in columns["id"]]
        if not all(ids):
            return None
        for key, name in fields.quantities.items():
            columns[key] = _quantities(_column(rows, key, fields), name)
        curves = {key: _curve_column(rows, key, fields) for key in CURVES}
        currents = _curve_column(rows, TORQUE_CURRENT, fields,
                                 (_CURRENT_KEYS, ("current", "torque"),
                                  ("curve_current", "curve_torque")))
        if not _increasing(currents[0]) or not _consistent(columns):
            return None
    except _NotCommonError:
        return None
    return _table(rows, ids, columns, curves, catalog, _curves_of(currents), provenance,
                  row_provenance)


def _row_provenance(data: dict[str, Any], rows: list[dict[str, Any]],
                   common: FigureSources | None) -> list[FigureSources | None] | None:
    """Each row's FigureSources (as the field-by-field load gives them), or None where a
    row's ``figure_sources`` is not plainly well formed (the model then words it)."""
    if not any(FIGURE_SOURCES in row for row in rows):
        return [common] * len(rows)
    given = data.get("sources")
    if type(given) is not dict or not all(type(key) is str and key == key.strip()
                                          for key in given):
        return None
    try:
        sources = sources_adapter().validate_python(given)
    except ValidationError:
        return None
    shared, _ = file_sources(sources, None)
    figures = frozenset(figure_names(MotorInput))
    out: list[FigureSources | None] = []
    for row in rows:
        named = row.get(FIGURE_SOURCES)
        if named is None and FIGURE_SOURCES not in row:
            out.append(common)
            continue
        if type(named) is not dict or not all(
                type(figure) is str and figure in figures and figure in row
                and type(key) is str and key in shared for figure, key in named.items()):
            return None
        out.append(row_sources(named, shared, common))
    return out


def _column(rows: list[dict[str, Any]], key: str, fields: _Fields) -> list[Any]:
    """A field of every motor: its default where it is not given; an explicit null of a
    field that takes none is not common."""
    values = [row.get(key) for row in rows]
    if key in fields.nullable:
        return values
    default = fields.defaults.get(key)
    if default is not None and None in values:
        values = [default if v is None and key not in row else v
                  for v, row in zip(values, rows, strict=True)]
    if None in values:
        raise _NotCommonError
    return values


def _texts(values: list[Any], *, nullable: bool) -> list[Any]:
    """A text column as the model's ``Text`` gives it: texts as written, numbers as text."""
    kinds = set(map(type, values))
    if kinds <= {str} or (nullable and kinds <= {str, type(None)}):
        return values
    if not kinds <= {str, int, float, type(None)} or (not nullable and type(None) in kinds):
        raise _NotCommonError
    return [str(v) if type(v) is int or type(v) is float else v for v in values]


def _quantities(values: list[Any], name: str) -> np.ndarray:
    """A quantity column in SI (NaN where none is given), every value in its range."""
    present = [i for i, v in enumerate(values) if v is not None]
    given = values if len(present) == len(values) else [values[i] for i in present]
    allowed = RANGES[name]
    converted = column_to_si(given, allowed.kind)
    if None in converted:
        raise _NotCommonError
    numbers = np.array(converted, dtype=float)
    if not allowed.contains_all(numbers).all():
        raise _NotCommonError
    numbers += 0.0  # -0.0 is 0.0
    if len(present) == len(values):
        return numbers
    out = np.full(len(values), np.nan)
    out[present] = numbers
    return out


def _increasing(table: CurveColumns) -> bool:
    """Every torque-current curve has >= 2 points, currents and torques strictly rising."""
    for given, first, size in zip(table.given.tolist(), table.start.tolist(),
                                  table.count.tolist(), strict=True):
        if not given:
            continue
        x, y = table.speed[first:first + size], table.torque[first:first + size]
        if size < 2 or not (np.all(np.diff(x) > 0) and np.all(np.diff(y) > 0)):
            return False
    return True


def _curve_column(rows: list[dict[str, Any]], key: str, fields: _Fields,
                  kind: tuple[frozenset[str], tuple[str, str], tuple[str, str]] | None = None
                  ) -> tuple[CurveColumns, list[float], list[float]]:
    """One curve of every motor, flat, in SI (and the same points as float lists).

    ``kind``: the point's keys, their order and their ranges, if not (speed, torque) (the
    torque-current curve: its currents in the ``speed`` column)."""
    keys, (first_key, second_key), ranges = kind or (_POINT_KEYS, ("speed", "torque"),
                                                     fields.point)
    speeds: list[Any] = []
    torques: list[Any] = []
    count = len(rows)
    given, start, size = np.zeros(count, bool), np.zeros(count, np.intp), np.zeros(count, np.intp)
    for index, row in enumerate(rows):
        points = row.get(key)
        if points is None:
            continue
        if type(points) is not list:
            raise _NotCommonError
        given[index], start[index], size[index] = True, len(speeds), len(points)
        for point in points:
            point_type = type(point)
            if point_type is list and len(point) == 2:
                speeds.append(point[0])
                torques.append(point[1])
            elif point_type is dict and point.keys() == keys:
                speeds.append(point[first_key])
                torques.append(point[second_key])
            else:
                raise _NotCommonError
    speed_range, torque_range = ranges
    speed = _quantities(speeds, speed_range)
    torque = _quantities(torques, torque_range)
    if np.isnan(speed).any() or np.isnan(torque).any():
        raise _NotCommonError  # a null speed or torque
    return CurveColumns(given, start, size, speed, torque), speed.tolist(), torque.tolist()


def _curves_of(column: tuple[CurveColumns, list[float], list[float]]
               ) -> list[tuple[tuple[float, float], ...] | None]:
    table, speeds, torques = column
    out: list[tuple[tuple[float, float], ...] | None] = []
    for given, first, size in zip(table.given.tolist(), table.start.tolist(),
                                  table.count.tolist(), strict=True):
        out.append(tuple(zip(speeds[first:first + size], torques[first:first + size],
                             strict=True)) if given else None)
    return out


def _floats(column: np.ndarray) -> list[float | None]:
    """An SI column as Python floats, None where none is given."""
    return [None if x != x else x for x in column.tolist()]


def _whole(value: float | None) -> int | None:
    return None if value is None else int(value)


def _table(rows: list[dict[str, Any]], ids: list[str], columns: dict[str, Any],
           curves: dict[str, tuple[CurveColumns, list[float], list[float]]],
           catalog: dict[str, Any],
           currents: list[tuple[tuple[float, float], ...] | None],
           provenance: FigureSources | None,
           row_provenance: list[FigureSources | None]) -> CatalogTable:
    manufacturer = catalog.get("manufacturer")
    source = catalog_source_text(catalog.get("source"), provenance)
    makers = [m or manufacturer for m in columns["manufacturer"]]
    sources = [s or source for s in columns["source"]]
    fields = _fields()
    # a field that takes no null is given, or defaulted, for every motor (_column)
    given: dict[str, list[float]] = {key: columns[key].tolist() for key in fields.quantities
                                     if key not in fields.nullable}
    numbers = {key: _floats(columns[key]) for key in fields.quantities if key in fields.nullable}
    continuous, intermittent = (_curves_of(curves[key]) for key in CURVES)
    motors = [
        Motor(id=ids[i], inertia=given["inertia"][i],
              continuous_torque=given["continuous_torque"][i],
              peak_torque=given["peak_torque"][i], rated_speed=given["rated_speed"][i],
              max_speed=numbers["max_speed"][i], continuous_curve=continuous[i],
              intermittent_curve=intermittent[i], damping=given["damping"][i],
              source=sources[i], part_number=columns["part_number"][i],
              manufacturer=makers[i], price=numbers["price"][i], mass=numbers["mass"][i],
              torque_constant=numbers["torque_constant"][i],
              winding_resistance=line_to_line(numbers["winding_resistance"][i],
                                              numbers["phase_resistance"][i]),
              winding_inductance=line_to_line(numbers["winding_inductance"][i],
                                              numbers["phase_inductance"][i]),
              back_emf_constant=numbers["back_emf_constant"][i],
              poles=_whole(numbers["poles"][i]),
              continuous_current=numbers["continuous_current"][i],
              peak_current=numbers["peak_current"][i],
              dc_bus_voltage=bus_voltage(numbers["dc_bus_voltage"][i],
                                         numbers["supply_voltage"][i]),
              commutation=columns["commutation"][i],
              brake_holding_torque=numbers["brake_holding_torque"][i],
              brake_inertia=numbers["brake_inertia"][i] or 0.0,
              thermal_time_constant=numbers["thermal_time_constant"][i],
              max_winding_temperature_rise=numbers["max_winding_temperature_rise"][i],
              torque_current_curve=currents[i], radial_load=numbers["radial_load"][i],
              axial_load=numbers["axial_load"][i],
              radial_load_point=numbers["radial_load_point"][i],
              provenance=row_provenance[i])
        for i in range(len(rows))]
    idealized = {m: is_idealized(m) for m in set(makers)}
    figures = Figures(*(columns[key] for key in ("inertia", "continuous_torque", "peak_torque",
                                                 "rated_speed", "max_speed")))
    table = MotorColumns(figures, {key: curves[key][0] for key in CURVES},
                         np.array([idealized[m] for m in makers], dtype=bool))
    return CatalogTable(motors, table, manufacturer, source)

