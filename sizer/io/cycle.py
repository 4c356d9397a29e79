"""A design's ``cycle:`` into a :class:`sizer.model.cycle.Cycle` (SI), checked (issue 12).

The checks that span fields or segments, each a UserError at the file, line and field
(``cycle.segments[2].move.end_speed``): one axis for every displacement and speed, the
load-change fields of that axis, a run's speed and extent, speed continuity between
segments, a closed cycle, the time budget (cycle time or rate against the fixed
durations), ``minimize``, the share rule, boundary speeds only with laws that have a
form with boundary speeds, and boundary accelerations only with laws that meet them
(polynomials of degree 5 and 7). A move between boundary speeds may also take a law of
fixed shape (a law defined by data without such a form: the span of an exported cam
table or segment file) at a fixed ``duration`` at which its end slopes are the move's
speeds v T/h (and its end accelerations a T^2/h where given), within
sizer.model.cycle.SHAPE_TOLERANCE; else an error at its ``law`` with the numbers.
Accelerations need not be continuous between segments: a step is a jerk impulse, which
the reports mark.

    motion_of(task, cycle, laws, source) -> Cycle, warnings
    build_cycle(given, source)           -> Cycle
"""

from __future__ import annotations

import math
from typing import Any

from pydantic import BaseModel

from sizer.errors import UserError
from sizer.io.data_law_rules import (
    LocatedLaw,
    check_cycle_laws,
    check_task_laws,
    law_displacement,
    master_duration,
    moving_ends,
    scale_warnings,
)
from sizer.io.schema.cycle_inputs import CycleInput, DwellInput, MoveInput, RunInput
from sizer.io.schema.inputs import TaskInput
from sizer.io.schema.inputs_base import axis_range, convert_in, given_text, show_value
from sizer.io.schema.ranges import RANGES, check_range, number_text
from sizer.io.yaml_source import YamlSource, format_path
from sizer.laws.choice import law_choice
from sizer.model.cycle import (
    Cycle,
    Dwell,
    Move,
    Run,
    Segment,
    SegmentLoad,
    ShareRule,
    Task,
    boundary_laws,
    from_task,
    shorthand_task,
)
from sizer.units import parse_displacement, to_si

SPEED_TOLERANCE = 1e-9
"""Relative: consecutive speeds are equal when they differ by at most this fraction of the
larger magnitude (two exact zeros are equal)."""

CLOSURE_TOLERANCE = 1e-9
"""Relative: a closed cycle's net displacement is at most this fraction of its largest
segment displacement."""

TIME_TOLERANCE = 1e-9
"""Relative: a cycle time without free segments equals the sum of the durations."""

BOUNDARY_SPEED_FAMILIES = ("trapezoidal", "double_s", "polynomial", "constant_acceleration")
"""The law families with a form between non-zero boundary speeds, for the messages
(sizer.laws.boundary_speeds decides: polynomials of degree 3, 5 and 7)."""


def has_boundary_form(spec: str) -> bool:
    """Whether law ``spec`` has a form with non-zero start and end speeds."""
    from sizer.laws.boundary_speeds import has_boundary_form as decides

    return decides(spec)


def meets_accelerations(spec: str) -> bool:
    """Whether law ``spec`` can start and end at non-zero accelerations."""
    from sizer.laws.boundary_speeds import meets_accelerations as decides

    return decides(spec)


Path_ = tuple[Any, ...]


