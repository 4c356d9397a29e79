"""Fuzzed inputs for the CLI: mutated example designs and catalogs, and the checks every run passes.

Shared by ``tests/test_cli_fuzz.py`` (a fixed seed, a modest count) and ``tools/fuzz_inputs.py``
(thousands of cases in worker processes). A case is a :class:`FuzzInput`: the files of a folder
(an example design or catalog, mutated) and one command over them. :func:`fuzz_inputs` is the
hypothesis strategy; :func:`run_input` runs a case in-process and returns its :class:`Outcome`,
whose ``failures`` list every broken invariant (issue 10):

- exit code 0, 1 or 2 only; no traceback, no exception out of the CLI;
- no Python warning (recorded, whatever the filters) and no ``Warning:`` on stderr;
- with exit code 0 or 1, no ``nan``/``inf`` printed, and JSON that ``json.loads`` reads while
  refusing ``NaN`` and ``Infinity``;
- with exit code 2, nothing on stdout and exactly one ``error:`` line, naming an input file
  (or the option at fault);
- no input file changed; no run longer than :data:`HANG_LIMIT` seconds in the suite,
  :data:`TIME_LIMIT` in tools/fuzz_inputs.py.

The mutations work on the parsed YAML (deleted keys, swapped types, wrong units, extreme numbers,
truncated and duplicated lists, swapped fields, random strings) and then, sometimes, on the text
(a truncation, a broken line). They never bring in an ``auto`` law or ``minimize``, which make
some designs take seconds (the examples' slow designs are left out or cut down for the same
reason: ``auto`` laws removed, ``--motor`` naming one motor).
"""

from __future__ import annotations

import contextlib
import copy
import json
import math
import re
import time
import traceback
import warnings
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path
from typing import Any

import yaml
from hypothesis import strategies as st

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
BUNDLED = ROOT / "sizer" / "catalogs"
TIME_LIMIT = 10.0
"""Seconds a run may take (issue 10: no hang over 10 s): judged by tools/fuzz_inputs.py,
whose report is the measurement (issue 11: no test asserts a time)."""
HANG_LIMIT = 120.0
"""What the test suite calls a hang: far above any run, so that a shared, loaded machine
never fails a test for being slow."""

NON_FINITE = re.compile(r"(?<![A-Za-z_])(nan|-?inf(inity)?)(?![A-Za-z_])", re.IGNORECASE)
"""A ``nan`` or ``inf`` token (the pattern of tests/bad_input_cases.py)."""


# --- the bases: fast example designs and catalogs -------------------------------------------

@dataclass(frozen=True)
class Base:
    """An example to mutate: which file of the case folder it is, and the commands to run."""

    name: str
    source: Path
    target: str
    """Where the mutated file goes in the case folder ('design.yaml', 'catalogs/...')."""
    commands: tuple[tuple[str, ...], ...]
    """Arguments; ``{tmp}`` is the case folder."""
    design: str | None = None
    """For a catalog base sized through a design: the example design (relative to examples/)."""
    edit: Any = None
    """A function making the parsed example fast (e.g. removing its ``auto`` laws)."""
    design_edit: Any = None
    """For a base sized through a design: the function making that design (default: the
    indexing table's, or the gearbox catalog's)."""
    extra_files: tuple[tuple[str, Path], ...] = ()
    """Unmutated files the case folder also needs: (relative path, source)."""

    @property
    def is_csv(self) -> bool:
        """A CSV base is mutated as text, row by row (it is not YAML)."""
        return self.target.endswith(".csv")


_SIZE = ("size", "{tmp}/design.yaml")
_CHECK = ("check", "{tmp}/design.yaml")
DESIGN_COMMANDS: tuple[tuple[str, ...], ...] = (
    _SIZE, (*_SIZE, "--format", "json"), (*_SIZE, "--format", "csv"),
    (*_SIZE, "--all", "--format", "md"), (*_SIZE, "--format", "csv", "--output", "{tmp}/out.csv"),
    _CHECK, (*_CHECK, "--format", "json"), (*_CHECK, "{tmp}/good.yaml"),
)
"""``good.yaml`` is the example unmutated: ``check`` must still check it after a bad file."""


def _fast_indexing_table(data: Any) -> Any:
    """indexing-table.yaml without its ``auto`` law (6 s of search with friction)."""
    if isinstance(data, dict) and isinstance(data.get("laws"), list):
        data["laws"] = [law for law in data["laws"] if "auto" not in str(law)]
    return data


