"""The sanity rules of a catalog motor, written once: a registry of rule objects.

The schema (:class:`sizer.io.schema.inputs.MotorInput` and the ranges of
:mod:`sizer.io.schema.ranges`) holds units, types and each field's range; the rules of
:data:`RULES` look at how a motor's figures fit together. Each rule has a name, what it
checks, its kind and the function that finds its problems in one motor (with the
message); the loader (:mod:`sizer.io.loader`), ``sizer catalog validate`` and the CSV
import (:mod:`sizer.catalog_tools`) all run these. Three kinds:

- ``impossible`` (an error, refused at load, exit 2): peak torque below the continuous
  torque, max speed below the rated speed, a curve of fewer than 2 points or with speeds
  not strictly increasing, a curve point beyond max_speed, the continuous region above
  the intermittent one at some speed (both regions completed the book's way, compared on
  the union of their corner speeds, where their difference is extreme: it is piecewise
  linear);
- ``catalog`` (an error of ``sizer catalog validate`` only; loading accepts them): a real
  motor without rotor inertia (0 is the textbook idealization, its rotor counted in the
  load) and a motor without a source;
- ``warning``: the plausibility bands below, a curve's first torque far from the scalar
  rating, a continuous region reaching beyond the intermittent one's speed.

The rules that loading applies to every motor of a catalog also have a ``screen``: the
same test on the catalog's columns at once (numpy), true for every motor the rule may
concern (exactly the rule for the scalar ones, a superset for the curves and regions), so
that the exact rule runs only on those motors.

The plausibility bands (:data:`BANDS`) are the range of the 64 bundled motors
(sizer/catalogs/*.yaml: Yaskawa, Mitsubishi, Siemens, TECO, maxon) and of the other
motors in the research notes (motor-data.md: Beckhoff AM3000/AM8000, Wittenstein premo,
maxon and Pittman DC motors), widened by a factor of about 3 to 10. They warn in
``sizer catalog validate`` for every figure, and at loading for a bare number
(:mod:`sizer.io.plausibility`):

==========================  ==========================  ==========================  =========
figure                      bundled motors              with motor-data.md          band
==========================  ==========================  ==========================  =========
tau_p / tau_c               2.35 .. 5.06                up to 20 (DC stall torque)  1 .. 30
tau_p / J_m [rad/s^2]       7.2e3 .. 2.6e5              up to 4e5 (AM3011)          5e2 .. 5e6
tau_c v_n / J_m [W/kg m^2]  5.7e5 .. 2.7e7              up to 9e7 (AM3011)          5e4 .. 1e9
max speed / rated speed     1.0 .. 2.0                  up to 1.6 (maxon 353297)    1 .. 6
rated speed [rpm]           1500 .. 6000                1000 .. 8000 (AM3000)       50 .. 15000
max speed [rpm]             3000 .. 9000                up to 10530 (premo 1C)      <= 25000
==========================  ==========================  ==========================  =========

tau_p / J_m is the motor's acceleration capacity (its own rotor at peak torque), tau_c v_n /
J_m the rated power per rotor inertia: a 100 W motor of 3 kg*m^2 has 33 W/(kg*m^2). A
speed in rad/s where rpm was meant is 9.55 times too high (3000 rpm written as '3000 rad/s'
is 28648 rpm). Idealized textbook motors (manufacturer 'idealized ...') are not checked
for plausibility.
"""

from __future__ import annotations

import itertools
import math
import re
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np

from sizer.envelope import continuous_region, intermittent_region
from sizer.model.domain import Curve, Motor

Severity = Literal["error", "warning"]
RuleKind = Literal["impossible", "catalog", "warning"]

RPM = math.pi / 30
"""rad/s per rpm."""
RPM_PER_RAD_S = 30.0 / math.pi

RELATIVE_TOLERANCE = 1e-9
"""Rounding allowance when comparing figures given in different units."""

CURVE_START_TOLERANCE = 0.10
"""A curve's first torque may differ from the scalar rating by this fraction (a warning)."""

