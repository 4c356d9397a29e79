"""Time the batch time-optimal double S against Ruckig called in a loop (CPU time, one run).

    python benchmarks/bench_double_s.py --problems 10000 --repeat 5

Issue 34's row "batch time-optimal double S": sizer.sizing.optimal_shapes.optimal_double_s
on N random rest-to-rest problems (h, v_max, a_max, j_max log-uniform, no RMS bound:
book sec. 3.4.3, every case present) against Ruckig (the `ruckig` package) computing the
same time-optimal durations one problem at a time in a Python loop, as
tests/reference_values.py's ruckig_duration does but with one Ruckig, InputParameter and
Trajectory reused (only the target and the limits set per problem). Also timed: the
search optimal_double_s used before the closed form (searched_double_s). Each figure is
the best of --repeat runs; the max relative difference of T to Ruckig's is printed.
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from ruckig import InputParameter, Result, Ruckig, Trajectory

from sizer.sizing.optimal_shapes import BoundScales, optimal_double_s, searched_double_s

LOW = 5e-11  # the open ends alpha, beta -> 0 inset as in sizer.sizing.choices


def problems(n: int, seed: int = 1) -> tuple[np.ndarray, ...]:
    rng = np.random.default_rng(seed)
    return (10 ** rng.uniform(-2, 1, n), 10 ** rng.uniform(-1, 1, n),
            10 ** rng.uniform(-1, 2, n), 10 ** rng.uniform(-1, 3, n))


def ruckig_loop(h, v, a, j) -> np.ndarray:
    otg, inp, trajectory = Ruckig(1), InputParameter(1), Trajectory(1)
    inp.current_position = [0.0]
    out = np.empty(len(h))
    for i, (hh, vv, aa, jj) in enumerate(zip(h.tolist(), v.tolist(), a.tolist(), j.tolist(),
                                             strict=True)):
        inp.target_position = [hh]
        inp.max_velocity, inp.max_acceleration, inp.max_jerk = [vv], [aa], [jj]
        if otg.calculate(inp, trajectory) != Result.Working:
            raise RuntimeError(f"ruckig failed on problem {i}")
        out[i] = trajectory.duration
    return out


def best_of(repeat: int, run) -> tuple[float, object]:
    best, result = float("inf"), None
    for _ in range(repeat):
        start = time.process_time()
        result = run()
        best = min(best, time.process_time() - start)
    return best, result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--problems", type=int, default=10000)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    h, v, a, j = problems(args.problems)
    zero = np.zeros(len(h))
    scales = BoundScales(h / v, h / a, zero, h / j, 0.0, np.ones(len(h), bool))
    n = args.problems
    t_sizer, solution = best_of(args.repeat, lambda: optimal_double_s(scales, LOW, LOW))
    t_ruckig, reference = best_of(args.repeat, lambda: ruckig_loop(h, v, a, j))
    t_search, (_, searched) = best_of(1, lambda: searched_double_s(scales, LOW, LOW, 0.5, 0.5))
    difference = np.max(np.abs(solution.duration / reference - 1.0))
    to_search = np.max(np.abs(solution.duration / searched - 1.0))
    print(f"{n} problems, CPU time, best of {args.repeat}")
    print(f"optimal_double_s (closed form)  {1e6 * t_sizer / n:9.3f} us per solve")
    print(f"ruckig in a Python loop         {1e6 * t_ruckig / n:9.3f} us per solve")
    print(f"searched_double_s (before)      {1e6 * t_search / n:9.3f} us per solve (1 run)")
    print(f"ratio closed form / ruckig      {t_sizer / t_ruckig:9.4f}  "
          f"(ruckig / closed form {t_ruckig / t_sizer:.1f}x)")
    print(f"ratio searched / ruckig         {t_search / t_ruckig:9.2f}")
    print(f"max |T / T_ruckig - 1|          {difference:9.2e}")
    print(f"max |T / T_searched - 1|        {to_search:9.2e}")


if __name__ == "__main__":
    main()
