"""The rows of issue 34 with no benchmark of their own, each against its same-run reference.

    python benchmarks/bench_axes.py --case shaped          # 64 motors, best of 3
    python benchmarks/bench_axes.py --case vibration
    python benchmarks/bench_axes.py --case linkage
    python benchmarks/bench_axes.py --case segments --repeat 2
    python benchmarks/bench_axes.py --case spline --repeat 2
    python benchmarks/bench_axes.py --case all --repeat 2

Each case is sized twice in the same run, alternately, CPU time (best of --repeat), after
a warm-up on two motors (imports and law caches); minimize mode throughout:

- ``shaped``: examples/indexing-table-vibration.yaml without its residual-vibration limit,
  law ``{kind: shaped, law: cycloidal, shaper: zv}`` (shaped at each candidate's own T)
  against the unshaped ``cycloidal``, on --motors synthetic motors (benchmarks/synthetic.py,
  speed-torque curves). Goal <= 3x.
- ``vibration``: the same example's three fixed laws (cycloidal, trapezoidal, double S)
  with its 20 arcsec residual-vibration limit against the same design without it.
  Goal <= 3x.
- ``linkage``: examples/press-slider-crank-cycle.yaml on the synthetic motors against the
  same cycle (strokes, dwell force, 6 kg, 20 N friction) with the slider-crank removed:
  the gearbox alone drives the law's coordinate (ratio 10 read per metre). Goal <= 3x.
- ``segments``: the synthetic scale problem (2 laws x 3 ratios, --segment-motors motors) on
  a closed cycle of 400 segments (100 x move, dwell, move back, a longer dwell: every move
  free) against the 4-segment cycle of one such block (not the task shorthand: the dwells
  differ, so both go segment by segment). Ratio of the times per segment; goal <= 1.5x.
- ``spline``: ``cubic_spline`` through 32 positions with ``times: auto`` against the same
  spline with given, equally spaced times: the law built afresh (its cache cleared) and
  sized on the book problem with --spline-motors motors. Goal <= 3x.

Prints the case, both times, the ratio and the goal. These are measurements, not gates:
the exit status is 0.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # this checkout's sizer
from synthetic import RATIOS, SCALE_LAWS, book_problem, curved_motors, scale_problem

from sizer.io.loader import load_design
from sizer.laws.data_law import data_law_of
from sizer.model.cycle import Cycle, Dwell, Move
from sizer.sizing import size_design

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
SHAPED = "{kind: shaped, law: cycloidal, shaper: zv}"
SPLINE_POINTS = 32
SEGMENTS = 400


class Case:
    """A design against its reference, how to size one (``run``) and the goal."""

    def __init__(self, name: str, what: str, case: object, reference: object, goal: float,
                 per: tuple[int, int] = (1, 1), run: Callable[[object], object] = size_design,
                 warm: Callable[[object], object] | None = None) -> None:
        self.name, self.what, self.case, self.reference = name, what, case, reference
        self.goal, self.per, self.run = goal, per, run
        self.warm = warm or (lambda d: size_design(replace(d, motors=d.motors[:2])))


def vibration_base(motors: int):
    design = load_design(EXAMPLES / "indexing-table-vibration.yaml")
    return replace(design, motors=curved_motors(motors))


def shaped(args) -> Case:
    base = vibration_base(args.motors)
    base = replace(base, limits=replace(base.limits, residual_vibration=None))
    return Case("shaped", f"open shaped cycloidal (zv) vs cycloidal, {args.motors} motors",
                replace(base, laws=(SHAPED,)), replace(base, laws=("cycloidal",)), 3.0)


def vibration(args) -> Case:
    base = vibration_base(args.motors)
    base = replace(base, laws=tuple(c.text for c in base.laws[:3]))
    free = replace(base, limits=replace(base.limits, residual_vibration=None))
    return Case("vibration", f"20 arcsec residual limit vs none, 3 laws, {args.motors} motors",
                base, free, 3.0)


def linkage(args) -> Case:
    press = load_design(EXAMPLES / "press-slider-crank-cycle.yaml")
    press = replace(press, motors=curved_motors(args.motors))
    plain = replace(press, transmission=replace(press.transmission, linkage=None))
    return Case("linkage", f"slider-crank press cycle vs gearbox alone, {args.motors} motors",
                press, plain, 3.0)


def segments(args) -> Case:
    design = scale_problem(args.segment_motors, laws=SCALE_LAWS[:2], ratios=RATIOS[:3])
    h, dwell = design.task.displacement, design.task.dwell

    def cycle(count: int):
        block = (Move(h, None), Dwell(dwell), Move(-h, None), Dwell(2 * dwell))
        return replace(design, cycle=Cycle(block * (count // 4), closed=True))

    return Case("segments", f"{SEGMENTS} vs 4 segments, per segment, "
                f"{args.segment_motors} motors x 2 laws x 3 ratios",
                cycle(SEGMENTS), cycle(4), 1.5, per=(SEGMENTS, 4))


def spline_spec(times: str) -> str:
    n = SPLINE_POINTS
    positions = [0.5 - 0.5 * math.cos(math.pi * i / (n - 1)) + 0.02 * math.sin(3.0 * i)
                 for i in range(n)]
    positions[0], positions[-1] = 0.0, 1.0
    q = ", ".join(f"{p:.6f}" for p in positions)
    return f"{{kind: cubic_spline, times: {times}, positions: [{q}]}}"


def spline(args) -> Case:
    design = book_problem(args.spline_motors, laws=("cycloidal",), ratios=RATIOS[:3])
    given = "[" + ", ".join(f"{i / (SPLINE_POINTS - 1):.12g}" for i in range(SPLINE_POINTS)) + "]"

    def fresh(d):  # the law built again: data_law_of caches it per process
        data_law_of.cache_clear()
        return size_design(d)

    return Case("spline", f"cubic_spline times: auto vs given, {SPLINE_POINTS} points, "
                f"{args.spline_motors} motors", replace(design, laws=(spline_spec("auto"),)),
                replace(design, laws=(spline_spec(given),)), 3.0, run=fresh,
                warm=lambda d: size_design(replace(design, motors=design.motors[:1])))


CASES = {"shaped": shaped, "vibration": vibration, "linkage": linkage,
         "segments": segments, "spline": spline}


def cpu(run: Callable[[object], object], design: object) -> float:
    start = time.process_time()
    run(design)
    return time.process_time() - start


def measure(case: Case, repeat: int) -> None:
    for d in (case.case, case.reference):
        case.warm(d)
    timed: list[float] = []
    reference: list[float] = []
    for _ in range(repeat):
        timed.append(cpu(case.run, case.case))
        reference.append(cpu(case.run, case.reference))
    c, r = min(timed), min(reference)
    ratio = (c / case.per[0]) / (r / case.per[1])
    print(f"bench_axes --case {case.name}: {case.what}, minimize, best of {repeat} (CPU)")
    print(f"  case {c:9.3f} s   reference {r:9.3f} s   ratio {ratio:7.2f}x   "
          f"goal <= {case.goal:g}x   {'ok' if ratio <= case.goal else 'missed'}")
    if case.per != (1, 1):
        print(f"  per segment: case {1e3 * c / case.per[0]:.2f} ms, "
              f"reference {1e3 * r / case.per[1]:.2f} ms")


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--case", choices=(*CASES, "all"), default="all")
    parser.add_argument("--motors", type=int, default=64)
    parser.add_argument("--segment-motors", type=int, default=2)
    parser.add_argument("--spline-motors", type=int, default=4)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    for name in CASES if args.case == "all" else (args.case,):
        measure(CASES[name](args), args.repeat)
    return 0


if __name__ == "__main__":
    sys.exit(main())