PEAK_TO_CONTINUOUS = (1.0, 30.0)
ACCELERATION_CAPACITY = (5e2, 5e6)
"""tau_p / J_m, rad/s^2."""
POWER_PER_INERTIA = (5e4, 1e9)
"""tau_c v_n / J_m, W/(kg*m^2)."""
MAX_TO_RATED_SPEED = (1.0, 6.0)
RATED_SPEED = (50 * RPM, 15000 * RPM)
MAX_SPEED = 25000 * RPM

IDEALIZED_MARK = "idealized"
"""A manufacturer text containing this word marks textbook motors: no rotor inertia needed."""

CURVES = (("continuous_curve", "continuous_torque"), ("intermittent_curve", "peak_torque"))
"""The curves of a motor and the scalar rating each starts from."""


def is_idealized(manufacturer: str | None) -> bool:
    """True for the textbook motors (``manufacturer: idealized ...``)."""
    return manufacturer is not None and IDEALIZED_MARK in manufacturer.lower()


# ------------------------------------------------------------------ figures


@dataclass(frozen=True)
class Figures:
    """The scalar figures of one motor (floats) or of a catalog's motors (arrays), SI;
    ``max_speed`` is NaN where none is given. A rule's test reads the same attributes in
    both cases."""

    inertia: Any
    continuous_torque: Any
    peak_torque: Any
    rated_speed: Any
    max_speed: Any

    @classmethod
    def of(cls, motor: Motor) -> Figures:
        """The figures of one motor, as numpy scalars (a division by 0 gives inf)."""
        top = math.nan if motor.max_speed is None else motor.max_speed
        return cls(*(np.float64(x) for x in (motor.inertia, motor.continuous_torque,
                                             motor.peak_torque, motor.rated_speed, top)))


@dataclass(frozen=True)
class CurveColumns:
    """One curve of every motor of a catalog, flat: the points of motor i are
    ``speed[start[i]:start[i] + count[i]]``; ``given[i]`` is False where it has none."""

    given: np.ndarray
    start: np.ndarray
    count: np.ndarray
    speed: np.ndarray
    torque: np.ndarray

    def reduce(self, values: np.ndarray, ufunc: np.ufunc, empty: float) -> np.ndarray:
        """``ufunc.reduce`` of ``values`` (one per point) over each motor's points;
        ``empty`` for a motor without points."""
        out = np.full(len(self.count), empty)
        rows = self.count > 0
        if rows.any():
            out[rows] = ufunc.reduceat(values, self.start[rows])
        return out


@dataclass(frozen=True)
class MotorColumns:
    """The figures and curves of a catalog's motors as columns (for the screens)."""

    figures: Figures
    curves: Mapping[str, CurveColumns]
    idealized: np.ndarray


# ------------------------------------------------------------------ problems and rules


@dataclass(frozen=True)
class MotorProblem:
    """A problem at ``path`` inside the motor's mapping, e.g. ("continuous_curve", 2).

    ``at_load``: loading the catalog refuses it (an impossible motor); the other errors
    are rules of ``sizer catalog validate``.
    """

    path: tuple[Any, ...]
    message: str
    severity: Severity = "error"
    at_load: bool = False


@dataclass(frozen=True)
class Context:
    """What a rule may read beside the motor: the catalog-level defaults, the motor's
    mapping as written (a warning names the bare number behind it)."""

    manufacturer: str | None = None
    source: str | None = None
    given: Mapping[str, Any] = field(default_factory=dict)


Finder = Callable[[Motor, Context], list[tuple[tuple[Any, ...], str]]]
"""A rule's test of one motor: its problems as (path, message)."""


@dataclass(frozen=True)
class MotorRule:
    """One sanity rule: ``name``, what it ``checks``, its ``kind``, how it finds its
    problems in a motor (``find``) and, for the rules loading applies, ``screen``: the
    motors of a catalog it may concern, from the columns at once (never fewer than
    ``find`` reports)."""

    name: str
    checks: str
    kind: RuleKind
    find: Finder
    screen: Callable[[MotorColumns], np.ndarray] | None = None

    @property
    def severity(self) -> Severity:
        return "warning" if self.kind == "warning" else "error"

    def problems(self, motor: Motor, context: Context) -> list[MotorProblem]:
        return [MotorProblem(path, message, self.severity, self.kind == "impossible")
                for path, message in self.find(motor, context)]


def _rpm(speed: float) -> str:
    return f"{speed * RPM_PER_RAD_S:.5g} rpm"


