"""A cycle of segments through a linkage at the load (issue 14 with issue 12's cycles).

The segments follow each other on the linkage: each move starts where the crank stopped,
so its motion through the position-dependent ratio has its own profile
(sizer.sizing.linkage_sizing, computed once per move, law and start); a dwell holds the
output's static load at the crank angle reached. With the law on the crank (turned by
the motor), a run turns the crank at its constant speed and a move may start and end at
the crank speeds of its neighbours (its shape, the law's boundary form, then depends on
its duration, which must be fixed: sizer.io.linkage says so); its profile is computed
once at that duration (linkage_sizing.FixedShape).
The free durations scale with one factor s (book sec. 5.2), as in
sizer.sizing.segment_cycle: peaks are the largest over the segments, the RMS torque sums
the segments' exact squares over the cycle time.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from sizer.laws import MotionLaw
from sizer.mechanics.drive import Drive
from sizer.model.cycle import Cycle, Move, Run
from sizer.model.domain import Design, Limits, Load, Task
from sizer.sizing.cycle import CycleMetrics, rule_speed
from sizer.sizing.linkage_sizing import (
    FixedShape,
    LinkageCalculator,
    LinkageProfile,
    crank_drive,
    profile_of,
)
from sizer.sizing.motors import MotorArrays
from sizer.sizing.segment_cycle import cycle_laws, segment_load


@dataclass(frozen=True)
class HeldDwell:
    """A dwell on the linkage: its static crank torque (the output's load through the
    ratio at the crank angle reached; 0 at a dead point)."""

    hold: float
    force: float
    """The output's static load held (N or N*m)."""


