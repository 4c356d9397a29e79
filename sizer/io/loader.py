"""Load design files and motor catalogs into the SI domain objects of sizer.model.domain.

    load_design("machine.yaml")                 -> Design
    load_catalog("book-examples")               -> tuple[Motor, ...]
    bundled_catalogs()                          -> {"book-examples": Path(...), ...}
    design_schema(), catalog_schema(),
    gearbox_catalog_schema()                    -> JSON Schema dicts (draft 2020-12)

Every mistake in a file ends in a UserError naming the file, the line and the field.
"""

from __future__ import annotations

import difflib
import fnmatch
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, replace
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np
from pydantic import BaseModel

from sizer.bounded_yaml import parse_path
from sizer.errors import UserError
from sizer.input_limits import MAX_DESIGN_BYTES, MAX_DESIGN_NODES
from sizer.io.catalog_table import read_table
from sizer.io.cycle import motion_of
from sizer.io.data_law_rules import LocatedLaw, locate_laws, oscillation_warnings
from sizer.io.data_laws import canonical_data_laws
from sizer.io.linkage import check_linkage_design, linkage_cycle, output_linear
from sizer.io.motor_rules import (
    MotorProblem,
    impossibilities,
    maybe_implausible,
    maybe_impossible,
    motor_of,
)
from sizer.io.plausibility import bare_number_warnings, motor_warnings
from sizer.io.schema.inputs import (
    CatalogFile,
    DesignFile,
    DriveCatalogFile,
    DriveInput,
    LimitsInput,
    LoadInput,
    MotorInput,
)
from sizer.io.schema.inputs_base import axis_range, convert_in
from sizer.io.schema.provenance import catalog_source_text, file_sources, row_sources
from sizer.io.schema.transmission_inputs import GearboxCatalogFile
from sizer.io.transmission import build_transmission
from sizer.io.validation import validate
from sizer.io.yaml_source import (
    YamlSource,
    format_path,
    no_garbage_collection,
    parse_mapping,
    read_yaml,
)
from sizer.mechanics import linear_load
from sizer.mechanics.loads import GRAVITY
from sizer.model.cycle import Cycle, Move, Run
from sizer.model.domain import (
    Design,
    FigureSources,
    GravityLoad,
    InertiaTableLoad,
    Limits,
    Load,
    Motor,
    Provenance,
    ServoDrive,
    SpringLoad,
    TableLoad,
    Transmission,
)
from sizer.model.tolerance import DEFAULT_SIGMAS, Tolerance
from sizer.vibration.elastic_load import ElasticLoad

PathLike = str | Path


# ------------------------------------------------------------------- catalogs


def bundled_catalogs() -> dict[str, Path]:
    """The catalogs shipped with sizer, by name (the file stem)."""
    folder = Path(str(resources.files("sizer").joinpath("catalogs")))
    if not folder.is_dir():
        return {}
    return {p.stem: p for p in sorted(folder.glob("*.yaml"))}


def bundled_drive_catalogs() -> dict[str, Path]:
    """The drive catalogs shipped with sizer (sizer/catalogs/drives), by name."""
    folder = Path(str(resources.files("sizer").joinpath("catalogs", "drives")))
    if not folder.is_dir():
        return {}
    return {p.stem: p for p in sorted(folder.glob("*.yaml"))}


NOT_DEFAULT_CATALOGS = frozenset({"book-examples", "maxon-ec"})
"""Bundled catalogs left out of the default set: the book's idealized motors (no rotor
inertia, bare SI numbers) would rank among real motors without being buyable; maxon's
small brushless DC motors (maxon-ec) give as peak torque their stall torque, the end of
the voltage line at nominal voltage and up to 28 times the nominal torque, not an overload
they may carry: name them with a drive whose current limits the peak (e.g. maxon-escon)."""


def default_catalogs() -> dict[str, Path]:
    """The bundled catalogs of real motors: the motors of a design that names none.

    All bundled catalogs but those in NOT_DEFAULT_CATALOGS, by name.
    """
    return {name: path for name, path in bundled_catalogs().items()
            if name not in NOT_DEFAULT_CATALOGS}


def load_catalog(path_or_name: PathLike) -> tuple[Motor, ...]:
    """The motors of a catalog file or of a bundled catalog (by name)."""
    return read_catalog(path_or_name).motors


@dataclass(frozen=True)
class LoadedCatalog:
    """The motors of a catalog file and the warnings about its figures.

    ``warnings`` are located texts, ``file:line: field: text`` (bare numbers far from the
    plausible range, see :mod:`sizer.io.plausibility`); empty for a clean catalog.
    """

    motors: tuple[Motor, ...]
    warnings: tuple[str, ...] = ()


def read_catalog(path_or_name: PathLike) -> LoadedCatalog:
    """A catalog file or a bundled catalog (by name): its motors and warnings."""
    path = resolve_catalog(path_or_name, Path.cwd())
    warnings: list[str] = []
    motors = _read_catalog(path, warnings)
    _check_unique(motors)
    return LoadedCatalog(tuple(m.motor for m in motors), tuple(warnings))


def resolve_catalog(reference: PathLike, base: Path, *, source: YamlSource | None = None,
                    at: Sequence[Any] = ()) -> Path:
    """The file of a catalog reference: a path (relative to ``base``) or a bundled name.

    An existing file wins over a bundled catalog of the same name. Errors are placed at
    ``at`` in ``source`` (the design file) when given.
    """

    def fail(message: str) -> UserError:
        if source is not None:
            return source.error(message, at)
        return UserError(message)

    text = str(reference)
    bundled = bundled_catalogs()
    try:
        path = Path(text).expanduser()
        if not path.is_absolute():
            path = base / path
        is_dir = path.is_dir()
        if path.is_file() or (path.exists() and not is_dir):
            return path  # a FIFO or a device: read_yaml refuses it with what it is
    except (OSError, ValueError):  # a name too long, a NUL byte...
        path, is_dir = Path(text), False
    if text in bundled:
        return bundled[text]
    if is_dir:
        raise fail(f"catalog {text!r} is a directory, not a YAML file")
    names = ", ".join(bundled) or "none"
    looks_like_path = any(c in text for c in "/\\") or Path(text).suffix in (".yaml", ".yml")
    if looks_like_path:
        raise fail(f"catalog file not found: {path} (bundled catalogs: {names})")
    close = difflib.get_close_matches(text, list(bundled), n=1)
    hint = f"did you mean {close[0]!r}? " if close else ""
    raise fail(f"unknown catalog {text!r}: no such file and no such bundled catalog; "
               f"{hint}bundled catalogs: {names}")


