"""Input models of a design's ``cycle:``: a machine cycle of segments (issue 12).

A segment is a one-key mapping: ``move``, ``run`` or ``dwell``. Quantities whose kind is
fixed (durations, weights, the rate) are converted to SI here; those whose kind depends on
the axis (displacements, speeds, accelerations, added inertia or mass, torque or force)
stay as given and are converted by :mod:`sizer.io.cycle`, which also runs the checks that
span several segments (speed continuity, a closed cycle, the time budget) and builds the
:class:`sizer.model.cycle.Cycle`.
"""


import difflib
import math
import re
from typing import Annotated, Any

from pydantic import BeforeValidator, ConfigDict, Field, StrictBool, WithJsonSchema, model_validator

from sizer.input_limits import MAX_CYCLE_SEGMENTS
from sizer.io.schema.inputs_base import (
    Identifier,
    Ranged,
    RangeRef,
    RawQuantity,
    RawValue,
    Strict,
    at_most,
    convert,
    convert_in,
    not_null,
    quantity_text,
    range_schema,
    show_value,
)
from sizer.io.schema.law_schema import LawSpecText
from sizer.io.schema.ranges import RANGES, check_range

SEGMENT_KINDS = ("move", "run", "dwell")
"""The keys of a segment's one-key mapping."""

SHARE_RULES = ("equal", "displacement", "sqrt_displacement", "weights")
"""The values of ``cycle.share`` (sizer.model.cycle.ShareRule) that are texts."""

SHARE_GOALS = ("rms", "energy", "vibration")
"""What ``share: {optimize: GOAL}`` may minimize (docs/allocation.md)."""
PER_MOVE_GOALS = ("rms", "energy")
"""The goals with which ``laws: per_move`` chooses a law for each move (sums of one term
per move: sizer.allocation.allocate_laws)."""
GOALS_NOT_YET: tuple[str, ...] = ()
"""Goals named in the issue that are not built yet: refused with "not yet"."""


def _share(value: Any) -> str:
    """``cycle.share``: a rule's name, or ``{optimize: rms | energy | vibration}`` (a split
    chosen per candidate motor, or for all: sizer.allocation), as the ShareRule value
    ("optimize: rms")."""
    rules = ", ".join(SHARE_RULES)
    expected = f"one of {rules}, or {{optimize: {' | '.join(SHARE_GOALS)}}}"
    if isinstance(value, str) and value in SHARE_RULES:
        return value
    if isinstance(value, dict) and set(value) == {"optimize", "laws"}:
        goal, laws = value["optimize"], value["laws"]
        if laws != "per_move":
            raise ValueError(f"laws takes per_move (a law of the design's list chosen for "
                             f"each move with the split), got {show_value(laws)}")
        if isinstance(goal, str) and goal in PER_MOVE_GOALS:
            return f"optimize: {goal}, laws: per_move"
        raise ValueError(f"`laws: per_move` is chosen with the split for "
                         f"{' or '.join(PER_MOVE_GOALS)}, got optimize: {show_value(goal)}")
    if isinstance(value, dict) and set(value) == {"optimize"}:
        goal = value["optimize"]
        if isinstance(goal, str) and goal in SHARE_GOALS:
            return f"optimize: {goal}"
        if isinstance(goal, str) and goal in GOALS_NOT_YET:
            raise ValueError(f"optimize: {goal} is not yet built (the split minimizes "
                             f"{' or '.join(SHARE_GOALS)})")
        raise ValueError(f"optimize takes {' or '.join(SHARE_GOALS)}, got {show_value(goal)}")
    close = difflib.get_close_matches(value, SHARE_RULES, n=1) if isinstance(value, str) \
        else []
    hint = f" (did you mean {close[0]!r}?)" if close else ""
    raise ValueError(f"must be {expected}, got {show_value(value)}{hint}")


Share = Annotated[
    str,
    BeforeValidator(_share),
    WithJsonSchema({"anyOf": [
        {"type": "string", "enum": list(SHARE_RULES)},
        {"type": "object", "properties": {"optimize": {"type": "string",
                                                       "enum": list(SHARE_GOALS)},
                                          "laws": {"const": "per_move"}},
         "required": ["optimize"], "additionalProperties": False}],
        "description": "how free durations share the time: equal, in proportion to |h| "
                       "(displacement) or sqrt(|h|) (sqrt_displacement), by each segment's "
                       "weight (weights), or {optimize: rms | energy | vibration}: each "
                       "motor's own split of a given cycle time that minimizes its RMS "
                       "torque or its energy per cycle, or the split that minimizes the "
                       "worst residual vibration; with laws: per_move (rms or energy) also a "
                       "law of the design's list for each move (docs/allocation.md)"}),
]
"""``cycle.share``, as a sizer.model.cycle.ShareRule value."""


