"""``sizer plot`` (speed-torque diagram of a design's motor and laws) and ``sizer plot-law``
(position, velocity, acceleration and jerk of motion laws), as PNG or SVG files.

matplotlib is imported only when one of these commands runs.
"""

from __future__ import annotations

import re
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from sizer.cli.catalog_option import CatalogOption, DesignArgument, load_design_file
from sizer.cli.options import as_option, blame_option, check_law_specs, scaled_move
from sizer.cli.size_command import FrontByOption
from sizer.errors import UserError
from sizer.report.printable import printable

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from sizer.model.domain import Design
    from sizer.report.plots.cam_plots import CamView
    from sizer.sizing import CandidateResult

FigureOutput = Annotated[
    Path,
    typer.Option(
        "--output", "-o", dir_okay=False, metavar="FILE",
        help="The figure file: FILE.png or FILE.svg (the suffix sets the format).",
        show_default=False,
    ),
]

DpiOption = Annotated[
    int,
    typer.Option("--dpi", metavar="N", min=10, max=1200,
                 help="Resolution of a PNG in dots per inch (SVG: the size of raster parts)."),
]

SizeOption = Annotated[
    str | None,
    typer.Option("--size", metavar="WxH",
                 help="Figure size in inches, e.g. 8x6. Default: 8x6 (13x6 with "
                      "--acceleration, 10x6 with --time) for plot, 8x9 for plot-law.",
                 show_default=False),
]

SIZE_PATTERN = re.compile(r"^\s*([0-9]*\.?[0-9]+)\s*[xX*,]\s*([0-9]*\.?[0-9]+)\s*$")


def parse_size(text: str | None, field: str = "--size") -> tuple[float, float] | None:
    """'8x6' -> (8.0, 6.0) inches; None stays None."""
    if text is None:
        return None
    match = SIZE_PATTERN.match(text)
    if not match:
        raise UserError(f"expected WIDTHxHEIGHT in inches like 8x6, got {text!r}", field=field)
    width, height = float(match.group(1)), float(match.group(2))
    if not (0.5 <= width <= 100.0 and 0.5 <= height <= 100.0):
        raise UserError(f"width and height must be between 0.5 and 100 inches, got {text!r}",
                        field=field)
    return width, height


