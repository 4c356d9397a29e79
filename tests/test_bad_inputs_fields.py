"""Bad values of every field of the design file: each answered by one located message that
names the file, the field and what is allowed (the range in SI units, or the choices).

The ranges are those of sizer/io/schema/ranges.py (docs/input-ranges.md); the last test walks
the models and fails when a field of the design, motor catalog, gearbox catalog or machine
files has no case here, in tests/test_bad_inputs_catalogs.py or
tests/test_bad_inputs_machine.py.
"""

from __future__ import annotations

import pytest
from bad_input_cases import LINKAGE_READINGS, Case, edited
from bad_input_cases import run_case as run

from sizer.io.schema.fields import input_fields

ROTARY = "book/ex6_1-6_2.yaml"
"""A rotary axis, a direct drive, the book's motors (a mapping per section)."""
LINEAR = "vendor-ballscrew.yaml"
"""A linear axis: transmission[0] a gearbox, transmission[1] a ball screw."""
GEARBOX = "indexing-table.yaml"
"""A rotary axis with one gearbox given as a mapping (transmission.ratio), limits."""

D = "design.yaml:"


def case(id: str, base: str, value: dict, words: tuple[str, ...], fields: tuple[str, ...],
         delete: tuple[str, ...] = ()) -> Case:
    """A design edited from ``base``; the words always hold the file name."""
    return Case(id, design=edited(base, set=value, delete=delete), words=(D, *words),
                fields=fields)


def belt(**fields: object) -> dict:
    return {"transmission": [{"type": "belt", "driver_diameter": "50 mm", **fields}]}


def rotary_belt(**fields: object) -> dict:
    return {"transmission": {"type": "belt", "driver_diameter": "50 mm",
                             "driven_diameter": "100 mm", **fields}}


def rack(**fields: object) -> dict:
    return {"transmission": [{"type": "rack_pinion", "pitch_radius": "20 mm", **fields}]}


SCREW = "transmission[1]"
GB = "transmission[gearbox]"

TASK = [
    case("duration-subnormal", ROTARY, {"task.duration": "1e-320 s"},
         ("task.duration", "[1e-6, 1e6] s", "1e-320"), ("task.duration",)),
    case("duration-1e308", ROTARY, {"task.duration": 1e308},
         ("task.duration", "[1e-6, 1e6] s", "got 1e308 s"), ("task.duration",)),
    case("duration-negative-zero", ROTARY, {"task.duration": -0.0},
         ("task.duration", "[1e-6, 1e6] s", "got 0 s"), ("task.duration",)),
    case("duration-bool", ROTARY, {"task.duration": True},
         ("task.duration", "expected a time"), ("task.duration",)),
    case("duration-list", ROTARY, {"task.duration": [1, 2]},
         ("task.duration", "expected a time"), ("task.duration",)),
    case("master-speed-and-duration", ROTARY, {"task.master_speed": "120 rpm"},
         ("task", "the duration or the master_speed, not both"), ("task.master_speed",)),
    case("master-speed-negative", ROTARY, {"task.master_speed": "-120 rpm"},
         ("task.master_speed", "[1e-6, 1e6] rad/s"), ("task.master_speed",),
         delete=("task.duration",)),
    case("master-speed-without-a-cam", ROTARY, {"task.master_speed": "120 rpm"},
         ("laws", "master_speed needs laws on a master axis"), ("task.master_speed",),
         delete=("task.duration",)),
    case("dwell-subnormal", ROTARY, {"task.dwell": "1e-320 s"},
         ("task.dwell", "0 or in [1e-6, 1e6] s"), ("task.dwell",)),
    case("dwell-two-million-seconds", ROTARY, {"task.dwell": "2e6 s"},
         ("task.dwell", "0 or in [1e-6, 1e6] s", "2e6 s"), ("task.dwell",)),
    case("displacement-zero", ROTARY, {"task.displacement": "0 deg"},
         ("task.displacement", "must not be zero"), ("task.displacement",)),
    case("displacement-integer-too-large", ROTARY, {"task.displacement": 10**400},
         ("task.displacement", "too large", "finite"),
         ("task.displacement",)),
    case("displacement-angle-too-large", ROTARY, {"task.displacement": "1e9 rad"},
         ("task.displacement", "of magnitude in [1e-6, 1e7] rad", "1e9 rad"),
         ("task.displacement",)),
    case("displacement-length-subnormal", LINEAR, {"task.displacement": "-1e-320 m"},
         ("task.displacement", "of magnitude in [1e-7, 1e4] m"), ("task.displacement",)),
    case("return-not-a-bool", ROTARY, {"task.return": "sometimes"},
         ("task.return", "expected true or false"), ("task.return",)),
    case("task-not-a-mapping", ROTARY, {"task": "fast"},
         ("task", "expected a mapping"), ("task",)),
]

