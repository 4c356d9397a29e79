"""Time sizer's start-up against ``python -c "import numpy"`` (issues 11 and 34).

    python benchmarks/bench_startup.py --repeat 7

Runs, in fresh processes from the repository root, ``python -c "import numpy"``,
``python -m sizer --help`` and ``python -m sizer size`` of each book example, ``--repeat``
rounds with the commands interleaved (so that a busy machine slows them alike), and
prints the best wall time and the best CPU time (user + system) of each and their ratios
to the numpy import. The goals: --help at most 2x, each ``size`` at most 2.5x (issue 34;
issue 11's was 6x), judged on the CPU times (on a machine shared with other jobs the wall
times wait for the processor; ``--wall`` judges the wall times). Exits 1 if a goal is
missed. Results are in benchmarks/README.md. The children read their bytecode from a
private cache filled by one untimed round, as an installed sizer does
(benchmarks/bytecode_cache.py).

    python benchmarks/bench_startup.py --all --repeat 3

sizes every bundled example (examples/, examples/book/, examples/machines/) instead of the
book's five, each against the goal of issue 34, 5x (``--size-goal``). ``--against TREE``
also runs each sizer command from another source tree (say ``git archive BASE | tar -x -C
/tmp/base``), interleaved with this one's, on lines marked ``before:`` (not judged).

The sizer process runs numpy's BLAS on one thread (sizer.cli.process): the reference,
a plain ``import numpy``, starts OpenBLAS's workers, which spin until it exits (on two
cores about 0.05 s of its ~0.14 s of CPU). The second reference line is the same import
on one BLAS thread, and the last column each command's CPU ratio to it (not judged):
the cost of sizer's own imports and work, without the spin that the setting saves.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))

from bytecode_cache import bytecode_env  # noqa: E402

BOOK = ("ex6_1-6_2", "ex6_3", "ex6_3-vmax4", "ex6_4", "ex6_5")


def timed(command: list[str], env: dict[str, str], root: Path = ROOT,
          extra: dict[str, str] | None = None) -> tuple[float, float]:
    """The wall time and the CPU time (user + system) of one run of ``command`` in the
    source tree ``root`` (``extra``: more environment variables)."""
    environment = {**env, "PYTHONPATH": str(root), **(extra or {})}
    start = time.perf_counter()
    process = subprocess.Popen(command, cwd=root, env=environment,
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(process.pid, 0)
    wall = time.perf_counter() - start
    process.returncode = os.waitstatus_to_exitcode(status)
    if process.returncode != 0:
        raise SystemExit(f"failed ({process.returncode}): {' '.join(command)}")
    return wall, usage.ru_utime + usage.ru_stime


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repeat", type=int, default=7, help="rounds (best of; default 7)")
    parser.add_argument("--examples", nargs="*", default=list(BOOK),
                        help="book examples to size (default: all five)")
    parser.add_argument("--all", action="store_true",
                        help="size every bundled example, not only the book's")
    parser.add_argument("--help-goal", type=float, default=2.0)
    parser.add_argument("--size-goal", type=float, default=None,
                        help="the goal of each size (default: 2.5x, with --all 5x)")
    parser.add_argument("--against", type=Path, default=None, metavar="TREE",
                        help="also time each sizer command in this source tree")
    parser.add_argument("--wall", action="store_true",
                        help="judge the goals on wall time (default: CPU time, steadier on "
                             "a shared machine)")
    args = parser.parse_args()
    python = sys.executable
    commands: list[tuple[str, list[str], float | None, Path]] = [
        ('python -c "import numpy"', [python, "-c", "import numpy"], None, ROOT),
        ("  the same, one BLAS thread", [python, "-c", "import numpy"], None, ROOT),
        ("sizer --help", [python, "-m", "sizer", "--help"], args.help_goal, ROOT),
    ]
    one_thread = {"OPENBLAS_NUM_THREADS": "1"}
    paths = [f"examples/book/{name}.yaml" for name in args.examples]
    if args.all:
        paths = [str(path.relative_to(ROOT)) for folder in ("", "book", "machines")
                 for path in sorted((ROOT / "examples" / folder).glob("*.yaml"))]
    goal = args.size_goal or (5.0 if args.all else 2.5)
    for path in paths:
        commands.append((f"sizer size {path}", [python, "-m", "sizer", "size", path], goal,
                         ROOT))
    if args.against is not None:
        commands[2:] = [twin for label, command, goal, root in commands[2:] for twin in
                        ((f"before: {label}", command, None, args.against.resolve()),
                         (label, command, goal, root))]
    wall = [float("inf")] * len(commands)
    cpu = [float("inf")] * len(commands)
    with bytecode_env() as env:
        for i, (_, command, _, root) in enumerate(commands):
            timed(command, env, root, one_thread if i == 1 else None)  # untimed: the cache
        for _ in range(args.repeat):
            for i, (_, command, _, root) in enumerate(commands):
                seconds, used = timed(command, env, root, one_thread if i == 1 else None)
                wall[i], cpu[i] = min(wall[i], seconds), min(cpu[i], used)
    width = max(len(label) for label, *_ in commands)
    print(f"{'command':{width}s} {'wall [s]':>9s} {'x numpy':>8s} {'cpu [s]':>8s} "
          f"{'x numpy':>8s} {'x 1 thr':>8s} {'goal':>6s}  met")
    missed = 0
    for (label, _, goal, _), seconds, used in zip(commands, wall, cpu, strict=True):
        ratio, cpu_ratio = seconds / wall[0], used / cpu[0]
        line = (f"{label:{width}s} {seconds:9.3f} {ratio:8.2f} {used:8.3f} {cpu_ratio:8.2f} "
                f"{used / cpu[1]:8.2f}")
        if goal is None:
            print(line)
            continue
        met = (ratio if args.wall else cpu_ratio) <= goal
        missed += not met
        print(f"{line} {goal:5.1f}x  {'yes' if met else 'NO'}")
    return 1 if missed else 0


if __name__ == "__main__":
    sys.exit(main())
