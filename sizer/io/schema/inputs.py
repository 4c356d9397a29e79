"""Pydantic models of the YAML input files: the design file and the motor catalog.

They check the shape of a file (known fields, types) and convert every quantity whose kind
is fixed to an SI float with :func:`sizer.units.to_si` ("3000 rpm" -> 314.159...). The
quantities whose kind depends on the axis (a rotary or a linear load) stay as given and are
converted by :mod:`sizer.io.loader`, which also runs the checks that span several fields
(curve order, max speed >= rated speed, ...: the rules of :mod:`sizer.io.motor_rules`) and
builds the domain objects of :mod:`sizer.model.domain`; a catalog in the common form is
read as columns without these models (:mod:`sizer.io.catalog_table`), to the same motors.

Validators raise ValueError with a one-line message; the loader turns pydantic's
ValidationError into a UserError at the file, line and field.
"""


import re
from itertools import pairwise
from typing import Annotated, Any, ClassVar, Literal, Self

from pydantic import (
    BeforeValidator,
    ConfigDict,
    Discriminator,
    Field,
    ModelWrapValidatorHandler,
    PrivateAttr,
    StrictBool,
    Tag,
    WithJsonSchema,
    model_validator,
)
from pydantic_core import PydanticCustomError

from sizer.io.schema.cycle_inputs import CycleInput
from sizer.io.schema.inputs_base import (
    Identifier,
    OneOrList,
    OrArray,
    Ranged,
    RangeRef,
    RawQuantity,
    RawValue,
    Strict,
    Text,
    convert_in,
    given,
    not_null,
    quantity_text,
)
from sizer.io.schema.law_schema import LawSpecText
from sizer.io.schema.provenance import (
    FigureSourcesInput,
    SourceKey,
    Sources,
    check_provenance,
)
from sizer.io.schema.ranges import RANGES
from sizer.io.schema.tolerance_inputs import ToleranceValue
from sizer.io.schema.transmission_inputs import TransmissionStageInput
from sizer.model.domain import DEFAULT_ENVELOPE, EnvelopeRule

# ---------------------------------------------------------------- catalog


class CurvePointInput(Strict):
    """A (speed, torque) point of a speed-torque curve."""

    speed: Annotated[float, Ranged("curve_speed")]
    torque: Annotated[float, Ranged("curve_torque")]


CurvePoint = Annotated[CurvePointInput, OrArray(("speed", "torque"), "curve point")]
"""A point as a mapping or as the pair [speed, torque], e.g. ['3000 rpm', '0.3 N*m']."""


class TorqueCurrentPointInput(Strict):
    """A (current, torque) point of a motor's torque-current curve."""

    current: Annotated[float, Ranged("curve_current")]
    torque: Annotated[float, Ranged("curve_torque")]


TorqueCurrentPoint = Annotated[TorqueCurrentPointInput,
                               OrArray(("current", "torque"), "torque-current point")]
"""A point as a mapping or as the pair [current, torque], e.g. ['18 A', '15 N*m']."""


def _increasing_points(points: list[Any] | None) -> list[Any] | None:
    """A torque-current curve: >= 2 points, currents and torques strictly increasing."""
    if points is None:
        return None
    if len(points) < 2:
        raise ValueError("a torque-current curve needs at least 2 points")
    for a, b in pairwise(points):
        if not (b.current > a.current and b.torque > a.torque):
            raise ValueError(f"currents and torques must both increase strictly: "
                             f"({a.current:g} A, {a.torque:g} N*m) then "
                             f"({b.current:g} A, {b.torque:g} N*m)")
    return points


INLINE_TOLERANCE_FIELDS = ("inertia", "mass", "friction", "damping", "torque", "force",
                           "natural_frequency")
"""The load's fields that may carry a tolerance beside the value ('0.35 kg*m^2 +- 20 %'):
the loader reads it as ``load.<field>`` of the ``tolerances:`` section (docs/robust.md)."""

_PLUS_MINUS = re.compile(r"\+\s*-|\+\s*/\s*-|\u00b1")
"""'+-', '+/-' or the sign itself, between a value and its tolerance."""


def split_inline_tolerance(value: Any) -> tuple[Any, str | None]:
    """``value`` as (quantity, tolerance text): '0.35 kg*m^2 +- 20 %' is ('0.35 kg*m^2',
    '20 %'), a value without a tolerance is (value, None); ValueError when one side of the
    sign is missing or the sign is written twice."""
    if not isinstance(value, str):
        return value, None
    parts = _PLUS_MINUS.split(value)
    if len(parts) == 1:
        return value, None
    if len(parts) > 2:
        raise ValueError(f"one tolerance beside a value, like '0.35 kg*m^2 +- 20 %', got "
                         f"{value!r}")
    quantity, tolerance = (part.strip() for part in parts)
    if not quantity or not tolerance:
        raise ValueError(f"expected a value and its tolerance, like '0.35 kg*m^2 +- 20 %' "
                         f"or '0.35 kg*m^2 +- 0.05 kg*m^2', got {value!r}")
    return quantity, tolerance