@dataclass(frozen=True)
class _Located:
    """A motor and where it was defined (for duplicate-id messages)."""

    motor: Motor
    source: YamlSource
    at: tuple[Any, ...]

    @property
    def line(self) -> int | None:
        return self.source.line_of((*self.at, "id"))

    @property
    def field(self) -> str:
        return format_path((*self.at, "id"))


def _read_catalog(path: Path, warnings: list[str],
                  drives: list[_LocatedDrive] | None = None) -> list[_Located]:
    """The motors of a catalog file; warnings about them are appended to ``warnings``.

    A catalog in the common form is read as columns (:mod:`sizer.io.catalog_table`), the
    rules that loading applies screened on the columns at once and run on the motors they
    may concern; any other is validated field by field, which words its first problem.
    """
    with no_garbage_collection():  # many small objects, none of them garbage
        source = read_yaml(path)
        table = read_table(source.data)
        if table is None:
            return _validated_catalog(source, warnings, drives)
        rows = source.data["motors"]
        for index in np.flatnonzero(maybe_impossible(table.columns)).tolist():
            _refuse_impossible(table.motors[index], source, ("motors", index))
        for index in np.flatnonzero(maybe_implausible(table.columns)).tolist():
            warnings += motor_warnings(source, ("motors", index), rows[index],
                                       table.motors[index])
        return [_Located(motor, source, ("motors", index))
                for index, motor in enumerate(table.motors)]


def _validated_catalog(source: YamlSource, warnings: list[str],
                       drives: list[_LocatedDrive] | None = None) -> list[_Located]:
    """The motors of a catalog validated by its model, field by field (its drives, if
    any, appended to ``drives``)."""
    catalog = validate(CatalogFile, source)
    shared, common = file_sources(catalog.sources, catalog.default_source)
    source_text = catalog_source_text(catalog.source, common)
    if drives is not None:
        drives.extend(_drives_of(catalog.drives or (), source, catalog.manufacturer,
                                 source_text, shared, common))
    if not catalog.motors:
        raise source.error("the catalog has no motors", ("motors",))
    located = []
    for index, item in enumerate(catalog.motors):
        at = ("motors", index)
        for field in item.inline_tolerances:  # a design's, not a catalog's
            raise source.error(f"a tolerance beside a catalog motor's {field}: give it in "
                               f"the design (tolerances: {{motor.{field}: ...}} for every "
                               f"motor, or beside an inline motor's value)", (*at, field))
        motor = _motor(item, source, at, manufacturer=catalog.manufacturer,
                       source_text=source_text,
                       provenance=row_sources(item.figure_sources, shared, common))
        warnings += _motor_warnings(motor, source, at)
        located.append(_Located(motor, source, at))
    return located


def _motor(item: MotorInput, source: YamlSource, at: tuple[Any, ...], *,
           manufacturer: str | None = None, source_text: str | None = None,
           provenance: FigureSources | None = None) -> Motor:
    """A Motor from its validated input; an impossible motor (the impossible rules of
    :mod:`sizer.io.motor_rules`) is refused at its first problem, with its id.
    ``manufacturer`` and ``source_text`` are the catalog's, for a motor without its own;
    ``provenance`` its figures' sources."""
    motor = motor_of(item)
    _refuse_impossible(motor, source, at)
    return replace(motor, source=item.source or source_text,
                   manufacturer=item.manufacturer or manufacturer, provenance=provenance)


def _refuse_impossible(motor: Motor, source: YamlSource, at: tuple[Any, ...]) -> None:
    """A UserError at the first impossibility of ``motor`` (defined at ``at``), if any."""
    problems: list[MotorProblem] = impossibilities(motor)
    if problems:
        first = problems[0]
        more = len(problems) - 1
        tail = f" (and {more} more problem{'s' * (more > 1)} of this motor)" if more else ""
        raise source.error(f"motor {motor.id!r}: {first.message}{tail}", (*at, *first.path))


def _motor_warnings(motor: Motor, source: YamlSource, at: tuple[Any, ...]) -> list[str]:
    given = source.data
    for part in at:
        given = given[part]
    return motor_warnings(source, at, given, motor)


@dataclass(frozen=True)
class _LocatedDrive:
    """A drive and where it was defined."""

    drive: ServoDrive
    source: YamlSource
    at: tuple[Any, ...]


def _drives_of(items: Iterable[DriveInput], source: YamlSource, manufacturer: str | None,
               source_text: str | None, shared: Mapping[str, Provenance] | None = None,
               common: FigureSources | None = None) -> list[_LocatedDrive]:
    return [_LocatedDrive(ServoDrive(
        id=item.id, continuous_current=item.continuous_current,
        peak_current=item.peak_current, dc_bus_voltage=item.dc_bus_voltage,
        bus_capacitance=item.bus_capacitance, max_bus_voltage=item.max_bus_voltage,
        braking_threshold=item.braking_threshold,
        braking_resistor_power=item.braking_resistor_power, price=item.price,
        motors=None if item.motors is None else tuple(m.strip() for m in item.motors),
        source=item.source or source_text, part_number=item.part_number,
        manufacturer=item.manufacturer or manufacturer,
        provenance=row_sources(item.figure_sources, shared or {}, common)),
        source, ("drives", index))
        for index, item in enumerate(items)]


