"""Units written the way datasheets write them: every spelling gives the same SI value.

The expected values are computed here from the exact defining factors (2*pi/60 rad/s per
rpm, 0.0254 m per inch, 0.45359237 kg per pound, 0.028349523125 kg per ounce, 9.80665 m/s^2
standard gravity), not from sizer's own units; and each spelling is read in a design file,
in a catalog, through ``sizer catalog validate`` and through ``sizer catalog import``.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from cli_run import run_cli

from sizer.catalog_tools import import_csv, parse_column_map, validate_catalogs
from sizer.errors import UserError
from sizer.io import load_catalog, load_design
from sizer.units import to_si

RPM = 2 * math.pi / 60
INCH = 0.0254
FOOT = 12 * INCH
POUND = 0.45359237
OUNCE = 0.028349523125
G_N = 9.80665
REL = 1e-14

SPEEDS = ["3000 min^-1", "3000 min⁻¹", "3000 1/min", "3000 r/min", "3000 rpm", "3000 RPM",
          "3000 U/min", "50 rps", "50 Hz", "50 rev/s", "50 r/s", "50 1/s", "50 s^-1",
          "314.1592653589793 rad/s", "18000 deg/s", "0.05 1/ms"]
"""All of them 3000 rpm."""


@pytest.mark.parametrize("text", SPEEDS)
def test_every_speed_spelling_is_3000_rpm(text: str) -> None:
    assert to_si(text, "angular_speed") == pytest.approx(3000 * RPM, rel=REL)
    assert to_si(text, "angular_speed") == pytest.approx(100 * math.pi, rel=REL)


@pytest.mark.parametrize(
    ("text", "kind", "expected"),
    [
        # a frequency where an angular quantity is expected: revolutions per unit time
        ("1 rpm/s", "angular_acceleration", RPM),
        ("1 Hz/s", "angular_acceleration", 2 * math.pi),
        ("1 1/s^2", "angular_acceleration", 2 * math.pi),
        ("1 s^-2", "angular_acceleration", 2 * math.pi),
        ("1 min^-2", "angular_acceleration", 2 * math.pi / 3600),
        ("1 rev/s^2", "angular_acceleration", 2 * math.pi),
        ("1 r/s^2", "angular_acceleration", 2 * math.pi),
        ("1 rad/s^2", "angular_acceleration", 1.0),
        ("1 deg/s^2", "angular_acceleration", math.pi / 180),
        ("1 1/s^3", "angular_jerk", 2 * math.pi),
        ("1 Hz/s^2", "angular_jerk", 2 * math.pi),
        ("1 rpm/s^2", "angular_jerk", RPM),
        ("1 rad/s^3", "angular_jerk", 1.0),
    ],
)
def test_angular_accelerations_and_jerks_follow_the_same_rule(text: str, kind: str,
                                                              expected: float) -> None:
    assert to_si(text, kind) == pytest.approx(expected, rel=REL)


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("1.5 Nm", 1.5), ("1.5 N.m", 1.5), ("1.5 N·m", 1.5), ("1.5 N⋅m", 1.5), ("1.5 N-m", 1.5),
        ("1.5 N*m", 1.5), ("1500 mNm", 1.5), ("1500 mN*m", 1.5), ("0.0015 kNm", 1.5),
        ("150 Ncm", 1.5), ("150 N*cm", 1.5), ("1500 Nmm", 1.5),
        # gravitational units of US and Japanese catalogs: the mass is a weight
        ("1 oz*in", OUNCE * G_N * INCH), ("1 oz-in", OUNCE * G_N * INCH),
        ("1 ozf*in", OUNCE * G_N * INCH), ("1 lbf*in", POUND * G_N * INCH),
        ("1 lb*in", POUND * G_N * INCH), ("1 lbf*ft", POUND * G_N * FOOT),
        ("1 lb*ft", POUND * G_N * FOOT), ("1 lb-ft", POUND * G_N * FOOT),
        ("1 kgf*cm", G_N / 100), ("1 kg*cm", G_N / 100),
    ],
)
def test_torque_spellings(text: str, expected: float) -> None:
    assert to_si(text, "torque") == pytest.approx(expected, rel=REL)


def test_imperial_factors_match_the_published_ones() -> None:
    # the published factors have 8 digits: within half a unit of the 8th

    assert to_si("1 oz*in", "torque") == pytest.approx(7.0615518e-3, rel=5e-8)
    assert to_si("1 lb*in^2", "inertia") == pytest.approx(2.9263965e-4, rel=5e-8)
    assert to_si("1 oz*in*s^2", "inertia") == pytest.approx(7.0615518e-3, rel=5e-8)


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("1 lb*in^2", POUND * INCH**2), ("1 lb*in²", POUND * INCH**2),
        ("1 oz*in^2", OUNCE * INCH**2),
        ("1 oz*in*s^2", OUNCE * G_N * INCH), ("1 ozf*in*s^2", OUNCE * G_N * INCH),
        ("1 oz-in-s^2", OUNCE * G_N * INCH),
        ("1 lbf*in*s^2", POUND * G_N * INCH), ("1 lb*in*s^2", POUND * G_N * INCH),
        ("1 lbf*ft*s^2", POUND * G_N * FOOT),
        ("1.2 kg*cm^2", 1.2e-4), ("1.2 kg·cm²", 1.2e-4), ("1.2 kgcm^2", 1.2e-4),
        ("1.2 kgm^2", 1.2), ("92.5 gcm^2", 92.5e-7), ("92.5 g*cm^2", 92.5e-7),
    ],
)
def test_inertia_spellings(text: str, expected: float) -> None:
    assert to_si(text, "inertia") == pytest.approx(expected, rel=REL)


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("0.04 kgf*m^2 GD^2", 0.01), ("0.04 kgf*m² GD²", 0.01), ("0.04 kgf*m^2 GD2", 0.01),
        ("0.04 kg*m^2 GD^2", 0.01), ("400 kgf*cm^2 GD^2", 0.01),
        ("0.392266 N*m^2 GD^2", 0.01),
    ],
)
def test_gd2_is_four_times_the_inertia(text: str, expected: float) -> None:
    # J = G D^2 / 4 with G the mass (kg) when GD^2 is in kgf*m^2; 0.392266 N*m^2 = 0.04 kgf*m^2
    assert to_si(text, "inertia") == pytest.approx(expected, rel=REL)


def test_gd2_in_kgf_m2_is_exact() -> None:
    for gd2 in (0.04, 0.1, 1.7, 3.3e-5, 12.25):
        assert to_si(f"{gd2} kgf*m^2 GD^2", "inertia") == gd2 / 4


@pytest.mark.parametrize(
    ("text", "kind"),
    [
        ("0.04 kgf*m^2 GD^2", "torque"),     # GD^2 only where an inertia is expected
        ("0.04 N*m GD^2", "inertia"),        # not a GD^2 unit
        ("1 rad^2/s", "angular_speed"),      # an angle squared
        ("1 oz*in", "inertia"),              # a torque, not an inertia
        ("1 Nm", "length"),                  # Nm is a torque only where a torque is expected
        ("1 Hz", "angular_acceleration"),
    ],
)
def test_spellings_out_of_place_are_errors(text: str, kind: str) -> None:
    with pytest.raises(UserError):
        to_si(text, kind)


def test_other_kinds_are_unchanged() -> None:
    assert to_si("200 nm", "length") == pytest.approx(2e-7, rel=REL)
    assert to_si("1.5 m/s", "linear_speed") == 1.5
    assert to_si("0.01 N*m*s/rad", "rotary_damping") == pytest.approx(0.01, rel=REL)
    assert to_si("1 Nm/rpm", "rotary_damping") == pytest.approx(1 / RPM, rel=REL)
    assert to_si(314.0, "angular_speed") == 314.0  # a bare number stays SI (rad/s)


# ------------------------------------------------------------------ in files

MOTOR_FIELDS = """\
    inertia: {inertia}
    continuous_torque: {torque}
    peak_torque: 2.23 N*m
    rated_speed: {speed}
    max_speed: 6000 r/min