MOTOR_INLINE_TOLERANCE_FIELDS = ("inertia", "continuous_torque", "peak_torque", "rated_speed")
"""An inline motor's figures that may carry a tolerance beside the value ('2.4 N*m +- 10 %'):
the loader reads it as ``motor.<field>`` of that motor alone (docs/robust.md)."""


class InlineTolerances(Strict):
    """A model whose ``inline_fields`` may carry a tolerance beside the value ('0.35 kg*m^2
    +- 20 %'): the field keeps the quantity, :attr:`inline_tolerances` the tolerance's
    text (the loader reads it as the ``tolerances:`` section's)."""

    inline_fields: ClassVar[tuple[str, ...]] = ()
    _inline: dict[str, str] = PrivateAttr(default_factory=dict)

    @model_validator(mode="wrap")
    @classmethod
    def _tolerances_beside_values(cls, data: Any,
                                  handler: ModelWrapValidatorHandler[Self]) -> Self:
        found: dict[str, str] = {}
        if isinstance(data, dict):
            data = dict(data)
            for name in [n for n in data if n in cls.inline_fields]:  # file order
                try:
                    quantity, tolerance = split_inline_tolerance(data.get(name))
                except ValueError as error:
                    raise PydanticCustomError("inline_tolerance", str(error),
                                              {"at": (name,)}) from None
                if tolerance is not None:
                    data[name], found[name] = quantity, tolerance
        model = handler(data)
        model._inline = found
        return model

    @property
    def inline_tolerances(self) -> dict[str, str]:
        """Each field given with a tolerance beside it: the tolerance as written."""
        return dict(self._inline)