def _free_duration(value: Any) -> float | None:
    if isinstance(value, str) and value.strip().lower() == "free":
        return None
    return convert_in(value, "duration")


FreeDuration = Annotated[
    float | None,
    BeforeValidator(_free_duration),
    WithJsonSchema({"anyOf": [{"type": "number", "minimum": RANGES["duration"].low,
                               "maximum": RANGES["duration"].high},
                              quantity_text("free")],
                    "description": "time like '0.3 s', or 'free' (scaled with the other "
                                   "free segments, sec. 5.2); must be "
                                   f"{RANGES['duration'].text()} (SI)"}),
    RangeRef("duration"),
]
"""A segment's duration: a time, or ``free``."""

_SLASH = re.compile(r"^(\s*[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*/")


def _rate(value: Any) -> float:
    """Cycles per second from '50 /min', '50 1/min', '50 cycles/min', '0.8 Hz' or a bare
    number (1/s): a unit with an angle counts it in cycles (rev, turn), one without counts
    cycles (the angular speed's rule, sizer.units)."""
    if not isinstance(value, str):
        return convert_in(value, "cycle_rate")
    text = _SLASH.sub(r"\1 1/", value, count=1)  # '50 /min' = '50 1/min'
    try:
        cycles = convert(text, "angular_speed") / (2 * math.pi)
    except ValueError:
        raise ValueError(f"expected a rate like '50 /min', '50 1/min' or '0.8 Hz', got "
                         f"{show_value(value)}") from None
    try:
        check_range("cycle_rate", cycles)
    except ValueError as error:
        raise ValueError(f"{error} ({value.strip()})") from None
    return cycles


Rate = Annotated[
    float,
    BeforeValidator(_rate),
    WithJsonSchema(range_schema(RANGES["cycle_rate"],
                                "cycles per time, e.g. '50 /min' (a cycle time of 1.2 s)",
                                slash=True)),
    RangeRef("cycle_rate"),
]


Displacement = Annotated[RawValue, RawQuantity(
    "'90 deg' or '200 mm'", rotary="angle_displacement", linear="length_displacement")]
Speed = Annotated[RawValue, RawQuantity(
    "'30 rpm' or '0.5 m/s'", rotary="segment_angular_speed", linear="segment_linear_speed")]
Acceleration = Annotated[RawValue, RawQuantity(
    "'500 deg/s^2' or '2 m/s^2'", rotary="segment_angular_acceleration",
    linear="segment_linear_acceleration")]


LawSpec = LawSpecText
"""A law spec, checked as ``laws:`` entries are (sizer.io.schema.law_schema.check_law_spec)."""


AddedInertia = Annotated[RawValue, RawQuantity("'0.1 kg*m^2'", rotary="added_inertia")]
AddedMass = Annotated[RawValue, RawQuantity("'2 kg'", linear="added_mass")]
AddedTorque = Annotated[RawValue, RawQuantity("'15 N*m'", rotary="load_torque")]
AddedForce = Annotated[RawValue, RawQuantity("'20 N'", linear="load_force")]
"""What a segment adds to the design's load (sizer.model.cycle.SegmentLoad), per axis."""

_INERTIA = "rotary axis: inertia added while the segment lasts"
_MASS = "linear axis: mass added while the segment lasts (a part held)"
_TORQUE = "rotary axis: external torque added, positive opposes a positive move"
_FORCE = ("linear axis: external force added (pressing, a payload's weight), positive "
          "opposes a positive move")


class MoveInput(Strict):
    """A move of ``displacement`` by a motion law, from ``start_speed`` to ``end_speed``
    (and from ``start_acceleration`` to ``end_acceleration``)."""

    displacement: Displacement = Field(
        description="h of this move, signed: an angle (rotary axis) or a length (linear); "
                    "not zero")
    duration: FreeDuration = None
    law: LawSpec | None = Field(
        None, description="this move's law; omitted = each of the design's laws in turn; "
                          "with start or end speeds not 0, a law with boundary speeds "
                          "(trapezoidal, double_s, polynomial, constant_acceleration)")
    start_speed: Speed | None = Field(
        None, description="signed speed at the start (at the load); 0 = from rest")
    end_speed: Speed | None = Field(
        None, description="signed speed at the end (at the load); 0 = to rest")
    start_acceleration: Acceleration | None = Field(
        None, description="signed acceleration at the start (at the load); 0 when omitted; "
                          "not 0 only with a law that meets it (poly5, poly7)")
    end_acceleration: Acceleration | None = Field(
        None, description="signed acceleration at the end (at the load); 0 when omitted; "
                          "not 0 only with a law that meets it (poly5, poly7)")
    weight: Annotated[float, Ranged(
        "segment_weight", note="its share of the free time with `share: weights`")] | None = None
    inertia: AddedInertia | None = Field(None, description=_INERTIA)
    mass: AddedMass | None = Field(None, description=_MASS)
    torque: AddedTorque | None = Field(None, description=_TORQUE)
    force: AddedForce | None = Field(None, description=_FORCE)
    name: Identifier | None = None