class LinkageCycle:
    """The requirements of a cycle through a linkage for each candidate at scales s (the
    interface of sizer.sizing.segment_cycle.SegmentCycle that minimum_duration uses)."""

    segmented = True

    def __init__(self, design: Design, law: MotionLaw | None, drive: Drive,
                 motors: MotorArrays, thermal_rule: str) -> None:
        cycle = design.cycle
        stage = design.transmission.linkage
        assert cycle is not None and stage is not None
        self.cycle, self.motors, self.thermal_rule = cycle, motors, thermal_rule
        self.law = law
        self.laws = cycle_laws(cycle, law)
        self.weights = np.array(cycle.weights())
        free = cycle.free
        self.fixed = np.array([np.nan if s.duration is None or i in free else s.duration
                               for i, s in enumerate(cycle.segments)], dtype=float)
        self.parts: list[LinkageProfile | HeldDwell] = []
        theta = stage.start_angle
        for i, (segment, own) in enumerate(zip(cycle.segments, self.laws, strict=True)):
            load = segment_load(design.load, segment)
            if isinstance(segment, Move | Run):
                duration = None if np.isnan(self.fixed[i]) else float(self.fixed[i])
                shape = _shape(segment, own, duration)
                profile = profile_of(replace(stage, start_angle=theta), load,
                                     segment.displacement, duration, shape)
                self.parts.append(profile)
                theta = float(profile.theta[-1])
            else:
                self.parts.append(HeldDwell(_hold(stage, load, theta), abs(load.torque)))
        profiles = [p for p in self.parts if isinstance(p, LinkageProfile)]
        heaviest = max(profiles, key=lambda p: p.max_inertia)
        self.drive = crank_drive(design, drive, heaviest)
        self.task = Task(cycle.moves[0].displacement, None, linear=cycle.linear)

    def issues(self) -> tuple[str, ...]:
        """The dead-point rule broken by any move, each named by its segment."""
        out = []
        for segment, part in zip(self.cycle.segments, self.parts, strict=True):
            if isinstance(part, LinkageProfile):
                name = segment.name or "move"
                out += [f"{name}: {issue}" for issue in part.issues]
            elif not np.isfinite(part.hold):
                out.append(f"{segment.name or 'dwell'}: the motor on the rocker cannot hold "
                           f"the output's load at a dead point (crank and coupler in line)")
        return tuple(out)

    def durations(self, s: np.ndarray) -> list[np.ndarray]:
        return [np.full_like(s, fixed) if np.isfinite(fixed) else w * s
                for fixed, w in zip(self.fixed, self.weights, strict=True)]

    def take(self, index: np.ndarray) -> LinkageCycle:
        out = object.__new__(LinkageCycle)
        out.__dict__.update(self.__dict__)
        out.motors = self.motors.subset(index)
        out.drive = self.drive.take(index)
        return out

    def peak_bound(self, limits: Limits) -> None:
        return None

    def _move(self, profile: LinkageProfile) -> LinkageCalculator:
        return LinkageCalculator(profile, Task(0.0, None), self.drive, self.motors,
                                 self.thermal_rule, self.law)

    def initial_guess(self) -> np.ndarray:
        """A scale from the free moves' speed and inertial bounds."""
        guess = np.full(len(self.motors), 1e-3)
        for part, w in zip(self.parts, self.weights, strict=True):
            if isinstance(part, LinkageProfile) and w > 0.0:
                guess = np.maximum(guess, self._move(part).initial_guess() / w)
        return np.where(np.isfinite(guess) & (guess > 0.0), guess, 1.0)

    def figures(self, s: np.ndarray) -> list[dict[str, np.ndarray]]:
        """Per segment and candidate: duration, peak torque, peak ratio, the integral of
        tau^2 and of omega^2, peak speed, the crank's turn, the work at the motor shaft, the
        load's peaks and the stages' figures."""
        out = []
        n = len(self.motors)
        N, eta = self.drive.ratio, self.drive.efficiency
        for part, T in zip(self.parts, self.durations(np.asarray(s, dtype=float)),
                           strict=True):
            if isinstance(part, HeldDwell):
                hold = np.broadcast_to(abs(part.hold) / (N * eta), (n,))
                limit = self.motors.intermittent.limit_clipped(np.zeros((n, 1)))[:, 0]
                with np.errstate(divide="ignore", invalid="ignore"):
                    ratio = np.where(limit > 0.0, hold / limit, np.where(hold > 0, np.inf, 0))
                zeros = np.zeros(n)
                stages = len(self.drive.stages)
                out.append({"duration": T, "peak_torque": hold, "peak_ratio": ratio,
                            "square": T * hold**2, "speed_square": zeros, "max_speed": zeros,
                            "turn": zeros, "energy": zeros, "load_speed": zeros,
                            "load_acceleration": zeros, "load_jerk": zeros,
                            "load_torque": np.full(n, part.force),
                            "stage_peak": [zeros] * stages, "stage_square": [zeros] * stages,
                            "stage_speed": [zeros] * stages, "start_acceleration": zeros,
                            "end_acceleration": zeros})
                continue
            calc = self._move(part)
            metrics = calc.evaluate(T)
            speed, torque, _ = calc.motor_samples(T)
            weights = part.weights
            out.append({
                "duration": T, "peak_torque": metrics.peak_torque,
                "peak_ratio": metrics.peak_ratio, "square": T * (torque**2 @ weights),
                "speed_square": T * (speed**2 @ weights), "max_speed": metrics.max_speed,
                "turn": np.broadcast_to(N * abs(part.turn), (n,)),
                "energy": T * ((torque * speed) @ weights),
                "load_speed": metrics.load_speed,
                "load_acceleration": metrics.load_acceleration,
                "load_jerk": metrics.load_jerk, "load_torque": metrics.load_torque,
                "stage_peak": metrics.stage_peak,
                "stage_square": [T * r**2 for r in metrics.stage_rms],
                "stage_speed": metrics.stage_speed,
                "start_acceleration": np.full(n, part.s2[0]) / T**2,
                "end_acceleration": np.full(n, part.s2[-1]) / T**2})
        return out

    def evaluate(self, duration: np.ndarray, peaks: bool = True) -> CycleMetrics:
        parts = self.figures(duration)
        cycle = sum((p["duration"] for p in parts), np.zeros(len(self.motors)))

        def most(name: str) -> np.ndarray:
            return np.max([np.broadcast_to(p[name], cycle.shape) for p in parts], axis=0)

        def total(name: str) -> np.ndarray:
            return sum((p[name] for p in parts), np.zeros_like(cycle))

        stages = len(self.drive.stages)
        thermal = rule_speed(self.thermal_rule, most("max_speed"), total("speed_square"),
                             total("turn"), cycle)
        return CycleMetrics(
            duration=cycle, max_speed=most("max_speed"), peak_torque=most("peak_torque"),
            peak_ratio=most("peak_ratio"), rms_torque=np.sqrt(total("square") / cycle),
            thermal_speed=thermal, load_speed=most("load_speed"),
            load_acceleration=most("load_acceleration"), load_jerk=most("load_jerk"),
            load_torque=most("load_torque"),
            stage_peak=[np.max([p["stage_peak"][k] for p in parts], axis=0)
                        for k in range(stages)],
            stage_rms=[np.sqrt(sum(p["stage_square"][k] for p in parts) / cycle)
                       for k in range(stages)],
            stage_speed=[np.max([np.broadcast_to(p["stage_speed"][k], cycle.shape)
                                 for p in parts], axis=0) for k in range(stages)])


