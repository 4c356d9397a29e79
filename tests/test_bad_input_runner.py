"""The bad-input case runner itself: it passes a clean answer and catches a dirty one."""

from __future__ import annotations

import subprocess

import pytest
import yaml
from bad_input_cases import Case, assert_clean_answer, edited, run_case


def test_a_missing_design_file_is_a_clean_user_error(tmp_path):
    run_case(Case("missing", args=("size", "{tmp}/nowhere.yaml"), words=("nowhere.yaml",)),
             tmp_path)


def test_edited_sets_and_deletes_keys():
    data = yaml.safe_load(edited("book/ex6_3.yaml", set={"task.displacement": "1 rad",
                                                         "laws[1]": "poly5"},
                                 delete=["check"]))
    assert data["task"]["displacement"] == "1 rad"
    assert data["laws"] == ["harmonic", "poly5"]
    assert "check" not in data


@pytest.mark.parametrize("stdout, stderr, code", [
    ("T = nan s\n", "", 0),
    ("peak inf N*m\n", "", 0),
    ("", "Traceback (most recent call last):\n", 2),
    ("", "RuntimeWarning: overflow\nerror: x\n", 2),
    ("", "error: one\nerror: two\n", 2),
    ("partial table\n", "error: x\n", 2),
])
def test_a_dirty_answer_is_caught(stdout, stderr, code):
    result = subprocess.CompletedProcess((), code, stdout, stderr)
    with pytest.raises(AssertionError):
        assert_clean_answer(result, code)


def test_words_like_infeasible_are_not_non_finite_numbers():
    result = subprocess.CompletedProcess((), 0, "infeasible; info; Inflection\n", "")
    assert_clean_answer(result, 0)
