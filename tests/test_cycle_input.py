"""``cycle:`` in design files (issue 12): the segments read into sizer.model.cycle's
dataclasses in SI, and every mistake answered by one located message (file, line, field),
exit code 2, through the CLI as the other bad inputs are (tests/bad_input_cases.py).

The SI values are written from the units' definitions (1 rpm = 2 pi / 60 rad/s,
1 kg*cm^2 = 1e-4 kg*m^2, 50 /min = 50 / 60 s^-1), not from the loader's output.
"""

from __future__ import annotations

import copy
import math
from pathlib import Path
from typing import Any

import pytest
import yaml
from bad_input_cases import EXAMPLES, Case, run_case
from jsonschema import Draft202012Validator
from pydantic import ValidationError

from sizer.errors import UserError
from sizer.io.cycle import BOUNDARY_SPEED_FAMILIES, has_boundary_form, meets_accelerations
from sizer.io.loader import design_schema, load_design, load_design_data
from sizer.io.schema.inputs import DesignFile
from sizer.model.cycle import Dwell, Move, Run, SegmentLoad, ShareRule
from sizer.model.domain import Task

ROTARY: dict[str, Any] = {
    "name": "rotary cycle",
    "cycle": {"segments": [
        {"move": {"displacement": "90 deg", "duration": "0.3 s", "name": "index"}},
        {"dwell": {"duration": "0.2 s", "name": "rest"}},
    ]},
    "load": {"inertia": "0.01 kg*m^2"},
    "motors": "book-examples",
}
"""A rotary cycle whose durations are all fixed: index 90 deg in 0.3 s, rest 0.2 s."""

LINEAR: dict[str, Any] = {
    "name": "linear cycle",
    "cycle": {"closed": True, "segments": [
        {"move": {"displacement": "100 mm", "duration": "0.3 s", "end_speed": "0.5 m/s",
                  "law": "trapezoidal(alpha=1/3)", "name": "approach"}},
        {"run": {"speed": "0.5 m/s", "duration": "0.2 s", "name": "glue"}},
        {"move": {"displacement": "-200 mm", "start_speed": "500 mm/s", "law": "poly5",
                  "name": "back"}},
        {"dwell": {"duration": "0.1 s"}},
    ]},
    "load": {"mass": "5 kg"},
    "motors": "book-examples",
}
"""A closed linear cycle: 100 mm to 0.5 m/s, a 0.2 s run at 0.5 m/s (100 mm), 200 mm back
from 0.5 m/s to rest (free), a dwell."""


def edit(base: dict[str, Any], changes: dict[str, Any] | None = None,
         delete: tuple[str, ...] = ()) -> dict[str, Any]:
    """A copy of ``base`` with dotted paths set (``cycle.segments[0].move.law``) or deleted."""
    data = copy.deepcopy(base)
    for path, value in [*(changes or {}).items(), *((p, _DELETE) for p in delete)]:
        parts = [int(p) if p.isdigit() else p
                 for p in path.replace("[", ".").replace("]", "").split(".")]
        target = data
        for part in parts[:-1]:
            target = target[part]
        if value is _DELETE:
            del target[parts[-1]]
        else:
            target[parts[-1]] = value
    return data


_DELETE = object()


def text(data: dict[str, Any]) -> str:
    return yaml.safe_dump(data, sort_keys=False, allow_unicode=True)


def write(tmp_path: Path, data: dict[str, Any] | str) -> Path:
    path = tmp_path / "design.yaml"
    path.write_text(data if isinstance(data, str) else text(data), encoding="utf-8")
    return path


def error_of(tmp_path: Path, data: dict[str, Any]) -> UserError:
    with pytest.raises(UserError) as caught:
        load_design(write(tmp_path, data))
    return caught.value


def line_of(source: str, fragment: str) -> int:
    return next(i for i, line in enumerate(source.splitlines(), 1) if fragment in line)


RPM = 2 * math.pi / 60


# ------------------------------------------------------------------ what loads


def test_the_two_examples_load_to_their_cycles() -> None:
    index = load_design(EXAMPLES / "indexing-duty-cycle.yaml")
    cycle = index.cycle
    assert cycle is not None and not cycle.linear and not cycle.closed
    assert cycle.share is ShareRule.SQRT_DISPLACEMENT and cycle.cycle_time is None
    assert [type(s) for s in cycle.segments] == [Move, Dwell, Move, Dwell]
    assert [s.name for s in cycle.segments] == ["index 1", "check", "index 2", "press"]
    assert cycle.segments[0].displacement == pytest.approx(math.pi / 2, rel=1e-15)
    assert cycle.segments[2].displacement == pytest.approx(math.pi, rel=1e-15)
    assert cycle.free == (0, 2) and cycle.minimize
    assert cycle.segments[3].load == SegmentLoad(torque=6.0)
    assert cycle.fixed_time == pytest.approx(0.7, rel=1e-15)
    assert index.task == Task(displacement=cycle.segments[0].displacement, duration=None,
                              dwell=0.0, return_move=False, linear=False)
    assert index.machine_cycle is cycle and index.motors  # the example catalog

    lift = load_design(EXAMPLES / "vertical-pick-and-place.yaml", default_motors=True)
    cycle = lift.cycle
    assert cycle is not None and cycle.linear and cycle.closed
    assert cycle.minimize_segment == "lift" and cycle.free == (2,) and cycle.minimize
    down, pick, up, place = cycle.segments
    assert (down.displacement, down.duration) == (-0.15, 0.25)
    assert up.displacement == 0.15 and up.duration is None
    assert up.load == SegmentLoad(inertia=2.0)  # 2 kg; its weight from the incline
    assert down.load.is_zero and pick.load.is_zero and place.load.is_zero
    assert cycle.net_displacement == 0.0
    assert lift.task.linear and lift.task.duration is None
    assert lift.load.torque == pytest.approx(4 * 9.80665, rel=1e-12)  # the carriage's weight
    assert lift.warnings == () and index.warnings == ()