# ----------------------------------------------------------------------- sizer plot
def plot(
    design: DesignArgument,
    output: FigureOutput,
    motor: Annotated[str | None, typer.Option(
        "--motor", "-m", metavar="ID",
        help="The motor to draw. Default: the design's check motor, else the motor of "
             "the best-ranked feasible pair.", show_default=False)] = None,
    law: Annotated[list[str] | None, typer.Option(
        "--law", "-l", metavar="SPEC",
        help="A law to draw for the motor (repeat for more). Default: the design's check "
             "law, else the best-ranked law for the motor.", show_default=False)] = None,
    catalog: CatalogOption = None,
    acceleration: Annotated[bool, typer.Option(
        "--acceleration", "-a",
        help="Add a panel in the speed-acceleration plane (Fig. 6.7 b).")] = False,
    over_time: Annotated[bool, typer.Option(
        "--time", "-t",
        help="Draw motor torque and motor speed over time instead, over the whole "
             "machine cycle with its segments marked.")] = False,
    over_crank: Annotated[bool, typer.Option(
        "--linkage",
        help="A design with a linkage (slider_crank, four_bar): draw its transmission "
             "ratio and the motor torque over the crank angle instead, dead points "
             "marked.")] = False,
    over_cam: Annotated[bool, typer.Option(
        "--cam",
        help="A design with a disc_cam: draw the follower's lift, velocity, acceleration "
             "and jerk over the cam angle and the cam's profile (pitch curve, profile, "
             "base circle, roller) instead; each law its own cam.")] = False,
    points: Annotated[Path | None, typer.Option(
        "--points", dir_okay=False, metavar="FILE.csv",
        help="With --cam: also write the cam's profile as points (x, y of the pitch curve "
             "and of the profile in mm, every 0.1 deg of cam angle); one law.",
        show_default=False)] = None,
    speed_unit: Annotated[str, typer.Option(
        "--speed-unit", metavar="rpm|rad/s", help="Unit of the speed axis.")] = "rpm",
    samples: Annotated[int, typer.Option(
        "--samples", "-n", metavar="N", min=11, max=100_000,
        help="Samples of each move of the cycle.")] = 401,
    dpi: DpiOption = 100,
    size: SizeOption = None,
    front: Annotated[bool, typer.Option(
        "--front",
        help="Draw the trade-off front instead: every feasible pair's motor size against "
             "its time (T_min, or with a given duration its smallest margin), the front "
             "and its knee marked (docs/trade-off.md). With --law: the front of those "
             "laws.")] = False,
    front_by: FrontByOption = None,
) -> None:
    """Draw the speed-torque diagram of a motor with the task of one or more laws.

    The motor's continuous and intermittent regions, the mechanical task (speed(t),
    torque(t)) over the machine cycle of each law at its duration (T_min with
    'duration: minimize') and its RMS point (book Figs. 6.1-6.3), at the motor shaft;
    the title gives the peak, rms and speed margins. --acceleration adds the
    speed-acceleration plane (Fig. 6.7). A cycle of segments ('cycle:') has the start of
    each segment marked on the task curve. --time draws motor torque and speed over time
    instead, each segment of the cycle shaded and named. --cam (a design with a
    disc_cam) draws the follower's lift, velocity, acceleration and jerk over the cam angle
    and the cam's profile, each law's cam as the sizing resolved it; --points FILE.csv
    also writes its profile as points (docs/disc-cams.md).

    Without --motor and --law: the design's `check` pair if it names one, else the
    best-ranked feasible pair.

    Examples:

        sizer plot examples/indexing-table.yaml -o indexing.png

        sizer plot examples/indexing-table.yaml --time -o indexing-time.png

        sizer plot examples/book/ex6_1-6_2.yaml --motor ex6_1 --law cycloidal
        --law 'trapezoidal(alpha=0.12732200375003505)' --speed-unit rad/s -o fig6_2.svg

        sizer plot examples/indexing-table-gearboxes.yaml --front -o front.png

        sizer plot examples/disc-cam.yaml --cam -o cam.png --points cam.csv
    """
    from sizer.cli.output_guard import check_output, check_outputs
    from sizer.report.cycle_summary import duration_name as cycle_duration_name
    from sizer.report.plots import (
        curve_for,
        figure_format,
        save_figure,
        speed_torque_figure,
        time_figure,
    )
    from sizer.report.plots.speed_torque import SPEED_UNITS

    figure_format(output)
    if front or front_by is not None:
        _plot_front(design, output, catalog, motor, law, front_by,
                    refused={"--acceleration": acceleration, "--time": over_time,
                             "--linkage": over_crank, "--cam": over_cam,
                             "--points": points is not None, "--front": not front},
                    size=parse_size(size), dpi=dpi)
        return
    _check_cam_options(over_cam, points, output,
                       {"--linkage": over_crank, "--time": over_time,
                        "--acceleration": acceleration})
    if over_crank and (over_time or acceleration):
        raise UserError("--linkage draws the ratio and torque over the crank angle; it "
                        "does not combine with --time or --acceleration", field="--linkage")
    if over_time and acceleration:
        raise UserError("the speed-acceleration panel belongs to the speed-torque diagram; "
                        "--time draws torque and speed over time instead", field="--time")
    if speed_unit not in SPEED_UNITS:
        raise UserError(f"expected one of {', '.join(SPEED_UNITS)}, got "
                        f"{printable(repr(speed_unit))}", field="--speed-unit")
    figure_size = parse_size(size)
    check_law_specs(law or [], "--law")
    check_output(output, [design, *(catalog or ())])
    check_output(points, [design, *(catalog or ())], field="--points")
    loaded = load_design_file(design, catalog)
    check_outputs([output], loaded.files)
    if points is not None:
        check_outputs([points], loaded.files, field="--points")
    if over_cam:
        _check_cam_design(loaded, law or (), points is not None)
    try:
        results = plot_pairs(loaded, motor, law or ())
    except UserError as error:
        if (error.field or "").startswith("--"):  # an option's mistake, not the file's
            raise
        raise error.located(file=str(design)) from None
    drawn, curves = [], []
    for result in results:
        if result.duration is None:
            sys.stderr.write(printable(f"note: {result.motor} with {_label(result.spec)} has no "
                                       f"feasible duration, not drawn ({result.reason})")
                             + "\n")
            continue
        drawn.append(result)
        curves.append(curve_for(loaded, result, samples=samples))
    if not curves:
        raise UserError(f"{results[0].motor}: no law with a feasible duration, nothing to "
                        f"draw", file=str(design))
    duration_name = cycle_duration_name(loaded)
    if over_cam:
        figure, written = _cam_outputs(loaded, drawn, figure_size, dpi, points)
        what = ("follower's motion over the cam angle and the cam's profile"
                + (f" (profile points: {points})" if written else ""))
    elif over_crank:
        figure = _linkage_figure(loaded, drawn, figure_size, dpi)
        what = "transmission ratio and motor torque over the crank angle"
    elif over_time:
        figure = time_figure(curves, speed_unit=speed_unit, size=figure_size, dpi=dpi,
                             title=loaded.name, duration_name=duration_name)
        what = "torque and speed over time"
    else:
        figure = speed_torque_figure(curves, drawn, acceleration=acceleration,
                                     speed_unit=speed_unit, size=figure_size, dpi=dpi,
                                     title=loaded.name, duration_name=duration_name,
                                     mark_segments=loaded.cycle is not None)
        what = "speed-torque diagram"
    save_figure(figure, output, dpi=dpi)
    typer.echo(printable(f"{output}: {what} of {drawn[0].motor} with "
                         f"{', '.join(_label(r.spec) for r in drawn)}"))