def read_drive_catalog(path: Path) -> list[_LocatedDrive]:
    """The drives of a drive catalog file (or of a motor catalog's ``drives:``)."""
    source = read_yaml(path)
    if isinstance(source.data, dict) and "motors" in source.data:
        catalog = validate(CatalogFile, source)
        if not catalog.drives:
            raise source.error("the catalog has no drives (a design's `drives:` names drive "
                               "catalogs)", ("drives",))
        shared, common = file_sources(catalog.sources, catalog.default_source)
        return _drives_of(catalog.drives, source, catalog.manufacturer,
                          catalog_source_text(catalog.source, common), shared, common)
    drive_catalog = validate(DriveCatalogFile, source)
    if not drive_catalog.drives:
        raise source.error("the catalog has no drives", ("drives",))
    shared, common = file_sources(drive_catalog.sources, drive_catalog.default_source)
    return _drives_of(drive_catalog.drives, source, drive_catalog.manufacturer,
                      catalog_source_text(drive_catalog.source, common), shared, common)


def resolve_drive_catalog(reference: str, base: Path, source: YamlSource,
                          at: Sequence[Any]) -> Path:
    """The file of a drive catalog reference: a path (relative to ``base``) or a bundled
    drive catalog's name."""
    bundled = bundled_drive_catalogs()
    try:
        path = Path(reference).expanduser()
        if not path.is_absolute():
            path = base / path
        if path.is_file():
            return path
    except (OSError, ValueError):
        path = Path(reference)
    if reference in bundled:
        return bundled[reference]
    names = ", ".join(bundled) or "none"
    raise source.error(f"unknown drive catalog {reference!r}: no such file and no such "
                       f"bundled drive catalog; bundled drive catalogs: {names}", at)


def _design_drives(model: DesignFile, source: YamlSource, folder: Path,
                   from_catalogs: list[_LocatedDrive], motors: Sequence[Motor],
                   files: list[Path]) -> tuple[ServoDrive, ...]:
    """The drives of a design (its ``drives:`` catalogs, then those of its motor catalogs),
    each checked against the loaded motors: an id it names must be loaded (a bundled
    catalog's drive naming motors that are not loaded is simply not paired with them), and
    a motor it names must give its torque constant."""
    located: list[_LocatedDrive] = []
    read: set[Path] = set()
    bundled = {p.resolve() for p in bundled_drive_catalogs().values()}
    shipped: set[int] = set()  # ids of the YamlSources of bundled catalogs
    for index, reference in enumerate(model.drives or ()):
        path = resolve_drive_catalog(reference.strip(), folder, source, ("drives", index))
        if path.resolve() not in read:
            read.add(path.resolve())
            files.append(path)
            items = read_drive_catalog(path)
            if path.resolve() in bundled:
                shipped.update(id(item.source) for item in items)
            located.extend(items)
    located.extend(from_catalogs)
    first: dict[str, _LocatedDrive] = {}
    ids = [m.id for m in motors]
    by_id = {m.id: m for m in motors}
    for item in located:
        if item.drive.id in first:
            raise item.source.error(f"duplicate drive id {item.drive.id!r}",
                                    (*item.at, "id"))
        first[item.drive.id] = item
        for k, pattern in enumerate(item.drive.motors or ()):
            matched = fnmatch.filter(ids, pattern)
            at = (*item.at, "motors", k)
            if not matched and id(item.source) in shipped:
                continue
            if not matched:
                shown = ", ".join(ids[:12]) + (", ..." if len(ids) > 12 else "") or "none"
                raise item.source.error(f"drive {item.drive.id!r}: no loaded motor is "
                                        f"{pattern!r}; loaded motors: {shown}", at)
            lacking = [i for i in matched if by_id[i].torque_constant is None]
            if lacking:
                raise item.source.error(
                    f"drive {item.drive.id!r}: motor {lacking[0]!r} gives no "
                    "torque_constant: the drive's currents become torques through it "
                    "(give the motor's torque_constant, N*m/A)", at)
    return tuple(item.drive for item in located)


def _check_unique(motors: Iterable[_Located]) -> None:
    first: dict[str, _Located] = {}
    for item in motors:
        earlier = first.get(item.motor.id)
        if earlier is not None:
            where = earlier.source.file or "?"
            if earlier.line is not None:
                where += f":{earlier.line}"
            raise UserError(f"duplicate motor id {item.motor.id!r} (first defined at {where})",
                            file=item.source.file, line=item.line, field=item.field)
        first[item.motor.id] = item


# ------------------------------------------------------------------- design


def load_design(path: PathLike, extra_catalogs: Iterable[PathLike] = (), *,
                default_motors: bool = False) -> Design:
    """Read a design file into a Design (SI).

    ``Design.motors`` holds the motors of the design's ``motors:`` entries, then those of
    ``extra_catalogs`` (paths relative to the working directory, or bundled names). A
    catalog file named twice is read once.

    With ``default_motors``, a design without a ``motors:`` entry, with no extra catalogs
    and none of the load's limits (those ask for a plan without a motor) is sized against
    the bundled catalogs of real motors (``default_catalogs()``); ``motors: []`` still
    means none. Without it such a design has no motors.
    """
    path = Path(path)
    source = read_yaml(path, limit=MAX_DESIGN_BYTES, max_nodes=MAX_DESIGN_NODES)
    return _design_of(source, path.parent, path.stem, [path], extra_catalogs,
                      default_motors)


def at_its_line(error: UserError, path: PathLike) -> UserError:
    """``error`` (raised while sizing the design file ``path``) placed in that file, at
    the line of its field where it names one of the file's keys (``laws``,
    ``transmission[0]``...) and gives no line of its own."""
    if error.file is not None or error.line is not None:
        return error.located(file=str(path))
    at = parse_path(error.field) if error.field else None
    line = None
    if at:  # the line of the field, or of its nearest key the file has (None: none)
        try:
            line = read_yaml(path, limit=MAX_DESIGN_BYTES,
                             max_nodes=MAX_DESIGN_NODES).line_of(at)
        except UserError:  # the file changed since it was read: its name alone
            line = None
    return error.located(file=str(path), line=line)