def test_a_task_design_has_no_cycle_and_loads_as_before() -> None:
    design = load_design(EXAMPLES / "indexing-table.yaml")
    assert design.cycle is None
    assert design.task == Task(displacement=math.pi / 2, duration=0.25, dwell=0.35)


def test_units_as_datasheets_write_them(tmp_path: Path) -> None:
    data = {"cycle": {"share": "weights", "rate": "50 /min", "segments": [
        {"move": {"displacement": "0.25 rev", "start_speed": 0, "end_speed": "30 rpm",
                  "law": "double_s(alpha=1/3, beta=1/4)", "inertia": "500 kg*cm^2",
                  "torque": "1.5 N*m", "weight": 2, "name": "speed up"}},
        {"run": {"speed": "180 deg/s", "displacement": "90 deg", "torque": "-0.5 N*m",
                 "name": "cut"}},
        {"move": {"displacement": "0.5 turn", "start_speed": "3.14159265358979 rad/s",
                  "law": "poly7", "duration": "free"}},
        {"dwell": {"duration": "free", "weight": 0.5, "torque": "2 N*m"}},
    ]}, "load": {"inertia": "0.02 kg*m^2"}, "motors": "book-examples"}
    design = load_design(write(tmp_path, data))
    cycle = design.cycle
    assert cycle is not None and not cycle.linear and cycle.share is ShareRule.WEIGHTS
    speed_up, cut, stop, rest = cycle.segments
    assert isinstance(speed_up, Move) and isinstance(cut, Run) and isinstance(rest, Dwell)
    assert speed_up.displacement == pytest.approx(math.pi / 2, rel=1e-15)
    assert speed_up.end_speed == pytest.approx(30 * RPM, rel=1e-15)
    assert speed_up.load == SegmentLoad(inertia=pytest.approx(0.05, rel=1e-15), torque=1.5)
    assert (speed_up.weight, speed_up.duration, speed_up.law) == (
        2.0, None, "double_s(alpha=1/3, beta=1/4)")
    assert cut.speed == pytest.approx(math.pi, rel=1e-15)
    assert cut.duration == pytest.approx(0.5, rel=1e-15)  # 90 deg at 180 deg/s
    assert cut.load == SegmentLoad(torque=-0.5)
    assert stop.displacement == pytest.approx(math.pi, rel=1e-15) and stop.weight == 1.0
    assert rest == Dwell(None, weight=0.5, load=SegmentLoad(torque=2.0))
    assert cycle.cycle_time == pytest.approx(60 / 50, rel=1e-15)
    assert cycle.free == (0, 2, 3) and not cycle.minimize
    assert cycle.weights() == (2.0, 0.0, 1.0, 0.5)
    assert design.task == Task(speed_up.displacement, pytest.approx(1.2, rel=1e-15),
                               linear=False)


DEG = math.pi / 180


@pytest.mark.parametrize(("axis", "given", "si"), [
    ("rotary", "500 deg/s^2", 500 * DEG), ("rotary", "-12.5 rad/s^2", -12.5),
    ("rotary", "2 rev/s^2", 4 * math.pi), ("rotary", 3, 3.0), ("rotary", "0 deg/s^2", 0.0),
    ("linear", "2 m/s^2", 2.0), ("linear", "-500 mm/s^2", -0.5), ("linear", 0.25, 0.25),
])
def test_boundary_accelerations_as_datasheets_write_them(axis: str, given: Any,
                                                         si: float) -> None:
    """A move's start and end accelerations in SI at the load; a step against the
    neighbour's (a dwell and a run are at 0) is allowed: a jerk impulse, not an error."""
    base, index = (ROTARY, 0) if axis == "rotary" else (LINEAR, 2)
    move = f"cycle.segments[{index}].move"
    data = edit(base, {f"{move}.law": "poly5" if axis == "rotary" else "poly7",
                       f"{move}.start_acceleration": given,
                       f"{move}.end_acceleration": given})
    segment = load_design_data(data).cycle.segments[index]
    assert isinstance(segment, Move)
    assert segment.start_acceleration == pytest.approx(si, rel=1e-15)
    assert segment.end_acceleration == pytest.approx(si, rel=1e-15)
    assert segment.rest_to_rest is (axis == "rotary" and si == 0.0)
    plain = load_design_data(base).cycle.segments[index]
    assert (plain.start_acceleration, plain.end_acceleration) == (0.0, 0.0)


