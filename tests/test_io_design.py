"""Design files: SI values, linear axes, catalogs, and errors located by file, line, field."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from sizer.errors import UserError
from sizer.io import default_laws, design_schema, load_design
from sizer.io.yaml_source import parse_yaml
from sizer.laws import DEFAULT_LAW_SPECS

CATALOG = """\
catalog: Example servo motors
manufacturer: Example Corp
motors:
  - id: EX-100
    inertia: 0.26 kg*cm^2
    continuous_torque: 0.32 N*m
    peak_torque: 0.95 N*m
    rated_speed: 3000 rpm
  - id: EX-200
    inertia: 1.2 kg*cm^2
    continuous_torque: 0.64 N*m
    peak_torque: 1.9 N*m
    rated_speed: 3000 rpm
    max_speed: 6000 rpm
"""

DESIGN = """\
name: Indexing table
task:
  displacement: 90 deg
  duration: 0.25 s
  dwell: 0.15 s
  return: true
load:
  inertia: 0.35 kg*m^2
  damping: 0.01 N*m*s/rad
  friction: 0.2 N*m
  torque: 0 N*m
transmission:
  type: gearbox
  ratio: 10
  efficiency: 95 %
  inertia: 1.2 kg*cm^2
laws:
  - cycloidal
  - poly5
  - "trapezoidal(alpha=1/3)"
  - "double_s(alpha=auto, beta=auto)"
motors:
  - catalogs/example-servo.yaml
  - book-examples
  - id: INLINE-1
    inertia: 2 kg*cm^2
    continuous_torque: 1.3 N*m
    peak_torque: 3.9 N*m
    rated_speed: 3000 rpm
check:
  motor: EX-200
  law: cycloidal
limits:
  torque_margin: 10 %
  speed_margin: 5 %
  inertia_ratio: 10
  max_acceleration: 500 rad/s^2
  max_jerk: 1e5 rad/s^3
  thermal_speed: rms
"""

LINEAR = """\
task:
  displacement: 200 mm
  duration: minimize
load:
  mass: 12 kg
  damping: 5 N*s/m
  friction: 10 N
  force: 50 N
transmission: {type: ball_screw, lead: 200 mm, efficiency: 0.9, inertia: 0}
motors: book-examples
limits:
  max_acceleration: 20 m/s^2
  max_jerk: 1000 m/s^3
