"""``sizer size``: every motor x law of a design, checked and ranked."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Annotated

import typer

from sizer.cli.catalog_option import (
    CatalogOption,
    DesignArgument,
    is_machine,
    load_design_file,
    refuse_motor_options,
)
from sizer.cli.options import (
    EnvelopeOption,
    FormatOption,
    JobsOption,
    MotorsOption,
    OutputOption,
    as_option,
    blame_option,
    check_law_specs,
)
from sizer.errors import UserError
from sizer.report.formats import Format

if TYPE_CHECKING:
    from pathlib import Path

    from sizer.model.domain import Design
    from sizer.sizing import SizingResult
    from sizer.sizing.front import Front, FrontBy

RANK_HELP = ("Rank the feasible pairs by size (alias power: the smallest motor first, by "
             "rated power tau_c*v_n), duration (shortest first), margin (most room left at "
             "the tightest limit first), rms or peak (smallest motor torque first), price "
             "or mass (cheapest or lightest motor first), vibration (smallest residual "
             "vibration first, with the load's natural_frequency), worst_margin (alias "
             "robust; with --robust: the largest worst-case margin over the tolerances "
             "first); ties go to the next criteria (size, margin, rotor inertia, finally "
             "motor id, law spec, ratio). Default: duration with 'duration: minimize', size "
             "otherwise.")

LawsOption = Annotated[list[str] | None, typer.Option(
    "--law", "-l", metavar="SPEC",
    help="Size this law instead of the design's 'laws:' (repeat for more), e.g. --law "
         "cycloidal --law 'trapezoidal(alpha=auto)'. The design file is not changed.",
    show_default=False)]
"""``--law``: the laws to size instead of the design's (sizer.api.override)."""

FrontOption = Annotated[bool, typer.Option(
    "--front",
    help="Show only the trade-off front: the feasible pairs that no other beats on both "
         "time and motor size, smallest motor first, the knee marked (docs/trade-off.md). "
         "Time: T_min (or the shortest cycle time) with 'duration: minimize'; with a "
         "given duration, the smallest margin beyond the required one (larger better).")]
"""``--front``: only the front's rows, sorted by the size objective."""

FrontByOption = Annotated[str | None, typer.Option(
    "--front-by", metavar="power|price|mass|energy",
    help="The size objective of the front (and of the 'front' column of every CSV and "
         "JSON): the motor's rated power tau_c*v_n (default), its catalog price or mass, "
         "or the net energy drawn from the DC bus per cycle (designs with energy or heat "
         "checks). Pairs without the figure are left out of the front (and counted).",
    show_default=False)]
"""``--front-by``: the size objective (sizer.sizing.front.FrontBy)."""