class MotorInput(InlineTolerances):
    """One motor of a catalog (or inline in a design file, whose figures
    MOTOR_INLINE_TOLERANCE_FIELDS may carry a tolerance beside the value)."""

    inline_fields: ClassVar[tuple[str, ...]] = MOTOR_INLINE_TOLERANCE_FIELDS

    id: Identifier = Field(description="unique among all loaded motors")
    inertia: Annotated[float, Ranged(
        "motor_inertia", note="rotor inertia J_m; 0 for idealized motors whose inertia is "
                              "counted in the load (the book's examples)")]
    continuous_torque: Annotated[float, Ranged(
        "motor_torque", note="tau_c, continuous (S1) torque up to rated speed")]
    peak_torque: Annotated[float, Ranged(
        "motor_torque", note="tau_p, intermittent peak torque, >= continuous_torque")]
    rated_speed: Annotated[float, Ranged("motor_speed", note="v_n")]
    max_speed: Annotated[float, Ranged("motor_speed", note=">= rated_speed")] | None = None
    damping: Annotated[float, Ranged("motor_damping", note="viscous B_m")] = 0.0
    continuous_curve: list[CurvePoint] | None = Field(
        None, description="continuous region boundary, speeds strictly increasing, >= 2 points")
    intermittent_curve: list[CurvePoint] | None = Field(
        None, description="intermittent region boundary, speeds strictly increasing, "
                          ">= 2 points")
    source: Text | None = None
    part_number: Text | None = None
    manufacturer: Text | None = None
    price: Annotated[float, Ranged("price")] | None = None
    mass: Annotated[float, Ranged("motor_mass")] | None = None
    torque_constant: Annotated[float, Ranged(
        "torque_constant", note="k_t, N*m per ampere RMS ('N*m/A', 'N*m/Arms'); needed "
                                "to pair the motor with a drive")] | None = None
    winding_resistance: Annotated[float, Ranged(
        "winding_resistance", note="phase to phase (line to line, between two "
                                   "terminals), ohm")] | None = None
    phase_resistance: Annotated[float, Ranged(
        "winding_resistance", note="per phase of a star winding, as some vendors give it "
                                   "(Siemens R_ph): read as winding_resistance = 2 x this; "
                                   "give one of the two")] | None = None
    winding_inductance: Annotated[float, Ranged(
        "winding_inductance", note="phase to phase (line to line, between two terminals), "
                                   "e.g. '12.5 mH'")] | None = None
    phase_inductance: Annotated[float, Ranged(
        "winding_inductance", note="per phase of a star winding: read as "
                                   "winding_inductance = 2 x this; give one of the "
                                   "two")] | None = None
    back_emf_constant: Annotated[float, Ranged(
        "back_emf_constant", note="k_e: RMS line-to-line back-EMF per speed, as Kollmorgen, "
                                  "Siemens and Beckhoff print it ('52 V/krpm', "
                                  "'52 mV/min^-1'); sinusoidal: k_t = sqrt(3) k_e")] | None = None
    poles: Annotated[float, Ranged(
        "poles", note="the rotor's magnetic poles (even; pole pairs = poles / 2): the "
                      "winding's electrical frequency for its inductance")] | None = None
    continuous_current: Annotated[float, Ranged(
        "motor_current", note="the current of continuous_torque (standstill or rated), "
                              "A rms")] | None = None
    peak_current: Annotated[float, Ranged(
        "motor_current", note="the motor's maximum (peak) current, A rms")] | None = None
    dc_bus_voltage: Annotated[float, Ranged(
        "bus_voltage", note="the DC-link (or supply) voltage the ratings are given for: "
                            "the voltage limit of the electrical envelope")] | None = None
    supply_voltage: Annotated[float, Ranged(
        "supply_voltage", note="the AC mains the ratings are given for, line to line RMS: "
                               "read as dc_bus_voltage = sqrt(2) x this; give one of the "
                               "two")] | None = None
    commutation: Literal["sinusoidal", "block"] = Field(
        "sinusoidal", description="sinusoidal (AC servo, field-oriented: the default) or "
                                  "block (a brushless DC motor's six-step, as maxon's EC "
                                  "data: U = R I + k_t omega at the terminals)")
    brake_holding_torque: Annotated[float, Ranged(
        "brake_holding_torque", note="a holding brake's static torque, e.g. '1.27 N*m': "
                                     "the motor is the brake variant")] | None = None
    brake_inertia: Annotated[float, Ranged(
        "brake_inertia", note="the brake's inertia, added to the rotor's (the datasheet's "
                              "inertia with brake minus without)")] | None = None
    thermal_time_constant: Annotated[float, Ranged(
        "thermal_time_constant", note="'35 min' or '251 s'")] | None = None
    max_winding_temperature_rise: Annotated[float, Ranged(
        "winding_temperature_rise", note="over the ambient, e.g. '100 K'")] | None = None
    torque_current_curve: list[TorqueCurrentPoint] | None = Field(
        None, description="torque vs current (saturation), [current, torque] points, both "
                          "strictly increasing; without it torque = k_t x current")
    radial_load: Annotated[float, Ranged(
        "shaft_load", note="the maker's permissible radial load on the shaft, e.g. "
                           "'245 N' (docs/shaft-loads.md)")] | None = None
    axial_load: Annotated[float, Ranged(
        "shaft_load", note="the maker's permissible axial (thrust) load on the "
                           "shaft")] | None = None
    radial_load_point: Annotated[float, Ranged(
        "shaft_load_point", note="from the flange to where radial_load acts, as the "
                                 "maker states it")] | None = None
    figure_sources: FigureSourcesInput | None = None
    notes: Text | None = Field(None, description="free text, ignored by the tool")

    @model_validator(mode="after")
    def _resistances(self) -> Self:
        """One resistance convention; the torque-current curve increasing."""
        if self.winding_resistance is not None and self.phase_resistance is not None:
            raise PydanticCustomError("two_resistances", "give winding_resistance (phase to "
                                      "phase) or phase_resistance (per phase), not both",
                                      {"at": ("phase_resistance",)})
        for one, other, what in (("winding_inductance", "phase_inductance", "inductance"),
                                 ("dc_bus_voltage", "supply_voltage", "voltage")):
            if getattr(self, one) is not None and getattr(self, other) is not None:
                raise PydanticCustomError(f"two_{what}s", f"give {one} or {other}, not both",
                                          {"at": (other,)})
        if self.poles is not None and (self.poles != int(self.poles) or self.poles % 2):
            raise PydanticCustomError("poles", f"poles must be an even whole number (twice "
                                      f"the pole pairs), got {self.poles:g}",
                                      {"at": ("poles",)})
        if (self.peak_current is not None and self.continuous_current is not None
                and self.peak_current < self.continuous_current):
            raise PydanticCustomError(
                "peak_below_continuous", f"peak_current {self.peak_current:g} A is below "
                f"continuous_current {self.continuous_current:g} A", {"at": ("peak_current",)})
        try:
            _increasing_points(self.torque_current_curve)
        except ValueError as error:
            raise PydanticCustomError("torque_current_curve", str(error),
                                      {"at": ("torque_current_curve",)}) from None
        return self