@pytest.mark.parametrize("spec", ["poly5", "poly7", "polynomial(degree=5)", "polynomial(7)"])
def test_laws_that_meet_boundary_accelerations(spec: str) -> None:
    assert meets_accelerations(spec)
    data = edit(LINEAR, {"cycle.segments[0].move.law": spec,
                         "cycle.segments[0].move.start_acceleration": "1 m/s^2"})
    assert load_design_data(data).cycle.segments[0].start_acceleration == 1.0


@pytest.mark.parametrize("spec", ["trapezoidal(alpha=1/3)", "constant_acceleration",
                                  "double_s(alpha=1/3, beta=1/4)", "poly3", "cycloidal"])
def test_laws_that_cannot_meet_them_are_refused(spec: str, tmp_path: Path) -> None:
    assert not meets_accelerations(spec)
    at_zero = edit(LINEAR, {"cycle.segments[0].move.law": spec,
                            "cycle.segments[0].move.end_acceleration": "0 m/s^2"})
    if spec != "cycloidal":  # 0 is no acceleration: the speeds' rule alone
        assert load_design_data(at_zero).cycle.segments[0].end_acceleration == 0.0
    data = edit(ROTARY, {"cycle.segments[0].move.law": spec,
                         "cycle.segments[0].move.start_acceleration": "-100 deg/s^2"})
    error = error_of(tmp_path, data)
    assert error.field == "cycle.segments[0].move.law"
    assert error.line == line_of(text(data), "law: ")
    assert error.message.startswith(
        f"law {spec!r} cannot start or end at a non-zero acceleration; polynomials of "
        f"degree 5 and 7 can")
    assert "start_acceleration is not 0" in error.message


@pytest.mark.parametrize(("rate", "cycle_time"), [
    ("50 /min", 1.2), ("50/min", 1.2), ("50 1/min", 1.2), ("50 min^-1", 1.2),
    ("50 rpm", 1.2), ("50 cycles/min", 1.2), ("0.8 Hz", 1.25), (2, 0.5), ("3600 1/h", 1.0),
])
def test_a_rate_is_cycles_per_time(rate: Any, cycle_time: float) -> None:
    data = edit(ROTARY, {"cycle.rate": rate, "cycle.segments[1].dwell.duration": "free",
                         "cycle.share": "weights"})
    cycle = load_design_data(data).cycle
    assert cycle is not None and cycle.cycle_time == pytest.approx(cycle_time, rel=1e-14)


def test_a_linear_cycle_and_its_summary_task() -> None:
    design = load_design_data(LINEAR)
    cycle = design.cycle
    assert cycle is not None and cycle.linear and cycle.closed
    approach, glue, back, rest = cycle.segments
    assert approach.end_speed == 0.5 and glue == Run(0.5, 0.2, name="glue")
    assert back.start_speed == 0.5 and back.duration is None and back.law == "poly5"
    assert rest == Dwell(0.1)
    assert cycle.net_displacement == pytest.approx(0.0, abs=1e-15)
    assert design.task == Task(0.1, None, linear=True)  # free, no cycle time: minimized
    fixed = load_design_data(ROTARY)
    assert fixed.task == Task(math.pi / 2, 0.5)  # every duration fixed: the cycle time
    timed = load_design_data(edit(LINEAR, {"cycle.cycle_time": "1.5 s"}))
    assert timed.task == Task(0.1, 1.5, linear=True)


@pytest.mark.parametrize("share", ["equal", "displacement", "sqrt_displacement", "weights"])
def test_every_share_rule(share: str) -> None:
    cycle = load_design_data(edit(LINEAR, {"cycle.share": share})).cycle
    assert cycle is not None and cycle.share is ShareRule(share)


def test_speeds_within_the_tolerance_are_continuous(tmp_path: Path) -> None:
    close = edit(LINEAR, {"cycle.segments[0].move.end_speed": 0.5 * (1 + 4e-10)})
    assert load_design_data(close).cycle is not None
    apart = edit(LINEAR, {"cycle.segments[0].move.end_speed": 0.5 * (1 + 4e-9)})
    error = error_of(tmp_path, apart)
    assert error.field == "cycle.segments[0].move.end_speed"


def test_a_closed_cycle_within_the_tolerance(tmp_path: Path) -> None:
    # 0.1 + 0.1 - 0.2 m in floats, and 2e-10 m off (1e-9 of the largest, 0.2 m)
    near = edit(LINEAR, {"cycle.segments[2].move.displacement": -0.2 + 1e-10})
    assert load_design_data(near).cycle is not None
    far = edit(LINEAR, {"cycle.segments[2].move.displacement": -0.2 + 1e-9})
    assert error_of(tmp_path, far).field == "cycle.closed"


@pytest.mark.parametrize("spec", [
    "trapezoidal(alpha=1/3)", "trapezoidal(alpha=1/4, alpha_d=1/3)",
    "double_s(alpha=1/3, beta=1/4)", "poly3", "poly5", "poly7", "polynomial(degree=5)",
    "constant_acceleration",
])
def test_laws_with_a_boundary_speed_form(spec: str) -> None:
    assert has_boundary_form(spec)
    data = edit(LINEAR, {"cycle.segments[0].move.law": spec})
    assert load_design_data(data).cycle.segments[0].law == spec


def test_a_move_law_with_auto_is_refused(tmp_path: Path) -> None:
    error = error_of(tmp_path, edit(ROTARY, {"cycle.segments[0].move.law":
                                             "trapezoidal(alpha=auto)"}))
    assert error.field == "cycle.segments[0].move.law"
    assert "`auto` shape parameters" in str(error)


