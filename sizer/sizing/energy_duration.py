"""The shortest move duration at which the energy and heat checks pass (minimize mode).

T_min is searched on the checks of the cycle (sizer.sizing.minimum_duration); where the
winding temperature rise or the braking resistor's power (sizer.sizing.energy_check)
fails there, a longer move is tried: both fall as the move slows (the torques fall as
1/T^2, the speeds and the returned energy per cycle as 1/T, the cycle grows), so the
first duration at which both pass is bracketed by doubling T from T_min and found by the
project's root finder (sizer.numerics.roots.illinois) on the smaller of the two slacks.
The heat check's slack may jump where the rule switches from the RMS-equivalent rise to
the winding model (book sec. 6.1.1, footnote: the cycle against 1/10 of tau_th); the
root finder keeps a passing end, so the duration returned passes.
"""

from __future__ import annotations

import numpy as np

from sizer.model.domain import Design
from sizer.numerics.roots import illinois
from sizer.sizing.checks import TOLERANCE
from sizer.sizing.cycle import CycleCalculator
from sizer.sizing.energy_check import energy_checks, without_power_figures

DOUBLINGS = 30
"""How far past T_min a passing duration is looked for: T_min 2^30."""

XTOL = 1e-12
"""Relative width of the final bracket of the duration."""


def energy_slack(design: Design, calculator: CycleCalculator, duration: np.ndarray,
                 rows: np.ndarray) -> np.ndarray:
    """The smallest slack of the energy and heat checks of the candidates at ``rows`` of
    ``calculator``, each moving in its ``duration``; >= 0 where both pass (with the
    checks' tolerance)."""
    sub = calculator.take(rows)
    T = np.asarray(duration, dtype=float)
    metrics = sub.evaluate(T)
    with without_power_figures():
        energy = energy_checks(design, sub, T, metrics, np.ones(len(rows), dtype=bool),
                               False)
    if energy is None or not energy.checks:
        return np.full(len(rows), np.inf)
    return np.min([check.slack for check in energy.checks], axis=0) + TOLERANCE


def energy_duration(design: Design, calculator: CycleCalculator, duration: np.ndarray,
                    slack: np.ndarray | None = None) -> np.ndarray:
    """Per candidate, the smallest duration >= ``duration`` at which the energy and heat
    checks pass; inf where none does up to ``duration`` 2^DOUBLINGS. ``slack``: that of
    :func:`energy_slack` at ``duration`` where the caller has it (else evaluated)."""
    lo = np.array(duration, dtype=float)
    n = len(lo)
    f_lo = np.array(slack, dtype=float) if slack is not None \
        else energy_slack(design, calculator, lo, np.arange(n))
    out = np.where(f_lo >= 0.0, lo, np.inf)
    hi, f_hi = np.full(n, np.nan), np.full(n, np.nan)
    todo = np.flatnonzero(f_lo < 0.0)
    for _ in range(DOUBLINGS):
        if not todo.size:
            break
        trial = 2.0 * lo[todo]
        slack = energy_slack(design, calculator, trial, todo)
        passed = slack >= 0.0
        hi[todo[passed]], f_hi[todo[passed]] = trial[passed], slack[passed]
        lo[todo[~passed]], f_lo[todo[~passed]] = trial[~passed], slack[~passed]
        todo = todo[~passed]
    found = np.flatnonzero(np.isfinite(hi) & ~np.isfinite(out))
    if found.size:
        def f(x: np.ndarray, index: np.ndarray) -> np.ndarray:
            return energy_slack(design, calculator, x, found[index])

        _, top = illinois(f, lo[found], hi[found], f_lo[found], f_hi[found], XTOL,
                          args=(np.arange(found.size),), bracket=True)
        out[found] = top
    return out
