"""IDTA 02021 ApplicationRequirements -> a sizer design (a mapping, as a design file holds it).

The motion sections' CSV files (``idShort [unit]`` headers, ``;`` between fields, ``.`` as the
decimal point) become one cam table over time (sizer's CSV: ``t [s],q [rad]``), the section's
loads the design's ``load``, the TransformationMechanism its ``transmission``. Whatever has
no place in a sizer design is named in :attr:`IdtaDesign.notes`, never dropped silently.

The template's defects are tolerated: every quantity is read as a real number whatever its
``valueType`` (the template types them ``xs:long``); ``RotraryTable`` (the template's
spelling) and ``RotaryTable`` both name the rotary table.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from sizer.errors import UserError
from sizer.idta.template import (
    ALIASES,
    LINEAR_SECTION,
    MECHANISMS,
    ROTATIVE_SECTION,
    SUBMODEL_ID_SHORT,
    SUBMODEL_SEMANTIC_ID,
    TEMPLATE,
    semantic_id,
)
from sizer.units import to_si

Element = Mapping[str, Any]

"""Time units of a motion file that the cycle (UsageProfile.CyclesPerMinute) can use."""
DEFAULT_UNITS = {"Time": "s", "AngularPosition": "rad", "Position": "m"}
"""The template's units (its concept descriptions) where a header gives none."""
POSITION_COLUMNS = {"AngularPosition": "rotary", "Position": "linear"}
DERIVED_COLUMNS = {"AngularVelocity", "AngularAcceleration", "AngularJerk", "LinearVelocity",
                   "LinearAcceleration", "LinearJerk", "Velocity", "Acceleration"}
"""Columns the cam table's fit replaces (it differentiates the positions)."""
_HEADER = re.compile(r"^\s*([A-Za-z_][A-Za-z0-9_]*)\s*(?:\[([^\]]*)\])?\s*$")


@dataclass(frozen=True)
class MotionTable:
    """One motion section's samples: ``axis`` 'rotary' or 'linear', times and positions in
    the file's ``units`` (``{'time': 's', 'position': 'rad'}``), the other columns' notes."""

    axis: str
    times: tuple[float, ...]
    positions: tuple[float, ...]
    units: dict[str, str]
    notes: tuple[str, ...] = ()


@dataclass(frozen=True)
class IdtaDesign:
    """What an IDTA 02021 file (or one motion CSV) becomes: the design mapping (its one law a
    ``cam_table`` whose ``file`` is the ``cam_file`` given to the reader), the cam table's
    CSV text, and the notes on what the design does not carry or had to assume."""

    design: dict[str, Any]
    cam_csv: str
    notes: tuple[str, ...] = field(default=())


def _number(text: str, where: str, source: str, line: int | None = None) -> float:
    """A real number written with '.' (an integer too: the template's xs:long)."""
    cleaned = text.strip()
    try:
        value = float(cleaned)
    except ValueError:
        hint = " (the decimal point is '.')" if "," in cleaned else ""
        raise UserError(f"{where}: {cleaned!r} is not a number{hint}", file=source,
                        line=line) from None
    if not math.isfinite(value):
        raise UserError(f"{where}: {cleaned!r} is not a finite number", file=source, line=line)
    return value


