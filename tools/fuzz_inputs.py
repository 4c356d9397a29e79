"""Fuzz the sizer CLI with thousands of mutated example designs and catalogs (issue 10).

    python tools/fuzz_inputs.py --cases 10000 [--seed N] [--jobs 2] [--out DIR]

The cases come from the generator of the test suite (``tests/fuzz_cases.py``: the examples'
designs and catalogs with deleted keys, swapped types and units, extreme numbers, truncated or
duplicated lists, random strings, truncated YAML), drawn by hypothesis from ``--seed`` (the same
seed gives the same cases). Each case runs in a worker process (``--jobs`` of them) with a hard
timeout (``--timeout``, 10 s): a case still running then is killed, counted as a hang, and its
worker replaced. Every run must give a clean answer: exit code 0, 1 or 2, no traceback, no
Python warning, no nan/inf printed, valid JSON, one ``error:`` line naming the file for exit
code 2, input files unchanged, at most 10 s.

Each failing case goes to ``DIR/<class>/<n>/`` (default DIR: ``fuzz-failures``): its input
files, ``command.txt`` (the command and the mutations), ``stdout.txt``, ``stderr.txt`` and
``failures.txt``; rerun it with ``cd DIR/<class>/<n> && sh command.txt``. ``DIR/summary.txt``
lists the classes of failure (where the traceback was raised, which warning, which format
printed a non-finite number...), their counts and the smallest case of each.

Progress is shown with rich on a terminal (a line every 500 cases otherwise). Exit code 0 when
no case failed, 1 otherwise. Each worker's address space is capped (``--memory``, 3 GB) so a
memory blow-up ends as a MemoryError case instead of exhausting the machine.
"""

from __future__ import annotations

import argparse
import contextlib
import hashlib
import json
import multiprocessing as mp
import re
import shutil
import sys
import tempfile
import time
from collections import Counter, defaultdict
from dataclasses import dataclass
from multiprocessing.connection import Connection, wait
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
STARTUP = 300
"""Seconds a new worker may take to import sizer (a loaded machine is slow)."""
CHUNK = 250
"""Cases drawn per hypothesis run (each chunk has its own seed, derived from --seed)."""


def _setup_path() -> None:
    """The worktree's sizer and the tests' helpers first on the path."""
    for folder in (str(ROOT / "tests"), str(ROOT)):
        if folder in sys.path:
            sys.path.remove(folder)
        sys.path.insert(0, folder)


