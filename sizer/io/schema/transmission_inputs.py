"""Input models of the transmission stages and of gearbox catalog files (YAML).

A stage's ``ratio`` may be a number, a list of ratios to try, ``optimize`` (between 1 and
100) or ``{optimize: [min, max]}``; a gearbox may instead name a gearbox ``catalog``
whose ratios are the options. Quantities are converted to SI like the other inputs.
"""


from typing import Annotated, Any, Literal, Self

from pydantic import BaseModel, BeforeValidator, Field, WithJsonSchema, model_validator

from sizer.io.schema.inputs_base import (
    Ranged,
    RangeRef,
    Strict,
    Text,
    convert_in,
    quantity_text,
    show_value,
)
from sizer.io.schema.provenance import (
    FigureSourcesInput,
    SourceKey,
    Sources,
    check_provenance,
)
from sizer.io.schema.ranges import RANGES
from sizer.mechanics.stages import STEEL_DENSITY, Mounting

DEFAULT_RATIO_BOUNDS = (1.0, 100.0)

RatioSpec = tuple[str, tuple[float, ...]]
"""("fixed", (k,)), ("list", (k1, k2, ...)) or ("optimize", (min, max))."""


def _ratio_of(name: str) -> Any:
    """The parser of a ratio field whose ratios lie in ``RANGES[name]``."""

    def parse(value: Any) -> RatioSpec:
        if isinstance(value, str) and value.strip().lower() == "optimize":
            return ("optimize", DEFAULT_RATIO_BOUNDS)
        if isinstance(value, dict):
            if set(value) != {"optimize"}:
                raise ValueError(f"a ratio is a number, a list, 'optimize' or {{optimize: "
                                 f"[min, max]}}, got {show_value(value)}")
            bounds = value["optimize"]
            if not isinstance(bounds, list) or len(bounds) != 2:
                raise ValueError(f"optimize takes [min, max], got {show_value(bounds)}")
            lo, hi = (convert_in(b, name) for b in bounds)
            if not hi > lo:
                raise ValueError(f"optimize bounds must have min < max, got [{lo:g}, {hi:g}]")
            return ("optimize", (lo, hi))
        if isinstance(value, list):
            if not value:
                raise ValueError("a list of ratios must not be empty")
            if len(value) > MAX_RATIO_OPTIONS:
                raise ValueError(f"a list of ratios holds at most {MAX_RATIO_OPTIONS}, got "
                                 f"{len(value)}")
            ratios = tuple(convert_in(v, name) for v in value)
            repeated = sorted({r for r in ratios if ratios.count(r) > 1})
            if repeated:
                raise ValueError(f"ratio {repeated[0]:g} is listed twice")
            return ("list", ratios)
        return ("fixed", (convert_in(value, name),))

    return parse


def _ratio_schema(name: str, optimize: bool) -> dict[str, Any]:
    allowed = RANGES[name]
    number = {"type": "number", "minimum": allowed.low, "maximum": allowed.high}
    item = {"anyOf": [number, quantity_text()]}
    branches: list[dict[str, Any]] = [
        number, {"type": "array", "minItems": 1, "maxItems": MAX_RATIO_OPTIONS,
                 "items": item}]
    if optimize:
        branches += [
            {"type": "string", "enum": ["optimize"]},
            {"type": "object", "properties": {"optimize": {
                "type": "array", "minItems": 2, "maxItems": 2, "items": item}},
             "required": ["optimize"], "additionalProperties": False}]
    return {"anyOf": branches,
            "description": f"input over output speed: a number, a list to try, 'optimize' "
                           f"(1 to 100) or {{optimize: [min, max]}}; ratios must be "
                           f"{allowed.text()}"}




MAX_RATIO_OPTIONS = 1000
"""At most this many ratios in a list (each is a candidate for every motor and law)."""

Ratio = Annotated[Any, BeforeValidator(_ratio_of("gear_ratio")),
                  WithJsonSchema(_ratio_schema("gear_ratio", True)), RangeRef("gear_ratio")]
