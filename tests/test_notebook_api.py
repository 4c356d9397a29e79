"""The notebook API (issue 36): flat records with every margin, the limiting check and
the units; to_pandas() with pandas (an optional extra) or a clear ImportError without;
an HTML table for Jupyter; no absolute path of the machine in a cam table's spec."""

from __future__ import annotations

import json
import math
import shutil
import sys
from dataclasses import replace
from pathlib import Path

import pytest

import sizer
from sizer.sizing.results import RECORD_UNITS, SizingResult, flat_record

ROOT = Path(__file__).resolve().parents[1]
BOOK = ROOT / "examples/book/ex6_3.yaml"
KNIFE = ROOT / "examples/rotary-knife.yaml"


@pytest.fixture(scope="module")
def book() -> SizingResult:
    return sizer.size(BOOK)


@pytest.fixture(scope="module")
def knife() -> SizingResult:
    return sizer.size(KNIFE)


@pytest.mark.parametrize("name", ["book", "knife"])
def test_records_carry_figures_every_margin_and_the_limiting_check(name, request) -> None:
    result = request.getfixturevalue(name)
    records = result.records()
    assert len(records) == len(result.results)
    checks = result.check_names()
    for rank, (row, r) in enumerate(zip(records, result.results, strict=True), 1):
        assert row["rank"] == rank and row["motor"] == r.motor and row["law"] == r.law
        assert row["spec"] == r.spec and row["feasible"] is r.feasible
        for key in ("duration", "peak_torque", "rms_torque", "max_speed"):
            assert row[key] == getattr(r, key)
        assert {f"margin_{c}" for c in checks} <= set(row)
        assert row["limiting"] == r.limiting and isinstance(row["limiting"], str)
        if r.duration is None:
            continue
        for check in r.checks:  # margin = 1 - value/limit, computed again here
            margin = row[f"margin_{check.name}"]
            if math.isfinite(check.value) and check.limit > 0:
                assert margin == pytest.approx(1 - check.value / check.limit, abs=1e-12)
        slack = {c.name: c.margin - c.required for c in r.checks}
        assert slack[row["limiting"]] == min(slack.values())
        assert row["limiting_margin"] == row[f"margin_{row['limiting']}"]
    json.dumps(records, allow_nan=False)  # plain data: no NaN, no numpy scalars


def test_units_name_every_key_in_si(book) -> None:
    units = book.units()
    assert set(book.records()[0]) <= set(units)
    assert units["duration"] == "s" and units["peak_torque"] == "N*m"
    assert units["max_speed"] == "rad/s" and units["margin_peak"] == "1"
    assert RECORD_UNITS["rated_power"] == "W"


def test_a_record_of_one_candidate(book) -> None:
    first = book.results[0]
    assert first.record() == {k: v for k, v in flat_record(first).items()}
    assert "rank" not in first.record() and first.record()["motor"] == first.motor


def test_to_pandas_without_pandas_names_the_extra(book, monkeypatch) -> None:
    monkeypatch.setitem(sys.modules, "pandas", None)  # import pandas fails
    with pytest.raises(ImportError, match=r"pip install 'sizer-motion\[pandas\]'"):
        book.to_pandas()


def test_the_extra_is_declared() -> None:
    text = (ROOT / "pyproject.toml").read_text()
    assert '\npandas = ["pandas' in text


def test_to_pandas_with_pandas(book) -> None:
    pd = pytest.importorskip("pandas")
    frame = book.to_pandas()
    assert isinstance(frame, pd.DataFrame) and list(frame.index) == [1, 2, 3]
    assert frame.index.name == "rank"
    assert list(frame["motor"]) == [r.motor for r in book.results]
    assert frame.attrs["units"]["duration"] == "s"


def _assert_self_contained(html: str) -> None:
    lowered = html.lower()
    for external in ("http:", "https:", "src=", "<script", "<link", "url(", "@import"):
        assert external not in lowered


