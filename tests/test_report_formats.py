"""Formatting helpers of sizer.report: numbers, tables, CSV and JSON text."""

from __future__ import annotations

import csv
import io
import json
import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from sizer.report.csv_text import render_csv
from sizer.report.json_text import render_json, render_json_flat_arrays
from sizer.report.markdown_table import render_markdown_table
from sizer.report.numbers import (
    continuity_text,
    continuity_value,
    fraction_or_short,
    full,
    short,
    short_column,
)
from sizer.report.table import Column, make_table
from sizer.report.text_table import render_text_table

finite = st.floats(allow_nan=False, allow_infinity=False)


@given(finite)
def test_full_reads_back_exactly(value: float) -> None:
    assert float(full(value)) == value


def test_full_accepts_numpy_scalars() -> None:
    np = pytest.importorskip("numpy")
    assert full(np.float64(0.1)) == "0.1"


@pytest.mark.parametrize(
    ("value", "text"),
    [(2 * math.pi, "6.2832"), (1.4999999999999998, "1.5"), (0.0, "0"), (-0.0, "0"),
     (310.0627668, "310.06"), (1.2e-7, "1.2e-07"), (-4.5, "-4.5")],
)
def test_short_keeps_five_significant_digits(value: float, text: str) -> None:
    assert short(value) == text


def test_short_column_hides_rounding_noise_only() -> None:
    assert short_column([3e-15, 246.74011, -1e-13]) == ["0", "246.74", "0"]
    assert short_column([3e-15, 1e-14]) == ["3e-15", "1e-14"]  # same scale: real values
    assert short_column([]) == []


@pytest.mark.parametrize(
    ("value", "text"),
    [(0.0, "0"), (1.0, "1"), (0.5, "1/2"), (1 / 3, "1/3"), (1 - 1 / 3, "2/3"),
     (0.6666666666666667, "2/3"), (0.1339745962155614, "0.13397")],
)
def test_fraction_or_short(value: float, text: str) -> None:
    assert fraction_or_short(value) == text


def test_continuity() -> None:
    assert continuity_value(2.0) == 2 and isinstance(continuity_value(2.0), int)
    assert continuity_value(math.inf) == "inf"
    assert continuity_text(1) == "C^1" and continuity_text(math.inf) == "C^inf"
    assert continuity_text(2, unicode=True) == "C²"
    assert continuity_text(math.inf, unicode=True) == "C∞"


TABLE = make_table(
    [Column("law", "left"), Column("C_v")],
    [["cycloidal", "2"], ["poly|5", "1.875"]],
    title="t",
)


def test_text_table_is_aligned() -> None:
    assert render_text_table(TABLE) == (
        "law          C_v\n"
        "---------  -----\n"
        "cycloidal      2\n"
        "poly|5     1.875\n"
    )


def test_markdown_table_escapes_pipes() -> None:
    assert render_markdown_table(TABLE).splitlines() == [
        "| law | C_v |",
        "| :--- | ---: |",
        "| cycloidal | 2 |",
        "| poly\\|5 | 1.875 |",
    ]


def test_table_rejects_ragged_rows() -> None:
    with pytest.raises(ValueError, match="cells"):
        make_table([Column("a")], [["1", "2"]])


def test_csv_quotes_only_when_needed_and_uses_newlines() -> None:
    text = render_csv(["law", "spec"], [["double_s", "double_s(alpha=1/3, beta=1/4)"]])
    assert text == 'law,spec\ndouble_s,"double_s(alpha=1/3, beta=1/4)"\n'
    assert list(csv.reader(io.StringIO(text)))[1][1] == "double_s(alpha=1/3, beta=1/4)"


@given(st.dictionaries(st.text(max_size=5), st.lists(finite, max_size=5), max_size=4))
def test_json_flat_arrays_is_valid_json(value: dict) -> None:
    text = render_json_flat_arrays(value)
    assert json.loads(text) == value
    assert text.endswith("}\n")


def test_json_rejects_nan() -> None:
    with pytest.raises(ValueError):
        render_json([math.nan])
    assert render_json({"b": 1, "a": [0.1]}) == '{\n  "b": 1,\n  "a": [\n    0.1\n  ]\n}\n'