def read_motion_csv(text: str, *, source: str) -> MotionTable:
    """A motion section file: the header ``Time [s];AngularPosition [rad];...`` (or
    ``Position [m]``), then one row of numbers per sample; times must increase."""
    rows = [(number, line) for number, line in enumerate(text.splitlines(), 1)
            if line.strip() and not line.lstrip().startswith("#")]
    if not rows:
        raise UserError("the motion file is empty", file=source)
    header_line, header = rows[0]
    names: list[str] = []
    units: list[str | None] = []
    for cell in header.rstrip().rstrip(";").split(";"):
        match = _HEADER.match(cell)
        if match is None:
            raise UserError(f"header cell {cell.strip()!r} is not 'idShort [unit]'",
                            file=source, line=header_line)
        names.append(match.group(1))
        units.append(match.group(2).strip() if match.group(2) else None)
    if "Time" not in names:
        raise UserError("the header has no 'Time' column", file=source, line=header_line)
    positions = [n for n in names if n in POSITION_COLUMNS]
    if len(positions) != 1:
        raise UserError("the header needs one position column, 'AngularPosition' (rotary) or "
                        "'Position' (linear)", file=source, line=header_line)
    position = positions[0]
    columns: list[list[float]] = [[] for _ in names]
    for number, line in rows[1:]:
        cells = line.rstrip().rstrip(";").split(";")
        if len(cells) != len(names):
            raise UserError(f"{len(cells)} fields where the header has {len(names)}",
                            file=source, line=number)
        for column, (name, cell) in enumerate(zip(names, cells, strict=True)):
            columns[column].append(_number(cell, name, source, number))
    times = columns[names.index("Time")]
    if len(times) < 2:
        raise UserError("the motion file needs at least 2 samples", file=source)
    for k in range(1, len(times)):
        if not times[k] > times[k - 1]:
            raise UserError(f"Time: the times must increase ({times[k]!r} after "
                            f"{times[k - 1]!r})", file=source, line=rows[k + 1][0])
    notes = []
    for name, values in zip(names, columns, strict=True):
        if name in ("Time", position):
            continue
        if name in DERIVED_COLUMNS:
            notes.append(f"{source}: column {name} not used: the cam table's fit differentiates "
                         "the positions")
        elif any(values):
            notes.append(f"{source}: column {name} (a load varying over the motion) is not "
                         "supported: not in the design")
    unit_of = dict(zip(names, units, strict=True))
    return MotionTable(
        axis=POSITION_COLUMNS[position], times=tuple(times),
        positions=tuple(columns[names.index(position)]),
        units={"time": unit_of["Time"] or DEFAULT_UNITS["Time"],
               "position": unit_of[position] or DEFAULT_UNITS[position]},
        notes=tuple(notes))


# --- the AAS structure ---------------------------------------------------------------

def _semantic_value(element: Element) -> str | None:
    keys = (element.get("semanticId") or {}).get("keys") or []
    return str(keys[0].get("value", "")).strip() if keys else None


def _children(element: Element) -> list[Element]:
    if element.get("modelType") == "Entity":
        return list(element.get("statements") or [])
    value = element.get("value")
    return list(value) if isinstance(value, list) else []


def _is(element: Element, name: str, semantic: str | None = None) -> bool:
    """``element`` is the template's ``name``: by its semantic ID, or by its idShort (with a
    number appended, as several sections are named: ``RotativeSection02``)."""
    spellings = (name, *(a for a, b in ALIASES.items() if b == name))
    semantics = {semantic} if semantic else {semantic_id(s) for s in spellings}
    if _semantic_value(element) in semantics:
        return True
    id_short = str(element.get("idShort", ""))
    for spelling in spellings:
        if id_short == spelling or (id_short.startswith(spelling)
                                    and id_short[len(spelling):].isdigit()):
            return True
    return False


def _all(element: Element, name: str, semantic: str | None = None) -> list[Element]:
    return [c for c in _children(element) if _is(c, name, semantic)]


def _one(element: Element | None, name: str) -> Element | None:
    if element is None:
        return None
    found = _all(element, name)
    return found[0] if found else None


class _Reader:
    """Reads the numbers of one submodel, with the path of each in its messages."""

    def __init__(self, source: str) -> None:
        self.source = source
        self.notes: list[str] = []

    def number(self, element: Element | None, name: str, path: str) -> float | None:
        """The value of the property ``name`` of ``element`` as a real number (None when
        absent or empty), whatever its valueType."""
        found = _one(element, name)
        if found is None:
            return None
        value = found.get("value")
        if value is None or str(value).strip() == "":
            return None
        return _number(str(value), f"{path}.{found.get('idShort', name)}", self.source)


