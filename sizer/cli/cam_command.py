"""``sizer cam``: a candidate's motion as a controller's cam (a point table), with a
certificate: the table re-evaluated as the controller interpolates it and its true largest
errors against the sized law (sizer.export, docs/cam-export.md).

Exit codes: 0 written and within the tolerance; 1 written, clipped to the target's limit,
and the tolerance not met; 2 bad input.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any

import typer

from sizer.cli.cam_output import exit_on_failures, publish_certificate
from sizer.cli.catalog_option import CatalogOption
from sizer.errors import UserError
from sizer.report.cam_certificate import record_head, segment_records
from sizer.report.output import write_text_atomically
from sizer.report.printable import printable

if TYPE_CHECKING:
    from sizer.export.sampling import PointTable
    from sizer.export.targets import Target
    from sizer.laws.base import MotionLaw
    from sizer.laws.per_move import RankedLaw

DEFAULT_TOLERANCE = 1e-4


def cam(
    source: Annotated[str, typer.Argument(
        metavar="DESIGN.yaml|SPEC",
        help="The design file; or, with --displacement and --duration, a law spec.",
        show_default=False)],
    to: Annotated[str, typer.Option(
        "--to", metavar="FORMAT",
        help="The target: csv, codesys-xy (CODESYS ASCII X/Y table, at most 128 points) "
             "or sew (SEW MOVI-C: n, then n 'master;slave' lines), or codesys-xyva "
             "(CODESYS XYVA X,Y,V,A table, quintic Hermite, at most 128 points; with "
             "the motor's torques re-computed on it), or twincat-mc3 (TwinCAT 3 MC3 "
             "motion functions: the law itself, segment-exact), or siemens-tcpu (Siemens "
             "Technology CPU cam segments: polynomial of degree <= 6 plus a sine per "
             "segment, exact or fitted within --tolerance; with the motor's torques "
             "re-computed on them).", show_default=False)],
    output: Annotated[Path, typer.Option(
        "--output", "-o", dir_okay=False, metavar="FILE",
        help="The cam file (replaced atomically).", show_default=False)],
    motor: Annotated[str | None, typer.Option(
        "--motor", "-m", metavar="ID",
        help="The motor whose sized motion to export. Default: the design's check motor, "
             "else the best-ranked feasible pair's.", show_default=False)] = None,
    law: Annotated[str | None, typer.Option(
        "--law", "-l", metavar="SPEC",
        help="The law to export. Default: the design's check law, else the best-ranked "
             "law for the motor.", show_default=False)] = None,
    catalog: CatalogOption = None,
    tolerance: Annotated[float | None, typer.Option(
        "--tolerance", metavar="T",
        help="Largest position error of the controller's interpolation against the law, "
             f"as a fraction of the stroke (default {DEFAULT_TOLERANCE:g}); sets the "
             "number of points.", show_default=False)] = None,
    points: Annotated[int | None, typer.Option(
        "--points", "-n", metavar="N",
        help="The number of points instead of a tolerance.", show_default=False)] = None,
    master_range: Annotated[str | None, typer.Option(
        "--master-range", metavar="ANGLE",
        help="A table over a master range instead of time: the master's travel over the "
             "move (degrees if bare: 360, or '2 rev'), proportional to time.",
        show_default=False)] = None,
    displacement: Annotated[str | None, typer.Option(
        "--displacement", metavar="H",
        help="A law alone: the stroke ('90 deg', rad if bare, or '200 mm'); with "
             "--duration.", show_default=False)] = None,
    duration: Annotated[str | None, typer.Option(
        "--duration", metavar="T", help="A law alone: the move's duration ('0.2 s').",
        show_default=False)] = None,
    whole_cycle: Annotated[bool, typer.Option(
        "--cycle",
        help="The task's whole machine cycle: the move, its dwell, and with 'return: "
             "true' the move back and its dwell (default: the move alone). A design with "
             "a `cycle:` of segments always exports its whole cycle.")] = False,
    certificate: Annotated[Path | None, typer.Option(
        "--certificate", dir_okay=False, metavar="FILE.json",
        help="Also write the certificate as JSON.", show_default=False)] = None,
) -> None:
    """Export a sized motion as a controller's cam table, with a certificate.

    The top-ranked feasible pair's move (or the --motor/--law pair, or the design's
    `check:` pair), or a law alone with --displacement and --duration, as a point table
    over time or over a master range; --cycle: the task's whole machine cycle. A design
    with a `cycle:` of segments exports its whole sized cycle (each segment at the
    duration the sizing used; --master-range spans the cycle). The number
    of points comes from --tolerance (or --points), clipped to the target's limit. The
    certificate re-evaluates the table as the controller interpolates it (linearly) and
    gives the true largest position and velocity errors against the law; its
    acceleration is a train of impulses. Exit 1 when the tolerance is not met within the
    target's limit.

    Examples:

        sizer cam examples/indexing-table.yaml --to sew -o index.txt

        sizer cam examples/indexing-table.yaml --to codesys-xy --master-range 360
        -o index-cam.txt --certificate index-cam.json

        sizer cam cycloidal --displacement '90 deg' --duration '0.25 s' --to csv -o c.csv
    """
    from sizer.cli.options import scaled_move

    target = _target(to)
    if tolerance is not None and points is not None:
        raise UserError("give either --tolerance or --points, not both", field="--points")
    if tolerance is not None and not (math.isfinite(tolerance) and 0.0 < tolerance < 1.0):
        raise UserError(f"must be a fraction of the stroke in (0, 1), got {tolerance!r}",
                        field="--tolerance")
    if points is not None and not 2 <= points <= target.limit:
        raise UserError(f"{target.name} takes 2 to {target.limit} points, got {points}",
                        field="--points")
    span_master = None if master_range is None else _master_range(master_range)
    if certificate is not None and output.resolve() == certificate.resolve():
        raise UserError("the certificate must not overwrite the cam file",
                        field="--certificate")
    move = scaled_move(displacement, duration, "a design file")
    if move is not None:
        for option, given in (("--motor", motor), ("--law", law), ("--catalog", catalog),
                              ("--cycle", whole_cycle)):
            if given:
                raise UserError("a law alone (--displacement, --duration) has no motor or "
                                "design: leave out " + option, field=option)
        h, T, linear = move
        the_law: RankedLaw = _law_alone(source, output, certificate)
        pair, task = None, None
    else:
        h, T, linear, the_law, pair, task = _sized_move(Path(source), motor, law, catalog,
                                                        [output, certificate])
    profile = None
    if pair is not None and task is not None and getattr(task, "cycle", None) is not None:
        # a cycle of segments (task is its Design): always the whole cycle (--cycle implied)
        from sizer.cli.cam_cycle import sized_cycle

        profile = sized_cycle(task, the_law, T, span_master, Path(source), pair)
        whole_cycle = True
    if target.interpolation == "segment-exact":  # the law itself (twincat-mc3)
        from sizer.cli.cam_segment_exact import export_segments

        export_segments(target.name, the_law, h, T, linear, span_master,
                        task if whole_cycle else None, output, certificate, pair,
                        tolerance, points, profile)
        return
    if target.interpolation == "coefficient-segments":  # sizer.cli.cam_coefficients
        from sizer.cli.cam_coefficients import export_coefficients

        return export_coefficients(target, the_law, h, T, linear, span_master, tolerance,
                                   points, task if whole_cycle else None, output,
                                   certificate, pair, None if pair is None else Path(source),
                                   catalog, DEFAULT_TOLERANCE, profile)
    if target.interpolation == "quintic_hermite":  # XYVA: sizer.cli.cam_smooth
        from sizer.cli.cam_smooth import export_smooth

        return export_smooth(target, the_law, h, T, linear, span_master, tolerance, points,
                             task if whole_cycle else None, output, certificate, pair,
                             None if pair is None else Path(source), catalog,
                             DEFAULT_TOLERANCE, profile)
    table = _table(the_law, h, T, linear, span_master, target, tolerance, points,
                   task if whole_cycle else None, profile)
    write_text_atomically(output, target.write(table), "--output")
    record = certificate_record(table, target, output, pair, duration=T)
    if profile is not None:
        from sizer.cli.cam_cycle import with_cycle

        record = with_cycle(record, profile, T)
    publish_certificate(record, certificate_text(record), certificate)
    exit_on_failures(None if table.met else (
        f"{output}: the tolerance {table.tolerance:g} is not met within {target.name}'s "
        f"limit of {table.limit} points"))


def register(app: typer.Typer) -> None:
    app.command("cam")(cam)


# ----------------------------------------------------------------------- helpers
def _target(name: str) -> Target:
    from sizer.export.coefficient_targets import COEFFICIENT_TARGETS
    from sizer.export.segment_targets import SEGMENT_TARGETS
    from sizer.export.smooth_targets import SMOOTH_TARGETS
    from sizer.export.targets import TARGETS

    targets = {**TARGETS, **SMOOTH_TARGETS, **SEGMENT_TARGETS, **COEFFICIENT_TARGETS}
    if name not in targets:
        raise UserError(f"expected one of {', '.join(targets)}, got {printable(repr(name))}",
                        field="--to")
    return targets[name]


def _master_range(text: str) -> float:
    """The master range in degrees: a bare number is degrees."""
    from sizer.units import to_si

    try:
        value = float(text)
    except ValueError:
        value = math.degrees(to_si(text, "angle", field="--master-range"))
    if not (math.isfinite(value) and value > 0.0):
        raise UserError(f"must be a positive angle, got {text!r}", field="--master-range")
    return value


def _law_alone(spec: str, output: Path, certificate: Path | None) -> MotionLaw:
    from sizer.cli.options import blame_option
    from sizer.cli.output_guard import check_output
    from sizer.laws import make_law

    for path, field in ((output, "--output"), (certificate, "--certificate")):
        check_output(path, field=field)
    with blame_option("SPEC"):
        law = make_law(spec)
    for path, field in ((output, "--output"), (certificate, "--certificate")):
        check_output(path, field=field)  # again: not over a file a law read (a cam table)
    return law


def _sized_move(design: Path, motor: str | None, law: str | None,
                catalog: list[str] | None, outputs: list[Path | None]
                ) -> tuple[float, float, bool, RankedLaw, Any, Any]:
    """(h, T, linear, law, result, task) of the design's pair to export; for a cycle of
    segments task is the Design itself (its ``cycle`` set) and T the cycle time the
    result reports."""
    from sizer.cli.catalog_option import load_design_file
    from sizer.cli.options import check_law_specs
    from sizer.cli.output_guard import check_output
    from sizer.cli.plot_command import plot_pairs
    from sizer.laws.data_spec import law_label

    check_law_specs([law] if law else [], "--law")
    inputs = [design, *(catalog or ())]
    for path, field in zip(outputs, ("--output", "--certificate"), strict=True):
        check_output(path, inputs, field=field)
    loaded = load_design_file(design, catalog)
    for path, field in zip(outputs, ("--output", "--certificate"), strict=True):
        check_output(path, loaded.files, field=field)
    if loaded.cycle is not None and loaded.transmission.linkage is not None:
        raise UserError("a cycle of segments through a linkage is not exported: its moves' "
                        "laws are at the linkage's output, not at the motor; export a law "
                        "alone with SPEC --displacement H --duration T",
                        file=str(design), field="cycle")
    try:
        result = plot_pairs(loaded, motor, [law] if law else ())[0]
    except UserError as error:
        if (error.field or "").startswith("--"):
            raise
        raise error.located(file=str(design)) from None
    if result.duration is None:
        raise UserError(f"{result.motor} with {law_label(result.spec)} has no feasible "
                        f"duration ({result.reason}): no motion to export", file=str(design))
    if loaded.cycle is not None:
        cycle = loaded.cycle
        return (max((s.displacement for s in cycle.segments), key=abs), result.duration,
                cycle.linear,
                result.law_object, result, loaded)
    task = loaded.task
    return task.displacement, result.duration, task.linear, result.law_object, result, task


def _table(law: RankedLaw, h: float, T: float, linear: bool, master_range: float | None,
           target: Target, tolerance: float | None, points: int | None,
           task: Any = None, profile: Any = None) -> PointTable:
    """The certified table of the move (or with ``task``, its machine cycle; or the
    ``profile`` given: a cycle of segments)."""
    from sizer.export.profile import move_profile
    from sizer.export.sampling import fewest_points, table_for_tolerance, table_of

    if profile is None:
        profile = move_profile(law, h, T, linear, master_range, task)
    if points is not None:
        fewest = fewest_points(profile, target.per_segment)
        if points < fewest:
            raise UserError(f"the machine cycle's table needs at least {fewest} points (its "
                            f"segments' ends), got {points}", field="--points")
        return table_of(profile, points, target.limit, per_segment=target.per_segment)
    return table_for_tolerance(profile, DEFAULT_TOLERANCE if tolerance is None
                               else tolerance, target.limit, target.per_segment)


# ------------------------------------------------------------------- certificate
def certificate_record(table: PointTable, target: Target, output: Path, pair: Any,
                       duration: float) -> dict[str, Any]:
    """The certificate as plain data (the JSON of --certificate)."""
    from sizer.export.sampling import MAX_POINTS

    profile, errors = table.profile, table.errors
    peak_velocity = profile.peak_velocity
    velocity_unit = f"{profile.slave_unit}/{profile.master_unit}"
    notes = []
    if table.clipped:
        needed = ("more" if table.needed is None else f"{table.needed}")
        notes.append(f"clipped to {table.limit} points, {target.name}'s limit; the "
                     f"tolerance needs {needed}: NOT met")
    return {
        **record_head(target.name, target.title, str(output), profile,
                      None if pair is None else pair.motor, duration),
        "segments": segment_records(profile),
        "points": table.points,
        "limit": None if table.limit >= MAX_POINTS else table.limit,
        "clipped": table.clipped,
        "points_needed": table.needed,
        "tolerance": table.tolerance,
        "tolerance_met": table.met if table.tolerance is not None else None,
        "interpolation": {"kind": target.interpolation, "source": target.source},
        "errors": {
            "position": {"max": errors.position, "at": errors.position_at,
                         "unit": profile.slave_unit,
                         "of_stroke": errors.position / abs(profile.stroke)},
            "velocity": {"max": errors.velocity, "at": errors.velocity_at,
                         "unit": velocity_unit,
                         "of_peak": errors.velocity / peak_velocity},
            "acceleration": {"finite": False,
                             "note": "linear interpolation: the acceleration is a train of "
                                     "impulses, one at each point, of the velocity step",
                             "largest_velocity_step": errors.velocity_step,
                             "unit": velocity_unit},
        },
        "notes": notes,
    }


def certificate_text(record: dict[str, Any]) -> list[str]:
    """The certificate as the command prints it, line by line."""
    from sizer.report.cam_certificate import certificate_head

    acc = record["errors"]["acceleration"]
    lines = [*certificate_head(record),
             f"acceleration: not finite, a train of impulses (largest velocity step "
             f"{acc['largest_velocity_step']:.6g} {acc['unit']})"]
    lines += [f"note: {n}" for n in record["notes"]]
    return lines
