"""Every bundled example sized from the command line, timed (issue 11: each under 1 s).

Run from the repository root:

    python benchmarks/bench_examples.py [--repeat 3] [--goal 1.0]

Each example is run as `python -m sizer size EXAMPLE` in a subprocess, best of --repeat;
`python -c "import numpy"` is timed the same way in the same run, and the table gives both
the seconds and the ratio to it (the machine is shared: the ratio is the steadier figure).
Exits 1 when an example takes longer than --goal seconds.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def best_time(args: list[str], repeat: int) -> float:
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        subprocess.run(args, cwd=ROOT, check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
        best = min(best, time.perf_counter() - start)
    return best


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--goal", type=float, default=1.0, help="seconds per example")
    options = parser.parse_args()
    examples = sorted((ROOT / "examples").glob("*.yaml")) + \
        sorted((ROOT / "examples" / "book").glob("*.yaml"))
    numpy = best_time([sys.executable, "-c", "import numpy"], options.repeat)
    print(f"{'example':45s} {'seconds':>8s} {'x numpy':>8s}")
    reference = 'python -c "import numpy"'
    print(f"{reference:45s} {numpy:8.3f} {1.0:8.1f}")
    slow = 0
    for path in examples:
        seconds = best_time([sys.executable, "-m", "sizer", "size", str(path)], options.repeat)
        slow += seconds > options.goal
        name = str(path.relative_to(ROOT))
        print(f"{name:45s} {seconds:8.3f} {seconds / numpy:8.1f}"
              f"{'  over the goal' if seconds > options.goal else ''}")
    return 1 if slow else 0


if __name__ == "__main__":
    sys.exit(main())