class DriveInput(Strict):
    """One drive (servo amplifier) of a catalog."""

    id: Identifier = Field(description="unique among the loaded drives")
    continuous_current: Annotated[float, Ranged(
        "drive_current", note="rated (continuous) output current, A rms")]
    peak_current: Annotated[float, Ranged(
        "drive_current", note="maximum (peak) output current, A rms, >= continuous_current")]
    dc_bus_voltage: Annotated[float, Ranged(
        "bus_voltage", note="nominal DC-link voltage")] | None = None
    bus_capacitance: Annotated[float, Ranged(
        "bus_capacitance", note="DC-link capacitance, e.g. '110 uF'")] | None = None
    max_bus_voltage: Annotated[float, Ranged(
        "bus_voltage", note="DC-link overvoltage trip level")] | None = None
    braking_threshold: Annotated[float, Ranged(
        "bus_voltage", note="DC-link voltage where braking starts")] | None = None
    braking_resistor_power: Annotated[float, Ranged(
        "braking_power", note="continuous power of the internal braking "
                              "resistor; 0 = none")] | None = None
    price: Annotated[float, Ranged("price")] | None = None
    motors: Annotated[list[Text] | None, OneOrList("string")] = Field(
        None, description="motor ids or patterns ('SGM7J-*') the drive suits; omitted: "
                          "matched by rule (continuous current >= the motor's, "
                          "continuous_torque / torque_constant)")
    source: Text | None = None
    part_number: Text | None = None
    manufacturer: Text | None = None
    figure_sources: FigureSourcesInput | None = None
    notes: Text | None = Field(None, description="free text, ignored by the tool")

    @model_validator(mode="after")
    def _levels(self) -> Self:
        """Peak current >= continuous; the bus levels consistent (bus_level_fault)."""
        from sizer.model.machine import bus_level_fault

        if self.peak_current < self.continuous_current:
            raise PydanticCustomError(
                "peak_below_continuous", f"peak current {self.peak_current:g} A is below the "
                f"continuous current {self.continuous_current:g} A", {"at": ("peak_current",)})
        fault = bus_level_fault(self.dc_bus_voltage, self.braking_threshold,
                                self.max_bus_voltage, voltage_name="dc_bus_voltage")
        if fault is not None:
            raise PydanticCustomError("bus_levels", fault[1], {"at": (fault[0],)})
        return self


class CatalogFile(Strict):
    """A motor catalog file."""

    catalog: Text | None = Field(None, description="the catalog's name")
    manufacturer: Text | None = Field(None, description="default for the motors")
    source: Text | None = Field(None, description="default for the motors")
    sources: Sources | None = None
    default_source: SourceKey | None = None
    notes: Text | None = Field(None, description="free text, ignored by the tool")
    motors: list[MotorInput] = Field(description="at least one motor")
    drives: list[DriveInput] | None = Field(
        None, description="drives (amplifiers) for these motors; a design that loads this "
                          "catalog pairs its motors with them")

    @model_validator(mode="after")
    def _provenance(self) -> Self:
        """default_source and figure_sources name sources and figures of the file."""
        rows: list[tuple[tuple[Any, ...], Strict]] = [
            (("motors", i), m) for i, m in enumerate(self.motors)]
        rows += [(("drives", i), d) for i, d in enumerate(self.drives or ())]
        check_provenance(self.sources, self.default_source, rows)
        return self


class DriveCatalogFile(Strict):
    """A drive catalog file (named by a design's ``drives:``)."""

    catalog: Text | None = Field(None, description="the catalog's name")
    manufacturer: Text | None = Field(None, description="default for the drives")
    source: Text | None = Field(None, description="default for the drives")
    sources: Sources | None = None
    default_source: SourceKey | None = None
    notes: Text | None = Field(None, description="free text, ignored by the tool")
    drives: list[DriveInput] = Field(description="at least one drive")

    @model_validator(mode="after")
    def _provenance(self) -> Self:
        """default_source and figure_sources name sources and figures of the file."""
        check_provenance(self.sources, self.default_source,
                         [(("drives", i), d) for i, d in enumerate(self.drives)])
        return self


# ---------------------------------------------------------------- design


def _duration(value: Any) -> float | None:
    if isinstance(value, str) and value.strip().lower() == "minimize":
        return None
    return convert_in(value, "duration")


def _duration_or_master(schema: dict[str, Any]) -> None:
    """The task's schema: a duration or a master speed, one of the two."""
    required = schema.get("required", [])
    if "duration" in required:
        required.remove("duration")
    schema["oneOf"] = [{"required": ["duration"]}, {"required": ["master_speed"]}]