"""


@pytest.fixture
def project(tmp_path: Path) -> Path:
    """A folder with the example catalog in catalogs/."""
    (tmp_path / "catalogs").mkdir()
    (tmp_path / "catalogs" / "example-servo.yaml").write_text(CATALOG)
    return tmp_path


def write(folder: Path, text: str, name: str = "design.yaml") -> Path:
    path = folder / name
    path.write_text(text)
    return path


def line_of(text: str, needle: str) -> int:
    """1-based line of the last line containing ``needle`` (the whole line if it ends in $)."""
    if needle.endswith("$"):
        hits = [i for i, line in enumerate(text.splitlines(), 1)
                if line.strip() == needle[:-1].strip()]
    else:
        hits = [i for i, line in enumerate(text.splitlines(), 1) if needle in line]
    return hits[-1]


def error_of(path: Path, **kwargs) -> UserError:
    with pytest.raises(UserError) as info:
        load_design(path, **kwargs)
    return info.value


# ------------------------------------------------------------------ valid


def test_design_loads_in_si(project, monkeypatch):
    monkeypatch.chdir("/")  # catalog paths are relative to the design file, not the cwd
    design = load_design(write(project, DESIGN))
    assert design.name == "Indexing table"
    task = design.task
    assert task.displacement == pytest.approx(math.pi / 2)
    assert task.duration == pytest.approx(0.25)
    assert task.dwell == pytest.approx(0.15)
    assert task.return_move is True
    assert task.linear is False
    load = design.load
    assert (load.inertia, load.damping, load.friction, load.torque) == \
        pytest.approx((0.35, 0.01, 0.2, 0.0))
    (stage,) = design.transmission.stages
    assert stage.kind == "gearbox"
    assert stage.ratio == 10
    assert stage.efficiency == pytest.approx(0.95)
    assert stage.inertia == pytest.approx(1.2e-4)
    assert design.transmission.ratio == 10
    assert design.laws == ("cycloidal", "poly5", "trapezoidal(alpha=1/3)",
                           "double_s(alpha=auto, beta=auto)")
    ids = [m.id for m in design.motors]
    assert ids == ["EX-100", "EX-200", "ex6_1", "ex6_3", "ex6_4", "INLINE-1"]
    ex200 = design.motors[1]
    assert ex200.rated_speed == pytest.approx(100 * math.pi)
    assert ex200.max_speed == pytest.approx(200 * math.pi)
    assert ex200.inertia == pytest.approx(1.2e-4)
    assert ex200.manufacturer == "Example Corp"
    assert design.motors[-1].inertia == pytest.approx(2e-4)
    assert design.chosen_motor == "EX-200"
    assert design.chosen_law == "cycloidal"
    limits = design.limits
    assert limits.torque_margin == pytest.approx(0.1)
    assert limits.speed_margin == pytest.approx(0.05)
    assert limits.inertia_ratio == 10
    assert limits.max_acceleration == pytest.approx(500)
    assert limits.max_jerk == pytest.approx(1e5)
    assert limits.thermal_speed == "rms"


def test_linear_axis(tmp_path):
    design = load_design(write(tmp_path, LINEAR))
    assert design.task.linear is True
    assert design.task.displacement == pytest.approx(0.2)
    assert design.task.duration is None and design.task.minimize
    assert design.load.inertia == pytest.approx(12)  # the mass
    assert design.load.torque == pytest.approx(50)  # the force
    assert design.load.damping == pytest.approx(5)
    assert design.load.friction == pytest.approx(10)
    assert design.limits.max_acceleration == pytest.approx(20)
    assert design.limits.max_jerk == pytest.approx(1000)
    assert design.transmission.efficiency == pytest.approx(0.9)
    assert design.name == "design"  # no name: the file's stem


def test_minimal_design_defaults(tmp_path):
    text = "task: {displacement: 1, duration: 1}\nload: {inertia: 1}\n"
    design = load_design(write(tmp_path, text))
    assert design.task.displacement == 1.0 and design.task.dwell == 0.0
    assert design.task.return_move is False
    assert design.transmission.stages == ()
    assert design.motors == ()
    assert design.chosen_motor is None and design.chosen_law is None
    assert design.laws == default_laws()
    assert "exponential(sigma=7.1, lam=0.2)" not in design.laws
    assert set(design.laws) == set(DEFAULT_LAW_SPECS) - {"exponential(sigma=7.1, lam=0.2)"}
    assert design.limits.thermal_speed == "max"
    assert design.limits.inertia_ratio is None


def test_direct_transmission_and_stage_list(tmp_path):
    text = "task: {displacement: 1, duration: 1}\nload: {inertia: 1}\ntransmission:\n" \
           "  type: direct\n"
    assert load_design(write(tmp_path, text)).transmission.stages == ()
    text = ("task: {displacement: 1, duration: 1}\nload: {inertia: 1}\ntransmission:\n"
            "  - {type: gearbox, ratio: 3, name: first}\n"
            "  - {type: gearbox, ratio: 5, inertia: 1e-4}\n")
    transmission = load_design(write(tmp_path, text)).transmission
    assert [s.ratio for s in transmission.stages] == [3, 5]
    assert transmission.stages[0].name == "first"
    assert transmission.ratio == 15
    assert transmission.inertia == pytest.approx(1e-4 / 9)


def test_single_law_and_single_catalog_as_text(tmp_path):
    text = ("task: {displacement: 1, duration: 1}\nload: {inertia: 1}\nlaws: harmonic\n"
            "motors: book-examples\n")
    design = load_design(write(tmp_path, text))
    assert design.laws == ("harmonic",)
    assert len(design.motors) == 3


def test_extra_catalogs(project, monkeypatch):
    text = "task: {displacement: 1, duration: 1}\nload: {inertia: 1}\nmotors: book-examples\n"
    path = write(project, text)
    monkeypatch.chdir(project)
    design = load_design(path, extra_catalogs=["catalogs/example-servo.yaml"])
    assert [m.id for m in design.motors] == ["ex6_1", "ex6_3", "ex6_4", "EX-100", "EX-200"]
    # the same catalog named twice is read once
    extra = ["book-examples", Path("catalogs/example-servo.yaml")]
    design = load_design(path, extra_catalogs=extra)
    assert len(design.motors) == 5


def test_check_motor_from_extra_catalog(project, monkeypatch):
    text = "task: {displacement: 1, duration: 1}\nload: {inertia: 1}\ncheck: {motor: EX-100}\n"
    monkeypatch.chdir(project)
    design = load_design(write(project, text), extra_catalogs=["catalogs/example-servo.yaml"])
    assert design.chosen_motor == "EX-100"


def test_yaml_anchors_and_merge_keys(tmp_path):
    text = ("defaults: &d {type: gearbox, efficiency: 0.9}\n"
            "task: {displacement: 1, duration: 1}\nload: {inertia: 1}\n")
    # an unknown top-level key is an error even when used only as an anchor
    error = error_of(write(tmp_path, text))
    assert (error.line, error.field) == (1, "defaults")
    text = ("task: {displacement: 1, duration: 1}\nload: {inertia: 1}\n"
            "transmission:\n  - &g {type: gearbox, ratio: 2, efficiency: 0.9}\n"
            "  - {<<: *g, ratio: 3}\n")
    stages = load_design(write(tmp_path, text)).transmission.stages
    assert [(s.ratio, s.efficiency) for s in stages] == [(2, 0.9), (3, 0.9)]


def test_schema_names_the_sections():
    schema = design_schema()
    # task or cycle: see test_cycle_input.py; load is required by the loader but for a plan
    # without a motor (test_planning.py), so not by the schema
    assert "load" not in schema.get("required", [])
    assert {"name", "task", "cycle", "load", "transmission", "laws", "motors", "drives",
            "check", "limits", "tolerances", "efficiency_applies_to"} == set(schema["properties"])
    assert "return" in schema["$defs"]["TaskInput"]["properties"]


def test_yaml_lines():
    source = parse_yaml(DESIGN, "d.yaml")
    assert source.lines[("task", "duration")] == 4
    assert source.lines[("laws", 2)] == 20
    assert source.lines[("motors", 2, "inertia")] == line_of(DESIGN, "inertia: 2 kg*cm^2")
    assert source.line_of(("motors", 2, "nothing", 3)) == line_of(DESIGN, "- id: INLINE-1")


# ------------------------------------------------------------------ errors

BAD_CASES = [
    # (old, new, needle of the expected line, field, message part)
    ("  duration: 0.25 s\n", "", "task:", "task.duration", "required field is missing"),
    ("  duration: 0.25 s\n", "  durration: 0.25 s\n", "durration", "task.durration",
     "did you mean 'duration'"),
    ("duration: 0.25 s", "duration: 3000 N*m", "duration: 3000", "task.duration",
     "expected a time"),
    ("duration: 0.25 s", "duration: -1 s", "duration: -1", "task.duration",
     "must be in [1e-6, 1e6] s"),
    ("duration: 0.25 s", "duration: .nan", "duration: .nan", "task.duration",
     "not a finite number"),
    ("duration: 0.25 s", "duration: soon", "duration: soon", "task.duration",
     "expected a time"),
    ("dwell: 0.15 s", "dwell: -0.15 s", "dwell: -0.15", "task.dwell",
     "must be 0 or in [1e-6, 1e6] s"),
    ("return: true", "return: sometimes", "return: sometimes", "task.return",
     "expected true or false"),
    ("displacement: 90 deg", "displacement: 90 N", "displacement: 90 N", "task.displacement",
     "expected an angle"),
    ("displacement: 90 deg", "displacement: 0 deg", "displacement: 0", "task.displacement",
     "must not be zero"),
    ("displacement: 90 deg", "displacement: [90 deg]", "displacement: [90", "task.displacement",
     "expected a number or a quantity"),
    ("displacement: 90 deg", "displacement: 200 mm", "inertia: 0.35", "load.inertia",
     "a linear axis (the displacement is a length) takes 'mass', not 'inertia'"),
    ("inertia: 0.35 kg*m^2", "mass: 12 kg", "mass: 12 kg", "load.mass",
     "a rotary axis (the displacement is an angle) takes 'inertia', not 'mass'"),
    ("torque: 0 N*m", "force: 50 N", "force: 50 N", "load.force",
     "a rotary axis (the displacement is an angle) takes 'torque', not 'force'"),
    ("  inertia: 0.35 kg*m^2\n", "", "load:", "load.inertia", "required field is missing"),
    ("inertia: 0.35 kg*m^2", "inertia: 0 kg*m^2", "inertia: 0 kg*m^2", "load.inertia",
     "must be in [1e-12, 1e8] kg*m^2"),
    ("inertia: 0.35 kg*m^2", "inertia: 0.35 kg", "inertia: 0.35 kg", "load.inertia",
     "expected an inertia"),
    ("damping: 0.01 N*m*s/rad", "damping: 0.01 N*s/m", "damping: 0.01 N*s/m", "load.damping",
     "expected a rotary damping"),
    ("friction: 0.2 N*m", "friction: -0.2 N*m", "friction: -0.2", "load.friction",
     "must be 0 or in [1e-9, 1e8] N*m"),
    ("torque: 0 N*m", "torque: 5 N", "torque: 5 N", "load.torque", "expected a torque"),
    ("type: gearbox", "type: chain", "type: chain", "transmission.type",
     "unknown type 'chain'; expected one of: gearbox, belt, ball_screw, rack_pinion, direct, "
     "slider_crank, four_bar"),
    ("  type: gearbox\n", "", "transmission:", "transmission.type",
     "required field is missing (one of: gearbox, belt, ball_screw, rack_pinion, direct, "
     "slider_crank, four_bar, disc_cam)"),
    ("  ratio: 10\n", "", "transmission:", "transmission.ratio", "required field is missing"),
    ("  ratio: 10\n", "  ratio: 0\n", "ratio: 0", "transmission.ratio", "must be in [0.001, 1e5]"),
    ("  ratio: 10\n", "  ratio: -10\n", "ratio: -10", "transmission.ratio",
     "must be in [0.001, 1e5]"),
    ("  ratio: 10\n", "  ratio: 10 rpm\n", "ratio: 10 rpm", "transmission.ratio",
     "expected a ratio"),
    ("efficiency: 95 %", "efficiency: 1.5", "efficiency: 1.5", "transmission.efficiency",
     "must be in [0.01, 1]"),
    ("efficiency: 95 %", "efficiency: 0", "efficiency: 0", "transmission.efficiency",
     "must be in [0.01, 1]"),
    ("efficiency: 95 %", "efficiency: 120 %", "efficiency: 120", "transmission.efficiency",
     "must be in [0.01, 1]"),
    ("  inertia: 1.2 kg*cm^2\n", "  inertia: -1.2 kg*cm^2\n", "inertia: -1.2",
     "transmission.inertia", "must be 0 or in [1e-12, 1000] kg*m^2"),
    ("  inertia: 1.2 kg*cm^2\n", "  inertia: 1.2 kg*cm^2\n  colour: red\n", "colour: red",
     "transmission.colour", "unknown field 'colour'"),
    ("  - poly5\n", "  - poly9\n", "- poly9", "laws[1]", "unknown law 'poly9'"),
    ("  - \"trapezoidal(alpha=1/3)\"\n", "  - \"trapezoidal(alpha=0.7)\"\n", "alpha=0.7",
     "laws[2]", "out of range"),
    ("  - \"trapezoidal(alpha=1/3)\"\n", "  - \"trapezoidal(alpha=auto, beta=1)\"\n",
     "beta=1", "laws[2]", "unknown parameter(s) beta"),
    ("  - \"trapezoidal(alpha=1/3)\"\n", "  - \"trapezoidal(alpha=1e400)\"\n", "1e400",
     "laws[2]", "too large"),
    ("  - \"double_s(alpha=auto, beta=auto)\"\n", "  - \"double_s(alpha=auto, beta=0.9)\"\n",
     "beta=0.9", "laws[3]", "out of range"),
    ("  - \"trapezoidal(alpha=1/3)\"\n", "  - \"trapezoidal(alpha=\"\n", "alpha=\"",
     "laws[2]", "cannot read law spec"),
    ("  - poly5\n", "  - 5\n", "- 5", "laws[1]", "expected a law spec"),
    ("laws:\n  - cycloidal\n  - poly5\n  - \"trapezoidal(alpha=1/3)\"\n"
     "  - \"double_s(alpha=auto, beta=auto)\"\n", "laws: []\n", "laws: []", "laws",
     "at least 1 item"),
    ("  law: cycloidal\n", "  law: cycloid\n", "law: cycloid", "check.law",
     "unknown law 'cycloid'"),
    ("  motor: EX-200\n", "  motor: EX-300\n", "motor: EX-300", "check.motor",
     "unknown motor 'EX-300'"),
    ("  motor: EX-200\n", "  motor: ex6_2\n", "motor: ex6_2", "check.motor",
     "did you mean 'ex6_"),
    ("  motor: EX-200\n", "  motorr: EX-200\n", "motorr:", "check.motorr",
     "unknown field 'motorr'"),
    ("  - book-examples\n", "  - book-exampels\n", "- book-exampels", "motors[1]",
     "unknown catalog 'book-exampels'"),
    ("  - book-examples\n", "  - catalogs/missing.yaml\n", "- catalogs/missing.yaml",
     "motors[1]", "catalog file not found"),
    ("  - book-examples\n", "  - 42\n", "- 42", "motors[1]",
     "expected a catalog (a file path or a bundled catalog name) or a motor mapping"),
    ("    rated_speed: 3000 rpm\ncheck:", "    rated_speed: 3000 N*m\ncheck:",
     "rated_speed: 3000 N*m", "motors[2].rated_speed", "expected an angular speed"),
    ("    peak_torque: 3.9 N*m\n", "", "- id: INLINE-1", "motors[2].peak_torque",
     "required field is missing"),
    ("    peak_torque: 3.9 N*m\n", "    peak_torque: 0.9 N*m\n", "peak_torque: 0.9 N*m",
     "motors[2].peak_torque", "below the continuous torque"),
    ("  - id: INLINE-1\n", "  - id: EX-100\n", "- id: EX-100", "motors[2].id",
     "duplicate motor id 'EX-100' (first defined at "),
    ("  - id: INLINE-1\n", "  - id: ex6_3\n", "- id: ex6_3", "motors[2].id",
     "duplicate motor id 'ex6_3'"),
    ("torque_margin: 10 %", "torque_margin: 100 %", "torque_margin: 100", "limits.torque_margin",
     "must be 0 or in [1e-9, 0.95]"),
    ("speed_margin: 5 %", "speed_margin: -5 %", "speed_margin: -5", "limits.speed_margin",
     "must be 0 or in [1e-9, 0.95]"),
    ("inertia_ratio: 10", "inertia_ratio: 0", "inertia_ratio: 0", "limits.inertia_ratio",
     "must be in [0.001, 1e6]"),
    ("max_acceleration: 500 rad/s^2", "max_acceleration: 500 m/s^2", "max_acceleration: 500",
     "limits.max_acceleration", "expected an angular acceleration"),
    ("max_acceleration: 500 rad/s^2", "max_acceleration: -500 rad/s^2",
     "max_acceleration: -500", "limits.max_acceleration", "must be in [1e-6, 1e9] rad/s^2"),
    ("max_jerk: 1e5 rad/s^3", "max_jerk: 1e5 rad/s^2", "max_jerk: 1e5",
     "limits.max_jerk", "expected an angular jerk"),
    ("thermal_speed: rms", "thermal_speed: peak", "thermal_speed: peak",
     "limits.thermal_speed", "expected 'max', 'rms' or 'mean'"),
    ("name: Indexing table", "name: Indexing table\nowner: me", "owner: me", "owner",
     "unknown field 'owner'"),
    ("name: Indexing table", "name: [1, 2]", "name: [1, 2]", "name", "expected text"),
    ("load:\n", "load: 3\nx:\n", "load: 3", "load", "expected a mapping"),
    ("  dwell: 0.15 s\n", "  dwell: 0.15 s\n  dwell: 0.2 s\n", "dwell: 0.2 s", "task.dwell",
     "duplicate key 'dwell' (first given on line 5)"),
    ("limits:\n", "limits:\nlimits:\n", "limits:", "limits", "duplicate key 'limits'"),
]


@pytest.mark.parametrize(("old", "new", "needle", "field", "message"), BAD_CASES,
                         ids=[f"{i}-{c[3]}" for i, c in enumerate(BAD_CASES)])
def test_bad_design(project, old, new, needle, field, message):
    assert old in DESIGN
    text = DESIGN.replace(old, new, 1)
    path = write(project, text)
    error = error_of(path)
    assert message in error.message
    assert error.file == str(path)
    assert error.field == field
    assert error.line == line_of(text, needle)
    assert str(error).startswith(f"{path}:{error.line}: {field}: ")


def test_linear_axis_errors(tmp_path):
    cases = [
        ("force: 50 N", "torque: 50 N*m", "load.torque", "takes 'force', not 'torque'"),
        ("mass: 12 kg", "mass: 12 kg*m^2", "load.mass", "expected a mass"),
        ("damping: 5 N*s/m", "damping: 5 N*m*s/rad", "load.damping", "expected a linear damping"),
        ("friction: 10 N", "friction: 10 N*m", "load.friction", "expected a force"),
        ("max_acceleration: 20 m/s^2", "max_acceleration: 20 rad/s^2",
         "limits.max_acceleration", "expected a linear acceleration"),
        ("max_jerk: 1000 m/s^3", "max_jerk: 1000 rad/s^3", "limits.max_jerk",
         "expected a linear jerk"),
    ]
    for old, new, field, message in cases:
        text = LINEAR.replace(old, new)
        error = error_of(write(tmp_path, text))
        assert message in error.message, (new, error)
        assert error.field == field
        assert error.line == line_of(text, new)


def test_linear_axis_without_mass(tmp_path):
    text = LINEAR.replace("  mass: 12 kg\n", "")
    error = error_of(write(tmp_path, text))
    assert (error.line, error.field) == (line_of(text, "load:"), "load.mass")
    assert "required field is missing for a linear axis" in error.message


def test_duplicate_ids_across_catalogs(project):
    second = CATALOG.replace("EX-100", "EX-900").replace("catalog: Example servo motors",
                                                          "catalog: copy")
    write(project / "catalogs", second, "copy.yaml")
    text = DESIGN.replace("  - book-examples\n", "  - catalogs/copy.yaml\n")
    error = error_of(write(project, text))
    assert error.file == str(project / "catalogs" / "copy.yaml")
    assert error.line == line_of(second, "id: EX-200")
    assert error.field == "motors[1].id"
    assert f"first defined at {project / 'catalogs' / 'example-servo.yaml'}:" \
           f"{line_of(CATALOG, 'id: EX-200')}" in error.message


def test_duplicate_ids_with_extra_catalog(project, monkeypatch):
    monkeypatch.chdir(project)
    write(project, CATALOG.replace("EX-200", "EX-900"), "other.yaml")
    error = error_of(write(project, DESIGN), extra_catalogs=["other.yaml"])
    assert error.file == "other.yaml" or error.file.endswith("other.yaml")
    assert error.line == line_of(CATALOG, "id: EX-100")
    assert "duplicate motor id 'EX-100'" in error.message


def test_error_inside_a_referenced_catalog(project):
    broken = CATALOG.replace("rated_speed: 3000 rpm", "rated_speed: 3000 N*m", 1)
    write(project / "catalogs", broken, "example-servo.yaml")
    error = error_of(write(project, DESIGN))
    assert error.file == str(project / "catalogs" / "example-servo.yaml")
    assert error.line == line_of(broken, "3000 N*m")
    assert error.field == "motors[0].rated_speed"


def test_check_motor_with_no_motors(tmp_path):
    text = "task: {displacement: 1, duration: 1}\nload: {inertia: 1}\ncheck:\n  motor: A\n"
    error = error_of(write(tmp_path, text))
    assert (error.line, error.field) == (4, "check.motor")
    assert "no motors are loaded" in error.message


def test_missing_sections(tmp_path):
    error = error_of(write(tmp_path, "name: x\nload: {inertia: 1}\n"))
    assert (error.line, error.field) == (1, "task")
    assert error.message == "required field is missing"


def test_top_level_not_a_mapping(tmp_path):
    error = error_of(write(tmp_path, "\n\n- task\n- load\n"))
    assert error.line == 3
    assert "must hold a mapping" in error.message


def test_malformed_yaml(tmp_path):
    text = DESIGN.replace("  dwell: 0.15 s\n", "  dwell: [0.15 s\n")
    error = error_of(write(tmp_path, text))
    assert error.message.startswith("invalid YAML")
    assert error.line == line_of(text, "return: true")  # where the parser notices


def test_tab_indentation(tmp_path):
    text = "task:\n\tdisplacement: 1\n"
    error = error_of(write(tmp_path, text))
    assert error.message.startswith("invalid YAML")
    assert error.line == 2


def test_missing_design_file(tmp_path):
    error = error_of(tmp_path / "nope.yaml")
    assert error.file == str(tmp_path / "nope.yaml")
    assert "not found" in error.message


def test_several_problems_reports_first_and_counts(project):
    text = DESIGN.replace("ratio: 10", "ratio: -1").replace("dwell: 0.15 s", "dwell: x")
    error = error_of(write(project, text))
    assert error.field == "task.dwell"
    assert error.message.endswith("(and 2 more problems in this file)")  # inertia_ratio too