LOAD = [
    case("load-inertia-subnormal", ROTARY, {"load.inertia": "1e-320 kg*m^2"},
         ("load.inertia", "[1e-12, 1e8] kg*m^2"), ("load.inertia",)),
    case("load-inertia-list", ROTARY, {"load.inertia": [1, 2]},
         ("load.inertia", "expected a number or a quantity"), ("load.inertia",)),
    case("load-mass-huge", LINEAR, {"load.mass": "1e12 kg"},
         ("load.mass", "[1e-6, 1e7] kg", "1e12 kg"), ("load.mass",)),
    case("load-damping-rotary-negative", ROTARY, {"load.damping": "-0.3 N*m*s/rad"},
         ("load.damping", "0 or in [1e-12, 1e8] N*m*s/rad"), ("load.damping",)),
    case("load-damping-linear-huge", LINEAR, {"load.damping": "1e10 N*s/m"},
         ("load.damping", "0 or in [1e-9, 1e9] N*s/m"), ("load.damping",)),
    case("load-friction-rotary-1e300", GEARBOX, {"load.friction": 1e300},
         ("load.friction", "0 or in [1e-9, 1e8] N*m"), ("load.friction",)),
    case("load-friction-linear-negative", LINEAR, {"load.friction": "-490 N"},
         ("load.friction", "0 or in [1e-9, 1e9] N", "-490 N"), ("load.friction",)),
    case("load-torque-huge", ROTARY, {"load.torque": "1e9 N*m"},
         ("load.torque", "of magnitude in [1e-9, 1e8] N*m"), ("load.torque",)),
    case("load-torque-on-linear-axis", LINEAR, {"load.torque": "1 N*m"},
         ("load.torque", "takes 'force'"), ("load.torque",)),
    case("load-force-subnormal", LINEAR, {"load.force": "1e-320 N"},
         ("load.force", "of magnitude in [1e-9, 1e9] N"), ("load.force",)),
    case("load-incline-beyond-vertical", LINEAR, {"load.incline": "100 deg"},
         ("load.incline", "of magnitude in [1e-9, 1.5708] rad", "100 deg"),
         ("load.incline",)),
    case("load-friction-coefficient-20", LINEAR, {"load.friction_coefficient": 20},
         ("load.friction_coefficient", "0 or in [1e-6, 10]"),
         ("load.friction_coefficient",)),
    case("load-not-a-mapping", ROTARY, {"load": [1, 2]},
         ("load", "expected a mapping"), ("load",)),
]

