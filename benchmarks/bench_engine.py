"""sizer's engine against a plain numpy closed form of the same problem (issue 11).

    python benchmarks/bench_engine.py                 # 300 motors x 12 ratios x 15 laws

The book's case of eq. (6.2): rectangular regions (ratings only, envelope ``book``), an
inertial load through an ideal gearbox whose ratio is chosen from a list of 12, minimize
mode, a cycle with dwell and return move, torque margin 10 %, speed margin 5 %
(benchmarks/synthetic.py). The closed form, vectorized over all motors x ratios x laws:

    T_min = max(C_v k h / w_n', sqrt(C_a J_t k h / tau_p'), T_rms),
    T_rms^3 (T_rms + t_dwell) = (J_t k h C_a_rms / tau_c')^2      (Newton on log T)

with J_t = J_m + J_gear + J_l / k^2 and the margins applied to the ratings (w_n', tau_p',
tau_c'); per motor and law the best ratio is the one with the smallest T_min. Both sides
get the laws' coefficients for free: the closed form reads them from the law objects
built before the clock starts, and sizer is run once on a 2-motor design with the same
laws before it is timed.

Goals: sizer's time <= 20 x the closed form's, measured in the same run; T_min equal to
1e-9 (relative), feasibility and the best ratio equal. Exits 1 when a goal is missed.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # this checkout's sizer
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

GOAL_RATIO = 20.0
GOAL_REL = 1e-9


def rms_duration(scale: np.ndarray, dwell: float) -> np.ndarray:
    """Smallest T with T^3 (T + dwell) = scale^2, by Newton on u = log T (g' in [3, 4])."""
    log_target = 2.0 * np.log(scale)
    u = (log_target - np.log(np.sqrt(scale) + dwell)) / 3.0  # exact for dwell 0 or T << dwell
    for _ in range(50):  # quadratic: after a step below 1e-8, one more reaches rounding
        T = np.exp(u)
        g = 3.0 * u + np.log(T + dwell) - log_target
        step = g / (3.0 + T / (T + dwell))
        u = u - step
        if np.max(np.abs(step)) < 1e-8:
            T = np.exp(u)
            u = u - (3.0 * u + np.log(T + dwell) - log_target) / (3.0 + T / (T + dwell))
            break
    return np.exp(u)


def closed_form(coefficients: np.ndarray, inertia: np.ndarray, tau_c: np.ndarray,
                tau_p: np.ndarray, speed: np.ndarray, ratios: np.ndarray):
    """T_min (laws, motors, ratios), then per law and motor the best T_min and ratio index.

    ``coefficients`` is (laws, 3): C_v, C_a, C_a_rms.
    """
    c_v, c_a, c_a_rms = (coefficients[:, i, None, None] for i in range(3))
    k = ratios[None, None, :]
    J_t = inertia[None, :, None] + GEAR_INERTIA + LOAD_INERTIA / k**2
    w_n = speed[None, :, None] * (1.0 - SPEED_MARGIN)
    t_p = tau_p[None, :, None] * (1.0 - TORQUE_MARGIN)
    t_c = tau_c[None, :, None] * (1.0 - TORQUE_MARGIN)
    T_v = c_v * k * H / w_n
    T_a = np.sqrt(c_a * J_t * k * H / t_p)
    T_r = rms_duration(J_t * k * H * c_a_rms / t_c, DWELL)
    T = np.maximum(np.maximum(T_v, T_a), T_r)
    best = np.argmin(T, axis=2)
    return T, np.take_along_axis(T, best[..., None], axis=2)[..., 0], best


def timed(function, repeat: int) -> tuple[float, object]:
    """The best of ``repeat`` runs (seconds) and the last result."""
    best, out = float("inf"), None
    for _ in range(repeat):
        start = time.perf_counter()
        out = function()
        best = min(best, time.perf_counter() - start)
    return best, out


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--motors", type=int, default=300)
    parser.add_argument("--repeat", type=int, default=1, help="sizer runs (best is kept)")
    args = parser.parse_args()
    design = book_problem(args.motors)
    laws = [make_law(s) for s in BOOK_LAWS]
    coefficients = np.array([[law.coefficients.C_v, law.coefficients.C_a,
                              law.coefficients.C_a_rms] for law in laws])
    motors = design.motors
    inertia = np.array([m.inertia for m in motors])
    tau_c = np.array([m.continuous_torque for m in motors])
    tau_p = np.array([m.peak_torque for m in motors])
    speed = np.array([m.rated_speed for m in motors])
    ratios = np.array(RATIOS)

    def numpy_run():
        return closed_form(coefficients, inertia, tau_c, tau_p, speed, ratios)

    numpy_seconds, (_, T_best, best) = timed(numpy_run, 20)
    size_design(book_problem(2))  # warm-up: law caches, imports
    sizer_seconds, result = timed(lambda: size_design(design), args.repeat)

    law_index = {spec: j for j, spec in enumerate(BOOK_LAWS)}
    law_index.update({law.spec: j for j, law in enumerate(laws)})
    motor_index = {m.id: i for i, m in enumerate(motors)}
    worst_rel, infeasible, wrong_ratio, seen = 0.0, 0, 0, 0
    T_all = numpy_run()[0]
    for r in result.results:
        j, i = law_index[spec_of(r)], motor_index[motor_id(r)]
        seen += 1
        if not r.feasible or r.duration is None:
            infeasible += 1
            continue
        worst_rel = max(worst_rel, abs(r.duration - T_best[j, i]) / T_best[j, i])
        chosen = int(np.argmin(np.abs(ratios - r.ratio)))
        if chosen != best[j, i] and abs(T_all[j, i, chosen] - T_best[j, i]) > \
                GOAL_REL * T_best[j, i]:
            wrong_ratio += 1
    expected = len(motors) * len(laws)
    factor = sizer_seconds / numpy_seconds
    rows = [
        ("closed form (numpy) [s]", f"{numpy_seconds:.4f}", "", True),
        ("sizer size_design [s]", f"{sizer_seconds:.3f}", "", True),
        ("sizer / closed form", f"{factor:.0f}x", f"<= {GOAL_RATIO:g}x", factor <= GOAL_RATIO),
        ("T_min max rel. difference", f"{worst_rel:.2e}", f"<= {GOAL_REL:g}",
         worst_rel <= GOAL_REL),
        ("results (motor x law)", f"{seen}", f"= {expected}", seen == expected),
        ("infeasible (closed form: 0)", f"{infeasible}", "= 0", infeasible == 0),
        ("best ratio differs", f"{wrong_ratio}", "= 0", wrong_ratio == 0),
    ]
    print(f"bench_engine: {len(motors)} motors x {len(ratios)} ratios x {len(laws)} laws = "
          f"{len(motors) * len(ratios) * len(laws):,} candidates, minimize, rectangular "
          f"regions, inertial load, dwell {DWELL} s with return")
    print(f"{'what':30s} {'measured':>10s}  {'goal':12s} verdict")
    for name, value, goal, ok in rows:
        print(f"{name:30s} {value:>10s}  {goal:12s} {'' if not goal else 'ok' if ok else 'MISSED'}")
    return 0 if all(ok for *_, ok in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
