"""The load and transmission seen from the motor shaft (book sec. 6.1.1, eq. 6.1).

Stages run from the motor to the load. Each stage adds, at its input, the torque to
accelerate its own inertia and its preload friction. Two conventions for the efficiency
(``Transmission.efficiency_applies_to``):

- ``power_flow`` (Siemens, Mitsubishi; the default): a torque x at a stage's output (along
  the motion) needs x/(k*eta) at its input while power flows to the load (x >= 0) and
  x*eta/k while the load drives (x < 0); the motor torque is piecewise linear in a, v.
- ``steady_load`` (Yaskawa): only the load's steady torque (friction, damping, constant
  load, preloads) passes the stages with its efficiency, x_s/(k*eta) while its constant
  part opposes the motion and x_s*eta/k while it drives; the inertial torque passes
  without loss (T_L = F P_B / (2 pi R eta), T_a = (J_M + J_L) omega / t_a). The motor
  torque is linear in a, v, and the closed forms of the ideal chain apply.

With eta = 1 everywhere both are the book's J_t = J_m + J_gear + J_l/k^2 and
B_t = B_m + B_l/k^2. A linear axis reads mass for inertia, force for torque, and rad/m
for the last stage's ratio.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from sizer.mechanics.load_figures import LoadFigures
from sizer.model.domain import Load, Stage, Transmission

LIMITS = ("max_input_speed", "rated_output_torque", "peak_output_torque")
"""The optional limits of a stage (None: not rated)."""


@dataclass(frozen=True, eq=False)
class StageArrays:
    """One stage position of the transmission options, each figure an array over the
    candidates (length 1 when every candidate has the same transmission).

    A limit is None when no option rates it; otherwise an array with inf where the
    candidate's option does not, and ``rated[name]`` says which candidates are rated.
    """

    kind: str
    name: str
    ratio: np.ndarray
    efficiency: np.ndarray
    inertia: np.ndarray
    preload_torque: np.ndarray
    max_input_speed: np.ndarray | None
    rated_output_torque: np.ndarray | None
    peak_output_torque: np.ndarray | None
    rated: dict[str, np.ndarray]

    @classmethod
    def of(cls, stages: Sequence[Stage], option: np.ndarray | None) -> StageArrays:
        def column(values):
            array = np.asarray(values, dtype=float)
            return array if option is None else array[option]

        limits: dict[str, np.ndarray | None] = {}
        rated: dict[str, np.ndarray] = {}
        for name in LIMITS:
            values = [getattr(s, name) for s in stages]
            if all(v is None for v in values):
                limits[name] = None
                continue
            limits[name] = column([np.inf if v is None else v for v in values])
            given = np.array([v is not None for v in values])
            rated[name] = given if option is None else given[option]
        first = stages[0]
        return cls(first.kind, first.name, column([s.ratio for s in stages]),
                   column([s.efficiency for s in stages]), column([s.inertia for s in stages]),
                   column([s.preload_torque for s in stages]), limits["max_input_speed"],
                   limits["rated_output_torque"], limits["peak_output_torque"], rated)

    def take(self, index: np.ndarray) -> StageArrays:
        def pick(x):
            return None if x is None else (x if len(x) == 1 else x[index])

        return StageArrays(self.kind, self.name, pick(self.ratio), pick(self.efficiency),
                           pick(self.inertia), pick(self.preload_torque),
                           pick(self.max_input_speed), pick(self.rated_output_torque),
                           pick(self.peak_output_torque),
                           {k: pick(v) for k, v in self.rated.items()})


def _per_candidate(value: float | np.ndarray) -> np.ndarray:
    """A load figure as an array over the candidates: length 1 where it is one number."""
    return np.array(value, dtype=float, ndmin=1)


def _along(values: np.ndarray, like: np.ndarray) -> np.ndarray:
    """Per-candidate values shaped to broadcast over candidate-major ``like``."""
    ndim = np.ndim(like)
    if ndim <= 1:
        return values
    return np.reshape(values, (-1,) + (1,) * (ndim - 1))


class Drive:
    """Load plus transmission; everything the motor drives apart from its own rotor.

    ``transmissions`` are the options of the candidates (the design's transmission, or it
    with a chosen ratio or catalog gearbox in place, all with the same stage kinds) and
    ``option`` the option of each candidate (None: one transmission for all). Every
    figure is an array over the candidates (length 1 with a single transmission), so
    that motors x transmission options are evaluated as one flat axis.

    ``figures``: the load's J_l, B_l, F and tau_ext as the computations read them, per
    candidate where each drives its own build of the load (sizer.mechanics.load_figures;
    robust sizing); by default ``load``'s own.
    """

    def __init__(self, load: Load, transmission: Transmission | Sequence[Transmission],
                 option: np.ndarray | None = None,
                 figures: LoadFigures | None = None) -> None:
        options = (transmission,) if isinstance(transmission, Transmission) \
            else tuple(transmission)
        counts = {len(t.stages) for t in options}
        if len(counts) != 1:
            raise ValueError("transmission options must have the same number of stages")
        self.load = load
        self.figures = LoadFigures.of(load) if figures is None else figures
        self.transmissions = options
        self.option = None if option is None or len(options) == 1 \
            else np.asarray(option, dtype=np.intp)
        self.stages = tuple(StageArrays.of([t.stages[i] for t in options], self.option)
                            for i in range(counts.pop()))

    def take(self, index: np.ndarray) -> Drive:
        """The drive of the candidates at ``index`` (repeats allowed)."""
        if self.option is None and not self.figures.varies:
            return self
        if self.option is None:
            return self._copy(figures=self.figures.take(index))
        return self._copy(figures=self.figures.take(index), option=self.option[index],
                          stages=tuple(s.take(index) for s in self.stages))

    def with_load(self, load: Load) -> Drive:
        """The same transmission options and candidates driving ``load`` instead (each
        build of the load changed as ``load`` changes the design's:
        LoadFigures.moved)."""
        if load is self.load:
            return self
        return self._copy(load=load, figures=self.figures.moved(self.load, load))

    def _copy(self, **changed: object) -> Drive:
        """This drive with the fields ``changed`` (its five: load, figures,
        transmissions, option, stages), its cached figures computed again."""
        out = object.__new__(Drive)
        fields = {"load": self.load, "figures": self.figures,
                  "transmissions": self.transmissions, "option": self.option,
                  "stages": self.stages}
        out.__dict__.update(fields, **changed)
        return out

    @property
    def transmission(self) -> Transmission:
        """The first option (the design's when there is one): its stages' kinds and rule."""
        return self.transmissions[0]

    def _product(self, figure: str) -> np.ndarray:
        out = np.ones(1)
        for s in self.stages:
            out = out * getattr(s, figure)
        return out

    @cached_property
    def ratio(self) -> np.ndarray:
        """Motor speed over load speed, K, per candidate."""
        return self._product("ratio")

    @cached_property
    def efficiency(self) -> np.ndarray:
        """The stages' efficiencies multiplied, per candidate."""
        return self._product("efficiency")

    @cached_property
    def input_ratios(self) -> tuple[np.ndarray, ...]:
        """Speed of each stage's input over the load speed."""
        out, speed = [], np.ones(1)
        for stage in reversed(self.stages):
            speed = speed * stage.ratio
            out.append(speed)
        return tuple(reversed(out))

    @property
    def steady_load_efficiency(self) -> bool:
        """The efficiencies act on the load's steady torque only (Yaskawa's convention)."""
        return self.transmission.efficiency_applies_to == "steady_load"

    @cached_property
    def is_ideal(self) -> bool:
        """The motor torque is linear in the load's a, v: all efficiencies are 1, or they
        act on the steady load only. The closed forms (``linear_chain``) then apply."""
        return self.steady_load_efficiency or all(bool(np.all(s.efficiency == 1.0))
                                                  for s in self.stages)

    @cached_property
    def transmission_inertia(self) -> np.ndarray:
        """Inertia of all stages reflected to the motor shaft (no efficiency)."""
        total, upstream = np.zeros(1), np.ones(1)
        for stage in self.stages:
            total = total + stage.inertia / upstream**2
            upstream = upstream * stage.ratio
        return total

    @cached_property
    def reflected_load_inertia(self) -> np.ndarray:
        """J_l/K^2, the load alone reflected to the motor (no efficiency)."""
        return self.figures.inertia / self.ratio**2

    @property
    def driven_inertia(self) -> np.ndarray:
        """Everything the motor drives, reflected to it: load, screws, gears, couplings."""
        return self.transmission_inertia + self.reflected_load_inertia

    def inertia_ratio_numerator(self, of: str = "driven") -> np.ndarray:
        """The inertia ratio's numerator: ``driven`` (vendors' definition) or ``load``."""
        return self.driven_inertia if of == "driven" else self.reflected_load_inertia

    def load_torque(self, a_l: np.ndarray, v_l: np.ndarray,
                    direction: float | np.ndarray,
                    index: np.ndarray | None = None) -> np.ndarray:
        """u = J_l a + B_l v + F + direction*tau_ext: the load's torque along the motion
        (``index``: the candidates of the rows, as in :meth:`chain`)."""
        J, B, F, tau = self._figures_along(a_l, index)
        return J * a_l + B * v_l + F + direction * tau

    def _figures_along(self, like: np.ndarray, index: np.ndarray | None = None):
        """The load's (J_l, B_l, F, tau_ext) shaped to broadcast over candidate-major
        ``like`` whose rows are the candidates ``index`` (default: all; numbers where
        every candidate drives the same load)."""
        f = self.figures if index is None else self.figures.take(index)
        values = (f.inertia, f.damping, f.friction, f.torque)
        if not f.varies:
            return values
        return tuple(_along(np.asarray(x), like) for x in values)

    def _stage_values(self, index: np.ndarray | None, like: np.ndarray):
        """Per stage (ratio, efficiency, inertia, preload, input ratio), each shaped to
        broadcast over candidate-major ``like`` (rows ``index`` of the candidates)."""
        if index is None:  # the common case, kept per number of dimensions
            key = np.ndim(like)
            cache = self.__dict__.setdefault("_shaped", {})
            if key not in cache:
                cache[key] = self._shaped_values(None, like)
            return cache[key]
        return self._shaped_values(index, like)

    def _shaped_values(self, index: np.ndarray | None, like: np.ndarray):
        def shaped(x):
            if index is not None and len(x) > 1:
                x = x[index]
            return _along(x, like)

        return [(shaped(s.ratio), shaped(s.efficiency), shaped(s.inertia),
                 shaped(s.preload_torque), shaped(k_in))
                for s, k_in in zip(self.stages, self.input_ratios, strict=True)]

    def chain(self, a_l: np.ndarray, v_l: np.ndarray, direction: float | np.ndarray,
              index: np.ndarray | None = None,
              extra: tuple[np.ndarray, np.ndarray] | None = None
              ) -> tuple[np.ndarray, list[np.ndarray]]:
        """Torque the transmission needs at the motor shaft, and each stage's output torque.

        a_l, v_l are the load's acceleration and speed along the motion (magnitudes for
        the move's direction), candidate-major; ``index`` names the candidates of their
        rows (default: all, in order). ``extra`` (inertial, steady): torques the load adds
        along the motion beyond :meth:`load_torque`, as the terms of its position
        (sizer.model.domain.Load.position_terms: the inertia table's, the position
        torque); with power-flow efficiencies both pass the stages as the rest of the
        load (the position engine reflects its whole crank torque so,
        sizer.sizing.linkage_move.LinkageCalculator.motor_samples), with the steady-load
        rule as :meth:`_steady_load_chain` says. Returns (shaft torque without the rotor,
        [output torque of stage 0, ..., output torque of the last stage = u]).
        """
        values = self._stage_values(index, a_l)
        if self.steady_load_efficiency:
            return self._steady_load_chain(a_l, v_l, direction, values, extra, index)
        x = self.load_torque(a_l, v_l, direction, index)
        if extra is not None:
            x = x + extra[0] + extra[1]
        outputs = [x]
        for ratio, efficiency, inertia, preload, k_in in reversed(values):
            reflected = np.where(x >= 0.0, x / (ratio * efficiency), x * efficiency / ratio)
            x = inertia * k_in * a_l + preload + reflected
            outputs.append(x)
        outputs.pop()  # the last one is the shaft torque, not a stage output
        return x, outputs[::-1]

    def _steady_load_chain(self, a_l, v_l, direction: float | np.ndarray, values,
                           extra: tuple[np.ndarray, np.ndarray] | None = None,
                           index: np.ndarray | None = None):
        """``chain`` with the efficiencies on the steady torque only (Yaskawa). An
        ``extra`` (inertial, steady) sorts as the position engine sorts the terms
        (sizer.sizing.linkage_move.position_profile): the inertia table's terms are
        inertial (without loss), the position torque is steady (gravity on a vertical
        axis is Yaskawa's steady load: T_L = F P_B / (2 pi R eta)), so it joins the
        constant part whose sign picks 1/eta or eta, now at each sample. (The position
        engine itself refuses this rule: sizer.sizing.linkage_move.check_position_drive.)"""
        J, B, F, tau = self._figures_along(a_l, index)
        inertial = J * a_l
        steady = B * v_l + F + direction * tau
        constant: np.ndarray = np.asarray(F + direction * tau, dtype=float)
        if extra is not None:
            inertial = inertial + extra[0]
            steady = steady + extra[1]
            constant = constant + extra[1]
        outputs = [inertial + steady]
        for ratio, efficiency, inertia, preload, k_in in reversed(values):
            factor = _steady_factor(efficiency, constant)
            inertial = inertia * k_in * a_l + inertial / ratio
            steady = preload + steady * factor / ratio
            constant = preload + constant * factor / ratio
            outputs.append(inertial + steady)
        outputs.pop()
        return inertial + steady, outputs[::-1]

    def linear_chain(self, direction: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(A, B, C) per candidate with shaft torque = A a_l + B v_l + C, valid when
        ``is_ideal``."""
        K, f = self.ratio, self.figures
        a_part = f.inertia / K
        for s, k_in in zip(self.stages, self.input_ratios, strict=True):
            a_part = a_part + s.inertia * k_in**2 / K
        v_part = _per_candidate(f.damping)
        const = _per_candidate(f.friction + direction * f.torque)
        for stage in reversed(self.stages):
            factor = _steady_factor(stage.efficiency, const) if self.steady_load_efficiency \
                else 1.0
            v_part = v_part * factor / stage.ratio
            const = stage.preload_torque + const * factor / stage.ratio
        return a_part, v_part, const

    def linear_pieces(self, direction: float):
        """The shaft torque (without the rotor) and each stage's output torque as maxima of
        linear functions of the load's (a_l, v_l): lists of (A, B, C) arrays over the
        candidates, value = max over the list of A a_l + B v_l + C.

        With power-flow efficiencies a stage's reflection is max(x/(k eta), x eta/k) (the
        first while power flows to the load, x >= 0), increasing in x; so every choice of
        direction per stage gives one linear function and the torque is their maximum.
        With the steady-load rule or ideal stages each list has one function
        (:meth:`linear_chain`). Returns (shaft list, [list of stage 0's output, ...]),
        built once per direction (a drive's figures do not change; each evaluation of a
        law move reads them): the arrays are read-only, the lists tuples.
        """
        cache = self.__dict__.setdefault("_pieces_by_direction", {})
        key = float(direction)
        if key not in cache:
            shaft, outputs = self._linear_pieces(key)
            cache[key] = (_frozen(shaft), tuple(_frozen(pieces) for pieces in outputs))
        return cache[key]

    def _linear_pieces(self, direction: float):
        """:meth:`linear_pieces`, built."""
        f = self.figures
        if self.is_ideal:
            shaft = [self.linear_chain(direction)]
            zero, one = np.zeros(1), np.ones(1)
            _, out_a = self.chain(one, zero, direction)
            _, out_v = self.chain(zero, one, direction)
            _, out_0 = self.chain(zero, zero, direction)
            stages = [[(xa - x0, xv - x0, x0)]
                      for xa, xv, x0 in zip(out_a, out_v, out_0, strict=True)]
            return shaft, stages
        x = [(_per_candidate(f.inertia), _per_candidate(f.damping),
              _per_candidate(f.friction + direction * f.torque))]
        outputs = [x]
        for stage, k_in in zip(reversed(self.stages), reversed(self.input_ratios), strict=True):
            factors = [1.0 / (stage.ratio * stage.efficiency)]
            if not np.all(stage.efficiency == 1.0):
                factors.append(stage.efficiency / stage.ratio)
            x = [(stage.inertia * k_in + A * f, B * f, stage.preload_torque + C * f)
                 for A, B, C in x for f in factors]
            outputs.append(x)
        outputs.pop()
        return x, outputs[::-1]

    def holding_torques(self) -> tuple[np.ndarray, list[np.ndarray]]:
        """|Torque| at the motor shaft and at each stage output holding the constant load.

        At rest the power flow is undefined; holding counts as driving (divide by eta),
        the conservative choice.
        """
        x = _per_candidate(np.abs(self.figures.torque))
        outputs = [x]
        for stage in reversed(self.stages):
            x = x / (stage.ratio * stage.efficiency)
            outputs.append(x)
        outputs.pop()
        return x, outputs[::-1]

    @property
    def holding_torque(self) -> np.ndarray:
        return self.holding_torques()[0]


def _steady_factor(efficiency, constant):
    """1/eta while the steady torque opposes the motion, eta while it drives."""
    return np.where(np.asarray(constant) >= 0.0, 1.0 / efficiency, efficiency)


def _frozen(pieces) -> tuple[tuple[np.ndarray, ...], ...]:
    """Linear functions (A, B, C) as a tuple of read-only arrays (a cached value that
    no reader may change)."""
    out = []
    for piece in pieces:
        arrays = tuple(np.array(x, dtype=float) for x in piece)
        for x in arrays:
            x.setflags(write=False)
        out.append(arrays)
    return tuple(out)
