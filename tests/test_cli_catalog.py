"""``sizer catalog list|show|validate|import``: output, files, exit codes.

The commands run in this process on a small app with only ``catalog`` registered, through
the same error handling as ``sizer.cli.app.main`` (a UserError is one 'error:' line and
exit code 2). Once ``catalog_command`` is in ``sizer.cli.app.COMMAND_MODULES``, one test
also runs the real ``main``.
"""

from __future__ import annotations

import csv
import io
import json
import subprocess
import sys
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

import pytest
import typer
import yaml

from sizer.cli import catalog_command
from sizer.errors import UserError


def _app() -> typer.Typer:
    app = typer.Typer(add_completion=False)

    @app.callback()
    def _root() -> None:
        """sizer"""

    catalog_command.register(app)
    return app


APP = _app()


def run(*args: str) -> subprocess.CompletedProcess[str]:
    """``sizer catalog ARGS`` in this process: exit code, stdout and stderr."""
    stdout, stderr = io.StringIO(), io.StringIO()
    code = 0
    with redirect_stdout(stdout), redirect_stderr(stderr):
        try:
            APP(args=["catalog", *args])
        except SystemExit as exit_:
            code = exit_.code if isinstance(exit_.code, int) else int(exit_.code is not None)
        except UserError as error:  # what sizer.cli.app.main does
            sys.stderr.write(f"error: {error}\n")
            code = 2
    return subprocess.CompletedProcess(args, code, stdout.getvalue(), stderr.getvalue())


def ok(*args: str) -> str:
    result = run(*args)
    assert result.returncode == 0, result.stderr
    return result.stdout


# ------------------------------------------------------------------ list


def test_list_bundled_catalogs():
    text = ok("list")
    lines = text.splitlines()
    assert lines[0].split()[:4] == ["catalog", "motors", "manufacturers", "default"]
    row = next(line for line in lines if line.startswith("yaskawa-sgm7j "))
    assert row.split()[1:4] == ["7", "Yaskawa", "yes"]
    assert "yaskawa-sgm7j.yaml" in row
    data = json.loads(ok("list", "--format", "json"))
    by_name = {c["catalog"]: c for c in data}
    assert by_name["book-examples"]["default"] is False
    assert sum(c["motors"] for c in data if c["default"]) >= 40


def test_list_the_motors_of_one_catalog():
    text = ok("list", "yaskawa-sgm7j")
    assert "cont. torque [N*m]" in text and "inertia [kg*cm^2]" in text
    row = next(line for line in text.splitlines() if line.startswith("SGM7J-02A "))
    assert row.split() == ["SGM7J-02A", "Yaskawa", "0.637", "2.23", "3000", "6000", "0.263",
                           "no"]
    rows = list(csv.DictReader(io.StringIO(ok("list", "mitsubishi-hc", "-f", "csv"))))
    assert rows[0]["id"] == "HC52" and rows[0]["curves"] == "true"
    assert float(rows[0]["rated_speed [rad/s]"]) == pytest.approx(2000 * 3.141592653589793 / 30)
    md = ok("list", "siemens-1ft7", "--format", "md")
    assert md.startswith("| id |") and "| 1FT7044-AK7 | Siemens |" in md


def test_list_an_unknown_catalog_is_a_user_error():
    result = run("list", "yaskawa-sgm7")
    assert result.returncode == 2
    assert "unknown catalog 'yaskawa-sgm7'" in result.stderr and "did you mean" in result.stderr


# ------------------------------------------------------------------ show


def test_show_one_motor_with_its_regions_and_source():
    text = ok("show", "1FT7044-AK7")
    assert "5.43e-4 kg*m^2" in text and "5.43 kg*cm^2" in text
    assert "continuous region [1]" in text and "6000 rpm, 2 N*m" in text
    assert "intermittent region [0]" in text and "0 rpm, 23 N*m" in text
    assert "https://www.easymanua.ls/siemens/1ft7" in text and "grade B" in text
    data = json.loads(ok("show", "HC52", "--format", "json"))
    assert data["given"]["continuous_curve"] == [["0 rpm", "2.94 N*m"],
                                                 ["2000 rpm", "2.39 N*m"]]
    assert data["continuous_region"][1] == pytest.approx([2000 * 3.141592653589793 / 30, 2.39])
    assert data["units"]["regions"] == "[rad/s, N*m]" and data["catalog"] == "mitsubishi-hc"


def test_show_from_a_given_catalog_and_an_unknown_id(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "mine.yaml").write_text(
        "source: s\nmotors:\n  - {id: M1, inertia: 1 kg*cm^2, continuous_torque: 1 N*m, "
        "peak_torque: 2 N*m, rated_speed: 3000 rpm}\n")
    assert "M1" in ok("show", "M1", "--catalog", "mine.yaml", "-f", "csv")
    result = run("show", "SGM7J-2A")
    assert result.returncode == 2 and "did you mean 'SGM7J-C2A'" in result.stderr


# ------------------------------------------------------------------ validate


def test_validate_the_bundled_catalogs_exits_0():
    result = run("validate")
    assert result.returncode == 0, result.stdout
    assert result.stdout == ""
    assert "no findings" in result.stderr


