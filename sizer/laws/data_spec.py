"""The spec of a law defined by data: a YAML mapping, and its canonical one-line text.

A data-defined law (book ch. 4, seed 002) is written in a design file as a mapping,
``{kind: cubic_spline, points: [[0, 0], [0.4, 0.3], [1, 1]]}``, and travels through sizer
as its canonical text: a YAML flow mapping with ``kind`` first and the other keys sorted,
numbers written to round-trip. The text parses back (by :func:`read_data_spec`) to the
same mapping, so laws compare, hash and cache by it like every other spec, and an export
that prints it can be read again. ``kind`` names a builder in :data:`DATA_LAW_KINDS`.
"""

from __future__ import annotations

import importlib
import math
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, TypeGuard

from sizer.errors import UserError
from sizer.input_limits import MAX_DATA_LAW_CHARS, MAX_DESIGN_NODES, MAX_YAML_DEPTH


@dataclass(frozen=True)
class DataKind:
    """A kind of data-defined law: its builder (``module:function``, imported on first use
    so that scipy loads only when such a law is built) and its title."""

    name: str
    builder: str
    title: str

    def build(self) -> Callable[..., Any]:
        module, function = self.builder.split(":")
        return getattr(importlib.import_module(module), function)  # type: ignore[no-any-return]


DATA_LAW_KINDS: Mapping[str, DataKind] = {k.name: k for k in (
    DataKind("cubic_spline", "sizer.laws.multipoint.cubic_splines:build_cubic_spline",
             "Cubic spline through via-points (sec. 4.4)"),
    DataKind("smoothing_spline",
             "sizer.laws.multipoint.smoothing_splines:build_smoothing_spline",
             "Smoothing cubic spline (sec. 4.4.5)"),
    DataKind("poly_spline", "sizer.laws.multipoint.poly_splines:build_poly_spline",
             "Polynomial spline of order k (slides)"),
    DataKind("bspline", "sizer.laws.multipoint.bsplines:build_bspline",
             "B-spline (sec. 4.5, slides)"),
    DataKind("nurbs", "sizer.laws.multipoint.nurbs:build_nurbs", "NURBS (slides)"),
    DataKind("via_trapezoid", "sizer.laws.multipoint.via_trapezoid:build_via_trapezoid",
             "Trapezoidal velocity through a sequence of points (sec. 3.2.4)"),
    DataKind("interpolating_polynomial",
             "sizer.laws.multipoint.interpolating_polynomial:build_interpolating_polynomial",
             "Polynomial through n points (sec. 4.1)"),
    DataKind("least_squares_polynomial",
             "sizer.laws.multipoint.least_squares_polynomial:build_least_squares_polynomial",
             "Least-squares orthogonal polynomials (sec. 4.2)"),
    DataKind("trigonometric_polynomial",
             "sizer.laws.multipoint.trigonometric_polynomial:build_trigonometric_polynomial",
             "Trigonometric polynomial through periodic points (sec. 4.3)"),
    DataKind("cam_table", "sizer.io.cam_table_law:build_cam_table_law",
             "Cam table: samples fitted by a spline"),
    DataKind("cam_segments", "sizer.io.segment_table_law:build_cam_segments_law",
             "Coefficient segments: polynomial of degree <= 6 plus a sine, per segment"),
    DataKind("shaped", "sizer.vibration.shaped_law:build_shaped",
             "A law convolved with an input shaper (sec. 7.4.2)"),
)}
"""Data-defined law kinds by name."""

COMMON_FIELDS = ("kind", "units", "name")
"""Fields every kind reads (the law layer): the kind, the units of the numbers and a
name that tables show instead of the whole mapping."""

_BARE = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")
_YAML_WORDS = frozenset({"y", "n", "yes", "no", "on", "off", "true", "false", "null", "~"})


def is_data_spec(text: object) -> TypeGuard[str]:
    """True for a spec text written as a mapping (``{kind: ...}``)."""
    return isinstance(text, str) and text.lstrip().startswith("{")


def data_spec_text(fields: Mapping[str, Any]) -> str:
    """The canonical text of a data-law mapping; UserError for a mapping sizer cannot read.

    ``kind`` comes first, the other keys sorted; floats written by repr (which reads back
    to the same float), integral values as integers.
    """
    kind = fields.get("kind")
    if kind is None:
        raise UserError(f"a law written as a mapping needs a kind; kinds: "
                        f"{', '.join(DATA_LAW_KINDS)}", field="kind")
    if not isinstance(kind, str) or kind not in DATA_LAW_KINDS:
        raise UserError(f"unknown kind {kind!r}; kinds of laws defined by data: "
                        f"{', '.join(DATA_LAW_KINDS)}", field="kind")
    rest = {str(k): v for k, v in fields.items() if k != "kind"}
    size = _expanded_size(fields, {}, set())
    if size > MAX_DATA_LAW_CHARS:  # shared values (YAML aliases) repeat in the text
        raise UserError(f"a law of at least {size:,} characters once its YAML aliases are "
                        f"expanded: the limit is {MAX_DATA_LAW_CHARS:,}")
    text = _flow({"kind": kind, **dict(sorted(rest.items()))})
    if len(text) > MAX_DATA_LAW_CHARS:
        raise UserError(f"a law of {len(text):,} characters: the limit is "
                        f"{MAX_DATA_LAW_CHARS:,}; put long tables in a cam_table file",
                        field="kind")
    return text