class TaskInput(Strict):
    """The motion task: a move of h in T, then a dwell (and a move back)."""

    model_config = ConfigDict(json_schema_extra=lambda schema, _: _duration_or_master(schema))

    displacement: Annotated[RawValue, RawQuantity(
        "'90 deg' or '200 mm'", rotary="angle_displacement",
        linear="length_displacement")] | None = Field(
        None,
        description="h at the load: an angle ('90 deg', rotary axis) or a length "
                    "('200 mm', linear axis); a bare number is rad; negative moves back "
                    "first (not zero); omitted, the displacement of laws defined by data "
                    "with units of their own")
    duration: Annotated[
        float | None,
        BeforeValidator(_duration),
        WithJsonSchema({"anyOf": [{"type": "number", "minimum": RANGES["duration"].low,
                                   "maximum": RANGES["duration"].high},
                                  quantity_text("minimize")],
                        "description": "T, time like '0.25 s', or 'minimize'; must be "
                                       f"{RANGES['duration'].text()} (SI)"}),
        RangeRef("duration"),
    ]
    dwell: Annotated[float, Ranged("dwell")] = 0.0
    return_move: StrictBool = Field(False, alias="return",
                                    description="cycle = move, dwell, move back, dwell")
    master_speed: Annotated[float, Ranged(
        "master_speed", note="instead of the duration: the move lasts the master angle of "
                             "its laws (a cam law on a master axis, units: {time: deg}) at "
                             "this speed")] | None = None

    @model_validator(mode="before")
    @classmethod
    def _duration_or_master(cls, data: Any) -> Any:
        """The duration, or the master speed of a cam on a master axis: one of the two
        (the loader computes the duration of the second)."""
        if isinstance(data, dict) and data.get("master_speed") is not None:
            if "duration" in data:
                raise ValueError("give the duration or the master_speed, not both")
            data = {**data, "duration": "minimize"}
        return data


class GravityInput(Strict):
    """Gravity on an arm (rotary axis): tau = m g r cos(q + q0), q the load's rotation from
    the start of the move (docs/position-loads.md)."""

    mass: Annotated[float, Ranged("arm_mass", note="m: the arm's and payload's mass")]
    radius: Annotated[float, Ranged("arm_radius", note="r: from the axis to their centre of "
                                                       "mass")]
    offset: Annotated[float, Ranged("arm_angle", note="q0: the arm's angle above the "
                                                      "horizontal at the start, e.g. "
                                                      "'-30 deg'; default 0")] | None = None
    g: Annotated[float, Ranged("gravity", note="default 9.80665 m/s^2")] | None = None


class SpringInput(Strict):
    """A spring on the load (rotary axis): tau = k (q - q_free) + preload, positive
    opposing a positive move (docs/position-loads.md)."""

    stiffness: Annotated[float, Ranged("spring_rotary_stiffness", note="k, e.g. "
                                                                      "'2 N*m/rad'")]
    preload: Annotated[float, Ranged("spring_rotary_preload", note="its torque at the free "
                                                                   "position; default 0")
                       ] | None = None
    free_position: Annotated[float, Ranged("spring_free_angle", note="q_free, from the "
                                                                     "start of the move; "
                                                                     "default 0")
                             ] | None = None


TablePoint = tuple[Annotated[float, Ranged("table_angle")],
                   Annotated[float, Ranged("table_torque")]]
"""A torque table's point [q, tau], each a number (SI) or a text with its unit."""


class TorqueTableInput(Strict):
    """A torque of the load's position (rotary axis) as a table, linear between its points,
    positive opposing a positive move (docs/position-loads.md): ``points`` or ``file``."""

    points: Annotated[list[TablePoint], RangeRef("table_angle"),
                      RangeRef("table_torque")] | None = Field(
        None, description="[[q, tau], ...], e.g. [[0 deg, 1.5 N*m], [30 deg, 2.2 N*m]], q "
                          "strictly increasing")
    file: str | None = Field(
        None, description="a CSV file (relative to the design): its first two columns q "
                          "and tau, units in the header, e.g. 'q [deg],tau [N*m]'")
    offset: Annotated[float, Ranged("table_angle", note="the table's q at the start of the "
                                                        "move; default 0")] | None = None


ForcePoint = tuple[Annotated[float, Ranged("table_length")],
                   Annotated[float, Ranged("table_force")]]
"""A force table's point [s, F], each a number (SI) or a text with its unit."""