"""A stage's ratio field (fixed, list or optimize) with its ratios in ``RANGES[name]``."""
BeltRatio = Annotated[Any, BeforeValidator(_ratio_of("belt_ratio")),
                      WithJsonSchema(_ratio_schema("belt_ratio", True)), RangeRef("belt_ratio")]
Efficiency = Annotated[float, Ranged("efficiency")]
Inertia = Annotated[float, Ranged("stage_inertia", note="reflected to the stage input")]
Speed = Annotated[float, Ranged("stage_speed")]
Torque = Annotated[float, Ranged("stage_torque")]
OutputRadialLoad = Annotated[float, Ranged(
    "shaft_load", note="the maker's permissible radial load on the gearbox's output shaft "
                       "(e.g. Beckhoff's F2RMax), docs/shaft-loads.md")]
OutputAxialLoad = Annotated[float, Ranged(
    "shaft_load", note="the maker's permissible axial load on the gearbox's output shaft "
                       "(e.g. Beckhoff's FaStat, F2AMax)")]
OutputRadialLoadLife = Annotated[float, Ranged(
    "shaft_load", note="the radial force on the gearbox's output shaft its maker rates for "
                       "the bearing life output_load_life (e.g. Beckhoff's 'radial force "
                       "for 20000 h'), against the cycle's equivalent force, "
                       "docs/shaft-loads.md")]
OutputAxialLoadLife = Annotated[float, Ranged(
    "shaft_load", note="the axial force on the gearbox's output shaft rated for the bearing "
                       "life output_load_life")]
OutputLoadLife = Annotated[float, Ranged(
    "bearing_life", note="the bearing life the output forces for a life are rated for, "
                         "e.g. '20000 h' (required with them)")]


def _on_gearbox_output() -> Any:
    return Field(False, description="the stage sits on the output shaft of the gearbox "
                                    "stage right before it: its load is checked against "
                                    "that gearbox's output_radial_load / output_axial_load "
                                    "(docs/shaft-loads.md)")


class GearboxInput(Strict):
    """A gearbox: motor speed = ratio x output speed. Or the ratios of a gearbox catalog."""

    type: Literal["gearbox"]
    ratio: Ratio | None = None
    catalog: Text | None = Field(
        None, description="a gearbox catalog file (relative to the design); its ratios are "
                          "the options, each with its own efficiency, inertia and limits")
    efficiency: Efficiency = 1.0
    inertia: Inertia = 0.0
    max_input_speed: Speed | None = None
    rated_output_torque: Torque | None = None
    peak_output_torque: Torque | None = None
    backlash: Annotated[float, Ranged("backlash", note="informative")] | None = None
    output_radial_load: OutputRadialLoad | None = None
    output_axial_load: OutputAxialLoad | None = None
    output_radial_load_life: OutputRadialLoadLife | None = None
    output_axial_load_life: OutputAxialLoadLife | None = None
    output_load_life: OutputLoadLife | None = None
    name: Text | None = None


class BeltInput(Strict):
    """A timing belt on two pulleys; as the last stage of a linear axis the load rides on it."""

    type: Literal["belt"]
    ratio: BeltRatio | None = None
    driver_diameter: Annotated[float, Ranged("pulley_diameter")] | None = None
    driven_diameter: Annotated[float, Ranged("pulley_diameter")] | None = None
    driver_inertia: Inertia = 0.0
    driven_inertia: Inertia = 0.0
    belt_mass: Annotated[float, Ranged("belt_mass")] = 0.0
    efficiency: Efficiency = 1.0
    on_motor_shaft: bool = Field(
        False, description="the driver pulley sits on the motor's shaft (the first stage): "
                           "its radial load is checked against the motor's radial_load "
                           "(needs pretension and driver_diameter)")
    pretension: Annotated[float, Ranged(
        "belt_pretension", note="static tension per strand as installed, e.g. "
                                "'200 N'")] | None = None
    wrap_angle: Annotated[float, Ranged(
        "wrap_angle", note="on the driver pulley; 180 deg for equal pulleys")] | None = None
    on_gearbox_output: bool = _on_gearbox_output()
    name: Text | None = None


