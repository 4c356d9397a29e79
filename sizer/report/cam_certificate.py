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