def _submodel(data: Mapping[str, Any], source: str) -> Element:
    if data.get("modelType") == "Submodel":
        candidates: Sequence[Element] = [data]
    else:
        candidates = list(data.get("submodels") or [])
    for submodel in candidates:
        if (_semantic_value(submodel) == SUBMODEL_SEMANTIC_ID
                or submodel.get("idShort") == SUBMODEL_ID_SHORT):
            return submodel
    raise UserError(f"no {TEMPLATE} submodel (semanticId {SUBMODEL_SEMANTIC_ID}): a submodel, "
                    "or an environment with 'submodels'", file=source)


def _elements(submodel: Element) -> Element:
    return {"modelType": "SubmodelElementCollection",
            "value": list(submodel.get("submodelElements") or [])}


def _sections(requirements: Element | None) -> Iterator[tuple[str, Element]]:
    pattern = _one(requirements, "MotionPattern")
    sections = _one(pattern, "MotionPatternSections")
    if sections is None:
        return
    for child in _children(sections):
        if _is(child, "RotativeSection", ROTATIVE_SECTION):
            yield "rotary", child
        elif _is(child, "LinearSection", LINEAR_SECTION):
            yield "linear", child


def _file_path(section: Element) -> str | None:
    found = _one(section, "MotionSectionFile")
    value = found.get("value") if found else None
    return str(value).strip() if value else None


def _join(tables: Sequence[MotionTable], names: Sequence[str], source: str) -> MotionTable:
    """The sections one after the other: a section whose times start at or before the end
    of the previous one is shifted to start there (its times are relative)."""
    first = tables[0]
    times, positions = list(first.times), list(first.positions)
    for table, name in zip(tables[1:], names[1:], strict=True):
        if table.units != first.units or table.axis != first.axis:
            raise UserError(f"{name}: its axis and units ({table.axis}, {table.units}) differ "
                            f"from the first section's ({first.axis}, {first.units})", file=source)
        if abs(table.positions[0] - positions[-1]) > 1e-9 * max(1.0, abs(positions[-1])):
            raise UserError(f"{name}: starts at position {table.positions[0]!r} where the "
                            f"previous section ended at {positions[-1]!r}", file=source)
        shift = times[-1] - table.times[0] if table.times[0] <= times[-1] else 0.0
        times.extend(t + shift for t in table.times[1:])
        positions.extend(table.positions[1:])
    return MotionTable(first.axis, tuple(times), tuple(positions), first.units,
                       tuple(n for t in tables for n in t.notes))


def _with_rest(table: MotionTable, cycle: float, reader: _Reader) -> MotionTable:
    """The table held at its last position until ``cycle`` (in the table's time unit), at the
    table's last sample interval: the cycle's rest, inside the cam table."""
    end = table.times[-1]
    duration = end - table.times[0]
    if cycle <= duration * (1 + 1e-9):
        if cycle < duration * (1 - 1e-9):
            reader.notes.append(f"UsageProfile.CyclesPerMinute: the cycle ({cycle:g} "
                                f"{table.units['time']}) is shorter than the motion "
                                f"({duration:g}): ignored")
        return table
    step = table.times[-1] - table.times[-2]
    count = max(1, math.ceil((cycle - duration) / step - 1e-9))
    rest = [end + (cycle - duration) * k / count for k in range(1, count + 1)]
    reader.notes.append(f"UsageProfile.CyclesPerMinute: the cycle is {cycle:g} "
                        f"{table.units['time']}: the table holds its last position for the "
                        f"{cycle - duration:g} {table.units['time']} of rest")
    return MotionTable(table.axis, (*table.times, *rest),
                       (*table.positions, *[table.positions[-1]] * count), table.units,
                       table.notes)


def cam_csv(table: MotionTable, source: str) -> str:
    """The table as sizer's cam table CSV (``t [s],q [rad]``), numbers written exactly."""
    lines = [f"# motion of {source} ({TEMPLATE}), one machine cycle",
             f"t [{table.units['time']}],q [{table.units['position']}]"]
    lines += [f"{t!r},{q!r}" for t, q in zip(table.times, table.positions, strict=True)]
    return "\n".join(lines) + "\n"


