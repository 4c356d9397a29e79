"""Build the transmission (and its free ratio) of a design file, and read gearbox catalogs.

Checks that span fields: at most one stage with a free ratio; a linear axis ends in a
stage that turns rotation into travel (ball screw, rack and pinion, belt) unless it is a
direct (linear motor) drive, and a rotary axis has no such stage; a ball screw needs its
inertia or diameter and length; a belt its ratio or diameters.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Sequence
from importlib import resources
from pathlib import Path
from typing import Any, Literal

from sizer.io.linkage import linkage_stage
from sizer.io.schema.provenance import file_sources, gearbox_sources
from sizer.io.schema.ranges import TOTAL_EFFICIENCY, TOTAL_RATIO, number_text
from sizer.io.schema.transmission_inputs import (
    LINEAR_OUTPUT_TYPES,
    BallScrewInput,
    BeltInput,
    DirectInput,
    DiscCamInput,
    FourBarInput,
    GearboxCatalogFile,
    GearboxInput,
    GearboxSeriesInput,
    RackPinionInput,
    SliderCrankInput,
)
from sizer.io.validation import validate
from sizer.io.yaml_source import YamlSource, read_yaml
from sizer.mechanics import ball_screw, belt, gearbox, rack_pinion
from sizer.mechanics.stages import ScrewRatings
from sizer.model.domain import GearboxOption, RatioChoice, ShaftLoad, Stage, Transmission


def build_transmission(items: Sequence[Any] | None, source: YamlSource, folder: Path,
                       linear: bool, files: list[Path]
                       ) -> tuple[Transmission, RatioChoice | None, tuple[Any, ...]]:
    """The stages from motor to load, the free ratio if a stage has one, and where the
    linkage stage's ``start_angle`` is written; the gearbox catalogs read go to ``files``."""
    items = list(items or ())
    as_list = isinstance(source.data, dict) and isinstance(source.data.get("transmission"),
                                                           list)

    def at(index: int, *keys: Any) -> tuple[Any, ...]:
        return ("transmission", index, *keys) if as_list else ("transmission", *keys)

    moving = [i for i, item in enumerate(items) if not isinstance(item, DirectInput)]
    if linear and moving and items[moving[-1]].type not in LINEAR_OUTPUT_TYPES:
        raise source.error("a linear axis (the displacement is a length) needs a last stage "
                           "that turns rotation into travel: ball_screw, rack_pinion or belt "
                           "(or a direct drive by a linear motor)", at(moving[-1], "type"))
    stages: list[Stage] = []
    choice: RatioChoice | None = None
    choice_at: tuple[Any, ...] = ()
    linkage = None
    linkage_at: tuple[Any, ...] = ()
    for index, item in enumerate(items):
        if isinstance(item, DirectInput):
            continue
        if isinstance(item, SliderCrankInput | FourBarInput | DiscCamInput):
            if index != moving[-1]:
                raise source.error(f"a {item.type} must be the last stage of the "
                                   f"transmission: its output is the load", at(index, "type"))
            linkage = linkage_stage(item, source, at(index))
            linkage_at = at(index, "start_angle") if item.type != "disc_cam" else at(index)
            continue
        last = index == moving[-1]
        if item.type in ("ball_screw", "rack_pinion") and not linear:
            raise source.error(f"a {item.type} moves a linear axis, but the displacement is an "
                               f"angle (give it as a length, e.g. '200 mm')", at(index, "type"))
        stage, free = _stage(item, source, at, index, linear and last, folder, files)
        shaft = _shaft_load(item, source, at(index), first=not stages,
                            last=last and linear,
                            after_gearbox=bool(stages) and stages[-1].kind == "gearbox")
        if shaft is not None:
            stage = dataclasses.replace(stage, shaft_load=shaft)
        if free is not None:
            if choice is not None:
                raise source.error(f"only one stage may have a free ratio (the one at line "
                                   f"{source.line_of(choice_at)} has one too)", at(index))
            choice = dataclasses.replace(free, stage=len(stages))
            choice_at = at(index)
        stages.append(stage)
    _check_total_ratio(stages, choice, source, linear and linkage is None)
    return Transmission(tuple(stages), linkage=linkage), choice, linkage_at