def size(
    design: DesignArgument,
    catalog: CatalogOption = None,
    motor: MotorsOption = None,
    law: LawsOption = None,
    rank_by: Annotated[str | None, typer.Option(
        "--rank-by", "-r", metavar="KEY", help=RANK_HELP, show_default=False)] = None,
    top: Annotated[int | None, typer.Option(
        "--top", "-n", metavar="N", min=1, help="Show only the first N rows.",
        show_default=False)] = None,
    show_all: Annotated[bool, typer.Option(
        "--all", "-a", help="Also show the infeasible pairs, with the limits they fail.",
    )] = False,
    fmt: FormatOption = Format.TABLE,
    output: OutputOption = None,
    envelope: EnvelopeOption = None,
    jobs: JobsOption = None,
    front: FrontOption = False,
    front_by: FrontByOption = None,
    robust: Annotated[bool, typer.Option(
        "--robust",
        help="Also size every pair at the corners of the design's tolerances ('tolerances:' "
             "or beside a value, '0.35 kg*m^2 +- 20 %') and show its worst-case margin "
             "(with 'minimize': its worst-case T_min; a chosen ratio stays the nominal "
             "pair's); the pairs feasible at every corner rank first (docs/robust.md).")] = False,
    samples: Annotated[int | None, typer.Option(
        "--samples", metavar="N",
        help="With --robust (implied): also size every pair at N builds drawn from the "
             "tolerances' distributions and show the share that passes, with its 95 % "
             "interval; with more than 10 tolerances, instead of the corners.",
        show_default=False)] = None,
    seed: Annotated[int | None, typer.Option(
        "--seed", metavar="S",
        help="The seed of --samples (default 0: the same builds, the same output).",
        show_default=False)] = None,
) -> None:
    """Size a design: every motor with every motion law, feasible pairs ranked.

    With a given duration each pair is checked (speed, peak and RMS torque against the
    motor's regions, inertia ratio, ...) and the margins are reported; with
    'duration: minimize' each pair gets its shortest feasible duration T_min.
    Exit code 0 even when no pair is feasible (the report says so); 2 for bad input;
    3 for an internal error (a bug in sizer).

    With no motors ('motors:' left out or []) and the load's limits (limits.max_speed,
    max_acceleration, max_jerk) each law is planned without a motor: its shortest
    duration, or for a given duration the scaling factor lambda, and the limit that binds
    (docs/planning.md).

    On a terminal too narrow for the table (80 columns) the table abbreviates rather than
    cuts: mrg = margin, pk = peak, spd = speed, limit = the limiting check (J_ratio =
    inertia_ratio, winding_dT = winding_temperature_rise, drv_pk_I / drv_rms_I = the
    drive's currents, ...), and laws with their parameters by position (trap(1/3) =
    trapezoidal(alpha=1/3), poly(5) = polynomial(degree=5), mod_sine =
    modified_sinusoidal, cycl = cycloidal); --format md, csv or json keep the full words.

    Examples:

        sizer size examples/indexing-table.yaml

        sizer size examples/indexing-table.yaml --all --format md --output sizing.md

        sizer size machine.yaml --catalog my-motors.yaml --rank-by price --top 5

        sizer size examples/book/ex6_3.yaml --motor ex6_3

        sizer size examples/indexing-table-gearboxes.yaml --front

        sizer size examples/indexing-table.yaml --law cycloidal --law poly5
    """
    from sizer.cli.output_guard import check_output
    from sizer.report.sizing_table import SizingDocument, publish_sizing

    check_rank_key(rank_by)
    robust = robust or samples is not None
    check_robust_options(robust, rank_by, samples, seed)
    front_key = check_front_key(front_by)
    check_laws(law or ())
    check_output(output, [design, *(catalog or ())])
    if robust and (is_machine(design) or front or front_by):
        raise UserError("not with a machine file or --front (size one design's pairs "
                        "robustly)", field="--robust")
    if is_machine(design):
        if law:
            raise UserError("not for a machine file: each axis names its laws",
                            field="--law")
        if front or front_by:
            raise UserError("not for a machine file: size one axis's design for its "
                            "front", field="--front" if front else "--front-by")
        _size_machine(design, catalog, motor, rank_by, top, show_all, fmt, output, envelope,
                      jobs)
        return
    loaded = load_overridden(design, catalog, motor, rank_by, envelope=envelope,
                             outputs=() if output is None else (output,), laws=law)
    if not loaded.motors and _plans_without_motor(loaded):  # and the load's limits
        _plan(design, loaded, refused=((rank_by, "--rank-by"), (front, "--front"),
                                       (front_by, "--front-by"), (envelope, "--envelope"),
                                       (robust, "--robust")),
              top=top, fmt=fmt, output=output)
        return
    if robust:
        _size_robust(design, loaded, rank_by, top, show_all, fmt, output, jobs, law,
                     samples=samples or 0, seed=seed)
        return
    note_tolerances(loaded)
    sizing = size_loaded(design, loaded, rank_by, workers=jobs, laws=law)
    document = SizingDocument(sizing, loaded, rank_by=rank_by, top=top,
                              include_infeasible=show_all,
                              front=front_of(sizing, front_key, design), front_only=front)
    publish_sizing(document, fmt, output)


def note_tolerances(loaded: Design) -> None:
    """A line on stderr where the design gives tolerances (beside its values or in
    ``tolerances:``) that a sizing without --robust leaves aside: the answer is the nominal
    machine's, unchanged."""
    if loaded.tolerances:
        from sizer.model.tolerance import tolerance_of

        names = ", ".join(tolerance_of(t).name for t in loaded.tolerances)
        typer.echo(f"note: the design gives tolerances ({names}); this is the nominal "
                   f"machine's sizing: add --robust to check the pairs at them "
                   f"(docs/robust.md)", err=True)