class BallScrewInput(Strict):
    """A ball screw: ratio 2 pi / lead (rad/m)."""

    type: Literal["ball_screw"]
    lead: Annotated[float, Ranged("screw_lead", note="travel per screw turn")]
    efficiency: Efficiency = 0.9
    inertia: Inertia | None = None
    diameter: Annotated[float, Ranged("screw_diameter")] | None = None
    length: Annotated[float, Ranged("screw_length")] | None = None
    density: Annotated[float, Ranged(
        "density", note="of a screw given by diameter and length; vendors use "
                        "7.87e3 (Yaskawa) or 7.8e3 (Mitsubishi)")] = STEEL_DENSITY
    preload_torque: Annotated[float, Ranged("preload_torque")] = 0.0
    max_speed: Speed | None = None
    mounting: Mounting | None = Field(
        None, description="the screw shaft's end mounting (THK's names): with root_diameter "
                          "it adds the critical speed and buckling checks")
    root_diameter: Annotated[float, Ranged(
        "screw_diameter", note="the thread minor diameter d_r (THK: d_1) of the "
                               "datasheet")] | None = None
    support_distance: Annotated[float, Ranged(
        "screw_length", note="between the mounting surfaces, for the critical speed; "
                             "default: length")] | None = None
    buckling_length: Annotated[float, Ranged(
        "screw_length", note="between the nut (at its farthest) and the mounting that "
                             "takes the thrust; default: support_distance")] | None = None
    speed_factor: Annotated[float, Ranged(
        "screw_safety_factor", note="permissible share of the critical speed")] = 0.8
    buckling_factor: Annotated[float, Ranged(
        "screw_safety_factor", note="permissible share of the buckling load")] = 0.5
    dynamic_load_rating: Annotated[float, Ranged(
        "screw_load_rating", note="C_a of the datasheet, e.g. '12.3 kN'; with "
                                  "required_life it adds the life check")] | None = None
    load_factor: Annotated[float, Ranged("screw_load_factor")] = 1.0
    required_life: Annotated[float, Ranged(
        "screw_life", note="the L10 life the screw must reach, e.g. '20000 h'")] | None = None
    on_motor_shaft: bool = Field(
        False, description="the screw is coupled directly to the motor and the motor's "
                           "bearing takes its axial force: checked against the motor's "
                           "axial_load")
    on_gearbox_output: bool = _on_gearbox_output()
    name: Text | None = None


class RackPinionInput(Strict):
    """A rack and pinion: ratio 1/r (rad/m)."""

    type: Literal["rack_pinion"]
    pitch_radius: Annotated[float, Ranged("pitch_radius")] | None = None
    pitch_diameter: Annotated[float, Ranged("pitch_diameter")] | None = None
    inertia: Inertia = 0.0
    efficiency: Efficiency = 1.0
    on_motor_shaft: bool = Field(
        False, description="the pinion sits on the motor's shaft (the only stage): its "
                           "tooth force is checked against the motor's radial_load")
    pressure_angle: Annotated[float, Ranged(
        "gear_pressure_angle", note="default 20 deg (the standard basic rack)")] | None = None
    on_gearbox_output: bool = _on_gearbox_output()
    name: Text | None = None


Length = Annotated[float, Ranged("link_length")]
LinkMass = Annotated[float, Ranged("link_mass", note="a point mass at the joint")]
LawOn = Literal["crank", "output"]


def _no_bool(value: Any) -> Any:
    """A YAML true/false is not the number 1/0 (pydantic would take True for 1)."""
    if isinstance(value, bool):
        raise ValueError(f"expected 1 or -1, got {value}")
    return value


Branch = Annotated[Literal[1, -1], BeforeValidator(_no_bool)]
"""A four-bar's assembly: 1 (open) or -1 (crossed), a number, not a boolean."""


