"""YAML composed with bounded work: nodes (aliases expanded), depth and scalar length.

The one composer of every YAML text sizer reads: the files (:mod:`sizer.io.yaml_source`)
and the texts of laws defined by data (``--law '{kind: cubic_spline, ...}'``,
:mod:`sizer.laws.data_spec`). An alias counts the nodes it repeats, so an alias bomb is
refused while it is composed, before anything walks or prints it; the error names the
line and the path of the node where the limit is passed (``laws[2].positions[4]``).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import yaml

from sizer.errors import UserError
from sizer.input_limits import MAX_SCALAR_CHARS, MAX_YAML_DEPTH

if getattr(yaml, "__with_libyaml__", False):
    from yaml._yaml import CParser

    class SafeLoader(yaml.composer.Composer, CParser, yaml.constructor.SafeConstructor,
                     yaml.resolver.Resolver):
        """libyaml's scanner and parser (7x faster) under PyYAML's composer, which counts."""

        def __init__(self, text: str) -> None:
            CParser.__init__(self, text)
            yaml.constructor.SafeConstructor.__init__(self)
            yaml.resolver.Resolver.__init__(self)
            yaml.composer.Composer.__init__(self)
else:  # pragma: no cover - PyYAML built without libyaml
    SafeLoader = yaml.SafeLoader  # type: ignore[misc]  # PyYAML ships no stubs


def format_path(path: Sequence[Any]) -> str:
    """``('motors', 3, 'inertia')`` -> ``'motors[3].inertia'``."""
    text = ""
    for part in path:
        if isinstance(part, int) and not isinstance(part, bool):
            text += f"[{part}]"
        elif isinstance(part, str) and part.isidentifier():
            text += f".{part}" if text else part
        else:  # an odd key, e.g. '12 kg' or 0: shown as in Python
            shown = repr(part)
            text += f"[{shown if len(shown) <= 40 else shown[:37] + '...'}]"
    return text


def parse_path(text: str) -> tuple[Any, ...] | None:
    """The inverse of :func:`format_path` for identifiers and item indices
    (``'motors[3].inertia'`` -> ``('motors', 3, 'inertia')``); None for any other text
    (an odd key, an option such as ``--law``)."""
    parts: list[Any] = []
    for chunk in text.split("."):
        name, _, rest = chunk.partition("[")
        if not name.isidentifier():
            return None
        parts.append(name)
        for index in (rest.split("[") if rest else ()):
            if not index.endswith("]") or not index[:-1].isdigit():
                return None
            parts.append(int(index[:-1]))
    return tuple(parts)


class BoundedLoader(SafeLoader):
    """The safe loader with bounded work: nodes (aliases expanded), depth, scalar length.

    A refusal is a UserError at the ``file``, the line of the node and its path (field).
    """

    def __init__(self, text: str, file: str | None, max_nodes: int) -> None:
        super().__init__(text)
        self.file = file
        self.max_nodes = max_nodes
        self.depth = 0
        self.expanded = 0  # nodes composed so far, an alias counting what it repeats
        self.sizes: dict[int, int] = {}  # expanded size of each finished node
        self.path: list[Any] = []  # keys and indices of the node being composed

    def _fail(self, message: str, event: Any) -> UserError:
        field = format_path(self.path)
        return UserError(message, file=self.file, line=event.start_mark.line + 1,
                         field=(field if len(field) <= 80 else f"{field[:77]}...") or None)

    def _add(self, count: int, event: Any) -> None:
        self.expanded += count
        if self.expanded > self.max_nodes:
            raise self._fail(f"too many YAML nodes: more than {self.max_nodes:,} values once "
                             f"aliases are expanded (an alias bomb?)", event)

    def compose_node(self, parent: Any, index: Any) -> Any:
        event = self.peek_event()
        part = (index.value if isinstance(index, yaml.ScalarNode)
                else index if isinstance(index, int) else None)
        if part is not None:
            self.path.append(part)
        if isinstance(event, yaml.AliasEvent):
            node = super().compose_node(parent, index)
            self._add(self.sizes.get(id(node), 1), event)  # unfinished: recursive, see _walk
        else:
            self.depth += 1
            if self.depth > MAX_YAML_DEPTH:
                raise self._fail(f"nested too deeply: more than {MAX_YAML_DEPTH} levels of "
                                 f"mappings and lists", event)
            start = self.expanded
            self._add(1, event)
            node = super().compose_node(parent, index)
            self.depth -= 1
            self.sizes[id(node)] = self.expanded - start
        if part is not None:
            self.path.pop()
        return node

    def compose_scalar_node(self, anchor: Any) -> Any:
        event = self.peek_event()
        if len(event.value) > MAX_SCALAR_CHARS:
            raise self._fail(f"a value of {len(event.value):,} characters: the limit is "
                             f"{MAX_SCALAR_CHARS:,}", event)
        return super().compose_scalar_node(anchor)


def load_bounded(text: str, *, max_nodes: int) -> Any:
    """The data of a one-document YAML text (safe types), composed under the limits.

    yaml.YAMLError for malformed YAML; UserError (no file, no line: a text given on its
    own, e.g. a command-line option) naming the path inside the text where a limit is
    passed.
    """
    loader = BoundedLoader(text, None, max_nodes)
    try:
        try:
            node = loader.get_single_node()
        except UserError as error:
            where = f" (at {error.field})" if error.field else ""
            raise UserError(f"{error.message}{where}") from None
        except RecursionError:
            raise UserError(f"nested too deeply: more than {MAX_YAML_DEPTH} levels of "
                            f"mappings and lists") from None
        return None if node is None else loader.construct_document(node)
    finally:
        loader.dispose()
