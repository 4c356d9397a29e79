"""Bad-input cases: a file or a command, the exit code it must give, the words its message holds.

Each ``tests/test_bad_inputs_*.py`` module lists :class:`Case` objects and runs them with
:func:`run_case`, which checks what every answer to a bad input must be (issue 10):

- the expected exit code (2 for a user error), and every listed word in stderr;
- with exit code 2, exactly one ``error:`` line and nothing on stdout;
- no traceback, no Python warning (recorded, whatever pytest's filters), no ``nan``/``inf``
  printed as a result;
- every input file unchanged (same bytes), whatever the command wrote.

A design or catalog is given as text, or as an edit of an example: :func:`edited` sets
(dotted paths, list indices in brackets) and deletes keys of the parsed YAML and dumps it.
Placeholders in ``args``: ``{design}``, ``{catalog}`` and ``{tmp}`` (the case's folder).
"""

from __future__ import annotations

import copy
import functools
import re
import subprocess
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml
from cli_run import run_cli

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"

NON_FINITE = re.compile(r"(?<![A-Za-z_])(nan|-?inf(inity)?)(?![A-Za-z_])", re.IGNORECASE)
"""A ``nan`` or ``inf`` token in an output (not 'info', 'infeasible' or 'Infinity' in a word)."""

_DELETE = object()


@dataclass(frozen=True)
class Case:
    """One bad input and the answer it must get."""

    id: str
    args: tuple[str, ...] = ("size", "{design}")
    design: str | None = None
    catalog: str | None = None
    exit_code: int = 2
    words: tuple[str, ...] = ()
    fields: tuple[str, ...] = ()
    """The design or catalog fields the case exercises (dotted, e.g. 'task.duration')."""
    extra_files: dict[str, str | bytes] = field(default_factory=dict)
    """More files in the case's folder, by name (e.g. a gearbox catalog the design names)."""

    def __str__(self) -> str:
        return self.id


def edited(example: str, set: dict[str, Any] | None = None,
           delete: tuple[str, ...] | list[str] = ()) -> str:
    """The YAML text of ``examples/<example>`` with keys set and deleted.

    Paths are dotted with list indices in brackets: ``'motors[0].inertia'``. A relative
    catalog named by the example keeps working: the cases copy ``examples/catalogs`` beside
    the design.
    """
    data = copy.deepcopy(_example_data(example))
    for path, value in (set or {}).items():
        _put(data, _parts(path), value)
    for path in delete:
        _put(data, _parts(path), _DELETE)
    return yaml.safe_dump(data, sort_keys=False, allow_unicode=True)


@functools.cache
def _example_data(example: str) -> Any:
    """The parsed example, once a process: the cases edit ~20 examples ~420 times while
    pytest collects them, and parsing took most of that time (each edit deep-copies)."""
    return yaml.safe_load((EXAMPLES / example).read_text(encoding="utf-8"))


def _parts(path: str) -> list[str | int]:
    parts: list[str | int] = []
    for name, index in re.findall(r"([^.\[\]]+)|\[(\d+)\]", path):
        parts.append(int(index) if index else name)
    return parts


def _put(data: Any, parts: list[str | int], value: Any) -> None:
    for part in parts[:-1]:
        data = data[part]
    last = parts[-1]
    if value is _DELETE:
        del data[last]
    elif isinstance(data, list) and isinstance(last, int) and last == len(data):
        data.append(value)
    else:
        data[last] = value


def case_files(case: Case, folder: Path) -> dict[str, Path]:
    """Write the case's files into ``folder``; the placeholders and their paths."""
    catalogs = folder / "catalogs"
    catalogs.mkdir(exist_ok=True)
    for source in (EXAMPLES / "catalogs").iterdir():
        (catalogs / source.name).write_bytes(source.read_bytes())
    paths = {"tmp": folder}
    if case.design is not None:
        paths["design"] = folder / "design.yaml"
        paths["design"].write_text(case.design, encoding="utf-8")
    if case.catalog is not None:
        paths["catalog"] = folder / "motors.yaml"
        paths["catalog"].write_text(case.catalog, encoding="utf-8")
    for name, content in case.extra_files.items():
        target = folder / name
        if isinstance(content, bytes):
            target.write_bytes(content)
        else:
            target.write_text(content, encoding="utf-8")
    return paths