def _band_rpm(speed: float) -> str:
    """A speed in the bands' messages: divided by RPM, where :func:`_rpm` multiplies by its
    inverse (the two round apart at some ties of the 5th digit; each message is kept as
    it was written)."""
    return f"{speed / RPM:.5g} rpm"


def _nm(torque: float) -> str:
    return f"{torque:.4g} N*m"


def _quotient(a: Any, b: Any) -> Any:
    """a / b for numpy scalars or arrays, inf (or NaN) where b is 0."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.divide(a, b)


# ------------------------------------------------------------------ scalar rules


def _peak_below_continuous(f: Figures) -> Any:
    return f.peak_torque < f.continuous_torque * (1 - RELATIVE_TOLERANCE)


def _max_below_rated(f: Figures) -> Any:
    return f.max_speed < f.rated_speed * (1 - RELATIVE_TOLERANCE)


def _max_below_rated_text(m: Motor) -> str:
    assert m.max_speed is not None  # found only where given (a missing one is NaN: False)
    return f"max speed {_rpm(m.max_speed)} is below the rated speed {_rpm(m.rated_speed)}"


def _scalar_rule(name: str, checks: str, test: Callable[[Figures], Any], at: str,
                 message: Callable[[Motor], str]) -> MotorRule:
    """An impossible motor by its scalar figures: ``test`` on one motor or the columns."""

    def find(motor: Motor, context: Context) -> list[tuple[tuple[Any, ...], str]]:
        return [((at,), message(motor))] if test(Figures.of(motor)) else []

    return MotorRule(name, checks, "impossible", find, lambda c: test(c.figures))


def _no_rotor_inertia(motor: Motor, context: Context) -> list[tuple[tuple[Any, ...], str]]:
    if motor.inertia > 0 or is_idealized(motor.manufacturer or context.manufacturer):
        return []
    return [(("inertia",), "the rotor inertia is 0: a real motor needs its datasheet "
                           "inertia (only idealized textbook motors, manufacturer "
                           f"'{IDEALIZED_MARK} ...', may have 0)")]


def _no_source(motor: Motor, context: Context) -> list[tuple[tuple[Any, ...], str]]:
    if (motor.source or context.source or "").strip():
        return []
    return [(("source",), "no source: give the datasheet's title and web address (on the "
                          "motor, or 'source:' at the catalog level)")]


# ------------------------------------------------------------------ plausibility bands


@dataclass(frozen=True)
class Band:
    """A plausibility band of servomotor figures: ``outside`` tells whether a motor's
    figures (one motor or the columns) leave it; ``text`` words it for one motor.
    ``field`` is where it is reported, ``fields`` all the figures involved."""

    name: str
    field: str
    fields: tuple[str, ...]
    outside: Callable[[Figures], Any]
    text: Callable[[Figures], str]


@dataclass(frozen=True)
class Implausible:
    """A motor figure outside a band: where it is reported, the figures involved, why."""

    field: str
    fields: tuple[str, ...]
    message: str


def _power_per_inertia_outside(f: Figures) -> Any:
    ratio = _quotient(f.continuous_torque * f.rated_speed, f.inertia)
    return (f.inertia > 0) & ((ratio < POWER_PER_INERTIA[0]) | (ratio > POWER_PER_INERTIA[1]))


def _power_per_inertia_text(f: Figures) -> str:
    power = f.continuous_torque * f.rated_speed
    low, high = POWER_PER_INERTIA
    return (f"a rotor inertia of {f.inertia:.4g} kg*m^2 for {power:.4g} W rated power "
            f"(continuous torque x rated speed) is {power / f.inertia:.3g} W per kg*m^2, "
            f"outside the range of servomotors ({low:g} to {high:g})")


def _capacity_outside(f: Figures) -> Any:
    capacity = _quotient(f.peak_torque, f.inertia)
    return (f.inertia > 0) & ((capacity < ACCELERATION_CAPACITY[0])
                              | (capacity > ACCELERATION_CAPACITY[1]))


def _capacity_text(f: Figures) -> str:
    low, high = ACCELERATION_CAPACITY
    return (f"peak torque / rotor inertia = {f.peak_torque / f.inertia:.3g} rad/s^2 is "
            f"outside the range of servomotors ({low:g} to {high:g} rad/s^2): check the "
            f"inertia's unit (1 kg*cm^2 = 1e-4 kg*m^2)")


BANDS: tuple[Band, ...] = (
    Band("peak_to_continuous", "peak_torque", ("peak_torque", "continuous_torque"),
         lambda f: _quotient(f.peak_torque, f.continuous_torque) > PEAK_TO_CONTINUOUS[1],
         lambda f: f"peak torque {f.peak_torque:.4g} N*m is "
                   f"{f.peak_torque / f.continuous_torque:.3g} times the continuous torque "
                   f"{f.continuous_torque:.4g} N*m; servomotors have at most "
                   f"{PEAK_TO_CONTINUOUS[1]:g} (check the units)"),
    Band("power_per_inertia", "inertia", ("inertia", "continuous_torque", "rated_speed"),
         _power_per_inertia_outside, _power_per_inertia_text),
    Band("acceleration_capacity", "inertia", ("inertia", "peak_torque"),
         _capacity_outside, _capacity_text),
    Band("rated_speed", "rated_speed", ("rated_speed",),
         lambda f: (f.rated_speed < RATED_SPEED[0]) | (f.rated_speed > RATED_SPEED[1]),
         lambda f: f"rated speed {_band_rpm(f.rated_speed)} is outside the range of "
                   f"servomotors ({_band_rpm(RATED_SPEED[0])} to {_band_rpm(RATED_SPEED[1])}): "
                   f"check its unit (a bare number is rad/s)"),
    Band("max_speed", "max_speed", ("max_speed",),
         lambda f: f.max_speed > MAX_SPEED,
         lambda f: f"max speed {_band_rpm(f.max_speed)} is above {_band_rpm(MAX_SPEED)}, beyond "
                   f"servomotors: check its unit (a bare number is rad/s)"),
    Band("max_to_rated_speed", "max_speed", ("max_speed", "rated_speed"),
         lambda f: _quotient(f.max_speed, f.rated_speed) > MAX_TO_RATED_SPEED[1],
         lambda f: f"max speed {_band_rpm(f.max_speed)} is {f.max_speed / f.rated_speed:.3g} "
                   f"times the rated speed {_band_rpm(f.rated_speed)}; servomotors have at most "
                   f"{MAX_TO_RATED_SPEED[1]:g} (are both in the same unit?)"),
)
"""The bands of the module's table, in the order their warnings are given."""