GEARBOXES = [
    case("gearbox-ratio-1e301", GEARBOX, {"transmission.ratio": 1e301},
         ("transmission.ratio", "[0.001, 1e5]", "1e301"), (f"{GB}.ratio",)),
    case("gearbox-ratio-1e-200", GEARBOX, {"transmission.ratio": 1e-200},
         ("transmission.ratio", "[0.001, 1e5]"), (f"{GB}.ratio",)),
    case("gearbox-ratio-listed-twice", GEARBOX, {"transmission.ratio": [5, 10, 5]},
         ("transmission.ratio", "ratio 5 is listed twice"), (f"{GB}.ratio",)),
    case("gearbox-ratio-optimize-from-zero", GEARBOX,
         {"transmission.ratio": {"optimize": [0, 10]}},
         ("transmission.ratio", "[0.001, 1e5]"), (f"{GB}.ratio",)),
    case("gearbox-unknown-type", GEARBOX, {"transmission.type": "harmonic"},
         ("transmission.type", "unknown type 'harmonic'", "gearbox", "ball_screw"),
         (f"{GB}.type",)),
    case("gearbox-last-on-a-linear-axis", LINEAR,
         {"transmission": [{"type": "gearbox", "ratio": 2}]},
         ("transmission[0].type", "ball_screw, rack_pinion or belt"), (f"{GB}.type",)),
    case("gearbox-catalog-missing", GEARBOX, {"transmission.catalog": "nope.yaml"},
         ("transmission.catalog", "no gearbox catalog file", "nope.yaml"),
         (f"{GB}.catalog",), delete=("transmission.ratio",)),
    case("gearbox-efficiency-0.1-percent", GEARBOX, {"transmission.efficiency": "0.1 %"},
         ("transmission.efficiency", "[0.01, 1]", "0.1 %"), (f"{GB}.efficiency",)),
    case("gearbox-inertia-negative", GEARBOX, {"transmission.inertia": "-0.3 kg*cm^2"},
         ("transmission.inertia", "0 or in [1e-12, 1000] kg*m^2"), (f"{GB}.inertia",)),
    case("gearbox-max-input-speed-zero", GEARBOX, {"transmission.max_input_speed": "0 rpm"},
         ("transmission.max_input_speed", "[0.001, 1e5] rad/s"),
         (f"{GB}.max_input_speed",)),
    case("gearbox-rated-output-torque-huge", GEARBOX,
         {"transmission.rated_output_torque": "1e8 N*m"},
         ("transmission.rated_output_torque", "[1e-6, 1e7] N*m"),
         (f"{GB}.rated_output_torque",)),
    case("gearbox-peak-output-torque-bool", GEARBOX,
         {"transmission.peak_output_torque": True},
         ("transmission.peak_output_torque", "expected a torque"),
         (f"{GB}.peak_output_torque",)),
    case("gearbox-backlash-90-deg", GEARBOX, {"transmission.backlash": "90 deg"},
         ("transmission.backlash", "0 or in [1e-9, 0.5] rad"), (f"{GB}.backlash",)),
    case("gearbox-name-list", GEARBOX, {"transmission.name": ["a"]},
         ("transmission.name", "expected text"), (f"{GB}.name",)),
    case("transmission-total-ratio", LINEAR,
         {"transmission[0].ratio": 1e5, f"{SCREW}.lead": "0.01 mm"},
         ("transmission", "total ratio", "[1e-6, 1e9] rad/m", "6.28319e10"),
         ("transmission",)),
    case("transmission-total-efficiency", ROTARY,
         {"transmission": [{"type": "gearbox", "ratio": 2, "efficiency": 0.02}] * 3},
         ("transmission", "total efficiency", "at least 1e-4", "8e-06"), ("transmission",)),
]

BELTS = [
    case("belt-ratio-1e4", ROTARY, {"transmission": {"type": "belt", "ratio": 1e4}},
         ("transmission.ratio", "[0.001, 1000]"), ("transmission[belt].ratio",)),
    case("belt-driver-diameter-tiny", LINEAR, belt(driver_diameter="0.01 mm"),
         ("transmission[0].driver_diameter", "[1e-4, 10] m"),
         ("transmission[belt].driver_diameter",)),
    case("belt-driven-diameter-20-m", ROTARY, rotary_belt(driven_diameter="20 m"),
         ("transmission.driven_diameter", "[1e-4, 10] m", "20 m"),
         ("transmission[belt].driven_diameter",)),
    case("belt-driver-inertia-negative", ROTARY, rotary_belt(driver_inertia="-1 kg*cm^2"),
         ("transmission.driver_inertia", "0 or in [1e-12, 1000] kg*m^2"),
         ("transmission[belt].driver_inertia",)),
    case("belt-driven-inertia-huge", ROTARY, rotary_belt(driven_inertia="1e4 kg*m^2"),
         ("transmission.driven_inertia", "0 or in [1e-12, 1000] kg*m^2"),
         ("transmission[belt].driven_inertia",)),
    case("belt-mass-negative", LINEAR, belt(belt_mass="-0.2 kg"),
         ("transmission[0].belt_mass", "0 or in [1e-6, 1e4] kg"),
         ("transmission[belt].belt_mass",)),
    case("belt-efficiency-150-percent", LINEAR, belt(efficiency="150 %"),
         ("transmission[0].efficiency", "[0.01, 1]"), ("transmission[belt].efficiency",)),
    case("belt-name-mapping", LINEAR, belt(name={"a": 1}),
         ("transmission[0].name", "expected text"), ("transmission[belt].name",)),
    case("belt-type-a-number", LINEAR, {"transmission": [{"type": 5}]},
         ("transmission[0].type", "unknown type", "belt"), ("transmission[belt].type",)),
]