def _efficiency(value: float | None, path: str, reader: _Reader) -> float | None:
    if value is None:
        return None
    if 1 < value <= 100:
        reader.notes.append(f"{path}.Efficiency {value:g} read as a percentage ({value / 100:g})")
        value /= 100
    if not 0 < value <= 1:
        raise UserError(f"{path}.Efficiency: {value:g} is not in (0, 1]", file=reader.source)
    return value


LINEAR_FEEDS = ("BeltConveyor", "ChainConveyor", "RollerConveyor", "TravelingDrive")
"""Mechanisms given by their feed constant alone: a pinion of circumference FeedConstant."""


def _transmission(mechanism: Element | None, axis: str, reader: _Reader
                  ) -> tuple[dict[str, Any] | None, dict[str, Any]]:
    """The design's transmission stage and the load fields the mechanism adds."""
    extra: dict[str, Any] = {}
    if mechanism is None:
        if axis == "linear":
            raise UserError("a linear section needs a TransformationMechanism with its "
                            "FeedConstant (SpindleDrive, BeltDrive, RackDrive...)",
                            file=reader.source)
        reader.notes.append("no TransformationMechanism: the motor drives the load directly")
        return None, extra
    entities = [(name, e) for e in _children(mechanism) for name in MECHANISMS if _is(e, name)]
    if not entities:
        reader.notes.append("TransformationMechanism names no mechanism: the motor drives the "
                            "load directly")
        return None, extra
    if len(entities) > 1:
        reader.notes.append("TransformationMechanism: " + ", ".join(n for n, _ in entities)
                            + f": only the first ({entities[0][0]}) is used")
    name, entity = entities[0]
    path = f"TransformationMechanism.{entity.get('idShort', name)}"
    values = {p: reader.number(entity, p, path) for p in (
        "Efficiency", "InertiaMotorSide", "FeedConstant", "DiameterPinion", "NoLoadTorque",
        "InclinationAngle", "FrictionCoefficient", "LeverArmAxialForce", "LeverArmRadialForce",
        "StaticEccentricity", "CentroidAngle", "HelixAngle")}
    efficiency = _efficiency(values["Efficiency"], path, reader)
    stage: dict[str, Any]
    used = {"Efficiency", "InertiaMotorSide"}
    if name == "RotraryTable":
        if axis != "rotary":
            raise UserError(f"{path}: a rotary table needs a RotativeSection",
                            file=reader.source)
        stage = {"type": "gearbox", "ratio": 1, "name": "rotary table"}
        reader.notes.append(f"{path}: the template gives no ratio: ratio 1 (edit "
                            "transmission.ratio, or 'optimize')")
    elif name in ("Fan", "Pump"):
        raise UserError(f"{path}: a {name} (a load that depends on speed) is not supported",
                        file=reader.source)
    else:
        if axis != "linear":
            raise UserError(f"{path}: a {name} needs a LinearSection", file=reader.source)
        feed = values["FeedConstant"]
        used.add("FeedConstant")
        if name == "RackDrive" and values["DiameterPinion"] is not None:
            stage = {"type": "rack_pinion", "pitch_diameter": f"{values['DiameterPinion']!r} m"}
            used.add("DiameterPinion")
        elif feed is None or feed <= 0:
            raise UserError(f"{path}.FeedConstant: required and positive (m/rev)",
                            file=reader.source)
        elif name == "SpindleDrive":
            stage = {"type": "ball_screw", "lead": f"{feed!r} m"}
            if values["NoLoadTorque"] is not None:
                stage["preload_torque"] = f"{values['NoLoadTorque']!r} N*m"
                used.add("NoLoadTorque")
        elif name == "BeltDrive":
            stage = {"type": "belt", "driver_diameter": f"{feed / math.pi!r} m"}
        else:
            stage = {"type": "rack_pinion", "pitch_diameter": f"{feed / math.pi!r} m"}
            if name != "RackDrive":
                reader.notes.append(f"{path}: a {name} sized as a pinion of circumference "
                                    f"FeedConstant ({feed:g} m)")
        if values["InclinationAngle"] is not None:
            extra["incline"] = f"{values['InclinationAngle']!r} rad"
            used.add("InclinationAngle")
        if values["FrictionCoefficient"] is not None:
            extra["friction_coefficient"] = values["FrictionCoefficient"]
            used.add("FrictionCoefficient")
    if efficiency is not None:
        stage["efficiency"] = efficiency
    inertia = values["InertiaMotorSide"]
    if inertia is not None:
        key = {"belt": "driver_inertia"}.get(stage["type"], "inertia")
        stage[key] = f"{inertia!r} kg*m^2"
    for prop, value in values.items():
        if value is not None and prop not in used:
            reader.notes.append(f"{path}.{prop} = {value:g}: not used by sizer")
    return stage, extra