def _check_total_ratio(stages: Sequence[Stage], choice: RatioChoice | None,
                       source: YamlSource, linear: bool) -> None:
    """The product of the stage ratios (every option of a free ratio) in TOTAL_RATIO, the
    product of their efficiencies at least TOTAL_EFFICIENCY."""
    if not stages:
        return
    fixed = [s.ratio for i, s in enumerate(stages) if choice is None or i != choice.stage]
    free = [1.0]
    if choice is not None:
        free = [*choice.ratios, *(choice.bounds or ()),
                *(g.stage.ratio for g in choice.gearboxes)] or [stages[choice.stage].ratio]
    efficiency = math.prod(s.efficiency for s in stages)
    if efficiency < TOTAL_EFFICIENCY:
        raise source.error(
            f"the transmission's total efficiency (the product of its stages' efficiencies) "
            f"must be at least {number_text(TOTAL_EFFICIENCY)}, got {efficiency:.3g}",
            ("transmission",))
    product = math.prod(fixed)
    low, high = TOTAL_RATIO
    for total in (product * min(free), product * max(free)):
        if not low <= total <= high:
            unit = "rad/m" if linear else "rad/rad"
            raise source.error(
                f"the transmission's total ratio (motor speed over load speed, the product "
                f"of its stages' ratios) must be in [{number_text(low)}, "
                f"{number_text(high)}] {unit}, got {number_text(total)} {unit}",
                ("transmission",))


def _stage(item: Any, source: YamlSource, at, index: int, linear_output: bool,
           folder: Path, files: list[Path]) -> tuple[Stage, RatioChoice | None]:
    name = item.name or ""
    if isinstance(item, GearboxInput):
        return _gearbox(item, source, at, index, folder, files)
    if isinstance(item, BeltInput):
        ratio, free = _ratio(item.ratio)
        if linear_output:
            if item.driver_diameter is None:
                raise source.error("a belt carrying the load needs driver_diameter (the "
                                   "load moves d/2 per radian)", at(index))
            if item.ratio is not None:
                raise source.error("a belt carrying the load has its ratio from "
                                   "driver_diameter (2/d rad/m); drop 'ratio'", at(index, "ratio"))
        elif ratio is None and (item.driver_diameter is None or item.driven_diameter is None):
            raise source.error("a belt needs its ratio or both pulley diameters", at(index))
        if item.belt_mass and item.driver_diameter is None:
            raise source.error("a belt mass needs driver_diameter", at(index, "belt_mass"))
        stage = belt(ratio=ratio,
                     driver_diameter=item.driver_diameter, driven_diameter=item.driven_diameter,
                     driver_inertia=item.driver_inertia, driven_inertia=item.driven_inertia,
                     belt_mass=item.belt_mass, efficiency=item.efficiency,
                     linear=linear_output, name=name)
        return stage, free
    if isinstance(item, BallScrewInput):
        if item.inertia is None and (item.diameter is None or item.length is None):
            raise source.error("a ball screw needs its inertia, or its diameter and length "
                               "(a steel screw)", at(index))
        screw = _screw_ratings(item, source, at, index, linear_output)
        return ball_screw(item.lead, efficiency=item.efficiency, inertia=item.inertia,
                          diameter=item.diameter, length=item.length, density=item.density,
                          preload_torque=item.preload_torque, max_speed=item.max_speed,
                          screw=screw, name=name), None
    if isinstance(item, RackPinionInput):
        if (item.pitch_radius is None) == (item.pitch_diameter is None):
            raise source.error("a rack and pinion needs pitch_radius or pitch_diameter "
                               "(one of them)", at(index))
        if item.pitch_radius is not None:
            radius = item.pitch_radius
        else:
            assert item.pitch_diameter is not None  # one of the two, checked above
            radius = item.pitch_diameter / 2.0
        return rack_pinion(radius, inertia=item.inertia, efficiency=item.efficiency,
                           name=name), None
    raise AssertionError(f"unknown stage {item!r}")