@pytest.mark.parametrize("spec", ["cycloidal", "harmonic", "modified_sinusoidal",
                                  "modified_trapezoidal", "elliptic"])
def test_laws_without_one_are_refused_only_between_speeds(spec: str, tmp_path: Path) -> None:
    assert not has_boundary_form(spec)
    assert load_design_data(edit(ROTARY, {"cycle.segments[0].move.law": spec})).cycle
    error = error_of(tmp_path, edit(LINEAR, {"cycle.segments[0].move.law": spec}))
    assert error.field == "cycle.segments[0].move.law"
    assert all(family in error.message for family in BOUNDARY_SPEED_FAMILIES)


def test_errors_are_on_the_line_of_their_field(tmp_path: Path) -> None:
    """The line of the field named, where the file has it; else of its mapping."""
    cases = [
        (edit(LINEAR, {"cycle.segments[0].move.end_speed": "0.4 m/s"}),
         "cycle.segments[0].move.end_speed", "end_speed: 0.4 m/s"),
        (edit(LINEAR, {"cycle.segments[2].move.start_speed": "0.4 m/s"}),
         "cycle.segments[2].move.start_speed", "start_speed: 0.4 m/s"),
        (edit(ROTARY, {"cycle.segments[1]": {"run": {"speed": "10 rpm"}}}),
         "cycle.segments[1].run.duration", "- run:"),
        (edit(ROTARY, {"cycle.minimize": "press"}), "cycle.minimize", "minimize: press"),
        (edit(LINEAR, {"cycle.segments[2].move.displacement": "-150 mm"}), "cycle.closed",
         "closed: true"),
        (edit(ROTARY, {"cycle.segments[0].move.mass": "2 kg"}),
         "cycle.segments[0].move.mass", "mass: 2 kg"),
        (edit(ROTARY, delete=("cycle.segments[0].move.displacement",)),
         "cycle.segments[0].move.displacement", "- move:"),
        (edit(ROTARY, {"task": {"displacement": 1, "duration": 1}}), "cycle", "cycle:"),
    ]
    for data, field, fragment in cases:
        error = error_of(tmp_path, data)
        assert (error.field, error.line) == (field, line_of(text(data), fragment)), field
        assert error.file == str(tmp_path / "design.yaml")


# ------------------------------------------------------------------ the schema


def _schema_accepts(data: Any) -> bool:
    return not list(Draft202012Validator(design_schema()).iter_errors(data))


def _model_accepts(data: Any) -> bool:
    try:
        DesignFile.model_validate(data)
    except ValidationError:
        return False
    return True


LOAD = {"inertia": 1}
MOVE = {"move": {"displacement": "90 deg"}}


@pytest.mark.parametrize(("data", "accepted"), [
    ({"cycle": {"segments": [MOVE]}, "load": LOAD}, True),
    ({"task": {"displacement": 1, "duration": 1}, "load": LOAD}, True),
    ({"task": {"displacement": 1, "duration": 1}, "cycle": {"segments": [MOVE]},
      "load": LOAD}, False),
    ({"load": LOAD}, False),
    ({"task": None, "cycle": {"segments": [MOVE]}, "load": LOAD}, False),
    ({"cycle": None, "load": LOAD}, False),
    ({"cycle": {"segments": []}, "load": LOAD}, False),
    ({"cycle": {"segments": [{}]}, "load": LOAD}, False),
    ({"cycle": {"segments": [{"move": None}]}, "load": LOAD}, False),
    ({"cycle": {"segments": [{**MOVE, "dwell": {"duration": 1}}]}, "load": LOAD}, False),
    ({"cycle": {"segments": [{"jump": {"duration": 1}}]}, "load": LOAD}, False),
    ({"cycle": {"segments": [MOVE, {"dwell": {"duration": "free"}},
                             {"run": {"speed": "1 rad/s", "duration": "1 s"}}],
                "share": "weights", "rate": "50 /min", "closed": False, "minimize": "a"},
      "load": LOAD}, True),
    ({"cycle": {"segments": [MOVE], "share": "fair"}, "load": LOAD}, False),
    ({"cycle": {"segments": [MOVE], "closed": "yes"}, "load": LOAD}, False),
    ({"cycle": {"segments": [{"dwell": {}}]}, "load": LOAD}, False),
    ({"cycle": {"segments": [{"run": {"duration": 1}}]}, "load": LOAD}, False),
])
def test_schema_and_models_agree_on_cycles(data: dict, accepted: bool) -> None:
    assert _model_accepts(data) is accepted
    assert _schema_accepts(data) is accepted


# ------------------------------------------------------------------ bad inputs, CLI

D = "design.yaml:"
S = "cycle.segments"


def case(id: str, data: dict[str, Any], words: tuple[str, ...],
         fields: tuple[str, ...]) -> Case:
    """A design's bad cycle; the words always hold the file name."""
    return Case(id, design=text(data), words=(D, *words), fields=fields)


def seg(i: int, kind: str, key: str = "") -> str:
    return f"cycle.segments[{i}].{kind}" + (f".{key}" if key else "")


FREE_DWELL = {"cycle.share": "weights", "cycle.segments[1].dwell.duration": "free"}