ROTARY_LOADS = {"MomentOfInertiaOfLoad": ("inertia", "kg*m^2", 1.0),
                "FrictionTorque": ("friction", "N*m", 1.0),
                "LoadTorque": ("torque", "N*m", -1.0)}
LINEAR_LOADS = {"LoadMass": ("mass", "kg", 1.0), "FrictionForce": ("friction", "N", 1.0),
                "LoadSideForce": ("force", "N", -1.0)}
"""Section property -> (load field, unit, sign). The template's load torque and force act in
the direction of increasing position; sizer's oppose a positive move: the sign flips."""


def _load(axis: str, sections: Sequence[Element], names: Sequence[str],
          reader: _Reader) -> dict[str, Any]:
    table = ROTARY_LOADS if axis == "rotary" else LINEAR_LOADS
    load: dict[str, Any] = {}
    first = sections[0]
    for prop, (key, unit, sign) in table.items():
        value = reader.number(first, prop, names[0])
        if value is not None:
            load[key] = f"{sign * value + 0.0!r} {unit}"
    if axis == "linear":
        coefficient = reader.number(first, "FrictionCoefficient", names[0])
        if coefficient is not None:
            load["friction_coefficient"] = coefficient
        counter = reader.number(first, "CounterMass", names[0])
        if counter is not None:
            reader.notes.append(f"{names[0]}.CounterMass = {counter:g} kg: not used (sizer has "
                                "no counterweight; add its mass to load.mass if it moves "
                                "with the load)")
    ignored = (("LeverArmAxialForce", "AxialForce", "LeverArmRadialForce", "RadialForce")
               if axis == "rotary" else ("CompensationForce",))
    for prop in ignored:
        value = reader.number(first, prop, names[0])
        if value is not None:
            reader.notes.append(f"{names[0]}.{prop} = {value:g}: not used by sizer (bearing "
                                "and compensation loads are not checked)")
    if "inertia" not in load and "mass" not in load:
        load["inertia" if axis == "rotary" else "mass"] = (
            "0 kg*m^2" if axis == "rotary" else "0 kg")
        reader.notes.append(f"{names[0]}: no load inertia or mass given: 0")
    for section, name in zip(sections[1:], names[1:], strict=True):
        for prop in table:
            if reader.number(section, prop, name) != reader.number(first, prop, names[0]):
                reader.notes.append(f"{name}.{prop} differs from the first section's: sizer "
                                    "takes one load per axis, the first section's")
    return load