def check_robust_options(robust: bool, rank_by: str | None, samples: int | None,
                         seed: int | None) -> None:
    """UserErrors naming the option: a robust --rank-by key without --robust, a negative
    --samples, --seed without --samples."""
    if rank_by is not None and not robust:
        from sizer.sizing.ranking import is_robust_key

        if is_robust_key(rank_by):
            raise UserError(f"{rank_by!r} ranks by the worst-case margin over the design's "
                            f"tolerances: add --robust", field="--rank-by")
    if samples is not None:
        from sizer.robust import MAX_SAMPLES

        if not 1 <= samples <= MAX_SAMPLES:
            raise UserError(f"the number of samples must be in [1, {MAX_SAMPLES}], got "
                            f"{samples}", field="--samples")
    if seed is not None and samples is None:
        raise UserError("the seed of the samples: only with --samples N", field="--seed")


def _size_robust(path: Path, loaded: Design, rank_by: str | None, top: int | None,
                 show_all: bool, fmt: Format, output: Path | None, jobs: int | None,
                 law: Sequence[str] | None, *, samples: int = 0,
                 seed: int | None = None) -> None:
    """``sizer size --robust``: the sizing, then every pair at the corners of the design's
    tolerances and at ``samples`` builds drawn from them (sizer.robust)."""
    from sizer.report.robust_table import RobustDocument
    from sizer.report.sizing_table import publish_sizing
    from sizer.robust import DEFAULT_SEED, check_tolerances, robust_sizing
    from sizer.sizing.ranking import nominal_rank_by

    try:
        check_tolerances(loaded, samples)
    except UserError as error:
        raise (error if (error.field or "").startswith("--")
               else error.located(file=str(path))) from None
    nominal_key = nominal_rank_by(rank_by)
    sizing = size_loaded(path, loaded, nominal_key, workers=jobs, laws=law)
    try:
        robust = robust_sizing(loaded, sizing, rank_by=rank_by, workers=jobs,
                               samples=samples, seed=DEFAULT_SEED if seed is None else seed)
    except UserError as error:
        raise error.located(file=str(path)) from None
    publish_sizing(RobustDocument(robust, loaded, rank_by=nominal_key, top=top,
                                  include_infeasible=show_all), fmt, output)


def _size_machine(path: Path, catalog: Sequence[str] | None, motor: Sequence[str] | None,
                  rank_by: str | None, top: int | None, show_all: bool, fmt: Format,
                  output: Path | None, envelope: str | None, jobs: int | None) -> None:
    """``sizer size`` of a machine file: every axis at the master speed, and the bus
    (each axis's sizings in ``jobs`` processes, as a design's)."""
    from sizer import api
    from sizer.cli.output_guard import check_outputs
    from sizer.cli.progress import sizing_progress
    from sizer.report.machine_report import MachineDocument, publish_machine

    refuse_motor_options(catalog, motor)
    machine = api.load_machine(path)
    check_outputs(() if output is None else (output,), machine.files)
    try:
        with sizing_progress(f"sizing {path.name}", unit="laws") as progress:
            result = api.size_machine(machine, rank_by=rank_by, envelope=envelope or None,
                                      progress=progress, workers=jobs)
    except UserError as error:
        raise error.located(file=str(path)) from None
    document = MachineDocument(result, machine, rank_by=rank_by, top=top,
                               include_infeasible=show_all)
    publish_machine(document, fmt, output)


def _plan(path: Path, design: Design, *, refused: Sequence[tuple[object, str]],
          top: int | None, fmt: Format, output: Path | None) -> None:
    """``sizer size`` of a design without motors: each law planned against the load's
    limits (sizer.sizing.planning, docs/planning.md); the ``refused`` (value, option)
    pairs are motor options, a UserError when given."""
    from sizer.report.planning_table import PlanningDocument, publish_planning
    from sizer.sizing.planning import plan

    for given, option in refused:
        if given:
            raise UserError("not for a plan without a motor (no motors, and the load's "
                            "limits): it ranks the laws by T_min or lambda", field=option)
    try:
        result = plan(design)
    except UserError as error:
        raise error.located(file=str(path)) from None
    publish_planning(PlanningDocument(result, top=top), fmt, output)


