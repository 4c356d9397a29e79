"""The catalog validator: every kind of bad entry found, each at its file, line and field."""

from __future__ import annotations

from pathlib import Path

import pytest

from sizer.catalog_tools import Finding, check_motor, validate_catalogs
from sizer.io.schema.inputs import MotorInput

ROOT = Path(__file__).resolve().parents[1]

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
        ("motors[4].continuous_torque", line_of(BAD, "continuous_torque: -1 N*m"),
         "in [1e-6, 1e6] N*m"),
        ("motors[4].peak_torque", line_of(BAD, "peak_torque: 3 rpm"), "expected a torque"),
        ("motors[4].intermittent_curve[1].torque", line_of(BAD, "[3000 rpm, -1 N*m]"),
         "0 or in [1e-6, 1e6] N*m"),
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


# ------------------------------------------------------------------ plausibility

SGM7J_01A = {"inertia": "0.0659e-4 kg*m^2", "continuous_torque": "0.318 N*m",
             "peak_torque": "1.11 N*m", "rated_speed": "3000 rpm", "max_speed": "6000 rpm"}
"""A real 100 W servomotor (Yaskawa SGM7J-01A, datasheet figures)."""

IMPLAUSIBLE = [
    # (what is wrong, fields changed, the field flagged, a fragment of the message)
    ("100 W motor with 3 kg*m^2", {"inertia": "3 kg*m^2"}, "inertia", "W per kg*m^2"),
    ("kg*cm^2 written as kg*m^2", {"inertia": "0.0659 kg*m^2"}, "inertia",
     "rad/s^2"),
    ("rated speed 30 rpm", {"rated_speed": "30 rpm", "max_speed": "60 rpm"}, "rated_speed",
     "30 rpm is outside the range"),
    ("speeds in rad/s where rpm was meant", {"rated_speed": "3000 rad/s",
                                             "max_speed": "6000 rad/s"}, "rated_speed",
     "28648 rpm is outside the range"),
    ("speeds in rad/s where rpm was meant", {"rated_speed": "3000 rad/s",
                                             "max_speed": "6000 rad/s"}, "max_speed",
     "above 25000 rpm"),
    ("peak torque in N*m, continuous in mN*m", {"peak_torque": "1110 N*m"}, "peak_torque",
     "times the continuous torque"),
    ("max speed in rpm, rated in rev/s", {"max_speed": "6000 rpm", "rated_speed": "50 rpm"},
     "max_speed", "120 times the rated speed"),
]


def _catalog_of(fields: dict[str, object]) -> str:
    lines = "".join(f"    {key}: {value}\n" for key, value in fields.items())
    return f"source: s\nmotors:\n  - id: M\n{lines}"


def test_a_real_motor_is_plausible(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    write(tmp_path, _catalog_of(SGM7J_01A), "m.yaml")
    assert validate_catalogs(["m.yaml"]).findings == []


@pytest.mark.parametrize(("what", "changes", "field", "fragment"), IMPLAUSIBLE)
def test_implausible_motors_are_flagged(tmp_path, monkeypatch, what, changes, field, fragment):
    monkeypatch.chdir(tmp_path)
    text = _catalog_of({**SGM7J_01A, **changes})
    write(tmp_path, text, "m.yaml")
    report = validate_catalogs(["m.yaml"])
    hits = found(report, f"motors[0].{field}")
    assert any(fragment in f.message and f.severity == "warning" for f in hits), \
        (what, [str(f) for f in report.findings])
    assert hits[0].line == line_of(text, f"{field}:")
    assert report.exit_code == 1


def test_a_bare_number_behind_a_finding_is_named(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    write(tmp_path, _catalog_of({**SGM7J_01A, "rated_speed": 3000, "max_speed": 6000}),
          "m.yaml")
    messages = [f.message for f in validate_catalogs(["m.yaml"]).findings]
    assert any("(bare number 3000 read as 3000 rad/s)" in m for m in messages), messages


def test_idealized_motors_are_not_checked_for_plausibility():
    item = MotorInput.model_validate({"id": "x", "inertia": 3, "continuous_torque": 1,
                                      "peak_torque": 100, "rated_speed": 2})
    assert check_motor(item, manufacturer="idealized (textbook)", source="the book") == []
    assert len(check_motor(item, source="the book")) >= 3


def _bundled_figures() -> list[dict[str, float]]:
    from sizer.io import NOT_DEFAULT_CATALOGS, bundled_catalogs, load_catalog

    figures = []
    for name, path in bundled_catalogs().items():
        if name in NOT_DEFAULT_CATALOGS:  # idealized, or peaks that are stall torques
            continue
        for m in load_catalog(path):
            figures.append({
                "peak/continuous": m.peak_torque / m.continuous_torque,
                "acceleration": m.peak_torque / m.inertia,
                "power/inertia": m.continuous_torque * m.rated_speed / m.inertia,
                "max/rated": (m.max_speed or m.rated_speed) / m.rated_speed,
                "rated": m.rated_speed, "max": m.max_speed or m.rated_speed})
    return figures


def test_the_bands_are_wide_around_every_bundled_motor():
    # every bundled motor is inside each band with room to spare: at least a factor 2.4
    # (speeds) or 3 (ratios) from its edges, where the band has an edge on that side
    from sizer.io import motor_rules as p

    figures = _bundled_figures()
    assert len(figures) == 64

    def span(key: str) -> tuple[float, float]:
        return min(f[key] for f in figures), max(f[key] for f in figures)

    assert span("peak/continuous")[1] * 3 <= p.PEAK_TO_CONTINUOUS[1]
    low, high = span("acceleration")
    assert p.ACCELERATION_CAPACITY[0] * 3 <= low and high * 3 <= p.ACCELERATION_CAPACITY[1]
    low, high = span("power/inertia")
    assert p.POWER_PER_INERTIA[0] * 3 <= low and high * 3 <= p.POWER_PER_INERTIA[1]
    assert span("max/rated")[1] * 3 <= p.MAX_TO_RATED_SPEED[1]
    low, high = span("rated")
    assert p.RATED_SPEED[0] * 2.4 <= low and high * 2.4 <= p.RATED_SPEED[1]
    assert span("max")[1] * 2.4 <= p.MAX_SPEED


def test_every_bundled_catalog_validates_clean():
    from sizer.io import bundled_catalogs

    report = validate_catalogs([str(p) for p in bundled_catalogs().values()])
    # 3 of the book, 64 servomotors, 56 maxon EC motors (issue 35)
    assert report.findings == [] and report.unreadable == [] and report.motors == 123


def test_drive_catalogs_are_validated_as_drive_catalogs(tmp_path):
    """The bundled drive catalogs pass; a drive whose peak current is below its
    continuous one and a repeated drive id are findings (exit 1), with file and line."""
    drives = sorted((ROOT / "sizer" / "catalogs" / "drives").glob("*.yaml"))
    report = validate_catalogs([str(p) for p in drives])
    assert report.findings == [] and report.drives >= 3 and report.exit_code == 0
    bad = tmp_path / "drives.yaml"
    bad.write_text("drives:\n  - {id: A, continuous_current: 5 A, peak_current: 3 A}\n"
                   "  - {id: A, continuous_current: 5 A, peak_current: 10 A}\n")
    report = validate_catalogs([str(bad)])
    assert [(f.line, f.field) for f in report.findings] == [(2, "drives[0].peak_current"),
                                                            (3, "drives[1].id")]
    assert report.exit_code == 1
