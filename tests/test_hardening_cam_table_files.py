"""A cam table's file (issue 32): read by the bounded reader, one CSV dialect reader for
cam tables and catalog imports, and every message at the place of the mistake."""

from __future__ import annotations

import os
import resource
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from sizer.errors import UserError
from sizer.input_limits import MAX_CAM_TABLE_BYTES, MIB
from sizer.io.cam_table import build_cam_table, read_cam_table
from sizer.io.csv_rows import csv_records, sniff_delimiter
from tests.cli_run import assert_user_error, run_cli

ROOT = Path(__file__).resolve().parents[1]
T = [i / 10 for i in range(11)]
Q = [10 * t**3 - 15 * t**4 + 6 * t**5 for t in T]
"""The poly5 rise at 11 points: the default quintic spline fits it exactly."""


def _table(separator: str, decimal_comma: bool, header: str | None = "t [s],q [mm]") -> str:
    def cell(value: float) -> str:
        text = repr(value)
        return text.replace(".", ",") if decimal_comma else text

    lines = ["# a poly5 rise, written by a spreadsheet (q, in mm, is 1000 x q_N)"]
    if header is not None:
        lines.append(header.replace(",", separator))
    lines += [f"{cell(t)}{separator}{cell(1000.0 * q)}" for t, q in zip(T, Q, strict=True)]
    return "\n".join(lines) + "\n"


# --------------------------------------------------------------- the bounded reader

def test_dev_zero_as_a_cam_table_is_refused_at_once() -> None:
    """In a process of at most 1 GiB: the old reader read /dev/zero until memory ran out."""
    def limit() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (1 << 30, 1 << 30))

    code = ("import sys; from sizer.cli.app import main; "
            "main(['law', '{kind: cam_table, file: /dev/zero}', '--displacement', '1', "
            "'--duration', '1'])")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            timeout=120, preexec_fn=limit, cwd=ROOT)
    assert result.returncode == 2, result.stderr[-2000:]
    assert result.stderr.startswith("error: /dev/zero: "), result.stderr
    assert "is a character device" in result.stderr and len(result.stderr.splitlines()) == 1


def test_an_over_limit_cam_table_is_refused_by_its_size_naming_the_limit(
        tmp_path: Path) -> None:
    big = tmp_path / "big.csv"
    with big.open("wb") as handle:  # sparse: its size is known without reading it
        handle.truncate(MAX_CAM_TABLE_BYTES + 1)
    line = assert_user_error(run_cli("law", f"{{kind: cam_table, file: {big}}}",
                                     "--displacement", "1", "--duration", "1"),
                             str(big), "too big", f"{MAX_CAM_TABLE_BYTES / MIB:.1f} MiB")
    assert "the limit is" in line


def test_a_fifo_cam_table_is_refused_without_blocking(tmp_path: Path) -> None:
    fifo = tmp_path / "cam.csv"
    os.mkfifo(fifo)
    assert_user_error(run_cli("law", f"{{kind: cam_table, file: {fifo}}}",
                              "--displacement", "1", "--duration", "1"),
                      str(fifo), "named pipe")


# ------------------------------------------------------------ one CSV dialect reader

@pytest.mark.parametrize(("separator", "decimal_comma"),
                         [(";", True), (";", False), ("\t", True), ("\t", False),
                          ("|", True)])
@pytest.mark.parametrize("header", ["t [s],q [mm]", None])
def test_semicolons_tabs_and_decimal_commas_give_the_comma_table(
        tmp_path: Path, separator: str, decimal_comma: bool, header: str | None) -> None:
    (tmp_path / "comma.csv").write_text(_table(",", False, header))
    (tmp_path / "other.csv").write_text(_table(separator, decimal_comma, header))
    comma = read_cam_table(tmp_path / "comma.csv")
    other = read_cam_table(tmp_path / "other.csv")
    assert other.x.tolist() == T and other.q.tolist() == [1000.0 * q for q in Q]
    assert (other.names, other.units, other.lines.tolist()) == (
        comma.names, comma.units, comma.lines.tolist())
    fits = [build_cam_table({"file": name}, tmp_path).curve for name in ("comma.csv",
                                                                         "other.csv")]
    tau = np.linspace(0.0, 1.0, 101)
    for order in range(4):
        assert np.array_equal(fits[0](tau, order), fits[1](tau, order))
    # and the fit is the poly5 rise: v(0.5) = 30 t^2 - 60 t^3 + 30 t^4 = 1.875 (x 1000 mm/s)
    assert fits[1](np.array([0.5]), 1)[0] == pytest.approx(1875.0, rel=1e-9)