SCREWS = [
    case("screw-lead-subnormal", LINEAR, {f"{SCREW}.lead": "1e-320 m"},
         (f"{SCREW}.lead", "[1e-5, 2] m"), ("transmission[ball_screw].lead",)),
    case("screw-efficiency-zero", LINEAR, {f"{SCREW}.efficiency": 0},
         (f"{SCREW}.efficiency", "[0.01, 1]"), ("transmission[ball_screw].efficiency",)),
    case("screw-inertia-negative", LINEAR, {f"{SCREW}.inertia": "-1 kg*m^2"},
         (f"{SCREW}.inertia", "0 or in [1e-12, 1000] kg*m^2"),
         ("transmission[ball_screw].inertia",)),
    case("screw-diameter-2-m", LINEAR, {f"{SCREW}.diameter": "2 m"},
         (f"{SCREW}.diameter", "[0.001, 1] m"), ("transmission[ball_screw].diameter",)),
    case("screw-length-1-km", LINEAR, {f"{SCREW}.length": "1 km"},
         (f"{SCREW}.length", "[0.001, 100] m", "1 km"), ("transmission[ball_screw].length",)),
    case("screw-density-subnormal", LINEAR, {f"{SCREW}.density": "1e-320 kg/m^3"},
         (f"{SCREW}.density", "[100, 1e5] kg/m^3"), ("transmission[ball_screw].density",)),
    case("screw-preload-huge", LINEAR, {f"{SCREW}.preload_torque": "1e5 N*m"},
         (f"{SCREW}.preload_torque", "0 or in [1e-9, 1e4] N*m"),
         ("transmission[ball_screw].preload_torque",)),
    case("screw-max-speed-1e6-rpm", LINEAR, {f"{SCREW}.max_speed": "1e6 rpm"},
         (f"{SCREW}.max_speed", "[0.001, 1e5] rad/s", "1e6 rpm"),
         ("transmission[ball_screw].max_speed",)),
    case("screw-name-empty-list", LINEAR, {f"{SCREW}.name": []},
         (f"{SCREW}.name", "expected text"), ("transmission[ball_screw].name",)),
    case("screw-on-a-rotary-axis", ROTARY,
         {"transmission": {"type": "ball_screw", "lead": "10 mm", "inertia": 0}},
         ("transmission.type", "moves a linear axis"), ("transmission[ball_screw].type",)),
]

