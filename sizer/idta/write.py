"""A sizing result -> the IDTA 02021 submodel with its SizingResult (AAS V3.0 JSON).

The submodel carries SizingProjectInformation (project name, tool, dates) and SizingResult:
one MainComponent for the motor (and one for a catalog gearbox), with the utilisations
1 - margin of the peak torque, the RMS torque and the speed, and the Messages (sizer's notes
and the limiting check). Real quantities are written with ``valueType`` ``xs:double``: the
template types them ``xs:long``, which cannot hold 0.15 N*m (docs/idta-02021.md).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from sizer.idta.template import (
    ECLASS,
    PROJECT_INFORMATION_SEMANTIC_ID,
    RESULT_SEMANTIC_IDS,
    SUBMODEL_ID_SHORT,
    SUBMODEL_SEMANTIC_ID,
    semantic_id,
)

REAL = "xs:double"
"""The valueType sizer writes for a real quantity (the template's ``xs:long`` is a defect)."""


@dataclass(frozen=True)
class PairResult:
    """The chosen pair of a sizing, in SI units: torques N*m, speed rad/s at the motor,
    margins as fractions (utilisation = 1 - margin)."""

    motor: str
    manufacturer: str | None
    feasible: bool
    peak_torque: float
    rms_torque: float
    max_speed: float
    margin_peak: float
    margin_rms: float
    margin_speed: float
    limiting: str
    law: str
    ratio: float | None = None
    gearbox: str | None = None
    reason: str = ""
    notes: tuple[str, ...] = field(default=())
    part_number: str | None = None
    """The motor's order code where its catalog gives one (else its id is written)."""


def _reference(value: str) -> dict[str, Any]:
    return {"type": "ExternalReference", "keys": [{"type": "GlobalReference", "value": value}]}


def _semantic(name: str) -> str:
    return ECLASS.get(name) or RESULT_SEMANTIC_IDS.get(name) or semantic_id(name)


def _property(name: str, value: str, value_type: str = "xs:string") -> dict[str, Any]:
    return {"idShort": name, "semanticId": _reference(_semantic(name)),
            "valueType": value_type, "value": value, "modelType": "Property"}


def _real(name: str, value: float) -> dict[str, Any]:
    return _property(name, repr(float(value)), REAL)


def _text(name: str, text: str, semantic: str | None = None) -> dict[str, Any]:
    return {"idShort": name, "semanticId": _reference(semantic or _semantic(name)),
            "value": [{"language": "en", "text": text}],
            "modelType": "MultiLanguageProperty"}


def _collection(name: str, value: Sequence[dict[str, Any]], semantic: str | None = None
                ) -> dict[str, Any]:
    return {"idShort": name, "semanticId": _reference(semantic or semantic_id(name)),
            "value": list(value), "modelType": "SubmodelElementCollection"}


def _entity(name: str, statements: Sequence[dict[str, Any]], id_short: str) -> dict[str, Any]:
    return {"idShort": id_short, "semanticId": _reference(semantic_id(name)),
            "statements": list(statements), "entityType": "CoManagedEntity",
            "modelType": "Entity"}


def _percent(margin: float) -> float:
    return 100.0 * (1.0 - margin)


def _component(kind: str, name: str, manufacturer: str | None,
               article: str | None = None) -> list[dict[str, Any]]:
    return [_property("MainComponentType", kind),
            _property("ManufacturerName", manufacturer or "unknown"),
            _property("ManufacturerArticleNumber", article or name),
            _text("ManufacturerProductDesignation", name),
            _property("ManufacturerOrderCode", article or name)]


def _motor(pair: PairResult) -> dict[str, Any]:
    statements = _component("Motor", pair.motor, pair.manufacturer, pair.part_number)
    figures = [("MaxTorqueUtilizationPercentage", _percent(pair.margin_peak)),
               ("MaxTorqueUtilization", pair.peak_torque),
               ("MaxThermalUtilizationPercentage", _percent(pair.margin_rms)),
               ("MaxRotationSpeedUtilizationPercentage", _percent(pair.margin_speed)),
               ("MaxRotationSpeedUtilization", pair.max_speed * 60.0 / (2.0 * math.pi)),
               ("RmsOfMotorTorque", pair.rms_torque)]
    statements += [_real(name, value) for name, value in figures if math.isfinite(value)]
    return _entity("MainComponent", statements, "MainComponent00")


def _messages(pair: PairResult) -> dict[str, Any]:
    lines: list[tuple[str, str]] = []
    if pair.feasible:
        lines.append(("Info", f"feasible; limiting check: {pair.limiting} (margin "
                              f"{100 * _limiting_margin(pair):.1f} %); law {pair.law}"
                              + (f"; ratio {pair.ratio:g}" if pair.ratio is not None else "")))
    else:
        lines.append(("Error", f"infeasible: {pair.reason or pair.limiting}; law {pair.law}"))
    lines += [("Info", note) for note in pair.notes]
    messages = [_collection(f"Message{k:02d}", [_property("CriticalityOfMessage", level),
                                                _text("MessageText", text)],
                            semantic_id("Message"))
                for k, (level, text) in enumerate(lines)]
    return _collection("Messages", messages)


def _limiting_margin(pair: PairResult) -> float:
    return {"peak": pair.margin_peak, "rms": pair.margin_rms,
            "speed": pair.margin_speed}.get(pair.limiting, min(
                pair.margin_peak, pair.margin_rms, pair.margin_speed))


def sizing_result_submodel(pair: PairResult, *, submodel_id: str, project: str, tool: str,
                           created: str) -> dict[str, Any]:
    """The IDTA 02021 submodel (AAS V3.0 JSON, ``kind`` Instance) with the SizingResult of
    ``pair``. ``created`` is an xs:dateTime (``2026-12-06T16:40:00Z``)."""
    components = [_motor(pair)]
    if pair.gearbox:
        components.append(_entity("MainComponent", _component(
            "Gearbox", pair.gearbox, None), "MainComponent01"))  # catalogs name no maker per
        # gearbox option yet: the template's ManufacturerName is written as unknown
    result = _collection("SizingResult", [*components, _messages(pair)])
    information = _collection("SizingProjectInformation", [
        _property("SizingProjectName", project),
        _property("SizingToolName", tool),
        _property("DateCreated", created, "xs:dateTime"),
        _property("DateChanged", created, "xs:dateTime"),
    ], PROJECT_INFORMATION_SEMANTIC_ID)
    return {"idShort": SUBMODEL_ID_SHORT, "id": submodel_id, "kind": "Instance",
            "semanticId": {"type": "ModelReference",
                           "keys": [{"type": "Submodel", "value": SUBMODEL_SEMANTIC_ID}]},
            "submodelElements": [information, result], "modelType": "Submodel"}


def _figure(record: dict[str, Any], key: str) -> float:
    value = record.get(key)
    return float(value) if isinstance(value, int | float) else math.nan


def pair_from_record(record: dict[str, Any], *, manufacturer: str | None,
                     part_number: str | None = None, notes: Sequence[str] = ()) -> PairResult:
    """The :class:`PairResult` of one flat record of ``SizingResult.records()``."""
    ratio = record.get("ratio")
    return PairResult(
        motor=str(record["motor"]), manufacturer=manufacturer,
        feasible=bool(record["feasible"]),
        peak_torque=_figure(record, "peak_torque"), rms_torque=_figure(record, "rms_torque"),
        max_speed=_figure(record, "max_speed"), margin_peak=_figure(record, "margin_peak"),
        margin_rms=_figure(record, "margin_rms"), margin_speed=_figure(record, "margin_speed"),
        limiting=str(record.get("limiting") or ""), law=str(record.get("spec") or ""),
        ratio=float(ratio) if isinstance(ratio, int | float) else None,
        gearbox=str(record["gearbox"]) if record.get("gearbox") else None,
        reason=str(record.get("reason") or ""), notes=tuple(notes), part_number=part_number)