def implausibilities(motor: Motor) -> list[Implausible]:
    """The figures of a motor outside the bands (idealized motors included: the callers
    skip them)."""
    figures = Figures.of(motor)
    return [Implausible(band.field, band.fields, band.text(figures))
            for band in BANDS if band.outside(figures)]


def maybe_implausible(columns: MotorColumns) -> np.ndarray:
    """The motors of a catalog (boolean mask) outside some band, idealized ones excepted."""
    out = np.zeros(len(columns.idealized), dtype=bool)
    for band in BANDS:
        out |= band.outside(columns.figures)
    return out & ~columns.idealized


SI_UNITS = {"inertia": "kg*m^2", "continuous_torque": "N*m", "peak_torque": "N*m",
            "rated_speed": "rad/s", "max_speed": "rad/s"}

_NUMBER = re.compile(r"^\s*[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?\s*$")


def is_bare(value: Any) -> bool:
    """A number without a unit: an int or float, or a text holding only a number."""
    if isinstance(value, bool):
        return False
    return isinstance(value, int | float) or (isinstance(value, str)
                                              and _NUMBER.match(value) is not None)


def bare_note(found: Implausible, given: Mapping[str, Any]) -> str:
    """'bare number 3 read as 3 kg*m^2' for the first bare figure involved, or ''."""
    for name in found.fields:
        value = given.get(name)
        if is_bare(value):
            shown = str(value).strip()
            return f"bare number {shown} read as {shown} {SI_UNITS[name]}"
    return ""


