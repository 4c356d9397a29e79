"""YAML text with the line of every mapping key and sequence item.

``read_yaml(path)`` / ``parse_yaml(text, file)`` return a :class:`YamlSource`: the plain
data (safe loader: dicts, lists, str, int, float, bool, None, dates) and a map from paths
like ``("task", "duration")`` or ``("motors", 3, "inertia")`` to 1-based line numbers.
Malformed YAML, duplicate keys and a top level that is not a mapping raise UserError with
the file and line. The work is bounded (sizer.input_limits): files are read by
:func:`sizer.io.files.read_user_text`; nodes are counted as they are composed, aliases by the
size of what they repeat (an alias bomb is refused before it is walked), and the nesting
depth, the length of a value and the digits of an integer are limited. A number that is not
finite (``.inf``, ``.nan``, ``1.0e999``) or an integer beyond the float range is refused
where it is written.
"""

from __future__ import annotations

import gc
import math
from collections.abc import Hashable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

from sizer.bounded_yaml import BoundedLoader as _BoundedLoader
from sizer.bounded_yaml import format_path
from sizer.errors import UserError
from sizer.input_limits import (
    MAX_CATALOG_BYTES,
    MAX_CATALOG_NODES,
    MAX_DESIGN_BYTES,
    MAX_DESIGN_NODES,
    MAX_INT_DIGITS,
    MAX_SCALAR_CHARS,
    MAX_YAML_DEPTH,
)
from sizer.io.files import read_user_text

Path_ = tuple[Any, ...]
"""A path into the YAML data: mapping keys and sequence indices."""

_MERGE_TAG = "tag:yaml.org,2002:merge"
_INT_TAG = "tag:yaml.org,2002:int"
_FLOAT_MAX = 1.7976931348623157e308


if getattr(yaml, "__with_libyaml__", False):
    from yaml._yaml import CParser


class _NotPlainError(Exception):
    """The document needs the general path (an anchor, a tag, an error...)."""


_STR_TAG = "tag:yaml.org,2002:str"
_FLOAT_TAG = "tag:yaml.org,2002:float"
_SCALAR_TAGS = frozenset({_STR_TAG, _INT_TAG, _FLOAT_TAG, "tag:yaml.org,2002:bool",
                          "tag:yaml.org,2002:null", "tag:yaml.org,2002:timestamp"})
_RESOLVERS = yaml.resolver.Resolver.yaml_implicit_resolvers
_CONSTRUCTOR = yaml.constructor.SafeConstructor()


def _plain_scalar(event: Any) -> Any:
    """The value of a scalar event, as SafeConstructor gives it, with the checks of
    :func:`_construct_scalar`; _NotPlainError where those would fail or for an explicit tag."""
    value = event.value
    if event.tag is not None or len(value) > MAX_SCALAR_CHARS:
        raise _NotPlainError
    if not event.implicit[0]:
        return value  # quoted: a string
    tag = _STR_TAG
    for candidate, pattern in _RESOLVERS.get(value[0] if value else "", ()):
        if pattern.match(value):
            tag = candidate
            break
    if tag == _STR_TAG:
        return value
    if tag not in _SCALAR_TAGS:
        raise _NotPlainError  # '<<' (merge), '=' (value)
    if tag == _INT_TAG and sum(c.isdigit() for c in value) > MAX_INT_DIGITS:
        raise _NotPlainError
    try:
        result = _CONSTRUCTOR.yaml_constructors[tag](
            _CONSTRUCTOR, yaml.ScalarNode(tag, value, event.start_mark, event.end_mark))
    except Exception:
        raise _NotPlainError from None
    if isinstance(result, int) and not isinstance(result, bool) and abs(result) > _FLOAT_MAX:
        raise _NotPlainError
    if isinstance(result, float) and not math.isfinite(result):
        raise _NotPlainError
    return result


def _parse_plain(text: str, file: str | None, max_nodes: int) -> YamlSource | None:
    """The data and lines of a plain document read in one pass over libyaml's events, or
    None when the document needs the general path (see :func:`parse_yaml`).

    The same data, lines and limits as the general path: each node counts one, a node
    deeper than MAX_YAML_DEPTH, a scalar longer than MAX_SCALAR_CHARS, an anchor, an
    alias, a tag, a merge key, a key that is not a scalar, a duplicate key, a value that
    does not construct and a top level that is not a mapping all mean None.
    """
    if not getattr(yaml, "__with_libyaml__", False):  # pragma: no cover
        return None
    with no_garbage_collection():
        try:
            return _plain_events(CParser(text), file, max_nodes)
        except Exception:  # _NotPlainError, or an error the general path words
            return None


