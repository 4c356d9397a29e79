"""The plausible range of every quantity of the input files, written once.

Each field of a design, motor catalog or gearbox catalog that holds a quantity names one
:class:`Range` of :data:`RANGES`. The same table checks the values (a value outside gives
a one-line message with the range in SI units and the value given), writes ``minimum`` and
``maximum`` into the JSON Schema and is printed in docs/input-ranges.md (a test compares
the document with :func:`ranges_markdown`).

The bounds are generous for real machines (a 1 us move, a 100 t load, a 1e5:1 gearbox)
and keep every computation of the sizing finite: docs/input-ranges.md derives the largest
speeds, torques and their squares that the extreme combinations give.
"""

from __future__ import annotations

import math
import re
import sys
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from sizer.units import KINDS


def number_text(x: float) -> str:
    """A short text of a bound: 1e-06 -> '1e-6', 100000 -> '1e5', 1.5707963 -> '1.5708'."""
    if x != 0.0 and abs(x) < sys.float_info.min:
        return repr(x)  # a subnormal as written (1e-320), not its rounded mantissa
    if x != 0.0 and not 1e-3 <= abs(x) < 1e4:
        mantissa, exponent = f"{x:.5e}".split("e")
        mantissa = mantissa.rstrip("0").rstrip(".")
        return f"{mantissa}e{int(exponent)}"
    text = f"{x:.6g}"
    return re.sub(r"e([+-])0*(\d)", lambda m: f"e{'-' if m.group(1) == '-' else ''}"
                  f"{m.group(2)}", text)


@dataclass(frozen=True)
class Range:
    """Allowed values of a quantity, in SI: ``low <= |x| <= high`` (or x itself).

    ``zero``: 0 is allowed too (meaning none: no dwell, no damping), smaller magnitudes
    are not (a subnormal 1e-320 is a mistake, never a figure). ``signed``: the sign is
    free and the magnitude must be in range (a load torque, a displacement).
    """

    kind: str
    low: float
    high: float
    why: str
    zero: bool = False
    signed: bool = False

    @property
    def unit(self) -> str:
        """The SI unit of the kind ('' for a pure number)."""
        unit = KINDS[self.kind].si_unit
        return "" if unit == "1" else unit

    def contains(self, x: float) -> bool:
        """True if ``x`` (SI) is allowed."""
        return bool(self.contains_all(np.float64(x)))

    def contains_all(self, x: npt.NDArray[np.float64] | np.float64) -> npt.NDArray[np.bool_]:
        """:meth:`contains` of each value of an array (SI), as a boolean array."""
        size = np.abs(x) if self.signed else x
        inside = (self.low <= size) & (size <= self.high)
        zero = self.zero or (self.low == 0.0 and not self.signed)
        return np.where(x == 0.0, zero, inside) & np.isfinite(x)

    def text(self) -> str:
        """'in [1e-6, 1e6] s', '0 or in [...]', '0 or of magnitude in [...]'."""
        interval = f"[{number_text(self.low)}, {number_text(self.high)}]"
        unit = f" {self.unit}" if self.unit else ""
        core = f"of magnitude in {interval}" if self.signed else f"in {interval}"
        return f"{'0 or ' if self.zero else ''}{core}{unit}"

    @property
    def span(self) -> tuple[float, float]:
        """The smallest and largest allowed values (for the JSON Schema)."""
        if self.signed:
            return -self.high, self.high
        return (0.0 if self.zero else self.low), self.high


def _r(kind: str, low: float, high: float, why: str, **flags: bool) -> Range:
    return Range(kind, low, high, why, **flags)