def _gearbox_catalog_table(data: Any) -> Any:
    """The fast indexing table choosing its gearbox from a (mutated) gearbox catalog."""
    data = _fast_indexing_table(data)
    data["transmission"] = {"type": "gearbox", "catalog": "gearboxes.yaml"}
    data["laws"] = ["modified_sinusoidal", "poly5"]
    return data


def _bases() -> list[Base]:
    bases = []
    one_motor = ("--motor", "HG-KN43J")
    for path in sorted((EXAMPLES / "book").glob("*.yaml")) + sorted(EXAMPLES.glob("vendor-*.yaml")):
        bases.append(Base(str(path.relative_to(EXAMPLES)), path, "design.yaml", DESIGN_COMMANDS))
    table = EXAMPLES / "indexing-table.yaml"
    bases.append(Base("indexing-table.yaml (no auto law)", table, "design.yaml",
                      tuple((*c, *one_motor) if c[0] == "size" else c for c in DESIGN_COMMANDS),
                      edit=_fast_indexing_table))
    validate = (("catalog", "validate", "{tmp}/motors.yaml"),)
    servo = sorted((EXAMPLES / "catalogs").glob("*-servo.yaml"))
    for path in [*servo, *sorted(BUNDLED.glob("*.yaml"))]:
        bases.append(Base(f"catalog {path.name}", path, "motors.yaml", (
            *validate,
            ("size", "{tmp}/design.yaml", "--catalog", "{tmp}/motors.yaml"),
            ("size", "{tmp}/design.yaml", "--catalog", "{tmp}/motors.yaml", "--format", "json"),
        ), design="book/ex6_3-vmax4.yaml"))
    bases.append(Base("catalog example-servo.yaml (used by indexing-table)",
                      EXAMPLES / "catalogs" / "example-servo.yaml", "catalogs/example-servo.yaml",
                      (_SIZE, (*_SIZE, "--format", "json"), _CHECK),
                      design="indexing-table.yaml"))
    bases.append(Base("gearbox catalog example-gearboxes.yaml",
                      EXAMPLES / "catalogs" / "example-gearboxes.yaml", "gearboxes.yaml",
                      ((*_SIZE, *one_motor), (*_SIZE, *one_motor, "--format", "json")),
                      design="indexing-table.yaml"))
    return bases


BASES = _bases()


# --- the bases of the input kinds of issues 12-31 (issue 32) ---------------------------------

def _commands(design: str, motor: str | None,
              *more: tuple[str, ...]) -> tuple[tuple[str, ...], ...]:
    """size (table, json, csv to a file), check and ``more`` over ``design``, one motor."""
    one = ("--motor", motor) if motor else ()
    size = ("size", design, *one)
    return (size, (*size, "--format", "json"),
            (*size, "--format", "csv", "--output", "{tmp}/out.csv"),
            ("check", design, *one, "--format", "json"), *more)


def _one_law(data: Any) -> Any:
    """A design made fast: its first law only (the law lists are what cost)."""
    if isinstance(data, dict) and isinstance(data.get("laws"), list) and data["laws"]:
        data["laws"] = data["laws"][:1]
    return data


def _with_drives(data: Any) -> Any:
    """Book example 6.3 on the Siemens 1FT7 motors with their drive catalog."""
    data["motors"] = ["siemens-1ft7"]
    data["drives"] = ["drives.yaml"]
    data.pop("check", None)  # it names the book's motor
    return data


