"""Every bundled example sized from the command line, timed (issue 11: each under 1 s).

Run from the repository root:

    python benchmarks/bench_examples.py [--repeat 3] [--goal 1.0]

Each example is run as `python -m sizer size EXAMPLE` in a subprocess, best of --repeat;
`python -c "import numpy"` is timed the same way in the same run, and the table gives both
the seconds and the ratio to it (the machine is shared: the ratio is the steadier figure),
and the CPU seconds (user + system) of the run that was fastest: on a loaded host the wall
time can be several times the CPU time. ``--only`` times the examples whose file name
contains one of the given words. Exits 1 when an example takes longer than --goal seconds
(wall time).

The runs write and read bytecode as an installed sizer does, whatever the environment
says (a host that sets PYTHONDONTWRITEBYTECODE would otherwise compile every module of
sizer on every run): into a private cache (PYTHONPYCACHEPREFIX, a temporary folder), filled
by one untimed run of each command first.
"""

from __future__ import annotations

import argparse
import resource
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))

from bytecode_cache import bytecode_env  # noqa: E402


def _children_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def best_time(args: list[str], repeat: int, env: dict[str, str]) -> tuple[float, float]:
    """(wall seconds, CPU seconds) of the fastest of ``repeat`` runs, after one untimed
    run (it fills the bytecode cache)."""
    def run() -> None:
        subprocess.run(args, cwd=ROOT, check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL, env=env)

    run()
    best, cpu = float("inf"), float("nan")
    for _ in range(repeat):
        start, used = time.perf_counter(), _children_cpu()
        run()
        wall = time.perf_counter() - start
        if wall < best:
            best, cpu = wall, _children_cpu() - used
    return best, cpu


def example_files(only: list[str] | None) -> list[Path]:
    """The bundled examples (the book's last), those whose name holds a word of ``only``."""
    examples = sorted((ROOT / "examples").glob("*.yaml")) + \
        sorted((ROOT / "examples" / "book").glob("*.yaml"))
    if only:
        examples = [p for p in examples if any(word in p.name for word in only)]
    return examples


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--goal", type=float, default=1.0, help="seconds per example")
    parser.add_argument("--only", nargs="*", default=None,
                        help="time only the examples whose file name contains one of these")
    options = parser.parse_args()
    with bytecode_env() as env:
        return _run(options, env)


def _run(options: argparse.Namespace, env: dict[str, str]) -> int:
    examples = example_files(options.only)
    numpy, numpy_cpu = best_time([sys.executable, "-c", "import numpy"], options.repeat, env)
    print(f"{'example':45s} {'seconds':>8s} {'x numpy':>8s} {'cpu [s]':>8s}")
    reference = 'python -c "import numpy"'
    print(f"{reference:45s} {numpy:8.3f} {1.0:8.1f} {numpy_cpu:8.3f}")
    slow = 0
    for path in examples:
        seconds, cpu = best_time([sys.executable, "-m", "sizer", "size", str(path)],
                                 options.repeat, env)
        slow += seconds > options.goal
        name = str(path.relative_to(ROOT))
        print(f"{name:45s} {seconds:8.3f} {seconds / numpy:8.1f} {cpu:8.3f}"
              f"{'  over the goal' if seconds > options.goal else ''}")
    return 1 if slow else 0


if __name__ == "__main__":
    sys.exit(main())