def test_the_cli_law_of_a_semicolon_table_is_that_of_the_comma_table(tmp_path: Path) -> None:
    (tmp_path / "comma.csv").write_text(_table(",", False))
    (tmp_path / "semi.csv").write_text(_table(";", True))
    outputs = [run_cli("law", f"{{kind: cam_table, file: {tmp_path / name}}}", "-n", "5",
                       "-f", "csv") for name in ("comma.csv", "semi.csv")]
    assert outputs[0].returncode == 0, outputs[0].stderr
    assert outputs[1].stdout == outputs[0].stdout
    assert outputs[0].stdout.splitlines()[0].startswith("t [s],q [m]")


def test_sniffing_prefers_the_separator_that_splits_every_line_evenly() -> None:
    assert sniff_delimiter(["0,5;1,25", "1,5;2,25"]) == ";"  # commas are decimal commas
    assert sniff_delimiter(["a;b,c", "1,2"]) == ","  # the ';' is in one line only
    assert sniff_delimiter(["Model\tJ\tT", "A\t0,5\t1,2"]) == "\t"
    assert sniff_delimiter(['id,notes', '1,"x; y"']) == ","
    assert sniff_delimiter(["only"]) == ","
    assert sniff_delimiter([]) == ","


def test_records_keep_the_line_where_they_start() -> None:
    text = '# c, o; m\nt;q\n\n1;"two\nlines"\n3;4\n'
    records = list(csv_records(text, "x.csv", ";", comment="#"))
    assert records == [(1, []), (2, ["t", "q"]), (3, []), (4, ["1", "two\nlines"]),
                       (6, ["3", "4"])]
    with pytest.raises(UserError) as caught:
        list(csv_records('a,"b\n', "x.csv", ","))
    assert caught.value.file == "x.csv" and "invalid CSV" in caught.value.message


def test_a_thousands_separator_in_a_decimal_comma_table_is_not_a_number(
        tmp_path: Path) -> None:
    path = tmp_path / "cam.csv"
    path.write_text("t;q\n0;0\n0,5;1.234,5\n1;2000\n")
    with pytest.raises(UserError) as caught:
        read_cam_table(path)
    assert (caught.value.file, caught.value.line, caught.value.field) == (
        str(path), 3, "column 1 (q)")


def test_catalog_import_reads_semicolons_with_the_same_reader(tmp_path: Path) -> None:
    csv = tmp_path / "vendor.csv"
    csv.write_text("Model;J (kgcm2);Tc;Tp;n\nM1;0,5;1,3;3,8;3000\n")
    out = tmp_path / "motors.yaml"
    result = run_cli("catalog", "import", str(csv), "--map", "Model=id",
                     "--map", "J (kgcm2)=inertia:kg*cm^2", "--map", "Tc=continuous_torque:N*m",
                     "--map", "Tp=peak_torque:N*m", "--map", "n=rated_speed:rpm",
                     "--source", "test", "--decimal-comma", "-o", str(out))
    assert result.returncode == 0, result.stderr
    text = out.read_text()
    assert "inertia: 0.5 kg*cm^2" in text and "peak_torque: 3.8 N*m" in text


# -------------------------------------------------------- messages at the right place

