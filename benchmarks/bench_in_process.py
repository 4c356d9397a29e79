"""One design sized in process: the best of N runs of size_design after a warm one.

    python benchmarks/bench_in_process.py examples/press-slider-crank-cycle.yaml 30

To compare two source trees, run it alternately with PYTHONPATH set to each tree's root
(the CLI's start-up, a few hundred ms on a shared host, is left out of the figure).
"""

from __future__ import annotations

import argparse
import time

import sizer.api as api
from sizer.sizing import size_design


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("design")
    parser.add_argument("runs", type=int, nargs="?", default=20)
    args = parser.parse_args()
    design = api.load(args.design)
    size_design(design)  # warm: the laws' analyses are cached per law
    best = float("inf")
    for _ in range(args.runs):
        start = time.perf_counter()
        size_design(design)
        best = min(best, time.perf_counter() - start)
    print(f"{args.design}: size_design best of {args.runs}: {best * 1000:.1f} ms")


if __name__ == "__main__":
    main()
