"""Time `auto` shape parameters against a fixed law, in the same process (CPU time).

    python benchmarks/bench_auto_shape.py --motors 200 --searched 64 4 2 1 --ideal 64 64 2 1

With friction (issue 34): the load has Coulomb friction (0.5 N*m), trapezoidal(alpha=auto)
on 64 motors, double_s(alpha=auto, beta=auto) on 64 through the ideal gearbox and on 4
through the efficient one, fifteen_segments with three auto parameters on 2 and
exponential(sigma=auto, lam=auto) on 1 (fewer motors: they are slower; --ideal and
--searched set the counts), each printed as the ratio of size_design
with the auto spec to size_design with one fixed law of the family (best of 3) on the same
motors. Through the ideal gearbox the friction is a constant torque per move, so the
trapezoid and the double S take the closed forms with constant torques
(sizer.sizing.optimal_shapes.exact_time_optimal; fixed laws likewise,
sizer.sizing.shortest_duration.closed_form_duration); fifteen_segments has none and is
searched (sizer.sizing.choices.search_shape, every point a T_min search). The same rows
with a gearbox efficiency of 0.9 (power flow: the motor torque is no longer linear) are
searched: the trapezoid and the double S on closed forms of their T_min at each shape
(sizer.sizing.optimal_shapes.trusted_phase_model: no damping, their torques functions of
the acceleration alone), the others with the engine's T_min at every point.

The book's case of eq. (6.2) (rectangular regions, purely inertial load, ideal gearbox),
minimize mode, synthetic motors (a geometric family of ratings, NOT datasheet figures),
a load jerk limit for the double S. For each family it times: the exact choice of the
auto parameters for all motors (sizer.sizing.choices.choose_shape), the whole size_design
with the auto spec (which then evaluates each motor's own law), and size_design with one
fixed law of the family. Results are in benchmarks/README.md.
"""

from __future__ import annotations

import argparse
import math
import time
from functools import partial

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


SEARCHED = (("trapezoidal(alpha=auto)", "trapezoidal(alpha=1/3)"),
            ("double_s(alpha=auto, beta=auto)", "double_s(alpha=1/3, beta=1/4)"),
            ("fifteen_segments(alpha=auto, beta=auto, gamma=auto)",
             "fifteen_segments(alpha=1/3, beta=1/4, gamma=1/4)"),
            ("exponential(sigma=auto, lam=auto)", "exponential(sigma=7.1, lam=0.2)"))


def design(count: int, spec: str, friction: float = 0.0, efficiency: float = 1.0) -> Design:
    """The trapezoid has jerk impulses: the jerk limit only for the others."""
    task = Task(math.pi / 2, None, dwell=0.15, return_move=True)
    jerk = None if spec.startswith("trapezoidal") else 2e4
    return Design(task, Load(0.35, friction=friction),
                  Transmission((Stage("gearbox", 10.0, efficiency, 1.2e-4),)),
                  laws=(spec,), motors=rectangular_motors(count),
                  limits=Limits(torque_margin=0.1, max_jerk=jerk))


def with_friction(count: int, spec: str, efficiency: float) -> None:
    """size_design of the design with friction 0.5 N*m and the gearbox's efficiency."""
    size_design(design(count, spec, 0.5, efficiency))


def timed(function, repeat: int = 1) -> float:
    """The least CPU time of ``repeat`` calls."""
    best = math.inf
    for _ in range(repeat):
        start = time.process_time()
        function()
        best = min(best, time.process_time() - start)
    return best


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--motors", type=int, default=200)
    parser.add_argument("--searched", type=int, nargs=4, default=(64, 4, 2, 1),
                        help="motors of the four cases through the efficient gearbox "
                             "(0 skips one)")
    parser.add_argument("--ideal", type=int, nargs=4, default=(64, 64, 2, 1),
                        help="motors of the four cases through the ideal gearbox")
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
    for efficiency in (1.0, 0.9):
        print(f"\nfriction 0.5 N*m, gearbox efficiency {efficiency:g}, CPU time\n"
              f"{'family':52s} {'motors':>6s} {'auto [s]':>9s} {'fixed [s]':>9s} "
              f"{'ratio':>7s}")
        counts = args.ideal if efficiency == 1.0 else args.searched
        for (auto, fixed), count in zip(SEARCHED, counts, strict=True):
            if count:
                whole = timed(partial(with_friction, count, auto, efficiency))
                one = timed(partial(with_friction, count, fixed, efficiency), 3)
                print(f"{auto:52s} {count:6d} {whole:9.3f} {one:9.4f} {whole / one:7.1f}")


if __name__ == "__main__":
    main()
