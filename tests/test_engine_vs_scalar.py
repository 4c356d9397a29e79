"""The engine equals a plain scalar evaluation of the same candidates (issue 11).

Random small designs (seeded): motors with and without speed-torque curves, gearboxes
with and without efficiency, friction, damping, a constant load, dwell, a return move,
a list of ratios to choose from, stage limits, load limits. Each is sized by
sizer.sizing.size_design with a given duration and with ``minimize``; every result row
(one per motor and law, at the ratio the engine chose) is compared with
tests/scalar_reference.py, which evaluates one candidate at a time from the definitions
(sec. 6.1.1): duration (T_min), peak and RMS torque, max speed, every check's value,
limit and margin to 1e-9, the verdict (it may differ only where the worst margin is
within 1e-9 of its requirement), and the chosen ratio (the best by the reference's own
figures, up to a tie within 1e-9).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scalar_reference import TOLERANCE, Candidate, Evaluation, evaluate, minimum_duration

from sizer.laws import DEFAULT_LAW_SPECS, make_law
from sizer.model import Design, Limits, Load, Motor, RatioChoice, Stage, Task, Transmission
from sizer.sizing import size_design

REL = 1e-9
"""Relative agreement of every figure (margins: absolute, they are fractions)."""

LAWS = tuple(s for s in DEFAULT_LAW_SPECS if not s.startswith("exponential"))
"""The default laws but the exponential one, whose features within 1e-6 of the piece ends
the reference's uniform sampling does not resolve."""

RATIOS = (3.0, 5.0, 8.0, 12.0, 20.0)


def random_motor(rng: np.random.Generator, index: int) -> Motor:
    """A plausible servo: rectangles, a falling intermittent curve, or both curves."""
    tau_c = float(rng.uniform(0.3, 4.0))
    tau_p = tau_c * float(rng.uniform(2.5, 4.0))
    v_n = float(rng.uniform(200.0, 400.0))
    v_max = v_n * float(rng.uniform(1.3, 2.0)) if rng.random() < 0.6 else None
    kind = int(rng.integers(3))
    top = v_max or 1.5 * v_n
    intermittent = ((0.0, tau_p), (v_n, tau_p), (top, 0.45 * tau_p)) if kind else None
    continuous = ((0.2 * v_n, 1.05 * tau_c), (0.6 * v_n, tau_c),
                  (top, 0.6 * tau_c)) if kind == 2 else None
    return Motor(f"m{index}", inertia=5e-5 * tau_c**1.3 * float(rng.uniform(0.7, 1.4)),
                 continuous_torque=tau_c, peak_torque=tau_p, rated_speed=v_n, max_speed=v_max,
                 intermittent_curve=intermittent, continuous_curve=continuous,
                 damping=float(rng.uniform(1e-5, 1e-4)) if rng.random() < 0.3 else 0.0)


def random_design(seed: int) -> Design:
    """A small design (2 motors, 2 laws, 2 or 3 ratios) with a given duration."""
    rng = np.random.default_rng(seed)
    maybe = rng.random
    load = Load(float(rng.uniform(0.01, 0.1)),
                damping=float(rng.uniform(0.0, 0.02)) if maybe() < 0.5 else 0.0,
                friction=float(rng.uniform(0.05, 0.5)) if maybe() < 0.5 else 0.0,
                torque=float(rng.uniform(-0.5, 0.5)) if maybe() < 0.4 else 0.0)
    ideal = maybe() < 0.4
    gearbox = Stage("gearbox", 10.0, 1.0 if ideal else float(rng.uniform(0.8, 0.97)),
                    float(rng.uniform(0.0, 2e-5)),
                    max_input_speed=600.0 if maybe() < 0.3 else None,
                    rated_output_torque=float(rng.uniform(3.0, 10.0)) if maybe() < 0.3 else None,
                    peak_output_torque=float(rng.uniform(8.0, 25.0)) if maybe() < 0.3 else None)
    stages = [gearbox]
    if maybe() < 0.4:
        stages.append(Stage("belt", 2.0, 1.0 if ideal else 0.95, float(rng.uniform(0, 1e-4)),
                            preload_torque=float(rng.uniform(0.0, 0.05)) if maybe() < 0.5
                            else 0.0))
    ratios = tuple(float(r) for r in rng.choice(RATIOS, size=int(rng.integers(2, 4)),
                                                replace=False))
    dwell = float(rng.uniform(0.05, 0.3)) if maybe() < 0.7 else 0.0
    task = Task(float(rng.choice([-1.0, 1.0]) * rng.uniform(0.5, 3.0)),
                float(rng.uniform(0.06, 0.4)), dwell=dwell, return_move=bool(maybe() < 0.5))
    limits = Limits(
        torque_margin=float(rng.uniform(0.0, 0.2)),
        speed_margin=0.05 if maybe() < 0.3 else 0.0,
        inertia_ratio=float(rng.uniform(5.0, 30.0)) if maybe() < 0.4 else None,
        thermal_speed=str(rng.choice(["max", "rms", "mean"])),
        envelope=str(rng.choice(["book", "linear", "linear_intermittent"])),
        max_speed=float(rng.uniform(20.0, 40.0)) if maybe() < 0.2 else None,
        max_acceleration=float(rng.uniform(300.0, 3000.0)) if maybe() < 0.2 else None,
        max_jerk=float(rng.uniform(1e5, 1e6)) if maybe() < 0.15 else None,
    )
    laws = tuple(str(s) for s in rng.choice(LAWS, size=2, replace=False))
    motors = tuple(random_motor(rng, i) for i in range(2))
    return Design(task, load, Transmission(tuple(stages)), laws=laws, motors=motors,
                  limits=limits, ratio_choice=RatioChoice(stage=0, ratios=ratios))