@contextmanager
def no_garbage_collection() -> Iterator[None]:
    """The cyclic garbage collector paused: building many small containers (none of them
    garbage) would run it again and again for nothing."""
    collecting = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if collecting:
            gc.enable()


_NO_KEY = object()


_PLAIN_STR_FIRST = frozenset(chr(c) for c in range(32, 127)) - set(_RESOLVERS)
"""First characters of a plain scalar that no implicit resolver can match: a string."""


def _plain_events(parser: Any, file: str | None, max_nodes: int) -> YamlSource:
    """The loop of :func:`_parse_plain`: one pass over the events, the innermost open
    collection in locals. A scalar is a string without the resolvers when it is quoted,
    starts with a character no resolver starts with, or holds a space and is not a
    timestamp (only the timestamp pattern admits a space, after 'YYYY-')."""
    get = parser.get_event
    if type(get()) is not yaml.StreamStartEvent or \
            type(get()) is not yaml.DocumentStartEvent:
        raise _NotPlainError
    event = get()
    if type(event) is not yaml.MappingStartEvent or event.anchor is not None \
            or event.tag is not None:
        raise _NotPlainError
    source = YamlSource({}, file)
    lines = source.lines
    lines[()] = event.start_mark.line + 1
    # the innermost open collection, its path, its pending key (a mapping's), and the
    # enclosing ones as (container, path, key, is_mapping)
    container: Any = source.data
    path: Path_ = ()
    key: Any = _NO_KEY
    is_mapping = True
    outer: list[tuple[Any, Path_, Any, bool]] = []
    count = 1
    deepest = MAX_YAML_DEPTH - 1  # enclosing collections of the innermost, at most
    scalar_event, mapping_start = yaml.ScalarEvent, yaml.MappingStartEvent
    sequence_start = yaml.SequenceStartEvent
    ends = (yaml.MappingEndEvent, yaml.SequenceEndEvent)
    first_str, longest, no_key = _PLAIN_STR_FIRST, MAX_SCALAR_CHARS, _NO_KEY
    while True:
        event = get()
        kind = type(event)
        if kind is scalar_event:
            count += 1
            if count > max_nodes or len(outer) >= deepest or event.anchor is not None:
                raise _NotPlainError
            value = event.value
            if event.tag is not None or len(value) > longest or not (
                    not event.implicit[0] or (value and value[0] in first_str)
                    or (" " in value and value[4:5] != "-")):
                value = _plain_scalar(event)
            if is_mapping:
                if key is no_key:
                    at = (*path, value)
                    if value in container or at in lines:
                        raise _NotPlainError  # a duplicate key
                    key = value
                    lines[at] = event.start_mark.line + 1
                else:
                    container[key] = value
                    key = no_key
            else:
                lines[(*path, len(container))] = event.start_mark.line + 1
                container.append(value)
            continue
        if kind in ends:
            if not outer:
                break
            done = container
            container, path, key, is_mapping = outer.pop()
            if is_mapping:
                container[key] = done
                key = no_key
            else:
                container.append(done)
            continue
        if kind is not mapping_start and kind is not sequence_start:
            raise _NotPlainError  # an alias
        count += 1
        if count > max_nodes or len(outer) >= deepest or event.anchor is not None \
                or event.tag is not None:
            raise _NotPlainError
        if is_mapping:
            if key is no_key:
                raise _NotPlainError  # a key that is a collection
            at = (*path, key)
        else:
            at = (*path, len(container))
            lines[at] = event.start_mark.line + 1
        outer.append((container, path, key, is_mapping))
        container, path, key = ({} if kind is mapping_start else []), at, no_key
        is_mapping = kind is mapping_start
    if type(get()) is not yaml.DocumentEndEvent or type(get()) is not yaml.StreamEndEvent:
        raise _NotPlainError  # more than one document
    return source


@dataclass
class YamlSource:
    """Parsed YAML data and where each key or item starts (1-based lines)."""

    data: Any
    file: str | None = None
    lines: dict[Path_, int] = field(default_factory=dict)

    def line_of(self, path: Sequence[Any]) -> int | None:
        """The line of ``path``, or of its nearest ancestor whose line is known."""
        path = tuple(path)
        while True:
            line = self.lines.get(path)
            if line is not None:
                return line
            if not path:
                return None
            path = path[:-1]

    def error(self, message: str, path: Sequence[Any] = (), *,
              field: str | None = None) -> UserError:
        """A UserError at ``path`` (the field name defaults to the path's text)."""
        return UserError(message, file=self.file, line=self.line_of(path),
                         field=field if field is not None else (format_path(path) or None))

    def relocate(self, error: UserError, path: Sequence[Any]) -> UserError:
        """``error`` placed at ``path`` of this file, keeping its own location if it has one."""
        if error.file is not None:
            return error
        return UserError(error.message, file=self.file, line=self.line_of(path),
                         field=format_path(path) or error.field)