def load_design_data(data: Mapping[str, Any], extra_catalogs: Iterable[PathLike] = (), *,
                     default_motors: bool = False, base: Path | None = None,
                     name: str = "design") -> Design:
    """A design given as a mapping (the content of a design file, e.g. from Python or
    JSON): the same checks and messages as a file (``<design>`` for the file name, with
    the line of the mapping written out as YAML); catalog paths relative to ``base``."""
    source = parse_mapping(data, "design")
    return _design_of(source, base or Path.cwd(), name, [], extra_catalogs, default_motors)


def _design_of(source: YamlSource, folder: Path, name: str, files: list[Path],
               extra_catalogs: Iterable[PathLike], default_motors: bool,
               plans: bool = True) -> Design:
    """The Design of a parsed design document (``folder``: where relative paths start)."""
    canonical_data_laws(source, folder)
    model = validate(DesignFile, source)
    laws = _located_laws(model)
    cycle, noted = motion_of(model.task, model.cycle, laws, source)
    linear = cycle.linear
    warnings = [*bare_number_warnings(source, linear), *noted,
                *oscillation_warnings(laws, source)]
    extra = list(extra_catalogs)
    planned = plans and _planned(model) and not extra
    load = _load(model, source, output_linear(model.transmission, linear), folder, cycle,
                 planned=planned)
    files = list(files)
    files += _position_table_files(model, folder)  # never written over (output guard)
    transmission, ratio_choice, linkage_at = build_transmission(
        model.transmission, source, folder, linear, files)
    if transmission.linkage is not None:
        cycle = linkage_cycle(cycle, transmission.linkage, source, linkage_at)
        linear = cycle.linear
        check_linkage_design(model, source)
    if default_motors and model.motors is None and not extra \
            and not (plans and _load_limits_given(model)):
        extra = list(default_catalogs().values())
    transmission = replace(transmission, efficiency_applies_to=model.efficiency_applies_to)
    _check_position_drive(model, source, transmission)
    catalog_drives: list[_LocatedDrive] = []
    motors = _design_motors(model, source, folder, extra, warnings, files, catalog_drives)
    drives = _design_drives(model, source, folder, catalog_drives, motors, files)
    limits = _limits(model, source, linear)
    if limits.thermal_duty == "once" and cycle.minimize:
        raise source.error("'once' is checked at given durations (with minimize the RMS "
                           "check bounds T_min); give the duration", ("limits", "thermal_duty"))
    by_id = {m.id: m for m in motors}
    chosen_motor = chosen_law = None
    if model.check is not None:
        chosen_motor, chosen_law = model.check.motor, model.check.law
        if chosen_motor is not None and chosen_motor not in by_id:
            raise source.error(_unknown_motor(chosen_motor, list(by_id)), ("check", "motor"))
    return Design(
        load=load,
        transmission=transmission,
        ratio_choice=ratio_choice,
        laws=tuple(model.laws) if model.laws is not None else default_laws(),
        motors=motors,
        limits=limits,
        chosen_motor=chosen_motor,
        chosen_law=chosen_law,
        name=model.name if model.name is not None else name,
        warnings=tuple(warnings),
        files=tuple(files),
        machine_cycle=cycle,
        drives=drives,
        tolerances=_tolerances(model, source, linear),
    )


TOLERANCE_KEYS = {
    "load.inertia": False, "load.mass": True, "load.friction": None, "load.damping": None,
    "load.torque": False, "load.force": True, "load.natural_frequency": None,
    "load.damping_ratio": None, "transmission.efficiency": None,
    "motor.continuous_torque": None, "motor.peak_torque": None, "motor.rated_speed": None,
    "motor.inertia": None}
"""The inputs a ``tolerances:`` section may name (docs/robust.md), and whether the name
is for a linear axis (True), a rotary one (False) or both (None)."""


TOLERANCE_KINDS: dict[str, tuple[str, str] | None] = {
    "load.inertia": ("inertia", "inertia"), "load.mass": ("mass", "mass"),
    "load.friction": ("torque", "force"),
    "load.damping": ("rotary_damping", "linear_damping"),
    "load.torque": ("torque", "torque"), "load.force": ("force", "force"),
    "load.natural_frequency": ("rate", "rate"), "load.damping_ratio": None,
    "transmission.efficiency": None,
    "motor.continuous_torque": ("torque", "torque"), "motor.peak_torque": ("torque", "torque"),
    "motor.rated_speed": ("angular_speed", "angular_speed"),
    "motor.inertia": ("inertia", "inertia")}
"""The kind of an absolute tolerance of each input (rotary, linear axis); None: relative
only (an efficiency's tolerance is a fraction of it)."""


def _tolerances(model: DesignFile, source: YamlSource, linear: bool
                ) -> tuple[Tolerance, ...]:
    """The design's ``tolerances:`` (sizer.model.tolerance.Tolerance): each key a known
    input of the axis; each value a fraction (relative: in (0, 100 %], below 100 % where
    the input must stay positive) or a positive quantity of the input's kind (absolute),
    uniform over +-it or normal with that sigma, truncated at ``truncate`` sigmas (the
    corners at +-truncate sigma, within the same bounds)."""
    out = []
    for key, given in (model.tolerances or {}).items():
        at: tuple[str, ...] = ("tolerances", key)
        axis = TOLERANCE_KEYS.get(key, "unknown")
        if axis == "unknown" or (axis is not None and axis != linear):
            known = [k for k, a in TOLERANCE_KEYS.items() if a is None or a == linear]
            raise source.error(f"not an input a tolerance can name; one of: "
                               f"{', '.join(known)}", at)
        normal = given.distribution == "normal"
        value = given.sigma if normal else given.plus_minus
        if normal:
            at = (*at, "sigma")
        elif "distribution" in given.model_fields_set:
            at = (*at, "plus_minus")
        assert value is not None
        out.append(_tolerance(source, key, value, at, linear,
                              (given.truncate or DEFAULT_SIGMAS) if normal else None))
    named = {t.name for t in out}
    for field, value in model.load.inline_tolerances.items():  # '0.35 kg*m^2 +- 20 %'
        key = f"load.{field}"
        if key in named:
            raise source.error(f"a tolerance beside the value and one in 'tolerances:' "
                               f"({key}): give it in one place", ("load", field))
        out.append(_tolerance(source, key, value, ("load", field), linear, None))
    for index, item in enumerate(model.motors or ()):  # an inline motor's: its own
        if isinstance(item, str):
            continue
        for field, value in item.inline_tolerances.items():
            key, where = f"motor.{field}", ("motors", index, field)
            if key in named:
                raise source.error(f"a tolerance beside motor {item.id!r}'s {field} and one "
                                   f"for every motor in 'tolerances:' ({key}): give one",
                                   where)
            found = _tolerance(source, key, value, where, linear, None)
            out.append(replace(found, name=f"{key}[{item.id}]"))
    return tuple(out)