class _LinkageInput(Strict):
    """What every linkage stage has (seed 003): where the motion law is given, the crank's
    start and turning direction, the crank's inertia and the connecting link as two point
    masses. The load (``load:``) is the linkage's output."""

    law_on: LawOn = Field("crank", description="crank: the law moves the crank by the task's "
                          "displacement (an angle); output: the law moves the output (the "
                          "slider or the rocker) and the crank follows by inverse kinematics")
    start_angle: Annotated[float, Ranged("crank_angle")] = 0.0
    direction: Literal["positive", "negative"] = Field(
        "positive", description="the crank's turning direction during the move")
    crank_inertia: Inertia = 0.0
    name: Text | None = None


class SliderCrankInput(_LinkageInput):
    """A slider-crank: the motor turns the crank; the output is the slider (linear) or
    the rod's angle."""

    type: Literal["slider_crank"]
    output: Literal["slider_position", "rod_angle"] | None = Field(
        None, description="the load's coordinate: slider_position (default; the load is "
                          "linear) or rod_angle (the rod's angle to the slider's line, "
                          "rotary)")
    crank_radius: Length
    rod_length: Length
    offset: Annotated[float, Ranged("link_offset")] = 0.0
    rod_mass_at_crank: LinkMass = 0.0
    rod_mass_at_slider: LinkMass = 0.0


class FourBarInput(_LinkageInput):
    """A four-bar crank-rocker: the motor turns the crank (or the rocker); the output is
    the rocker's, the coupler's or (rocker driven) the crank's angle."""

    type: Literal["four_bar"]
    driven_link: Literal["crank", "rocker"] = Field(
        "crank", description="the link the motor (the stages before) turns: crank, or "
                             "rocker (the linkage read the other way; its dead points are "
                             "where crank and coupler are in line)")
    output: Literal["rocker_angle", "coupler_angle", "crank_angle"] | None = Field(
        None, description="the load's coordinate: rocker_angle (default with the crank "
                          "driven) or coupler_angle; with the rocker driven crank_angle "
                          "(default) or coupler_angle")
    crank: Length
    coupler: Length
    rocker: Length
    ground: Length
    branch: Branch = Field(1, description="the assembly: 1 open, -1 crossed")
    coupler_mass_at_crank: LinkMass = 0.0
    coupler_mass_at_rocker: LinkMass = 0.0


def _base_radius(value: Any) -> float | None:
    """``auto`` (None: the smallest that keeps the checks) or a length in its range."""
    if isinstance(value, str) and value.strip().lower() == "auto":
        return None
    return convert_in(value, "cam_radius")


CamBaseRadius = Annotated[Any, BeforeValidator(_base_radius), WithJsonSchema({
    "anyOf": [{"type": "number", "minimum": RANGES["cam_radius"].low,
               "maximum": RANGES["cam_radius"].high}, quantity_text(),
               {"type": "string", "enum": ["auto"]}],
    "description": "the base circle's radius of the cam's profile, or 'auto' (the smallest "
                   "that keeps the pressure angle and curvature checks)"}),
    RangeRef("cam_radius")]
"""A cam's base radius: a length or ``auto``."""


class DiscCamInput(Strict):
    """A disc cam with a translating or oscillating roller follower (docs/disc-cams.md):
    the motor turns the cam (one turn per machine cycle, at constant speed); the output
    is the follower, whose lift over the cam angle is the task's or cycle's motion (a
    length, or an angle for an oscillating follower)."""

    type: Literal["disc_cam"]
    follower: Literal["translating_roller", "oscillating_roller"] = Field(
        "translating_roller", description="the follower: translating_roller (default) or "
                                          "oscillating_roller (an arm on a pivot)")
    base_radius: CamBaseRadius
    roller_radius: Annotated[float, Ranged("cam_radius")]
    offset: Annotated[float, Ranged("cam_offset")] = 0.0
    pivot_distance: Annotated[float, Ranged("cam_radius")] | None = Field(
        None, description="an oscillating follower: its pivot's distance from the cam's "
                          "centre")
    arm_length: Annotated[float, Ranged("cam_radius")] | None = Field(
        None, description="an oscillating follower: from its pivot to the roller's centre")
    pressure_angle: Annotated[float, Ranged("pressure_angle")] | None = Field(
        None, description="the pressure angle's limit (default 30 deg translating, 45 deg "
                          "oscillating)")
    follower_mass: Annotated[float, Ranged("follower_mass")] = 0.0
    cam_inertia: Inertia = 0.0
    spring_preload: Annotated[float, Ranged("spring_force")] | None = Field(
        None, description="a force-closed translating follower: the spring's force with "
                          "the follower on the base circle (its lowest)")
    spring_force_at_top: Annotated[float, Ranged("spring_force")] | None = Field(
        None, description="the spring's force at the follower's highest lift (default: the "
                          "preload, a constant force)")
    spring_torque_preload: Annotated[float, Ranged("spring_torque")] | None = Field(
        None, description="a force-closed oscillating follower: the spring's torque on the "
                          "arm with the roller on the base circle")
    spring_torque_at_top: Annotated[float, Ranged("spring_torque")] | None = Field(
        None, description="the spring's torque at the arm's largest swing (default: the "
                          "preload)")
    name: Text | None = None


