"""Warnings for bare numbers far from their plausible range: located, carried, printed.

A bare number stays SI (the sizing does not change); the warning says how it was read and
what to write if another unit was meant. They travel on Design.warnings and
LoadedCatalog.warnings and the CLI prints them on stderr as 'warning: ...' lines.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from cli_run import run_cli

from sizer.catalog_tools import import_csv, parse_column_map
from sizer.io import bundled_catalogs, load_design, read_catalog
from sizer.io.machine_loader import load_machine

ROOT = Path(__file__).resolve().parent.parent

MOTOR = """\
  - id: SGM7J-01A
    inertia: {inertia}
    continuous_torque: 0.318 N*m
    peak_torque: 1.11 N*m
    rated_speed: {speed}
"""


def design_text(task: str, inertia: str = "0.0659 kg*cm^2", speed: str = "3000 rpm") -> str:
    return ("name: warned\n"
            f"task:\n{task}"
            "load:\n  inertia: 1 kg*cm^2\n"
            "laws: [cycloidal]\n"
            "motors:\n" + MOTOR.format(inertia=inertia, speed=speed)
            + "check: {motor: SGM7J-01A, law: cycloidal}\n")


def line_of(text: str, needle: str) -> int:
    return next(i for i, line in enumerate(text.splitlines(), 1) if needle in line)


def write(tmp_path: Path, text: str, name: str = "design.yaml") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


def test_a_bare_duration_of_250_s_warns_at_its_line(tmp_path: Path) -> None:
    text = design_text("  displacement: 90 deg\n  duration: 250\n")
    path = write(tmp_path, text)
    design = load_design(path)
    assert design.task.duration == 250.0  # still SI
    line = line_of(text, "duration: 250")
    assert design.warnings == (f"{path}:{line}: task.duration: bare number 250 read as 250 s; "
                               f"write '250 ms' if that was meant",)


def test_a_bare_dwell_and_a_bare_displacement_warn(tmp_path: Path) -> None:
    text = design_text("  displacement: 90\n  duration: 0.25 s\n  dwell: 350\n")
    path = write(tmp_path, text)
    warnings = load_design(path).warnings
    assert warnings == (
        f"{path}:{line_of(text, 'dwell: 350')}: task.dwell: bare number 350 read as 350 s; "
        f"write '350 ms' if that was meant",
        f"{path}:{line_of(text, 'displacement: 90')}: task.displacement: bare number 90 read "
        f"as 90 rad (14.3 turns); write '90 deg' if that was meant")


@pytest.mark.parametrize("task", [
    "  displacement: 90 deg\n  duration: 0.25\n  dwell: 0.35\n",   # plausible bare numbers
    "  displacement: 1.5\n  duration: 250 ms\n",
    "  displacement: 90 rad\n  duration: 250 s\n  dwell: 1000 s\n",  # units: as written
    "  displacement: 200 mm\n  duration: minimize\n",
])
def test_plausible_or_explicit_values_do_not_warn(tmp_path: Path, task: str) -> None:
    text = design_text(task)
    if "mm" in task:  # a linear axis
        text = text.replace("inertia: 1 kg*cm^2", "mass: 2 kg")
    assert load_design(write(tmp_path, text)).warnings == ()


@pytest.mark.parametrize(("inertia", "speed", "field", "fragment"), [
    ("3", "3000 rpm", "inertia", "bare number 3 read as 3 kg*m^2, but a rotor inertia of "
                                 "3 kg*m^2 for 99.9 W rated power"),
    ("0.0659 kg*cm^2", "3", "rated_speed", "bare number 3 read as 3 rad/s, but rated speed "
                                           "28.648 rpm is outside the range"),
    ("0.0659 kg*cm^2", "3000", "rated_speed", "bare number 3000 read as 3000 rad/s, but "
                                              "rated speed 28648 rpm is outside the range"),
])
def test_implausible_bare_motor_figures_warn(tmp_path: Path, inertia: str, speed: str,
                                             field: str, fragment: str) -> None:
    text = design_text("  displacement: 90 deg\n  duration: 0.2 s\n", inertia, speed)
    path = write(tmp_path, text)
    warnings = load_design(path).warnings
    assert len(warnings) == 1, warnings
    line = line_of(text, f"{field}: {inertia if field == 'inertia' else speed}")
    assert warnings[0].startswith(f"{path}:{line}: motors[0].{field}: {fragment}"), warnings
    assert warnings[0].endswith("write the unit if another was meant")


def test_the_same_figures_with_units_do_not_warn_at_loading(tmp_path: Path) -> None:
    # with a unit the value is what the user wrote; `sizer catalog validate` flags it
    text = design_text("  displacement: 90 deg\n  duration: 0.2 s\n", "3 kg*m^2", "30 rpm")
    assert load_design(write(tmp_path, text)).warnings == ()


def test_catalog_warnings_travel_on_the_catalog_and_the_design(tmp_path: Path) -> None:
    catalog = "source: s\nmotors:\n" + MOTOR.format(inertia="3", speed="3000 rpm")
    path = write(tmp_path, catalog, "motors.yaml")
    loaded = read_catalog(path)
    expected = (f"{path}:{line_of(catalog, 'inertia: 3')}: motors[0].inertia: bare number 3 "
                f"read as 3 kg*m^2")
    assert len(loaded.warnings) == 1 and loaded.warnings[0].startswith(expected)
    design = design_text("  displacement: 90 deg\n  duration: 0.2 s\n").split("motors:")[0]
    design += "motors: motors.yaml\n"
    assert load_design(write(tmp_path, design)).warnings == loaded.warnings


def test_idealized_motors_with_bare_numbers_do_not_warn(tmp_path: Path) -> None:
    catalog = ("manufacturer: idealized (textbook)\nsource: the book\nmotors:\n"
               "  - {id: ex, inertia: 0, continuous_torque: 8, peak_torque: 20, "
               "rated_speed: 2}\n")
    assert read_catalog(write(tmp_path, catalog, "book.yaml")).warnings == ()


def test_bundled_catalogs_and_examples_have_no_warnings() -> None:
    for path in bundled_catalogs().values():
        assert read_catalog(path).warnings == (), path
    designs = [p for p in sorted((ROOT / "examples").rglob("*.yaml"))
               if "task:" in p.read_text() and "axes:" not in p.read_text()]
    assert len(designs) >= 8
    for path in designs:
        assert load_design(path, default_motors=True).warnings == (), path
    machines = [p for p in sorted((ROOT / "examples").rglob("*.yaml"))
                if "axes:" in p.read_text()]
    assert machines
    for path in machines:
        assert load_machine(path).warnings == (), path


# ------------------------------------------------------------------ CLI


def test_the_cli_prints_warnings_on_stderr_and_keeps_its_exit_codes(tmp_path: Path) -> None:
    text = design_text("  displacement: 90 deg\n  duration: 250\n")
    path = write(tmp_path, text)
    line = line_of(text, "duration: 250")
    expected = (f"warning: {path}:{line}: task.duration: bare number 250 read as 250 s; "
                f"write '250 ms' if that was meant")
    for command in ("size", "check"):
        result = run_cli(command, str(path))
        assert result.returncode == 0, result.stderr
        assert [x for x in result.stderr.splitlines() if x.startswith("warning:")] == [expected]
        assert "warning" not in result.stdout and "Traceback" not in result.stderr


def test_the_cli_prints_nothing_without_warnings(tmp_path: Path) -> None:
    path = write(tmp_path, design_text("  displacement: 90 deg\n  duration: 0.25 s\n"))
    for command in ("size", "check"):
        result = run_cli(command, str(path))
        assert result.returncode == 0 and "warning" not in result.stderr


CSV = ("Model,J (kgcm2),T_N (Nm),T_max (Nm),n_N (rpm)\n"
       "GOOD,0.0659,0.318,1.11,3000\n"
       "HEAVY,30000,0.318,1.11,3000\n")
MAPS = ["Model=id", "J (kgcm2)=inertia:kg*cm^2", "T_N (Nm)=continuous_torque:Nm",
        "T_max (Nm)=peak_torque:Nm", "n_N (rpm)=rated_speed:rpm"]


def test_catalog_import_warns_about_implausible_rows_and_still_writes(tmp_path: Path) -> None:
    csv = write(tmp_path, CSV, "vendor.csv")
    imported = import_csv(csv, [parse_column_map(m) for m in MAPS], source="s")
    assert [m["id"] for m in imported.motors] == ["GOOD", "HEAVY"]
    assert len(imported.warnings) == 2  # acceleration capacity, power per inertia
    assert all(w.startswith(f"{csv}:3: inertia (column 'J (kgcm2)'): implausible: ")
               for w in imported.warnings)
    out = tmp_path / "out.yaml"
    args = ["catalog", "import", str(csv), "--source", "s", "-o", str(out)]
    for item in MAPS:
        args += ["--map", item]
    result = run_cli(*args)
    assert result.returncode == 0, result.stderr
    assert [x for x in result.stderr.splitlines() if x.startswith("warning:")] == \
        [f"warning: {w}" for w in imported.warnings]
    assert out.read_text() == imported.yaml()