def _tolerance(source: YamlSource, key: str, value: str, at: tuple[str | int, ...],
               linear: bool, sigmas: float | None) -> Tolerance:
    """One tolerance of ``key`` given as ``value`` at ``at`` (sigma with ``sigmas``
    for a normal one, else the half-width of a uniform one)."""
    from sizer.units import KINDS, to_si

    normal = sigmas is not None
    field = format_path(at)
    kinds = TOLERANCE_KINDS[key]
    absolute = False
    try:
        fraction = to_si(value, "fraction", field=field)
    except UserError as error:
        if kinds is None:
            raise source.relocate(error, at) from None
        kind = KINDS[kinds[linear]]
        try:
            fraction, absolute = to_si(value, kind.name, field=field), True
        except UserError:
            raise source.error(
                f"expected a fraction like '10 %' (relative) or an absolute "
                f"{kind.name.replace('_', ' ')} like {kind.example!r}, got "
                f"{value!r}", at) from None
    width = fraction * (sigmas or 1.0)
    if absolute:
        if not fraction > 0.0:
            raise source.error(f"an absolute tolerance must be positive, got {value!r}", at)
    else:
        zero_ok = key in ("load.friction", "load.damping", "load.torque", "load.force",
                          "load.damping_ratio")
        if not (0.0 < width < 1.0 or (zero_ok and width == 1.0)):
            bound = "(0, 100 %]" if zero_ok else "(0, 100 %)"
            what = (f"truncate x sigma ({sigmas:g} x {value!r})" if normal
                    else repr(value))
            raise source.error(f"a relative tolerance must be in {bound}, got {what}", at)
    return Tolerance(key, width, absolute=absolute,
                     distribution="normal" if normal else "uniform", sigmas=sigmas)


def design_of_source(source: YamlSource, folder: Path, name: str, files: list[Path],
                     extra_catalogs: Iterable[PathLike] = (), *, plans: bool = True
                     ) -> Design:
    """The Design of a parsed design document (an axis of a machine file, a design at a
    git revision: its lines are the text's), with the motors of ``extra_catalogs`` added
    as :func:`load_design` adds them; sized against the bundled catalogs when it names no
    motors and no extra catalogs, and (with ``plans``) gives none of the load's limits.
    Without ``plans`` (a machine's axis: a machine is sized, never planned) the load's
    limits do not ask for a plan."""
    return _design_of(source, folder, name, files, extra_catalogs, True, plans)


def default_laws() -> tuple[str, ...]:
    """The laws of a design without ``laws:``: DEFAULT_LAW_SPECS minus the exponential."""
    from sizer.laws import DEFAULT_LAW_SPECS, law_choice

    return tuple(s for s in DEFAULT_LAW_SPECS if law_choice(s).family.law_id != "exponential")


def _quantity(source: YamlSource, at: tuple[Any, ...], value: Any, name: str) -> float:
    """``value`` in SI, checked against ``RANGES[name]``; a UserError at ``at`` if not."""
    try:
        return convert_in(value, name)
    except ValueError as error:
        raise source.error(str(error), at) from None


def _located_laws(model: DesignFile) -> list[LocatedLaw]:
    """The design's laws with where each is written (``laws`` when defaulted)."""
    laws: list[tuple[str, tuple[Any, ...]]]
    if model.laws is None:
        laws = [(spec, ("laws",)) for spec in default_laws()]
    else:
        laws = [(spec, ("laws", i)) for i, spec in enumerate(model.laws)]
    if model.check is not None and model.check.law is not None:
        laws.append((model.check.law, ("check", "law")))
    return locate_laws(laws)


def _load(model: DesignFile, source: YamlSource, linear: bool,
          folder: Path | None = None, cycle: Cycle | None = None, *,
          planned: bool = False) -> Load:
    """The design's load; ``planned`` (a plan without a motor, which reads no load): its
    inertia or mass may be left out."""
    given = model.load
    axis = ("a linear axis (the displacement is a length)" if linear
            else "a rotary axis (the displacement is an angle)")
    mass_key, torque_key = ("mass", "force") if linear else ("inertia", "torque")
    for wrong, right in (("inertia", "mass"), ("torque", "force")) if linear \
            else (("mass", "inertia"), ("force", "torque")):
        if getattr(given, wrong) is not None:
            raise source.error(f"{axis} takes '{right}', not '{wrong}'", ("load", wrong))
    inertia = getattr(given, mass_key)
    if inertia is None and planned:
        return Load(inertia=0.0)
    if inertia is None:
        raise source.error(f"required field is missing for {axis}", ("load",),
                           field=f"load.{mass_key}")

    def quantity(key: str, default: float = 0.0) -> float:
        value = getattr(given, key)
        if value is None:
            return default
        return _quantity(source, ("load", key), value, axis_range(LoadInput, key, linear))

    if not linear:
        for key in ("incline", "friction_coefficient"):
            if getattr(given, key) is not None:
                raise source.error(f"{axis} has no '{key}' (it is for linear axes)",
                                   ("load", key))
        load = Load(
            inertia=quantity(mass_key),
            damping=quantity("damping"),
            friction=quantity("friction"),
            torque=quantity(torque_key),
        )
    else:
        load = linear_load(
            quantity(mass_key),
            incline=given.incline or 0.0,
            friction_coefficient=given.friction_coefficient or 0.0,
            friction_force=quantity("friction"),
            force=quantity(torque_key),
            damping=quantity("damping"),
        )
    gravity, spring = _position_terms(model, source, linear, cycle)
    reach = _reach(model, cycle)
    table = _position_table(model, source, folder if folder is not None else Path.cwd(),
                            linear, reach)
    inertia_table = _inertia_table(model, source, linear,
                                   folder if folder is not None else Path.cwd(), reach)
    if inertia_table is not None and not inertia_table.varies:  # a constant: no term
        load = replace(load, inertia=load.inertia + inertia_table.inertia[0])
        inertia_table = None
    return replace(load, elastic=_elastic(model, source), gravity=gravity, spring=spring,
                   table=table, inertia_table=inertia_table)