def _new_kind_bases() -> list[Base]:
    design = "{tmp}/design.yaml"
    segments = ("segments", design, "--format", "json")
    cases = (  # example, one motor, the commands beyond size and check
        ("pick-and-place.yaml", "SGM7J-02A", (*segments, "--motor", "SGM7J-02A")),
        ("flying-saw.yaml", "SGM7A-15A", (*segments, "--motor", "SGM7A-15A")),
        ("indexing-duty-cycle.yaml", "HG-KN43J", (*segments, "--motor", "HG-KN43J")),
        ("press-slider-crank.yaml", "HG-KN43J", (*segments, "--motor", "HG-KN43J")),
        ("press-slider-crank-cycle.yaml", "HG-KN43J", (*segments, "--motor", "HG-KN43J")),
        ("four-bar-coupler.yaml", "HG-KN43J", None),
        ("four-bar-rocker-driven.yaml", "HG-KN43J", None),
        ("pusher-via-points.yaml", "SGM7J-02A", (*segments, "--motor", "SGM7J-02A")),
        ("rotary-knife.yaml", "HG-KN43J", (*segments, "--motor", "HG-KN43J")),
        ("indexing-table-vibration.yaml", "HG-KN43J",
         ("vibration", design, "--points", "5", "--format", "json")),
    )
    knife = (("cams/rotary-knife.csv", EXAMPLES / "cams" / "rotary-knife.csv"),)
    # flying-saw's first law cannot join its boundary speeds: it keeps its four laws
    bases = [Base(name if name == "flying-saw.yaml" else f"{name} (first law)", EXAMPLES / name,
                  "design.yaml", _commands(design, motor, *((more,) if more else ())),
                  edit=None if name == "flying-saw.yaml" else _one_law,
                  extra_files=knife if name == "rotary-knife.yaml" else ())
             for name, motor, more in cases]
    packer = EXAMPLES / "machines" / "two-axis-packer.yaml"
    bases.append(Base("machine two-axis-packer.yaml", packer, "machines/machine.yaml",
                      (("size", "{tmp}/machines/machine.yaml"),
                       ("size", "{tmp}/machines/machine.yaml", "--format", "json"))))
    bases.append(Base("drive catalog siemens-s120.yaml", BUNDLED / "drives" / "siemens-s120.yaml",
                      "drives.yaml", _commands(design, None), design="book/ex6_3-vmax4.yaml",
                      design_edit=_with_drives))
    bases.append(Base("cam table rotary-knife.csv", EXAMPLES / "cams" / "rotary-knife.csv",
                      "cams/rotary-knife.csv",
                      (*_commands(design, "HG-KN43J"),
                       ("law", "{kind: cam_table, file: '{tmp}/cams/rotary-knife.csv'}",
                        "--duration", "0.5 s", "--format", "json")),
                      design="rotary-knife.yaml", design_edit=_one_law))
    return bases


NEW_KIND_BASES = _new_kind_bases()


@cache
def _parsed(path: Path) -> Any:
    return yaml.safe_load(path.read_text(encoding="utf-8"))


@cache
def _companion_design(base: Base) -> str | None:
    """The design text a catalog base is sized through (made fast), or None."""
    if base.design is None:
        return None
    data = copy.deepcopy(_parsed(EXAMPLES / base.design))
    if base.design_edit is not None:
        data = base.design_edit(data)
    elif base.name.startswith("gearbox"):
        data = _gearbox_catalog_table(data)
    else:
        data = _fast_indexing_table(data)
    return _dump(data)


def _dump(data: Any) -> str:
    return yaml.safe_dump(data, sort_keys=False, allow_unicode=True, width=1000)


# --- a case --------------------------------------------------------------------------------

@dataclass(frozen=True)
class FuzzInput:
    """One fuzz case: the base it mutates, the mutations, the files written and the command."""

    base: str
    mutations: tuple[str, ...]
    files: dict[str, str]
    """Relative path in the case folder -> text (written as UTF-8, surrogates passed)."""
    args: tuple[str, ...]

    def command(self, folder: Path | str = "{tmp}") -> list[str]:
        """The CLI arguments with the case folder filled in."""
        return [a.replace("{tmp}", str(folder)) for a in self.args]

    def describe(self) -> str:
        """A short description: base, command, mutations."""
        return f"{self.base} | sizer {' '.join(self.args)} | " + "; ".join(self.mutations)

    def to_json(self) -> dict[str, Any]:
        return {"base": self.base, "mutations": list(self.mutations), "files": self.files,
                "args": list(self.args)}

    @classmethod
    def from_json(cls, data: dict[str, Any]) -> FuzzInput:
        return cls(data["base"], tuple(data["mutations"]), dict(data["files"]), tuple(data["args"]))


# --- the values a mutation puts in ---------------------------------------------------------

