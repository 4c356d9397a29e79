"""The catalog validator: every kind of bad entry found, each at its file, line and field."""

from __future__ import annotations

from pathlib import Path

import pytest

from sizer.catalog_tools import Finding, check_motor, validate_catalogs
from sizer.model.inputs import MotorInput

GOOD = """\
catalog: Good motors
manufacturer: ACME
source: "ACME servo catalog, https://example.com/acme.pdf"
motors:
  - id: G1
    inertia: 1.2 kg*cm^2
    continuous_torque: 1.3 N*m
    peak_torque: 3.8 N*m
    rated_speed: 3000 rpm
    max_speed: 5000 rpm
  - id: G2
    inertia: 5.43e-4 kg*m^2
    continuous_torque: 5 N*m
    peak_torque: 23 N*m
    rated_speed: 6000 rpm
    continuous_curve: [[0 rpm, 5 N*m], [6000 rpm, 2 N*m]]
"""

BAD = """\
catalog: Bad motors
manufacturer: ACME
motors:
  - id: PEAK
    inertia: 1 kg*cm^2
    continuous_torque: 2 N*m
    peak_torque: 1 N*m
    rated_speed: 3000 rpm
    max_speed: 2000 rpm
    source: s
  - id: NOSOURCE
    inertia: 0 kg*m^2
    continuous_torque: 1 N*m
    peak_torque: 3 N*m
    rated_speed: 3000 rpm
  - id: ORDER
    inertia: 1 kg*cm^2
    continuous_torque: 1 N*m
    peak_torque: 3 N*m
    rated_speed: 3000 rpm
    continuous_curve:
      - [0 rpm, 1 N*m]
      - [2000 rpm, 1 N*m]
      - [1000 rpm, 0.5 N*m]
    source: s
  - id: ABOVE
    inertia: 1 kg*cm^2
    continuous_torque: 1 N*m
    peak_torque: 3 N*m
    rated_speed: 3000 rpm
    max_speed: 3000 rpm
    continuous_curve:
      - [0 rpm, 1.5 N*m]
      - [3000 rpm, 1.2 N*m]
    intermittent_curve:
      - [0 rpm, 3 N*m]
      - [4000 rpm, 0.2 N*m]
    source: s
  - id: SCHEMA
    inertia: 1 kg*cm^2
    continuous_torque: -1 N*m
    peak_torque: 3 rpm
    rated_speed: 3000 rpm
    intermittent_curve: [[0 rpm, 3 N*m], [3000 rpm, -1 N*m]]
    colour: red
    source: s
  - id: PEAK
    inertia: 1 kg*cm^2
    continuous_torque: 1 N*m
    peak_torque: 3 N*m
    rated_speed: 3000 rpm
    source: s
"""


def write(folder: Path, text: str, name: str) -> Path:
    path = folder / name
    path.write_text(text)
    return path


def line_of(text: str, needle: str, after: str = "") -> int:
    """1-based line of the first line containing ``needle`` after the line with ``after``."""
    lines = text.splitlines()
    start = next(i for i, line in enumerate(lines) if after in line) if after else 0
    return next(i for i, line in enumerate(lines) if i >= start and needle in line) + 1


