"""Building blocks of the input models: quantities with units, text, strict models.

Quantities whose kind is fixed are converted to SI floats with :func:`sizer.units.to_si`
("3000 rpm" -> 314.159...); validators raise ValueError with a one-line message that the
loader turns into a UserError at the file, line and field.
"""

from __future__ import annotations

import math
import reprlib
import types
import typing
from dataclasses import dataclass
from typing import Annotated, Any, Literal

from pydantic import (
    BaseModel,
    BeforeValidator,
    ConfigDict,
    GetCoreSchemaHandler,
    GetJsonSchemaHandler,
)
from pydantic.json_schema import JsonSchemaValue
from pydantic_core import core_schema

from sizer.errors import UserError
from sizer.input_limits import MAX_QUANTITY_CHARS
from sizer.io.schema.ranges import RANGES, Range, check_range, number_text
from sizer.units import KINDS, quantity_pattern, to_si

# ---------------------------------------------------------------- quantities


_REPR = reprlib.Repr()
_REPR.maxlevel, _REPR.maxdict, _REPR.maxlist, _REPR.maxtuple = 2, 3, 3, 3
_REPR.maxstring, _REPR.maxother, _REPR.maxlong = 50, 50, 40


def show_value(value: Any) -> str:
    """A short repr of a user's value for messages; bounded even for huge or shared data."""
    text = _REPR.repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


_show = show_value


def _a(name: str) -> str:
    return f"an {name}" if name[0] in "aeiou" else f"a {name}"


def convert(value: Any, kind: str) -> float:
    """``to_si`` of a number or a text, with ValueErrors for what is not one (a bool, a
    list, a long text, an integer too large for a float); -0.0 becomes 0.0."""
    if isinstance(value, bool) or not isinstance(value, str | int | float):
        spec = KINDS[kind]
        raise ValueError(f"expected {_a(kind.replace('_', ' '))} like {spec.example!r}, "
                         f"got {_show(value)}")
    if isinstance(value, str) and len(value) > 100:
        raise ValueError(f"expected {_a(kind.replace('_', ' '))} like "
                         f"{KINDS[kind].example!r}, got a text of {len(value)} characters")
    try:
        result = to_si(value, kind)
    except UserError as error:
        raise ValueError(error.message) from None
    except OverflowError:
        raise TooLargeError(f"{_show(value)} is too large for a number") from None
    return result + 0.0


class TooLargeError(ValueError):
    """A number beyond the floats (an integer of 400 digits)."""


def given_text(value: Any, shown: str) -> str:
    """' (3000 rpm)' when the user wrote the value otherwise than ``shown``."""
    if isinstance(value, int | float) or value.strip() == shown:
        return ""
    try:
        float(value)
        return ""  # a bare number in a text ('1e308'): shown already, in SI
    except ValueError:
        pass
    return f" ({value.strip()})"


def convert_in(value: Any, name: str) -> float:
    """``to_si`` of a quantity and the check of its range ``RANGES[name]``; ValueError with
    the allowed range in SI units and the value given otherwise."""
    allowed = RANGES[name]
    try:
        result = convert(value, allowed.kind)
    except TooLargeError as error:
        raise ValueError(f"{error}; must be {allowed.text()}") from None
    try:
        check_range(name, result)
    except ValueError as error:
        unit = f" {allowed.unit}" if allowed.unit else ""
        raise ValueError(f"{error}{given_text(value, number_text(result) + unit)}") from None
    return result


_UNIT_NOTES = {
    **dict.fromkeys(("angular_speed", "angular_acceleration", "angular_jerk"),
                    "; a unit without an angle (Hz, 1/min, min^-1, 1/s^2) counts revolutions"),
    "torque": "; Nm, mNm, Ncm and oz*in, lbf*ft are accepted",
    "inertia": "; lb*in^2, oz*in*s^2 and a GD^2 like '0.04 kgf*m^2 GD^2' are accepted",
}
"""What the JSON Schema says about the datasheet spellings of a kind (sizer.units)."""


def quantity_text(*words: str, slash: bool = False) -> dict[str, Any]:
    """The JSON Schema of a quantity written as text ('0.5 s', '0.5s', '3000rpm'): the
    form :func:`sizer.units.to_si` reads (:func:`sizer.units.quantity_pattern`), or one of
    ``words`` ('free', 'minimize': any case, spaces around)."""
    text = {"type": "string", "pattern": quantity_pattern(slash=slash),
            "maxLength": MAX_QUANTITY_CHARS}
    if not words:
        return text
    spelled = "|".join("".join(f"[{c.lower()}{c.upper()}]" for c in w) for w in words)
    return {"anyOf": [text, {"type": "string",
                             "pattern": f"^[ \\t\\n\\r\\f\\v]*(?:{spelled})[ \\t\\n\\r\\f\\v]*$"}]}


def _quantity_schema(kind: str, note: str = "") -> dict[str, Any]:
    spec = KINDS[kind]
    name = kind.replace("_", " ")
    text = f"{name} like '{spec.example}'"
    if spec.si_unit != "1":
        text += f"; a bare number is in {spec.si_unit}"
    text += _UNIT_NOTES.get(kind, "")
    return {"anyOf": [{"type": "number"}, quantity_text()],
            "description": f"{text}{'; ' + note if note else ''}"}


