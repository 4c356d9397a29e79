"""Mutated design files: load_design succeeds or raises UserError, never anything else."""

from __future__ import annotations

import copy
import os
import tempfile
from pathlib import Path
from typing import Any

import yaml
from fuzz_cases import data_paths
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from sizer.errors import UserError
from sizer.io import load_catalog, load_design
from sizer.model.domain import Design

DESIGN = """\
name: Indexing table
task:
  displacement: 90 deg
  duration: 0.25 s
  dwell: 0.15 s
  return: true
load:
  inertia: 0.35 kg*m^2
  damping: 0.01 N*m*s/rad
  friction: 0.2 N*m
  torque: 0 N*m
transmission:
  type: gearbox
  ratio: 10
  efficiency: 95 %
  inertia: 1.2 kg*cm^2
laws: [cycloidal, poly5, "trapezoidal(alpha=1/3)", "double_s(alpha=auto, beta=auto)"]
motors:
  - book-examples
  - id: EX-100
    inertia: 0.26 kg*cm^2
    continuous_torque: 0.32 N*m
    peak_torque: 0.95 N*m
    rated_speed: 3000 rpm
    max_speed: 6000 rpm
    continuous_curve: [[0 rpm, 0.32 N*m], [3000 rpm, 0.30 N*m], [6000 rpm, 0.2 N*m]]
    intermittent_curve:
      - {speed: 0 rpm, torque: 0.95 N*m}
      - [6000 rpm, 0.5 N*m]
check:
  motor: EX-100
  law: cycloidal
limits:
  torque_margin: 10 %
  speed_margin: 5 %
  inertia_ratio: 10
  max_acceleration: 500 rad/s^2
  max_jerk: 1e5 rad/s^3
  thermal_speed: max
"""

DATA = yaml.safe_load(DESIGN)

# SIZER_FUZZ_EXAMPLES=5000 for a longer hunt; the suite default stays fast.
FUZZ = settings(max_examples=int(os.environ.get("SIZER_FUZZ_EXAMPLES", "200")), deadline=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])

# Values a hand-edited file might hold in the wrong place.
quantity_texts = st.sampled_from([
    "0", "-1", "1e400", "nan", "inf", "-inf", ".5", "90 deg", "200 mm", "3000 rpm", "3000 N*m",
    "0.5 N*m", "12 kg", "10 %", "1.2 kg*cm^2", "1 m/s^2", "minimize", "auto", "max", "rms",
    "cycloidal", "trapezoidal(alpha=1/3)", "double_s(alpha=auto, beta=1e999)", "poly5(",
    "book-examples", "../nope.yaml", "/", "", " ", "deg", "1 / 0 s", "1 s**s", "1e5 rad/s^3",
    "10 kelvin", "3 degC", "5 percent", "1 rev", "0x10", "1_000", "∞", "1 N*m*s/rad",
    "EX-100", "gearbox", "direct", "belt", "\x00", "a" * 300, "1 " + "m*" * 40 + "m",
])
scalars = st.one_of(
    st.none(), st.booleans(), st.integers(-10**30, 10**30),
    st.floats(allow_nan=True, allow_infinity=True), quantity_texts, st.text(max_size=20),
)
values = st.recursive(
    scalars,
    lambda inner: st.one_of(st.lists(inner, max_size=4),
                            st.dictionaries(st.one_of(st.text(max_size=8), quantity_texts),
                                            inner, max_size=4)),
    max_leaves=8,
)


PATHS = data_paths(DATA)


def _set(data: Any, path: tuple[Any, ...], value: Any, *, drop: bool = False) -> None:
    parent = data
    for part in path[:-1]:
        parent = parent[part]
    if drop:
        del parent[path[-1]]
    else:
        parent[path[-1]] = value


@st.composite
def mutated_data(draw: st.DrawFn) -> Any:
    data = copy.deepcopy(DATA)
    for _ in range(draw(st.integers(1, 3))):
        paths = data_paths(data)
        if not paths:
            break
        path = draw(st.sampled_from(paths))
        action = draw(st.sampled_from(["drop", "replace", "replace", "add"]))
        try:
            if action == "drop":
                _set(data, path, None, drop=True)
            elif action == "replace":
                _set(data, path, draw(values))
            else:
                parent = data
                for part in path[:-1]:
                    parent = parent[part]
                if isinstance(parent, dict):
                    parent[draw(quantity_texts)] = draw(values)
                else:
                    parent.append(draw(values))
        except (KeyError, IndexError, TypeError):
            pass
    return data


def _load(text: str | bytes) -> Design | None:
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "design.yaml"
        if isinstance(text, bytes):
            path.write_bytes(text)
        else:
            path.write_text(text, encoding="utf-8", errors="surrogatepass")
        try:
            return load_design(path)
        except UserError as error:
            assert error.file == str(path) or error.file is None or "catalog" in str(error) \
                or error.file.endswith(".yaml"), error
            assert error.message and "\n" not in error.message, repr(error.message)
            return None


def test_the_unmutated_design_loads():
    assert _load(DESIGN) is not None


@FUZZ
@given(mutated_data())
def test_mutated_values_give_user_errors_only(data):
    text = yaml.safe_dump(data, allow_unicode=True, sort_keys=False)
    _load(text)


@FUZZ
@given(st.data())
def test_mutated_text_gives_user_errors_only(data):
    lines = DESIGN.splitlines(keepends=True)
    for _ in range(data.draw(st.integers(1, 3))):
        index = data.draw(st.integers(0, len(lines) - 1))
        action = data.draw(st.sampled_from(["insert", "duplicate", "delete", "replace"]))
        if action == "insert":
            line = lines[index]
            at = data.draw(st.integers(0, len(line)))
            garbage = data.draw(st.one_of(
                st.text(max_size=5),
                st.sampled_from([":", "- ", "[", "]", "{", "}", "&a ", "*a", "!!str ", "\t",
                                 "'", '"', "#", "? ", "|", ">", "%", "@", "`", "<<: ",
                                 "!!python/object:os.system ", "\x00", "\ufeff", "\r"]),
            ))
            lines[index] = line[:at] + garbage + line[at:]
        elif action == "duplicate":
            lines.insert(index, lines[index])
        elif action == "delete" and len(lines) > 1:
            del lines[index]
        else:
            lines[index] = data.draw(st.text(max_size=30)) + "\n"
    _load("".join(lines))


@FUZZ
@given(st.binary(max_size=200))
def test_random_bytes_give_user_errors_only(raw):
    _load(DESIGN.encode()[:100] + raw)


@FUZZ
@given(st.lists(st.tuples(st.sampled_from(["inertia", "continuous_torque", "peak_torque",
                                           "rated_speed", "max_speed", "damping",
                                           "continuous_curve", "intermittent_curve",
                                           "price", "mass", "id", "source"]),
                          values), max_size=3))
def test_mutated_catalog_gives_user_errors_only(changes):
    motor: dict[str, Any] = {"id": "A", "inertia": "1 kg*cm^2", "continuous_torque": 1,
                             "peak_torque": 3, "rated_speed": "3000 rpm"}
    for key, value in changes:
        motor[key] = value
    text = yaml.safe_dump({"motors": [motor]}, allow_unicode=True)
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "catalog.yaml"
        path.write_text(text)
        try:
            load_catalog(path)
        except UserError as error:
            assert error.file == str(path)
            assert error.line is not None