class _Axis:
    """The axis of a cycle (from its first move) and the conversions that depend on it."""

    def __init__(self, source: YamlSource, linear: bool, first: Path_) -> None:
        self.source, self.linear, self.first = source, linear, first
        self.friction_coefficient, self.incline = _guides(source) if linear else (0.0, 0.0)
        self.name = "linear" if linear else "rotary"
        self.why = (f"a {self.name} axis: the first move's displacement "
                    f"({format_path(first)}) is {'a length' if linear else 'an angle'}")

    def quantity(self, model: type[BaseModel], key: str, value: Any, at: Path_) -> float:
        """``value`` of ``model.key`` in SI on this axis; a UserError at ``at`` if not."""
        try:
            return convert_in(value, axis_range(model, key, self.linear))
        except ValueError as error:
            text = str(error)
            if text.startswith("expected"):
                text += f" ({self.why})"
            raise self.source.error(text, at) from None

    def load_change(self, model: type[BaseModel], given: Any, at: Path_,
                    keys: tuple[str, ...] = ("inertia", "torque")) -> SegmentLoad:
        """The segment's added inertia (or mass) and torque (or force) on this axis."""
        pairs = {"inertia": "mass", "torque": "force"}
        values = {}
        for key in keys:
            rotary, linear = key, pairs[key]
            right, wrong = (linear, rotary) if self.linear else (rotary, linear)
            if getattr(given, wrong) is not None:
                raise self.source.error(f"takes '{right}', not '{wrong}' ({self.why})",
                                        (*at, wrong))
            value = getattr(given, right)
            values[key] = 0.0 if value is None else self.quantity(model, right, value,
                                                                  (*at, right))
        return SegmentLoad(inertia=values.get("inertia", 0.0), torque=values.get("torque", 0.0),
                           friction_coefficient=self.friction_coefficient, incline=self.incline)


WEIGHT_MATCH = 0.02
"""A segment's force within this share of its part's weight along the axis looks like it."""


def weight_twice_warnings(cycle: Cycle, source: YamlSource) -> list[str]:
    """A located warning per move or run of a linear, inclined axis whose added ``mass``
    comes with a ``force`` equal to that mass's weight along the axis: the weight follows
    from the design's incline (SegmentLoad), so it would count twice.

    Not yet among :func:`motion_of`'s warnings: examples/vertical-pick-and-place.yaml
    still gives its part's weight as a force (and a test asserts it loads without a
    warning); once the example drops it, add these to the warnings there."""
    from sizer.io.plausibility import warning_text
    from sizer.mechanics.loads import GRAVITY

    out = []
    for i, segment in enumerate(cycle.segments):
        if isinstance(segment, Dwell) or not cycle.linear:
            continue
        added = segment.load
        weight = added.inertia * GRAVITY * math.sin(added.incline)
        if added.inertia <= 0.0 or weight == 0.0 or added.torque == 0.0:
            continue
        if abs(added.torque - weight) > WEIGHT_MATCH * abs(weight):
            continue
        kind = "move" if isinstance(segment, Move) else "run"
        out.append(warning_text(source, ("cycle", "segments", i, kind, "force"), (
            f"{number_text(added.torque)} N is the added {number_text(added.inertia)} kg's "
            f"weight along the axis, m g sin(incline) = {number_text(weight)} N, which the "
            f"mass already brings with the design's incline (and its friction with the "
            f"design's friction_coefficient): give `force` only for what acts on top, or the "
            f"weight counts twice (docs/machine-cycles.md)")))
    return out


def _guides(source: YamlSource) -> tuple[float, float]:
    """The design's friction coefficient and incline (``load:``, 0 if not given): a part
    a segment picks up on a linear axis rides the same guides (SegmentLoad). The section
    was validated with the design; a document without one (a cycle alone) gives 0."""
    from pydantic import ValidationError

    from sizer.io.schema.inputs import LoadInput

    data = source.data.get("load") if isinstance(source.data, dict) else None
    if not isinstance(data, dict):
        return 0.0, 0.0
    keys = ("friction_coefficient", "incline")
    try:  # the two fields alone: their units and ranges, as the design read them
        given = LoadInput.model_validate({k: data[k] for k in keys if k in data})
    except ValidationError:  # not reached: the design's load was validated before
        return 0.0, 0.0
    return given.friction_coefficient or 0.0, given.incline or 0.0