def _plot_front(design: Path, output: Path, catalog: Sequence[str] | None,
                motor: str | None, laws: Sequence[str] | None, front_by: str | None, *,
                refused: dict[str, bool], size: tuple[float, float] | None,
                dpi: float) -> None:
    """``sizer plot --front``: size the design (its laws, or the --law ones) and draw the
    front of its feasible pairs (sizer.report.plots.front_plot)."""
    from sizer.cli.output_guard import check_output
    from sizer.cli.size_command import check_front_key, check_laws, front_of, load_and_size
    from sizer.report.cycle_summary import duration_name
    from sizer.report.plots.figure_files import save_figure
    from sizer.report.plots.front_plot import front_figure

    if motor is not None:
        raise UserError("the front compares every motor; leave out --motor",
                        field="--motor")
    for option, given in refused.items():
        if given:
            message = ("--front-by chooses the size of the front: give --front too"
                       if option == "--front" else
                       f"--front draws the trade-off front; it does not combine with "
                       f"{option}")
            raise UserError(message, field=option)
    key = check_front_key(front_by)
    check_laws(laws or ())
    check_output(output, [design, *(catalog or ())])
    loaded, sizing = load_and_size(design, catalog, None, None, outputs=(output,),
                                   laws=laws)
    trade = front_of(sizing, key, design)
    if not len(trade.members):
        raise UserError("no feasible motor/law pair: no front to draw", file=str(design))
    figure = front_figure(sizing, trade, duration_name=duration_name(loaded),
                          title=loaded.name, size=size, dpi=dpi)
    save_figure(figure, output, dpi=dpi)
    knee = ("" if trade.knee is None else
            f", knee {sizing.results[trade.knee].motor} with "
            f"{_label(sizing.results[trade.knee].spec)}")
    typer.echo(printable(f"{output}: trade-off front of {len(trade.members)} of "
                         f"{len(sizing.feasible)} feasible pairs{knee}"))


def plot_pairs(design: Design, motor: str | None = None, laws: Sequence[str] = (),
               rank_by: str | None = None) -> list[CandidateResult]:
    """The sizing results to draw: one motor, one result per law.

    - neither motor nor laws: the design's check pair if it names one, else the
      best-ranked feasible pair (the best-ranked pair when none is feasible);
    - a motor only: its best-ranked law;
    - laws only: for the check motor if the design names one, else for the motor of the
      best-ranked feasible pair among those laws;
    - both: those.
    Each law is sized on its own (sizer.api.size; its ratio or auto shape chosen as in
    ``sizer size``).
    """
    from sizer import api
    from sizer.sizing.ranking import rank

    field, given_laws = "--motor", bool(laws)
    if motor is None and not laws and design.chosen_motor and design.chosen_law:
        motor, laws, field = design.chosen_motor, (design.chosen_law.text,), "check.motor"
    elif motor is None and laws and design.chosen_motor:
        motor, field = design.chosen_motor, "check.motor"
    if motor is not None:
        with as_option("motors", field):
            design = api.override(design, motors=[motor])
    from sizer.cli.progress import sizing_progress

    laws = tuple(dict.fromkeys(laws))
    if not laws:
        with sizing_progress(f"sizing {design.name}", unit="laws") as progress:
            return [best_of(api.size(design, rank_by=rank_by, progress=progress).results)]
    with as_option("laws", "--law" if given_laws else "check.law"), \
            sizing_progress(f"sizing {design.name}", unit="laws") as progress:
        # the sizing's word on a law names its source
        per_law = [api.size(design, laws=[spec], rank_by=rank_by, progress=progress)
                   for spec in laws]
    if motor is None:
        pooled = [r for sizing in per_law for r in sizing.results]
        motor = best_of(rank(pooled, rank_by, per_law[0].mode)).motor
    return [next(r for r in sizing.results if r.motor == motor) for sizing in per_law]


