"""A cycle with moves between boundary speeds against the same strokes rest-to-rest (issue 34).

    python benchmarks/bench_boundary_moves.py                # 64 motors, best of 3
    python benchmarks/bench_boundary_moves.py --motors 16 --repeat 5

The flying saw (examples/flying-saw.yaml: accelerate to the line speed, run with it while
cutting, stop, return, wait) on the synthetic motors of benchmarks/synthetic.py (speed-torque
curves), minimized, sized twice in the same run, alternately, CPU time (best of --repeat):

- as given: two moves meet the line's speed, so each candidate's move is its own piecewise
  polynomial (sizer.sizing.move.polynomial_move), and the search starts from the bound of
  those moves' peak checks (SegmentCycle.peak_bound);
- the reference: the same strokes rest-to-rest (the run a fixed move of its length and
  duration), each move one move of the single-law engine.

Prints the ratio (goal <= 3x) and the time per motor. Exits 1 when the goal is missed.
"""

from __future__ import annotations

import argparse
import sys
import time
from dataclasses import replace
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # this checkout's sizer
from synthetic import curved_motors

from sizer.io.loader import load_design
from sizer.model.cycle import Move, Run
from sizer.sizing import size_design

ROOT = Path(__file__).resolve().parents[1]
GOAL_RATIO = 3.0


def designs(motors: int):
    """(the flying saw on ``motors`` synthetic motors, the same strokes rest-to-rest)."""
    saw = load_design(ROOT / "examples" / "flying-saw.yaml")
    saw = replace(saw, motors=curved_motors(motors))
    segments = []
    for s in saw.machine_cycle.segments:
        if isinstance(s, Move):
            segments.append(replace(s, start_speed=0.0, end_speed=0.0))
        elif isinstance(s, Run):
            segments.append(Move(s.speed * s.duration, s.duration, load=s.load, name=s.name))
        else:
            segments.append(s)
    rest = replace(saw, cycle=replace(saw.machine_cycle, segments=tuple(segments)))
    return saw, rest


def cpu(design) -> float:
    start = time.process_time()
    size_design(design)
    return time.process_time() - start


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--motors", type=int, default=64)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    saw, rest = designs(args.motors)
    for d in (saw, rest):  # imports and law caches warm
        size_design(replace(d, motors=d.motors[:2]))
    boundary, reference = [], []
    for _ in range(args.repeat):
        boundary.append(cpu(saw))
        reference.append(cpu(rest))
    b, r = min(boundary), min(reference)
    ratio = b / r
    print(f"bench_boundary_moves: flying saw, {args.motors} motors x "
          f"{len(saw.laws)} laws, minimize, best of {args.repeat} (CPU)")
    print(f"{'what':<40} {'measured':>10}  {'goal':<9} verdict")
    print(f"{'rest-to-rest strokes [s]':<40} {r:>10.3f}")
    print(f"{'boundary-speed moves [s]':<40} {b:>10.3f}")
    print(f"{'boundary-speed moves per motor [ms]':<40} {1e3 * b / args.motors:>10.1f}")
    print(f"{'boundary / rest-to-rest':<40} {ratio:>9.2f}x  <= {GOAL_RATIO:g}x    "
          f"{'ok' if ratio <= GOAL_RATIO else 'MISSED'}")
    return 0 if ratio <= GOAL_RATIO else 1


if __name__ == "__main__":
    sys.exit(main())