def _position_terms(model: DesignFile, source: YamlSource, linear: bool,
                    cycle: Cycle | None = None
                    ) -> tuple[GravityLoad | None, SpringLoad | None]:
    """The load's terms of its position (docs/position-loads.md): gravity on an arm and a
    spring, on a rotary axis, in a task (with or without its return) or a cycle of
    segments (each move with boundary speeds of its own duration: its shape depends on
    it, the time scaling of free durations does not hold for it)."""
    given = model.load
    key = _position_key(given)
    if key is None:
        return None, None
    if linear:
        for term, what in (("gravity", "gravity on a linear axis is its constant force: give "
                                       "load.incline"),
                           ("spring", "a spring on a linear axis is not supported yet")):
            if getattr(given, term) is not None:
                raise source.error(f"{what} (gravity and spring terms are for rotary axes)",
                                   ("load", term))
    for right, wrong in (("force_table", "torque_table"), ("mass_table", "inertia_table")):
        if not linear:
            right, wrong = wrong, right
        if getattr(given, wrong) is not None:
            axis = ("a linear axis (the displacement is a length)" if linear
                    else "a rotary axis (the displacement is an angle)")
            raise source.error(f"{axis} takes '{right}', not '{wrong}'", ("load", wrong))
    free = cycle.free if cycle is not None else ()
    for i, segment in enumerate(cycle.segments if cycle is not None else ()):
        if isinstance(segment, Move) and not segment.rest_to_rest and (
                segment.duration is None or i in free):
            raise source.error("a load term of the position with a move between boundary "
                               "speeds or accelerations needs that move's own duration (its "
                               "shape depends on it)", ("cycle", "segments", i))
    gravity = spring = None
    if given.gravity is not None:
        arm = given.gravity
        gravity = GravityLoad(moment=arm.mass * arm.radius, offset=arm.offset or 0.0,
                              g=GRAVITY if arm.g is None else arm.g)
    if given.spring is not None:
        sp = given.spring
        spring = SpringLoad(stiffness=sp.stiffness, preload=sp.preload or 0.0,
                            free_position=sp.free_position or 0.0)
    return gravity, spring


def _position_key(given: LoadInput) -> str | None:
    """The first position term the load gives (None: none), where messages point."""
    for key in ("gravity", "spring", "torque_table", "force_table", "inertia_table",
                "mass_table"):
        if getattr(given, key) is not None:
            return key
    return None


def _reach(model: DesignFile, cycle: Cycle | None) -> tuple[float, float] | None:
    """The least and largest position the load reaches over the cycle, at the moves' and
    runs' ends from where it starts (0); None where the cycle's displacements are not the
    load's (through a linkage with the law on its crank: the engine checks the tables
    against the output's positions) or no cycle is given."""
    if cycle is None:
        return None
    items = model.transmission if isinstance(model.transmission, list) else \
        [model.transmission] if model.transmission is not None else []
    last = items[-1] if items else None
    if getattr(last, "type", None) in ("slider_crank", "four_bar", "disc_cam") and \
            getattr(last, "law_on", "crank") != "output":
        return None
    x, lo, hi = 0.0, 0.0, 0.0
    for segment in cycle.segments:
        if isinstance(segment, Move | Run):
            x += segment.displacement
            lo, hi = min(lo, x), max(hi, x)
    return lo, hi


def _inertia_table(model: DesignFile, source: YamlSource, linear: bool, folder: Path,
                   reach: tuple[float, float] | None = None) -> InertiaTableLoad | None:
    """``load.inertia_table`` (rotary) or ``load.mass_table`` (linear; :func:`_position_terms`
    has refused the other axis's and a task that is no single move): as a torque table
    (:func:`_table_points`), its CSV header ``q [deg],J [kg*m^2]`` (docs/position-loads.md)."""
    key = "mass_table" if linear else "inertia_table"
    given = getattr(model.load, key)
    if given is None:
        return None
    at = ("load", key)
    if linear and (model.load.incline or model.load.friction_coefficient):
        raise source.error("a mass table is inertia only: its weight on an incline and its "
                           "friction (mu m g) are not modelled yet; give them as "
                           "load.force_table and load.friction", at)
    kinds = (("length", "a length", "mm or m"), ("mass", "a mass", "kg")) if linear else \
        (("angle", "an angle", "deg or rad"), ("inertia", "an inertia", "kg*m^2"))
    header = "s [mm],m [kg]" if linear else "q [deg],J [kg*m^2]"
    x, values = _table_points(model, given, source, folder, linear, at, (kinds, header),
                              reach)
    return InertiaTableLoad(x, values, offset=given.offset or 0.0)


def _position_table(model: DesignFile, source: YamlSource, folder: Path, linear: bool,
                    reach: tuple[float, float] | None = None) -> TableLoad | None:
    """``load.torque_table`` (rotary) or ``load.force_table`` (linear): inline ``points``
    or a CSV ``file`` (read as a cam table is: sizer.io.cam_table, its header giving the
    units) (docs/position-loads.md). :func:`_position_terms` has refused the other axis's."""
    key = "force_table" if linear else "torque_table"
    given = getattr(model.load, key)
    if given is None:
        return None
    x, tau = _table_points(model, given, source, folder, linear, ("load", key), None, reach)
    return TableLoad(x, tau, offset=given.offset or 0.0)