def test_html_table_of_a_result(book) -> None:
    html = book._repr_html_()
    assert html.count("<table") == 1 and "</table>" in html
    assert html.count("<tr>") == len(book.results) + 1  # the header and a row each
    for r in book.results:
        assert f">{r.motor}<" in html
    for header in ("peak margin [%]", "rms margin [%]", "speed margin [%]", "limiting"):
        assert header in html
    _assert_self_contained(html)


def test_html_of_a_candidate_has_a_row_per_check(book) -> None:
    first = book.results[0]
    html = first._repr_html_()
    assert html.count("<tr>") == len(first.checks) + 1
    _assert_self_contained(html)


def test_html_escapes_texts(book) -> None:
    first = book.results[0]
    odd = replace(first, motor_object=replace(first.motor_object, id="<b>&x</b>"))
    hand = SizingResult(book.mode, [odd], design_name='<script>"a"</script>')
    html = hand._repr_html_()
    assert "<b>" not in html and "&lt;b&gt;&amp;x&lt;/b&gt;" in html
    assert "<script>" not in html and "&lt;script&gt;" in html
    assert "<b>" not in odd._repr_html_()


def test_html_shows_a_bounded_number_of_rows(knife) -> None:
    from sizer.notebook import sizing_html

    html = sizing_html(knife, max_rows=2)
    assert html.count("<tr>") == 3 and f"{len(knife.results) - 2} more" in html


# --- a cam table's path as the user wrote it --------------------------------------------

def test_a_cam_table_spec_is_relative_to_the_design_folder(monkeypatch) -> None:
    monkeypatch.chdir(KNIFE.parent)
    in_folder = sizer.size(KNIFE.name)
    spec = in_folder.results[0].spec
    assert 'file: "cams/rotary-knife.csv"' in spec or "file: cams/rotary-knife.csv" in spec
    monkeypatch.chdir(ROOT)
    from_root = sizer.size("examples/rotary-knife.yaml")
    assert "examples/cams/rotary-knife.csv" in from_root.results[0].spec
    for result in (in_folder, from_root):  # no absolute path in any export
        text = json.dumps([result.to_dict(), result.records()])
        assert str(ROOT) not in text and "/work/" not in text
    # the same file read: the same figures
    assert [r.rms_torque for r in in_folder.results] == \
        [r.rms_torque for r in from_root.results]


def test_a_cam_table_in_a_copied_folder(tmp_path, monkeypatch) -> None:
    name = f"tables/{tmp_path.name}.csv"  # a text no other test gives (laws are cached)
    (tmp_path / "tables").mkdir()
    text = KNIFE.read_text().replace("file: cams/rotary-knife.csv", f"file: {name}")
    (tmp_path / "knife.yaml").write_text(text)
    shutil.copy(ROOT / "examples/cams/rotary-knife.csv", tmp_path / name)
    monkeypatch.chdir(tmp_path)
    result = sizer.size("knife.yaml")
    assert str(tmp_path) not in result.results[0].spec
    assert f"file: {name}" in result.results[0].spec.replace('"', "")


def test_the_same_relative_text_for_another_file_is_written_absolute(tmp_path,
                                                                     monkeypatch) -> None:
    """Laws are cached by spec: after a chdir, ``cams/rotary-knife.csv`` naming another
    file must not get the first file's law."""
    monkeypatch.chdir(KNIFE.parent)
    first = sizer.size(KNIFE.name)
    assert "file: cams/rotary-knife.csv" in first.results[0].spec.replace('"', "")
    (tmp_path / "cams").mkdir()
    shutil.copy(KNIFE, tmp_path / "knife.yaml")
    table = (ROOT / "examples/cams/rotary-knife.csv").read_text()
    (tmp_path / "cams/rotary-knife.csv").write_text(table)
    monkeypatch.chdir(tmp_path)
    other = sizer.size("knife.yaml")
    assert str(tmp_path / "cams/rotary-knife.csv") in other.results[0].spec
    assert [r.rms_torque for r in other.results] == [r.rms_torque for r in first.results]