def _shape(segment: Move | Run, law: MotionLaw | None,
           duration: float | None) -> MotionLaw | FixedShape:
    """The shape of a move or run over u = t/T: the law itself for a move from rest to
    rest; for a run or a move with boundary speeds, at its fixed duration T."""
    if isinstance(segment, Run):
        return FixedShape()
    assert law is not None
    if segment.rest_to_rest:
        return law
    assert duration is not None  # sizer.io.linkage asks for it
    h, T = segment.displacement, duration
    return FixedShape(law.spec, segment.start_speed * T / h, segment.end_speed * T / h,
                      segment.start_acceleration * T * T / h,
                      segment.end_acceleration * T * T / h)


def _hold(stage, load: Load, theta: float) -> float:
    """The static torque at the driven link holding the output's constant load at crank
    angle theta (inf: a driven rocker at a dead point cannot hold a load)."""
    from sizer.sizing.linkage_sizing import static_torque

    return static_torque(stage, load.torque, theta)


def evaluate_linkage_cycle(design: Design, law: MotionLaw, motors: MotorArrays,
                           drive: Drive):
    """(duration, metrics, checks, feasible) of a cycle through the design's linkage."""
    from sizer.sizing.checks import evaluate_checks
    from sizer.sizing.checks import feasible as all_pass
    from sizer.sizing.cycle_shape import given_scale
    from sizer.sizing.linkage_sizing import (
        dead_point_check,
        singular_metrics,
        unbounded_checks,
    )
    from sizer.sizing.minimum_duration import minimum_duration

    cycle: Cycle | None = design.cycle
    assert cycle is not None
    calculator = LinkageCycle(design, law, drive, motors, design.limits.thermal_speed)
    n = len(motors)
    issues = calculator.issues()
    point = dead_point_check(issues, n)
    if cycle.minimize and not issues:
        solution = minimum_duration(calculator, design.limits)
        duration = np.where(solution.feasible, solution.metrics.duration, np.nan)
        return duration, solution.metrics, [point, *solution.checks], solution.feasible
    s = calculator.initial_guess() if cycle.minimize else np.full(n, given_scale(cycle))
    metrics = calculator.evaluate(s)
    if issues:
        metrics = singular_metrics(metrics)
    checks = [point, *evaluate_checks(metrics, motors, calculator.drive, design.limits,
                                      cycle.linear)]
    if issues:
        checks = unbounded_checks(checks)
    feasible = all_pass(checks)
    duration = np.where(feasible, metrics.duration, np.nan) if cycle.minimize \
        else metrics.duration
    return duration, metrics, checks, feasible


def cycle_of_result(design: Design, motor, law: MotionLaw, transmission=None
                    ) -> LinkageCycle:
    """The cycle calculator of one result (a motor, a law, its transmission)."""
    drive = Drive(design.load, transmission or design.transmission)
    return LinkageCycle(design, law, drive, MotorArrays.of([motor], design.limits.envelope),
                        design.limits.thermal_speed)


