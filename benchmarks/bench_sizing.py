"""Time the sizing engine on a large synthetic catalog (motors x laws).

    python benchmarks/bench_sizing.py --motors 1000 --mode both

The motors are synthetic (a geometric family of ratings, NOT real datasheet figures):
they only exercise the vectorized code paths. Goals on the 2-core reference machine:
1000 motors x 15 laws in well under a minute per mode, with and without the exact
efficiency / friction path.
"""

from __future__ import annotations

import argparse
import math
import time

from sizer.laws import DEFAULT_LAW_SPECS
from sizer.model import Design, Limits, Load, Motor, Stage, Task, Transmission
from sizer.sizing import size_design


def synthetic_motors(count: int) -> tuple[Motor, ...]:
    motors = []
    for i in range(count):
        torque = 0.1 * 500.0 ** (i / max(count - 1, 1))  # 0.1 .. 50 N*m continuous
        motors.append(Motor(
            id=f"syn-{i:05d}",
            inertia=2e-5 * torque**1.3,
            continuous_torque=torque,
            peak_torque=3.0 * torque,
            rated_speed=3000 * math.pi / 30,
            max_speed=6000 * math.pi / 30,
            intermittent_curve=((0.0, 3.0 * torque), (3000 * math.pi / 30, 3.0 * torque),
                                (6000 * math.pi / 30, 1.2 * torque)) if i % 2 else None,
        ))
    return tuple(motors)


def design(count: int, minimize: bool, ideal: bool) -> Design:
    load = Load(0.35) if ideal else Load(0.35, damping=0.01, friction=0.2, torque=0.5)
    stage = Stage("gearbox", 10.0, 1.0 if ideal else 0.95, 1.2e-4)
    task = Task(math.pi / 2, None if minimize else 0.25, dwell=0.15, return_move=True)
    laws = tuple(s for s in DEFAULT_LAW_SPECS if not s.startswith("exponential"))
    return Design(task, load, Transmission((stage,)), laws=laws,
                  motors=synthetic_motors(count), limits=Limits(torque_margin=0.1))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--motors", type=int, default=1000)
    parser.add_argument("--mode", choices=["duration", "minimize", "both"], default="both")
    args = parser.parse_args()
    modes = ["duration", "minimize"] if args.mode == "both" else [args.mode]
    print(f"{'mode':10s} {'loads':8s} {'motors':>7s} {'laws':>5s} {'pairs':>7s} {'seconds':>8s}")
    for mode in modes:
        for ideal in (True, False):
            d = design(args.motors, mode == "minimize", ideal)
            start = time.perf_counter()
            result = size_design(d)
            elapsed = time.perf_counter() - start
            print(f"{mode:10s} {'ideal' if ideal else 'real':8s} {args.motors:7d} "
                  f"{len(d.laws):5d} {len(result.results):7d} {elapsed:8.2f}")


if __name__ == "__main__":
    main()
