"""Sensitivities: how much each margin (and, minimizing, T_min) moves per relative change
of each input, for one motor x law pair (``sizer sensitivity``).

For an input x the sensitivity is d margin / d ln x (a 1 % larger x changes the margin by
about 0.01 times it), by central differences of sizings of the design perturbed to
x (1 +- h). The pair is fixed as the sizing chose it (motor, drive, law, and the ratio or
catalog gearbox of a ratio choice); with a given duration the duration stays the design's,
with ``minimize`` T_min is sized again for each perturbed design.

h = 1e-6: the margins are smooth functions of the inputs away from a kink, so the central
difference's truncation error is O(h^2) ~ 1e-12 of the margin's second derivative, while
the round-off of the sizing (relative ~1e-15) divided by h stays ~1e-9: both far below the
figures shown, and the one-sided differences (error O(h) ~ 1e-6) still tell a kink (a
change of slope of order one) from curvature.

The motor's perturbations are candidate rows of ONE sizing (sizer.api.size with the
perturbed Motor objects), and so are the load's figures (J, B, F, tau_ext: copies of the
pair's motor each driving its perturbed load, sizer.mechanics.load_figures, where the
design's engine reads them); every other input (a stage's ratio or efficiency, a
displacement, a duration) is two sizings, of its two perturbed designs. Pure: sizer.api,
the engine and the model objects, no printing, files or CLI.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from copy import copy
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, TypeVar

from sizer.errors import UserError
from sizer.model.cycle import Move

if TYPE_CHECKING:
    from sizer.model.domain import Design, Motor
    from sizer.sizing.results import CandidateResult

_T = TypeVar("_T")

STEP = 1e-6
"""The relative step h of the central differences (see the module's text)."""

KINK_TOLERANCE = 1e-3
"""One-sided slopes that differ by more than this (absolute, plus as much relative to the
larger) mark a kink; a smooth margin's differ by ~h times its curvature."""

T_MIN = "T_min"
"""The name of the minimized duration's row in :attr:`InputSensitivity.slopes`."""


@dataclass(frozen=True)
class Slope:
    """d quantity / d ln x of one margin (or T_min, in s): the central value, and where
    the quantity has a kink at x, both one-sided values."""

    central: float
    minus: float
    plus: float
    kink: bool

    @property
    def influence(self) -> float:
        """The magnitude that ranks the inputs: the larger one-sided value at a kink."""
        return max(abs(self.minus), abs(self.plus)) if self.kink else abs(self.central)


@dataclass(frozen=True)
class InputSensitivity:
    """One input: its name, value and unit, and the slope of each margin (by check name;
    ``T_min`` in minimize mode). ``limiting`` the limiting checks at x (1 - h) and
    x (1 + h) where they differ (else None)."""

    name: str
    value: float
    unit: str
    slopes: dict[str, Slope]
    limiting: tuple[str | None, str | None] | None = None

    def influence(self, t_min: float | None = None) -> float:
        """The largest |d margin / d ln x| and, given the nominal ``t_min``,
        |d ln T_min / d ln x| (T_min's slope relative to it, dimensionless like a
        margin's)."""
        values = [s.influence / (t_min if name == T_MIN and t_min else 1.0)
                  for name, s in self.slopes.items() if name != T_MIN or t_min]
        return max(values, default=0.0)

    @property
    def kinked(self) -> bool:
        return self.limiting is not None or any(s.kink for s in self.slopes.values())


@dataclass(frozen=True)
class Sensitivity:
    """The sensitivities of one pair: its nominal result and the inputs, most
    influential first."""

    result: CandidateResult
    minimize: bool
    step: float
    inputs: tuple[InputSensitivity, ...]
    skipped: tuple[tuple[str, str], ...] = ()
    """The inputs whose perturbed design cannot be sized (at an edge of its range: a
    closed cam cycle, a linkage's end), with the reason."""

    @property
    def quantities(self) -> tuple[str, ...]:
        """The margins' names (the checks' order), then T_min when minimizing."""
        names = tuple(str(c.name) for c in self.result.checks)
        return (*names, T_MIN) if self.minimize else names


# ---------------------------------------------------------------------- the pair


def pair(design: Design, motor: str | None = None, law: str | None = None
         ) -> CandidateResult:
    """The pair's nominal result: ``motor`` and ``law`` (each defaulting to the design's
    ``check:`` pair, else to the top-ranked feasible pair). UserError (field ``motor`` or
    ``law``) where a motor id is unknown, no pair is feasible, or minimizing the pair has
    no feasible duration."""
    from sizer import api

    motor = motor if motor is not None else design.chosen_motor
    spec = law if law is not None else (design.chosen_law.text if design.chosen_law
                                        else None)
    if motor is None or spec is None:
        ranked = api.size(api.override(
            design, motors=[motor] if motor is not None else None,
            laws=[spec] if spec is not None else None))
        best = next((r for r in ranked.results if r.feasible), None)
        if best is None:
            raise UserError("no feasible pair to take the sensitivities of; name one "
                            "with --motor and --law", field="motor")
        return best
    try:
        fixed = api.override(design, motors=[motor], laws=[spec])
    except UserError as error:
        raise UserError(error.message, field="motor" if error.field == "motors"
                        else "law") from None
    except ValueError as error:
        raise UserError(str(error), field="law") from None
    result = api.size(fixed).results[0]
    if design.machine_cycle.minimize and result.duration is None:
        raise UserError(f"{result.motor} with {result.spec} has no feasible duration to "
                        f"minimize ({result.reason or 'no duration meets every limit'})",
                        field="motor")
    return result


def fixed_pair(design: Design, result: CandidateResult) -> Design:
    """``design`` with only ``result``'s motor, drive and law, and the transmission the
    sizing chose (a ratio choice fixed: CandidateResult.fixed_in); the duration
    as the design has it (given, or minimized again)."""
    from sizer.laws.choice import law_choice
    from sizer.laws.per_move import LawsPerMove

    if isinstance(result.law_object, LawsPerMove):  # its laws written in, kept fixed
        from sizer.sizing.cycle import with_move_laws

        return with_move_laws(result.fixed_in(design), result.law_object)
    return replace(result.fixed_in(design), laws=(law_choice(result.spec),))


# ---------------------------------------------------------------------- the inputs


@dataclass(frozen=True)
class _Input:
    name: str
    value: float
    unit: str
    build: Callable[[float], Design] | None = None
    """The design with the input scaled by a factor (None: a motor figure)."""
    motor_field: str = ""


def _scaled(obj: _T, name: str, factor: float) -> _T:
    """``obj`` (a frozen dataclass) with its number ``name`` times ``factor``."""
    return replace(obj, **{name: getattr(obj, name) * factor})  # type: ignore[type-var]


LOAD_FIGURES = frozenset(f"load.{name}" for name in ("inertia", "mass", "damping", "friction",
                                                     "torque", "force"))
"""The inputs that are the load's figures (Load's inertia, damping, friction and torque; a
linear axis names them mass and force), which the engine takes per candidate row
(sizer.mechanics.load_figures)."""


MODE_INPUTS = frozenset(("load.natural_frequency", "load.damping_ratio"))
"""The inputs of the load's mode (they move the residual vibration only)."""


def row_input(design: Design, name: str) -> bool:
    """Whether the input ``name`` is one the engine of ``design`` takes per candidate row
    (a build of the machine, sizer.sizing.candidates.Builds: sizer.sizing.engine.
    reads_builds): the load's figures, a stage's ratio or efficiency
    (``transmission.ratio``, ``stage 2.efficiency``...) and the load's mode."""
    from sizer.sizing.engine import reads_builds

    stage = name.startswith(("transmission.", "stage ")) and name.endswith(
        (".ratio", ".efficiency"))
    return (name in LOAD_FIGURES or stage or name in MODE_INPUTS) \
        and reads_builds(design, name in MODE_INPUTS)


def design_inputs(design: Design) -> list[_Input]:
    """The inputs present and non-zero in ``design`` (fixed to one pair): the load's, the
    transmission stages', the task's and the motor's figures."""
    linear = design.machine_cycle.linear
    out: list[_Input] = []
    load = design.load
    for name, rotary, lin in (("inertia", "kg*m^2", "kg"), ("friction", "N*m", "N"),
                              ("damping", "N*m*s/rad", "N*s/m"), ("torque", "N*m", "N")):
        value = float(getattr(load, name))
        if value != 0.0:
            label = {"inertia": "mass", "torque": "force"}.get(name, name) if linear else name
            out.append(_Input(f"load.{label}", value, lin if linear else rotary,
                              _load(design, name)))
    out.extend(_mode_inputs(design))
    stages = design.transmission.stages
    for i, stage in enumerate(stages):
        prefix = f"stage {i + 1}" if len(stages) > 1 else "transmission"
        if stage.ratio != 1.0:
            out.append(_Input(f"{prefix}.ratio", stage.ratio, "", _stage(design, i, "ratio")))
        if 0.0 < stage.efficiency < 1.0:
            out.append(_Input(f"{prefix}.efficiency", stage.efficiency, "",
                              _stage(design, i, "efficiency")))
    task = design.machine_cycle.shorthand
    if task is not None:
        unit = "m" if linear else "rad"
        figures: tuple[tuple[str, float | None, str], ...] = (
            ("displacement", task.displacement, unit), ("duration", task.duration, "s"),
            ("dwell", task.dwell, "s"))
        for name, given, unit_ in figures:
            if given:
                out.append(_Input(f"task.{name}", float(given), unit_, _task(design, name)))
    elif not design.machine_cycle.shorthand:
        out.extend(_cycle_inputs(design))
    motor = design.motors[0]
    for name, unit in (("continuous_torque", "N*m"), ("peak_torque", "N*m"),
                       ("rated_speed", "rad/s"), ("inertia", "kg*m^2")):
        value = float(getattr(motor, name))
        if value != 0.0:
            out.append(_Input(f"motor.{name}", value, unit, motor_field=name))
    return out


def _mode_inputs(design: Design) -> list[_Input]:
    """The load's mode (sec. 7.1.1) where the design gives one: its natural frequency and
    (when not zero) its damping ratio; they move the residual vibration only."""
    elastic = design.load.elastic
    if elastic is None:
        return []

    def build(name: str) -> Callable[[float], Design]:
        def scaled(factor: float) -> Design:
            return replace(design, load=replace(design.load, elastic=_scaled(elastic, name,
                                                                               factor)))
        return scaled

    out = [_Input("load.natural_frequency", elastic.natural_frequency, "Hz",
                  build("natural_frequency"))]
    if elastic.damping_ratio > 0.0:
        out.append(_Input("load.damping_ratio", elastic.damping_ratio, "",
                          build("damping_ratio")))
    return out


def _cycle_inputs(design: Design) -> list[_Input]:
    """A cycle of segments: its cycle time (when given), each given segment duration and,
    in an open cycle, each move's displacement (a closed cycle must end where it starts)."""
    cycle = design.machine_cycle
    unit = "m" if cycle.linear else "rad"
    out: list[_Input] = []
    if cycle.cycle_time:
        out.append(_Input("cycle.cycle_time", float(cycle.cycle_time), "s",
                          _cycle(design, None, "cycle_time")))
    for i, segment in enumerate(cycle.segments):
        label = segment.name or f"segment {i + 1}"
        if isinstance(segment, Move) and segment.displacement and not cycle.closed:
            out.append(_Input(f"{label}.displacement", float(segment.displacement), unit,
                              _cycle(design, i, "displacement")))
        if segment.duration:
            out.append(_Input(f"{label}.duration", float(segment.duration), "s",
                              _cycle(design, i, "duration")))
    return out


def _cycle(design: Design, index: int | None, name: str) -> Callable[[float], Design]:
    cycle = design.machine_cycle

    def build(factor: float) -> Design:
        if index is None:
            return replace(design, machine_cycle=_scaled(cycle, name, factor))
        segments = list(cycle.segments)
        segments[index] = _scaled(segments[index], name, factor)
        return replace(design, machine_cycle=replace(cycle, segments=tuple(segments)))
    return build


def _load(design: Design, name: str) -> Callable[[float], Design]:
    def build(factor: float) -> Design:
        return replace(design, load=_scaled(design.load, name, factor))
    return build


def _task(design: Design, name: str) -> Callable[[float], Design]:
    from sizer.model.cycle import from_task

    task = design.machine_cycle.shorthand
    assert task is not None

    def build(factor: float) -> Design:
        return replace(design, machine_cycle=from_task(_scaled(task, name, factor)))
    return build


def _stage(design: Design, index: int, name: str) -> Callable[[float], Design]:
    def build(factor: float) -> Design:
        transmission = design.transmission
        stage = transmission.stages[index]
        return replace(design, transmission=transmission.with_stage(
            index, _scaled(stage, name, factor)))  # type: ignore[arg-type]
    return build


# ---------------------------------------------------------------------- the slopes


def _values(result: CandidateResult, minimize: bool) -> dict[str, float]:
    out = {str(c.name): float(c.margin) for c in result.checks}
    if minimize:
        out[T_MIN] = math.nan if result.duration is None else float(result.duration)
    return out


def _slope(minus: float, nominal: float, plus: float, h: float) -> Slope | None:
    if not all(math.isfinite(v) for v in (minus, nominal, plus)):
        return None
    down, up = (nominal - minus) / h, (plus - nominal) / h
    central = (plus - minus) / (2.0 * h)
    kink = abs(up - down) > KINK_TOLERANCE * (1.0 + max(abs(up), abs(down)))
    return Slope(central, down, up, kink)


def _input(item: _Input, nominal: CandidateResult, minus: CandidateResult,
           plus: CandidateResult, minimize: bool, h: float) -> InputSensitivity:
    base = _values(nominal, minimize)
    low, high = _values(minus, minimize), _values(plus, minimize)
    slopes = {}
    for name, value in base.items():
        slope = _slope(low.get(name, math.nan), value, high.get(name, math.nan), h)
        if slope is not None:
            slopes[name] = slope
    limiting = None
    if minus.limiting != plus.limiting or minus.limiting != nominal.limiting:
        limiting = (minus.limiting, plus.limiting)
    return InputSensitivity(item.name, item.value, item.unit, slopes, limiting)


def _motor_results(design: Design, motors: Sequence[Motor]) -> list[CandidateResult]:
    """The perturbed motors sized in one call (candidate rows), in the order given."""
    from sizer import api

    results = api.size(design, motors=list(motors)).results
    out = []
    for motor in motors:
        match = next((r for r in results if r.motor_object == motor), None)
        if match is None:  # pragma: no cover - the engine returns every candidate
            raise RuntimeError(f"no result for the perturbed motor {motor!r}")
        out.append(match)
    return out


def _row_results(design: Design, inputs: Sequence[_Input], step: float
                 ) -> dict[_Input, tuple[CandidateResult, CandidateResult]]:
    """The ``inputs`` the engine takes per row (:func:`row_input`) each at 1 -+ ``step``
    as candidate rows of one sizing (copies of the pair's motor, each in its build of the
    machine: sizer.sizing.candidates.Builds), where the design's engine reads them; empty
    where it does not, or where a build cannot be sized (each is then sized alone)."""
    from sizer import api
    from sizer.sizing.candidates import Builds
    from sizer.sizing.engine import size_design

    if not inputs:
        return {}
    builds: list[Design] = []
    for item in inputs:
        assert item.build is not None, "a load figure is the design's input"
        builds += [item.build(1.0 - step), item.build(1.0 + step)]
    copies = [copy(design.motors[0]) for _ in builds]  # each its own object: its row
    try:
        sized = size_design(api.override(design, motors=copies),
                            builds=Builds.of(builds, design))
    except (UserError, ValueError):
        return {}
    found = {id(r.motor_object): r for r in sized.results}
    rows = [found[id(c)] for c in copies]
    return {item: (rows[2 * k], rows[2 * k + 1]) for k, item in enumerate(inputs)}


def sensitivity(design: Design, motor: str | None = None, law: str | None = None, *,
                step: float = STEP) -> Sensitivity:
    """The sensitivities of the pair (:func:`pair`) of ``design``, most influential
    input first."""
    from sizer import api

    nominal_pair = pair(design, motor, law)
    fixed = fixed_pair(design, nominal_pair)
    minimize = design.machine_cycle.minimize
    nominal = api.size(fixed).results[0]
    if nominal.spec != nominal_pair.spec:  # a law per move written in: the pair's label
        nominal = replace(nominal, law_object=nominal_pair.law_object)
    inputs = design_inputs(fixed)
    rows: list[InputSensitivity] = []
    motor_inputs = [i for i in inputs if i.build is None]
    if motor_inputs:
        base = fixed.motors[0]
        perturbed = [_scaled(base, i.motor_field, f) for i in motor_inputs
                     for f in (1.0 - step, 1.0 + step)]
        sized = _motor_results(fixed, perturbed)  # type: ignore[arg-type]
        for k, item in enumerate(motor_inputs):
            rows.append(_input(item, nominal, sized[2 * k], sized[2 * k + 1], minimize,
                               step))
    skipped: list[tuple[str, str]] = []
    batched = _row_results(fixed, [i for i in inputs if row_input(fixed, i.name)], step)
    for item, (low, high) in batched.items():
        rows.append(_input(item, nominal, low, high, minimize, step))
    for item in inputs:
        if item.build is None or item in batched:
            continue
        try:
            low = api.size(item.build(1.0 - step)).results[0]
            high = api.size(item.build(1.0 + step)).results[0]
        except (UserError, ValueError) as error:  # the design is at an edge of this input
            message = error.message if isinstance(error, UserError) else str(error)
            skipped.append((item.name, message))
            continue
        rows.append(_input(item, nominal, low, high, minimize, step))
    t_min = nominal.duration if minimize else None
    rows.sort(key=lambda r: -r.influence(t_min))
    return Sensitivity(nominal, minimize, step, tuple(rows), tuple(skipped))