EXTREME_NUMBERS = (
    "0", "-0.0", "-1", "1e-320", "5e-324", "1e-200", "1e-15", "1e15", "1e301", "1e308",
    "1.7976931348623157e308", "-1e308", "1e400", "-1e400", "1" + "0" * 400, "nan", "NaN", ".nan",
    "inf", "-inf", ".inf", "-.inf", "Infinity", "1_000", "0x10", "1/0", "2**1000",
)
UNITS = (
    "", "s", "ms", "rad", "deg", "rev", "mm", "m", "rpm", "rev/min", "rad/s", "deg/s", "m/s",
    "rad/s^2", "m/s^2", "rad/s^3", "N*m", "mN*m", "N", "kg", "kg*m^2", "kg*cm^2", "g*cm^2",
    "N*m*s/rad", "%", "kg/m^3", "W", "kelvin", "degC", "1/s", "Hz", "arcmin", "furlong",
)
NASTY_TEXTS = (
    "", " ", "\t", "~", "null", "yes", "no", "-", "[]", "{}", ":", "#", "N*m", "rpm", "%",
    "cycloidal", "poly5(", "trapezoidal(alpha=)", "trapezoidal(alpha=1e999)",
    "double_s(alpha=1/3, beta=1e-320)", "trapezoidal(alpha=1/3, alpha=1/4)", "book-examples",
    "catalogs/nope.yaml", "../../../../etc/passwd", "/dev/null", "gearbox", "direct", "belt",
    "ball_screw", "max", "rms", "book", "linear", "HG-KN43J", "ex6_4", "\x1b[31mred\x1b[0m",
    "a\rb", "\x00", "\u202e", "∞", "1 / 0 s", "1 s**s", "1 " + "m*" * 40 + "m", "x" * 500,
)
TYPE_SWAPS = st.one_of(
    st.none(), st.booleans(), st.integers(-3, 10**6),
    st.floats(allow_nan=False, allow_infinity=False),
    st.sampled_from(NASTY_TEXTS), st.builds(list), st.builds(dict),
    st.lists(st.integers(0, 3), max_size=3),
    st.dictionaries(st.sampled_from(["a", "id", "value", "speed", "torque"]),
                    st.sampled_from([1, "x", None]), max_size=2),
)
NUMBER = re.compile(r"[-+]?(\d+(\.\d*)?|\.\d+)([eE][-+]?\d+)?")


def _is_slow(value: Any) -> bool:
    return isinstance(value, str) and ("auto" in value or "minimize" in value)


def data_paths(data: Any, prefix: tuple[Any, ...] = ()) -> list[tuple[Any, ...]]:
    """Every path into the data (mapping keys and list indices), the root excluded."""
    out = [prefix] if prefix else []
    if isinstance(data, dict):
        for key, value in data.items():
            out += data_paths(value, (*prefix, key))
    elif isinstance(data, list):
        for index, value in enumerate(data):
            out += data_paths(value, (*prefix, index))
    return out


def _get(data: Any, path: tuple[Any, ...]) -> Any:
    for part in path:
        data = data[part]
    return data


def _name(path: tuple[Any, ...]) -> str:
    out = ""
    for part in path:
        out += f"[{part}]" if isinstance(part, int) else (f".{part}" if out else str(part))
    return out or "<root>"


def _extreme_in_text(draw: st.DrawFn, text: str) -> str | None:
    """The text with one of its numbers replaced by an extreme one (None without numbers)."""
    numbers = list(NUMBER.finditer(text))
    if not numbers:
        return None
    match = draw(st.sampled_from(numbers))
    return text[:match.start()] + draw(st.sampled_from(EXTREME_NUMBERS)) + text[match.end():]


def _extreme_value(draw: st.DrawFn, value: Any) -> Any:
    """An extreme number in place of a number, keeping a quantity's unit."""
    if isinstance(value, str):
        changed = _extreme_in_text(draw, value)
        return changed if changed is not None else draw(st.sampled_from(EXTREME_NUMBERS))
    choice = draw(st.sampled_from(EXTREME_NUMBERS))
    try:  # a YAML number where the example has one (10**400 stays an int)
        return int(choice) if re.fullmatch(r"-?\d+", choice) else float(choice)
    except ValueError:
        return choice


def _wrong_unit(draw: st.DrawFn, value: Any) -> Any:
    """The value's unit replaced (or a unit put on a bare number)."""
    unit = draw(st.sampled_from(UNITS))
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return f"{value} {unit}".strip()
    if isinstance(value, str):
        match = NUMBER.match(value.strip())
        if match:
            return f"{match.group(0)} {unit}".strip()
    return f"{draw(st.sampled_from(['1', '0.5', '3000', '1e-3']))} {unit}".strip()