def best_of(results: Sequence[CandidateResult]) -> CandidateResult:
    """The first feasible result of a ranked list, else the first."""
    return next((r for r in results if r.feasible), results[0])


# ------------------------------------------------------------------- sizer plot-law
def plot_law(
    specs: Annotated[list[str], typer.Argument(
        metavar="SPEC...", help="Laws, e.g. cycloidal poly5 'trapezoidal(alpha=1/3)'.",
        show_default=False)],
    output: FigureOutput,
    displacement: Annotated[str | None, typer.Option(
        "--displacement", metavar="H",
        help="Scale to a move of h: an angle ('90 deg', rad if bare) or a length "
             "('200 mm'); with --duration. Default: normalized, h = 1.",
        show_default=False)] = None,
    duration: Annotated[str | None, typer.Option(
        "--duration", metavar="T", help="Duration T of the move ('0.2 s'); with "
                                        "--displacement. Default: normalized, T = 1.",
        show_default=False)] = None,
    samples: Annotated[int, typer.Option(
        "--samples", "-n", metavar="N", min=11, max=100_000,
        help="Samples over the move (spread over the law's pieces).")] = 401,
    dpi: DpiOption = 100,
    size: SizeOption = None,
) -> None:
    """Draw position, velocity, acceleration and jerk of motion laws (Figs. 6.4-6.6).

    Normalized (h = T = 1) by default, or scaled to a move with --displacement and
    --duration. Where the acceleration jumps the jerk is an impulse: an arrow labelled
    with the size of the jump.

    Examples:

        sizer plot-law cycloidal poly5 modified_sinusoidal -o laws.png

        sizer plot-law 'trapezoidal(alpha=1/3)' 'double_s(alpha=1/3, beta=1/4)'
        --displacement '90 deg' --duration '0.25 s' -o trapezoid.svg
    """
    from sizer.cli.output_guard import check_output
    from sizer.laws import make_law  # lazy: keeps --help fast
    from sizer.laws.motion import scale_fault
    from sizer.report.plots import figure_format, law_profiles_figure, save_figure

    figure_format(output)
    figure_size = parse_size(size)
    check_output(output)
    h, T, linear = None, None, False
    move = scaled_move(displacement, duration, "normalized laws")
    if move is not None:
        h, T, linear = move
        fault = scale_fault(h, T)
        if fault is not None:
            raise UserError(f"a move of {h:g} in {T:g} s: {fault}", field="--duration")
    with blame_option("SPEC"):
        laws = [make_law(spec) for spec in dict.fromkeys(specs)]
    check_output(output)  # again: not over a file a law read (a cam table)
    figure = law_profiles_figure(laws, displacement=h, duration=T, linear=linear,
                                 samples=samples, size=figure_size, dpi=dpi)
    save_figure(figure, output, dpi=dpi)
    typer.echo(printable(f"{output}: position, velocity, acceleration and jerk of "
                         f"{', '.join(_label(law.spec) for law in laws)}"))


def register(app: typer.Typer) -> None:
    app.command("plot")(plot)
    app.command("plot-law")(plot_law)


def _label(spec: str) -> str:
    from sizer.laws.data_spec import law_label  # lazy: keeps --help fast

    return law_label(spec)