@dataclass(frozen=True)
class RangeRef:
    """Marks a field's annotation with the name of its range (for the docs and tests)."""

    name: str


def range_schema(allowed: Range, note: str = "", *, slash: bool = False) -> dict[str, Any]:
    """The JSON Schema of a ranged quantity: a number within the range's span (SI), or a
    text with a unit (``slash``: also '50 /min'); the exact rule in the description."""
    low, high = allowed.span
    text = _quantity_schema(allowed.kind)["description"]
    extra = f"; must be {allowed.text()} (SI)" + (f"; {note}" if note else "")
    return {"anyOf": [{"type": "number", "minimum": low, "maximum": high},
                      quantity_text(slash=slash)], "description": text + extra}


@dataclass(frozen=True)
class Ranged(RangeRef):
    """A float within ``RANGES[name]``, written ``Annotated[float, Ranged(name)]``: a
    number (SI) or a text with a unit; ``note`` is added to its JSON Schema."""

    note: str = ""

    def __get_pydantic_core_schema__(self, source: Any,
                                     handler: GetCoreSchemaHandler) -> core_schema.CoreSchema:
        return core_schema.no_info_before_validator_function(
            lambda v: convert_in(v, self.name), handler(source))

    def __get_pydantic_json_schema__(self, schema: core_schema.CoreSchema,
                                     handler: GetJsonSchemaHandler) -> JsonSchemaValue:
        return range_schema(RANGES[self.name], self.note)


RawValue = str | float | int
"""A quantity as written: its kind (torque or force...) is known once the axis is."""


@dataclass(frozen=True)
class RawQuantity:
    """A quantity kept as given, written ``Annotated[RawValue, RawQuantity(...)]``.

    ``examples`` shows the accepted forms in messages, e.g. "'0.2 N*m' or '10 N'".
    ``rotary`` and ``linear`` name its range (``RANGES``) on each axis; a field of one
    axis only names one. The loader converts and checks it (:func:`axis_range`).
    """

    examples: str
    rotary: str | None = None
    linear: str | None = None

    def _check(self, value: Any) -> Any:
        if isinstance(value, bool) or not isinstance(value, str | int | float):
            raise ValueError(f"expected a number or a quantity like {self.examples}, "
                             f"got {_show(value)}")
        if isinstance(value, float) and not math.isfinite(value):
            raise ValueError(f"{value!r} is not a finite number")
        return value

    def __get_pydantic_core_schema__(self, source: Any,
                                     handler: GetCoreSchemaHandler) -> core_schema.CoreSchema:
        return core_schema.no_info_before_validator_function(self._check, handler(source))

    def __get_pydantic_json_schema__(self, schema: core_schema.CoreSchema,
                                     handler: GetJsonSchemaHandler) -> JsonSchemaValue:
        names = [n for n in (self.rotary, self.linear) if n is not None]
        if not names:
            return {"anyOf": [{"type": "number"}, quantity_text()]}
        low = min(RANGES[n].span[0] for n in names)
        high = max(RANGES[n].span[1] for n in names)
        axes = [f"{axis}: {RANGES[n].text()}" for axis, n in (("rotary", self.rotary),
                                                               ("linear", self.linear))
                if n is not None]
        return {"anyOf": [{"type": "number", "minimum": low, "maximum": high},
                          quantity_text()],
                "description": f"must be ({'; '.join(axes)}) (SI)"}


def markers(annotation: Any) -> list[Any]:
    """The metadata of the Annotated types in ``annotation`` (through unions, not lists)."""
    found: list[Any] = []
    origin = typing.get_origin(annotation)
    if origin is Annotated:
        found += list(annotation.__metadata__)
        found += markers(typing.get_args(annotation)[0])
    elif origin is typing.Union or origin is types.UnionType:
        for arg in typing.get_args(annotation):
            found += markers(arg)
    return found


def field_markers(model: type[BaseModel], field: str) -> list[Any]:
    """The markers of one field of ``model`` (its annotation's and the FieldInfo's)."""
    info = model.model_fields[field]
    return [*info.metadata, *markers(info.annotation)]


def axis_range(model: type[BaseModel], field: str, linear: bool) -> str:
    """The range name of ``model``'s axis-dependent ``field`` on the given axis."""
    for marker in field_markers(model, field):
        if isinstance(marker, RawQuantity):
            name = marker.linear if linear else marker.rotary
            if name:
                return name
    raise KeyError(f"{model.__name__}.{field} has no range on this axis")


def _text(value: Any) -> Any:
    """Numbers are accepted as text (part numbers, ids like 100)."""
    if isinstance(value, int | float) and not isinstance(value, bool):
        return str(value)
    if value is None or not isinstance(value, str):
        raise ValueError(f"expected text, got {_show(value)}")
    return value


Text = Annotated[str, BeforeValidator(_text)]


def _identifier(value: Any) -> str:
    text = _text(value).strip()
    if not text:
        raise ValueError("must not be empty")
    return text