CYCLE = [
    case("cycle-not-a-mapping", edit(ROTARY, {"cycle": "fast"}),
         ("cycle", "expected a mapping"), ("cycle",)),
    case("cycle-null", edit(ROTARY, {"cycle": None}), ("cycle", "expected a mapping"),
         ("cycle",)),
    case("cycle-and-task", edit(ROTARY, {"task": {"displacement": 1, "duration": 1}}),
         ("cycle", "not both"), ("cycle",)),
    case("cycle-typo", edit(ROTARY, {"cycle.segmnts": []}),
         ("cycle.segmnts", "unknown field", "did you mean 'segments'"), ("cycle",)),
    case("share-unknown", edit(ROTARY, {"cycle.share": "fair"}),
         ("cycle.share", "sqrt_displacement", "weights"), ("cycle.share",)),
    case("cycle-time-and-rate", edit(ROTARY, {**FREE_DWELL, "cycle.cycle_time": "1 s",
                                              "cycle.rate": "60 /min"}),
         ("cycle.rate", "not both"), ("cycle.rate",)),
    case("rate-a-length", edit(ROTARY, {"cycle.rate": "50 m"}),
         ("cycle.rate", "expected a rate"), ("cycle.rate",)),
    case("rate-negative", edit(ROTARY, {"cycle.rate": "-50 /min"}),
         ("cycle.rate", "[1e-6, 1e6] 1/s", "got -0.833333 1/s (-50 /min)"), ("cycle.rate",)),
    case("rate-below-the-fixed-time", edit(LINEAR, {"cycle.rate": "200 /min"}),
         ("cycle.rate", "1 / rate", "leaves no time", "0.6 s"), ("cycle.rate",)),
    case("cycle-time-below-the-fixed-time", edit(LINEAR, {"cycle.cycle_time": "0.6 s"}),
         ("cycle.cycle_time", "leaves no time", "0.6 s"), ("cycle.cycle_time",)),
    case("cycle-time-not-the-fixed-time", edit(ROTARY, {"cycle.cycle_time": "1 s"}),
         ("cycle.cycle_time", "no segment is free", "0.5 s"), ("cycle.cycle_time",)),
    case("cycle-time-subnormal", edit(LINEAR, {"cycle.cycle_time": "1e-320 s"}),
         ("cycle.cycle_time", "[1e-6, 1e6] s"), ("cycle.cycle_time",)),
    case("minimize-unknown", edit(ROTARY, {"cycle.minimize": "press"}),
         ("cycle.minimize", "no segment is named 'press'", "'index', 'rest'"),
         ("cycle.minimize",)),
    case("minimize-a-fixed-segment", edit(ROTARY, {"cycle.minimize": "index"}),
         ("cycle.minimize", "fixed duration", "nothing to minimize"), ("cycle.minimize",)),
    case("minimize-with-another-free", edit(LINEAR, {"cycle.minimize": "back"},
                                            delete=(f"{S}[0].move.duration",)),
         (seg(0, "move", "duration"), "every other segment has a fixed duration"),
         ("cycle.minimize",)),
    case("minimize-and-cycle-time", edit(LINEAR, {"cycle.minimize": "back",
                                                  "cycle.cycle_time": "2 s"}),
         ("cycle.minimize", "not both"), ("cycle.minimize",)),
    case("closed-not-a-bool", edit(ROTARY, {"cycle.closed": "yes"}),
         ("cycle.closed", "expected true or false"), ("cycle.closed",)),
    case("closed-net-displacement", edit(LINEAR, {f"{S}[2].move.displacement": "-150 mm"}),
         ("cycle.closed", "sum to 0.05 m"), ("cycle.closed",)),
    case("repeat-speed", edit(ROTARY, {"cycle.segments": [
        {"run": {"speed": "30 deg/s", "duration": "1 s"}},
        {"move": {"displacement": "-30 deg", "start_speed": "30 deg/s", "law": "poly5",
                  "duration": "1 s"}}]}),
         ("cycle.segments", "a cycle repeats", "ends at 0 rad/s", "starts at 0.523599 rad/s"),
         ("cycle.segments",)),
    case("segments-empty", edit(ROTARY, {"cycle.segments": []}),
         ("cycle.segments", "at least 1 item"), ("cycle.segments",)),
    case("segments-not-a-list", edit(ROTARY, {"cycle.segments": "move"}),
         ("cycle.segments", "expected a list"), ("cycle.segments",)),
    case("segments-without-a-move", edit(ROTARY, {"cycle.segments": [
        {"dwell": {"duration": "1 s"}}]}), ("cycle.segments", "at least one move"),
         ("cycle.segments",)),
    case("segment-unknown-kind", edit(ROTARY, {f"{S}[1]": {"wait": {"duration": "1 s"}}}),
         ("cycle.segments[1]", "unknown segment kind 'wait'", "move, run, dwell"),
         ("cycle.segments",)),
    case("segment-two-kinds", edit(ROTARY, {f"{S}[1].move": {"displacement": 1}}),
         ("cycle.segments[1]", "exactly one kind", "dwell and move"), ("cycle.segments",)),
    case("segment-not-a-mapping", edit(ROTARY, {f"{S}[1]": "dwell"}),
         ("cycle.segments[1]", "one-key mapping"), ("cycle.segments",)),
    # ---- moves
    case("move-null", edit(ROTARY, {f"{S}[0]": {"move": None}}),
         ("cycle.segments[0]", "a move needs its fields"), ("cycle.segments.move",)),
    case("move-unknown-field", edit(ROTARY, {f"{S}[0].move.speed": "1 rad/s"}),
         (seg(0, "move", "speed"), "unknown field 'speed'", "start_speed"),
         ("cycle.segments.move",)),
    case("move-missing-displacement", edit(ROTARY, delete=(f"{S}[0].move.displacement",)),
         (seg(0, "move", "displacement"), "required field is missing"),
         ("cycle.segments.move.displacement",)),
    case("move-zero-displacement", edit(ROTARY, {f"{S}[0].move.displacement": "0 deg"}),
         (seg(0, "move", "displacement"), "must not be zero", "dwell"),
         ("cycle.segments.move.displacement",)),
    case("move-displacement-of-another-axis",
         edit(LINEAR, {f"{S}[2].move.displacement": "-20 deg"}),
         (seg(2, "move", "displacement"), "is an angle", "linear axis"),
         ("cycle.segments.move.displacement",)),
    case("move-displacement-out-of-range",
         edit(ROTARY, {f"{S}[0].move.displacement": "1e9 rad"}),
         (seg(0, "move", "displacement"), "[1e-6, 1e7] rad"),
         ("cycle.segments.move.displacement",)),
    case("move-duration-a-word", edit(ROTARY, {f"{S}[0].move.duration": "soon"}),
         (seg(0, "move", "duration"), "expected a time"), ("cycle.segments.move.duration",)),
    case("move-duration-negative", edit(ROTARY, {f"{S}[0].move.duration": "-0.3 s"}),
         (seg(0, "move", "duration"), "[1e-6, 1e6] s"), ("cycle.segments.move.duration",)),
    case("move-law-unknown", edit(ROTARY, {f"{S}[0].move.law": "sinusoid"}),
         (seg(0, "move", "law"), "unknown law 'sinusoid'"), ("cycle.segments.move.law",)),
    case("move-law-without-boundary-speeds",
         edit(LINEAR, {f"{S}[0].move.law": "cycloidal"}),
         (seg(0, "move", "law"), "no form with boundary speeds", "constant_acceleration"),
         ("cycle.segments.move.law",)),
    case("move-start-speed-a-force", edit(LINEAR, {f"{S}[2].move.start_speed": "5 N"}),
         (seg(2, "move", "start_speed"), "expected a linear speed", "a linear axis"),
         ("cycle.segments.move.start_speed",)),
    case("move-start-speed-jump", edit(LINEAR, {f"{S}[2].move.start_speed": "0.4 m/s"}),
         (seg(2, "move", "start_speed"), "speed jumps", "0.5 m/s", "0.4 m/s"),
         ("cycle.segments.move.start_speed",)),
    case("move-end-speed-jump", edit(LINEAR, {f"{S}[0].move.end_speed": "0.4 m/s"}),
         (seg(0, "move", "end_speed"), "speed jumps", "'approach'", "'glue'"),
         ("cycle.segments.move.end_speed",)),
    case("move-end-speed-into-a-dwell", edit(ROTARY, {f"{S}[0].move.end_speed": "10 rpm",
                                                      f"{S}[0].move.law": "poly5"}),
         (seg(0, "move", "end_speed"), "speed jumps", "1.0472 rad/s", "dwell is at 0"),
         ("cycle.segments.move.end_speed",)),
    case("move-end-speed-out-of-range", edit(ROTARY, {f"{S}[0].move.end_speed": "1e7 rad/s"}),
         (seg(0, "move", "end_speed"), "[1e-6, 1e6] rad/s"),
         ("cycle.segments.move.end_speed",)),
    case("move-start-acceleration-a-speed",
         edit(LINEAR, {f"{S}[2].move.start_acceleration": "1 m/s"}),
         (seg(2, "move", "start_acceleration"), "expected a linear acceleration",
          "a linear axis"), ("cycle.segments.move.start_acceleration",)),
    case("move-start-acceleration-a-bool", edit(ROTARY, {f"{S}[0].move.start_acceleration": True}),
         (seg(0, "move", "start_acceleration"), "expected a number or a quantity",
          "500 deg/s^2"), ("cycle.segments.move.start_acceleration",)),
    case("move-end-acceleration-of-another-axis",
         edit(ROTARY, {f"{S}[0].move.end_acceleration": "2 m/s^2"}),
         (seg(0, "move", "end_acceleration"), "expected an angular acceleration",
          "a rotary axis"), ("cycle.segments.move.end_acceleration",)),
    case("move-end-acceleration-out-of-range",
         edit(ROTARY, {f"{S}[0].move.end_acceleration": "1e10 rad/s^2",
                       f"{S}[0].move.law": "poly5"}),
         (seg(0, "move", "end_acceleration"), "0 or of magnitude in [1e-6, 1e9] rad/s^2",
          "got 1e10 rad/s^2"), ("cycle.segments.move.end_acceleration",)),
    case("move-end-acceleration-subnormal",
         edit(LINEAR, {f"{S}[0].move.end_acceleration": "1e-320 m/s^2"}),
         (seg(0, "move", "end_acceleration"), "[1e-6, 1e8] m/s^2"),
         ("cycle.segments.move.end_acceleration",)),
    case("move-law-without-boundary-accelerations",
         edit(LINEAR, {f"{S}[0].move.end_acceleration": "2 m/s^2"}),
         (seg(0, "move", "law"), "law 'trapezoidal(alpha=1/3)' cannot start or end at a "
          "non-zero acceleration; polynomials of degree 5 and 7 can"),
         ("cycle.segments.move.law",)),
    case("move-weight-without-weights", edit(ROTARY, {f"{S}[0].move.weight": 2}),
         (seg(0, "move", "weight"), "share: weights", "'equal'"),
         ("cycle.segments.move.weight",)),
    case("move-weight-zero", edit(ROTARY, {"cycle.share": "weights",
                                           f"{S}[0].move.weight": 0}),
         (seg(0, "move", "weight"), "[1e-6, 1e6]"), ("cycle.segments.move.weight",)),
    case("move-inertia-on-a-linear-axis",
         edit(LINEAR, {f"{S}[0].move.inertia": "0.1 kg*m^2"}),
         (seg(0, "move", "inertia"), "takes 'mass', not 'inertia'"),
         ("cycle.segments.move.inertia",)),
    case("move-mass-on-a-rotary-axis", edit(ROTARY, {f"{S}[0].move.mass": "2 kg"}),
         (seg(0, "move", "mass"), "takes 'inertia', not 'mass'"),
         ("cycle.segments.move.mass",)),
    case("move-torque-on-a-linear-axis", edit(LINEAR, {f"{S}[0].move.torque": "1 N*m"}),
         (seg(0, "move", "torque"), "takes 'force', not 'torque'"),
         ("cycle.segments.move.torque",)),
    case("move-force-out-of-range", edit(LINEAR, {f"{S}[0].move.force": "1e12 N"}),
         (seg(0, "move", "force"), "[1e-9, 1e9] N"), ("cycle.segments.move.force",)),
    case("move-name-empty", edit(ROTARY, {f"{S}[0].move.name": " "}),
         (seg(0, "move", "name"), "must not be empty"), ("cycle.segments.move.name",)),
    # ---- runs
    case("run-unknown-field", edit(LINEAR, {f"{S}[1].run.time": "1 s"}),
         (seg(1, "run", "time"), "unknown field 'time'"), ("cycle.segments.run",)),
    case("run-zero-speed", edit(LINEAR, {f"{S}[1].run.speed": "0 m/s"}),
         (seg(1, "run", "speed"), "zero speed", "dwell"), ("cycle.segments.run.speed",)),
    case("run-speed-missing", edit(LINEAR, delete=(f"{S}[1].run.speed",)),
         (seg(1, "run", "speed"), "required field is missing"), ("cycle.segments.run.speed",)),
    case("run-duration-and-displacement", edit(LINEAR, {f"{S}[1].run.displacement": "0.1 m"}),
         (seg(1, "run", "displacement"), "not both"), ("cycle.segments.run.displacement",)),
    case("run-without-an-extent", edit(LINEAR, delete=(f"{S}[1].run.duration",)),
         (seg(1, "run", "duration"), "needs its duration"), ("cycle.segments.run.duration",)),
    case("run-duration-free", edit(LINEAR, {f"{S}[1].run.duration": "free"}),
         (seg(1, "run", "duration"), "expected a time"), ("cycle.segments.run.duration",)),
    case("run-displacement-against-the-speed",
         edit(LINEAR, {f"{S}[1].run.displacement": "-100 mm"},
              delete=(f"{S}[1].run.duration",)),
         (seg(1, "run", "displacement"), "sign of its speed"),
         ("cycle.segments.run.displacement",)),
    case("run-inertia-on-a-linear-axis", edit(LINEAR, {f"{S}[1].run.inertia": 0.1}),
         (seg(1, "run", "inertia"), "takes 'mass', not 'inertia'"),
         ("cycle.segments.run.inertia",)),
    case("run-mass-negative", edit(LINEAR, {f"{S}[1].run.mass": "-1 kg"}),
         (seg(1, "run", "mass"), "0 or in [1e-6, 1e7] kg"), ("cycle.segments.run.mass",)),
    case("run-torque-on-a-linear-axis", edit(LINEAR, {f"{S}[1].run.torque": "1 N*m"}),
         (seg(1, "run", "torque"), "takes 'force', not 'torque'"),
         ("cycle.segments.run.torque",)),
    case("run-force-a-torque", edit(LINEAR, {f"{S}[1].run.force": "2 N*m"}),
         (seg(1, "run", "force"), "expected a force"), ("cycle.segments.run.force",)),
    case("run-name-a-list", edit(LINEAR, {f"{S}[1].run.name": ["glue"]}),
         (seg(1, "run", "name"), "expected text"), ("cycle.segments.run.name",)),
    # ---- dwells
    case("dwell-unknown-field", edit(ROTARY, {f"{S}[1].dwell.inertia": 1}),
         (seg(1, "dwell", "inertia"), "unknown field 'inertia'"), ("cycle.segments.dwell",)),
    case("dwell-free-without-weights", edit(ROTARY, {f"{S}[1].dwell.duration": "free"}),
         (seg(1, "dwell", "duration"), "free dwell", "share: weights"),
         ("cycle.segments.dwell.duration",)),
    case("dwell-duration-missing", edit(ROTARY, delete=(f"{S}[1].dwell.duration",)),
         (seg(1, "dwell", "duration"), "required field is missing"),
         ("cycle.segments.dwell.duration",)),
    case("dwell-weight-without-weights", edit(ROTARY, {f"{S}[1].dwell.weight": 2}),
         (seg(1, "dwell", "weight"), "share: weights"), ("cycle.segments.dwell.weight",)),
    case("dwell-torque-on-a-linear-axis", edit(LINEAR, {f"{S}[3].dwell.torque": "1 N*m"}),
         (seg(3, "dwell", "torque"), "takes 'force', not 'torque'"),
         ("cycle.segments.dwell.torque",)),
    case("dwell-force-on-a-rotary-axis", edit(ROTARY, {f"{S}[1].dwell.force": "10 N"}),
         (seg(1, "dwell", "force"), "takes 'torque', not 'force'"),
         ("cycle.segments.dwell.force",)),
    case("dwell-name-taken", edit(ROTARY, {f"{S}[1].dwell.name": "index"}),
         (seg(1, "dwell", "name"), "'index' is taken", "unique"),
         ("cycle.segments.dwell.name",)),
]
CASES = CYCLE
"""Every field of ``cycle:`` has a case (tests/test_bad_inputs_fields.py counts them)."""