RACKS = [
    case("rack-pitch-radius-tiny", LINEAR, rack(pitch_radius="0.01 mm"),
         ("transmission[0].pitch_radius", "[1e-4, 10] m"),
         ("transmission[rack_pinion].pitch_radius",)),
    case("rack-pitch-diameter-50-m", LINEAR,
         {"transmission": [{"type": "rack_pinion", "pitch_diameter": "50 m"}]},
         ("transmission[0].pitch_diameter", "[2e-4, 20] m"),
         ("transmission[rack_pinion].pitch_diameter",)),
    case("rack-inertia-huge", LINEAR, rack(inertia="1e4 kg*m^2"),
         ("transmission[0].inertia", "0 or in [1e-12, 1000] kg*m^2"),
         ("transmission[rack_pinion].inertia",)),
    case("rack-efficiency-zero-percent", LINEAR, rack(efficiency="0 %"),
         ("transmission[0].efficiency", "[0.01, 1]"),
         ("transmission[rack_pinion].efficiency",)),
    case("rack-name-bool", LINEAR, rack(name=True),
         ("transmission[0].name", "expected text"), ("transmission[rack_pinion].name",)),
    case("rack-on-a-rotary-axis", ROTARY,
         {"transmission": {"type": "rack_pinion", "pitch_radius": "20 mm"}},
         ("transmission.type", "moves a linear axis"), ("transmission[rack_pinion].type",)),
    case("direct-capitalized", ROTARY, {"transmission": {"type": "Direct"}},
         ("transmission.type", "unknown type 'Direct'", "direct"),
         ("transmission[direct].type",)),
    case("direct-name-list", ROTARY, {"transmission": {"type": "direct", "name": [1]}},
         ("transmission.name", "expected text"), ("transmission[direct].name",)),
]

REST = [
    case("laws-empty", ROTARY, {"laws": []}, ("laws", "at least 1"), ("laws",)),
    case("laws-alpha-out-of-range", ROTARY, {"laws": ["trapezoidal(alpha=2)"]},
         ("laws[0]", "alpha"), ("laws",)),
    case("motors-a-number", ROTARY, {"motors": [42]},
         ("motors[0]", "a catalog", "motor mapping"), ("motors",)),
    case("check-unknown-motor", ROTARY, {"check.motor": "ex6_9"},
         ("check.motor", "unknown motor 'ex6_9'", "ex6_1"), ("check.motor",)),
    case("check-unknown-law", ROTARY, {"check.law": "cycloid"},
         ("check.law", "cycloid"), ("check.law",)),
    case("check-not-a-mapping", ROTARY, {"check": "yes"},
         ("check", "expected a mapping"), ("check",)),
    case("torque-margin-96-percent", GEARBOX, {"limits.torque_margin": "96 %"},
         ("limits.torque_margin", "0 or in [1e-9, 0.95]", "96 %"),
         ("limits.torque_margin",)),
    case("speed-margin-negative", GEARBOX, {"limits.speed_margin": -0.1},
         ("limits.speed_margin", "0 or in [1e-9, 0.95]"), ("limits.speed_margin",)),
    case("inertia-ratio-zero", GEARBOX, {"limits.inertia_ratio": 0},
         ("limits.inertia_ratio", "[0.001, 1e6]"), ("limits.inertia_ratio",)),
    case("max-speed-rotary-huge", GEARBOX, {"limits.max_speed": "1e7 rad/s"},
         ("limits.max_speed", "[1e-6, 1e6] rad/s"), ("limits.max_speed",)),
    case("max-speed-linear-huge", LINEAR, {"limits": {"max_speed": "2e4 m/s"}},
         ("limits.max_speed", "[1e-6, 1e4] m/s"), ("limits.max_speed",)),
    case("max-speed-linear-given-in-rpm", LINEAR, {"limits": {"max_speed": "300 rpm"}},
         ("limits.max_speed", "expected a linear speed"), ("limits.max_speed",)),
    case("max-acceleration-rotary-subnormal", GEARBOX,
         {"limits.max_acceleration": "1e-320 rad/s^2"},
         ("limits.max_acceleration", "[1e-6, 1e9] rad/s^2"), ("limits.max_acceleration",)),
    case("max-acceleration-linear-huge", LINEAR, {"limits": {"max_acceleration": "1e9 m/s^2"}},
         ("limits.max_acceleration", "[1e-6, 1e8] m/s^2"), ("limits.max_acceleration",)),
    case("max-jerk-rotary-huge", GEARBOX, {"limits.max_jerk": "1e14 rad/s^3"},
         ("limits.max_jerk", "[1e-6, 1e13] rad/s^3"), ("limits.max_jerk",)),
    case("max-jerk-linear-negative", LINEAR, {"limits": {"max_jerk": "-5 m/s^3"}},
         ("limits.max_jerk", "[1e-6, 1e12] m/s^3"), ("limits.max_jerk",)),
    case("thermal-speed-peak", GEARBOX, {"limits.thermal_speed": "peak"},
         ("limits.thermal_speed", "max", "rms", "mean"), ("limits.thermal_speed",)),
    case("inertia-ratio-of-motor", GEARBOX, {"limits.inertia_ratio_of": "motor"},
         ("limits.inertia_ratio_of", "driven", "load"), ("limits.inertia_ratio_of",)),
    case("envelope-curvy", GEARBOX, {"limits.envelope": "curvy"},
         ("limits.envelope", "book", "linear", "linear_intermittent"), ("limits.envelope",)),
    case("limits-a-list", GEARBOX, {"limits": [1]},
         ("limits", "expected a mapping"), ("limits",)),
    case("efficiency-applies-to-abb", LINEAR, {"efficiency_applies_to": "abb"},
         ("efficiency_applies_to", "power_flow", "steady_load"), ("efficiency_applies_to",)),
    case("name-a-mapping", ROTARY, {"name": {"a": 1}}, ("name", "expected text"), ("name",)),
]