def displacement_of(given: Any, source: YamlSource, at: Path_, *, zero_note: str,
                    linear: bool | None = None) -> tuple[float, bool]:
    """A displacement h in SI and whether it is a length, not zero, within its range.

    ``linear``: the axis it must be on (None: any; it then decides the axis, and a bare
    number is rad as for ``task.displacement``); on a known axis a bare number is SI (m on
    a linear axis).
    """
    try:
        if linear is not None and not isinstance(given, str):
            h, is_linear = to_si(given, "length" if linear else "angle"), linear
        else:
            h, is_linear = parse_displacement(given)
    except UserError as error:
        raise source.error(error.message, at) from None
    except OverflowError:
        allowed = RANGES[axis_range(TaskInput, "displacement", False)]
        raise source.error(f"{show_value(given)} is too large for a number; must be "
                           f"{allowed.text()} (or a length)", at) from None
    if not (math.isfinite(h) and h != 0.0):
        raise source.error(f"must not be zero, got {given!r} ({zero_note})", at)
    if linear is not None and is_linear != linear:
        axis, other = ("linear", "an angle") if linear else ("rotary", "a length")
        raise source.error(f"{given!r} is {other}, but the cycle is on a {axis} axis (its "
                           f"first move's displacement): every displacement of a cycle is "
                           f"on one axis", at)
    name = axis_range(TaskInput, "displacement", is_linear)
    try:
        check_range(name, h)
    except ValueError as error:
        shown = f"{number_text(h)} {RANGES[name].unit}"
        raise source.error(f"{error}{given_text(given, shown)}", at) from None
    return h, is_linear


def _same_speed(a: float, b: float) -> bool:
    return abs(a - b) <= SPEED_TOLERANCE * max(abs(a), abs(b))


def build_cycle(given: CycleInput, source: YamlSource) -> Cycle:
    """The Cycle of a validated ``cycle:`` section, every check of the module run."""
    base: Path_ = ("cycle",)
    kinds = [next(k for k in ("move", "run", "dwell") if getattr(item, k) is not None)
             for item in given.segments]
    at = [(*base, "segments", i, kind) for i, kind in enumerate(kinds)]
    first = next((i for i, kind in enumerate(kinds) if kind == "move"), None)
    if first is None:
        raise source.error("a cycle needs at least one move (a displacement by a motion "
                           "law)", (*base, "segments"))
    first_move = given.segments[first].move
    assert first_move is not None
    _, linear = displacement_of(first_move.displacement, source, (*at[first], "displacement"),
                                zero_note="a segment without motion is a `dwell:`")
    axis = _Axis(source, linear, (*at[first], "displacement"))
    share = ShareRule(given.share)  # a rule's name or "optimize: GOAL" (cycle_inputs)
    segments: list[Segment] = []
    for i, item in enumerate(given.segments):
        if item.move is not None:
            segments.append(_move(item.move, axis, at[i], share))
        elif item.run is not None:
            segments.append(_run(item.run, axis, at[i]))
        else:
            assert item.dwell is not None
            segments.append(_dwell(item.dwell, axis, at[i], share))
    _check_names(segments, source, at)
    _check_continuity(segments, kinds, source, at, axis)
    if given.closed:
        _check_closed(segments, source, base, axis)
    _check_repeats(segments, source, base, axis)
    cycle_time = _cycle_time(given, source, base)
    cycle = Cycle(tuple(segments), share=share, cycle_time=cycle_time,
                  minimize_segment=given.minimize, closed=given.closed, linear=linear)
    _check_minimize(cycle, source, base, at)
    _check_optimized_share(cycle, source, base)
    _check_time(cycle, source, base, at, "rate" if given.rate is not None else "cycle_time")
    return cycle


def motion_of(task: TaskInput | None, cycle: CycleInput | None, laws: list[LocatedLaw],
              source: YamlSource) -> tuple[Cycle, list[str]]:
    """A design's motion, one Cycle: its ``cycle:``, or the cycle its ``task:`` shorthand
    means (``shorthand`` set); with the warnings of the task's laws whose own displacement
    it scales, or of the cycle's segment forces that help their motion (force_sign)."""
    if cycle is not None:
        built = build_cycle(cycle, source)
        check_cycle_laws(laws, source)
        _check_law_list(built, laws, source)
        from sizer.io.force_sign import force_sign_warnings

        return built, [*force_sign_warnings(built, source),
                       *weight_twice_warnings(built, source)]
    assert task is not None  # a task or a cycle (DesignFile)
    shorthand, noted = _task_of(task, laws, source)
    return from_task(shorthand), noted