def load_and_size(design: Path, catalog: Sequence[str] | None, motor: Sequence[str] | None,
                  rank_by: str | None, *, envelope: str | None = None,
                  outputs: Sequence[Path] = (), workers: int | None = None,
                  laws: Sequence[str] | None = None) -> tuple[Design, SizingResult]:
    """Load a design (plus --catalog), restrict it to the --motor ids, with --envelope and
    the --law specs instead of the design's laws (None: the design's), and size it
    (sizer.api) in ``workers`` processes (None: every CPU for a large design);
    UserErrors of the sizing name the design file (those of a --law name the option).
    None of the ``outputs`` may be a file the load read (checked before the sizing)."""
    loaded = load_overridden(design, catalog, motor, rank_by, envelope=envelope,
                             outputs=outputs, laws=laws)
    return loaded, size_loaded(design, loaded, rank_by, workers=workers, laws=laws)


def load_overridden(design: Path, catalog: Sequence[str] | None,
                    motor: Sequence[str] | None, rank_by: str | None, *,
                    envelope: str | None = None, outputs: Sequence[Path] = (),
                    laws: Sequence[str] | None = None) -> Design:
    """The first half of :func:`load_and_size`: the design loaded with its options."""
    from sizer import api
    from sizer.cli.output_guard import check_outputs

    check_rank_key(rank_by)  # an unknown key fails before any work
    loaded = load_design_file(design, catalog)
    check_outputs(outputs, loaded.files)
    with as_option("motors", "--motor"):
        loaded = api.override(loaded, motors=motor or None, envelope=envelope or None)
    if laws:
        with as_option("laws", "--law"):
            loaded = api.override(loaded, laws=list(dict.fromkeys(laws)))
    return loaded


def size_loaded(design: Path, loaded: Design, rank_by: str | None, *,
                workers: int | None = None,
                laws: Sequence[str] | None = None) -> SizingResult:
    """The second half of :func:`load_and_size`: the loaded design sized."""
    from sizer import api
    from sizer.cli.progress import sizing_progress

    try:
        with sizing_progress(f"sizing {design.name}", unit="laws") as progress:
            if laws:  # a law's own mistake (a data law's file) names the option
                with as_option("laws", "--law"):
                    return api.size(loaded, rank_by=rank_by, progress=progress,
                                    workers=workers)
            return api.size(loaded, rank_by=rank_by, progress=progress, workers=workers)
    except UserError as error:
        if error.field == "--law":  # the option's mistake, not the file's
            raise
        from sizer.io.loader import at_its_line

        raise at_its_line(error, design) from None


def check_laws(specs: Sequence[str]) -> None:
    """Every --law spec reads as a law and, without ``auto`` parameters, builds (its
    parameters in range); else a UserError naming --law, before any file is read."""
    from sizer.laws import law_choice  # lazy: keeps --help fast

    check_law_specs(list(specs), "--law")
    for spec in specs:
        with blame_option("--law"):
            choice = law_choice(spec)
            if choice.is_fixed:
                choice.law  # noqa: B018 (built for its check)


def check_front_key(front_by: str | None) -> FrontBy:
    """The --front-by objective (power by default); a UserError naming the option."""
    from sizer.sizing.front import front_by as read_front_by

    with as_option("front_by", "--front-by"):
        return read_front_by(front_by)


def front_of(sizing: SizingResult, by: FrontBy, design: Path) -> Front:
    """The trade-off front of a sizing by ``by``; its UserError names --front-by (and the
    design file)."""
    from sizer.sizing.front import trade_off

    try:
        with as_option("front_by", "--front-by"):
            return trade_off(sizing, by)
    except UserError as error:
        raise error.located(file=str(design)) from None


def check_rank_key(rank_by: str | None, field: str = "--rank-by") -> None:
    """UserError naming the option and its choices (sizer.api.check_rank_by) when
    ``rank_by`` is not a key."""
    from sizer import api

    with as_option("rank_by", field):
        api.check_rank_by(rank_by)


def register(app: typer.Typer) -> None:
    app.command("size")(size)


def _plans_without_motor(design: Design) -> bool:
    """sizer.sizing.planning.plans_without_motor, its module imported only for a design
    without motors (a plan: docs/planning.md)."""
    from sizer.sizing.planning import plans_without_motor

    return plans_without_motor(design)