RANGES: dict[str, Range] = {
    # task
    "duration": _r("time", 1e-6, 1e6, "1 us is shorter than any servo's control period; "
                   "1e6 s is 11.6 days for one move"),
    "dwell": _r("time", 1e-6, 1e6, "as a duration; 0 = no rest", zero=True),
    "angle_displacement": _r("angle", 1e-6, 1e7, "0.2 arcsec to 1.6 million turns; the "
                             "sign is the direction", signed=True),
    "length_displacement": _r("length", 1e-7, 1e4, "0.1 um to 10 km; the sign is the "
                              "direction", signed=True),
    "master_speed": _r("angular_speed", 1e-6, 1e6, "the speed of the master axis of an "
                       "electronic cam, e.g. '120 rpm'"),
    # machine (several axes on one master: book sec. 5.3)
    "master_angle": _r("angle", 1e-6, 1e7, "a share of the master's cycle, e.g. '120 deg' "
                       "of its 360 deg"),
    "master_phase": _r("angle", 1e-6, 1e7, "where an axis's cycle starts on the master, "
                       "0 = at the machine cycle's start", zero=True),
    "master_dwell": _r("angle", 1e-6, 1e7, "a rest on the master, 0 = none", zero=True),
    # cycle (segments of a machine cycle)
    "cycle_rate": _r("rate", 1e-6, 1e6, "cycles per second: the inverse of the durations' "
                     "range (one cycle in 11.6 days to one in 1 us)"),
    "segment_angular_speed": _r("angular_speed", 1e-6, 1e6, "a boundary or run speed at "
                                "the load, as limits.max_speed; the sign is the direction, "
                                "0 = at rest", zero=True, signed=True),
    "segment_linear_speed": _r("linear_speed", 1e-6, 1e4, "as limits.max_speed on a linear "
                               "axis; the sign is the direction, 0 = at rest", zero=True,
                               signed=True),
    "segment_angular_acceleration": _r("angular_acceleration", 1e-6, 1e9, "a boundary "
                                       "acceleration at the load, as limits.max_acceleration; "
                                       "the sign is the direction, 0 = none", zero=True,
                                       signed=True),
    "segment_linear_acceleration": _r("linear_acceleration", 1e-6, 1e8, "as "
                                      "limits.max_acceleration on a linear axis; the sign is "
                                      "the direction, 0 = none", zero=True, signed=True),
    "segment_weight": _r("ratio", 1e-6, 1e6, "relative shares of the free time"),
    "added_inertia": _r("inertia", 1e-12, 1e8, "as the load's inertia; 0 = none", zero=True),
    "added_mass": _r("mass", 1e-6, 1e7, "as the load's mass; 0 = none", zero=True),
    # load
    "load_inertia": _r("inertia", 1e-12, 1e8, "a watch gear (1e-12 kg*m^2) to a 500 t "
                       "turntable of 20 m diameter"),
    "load_mass": _r("mass", 1e-6, 1e7, "1 mg to 10,000 t"),
    "load_rotary_damping": _r("rotary_damping", 1e-12, 1e8, "as the inertia", zero=True),
    "load_linear_damping": _r("linear_damping", 1e-9, 1e9, "as the mass", zero=True),
    "load_friction_torque": _r("torque", 1e-9, 1e8, "as the torques", zero=True),
    "load_friction_force": _r("force", 1e-9, 1e9, "as the forces", zero=True),
    "load_torque": _r("torque", 1e-9, 1e8, "1 nN*m to 100 MN*m, either sign", zero=True,
                      signed=True),
    "load_force": _r("force", 1e-9, 1e9, "1 nN to 1 GN (100,000 t), either sign",
                     zero=True, signed=True),
    "incline": _r("angle", 1e-9, math.pi / 2, "horizontal to vertical, up or down",
                  zero=True, signed=True),
    "friction_coefficient": _r("ratio", 1e-6, 10.0, "PTFE (0.04) to rubber on a rough "
                               "surface (about 1), widened", zero=True),
    "natural_frequency": _r("rate", 1e-3, 1e6, "a mode of the load (sec. 7.1.1), in Hz (a bare "
                            "number is Hz): a crane's sway (0.01 Hz) to 1 MHz"),
    "damping_ratio": _r("ratio", 1e-9, 0.999999, "under-damped, below 1 (the residual "
                        "vibration of sec. 7.2 needs an oscillating mode); 0 = undamped",
                        zero=True),
    # transmission
    "gear_ratio": _r("ratio", 1e-3, 1e5, "a 1000:1 speed-up to a 100,000:1 gear train "
                     "(harmonic and worm stages reach 1:160 each)"),
    "belt_ratio": _r("ratio", 1e-3, 1e3, "pulleys of 1 mm and 1 m"),
    "efficiency": _r("fraction", 0.01, 1.0, "1 %: below a self-locking worm gear (about "
                     "30 %) by far; 1/efficiency multiplies torques by at most 100"),
    "stage_inertia": _r("inertia", 1e-12, 1e3, "a pinion of 1 mm to a 10 t flywheel; "
                        "0 = negligible", zero=True),
    "stage_speed": _r("angular_speed", 1e-3, 1e5, "0.01 rpm to 955,000 rpm (a spindle "
                      "turbine)"),
    "stage_torque": _r("torque", 1e-6, 1e7, "1 uN*m to 10 MN*m (a mill's gearbox)"),
    "backlash": _r("angle", 1e-9, 0.5, "up to 29 deg; informative", zero=True),
    "pulley_diameter": _r("length", 1e-4, 10.0, "0.1 mm to 10 m: ratio 2/d of a belt "
                          "carrying the load in [0.2, 20,000] rad/m"),
    "belt_mass": _r("mass", 1e-6, 1e4, "as a load; 0 = negligible", zero=True),
    "screw_lead": _r("length", 1e-5, 2.0, "10 um to 2 m: ratio 2 pi / lead in [3.14, "
                     "628,319] rad/m (a lead of 0.1 mm is 62,832 rad/m)"),
    "screw_diameter": _r("length", 1e-3, 1.0, "1 mm to 1 m"),
    "screw_length": _r("length", 1e-3, 100.0, "1 mm to 100 m"),
    "density": _r("density", 100.0, 1e5, "foams (100 kg/m^3) to beyond osmium "
                  "(22,590 kg/m^3)"),
    "preload_torque": _r("torque", 1e-9, 1e4, "as the torques; 0 = none", zero=True),
    "screw_safety_factor": _r("fraction", 0.01, 1.0, "a ball screw's permissible share of "
                              "its critical speed (THK: 0.8) or buckling load (THK: 0.5)"),
    "screw_load_rating": _r("force", 1.0, 1e8, "a ball screw's basic dynamic load rating "
                            "C_a: 1 N to 100 MN (the largest screws: a few MN)"),
    "screw_load_factor": _r("ratio", 1.0, 10.0, "f_w: THK gives 1.0 to 1.2 (smooth), 1.2 to "
                            "1.5 (normal), 1.5 to 3.0 (impacts)"),
    "screw_life": _r("time", 1.0, 1e10, "the required L10 life of a ball screw, e.g. "
                     "'20000 h' (7.2e7 s); up to 317 years"),
    "link_length": _r("length", 1e-4, 100.0, "0.1 mm to 100 m: a crank, a rod or a link of a "
                      "linkage"),
    "link_offset": _r("length", 1e-9, 100.0, "the slider line's distance from the crank "
                      "axis; 0 = in line", zero=True, signed=True),
    "link_mass": _r("mass", 1e-6, 1e4, "a link's mass as point masses at its joints; "
                    "0 = negligible", zero=True),
    "crank_angle": _r("angle", 1e-9, 1e3, "the crank's angle at the start of the move, "
                      "from the slider line or the ground link", zero=True, signed=True),
    "cam_radius": _r("length", 1e-4, 10.0, "0.1 mm to 10 m: a cam's base circle or its "
                     "roller"),
    "cam_offset": _r("length", 1e-9, 10.0, "the follower's axis from the cam's centre; "
                     "0 = in line", zero=True, signed=True),
    "pressure_angle": _r("angle", 1e-3, 1.5, "a cam's largest pressure angle, below 86 deg "
                         "(30 deg for a translating follower)"),
    "follower_mass": _r("mass", 1e-6, 1e4, "a cam follower's own mass; 0 = in the load",
                        zero=True),
    "spring_force": _r("force", 1e-9, 1e7, "a cam follower's spring force; 0 = none",
                       zero=True),
    "spring_torque": _r("torque", 1e-9, 1e6, "an oscillating cam follower's spring torque; "
                        "0 = none", zero=True),
    "pitch_radius": _r("length", 1e-4, 10.0, "0.1 mm to 10 m: ratio 1/r in [0.1, 10,000] "
                       "rad/m (r = 1 mm is 1000 rad/m)"),
    "belt_pretension": _r("force", 1e-3, 1e7, "a belt's static tension per strand, as "
                          "installed: 1 mN to 10 MN"),
    "wrap_angle": _r("angle", 1e-3, 2.0 * math.pi, "the belt's arc of contact on the "
                     "driver pulley, up to a full turn"),
    "gear_pressure_angle": _r("angle", 1e-3, 1.0, "a spur pinion's pressure angle (20 deg "
                              "standard, 14.5 deg old), below 57 deg"),
    "pitch_diameter": _r("length", 2e-4, 20.0, "twice the pitch radius"),
    # motors
    "motor_inertia": _r("inertia", 1e-12, 1e3, "a micro motor (1e-12 kg*m^2) to a 1000 "
                        "kg*m^2 torque motor; 0 only for idealized textbook motors whose "
                        "rotor is counted in the load", zero=True),
    "motor_torque": _r("torque", 1e-6, 1e6, "1 uN*m (a watch motor) to 1 MN*m (a ship's "
                       "direct drive)"),
    "motor_speed": _r("angular_speed", 1e-3, 1e5, "0.01 rpm to 955,000 rpm"),
    "motor_damping": _r("rotary_damping", 1e-12, 1e3, "viscous friction of the rotor; "
                        "0 = none", zero=True),
    "curve_speed": _r("angular_speed", 1e-3, 1e5, "as the motor's speeds; a curve may "
                      "start at 0", zero=True),
    "curve_torque": _r("torque", 1e-6, 1e6, "as the motor's torques; a curve may end at 0",
                       zero=True),
    "price": _r("money", 1e-3, 1e9, "any currency; 0 = free", zero=True),
    "motor_mass": _r("mass", 1e-4, 1e5, "0.1 g to 100 t"),
    "torque_constant": _r("torque_constant", 1e-5, 1e3, "k_t, torque per ampere (RMS): "
                          "10 uN*m/A (a micro motor) to 1000 N*m/A (a large torque motor)"),
    "winding_resistance": _r("resistance", 1e-4, 1e4, "0.1 mOhm (a large motor) to 10 "
                             "kOhm (a micro motor's fine winding)"),
    "winding_inductance": _r("inductance", 1e-8, 10.0, "10 nH (a large motor's winding) to "
                             "10 H (a micro motor's fine winding)"),
    "back_emf_constant": _r("back_emf_constant", 1e-5, 1e4, "k_e, RMS line to line, per "
                            "rad/s: about 1 mV/krpm to 1 MV/krpm, as torque_constant"),
    "poles": _r("ratio", 2.0, 1000.0, "the rotor's magnetic poles (twice the pole pairs): "
                "servo motors have 4 to 50"),
    "motor_current": _r("current", 1e-4, 1e5, "0.1 mA to 100 kA, RMS (a motor's rated or "
                        "peak current)"),
    "supply_voltage": _r("voltage", 1.0, 1e4, "1 V to 10 kV AC, line to line (RMS)"),
    "brake_holding_torque": _r("torque", 1e-6, 1e6, "a holding brake's static friction torque "
                               "at the motor shaft, as the motors' torques"),
    "shaft_load": _r("force", 1e-3, 1e7, "a motor's or a gearbox output's permissible "
                     "radial or axial shaft load (or one rated for a bearing life): 1 mN (a "
                     "micro motor) to 10 MN"),
    "bearing_life": _r("time", 1.0, 1e10, "the bearing life a gearbox's rated output "
                       "forces are for, e.g. '20000 h' (7.2e7 s); up to 317 years"),
    "shaft_load_point": _r("length", 1e-4, 10.0, "0.1 mm to 10 m from the flange",
                           zero=True),
    "brake_inertia": _r("inertia", 1e-12, 1e3, "what the brake adds to the rotor's inertia; "
                        "0 = negligible", zero=True),
    "thermal_time_constant": _r("time", 0.1, 1e6, "0.1 s (a winding alone) to 11.6 days; "
                                "never 0 (a motor has some heat capacity)"),
    "winding_temperature_rise": _r("temperature_rise", 1.0, 400.0, "the winding's allowed "
                                   "rise over the ambient: vendors give 60 K to 155 K"),
    "curve_current": _r("current", 1e-4, 1e5, "as the currents of motors and drives; a "
                        "torque-current curve may start at 0", zero=True),
    # drives
    "drive_current": _r("current", 1e-4, 1e5, "0.1 mA to 100 kA, RMS; never 0 (a drive "
                        "with no current drives nothing)"),
    "bus_voltage": _r("voltage", 1.0, 1e4, "1 V to 10 kV DC"),
    "bus_capacitance": _r("capacitance", 1e-9, 10.0, "1 nF to 10 F"),
    "braking_power": _r("power", 1e-3, 1e7, "continuous power of the braking resistor; 0 = "
                        "none built in", zero=True),
    # limits
    "margin": _r("fraction", 1e-9, 0.95, "a margin of 95 % leaves 1/20 of the capability; "
                 "0 = none", zero=True),
    "inertia_ratio": _r("ratio", 1e-3, 1e6, "vendors allow 3 to 30, direct drives "
                        "thousands"),
    "load_max_angular_speed": _r("angular_speed", 1e-6, 1e6, "at the load"),
    "load_max_linear_speed": _r("linear_speed", 1e-6, 1e4, "at the load: up to 10 km/s"),
    "load_max_angular_acceleration": _r("angular_acceleration", 1e-6, 1e9, "at the load"),
    "load_max_linear_acceleration": _r("linear_acceleration", 1e-6, 1e8, "at the load"),
    "load_max_angular_jerk": _r("angular_jerk", 1e-6, 1e13, "at the load"),
    "load_max_linear_jerk": _r("linear_jerk", 1e-6, 1e12, "at the load"),
    "residual_angle": _r("angle", 1e-12, 10.0, "the amplitude of the vibration a move leaves "
                         "at the load (sec. 7.2)"),
    "residual_length": _r("length", 1e-12, 10.0, "the amplitude of the vibration a move "
                          "leaves at the load (sec. 7.2)"),
    # loads of the load's position (docs/position-loads.md)
    "arm_mass": _r("mass", 1e-6, 1e7, "as the load's mass; 0 = no gravity term", zero=True),
    "arm_radius": _r("length", 1e-6, 1e3, "the distance from the axis to the arm's centre "
                     "of mass: 1 um to 1 km"),
    "arm_angle": _r("angle", 1e-9, 2.0 * math.pi, "the arm's angle above the horizontal "
                    "at the start of the move, either sign", zero=True, signed=True),
    "gravity": _r("linear_acceleration", 1e-3, 1e3, "9.80665 m/s^2 on Earth (the default), "
                  "1.62 on the Moon, up to a centrifuge's"),
    "spring_rotary_stiffness": _r("torque", 1e-9, 1e9, "N*m/rad (written '2 N*m/rad' or "
                                  "'0.1 N*m/deg'); 0 = none", zero=True),
    "spring_rotary_preload": _r("torque", 1e-9, 1e8, "as the load's torque, either sign",
                                zero=True, signed=True),
    "spring_free_angle": _r("angle", 1e-9, 1e3, "from the start of the move, either sign",
                            zero=True, signed=True),
    "table_angle": _r("angle", 1e-9, 1e3, "a torque table's position (its offset: the "
                      "table's position at the start of the move), either sign",
                      zero=True, signed=True),
    "table_torque": _r("torque", 1e-9, 1e8, "a torque table's torque, positive opposing a "
                       "positive move, either sign", zero=True, signed=True),
    "table_length": _r("length", 1e-9, 1e4, "a force table's position (its offset: the "
                       "table's position at the start of the move), either sign",
                       zero=True, signed=True),
    "table_force": _r("force", 1e-9, 1e9, "a force table's force, positive opposing a "
                      "positive move, either sign", zero=True, signed=True),
    "table_inertia": _r("inertia", 1e-12, 1e8, "an inertia table's inertia, added to the "
                        "load's: as the load's inertia, 0 allowed", zero=True),
    "table_mass": _r("mass", 1e-9, 1e7, "a mass table's mass, added to the load's: as the "
                     "load's mass, 0 allowed", zero=True),
}
"""Every range of the input files, by name (the fields name them)."""