def _linkage_figure(design: Design, drawn: list[CandidateResult],
                    size: tuple[float, float] | None, dpi: float):
    """The ratio-and-torque figure of the drawn results (sizer plot --linkage)."""
    import numpy as np

    from sizer.report.plots import linkage_figure
    from sizer.sizing.samples import linkage_curve_of

    if design.transmission.linkage is None:
        raise UserError("the design's transmission has no linkage (slider_crank or "
                        "four_bar)", field="--linkage")
    curves = {}
    for r in drawn:
        assert r.duration is not None, "plot draws only results with a feasible duration"
        curves[f"{r.motor}, {_label(r.spec)}"] = linkage_curve_of(
            design, r.motor_object, r.law_object, r.duration, r.transmission)
    first = next(iter(curves.values()))
    torques = {}
    for key, curve in curves.items():  # each law's samples read at the first one's angles
        order = np.argsort(curve.theta)
        torques[key] = np.interp(first.theta, curve.theta[order], curve.motor_torque[order])
    return linkage_figure(first.theta, first.ratio, torques, first.dead_points,
                          linear=first.linear, size=size, dpi=dpi, title=design.name)


PROFILE_POINTS = 3601
"""Points of ``--points`` over a turn of the cam (every 0.1 deg, the first again last)."""


def _check_cam_options(over_cam: bool, points: Path | None, output: Path,
                       refused: dict[str, bool]) -> None:
    """--cam draws alone; --points needs --cam and is not the figure's file."""
    if points is not None and not over_cam:
        raise UserError("the profile's points are a disc cam's: give --cam too",
                        field="--points")
    if not over_cam:
        return
    for option, given in refused.items():
        if given:
            raise UserError(f"--cam draws the follower over the cam angle and the cam's "
                            f"profile; it does not combine with {option}", field="--cam")
    if points is not None:
        if points.suffix.lower() != ".csv":
            raise UserError("the profile's points are CSV: name the file *.csv",
                            file=str(points), field="--points")
        if points.resolve() == output.resolve():
            raise UserError("the profile's points must not overwrite the figure",
                            field="--points")


def _check_cam_design(design: Design, laws: Sequence[str], points: bool) -> None:
    """UserError (--cam) unless the design's last stage is a disc_cam; (--points) when
    --points would have several cams to write."""
    from sizer.mechanics.disc_cam import CamStage

    if not isinstance(design.transmission.linkage, CamStage):
        raise UserError("the design's transmission has no disc_cam stage: --cam draws a "
                        "disc cam's follower and profile", field="--cam")
    if points and len(set(laws)) > 1:
        raise UserError("--points writes one cam's profile: give one --law",
                        field="--points")


def _cam_views(design: Design, drawn: list[CandidateResult]
               ) -> tuple[list[CamView], list[tuple[str, float, float]]]:
    """Each drawn result's cam as the sizing resolved it (its lift, speed and base
    radius: sizer.sizing.linkage_move.cam_design), with its follower's motion and its
    profile's points; and the cycle's segments as (name, start, end) in cam angle."""
    from sizer.mechanics.disc_cam import CamStage, follower_motion, profile_points
    from sizer.report.plots.cam_plots import CamView
    from sizer.sizing.linkage_move import cam_design

    views: list[CamView] = []
    segments: list[tuple[str, float, float]] = []
    for r in drawn:
        resolved = cam_design(design, r.law_object)
        stage = resolved.transmission.linkage
        assert isinstance(stage, CamStage) and stage.lift is not None, "a resolved cam"
        views.append(CamView(f"{r.motor}, {_label(r.spec)}", stage, follower_motion(stage),
                             profile_points(stage, PROFILE_POINTS)))
        if not segments:
            # the design's own names (the cam's cycle may be the task it is a shorthand of)
            own = resolved.machine_cycle.segments
            given = design.machine_cycle.segments
            if len(given) != len(own):
                given = own
            names = [a.name or b.name or "" for a, b in zip(given, own, strict=True)]
            segments = [(name, p.start, p.start + p.angle)
                        for name, p in zip(names, stage.lift.pieces, strict=True)]
    return views, segments


def _cam_outputs(design: Design, drawn: list[CandidateResult],
                 size: tuple[float, float] | None, dpi: float, points: Path | None
                 ) -> tuple[Figure, bool]:
    """(the --cam figure, whether the --points file was written): the CSV is written
    first, atomically."""
    from sizer.report.cam_profile_csv import profile_csv
    from sizer.report.output import write_text_atomically
    from sizer.report.plots.cam_plots import cam_figure

    views, segments = _cam_views(design, drawn)
    if points is not None:
        if len(views) > 1:
            raise UserError("--points writes one cam's profile: give one --law",
                            field="--points")
        view = views[0]
        write_text_atomically(points, profile_csv(view.stage, view.points, title=design.name,
                                                  label=view.label), "--points")
    return cam_figure(views, segments, size=size, dpi=dpi, title=design.name), \
        points is not None