PRESS = "press-slider-crank.yaml"
SC = "transmission[1]"
FOUR_BAR = {"type": "four_bar", "crank": "75 mm", "coupler": "175 mm", "rocker": "100 mm",
            "ground": "175 mm"}


def four_bar(**fields: object) -> dict:
    """The press with the paper's four-bar in place of its slider-crank (a rotary load)."""
    return {"transmission[1]": {**FOUR_BAR, **fields}, "load": {"inertia": "0.01 kg*m^2"},
            "task.displacement": "360 deg", "laws": ["poly5"]}


def crank(**fields: object) -> dict:
    return {f"{SC}.{k}": v for k, v in fields.items()}


LINKAGES = [
    case("slider-crank-radius-tiny", PRESS, crank(crank_radius="0.01 mm"),
         (f"{SC}.crank_radius", "[1e-4, 100] m"), ("transmission[slider_crank].crank_radius",)),
    case("slider-crank-rod-shorter-than-crank", PRESS, crank(rod_length="40 mm"),
         (f"{SC}.rod_length", "longer than the crank radius"),
         ("transmission[slider_crank].rod_length",)),
    case("slider-crank-offset-too-large", PRESS, crank(offset="200 mm"),
         (f"{SC}.rod_length", "plus the offset"), ("transmission[slider_crank].offset",)),
    case("slider-crank-rod-mass-negative", PRESS, crank(rod_mass_at_crank="-1 kg"),
         (f"{SC}.rod_mass_at_crank", "[1e-6, 1e4] kg"),
         ("transmission[slider_crank].rod_mass_at_crank",)),
    case("slider-crank-rod-mass-slider-huge", PRESS, crank(rod_mass_at_slider="1e5 kg"),
         (f"{SC}.rod_mass_at_slider", "[1e-6, 1e4] kg"),
         ("transmission[slider_crank].rod_mass_at_slider",)),
    case("slider-crank-crank-inertia-huge", PRESS, crank(crank_inertia="1e4 kg*m^2"),
         (f"{SC}.crank_inertia", "[1e-12, 1000] kg*m^2"),
         ("transmission[slider_crank].crank_inertia",)),
    case("slider-crank-law-on-motor", PRESS, crank(law_on="motor"),
         (f"{SC}.law_on", "crank", "output"), ("transmission[slider_crank].law_on",)),
    case("slider-crank-direction-cw", PRESS, crank(direction="cw"),
         (f"{SC}.direction", "positive", "negative"), ("transmission[slider_crank].direction",)),
    case("slider-crank-start-angle-a-length", PRESS, crank(start_angle="10 mm"),
         (f"{SC}.start_angle", "expected an angle"),
         ("transmission[slider_crank].start_angle",)),
    case("slider-crank-name-a-list", PRESS, crank(name=[1]),
         (f"{SC}.name", "expected text"), ("transmission[slider_crank].name",)),
    case("slider-crank-not-last", PRESS, {"task.displacement": "360 deg",
                                          "load": {"inertia": "0.01 kg*m^2"}, "transmission": [
        {"type": "slider_crank", "crank_radius": "50 mm", "rod_length": "200 mm"},
        {"type": "gearbox", "ratio": 10}]},
         ("transmission[0].type", "must be the last stage"),
         ("transmission[slider_crank].type",)),
    case("four-bar-cannot-close", PRESS, four_bar(ground="900 mm"),
         ("transmission[1]", "cannot close"), ("transmission[four_bar].ground",)),
    case("four-bar-crank-not-shortest", PRESS, four_bar(crank="180 mm"),
         ("transmission[1].crank", "crank"), ("transmission[four_bar].crank",)),
    case("four-bar-coupler-zero", PRESS, four_bar(coupler="0 mm"),
         ("transmission[1].coupler", "[1e-4, 100] m"), ("transmission[four_bar].coupler",)),
    case("four-bar-rocker-huge", PRESS, four_bar(rocker="1 km"),
         ("transmission[1].rocker", "[1e-4, 100] m"), ("transmission[four_bar].rocker",)),
    case("four-bar-branch-two", PRESS, four_bar(branch=2),
         ("transmission[1].branch",), ("transmission[four_bar].branch",)),
    case("four-bar-coupler-mass-negative", PRESS, four_bar(coupler_mass_at_crank="-2 kg"),
         ("transmission[1].coupler_mass_at_crank", "[1e-6, 1e4] kg"),
         ("transmission[four_bar].coupler_mass_at_crank",)),
    case("four-bar-coupler-mass-rocker-huge", PRESS, four_bar(coupler_mass_at_rocker="1e5 kg"),
         ("transmission[1].coupler_mass_at_rocker",),
         ("transmission[four_bar].coupler_mass_at_rocker",)),
    case("four-bar-crank-inertia-negative", PRESS, four_bar(crank_inertia="-1 kg*m^2"),
         ("transmission[1].crank_inertia",), ("transmission[four_bar].crank_inertia",)),
    case("four-bar-law-on-rocker", PRESS, four_bar(law_on="rocker"),
         ("transmission[1].law_on", "crank", "output"), ("transmission[four_bar].law_on",)),
    case("four-bar-direction-number", PRESS, four_bar(direction=1),
         ("transmission[1].direction",), ("transmission[four_bar].direction",)),
    case("four-bar-start-angle-huge", PRESS, four_bar(start_angle="1e6 rad"),
         ("transmission[1].start_angle",), ("transmission[four_bar].start_angle",)),
    case("four-bar-name-a-list", PRESS, four_bar(name=[5]),
         ("transmission[1].name", "expected text"), ("transmission[four_bar].name",)),
    case("four-bar-on-a-linear-axis", PRESS, {**four_bar(), "task.displacement": "100 mm",
                                              "transmission[1].law_on": "output"},
         ("transmission", "linear"), ("transmission[four_bar].type",)),
]

