"""A cycle of segments against the task shorthand it equals (issue 12).

    python benchmarks/bench_cycle.py                  # 64 motors x 5 ratios x 5 laws
    python benchmarks/bench_cycle.py --motors 16

The synthetic scale problem (benchmarks/synthetic.py: speed-torque curves, friction,
damping, a constant load, an efficiency, a ratio chosen from a list) in minimize mode,
sized twice in the same run: as its task (move, dwell, return, dwell: the single-law
engine, its closed forms and bounds) and as the same cycle with its first dwell split in
two, which is no shorthand and goes segment by segment (sizer.sizing.segment_cycle: the
free moves' peak bounds, then the rounds on the cycle's RMS model, then the search).
Both give the same answers (tests/test_cycle_shorthand.py); this measures what the
segment engine costs. Goal: the cycle within 3x the task's time, measured in the same
run; the T_min equal to 1e-9. Exits 1 when a goal is missed.
"""

from __future__ import annotations

import argparse
import sys
import time
from dataclasses import replace
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # this checkout's sizer
from synthetic import RATIOS, SCALE_LAWS, scale_problem

from sizer.model.cycle import Cycle, Dwell, Move
from sizer.sizing import size_design

GOAL_RATIO = 3.0
GOAL_REL = 1e-9


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--motors", type=int, default=64)
    args = parser.parse_args()
    design = scale_problem(args.motors, laws=SCALE_LAWS[:5], ratios=RATIOS[:5])
    h, dwell = design.task.displacement, design.task.dwell
    cycle = Cycle((Move(h, None), Dwell(dwell / 3), Dwell(2 * dwell / 3), Move(-h, None),
                   Dwell(dwell)), closed=True)
    size_design(replace(design, motors=design.motors[:2]))  # imports and law caches warm
    size_design(replace(design, motors=design.motors[:2], cycle=cycle))
    start = time.perf_counter()
    plain = size_design(design)
    task_seconds = time.perf_counter() - start
    start = time.perf_counter()
    cycled = size_design(replace(design, cycle=cycle))
    cycle_seconds = time.perf_counter() - start
    by_key = {(r.motor, r.law_object.spec): r for r in plain.results}
    worst, same = 0.0, True
    for r in cycled.results:
        x = by_key[(r.motor, r.law_object.spec)]
        same &= r.feasible == x.feasible
        if x.feasible and r.feasible:
            worst = max(worst, abs(r.duration - 2 * (x.duration + dwell)) / r.duration)
    ratio = cycle_seconds / task_seconds
    print(f"bench_cycle: {args.motors} motors x {len(RATIOS[:5])} ratios x 5 laws, minimize")
    print(f"{'what':<36} {'measured':>10}  {'goal':<9} verdict")
    print(f"{'task (single-law engine) [s]':<36} {task_seconds:>10.2f}")
    print(f"{'cycle (segment engine) [s]':<36} {cycle_seconds:>10.2f}")
    print(f"{'cycle / task':<36} {ratio:>9.2f}x  <= {GOAL_RATIO:g}x    "
          f"{'ok' if ratio <= GOAL_RATIO else 'MISSED'}")
    print(f"{'T_min max rel. difference':<36} {worst:>10.2e}  <= {GOAL_REL:g}  "
          f"{'ok' if worst <= GOAL_REL and same else 'MISSED'}")
    return 0 if ratio <= GOAL_RATIO and worst <= GOAL_REL and same else 1


if __name__ == "__main__":
    sys.exit(main())