def _band_rule(band: Band) -> MotorRule:
    def find(motor: Motor, context: Context) -> list[tuple[tuple[Any, ...], str]]:
        if is_idealized(motor.manufacturer or context.manufacturer):
            return []
        figures = Figures.of(motor)
        if not band.outside(figures):
            return []
        note = bare_note(Implausible(band.field, band.fields, ""), context.given)
        message = f"implausible: {band.text(figures)}" + (f" ({note})" if note else "")
        return [((band.field,), message)]

    return MotorRule(f"plausible_{band.name}", f"{band.name.replace('_', ' ')} within the "
                     f"band of servomotors", "warning", find)


# ------------------------------------------------------------------ curves and regions


def curve_usable(points: Curve | None) -> bool:
    """A curve that is a region's boundary: at least 2 points, speeds strictly increasing."""
    return points is not None and len(points) >= 2 and all(
        b[0] > a[0] for a, b in itertools.pairwise(points))


def _curve_rule(name: str, curve: str, checks: str, find: Finder,
                screen: Callable[[CurveColumns, Figures], np.ndarray] | None,
                kind: RuleKind = "impossible") -> MotorRule:
    return MotorRule(f"{curve}.{name}", checks, kind, find,
                     None if screen is None else
                     (lambda c: screen(c.curves[curve], c.figures)))


def _too_few(curve: str) -> Finder:
    def find(motor: Motor, context: Context) -> list[tuple[tuple[Any, ...], str]]:
        points = getattr(motor, curve)
        if points is None or len(points) >= 2:
            return []
        return [((curve,), f"a speed-torque curve needs at least 2 points, got {len(points)}")]

    return find


def _not_increasing(curve: str) -> Finder:
    def find(motor: Motor, context: Context) -> list[tuple[tuple[Any, ...], str]]:
        points = getattr(motor, curve) or ()
        return [((curve, index), f"curve speeds must be strictly increasing: "
                                 f"{_rpm(points[index][0])} follows "
                                 f"{_rpm(points[index - 1][0])}")
                for index in range(1, len(points))
                if not points[index][0] > points[index - 1][0]]

    return find


def _not_increasing_screen(c: CurveColumns, f: Figures) -> np.ndarray:
    steps = np.diff(c.speed) <= 0
    steps[c.start[c.count > 0][1:] - 1] = False  # across two motors' curves
    return c.reduce(np.append(steps, False), np.logical_or, 0.0).astype(bool)


def _beyond_max_speed(curve: str) -> Finder:
    def find(motor: Motor, context: Context) -> list[tuple[tuple[Any, ...], str]]:
        points, top = getattr(motor, curve), motor.max_speed
        if not points or top is None or points[-1][0] <= top * (1 + RELATIVE_TOLERANCE):
            return []
        beyond = next(i for i, p in enumerate(points) if p[0] > top * (1 + RELATIVE_TOLERANCE))
        return [((curve, beyond), f"the curve reaches {_rpm(points[beyond][0])}, above "
                                  f"max_speed {_rpm(top)}")]

    return find


def _beyond_max_speed_screen(c: CurveColumns, f: Figures) -> np.ndarray:
    highest = c.reduce(c.speed, np.maximum, -np.inf)
    return highest > f.max_speed * (1 + RELATIVE_TOLERANCE)


def _far_start(curve: str, rating: str) -> Finder:
    def find(motor: Motor, context: Context) -> list[tuple[tuple[Any, ...], str]]:
        points, value = getattr(motor, curve), getattr(motor, rating)
        if not curve_usable(points):
            return []
        first = points[0][1]
        if abs(first - value) <= CURVE_START_TOLERANCE * value:
            return []
        return [((curve, 0), f"the curve starts at {_nm(first)}, more than "
                             f"{CURVE_START_TOLERANCE:.0%} away from {rating} {_nm(value)}")]

    return find


def _regions(motor: Motor) -> tuple[Curve, Curve, tuple[Any, ...]] | None:
    """The two regions completed the book's way and where a problem of theirs is reported;
    None unless the motor has a curve and its curves are usable."""
    curves = (motor.continuous_curve, motor.intermittent_curve)
    if not any(curves) or any(c is not None and not curve_usable(c) for c in curves):
        return None
    at = ("continuous_curve",) if motor.continuous_curve else ("continuous_torque",)
    return continuous_region(motor), intermittent_region(motor), at


