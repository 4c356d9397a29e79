"""IDTA 02021 ApplicationRequirements -> a sizer design (a mapping, as a design file holds it).

The motion sections' CSV files (``idShort [unit]`` headers, ``;`` between fields, ``.`` as the
decimal point, read by sizer.io.csv_rows) become the design's motion: each move between rests a
cam table over time (sizer's CSV: ``t [s],q [rad]``), each rest (a span where the position
holds, and the rest to the cycle time) a dwell; a motion without a rest one periodic cam table.
The section's loads become the design's ``load``, the TransformationMechanism its
``transmission``. Whatever has
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
from sizer.io.csv_rows import NUMBER, csv_records
from sizer.units import to_si

Element = Mapping[str, Any]

MOTION_DELIMITER = ";"
"""The separator of a motion section file (the template's rule, with '.' as the decimal
point)."""
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
    """What an IDTA 02021 file (or one motion CSV) becomes: the design mapping, the cam
    tables its laws name (``cams``: file name, CSV text; one file, the ``cam_file`` given to
    the reader, or one per move, ``cam_file``'s stem with ``-1``, ``-2``...) and the notes on
    what the design does not carry or had to assume."""

    design: dict[str, Any]
    cams: tuple[tuple[str, str], ...]
    notes: tuple[str, ...] = field(default=())

    @property
    def cam_csv(self) -> str:
        """The CSV text of the first (usually the only) cam table."""
        return self.cams[0][1]


def _number(text: str, where: str, source: str, line: int | None = None) -> float:
    """A real number written with '.' (an integer too: the template's xs:long), in the form
    every sizer CSV reads (sizer.io.csv_rows.NUMBER: no ``nan``, ``inf`` or ``1_000``)."""
    cleaned = text.strip()
    if NUMBER.match(cleaned) is None:
        hint = " (the decimal point is '.')" if "," in cleaned else ""
        raise UserError(f"{where}: {cleaned!r} is not a number{hint}", file=source,
                        line=line)
    return float(cleaned)


def _cells(record: list[str]) -> list[str]:
    """A record's cells without the empty one a trailing ';' leaves."""
    return record[:-1] if len(record) > 1 and not record[-1].strip() else record


def read_motion_csv(text: str, *, source: str) -> MotionTable:
    """A motion section file: the header ``Time [s];AngularPosition [rad];...`` (or
    ``Position [m]``), then one row of numbers per sample; times must increase. Records are
    read by sizer's CSV reader (sizer.io.csv_rows) with the template's separator ``;``
    (not sniffed: a ',' is never a separator nor a decimal comma here)."""
    rows = [(number, _cells(cells)) for number, cells in
            csv_records(text, source, MOTION_DELIMITER, comment="#")
            if any(cell.strip() for cell in cells)]
    if not rows:
        raise UserError("the motion file is empty", file=source)
    header_line, header = rows[0]
    names: list[str] = []
    units: list[str | None] = []
    for cell in header:
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
    for number, cells in rows[1:]:
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


def _with_rest(table: MotionTable, rest: float) -> MotionTable:
    """The table held at its last position for ``rest`` more (in the table's time unit), at
    the table's last sample interval: the cycle's rest inside a periodic cam table."""
    end = table.times[-1]
    step = table.times[-1] - table.times[-2]
    count = max(1, math.ceil(rest / step - 1e-9))
    times = [end + rest * k / count for k in range(1, count + 1)]
    return MotionTable(table.axis, (*table.times, *times),
                       (*table.positions, *[table.positions[-1]] * count), table.units,
                       table.notes)


def _cycle_rest(table: MotionTable, cycle: float | None, notes: list[str]) -> float:
    """The rest after the motion's last sample that the cycle time ``cycle`` (the table's
    time unit) leaves: 0 without a cycle time, or one shorter than the motion (a note)."""
    duration = table.times[-1] - table.times[0]
    if cycle is None or cycle <= duration * (1 + 1e-9):
        if cycle is not None and cycle < duration * (1 - 1e-9):
            notes.append(f"UsageProfile.CyclesPerMinute: the cycle ({cycle:g} "
                         f"{table.units['time']}) is shorter than the motion ({duration:g}): "
                         "ignored")
        return 0.0
    return cycle - duration


def _rests(positions: Sequence[float]) -> list[tuple[int, int]]:
    """The rests of a sample sequence: maximal runs i..j (j > i) of samples at the very same
    position (as written: a hold is written as the same number)."""
    rests = []
    i = 0
    while i < len(positions) - 1:
        j = i
        while j + 1 < len(positions) and positions[j + 1] == positions[i]:
            j += 1
        if j > i:
            rests.append((i, j))
        i = max(j, i + 1)
    return rests


@dataclass(frozen=True)
class _Span:
    kind: str
    """'move' or 'rest'."""
    times: tuple[float, ...]
    positions: tuple[float, ...]

    @property
    def duration(self) -> float:
        return self.times[-1] - self.times[0]


def _cycle_spans(table: MotionTable, rest_after: float, notes: list[str]) -> list[_Span] | None:
    """The machine cycle of ``table`` (repeated, with ``rest_after`` at its end) as moves
    and rests, starting with the move that follows a rest: None without a rest. The cycle
    is read around its end: a rest before the first move is the end of the last one, and a
    motion from the last rest to the table's end goes on into the table's start."""
    times, positions = list(table.times), list(table.positions)
    if rest_after > 0:
        times.append(times[-1] + rest_after)
        positions.append(positions[-1])
    rests = _rests(positions)
    if not rests:
        return None
    period = times[-1] - times[0]
    unit = table.units["time"]
    if rests[0][0] == 0:
        start = rests[0][1]  # begin after the leading rest, which ends the cycle
        if rests[0][1] < len(positions) - 1:
            notes.append(f"the motion rests {times[start] - times[0]:g} {unit} before its first "
                         "move: read as the end of the cycle's last rest")
    elif rests[-1][1] == len(positions) - 1:
        start = 0
    else:
        start = rests[0][1]
        tail = times[-1] - times[rests[-1][1]]
        notes.append(f"the motion from its last rest to its end ({tail:g} {unit}) goes on "
                     "into its start: one move across the cycle's end")
    # the samples before start, after the end: times one period on, positions one net
    # displacement on ((q - q_first) + q_last keeps a rest's equal numbers equal)
    first, last = positions[0], positions[-1]
    turned_t = times[start:] + [t + period for t in times[1:start + 1]]
    turned_q = positions[start:] + [(q - first) + last for q in positions[1:start + 1]]
    spans = []
    edges = [0]
    for i, j in _rests(turned_q):
        edges += [i, j]
    edges.append(len(turned_q) - 1)
    for k in range(len(edges) - 1):
        i, j = edges[k], edges[k + 1]
        if j > i:
            spans.append(_Span("rest" if k % 2 else "move", tuple(turned_t[i:j + 1]),
                               tuple(turned_q[i:j + 1])))
    return spans


def cam_csv(table: MotionTable, source: str) -> str:
    """The table as sizer's cam table CSV (``t [s],q [rad]``), numbers written exactly."""
    lines = [f"# motion of {source} ({TEMPLATE})",
             f"t [{table.units['time']}],q [{table.units['position']}]"]
    lines += [f"{t!r},{q!r}" for t, q in zip(table.times, table.positions, strict=True)]
    return "\n".join(lines) + "\n"


def _span_text(value: float, unit: str) -> str:
    """A duration or displacement of the design, the difference of two numbers of the file
    to 15 significant digits (``0.2 s``, not the ``0.19999999999999996`` of 0.6 - 0.4)."""
    return f"{float(f'{value:.15g}')!r} {unit}"


def _cam_name(cam_file: str, k: int, count: int) -> str:
    if count == 1:
        return cam_file
    stem, dot, suffix = cam_file.rpartition(".")
    return f"{stem}-{k}.{suffix}" if dot else f"{cam_file}-{k}"


def _motion_design(table: MotionTable, cycle: float | None, source: str, cam_file: str
                   ) -> tuple[dict[str, Any], tuple[tuple[str, str], ...], list[str]]:
    """The design's motion fields (``task`` and ``laws``, or ``cycle``), its cam tables and
    notes. A rest of the motion (samples holding a position, and the rest to the cycle time)
    is a dwell: one move gives ``task: {duration, dwell}`` with its cam table, several
    moves a ``cycle`` of moves (each its own cam table) and dwells. Without a rest the table
    is one periodic cam table; likewise when a move between rests ends where it started (a
    move of displacement 0 is no move in a sizer cycle)."""
    notes: list[str] = []
    rest_after = _cycle_rest(table, cycle, notes)
    unit, length = table.units["time"], table.units["position"]
    spans = _cycle_spans(table, rest_after, notes)
    if spans is not None and not any(s.kind == "move" for s in spans):
        raise UserError("the motion holds one position throughout: no move to size",
                        file=source)
    moves = [s for s in spans or () if s.kind == "move"]
    closed = [m for m in moves if abs(m.positions[-1] - m.positions[0])
              <= 1e-9 * (max(m.positions) - min(m.positions))]
    if spans is None or closed:
        if closed:
            notes.append(f"a move from {closed[0].times[0]:g} {unit} returns to its start "
                         "(a move of displacement 0 is not a move of a sizer cycle): its rests "
                         "are kept in one periodic cam table")
        if rest_after > 0:
            notes.append(f"UsageProfile.CyclesPerMinute: the cycle is {cycle:g} {unit}: the "
                         f"table holds its last position for the {rest_after:g} {unit} of rest")
            table = _with_rest(table, rest_after)
        task = {"duration": _span_text(table.times[-1] - table.times[0], unit),
                "dwell": f"0 {unit}"}
        return ({"task": task, "laws": [{"kind": "cam_table", "file": cam_file,
                                         "periodic": True}]},
                ((cam_file, cam_csv(table, source)),), notes)
    if rest_after > 0:
        notes.append(f"UsageProfile.CyclesPerMinute: the cycle is {cycle:g} {unit}: "
                     f"{rest_after:g} {unit} of rest after the motion")
    names = [_cam_name(cam_file, k, len(moves)) for k in range(1, len(moves) + 1)]
    cams = tuple((name, cam_csv(MotionTable(table.axis, move.times, move.positions,
                                            table.units), source))
                 for name, move in zip(names, moves, strict=True))
    rests = [s for s in spans if s.kind == "rest"]
    notes.append(f"the motion's rests ({', '.join(f'{r.duration:g}' for r in rests)} {unit}) "
                 "are the design's dwell" + ("s" if len(rests) > 1 else "")
                 + (f", its {len(moves)} moves a cycle" if len(moves) > 1 else ""))
    if len(moves) == 1:
        move = moves[0]
        dwell = sum(r.duration for r in rests)
        task = {"duration": _span_text(move.duration, unit), "dwell": _span_text(dwell, unit)}
        return {"task": task, "laws": [{"kind": "cam_table", "file": cam_file}]}, cams, notes
    segments: list[dict[str, Any]] = []
    names_of = iter(names)
    for span in spans:
        if span.kind == "move":
            segments.append({"move": {
                "displacement": _span_text(span.positions[-1] - span.positions[0], length),
                "duration": _span_text(span.duration, unit),
                "law": {"kind": "cam_table", "file": next(names_of)}}})
        else:
            segments.append({"dwell": {"duration": _span_text(span.duration, unit)}})
    return {"cycle": {"segments": segments}}, cams, notes


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
    cycle = None
    if cycles is not None and cycles > 0:
        try:  # the seconds of one unit of the motion's time column (sizer.units)
            scale = to_si(f"1 {table.units['time']}", "time")
        except UserError:
            reader.notes.append("UsageProfile.CyclesPerMinute not used: the motion's time unit "
                                f"{table.units['time']!r} is not a time")
        else:
            cycle = 60.0 / cycles / scale
    motion, cams, motion_notes = _motion_design(table, cycle, source, cam_file)
    reader.notes.extend(motion_notes)
    load = _load(axis, sections, names, reader)
    stage, extra = _transmission(_one(root, "TransformationMechanism"), axis, reader)
    for key, value in extra.items():
        load.setdefault(key, value)
    info = _one(root, "SizingProjectInformation")
    pattern = _one(requirements, "MotionPattern")
    name_of = (_value(info, "SizingProjectName") or _value(pattern, "MotionPatternName")
               or source)
    design: dict[str, Any] = {"name": name_of}
    design.update((k, v) for k, v in motion.items() if k != "laws")
    design["load"] = load
    if stage is not None:
        design["transmission"] = stage
    if "laws" in motion:
        design["laws"] = motion["laws"]
    for other in ("Environmental", "OverallSystemRequirements"):
        if _one(requirements, other) is not None and any(
                c.get("value") not in (None, "", []) for c in _children(_one(requirements, other)
                                                                      or {})):
            reader.notes.append(f"ApplicationRequirements.{other}: not used by sizer")
    return IdtaDesign(design, cams, (*table.notes, *reader.notes))


def _value(element: Element | None, name: str) -> str | None:
    found = _one(element, name)
    value = found.get("value") if found else None
    return value.strip() or None if isinstance(value, str) else None


def read_csv_design(text: str, *, source: str, cam_file: str) -> IdtaDesign:
    """The design of one motion CSV alone: its law, and a load of 0 to be filled in."""
    table = read_motion_csv(text, source=source)
    key, unit = ("inertia", "kg*m^2") if table.axis == "rotary" else ("mass", "kg")
    motion, cams, motion_notes = _motion_design(table, None, source, cam_file)
    notes = [*table.notes, *motion_notes, f"a motion file alone: load.{key} 0, fill in the load"]
    if table.axis == "linear":
        notes.append("a linear motion needs a transmission: fill in 'transmission'")
    design: dict[str, Any] = {"name": source}
    design.update((k, v) for k, v in motion.items() if k != "laws")
    design["load"] = {key: f"0 {unit}"}
    if "laws" in motion:
        design["laws"] = motion["laws"]
    return IdtaDesign(design, cams, tuple(notes))
