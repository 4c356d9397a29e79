"""The load's figures per candidate: one build of the load for each (issue 39's robust
sizing as an axis of the candidate arrays, docs/robust.md).

A :class:`sizer.model.domain.Load` holds J_l, B_l, F and tau_ext once (eq. 6.1). Where the
candidates drive different builds of the same load (the corners and samples of the
design's tolerances on them: ``load.inertia +- 20 %``, ``load.friction``...), those four
figures are arrays over the candidates; everything else of the load (its mode, its terms
of the position) stays the design's. The drive reads the figures from here
(sizer.mechanics.drive.Drive.figures), so one evaluation sizes every motor at every build.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from sizer.model.domain import Load

FIGURES = ("inertia", "damping", "friction", "torque")
"""The load's numbers that may vary per candidate (Load's fields, SI)."""


@dataclass(frozen=True, eq=False)
class LoadFigures:
    """J_l, B_l, F and tau_ext (Load's ``inertia``, ``damping``, ``friction``,
    ``torque``): floats where every candidate drives the same load, arrays (candidates,)
    where each drives its own build (:attr:`varies`)."""

    inertia: float | np.ndarray
    damping: float | np.ndarray
    friction: float | np.ndarray
    torque: float | np.ndarray

    @classmethod
    def of(cls, load: Load) -> LoadFigures:
        """The load's own figures, the same for every candidate."""
        return cls(load.inertia, load.damping, load.friction, load.torque)

    @classmethod
    def builds(cls, loads: list[Load]) -> LoadFigures:
        """One build per candidate: ``loads[i]`` is candidate i's."""
        return cls(*(np.array([getattr(load, name) for load in loads], dtype=float)
                     for name in FIGURES))

    @property
    def varies(self) -> bool:
        """Whether the candidates drive builds of their own (arrays)."""
        return isinstance(self.inertia, np.ndarray)

    def take(self, index: np.ndarray) -> LoadFigures:
        """The figures of the candidates at ``index`` (repeats allowed)."""
        if not self.varies:
            return self
        return LoadFigures(*(np.asarray(getattr(self, name))[index] for name in FIGURES))

    def moved(self, old: Load, new: Load) -> LoadFigures:
        """The figures with ``new`` in place of ``old`` (a segment's added part, a
        position term's inertia): ``new``'s own where they are the load's, else each
        build changed by what ``new`` changes (new - old)."""
        if not self.varies:
            return LoadFigures.of(new)
        return LoadFigures(*(getattr(self, name) + (getattr(new, name) - getattr(old, name))
                             for name in FIGURES))

    def none(self, *names: str) -> bool:
        """Whether the figures ``names`` are zero for every candidate."""
        return all(bool(np.all(np.asarray(getattr(self, name)) == 0.0)) for name in names)

    def column(self, name: str, n: int) -> np.ndarray:
        """Figure ``name`` per candidate (n,) (a fresh array)."""
        return np.broadcast_to(np.asarray(getattr(self, name), dtype=float), (n,)).copy()
