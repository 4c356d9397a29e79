"""The lines a cam export's certificate starts with, whatever the target (``sizer cam``):
the table, the interpolation, the position and velocity errors."""

from __future__ import annotations

from typing import Any


def certificate_head(record: dict[str, Any]) -> list[str]:
    """The certificate's first lines: what was written, how the controller interpolates
    it, and its largest position and velocity errors (``record``: the certificate's JSON)."""
    master, errors = record["master"], record["errors"]
    pos, vel = errors["position"], errors["velocity"]
    mu, su = master["unit"], record["slave_unit"]
    who = "" if record["motor"] is None else f" sized for {record['motor']}"
    if len(record.get("segments") or ()) > 1:
        who += " (machine cycle: " + ", ".join(s["name"] for s in record["segments"]) + ")"
    tolerance = ("" if record["tolerance"] is None else
                 f", tolerance {record['tolerance']:g}"
                 + ("" if record["tolerance_met"] else ": NOT met"))
    return [
        f"{record['file']}: {record['title']}, {record['points']} points over "
        f"{master['span']:g} {mu} ({master['kind']}), {record['law']}{who}, stroke "
        f"{record['stroke']:g} {su}",
        f"interpolation: {record['interpolation']['kind']} "
        f"({record['interpolation']['source']})",
        f"position error: {pos['max']:.6g} {su} ({pos['of_stroke']:.3g} of the stroke"
        f"{tolerance}) at {pos['at']:.6g} {mu}",
        f"velocity error: {vel['max']:.6g} {vel['unit']} ({vel['of_peak']:.3g} of the peak "
        f"velocity) at {vel['at']:.6g} {mu}",
    ]


def record_head(name: str, title: str, file: str, profile: Any, motor: str | None,
                duration: float) -> dict[str, Any]:
    """The keys every cam certificate's JSON starts with: the target, what was written
    and where, the law, the motor, the stroke and the master (``profile``: the exported
    sizer.export.profile.CamProfile; ``duration``: the sized move's, s)."""
    return {
        "target": name,
        "title": title,
        "file": file,
        "law": profile.law.spec,
        "motor": motor,
        "stroke": profile.stroke,
        "slave_unit": profile.slave_unit,
        "master": {"kind": "time" if profile.over_time else "master position",
                   "span": profile.span, "unit": profile.master_unit,
                   "move_duration_s": duration},
    }


def segment_records(profile: Any) -> list[dict[str, Any]]:
    """The exported profile's segments as the certificate lists them."""
    return [{"name": s.name, "start": s.start, "span": s.span, "stroke": s.stroke}
            for s in profile.segments]