def run_case(case: Case, folder: Path) -> subprocess.CompletedProcess[str]:
    """Run a case in ``folder`` and assert the answer every bad input must get."""
    paths = case_files(case, folder)
    args = [a.format(**{k: str(v) for k, v in paths.items()}) for a in case.args]
    inputs = {p: p.read_bytes() for p in folder.rglob("*") if p.is_file()}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = run_cli(*args)
    assert_clean_answer(result, case.exit_code, case.words)
    assert not caught, [str(w.message) for w in caught]
    for path, content in inputs.items():
        assert path.read_bytes() == content, f"{path.name} was changed"
    return result


def assert_clean_answer(result: subprocess.CompletedProcess[str], exit_code: int,
                        words: tuple[str, ...] = ()) -> None:
    """The exit code, the words (case-insensitive) in stderr, no traceback, nothing non-finite."""
    shown = f"stdout:\n{result.stdout[-2000:]}\nstderr:\n{result.stderr[-2000:]}"
    assert result.returncode == exit_code, shown
    assert "Traceback" not in result.stderr, shown
    assert "Warning:" not in result.stderr, shown  # RuntimeWarning:, UserWarning: ...
    for word in words:
        assert word.lower() in result.stderr.lower(), f"{word!r} not in stderr\n{shown}"
    if exit_code == 2:
        errors = [line for line in result.stderr.splitlines() if line.startswith("error:")]
        assert len(errors) == 1, shown
        assert result.stdout == "", shown
    else:
        assert not NON_FINITE.search(result.stdout), shown


# ---------------------------------------------------------------- linkage readings (issue 14)
# A four-bar driven from its rocker and the outputs other than the slider and the rocker
# (transmission[1] of examples/four-bar-rocker-driven.yaml, of the press for the
# slider-crank); run with the field cases (tests/test_bad_inputs_fields.py).

_ROCKER = "four-bar-rocker-driven.yaml"
_STAGE = "transmission[1]"


def _linkage_case(id: str, example: str, set: dict[str, Any], words: tuple[str, ...],
                  fields: tuple[str, ...]) -> Case:
    return Case(id, design=edited(example, set=set), words=("design.yaml:", *words),
                fields=fields)


LINKAGE_READINGS = [
    _linkage_case("four-bar-driven-link-coupler", _ROCKER, {f"{_STAGE}.driven_link": "coupler"},
                  (f"{_STAGE}.driven_link", "crank", "rocker"),
                  ("transmission[four_bar].driven_link",)),
    _linkage_case("four-bar-output-slider", _ROCKER, {f"{_STAGE}.output": "slider_position"},
                  (f"{_STAGE}.output", "rocker_angle", "coupler_angle", "crank_angle"),
                  ("transmission[four_bar].output",)),
    _linkage_case("four-bar-rocker-driven-output-rocker", _ROCKER,
                  {f"{_STAGE}.output": "rocker_angle"},
                  (f"{_STAGE}.output", "with the motor on the rocker", "crank_angle"),
                  ("transmission[four_bar].output",)),
    _linkage_case("four-bar-rocker-swing-beyond-its-range", _ROCKER,
                  {"task.displacement": "-90 deg"},
                  ("task.displacement", "the rocker would move", "beyond its range"),
                  ("transmission[four_bar].driven_link",)),
    _linkage_case("slider-crank-output-rocker", "press-slider-crank.yaml",
                  {f"{_STAGE}.output": "rocker_angle"},
                  (f"{_STAGE}.output", "slider_position", "rod_angle"),
                  ("transmission[slider_crank].output",)),
    _linkage_case("slider-crank-rod-angle-with-a-mass", "press-slider-crank.yaml",
                  {f"{_STAGE}.output": "rod_angle"},
                  ("load.mass", "rotary", "takes 'inertia'"),
                  ("transmission[slider_crank].output",)),
]


def assert_well_formed(cases: list[Case]) -> None:
    """Case ids unique, and every field a case names a field of the input models."""
    from sizer.io.schema.fields import input_fields

    assert len({c.id for c in cases}) == len(cases)
    assert {f for c in cases for f in c.fields} <= set(input_fields())