def generate(count: int, seed: int) -> list[Any]:
    """``count`` distinct cases drawn by hypothesis, reproducibly from ``seed``."""
    _setup_path()
    import warnings

    from fuzz_cases import fuzz_inputs
    from hypothesis import HealthCheck, Phase, given, settings
    from hypothesis import seed as hseed

    cases: list[Any] = []
    seen: set[str] = set()
    chunk = 0
    while len(cases) < count and chunk < 10 * (count // CHUNK + 1):
        drawn: list[Any] = []

        @hseed(seed * 100_003 + chunk)
        @settings(max_examples=CHUNK, database=None, phases=[Phase.generate], deadline=None,
                  suppress_health_check=list(HealthCheck))
        @given(case=fuzz_inputs())
        def draw(case: Any) -> None:
            drawn.append(case)  # noqa: B023 - read before the next chunk rebinds it

        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            draw()
        for case in drawn:
            key = hashlib.sha1(json.dumps(case.to_json(), sort_keys=True).encode(
                "utf-8", "surrogatepass")).hexdigest()
            if key not in seen:
                seen.add(key)
                cases.append(case)
        chunk += 1
    return cases[:count]


# --- workers ---------------------------------------------------------------------------------

def _worker(conn: Connection, memory: int) -> None:
    """Run the cases sent on ``conn`` and send back their outcomes."""
    _setup_path()
    if memory > 0:
        try:
            import resource

            resource.setrlimit(resource.RLIMIT_AS, (memory, memory))
        except (ImportError, ValueError, OSError):
            pass
    from fuzz_cases import TIME_LIMIT, FuzzInput, run_input, warm_up

    warm_up()  # the imports, before the first case is timed
    conn.send("ready")
    while True:
        message = conn.recv()
        if message is None:
            return
        index, data = message
        case = FuzzInput.from_json(data)
        with tempfile.TemporaryDirectory(prefix="sizer-fuzz-") as folder:
            outcome = run_input(case, Path(folder), TIME_LIMIT)
        conn.send((index, outcome.returncode, outcome.stdout[-20000:], outcome.stderr[-20000:],
                   outcome.seconds, outcome.failures))


@dataclass
class Worker:
    process: mp.process.BaseProcess
    conn: Connection
    index: int | None = None
    started: float = 0.0


def _start(context: Any, memory: int) -> Worker:
    parent, child = context.Pipe()
    process = context.Process(target=_worker, args=(child, memory), daemon=True)
    process.start()
    child.close()
    if not parent.poll(STARTUP) or parent.recv() != "ready":
        raise RuntimeError(f"a worker did not start in {STARTUP} s")
    return Worker(process, parent)


# --- reporting -------------------------------------------------------------------------------

def _slug(text: str) -> str:
    return re.sub(r"[^A-Za-z0-9]+", "-", text).strip("-")[:80] or "failure"


class Recorder:
    """Writes failing cases under ``out`` and keeps the classes of failure."""

    def __init__(self, out: Path) -> None:
        self.out = out
        self.classes: dict[str, list[tuple[int, Any, str]]] = defaultdict(list)
        self.counts: Counter[str] = Counter()
        self.exit_codes: Counter[str] = Counter()

    def record(self, case: Any, returncode: int | None, stdout: str, stderr: str,
               seconds: float, failures: list[str]) -> None:
        self.exit_codes[str(returncode)] += 1
        if not failures:
            return
        for failure in failures:
            self.counts[failure] += 1
        first = failures[0]
        number = sum(where.startswith(_slug(first) + "/") for *_, where in self.classes[first]) + 1
        folder = self.out / _slug(first) / str(number)
        for failure in failures:  # the case is kept once, under its first failure
            self.classes[failure].append((_size(case), case, str(folder.relative_to(self.out))))
        for name, text in case.files.items():
            target = folder / name
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes(text.encode("utf-8", "surrogatepass"))
        command = " ".join(_quote(a) for a in case.command("."))
        (folder / "command.txt").write_text(
            f"# base: {case.base}\n# mutations: {'; '.join(case.mutations)}\n"
            f"PYTHONPATH={_quote(str(ROOT))} python -m sizer {command}\n", encoding="utf-8")
        (folder / "stdout.txt").write_text(stdout, encoding="utf-8", errors="replace")
        (folder / "stderr.txt").write_text(stderr, encoding="utf-8", errors="replace")
        (folder / "failures.txt").write_text(
            "\n".join(failures) + f"\nexit code: {returncode}\nseconds: {seconds:.2f}\n",
            encoding="utf-8")
        catalogs = folder / "catalogs"
        catalogs.mkdir(exist_ok=True)
        for source in (ROOT / "examples" / "catalogs").iterdir():
            if not (catalogs / source.name).exists():
                shutil.copyfile(source, catalogs / source.name)

    def summary(self, total: int, seconds: float) -> str:
        failed = sum(len(v) for v in self.classes.values())
        lines = [f"{total} cases in {seconds:.0f} s; {failed} failed; exit codes: "
                 + ", ".join(f"{k}: {v}" for k, v in sorted(self.exit_codes.items()))]
        for name, count in self.counts.most_common():
            lines.append(f"\n{count:6d}  {name}")
            if name in self.classes:
                _, case, where = min(self.classes[name], key=lambda item: item[0])
                lines.append(f"        smallest: {where}")
                lines.append(f"        {case.describe()[:400]}")
        return "\n".join(lines) + "\n"


def _size(case: Any) -> tuple[int, int]:
    return (len(case.mutations), sum(len(t) for t in case.files.values()))


def _quote(arg: str) -> str:
    return arg if re.fullmatch(r"[\w./=:@%+-]+", arg) else "'" + arg.replace("'", "'\\''") + "'"


# --- the run ---------------------------------------------------------------------------------

def run(cases: list[Any], jobs: int, timeout: float, memory: int, recorder: Recorder,
        progress: Any) -> int:
    """Run every case in the workers; the number of failing cases."""
    context = mp.get_context("spawn")
    workers = [_start(context, memory) for _ in range(jobs)]
    pending = list(range(len(cases)))[::-1]
    done = failed = hangs = 0
    try:
        while pending or any(w.index is not None for w in workers):
            for worker in workers:
                if worker.index is None and pending:
                    worker.index = pending.pop()
                    worker.started = time.monotonic()
                    worker.conn.send((worker.index, cases[worker.index].to_json()))
            busy = [w for w in workers if w.index is not None]
            left = min(timeout - (time.monotonic() - w.started) for w in busy)
            ready = wait([w.conn for w in busy], timeout=max(0.0, left))
            for worker in list(busy):
                index = worker.index
                assert index is not None
                result = None
                if worker.conn in ready:
                    try:
                        result = worker.conn.recv()
                    except (EOFError, OSError):
                        result = None
                    if result is None:  # the worker died (a segfault, the memory cap...)
                        outcome = (None, "", f"worker died (exit code {worker.process.exitcode})",
                                   time.monotonic() - worker.started,
                                   [f"worker died: exit code {worker.process.exitcode}"])
                    else:
                        outcome = result[1:]
                elif time.monotonic() - worker.started >= timeout:
                    outcome = (None, "", "", timeout, [f"hang: killed after {timeout:g} s "
                                                       f"({cases[index].base})"])
                else:
                    continue
                if result is None:
                    worker.process.kill()
                    worker.process.join()
                    workers[workers.index(worker)] = _start(context, memory)
                    hangs += outcome[4][0].startswith("hang")
                else:
                    worker.index = None
                recorder.record(cases[index], *outcome)
                done += 1
                failed += bool(outcome[4])
                progress(done, failed, hangs)
    finally:
        for worker in workers:
            with contextlib.suppress(OSError):
                worker.conn.send(None)
            worker.process.join(timeout=2)
            if worker.process.is_alive():
                worker.process.kill()
    return failed


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cases", type=int, default=10_000, help="number of cases (10000)")
    parser.add_argument("--seed", type=int, default=0, help="the generator's seed (0)")
    parser.add_argument("--jobs", type=int, default=2, help="worker processes (2)")
    parser.add_argument("--out", type=Path, default=Path("fuzz-failures"),
                        help="folder for the failing cases and summary.txt (fuzz-failures)")
    parser.add_argument("--timeout", type=float, default=10.0, help="seconds per case (10)")
    parser.add_argument("--memory", type=float, default=3.0,
                        help="address-space cap of a worker in GB, 0 for none (3)")
    args = parser.parse_args(argv)
    if args.out.exists() and any(args.out.iterdir()):
        parser.error(f"{args.out} is not empty: give a new folder with --out")
    args.out.mkdir(parents=True, exist_ok=True)
    start = time.monotonic()
    print(f"drawing {args.cases} cases (seed {args.seed})...", file=sys.stderr)
    cases = generate(args.cases, args.seed)
    recorder = Recorder(args.out)

    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

    interactive = sys.stderr.isatty()
    with Progress(TextColumn("fuzz"), BarColumn(), MofNCompleteColumn(),
                  TextColumn("{task.fields[failed]} failed, {task.fields[hangs]} hung"),
                  TimeElapsedColumn(), disable=not interactive) as bar:
        task = bar.add_task("fuzz", total=len(cases), failed=0, hangs=0)

        def progress(done: int, failed: int, hangs: int) -> None:
            bar.update(task, completed=done, failed=failed, hangs=hangs)
            if not interactive and done % 500 == 0:
                print(f"{done}/{len(cases)} cases, {failed} failed, {hangs} hung, "
                      f"{time.monotonic() - start:.0f} s", file=sys.stderr, flush=True)

        failed = run(cases, max(1, args.jobs), args.timeout, int(args.memory * 2**30),
                     recorder, progress)
    summary = recorder.summary(len(cases), time.monotonic() - start)
    (args.out / "summary.txt").write_text(summary, encoding="utf-8")
    print(summary, end="")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
