"""Cam tables (issue 13): reading the CSV of samples (sizer.io.cam_table)."""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np
import pytest

from sizer.errors import UserError
from sizer.io.cam_table import build_cam_table, read_cam_table
from tests.cli_run import run_cli


def _write(path: Path, text: str) -> Path:
    path.write_text(text, encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def law_csv(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The CSV that ``sizer law cycloidal`` writes: 101 samples of a 90 deg move in 0.2 s."""
    path = tmp_path_factory.mktemp("cam") / "cycloidal.csv"
    result = run_cli("law", "cycloidal", "--displacement", "90 deg", "--duration", "0.2",
                     "--format", "csv", "--output", str(path))
    assert result.returncode == 0, result.stderr
    return path


def test_round_trip_of_the_csv_that_sizer_law_prints(law_csv: Path) -> None:
    table = read_cam_table(law_csv)
    assert table.names == ("t", "q") and table.units == ("s", "rad")
    assert table.columns == (0, 1)
    # the same samples to the printed digits: the csv module reads the cells independently
    with law_csv.open(encoding="utf-8") as handle:
        rows = list(csv.reader(handle))[1:]
    assert len(table.x) == len(rows) == 101
    assert np.array_equal(table.x, [float(r[0]) for r in rows])
    assert np.array_equal(table.q, [float(r[1]) for r in rows])
    assert table.lines[0] == 2 and table.lines[-1] == 102
    # and they are the law: q = h (tau - sin(2 pi tau) / (2 pi)), tau = t / T
    tau = np.linspace(0.0, 1.0, 101)
    assert np.allclose(table.x, 0.2 * tau, rtol=0, atol=1e-15)
    h = math.pi / 2
    assert np.allclose(table.q, h * (tau - np.sin(2 * np.pi * tau) / (2 * np.pi)),
                       rtol=1e-12, atol=1e-15)


def test_columns_by_name_with_or_without_unit_or_by_index(law_csv: Path) -> None:
    by_name = read_cam_table(law_csv, columns=["t", "v"])
    by_text = read_cam_table(law_csv, columns=["t [s]", "v [rad/s]"])
    by_index = read_cam_table(law_csv, columns=[0, 2])
    for table in (by_name, by_text, by_index):
        assert table.columns == (0, 2)
        assert table.names == ("t", "v") and table.units == ("s", "rad/s")
    assert np.array_equal(by_name.q, by_index.q)


def test_build_fits_the_law_csv_back_to_the_cycloidal_coefficients(law_csv: Path) -> None:
    fit = build_cam_table({"kind": "cam_table", "file": law_csv.name, "columns": ["t", "q"]},
                          law_csv.parent)
    h, duration = math.pi / 2, 0.2
    t = np.linspace(0.0, duration, 100_001)
    assert fit.max_residual < 1e-14
    # C_v = 2 and C_a = 2 pi, scaled by h / T and h / T^2 (the printed 17 digits)
    assert np.max(np.abs(fit.curve(t, 1))) == pytest.approx(2 * h / duration, rel=1e-4)
    assert np.max(np.abs(fit.curve(t, 2))) == pytest.approx(2 * np.pi * h / duration ** 2,
                                                            rel=1e-4)


def test_headerless_table_with_angle_and_comments(tmp_path: Path) -> None:
    path = _write(tmp_path / "cam.csv", "# lift of cam 3\n0, 0\n\n90, 1.5\n180,4\n270, 1\n")
    table = read_cam_table(path)
    assert table.names == (None, None) and table.units == (None, None)
    assert table.x.tolist() == [0, 90, 180, 270] and table.q.tolist() == [0, 1.5, 4, 1]
    assert table.lines.tolist() == [2, 4, 5, 6]


def test_header_names_without_units(tmp_path: Path) -> None:
    path = _write(tmp_path / "cam.csv", "angle [deg],position [mm],note\n0,0,a\n10,1,b\n")
    table = read_cam_table(path, columns=["angle", "position"])
    assert table.names == ("angle", "position") and table.units == ("deg", "mm")
    path = _write(tmp_path / "plain.csv", "x,lift\n0,0\n1,2\n")
    assert read_cam_table(path).units == (None, None)
    assert read_cam_table(path).names == ("x", "lift")


def _error(path: Path, **kwargs: object) -> UserError:
    with pytest.raises(UserError) as caught:
        read_cam_table(path, **kwargs)
    return caught.value


def test_a_header_but_no_rows(tmp_path: Path) -> None:
    path = _write(tmp_path / "empty.csv", "t [s],q [rad]\n\n")
    error = _error(path)
    assert "empty.csv has a header but no rows" in error.message
    assert (error.file, error.line, error.field) == (str(path), 1, None)


def test_a_non_number_cell_names_row_and_column(tmp_path: Path) -> None:
    path = _write(tmp_path / "bad.csv", "t [s],q [rad]\n0,0\n0.1,0.5\n0.2,1..0\n")
    error = _error(path)
    assert "'1..0' is not a number" in error.message
    assert (error.file, error.line, error.field) == (str(path), 4, "column 1 (q [rad])")
    path = _write(tmp_path / "nan.csv", "0,0\n1,nan\n")
    error = _error(path)
    assert "not a finite number" in error.message and error.line == 2


def test_a_typo_in_the_first_row_is_not_taken_for_a_header(tmp_path: Path) -> None:
    path = _write(tmp_path / "typo.csv", "0,O.5\n1,1\n2,2\n")
    error = _error(path)
    assert "'O.5' is not a number" in error.message and error.line == 1


def test_fewer_than_two_rows(tmp_path: Path) -> None:
    error = _error(_write(tmp_path / "one.csv", "t,q\n0,0\n"))
    assert "needs at least 2 samples" in error.message and error.line == 2
    error = _error(_write(tmp_path / "none.csv", "\n# nothing\n"))
    assert "has no rows" in error.message and error.field is None


def test_missing_file_and_not_a_csv(tmp_path: Path) -> None:
    error = _error(tmp_path / "absent.csv")  # the mapping's field, located by the caller
    assert "not found" in error.message and str(tmp_path / "absent.csv") in error.message
    assert (error.file, error.field) == (None, "file")
    binary = tmp_path / "cam.xlsx"
    binary.write_bytes(b"PK\x03\x04\x00\x00\xff\xfe\x00")
    error = _error(binary)
    assert "is not a CSV file" in error.message and error.file == str(binary)


def test_missing_column_name(law_csv: Path, tmp_path: Path) -> None:
    error = _error(law_csv, columns=["angle", "q"])
    assert "no column 'angle'" in error.message and "t [s], q [rad]" in error.message
    assert (error.file, error.field) == (None, "columns[0]")  # the mapping's field
    assert "cycloidal.csv" in error.message and "(line 1)" in error.message
    error = _error(law_csv, columns=[0, 7])
    assert "out of range" in error.message and error.field == "columns[1]"
    headerless = _write(tmp_path / "h.csv", "0,0\n1,1\n")
    error = _error(headerless, columns=["t", "q"])
    assert "no header" in error.message and error.field == "columns[0]"


def test_short_row(tmp_path: Path) -> None:
    path = _write(tmp_path / "short.csv", "t,q\n0,0\n1\n2,2\n")
    error = _error(path)
    assert "row has 1 cells" in error.message and error.line == 3


def _build_error(tmp_path: Path, text: str, **fields: object) -> UserError:
    _write(tmp_path / "cam.csv", text)
    with pytest.raises(UserError) as caught:
        build_cam_table({"kind": "cam_table", "file": "cam.csv", **fields}, tmp_path)
    return caught.value


def test_build_x_not_increasing_names_the_line(tmp_path: Path) -> None:
    rows = "".join(f"{t},{t * t}\n" for t in (0, 1, 2, 3, 3, 5, 6, 7))
    error = _build_error(tmp_path, "angle [deg],lift [mm]\n" + rows)
    assert "angle must increase strictly: 3 follows 3" in error.message
    assert (error.file, error.line, error.field) == (str(tmp_path / "cam.csv"), 6,
                                                     "column 0 (angle [deg])")


def test_build_too_few_rows_for_the_order(tmp_path: Path) -> None:
    error = _build_error(tmp_path, "t,q\n0,0\n1,1\n2,4\n3,9\n", order=6)
    assert "order 6 needs at least 6 samples, got 4" in error.message
    assert (error.file, error.field) == (None, "order")  # the mapping's field
    fit = build_cam_table({"file": "cam.csv", "order": 4}, tmp_path)
    assert fit.max_residual < 1e-12


def test_build_fields(tmp_path: Path) -> None:
    error = _build_error(tmp_path, "0,0\n1,1\n", columns="t,q")
    assert error.field == "columns"
    error = _build_error(tmp_path, "0,0\n1,1\n", file_name="x")
    assert error.field == "file_name" and "no field" in error.message
    with pytest.raises(UserError) as caught:
        build_cam_table({"kind": "cam_table"}, tmp_path)
    assert caught.value.field == "file"
    with pytest.raises(UserError, match="not found") as caught:
        build_cam_table({"file": "elsewhere.csv"}, tmp_path)
    assert caught.value.field == "file" and str(tmp_path / "elsewhere.csv") in str(caught.value)
