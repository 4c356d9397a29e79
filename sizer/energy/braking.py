"""Braking at the DC bus: stops, the bus capacitors, the braking resistor (issue 16).

A stop is a maximal run of intervals where the bus power is negative (the motor returns
power); its regenerated energy is the integral of -P_bus over the run (exact for the
piecewise-linear power, sizer.energy.power). For a pure inertia decelerating through a
stage of efficiency eta with no copper loss this is eta * J omega^2 / 2 (Yaskawa's
E_S = J n_M^2 / 182 J with n_M in rpm, J = J_M + J_L: 182 = 2 (30/pi)^2 rounded).

Per stop the capacitors absorb up to E_C = C (U_max^2 - U_nom^2) / 2 (U_max where the
chopper switches on, U_nom = sqrt(2) U_mains for a rectified supply) or a drive's
absorbable energy from its datasheet; the resistor takes the rest E_K = E_stop - E_C
(Yaskawa's E_K = E_S - (E_L + E_M + E_C), with the load and winding losses E_L, E_M
already taken off here by the power flow and the copper loss). Assumed: the bus is back at
U_nom when a stop begins (the motoring between stops has drawn the stored energy). The
resistor's peak power is the largest regenerative bus power in a stop that overflows the
capacitors (the chopper may switch on at the peak: an upper bound), its continuous power
the energy it takes per cycle over the cycle time. With ``periodic`` the samples are one
cycle of a repeated motion: a stop running through the cycle's end continues at its start,
and a bus braking over the whole cycle leaves the capacitors full (they absorb nothing).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from sizer.energy.inputs import finite, nonnegative, per_candidate, samples, span, times
from sizer.energy.power import interval_parts
from sizer.errors import UserError


def capacitor_energy(capacitance: ArrayLike, u_max: ArrayLike,
                     u_nominal: ArrayLike) -> np.ndarray:
    """E_C = C (U_max^2 - U_nom^2) / 2 (J): what the bus capacitors absorb going from the
    nominal bus voltage to the chopper's switch-on voltage."""
    C = nonnegative(capacitance, "capacitance")
    top = nonnegative(u_max, "u_max")
    nominal = nonnegative(u_nominal, "u_nominal")
    if bool(np.any(top <= nominal)):
        raise UserError("must be above the nominal bus voltage u_nominal", field="u_max")
    return 0.5 * C * (top * top - nominal * nominal)


@dataclass(frozen=True)
class Braking:
    """Braking figures per candidate (SI: J, W).

    stops: number of stops in the samples; regenerated_energy: over all stops;
    worst_stop_energy; capacitor_energy and resistor_energy: what the capacitors and the
    resistor take in the worst stop; resistor_cycle_energy: the resistor's energy over
    all stops; resistor_peak_power and resistor_continuous_power (cycle mean);
    stop_energy: (candidates, intervals) each stop's energy at its first interval, zero
    elsewhere.
    """

    cycle_time: np.ndarray
    stops: np.ndarray
    regenerated_energy: np.ndarray
    worst_stop_energy: np.ndarray
    capacitor_energy: np.ndarray
    resistor_energy: np.ndarray
    resistor_cycle_energy: np.ndarray
    resistor_peak_power: np.ndarray
    resistor_continuous_power: np.ndarray
    stop_energy: np.ndarray


def braking(time: ArrayLike, bus_power: ArrayLike, absorbable_energy: ArrayLike = 0.0,
            periodic: bool = True) -> Braking:
    """Stops, capacitor and resistor figures of sampled bus power (W; module docstring).

    ``absorbable_energy`` (J): what the bus capacitors take per stop
    (:func:`capacitor_energy`, or a drive's datasheet figure), scalar or per candidate.
    """
    t = times(time)
    power = samples(bus_power, t, "bus_power")
    n, m = max(t.shape[0], power.shape[0]), t.shape[1] - 1
    power = np.broadcast_to(power, (n, m + 1))
    E_cap = per_candidate(nonnegative(finite(absorbable_energy, "absorbable_energy"),
                                      "absorbable_energy"), n, "absorbable_energy")[:, 0]
    E_cap = np.broadcast_to(E_cap, (n,))
    _, down = interval_parts(t, power)
    h = np.diff(t, axis=1)
    p0, p1 = power[:, :-1], power[:, 1:]
    braking_on = (down > 0.0) | ((h == 0.0) & (p0 < 0.0) & (p1 < 0.0))
    peak = np.where(braking_on, np.maximum(np.maximum(-p0, -p1), 0.0), 0.0)
    before = np.zeros_like(braking_on)
    before[:, 1:] = braking_on[:, :-1]
    starts = braking_on & ~before
    whole = braking_on.all(axis=1)
    if periodic:  # a stop through the cycle's end continues at its start
        wrap = braking_on[:, 0] & braking_on[:, -1] & ~whole
        starts[wrap, 0] = False
    run = np.cumsum(starts.ravel()).reshape(n, m) - 1  # stop ids over all rows
    if periodic:  # the leading part of a wrapping row joins the row's last stop
        head = wrap[:, None] & braking_on & (np.cumsum(starts, axis=1) == 0)
        run = np.where(head, run[:, -1:], run)
    count = int(run.max(initial=-1)) + 1
    ids = run[braking_on]
    rows = np.broadcast_to(np.arange(n)[:, None], (n, m))[braking_on]
    cols = np.broadcast_to(np.arange(m)[None, :], (n, m))[braking_on]
    energy = np.bincount(ids, weights=down[braking_on], minlength=count)
    run_peak = np.zeros(count)
    np.maximum.at(run_peak, ids, peak[braking_on])
    run_row = np.zeros(count, dtype=np.intp)
    run_row[ids] = rows
    run_start = np.full(count, m, dtype=np.intp)
    np.minimum.at(run_start, ids, cols)
    full = whole[run_row] & periodic  # steady braking: the capacitors stay full
    cap = np.where(full, 0.0, E_cap[run_row])
    into_resistor = np.maximum(energy - cap, 0.0)
    worst = np.zeros(n)
    np.maximum.at(worst, run_row, energy)
    worst_cap = np.zeros(n)
    worst_res = np.zeros(n)
    absorbed = energy - into_resistor
    # min(E, E_C) and max(E - E_C, 0) grow with E: their maxima are the worst stop's
    np.maximum.at(worst_res, run_row, into_resistor)
    np.maximum.at(worst_cap, run_row, absorbed)
    resistor_peak = np.zeros(n)
    np.maximum.at(resistor_peak, run_row, np.where(into_resistor > 0.0, run_peak, 0.0))
    stop_energy = np.zeros((n, m))
    stop_energy[run_row, run_start] = energy
    cycle = np.broadcast_to(span(t), (n,))
    resistor_cycle = np.bincount(run_row, weights=into_resistor, minlength=n)
    return Braking(
        cycle_time=cycle, stops=np.bincount(run_row, minlength=n),
        regenerated_energy=down.sum(axis=1), worst_stop_energy=worst,
        capacitor_energy=worst_cap, resistor_energy=worst_res,
        resistor_cycle_energy=resistor_cycle, resistor_peak_power=resistor_peak,
        resistor_continuous_power=resistor_cycle / cycle, stop_energy=stop_energy)