def _table_points(model: DesignFile, given: Any, source: YamlSource, folder: Path,
                  linear: bool, at: tuple[str, ...],
                  columns: tuple[Any, str] | None = None,
                  reach: tuple[float, float] | None = None
                  ) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """A table of the load's position (x, value) in SI: its inline ``points`` (q strictly
    increasing, at least two) or its CSV ``file`` (:func:`_position_table_file`, with the
    ``columns`` it expects); the positions the cycle reaches (``reach``, from ``offset``)
    must lie within it."""
    unit = "m" if linear else "rad"
    if (given.points is None) == (given.file is None):
        raise source.error("give the table's points or its file (one of them)", at)
    if given.points is not None:
        points = given.points
        if len(points) < 2:
            raise source.error(f"has {len(points)} point: a table needs at least 2",
                               (*at, "points"))
        for i in range(1, len(points)):
            if not points[i][0] > points[i - 1][0]:
                raise source.error(f"q must increase strictly: {points[i][0]:g} {unit} "
                                   f"follows {points[i - 1][0]:g} {unit}", (*at, "points", i))
        x = tuple(p[0] for p in points)
        values = tuple(p[1] for p in points)
    else:
        x, values = _position_table_file(folder, given.file or "", linear, source,
                                         (*at, "file"), columns)
    offset = given.offset or 0.0
    if reach is not None:
        ends = (offset + reach[0], offset + reach[1])
        slack = 1e-9 * (x[-1] - x[0])
        if ends[0] < x[0] - slack or ends[1] > x[-1] + slack:
            what = "move" if model.cycle is None else "cycle"
            raise source.error(f"the {what} covers q = {ends[0]:.6g} to {ends[1]:.6g} {unit} "
                               f"of the table (its offset {offset:.6g} {unit} and the "
                               f"displacements): the table covers {x[0]:.6g} to "
                               f"{x[-1]:.6g} {unit}; extend it or check its offset", at)
    return x, values


def _position_table_files(model: DesignFile, folder: Path) -> list[Path]:
    """The CSV files the load's position tables read (relative to the design's folder)."""
    out = []
    for key in ("torque_table", "force_table", "inertia_table", "mass_table"):
        given = getattr(model.load, key, None)
        if given is not None and given.file is not None and given.file.strip():
            path = Path(given.file)
            out.append(path if path.is_absolute() else folder / path)
    return out


def _position_table_file(folder: Path, name: str, linear: bool, source: YamlSource,
                         at: tuple[str, ...], columns: tuple[Any, str] | None = None
                         ) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """The (q, tau) in SI of a position table's CSV: its first two columns, their units in
    its header (``q [deg],tau [N*m]``; ``s [mm],F [N]`` on a linear axis); ``columns``
    (the two columns' (kind, what, example) and the header's example) for other tables."""
    from sizer.io.cam_table import read_cam_table
    from sizer.units import to_si

    if not name.strip():
        raise source.error("must be the path of a CSV file", at)
    path = Path(name)
    if not path.is_absolute():
        path = folder / path
    try:
        table = read_cam_table(path)
    except UserError as error:
        raise source.relocate(error, at) from None
    file = str(path)
    kinds = (("length", "a length", "mm or m"), ("force", "a force", "N")) if linear else \
        (("angle", "an angle", "deg or rad"), ("torque", "a torque", "N*m"))
    if columns is not None:
        kinds = columns[0]
    scales = []
    for i, (kind, what, example) in enumerate(kinds):
        unit = table.units[i]
        column = table.column_name(i)
        if unit is None:
            header = "s [mm],F [N]" if linear else "q [deg],tau [N*m]"
            if columns is not None:
                header = columns[1]
            raise UserError(f"{column} has no unit: the header gives each column's unit in "
                            f"brackets, e.g. '{header}'", file=file,
                            line=table.header_line or int(table.lines[0]), field=column)
        try:
            scales.append(to_si(f"1 {unit}", kind, field=column))
        except UserError:
            raise UserError(f"[{unit}] is not {what} unit (e.g. {example})", file=file,
                            line=table.header_line, field=column) from None
    bad = np.flatnonzero(np.diff(table.x) <= 0.0)
    if bad.size:
        i = int(bad[0]) + 1
        raise UserError(f"q must increase strictly: {table.x[i]:g} follows "
                        f"{table.x[i - 1]:g}", file=file, line=int(table.lines[i]),
                        field=table.column_name(0))
    return tuple(float(v) for v in table.x * scales[0]), \
        tuple(float(v) for v in table.q * scales[1])


def _check_position_drive(model: DesignFile, source: YamlSource,
                          transmission: Transmission) -> None:
    """Refuse the drives the position-load engine does not model (sizer.sizing.linkage_move):
    a linkage, a stage's preload torque, the steady-load efficiency rule."""
    key = _position_key(model.load)
    if key is None:
        return
    at = ("load", key)
    stage = transmission.linkage
    if stage is not None:
        given = model.load
        others = [k for k in ("gravity", "spring", "inertia_table", "mass_table")
                  if getattr(given, k) is not None]
        if others:
            raise source.error("a load term of the position through a linkage or a cam is a "
                               "force (torque) table of its output's position only "
                               "(load.force_table, load.torque_table)", ("load", others[0]))
        if stage.kind == "disc_cam" or (stage.law_on == "crank"
                                        and stage.driven_link != "crank"):
            raise source.error("a table of the output's position needs a slider-crank or "
                               "four-bar whose crank the motor turns, or the law on its "
                               "output (not through a disc cam, nor with the law on a "
                               "driven rocker)", at)
    if transmission.efficiency_applies_to == "steady_load":
        raise source.error("a load term of the position needs efficiency_applies_to: "
                           "power_flow", at)
    if any(stage.preload_torque for stage in transmission.stages):
        raise source.error("a load term of the position is not supported with a stage's "
                           "preload torque yet", at)