def cycle_breakdown(design: Design, motor, law: MotionLaw, duration: float,
                    transmission=None):
    """The segments of a cycle through a linkage for one result (the segment table)."""
    from sizer.sizing.segment_breakdown import (
        JOIN_TOLERANCE,
        SegmentBreakdown,
        SegmentRow,
        scale_of,
    )

    calculator = cycle_of_result(design, motor, law, transmission)
    s = np.array([scale_of(design, duration)])
    parts = calculator.figures(s)
    metrics = calculator.evaluate(s)
    total = sum(float(p["square"][0]) for p in parts)
    reference = max((float(np.max(np.abs(part.s2))) / float(p["duration"][0]) ** 2
                     for part, p in zip(calculator.parts, parts, strict=True)
                     if isinstance(part, LinkageProfile)), default=0.0)
    rows, start, before = [], 0.0, 0.0
    for segment, own, p in zip(design.cycle.segments, calculator.laws, parts, strict=True):
        T = float(p["duration"][0])
        step = float(p["start_acceleration"][0]) - before
        kind = "move" if isinstance(segment, Move) else "run" if isinstance(segment, Run) \
            else "dwell"
        rows.append(SegmentRow(
            name=segment.name or kind, kind=kind, law=own.spec if own is not None else None,
            start=start, end=start + T, peak_torque=float(p["peak_torque"][0]),
            rms_torque=float(np.sqrt(p["square"][0] / T)) if T > 0 else 0.0,
            rms_share=float(p["square"][0]) / total if total > 0 else 0.0,
            peak_speed=float(p["max_speed"][0]), energy=float(p["energy"][0]),
            acceleration_step=step if abs(step) > JOIN_TOLERANCE * reference else 0.0))
        start += T
        before = float(p["end_acceleration"][0])
    return SegmentBreakdown(motor.id, law.spec, float(metrics.duration[0]),
                            float(metrics.rms_torque[0]), tuple(rows))


def cycle_samples(design: Design, motor, law: MotionLaw, duration: float,
                  transmission=None, samples: int = 401):
    """The cycle through the linkage sampled in time for one result: per segment the
    times, crank angles, ratios ds/dtheta, output positions, speeds and accelerations,
    and the motor's speed, acceleration and torque; and the metrics."""
    from sizer.sizing.segment_breakdown import scale_of

    calculator = cycle_of_result(design, motor, law, transmission)
    s = np.array([scale_of(design, duration)])
    metrics = calculator.evaluate(s)
    N = float(calculator.drive.ratio[0])
    eta = float(calculator.drive.efficiency[0])
    out, t0 = [], 0.0
    theta = position = 0.0
    for part, T in zip(calculator.parts, calculator.durations(s), strict=True):
        T = float(T[0])
        if isinstance(part, HeldDwell):
            hold = abs(part.hold) / (N * eta)
            out.append({"time": np.array([t0, t0 + T]), "theta": np.full(2, theta),
                        "ratio": np.full(2, np.nan), "position": np.full(2, position),
                        "load_speed": np.zeros(2), "load_acceleration": np.zeros(2),
                        "motor_speed": np.zeros(2), "motor_acceleration": np.zeros(2),
                        "motor_torque": np.full(2, hold)})
        else:
            speed, torque, _ = calculator._move(part).motor_samples(np.array([T]))
            pick = np.flatnonzero(part.weights == 0.0)
            pick = pick[np.linspace(0, len(pick) - 1, samples).round().astype(int)]
            theta, position = float(part.theta[-1]), float(part.s[-1])
            out.append({"time": t0 + T * part.u[pick], "theta": part.theta[pick],
                        "ratio": part.ratio[pick], "position": part.s[pick],
                        "load_speed": part.s1[pick] / T,
                        "load_acceleration": part.s2[pick] / T**2,
                        "motor_speed": speed[0, pick],
                        "motor_acceleration": N * part.theta2[pick] / T**2,
                        "motor_torque": torque[0, pick]})
        t0 += T
    return out, metrics, calculator
