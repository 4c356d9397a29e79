"""Vectorized bracketed root finding (Illinois variant of regula falsi)."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

MAX_STEPS = 60


def illinois(f: Callable[..., np.ndarray], lo: np.ndarray, hi: np.ndarray,
             f_lo: np.ndarray, f_hi: np.ndarray, xtol: float = 1e-15,
             args: tuple[np.ndarray, ...] | None = None, bracket: bool = False):
    """Roots of f in [lo, hi] where f_lo and f_hi have opposite signs (elementwise).

    Superlinear like the secant method, never leaves the bracket like bisection: about
    8 evaluations reach machine precision where plain bisection takes 50. ``f(x)`` is
    called on whole arrays; with ``args`` it is elementwise, called as ``f(x, *args)``
    on the elements still open only (with their args).

    With ``bracket`` the final (lo, hi) is returned instead of its midpoint: the end on
    the side of f_hi's sign stays there (a feasible end stays feasible).

    This is the project's root finder for functions without a derivative: the sizing
    engine and the laws' coefficient peaks (sizer.laws.coefficients) use it (a
    polynomial's roots, with its derivative at hand: sizer.sizing.move._bracketed).
    """
    lo, hi, f_lo, f_hi = (np.array(x, dtype=float) for x in (lo, hi, f_lo, f_hi))
    if args is not None:
        return _compacting(f, lo, hi, f_lo, f_hi, xtol, args, bracket)
    side = np.zeros(lo.shape)
    for step in range(MAX_STEPS):
        width = np.maximum(xtol * np.maximum(1.0, np.abs(lo)), 2.0 * np.spacing(np.abs(hi)))
        open_ = (hi - lo) > width
        if not open_.any():
            break
        x = _point(lo, hi, f_lo, f_hi, step)
        lo, hi, f_lo, f_hi, side = _step(f(x), open_, x, lo, hi, f_lo, f_hi, side)
    return (lo, hi) if bracket else 0.5 * (lo + hi)


def first_passing(slack: Callable[[np.ndarray, np.ndarray], np.ndarray], lo: np.ndarray,
                  f_lo: np.ndarray, doublings: int = 30, xtol: float = 1e-12) -> np.ndarray:
    """Per element, the smallest x >= ``lo`` where ``slack(x, index) >= 0`` (``index``: the
    elements x is for), a slack that grows with x: ``lo`` itself where ``f_lo`` (its slack)
    passes, else x doubled until it passes (at most ``doublings`` times) and the crossing
    bracketed by :func:`illinois` to ``xtol``, its passing end returned; inf where no
    doubling passes. The later limits' passing scale (sizer.sizing.stage_life,
    sizer.sizing.energy_check)."""
    lo, f_lo = np.array(lo, dtype=float), np.array(f_lo, dtype=float)
    n = len(lo)
    out = np.where(f_lo >= 0.0, lo, np.inf)
    hi, f_hi = np.full(n, np.nan), np.full(n, np.nan)
    todo = np.flatnonzero(f_lo < 0.0)
    for _ in range(doublings):
        if not todo.size:
            break
        trial = 2.0 * lo[todo]
        value = slack(trial, todo)
        passed = value >= 0.0
        hi[todo[passed]], f_hi[todo[passed]] = trial[passed], value[passed]
        lo[todo[~passed]], f_lo[todo[~passed]] = trial[~passed], value[~passed]
        todo = todo[~passed]
    found = np.flatnonzero(np.isfinite(hi) & ~np.isfinite(out))
    if found.size:
        def f(x: np.ndarray, index: np.ndarray) -> np.ndarray:
            return slack(x, found[index])

        _, top = illinois(f, lo[found], hi[found], f_lo[found], f_hi[found], xtol,
                          args=(np.arange(found.size),), bracket=True)
        out[found] = top
    return out


def _point(lo, hi, f_lo, f_hi, step: int) -> np.ndarray:
    """The next point: the (weighted) secant, or the midpoint every sixth step."""
    with np.errstate(invalid="ignore", divide="ignore"):
        x = (lo * f_hi - hi * f_lo) / (f_hi - f_lo)
    bad = ~np.isfinite(x) | (x <= lo) | (x >= hi) | (step % 6 == 5)
    return np.where(bad, 0.5 * (lo + hi), x)


def _step(fx, open_, x, lo, hi, f_lo, f_hi, side):
    left = np.sign(fx) == np.sign(f_lo)  # root in [x, hi]: move lo
    move_lo, move_hi = open_ & left, open_ & ~left
    f_hi = np.where(move_lo & (side == -1), 0.5 * f_hi, f_hi)
    f_lo = np.where(move_hi & (side == 1), 0.5 * f_lo, f_lo)
    lo, f_lo = np.where(move_lo, x, lo), np.where(move_lo, fx, f_lo)
    hi, f_hi = np.where(move_hi, x, hi), np.where(move_hi, fx, f_hi)
    side = np.where(move_lo, -1, np.where(move_hi, 1, side))
    exact = open_ & (fx == 0.0)
    return np.where(exact, x, lo), np.where(exact, x, hi), f_lo, f_hi, side


def _compacting(f, lo, hi, f_lo, f_hi, xtol, args, bracket=False):
    """The elementwise mode: each step works on the elements still open only."""
    out_lo, out_hi = lo.copy(), hi.copy()
    index = np.arange(lo.size)
    side = np.zeros(lo.shape)
    args = tuple(np.asarray(a) for a in args)

    def result():
        return (out_lo, out_hi) if bracket else 0.5 * (out_lo + out_hi)

    for step in range(MAX_STEPS):
        width = np.maximum(xtol * np.maximum(1.0, np.abs(lo)), 2.0 * np.spacing(np.abs(hi)))
        open_ = (hi - lo) > width
        out_lo[index], out_hi[index] = lo, hi
        if not open_.any():
            return result()
        index, lo, hi, f_lo, f_hi, side = (v[open_] for v in (index, lo, hi, f_lo, f_hi, side))
        args = tuple(a[open_] for a in args)
        x = _point(lo, hi, f_lo, f_hi, step)
        lo, hi, f_lo, f_hi, side = _step(f(x, *args), np.ones(len(x), bool), x, lo, hi, f_lo,
                                         f_hi, side)
    out_lo[index], out_hi[index] = lo, hi
    return result()


def quadratic_roots(a2: np.ndarray, a1: np.ndarray, a0: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray]:
    """The real roots q/a2 and a0/q of a2 x^2 + a1 x + a0, elementwise, by the stable
    formula q = -(a1 + sign(a1) sqrt(a1^2 - 4 a2 a0))/2 (no cancellation); nan where the
    discriminant is negative. Where a2 = 0 the second is the line's root -a0/a1 (the
    first is then infinite or nan)."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        q = -0.5 * (a1 + np.copysign(np.sqrt(a1 * a1 - 4.0 * a2 * a0), a1))
        return q / a2, a0 / q