def candidate(design: Design, motor: Motor, spec: str, option: float) -> Candidate:
    stages = list(design.transmission.stages)
    stages[design.ratio_choice.stage] = dataclasses.replace(stages[0], ratio=option)
    return Candidate(motor, make_law(spec), design.task, design.load, tuple(stages),
                     design.limits)


def minimize_design(seed: int) -> Design:
    """:func:`random_design` as fast as possible (no duration given)."""
    design = random_design(seed)
    return dataclasses.replace(design, task=dataclasses.replace(design.task, duration=None))


def engine_calculator(design: Design, motor: Motor, spec: str, option: float):
    """The engine's cycle calculator of the same single candidate as :func:`candidate`."""
    from sizer.mechanics import Drive
    from sizer.sizing.candidates import MotorArrays
    from sizer.sizing.move import CycleCalculator

    stages = list(design.transmission.stages)
    stages[design.ratio_choice.stage] = dataclasses.replace(stages[0], ratio=option)
    return CycleCalculator(None, design.task, Drive(design.load, Transmission(tuple(stages))),
                           MotorArrays.of([motor], design.limits.envelope),
                           design.limits.thermal_speed, law=make_law(spec))


def option_of(design: Design, total: float) -> float:
    """The ratio option of the choice whose total ratio is ``total``."""
    others = math.prod(s.ratio for i, s in enumerate(design.transmission.stages)
                       if i != design.ratio_choice.stage)
    option = min(design.ratio_choice.ratios, key=lambda r: abs(r * others - total))
    assert option * others == pytest.approx(total, rel=1e-12)
    return option


def motor_id(result) -> str:
    return getattr(result.motor, "id", result.motor)


def spec_of(result) -> str:
    law = getattr(result, "law", None)
    return law.spec if hasattr(law, "spec") else result.spec


def close(a: float | None, b: float | None, rel: float = REL) -> bool:
    if a is None or b is None:
        return a is b
    if math.isinf(a) or math.isinf(b):
        return a == b
    return abs(a - b) <= rel * max(abs(a), abs(b))


def compare(result, ref: Evaluation, where: str) -> list[str]:
    """Every figure of one result row against the reference at the same duration."""
    errors = []
    for name, mine in (("peak_torque", ref.peak_torque), ("rms_torque", ref.rms_torque),
                       ("max_speed", ref.max_speed)):
        if not close(getattr(result, name), mine):
            errors.append(f"{where} {name}: engine {getattr(result, name)!r} reference {mine!r}")
    names = {c.name for c in result.checks}
    if names != set(ref.checks):
        errors.append(f"{where} checks: engine {sorted(names)} reference {sorted(ref.checks)}")
    for check in result.checks:
        if check.name not in ref.checks:
            continue
        value, limit, required = ref.checks[check.name]
        if not (close(check.value, value) and close(check.limit, limit)
                and check.required == pytest.approx(required, abs=1e-15)):
            errors.append(f"{where} {check.name}: engine {check.value!r}/{check.limit!r} "
                          f"reference {value!r}/{limit!r}")
        mine = ref.margin(check.name)
        if not (check.margin == mine or abs(check.margin - mine) <= REL):
            errors.append(f"{where} {check.name} margin: engine {check.margin!r} "
                          f"reference {mine!r}")
    return errors


def verdict_differs(result, ref: Evaluation) -> bool:
    """The verdicts differ, and not merely because the worst margin sits on the edge."""
    on_edge = abs(ref.worst_slack + TOLERANCE) <= REL or abs(ref.worst_slack) <= REL
    return result.feasible != ref.feasible and not on_edge