def _elastic(model: DesignFile, source: YamlSource) -> ElasticLoad | None:
    """The load's mode of vibration (sec. 7.1.1), or None; its limit needs it."""
    given = model.load
    if given.natural_frequency is None:
        if given.damping_ratio is not None:
            raise source.error("a damping_ratio needs the natural_frequency of its mode",
                               ("load", "damping_ratio"))
        if model.limits.residual_vibration is not None:
            raise source.error("a residual_vibration limit needs the load's mode: give "
                               "load.natural_frequency (and damping_ratio)",
                               ("limits", "residual_vibration"))
        return None
    return ElasticLoad(given.natural_frequency, given.damping_ratio or 0.0)


def _limits(model: DesignFile, source: YamlSource, linear: bool) -> Limits:
    given = model.limits

    def quantity(key: str) -> float | None:
        value = getattr(given, key)
        if value is None:
            return None
        return _quantity(source, ("limits", key), value, axis_range(LimitsInput, key, linear))

    return Limits(
        torque_margin=given.torque_margin,
        speed_margin=given.speed_margin,
        inertia_ratio=given.inertia_ratio,
        max_acceleration=quantity("max_acceleration"),
        max_jerk=quantity("max_jerk"),
        thermal_speed=given.thermal_speed,
        inertia_ratio_of=given.inertia_ratio_of,
        envelope=given.envelope,
        max_speed=quantity("max_speed"),
        residual_vibration=quantity("residual_vibration"),
        drive_current_margin=given.drive_current_margin,
        braking_resistor_power=given.braking_resistor_power,
        winding_temperature_rise=given.winding_temperature_rise,
        thermal_duty=given.thermal_duty,
    )


def _design_motors(model: DesignFile, source: YamlSource, folder: Path,
                   extra_catalogs: Iterable[PathLike], warnings: list[str],
                   files: list[Path] | None = None,
                   drives: list[_LocatedDrive] | None = None) -> tuple[Motor, ...]:
    located: list[_Located] = []
    read: set[Path] = set()

    def add_catalog(path: Path) -> None:
        key = path.resolve()
        if key not in read:
            read.add(key)
            if files is not None:
                files.append(path)
            located.extend(_read_catalog(path, warnings, drives))

    for index, item in enumerate(model.motors or ()):
        at = ("motors", index)
        if isinstance(item, str):
            add_catalog(resolve_catalog(item, folder, source=source, at=at))
        else:
            motor = _motor(item, source, at)
            warnings += _motor_warnings(motor, source, at)
            located.append(_Located(motor, source, at))
    for reference in extra_catalogs:
        add_catalog(resolve_catalog(reference, Path.cwd()))
    if not located and model.motors is not None:  # `motors: []` and no --catalog
        if _load_limits_given(model):  # planned without a motor (sizer.sizing.planning)
            return ()
        raise source.error("no motors to size: the list is empty (name a catalog or a motor, "
                           "or omit `motors:` and give --catalog; or give limits.max_speed, "
                           "max_acceleration or max_jerk to plan without a motor)",
                           ("motors",))
    _check_unique(located)
    return tuple(m.motor for m in located)


def _load_limits_given(model: DesignFile) -> bool:
    """Any of the load's limits (max speed, acceleration, jerk): no motors (`motors:` left
    out or `motors: []`, and no --catalog) then means a plan without a motor (book sec.
    5.2.1, docs/planning.md)."""
    limits = model.limits
    return any(v is not None for v in (limits.max_speed, limits.max_acceleration,
                                       limits.max_jerk))


def _planned(model: DesignFile) -> bool:
    """No motors named (``motors:`` left out or ``[]``) and the load's limits given: a
    plan without a motor, which needs no load."""
    return not model.motors and _load_limits_given(model)


def _unknown_motor(motor_id: str, known: list[str]) -> str:
    if not known:
        return (f"unknown motor {motor_id!r}: no motors are loaded (list catalogs under "
                f"'motors:')")
    close = difflib.get_close_matches(motor_id, known, n=1)
    hint = f"did you mean {close[0]!r}? " if close else ""
    shown = ", ".join(known[:12]) + (", ..." if len(known) > 12 else "")
    return f"unknown motor {motor_id!r}; {hint}loaded motors: {shown}"


# ------------------------------------------------------------------- schemas


SCHEMA_DIALECT = "https://json-schema.org/draft/2020-12/schema"
SCHEMA_VERSION = 1
"""Bumped when a schema stops accepting files it accepted (its ``$id`` ends with it)."""


def schema_id(name: str) -> str:
    """The ``$id`` of a schema: a name, not an address (nothing is fetched from it)."""
    return f"urn:sizer-motion:schema:{name}:{SCHEMA_VERSION}"


def schema_document(model: type[BaseModel], name: str) -> dict[str, Any]:
    """The model's JSON Schema (derived by pydantic, shorthands included) with ``$schema``
    (draft 2020-12) and ``$id`` first."""
    return {"$schema": SCHEMA_DIALECT, "$id": schema_id(name),
            **model.model_json_schema(by_alias=True)}


def design_schema() -> dict[str, Any]:
    """JSON Schema of the design file (for ``sizer schema design``)."""
    return schema_document(DesignFile, "design")


def catalog_schema() -> dict[str, Any]:
    """JSON Schema of the motor catalog file (for ``sizer schema catalog``)."""
    return schema_document(CatalogFile, "catalog")


def gearbox_catalog_schema() -> dict[str, Any]:
    """JSON Schema of the gearbox catalog file (for ``sizer schema gearboxes``)."""
    return schema_document(GearboxCatalogFile, "gearboxes")


__all__ = [
    "NOT_DEFAULT_CATALOGS",
    "LoadedCatalog",
    "bundled_catalogs",
    "catalog_schema",
    "default_catalogs",
    "default_laws",
    "design_schema",
    "gearbox_catalog_schema",
    "load_catalog",
    "load_design",
    "read_catalog",
    "resolve_catalog",
]