DEFAULT_PRESSURE_ANGLE = math.radians(20.0)
"""A spur pinion's pressure angle unless given: the standard basic rack (ISO 53)."""


def _shaft_load(item: Any, source: YamlSource, at: tuple[Any, ...], first: bool,
                last: bool, after_gearbox: bool = False) -> ShaftLoad | None:
    """What a belt, pinion or ball screw marked ``on_motor_shaft`` puts on the motor's
    shaft, or marked ``on_gearbox_output`` on the output shaft of the gearbox right before
    it (docs/shaft-loads.md), None for any other stage; the fields each kind needs."""
    motor = getattr(item, "on_motor_shaft", False)
    output = getattr(item, "on_gearbox_output", False)
    belt_only = ("pretension", "wrap_angle")
    if isinstance(item, BeltInput):
        given = [f for f in belt_only if getattr(item, f) is not None]
        if given and not (motor or output):
            raise source.error(f"{given[0]} is for the belt's load on the shaft it sits on: "
                               f"add on_motor_shaft: true (or on_gearbox_output: true)",
                               (*at, given[0]))
    if isinstance(item, RackPinionInput) and item.pressure_angle is not None \
            and not (motor or output):
        raise source.error("pressure_angle is for the pinion's load on the shaft it sits on: "
                           "add on_motor_shaft: true (or on_gearbox_output: true)",
                           (*at, "pressure_angle"))
    if not (motor or output):
        return None
    flag = "on_motor_shaft" if motor else "on_gearbox_output"
    if motor and output:
        raise source.error(f"the {item.type} sits on the motor's shaft or on a gearbox's "
                           f"output shaft, not both", (*at, "on_gearbox_output"))
    if motor and not first:
        raise source.error(f"on_motor_shaft: the {item.type} must be the first stage (on "
                           f"the motor's shaft)", (*at, "on_motor_shaft"))
    if output and not after_gearbox:
        raise source.error(f"on_gearbox_output: the {item.type} must come right after a "
                           f"gearbox stage (on its output shaft)", (*at, "on_gearbox_output"))
    shaft: Literal["motor", "gearbox"] = "motor" if motor else "gearbox"
    where = "the motor shaft" if motor else "a gearbox's output shaft"
    if isinstance(item, BeltInput):
        if item.pretension is None:
            raise source.error(f"a belt on {where} needs its pretension (the static "
                               f"tension per strand as installed, e.g. '200 N')",
                               (*at, flag))
        if item.driver_diameter is None:
            raise source.error(f"a belt on {where} needs driver_diameter (its pull "
                               f"is the torque over d/2)", (*at, flag))
        wrap = math.pi if item.wrap_angle is None else item.wrap_angle
        return ShaftLoad("belt", item.driver_diameter, item.pretension, wrap, shaft=shaft)
    if isinstance(item, RackPinionInput):
        radius = item.pitch_radius if item.pitch_radius is not None \
            else 0.5 * (item.pitch_diameter or 0.0)
        angle = DEFAULT_PRESSURE_ANGLE if item.pressure_angle is None \
            else item.pressure_angle
        return ShaftLoad("pinion", 2.0 * radius, pressure_angle=angle, shaft=shaft)
    if not last:
        raise source.error(f"{flag}: a ball screw's axial force is the load's when "
                           f"it is the last stage of a linear axis", (*at, flag))
    return ShaftLoad("screw", shaft=shaft)


SHAFT_FIELDS = ("mounting", "root_diameter", "support_distance", "buckling_length",
                "speed_factor", "buckling_factor")
LIFE_FIELDS = ("dynamic_load_rating", "load_factor", "required_life")