TOTAL_RATIO = (1e-6, 1e9)
"""The product of a transmission's stage ratios, motor speed over load speed (rad/rad or
rad/m), over every option of a free ratio: a 1e6:1 speed-up to a screw of 6 nm lead."""

TOTAL_EFFICIENCY = 1e-4
"""The smallest product of a transmission's stage efficiencies: two stages of 1 %. It
bounds the torque a chain of lossy stages multiplies (1 / efficiency)."""


def check_range(name: str, x: float) -> None:
    """Raise ValueError 'must be in [..] unit, got ..' if ``x`` (SI) is outside the range."""
    allowed = RANGES[name]
    if not allowed.contains(x):
        unit = f" {allowed.unit}" if allowed.unit else ""
        raise ValueError(f"must be {allowed.text()}, got {number_text(x)}{unit}")


def ranges_markdown(fields: dict[str, list[str]]) -> str:
    """The table of docs/input-ranges.md: range, allowed values (SI), fields, why.

    ``fields`` lists the fields that use each range (from the models' annotations).
    """
    lines = ["| range | allowed (SI) | fields | why |", "| --- | --- | --- | --- |"]
    for name, allowed in RANGES.items():
        used = ", ".join(f"`{f}`" for f in fields.get(name, ())) or "-"
        lines.append(f"| {name} | {allowed.text()} | {used} | {allowed.why} |")
    return "\n".join(lines) + "\n"
