"""``sizer cam --to codesys-xyva``: an XYVA table (quintic Hermite between points), its
certificate of position, velocity and acceleration errors, and the motor's torques
re-computed on the written table read back (docs/cam-export.md, "XYVA").

Exit codes: 0 written, tolerance met and every check the law passed still passed; 1
written but the tolerance is not met within the limit, or the exported profile fails a
check the law passed; 2 bad input.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any, cast

from sizer.cli.cam_output import exit_on_failures, publish_certificate
from sizer.cli.cam_torques import (
    newly_failed_message,
    resized_export,
    torque_lines,
    torques_record,
)
from sizer.errors import UserError
from sizer.report.cam_certificate import record_head, segment_records
from sizer.report.output import write_text_atomically

if TYPE_CHECKING:
    from collections.abc import Callable

    from sizer.export.hermite_certificate import HermiteTable
    from sizer.export.profile import CamProfile
    from sizer.export.resized import Resized
    from sizer.export.targets import Target
    from sizer.laws.per_move import RankedLaw


def export_smooth(target: Target, law: RankedLaw, h: float, T: float, linear: bool,
                  master_range: float | None, tolerance: float | None, points: int | None,
                  task: Any, output: Path, certificate: Path | None, pair: Any,
                  design: Path | None, catalog: list[str] | None,
                  default_tolerance: float, profile: CamProfile | None = None) -> None:
    """Write the XYVA table of the move (``task``: its machine cycle; ``profile``: the
    one given, a cycle of segments), print the certificate, write it as JSON, and exit 1
    when it says so."""
    table = _table(law, h, T, linear, master_range, target, tolerance, points, task,
                   default_tolerance, profile)
    write = cast("Callable[[Any], str]", target.write)  # a smooth target writes this table
    write_text_atomically(output, write(table), "--output")
    resized, skipped, specs = resized_export(
        lambda span: cam_table_spec(output, span), what="table", cycle=profile, task=task,
        pair=pair, design=design, catalog=catalog)
    record = certificate_record(table, target, output, pair, T, resized, skipped)
    if profile is not None:
        from sizer.cli.cam_cycle import with_cycle

        record = with_cycle(record, profile, T, specs)
    publish_certificate(record, certificate_text(record), certificate)
    exit_on_failures(
        None if table.met else (f"{output}: the tolerance {table.tolerance:g} is not met "
                                f"within {target.name}'s limit of {table.limit} points"),
        newly_failed_message(output, resized))


def _table(law: RankedLaw, h: float, T: float, linear: bool, master_range: float | None,
           target: Target, tolerance: float | None, points: int | None, task: Any,
           default_tolerance: float, profile: CamProfile | None = None) -> HermiteTable:
    from sizer.export.hermite_certificate import fewest_points, table_for_tolerance, table_of
    from sizer.export.profile import move_profile

    if profile is None:
        profile = move_profile(law, h, T, linear, master_range, task)
    fewest = fewest_points(profile)
    if fewest > target.limit:
        raise UserError(f"the law has {fewest} breakpoints, more than {target.name}'s limit "
                        f"of {target.limit} points", field="--to")
    if points is not None:
        if points < fewest:
            raise UserError(f"an XYVA table of this motion needs at least {fewest} points "
                            f"(its breakpoints), got {points}", field="--points")
        return table_of(profile, points, target.limit)
    return table_for_tolerance(profile, default_tolerance if tolerance is None
                               else tolerance, target.limit)


def cam_table_spec(path: Path, span: tuple[float, float] | None = None) -> str:
    """The law spec that reads the written XYVA table back (with ``span``, the rows
    between those X: one move of a cycle)."""
    rows = "" if span is None else f", span: [{span[0]!r}, {span[1]!r}]"
    return (f"{{kind: cam_table, file: {json.dumps(str(path))}, "
            f"interpolation: quintic_hermite{rows}}}")


# ------------------------------------------------------------------- certificate
def certificate_record(table: HermiteTable, target: Target, output: Path, pair: Any,
                       duration: float, resized: Resized | None, skipped: str | None
                       ) -> dict[str, Any]:
    """The certificate as plain data (the JSON of --certificate)."""
    profile, errors = table.profile, table.errors
    mu, su = profile.master_unit, profile.slave_unit
    notes = []
    if table.clipped:
        needed = "more" if table.needed is None else f"{table.needed}"
        notes.append(f"clipped to {table.limit} points, {target.name}'s limit; the "
                     f"tolerance needs {needed}: NOT met")
    peak_a = profile.peak_acceleration
    torques = torques_record(resized, skipped, cam_table_spec(output))
    return {
        **record_head(target.name, target.title, str(output), profile,
                      None if pair is None else pair.motor, duration),
        "segments": segment_records(profile),
        "points": table.points,
        "limit": table.limit,
        "clipped": table.clipped,
        "points_needed": table.needed,
        "tolerance": table.tolerance,
        "tolerance_met": table.met if table.tolerance is not None else None,
        "interpolation": {"kind": target.interpolation, "source": target.source},
        "errors": {
            "position": {"max": errors.position.max, "at": errors.position.at,
                         "unit": su, "of_stroke": errors.position.max / abs(profile.stroke)},
            "velocity": {"max": errors.velocity.max, "at": errors.velocity.at,
                         "unit": f"{su}/{mu}",
                         "of_peak": errors.velocity.max / profile.peak_velocity},
            "acceleration": {"finite": True, "max": errors.acceleration.max,
                             "at": errors.acceleration.at, "unit": f"{su}/{mu}^2",
                             "of_peak": (errors.acceleration.max / peak_a
                                         if math.isfinite(peak_a) and peak_a > 0 else None)},
        },
        "torques": torques,
        "notes": notes,
    }


def certificate_text(record: dict[str, Any]) -> list[str]:
    """The XYVA certificate as the command prints it, line by line."""
    from sizer.report.cam_certificate import certificate_head

    acc, mu = record["errors"]["acceleration"], record["master"]["unit"]
    acc_share = "" if acc["of_peak"] is None else f" ({acc['of_peak']:.3g} of the peak)"
    lines = [*certificate_head(record),
             f"acceleration error: {acc['max']:.6g} {acc['unit']}{acc_share} at "
             f"{acc['at']:.6g} {mu}"]
    lines += torque_lines(record["torques"], "exported table")
    lines += [f"note: {n}" for n in record["notes"]]
    return lines

