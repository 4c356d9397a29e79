"""Pydantic validation of YAML data, with errors turned into one-line UserErrors.

A ValidationError never escapes: its first problem (in file order) becomes a UserError at
the file, line and field of the YAML source; the ``loc`` of pydantic is walked along the
data (tags of unions and other markers of pydantic are skipped) to the nearest known path.
"""

from __future__ import annotations

import difflib
import types
import typing
from typing import Any, TypeVar

from pydantic import BaseModel, ValidationError

from sizer.errors import UserError
from sizer.io.schema.inputs_base import show_value as _show
from sizer.io.yaml_source import YamlSource, format_path

ModelT = TypeVar("ModelT", bound=BaseModel)


def validate(model: type[ModelT], source: YamlSource) -> ModelT:
    """``model.model_validate(source.data)``, raising UserError located in ``source``."""
    try:
        return model.model_validate(source.data)
    except ValidationError as error:
        raise user_error(error, model, source) from None
    except RecursionError:
        raise source.error("the data is nested too deeply") from None


def user_error(error: ValidationError, model: type[BaseModel], source: YamlSource) -> UserError:
    """The first problem of ``error`` in file order, as a UserError; notes how many more."""
    problems, order = _ordered(error, model, source)
    first = problems[order[0]]
    more = len(problems) - 1
    if more:
        first = UserError(f"{first.message} (and {more} more problem{'s' * (more > 1)} "
                          f"in this file)", file=first.file, line=first.line, field=first.field)
    return first


def all_problems(error: ValidationError, model: type[BaseModel],
                 source: YamlSource) -> list[UserError]:
    """Every problem of ``error`` as a located UserError, in the order of ``user_error``."""
    problems, order = _ordered(error, model, source)
    return [problems[i] for i in order]


def _ordered(error: ValidationError, model: type[BaseModel],
             source: YamlSource) -> tuple[list[UserError], list[int]]:
    """The problems of ``error`` and their order: file order, a typo before what it hides."""
    items = [_placed(item) for item in error.errors(include_url=False)]
    problems = [_problem(item, model, source) for item in items]
    # An unknown field is often a typo of a missing one in the same mapping: report it
    # first, in place of the missing one. Otherwise, file order.
    extra_lines = {tuple(item["loc"][:-1]): problem.line
                   for item, problem in zip(items, problems, strict=True)
                   if item.get("type") == "extra_forbidden" and problem.line is not None}
    keys = []
    for item, problem in zip(items, problems, strict=True):
        line = problem.line if problem.line is not None else 10**9
        if item.get("type") == "missing":
            line = extra_lines.get(tuple(item["loc"][:-1]), line)
        keys.append((line, item.get("type") != "extra_forbidden"))
    order = sorted(range(len(problems)), key=lambda i: keys[i])
    return problems, order


def _placed(item: Any) -> Any:
    """The item with ``ctx["at"]`` appended to its loc: a model's own check (one of two
    sections, say) names the field it is about (PydanticCustomError(..., {"at": path}))."""
    at = (item.get("ctx") or {}).get("at")
    if not at:
        return item
    return {**item, "loc": (*item.get("loc", ()), *at)}


def _problem(item: Any, model: type[BaseModel], source: YamlSource) -> UserError:
    loc = tuple(item.get("loc", ()))
    kind = item.get("type", "")
    names = _field_names(model)
    path: list[Any] = []  # the part of loc found in the data (for the line)
    field: list[Any] = []  # the part of loc worth naming (for the message)
    current: Any = source.data
    for part in loc:
        in_dict = isinstance(current, dict) and _has_key(current, part)
        in_list = (isinstance(current, list) and isinstance(part, int)
                   and not isinstance(part, bool) and 0 <= part < len(current))
        if in_dict or in_list:
            current = current[part]
            path.append(part)
            field.append(part)
        elif isinstance(part, str) and part in names:
            field.append(part)  # a missing field: named, but no line of its own
    value = item.get("input")
    ctx = item.get("ctx") or {}
    if kind in ("union_tag_invalid", "union_tag_not_found"):
        discriminator = str(ctx.get("discriminator", "type")).strip("'\"")
        if isinstance(current, dict) and _has_key(current, discriminator):
            path.append(discriminator)
        field.append(discriminator)
    message = _message(kind, item, value, ctx, model, loc)
    return UserError(message, file=source.file, line=source.line_of(path),
                     field=format_path(field) or None)


def _has_key(mapping: dict[Any, Any], key: Any) -> bool:
    try:
        return key in mapping
    except TypeError:
        return False