VIBRATION = [
    case("natural-frequency-negative", GEARBOX, {"load.natural_frequency": "-25 Hz"},
         ("load.natural_frequency", "[0.001, 1e6]", "got -25"), ("load.natural_frequency",)),
    case("natural-frequency-zero", GEARBOX, {"load.natural_frequency": 0},
         ("load.natural_frequency", "[0.001, 1e6]"), ("load.natural_frequency",)),
    case("natural-frequency-a-length", GEARBOX, {"load.natural_frequency": "25 mm"},
         ("load.natural_frequency",), ()),
    case("damping-ratio-one", GEARBOX, {"load.natural_frequency": "25 Hz",
                                        "load.damping_ratio": 1},
         ("load.damping_ratio", "0.999999", "got 1"), ("load.damping_ratio",)),
    case("damping-ratio-negative", GEARBOX, {"load.natural_frequency": "25 Hz",
                                             "load.damping_ratio": -0.1},
         ("load.damping_ratio", "got -0.1"), ()),
    case("damping-ratio-without-mode", GEARBOX, {"load.damping_ratio": 0.02},
         ("load.damping_ratio", "natural_frequency"), ()),
    case("residual-limit-without-mode", GEARBOX, {"limits.residual_vibration": "10 arcsec"},
         ("limits.residual_vibration", "natural_frequency"), ("limits.residual_vibration",)),
    case("residual-limit-a-length-on-a-rotary-axis", GEARBOX,
         {"load.natural_frequency": "25 Hz", "limits.residual_vibration": "0.1 mm"},
         ("limits.residual_vibration",), ()),
    case("residual-limit-negative", GEARBOX,
         {"load.natural_frequency": "25 Hz", "limits.residual_vibration": "-1 arcsec"},
         ("limits.residual_vibration",), ()),
]