class DirectInput(Strict):
    """Direct drive: the motor turns (or, a linear motor, moves) the load (no stage)."""

    type: Literal["direct"]
    name: Text | None = None


TransmissionStageInput = Annotated[
    GearboxInput | BeltInput | BallScrewInput | RackPinionInput | DirectInput
    | SliderCrankInput | FourBarInput | DiscCamInput,
    Field(discriminator="type"),
]
"""One transmission stage, told apart by ``type``."""

TRANSMISSION_TYPES: tuple[str, ...] = ("gearbox", "belt", "ball_screw", "rack_pinion", "direct",
                                       "slider_crank", "four_bar", "disc_cam")
LINEAR_OUTPUT_TYPES: tuple[str, ...] = ("ball_screw", "rack_pinion", "belt", "slider_crank",
                                        "disc_cam")
LINKAGE_TYPES: tuple[str, ...] = ("slider_crank", "four_bar", "disc_cam")

# ------------------------------------------------------------ gearbox catalog


class GearboxRatioInput(Strict):
    """One ratio of a gearbox series, with what differs per ratio."""

    ratio: Annotated[float, Ranged("gear_ratio")]
    inertia: Inertia = 0.0
    efficiency: Efficiency | None = None
    max_input_speed: Speed | None = None
    rated_output_torque: Torque | None = None
    peak_output_torque: Torque | None = None
    figure_sources: FigureSourcesInput | None = None


class GearboxSeriesInput(Strict):
    """A gearbox series: shared figures, and its ratios."""

    id: Text = Field(description="series or part id, unique in the file")
    efficiency: Efficiency = 1.0
    max_input_speed: Speed | None = None
    rated_output_torque: Torque | None = None
    peak_output_torque: Torque | None = None
    backlash: Annotated[float, Ranged("backlash")] | None = None
    output_radial_load: OutputRadialLoad | None = None
    output_axial_load: OutputAxialLoad | None = None
    output_radial_load_life: OutputRadialLoadLife | None = None
    output_axial_load_life: OutputAxialLoadLife | None = None
    output_load_life: OutputLoadLife | None = None
    source: Text | None = None
    figure_sources: FigureSourcesInput | None = None
    notes: Text | None = None
    ratios: list[GearboxRatioInput] = Field(min_length=1)


class GearboxCatalogFile(Strict):
    """A gearbox catalog file."""

    catalog: Text | None = None
    manufacturer: Text | None = None
    source: Text | None = None
    sources: Sources | None = None
    default_source: SourceKey | None = None
    notes: Text | None = None
    gearboxes: list[GearboxSeriesInput] = Field(min_length=1)

    @model_validator(mode="after")
    def _provenance(self) -> Self:
        """default_source and figure_sources name sources and figures of the file."""
        rows: list[tuple[tuple[Any, ...], BaseModel]] = []
        for i, series in enumerate(self.gearboxes):
            rows.append((("gearboxes", i), series))
            rows += [(("gearboxes", i, "ratios", k), r) for k, r in enumerate(series.ratios)]
        check_provenance(self.sources, self.default_source, rows)
        return self
