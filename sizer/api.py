"""The Python interface: size a design given as a file, a mapping or model objects.

    >>> import sizer
    >>> result = sizer.size("examples/book/ex6_3.yaml")           # doctest: +SKIP
    >>> result.to_records()[0]["motor"]                           # doctest: +SKIP

``size`` is what ``sizer size`` runs, without the terminal: the same loading (units,
ranges, located errors as :class:`sizer.errors.UserError`), the same engine and ranking
(book ch. 6). The result is a :class:`sizer.sizing.SizingResult`: ``results`` ranked (rows
built when read), ``table`` the same candidates as arrays, ``to_records()`` /
``to_dict()`` plain data.

The command line is built on these functions: each command parses its options, calls
:func:`load`, :func:`override`, then :func:`size` or :func:`check`, and formats what they
return. A UserError about one of their parameters names it (``field="motors"``,
``"rank_by"``, ``"envelope"``); the command line names its option instead.

The engine is imported when a function runs, not with this module.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import replace
from os import PathLike
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeAlias, get_args

from sizer.errors import UserError
from sizer.model.domain import Design, EnvelopeRule, Motor

if TYPE_CHECKING:
    from sizer.laws.choice import LawChoice
    from sizer.model.machine import Machine
    from sizer.sizing.machine import MachineResult
    from sizer.sizing.planning import PlanningResult
    from sizer.sizing.results import CandidateResult, SizingResult

DesignLike = str | PathLike[str] | Mapping[str, Any] | Design
"""A design file's path, the same content as a mapping, or a :class:`Design`."""

CatalogRef = str | PathLike[str]
"""A motor catalog: a YAML file (relative to the working directory) or a bundled name."""

Progress = Callable[[int, int], None]
"""``progress(done, total)``: called with (0, n), then as the design's n laws are sized
(after each, or once with (n, n) where they are sized together as one axis)."""

ENVELOPES: tuple[EnvelopeRule, ...] = get_args(EnvelopeRule)
"""The ``envelope`` rules (sizer.envelope.completion.ENVELOPE_RULES)."""


def load(design: DesignLike, catalogs: Iterable[CatalogRef] = (), *,
         base: str | PathLike[str] | None = None) -> Design:
    """The :class:`Design` of a path, a mapping (relative catalog paths from ``base``, the
    working directory by default) or a Design (returned as it is).

    ``catalogs`` add their motors to those the design names (``--catalog``). A design that
    names no motors and gets no ``catalogs`` is sized against the bundled catalogs, as on
    the command line. The Design keeps the loader's warnings (``Design.warnings``, located
    lines) and the files it read (``Design.files``).
    """
    from sizer.io.loader import load_design, load_design_data

    extra = tuple(str(c) for c in catalogs)  # the loader reads each as str(reference)
    if isinstance(design, Design):
        if extra:
            raise TypeError("catalogs are read with a design file or mapping; a Design "
                            "has its motors (pass motors= to replace them)")
        return design
    if isinstance(design, Mapping):
        return load_design_data(design, extra_catalogs=extra, default_motors=True,
                                base=Path(base) if base is not None else Path.cwd())
    return load_design(Path(design), extra_catalogs=extra, default_motors=True)


def override(design: Design, *, motors: Sequence[str] | Sequence[Motor] | None = None,
             laws: Sequence[LawChoice | str] | None = None,
             envelope: str | None = None) -> Design:
    """``design`` with what a command's options change (None keeps the design's own).

    - ``motors``: motor ids, to size only those among the design's motors (in catalog
      order; ``--motor``; an unknown id is a UserError with ``field="motors"``), or
      Motor objects to size instead of the design's;
    - ``laws``: law specs (or choices) to consider instead of the design's ``laws:``;
    - ``envelope``: the completion rule of regions without curves (``book``, ``linear``,
      ``linear_intermittent``, ``electrical``; ``--envelope``), instead of the design's
      ``limits.envelope`` (sec. 6.1.1).

    The notes of a sizing (:func:`assumptions`) follow the motors and envelope given.
    """
    if motors is not None:
        design = replace(design, motors=_motors(design.motors, motors))
    if laws is not None:
        from sizer.laws.choice import law_choice  # lazy: the law families load with a law

        design = replace(design, laws=tuple(law_choice(spec) for spec in laws))
    if envelope is not None:
        rule = next((r for r in ENVELOPES if r == str(envelope)), None)
        if rule is None:
            raise UserError(f"unknown rule {str(envelope)!r}; choose one of "
                            f"{', '.join(ENVELOPES)}", field="envelope")
        design = replace(design, limits=replace(design.limits, envelope=rule))
    return design