"""

SPELLINGS = [
    ("3000 min^-1", "0.637 Nm", "0.263 kg·cm²"),
    ("50 Hz", "637 mNm", "0.263 kgcm^2"),
    ("3000 1/min", "63.7 Ncm", "0.0263 kgf*cm^2 GD^2"),
    ("50 rps", "90.206 oz*in", "8.9873e-2 lb*in^2"),
    ("3000 RPM", "0.637 N.m", "2.3288e-4 oz*in*s^2"),
]
"""(speed, torque, inertia) of one motor, written differently on each row."""


def _expected(speed: str, torque: str, inertia: str) -> tuple[float, float, float]:
    del speed
    torques = {"0.637 Nm": 0.637, "637 mNm": 0.637, "63.7 Ncm": 0.637,
               "90.206 oz*in": 90.206 * OUNCE * G_N * INCH, "0.637 N.m": 0.637}
    inertias = {"0.263 kg·cm²": 0.263e-4, "0.263 kgcm^2": 0.263e-4,
                "0.0263 kgf*cm^2 GD^2": 0.0263e-4 / 4, "8.9873e-2 lb*in^2": 8.9873e-2
                * POUND * INCH**2, "2.3288e-4 oz*in*s^2": 2.3288e-4 * OUNCE * G_N * INCH}
    return 3000 * RPM, torques[torque], inertias[inertia]


def _catalog(rows: list[tuple[str, str, str]]) -> str:
    text = "source: a datasheet\nmotors:\n"
    for index, (speed, torque, inertia) in enumerate(rows):
        text += f"  - id: M{index}\n" + MOTOR_FIELDS.format(speed=speed, torque=torque,
                                                            inertia=inertia)
    return text


def test_spellings_in_a_catalog_and_in_catalog_validate(tmp_path: Path) -> None:
    path = tmp_path / "motors.yaml"
    path.write_text(_catalog(SPELLINGS))
    motors = load_catalog(path)
    for motor, row in zip(motors, SPELLINGS, strict=True):
        speed, torque, inertia = _expected(*row)
        assert motor.rated_speed == pytest.approx(speed, rel=REL)
        assert motor.max_speed == pytest.approx(2 * speed, rel=REL)
        assert motor.continuous_torque == pytest.approx(torque, rel=REL)
        assert motor.inertia == pytest.approx(inertia, rel=REL)
    report = validate_catalogs([path])
    assert report.findings == [] and report.unreadable == []


def test_spellings_in_a_design_file(tmp_path: Path) -> None:
    motors = "".join(f"  - id: M{i}\n" + MOTOR_FIELDS.format(speed=s, torque=t, inertia=j)
                     for i, (s, t, j) in enumerate(SPELLINGS))
    path = tmp_path / "design.yaml"
    path.write_text("task: {displacement: 90 deg, duration: 0.2 s}\n"
                    "load: {inertia: 0.9 oz*in*s^2, torque: 2 lb*in}\n"
                    "limits: {max_acceleration: 10 Hz/s}\n"
                    f"motors:\n{motors}")
    design = load_design(path)
    assert design.load.inertia == pytest.approx(0.9 * OUNCE * G_N * INCH, rel=REL)
    assert design.load.torque == pytest.approx(2 * POUND * G_N * INCH, rel=REL)
    assert design.limits.max_acceleration == pytest.approx(20 * math.pi, rel=REL)
    for motor, row in zip(design.motors, SPELLINGS, strict=True):
        speed, torque, inertia = _expected(*row)
        assert (motor.rated_speed, motor.continuous_torque, motor.inertia) == pytest.approx(
            (speed, torque, inertia), rel=REL)


def test_spellings_through_catalog_import(tmp_path: Path) -> None:
    csv = tmp_path / "vendor.csv"
    csv.write_text("Model;n_N (min-1);n_max (Hz);T_N (Nm);T_max (oz-in);J (lb-in2)\n"
                   "A;3000;100;0.637;315.8;0.08987\n")
    maps = ["Model=id", "n_N (min-1)=rated_speed:min^-1", "n_max (Hz)=max_speed:Hz",
            "T_N (Nm)=continuous_torque:Nm", "T_max (oz-in)=peak_torque:oz-in",
            "J (lb-in2)=inertia:lb*in^2"]
    imported = import_csv(csv, [parse_column_map(m) for m in maps], source="a datasheet")
    out = tmp_path / "imported.yaml"
    out.write_text(imported.yaml())
    (motor,) = load_catalog(out)
    assert motor.rated_speed == pytest.approx(3000 * RPM, rel=REL)
    assert motor.max_speed == pytest.approx(6000 * RPM, rel=REL)
    assert motor.continuous_torque == pytest.approx(0.637, rel=REL)
    assert motor.peak_torque == pytest.approx(315.8 * OUNCE * G_N * INCH, rel=REL)
    assert motor.inertia == pytest.approx(0.08987 * POUND * INCH**2, rel=REL)
    assert validate_catalogs([out]).findings == []
    args = ["catalog", "import", str(csv), "--source", "a datasheet"]
    for item in maps:
        args += ["--map", item]
    result = run_cli(*args)  # the command line gives the same catalog
    assert result.returncode == 0 and result.stdout == imported.yaml(), result.stderr
    assert "warning" not in result.stderr
