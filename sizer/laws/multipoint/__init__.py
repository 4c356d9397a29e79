"""Laws defined by data: splines through via-points, B-splines, NURBS and cam tables.

Book ch. 4 (sec. 4.4 cubic splines, 4.5 B-splines), the slides on polynomial splines,
B-splines and NURBS (seed 002) and the trajectory through a sequence of points (sec.
3.2.4). Each kind has a builder ``build(fields) -> Curve`` that reads its YAML mapping
(plain numbers in the user's units, see :mod:`sizer.laws.multipoint.fields`) and returns
the curve q(t) over [t_0, t_n]; :mod:`sizer.laws.data_law` normalizes it into a
:class:`~sizer.laws.base.MotionLaw`.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np


class Curve(Protocol):
    """A position q(t) over [x[0], x[-1]] with its derivatives, smooth between the
    breakpoints ``x``. ``scipy.interpolate.PPoly`` satisfies it; so does a NURBS."""

    x: np.ndarray
    """Breakpoints, increasing; the curve is smooth (C-infinity) between two of them."""

    def __call__(self, t: np.ndarray, nu: int = 0) -> np.ndarray:
        """The nu-th derivative at t (t inside [x[0], x[-1]])."""
        ...


@dataclass(frozen=True)
class FittedCurve:
    """What a builder may return instead of a bare curve: the curve, what it says about
    the fit (a cam table's fit error and derivative noise, by name), and the units its
    data carry (time or master-angle unit, position unit; None where not given)."""

    curve: Curve
    report: Mapping[str, float] = field(default_factory=dict)
    units: tuple[str | None, str | None] = (None, None)