def _check_law_list(cycle: Cycle, laws: list[LocatedLaw], source: YamlSource) -> None:
    """The ``laws:`` the moves that name none are sized with: laws shaped per duration
    are chosen for the task shorthand only (a cycle's moves have durations of their own),
    and some law must meet the moves' boundary speeds (and accelerations)."""
    listed = [law for law in laws if law.at[0] == "laws"]
    try:
        boundary_laws(cycle, [law.choice for law in listed])
    except ValueError as error:
        raise source.error(str(error), ("laws",)) from None
    open_moves = any(m.law is None for m in cycle.moves)
    for law in listed if open_moves and shorthand_task(cycle) is None else ():
        if law.choice.auto:
            raise source.error(f"{law.spec}: `auto` shape parameters are chosen for the task "
                               "shorthand only, not yet for a cycle of segments; give the "
                               "shape", law.at)
        if law.choice.open_shaped:
            raise source.error(f"{law.spec}: a shaped law without f_T is shaped for one "
                               "duration, and the moves of a cycle have their own: give "
                               "f_T", law.at)


def _task_of(given: TaskInput, laws: list[LocatedLaw],
             source: YamlSource) -> tuple[Task, list[str]]:
    """The ``task:`` shorthand in SI (its displacement and duration may come from its laws
    defined by data), and the warnings of laws whose own displacement it scales."""
    noted: list[str] = []
    if given.displacement is None:
        h, linear = law_displacement(laws, source, ("task", "displacement"))
    else:
        h, linear = displacement_of(given.displacement, source, ("task", "displacement"),
                                    zero_note="a negative displacement moves back first")
        noted = scale_warnings(laws, h, linear, source)
    duration = given.duration
    if given.master_speed is not None:
        duration = master_duration(laws, given.master_speed, source, ("task", "master_speed"))
    task = Task(displacement=h, duration=duration, dwell=given.dwell,
                return_move=given.return_move, linear=linear)
    check_task_laws(laws, task, source)
    return task, noted


def _check_weight(weight: float | None, share: ShareRule, source: YamlSource,
                  at: Path_) -> float:
    if weight is None:
        return 1.0
    if share is not ShareRule.WEIGHTS:
        raise source.error(f"a weight shares the free time only with `share: weights` "
                           f"(cycle.share is {share.value!r})", (*at, "weight"))
    return weight


def _move(given: MoveInput, axis: _Axis, at: Path_, share: ShareRule) -> Move:
    source = axis.source
    h, _ = displacement_of(given.displacement, source, (*at, "displacement"),
                           zero_note="a segment without motion is a `dwell:`",
                           linear=axis.linear)

    def boundary(key: str) -> float:
        value = getattr(given, key)
        return 0.0 if value is None else axis.quantity(MoveInput, key, value, (*at, key))

    start, end = boundary("start_speed"), boundary("end_speed")
    start_acceleration = boundary("start_acceleration")
    end_acceleration = boundary("end_acceleration")
    law = None if given.law is None else law_choice(given.law)
    if law is not None and law.auto:
        raise source.error(f"law {given.law!r}: `auto` shape parameters are chosen for the "
                           "task shorthand only, not yet for a move of a cycle; give the "
                           "shape", (*at, "law"))
    moving = start != 0.0 or end != 0.0 or start_acceleration != 0.0 \
        or end_acceleration != 0.0
    shaped = _shaped_law(given.law) if moving and given.law is not None else None
    if shaped is not None:  # a law of fixed shape between boundary speeds (a table's span)
        _check_shaped(given, shaped, h, (start, end, start_acceleration, end_acceleration),
                      axis, at)
    elif given.law is not None and (reason := moving_ends(given.law)) is not None:
        raise source.error(f"this move's law {reason}: in a cycle of segments a move's law "
                           f"must start and end at rest (the move's speeds are its "
                           f"start_speed and end_speed); size a periodic cam as a task with "
                           f"dwell 0", (*at, "law"))
    if shaped is None and given.law is not None and (start != 0.0 or end != 0.0) \
            and not has_boundary_form(given.law):
        laws = ", ".join(BOUNDARY_SPEED_FAMILIES).replace(
            "polynomial", "polynomial (poly3, poly5, poly7)")
        raise source.error(f"law {given.law!r} has no form with boundary speeds (this "
                           f"move's start_speed or end_speed is not 0); laws with one: "
                           f"{laws}", (*at, "law"))
    if shaped is None and given.law is not None \
            and (start_acceleration != 0.0 or end_acceleration != 0.0) \
            and not meets_accelerations(given.law):
        key = "start_acceleration" if start_acceleration != 0.0 else "end_acceleration"
        raise source.error(f"law {given.law!r} cannot start or end at a non-zero "
                           f"acceleration; polynomials of degree 5 and 7 can (poly5, poly7; "
                           f"this move's {key} is not 0)", (*at, "law"))
    return Move(displacement=h, duration=given.duration, law=law, start_speed=start,
                end_speed=end, weight=_check_weight(given.weight, share, source, at),
                load=axis.load_change(MoveInput, given, at), name=given.name or "",
                start_acceleration=start_acceleration, end_acceleration=end_acceleration)


