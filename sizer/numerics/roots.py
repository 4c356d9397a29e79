"""Vectorized bracketed root finding (Chandrupatla's method)."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

MAX_STEPS = 60


def bracketed_root(f: Callable[..., np.ndarray], lo: np.ndarray, hi: np.ndarray,
                   f_lo: np.ndarray, f_hi: np.ndarray, xtol: float = 1e-15,
                   args: tuple[np.ndarray, ...] | None = None, bracket: bool = False):
    """Roots of f in [lo, hi] where f_lo and f_hi have opposite signs (elementwise), to a
    bracket no wider than xtol * max(1, |x|) (or two ulps).

    Chandrupatla's method (1997; the method of scipy.optimize.elementwise.find_root):
    each step reads f at a + t (b - a), a the newest point and b the other end of the
    bracket, t from inverse quadratic interpolation through the last three points where
    f looks smooth enough there (Chandrupatla's test on their spacing), else 1/2; t is
    kept a quarter of the stopping width from both ends, so the bracket shrinks at every
    step and closes on the root. About 8-12 evaluations reach machine precision where
    plain bisection takes 50, and no end lingers: the Illinois variant of regula falsi
    used before took up to 50 when one end's value was 1e7 times the other's (the RMS
    crossings of a cycle). Written here rather than imported: scipy.optimize's import
    costs about 0.2 s, the start-up of a whole sizing.

    ``f(x)`` is called on whole arrays; with ``args`` it is elementwise, called as
    ``f(x, *args)`` on the elements still open only (with their args). With ``bracket``
    the final (lo, hi) is returned instead of its midpoint: the end on the side of
    f_hi's sign stays there (a feasible end stays feasible).

    This is the project's root finder for functions without a derivative: the sizing
    engine and the laws' coefficient peaks (sizer.laws.coefficients) use it (a
    polynomial's roots, with its derivative at hand: sizer.sizing.move._bracketed).
    """
    lo, hi, f_lo, f_hi = (np.array(x, dtype=float) for x in (lo, hi, f_lo, f_hi))
    state = _Bracket.of(lo, hi, f_lo, f_hi)
    out_lo, out_hi = lo.copy(), hi.copy()
    index = np.arange(lo.size)
    compact = args is not None
    extra = tuple(np.asarray(a) for a in args) if args is not None else ()
    for _ in range(MAX_STEPS):
        low, high = state.ends()
        width = np.maximum(xtol * np.maximum(1.0, np.abs(low)), 2.0 * np.spacing(np.abs(high)))
        open_ = (high - low > width) & (state.fa != 0.0) & (state.fb != 0.0)
        out_lo[index], out_hi[index] = state.results()
        if not open_.any():
            break
        if compact and not open_.all():
            index, state, width = index[open_], state.take(open_), width[open_]
            extra = tuple(a[open_] for a in extra)
            open_ = np.ones(index.size, dtype=bool)
        x = state.trial(0.25 * width)
        fx = f(x, *extra) if compact else f(x)
        state = state.moved(x, fx, open_)
    else:
        out_lo[index], out_hi[index] = state.results()
    return (out_lo, out_hi) if bracket else 0.5 * (out_lo + out_hi)


class _Bracket:
    """Chandrupatla's state per element: the newest point a, the bracket's other end b,
    the point before c (their values fa, fb, fc), the next step's share t of b - a, and
    the sign of the original upper end's value (which end to return as hi)."""

    def __init__(self, a, b, c, fa, fb, fc, t, up) -> None:
        self.a, self.b, self.c, self.fa, self.fb, self.fc, self.t, self.up = \
            a, b, c, fa, fb, fc, t, up

    @classmethod
    def of(cls, lo, hi, f_lo, f_hi) -> _Bracket:
        return cls(lo, hi, lo, f_lo, f_hi, f_lo, np.full(lo.shape, 0.5), np.sign(f_hi))

    def take(self, keep: np.ndarray) -> _Bracket:
        a, b, c, fa, fb, fc, t, up = (v[keep] for v in (self.a, self.b, self.c, self.fa,
                                                        self.fb, self.fc, self.t, self.up))
        return _Bracket(a, b, c, fa, fb, fc, t, up)

    def ends(self) -> tuple[np.ndarray, np.ndarray]:
        return np.minimum(self.a, self.b), np.maximum(self.a, self.b)

    def results(self) -> tuple[np.ndarray, np.ndarray]:
        """(lo, hi): hi the end whose value has the original f_hi's sign; a root hit
        exactly is both."""
        a_up = np.sign(self.fa) == self.up
        lo, hi = np.where(a_up, self.b, self.a), np.where(a_up, self.a, self.b)
        zero = np.where(self.fa == 0.0, self.a, self.b)
        hit = (self.fa == 0.0) | (self.fb == 0.0)
        return np.where(hit, zero, lo), np.where(hit, zero, hi)

    def trial(self, margin: np.ndarray) -> np.ndarray:
        """The next point: a + t (b - a), t kept ``margin`` from both ends."""
        span = self.b - self.a
        with np.errstate(divide="ignore", invalid="ignore"):
            least = np.minimum(margin / np.abs(span), 0.5)
        least = np.where(np.isfinite(least), least, 0.5)
        return self.a + np.clip(self.t, least, 1.0 - least) * span

    def moved(self, x: np.ndarray, fx: np.ndarray, open_: np.ndarray) -> _Bracket:
        """The state after reading f(x) = fx (only where ``open_``)."""
        same = np.sign(fx) == np.sign(self.fa)  # x replaces a; else b becomes a
        c, fc = np.where(same, self.a, self.b), np.where(same, self.fa, self.fb)
        b, fb = np.where(same, self.b, self.a), np.where(same, self.fb, self.fa)
        a, fa = x, fx
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            xi = (a - b) / (c - b)
            phi = (fa - fb) / (fc - fb)
            smooth = (phi * phi < xi) & ((1.0 - phi) ** 2 < 1.0 - xi)
            t = (fa / (fb - fa) * fc / (fb - fc)
                 + (c - a) / (b - a) * fa / (fc - fa) * fb / (fc - fb))
        t = np.where(smooth & np.isfinite(t), t, 0.5)
        if open_.all():
            return _Bracket(a, b, c, fa, fb, fc, t, self.up)
        a, b, c, fa, fb, fc, t = (np.where(open_, new, old) for new, old in (
            (a, self.a), (b, self.b), (c, self.c), (fa, self.fa), (fb, self.fb),
            (fc, self.fc), (t, self.t)))
        return _Bracket(a, b, c, fa, fb, fc, t, self.up)


def first_passing(slack: Callable[[np.ndarray, np.ndarray], np.ndarray], lo: np.ndarray,
                  f_lo: np.ndarray, doublings: int = 30, xtol: float = 1e-12) -> np.ndarray:
    """Per element, the smallest x >= ``lo`` where ``slack(x, index) >= 0`` (``index``: the
    elements x is for), a slack that grows with x: ``lo`` itself where ``f_lo`` (its slack)
    passes, else x doubled until it passes (at most ``doublings`` times) and the crossing
    bracketed by :func:`bracketed_root` to ``xtol``, its passing end returned; inf where no
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

        _, top = bracketed_root(f, lo[found], hi[found], f_lo[found], f_hi[found], xtol,
                                args=(np.arange(found.size),), bracket=True)
        out[found] = top
    return out


def quadratic_roots(a2: np.ndarray, a1: np.ndarray, a0: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray]:
    """The real roots q/a2 and a0/q of a2 x^2 + a1 x + a0, elementwise, by the stable
    formula q = -(a1 + sign(a1) sqrt(a1^2 - 4 a2 a0))/2 (no cancellation); nan where the
    discriminant is negative. Where a2 = 0 the second is the line's root -a0/a1 (the
    first is then infinite or nan)."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        q = -0.5 * (a1 + np.copysign(np.sqrt(a1 * a1 - 4.0 * a2 * a0), a1))
        return q / a2, a0 / q
