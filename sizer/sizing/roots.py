"""Vectorized bracketed root finding (Illinois variant of regula falsi)."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

MAX_STEPS = 60


def illinois(f: Callable[[np.ndarray], np.ndarray], lo: np.ndarray, hi: np.ndarray,
             f_lo: np.ndarray, f_hi: np.ndarray, xtol: float = 1e-15) -> np.ndarray:
    """Roots of f in [lo, hi] where f_lo and f_hi have opposite signs (elementwise).

    Superlinear like the secant method, never leaves the bracket like bisection: about
    8 evaluations reach machine precision where plain bisection takes 50.
    """
    lo, hi, f_lo, f_hi = (np.array(x, dtype=float) for x in (lo, hi, f_lo, f_hi))
    side = np.zeros(lo.shape)
    for step in range(MAX_STEPS):
        open_ = (hi - lo) > xtol * np.maximum(1.0, np.abs(lo))
        if not open_.any():
            break
        with np.errstate(invalid="ignore", divide="ignore"):
            x = (lo * f_hi - hi * f_lo) / (f_hi - f_lo)
        bad = ~np.isfinite(x) | (x <= lo) | (x >= hi) | (step % 6 == 5)
        x = np.where(bad, 0.5 * (lo + hi), x)
        fx = f(x)
        left = np.sign(fx) == np.sign(f_lo)  # root in [x, hi]: move lo
        move_lo, move_hi = open_ & left, open_ & ~left
        f_hi = np.where(move_lo & (side == -1), 0.5 * f_hi, f_hi)
        f_lo = np.where(move_hi & (side == 1), 0.5 * f_lo, f_lo)
        lo, f_lo = np.where(move_lo, x, lo), np.where(move_lo, fx, f_lo)
        hi, f_hi = np.where(move_hi, x, hi), np.where(move_hi, fx, f_hi)
        side = np.where(move_lo, -1, np.where(move_hi, 1, side))
        exact = open_ & (fx == 0.0)
        lo, hi = np.where(exact, x, lo), np.where(exact, x, hi)
    return 0.5 * (lo + hi)
