"""Small array helpers the core needs at start-up."""

from __future__ import annotations

import numpy as np


def sorted_unique(values: np.ndarray) -> np.ndarray:
    """The sorted distinct values of an array, flattened: ``np.unique(values)``.

    Written out because numpy 2's plain ``np.unique`` imports ``numpy.ma`` on its first
    call (about 60 ms, a tenth of sizing a book example); NaNs are not expected here.
    """
    x = np.sort(np.ravel(values))
    if x.size == 0:
        return x
    keep = np.empty(x.size, dtype=bool)
    keep[0] = True
    np.not_equal(x[1:], x[:-1], out=keep[1:])
    return x[keep]


def spread(x: np.ndarray | float, n: int) -> np.ndarray:
    """``x`` broadcast to shape (n,), to be read: ``x`` itself where it is an array of that
    shape already (np.broadcast_to costs about 2 us a call, and the engine makes thousands
    of such calls per sizing on arrays that already have it)."""
    if isinstance(x, np.ndarray) and x.shape == (n,):
        return x
    return np.broadcast_to(x, (n,))