def _motors(loaded: Sequence[Motor], chosen: Sequence[str] | Sequence[Motor]
            ) -> tuple[Motor, ...]:
    """The motors ``override`` sizes: ids selected from ``loaded``, or Motor objects."""
    if isinstance(chosen, str):
        raise TypeError("motors: a sequence of ids or Motor objects, not one string")
    objects = tuple(m for m in chosen if isinstance(m, Motor))
    if objects and len(objects) == len(chosen):
        return objects
    if objects:
        raise TypeError("motors: all ids or all Motor objects, not both")
    ids = [str(i) for i in chosen]
    known = {m.id for m in loaded}
    unknown = [i for i in dict.fromkeys(ids) if i not in known]
    if unknown:
        shown = ", ".join(m.id for m in loaded[:12]) + (", ..." if len(loaded) > 12 else "")
        raise UserError(f"unknown motor {unknown[0]!r}; loaded motors: {shown or 'none'}",
                        field="motors")
    wanted = set(ids)
    return tuple(m for m in loaded if m.id in wanted)


def check_rank_by(rank_by: str | None) -> None:
    """A UserError (``field="rank_by"``) naming the choices when ``rank_by`` is not a
    ranking key (sizer.sizing.ranking.RankKey or an alias); None is the mode's default."""
    from sizer.sizing.ranking import RANK_CHOICES, rank_key

    if rank_by is not None and rank_key(rank_by) is None:
        raise UserError(f"unknown key {rank_by!r}; choose one of {RANK_CHOICES}",
                        field="rank_by")


def size(design: DesignLike, *, catalogs: Iterable[CatalogRef] = (),
         rank_by: str | None = None, motors: Sequence[str] | Sequence[Motor] | None = None,
         laws: Sequence[LawChoice | str] | None = None, envelope: str | None = None,
         progress: Progress | None = None, workers: int | None = 1) -> SizingResult:
    """Every motor x law (x transmission option) of ``design``, ranked feasible first
    (``sizer size``; the checks of sec. 6.1, T_min of eq. (6.2) with ``minimize``).

    ``catalogs`` as in :func:`load`; ``motors``, ``laws`` and ``envelope`` as in
    :func:`override`; ``rank_by`` a ``--rank-by`` key (``size``, ``duration``,
    ``margin``, ``rms``, ``peak``, ``price``, ``mass``, alias ``power``; None: ``duration``
    with ``minimize``, else ``size``), checked before any work; ``progress(done, total)``
    is called per law. ``workers``: processes that size the laws (None: every CPU for a
    large design; the same result whatever their number). More than one starts worker
    processes, which import the calling script again: keep its work under ``if __name__
    == "__main__":`` (sizer.sizing.engine).
    """
    import sizer.sizing as sizing  # looked up when called: the engine stays replaceable

    check_rank_by(rank_by)
    sized = override(load(design, catalogs), motors=motors, laws=laws, envelope=envelope)
    return sizing.size_design(sized, rank_by=rank_by, progress=progress, workers=workers)


def check(design: DesignLike, *, catalogs: Iterable[CatalogRef] = (),
          envelope: str | None = None) -> CandidateResult:
    """The result of the motor and law the design's ``check:`` names (``sizer check``):
    ``feasible`` is the verdict, ``checks`` every limit with its value and margin."""
    import sizer.sizing as sizing

    return sizing.check_design(override(load(design, catalogs), envelope=envelope))


