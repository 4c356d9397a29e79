"""Laws written as mappings in a design file: located, checked, made canonical text.

A design's ``laws:`` entries, ``check.law`` and a cycle move's ``law`` may be a mapping
(``{kind: cubic_spline, points: ...}``, book ch. 4). Before the design is validated each
mapping is built once: a mistake is reported at the line of the field inside the mapping
(``points[3]``, ``start.velocity``), a cam table's relative ``file`` is taken from the
design's folder (and written relative to the working directory, where the cam-table
builder reads it: :func:`cam_table_file`), and the mapping is replaced by its canonical
text, the spec every later layer reads.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from sizer.errors import UserError
from sizer.io.yaml_source import YamlSource
from sizer.laws.open_shaped import is_open_shaped

_PART = re.compile(r"([^.\[\]]+)|\[(\d+)\]")


FILE_KINDS = ("cam_table", "cam_segments")
"""The data laws read from a file (``file:``, relative to the design's folder)."""

def law_paths(data: Any) -> Iterator[tuple[Any, ...]]:
    """The paths of every law entry of a design's data that is a mapping."""
    if not isinstance(data, dict):
        return
    laws = data.get("laws")
    if isinstance(laws, dict):
        yield ("laws",)
    elif isinstance(laws, list):
        yield from (("laws", i) for i, v in enumerate(laws) if isinstance(v, dict))
    check = data.get("check")
    if isinstance(check, dict) and isinstance(check.get("law"), dict):
        yield ("check", "law")
    cycle = data.get("cycle")
    segments = cycle.get("segments") if isinstance(cycle, dict) else None
    for i, segment in enumerate(segments if isinstance(segments, list) else ()):
        if not isinstance(segment, dict):
            continue
        for key, body in segment.items():
            if isinstance(body, dict) and isinstance(body.get("law"), dict):
                yield ("cycle", "segments", i, key, "law")


def canonical_data_laws(source: YamlSource, folder: Path) -> None:
    """Replace every law mapping of ``source.data`` by its canonical spec text, in place,
    after building its law (UserError at the line of the bad field)."""
    from sizer.laws import make_law
    from sizer.laws.data_spec import data_spec_text

    for path in list(law_paths(source.data)):
        parent = _at(source.data, path[:-1])
        fields = dict(parent[path[-1]])
        if fields.get("kind") in FILE_KINDS and isinstance(fields.get("file"), str):
            fields["file"] = cam_table_file(fields["file"], folder)
        try:
            text = data_spec_text(fields)
            if is_open_shaped(fields):
                _check_open_shaped(source, fields)
            else:
                make_law(text)
        except UserError as error:
            raise _located(source, path, error) from None
        if path == ("laws",):
            source.data["laws"] = [text]
            source.lines[("laws", 0)] = source.line_of(("laws",)) or 1
        else:
            parent[path[-1]] = text


def cam_table_file(written: str, folder: Path) -> str:
    """The ``file`` of a cam table in its law's spec: the path as the user wrote it when
    it is absolute or the design is in the working directory; else the file relative to
    the working directory (``examples/cams/knife.csv`` for ``cams/knife.csv`` written in
    ``examples/knife.yaml``), which is where the cam-table builder reads a relative path
    (sizer.io.cam_table_law). So an export that prints the spec names no absolute path of
    the machine (issue 36), and the spec pasted into ``sizer law`` from the same folder
    reads the same file. A file outside the working directory (``..``, another drive) is
    written absolute: ``..`` does not name the same folder through a symbolic link."""
    if Path(written).is_absolute():
        return written
    target = (folder / written).absolute()
    try:
        relative = os.path.relpath(target, Path.cwd())
    except ValueError:  # another drive (Windows): no relative path
        return str(target)
    if os.pardir in Path(relative).parts:
        return str(target)
    text = written if Path(relative) == Path(written) else relative
    if _RELATIVE_FILES.setdefault(text, str(target)) != str(target):
        return str(target)  # the text named another file before a chdir: laws are cached
    return text


_RELATIVE_FILES: dict[str, str] = {}
"""The file each relative cam-table path of a spec has named in this process. Laws are
built once per spec text (sizer.laws.registry): after a change of the working directory
the same text naming another file would get the law of the first, so that design's spec
names its file absolute instead."""


def _check_open_shaped(source: YamlSource, fields: dict[str, Any]) -> None:
    """A shaped law whose f_T the design's mode and durations give (sizer.sizing.
    shaped_sizing): the design must give the mode; the base law and shaper are built."""
    from sizer.laws import make_law
    from sizer.laws.data_spec import data_spec_text

    load = source.data.get("load") if isinstance(source.data, dict) else None
    if not isinstance(load, dict) or load.get("natural_frequency") is None:
        raise UserError("a shaped law without f_T is shaped for the load's mode: give "
                        "load.natural_frequency (or f_T)", field="f_T")
    make_law(data_spec_text({**fields, "f_T": 1e6}))  # the base law and the shaper


def _at(data: Any, path: tuple[Any, ...]) -> Any:
    for part in path:
        data = data[part]
    return data


def _located(source: YamlSource, path: tuple[Any, ...], error: UserError) -> UserError:
    """The error at the line of its field inside the law mapping at ``path`` (an error
    located in another file, the CSV of a cam table, keeps its own place)."""
    if error.file is not None:
        return error
    inner: tuple[Any, ...] = ()
    if error.field:
        inner = tuple(name if name else int(index)
                      for name, index in _PART.findall(error.field))
    if error.field and inner and not error.field.startswith(("units", "kind")) and \
            inner[0] not in _at(source.data, path):
        inner = ()  # a field the builder names but the user did not write (a default)
    return source.relocate(UserError(error.message, field=error.field), (*path, *inner))