@st.composite
def mutated(draw: st.DrawFn, data: Any) -> tuple[Any, list[str]]:
    """The parsed YAML with 1 to 3 mutations, and their descriptions."""
    data = copy.deepcopy(data)
    done: list[str] = []
    for _ in range(draw(st.sampled_from([1, 1, 1, 2, 2, 3]))):
        paths = data_paths(data)
        if not paths:
            break
        path = draw(st.sampled_from(paths))
        parent = _get(data, path[:-1])
        key = path[-1]
        value = parent[key]
        action = draw(st.sampled_from(
            ["delete", "type", "type", "unit", "unit", "unit", "extreme", "extreme", "extreme",
             "extreme", "extreme", "extreme", "truncate", "duplicate", "swap", "text", "add"]))
        where = _name(path)
        if action == "delete":
            del parent[key]
            done.append(f"delete {where}")
            continue
        if action == "truncate" or action == "duplicate":
            lists = [p for p in paths if isinstance(_get(data, p), list) and _get(data, p)]
            if not lists:
                continue
            path = draw(st.sampled_from(lists))
            items = _get(data, path)
            if action == "truncate":
                keep = draw(st.integers(0, len(items) - 1))
                del items[keep:]
                done.append(f"truncate {_name(path)} to {keep} item(s)")
            else:
                index = draw(st.integers(0, len(items) - 1))
                items.insert(index, copy.deepcopy(items[index]))
                done.append(f"duplicate {_name(path)}[{index}]")
            continue
        if action == "swap":
            siblings = [k for k in (parent if isinstance(parent, dict) else range(len(parent)))
                        if k != key]
            if not siblings:
                continue
            other = draw(st.sampled_from(siblings))
            parent[key], parent[other] = parent[other], parent[key]
            done.append(f"swap {where} and {_name((*path[:-1], other))}")
            continue
        if action == "add":
            target = parent if isinstance(parent, dict) else None
            if isinstance(value, dict):
                target = value
            if target is None:
                continue
            new_key = draw(st.sampled_from(["inertia", "mass", "friction", "torque", "ratio",
                                            "efficiency", "max_speed", "extra", "id", "name"]))
            new_value = copy.deepcopy(draw(st.one_of(TYPE_SWAPS, st.sampled_from(EXTREME_NUMBERS))))
            target[new_key] = new_value
            done.append(f"add {new_key}: {new_value!r} beside {where}")
            continue
        if action == "type":
            new = draw(TYPE_SWAPS)
        elif action == "unit":
            new = _wrong_unit(draw, value)
        elif action == "extreme":
            new = _extreme_value(draw, value)
        else:
            new = draw(st.one_of(st.text(max_size=12), st.sampled_from(NASTY_TEXTS)))
        if _is_slow(new):
            continue
        parent[key] = copy.deepcopy(new)  # a drawn value is never shared between cases
        done.append(f"{action} {where} = {new!r}"[:200])
    return data, done


GARBAGE = (":", "- ", "[", "]", "{", "}", "&a ", "*a", "!!str ", "!!float ", "\t", "'", '"', "#",
           "? ", "|", ">", "%", "@", "`", "<<: ", "!!python/object:os.system ", "\x00", "\ufeff",
           "\r", "\x85", "\\")


@st.composite
def text_mutated(draw: st.DrawFn, text: str) -> tuple[str, list[str]]:
    """The YAML text truncated or with a broken line."""
    action = draw(st.sampled_from(["truncate", "line", "line"]))
    if action == "truncate":
        at = draw(st.integers(0, max(0, len(text) - 1)))
        return text[:at], [f"text truncated to {at} of {len(text)} characters"]
    lines = text.splitlines(keepends=True) or [""]
    index = draw(st.integers(0, len(lines) - 1))
    how = draw(st.sampled_from(["insert", "duplicate", "delete", "replace"]))
    if how == "insert":
        at = draw(st.integers(0, len(lines[index])))
        garbage = draw(st.one_of(st.sampled_from(GARBAGE), st.text(max_size=4)))
        lines[index] = lines[index][:at] + garbage + lines[index][at:]
        note = f"line {index + 1}: {garbage!r} inserted at column {at + 1}"
    elif how == "duplicate":
        lines.insert(index, lines[index])
        note = f"line {index + 1} duplicated"
    elif how == "delete":
        del lines[index]
        note = f"line {index + 1} deleted"
    else:
        new = draw(st.text(max_size=30))
        lines[index] = new + "\n"
        note = f"line {index + 1} replaced by {new!r}"
    out = "".join(lines)
    return out, [note]


CSV_CELLS = (*EXTREME_NUMBERS, "", " ", "x", "1,5", "0;1", "1e", "--1", "1 m", "\x00",
             "deg", "[deg]", "t [parsecs]", "q [", "\ufeff1", '"1"', '"', "#")


