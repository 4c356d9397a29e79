"""sizer against a naive per-candidate baseline: dense sampling and bisection (issue 11).

    python benchmarks/bench_naive.py                  # 10 motors x 12 ratios x 15 laws

The problem is bench_engine's (benchmarks/synthetic.py ``book_problem``: rectangular
regions, inertial load, ideal gearbox with 12 ratios, minimize, dwell with return) on a
subset of the motors, where eq. (6.2) gives the exact T_min. The baseline is what one
writes first: for every candidate in a Python loop, the motor torque J_t k a(t) sampled
at SAMPLES points of each move (the law's samples computed once per law), its peak the
largest sample, its RMS by the trapezoidal rule over the cycle, and T_min by bisection
on that feasibility (BISECTIONS halvings of log T); then the best ratio per motor and law.

Goals: sizer at least 50 x faster than the baseline, and closer to the closed form
(the largest relative error of T_min over all motors and laws, both printed). Exits 1
when a goal is missed.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # this checkout's sizer
from bench_engine import closed_form
from synthetic import (
    BOOK_LAWS,
    DWELL,
    GEAR_INERTIA,
    LOAD_INERTIA,
    RATIOS,
    SPEED_MARGIN,
    TORQUE_MARGIN,
    H,
    book_problem,
    motor_id,
    spec_of,
)

from sizer.laws import make_law
from sizer.sizing import size_design

SAMPLES = 2001
BISECTIONS = 60
GOAL_FACTOR = 50.0


def naive_duration(v_n: np.ndarray, a_n: np.ndarray, tau: np.ndarray, J_t: float, k: float,
                   tau_c: float, tau_p: float, speed: float) -> float:
    """T_min of one candidate: bisection on the sampled checks (inf if none found)."""
    def feasible(T: float) -> bool:
        t = tau * T
        motor_speed = k * H / T * v_n
        torque = J_t * k * H / T**2 * a_n
        square = 2.0 * np.trapezoid(torque**2, t)  # the move and the return move
        rms = math.sqrt(square / (2.0 * (T + DWELL)))
        return (np.abs(motor_speed).max() <= speed * (1.0 - SPEED_MARGIN)
                and np.abs(torque).max() <= tau_p * (1.0 - TORQUE_MARGIN)
                and rms <= tau_c * (1.0 - TORQUE_MARGIN))

    lo, hi = math.log(1e-4), math.log(100.0)
    if not feasible(math.exp(hi)):
        return math.inf
    for _ in range(BISECTIONS):
        mid = 0.5 * (lo + hi)
        if feasible(math.exp(mid)):
            hi = mid
        else:
            lo = mid
    return math.exp(hi)


def naive_run(design) -> np.ndarray:
    """Best T_min per (law, motor) by the naive baseline."""
    tau = np.linspace(0.0, 1.0, SAMPLES)
    out = np.full((len(design.laws), len(design.motors)), np.inf)
    for j, spec in enumerate(design.laws):
        law = make_law(spec)
        v_n, a_n = law.velocity(tau), law.acceleration(tau)
        for i, m in enumerate(design.motors):
            for k in design.ratio_choice.ratios:
                J_t = m.inertia + GEAR_INERTIA + LOAD_INERTIA / k**2
                T = naive_duration(v_n, a_n, tau, J_t, k, m.continuous_torque,
                                   m.peak_torque, m.rated_speed)
                out[j, i] = min(out[j, i], T)
    return out


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--motors", type=int, default=10)
    args = parser.parse_args()
    design = book_problem(args.motors)
    laws = [make_law(s) for s in BOOK_LAWS]
    coefficients = np.array([[law.coefficients.C_v, law.coefficients.C_a,
                              law.coefficients.C_a_rms] for law in laws])
    motors = design.motors
    _, exact, _ = closed_form(coefficients, np.array([m.inertia for m in motors]),
                              np.array([m.continuous_torque for m in motors]),
                              np.array([m.peak_torque for m in motors]),
                              np.array([m.rated_speed for m in motors]), np.array(RATIOS))

    start = time.perf_counter()
    naive = naive_run(design)
    naive_seconds = time.perf_counter() - start
    size_design(book_problem(2))  # warm-up: law caches, imports
    start = time.perf_counter()
    result = size_design(design)
    sizer_seconds = time.perf_counter() - start

    law_index = {spec: j for j, spec in enumerate(BOOK_LAWS)}
    law_index.update({law.spec: j for j, law in enumerate(laws)})
    motor_index = {m.id: i for i, m in enumerate(motors)}
    sizer_T = np.full_like(exact, np.inf)
    for r in result.results:
        if r.feasible and r.duration is not None:
            sizer_T[law_index[spec_of(r)], motor_index[motor_id(r)]] = r.duration
    sizer_error = float(np.max(np.abs(sizer_T - exact) / exact))
    naive_error = float(np.max(np.abs(naive - exact) / exact))
    factor = naive_seconds / sizer_seconds
    candidates = len(motors) * len(RATIOS) * len(laws)
    rows = [
        ("naive baseline [s]", f"{naive_seconds:.2f}", "", True),
        ("sizer size_design [s]", f"{sizer_seconds:.2f}", "", True),
        ("naive / sizer", f"{factor:.2f}x", f">= {GOAL_FACTOR:g}x", factor >= GOAL_FACTOR),
        ("naive T_min max rel. error", f"{naive_error:.2e}", "", True),
        ("sizer T_min max rel. error", f"{sizer_error:.2e}", "< naive's",
         sizer_error < naive_error),
    ]
    print(f"bench_naive: {len(motors)} motors x {len(RATIOS)} ratios x {len(laws)} laws = "
          f"{candidates:,} candidates (bench_engine's problem); baseline: {SAMPLES} samples "
          f"per move, {BISECTIONS} bisections; errors against the closed form (eq. 6.2)")
    print(f"{'what':30s} {'measured':>10s}  {'goal':10s} verdict")
    for name, value, goal, ok in rows:
        print(f"{name:30s} {value:>10s}  {goal:10s} {'' if not goal else 'ok' if ok else 'MISSED'}")
    return 0 if all(ok for *_, ok in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