def _limit(curve: Curve, speed: float) -> float:
    """The piecewise linear torque limit of ``curve`` at ``speed`` (inside its range)."""
    for (s0, t0), (s1, t1) in itertools.pairwise(curve):
        if s0 <= speed <= s1:
            return t0 + (t1 - t0) * (speed - s0) / (s1 - s0)
    return curve[-1][1] if speed >= curve[-1][0] else curve[0][1]


def _crossing_regions(motor: Motor, context: Context) -> list[tuple[tuple[Any, ...], str]]:
    """The continuous region must lie under the intermittent one, compared where both are
    defined (two rectangles compare as peak >= continuous torque, checked above)."""
    found = _regions(motor)
    if found is None:
        return []
    continuous, intermittent, at = found
    top = min(continuous[-1][0], intermittent[-1][0])
    speeds = sorted({s for s, _ in (*continuous, *intermittent) if s <= top})
    worst, speed = max((_limit(continuous, s) - _limit(intermittent, s), s) for s in speeds)
    low, high = _limit(continuous, speed), _limit(intermittent, speed)
    if low <= high * (1 + RELATIVE_TOLERANCE) + 1e-12:
        return []
    what = "curve" if motor.continuous_curve else "torque"
    return [(at, f"the continuous region is above the intermittent region at {_rpm(speed)} "
                 f"({speed:.5g} rad/s): {_nm(low)} > {_nm(high)}, by {_nm(worst)} (the "
                 f"continuous {what} must lie under the intermittent one at every speed)")]


def _crossing_screen(c: MotorColumns) -> np.ndarray:
    """Motors with a curve whose continuous torques are not all below the intermittent
    ones: two piecewise linear limits lie within their points' torques."""
    continuous, intermittent = c.curves["continuous_curve"], c.curves["intermittent_curve"]
    highest = np.where(continuous.given, continuous.reduce(continuous.torque, np.maximum,
                                                           -np.inf),
                       c.figures.continuous_torque)
    lowest = np.where(intermittent.given, intermittent.reduce(intermittent.torque, np.minimum,
                                                              np.inf),
                      c.figures.peak_torque)
    return ((continuous.given | intermittent.given)
            & ~(highest <= lowest * (1 + RELATIVE_TOLERANCE) + 1e-12))


def _reach_beyond(motor: Motor, context: Context) -> list[tuple[tuple[Any, ...], str]]:
    found = _regions(motor)
    if found is None:
        return []
    continuous, intermittent, at = found
    if continuous[-1][0] <= intermittent[-1][0] * (1 + RELATIVE_TOLERANCE):
        return []
    return [(at, f"the continuous region reaches {_rpm(continuous[-1][0])}, beyond the "
                 f"intermittent region (up to {_rpm(intermittent[-1][0])}); the sizing limits "
                 f"the speed to the intermittent region")]


def _curve_rules(curve: str, rating: str) -> tuple[MotorRule, ...]:
    return (
        _curve_rule("points", curve, "at least 2 points", _too_few(curve),
                    lambda c, f: c.given & (c.count < 2)),
        _curve_rule("increasing", curve, "speeds strictly increasing", _not_increasing(curve),
                    _not_increasing_screen),
        _curve_rule("within_max_speed", curve, "no point beyond max_speed",
                    _beyond_max_speed(curve), _beyond_max_speed_screen),
        _curve_rule("start", curve, f"the first torque within "
                    f"{CURVE_START_TOLERANCE:.0%} of {rating}", _far_start(curve, rating),
                    None, "warning"),
    )


RULES: tuple[MotorRule, ...] = (
    _scalar_rule("peak_at_least_continuous", "peak torque >= continuous torque",
                 _peak_below_continuous, "peak_torque",
                 lambda m: f"peak torque {_nm(m.peak_torque)} is below the continuous "
                           f"torque {_nm(m.continuous_torque)}"),
    _scalar_rule("max_speed_at_least_rated", "max speed >= rated speed",
                 _max_below_rated, "max_speed", _max_below_rated_text),
    MotorRule("rotor_inertia", "a real motor has a rotor inertia > 0", "catalog",
              _no_rotor_inertia),
    MotorRule("source", "a source (the datasheet), on the motor or the catalog", "catalog",
              _no_source),
    *(_band_rule(band) for band in BANDS),
    *(rule for curve, rating in CURVES for rule in _curve_rules(curve, rating)),
    MotorRule("regions_nested", "the continuous region under the intermittent one at every "
              "speed", "impossible", _crossing_regions, _crossing_screen),
    MotorRule("continuous_within_intermittent_speed", "the continuous region ends at or "
              "before the intermittent one", "warning", _reach_beyond),
)
"""Every sanity rule of a motor, in the order of its problems."""