def _shaped_law(spec: str) -> Any:
    """The law of ``spec`` when it is defined by data with no form between boundary
    speeds (its shape is its own: the span of a cam table or of a segment file), else
    None (a family's law: the messages below say which have a form)."""
    from sizer.laws.data_law import DataLaw

    choice = law_choice(spec)
    if not (choice.is_fixed and issubclass(choice.family, DataLaw)) \
            or has_boundary_form(spec):
        return None
    return choice.law


def _check_shaped(given: MoveInput, law: Any, h: float,
                  ends: tuple[float, float, float, float], axis: _Axis, at: Path_) -> None:
    """A move between boundary speeds by a law of fixed shape: its duration is fixed (the
    shape does not stretch with it) and the law's end slopes (and accelerations, where
    given) are the move's (sizer.model.cycle.shape_mismatch), else an error at its law."""
    from sizer.model.cycle import shape_mismatch

    source = axis.source
    if given.duration is None:
        raise source.error(f"this move's law {given.law!r} is defined by data, with end "
                           f"slopes of its own: a move between boundary speeds takes it "
                           f"only at a fixed duration (give `duration`), at which its slopes "
                           f"are the move's speeds", (*at, "duration"))
    probe = Move(displacement=h, duration=given.duration, start_speed=ends[0],
                 end_speed=ends[1], start_acceleration=ends[2], end_acceleration=ends[3])
    reason = shape_mismatch(probe, law, given.duration, axis.linear)
    if reason is not None:
        raise source.error(f"this move's law does not meet its boundary speeds: {reason}",
                           (*at, "law"))


def _run(given: RunInput, axis: _Axis, at: Path_) -> Run:
    source = axis.source
    speed = axis.quantity(RunInput, "speed", given.speed, (*at, "speed"))
    if speed == 0.0:
        raise source.error("a run of zero speed: a rest is a `dwell:`", (*at, "speed"))
    unit = RANGES[axis_range(RunInput, "speed", axis.linear)].unit
    if given.displacement is not None and given.duration is not None:
        raise source.error("give a run's duration or its displacement, not both",
                           (*at, "displacement"))
    if given.displacement is None and given.duration is None:
        raise source.error("a run needs its duration (or its displacement)", at,
                           field=format_path((*at, "duration")))
    duration = given.duration
    if given.displacement is not None:
        where = (*at, "displacement")
        h, _ = displacement_of(given.displacement, source, where,
                               zero_note="a run moves: give its duration or a displacement",
                               linear=axis.linear)
        if (h > 0.0) != (speed > 0.0):
            length = RANGES[axis_range(RunInput, "displacement", axis.linear)].unit
            raise source.error(f"a run's displacement has the sign of its speed: "
                               f"{number_text(h)} {length} against {number_text(speed)} "
                               f"{unit}", where)
        duration = h / speed
        try:
            check_range("duration", duration)
        except ValueError as error:
            raise source.error(f"gives a duration (displacement / speed) that {error}",
                               where) from None
    assert duration is not None
    return Run(speed=speed, duration=duration, load=axis.load_change(RunInput, given, at),
               name=given.name or "")


