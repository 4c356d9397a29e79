"""Provenance of catalog figures (issue 35): ``sources:``, ``default_source:`` and a row's
``figure_sources:`` in motor, drive and gearbox catalogs; both motor load paths give the
same provenance; mistakes are one located error (exit code 2 from the CLI)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from sizer.errors import UserError
from sizer.io import loader
from sizer.io.catalog_table import read_table
from sizer.io.loader import load_catalog, read_drive_catalog
from sizer.io.schema.inputs import CatalogFile
from sizer.io.schema.transmission_inputs import GearboxCatalogFile
from sizer.model.domain import Provenance, figure_provenance

DATASHEET = "ACME, Servo catalog 2024, sec. 3, p. 12, https://acme.example/cat.pdf"
COMPUTED = "computed: k_e = k_t / sqrt(3)"


def catalog(**extra: object) -> dict:
    """Two motors, the first naming the source of its back-EMF constant."""
    data: dict = {
        "catalog": "test", "manufacturer": "ACME",
        "sources": {"ds": {"grade": "A", "text": DATASHEET},
                    "calc": {"grade": "C", "text": COMPUTED}},
        "default_source": "ds",
        "motors": [
            {"id": "M1", "inertia": "1 kg*cm^2", "continuous_torque": "1 N*m",
             "peak_torque": "3 N*m", "rated_speed": "3000 rpm",
             "torque_constant": "0.5 N*m/A", "back_emf_constant": "0.2886751 V*s/rad",
             "phase_resistance": "2 ohm",
             "figure_sources": {"back_emf_constant": "calc", "phase_resistance": "calc"}},
            {"id": "M2", "inertia": "2 kg*cm^2", "continuous_torque": "2 N*m",
             "peak_torque": "6 N*m", "rated_speed": "3000 rpm"},
        ],
    }
    data.update(extra)
    return data


def write(tmp_path: Path, data: dict, name: str = "motors.yaml") -> Path:
    path = tmp_path / name
    path.write_text(yaml.safe_dump(data, sort_keys=False), encoding="utf-8")
    return path


def error_of(path: Path) -> UserError:
    with pytest.raises(UserError) as caught:
        load_catalog(path)
    return caught.value


def test_a_graded_catalog_carries_each_figures_source(tmp_path: Path) -> None:
    first, second = load_catalog(write(tmp_path, catalog()))
    sheet, computed = Provenance("A", DATASHEET), Provenance("C", COMPUTED)
    shown = figure_provenance(first)
    assert shown["back_emf_constant"] == computed
    assert shown["winding_resistance"] == computed  # phase_resistance, read line to line
    assert shown["torque_constant"] == shown["inertia"] == sheet
    assert set(figure_provenance(second).values()) == {sheet}
    assert first.source == DATASHEET  # no `source:`: the default source's citation


def test_the_provenance_objects_are_shared_and_not_compared(tmp_path: Path) -> None:
    data = catalog()
    data["motors"][0].pop("figure_sources")
    first, second = load_catalog(write(tmp_path, data))
    assert first.provenance is second.provenance  # one object for the file's rows
    from dataclasses import replace
    assert replace(first, provenance=None) == first and hash(first) == hash(
        replace(first, provenance=None))


def test_a_file_without_sources_is_ungraded(tmp_path: Path) -> None:
    data = catalog(source="ACME catalog")
    for key in ("sources", "default_source"):
        data.pop(key)
    data["motors"][0].pop("figure_sources")
    motor = load_catalog(write(tmp_path, data))[0]
    assert motor.source == "ACME catalog" and motor.provenance is None
    assert set(figure_provenance(motor).values()) == {None}


@pytest.mark.parametrize("own_sources", [False, True])
def test_both_load_paths_give_the_same_motors(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                              own_sources: bool) -> None:
    """With and without a row's own figure_sources, the columns read the file, to the
    motors and provenance of the field-by-field validation."""
    data = catalog()
    if not own_sources:
        data["motors"][0].pop("figure_sources")
    path = write(tmp_path, data)
    assert read_table(yaml.safe_load(path.read_text())) is not None  # the columns read it
    fast = load_catalog(path)
    monkeypatch.setattr(loader, "read_table", lambda data: None)
    validated = load_catalog(path)
    assert fast == validated
    assert [figure_provenance(m) for m in fast] == [figure_provenance(m) for m in validated]
    assert [m.source for m in fast] == [m.source for m in validated]


@pytest.mark.parametrize(("edit", "field", "words"), [
    (lambda d: d["motors"][0]["figure_sources"].update(back_emf_constant="calx"),
     "motors[0].figure_sources.back_emf_constant", "unknown source 'calx' (did you mean"),
    (lambda d: d["sources"]["calc"].update(grade="E"), "sources.calc.grade", "'A', 'B'"),
    (lambda d: d["sources"]["calc"].update(page=3), "sources.calc.page", "unknown field"),
    (lambda d: d.update(default_source="dz"), "default_source", "unknown source 'dz'"),
    (lambda d: d["motors"][0]["figure_sources"].update(foo="calc"),
     "motors[0].figure_sources.foo", "'foo' is not a figure"),
    (lambda d: d["motors"][0]["figure_sources"].update(notes="calc"),
     "motors[0].figure_sources.notes", "is not a figure"),
    (lambda d: d["motors"][0]["figure_sources"].update(winding_inductance="calc"),
     "motors[0].figure_sources.winding_inductance", "is not given in this row"),
    (lambda d: [d.pop("sources"), d.pop("default_source")],
     "motors[0].figure_sources.back_emf_constant", "the file has no `sources:`"),
])
def test_a_provenance_mistake_is_located(tmp_path: Path, edit, field: str,
                                         words: str) -> None:
    data = catalog()
    edit(data)
    error = error_of(write(tmp_path, data))
    assert error.field == field and words in error.message and error.line is not None


def test_the_cli_exits_2_without_a_traceback(tmp_path: Path) -> None:
    data = catalog()
    data["motors"][0]["figure_sources"]["back_emf_constant"] = "nope"
    path = write(tmp_path, data)
    result = subprocess.run([sys.executable, "-m", "sizer", "catalog", "show", "M1", "-c",
                             str(path)], capture_output=True, text=True, check=False)
    assert result.returncode == 2 and "Traceback" not in result.stderr
    assert "motors[0].figure_sources.back_emf_constant: unknown source 'nope'" in result.stderr


def test_drive_catalogs_carry_provenance(tmp_path: Path) -> None:
    data = {"sources": {"m": {"grade": "B", "text": "ACME drive manual (mirror), p. 4"},
                        "list": {"grade": "A", "text": "ACME price list 2025, p. 2"}},
            "default_source": "m",
            "drives": [{"id": "D1", "continuous_current": "2 A", "peak_current": "6 A",
                        "price": 300, "figure_sources": {"price": "list"}}]}
    drive = read_drive_catalog(write(tmp_path, data, "drives.yaml"))[0].drive
    assert figure_provenance(drive) == {
        "continuous_current": Provenance("B", "ACME drive manual (mirror), p. 4"),
        "peak_current": Provenance("B", "ACME drive manual (mirror), p. 4"),
        "price": Provenance("A", "ACME price list 2025, p. 2")}
    data["drives"][0]["figure_sources"] = {"mass": "list"}
    with pytest.raises(UserError, match="'mass' is not a figure"):
        read_drive_catalog(write(tmp_path, data, "drives.yaml"))


def test_gearbox_catalogs_take_sources() -> None:
    data = {"sources": {"gb": {"grade": "A", "text": "ACME gearboxes, p. 7"}},
            "default_source": "gb",
            "gearboxes": [{"id": "G1", "efficiency": 0.95,
                           "figure_sources": {"efficiency": "gb"},
                           "ratios": [{"ratio": 5, "inertia": "0.1 kg*cm^2",
                                       "figure_sources": {"inertia": "gb"}}]}]}
    assert GearboxCatalogFile.model_validate(data).default_source == "gb"
    data["gearboxes"][0]["ratios"][0]["figure_sources"] = {"inertia": "gz"}
    with pytest.raises(ValueError, match="unknown source 'gz'"):
        GearboxCatalogFile.model_validate(data)


def test_the_schema_document_has_the_provenance_fields() -> None:
    schema = CatalogFile.model_json_schema()
    assert {"sources", "default_source"} <= set(schema["properties"])
    assert "figure_sources" in schema["$defs"]["MotorInput"]["properties"]


# ------------------------------------------------------------------ reports


def _sizer(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "sizer", *args], capture_output=True,
                          text=True, check=False, cwd=cwd)


def test_catalog_show_prints_each_figures_grade_and_the_sources(tmp_path: Path) -> None:
    write(tmp_path, catalog())
    result = _sizer("catalog", "show", "M1", "-c", "motors.yaml", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    rows = {line.split()[0]: line.split() for line in result.stdout.splitlines() if line}
    assert rows["inertia"][-1] == "A1" and rows["back_emf_constant"][-1] == "C2"
    assert rows["phase_resistance"][-1] == "C2"
    assert f"grade A: {DATASHEET}" in result.stdout and f"grade C: {COMPUTED}" in result.stdout
    assert "A 5, C 2" in result.stdout
    data = json.loads(_sizer("catalog", "show", "M1", "-c", "motors.yaml", "-f", "json",
                             cwd=tmp_path).stdout)["figure_sources"]
    assert data["sources"] == [{"number": 1, "grade": "A", "text": DATASHEET},
                               {"number": 2, "grade": "C", "text": COMPUTED}]
    assert data["figures"]["back_emf_constant"] == {"grade": "C", "source": 2}
    assert data["figures"]["winding_resistance"] == {"grade": "C", "source": 2}
    assert data["figures"]["inertia"] == {"grade": "A", "source": 1}
    listed = json.loads(_sizer("catalog", "list", "motors.yaml", "-f", "json",
                               cwd=tmp_path).stdout)
    assert [m["grades"] for m in listed["motors"]] == ["A 5, C 2", "A 4"]


DESIGN = {
    "name": "graded", "task": {"displacement": "90 deg", "duration": "0.5 s", "dwell": "0.5 s"},
    "load": {"inertia": "0.001 kg*m^2"}, "laws": ["cycloidal"], "motors": "motors.yaml",
    "check": {"motor": "M2", "law": "cycloidal"},
}


def test_the_sizing_and_check_json_carry_the_motors_grades(tmp_path: Path) -> None:
    write(tmp_path, catalog())
    write(tmp_path, DESIGN, "design.yaml")
    sized = _sizer("size", "design.yaml", "-f", "json", "--all", cwd=tmp_path)
    assert sized.returncode == 0, sized.stderr
    provenance = json.loads(sized.stdout)["design"]["figure_sources"]
    assert set(provenance["motors"]) == {"M1", "M2"}
    m1 = provenance["motors"]["M1"]
    number = m1["figures"]["back_emf_constant"]["source"]
    assert provenance["sources"][number - 1] == {"number": number, "grade": "C",
                                                 "text": COMPUTED}
    assert m1["grades"] == "A 5, C 2" and m1["source"] == DATASHEET
    checked = json.loads(_sizer("check", "design.yaml", "-f", "json", cwd=tmp_path).stdout)
    assert list(checked["design"]["figure_sources"]["motors"]) == ["M2"]


def test_the_design_reports_sources_and_grade_counts(tmp_path: Path) -> None:
    from sizer.report.figure_grades import cited_sources, grade_counts

    first, second = load_catalog(write(tmp_path, catalog()))
    assert grade_counts(first) == "A 5, C 2" and grade_counts(second) == "A 4"
    assert cited_sources(first) == [f"grade A: {DATASHEET}", f"grade C: {COMPUTED}"]
    ungraded = catalog(source="ACME catalog")
    for key in ("sources", "default_source"):
        ungraded.pop(key)
    ungraded["motors"][0].pop("figure_sources")
    plain = load_catalog(write(tmp_path, ungraded, "plain.yaml"))[0]
    assert grade_counts(plain) == "ungraded" and cited_sources(plain) == ["ACME catalog"]


def test_a_gearbox_ratio_takes_its_rows_sources_over_its_series() -> None:
    from sizer.io.schema.provenance import file_sources, gearbox_sources

    data = {"sources": {"gb": {"grade": "A", "text": "p. 7"}, "c": {"grade": "C", "text": "x"}},
            "default_source": "gb",
            "gearboxes": [{"id": "G1", "efficiency": 0.95, "backlash": "3 arcmin",
                           "figure_sources": {"efficiency": "c", "backlash": "c"},
                           "ratios": [{"ratio": 5, "efficiency": 0.9,
                                       "figure_sources": {"efficiency": "gb"}}]}]}
    model = GearboxCatalogFile.model_validate(data)
    shared, common = file_sources(model.sources, model.default_source)
    series = model.gearboxes[0]
    sources = gearbox_sources(series, series.ratios[0], shared, common)
    assert sources is not None
    assert sources.of("efficiency") == sources.of("ratio") == Provenance("A", "p. 7")
    assert sources.of("backlash") == Provenance("C", "x")