def check_design(design: Design) -> list[str]:
    minimize = design.task.minimize
    errors = []
    for result in size_design(design).results:
        motor = next(m for m in design.motors if m.id == motor_id(result))
        spec = spec_of(result)
        where = f"{motor.id} {spec} ratio {result.ratio:g}:"
        chosen = option_of(design, result.ratio)
        # the reference's figures for every option, and its best option
        keys: dict[float, tuple[float, float]] = {}
        refs: dict[float, Evaluation | None] = {}
        for option in design.ratio_choice.ratios:
            c = candidate(design, motor, spec, option)
            if minimize:
                T = minimum_duration(c)
                refs[option] = None if T is None else evaluate(c, T)
                keys[option] = (1.0, 0.0) if T is None else (0.0, T)
            else:
                ev = evaluate(c, design.task.duration)
                refs[option] = ev
                keys[option] = (0.0, ev.rms_torque) if ev.feasible else (1.0, -ev.worst_slack)
        ref = refs[chosen]
        if minimize:
            if (result.duration is None) != (ref is None):
                errors.append(f"{where} T_min: engine {result.duration!r} reference "
                              f"{None if ref is None else ref.duration!r}")
                continue
            if ref is None:
                continue  # infeasible at every duration: its figures are not defined
            if not close(result.duration, ref.duration):
                errors.append(f"{where} T_min: engine {result.duration!r} reference "
                              f"{ref.duration!r}")
            at_engine = evaluate(candidate(design, motor, spec, chosen), result.duration)
            errors += compare(result, at_engine, where)
            if not result.feasible:
                errors.append(f"{where} engine infeasible at its own T_min")
        else:
            assert result.duration == design.task.duration
            errors += compare(result, ref, where)
            if verdict_differs(result, ref):
                errors.append(f"{where} feasible: engine {result.feasible} reference "
                              f"{ref.feasible} (worst slack {ref.worst_slack!r})")
        best = min(keys, key=keys.get)
        if keys[best][0] == 0.0 and best != chosen:
            a, b = keys[best][1], keys[chosen][1]
            if keys[chosen][0] != 0.0 or not close(a, b):
                errors.append(f"{where} best ratio: reference {best:g} ({a!r}), engine "
                              f"{chosen:g} ({b!r})")
    return errors


@pytest.mark.parametrize("seed", range(8))
def test_given_duration_equals_the_scalar_reference(seed):
    errors = check_design(random_design(seed))
    assert not errors, "\n".join(errors)


@pytest.mark.parametrize("seed", range(3))
def test_minimize_equals_the_scalar_reference(seed):
    """The same designs as fastest as possible (two ratios: the reference's T_min, a
    root search of tens of evaluations, is the slow part of the test)."""
    design = random_design(seed)
    choice = dataclasses.replace(design.ratio_choice, ratios=design.ratio_choice.ratios[:2])
    design = dataclasses.replace(design, task=dataclasses.replace(design.task, duration=None),
                                 ratio_choice=choice)
    errors = check_design(design)
    assert not errors, "\n".join(errors)


def test_the_reference_meets_the_closed_form():
    """The reference itself: eq. (6.2) with the dwell on the book's rectangles."""
    motor = Motor("m", inertia=1e-4, continuous_torque=1.0, peak_torque=3.0, rated_speed=300.0)
    law = make_law("cycloidal")
    task = Task(math.pi / 2, None, dwell=0.1)
    stages = (Stage("gearbox", 10.0, 1.0, 1e-5),)
    c = Candidate(motor, law, task, Load(0.02), stages, Limits(torque_margin=0.1))
    K, h, J_t = 10.0, math.pi / 2, 1e-4 + 1e-5 + 0.02 / 100
    C_v, C_a, C_a_rms = 2.0, 2.0 * math.pi, math.sqrt(2.0) * math.pi
    s = (J_t * K * h * C_a_rms / 0.9) ** 2
    from scipy.optimize import brentq

    rms_bound = brentq(lambda T: T**3 * (T + 0.1) - s, 1e-3, 10.0, xtol=1e-15)
    expected = max(C_v * K * h / 300.0, math.sqrt(C_a * J_t * K * h / 2.7), rms_bound)
    assert minimum_duration(c) == pytest.approx(expected, rel=1e-12)
    ev = evaluate(c, 0.2)
    assert ev.peak_torque == pytest.approx(J_t * K * C_a * h / 0.04, rel=1e-13)
    assert ev.rms_torque == pytest.approx(J_t * K * C_a_rms * h / 0.04 * math.sqrt(0.2 / 0.3),
                                          rel=1e-12)


def convex_motor(rng: np.random.Generator, index: int) -> Motor:
    """A motor whose intermittent curve falls convexly (steep, then flatter: a constant
    power region), so that no line of it lies above the whole region (not concave)."""
    tau_c = float(rng.uniform(0.3, 4.0))
    tau_p = tau_c * float(rng.uniform(2.5, 4.0))
    v_n = float(rng.uniform(200.0, 400.0))
    curve = ((0.0, tau_p), (v_n, tau_p), (1.2 * v_n, 0.6 * tau_p), (1.8 * v_n, 0.45 * tau_p))
    return Motor(f"c{index}", inertia=5e-5 * tau_c**1.3, continuous_torque=tau_c,
                 peak_torque=tau_p, rated_speed=v_n, max_speed=1.8 * v_n,
                 intermittent_curve=curve)


@pytest.mark.parametrize("minimize", [False, True])
def test_convex_regions_equal_the_scalar_reference(minimize):
    """Regions that are not concave: the engine's exact ratio and its peak bound do not
    apply there (the grid search and a weaker bound do)."""
    design = minimize_design(1) if minimize else random_design(1)
    rng = np.random.default_rng(101)
    design = dataclasses.replace(design, motors=tuple(convex_motor(rng, i) for i in range(2)),
                                 ratio_choice=dataclasses.replace(
                                     design.ratio_choice, ratios=design.ratio_choice.ratios[:2]))
    errors = check_design(design)
    assert not errors, "\n".join(errors)