class ForceTableInput(Strict):
    """A force of the load's position (linear axis) as a table, linear between its points,
    positive opposing a positive move (docs/position-loads.md): ``points`` or ``file``."""

    points: Annotated[list[ForcePoint], RangeRef("table_length"),
                      RangeRef("table_force")] | None = Field(
        None, description="[[s, F], ...], e.g. [[0 mm, 20 N], [50 mm, 180 N]], s strictly "
                          "increasing")
    file: str | None = Field(
        None, description="a CSV file (relative to the design): its first two columns s "
                          "and F, units in the header, e.g. 's [mm],F [N]'")
    offset: Annotated[float, Ranged("table_length", note="the table's s at the start of the "
                                                         "move; default 0")] | None = None


InertiaPoint = tuple[Annotated[float, Ranged("table_angle")],
                     Annotated[float, Ranged("table_inertia")]]
"""An inertia table's point [q, J], each a number (SI) or a text with its unit."""


class InertiaTableInput(Strict):
    """An inertia of the load's position (rotary axis) as a table, added to load.inertia,
    a monotone cubic (PCHIP) between its points (docs/position-loads.md)."""

    points: Annotated[list[InertiaPoint], RangeRef("table_angle"),
                      RangeRef("table_inertia")] | None = Field(
        None, description="[[q, J], ...], e.g. [[0 deg, 0.02 kg*m^2], [90 deg, "
                          "0.08 kg*m^2]], q strictly increasing")
    file: str | None = Field(
        None, description="a CSV file (relative to the design): its first two columns, "
                          "units in the header, e.g. 'q [deg],J [kg*m^2]'")
    offset: Annotated[float, Ranged("table_angle", note="the table's q at the start of the "
                                                        "move; default 0")] | None = None


MassPoint = tuple[Annotated[float, Ranged("table_length")],
                  Annotated[float, Ranged("table_mass")]]
"""A mass table's point [s, m], each a number (SI) or a text with its unit."""


class MassTableInput(Strict):
    """A mass of the load's position (linear axis) as a table, added to load.mass, a
    monotone cubic (PCHIP) between its points (docs/position-loads.md)."""

    points: Annotated[list[MassPoint], RangeRef("table_length"),
                      RangeRef("table_mass")] | None = Field(
        None, description="[[s, m], ...], e.g. [[0 mm, 2 kg], [200 mm, 5 kg]], s strictly "
                          "increasing")
    file: str | None = Field(
        None, description="a CSV file (relative to the design): its first two columns, "
                          "units in the header, e.g. 's [mm],m [kg]'")
    offset: Annotated[float, Ranged("table_length", note="the table's s at the start of the "
                                                         "move; default 0")] | None = None


class LoadInput(InlineTolerances):
    """The load at the load side; rotary fields or linear ones, per the displacement.

    A quantity may carry its tolerance ('0.35 kg*m^2 +- 20 %', INLINE_TOLERANCE_FIELDS):
    the field keeps the quantity, :attr:`inline_tolerances` the tolerance's text."""

    inline_fields: ClassVar[tuple[str, ...]] = INLINE_TOLERANCE_FIELDS

    inertia: Annotated[RawValue, RawQuantity(
        "'0.35 kg*m^2'", rotary="load_inertia")] | None = Field(
        None, description="rotary axis: J_l, e.g. '0.35 kg*m^2'")
    mass: Annotated[RawValue, RawQuantity("'12 kg'", linear="load_mass")] | None = Field(
        None, description="linear axis: moving mass, e.g. '12 kg'")
    damping: Annotated[RawValue, RawQuantity(
        "'0.01 N*m*s/rad' or '5 N*s/m'", rotary="load_rotary_damping",
        linear="load_linear_damping")] | None = Field(
        None, description="viscous B_l: 'N*m*s/rad' (rotary) or 'N*s/m' (linear)")
    friction: Annotated[RawValue, RawQuantity(
        "'0.2 N*m' or '10 N'", rotary="load_friction_torque",
        linear="load_friction_force")] | None = Field(
        None, description="Coulomb friction magnitude: N*m (rotary) or N (linear)")
    torque: Annotated[RawValue, RawQuantity("'0.5 N*m'", rotary="load_torque")] | None = Field(
        None, description="rotary axis: constant external torque, positive opposes the move")
    force: Annotated[RawValue, RawQuantity("'50 N'", linear="load_force")] | None = Field(
        None, description="linear axis: constant external force, positive opposes the move")
    incline: Annotated[float, Ranged(
        "incline", note="linear axis: angle from the horizontal, 90 deg = vertical; "
                        "gravity opposes a positive move")] | None = None
    friction_coefficient: Annotated[float, Ranged(
        "friction_coefficient", note="linear axis: Coulomb mu, friction = mu m g "
                                     "cos(incline), added to friction")] | None = None
    natural_frequency: Annotated[float, Ranged(
        "natural_frequency", note="the load's mode (sec. 7.1.1), e.g. '25 Hz': sizer then "
                                  "gives each move's residual vibration")] | None = None
    damping_ratio: Annotated[float, Ranged(
        "damping_ratio", note="of that mode, delta in [0, 1); default 0")] | None = None
    gravity: GravityInput | None = Field(
        None, description="rotary axis: gravity on an arm, m g r cos(q + q0) "
                          "(docs/position-loads.md)")
    spring: SpringInput | None = Field(
        None, description="rotary axis: a spring, k (q - q_free) + preload "
                          "(docs/position-loads.md)")
    torque_table: TorqueTableInput | None = Field(
        None, description="rotary axis: a torque of the position as a table, linear between "
                          "its points (docs/position-loads.md)")
    force_table: ForceTableInput | None = Field(
        None, description="linear axis: a force of the position as a table, linear between "
                          "its points (docs/position-loads.md)")
    inertia_table: InertiaTableInput | None = Field(
        None, description="rotary axis: an inertia of the position as a table, added to "
                          "inertia, with its velocity term 1/2 J'(q) q'^2 "
                          "(docs/position-loads.md)")
    mass_table: MassTableInput | None = Field(
        None, description="linear axis: a mass of the position as a table, added to mass, "
                          "with its velocity term 1/2 m'(s) s'^2 (docs/position-loads.md)")


