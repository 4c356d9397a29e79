"""The root of a cubic Hermite model on [0, 1], vectorized: where a function known by its
values and slopes at two points (of opposite signs) crosses zero between them. The laws'
exact peaks (sizer.laws.linear_peaks: the stationary points between two samples) and the
engine's power-flow reversals (sizer.sizing.cycle) start from it and polish on the law.
"""

from __future__ import annotations

import numpy as np

NEWTON_STEPS = 6
"""Safeguarded Newton steps on the cubic (from the secant estimate three reach
rounding; the rest are margin)."""


def hermite_root(g0: np.ndarray, g1: np.ndarray, d0: np.ndarray,
                 d1: np.ndarray, xtol: float = 0.0) -> np.ndarray:
    """s in [0, 1] where the cubic H(s) = g0 + d0 s + c2 s^2 + c3 s^3 with H(0) = g0,
    H(1) = g1 (of opposite signs) and slopes d0, d1 vanishes: safeguarded Newton steps
    from the secant point, bisection where a step would leave the sign bracket. A row
    stops at its fixed point, or with ``xtol`` > 0 after a Newton step of at most xtol
    (the model is then to be polished on the function it stands for)."""
    shape = np.broadcast_shapes(np.shape(g0), np.shape(g1), np.shape(d0), np.shape(d1))
    g0, g1, d0, d1 = (np.ravel(np.broadcast_to(np.asarray(x, dtype=float), shape))
                      for x in (g0, g1, d0, d1))
    if not g0.size:
        return np.zeros(shape)
    c2 = 3.0 * (g1 - g0) - 2.0 * d0 - d1
    c3 = 2.0 * (g0 - g1) + d0 + d1
    low, high = np.zeros_like(g0), np.ones_like(g0)
    rising = g0 < 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        s = g0 / (g0 - g1)
    out = s.copy()
    # the rows still stepping, as a mask over the working rows: all of them at first (the
    # steps of a few hundred rows cost their calls, not their length), then, once fewer
    # than half of them step on, only those (``where``: their positions in ``out``; a
    # row's steps are its own, so the values are the same)
    open_ = np.ones(s.shape, dtype=bool)
    where: np.ndarray | None = None
    for _ in range(NEWTON_STEPS):
        h = g0 + s * (d0 + s * (c2 + s * c3))
        before = (h < 0.0) == rising  # the root lies above s
        low, high = np.where(before, s, low), np.where(before, high, s)
        with np.errstate(divide="ignore", invalid="ignore"):
            step = s - h / (d0 + s * (2.0 * c2 + 3.0 * s * c3))
        # a row at its fixed point (a zero of the model, or a step that returns s) keeps
        # it in every later step: it is done, the steps go on with the others
        open_ &= (h != 0.0) & (step != s)
        if not open_.any():
            break
        # a step inside the bracket, or one at rounding level (converged), is taken;
        # else bisect
        near = np.abs(step - s)
        take = ((step >= low) & (step <= high)) | (near <= 1e-15)
        new = np.where(take, step, 0.5 * (low + high))
        if where is None:
            out = np.where(open_, new, out)
        else:
            out[where] = np.where(open_, new, out[where])
        if xtol > 0.0:
            open_ &= ~(take & (near <= xtol))
            if not open_.any():
                break
        s = new
        if 2 * np.count_nonzero(open_) < open_.size:
            keep = np.flatnonzero(open_)
            where = keep if where is None else where[keep]
            g0, d0, c2, c3, low, high, s, rising = (
                x[keep] for x in (g0, d0, c2, c3, low, high, s, rising))
            open_ = open_[keep]
    return np.clip(out, 0.0, 1.0).reshape(shape)