Identifier = Annotated[str, BeforeValidator(_identifier)]


def at_most(limit: int, whole: str, items: str, name: str) -> Any:
    """A before-validator refusing a list of more than ``limit`` items before any item is
    read (``name``: the limit in sizer.input_limits)."""

    def check(value: Any) -> Any:
        if isinstance(value, list) and len(value) > limit:
            raise ValueError(f"a {whole} of {len(value)} {items}: the limit is {limit} "
                             f"(sizer.input_limits.{name})")
        return value

    return BeforeValidator(check)


def given(value: Any) -> Any:
    """A before-validator of an optional section: written out, it must not be null."""
    if value is None:
        raise ValueError("expected a mapping of fields (key: value), got None")
    return value


def not_null(*names: str, **extra: Any) -> Any:
    """A ``json_schema_extra`` that drops the null branch of the optional fields ``names``
    (omitted, not null: see :func:`given`) and adds ``extra`` to the model's schema."""

    def edit(schema: dict[str, Any]) -> None:
        for name in names:
            prop = schema["properties"][name]
            branches = [b for b in prop.pop("anyOf", ()) if b != {"type": "null"}]
            if len(branches) == 1:
                prop.update(branches[0])
            elif branches:
                prop["anyOf"] = branches
            prop.pop("default", None)
        schema.update(extra)

    return edit


class Strict(BaseModel):
    """Unknown fields are errors; models are immutable, built on first use (issue 34: start-up;
    so their modules keep annotations objects, not text pydantic evaluates one by one)."""

    model_config = ConfigDict(extra="forbid", populate_by_name=False, frozen=True, defer_build=True)


# ---------------------------------------------------------------- shorthands
#
# A shorthand is accepted by the validator and written into the JSON Schema by one object,
# so the schema (``sizer schema``) follows the models: it is derived from pydantic's own
# schema of the full form, never written by hand.

JsonType = Literal["string", "object"]

_PYTHON_TYPES: dict[str, type] = {"string": str, "object": dict}


def _array_branch(schema: dict[str, Any]) -> dict[str, Any] | None:
    """The ``{"type": "array", ...}`` part of a schema (itself or a branch of anyOf)."""
    if schema.get("type") == "array":
        return schema
    return next((b for b in schema.get("anyOf", ()) if b.get("type") == "array"), None)


@dataclass(frozen=True)
class OneOrList:
    """A list field that also takes one item of JSON type ``single`` alone (``laws:
    cycloidal``, a transmission of one stage as a mapping): the item becomes ``[item]``."""

    single: JsonType

    def __get_pydantic_core_schema__(self, source: Any,
                                     handler: GetCoreSchemaHandler) -> core_schema.CoreSchema:
        kind = _PYTHON_TYPES[self.single]
        return core_schema.no_info_before_validator_function(
            lambda v: [v] if isinstance(v, kind) else v, handler(source))

    def __get_pydantic_json_schema__(self, schema: core_schema.CoreSchema,
                                     handler: GetJsonSchemaHandler) -> JsonSchemaValue:
        json_schema = handler(schema)
        array = _array_branch(json_schema)
        if array is None:
            return json_schema
        item = array.get("items", {})
        one = item if item.get("type") == self.single else {
            "allOf": [item, {"type": self.single}]}
        if "anyOf" not in json_schema:
            return {"anyOf": [one, json_schema]}
        return {**json_schema, "anyOf": [one, *json_schema["anyOf"]]}


_MODEL_KEY = "sizer_or_array_model"


@dataclass(frozen=True)
class OrArray:
    """A mapping that may also be written as a list of its values in the order ``fields``
    (a curve point ``[speed, torque]`` for ``{speed: .., torque: ..}``)."""

    fields: tuple[str, ...]
    name: str = "value"

    def _as_mapping(self, value: Any) -> Any:
        if isinstance(value, list | tuple):
            if len(value) != len(self.fields):
                listed = ", ".join(self.fields)
                mapping = ", ".join(f"{f}: .." for f in self.fields)
                raise ValueError(f"{_a(self.name)} is [{listed}] or {{{mapping}}}, got "
                                 f"{show_value(value)}")
            return dict(zip(self.fields, value, strict=True))
        return value

    def __get_pydantic_core_schema__(self, source: Any,
                                     handler: GetCoreSchemaHandler) -> core_schema.CoreSchema:
        return core_schema.no_info_before_validator_function(
            self._as_mapping, handler(source), metadata={_MODEL_KEY: source})

    def __get_pydantic_json_schema__(self, schema: core_schema.CoreSchema,
                                     handler: GetJsonSchemaHandler) -> JsonSchemaValue:
        json_schema = handler(schema)
        model = (schema.get("metadata") or {}).get(_MODEL_KEY)
        properties = model.model_json_schema()["properties"] if model is not None else {}
        array = {"type": "array", "prefixItems": [properties.get(f, {}) for f in self.fields],
                 "minItems": len(self.fields), "maxItems": len(self.fields), "items": False,
                 "description": f"[{', '.join(self.fields)}]"}
        return {"anyOf": [array, json_schema]}