ENERGY = [
    case("winding-rise-limit-below-1-k", GEARBOX, {"limits.winding_temperature_rise": "0.5 K"},
         ("limits.winding_temperature_rise", "[1, 400] K", "0.5"),
         ("limits.winding_temperature_rise",)),
    case("winding-rise-limit-a-power", GEARBOX, {"limits.winding_temperature_rise": "80 W"},
         ("limits.winding_temperature_rise",), ()),
    case("braking-power-limit-negative", GEARBOX, {"limits.braking_resistor_power": "-5 W"},
         ("limits.braking_resistor_power", "0 or in [0.001, 1e7] W", "-5"),
         ("limits.braking_resistor_power",)),
    case("braking-power-limit-a-list", GEARBOX, {"limits.braking_resistor_power": [1, 2]},
         ("limits.braking_resistor_power",), ()),
    case("thermal-duty-unknown", GEARBOX, {"limits.thermal_duty": "sometimes"},
         ("limits.thermal_duty", "repeated", "once"), ("limits.thermal_duty",)),
    case("thermal-duty-once-with-minimize", GEARBOX,
         {"limits.thermal_duty": "once", "task.duration": "minimize"},
         ("limits.thermal_duty", "given durations"), ()),
]

CASES = [*TASK, *LOAD, *GEARBOXES, *BELTS, *SCREWS, *RACKS, *REST, *LINKAGES,
         *LINKAGE_READINGS, *VIBRATION, *ENERGY]


@pytest.mark.parametrize("case", CASES, ids=str)
def test_bad_input(case, tmp_path):
    run(case, tmp_path)


def test_case_ids_are_unique():
    ids = [c.id for c in CASES]
    assert len(ids) == len(set(ids))


def test_every_field_of_the_input_files_has_a_case():
    from test_bad_inputs_catalogs import CASES as CATALOG_CASES
    from test_bad_inputs_machine import CASES as MACHINE_CASES
    from test_ball_screw_checks import FIELD_CASES as SCREW_CASES  # a screw's ratings
    from test_cam_follower import FIELD_CASES as CAM_CASES  # a disc cam's fields
    from test_cycle_input import CASES as CYCLE_CASES  # the fields of `cycle:`
    from test_gearbox_output_life import FIELD_CASES as GEARBOX_LIFE_CASES  # its bearing life
    from test_gearbox_shaft_loads import FIELD_CASES as GEARBOX_SHAFT_CASES  # gearbox output
    from test_position_tables import POSITION_FIELD_CASES as POSITION_CASES  # position terms
    from test_robust import FIELD_CASES as ROBUST_CASES  # the design's tolerances
    from test_shaft_loads import FIELD_CASES as SHAFT_CASES  # shaft loads and ratings

    named = {f for c in (*CASES, *CATALOG_CASES, *CYCLE_CASES, *MACHINE_CASES, *SCREW_CASES,
                         *CAM_CASES, *POSITION_CASES, *ROBUST_CASES, *SHAFT_CASES,
                         *GEARBOX_SHAFT_CASES, *GEARBOX_LIFE_CASES)
             for f in c.fields}
    # an axis's design fields are read by the design loader: the design's cases cover them
    named |= {f"machine:axes.{f}" for f in named if f"machine:axes.{f}" in input_fields()}
    fields = set(input_fields())
    assert sorted(fields - named) == [], "fields without a bad-input case"
    assert sorted(named - fields) == [], "cases naming no field of the models"
    assert len(CASES) + len(CATALOG_CASES) >= 60