@pytest.fixture()
def bad(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    write(tmp_path, BAD, "bad.yaml")
    return validate_catalogs(["bad.yaml"])


def found(report, field: str) -> list[Finding]:
    return [f for f in report.findings if f.field == field]


def test_clean_catalog_has_no_findings(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    write(tmp_path, GOOD, "good.yaml")
    report = validate_catalogs(["good.yaml"])
    assert report.findings == [] and report.unreadable == []
    assert report.exit_code == 0 and report.files == ["good.yaml"] and report.motors == 2


def test_every_kind_of_bad_entry_is_found_at_its_line(bad):
    expected = {
        ("motors[0].peak_torque", line_of(BAD, "peak_torque: 1 N*m"), "below the continuous"),
        ("motors[0].max_speed", line_of(BAD, "max_speed: 2000 rpm"), "below the rated speed"),
        ("motors[1].source", line_of(BAD, "id: NOSOURCE"), "no source"),
        ("motors[1].inertia", line_of(BAD, "inertia: 0 kg*m^2"), "rotor inertia is 0"),
        ("motors[2].continuous_curve[2]", line_of(BAD, "[1000 rpm, 0.5 N*m]"),
         "strictly increasing"),
        ("motors[3].continuous_curve[0]", line_of(BAD, "[0 rpm, 1.5 N*m]"), "more than 10%"),
        ("motors[3].continuous_curve", line_of(BAD, "continuous_curve:", "id: ABOVE"),
         "above the intermittent region at 3000 rpm"),
        ("motors[3].intermittent_curve[1]", line_of(BAD, "[4000 rpm, 0.2 N*m]"),
         "above max_speed"),
        ("motors[4].continuous_torque", line_of(BAD, "continuous_torque: -1 N*m"), "> 0"),
        ("motors[4].peak_torque", line_of(BAD, "peak_torque: 3 rpm"), "expected a torque"),
        ("motors[4].intermittent_curve[1].torque", line_of(BAD, "[3000 rpm, -1 N*m]"),
         ">= 0"),
        ("motors[4].colour", line_of(BAD, "colour: red"), "unknown field 'colour'"),
        ("motors[5].id", line_of(BAD, "id: PEAK", "id: SCHEMA"),
         f"duplicate motor id 'PEAK' (first defined at bad.yaml:{line_of(BAD, 'id: PEAK')})"),
    }
    got = {(f.field, f.line, f.message) for f in bad.findings}
    for field, line, fragment in expected:
        assert any(g[0] == field and g[1] == line and fragment in g[2] for g in got), \
            (field, line, fragment, sorted(got, key=lambda g: g[1]))
    assert len(bad.findings) == len(expected)  # nothing reported twice
    assert all(f.file == "bad.yaml" for f in bad.findings)
    assert bad.exit_code == 1


def test_findings_print_as_file_line_field_message(bad):
    texts = [str(f) for f in bad.findings]
    line = line_of(BAD, "peak_torque: 1 N*m")
    assert (f"bad.yaml:{line}: motors[0].peak_torque: peak torque 1 N*m is below the "
            f"continuous torque 2 N*m") in texts
    warning = found(bad, "motors[3].continuous_curve[0]")[0]
    assert warning.severity == "warning" and str(warning).endswith("(warning)")
    assert [f.sort_key() for f in bad.findings] == sorted(f.sort_key() for f in bad.findings)


def test_duplicates_across_files_and_a_file_named_twice(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    write(tmp_path, GOOD, "good.yaml")
    write(tmp_path, GOOD.replace("id: G2", "id: G9"), "copy.yaml")
    report = validate_catalogs(["good.yaml", "good.yaml", str(tmp_path / "good.yaml")])
    assert report.findings == [] and report.files == ["good.yaml"]
    report = validate_catalogs(["good.yaml", "copy.yaml"])
    assert [(f.file, f.field) for f in report.findings] == [("copy.yaml", "motors[0].id")]
    assert "first defined at good.yaml:5" in report.findings[0].message


def test_unreadable_files_exit_2_and_the_others_are_still_checked(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    write(tmp_path, BAD, "bad.yaml")
    write(tmp_path, "motors: [\n", "broken.yaml")
    write(tmp_path, "- a list\n", "list.yaml")
    report = validate_catalogs(["missing.yaml", "broken.yaml", "list.yaml", "bad.yaml"])
    assert report.exit_code == 2
    assert len(report.unreadable) == 3
    assert {e.file for e in report.unreadable} == {"missing.yaml", "broken.yaml", "list.yaml"}
    assert "not found" in str(report.unreadable[0])
    assert report.unreadable[1].line is not None
    assert report.files == ["bad.yaml"] and report.findings


def test_catalog_level_problems(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    write(tmp_path, "catalog: x\nsource: s\nmotors: []\n", "empty.yaml")
    write(tmp_path, "catalog: x\nmotor: []\n", "typo.yaml")
    report = validate_catalogs(["empty.yaml", "typo.yaml"])
    messages = [(f.file, f.line, f.message) for f in report.findings]
    assert ("empty.yaml", 3, "the catalog has no motors") in messages
    assert any(f == "typo.yaml" and "unknown field 'motor'" in m for f, _, m in messages)
    assert report.exit_code == 1


def test_a_catalog_level_source_covers_its_motors_and_idealized_motors_may_weigh_nothing():
    item = MotorInput.model_validate({"id": "x", "inertia": 0, "continuous_torque": 1,
                                      "peak_torque": 2, "rated_speed": 10})
    assert [p.path for p in check_motor(item)] == [("inertia",), ("source",)]
    assert check_motor(item, manufacturer="idealized (textbook)", source="the book") == []
    assert [p.path for p in check_motor(item, source="datasheet")] == [("inertia",)]


def test_the_book_examples_validate_clean():
    report = validate_catalogs(["book-examples"])
    assert report.findings == [] and report.motors == 3