def read_yaml(path: str | Path, *, limit: int = MAX_CATALOG_BYTES,
              max_nodes: int = MAX_CATALOG_NODES) -> YamlSource:
    """Read and parse a YAML file whose top level is a mapping.

    At most ``limit`` bytes and ``max_nodes`` nodes (aliases expanded); the defaults are
    those of a catalog, :func:`sizer.io.loader.load_design` passes a design's.
    """
    return parse_yaml(read_user_text(path, limit=limit), str(path), max_nodes=max_nodes)


def parse_mapping(data: Mapping[str, Any], what: str) -> YamlSource:
    """A design or machine given as a mapping (from Python or JSON), written out as YAML
    and parsed as a file of that kind (``<what>`` for its name), so that its messages
    name the lines of the YAML text."""
    try:
        text = yaml.safe_dump(dict(data), sort_keys=False, allow_unicode=True)
    except yaml.YAMLError as error:
        raise UserError(f"the {what} mapping cannot be written as YAML: {error}") from None
    if len(text.encode()) > MAX_DESIGN_BYTES:
        raise UserError(f"the {what} mapping is larger than {MAX_DESIGN_BYTES} bytes")
    return parse_yaml(text, file=f"<{what}>", max_nodes=MAX_DESIGN_NODES)


def parse_yaml(text: str, file: str | None = None, *,
               max_nodes: int = MAX_CATALOG_NODES) -> YamlSource:
    """Parse YAML text (one document, a mapping at the top) keeping line numbers.

    A plain document (no anchor, alias, tag or merge key, within the limits, no
    duplicate key or bad value) is read straight from libyaml's events
    (:func:`_parse_plain`); anything else, including every error, takes the general
    path below, which gives the same data and lines and words every error.
    """
    fast = _parse_plain(text, file, max_nodes)
    if fast is not None:
        return fast
    try:
        loader = _BoundedLoader(text, file, max_nodes)
    except yaml.YAMLError as error:
        raise _yaml_error(error, text, file) from None
    try:
        node = loader.get_single_node()
        source = YamlSource(None, file)
        if node is not None:
            source.lines[()] = node.start_mark.line + 1
            _walk(node, (), source, loader, set(), set())
            data = loader.construct_document(node)
        else:
            data = None
    except yaml.YAMLError as error:
        raise _yaml_error(error, text, file) from None
    except RecursionError:
        raise UserError("invalid YAML: nested too deeply", file=file) from None
    except (ValueError, TypeError, OverflowError) as error:  # constructors of odd values
        raise UserError(f"invalid YAML: {error}", file=file) from None
    finally:
        loader.dispose()
    if not isinstance(data, dict):
        kind = "empty" if data is None else f"a {_kind(data)}"
        line = node.start_mark.line + 1 if node is not None else 1
        raise UserError(f"the file must hold a mapping (key: value lines), but it is {kind}",
                        file=file, line=line)
    source.data = data
    return source


def _kind(value: Any) -> str:
    if isinstance(value, list):
        return "list"
    if isinstance(value, str):
        return "text"
    if isinstance(value, bool):
        return "boolean"
    if isinstance(value, int | float):
        return "number"
    return type(value).__name__


def _walk(node: yaml.Node, path: Path_, source: YamlSource, loader: Any,
          seen: set[int], active: set[int]) -> None:
    """Record lines of keys/items under ``node`` and reject duplicate keys.

    Each node is visited once (aliases share nodes; this also stops recursive aliases and
    alias bombs), so paths reached only through an alias fall back to an ancestor's line.
    ``active`` holds the nodes being walked: meeting one again is a recursive alias.
    """
    if id(node) in active:
        raise UserError("recursive YAML alias (a collection that contains itself)",
                        file=source.file, line=node.start_mark.line + 1,
                        field=format_path(path) or None)
    if id(node) in seen:
        return
    seen.add(id(node))
    active.add(id(node))
    try:
        _walk_children(node, path, source, loader, seen, active)
    finally:
        active.discard(id(node))