def _motor_ref_tag(value: Any) -> str:
    return "catalog-name" if isinstance(value, str) else "inline-motor"


MotorRef = Annotated[
    Annotated[str, Tag("catalog-name")] | Annotated[MotorInput, Tag("inline-motor")],
    Discriminator(_motor_ref_tag),
]
"""A catalog (file path or bundled name) or an inline motor mapping."""


class CheckInput(Strict):
    """The motor and law that ``sizer check`` verifies."""

    motor: Identifier | None = Field(None, description="a motor id among the loaded motors")
    law: LawSpecText | None = None


class LimitsInput(Strict):
    """Margins and user limits (all optional)."""

    torque_margin: Annotated[float, Ranged(
        "margin", note="fraction of torque capability left unused")] = 0.0
    speed_margin: Annotated[float, Ranged(
        "margin", note="fraction of speed capability left unused")] = 0.0
    inertia_ratio: Annotated[float, Ranged(
        "inertia_ratio", note="max J_load reflected / J_motor")] | None = None
    max_speed: Annotated[RawValue, RawQuantity(
        "'300 rpm' or '2 m/s'", rotary="load_max_angular_speed",
        linear="load_max_linear_speed")] | None = Field(
        None, description="at the load: rad/s or rpm (rotary), m/s or m/min (linear: a "
                          "belt's or a screw's maximum linear speed)")
    max_acceleration: Annotated[RawValue, RawQuantity(
        "'500 rad/s^2' or '20 m/s^2'", rotary="load_max_angular_acceleration",
        linear="load_max_linear_acceleration")] | None = Field(
        None, description="at the load: rad/s^2 (rotary) or m/s^2 (linear)")
    max_jerk: Annotated[RawValue, RawQuantity(
        "'1e5 rad/s^3' or '1000 m/s^3'", rotary="load_max_angular_jerk",
        linear="load_max_linear_jerk")] | None = Field(
        None, description="at the load: rad/s^3 (rotary) or m/s^3 (linear)")
    residual_vibration: Annotated[RawValue, RawQuantity(
        "'0.05 mm' or '0.01 deg'", rotary="residual_angle",
        linear="residual_length")] | None = Field(
        None, description="at the load: the largest amplitude of the vibration a move may "
                          "leave (needs load.natural_frequency); m or mm (linear), rad or deg "
                          "(rotary)")
    thermal_speed: Literal["max", "rms", "mean"] = Field(
        "max", description="speed at which the RMS torque is checked against the "
                           "continuous region")
    inertia_ratio_of: Literal["driven", "load"] = Field(
        "driven", description="numerator of inertia_ratio: 'driven' = everything the motor "
                              "drives (load, screws, gears, couplings) reflected to the motor, "
                              "as vendors define it; 'load' = the load alone")
    drive_current_margin: Annotated[float, Ranged(
        "margin", note="fraction of a drive's currents left unused")] = 0.0
    braking_resistor_power: Annotated[float, Ranged(
        "braking_power", note="W: the largest continuous power of the braking "
                              "resistor (overrides the drives' "
                              "braking_resistor_power)")] | None = None
    winding_temperature_rise: Annotated[float, Ranged(
        "winding_temperature_rise", note="K over the ambient, e.g. '80 K': the largest "
                                         "winding rise (overrides the motors' "
                                         "max_winding_temperature_rise)")] | None = None
    thermal_duty: Literal["repeated", "once"] = Field(
        "repeated", description="how the cycle heats the winding (motors with "
                                "thermal_time_constant and max_winding_temperature_rise): "
                                "'repeated' (its periodic steady state) or 'once' (a "
                                "one-off run from the ambient: the winding model decides, "
                                "not the RMS check; given durations only)")
    envelope: EnvelopeRule = Field(
        DEFAULT_ENVELOPE, description="how a motor region without a curve is completed up "
                                      "to max_speed: book (rectangles up to the rated "
                                      "speed), linear (then straight lines down to "
                                      "max_speed), linear_intermittent (only the "
                                      "intermittent region extended) or electrical (the "
                                      "region the winding's supply allows where the motor "
                                      "gives its winding data, else linear)")


