"""Small array helpers the core needs at start-up."""

from __future__ import annotations

import numpy as np


def sorted_unique(values: np.ndarray) -> np.ndarray:
    """The sorted distinct values of an array, flattened: ``np.unique(values)`` (NaNs, last
    after the sort, kept once as it keeps them).

    Written out because numpy 2's plain ``np.unique`` imports ``numpy.ma`` on its first
    call (10-25 ms of CPU, up to a twentieth of sizing an example from the command line).
    """
    x = np.sort(np.ravel(values))
    if x.size == 0:
        return x
    keep = np.empty(x.size, dtype=bool)
    keep[0] = True
    np.not_equal(x[1:], x[:-1], out=keep[1:])
    if x.dtype.kind in "fc" and np.isnan(x[-1]):  # NaN != NaN: keep the first only
        first = int(np.argmax(np.isnan(x)))
        keep[first + 1:] = False
    return x[keep]


def spread(x: np.ndarray | float, n: int) -> np.ndarray:
    """``x`` broadcast to shape (n,), to be read: ``x`` itself where it is an array of that
    shape already (np.broadcast_to costs about 2 us a call, and the engine makes thousands
    of such calls per sizing on arrays that already have it)."""
    if isinstance(x, np.ndarray) and x.shape == (n,):
        return x
    return np.broadcast_to(x, (n,))
