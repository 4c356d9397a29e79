"""Every field of the input files, walked from the models, with the range it uses.

Paths are dotted, list items unmarked, a transmission stage named by its type:
``task.duration``, ``transmission[ball_screw].lead``; the fields of a motor catalog start
with ``catalog:`` (``catalog:motors.continuous_curve.speed``), those of a gearbox catalog
with ``gearboxes:``, those of a machine file with ``machine:``. An inline motor of a
design has the fields of a catalog motor.

    input_fields()   -> {"task.duration": InputField(...), ...}
    fields_by_range() -> {"duration": ["task.duration"], ...}
"""

from __future__ import annotations

import types
import typing
from dataclasses import dataclass
from typing import Annotated, Any

from pydantic import BaseModel

from sizer.io.schema.inputs import CatalogFile, DesignFile
from sizer.io.schema.inputs_base import RangeRef, RawQuantity, field_markers
from sizer.io.schema.machine_inputs import MachineFile
from sizer.io.schema.transmission_inputs import GearboxCatalogFile

FILES: dict[str, type[BaseModel]] = {"": DesignFile, "catalog:": CatalogFile,
                                     "gearboxes:": GearboxCatalogFile,
                                     "machine:": MachineFile}
"""The prefix of each file's field paths, and its model."""


@dataclass(frozen=True)
class InputField:
    """One field of an input file: its path and the ranges of its values (if a quantity)."""

    path: str
    ranges: tuple[str, ...] = ()
    quantity: bool = False
    """A number with a unit (or a ratio): it must name a range."""


def _members(tp: Any) -> list[Any]:
    origin = typing.get_origin(tp)
    if origin is Annotated:
        return _members(typing.get_args(tp)[0])
    if origin is typing.Union or origin is types.UnionType:
        return [m for arg in typing.get_args(tp) if arg is not type(None)
                for m in _members(arg)]
    if origin is list:
        return _members(typing.get_args(tp)[0])
    return [tp]


def _is_model(tp: Any) -> bool:
    return isinstance(tp, type) and issubclass(tp, BaseModel)


def _tag(model: type[BaseModel]) -> str | None:
    info = model.model_fields.get("type")
    if info is not None and typing.get_origin(info.annotation) is typing.Literal:
        return str(typing.get_args(info.annotation)[0])
    return None


def _walk(model: type[BaseModel], prefix: str, out: dict[str, InputField]) -> None:
    for name, info in model.model_fields.items():
        key = info.alias or name
        path = f"{prefix}{key}"
        found = field_markers(model, name)
        names = [m.name for m in found if isinstance(m, RangeRef)]
        for marker in found:
            if isinstance(marker, RawQuantity):
                names += [n for n in (marker.rotary, marker.linear) if n]
        members = _members(info.annotation)
        models = [m for m in members if _is_model(m)]
        quantity = bool(names) or float in members
        if path in out:  # the same field on two stage types is one field per type
            continue
        out[path] = InputField(path, tuple(dict.fromkeys(names)), quantity)
        if not models or str in members:  # a motor reference: a name or an inline motor
            continue
        tagged = len(models) > 1 and all(_tag(m) is not None for m in models)
        for sub in models:
            inner = f"{path}[{_tag(sub)}]." if tagged else f"{path}."
            _walk(sub, inner, out)


def input_fields() -> dict[str, InputField]:
    """Every field of the design, motor catalog and gearbox catalog files, by path."""
    out: dict[str, InputField] = {}
    for prefix, model in FILES.items():
        _walk(model, prefix, out)
    return out


def fields_by_range() -> dict[str, list[str]]:
    """The fields that use each range, by range name."""
    out: dict[str, list[str]] = {}
    for item in input_fields().values():
        for name in item.ranges:
            out.setdefault(name, []).append(item.path)
    return out
