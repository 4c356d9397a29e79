"""Time `auto` shape parameters against a fixed law, in the same process.

    python benchmarks/bench_auto_shape.py --motors 200

The book's case of eq. (6.2) (rectangular regions, purely inertial load, ideal gearbox),
minimize mode, synthetic motors (a geometric family of ratings, NOT datasheet figures),
a load jerk limit for the double S. For each family it times: the exact choice of the
auto parameters for all motors (sizer.sizing.auto_shape.choose_shape), the whole size_design
with the auto spec (which then evaluates each motor's own law), and size_design with one
fixed law of the family. Results are in benchmarks/README.md.
"""

from __future__ import annotations

import argparse
import math
import time

from sizer.laws import resolve
from sizer.model import Design, Limits, Load, Motor, Stage, Task, Transmission
from sizer.sizing import size_design
from sizer.sizing.candidates import Candidates, MotorArrays
from sizer.sizing.choices import choose_shape

FAMILIES = (("trapezoidal(alpha=auto)", "trapezoidal(alpha=1/3)"),
            ("double_s(alpha=auto, beta=auto)", "double_s(alpha=1/3, beta=1/4)"))


def rectangular_motors(count: int) -> tuple[Motor, ...]:
    motors = []
    for i in range(count):
        torque = 0.1 * 500.0 ** (i / max(count - 1, 1))  # 0.1 .. 50 N*m continuous
        motors.append(Motor(id=f"syn-{i:05d}", inertia=2e-5 * torque**1.3,
                            continuous_torque=torque, peak_torque=3.0 * torque,
                            rated_speed=3000 * math.pi / 30))
    return tuple(motors)


def design(count: int, spec: str) -> Design:
    """The trapezoid has jerk impulses: the jerk limit only for the double S."""
    task = Task(math.pi / 2, None, dwell=0.15, return_move=True)
    jerk = 2e4 if spec.startswith("double_s") else None
    return Design(task, Load(0.35), Transmission((Stage("gearbox", 10.0, 1.0, 1.2e-4),)),
                  laws=(spec,), motors=rectangular_motors(count),
                  limits=Limits(torque_margin=0.1, max_jerk=jerk))


def timed(function) -> float:
    start = time.perf_counter()
    function()
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--motors", type=int, default=200)
    args = parser.parse_args()
    print(f"{'family':32s} {'motors':>6s} {'choose [ms]':>11s} {'auto size [s]':>13s} "
          f"{'fixed size [s]':>14s}")
    for auto, fixed in FAMILIES:
        d = design(args.motors, auto)
        family, values = resolve(auto)
        candidates = Candidates.single(MotorArrays.of(d.motors), d.load, d.transmission)
        choose = timed(lambda: choose_shape(family, values, d, candidates))  # noqa: B023
        whole = timed(lambda: size_design(d))  # noqa: B023
        one = timed(lambda: size_design(design(args.motors, fixed)))  # noqa: B023
        print(f"{auto:32s} {args.motors:6d} {1000 * choose:11.1f} {whole:13.2f} {one:14.2f}")


if __name__ == "__main__":
    main()