@st.composite
def csv_mutated(draw: st.DrawFn, text: str) -> tuple[str, list[str]]:
    """A cam table's text with 1 to 3 edits: a cell replaced (an extreme number, a wrong unit
    in the header, garbage), a row deleted, duplicated, swapped with the next, cut short or
    given an extra cell, the separator changed, or the text truncated."""
    lines = text.splitlines(keepends=True)
    done: list[str] = []
    for _ in range(draw(st.sampled_from([1, 1, 2, 3]))):
        if not lines:
            break
        index = draw(st.integers(0, len(lines) - 1))
        action = draw(st.sampled_from(["cell", "cell", "cell", "delete", "duplicate", "swap",
                                       "short", "long", "separator", "truncate"]))
        row = lines[index].rstrip("\r\n").split(",")
        if action == "cell":
            column = draw(st.integers(0, len(row) - 1))
            row[column] = draw(st.one_of(st.sampled_from(CSV_CELLS), st.text(max_size=6)))
            lines[index] = ",".join(row) + "\n"
            done.append(f"line {index + 1} column {column} = {row[column]!r}")
        elif action == "delete":
            del lines[index]
            done.append(f"line {index + 1} deleted")
        elif action == "duplicate":
            lines.insert(index, lines[index])
            done.append(f"line {index + 1} duplicated")
        elif action == "swap" and index + 1 < len(lines):
            lines[index], lines[index + 1] = lines[index + 1], lines[index]
            done.append(f"lines {index + 1} and {index + 2} swapped")
        elif action == "short":
            lines[index] = row[0] + "\n"
            done.append(f"line {index + 1} cut to one cell")
        elif action == "long":
            lines[index] = ",".join([*row, "1"]) + "\n"
            done.append(f"line {index + 1} given a third cell")
        elif action == "separator":
            separator = draw(st.sampled_from([";", "\t", " ", "|"]))
            lines = [line.replace(",", separator) for line in lines]
            done.append(f"separator {separator!r}")
        elif action == "truncate":
            keep = draw(st.integers(0, len(lines) - 1))
            del lines[keep:]
            done.append(f"truncated to {keep} line(s)")
    return "".join(lines), done


@st.composite
def fuzz_inputs(draw: st.DrawFn, bases: list[Base] | None = None) -> FuzzInput:
    """A mutated example and one command over it (the strategy of the CLI fuzz)."""
    base = draw(st.sampled_from(bases or BASES))
    if base.is_csv:
        text, changes = draw(csv_mutated(base.source.read_text(encoding="utf-8")))
        return base_input(base, draw(st.sampled_from(base.commands)), text, tuple(changes))
    data = base_data(base)
    mutations: list[str] = []
    if draw(st.integers(0, 9)) < 8:
        data, mutations = draw(mutated(data))
    text = _dump(data)
    if not mutations or draw(st.integers(0, 4)) == 0:
        text, more = draw(text_mutated(text))
        mutations += more
    return base_input(base, draw(st.sampled_from(base.commands)), text, tuple(mutations))


def base_data(base: Base) -> Any:
    """The parsed example of a base, made fast (a copy: mutate it freely)."""
    data = copy.deepcopy(_parsed(base.source))
    return base.edit(data) if base.edit is not None else data


def base_input(base: Base, args: tuple[str, ...], text: str | None = None,
               mutations: tuple[str, ...] = ()) -> FuzzInput:
    """A case of ``base`` with ``text`` as its file (default: the example unmutated)."""
    if text is None:
        text = base.source.read_text(encoding="utf-8") if base.is_csv else _dump(base_data(base))
    files = {base.target: text}
    for name, source in base.extra_files:
        files[name] = source.read_text(encoding="utf-8")
    if "{tmp}/good.yaml" in args:
        files["good.yaml"] = _dump(base_data(base))
    companion = _companion_design(base)
    if companion is not None:
        files["design.yaml"] = companion
    return FuzzInput(base.name, mutations, files, args)


# --- the commands over laws alone: their options mutated -----------------------------------

OPTION_COMMANDS: tuple[tuple[str, ...], ...] = (
    ("spectrum", "cycloidal", "poly5", "--max-ft", "8", "--points", "50", "--format", "json"),
    ("spectrum", "trapezoidal(alpha=1/3)", "--displacement", "90 deg", "--duration", "0.25 s",
     "--max-ft", "4", "--points", "20", "--format", "csv"),
    ("spectrum", "cycloidal", "--period", "2", "--max-ft", "6"),
    ("spectrum", "poly7", "--order", "3", "--max-ft", "6", "--points", "30"),
    ("law", "double_s(alpha=1/3, beta=1/4)", "--displacement", "90 deg", "--duration",
     "0.25 s", "--samples", "40", "--start-position", "10 deg", "--format", "json"),
    ("law", "{kind: cubic_spline, times: auto, positions: [0, 0.3, 0.8, 1]}", "--displacement",
     "20 mm", "--duration", "1 s", "--samples", "30", "--format", "csv"),
    ("laws", "--law", "modified_trapezoidal", "--law",
     "{kind: bspline, degree: 3, points: [[0, 0], [0.3, 0.1], [0.7, 0.9], [1, 1]], "
     "start: {velocity: 0}, end: {velocity: 0}}", "--format", "json"),
)
"""Commands whose inputs are all on the command line: the option values are mutated."""


