"""The Python interface: size a design given as a file, a mapping or model objects.

    >>> import sizer
    >>> result = sizer.size("examples/book/ex6_3.yaml")           # doctest: +SKIP
    >>> result.to_records()[0]["motor"]                           # doctest: +SKIP

``size`` is what ``sizer size`` runs, without the terminal: the same loading (units,
ranges, located errors as :class:`sizer.errors.UserError`), the same engine and ranking.
The result is a :class:`sizer.sizing.SizingResult`: ``results`` ranked (rows built when
read), ``table`` the same candidates as arrays, ``to_records()`` / ``to_dict()`` plain
data.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from os import PathLike
from pathlib import Path
from typing import Any

from sizer.model.domain import Design, Motor
from sizer.sizing.engine import Progress, check_design, size_design
from sizer.sizing.results import CandidateResult, SizingResult

DesignLike = str | PathLike[str] | Mapping[str, Any] | Design
"""A design file's path, the same content as a mapping, or a :class:`Design`."""


def load(design: DesignLike, catalogs: Iterable[str | PathLike[str]] = (), *,
         base: str | PathLike[str] | None = None) -> Design:
    """The :class:`Design` of a path, a mapping (relative catalog paths from ``base``, the
    working directory by default) or a Design (returned as it is).

    A design that names no motors and gets no ``catalogs`` is sized against the bundled
    catalogs, as on the command line.
    """
    from sizer.io.loader import load_design, load_design_data

    if isinstance(design, Design):
        return design
    if isinstance(design, Mapping):
        return load_design_data(design, extra_catalogs=tuple(catalogs), default_motors=True,
                                base=Path(base) if base is not None else Path.cwd())
    return load_design(Path(design), extra_catalogs=tuple(catalogs), default_motors=True)


def size(design: DesignLike, *, catalogs: Iterable[str | PathLike[str]] = (),
         rank_by: str | None = None, motors: Sequence[Motor] | None = None,
         progress: Progress | None = None) -> SizingResult:
    """Every motor x law (x transmission option) of ``design``, ranked feasible first.

    ``rank_by`` is a ``--rank-by`` key (None: the mode's default); ``motors`` replaces
    the design's motors; ``progress(done, total)`` is called per law.
    """
    return size_design(load(design, catalogs), rank_by=rank_by, motors=motors,
                       progress=progress)


def check(design: DesignLike, *, catalogs: Iterable[str | PathLike[str]] = ()
          ) -> CandidateResult:
    """The result of the motor and law the design's ``check:`` names (``sizer check``)."""
    return check_design(load(design, catalogs))