def _walk_children(node: yaml.Node, path: Path_, source: YamlSource, loader: Any,
                   seen: set[int], active: set[int]) -> None:
    if isinstance(node, yaml.ScalarNode):
        _construct_scalar(node, path, source, loader)
    elif isinstance(node, yaml.SequenceNode):
        for index, item in enumerate(node.value):
            item_path = (*path, index)
            source.lines.setdefault(item_path, item.start_mark.line + 1)
            _walk(item, item_path, source, loader, seen, active)
    elif isinstance(node, yaml.MappingNode):
        first_line: dict[Hashable, int] = {}
        for key_node, value_node in node.value:
            line = key_node.start_mark.line + 1
            if key_node.tag == _MERGE_TAG:
                # '<<: *defaults': merged keys belong to this mapping, explicit keys win.
                merged = value_node.value if isinstance(value_node, yaml.SequenceNode) \
                    else [value_node]
                for part in merged:
                    if isinstance(part, yaml.MappingNode):
                        _walk_merged(part, path, source, loader, seen, active)
                continue
            key = _key(key_node, path, source, loader)
            if key in first_line:
                raise UserError(f"duplicate key {key!r} (first given on line {first_line[key]})",
                                file=source.file, line=line,
                                field=format_path((*path, key)))
            first_line[key] = line
            key_path = (*path, key)
            source.lines[key_path] = line
            _walk(value_node, key_path, source, loader, seen, active)


def _walk_merged(node: yaml.MappingNode, path: Path_, source: YamlSource,
                 loader: Any, seen: set[int], active: set[int]) -> None:
    for key_node, value_node in node.value:
        if key_node.tag == _MERGE_TAG:
            continue
        key_path = (*path, _key(key_node, path, source, loader))
        source.lines.setdefault(key_path, key_node.start_mark.line + 1)
        _walk(value_node, key_path, source, loader, seen, active)


def _construct_scalar(node: yaml.ScalarNode, path: Path_, source: YamlSource,
                      loader: Any) -> Any:
    """Construct a scalar now, so that a bad one (e.g. date 2024-02-30) has a line.

    Integers of more than MAX_INT_DIGITS digits or beyond the float range and floats that
    are not finite are refused here, wherever they are written.
    """

    def fail(message: str) -> UserError:
        return UserError(message, file=source.file, line=node.start_mark.line + 1,
                         field=format_path(path) or None)

    shown = _short(node.value)
    if node.tag == _INT_TAG and sum(c.isdigit() for c in node.value) > MAX_INT_DIGITS:
        raise fail(f"an integer of {sum(c.isdigit() for c in node.value)} digits is too "
                   f"large: numbers must be finite, below {_FLOAT_MAX:.4g}")
    try:
        value = loader.construct_object(node)
    except yaml.YAMLError:
        raise
    except Exception as error:  # the timestamp constructor raises ValueError and friends
        raise fail(f"invalid YAML value {shown}: {_short(str(error), 120)}") from None
    if isinstance(value, int) and not isinstance(value, bool) and abs(value) > _FLOAT_MAX:
        raise fail(f"an integer of {len(str(abs(value)))} digits is too large: numbers must be "
                   f"finite, below {_FLOAT_MAX:.4g}")
    if isinstance(value, float) and not math.isfinite(value):
        raise fail(f"{shown} is not a finite number: numbers must be finite (no .inf or "
                   f".nan), below {_FLOAT_MAX:.4g} in size")
    return value


def _short(text: str, limit: int = 60) -> str:
    """``repr`` of a text, cut to about ``limit`` characters for a message."""
    shown = repr(text)
    return shown if len(shown) <= limit else f"{shown[:limit - 3]}...' ({len(text):,} chars)"


def _key(node: yaml.Node, path: Path_, source: YamlSource, loader: Any) -> Hashable:
    """The constructed value of a scalar key; other keys by their position."""
    if isinstance(node, yaml.ScalarNode):
        value = _construct_scalar(node, path, source, loader)
        try:
            hash(value)
        except TypeError:
            return f"<key at line {node.start_mark.line + 1}>"
        return value
    return f"<complex key at line {node.start_mark.line + 1}>"


def _yaml_error(error: yaml.YAMLError, text: str, file: str | None) -> UserError:
    """A one-line UserError from a PyYAML error, at its line."""
    line = None
    mark = getattr(error, "problem_mark", None) or getattr(error, "context_mark", None)
    if mark is not None:
        line = mark.line + 1
    elif isinstance(error, yaml.reader.ReaderError):
        line = text[: error.position].count("\n") + 1
    if isinstance(error, yaml.MarkedYAMLError):
        parts = [error.context, error.problem]
        message = "; ".join(p for p in parts if p)
        if "nesting depth" in message:  # libyaml's own limit (PyYAML >= 6.0.4 wheels)
            message = (f"nested too deeply: more than {MAX_YAML_DEPTH} levels of mappings "
                       f"and lists")  # libyaml stops deeper than sizer's own limit
    elif isinstance(error, yaml.reader.ReaderError):
        char = error.character
        message = f"unacceptable character {chr(char) if isinstance(char, int) else char!r}"
    else:
        message = str(error).splitlines()[0] if str(error) else type(error).__name__
    return UserError(f"invalid YAML: {message or 'cannot parse'}", file=file, line=line)