@st.composite
def option_inputs(draw: st.DrawFn) -> FuzzInput:
    """A command over laws alone with one or two of its values replaced: an extreme number
    (unit kept), a wrong or glued unit, a nasty text, a spec with an extreme parameter."""
    args = list(draw(st.sampled_from(OPTION_COMMANDS)))
    values = [i for i, a in enumerate(args) if i > 0 and not a.startswith("--")]
    done = []
    for _ in range(draw(st.sampled_from([1, 1, 2]))):
        index = draw(st.sampled_from(values))
        how = draw(st.sampled_from(["extreme", "extreme", "unit", "glued", "text"]))
        value = args[index]
        if how == "extreme":
            new = _extreme_in_text(draw, value) or draw(st.sampled_from(EXTREME_NUMBERS))
        elif how == "unit":
            new = str(_wrong_unit(draw, value))
        elif how == "glued":
            new = value.replace(" ", "")
        else:
            new = draw(st.one_of(st.sampled_from(NASTY_TEXTS), st.text(max_size=8)))
        if _is_slow(new) or new.startswith("-"):  # an option name is typer's business
            continue
        args[index] = new
        done.append(f"{how} {args[0]} argument {index} = {new!r}"[:200])
    return FuzzInput(f"{args[0]} options", tuple(done), {}, tuple(args))


# --- running a case and checking the invariants --------------------------------------------

@dataclass
class Outcome:
    """What a run gave, and the invariants it broke (empty: a clean answer)."""

    returncode: int | None
    stdout: str
    stderr: str
    seconds: float
    failures: list[str] = field(default_factory=list)
    """One line per broken invariant, its class first ('crash: ...', 'warning: ...')."""


def write_case(case: FuzzInput, folder: Path) -> None:
    """The example catalogs, then the case's files, into ``folder``."""
    catalogs = folder / "catalogs"
    catalogs.mkdir(parents=True, exist_ok=True)
    for source in (EXAMPLES / "catalogs").iterdir():
        (catalogs / source.name).write_bytes(source.read_bytes())
    for name, text in case.files.items():
        target = folder / name
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(text.encode("utf-8", errors="surrogatepass"))


def _where(tb: traceback.StackSummary) -> str:
    """The innermost frame in sizer/ (else the innermost), as 'sizer/x.py:12 in f'."""
    frames = [f for f in tb if "/sizer/" in f.filename] or list(tb)
    if not frames:
        return "?"
    frame = frames[-1]
    name = frame.filename
    if "/sizer/" in name:
        name = "sizer/" + name.rsplit("/sizer/", 1)[1]
    return f"{name}:{frame.lineno} in {frame.name}"


_TB_FILE = re.compile(r'File "([^"]+)", line (\d+), in (\S+)')


def _printed_traceback(stderr: str) -> str:
    """'Type at sizer/x.py:12 in f' from a traceback printed on stderr."""
    frames = _TB_FILE.findall(stderr)
    inner = [f for f in frames if "/sizer/" in f[0]] or frames
    where = "?"
    if inner:
        name, line, func = inner[-1]
        if "/sizer/" in name:
            name = "sizer/" + name.rsplit("/sizer/", 1)[1]
        where = f"{name}:{line} in {func}"
    last = [ln for ln in stderr.strip().splitlines()
            if re.match(r"^\w[\w.]*(Error|Exception|Exit)\b", ln)]
    kind = last[-1].split(":")[0] if last else "Traceback"
    return f"{kind} at {where}"


_QUOTED = re.compile(r"'[^'\n]*'")
"""A quoted value from the input (findings and messages quote what the file says)."""


def _without_echoes(stdout: str, case: FuzzInput) -> str:
    """stdout without the input's own texts echoed (a name 'nan', a finding quoting 'inf N*m')."""
    out = _QUOTED.sub("''", stdout)
    for value in _echoable(case):
        out = out.replace(value, "")
    return out


def _echoable(case: FuzzInput) -> list[str]:
    """The input's strings holding a non-finite token, and its non-finite floats as messages
    quote them ('got inf', 'inf is not a finite number')."""
    found: set[str] = set()

    def walk(node: Any) -> None:
        if isinstance(node, dict):
            for key, value in node.items():
                walk(key)
                walk(value)
        elif isinstance(node, list):
            for value in node:
                walk(value)
        elif isinstance(node, str) and NON_FINITE.search(node):
            found.add(node)
        elif isinstance(node, float) and not math.isfinite(node):
            found.update((f"got {node}", f"{node} is not a finite"))

    for text in case.files.values():
        with contextlib.suppress(Exception):  # an unreadable file echoes nothing
            walk(yaml.safe_load(text))
    return sorted(found, key=len, reverse=True)