def test_validate_lists_every_finding_and_exits_1(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "bad.yaml").write_text(
        "motors:\n"
        "  - {id: A, inertia: 0, continuous_torque: 2, peak_torque: 1, rated_speed: 10}\n"
        "  - {id: A, inertia: 1e-4, continuous_torque: 1, peak_torque: 2, rated_speed: 10, "
        "source: s}\n")
    result = run("validate", "bad.yaml")
    assert result.returncode == 1
    assert result.stdout.splitlines() == [
        "bad.yaml:2: motors[0].inertia: the rotor inertia is 0: a real motor needs its "
        "datasheet inertia (only idealized textbook motors, manufacturer 'idealized ...', "
        "may have 0)",
        "bad.yaml:2: motors[0].peak_torque: peak torque 1 N*m is below the continuous torque "
        "2 N*m",
        "bad.yaml:2: motors[0].source: no source: give the datasheet's title and web address "
        "(on the motor, or 'source:' at the catalog level)",
        "bad.yaml:3: motors[1].id: duplicate motor id 'A' (first defined at bad.yaml:2)",
    ]
    assert "4 findings" in result.stderr
    assert run("validate", "bad.yaml", "--quiet").stderr == ""


def test_validate_an_unreadable_file_exits_2(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "broken.yaml").write_text("motors: [\n")
    result = run("validate", "broken.yaml", "siemens-1ft7")
    assert result.returncode == 2
    assert result.stderr.startswith("error: broken.yaml:")
    assert "2 file(s)" not in result.stderr and "1 file(s) not readable" in result.stderr


# ------------------------------------------------------------------ import

CSV = """\
Model,Rated torque (Nm),Peak torque (Nm),J (kgcm2),n_N
HG-KN13J,0.32,0.95,0.0783,3000
HG-KN23J,0.64,1.9,0.225,3000
"""

MAP_ARGS = ["--map", "Model=id", "--map", "Rated torque (Nm)=continuous_torque:N*m",
            "--map", "Peak torque (Nm)=peak_torque:N*m", "--map", "J (kgcm2)=inertia:kg*cm^2",
            "--map", "n_N=rated_speed:rpm"]


def test_import_writes_a_valid_catalog_atomically(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "kn.csv").write_text(CSV)
    (tmp_path / "kn.yaml").write_text("old content\n")
    result = run("import", "kn.csv", *MAP_ARGS, "--manufacturer", "Mitsubishi Electric",
                 "--source", "MR-JE specifications, https://example.com", "--catalog-name",
                 "HG-KN", "-o", "kn.yaml")
    assert result.returncode == 0, result.stderr
    assert "2 motor(s) written to kn.yaml" in result.stderr
    text = (tmp_path / "kn.yaml").read_text()
    data = yaml.safe_load(text)
    assert data["catalog"] == "HG-KN" and data["manufacturer"] == "Mitsubishi Electric"
    assert data["motors"][0]["inertia"] == "0.0783 kg*cm^2"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["kn.csv", "kn.yaml"]  # no temp
    assert run("validate", "kn.yaml").returncode == 0
    assert ok("import", "kn.csv", *MAP_ARGS, "--manufacturer", "Mitsubishi Electric",
              "--source", "MR-JE specifications, https://example.com", "--catalog-name",
              "HG-KN") == text  # stdout, and the same text again


def test_import_with_bad_rows_lists_them_all_and_writes_nothing(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "bad.csv").write_text(CSV + "X,1,0.5,0.1,3000\nY,a,2,0.1,3000\n")
    result = run("import", "bad.csv", *MAP_ARGS, "--source", "s", "-o", "out.yaml")
    assert result.returncode == 2
    errors = result.stderr.splitlines()
    assert len(errors) == 2
    assert errors[0] == ("error: bad.csv:4: peak_torque (column 'Peak torque (Nm)'): peak "
                         "torque 0.5 N*m is below the continuous torque 1 N*m")
    assert errors[1].startswith("error: bad.csv:5: continuous_torque (column 'Rated torque")
    assert not (tmp_path / "out.yaml").exists()


def test_import_option_errors(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "kn.csv").write_text(CSV)
    result = run("import", "kn.csv", *MAP_ARGS)
    assert result.returncode == 2 and "error: --source: no source" in result.stderr
    result = run("import", "kn.csv", *MAP_ARGS, "--source", "s", "--delimiter", ";;")
    assert result.returncode == 2 and "--delimiter" in result.stderr
    result = run("import", "kn.csv", "--map", "Model=id:rpm", "--source", "s")
    assert result.returncode == 2 and "id takes no unit" in result.stderr
    result = run("import", "missing.csv", *MAP_ARGS, "--source", "s")
    assert result.returncode == 2 and "missing.csv: file not found" in result.stderr


# ------------------------------------------------------------------ the real app


def test_registered_in_the_real_app():
    from sizer.cli import app as app_module

    if catalog_command not in getattr(app_module, "COMMAND_MODULES", ()):
        pytest.skip("catalog_command is not registered in sizer.cli.app yet")
    stdout, stderr = io.StringIO(), io.StringIO()
    with redirect_stdout(stdout), redirect_stderr(stderr), pytest.raises(SystemExit) as exit_:
        app_module.main(["catalog", "validate", "siemens-1ft7"])
    assert exit_.value.code == 0
    with redirect_stdout(stdout), redirect_stderr(stderr), pytest.raises(SystemExit) as exit_:
        app_module.main(["catalog", "show", "NOPE"])
    assert exit_.value.code == 2 and "error: ID: no motor 'NOPE'" in stderr.getvalue()


def test_help_lists_the_four_commands():
    text = ok("--help")
    for name in ("list", "show", "validate", "import"):
        assert name in text
    assert Path(catalog_command.__file__).name == "catalog_command.py"