def plan(design: DesignLike, *, catalogs: Iterable[CatalogRef] = (),
         laws: Sequence[LawChoice | str] | None = None) -> PlanningResult:
    """Each law's shortest duration (or, for a given duration, the book's scaling factor
    lambda, eq. 5.4) under the load's own limits, with no motor (``sizer size`` of a
    design with no motors and the load's limits; sizer.sizing.planning,
    docs/planning.md). The design's motors, if any, are not used."""
    from sizer.sizing.planning import plan as plan_laws

    return plan_laws(override(load(design, catalogs), laws=laws))


def fastest_by_law(design: DesignLike, laws: Sequence[str], *,
                   catalogs: Iterable[CatalogRef] = (), progress: Progress | None = None
                   ) -> list[tuple[float | None, str | None]]:
    """For each law spec of ``laws``: the design's shortest duration with that law (the
    fastest feasible motor, ranked by ``duration``) and that motor; (None, None) where no
    motor is feasible. The laws are sized together, in one call of :func:`size` (a
    ``sizer laws --sweep --design`` study). A UserError for a design that does not
    minimize its duration, or a spec that names no law."""
    from sizer.laws import make_law

    loaded = load(design, catalogs)
    if not loaded.machine_cycle.minimize:
        raise UserError("T_min needs a design that minimizes its duration (duration: "
                        "minimize)", field="laws")
    specs = [make_law(text).spec for text in laws]
    sized = size(loaded, rank_by="duration", laws=list(dict.fromkeys(specs)),
                 progress=progress)
    best: dict[str, tuple[float | None, str | None]] = {}
    for result in sized.feasible:  # ranked: the first of each law is its fastest
        best.setdefault(result.spec, (result.duration, result.motor))
    return [best.get(spec, (None, None)) for spec in specs]


def assumptions(design: Design) -> tuple[str, ...]:
    """What sizing ``design`` assumes, as the notes under a table say it (the envelope
    rule of motors without curves, the efficiency convention, the inertia ratio's
    definition...); the same as ``size(design).notes``."""
    import sizer.sizing as sizing

    return sizing.assumptions(design)


MachineLike: TypeAlias = "str | PathLike[str] | Mapping[str, Any] | Machine"
"""A machine file's path, the same content as a mapping, or a :class:`Machine` (a
string: the machine model is imported only when a machine is loaded)."""


def load_machine(machine: MachineLike, *, base: str | PathLike[str] | None = None
                 ) -> Machine:
    """The :class:`Machine` of a machine file's path or mapping (``axes:``; relative paths
    from ``base``, the working directory by default), or a Machine as it is."""
    from sizer.io.machine_loader import load_machine as read
    from sizer.io.machine_loader import load_machine_data
    from sizer.model.machine import Machine

    if isinstance(machine, Machine):
        return machine
    if isinstance(machine, Mapping):
        return load_machine_data(machine, base=Path(base) if base is not None else None)
    return read(Path(machine))


def size_machine(machine: MachineLike, *, rank_by: str | None = None,
                 envelope: str | None = None,
                 progress: Progress | None = None, workers: int | None = 1) -> MachineResult:
    """Every axis of a machine at its master speed, the slowest axis setting it with
    ``master_speed: minimize`` (book sec. 5.3), and the DC bus of the axes' choices
    (``sizer size`` of a machine file). ``rank_by``, ``envelope`` and ``workers`` as in
    :func:`size`, for every axis."""
    from sizer.sizing.machine import size_machine as run

    check_rank_by(rank_by)
    loaded = load_machine(machine)
    if envelope is not None:
        axes = tuple(replace(a, design=override(a.design, envelope=envelope))
                     for a in loaded.axes)
        loaded = replace(loaded, axes=axes)
    return run(loaded, rank_by, progress, workers)