DESIGN = """name: located
task: {{displacement: 90 deg, duration: 0.25 s, dwell: 0.35 s}}
load: {{inertia: 0.034 kg*m^2}}
transmission: {{type: gearbox, ratio: 10}}
motors: [mitsubishi-hg-kn]
laws:
  - cycloidal
  - kind: cam_table
    file: cam.csv
    {field}
"""
"""A design whose cam table mapping starts at line 8 (laws[1]); its extra field at line 10."""


def _design(tmp_path: Path, field: str, table: str | None = None) -> Path:
    (tmp_path / "cam.csv").write_text(table if table is not None else _table(",", False,
                                                                             "t,q"))
    path = tmp_path / "design.yaml"
    path.write_text(DESIGN.format(field=field))
    return path


@pytest.mark.parametrize(("field", "where", "words"), [
    ("order: 99", "laws[1].order", "between 2 and 10"),
    ("smoothing: banana", "laws[1].smoothing", "number"),
    ("periodic: maybe", "laws[1].periodic", "true or false"),
    ("columns: [0, 5]", "laws[1].columns[1]", "cam.csv has 2 columns"),
    ("columns: [t, z]", "laws[1].columns[1]", "no column 'z' in cam.csv"),
])
def test_a_design_field_of_a_cam_table_is_blamed_at_its_line(
        tmp_path: Path, field: str, where: str, words: str) -> None:
    design = _design(tmp_path, field)
    line = assert_user_error(run_cli("size", str(design)), words)
    assert line.startswith(f"error: {design}:10: {where}: "), line
    assert "cam.csv:" not in line


def test_a_missing_cam_table_file_is_blamed_at_the_file_field(tmp_path: Path) -> None:
    design = _design(tmp_path, "order: 6")
    (tmp_path / "cam.csv").unlink()
    line = assert_user_error(run_cli("size", str(design)), "not found",
                             str(tmp_path / "cam.csv"))
    assert line.startswith(f"error: {design}:9: laws[1].file: "), line


def test_a_design_field_on_the_command_line_names_no_file(tmp_path: Path) -> None:
    (tmp_path / "cam.csv").write_text(_table(",", False))
    line = assert_user_error(run_cli("laws", "--law", f"{{kind: cam_table, file: "
                                     f"{tmp_path / 'cam.csv'}, order: 99}}"),
                             "order", "between 2 and 10")
    assert str(tmp_path) not in line


@pytest.mark.parametrize(("table", "line", "field", "words"), [
    ("t,q\n0,0\n0.5,x\n1,1\n", 3, "column 1 (q)", "'x' is not a number"),
    ("t;q\n0;0\n0,5;0,5\n0,5;0,75\n1;1\n", 4, "column 0 (t)", "must increase strictly"),
    ("t [parsecs],q [mm]\n0,0\n0.5,0.5\n1,1\n", 1, "column 0 (t [parsecs])", "parsecs"),
    ("# units\nt [s],q [kg]\n0,0\n0.5,0.5\n1,1\n", 2, "column 1 (q [kg])", "length"),
])
def test_a_mistake_in_the_csv_is_blamed_at_its_line_and_column(
        tmp_path: Path, table: str, line: int, field: str, words: str) -> None:
    design = _design(tmp_path, "interpolation: cubic_spline", table)
    csv = tmp_path / "cam.csv"
    for args in (["size", str(design)],
                 ["law", f"{{kind: cam_table, file: {csv}, interpolation: cubic_spline}}",
                  "--displacement", "1",
                  "--duration", "1"]):
        shown = assert_user_error(run_cli(*args), words)
        assert shown.startswith(f"error: {csv}:{line}: {field}: "), shown


def test_rows_past_the_limit_are_refused_while_read_at_their_line(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr("sizer.io.cam_table.MAX_CAM_TABLE_ROWS", 5)
    path = tmp_path / "cam.csv"
    path.write_text(_table(",", False))  # a comment, a header, then rows from line 3
    with pytest.raises(UserError) as caught:
        read_cam_table(path)
    assert (caught.value.file, caught.value.line) == (str(path), 8)
    assert "the limit is 5" in caught.value.message