EFFICIENCY_ALIASES = {"siemens": "power_flow", "mitsubishi": "power_flow",
                      "yaskawa": "steady_load"}
"""Vendor names for the efficiency conventions (sizer.mechanics.drive)."""


def _efficiency_rule(value: Any) -> Any:
    if isinstance(value, str):
        key = value.strip().lower()
        return EFFICIENCY_ALIASES.get(key, key)
    return value


class DesignFile(Strict):
    """A design file: the task (or a cycle), the load, the transmission, laws, motors and
    limits."""

    model_config = ConfigDict(json_schema_extra=not_null(
        "task", "cycle", oneOf=[{"required": ["task"]}, {"required": ["cycle"]}]))

    name: Text | None = None
    task: Annotated[TaskInput | None, BeforeValidator(given)] = Field(
        None, description="one move, a dwell and an optional return; or give `cycle`")
    cycle: Annotated[CycleInput | None, BeforeValidator(given)] = Field(
        None, description="a machine cycle of segments (moves, runs, dwells); instead of "
                          "`task`")
    load: LoadInput = Field(
        default_factory=lambda: LoadInput.model_validate({}),
        description="required (its inertia or mass), but for a plan without a motor "
                    "(docs/planning.md)")
    transmission: Annotated[list[TransmissionStageInput] | None,
                            OneOrList("object")] = Field(
        None, description="one stage (a mapping) or a list of stages from the motor to the "
                          "load; omitted = direct drive")
    laws: Annotated[list[LawSpecText] | None, OneOrList("string")] = Field(
        None, min_length=1, description="law specs; omitted = the default laws")
    motors: Annotated[list[MotorRef] | None, OneOrList("string")] = Field(
        None, description="catalog paths (relative to this file), bundled catalog names "
                          "or inline motors; omitted: the bundled catalogs, or with "
                          "limits.max_speed, max_acceleration or max_jerk (and [] with "
                          "them) a plan without a motor (docs/planning.md)")
    drives: Annotated[list[Text] | None, OneOrList("string")] = Field(
        None, min_length=1,
        description="drive catalogs (paths relative to this file, or bundled names): "
                    "each motor is paired with each compatible drive")
    check: CheckInput | None = None
    limits: LimitsInput = Field(default_factory=lambda: LimitsInput.model_validate({}))
    tolerances: dict[str, ToleranceValue] | None = Field(
        None, description="tolerances of inputs for `sizer size --robust` (docs/robust.md), "
                          "e.g. {load.inertia: 20 %, load.friction: 2 N*m, "
                          "motor.peak_torque: {distribution: normal, sigma: 5 %}}: relative "
                          "or absolute, uniform or normal (truncated)")
    efficiency_applies_to: Annotated[
        Literal["power_flow", "steady_load"],
        BeforeValidator(_efficiency_rule),
        WithJsonSchema({"type": "string",
                        "enum": ["power_flow", "steady_load", *EFFICIENCY_ALIASES],
                        "description": "how stage efficiencies act: 'power_flow' (default; "
                                       "alias siemens, mitsubishi) on the whole torque in the "
                                       "direction of power flow, 'steady_load' (alias yaskawa) "
                                       "on the load's steady torque only"}),
    ] = "power_flow"

    @model_validator(mode="after")
    def _task_or_cycle(self) -> Self:
        """One of ``task`` and ``cycle``: the error at the field to add or remove."""
        if self.task is None and self.cycle is None:
            raise PydanticCustomError("missing", "required field is missing",
                                      {"at": ("task",)})
        if self.task is not None and self.cycle is not None:
            raise PydanticCustomError("task_and_cycle", "give `task:` (one move, a dwell, a "
                                      "return) or `cycle:` (segments), not both",
                                      {"at": ("cycle",)})
        check_provenance(None, None, [(("motors", i), m) for i, m in
                                      enumerate(self.motors or ()) if isinstance(m, MotorInput)])
        return self
