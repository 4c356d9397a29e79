"""Pydantic models of a machine file: several axes on one master (book sec. 5.3).

A machine file names the master's cycle (``machine:``: its angle, and its speed or its
cycle time, or ``minimize``), the axes (each a design whose move is a share of the
master's cycle instead of a duration) and optionally the DC bus they share (``bus:``).
An axis is a design file's content (load, transmission, laws, motors, drives, limits)
with ``task:`` in master angles; sizer.io.machine_loader builds the domain objects.
"""


from typing import Annotated, Any, Self

from pydantic import (
    BeforeValidator,
    ConfigDict,
    Field,
    StrictBool,
    WithJsonSchema,
    model_validator,
)
from pydantic_core import PydanticCustomError

from sizer.input_limits import MAX_MACHINE_AXES
from sizer.io.schema.inputs import DesignFile
from sizer.io.schema.inputs_base import (
    Identifier,
    Ranged,
    RangeRef,
    RawQuantity,
    RawValue,
    Strict,
    Text,
    at_most,
    convert_in,
    given,
    not_null,
    quantity_text,
)
from sizer.io.schema.ranges import RANGES

MINIMIZE = "minimize"


class AxisTaskInput(Strict):
    """An axis's move on the master: h while the master turns ``move``, a dwell, a return."""

    displacement: Annotated[RawValue, RawQuantity(
        "'90 deg' or '200 mm'", rotary="angle_displacement", linear="length_displacement")] = Field(
        description="h at the load: an angle ('90 deg', rotary axis) or a length ('200 mm', "
                    "linear axis); negative moves back first")
    move: Annotated[float, Ranged(
        "master_angle", note="the master angle the move lasts, e.g. '120 deg'")]
    dwell: Annotated[float, Ranged(
        "master_dwell", note="master angle of each rest; omitted: the rest of the machine cycle "
                             "(split in two with a return)")] | None = None
    return_move: StrictBool = Field(False, alias="return",
                                    description="cycle = move, dwell, move back, dwell")


def _no_cycle(schema: dict[str, Any]) -> None:
    """An axis's schema: ``task`` and ``name`` required; ``cycle`` and ``check`` only null
    (an axis has neither)."""
    schema.pop("oneOf", None)
    schema["required"] = sorted({*schema.get("required", []), "task", "name"})


class AxisInput(DesignFile):
    """One axis of the machine: a design whose task is in master angles."""

    model_config = ConfigDict(json_schema_extra=lambda schema, _: _no_cycle(schema))

    name: Identifier = Field(
        description="the axis's name, unique in the machine, not empty")
    task: Annotated[AxisTaskInput, BeforeValidator(given)] = Field(  # type: ignore[assignment]
        description="the move on the master, its dwell and an optional return")
    cycle: None = Field(None, description="not in an axis (a design file's cycle of "
                                          "segments)")
    check: None = Field(None, description="not in an axis (a design file's check)")
    start: Annotated[float, Ranged(
        "master_phase", note="the master angle where the axis's move begins (its phase in the "
                             "machine cycle)")] = 0.0

    @model_validator(mode="before")
    @classmethod
    def _task_only(cls, data: Any) -> Any:
        """No cycle of segments and no ``check:`` in an axis (not supported there yet)."""
        if isinstance(data, dict):
            for key, why in (("cycle", "an axis of a machine takes `task:` (a move on the "
                              "master, its dwell, a return); cycles of segments are not "
                              "supported in a machine yet"),
                             ("check", "`check:` is for design files; a machine's axes "
                              "are sized")):
                if key in data:
                    raise PydanticCustomError("axis_field", why, {"at": (key,)})
        return data


def _master_speed(value: Any) -> float | str | None:
    if value is None:
        return None
    if isinstance(value, str) and value.strip().lower() == MINIMIZE:
        return MINIMIZE
    return convert_in(value, "master_speed")


class MachineInput(Strict):
    """The master: the angle of one machine cycle and its speed (or cycle time)."""

    cycle: Annotated[float, Ranged(
        "master_angle", note="master angle of one machine cycle")] = 6.283185307179586
    master_speed: Annotated[
        float | str | None,
        BeforeValidator(_master_speed),
        WithJsonSchema({"anyOf": [{"type": "number",
                                   "minimum": RANGES["master_speed"].low,
                                   "maximum": RANGES["master_speed"].high},
                                  quantity_text("minimize")],
                        "description": "the master's constant speed ('120 rpm', "
                                       "'720 deg/s') or 'minimize': as fast as the slowest "
                                       "axis allows"}),
        RangeRef("master_speed"),
    ] = None
    cycle_time: Annotated[float, Ranged(
        "duration", note="instead of master_speed: the time of one machine cycle")] | None = None

    @model_validator(mode="after")
    def _speed(self) -> Self:
        """master_speed (a speed or 'minimize') or cycle_time: exactly one."""
        if (self.master_speed is None) == (self.cycle_time is None):
            raise PydanticCustomError(
                "speed_or_time", "give master_speed (a speed or 'minimize') or cycle_time, "
                "one of the two", {"at": ("master_speed",)})
        return self


class BusInput(Strict):
    """The DC bus the axes share (all optional: each fills what the drives leave out)."""

    capacitance: Annotated[float, Ranged(
        "bus_capacitance", note="the bus's whole capacitance; omitted: the sum of the chosen "
                                "drives' bus_capacitance")] | None = None
    voltage: Annotated[float, Ranged(
        "bus_voltage", note="nominal DC-link voltage; omitted: the drives'")] | None = None
    braking_threshold: Annotated[float, Ranged(
        "bus_voltage", note="where the braking chopper switches on; omitted: the "
                            "drives'")] | None = None
    braking_resistor_power: Annotated[float, Ranged(
        "braking_power", note="W: the shared braking resistor's continuous power, "
                              "checked against the axes' summed braking")] | None = None


class MachineFile(Strict):
    """A machine file: the master, two or more axes on it, and their DC bus."""

    model_config = ConfigDict(json_schema_extra=not_null("bus"))

    name: Text | None = None
    machine: Annotated[MachineInput, BeforeValidator(given)]
    axes: Annotated[list[AxisInput], at_most(MAX_MACHINE_AXES, "machine", "axes",
                                                    "MAX_MACHINE_AXES")] = Field(
        min_length=1, max_length=MAX_MACHINE_AXES,
        description=f"the axes on the master (1 to {MAX_MACHINE_AXES})")
    bus: Annotated[BusInput | None, BeforeValidator(given)] = Field(
        None, description="the DC bus the axes share; omitted: the bus figures use the "
                          "drives' data")

    @model_validator(mode="after")
    def _unique_names(self) -> Self:
        """Axis names are unique."""
        seen: set[str] = set()
        for i, axis in enumerate(self.axes):
            if axis.name in seen:
                raise PydanticCustomError("duplicate_axis", f"axis name {axis.name!r} is used "
                                          "twice", {"at": ("axes", i, "name")})
            seen.add(axis.name)
        return self