def _message(kind: str, item: Any, value: Any, ctx: dict[str, Any],
             model: type[BaseModel], loc: tuple[Any, ...]) -> str:
    if kind == "missing":
        return "required field is missing"
    if kind == "extra_forbidden":
        allowed = _allowed_fields(model, loc[:-1])
        key = loc[-1] if loc else "?"
        text = f"unknown field {key!r}"
        if allowed:
            close = difflib.get_close_matches(str(key), allowed, n=1)
            if close:
                text += f" (did you mean {close[0]!r}?)"
            text += f"; allowed fields: {', '.join(allowed)}"
        return text
    if kind == "value_error":
        error = ctx.get("error")
        return str(error) if error is not None else _strip_prefix(item.get("msg", ""))
    if kind == "union_tag_invalid":
        expected = str(ctx.get("expected_tags", "")).replace("'", "")
        return f"unknown type {ctx.get('tag')!r}; expected one of: {expected}"
    if kind == "union_tag_not_found":
        tags = _tags_at(model, loc)
        extra = f" (one of: {', '.join(tags)})" if tags else ""
        if not isinstance(value, dict):
            return f"expected a mapping with a 'type'{extra}, got {_show(value)}"
        return f"required field is missing{extra}"
    if kind == "literal_error":
        return f"expected {ctx.get('expected')}, got {_show(value)}"
    if kind in ("model_type", "model_attributes_type", "dict_type"):
        if loc and loc[-1] == "inline-motor":
            return (f"expected a catalog (a file path or a bundled catalog name) or a motor "
                    f"mapping, got {_show(value)}")
        return f"expected a mapping of fields (key: value), got {_show(value)}"
    if kind in ("list_type", "tuple_type"):
        return f"expected a list, got {_show(value)}"
    if kind == "bool_type":
        return f"expected true or false, got {_show(value)}"
    if kind in ("string_type", "string_unicode"):
        return f"expected text, got {_show(value)}"
    if kind == "too_short":
        count = ctx.get("min_length", 1)
        return f"needs at least {count} item{'s' * (count != 1)}"
    if kind == "too_long":
        count = ctx.get("max_length", 0)
        got = f", got {ctx['actual_length']}" if ctx.get("actual_length") is not None else ""
        return f"at most {count} item{'s' * (count != 1)}{got}"
    return _strip_prefix(str(item.get("msg", "invalid value")).splitlines()[0])


def _strip_prefix(text: str) -> str:
    for prefix in ("Value error, ", "Assertion failed, "):
        if text.startswith(prefix):
            return text[len(prefix):]
    return text


# ------------------------------------------------------------ model introspection


def _field_names(model: type[BaseModel]) -> set[str]:
    """All field names (by alias) of ``model`` and the models nested in it."""
    names: set[str] = set()
    for sub in _models_in(model, set()):
        for name, info in sub.model_fields.items():
            names.add(info.alias or name)
    return names


def _models_in(tp: Any, seen: set[Any]) -> list[type[BaseModel]]:
    found: list[type[BaseModel]] = []
    if _is_model(tp):
        if tp in seen:
            return found
        seen.add(tp)
        found.append(tp)
        for info in tp.model_fields.values():
            found += _models_in(info.annotation, seen)
        return found
    for arg in typing.get_args(tp):
        found += _models_in(arg, seen)
    return found


def _members(tp: Any) -> list[Any]:
    """The alternatives of a type: Annotated and Optional/Union unwrapped."""
    origin = typing.get_origin(tp)
    if origin is typing.Annotated:
        return _members(typing.get_args(tp)[0])
    if origin is typing.Union or origin is types.UnionType:
        out: list[Any] = []
        for arg in typing.get_args(tp):
            if arg is not type(None):
                out += _members(arg)
        return out
    return [tp]


def _is_model(tp: Any) -> bool:
    return isinstance(tp, type) and issubclass(tp, BaseModel)


def _models_at(model: type[BaseModel], loc: tuple[Any, ...]) -> list[type[BaseModel]]:
    """The models that may validate the value at ``loc`` (pydantic's loc, tags included)."""
    candidates: list[Any] = [model]
    for part in loc:
        nxt: list[Any] = []
        for tp in candidates:
            for member in _members(tp):
                if _is_model(member):
                    info = _field(member, part)
                    if info is not None:
                        nxt.append(info.annotation)
                    elif part in _tags_of(member):
                        nxt.append(member)  # a union tag: stay on that member
                elif typing.get_origin(member) in (list, tuple) and isinstance(part, int):
                    nxt += list(typing.get_args(member)[:1])
                elif isinstance(part, str) and not part.isidentifier():
                    nxt.append(member)  # a marker of pydantic like 'inline-motor'
        candidates = nxt
    return [m for tp in candidates for m in _members(tp) if _is_model(m)]


def _field(model: type[BaseModel], key: Any) -> Any:
    return next((info for name, info in model.model_fields.items()
                 if (info.alias or name) == key), None)


def _tags_of(model: type[BaseModel]) -> list[str]:
    info = model.model_fields.get("type")
    if info is not None and typing.get_origin(info.annotation) is typing.Literal:
        return [str(a) for a in typing.get_args(info.annotation)]
    return []


def _allowed_fields(model: type[BaseModel], loc: tuple[Any, ...]) -> list[str]:
    """The fields of the model at ``loc``, if exactly one model fits."""
    found = _models_at(model, loc)
    return [info.alias or name for name, info in found[0].model_fields.items()] \
        if len(found) == 1 else []


def _tags_at(model: type[BaseModel], loc: tuple[Any, ...]) -> list[str]:
    """The 'type' tags accepted at ``loc`` (a discriminated union of models)."""
    return [tag for found in _models_at(model, loc) for tag in _tags_of(found)]
