"""Energy and heat of the sized candidates (issue 16): the braking resistor's continuous
power and the winding temperature rise, as checks and figures of the engine.

On the samples of one machine cycle (sizer.sizing.samples) of each candidate at its
duration:

- ``braking_resistor_power``: the bus power (sizer.energy.axis_power: shaft power plus the
  copper loss 3/2 R_LL (tau/k_t)^2 where the motor gives k_t and R) split into stops
  (sizer.energy.braking); what a stop returns beyond the bus capacitors' absorbable energy
  C (U_max^2 - U_nom^2)/2 (U_max the chopper's threshold, else the overvoltage level)
  goes to the resistor, whose continuous power (energy per cycle over the cycle time) is
  checked against ``limits.braking_resistor_power`` or the drive's
  ``braking_resistor_power`` (W), with no margin;
- ``winding_temperature_rise``: the first-order winding model (sizer.thermal.winding_check,
  R_th from the motor's continuous torque at the thermal speed and its allowed rise) in the
  periodic steady state; where the cycle is shorter than 1/10 of tau_th the rise the RMS
  torque implies, dT_max (tau_rms/tau_c)^2 (book sec. 6.1.1: the RMS check), else the
  model's peak rise; against ``limits.winding_temperature_rise`` or the motor's
  ``max_winding_temperature_rise`` (K), with the rise margin 1 - (1 - m)^2 of the torque
  margin m, so that where the RMS check applies the verdict is the RMS check's.

Figures: ``regenerated_energy`` (J per cycle at the bus), ``braking_power`` (W, the
resistor's continuous power), ``stop_energy`` (J, what the largest stop returns) and
``braking_peak_power`` (W, the resistor's peak: the largest regenerative bus power of a
stop that overflows the capacitors, 0 when none does) with the braking check,
``winding_rise`` (K) with the heat check; NaN where a candidate has no such check. With
either check, for every candidate with a duration, the power at the shaft and the bus
(sizer.energy.power.PowerFigures):
``peak_power`` (the largest motoring shaft power tau*omega, W), ``mean_power`` (the
motoring shaft power's mean over the cycle, W), ``copper_loss`` (the mean copper loss, W)
and ``cycle_energy`` (the net energy drawn from the bus per cycle, J: motoring minus
regenerated, copper included); the last two NaN where the motor lacks k_t or R.

The shortest move duration at which the energy and heat checks pass (minimize mode,
:func:`energy_duration`).

T_min is searched on the checks of the cycle (sizer.sizing.shortest_duration); where the
winding temperature rise or the braking resistor's power
fails there, a longer move is tried: both fall as the move slows (the torques fall as
1/T^2, the speeds and the returned energy per cycle as 1/T, the cycle grows), so the
first duration at which both pass is bracketed by doubling T from T_min and found by the
project's root finder (sizer.numerics.roots.bracketed_root) on the smaller of the two slacks.
The heat check's slack may jump where the rule switches from the RMS-equivalent rise to
the winding model (book sec. 6.1.1, footnote: the cycle against 1/10 of tau_th); the
root finder keeps a passing end, so the duration returned passes.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass

import numpy as np

from sizer.model.cycle import shorthand_task
from sizer.model.domain import Design, Motor, ServoDrive
from sizer.numerics.roots import first_passing
from sizer.sizing.candidates import MotorArrays, catalog_facts
from sizer.sizing.checks import (
    BRAKING_RESISTOR_POWER,
    TOLERANCE,
    WINDING_TEMPERATURE_RISE,
    CheckArrays,
)
from sizer.sizing.evaluation import CycleMetrics, CycleModel
from sizer.sizing.shortest_duration import LaterChecks

REGENERATED = "regenerated_energy"
BRAKING_POWER = "braking_power"
WINDING_RISE = "winding_rise"
PEAK_POWER = "peak_power"
MEAN_POWER = "mean_power"
COPPER_LOSS = "copper_loss"
CYCLE_ENERGY = "cycle_energy"
STOP_ENERGY = "stop_energy"
BRAKING_PEAK = "braking_peak_power"
ENERGY_FIGURES = (REGENERATED, BRAKING_POWER, WINDING_RISE, PEAK_POWER, MEAN_POWER,
                  COPPER_LOSS, CYCLE_ENERGY, STOP_ENERGY, BRAKING_PEAK)
"""The optional figures of this module, in the order results list them."""

RMS_NOTE = "RMS-equivalent rise applied: the cycle is much shorter than the thermal time constant"
THERMAL_NOTE = ("thermal model applied: the cycle is not much shorter than the thermal time "
                "constant (the periodic peak rise)")
ONCE_NOTE = ("thermal model applied: one run of the cycle from the ambient (thermal_duty: "
             "once), its peak rise")


_POWER_FIGURES: ContextVar[bool] = ContextVar("sizer_power_figures", default=True)


@contextmanager
def without_power_figures() -> Iterator[None]:
    """Within: the energy checks sample only the candidates a check needs and leave out
    the power figures (the searches that only compare verdicts: ratio, auto shape, the
    energy lengthening, a machine's speed; their final tables are evaluated with them)."""
    token = _POWER_FIGURES.set(False)
    try:
        yield
    finally:
        _POWER_FIGURES.reset(token)


def has_heat_check(motors: tuple[Motor, ...]) -> bool:
    """A heat check where some motor gives its thermal time constant and allowed rise."""
    return catalog_facts(motors).heated


def has_braking_check(design: Design, drives: tuple[ServoDrive, ...]) -> bool:
    """A braking check where the design limits the resistor or a drive rates its own."""
    return design.limits.braking_resistor_power is not None \
        or any(d.braking_resistor_power is not None for d in drives)


def energy_notes(design: Design) -> list[str]:
    """What the energy and heat checks left out, for reports (none without them): a
    winding-rise limit the design states is never left out silently."""
    notes = []
    if design.limits.winding_temperature_rise is not None:
        cold = [m.id for m in design.motors if m.thermal_time_constant is None
                or m.max_winding_temperature_rise is None]
        if cold:
            shown = ", ".join(cold[:5]) + (f" and {len(cold) - 5} more" if len(cold) > 5 else "")
            notes.append("limits.winding_temperature_rise is not checked for the motors "
                         "without thermal_time_constant and max_winding_temperature_rise "
                         f"({shown}); their RMS check stands for it")
    if not (has_heat_check(design.motors) or has_braking_check(design, design.drives)):
        return notes
    if design.machine_cycle.minimize:
        what = "the move is" if shorthand_task(design.machine_cycle) else "the free durations are"
        notes.append("where winding_temperature_rise or braking_resistor_power fails at the "
                     f"T_min of the other checks, {what} lengthened to the first duration "
                     "that passes them")
    return notes


def _motor_column(motors: tuple[Motor, ...], index: np.ndarray, name: str) -> np.ndarray:
    return catalog_facts(motors).column(name)[index]


def _drive_column(drives: tuple[ServoDrive, ...], index: np.ndarray | None, n: int,
                  name: str) -> np.ndarray:
    if index is None or not drives:
        return np.full(n, np.nan)
    values = np.array([np.nan if getattr(d, name) is None else float(getattr(d, name))
                       for d in drives], dtype=float)
    return values[index]


def energy_checks(design: Design, calculator: CycleModel, duration: np.ndarray,
                  metrics: CycleMetrics) -> LaterChecks | None:
    """The braking and heat checks of the candidates of ``calculator`` at ``duration``
    (module docstring; none where it is NaN), their verdicts and figures, or None when
    the design has neither."""
    motors = calculator.motors
    heat = has_heat_check(motors.catalog)
    brake = has_braking_check(design, motors.drives)
    if not (heat or brake):
        return None
    n = len(motors)
    T = np.broadcast_to(np.asarray(duration, dtype=float), (n,))
    known = np.isfinite(T) & (T > 0.0)
    cycle_time = calculator.cycle_time(np.where(known, T, 1.0))
    thermal = np.zeros(n, dtype=bool)  # the winding model, where the cycle is not short
    once = design.limits.thermal_duty == "once"  # or always, for a one-off run
    if heat:
        thermal = _thermal_model_applies(motors, cycle_time, once) & known
    wound = None
    with_power = _POWER_FIGURES.get()
    if with_power:  # every candidate with a duration: its power figures
        rows = np.flatnonzero(known)
    else:  # only where a check needs samples: a braking limit, or the winding model
        need = thermal | (np.isfinite(_braking_limit(design, motors)) if brake else False)
        rows = np.flatnonzero(need & known)
    samples = power = None
    if rows.size:
        from sizer.sizing.samples import sampled  # lazy: start-up (issue 34)

        samples = sampled(calculator.take(rows), T[rows])
        power, wound = _axis_power(motors, samples, rows)
    feasible = np.ones(n, dtype=bool)
    checks: list[CheckArrays] = []
    figures: dict[str, np.ndarray] = {}
    if brake:
        check, regenerated, resistor, stop, peak = _braking(design, motors, power, rows,
                                                            known)
        checks.append(check)
        feasible &= check.passed
        figures[REGENERATED], figures[BRAKING_POWER] = regenerated, resistor
        figures[STOP_ENERGY], figures[BRAKING_PEAK] = stop, peak
    if heat:
        check, rise = _heat(design, motors, samples, rows, thermal, metrics, known)
        checks.append(check)
        feasible &= check.passed
        figures[WINDING_RISE] = rise
    if with_power:
        figures.update(_power_figures(n, power, wound, rows))
    return LaterChecks(checks, feasible, figures)


@dataclass(frozen=True)
class EnergyLimit:
    """The braking and heat checks as a later limit of the search for the shortest
    duration (sizer.sizing.shortest_duration.LaterLimit)."""

    design: Design

    def at(self, calculator: CycleModel, s: np.ndarray, metrics: CycleMetrics,
           known: np.ndarray) -> LaterChecks:
        energy = energy_checks(self.design, calculator, np.where(known, s, np.nan), metrics)
        assert energy is not None, "made only for a design with either check"
        return energy

    def passing_scale(self, calculator: CycleModel, rows: np.ndarray, s: np.ndarray,
                      found: LaterChecks) -> np.ndarray:
        slack = np.min([check.slack[rows] for check in found.checks], axis=0) + TOLERANCE
        return energy_duration(self.design, calculator.take(rows), s, slack)


def energy_limit(design: Design, motors: MotorArrays) -> EnergyLimit | None:
    """The design's braking and heat checks as a later limit, or None with neither."""
    if has_heat_check(motors.catalog) or has_braking_check(design, motors.drives):
        return EnergyLimit(design)
    return None


def _braking_limit(design: Design, motors) -> np.ndarray:
    """The resistor's allowed continuous power per candidate (NaN: no braking check)."""
    given = design.limits.braking_resistor_power
    if given is not None:
        return np.full(len(motors), float(given))
    return _drive_column(motors.drives, motors.drive, len(motors), "braking_resistor_power")


def _axis_power(motors, samples, rows: np.ndarray):
    """The shaft, copper and bus power of the candidates at ``rows`` (their samples), and
    where the copper loss is known (the motor gives k_t and R)."""
    from sizer.energy import axis_power

    k_t = _motor_column(motors.catalog, motors.index, "torque_constant")[rows]
    R = _motor_column(motors.catalog, motors.index, "winding_resistance")[rows]
    wound = np.isfinite(k_t) & np.isfinite(R)
    power = axis_power(samples.time, samples.torque, samples.speed,
                       torque_constant=np.where(wound, k_t, 1.0),
                       winding_resistance=np.where(wound, R, 0.0))
    return power, wound


def _power_figures(n: int, power, wound: np.ndarray | None,
                   rows: np.ndarray) -> dict[str, np.ndarray]:
    """Peak and mean motoring shaft power, mean copper loss and net bus energy per cycle
    for every candidate (NaN where unknown)."""
    out = {name: np.full(n, np.nan) for name in (PEAK_POWER, MEAN_POWER, COPPER_LOSS,
                                                 CYCLE_ENERGY)}
    if power is None or wound is None:
        return out
    f = power.figures()
    out[PEAK_POWER][rows] = f.peak_motoring_power
    out[MEAN_POWER][rows] = f.mean_motoring_power
    out[COPPER_LOSS][rows] = np.where(wound, f.mean_copper_loss, np.nan)
    out[CYCLE_ENERGY][rows] = np.where(wound, f.net_energy, np.nan)
    return out


def _braking(design: Design, motors, power, rows: np.ndarray, known: np.ndarray):
    """The braking check, the regenerated energy per cycle and the resistor's power; the
    bus power is that of the candidates at ``rows``."""
    from sizer.energy import braking, capacitor_energy

    n = len(motors)
    limit = _braking_limit(design, motors)
    applies = np.isfinite(limit)
    regenerated, resistor, stop, peak = (np.full(n, np.nan) for _ in range(4))
    if power is not None:
        C = _drive_column(motors.drives, motors.drive, n, "bus_capacitance")[rows]
        u_nom = _drive_column(motors.drives, motors.drive, n, "dc_bus_voltage")[rows]
        u_top = _drive_column(motors.drives, motors.drive, n, "braking_threshold")
        u_top = np.where(np.isfinite(u_top), u_top,
                         _drive_column(motors.drives, motors.drive, n, "max_bus_voltage"))[rows]
        stored = np.isfinite(C) & np.isfinite(u_nom) & np.isfinite(u_top) & (u_top > u_nom)
        absorbable = np.zeros(rows.size)
        if stored.any():
            absorbable[stored] = capacitor_energy(C[stored], u_top[stored], u_nom[stored])
        result = braking(power.time, power.bus, absorbable)
        regenerated[rows] = result.regenerated_energy
        resistor[rows] = result.resistor_continuous_power
        stop[rows] = result.worst_stop_energy
        peak[rows] = result.resistor_peak_power
    value = np.where(known & applies, np.nan_to_num(resistor, nan=0.0), 0.0)
    check = BRAKING_RESISTOR_POWER.arrays(value, np.where(applies, limit, 1.0), 0.0,
                                          None if applies.all() else applies)
    return check, *(np.where(known, x, np.nan) for x in (regenerated, resistor, stop, peak))


def _thermal_model_applies(motors, cycle_time: np.ndarray, once: bool = False) -> np.ndarray:
    """Where the heat check needs the winding model (the cycle is not much shorter than
    tau_th, sizer.thermal.applied_check, or a one-off run); elsewhere the RMS-equivalent
    rise applies."""
    from sizer.thermal.verdict import RMS_SHARE

    tau_th = _motor_column(motors.catalog, motors.index, "thermal_time_constant")
    allowed = _motor_column(motors.catalog, motors.index, "max_winding_temperature_rise")
    heated = np.isfinite(tau_th) & np.isfinite(allowed)
    if once:
        return heated
    return heated & ~(RMS_SHARE * np.where(heated, tau_th, 0.0) > cycle_time)


def _heat(design: Design, motors, samples, rows: np.ndarray, thermal: np.ndarray,
          metrics: CycleMetrics, known: np.ndarray):
    """The winding temperature rise check and the rise per candidate: the winding model's
    periodic peak where ``thermal`` (its samples at ``rows``), else the RMS rise."""
    from sizer.thermal import winding_check

    n = len(motors)
    tau_th = _motor_column(motors.catalog, motors.index, "thermal_time_constant")
    allowed = _motor_column(motors.catalog, motors.index, "max_winding_temperature_rise")
    region = catalog_facts(motors.catalog).continuous(motors.envelope)
    thermal_speed = np.broadcast_to(metrics.thermal_speed, (n,))
    tau_c = region.take(motors.index).limit_clipped(thermal_speed)
    applies = np.isfinite(tau_th) & np.isfinite(allowed) & (tau_c > 0.0)
    rms = np.broadcast_to(metrics.rms_torque, (n,))
    with np.errstate(divide="ignore", invalid="ignore"):
        rise = allowed * (rms / tau_c) ** 2
    by_rms = ~thermal
    modelled = thermal & applies
    if samples is not None and modelled.any():
        at = np.isin(rows, np.flatnonzero(modelled))
        pick = rows[at]
        result = winding_check(samples.time[at], samples.torque[at], tau_c[pick],
                               allowed[pick], tau_th[pick],
                               periodic=design.limits.thermal_duty != "once")
        rise[pick] = result.verdict.peak_rise
    given = design.limits.winding_temperature_rise
    limit = np.full(n, float(given)) if given is not None else allowed
    margin = design.limits.torque_margin
    value = np.where(known & applies, rise, 0.0)
    modelled_note = ONCE_NOTE if design.limits.thermal_duty == "once" else THERMAL_NOTE
    notes = np.where(by_rms, RMS_NOTE, modelled_note).astype(object)
    check = WINDING_TEMPERATURE_RISE.arrays(value, np.where(applies, limit, 1.0),
                                            1.0 - (1.0 - margin) ** 2,
                                            None if applies.all() else applies, notes)
    return check, np.where(known & applies, rise, np.nan)


DOUBLINGS = 30
"""How far past T_min a passing duration is looked for: T_min 2^30."""

XTOL = 1e-12
"""Relative width of the final bracket of the duration."""


def energy_slack(design: Design, calculator: CycleModel, duration: np.ndarray,
                 rows: np.ndarray) -> np.ndarray:
    """The smallest slack of the energy and heat checks of the candidates at ``rows`` of
    ``calculator``, each moving in its ``duration``; >= 0 where both pass (with the
    checks' tolerance)."""
    sub = calculator.take(rows)
    T = np.asarray(duration, dtype=float)
    metrics = sub.evaluate(T)
    with without_power_figures():
        energy = energy_checks(design, sub, T, metrics)
    if energy is None or not energy.checks:
        return np.full(len(rows), np.inf)
    return np.min([check.slack for check in energy.checks], axis=0) + TOLERANCE


def energy_duration(design: Design, calculator: CycleModel, duration: np.ndarray,
                    slack: np.ndarray | None = None) -> np.ndarray:
    """Per candidate, the smallest duration >= ``duration`` at which the energy and heat
    checks pass; inf where none does up to ``duration`` 2^DOUBLINGS. ``slack``: that of
    :func:`energy_slack` at ``duration`` where the caller has it (else evaluated)."""
    lo = np.array(duration, dtype=float)
    f_lo = np.array(slack, dtype=float) if slack is not None \
        else energy_slack(design, calculator, lo, np.arange(len(lo)))
    return first_passing(lambda x, rows: energy_slack(design, calculator, x, rows), lo, f_lo,
                         DOUBLINGS, XTOL)
