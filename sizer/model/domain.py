"""Domain objects in SI units (rad, rad/s, s, N*m, kg*m^2, m, N).

These are what the core (sizer.sizing, sizer.envelope, sizer.mechanics) reads. They are
built from YAML by sizer.io (which checks units and ranges) or directly from Python.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field, fields, replace
from pathlib import Path
from typing import TYPE_CHECKING, Literal

from sizer.model.cycle import Cycle, Task, from_task
from sizer.model.tolerance import Tolerance, tolerance_of
from sizer.vibration.elastic_load import ElasticLoad

if TYPE_CHECKING:
    from sizer.laws.choice import LawChoice

ThermalSpeedRule = Literal["max", "rms", "mean"]
"""Speed at which the RMS torque is checked against the continuous region (sec. 6.1.1)."""

EfficiencyRule = Literal["power_flow", "steady_load"]
"""Where the efficiencies act: on the whole torque in the direction of power flow
(Siemens, Mitsubishi; sizer's default), or on the load's steady torque only, the inertial
torque passing without loss (Yaskawa: T_L = F P / (2 pi R eta), T_a = J omega / t_a)."""

ThermalDuty = Literal["repeated", "once"]
"""A machine cycle repeated without end, or a one-off sequence (issue 16)."""
InertiaRatioRule = Literal["driven", "load"]
Commutation = Literal["sinusoidal", "block"]
"""A motor's winding fed with sinusoidal currents (an AC servo) or in six steps (a
brushless DC motor: maxon's EC data)."""
"""Numerator of the inertia ratio: everything the motor drives (load, screw, gears,
couplings, reflected to the motor; the vendors' definition) or the load alone."""

EnvelopeRule = Literal["book", "linear", "linear_intermittent", "electrical"]
"""How a region without a curve is completed up to max_speed (sizer.envelope.completion)."""
DEFAULT_ENVELOPE: EnvelopeRule = "electrical"
"""The rule of a design that names none (sizer.envelope.completion: why)."""

Curve = tuple[tuple[float, float], ...]
"""(speed rad/s, torque N*m) points, speed strictly increasing, piecewise linear between."""


@dataclass(frozen=True)
class Load:
    """The driven load at the load side (sec. 6.1.1, eq. 6.1).

    Rotary: inertia kg*m^2, damping N*m*s/rad, friction and torque N*m.
    Linear: mass kg (in ``inertia``), damping N*s/m, friction and force N (in ``torque``).
    ``friction`` is Coulomb friction opposing motion; ``torque`` a constant external load
    (gravity...) with its sign: positive opposes a positive move.
    """

    inertia: float
    damping: float = 0.0
    friction: float = 0.0
    torque: float = 0.0
    elastic: ElasticLoad | None = None
    """The load's mode of vibration (sec. 7.1.1) where the design gives one: each move's
    residual vibration is then computed (sizer.sizing.vibration_check)."""
    gravity: GravityLoad | None = None
    """Gravity on an arm, a torque of the load's position (sec. 5.2.2, docs/position-loads.md)."""
    spring: SpringLoad | None = None
    """A spring on the load, a torque or force of its position (docs/position-loads.md)."""
    table: TableLoad | None = None
    """A torque of the load's position given as a table (docs/position-loads.md)."""
    inertia_table: InertiaTableLoad | None = None
    """An inertia of the load's position given as a table, added to ``inertia``
    (docs/position-loads.md)."""

    @property
    def position_dependent(self) -> bool:
        """Whether a term of the load depends on its position (gravity on an arm, a
        spring, a table, an inertia table)."""
        return any(t is not None and t.active for t in (self.gravity, self.spring, self.table,
                                                        self.inertia_table))

    @property
    def position_knots(self) -> tuple[float, ...]:
        """The positions q (from the start of the move) where a position term has a kink:
        a table's knots, an inertia table's (empty without)."""
        out: tuple[float, ...] = ()
        if self.table is not None and self.table.active:
            out = self.table.knots
        if self.inertia_table is not None and self.inertia_table.varies:
            out = out + self.inertia_table.knots
        return tuple(sorted(set(out)))

    def position_torque(self, q):
        """The load's torque (force) of its position q (rad or m from the start of the
        move), positive opposing a positive move: the sum of its position terms (0 without)."""
        import numpy as np

        q = np.asarray(q, dtype=float)
        out = np.zeros(q.shape)
        for term in (self.gravity, self.spring, self.table):
            if term is not None:
                out = out + term.torque(q)
        return out

    def position_terms(self, q, speed, acceleration):
        """The load's terms of its position q moving at q' = ``speed``, q'' =
        ``acceleration`` (rad or m, per s, per s^2; arrays that broadcast), signed as
        :meth:`position_torque` (positive opposing a positive move): (inertial, steady),
        the inertia table's J(q) q'' + 1/2 J'(q) q'^2 (Lagrange's equation for the kinetic
        energy 1/2 J(q) q'^2: d/dt(J q') - 1/2 J' q'^2; book sec. 5.2.2, eq. 5.13 with
        the inertia of the position) and the position torque g(q) (gravity, spring,
        table). Both 0 without such terms; ``inertia`` and the constant loads are not in
        them."""
        import numpy as np

        q = np.asarray(q, dtype=float)
        qd, qdd = np.asarray(speed, dtype=float), np.asarray(acceleration, dtype=float)
        shape = np.broadcast_shapes(q.shape, qd.shape, qdd.shape)
        inertial = np.zeros(shape)
        table = self.inertia_table
        if table is not None and table.active:
            inertial = inertial + table.values(q) * qdd + 0.5 * table.values(q, 1) * qd**2
        return inertial, np.broadcast_to(self.position_torque(q), shape)


@dataclass(frozen=True)
class GravityLoad:
    """Gravity on an arm (book sec. 5.2.2, the g(q) of eq. 5.13): tau = m g r cos(q + q0).

    ``moment`` is m r (kg*m) of the arm and payload about the axis, ``offset`` q0 the
    arm's angle above the horizontal at the start of the move (rad), ``g`` m/s^2. q is
    the load's rotation from the start of the move: at q + q0 = 0 the arm is horizontal
    and gravity opposes a positive (upward) move with its largest torque m g r."""

    moment: float
    offset: float = 0.0
    g: float = 9.80665

    @property
    def active(self) -> bool:
        return self.moment * self.g != 0.0

    def torque(self, q):
        import numpy as np

        return self.moment * self.g * np.cos(np.asarray(q, dtype=float) + self.offset)


@dataclass(frozen=True)
class SpringLoad:
    """A spring on the load: tau = k (q - q_free) + preload, positive opposing a
    positive move (a spring stretched by a positive move pulls back).

    ``stiffness`` k (N*m/rad or N/m), ``preload`` its torque (force) at the free position
    (N*m or N), ``free_position`` q_free, the load's position (rad or m, from the start
    of the move) where the spring gives the preload alone."""

    stiffness: float
    preload: float = 0.0
    free_position: float = 0.0

    @property
    def active(self) -> bool:
        return self.stiffness != 0.0 or self.preload != 0.0

    def torque(self, q):
        import numpy as np

        return self.stiffness * (np.asarray(q, dtype=float) - self.free_position) + self.preload


@dataclass(frozen=True)
class TableLoad:
    """A torque of the load's position as a table (a measured process torque): points
    (x_i, tau_i), x strictly increasing, linear between them; tau positive opposing a
    positive move. ``offset`` x0 is the table's position at the start of the move (as
    gravity's q0): at the load's position q (from the start) the torque is tau(q + x0).
    Outside the table it holds the end values (the engine refuses a move that leaves it:
    sizer.sizing.linkage_move.position_profile)."""

    x: tuple[float, ...]
    tau: tuple[float, ...]
    offset: float = 0.0

    @property
    def active(self) -> bool:
        return any(t != 0.0 for t in self.tau)

    @property
    def knots(self) -> tuple[float, ...]:
        """The table's points as positions from the start of the move."""
        return tuple(x - self.offset for x in self.x)

    def torque(self, q):
        import numpy as np

        return np.interp(np.asarray(q, dtype=float) + self.offset, self.x, self.tau)


@dataclass(frozen=True)
class InertiaTableLoad:
    """An inertia of the load's position as a table (a lever, a linkage measured or taken
    from CAD): points (x_i, J_i), x strictly increasing, J >= 0, interpolated by the
    monotone piecewise cubic (PCHIP, Fritsch-Carlson with scipy's weighted harmonic mean
    and end slopes): J and J' continuous (the velocity term 1/2 J'(q) q'^2 has no jump),
    each interval monotone (J never leaves its neighbouring points' range: no invented
    peak, never negative). ``offset`` x0 as a torque table's: at the load's position q
    the inertia is J(q + x0), added to ``Load.inertia``. Outside the table it holds the
    end values (the engine refuses a move that leaves it)."""

    x: tuple[float, ...]
    inertia: tuple[float, ...]
    offset: float = 0.0

    @property
    def active(self) -> bool:
        """A table of zeros is no term (a constant one is: the loader folds it into
        ``Load.inertia``, so a design file's sizes as that constant inertia)."""
        return any(j != 0.0 for j in self.inertia)

    @property
    def varies(self) -> bool:
        """Whether J changes along the table (else J' = 0 and no knot is a kink)."""
        return any(j != self.inertia[0] for j in self.inertia)

    @property
    def knots(self) -> tuple[float, ...]:
        """The table's points as positions from the start of the move."""
        return tuple(x - self.offset for x in self.x)

    def slopes(self):
        """PCHIP's slopes dJ/dx at the points (as scipy.interpolate.PchipInterpolator)."""
        import numpy as np

        x, y = np.asarray(self.x, dtype=float), np.asarray(self.inertia, dtype=float)
        h = np.diff(x)
        m = np.diff(y) / h
        if len(x) == 2:
            return np.array([m[0], m[0]])
        d = np.zeros(len(x))
        w1, w2 = 2.0 * h[1:] + h[:-1], h[1:] + 2.0 * h[:-1]
        flat = (np.sign(m[1:]) != np.sign(m[:-1])) | (m[1:] == 0.0) | (m[:-1] == 0.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            mean = (w1 / m[:-1] + w2 / m[1:]) / (w1 + w2)
            d[1:-1] = np.where(flat, 0.0, 1.0 / mean)

        def edge(h0: float, h1: float, m0: float, m1: float) -> float:
            e = ((2.0 * h0 + h1) * m0 - h0 * m1) / (h0 + h1)
            if np.sign(e) != np.sign(m0):
                return 0.0
            if np.sign(m0) != np.sign(m1) and abs(e) > 3.0 * abs(m0):
                return 3.0 * m0
            return float(e)

        d[0] = edge(h[0], h[1], m[0], m[1])
        d[-1] = edge(h[-1], h[-2], m[-1], m[-2])
        return d

    def values(self, q, order: int = 0):
        """J (``order`` 0) or dJ/dq (1) at the load's positions q (from the start),
        beyond the table its end values (J) and end slopes (J', within rounding)."""
        import numpy as np

        x, y = np.asarray(self.x, dtype=float), np.asarray(self.inertia, dtype=float)
        d = self.slopes()
        xs = np.asarray(q, dtype=float) + self.offset
        inside = np.clip(xs, x[0], x[-1])
        i = np.clip(np.searchsorted(x, inside, side="right") - 1, 0, len(x) - 2)
        h = x[i + 1] - x[i]
        t = (inside - x[i]) / h
        y0, y1, d0, d1 = y[i], y[i + 1], d[i] * h, d[i + 1] * h
        if order == 0:
            return (2 * t**3 - 3 * t**2 + 1) * y0 + (t**3 - 2 * t**2 + t) * d0 \
                + (-2 * t**3 + 3 * t**2) * y1 + (t**3 - t**2) * d1
        slope = ((6 * t**2 - 6 * t) * y0 + (3 * t**2 - 4 * t + 1) * d0
                 + (-6 * t**2 + 6 * t) * y1 + (3 * t**2 - 2 * t) * d1) / h
        return slope  # at the end points beyond them (a move past a table is refused)

    def largest(self, q_low: float, q_high: float) -> float:
        """The largest J over the positions q_low..q_high (from the start): each interval
        is monotone, so at an end or a point between."""
        inner = [j for x, j in zip(self.knots, self.inertia, strict=True)
                 if q_low <= x <= q_high]
        ends = self.values([q_low, q_high])
        return float(max([*inner, *(float(v) for v in ends)]))


@dataclass(frozen=True)
class Stage:
    """One transmission stage: its output motion times ``ratio`` is its input motion.

    ``ratio`` is input speed over output speed: k_r for a gearbox or belt (rad/rad), 2*pi/lead
    for a ball screw and 1/r for a rack and pinion (rad/m). ``efficiency`` in (0, 1] applies
    as the transmission's ``efficiency_applies_to`` says. ``inertia`` is everything the stage
    moves, reflected to its input (kg*m^2): gear or pulley inertias, a screw, a belt's mass.
    ``preload_torque`` is a constant friction torque at its input while moving (a ball
    screw's preload).
    Limits, where known, are checked like the motor's: ``max_input_speed`` (rad/s, e.g. a
    gearbox's or a screw's critical speed), ``rated_output_torque`` against the RMS and
    ``peak_output_torque`` against the peak of the torque (or force) at its output.
    """

    kind: str = "gearbox"
    ratio: float = 1.0
    efficiency: float = 1.0
    inertia: float = 0.0
    name: str = ""
    preload_torque: float = 0.0
    max_input_speed: float | None = None
    rated_output_torque: float | None = None
    peak_output_torque: float | None = None
    backlash: float | None = None
    shaft_load: ShaftLoad | None = None
    """What this stage puts on the shaft it sits on (a belt's driver pulley, a pinion, a
    ball screw coupled directly): the motor's (``ShaftLoad.shaft`` "motor", the first
    stage) or the gearbox's output shaft before it ("gearbox"); None: nothing the
    bearings carry is known (sizer.mechanics.shaft_loads, docs/shaft-loads.md)."""
    output_radial_load: float | None = None
    """N: a gearbox's permissible radial load on its output shaft, as its maker rates it
    (Beckhoff's F2RMax, in relation to the shaft center); None: not published."""
    output_axial_load: float | None = None
    """N: a gearbox's permissible axial load on its output shaft (Beckhoff's FaStat,
    F2AMax); None: not published."""
    output_radial_load_life: float | None = None
    """N: the radial force on a gearbox's output shaft its maker rates for the bearing life
    ``output_load_life`` (Beckhoff's "radial force ... for 20000 h"); checked against the
    cycle's equivalent (mean cubic) radial force; None: not published."""
    output_axial_load_life: float | None = None
    """N: the axial force on the output shaft rated for ``output_load_life``."""
    output_load_life: float | None = None
    """s: the bearing life the two forces above are rated for (e.g. 20000 h)."""


@dataclass(frozen=True)
class ShaftLoad:
    """A stage's loads on the shaft it sits on (docs/shaft-loads.md): ``kind`` belt
    (its driver pulley of pitch ``diameter`` m on the shaft, static tension ``pretension``
    N per strand, ``wrap_angle`` rad on the pulley), pinion (pitch ``diameter``,
    ``pressure_angle`` rad) or screw (a ball screw coupled directly whose axial force the
    shaft's bearing takes)."""

    kind: Literal["belt", "pinion", "screw"]
    diameter: float = 0.0
    pretension: float = 0.0
    wrap_angle: float = math.pi
    pressure_angle: float = 0.0
    shaft: Literal["motor", "gearbox"] = "motor"
    """The shaft it sits on: the motor's (the first stage) or the output shaft of the
    gearbox stage right before it (checked against that gearbox's ratings)."""


@dataclass(frozen=True)
class LinkageStage:
    """A linkage at the load end of the transmission (seed 003): its kind and lengths (m),
    where the law is given (``law_on``: the crank angle, or the output), the crank's angle
    at the start (rad) and turning direction (+1/-1), and its masses: the crank's inertia
    (kg*m^2) and the connecting link as point masses at its crank end and output end (kg).
    ``lengths``: (r, l, e) for a slider_crank, (crank, coupler, rocker, ground) for a
    four_bar, whose ``branch`` is the assembly. The output's own mass or inertia and its
    loads are the design's ``load``. ``driven_link``: the link the motor turns ("crank",
    or a four-bar's "rocker"); ``output``: the load's coordinate ("" the default: the
    slider's position, the rocker's angle, or with a driven rocker the crank's angle;
    a four-bar's "rocker_angle", "coupler_angle", "crank_angle"; a slider-crank's
    "slider_position", "rod_angle")."""

    kind: str
    lengths: tuple[float, ...]
    law_on: Literal["crank", "output"] = "crank"
    start_angle: float = 0.0
    direction: int = 1
    branch: int = 1
    crank_inertia: float = 0.0
    link_mass_at_crank: float = 0.0
    link_mass_at_output: float = 0.0
    name: str = ""
    driven_link: str = "crank"
    output: str = ""

    @property
    def output_linear(self) -> bool:
        return self.kind == "slider_crank" and self.output in ("", "slider_position")


@dataclass(frozen=True)
class Transmission:
    """Stages from the motor to the load, in that order; empty = direct drive.

    ``efficiency_applies_to`` says how the stage efficiencies act (``EfficiencyRule``).
    ``linkage``: a linkage after the stages, at the load (its ratio varies with its
    angle, so it is not a Stage); the stages then end at its crank.
    """

    stages: tuple[Stage, ...] = ()
    efficiency_applies_to: EfficiencyRule = "power_flow"
    linkage: LinkageStage | None = None

    @property
    def ratio(self) -> float:
        """Total motor speed over load speed, k_r."""
        return math.prod(s.ratio for s in self.stages)

    @property
    def efficiency(self) -> float:
        return math.prod(s.efficiency for s in self.stages)

    @property
    def input_ratios(self) -> tuple[float, ...]:
        """Speed of each stage's input over the load's speed (the motor's for stage 0)."""
        out, speed = [], 1.0
        for stage in reversed(self.stages):
            speed *= stage.ratio
            out.append(speed)
        return tuple(reversed(out))

    @property
    def inertia(self) -> float:
        """Inertia of the stages reflected to the motor shaft, kg*m^2 (no efficiency)."""
        total, upstream = 0.0, 1.0
        for stage in self.stages:
            total += stage.inertia / upstream**2
            upstream *= stage.ratio
        return total

    def with_stage(self, index: int, stage: Stage) -> Transmission:
        """The same transmission with stage ``index`` replaced (ratio choice)."""
        stages = list(self.stages)
        stages[index] = stage
        return replace(self, stages=tuple(stages))


Grade = Literal["A", "B", "C", "D"]
"""How a figure is known: A printed as a number in the maker's own document, B the
maker's document read from a mirror or secondary copy, C computed from printed figures,
D assumed."""

GRADES: tuple[Grade, ...] = ("A", "B", "C", "D")


@dataclass(frozen=True)
class Provenance:
    """Where a catalog figure comes from: its grade and its source ("<maker>, <document>,
    <section>, p. <n>, <URL>")."""

    grade: Grade
    text: str


@dataclass(frozen=True)
class FigureSources:
    """The provenance of an object's figures: ``figures`` names the source of some,
    ``default`` (None: ungraded) is every other figure's. One object is shared by the rows
    of a file that name no figure source of their own."""

    default: Provenance | None = None
    figures: tuple[tuple[str, Provenance], ...] = ()

    def of(self, name: str) -> Provenance | None:
        """The provenance of figure ``name``; None: ungraded."""
        for figure, provenance in self.figures:
            if figure == name:
                return provenance
        return self.default


NOT_FIGURES = frozenset({"id", "source", "part_number", "manufacturer", "provenance",
                         "motors", "gearbox", "name", "kind"})
"""Fields of the catalog objects that are no figures (names, texts, references)."""


def figure_provenance(item: Motor | ServoDrive | GearboxOption
                      ) -> dict[str, Provenance | None]:
    """Each figure the object has (a field differing from its default; a gearbox option's
    stage fields) and its provenance (None: ungraded), in field order."""
    given = item.stage if isinstance(item, GearboxOption) else item
    sources = item.provenance
    out: dict[str, Provenance | None] = {}
    for f in fields(given):
        if f.name in NOT_FIGURES or getattr(given, f.name) == f.default:
            continue
        out[f.name] = None if sources is None else sources.of(f.name)
    return out


@dataclass(frozen=True)
class Motor:
    """A motor's ratings and, where known, its speed-torque curves (sec. 6.1).

    Scalar ratings alone give the book's rectangular regions: continuous torque tau_c and
    peak torque tau_p, both up to the rated speed v_n; ``Limits.envelope`` may complete a
    region without a curve up to ``max_speed`` (sizer.envelope.completion).
    """

    id: str
    inertia: float
    continuous_torque: float
    peak_torque: float
    rated_speed: float
    max_speed: float | None = None
    continuous_curve: Curve | None = None
    intermittent_curve: Curve | None = None
    damping: float = 0.0
    source: str | None = None
    part_number: str | None = None
    manufacturer: str | None = None
    price: float | None = None
    mass: float | None = None
    torque_constant: float | None = None
    """k_t, N*m per ampere RMS: a drive's currents become torques through it."""
    winding_resistance: float | None = None
    """Ohm, phase to phase (line to line: between two terminals; twice the per-phase
    resistance of a star winding)."""
    winding_inductance: float | None = None
    """H, phase to phase (as ``winding_resistance``)."""
    back_emf_constant: float | None = None
    """k_e, V*s/rad: RMS line-to-line back-EMF per rad/s (sinusoidal: k_t = sqrt(3) k_e)."""
    poles: int | None = None
    """The rotor's magnetic poles (pole pairs = poles / 2)."""
    continuous_current: float | None = None
    """A rms: the current of ``continuous_torque``."""
    peak_current: float | None = None
    """A rms: the motor's maximum current."""
    dc_bus_voltage: float | None = None
    """V: the DC link (or supply) the ratings are given for; the voltage limit of the
    electrical envelope (sizer.envelope.electrical)."""
    commutation: Commutation = "sinusoidal"
    """How the drive feeds the winding (sizer.envelope.electrical)."""
    brake_holding_torque: float | None = None
    """N*m: the holding brake's static torque (the motor is a brake variant); None: no
    brake."""
    brake_inertia: float = 0.0
    """kg*m^2: what the brake adds to ``inertia`` (sizing counts both)."""
    thermal_time_constant: float | None = None
    """s: the motor's (winding and frame) thermal time constant."""
    max_winding_temperature_rise: float | None = None
    """K: the winding's allowed temperature rise over the ambient (the rated figures')."""
    torque_current_curve: tuple[tuple[float, float], ...] | None = None
    """(current A rms, torque N*m) points, both strictly increasing: torque vs current with
    saturation; None: torque = k_t * current."""
    radial_load: float | None = None
    """N: the permissible radial load on the shaft (the maker's rating; at
    ``radial_load_point`` where it states one); None: not published."""
    axial_load: float | None = None
    """N: the permissible axial (thrust) load on the shaft; None: not published."""
    radial_load_point: float | None = None
    """m: from the flange to where ``radial_load`` acts, as the maker states it."""
    provenance: FigureSources | None = field(default=None, compare=False, repr=False)
    """Where each figure comes from (a catalog's ``sources:``); None: ungraded."""


@dataclass(frozen=True)
class ServoDrive:
    """A servo drive (amplifier) of a catalog: its current limits cap the torque of the
    motors it drives (through each motor's k_t, or its torque-current curve).

    Currents are RMS (A); ``dc_bus_voltage`` the nominal DC-link voltage, ``max_bus_voltage``
    its overvoltage trip level and ``braking_threshold`` the level where the braking chopper
    switches on (V); ``bus_capacitance`` (F); ``braking_resistor_power`` the continuous power
    of the built-in braking resistor (W, 0 = none). ``motors``: the motor ids (or fnmatch
    patterns such as ``SGM7J-*``) it suits; None: matched by rule (its continuous current
    covers the motor's, continuous_torque / k_t).
    """

    id: str
    continuous_current: float
    peak_current: float
    dc_bus_voltage: float | None = None
    bus_capacitance: float | None = None
    max_bus_voltage: float | None = None
    braking_threshold: float | None = None
    braking_resistor_power: float | None = None
    price: float | None = None
    motors: tuple[str, ...] | None = None
    source: str | None = None
    part_number: str | None = None
    manufacturer: str | None = None
    provenance: FigureSources | None = field(default=None, compare=False, repr=False)
    """Where each figure comes from (a catalog's ``sources:``); None: ungraded."""


@dataclass(frozen=True)
class Limits:
    """Margins and user limits. Margins are fractions of the motor's capability left unused.

    ``max_speed``, ``max_acceleration`` and ``max_jerk`` are at the load (rad/s or m/s,
    rad/s^2 or m/s^2, ...).
    ``inertia_ratio`` bounds the driven inertia reflected to the motor over J_m: with
    ``inertia_ratio_of = "driven"`` (the vendors' definition, default) the load, the
    screws, gears and couplings; with ``"load"`` the load alone (J_l/k^2). ``envelope``
    completes the regions of motors without curves up to max_speed
    (sizer.envelope.completion).
    """

    torque_margin: float = 0.0
    speed_margin: float = 0.0
    inertia_ratio: float | None = None
    max_acceleration: float | None = None
    max_jerk: float | None = None
    thermal_speed: ThermalSpeedRule = "max"
    inertia_ratio_of: InertiaRatioRule = "driven"
    envelope: EnvelopeRule = DEFAULT_ENVELOPE  # regions without curves (sizer.envelope)
    max_speed: float | None = None
    residual_vibration: float | None = None
    """The largest amplitude of vibration a move may leave at the load (m or rad)."""
    drive_current_margin: float = 0.0
    """Fraction of a drive's currents left unused (checks drive_peak_current and
    drive_rms_current)."""
    braking_resistor_power: float | None = None
    """W: the largest continuous power of the braking resistor (check
    braking_resistor_power; overrides the drives' ratings)."""
    winding_temperature_rise: float | None = None
    """K: the largest winding temperature rise over the ambient (check
    winding_temperature_rise; overrides the motors' allowed rise)."""
    thermal_duty: ThermalDuty = "repeated"
    """How the cycle heats the winding: "repeated" (the periodic steady state; the RMS
    check where the cycle is short) or "once" (one run from the ambient: the winding
    model's peak rise decides, the RMS check is no criterion where the motor has it)."""


@dataclass(frozen=True)
class GearboxOption:
    """One ratio of a catalog gearbox, with its efficiency, inertia and limits."""

    gearbox: str
    stage: Stage
    provenance: FigureSources | None = field(default=None, compare=False, repr=False)
    """Where each figure of the stage comes from (the catalog's ``sources:``)."""


@dataclass(frozen=True)
class RatioChoice:
    """A free ratio of stage ``stage``: a list to try, continuous bounds, or catalog gearboxes.

    The solver picks, for each motor and law, the ratio that minimizes T_min (minimize
    mode) or the RMS torque (duration given) among the feasible ones.
    """

    stage: int = 0
    ratios: tuple[float, ...] = ()
    bounds: tuple[float, float] | None = None
    gearboxes: tuple[GearboxOption, ...] = ()


@dataclass(frozen=True, init=False)
class Design:
    """A complete sizing problem: its machine cycle, load, transmission, laws, motors,
    limits.

    The motion is one :class:`Cycle`, ``machine_cycle``, the only one the core reads.
    ``Design(task, load, ...)`` takes the task shorthand and stores the cycle it means
    (``from_task``: ``shorthand`` set, for the reports); ``cycle=`` a cycle of segments.
    Of several given, ``cycle`` wins, then ``task`` (so ``replace(design, task=...)``).
    """

    machine_cycle: Cycle
    load: Load
    transmission: Transmission
    laws: tuple[LawChoice, ...]
    """The law choices to rank (a text given is read here: sizer.laws.choice)."""
    motors: tuple[Motor, ...]
    limits: Limits
    chosen_motor: str | None
    chosen_law: LawChoice | None
    name: str
    ratio_choice: RatioChoice | None
    warnings: tuple[str, ...]
    """Located warnings from loading (``file:line: field: text``), e.g. a bare number far
    from its plausible range; they never change the sizing."""
    files: tuple[Path, ...]
    """The files the loader read: the design file, the motor catalogs (named by the design
    or added), the gearbox catalogs. A command never writes its output over one of them."""
    drives: tuple[ServoDrive, ...]
    """The drives (amplifiers) to pair with the motors; empty: motors alone. With drives,
    a candidate is a motor with one of its compatible drives (sizer.sizing.drives)."""
    tolerances: tuple[Tolerance, ...]
    """The tolerances of inputs the design's ``tolerances:`` gives (relative or absolute,
    uniform or normal: sizer.model.tolerance; a plain (name, fraction) pair given to the
    constructor is a relative uniform one), for ``sizer size --robust`` (sizer.robust);
    they never change the sizing."""

    def __init__(self, task: Task | None = None, load: Load | None = None,
                 transmission: Transmission = Transmission(),
                 laws: Sequence[LawChoice | str] = (),
                 motors: tuple[Motor, ...] = (), limits: Limits = Limits(),
                 chosen_motor: str | None = None, chosen_law: LawChoice | str | None = None,
                 name: str = "", ratio_choice: RatioChoice | None = None,
                 warnings: tuple[str, ...] = (), files: tuple[Path, ...] = (),
                 drives: tuple[ServoDrive, ...] = (), cycle: Cycle | None = None,
                 machine_cycle: Cycle | None = None,
                 tolerances: Sequence[Tolerance | tuple[str, float]] = ()) -> None:
        from sizer.laws.choice import law_choice  # lazy: the law families load with a law

        given = dict(locals(), machine_cycle=cycle or (from_task(task) if task is not None
                                                       else machine_cycle),
                     laws=tuple(law_choice(s) for s in laws),
                     chosen_law=None if chosen_law is None else law_choice(chosen_law),
                     tolerances=tuple(tolerance_of(t) for t in tolerances))
        if given["machine_cycle"] is None or load is None:
            raise TypeError("a Design needs a task or a cycle, and a load")
        for f in fields(self):
            object.__setattr__(self, f.name, given[f.name])

    @property
    def cycle(self) -> Cycle | None:
        """The cycle of segments the design was written as; None for the task shorthand."""
        return self.machine_cycle if self.machine_cycle.shorthand is None else None

    @property
    def task(self) -> Task:
        """The task the design was written as; for a cycle, the task that summarizes it
        (for the reports): its first move, unscaled, no dwell; no duration when
        minimized, else the cycle time."""
        cycle = self.machine_cycle
        if cycle.shorthand is not None:
            return cycle.shorthand
        duration = None
        if not cycle.minimize:
            duration = cycle.cycle_time if cycle.cycle_time is not None else cycle.fixed_time
        return Task(cycle.moves[0].displacement, duration, linear=cycle.linear)
