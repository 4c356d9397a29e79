"""Where is a piecewise-smooth difference largest? The exact maxima of the export
certificates (sizer.export.hermite_certificate, coefficient_segments, linear_certificate).

On a cell where the difference e between a written curve and its law is smooth, the
largest |e^(k)| lies at the cell's ends or at a root of e^(k+1): e^(k+1) is sampled at
``samples`` + 1 points across each cell, every sign change between two neighbours is a
bracket, and its root is found by scipy's elementwise Chandrupatla root finder, all
brackets at once. A pair of roots closer than 1/``samples`` of a cell is not bracketed:
the method's one assumption (the certificates' tests check it against dense grids).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

Difference = Callable[[np.ndarray, np.ndarray, int], np.ndarray]
"""e^(order)(t) on the cells ``cell`` (an index per value of t)."""


@dataclass(frozen=True)
class Extreme:
    """The largest |error| of one derivative and the master value where it is."""

    max: float
    at: float


def bracketed_roots(f: Callable[..., np.ndarray], a: np.ndarray, b: np.ndarray,
                    *args: np.ndarray) -> np.ndarray:
    """The root of f(t, *args) in each bracket [a, b] (a sign change), vectorized; the
    ``args`` reach f with their own dtypes (the root finder carries them as floats)."""
    from scipy.optimize.elementwise import find_root  # lazy: scipy is heavy

    kinds = [np.asarray(v).dtype for v in args]

    def g(t: np.ndarray, *given: np.ndarray) -> np.ndarray:
        return f(t, *(v.astype(kind) for v, kind in zip(given, kinds, strict=True)))

    result = find_root(g, (a, b), args=tuple(np.asarray(v, dtype=float) for v in args))
    return np.clip(np.asarray(result.x, dtype=float), a, b)


def largest_difference(difference: Difference, lo: np.ndarray, hi: np.ndarray, order: int,
                       samples: int) -> Extreme:
    """max |e^(order)| over the cells [lo_i, hi_i] (module docstring) and where it is."""
    count = len(lo)
    ends = np.concatenate([lo, hi])
    both = np.concatenate([np.arange(count)] * 2)
    where = [ends]
    values = [np.abs(difference(ends, both, order))]
    fractions = np.linspace(0.0, 1.0, samples + 1)
    grid = lo[:, None] + (hi - lo)[:, None] * fractions[None, :]
    cells = np.broadcast_to(np.arange(count)[:, None], grid.shape)
    slope = difference(grid.ravel(), cells.ravel(), order + 1).reshape(grid.shape)
    change = slope[:, :-1] * slope[:, 1:] < 0.0
    if change.any():
        row, col = np.nonzero(change)
        roots = bracketed_roots(lambda t, i: difference(t, i, order + 1),
                                grid[row, col], grid[row, col + 1], row)
        where.append(roots)
        values.append(np.abs(difference(roots, row, order)))
    x, err = np.concatenate(where), np.concatenate(values)
    k = int(np.argmax(err))
    return Extreme(float(err[k]), float(x[k]))