def _screw_ratings(item: BallScrewInput, source: YamlSource, at, index: int,
                   last: bool) -> ScrewRatings | None:
    """A ball screw's ratings for its critical speed, buckling and life checks (docs/
    ball-screws.md), or None without them; each group complete or absent."""
    given = item.model_fields_set
    if not given & {*SHAFT_FIELDS, *LIFE_FIELDS}:
        return None
    first = next(f for f in (*SHAFT_FIELDS, *LIFE_FIELDS) if f in given)
    if not last:
        raise source.error("a ball screw's critical speed, buckling and life checks need it "
                           "as the last stage (the nut drives the load: the screw's axial "
                           "force is the load's)", at(index, first))
    shaft = bool(given & set(SHAFT_FIELDS))
    if shaft:
        if item.mounting is None:
            field = next(f for f in SHAFT_FIELDS if f in given)
            raise source.error("the critical speed and buckling checks need the screw's end "
                               "mounting: mounting: fixed-free, supported-supported, "
                               "fixed-supported or fixed-fixed", at(index, field))
        if item.root_diameter is None:
            raise source.error("the critical speed and buckling checks need root_diameter, "
                               "the thread minor diameter d_r of the datasheet (the makers' "
                               "formulas use it, not the nominal diameter)",
                               at(index, "mounting"))
        if item.diameter is not None and item.root_diameter > item.diameter:
            raise source.error(f"root_diameter ({item.root_diameter * 1e3:g} mm) must not "
                               f"exceed the nominal diameter ({item.diameter * 1e3:g} mm)",
                               at(index, "root_diameter"))
        if item.support_distance is None and item.length is None:
            raise source.error("the critical speed and buckling checks need "
                               "support_distance (between the mounting surfaces) or the "
                               "screw's length", at(index, "mounting"))
    if given & set(LIFE_FIELDS):
        for field in ("dynamic_load_rating", "required_life"):
            if field not in given:
                other = next(f for f in LIFE_FIELDS if f in given)
                raise source.error(f"the screw's life check needs dynamic_load_rating (C_a "
                                   f"of the datasheet) and required_life (e.g. '20000 h'); "
                                   f"{field} is missing", at(index, other))
    support = item.support_distance if item.support_distance is not None else item.length
    return ScrewRatings(
        mounting=item.mounting if shaft else None,
        root_diameter=item.root_diameter if shaft else None,
        support_distance=support if shaft else None,
        buckling_length=item.buckling_length, speed_factor=item.speed_factor,
        buckling_factor=item.buckling_factor, dynamic_load_rating=item.dynamic_load_rating,
        load_factor=item.load_factor, required_life=item.required_life)


def _ratio(spec: tuple[str, tuple[float, ...]] | None) -> tuple[float | None, RatioChoice | None]:
    """The stage's starting ratio and the free ratio choice, from the parsed ratio field."""
    if spec is None:
        return None, None
    kind, values = spec
    if kind == "fixed":
        return values[0], None
    if kind == "list":
        return values[0], RatioChoice(ratios=values)
    return values[0], RatioChoice(bounds=(values[0], values[1]))


def _gearbox(item: GearboxInput, source: YamlSource, at, index: int,
             folder: Path, files: list[Path]) -> tuple[Stage, RatioChoice | None]:
    if item.ratio is None and item.catalog is None:
        raise source.error("required field is missing: a gearbox needs a ratio (or a "
                           "gearbox catalog)", at(index, "ratio"))
    if item.ratio is not None and item.catalog is not None:
        raise source.error("give a ratio or a gearbox catalog, not both", at(index, "catalog"))
    limits = {"max_input_speed": item.max_input_speed,
              "rated_output_torque": item.rated_output_torque,
              "peak_output_torque": item.peak_output_torque, "backlash": item.backlash}
    if item.catalog is not None:
        path = folder / item.catalog
        bundled = bundled_gearbox_catalogs()
        if not path.exists() and item.catalog in bundled:
            path = bundled[item.catalog]
        if not path.exists() or path.is_dir():
            raise source.error(f"no gearbox catalog file {str(path)!r} (bundled gearbox "
                               f"catalogs: {', '.join(bundled) or 'none'})",
                               at(index, "catalog"))
        options = load_gearbox_catalog(path)
        files.append(path)
        return options[0].stage, RatioChoice(gearboxes=options)
    ratio, free = _ratio(item.ratio)
    assert ratio is not None  # no catalog: the ratio is given (checked above)
    stage = gearbox(ratio, item.efficiency, item.inertia, name=item.name or "", **limits)
    stage = dataclasses.replace(stage, output_radial_load=item.output_radial_load,
                                output_axial_load=item.output_axial_load)
    return _output_life(stage, item, lambda message, field: source.error(
        message, at(index, field))), free