class RunInput(Strict):
    """A run at constant ``speed`` for a ``duration`` or over a ``displacement``."""

    speed: Speed = Field(
        description="signed constant speed at the load, not zero")
    duration: Annotated[float, Ranged("duration")] | None = Field(
        None, description="the run's time; or give its displacement")
    displacement: Displacement | None = Field(
        None, description="the run's displacement, of the speed's sign; or give its duration")
    inertia: AddedInertia | None = Field(None, description=_INERTIA)
    mass: AddedMass | None = Field(None, description=_MASS)
    torque: AddedTorque | None = Field(None, description=_TORQUE)
    force: AddedForce | None = Field(None, description=_FORCE)
    name: Identifier | None = None


class DwellInput(Strict):
    """A rest of ``duration``, holding the design's load plus a torque or force."""

    duration: FreeDuration = Field(description="time like '0.2 s', or 'free' (needs "
                                               "`share: weights`)")
    weight: Annotated[float, Ranged(
        "segment_weight", note="its share of the free time with `share: weights`")] | None = None
    torque: AddedTorque | None = Field(
        None, description="rotary axis: external torque held while resting (pressing)")
    force: AddedForce | None = Field(
        None, description="linear axis: external force held while resting")
    name: Identifier | None = None


class SegmentInput(Strict):
    """One segment: a one-key mapping ``move: {...}``, ``run: {...}`` or ``dwell: {...}``."""

    model_config = ConfigDict(json_schema_extra=not_null(
        *SEGMENT_KINDS, minProperties=1, maxProperties=1))

    move: MoveInput | None = None
    run: RunInput | None = None
    dwell: DwellInput | None = None

    @model_validator(mode="before")
    @classmethod
    def _one_kind(cls, data: Any) -> Any:
        kinds = ", ".join(SEGMENT_KINDS)
        if not isinstance(data, dict):
            raise ValueError(f"a segment is a one-key mapping like {{move: {{displacement: "
                             f"90 deg}}}} ({kinds}), got {show_value(data)}")
        for key in data:
            if key not in SEGMENT_KINDS:
                close = difflib.get_close_matches(str(key), SEGMENT_KINDS, n=1)
                hint = f" (did you mean {close[0]!r}?)" if close else ""
                raise ValueError(f"unknown segment kind {show_value(key)}{hint}; a segment "
                                 f"is one of: {kinds}")
        if len(data) != 1:
            found = " and ".join(data) if data else "none"
            raise ValueError(f"a segment has exactly one kind ({kinds}), got {found}: write "
                             f"each as its own item of the list")
        kind, fields = next(iter(data.items()))
        if fields is None:
            raise ValueError(f"a {kind} needs its fields, e.g. {_EXAMPLES[kind]}")
        return data


_EXAMPLES = {"move": "{move: {displacement: 90 deg, duration: 0.3 s}}",
             "run": "{run: {speed: 0.5 m/s, duration: 0.2 s}}",
             "dwell": "{dwell: {duration: 0.2 s}}"}


class CycleInput(Strict):
    """A machine cycle: its segments, in order, repeated; how free durations share time."""

    share: Share = "equal"
    cycle_time: Annotated[float, Ranged(
        "duration", note="the target period of the cycle; omitted with free segments: "
                         "the shortest")] | None = None
    rate: Rate | None = None
    minimize: Identifier | None = Field(
        None, description="the name of the one segment whose duration is minimized (every "
                          "other has a fixed duration)")
    closed: StrictBool = Field(
        False, description="the cycle ends where it starts: net displacement 0, and the "
                           "last end speed equals the first start speed")
    segments: Annotated[list[SegmentInput], at_most(MAX_CYCLE_SEGMENTS, "cycle", "segments",
                                                          "MAX_CYCLE_SEGMENTS")] = Field(
        min_length=1, max_length=MAX_CYCLE_SEGMENTS,
        description=f"the segments, in order (1 to {MAX_CYCLE_SEGMENTS})")