@pytest.mark.parametrize("case", CASES, ids=str)
def test_bad_cycle(case: Case, tmp_path: Path) -> None:
    run_case(case, tmp_path)


def test_case_ids_are_unique() -> None:
    ids = [c.id for c in CASES]
    assert len(ids) == len(set(ids))


def test_every_field_of_cycle_has_a_case() -> None:
    from sizer.io.schema.fields import input_fields

    fields = {f for f in input_fields() if f == "cycle" or f.startswith("cycle.")}
    named = {f for c in CASES for f in c.fields}
    assert sorted(fields - named) == [] and sorted(named - fields) == []


def test_bare_numbers_far_from_plausible_warn(tmp_path: Path) -> None:
    data = edit(ROTARY, {"cycle.segments[0].move.duration": 250,
                         "cycle.segments[0].move.displacement": 90,
                         "cycle.segments[1].dwell.duration": 120})
    source = text(data)
    path = tmp_path / "design.yaml"
    assert load_design(write(tmp_path, data)).warnings == (
        f"{path}:{line_of(source, 'duration: 250')}: cycle.segments[0].move.duration: "
        f"bare number 250 read as 250 s; write '250 ms' if that was meant",
        f"{path}:{line_of(source, 'displacement: 90')}: cycle.segments[0].move.displacement: "
        f"bare number 90 read as 90 rad (14.3 turns); write '90 deg' if that was meant",
        f"{path}:{line_of(source, 'duration: 120')}: cycle.segments[1].dwell.duration: "
        f"bare number 120 read as 120 s; write '120 ms' if that was meant",
    )
    linear = edit(LINEAR, {"cycle.closed": False, "cycle.segments[1].run.duration": 5,
                           "cycle.segments[2].move.displacement": -20})
    design = load_design_data(linear)  # -20 m, not rad, on a linear axis: no warning
    assert design.cycle.segments[2].displacement == -20.0 and design.warnings == ()


