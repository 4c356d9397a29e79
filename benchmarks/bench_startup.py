"""Time sizer's start-up against ``python -c "import numpy"`` (issue 11).

    python benchmarks/bench_startup.py --repeat 7

Runs, in fresh processes from the repository root, ``python -c "import numpy"``,
``python -m sizer --help`` and ``python -m sizer size`` of each book example, ``--repeat``
rounds with the commands interleaved (so that a busy machine slows them alike), and
prints the best wall time of each and its ratio to the numpy import. The goals: --help at
most 2x, each ``size`` at most 6x. Exits 1 if a goal is missed. Results are in
benchmarks/README.md.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BOOK = ("ex6_1-6_2", "ex6_3", "ex6_3-vmax4", "ex6_4", "ex6_5")


def timed(command: list[str]) -> float:
    """The wall time of one run of ``command`` (which must succeed)."""
    environment = {**os.environ, "PYTHONPATH": str(ROOT)}
    start = time.perf_counter()
    subprocess.run(command, check=True, cwd=ROOT, env=environment,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repeat", type=int, default=7, help="rounds (best of; default 7)")
    parser.add_argument("--examples", nargs="*", default=list(BOOK),
                        help="book examples to size (default: all five)")
    parser.add_argument("--help-goal", type=float, default=2.0)
    parser.add_argument("--size-goal", type=float, default=6.0)
    args = parser.parse_args()
    python = sys.executable
    commands: list[tuple[str, list[str], float | None]] = [
        ('python -c "import numpy"', [python, "-c", "import numpy"], None),
        ("sizer --help", [python, "-m", "sizer", "--help"], args.help_goal),
    ]
    for name in args.examples:
        path = f"examples/book/{name}.yaml"
        commands.append((f"sizer size {path}", [python, "-m", "sizer", "size", path],
                         args.size_goal))
    best = [float("inf")] * len(commands)
    for _ in range(args.repeat):
        for i, (_, command, _) in enumerate(commands):
            best[i] = min(best[i], timed(command))
    baseline = best[0]
    width = max(len(label) for label, _, _ in commands)
    print(f"{'command':{width}s} {'best [s]':>9s} {'x numpy':>8s} {'goal':>6s}  met")
    missed = 0
    for (label, _, goal), seconds in zip(commands, best, strict=True):
        ratio = seconds / baseline
        if goal is None:
            print(f"{label:{width}s} {seconds:9.3f} {ratio:8.2f}")
            continue
        met = ratio <= goal
        missed += not met
        print(f"{label:{width}s} {seconds:9.3f} {ratio:8.2f} {goal:5.1f}x  "
              f"{'yes' if met else 'NO'}")
    return 1 if missed else 0


if __name__ == "__main__":
    sys.exit(main())