def _dwell(given: DwellInput, axis: _Axis, at: Path_, share: ShareRule) -> Dwell:
    source = axis.source
    if given.duration is None and share is not ShareRule.WEIGHTS:
        raise source.error(f"a free dwell takes its share of the time by its weight: it "
                           f"needs `share: weights` (cycle.share is {share.value!r})",
                           (*at, "duration"))
    return Dwell(duration=given.duration,
                 weight=_check_weight(given.weight, share, source, at),
                 load=axis.load_change(DwellInput, given, at, keys=("torque",)),
                 name=given.name or "")


def _check_names(segments: list[Segment], source: YamlSource, at: list[Path_]) -> None:
    seen: dict[str, int] = {}
    for i, segment in enumerate(segments):
        if not segment.name:
            continue
        if segment.name in seen:
            raise source.error(f"segment name {segment.name!r} is taken by "
                               f"{format_path(at[seen[segment.name]][:-1])}: names are "
                               f"unique", (*at[i], "name"))
        seen[segment.name] = i


def _label(segment: Segment, at: Path_) -> str:
    text = format_path(at[:-1])
    return f"{text} ({segment.name!r})" if segment.name else text


def _speed_text(x: float, unit: str) -> str:
    return f"{number_text(x)} {unit}"


def _check_continuity(segments: list[Segment], kinds: list[str], source: YamlSource,
                      at: list[Path_], axis: _Axis) -> None:
    """Each segment ends at the speed the next one starts with (a run's speed at both
    ends, a dwell's 0), to SPEED_TOLERANCE."""
    unit = RANGES[axis_range(MoveInput, "start_speed", axis.linear)].unit
    for i in range(len(segments) - 1):
        here, there = segments[i], segments[i + 1]
        if _same_speed(here.end_speed, there.start_speed):
            continue
        if kinds[i] == "move":
            where = (*at[i], "end_speed")
        elif kinds[i + 1] == "move":
            where = (*at[i + 1], "start_speed")
        else:
            where = at[i + 1]
        raise source.error(
            f"speed jumps between segments: {_label(here, at[i])} ends at "
            f"{_speed_text(here.end_speed, unit)}, {_label(there, at[i + 1])} starts at "
            f"{_speed_text(there.start_speed, unit)} (a run keeps its speed at both ends, "
            f"a dwell is at 0; equal within {SPEED_TOLERANCE:g} of the larger)", where)


def _check_closed(segments: list[Segment], source: YamlSource, base: Path_,
                  axis: _Axis) -> None:
    """A closed cycle: net displacement 0 (to CLOSURE_TOLERANCE of the largest one)."""
    net = math.fsum(s.displacement for s in segments)
    largest = max(abs(s.displacement) for s in segments)
    units = (RANGES[axis_range(MoveInput, "displacement", axis.linear)].unit,
             RANGES[axis_range(MoveInput, "start_speed", axis.linear)].unit)
    if abs(net) > CLOSURE_TOLERANCE * largest:
        raise source.error(f"a closed cycle ends where it starts, but its displacements sum "
                           f"to {number_text(net)} {units[0]} (within "
                           f"{CLOSURE_TOLERANCE:g} of the largest, {number_text(largest)} "
                           f"{units[0]})", (*base, "closed"))


def _check_repeats(segments: list[Segment], source: YamlSource, base: Path_,
                   axis: _Axis) -> None:
    """Every cycle repeats (closed or not, an indexing table goes on round): the last
    segment's end speed is the first one's start speed."""
    unit = RANGES[axis_range(MoveInput, "start_speed", axis.linear)].unit
    last, first = segments[-1].end_speed, segments[0].start_speed
    if not _same_speed(last, first):
        raise source.error(f"a cycle repeats: its last segment ends at "
                           f"{_speed_text(last, unit)}, its first starts at "
                           f"{_speed_text(first, unit)}", (*base, "segments"))