def test_the_documented_cycle_loads() -> None:
    import re

    doc = (Path(__file__).resolve().parents[1] / "docs" / "input-files.md").read_text()
    block = re.search(r"```yaml\n(cycle:.*?)```", doc, re.S)
    assert block is not None
    data = {**yaml.safe_load(block.group(1)), "load": {"inertia": "0.05 kg*m^2"},
            "motors": "book-examples"}
    cycle = load_design_data(data).cycle
    assert cycle is not None and [type(s) for s in cycle.segments] == [Move, Dwell, Move,
                                                                        Run, Move]
    assert cycle.free == (2, 4) and cycle.cycle_time == 2.0
    assert cycle.fixed_time == pytest.approx(0.7, rel=1e-15)
    assert cycle.segments[3].speed == pytest.approx(math.pi, rel=1e-15)  # 30 rpm
    assert cycle.segments[4].start_speed == pytest.approx(math.pi, rel=1e-15)  # 180 deg/s


def test_the_documented_boundary_acceleration_loads() -> None:
    import re

    doc = (Path(__file__).resolve().parents[1] / "docs" / "input-files.md").read_text()
    block = re.search(r"```yaml\n(\s*- move:[^`]*end_acceleration[^`]*)```", doc)
    assert block is not None
    hand_over = yaml.safe_load(block.group(1))[0]
    data = {"cycle": {"segments": [
        hand_over, {"run": {"speed": "60 rpm", "duration": "0.1 s"}},
        {"move": {"displacement": "45 deg", "start_speed": "60 rpm", "law": "poly7",
                  "duration": "0.2 s"}}]},
        "load": {"inertia": "0.05 kg*m^2"}, "motors": "book-examples"}
    move = load_design_data(data).cycle.segments[0]
    assert move.end_acceleration == pytest.approx(500 * DEG, rel=1e-15)
    assert move.end_speed == pytest.approx(60 * RPM, rel=1e-15) and move.law == "poly5"
