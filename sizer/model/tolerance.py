"""A tolerance of one input of a design (``tolerances:``, ``sizer size --robust``,
docs/robust.md): how far the built machine's value may lie from the one given, and how it
is distributed.

A :class:`Tolerance` is the input's name and the half-width of the box the corners use: a
fraction of the value for a relative tolerance, the change in SI for an absolute one. A
normal tolerance is truncated at ``sigmas`` standard deviations, so its corners are at
+-width = +-sigmas * sigma; a uniform one spreads evenly over the box. A plain
``(name, fraction)`` pair is a relative uniform tolerance (:func:`tolerance_of`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

Distribution = Literal["uniform", "normal"]
DISTRIBUTIONS: tuple[str, ...] = ("uniform", "normal")
DEFAULT_SIGMAS = 3.0
"""Where a normal tolerance is truncated (and has its corners) unless the design says."""


@dataclass(frozen=True)
class Tolerance:
    """An input's tolerance: its ``name`` (e.g. ``load.inertia``; ``motor.peak_torque[M1]``
    for one motor's figure alone) and ``width``, the
    box's half-width, ``absolute`` (the width in SI) or relative (a fraction);
    ``distribution`` uniform or normal, ``sigmas`` the normal's truncation in standard
    deviations (its sigma is width / sigmas; None for a uniform one)."""

    name: str
    width: float
    absolute: bool = False
    distribution: Distribution = "uniform"
    sigmas: float | None = None

    def __post_init__(self) -> None:
        if self.distribution not in DISTRIBUTIONS:
            raise ValueError(f"unknown distribution {self.distribution!r}")
        object.__setattr__(self, "width", float(self.width))
        if self.distribution == "normal" and self.sigmas is None:
            object.__setattr__(self, "sigmas", DEFAULT_SIGMAS)
        elif self.distribution == "uniform":
            object.__setattr__(self, "sigmas", None)

    @property
    def input(self) -> str:
        """The input's name without the one motor the tolerance is limited to
        (``motor.peak_torque[M1]``: ``motor.peak_torque``)."""
        return self.name.split("[", 1)[0]

    @property
    def motor(self) -> str | None:
        """The one motor a motor figure's tolerance applies to (given beside an inline
        motor's value: ``motor.<field>[<id>]``); None: every motor (or not a motor's)."""
        return self.name[len(self.input) + 1:-1] if "[" in self.name else None

    @property
    def sigma(self) -> float | None:
        """The normal's standard deviation (in the width's terms); None for uniform."""
        return None if self.sigmas is None else self.width / self.sigmas


def tolerance_of(given: Tolerance | tuple[str, float]) -> Tolerance:
    """``given`` as a Tolerance: itself, or a plain (name, fraction) as relative uniform."""
    if isinstance(given, Tolerance):
        return given
    name, width = given
    return Tolerance(name, width)