def read_submodel(data: Mapping[str, Any], *, source: str, read_file: Callable[[str], str],
                  cam_file: str) -> IdtaDesign:
    """The design of an IDTA 02021 submodel (or an environment holding one): ``read_file``
    gives the text of a MotionSectionFile's value (the CLI resolves it beside ``source``);
    ``cam_file`` is the name the design gives its cam table."""
    reader = _Reader(source)
    submodel = _submodel(data, source)
    root = _elements(submodel)
    requirements = _one(root, "ApplicationRequirements")
    if requirements is None:
        raise UserError("the submodel has no ApplicationRequirements", file=source)
    found = list(_sections(requirements))
    if not found:
        raise UserError("ApplicationRequirements.MotionPattern.MotionPatternSections has no "
                        "RotativeSection or LinearSection", file=source)
    axes = {axis for axis, _ in found}
    if len(axes) > 1:
        raise UserError("rotary and linear sections in one motion pattern: sizer sizes one axis",
                        file=source)
    axis = axes.pop()
    sections = [section for _, section in found]
    names = [f"MotionPatternSections.{s.get('idShort', '?')}" for s in sections]
    tables = []
    for section, name in zip(sections, names, strict=True):
        path = _file_path(section)
        if path is None:
            raise UserError(f"{name}.MotionSectionFile: no file (the section's motion CSV)",
                            file=source)
        table = read_motion_csv(read_file(path), source=path)
        if table.axis != axis:
            raise UserError(f"{path}: a {table.axis} motion in a {axis} section", file=source)
        tables.append(table)
    table = _join(tables, names, source)
    usage = _one(requirements, "UsageProfile")
    cycles = reader.number(usage, "CyclesPerMinute", "ApplicationRequirements.UsageProfile")
    if cycles is not None and cycles > 0:
        try:  # the seconds of one unit of the motion's time column (sizer.units)
            scale = to_si(f"1 {table.units['time']}", "time")
        except UserError:
            reader.notes.append("UsageProfile.CyclesPerMinute not used: the motion's time unit "
                                f"{table.units['time']!r} is not a time")
        else:
            table = _with_rest(table, 60.0 / cycles / scale, reader)
    load = _load(axis, sections, names, reader)
    stage, extra = _transmission(_one(root, "TransformationMechanism"), axis, reader)
    for key, value in extra.items():
        load.setdefault(key, value)
    info = _one(root, "SizingProjectInformation")
    pattern = _one(requirements, "MotionPattern")
    name_of = (_value(info, "SizingProjectName") or _value(pattern, "MotionPatternName")
               or source)
    design: dict[str, Any] = {
        "name": name_of,
        "task": {"duration": f"{table.times[-1] - table.times[0]!r} {table.units['time']}",
                 "dwell": f"0 {table.units['time']}"},
        "load": load,
    }
    if stage is not None:
        design["transmission"] = stage
    design["laws"] = [{"kind": "cam_table", "file": cam_file, "periodic": True}]
    for other in ("Environmental", "OverallSystemRequirements"):
        if _one(requirements, other) is not None and any(
                c.get("value") not in (None, "", []) for c in _children(_one(requirements, other)
                                                                      or {})):
            reader.notes.append(f"ApplicationRequirements.{other}: not used by sizer")
    return IdtaDesign(design, cam_csv(table, source), (*table.notes, *reader.notes))


def _value(element: Element | None, name: str) -> str | None:
    found = _one(element, name)
    value = found.get("value") if found else None
    return value.strip() or None if isinstance(value, str) else None


def read_csv_design(text: str, *, source: str, cam_file: str) -> IdtaDesign:
    """The design of one motion CSV alone: its law, and a load of 0 to be filled in."""
    table = read_motion_csv(text, source=source)
    key, unit = ("inertia", "kg*m^2") if table.axis == "rotary" else ("mass", "kg")
    notes = [*table.notes, f"a motion file alone: load.{key} 0, fill in the load"]
    if table.axis == "linear":
        notes.append("a linear motion needs a transmission: fill in 'transmission'")
    design: dict[str, Any] = {
        "name": source,
        "task": {"duration": f"{table.times[-1] - table.times[0]!r} {table.units['time']}",
                 "dwell": f"0 {table.units['time']}"},
        "load": {key: f"0 {unit}"},
        "laws": [{"kind": "cam_table", "file": cam_file, "periodic": True}],
    }
    return IdtaDesign(design, cam_csv(table, source), tuple(notes))