def _cycle_time(given: CycleInput, source: YamlSource, base: Path_) -> float | None:
    if given.cycle_time is not None and given.rate is not None:
        raise source.error("give the cycle_time or the rate, not both", (*base, "rate"))
    if given.rate is not None:
        return 1.0 / given.rate
    return given.cycle_time


def _check_minimize(cycle: Cycle, source: YamlSource, base: Path_, at: list[Path_]) -> None:
    """``minimize`` names one segment, free, and every other segment is fixed."""
    name = cycle.minimize_segment
    if name is None:
        return
    where = (*base, "minimize")
    names = [s.name for s in cycle.segments if s.name]
    if name not in names:
        known = ", ".join(repr(n) for n in names) or "none (give segments a `name`)"
        raise source.error(f"no segment is named {name!r}; named segments: {known}", where)
    if cycle.cycle_time is not None:
        raise source.error("minimize a segment or give the cycle time (cycle_time or rate), "
                           "not both", where)
    index = names_index(cycle, name)
    free = [i for i, s in enumerate(cycle.segments)
            if not isinstance(s, Run) and s.duration is None]  # as written
    if index not in free:
        raise source.error(f"segment {name!r} has a fixed duration: nothing to minimize "
                           f"(write `duration: free`)", where)
    for i in free:
        if i != index:
            raise source.error(f"with `minimize: {name}` every other segment has a fixed "
                               f"duration; {_label(cycle.segments[i], at[i])} is free",
                               (*at[i], "duration"))


def _check_optimized_share(cycle: Cycle, source: YamlSource, base: Path_) -> None:
    """``share: {optimize: GOAL}`` splits a given cycle time (sizer.allocation): it needs
    ``cycle_time`` or ``rate`` and no ``minimize``; the vibration goal needs the load's
    mode (``load.natural_frequency``: read from the file's data, the load is read
    elsewhere)."""
    goal = cycle.share.goal
    if goal is None:
        return
    if cycle.minimize_segment is not None:
        raise source.error(f"`share: {{optimize: {goal}}}` splits a given cycle time among "
                           f"the free moves; with `minimize` one segment is free and there "
                           f"is nothing to split: remove one of them", (*base, "share"))
    if cycle.cycle_time is None and cycle.free:
        raise source.error(f"`share: {{optimize: {goal}}}` splits a given cycle time among "
                           f"the free moves: give `cycle_time` (or `rate`); without one the "
                           f"cycle is minimized by one scale of a fixed rule (equal, "
                           f"sqrt_displacement, ...)", (*base, "share"))
    load = source.data.get("load") if isinstance(source.data, dict) else None
    if goal == "vibration" and not (isinstance(load, dict)
                                    and load.get("natural_frequency") is not None):
        raise source.error("`share: {optimize: vibration}` minimizes the residual vibration "
                           "of the load's mode: give load.natural_frequency (and "
                           "damping_ratio), or optimize rms or energy", (*base, "share"))


def names_index(cycle: Cycle, name: str) -> int:
    """The index of the segment named ``name``."""
    return next(i for i, s in enumerate(cycle.segments) if s.name == name)


def _check_time(cycle: Cycle, source: YamlSource, base: Path_, at: list[Path_],
                key: str) -> None:
    """A cycle time leaves time for the free segments, or equals the fixed durations."""
    if cycle.cycle_time is None:
        return
    target, fixed = cycle.cycle_time, cycle.fixed_time
    shown = (f"the cycle time {number_text(target)} s"
             + (" (1 / rate)" if key == "rate" else ""))
    if cycle.free and not target > fixed:
        raise source.error(f"{shown} leaves no time for the free segments: the fixed "
                           f"durations sum to {number_text(fixed)} s", (*base, key))
    if not cycle.free and abs(target - fixed) > TIME_TOLERANCE * max(target, fixed):
        raise source.error(f"{shown} differs from the sum of the durations, "
                           f"{number_text(fixed)} s, and no segment is free to take the "
                           f"difference (make a duration `free`)", (*base, key))