# ------------------------------------------------------------------ running the rules


def check_motor(motor: Motor, *, manufacturer: str | None = None, source: str | None = None,
                given: Mapping[str, Any] | None = None,
                rules: bool = True) -> list[MotorProblem]:
    """Every problem of a motor whose fields are valid, in the order of :data:`RULES`.

    ``motor`` is a domain Motor or a validated ``MotorInput``. ``manufacturer`` and
    ``source`` are the catalog-level defaults, used where the motor has none of its own.
    ``given`` is the motor's mapping as written: a plausibility warning names the bare
    number it involves. ``rules=False`` runs the impossible rules only.
    """
    if not isinstance(motor, Motor):
        motor = motor_of(motor)
    context = Context(manufacturer, source, given or {})
    return [problem for rule in RULES if rules or rule.kind == "impossible"
            for problem in rule.problems(motor, context)]


def impossibilities(motor: Motor) -> list[MotorProblem]:
    """The problems that make a motor physically impossible (refused at load)."""
    return check_motor(motor, rules=False)


def maybe_impossible(columns: MotorColumns) -> np.ndarray:
    """The motors of a catalog (boolean mask) some impossible rule may concern."""
    out = np.zeros(len(columns.idealized), dtype=bool)
    for rule in RULES:
        if rule.kind == "impossible":
            assert rule.screen is not None, rule.name
            out |= rule.screen(columns)
    return out


def motor_of(item: Any) -> Motor:
    """The domain Motor of a validated ``MotorInput`` (curves as (speed, torque) pairs)."""
    return Motor(
        id=item.id, inertia=item.inertia, continuous_torque=item.continuous_torque,
        peak_torque=item.peak_torque, rated_speed=item.rated_speed, max_speed=item.max_speed,
        continuous_curve=_pairs(item.continuous_curve),
        intermittent_curve=_pairs(item.intermittent_curve),
        damping=item.damping, source=item.source, part_number=item.part_number,
        manufacturer=item.manufacturer, price=item.price, mass=item.mass,
        torque_constant=item.torque_constant,
        winding_resistance=line_to_line(item.winding_resistance, item.phase_resistance),
        winding_inductance=line_to_line(item.winding_inductance, item.phase_inductance),
        back_emf_constant=item.back_emf_constant,
        poles=None if item.poles is None else int(item.poles),
        continuous_current=item.continuous_current, peak_current=item.peak_current,
        dc_bus_voltage=bus_voltage(item.dc_bus_voltage, item.supply_voltage),
        commutation=item.commutation,
        brake_holding_torque=item.brake_holding_torque,
        brake_inertia=item.brake_inertia or 0.0,
        thermal_time_constant=item.thermal_time_constant,
        max_winding_temperature_rise=item.max_winding_temperature_rise,
        torque_current_curve=None if item.torque_current_curve is None else tuple(
            (p.current, p.torque) for p in item.torque_current_curve),
        radial_load=item.radial_load, axial_load=item.axial_load,
        radial_load_point=item.radial_load_point)


def line_to_line(winding: float | None, phase: float | None) -> float | None:
    """The phase-to-phase resistance from the one given: ``winding_resistance`` as it is,
    a ``phase_resistance`` (per phase of a star) doubled."""
    if winding is not None:
        return winding
    return None if phase is None else 2.0 * phase


def bus_voltage(dc_bus: float | None, supply: float | None) -> float | None:
    """The DC link from the one given: ``dc_bus_voltage`` as it is, an AC ``supply_voltage``
    (line to line, RMS) rectified to its peak, sqrt(2) times it (a diode bridge's DC link
    without load)."""
    if dc_bus is not None:
        return dc_bus
    return None if supply is None else math.sqrt(2.0) * supply


def _pairs(points: Sequence[Any] | None) -> Curve | None:
    if points is None:
        return None
    return tuple((p.speed, p.torque) for p in points)
