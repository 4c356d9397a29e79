"""Every bundled example sized from the command line in two source trees, alternately.

Run from the repository root, with a checkout (or `git archive`) of another commit:

    git archive BASE | tar -x -C /tmp/base
    python benchmarks/bench_compare_trees.py /tmp/base [--only WORD ...]

Each example is run as `python -m sizer size EXAMPLE` from the other tree (``before``) and
then from this one (``after``), one run each, so that both see the same load; the table
gives the wall and the CPU seconds (user + system) of each run. On a loaded host the CPU
time is the steadier figure.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))

from bench_examples import _children_cpu, example_files  # noqa: E402


def timed(tree: Path, args: list[str]) -> tuple[float, float]:
    """(wall seconds, CPU seconds) of one run of python ``args`` in ``tree``."""
    start, used = time.perf_counter(), _children_cpu()
    subprocess.run([sys.executable, *args], cwd=tree, check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    return time.perf_counter() - start, _children_cpu() - used


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("before", type=Path, help="the other tree (its root)")
    parser.add_argument("--only", nargs="*", default=None,
                        help="only the examples whose file name contains one of these")
    options = parser.parse_args()
    examples = example_files(options.only)
    print(f"{'example':45s} {'before wall':>11s} {'cpu':>6s} {'after wall':>11s} {'cpu':>6s}")
    wall, cpu = timed(ROOT, ["-c", "import numpy"])
    reference = 'python -c "import numpy"'
    print(f"{reference:45s} {'':>11s} {'':>6s} {wall:11.3f} {cpu:6.3f}", flush=True)
    for path in examples:
        name = str(path.relative_to(ROOT))
        if not (options.before / name).exists():  # new in this tree: nothing to compare
            print(f"{name:45s} {'(new)':>11s}", flush=True)
            continue
        before = timed(options.before, ["-m", "sizer", "size", name])
        after = timed(ROOT, ["-m", "sizer", "size", name])
        print(f"{name:45s} {before[0]:11.3f} {before[1]:6.3f} {after[0]:11.3f} "
              f"{after[1]:6.3f}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
