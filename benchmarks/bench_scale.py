"""sizer at catalog scale: 10,000 motors x 12 ratios x 20 laws, minimize (issue 11).

    python benchmarks/bench_scale.py                  # 2.4 M candidates
    python benchmarks/bench_scale.py --motors 20      # smaller; the time is extrapolated
    python benchmarks/bench_scale.py --progress       # laws done so far, on stderr

Every motor has intermittent and continuous speed-torque curves; the load has friction,
damping and a constant torque, the gearbox an efficiency of 0.95 and a ratio chosen from
12; the cycle is move, dwell 0.15 s, return, dwell (benchmarks/synthetic.py). The sizing
runs in a child process (the design is built there before the clock starts), so that its
peak resident memory is measured alone (its own ru_maxrss, imports included). With worker
processes (``--workers``, default size_design's auto: every CPU at full size) the memory
judged is the sizing process's peak plus the peak of each process below it (the workers
and their forkserver, read from /proc while it runs): every process at its peak at once,
an upper bound.

Goals: size_design <= 10 s and peak memory <= 1 GB for 10,000 motors. With --motors N
below that, the time is extrapolated linearly to 10,000 motors (labelled so) and judged;
the memory is judged as measured. Exits 1 when a goal is missed.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import threading
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
FULL = 10_000
GOAL_SECONDS = 10.0
GOAL_BYTES = 1 << 30
POLL = 0.25
"""Seconds between two readings of the worker processes (each a scan of /proc)."""


class Descendants(threading.Thread):
    """Polls the processes below this one (the worker pool's, started by a forkserver:
    not this process's children, so getrusage does not see them) for their peak
    resident memory (VmHWM) and CPU time, the last values read per process (Linux)."""

    def __init__(self) -> None:
        super().__init__(daemon=True)
        self.peak: dict[int, int] = {}
        self.cpu: dict[int, float] = {}
        self._done = threading.Event()

    def run(self) -> None:
        while not self._done.wait(POLL):
            self.read()

    def stop(self) -> None:
        self._done.set()
        self.join()

    def read(self) -> None:
        parent: dict[int, int] = {}
        for entry in Path("/proc").iterdir():
            if entry.name.isdigit():
                try:
                    fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
                except OSError:
                    continue
                parent[int(entry.name)] = int(fields[1])
        mine, me = set(), os.getpid()
        for pid in parent:
            up = parent.get(pid)
            while up is not None and up > 1:
                if up == me:
                    mine.add(pid)
                    break
                up = parent.get(up)
        tick = os.sysconf("SC_CLK_TCK")
        for pid in mine:
            try:
                status = Path(f"/proc/{pid}/status").read_text()
                fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
            except OSError:
                continue
            for line in status.splitlines():
                if line.startswith("VmHWM:"):
                    self.peak[pid] = int(line.split()[1]) * 1024
            self.cpu[pid] = (int(fields[11]) + int(fields[12])) / tick


def child(motors: int, verbose: bool, workers: int | None) -> None:
    """Build the design, size it, print the seconds, the result count and the peak
    memory of the worker processes as JSON."""
    sys.path[:0] = [str(HERE), str(HERE.parent)]  # this checkout's sizer, not an installed one
    from synthetic import RATIOS, SCALE_LAWS, scale_problem

    from sizer.sizing import size_design

    design = scale_problem(motors)
    start, cpu = time.perf_counter(), time.process_time()

    def progress(done: int, total: int) -> None:  # on stderr, for a long run
        print(f"  {done}/{total} laws, {time.perf_counter() - start:.1f} s", file=sys.stderr,
              flush=True)

    from sizer.sizing.engine import worker_count

    count = worker_count(workers, motors * len(RATIOS), len(SCALE_LAWS))
    watch = Descendants()
    if count > 1:  # (a poll costs the sizing a little: not where there is nothing to see)
        watch.start()
    result = size_design(design, progress=progress if verbose else None, workers=count)
    seconds = time.perf_counter() - start
    if count > 1:
        watch.stop()
    cpu = time.process_time() - cpu
    results, feasible = len(result.results), sum(r.feasible for r in result.results)
    # this process's own peak with every result row built, as a report of them all would
    print(json.dumps({"seconds": seconds, "cpu": cpu, "workers": count,
                      "descendants_peak": sum(watch.peak.values()),
                      "descendants_cpu": sum(watch.cpu.values()),
                      "own_peak": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024,
                      "results": results, "feasible": feasible,
                      "candidates": motors * len(RATIOS) * len(SCALE_LAWS)}))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--motors", type=int, default=FULL)
    parser.add_argument("--progress", action="store_true", help="laws done, on stderr")
    parser.add_argument("--workers", type=int, default=None,
                        help="processes sizing the laws (default: size_design's auto, "
                             "every CPU at this size)")
    parser.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        child(args.motors, args.progress, args.workers)
        return 0
    command = [sys.executable, __file__, "--child", "--motors", str(args.motors)]
    if args.workers is not None:
        command += ["--workers", str(args.workers)]
    run = subprocess.run(command + (["--progress"] if args.progress else []),
                         stdout=subprocess.PIPE, text=True, check=False)
    if run.returncode != 0:
        print(run.stdout, file=sys.stderr)
        return 2
    figures = json.loads(run.stdout.strip().splitlines()[-1])
    # every process at its own peak at once (an upper bound): the sizing process and the
    # processes below it (the workers and their forkserver)
    peak = figures["own_peak"] + figures["descendants_peak"]
    seconds = figures["seconds"]
    full = args.motors >= FULL
    judged = seconds if full else seconds * FULL / args.motors
    print(f"bench_scale: {args.motors} motors x 12 ratios x 20 laws = "
          f"{figures['candidates']:,} candidates, minimize, curves, friction, damping, "
          f"constant load, efficiency 0.95, dwell with return")
    print(f"{'what':40s} {'measured':>12s}  {'goal':10s} verdict")
    rows = [("size_design [s]", f"{seconds:.2f}", "", True),
            ("processes sizing the laws", f"{figures['workers']}", "", True),
            ("size_design, CPU time of the process [s]", f"{figures['cpu']:.2f}", "", True),
            ("CPU time of the worker processes [s]", f"{figures['descendants_cpu']:.2f}", "",
             True)]
    if not full:
        rows.append((f"extrapolated to {FULL:,} motors [s] (linear)", f"{judged:.0f}",
                     f"<= {GOAL_SECONDS:g}", judged <= GOAL_SECONDS))
    else:
        rows[0] = ("size_design [s]", f"{seconds:.2f}", f"<= {GOAL_SECONDS:g}",
                   seconds <= GOAL_SECONDS)
    rows += [("peak memory, all processes [MiB]", f"{peak / 2**20:.0f}",
              f"<= {GOAL_BYTES / 2**20:.0f}", peak <= GOAL_BYTES),
             ("results (motor x law)", f"{figures['results']}", "", True),
             ("feasible results", f"{figures['feasible']}", "", True)]
    for name, value, goal, ok in rows:
        print(f"{name:40s} {value:>12s}  {goal:10s} {'' if not goal else 'ok' if ok else 'MISSED'}")
    return 0 if all(ok for *_, ok in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
