"""The per-law analysis of issue 34's open shaped laws and shape searches, laws built afresh.

    python benchmarks/bench_law_analysis.py                 # 64 motors, 138 laws, best of 2
    python benchmarks/bench_law_analysis.py --repeat 3

Three measurements, CPU time, best of --repeat, in one run:

- ``analysis``: 138 open-shaped laws ``{kind: shaped, law: cycloidal, shaper: zv, f_T: ...}``
  (as many as the shaped case builds for 64 motors) built and analysed: their linear
  peaks (samples and convex hull, sizer.laws.linear_peaks), coefficients and quadrature
  rule; and 200 ``trapezoidal(alpha=...)`` laws' linear peaks (an ``auto`` search's);
- ``shaped``: bench_axes.py's shaped case (examples/indexing-table-vibration.yaml without
  its residual limit, the open shaped cycloidal on --motors synthetic motors) with the
  law caches cleared before each run, so that every shaped law of the search is built and
  analysed in it (bench_axes.py's best of 3 reuses the laws of its first run), against
  the unshaped cycloidal in the same run.

Prints the times and the ratio; measurements, exit 0.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # this checkout's sizer
import bench_axes

import sizer.laws.registry as registry
from sizer.laws.base import _law_of_spec
from sizer.laws.data_law import data_law_of
from sizer.laws.registry import make_law
from sizer.sizing import size_design

SHAPED_LAWS = 138
TRAPEZOIDS = 200


def clear_laws() -> None:
    """Every law cache emptied: the next laws are built and analysed afresh."""
    data_law_of.cache_clear()
    _law_of_spec.cache_clear()
    for name in dir(registry):
        cached = getattr(registry, name)
        if hasattr(cached, "cache_clear"):
            cached.cache_clear()


def analyse_shaped() -> None:
    for i in range(SHAPED_LAWS):
        law = make_law("{kind: shaped, law: cycloidal, shaper: zv, f_T: %r}"
                       % (2.0 + 0.0371 * i))
        law.linear_peaks, law.coefficients, law.quadrature  # noqa: B018


def analyse_trapezoids() -> None:
    for i in range(TRAPEZOIDS):
        make_law(f"trapezoidal(alpha={0.05 + 0.4 * (i + 0.5) / TRAPEZOIDS!r})").linear_peaks  # noqa: B018


def cpu(function, *args) -> float:
    clear_laws()
    start = time.process_time()
    function(*args)
    return time.process_time() - start


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--motors", type=int, default=64)
    parser.add_argument("--repeat", type=int, default=2)
    args = parser.parse_args()
    case = bench_axes.shaped(args)
    case.warm(case.case)
    case.warm(case.reference)
    times: dict[str, list[float]] = {"shaped laws": [], "trapezoids": [], "case": [],
                                     "reference": []}
    for _ in range(args.repeat):
        times["shaped laws"].append(cpu(analyse_shaped))
        times["trapezoids"].append(cpu(analyse_trapezoids))
        times["case"].append(cpu(size_design, case.case))
        times["reference"].append(cpu(size_design, case.reference))
    best = {name: min(values) for name, values in times.items()}
    print(f"bench_law_analysis: best of {args.repeat} (CPU), laws built afresh")
    print(f"  {SHAPED_LAWS} shaped laws analysed  {best['shaped laws']:7.3f} s  "
          f"({1e3 * best['shaped laws'] / SHAPED_LAWS:.2f} ms a law)")
    print(f"  {TRAPEZOIDS} trapezoids' peaks     {best['trapezoids']:7.3f} s  "
          f"({1e3 * best['trapezoids'] / TRAPEZOIDS:.2f} ms a law)")
    print(f"  shaped case, {args.motors} motors  {best['case']:7.3f} s   reference "
          f"{best['reference']:.3f} s   ratio {best['case'] / best['reference']:.1f}x   "
          f"goal <= 3x")
    return 0


if __name__ == "__main__":
    sys.exit(main())
