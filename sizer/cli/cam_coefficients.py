"""``sizer cam --to siemens-tcpu``: the motion as coefficient segments (polynomial of degree
<= 6 plus a sine, a Siemens Technology CPU's MC_CamSectorAdd data), with its certificate
and the motor's torques re-computed on the written segments read back
(sizer.export.coefficient_segments, docs/cam-coefficients.md).

Exit codes: 0 written, tolerance met (in double and, by the estimate, in single
precision) and every check the law passed still passed; 1 written but the tolerance is
not met within the segment cap or by the single-precision estimate, or the exported profile
fails a check the law passed; 2 bad input.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

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
    from sizer.export.coefficient_segments import SegmentExport
    from sizer.export.profile import CamProfile
    from sizer.export.resized import Resized
    from sizer.export.targets import Target
    from sizer.laws.per_move import RankedLaw

FORMULA = "Y = A0 + A1*X + A2*X^2 + A3*X^3 + A4*X^4 + A5*X^5 + A6*X^6 + B0*sin(B1*X + B2)"


def export_coefficients(target: Target, law: RankedLaw, h: float, T: float, linear: bool,
                        master_range: float | None, tolerance: float | None,
                        points: int | None, task: Any, output: Path,
                        certificate: Path | None, pair: Any, design: Path | None,
                        catalog: list[str] | None, default_tolerance: float,
                        profile: CamProfile | None = None) -> None:
    """Write the segments of the move (``task``: its machine cycle; ``profile``: a
    cycle's profile already made), print the certificate, write it as JSON, and exit 1
    when it says so."""
    from sizer.export.coefficient_segments import export_segments, with_segments
    from sizer.export.profile import move_profile
    from sizer.laws.segment_table import format_segments, parse_segments

    if points is not None:
        raise UserError(f"{target.name} writes segments, not a point table: leave out "
                        f"--points (--tolerance bounds the fitted pieces)", field="--points")
    tol = default_tolerance if tolerance is None else tolerance
    cycle = profile is not None  # a design's cycle of segments, made by the caller
    if profile is None:
        profile = move_profile(law, h, T, linear, master_range, task)
    export = export_segments(profile, tol, target.limit)
    mu, su = profile.master_unit, profile.slave_unit
    comments = [f"sizer cam --to {target.name}: {profile.law.spec}, stroke "
                f"{profile.stroke!r} {su} over {profile.span!r} {mu}",
                f"{target.title}; one line per MC_CamSectorAdd polynomial data block",
                f"{FORMULA}; X the absolute master coordinate ({mu}), Y the slave "
                f"({su}), B1 in rad per {mu}",
                "numbers in double precision; the data block is REAL: see the certificate's "
                "single-precision estimate"]
    text = format_segments(export.segments, comments, mu, su)
    write_text_atomically(output, text, "--output")
    export = with_segments(export, parse_segments(text, str(output)).segments)
    resized, skipped, specs = resized_export(
        lambda span: segments_spec(output, span), what="segments",
        cycle=profile if cycle else None, task=task, pair=pair, design=design,
        catalog=catalog)
    record = certificate_record(export, target, output, pair, T, resized, skipped)
    if cycle:
        from sizer.cli.cam_cycle import with_cycle

        record = with_cycle(record, profile, T, specs)
    publish_certificate(record, certificate_text(record), certificate)
    real = export.real_position.max / abs(export.profile.stroke)
    exit_on_failures(
        None if export.met else (f"{output}: the tolerance {tol:g} is not met: splitting "
                                 f"stopped (the certificate's note says why)"),
        None if export.met_in_single_precision else (  # the data block is REAL (p. 6-181)
            f"{output}: in single precision (REAL, the data block's type) the position "
            f"error is about {real:.2g} of the stroke, over the tolerance {tol:g}: the "
            f"coefficients of absolute X cancel; export a shorter span (a move alone) or "
            f"check on the controller"),
        newly_failed_message(output, resized))


def segments_spec(path: Path, span: tuple[float, float] | None = None) -> str:
    """The law spec that reads the written segments back (with ``span``, the segments
    between those X: one move of a cycle)."""
    rows = "" if span is None else f", span: [{span[0]!r}, {span[1]!r}]"
    return f"{{kind: cam_segments, file: {json.dumps(str(path))}{rows}}}"


# ------------------------------------------------------------------- certificate
def certificate_record(export: SegmentExport, target: Target, output: Path, pair: Any,
                       duration: float, resized: Resized | None, skipped: str | None
                       ) -> dict[str, Any]:
    """The certificate as plain data (the JSON of --certificate)."""
    profile, errors = export.profile, export.errors
    mu, su = profile.master_unit, profile.slave_unit
    stroke = abs(profile.stroke)
    peak_a = profile.peak_acceleration
    notes = []
    if export.capped:
        notes.append(f"splitting stopped (at most {target.limit} segments, none shorter "
                     f"than 1e-4 of the span, and only while halving lowers the error: "
                     f"the rounding floor of absolute-X coefficients): the tolerance is "
                     f"NOT met")
    notes.append("the manual advises polynomials up to the 3rd order only: REAL "
                 "coefficients of higher orders may be inaccurate, and the CPU recomputes "
                 "the coefficients (S7T Config may show others, start and end Y swapped)")
    torques = torques_record(resized, skipped, segments_spec(output))
    how: dict[str, int] = {}
    for w in export.written:
        how[w.how] = how.get(w.how, 0) + 1
    return {
        **record_head(target.name, target.title, str(output), profile,
                      None if pair is None else pair.motor, duration),
        "segments": segment_records(profile),
        "points": len(export.written) + 1,
        "coefficient_segments": len(export.written),
        "limit": target.limit,
        "split": how,
        "fitted_pieces": export.fitted_pieces,
        "formula": FORMULA,
        "coordinates": {"X": f"absolute master coordinate ({mu}), inferred",
                        "B1": f"rad per {mu}, inferred"},
        "tolerance": export.tolerance,
        "tolerance_met": export.met,
        "interpolation": {"kind": target.interpolation, "source": target.source},
        "errors": {
            "precision": "double: the file's decimal numbers parsed back, evaluated as the "
                         "formula says",
            "position": {"max": errors.position.max, "at": errors.position.at,
                         "unit": su, "of_stroke": errors.position.max / stroke},
            "velocity": {"max": errors.velocity.max, "at": errors.velocity.at,
                         "unit": f"{su}/{mu}",
                         "of_peak": errors.velocity.max / profile.peak_velocity},
            "acceleration": {"finite": True, "max": errors.acceleration.max,
                             "at": errors.acceleration.at, "unit": f"{su}/{mu}^2",
                             "of_peak": (errors.acceleration.max / peak_a
                                         if math.isfinite(peak_a) and peak_a > 0 else None)},
        },
        "single_precision_estimate": {
            "what": "ESTIMATE, not a bound: position error with X, the coefficients and "
                    "the evaluation in IEEE single precision (REAL), on a grid of points",
            "position": {"max": export.real_position.max, "at": export.real_position.at,
                         "unit": su, "of_stroke": export.real_position.max / stroke},
            "within_tolerance": export.met_in_single_precision,
            "amplification": export.amplification,
            "amplification_note": "largest sum |A_i X^i| + |B0| over a segment, in "
                                  "strokes: a relative rounding r of the coefficients can "
                                  "move the position by about r times this many strokes",
        },
        "torques": torques,
        "notes": notes,
    }


def certificate_text(record: dict[str, Any]) -> list[str]:
    """The certificate as the command prints it, line by line."""
    from sizer.report.cam_certificate import certificate_head

    acc, mu = record["errors"]["acceleration"], record["master"]["unit"]
    acc_share = "" if acc["of_peak"] is None else f" ({acc['of_peak']:.3g} of the peak)"
    real = record["single_precision_estimate"]
    split = ", ".join(f"{n} {k}" for k, n in record["split"].items())
    lines = [*certificate_head(record),
             f"acceleration error: {acc['max']:.6g} {acc['unit']}{acc_share} at "
             f"{acc['at']:.6g} {mu}",
             f"segments: {record['coefficient_segments']} ({split}); {record['formula']}, "
             f"X absolute, B1 rad/{mu} (inferred)",
             f"single precision (REAL) ESTIMATE: position error "
             f"{real['position']['max']:.3g} {real['position']['unit']} "
             f"({real['position']['of_stroke']:.3g} of the stroke); coefficient "
             f"amplification {real['amplification']:.3g} strokes"]
    lines += torque_lines(record["torques"], "exported segments")
    lines += [f"note: {n}" for n in record["notes"]]
    return lines