def read_data_spec(text: str) -> dict[str, Any]:
    """The mapping of a data-law spec text (the inverse of :func:`data_spec_text`)."""
    import yaml

    from sizer.bounded_yaml import load_bounded

    if len(text) > MAX_DATA_LAW_CHARS:
        raise UserError(f"a law spec of {len(text):,} characters: the limit is "
                        f"{MAX_DATA_LAW_CHARS:,}")
    try:
        if "&" in text or text.count("[") + text.count("{") > MAX_YAML_DEPTH:
            # maybe aliases (an anchor: a bomb?) or deep nesting: composed under the limits
            fields = load_bounded(text, max_nodes=MAX_DESIGN_NODES)
        else:  # no alias: the nodes are bounded by the length (libyaml alone, fast)
            fields = yaml.load(text, Loader=getattr(yaml, "CSafeLoader", yaml.SafeLoader))
    except UserError as error:
        raise UserError(f"cannot read the law {text[:60]!r}: {error.message}") from None
    except yaml.YAMLError as error:
        mark = getattr(error, "problem_mark", None)
        where = f" at character {mark.index + 1}" if mark is not None else ""
        raise UserError(f"cannot read the law {text[:60]!r}{where}: write a mapping like "
                        f"{{kind: cubic_spline, points: [[0, 0], [1, 1]]}}") from None
    if not isinstance(fields, dict):
        raise UserError(f"cannot read the law {text[:60]!r}: expected a mapping like "
                        f"{{kind: cubic_spline, points: [[0, 0], [1, 1]]}}")
    return fields


def canonical_data_spec(text: str) -> str:
    """The canonical text of a data-law spec text as the user wrote it."""
    return data_spec_text(read_data_spec(text))


def _expanded_size(value: Any, sizes: dict[int, int], open_ids: set[int]) -> int:
    """At least the characters of ``_flow(value)``, counted once per shared value (an
    alias bomb costs its nodes, not its expansion); UserError for a value that holds
    itself (``&a [*a]``)."""
    if not isinstance(value, Mapping | list | tuple):
        return len(str(value))
    known = sizes.get(id(value))
    if known is not None:
        return known
    if id(value) in open_ids:
        raise UserError("recursive YAML alias (a collection that contains itself)")
    open_ids.add(id(value))
    items = ([(str(k), v) for k, v in value.items()] if isinstance(value, Mapping)
             else [("", v) for v in value])
    total = 2 + sum(len(k) + 2 + _expanded_size(v, sizes, open_ids) for k, v in items)
    open_ids.discard(id(value))
    sizes[id(value)] = total
    return total


def _flow(value: Any) -> str:
    """A YAML flow text of plain data that reads back to the same data."""
    if isinstance(value, Mapping):
        return "{" + ", ".join(f"{_key(k)}: {_flow(v)}" for k, v in value.items()) + "}"
    if isinstance(value, list | tuple):
        return "[" + ", ".join(_flow(v) for v in value) + "]"
    if isinstance(value, bool) or value is None:
        return {True: "true", False: "false", None: "null"}[value]
    if isinstance(value, int | float):
        number = float(value)
        if not math.isfinite(number):
            raise UserError(f"{value!r} is not a finite number")
        if number == int(number) and abs(number) < 1e15:
            return str(int(number))
        text = repr(number)
        mantissa, e, exponent = text.partition("e")
        # PyYAML reads 1e-05 as a string: a float needs a dot in its mantissa
        return f"{mantissa}.0e{exponent}" if e and "." not in mantissa else text
    text = str(value)
    if _BARE.match(text) and text.lower() not in _YAML_WORDS:
        return text
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def _key(key: Any) -> str:
    text = str(key)
    if not _BARE.match(text) or text.lower() in _YAML_WORDS:
        raise UserError(f"a field name must be a plain word, got {key!r}", field=text)
    return text


def data_law_label(text: str) -> str:
    """A short name of a data law for tables: its ``name``, else the kind with its file
    (a cam table) or its number of points; the spec text itself stays in CSV and JSON."""
    try:
        fields = read_data_spec(text)
    except UserError:
        return text
    if isinstance(fields.get("name"), str):
        return str(fields["name"])
    kind = str(fields.get("kind"))
    if isinstance(fields.get("file"), str):
        return f"{kind}({fields['file'].replace(chr(92), '/').rsplit('/', 1)[-1]})"
    for key in ("points", "positions", "control_points"):
        if isinstance(fields.get(key), list):
            return f"{kind}({len(fields[key])} {key.replace('_', ' ')})"
    if kind == "shaped" and isinstance(fields.get("shaper"), str):
        base = fields.get("law")
        inner = data_law_label(data_spec_text(base)) if isinstance(base, dict) else base
        return f"{fields['shaper']}({inner})"
    return kind


def law_label(spec: str) -> str:
    """How texts and tables name a law: its spec, or a data law's short label."""
    return data_law_label(spec) if is_data_spec(spec) else spec