OUTPUT_LIFE_FIELDS = ("output_radial_load_life", "output_axial_load_life", "output_load_life")
"""A gearbox's output forces rated for a bearing life, and that life (docs/shaft-loads.md)."""


def _output_life(stage: Stage, item: GearboxInput | GearboxSeriesInput,
                 error: Callable[[str, str], Exception]) -> Stage:
    """``stage`` with the gearbox's output forces for a bearing life and that life: a force
    needs the life it is rated for, the life a force."""
    given = [f for f in OUTPUT_LIFE_FIELDS if getattr(item, f) is not None]
    if given and "output_load_life" not in given:
        raise error(f"{given[0]} needs output_load_life, the bearing life it is rated for "
                    f"(e.g. '20000 h')", given[0])
    if given == ["output_load_life"]:
        raise error("output_load_life is the bearing life of output_radial_load_life or "
                    "output_axial_load_life: give one of them (or leave it out)",
                    "output_load_life")
    return dataclasses.replace(stage, output_radial_load_life=item.output_radial_load_life,
                               output_axial_load_life=item.output_axial_load_life,
                               output_load_life=item.output_load_life)


def bundled_gearbox_catalogs() -> dict[str, Path]:
    """The gearbox catalogs shipped with sizer (sizer/catalogs/gearboxes), by name."""
    folder = Path(str(resources.files("sizer").joinpath("catalogs", "gearboxes")))
    if not folder.is_dir():
        return {}
    return {p.stem: p for p in sorted(folder.glob("*.yaml"))}


def load_gearbox_catalog(path: str | Path) -> tuple[GearboxOption, ...]:
    """Every ratio of every series of a gearbox catalog, as options for the ratio choice."""
    source = read_yaml(path)
    model = validate(GearboxCatalogFile, source)
    shared, common = file_sources(model.sources, model.default_source)
    options = []
    seen: set[str] = set()
    for s_index, series in enumerate(model.gearboxes):
        if series.id in seen:
            raise source.error(f"duplicate gearbox id {series.id!r}",
                               ("gearboxes", s_index, "id"))
        seen.add(series.id)
        ratios_seen: dict[float, int] = {}
        life_error = _catalog_life_error(source, s_index)
        for r_index, ratio in enumerate(series.ratios):
            if ratio.ratio in ratios_seen:
                first = source.line_of(("gearboxes", s_index, "ratios", ratios_seen[ratio.ratio]))
                raise source.error(
                    f"gearbox {series.id!r}: ratio {ratio.ratio:g} is listed twice (first at "
                    f"line {first})", ("gearboxes", s_index, "ratios", r_index, "ratio"))
            ratios_seen[ratio.ratio] = r_index
            stage = gearbox(
                ratio.ratio,
                ratio.efficiency if ratio.efficiency is not None else series.efficiency,
                ratio.inertia,
                max_input_speed=_first(ratio.max_input_speed, series.max_input_speed),
                rated_output_torque=_first(ratio.rated_output_torque,
                                           series.rated_output_torque),
                peak_output_torque=_first(ratio.peak_output_torque, series.peak_output_torque),
                backlash=series.backlash,
                name="gearbox",
            )
            stage = dataclasses.replace(stage, output_radial_load=series.output_radial_load,
                                        output_axial_load=series.output_axial_load)
            stage = _output_life(stage, series, life_error)
            options.append(GearboxOption(f"{series.id} i={ratio.ratio:g}", stage,
                                         gearbox_sources(series, ratio, shared, common)))
    return tuple(options)


def _catalog_life_error(source: YamlSource, s_index: int
                        ) -> Callable[[str, str], Exception]:
    def error(message: str, field: str) -> Exception:
        return source.error(message, ("gearboxes", s_index, field))

    return error


def _first(*values: float | None) -> float | None:
    return next((v for v in values if v is not None), None)