def _refuse_constant(name: str) -> None:
    raise ValueError(f"non-finite JSON constant {name}")


def check_result(case: FuzzInput, folder: Path, returncode: int, stdout: str, stderr: str,
                 caught: list[warnings.WarningMessage], before: dict[Path, bytes],
                 seconds: float, time_limit: float = HANG_LIMIT) -> list[str]:
    """The invariants a run broke, one line each, its class first."""
    failures = []
    if returncode not in (0, 1, 2):
        failures.append(f"exit code {returncode}")
    if "Traceback" in stderr:
        failures.append(f"traceback printed: {_printed_traceback(stderr)}")
    for w in caught:
        source = Path(w.filename)
        name = "sizer/" + str(w.filename).rsplit("/sizer/", 1)[1] if "/sizer/" in str(w.filename) \
            else source.name
        message = re.sub(r"\d+(\.\d+)?", "N", str(w.message))[:80]
        failures.append(f"warning: {w.category.__name__}: {message} at {name}:{w.lineno}")
    if "Warning:" in stderr and not caught:
        failures.append("warning printed on stderr")
    if returncode == 2:
        errors = [line for line in stderr.splitlines() if line.startswith("error:")]
        if len(errors) != 1:
            failures.append(f"exit 2 with {len(errors)} 'error:' lines")
        elif not _names_input(errors[0], case):
            failures.append("exit 2: the error line names no input file or option")
        several = "{tmp}/good.yaml" in case.args
        if stdout and not several:
            failures.append("exit 2 with output on stdout")
        if several and not stdout:
            failures.append("check stopped at the bad file: good.yaml not checked")
    elif returncode in (0, 1):
        match = NON_FINITE.search(_without_echoes(stdout, case))
        if match:
            fmt = _format(case.args)
            failures.append(f"non-finite '{match.group(0).lower()}' printed by {case.args[0]} "
                            f"--format {fmt}")
        if _format(case.args) == "json":
            try:
                json.loads(stdout, parse_constant=_refuse_constant)
            except ValueError as error:
                failures.append(f"invalid JSON: {type(error).__name__}: "
                                f"{re.sub(r'[0-9]+', 'N', str(error))[:60]}")
    for path, content in before.items():
        if not path.exists() or path.read_bytes() != content:
            failures.append(f"input changed: {path.relative_to(folder)}")
    if seconds > time_limit:
        failures.append(f"slow: over {time_limit:g} s")
    return list(dict.fromkeys(failures))


def _format(args: tuple[str, ...]) -> str:
    return args[args.index("--format") + 1] if "--format" in args else "table"


def _names_input(line: str, case: FuzzInput) -> bool:
    names = {Path(name).name for name in case.files}
    names |= {p.name for p in (EXAMPLES / "catalogs").glob("*.yaml")}
    names |= {p.name for p in BUNDLED.glob("*.yaml")} | {p.stem for p in BUNDLED.glob("*.yaml")}
    return any(name in line for name in names) or "--" in line or "SPEC" in line


@cache
def warm_up() -> None:
    """Size a book example once: the first run's imports (seconds) are no case's time."""
    from cli_run import run_cli

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run_cli("size", str(EXAMPLES / "book" / "ex6_4.yaml"), "--format", "json")


def run_input(case: FuzzInput, folder: Path, time_limit: float = HANG_LIMIT) -> Outcome:
    """Write the case into ``folder``, run its command in-process, check every invariant
    (a run over ``time_limit`` seconds is a failure)."""
    from cli_run import run_cli

    warm_up()
    write_case(case, folder)
    before = {p: p.read_bytes() for p in folder.rglob("*") if p.is_file()}
    start = time.perf_counter()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            result = run_cli(*case.command(folder))
        except BaseException as error:  # a crash is what the fuzz looks for
            if isinstance(error, KeyboardInterrupt):
                raise
            seconds = time.perf_counter() - start
            tb = traceback.extract_tb(error.__traceback__)
            text = "".join(traceback.format_exception(error))
            return Outcome(None, "", text, seconds,
                           [f"crash: {type(error).__name__} at {_where(tb)}"])
    seconds = time.perf_counter() - start
    failures = check_result(case, folder, result.returncode, result.stdout, result.stderr,
                            list(caught), before, seconds, time_limit)
    return Outcome(result.returncode, result.stdout, result.stderr, seconds, failures)


def failure_class(line: str) -> str:
    """The class of a failure line: the line itself (the messages are already generic)."""
    return line
