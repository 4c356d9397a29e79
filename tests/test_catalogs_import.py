"""CSV import: a vendor spreadsheet -> catalog YAML -> loaded motors, every figure kept."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st

from sizer.catalog_tools import (
    CatalogImportError,
    ColumnMap,
    import_csv,
    parse_column_map,
    validate_catalogs,
)
from sizer.catalog_tools.catalog_yaml import scalar
from sizer.errors import UserError
from sizer.io import load_catalog

HEADER = ("Model,Rated torque (Nm),Peak torque (Nm),J (kgcm2),n_N (1/min),n_max (1/min),"
          "Weight (kg),B (mNm/krpm),Part no.,Remarks\n")

VENDOR_CSV = HEADER + """\
SGM7J-01A,0.318,1.11,0.0659,3000,6000,,,SGM7J-01AFC61,
SGM7J-02A,0.637,2.23,0.263,3000,6000,0.9,,SGM7J-02AFC61,"batteryless, 24 bit"
SGM7J-04A,1.27,4.46,0.486,3000,6000,1.2,0.5,SGM7J-04AFC61,
"""

MAPS = [
    "Model=id",
    "Rated torque (Nm)=continuous_torque:N*m",
    "Peak torque (Nm)=peak_torque:N*m",
    "J (kgcm2)=inertia:kg*cm^2",
    "n_N (1/min)=rated_speed:rpm",
    "n_max (1/min)=max_speed:rpm",
    "Weight (kg)=mass:kg",
    "B (mNm/krpm)=damping:mN*m/krpm",
    "Part no.=part_number",
    "Remarks=notes",
]

SOURCE = "Yaskawa Sigma-7 rotary servomotor manual, https://example.com/manual.pdf"

RPM = 2 * math.pi / 60
"""rad/s per rpm, written out here so the test does not use sizer's own units."""


def write(folder: Path, text: str, name: str = "vendor.csv") -> Path:
    path = folder / name
    path.write_text(text, encoding="utf-8")
    return path


def imported(tmp_path: Path, text: str = VENDOR_CSV, maps=MAPS, **options):
    options.setdefault("source", SOURCE)
    return import_csv(write(tmp_path, text), [parse_column_map(m) for m in maps], **options)


def problems_of(tmp_path: Path, text: str, maps=MAPS, **options) -> list[UserError]:
    with pytest.raises(CatalogImportError) as info:
        imported(tmp_path, text, maps, **options)
    return info.value.problems


# ------------------------------------------------------------------ round trip


def test_round_trip_keeps_every_figure(tmp_path):
    catalog = imported(tmp_path, manufacturer="Yaskawa", catalog_name="Sigma-7 test")
    out = tmp_path / "sgm7j.yaml"
    out.write_text(catalog.yaml(), encoding="utf-8")
    motors = {m.id: m for m in load_catalog(out)}
    assert list(motors) == ["SGM7J-01A", "SGM7J-02A", "SGM7J-04A"]
    rows = [line.split(",") for line in VENDOR_CSV.splitlines()[1:]]
    for row in rows:
        motor = motors[row[0]]
        assert motor.continuous_torque == pytest.approx(float(row[1]), rel=1e-12)
        assert motor.peak_torque == pytest.approx(float(row[2]), rel=1e-12)
        assert motor.inertia == pytest.approx(float(row[3]) * 1e-4, rel=1e-12)
        assert motor.rated_speed == pytest.approx(float(row[4]) * RPM, rel=1e-12)
        assert motor.max_speed == pytest.approx(float(row[5]) * RPM, rel=1e-12)
        if row[6]:
            assert motor.mass == pytest.approx(float(row[6]), rel=1e-12)
        else:
            assert motor.mass is None
        assert motor.part_number == row[8]
        assert motor.manufacturer == "Yaskawa" and motor.source == SOURCE
    # 0.5 mN*m per 1000 rpm = 5e-4 N*m / (1000 * 2 pi / 60 rad/s)
    assert motors["SGM7J-04A"].damping == pytest.approx(5e-4 / (1000 * RPM), rel=1e-12)
    assert motors["SGM7J-01A"].damping == 0.0


def test_the_yaml_keeps_the_spreadsheet_figures_with_their_units(tmp_path):
    data = yaml.safe_load(imported(tmp_path).yaml())
    first, second, _ = data["motors"]
    assert first == {"id": "SGM7J-01A", "part_number": "SGM7J-01AFC61",
                     "inertia": "0.0659 kg*cm^2", "continuous_torque": "0.318 N*m",
                     "peak_torque": "1.11 N*m", "rated_speed": "3000 rpm",
                     "max_speed": "6000 rpm"}  # empty cells stay absent
    assert second["mass"] == "0.9 kg" and second["notes"] == "batteryless, 24 bit"
    assert data["catalog"] == "vendor" and data["source"] == SOURCE
    assert "manufacturer" not in data


def test_output_is_deterministic_and_names_its_column_map(tmp_path):
    text = imported(tmp_path).yaml()
    assert imported(tmp_path).yaml() == text
    assert text.startswith("# Motor catalog imported by 'sizer catalog import' from vendor.csv")
    assert "#   'J (kgcm2)' -> inertia [kg*cm^2]\n" in text
    assert str(tmp_path) not in text  # no absolute paths, no dates


def test_the_imported_catalog_validates_clean(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "out.yaml").write_text(imported(tmp_path).yaml(), encoding="utf-8")
    report = validate_catalogs(["out.yaml"])
    assert report.findings == [] and report.exit_code == 0


def test_semicolons_decimal_commas_bom_and_quoted_cells(tmp_path):
    text = ("\ufeffModel;M0 [Nm];Mmax [Nm];J [kgcm²];n [1/min];Remarks\n"
            "AM8011;0,20;0,72;0,0294;8000;\"a; b\"\n")
    maps = ["Model=id", "M0 [Nm]=continuous_torque:N*m", "Mmax [Nm]=peak_torque:N*m",
            "J [kgcm²]=inertia:kg*cm^2", "n [1/min]=rated_speed:rpm", "Remarks=notes"]
    catalog = imported(tmp_path, text, maps, decimal_comma=True)
    (motor,) = catalog.motors
    assert motor["continuous_torque"] == "0.20 N*m" and motor["inertia"] == "0.0294 kg*cm^2"
    assert motor["notes"] == "a; b"
    problems = problems_of(tmp_path, text, maps)  # without --decimal-comma
    assert "give --decimal-comma" in problems[0].message


def test_a_column_without_unit_is_copied_as_written(tmp_path):
    text = "id,tau_c,tau_p,J,n\nX1,0.5 N*m,1.5 N*m,2e-5,3000 rpm\n"
    maps = ["id=id", "tau_c=continuous_torque", "tau_p=peak_torque", "J=inertia",
            "n=rated_speed"]
    (motor,) = imported(tmp_path, text, maps).motors
    assert motor["continuous_torque"] == "0.5 N*m" and motor["inertia"] == "2e-5"


@settings(max_examples=60, deadline=None)
@given(st.text(alphabet=st.characters(blacklist_categories=("Cs", "Cc")), max_size=30))
def test_scalars_load_back_as_the_same_text(text):
    assert yaml.safe_load(f"key: {scalar(text)}\n")["key"] == text


@pytest.mark.parametrize("text", ["007", "yes", "1e3", "#x", "- a", "a: b", "null", "0x10",
                                  "'q'", "line\nbreak", " lead", "tab\there"])
def test_awkward_texts_survive_the_yaml(tmp_path, text):
    catalog_text = imported(tmp_path, VENDOR_CSV.replace("batteryless, 24 bit",
                                                         text.replace("\n", " "))).yaml()
    assert yaml.safe_load(f"k: {scalar(text)}\n")["k"] == text
    assert yaml.safe_load(catalog_text)["motors"][1]["notes"] == text.replace("\n", " ").strip()


# ------------------------------------------------------------------ the column maps


def test_parse_column_map():
    assert parse_column_map("J (kgcm2)=inertia:kg*cm^2") == ColumnMap("J (kgcm2)", "inertia",
                                                                     "kg*cm^2")
    assert parse_column_map("a=b=id") == ColumnMap("a=b", "id", None)
    assert parse_column_map("T: rated=continuous_torque:N*m").column == "T: rated"
    for bad, fragment in (("nothing", "COLUMN=FIELD"), ("=id", "COLUMN=FIELD"),
                          ("x=torque", "unknown field 'torque'"),
                          ("x=continuous_torque:rpm", "not a unit of torque"),
                          ("x=id:mm", "takes no unit"), ("x=price:EUR", "takes no unit")):
        with pytest.raises(UserError) as info:
            parse_column_map(bad)
        assert fragment in info.value.message and info.value.field == "--map"


@pytest.mark.parametrize("maps, source, fragment", [
    (MAPS[1:], SOURCE, "required field(s) id"),
    ([*MAPS, "Part no.=notes"], SOURCE, "mapped twice"),
    (MAPS, None, "no source"),
    ([*MAPS[:-1], "Comments=notes"], SOURCE, "no column 'Comments'"),
])
def test_bad_maps_are_user_errors(tmp_path, maps, source, fragment):
    with pytest.raises(UserError) as info:
        import_csv(write(tmp_path, VENDOR_CSV), [parse_column_map(m) for m in maps],
                   source=source)
    assert not isinstance(info.value, CatalogImportError)
    assert fragment in info.value.message


# ------------------------------------------------------------------ bad rows


def test_every_bad_row_is_reported_at_its_line(tmp_path):
    lines = VENDOR_CSV.splitlines()
    text = "\n".join([
        lines[0],
        "A1,0.318,0.2,0.0659,3000,6000,,,,",  # 2: peak below continuous
        "A2,x,1.11,0.0659,3000,6000,,,,",  # 3: not a number
        "A3,0.318,,0.0659,3000,6000,,,,",  # 4: peak missing
        "",  # 5: blank, skipped
        "A4,0.318,1.11,0,3000,2000,,,,",  # 6: no inertia, max below rated
        "A1,0.318,1.11,0.0659,3000,6000,,,,",  # 7: duplicate id
        "A6,0.318,1.11,0.0659,3000,6000,-1,,,",  # 8: negative mass
    ]) + "\n"
    problems = problems_of(tmp_path, text)
    where = [(p.line, p.field.split()[0]) for p in problems]
    assert where == [(2, "peak_torque"), (3, "continuous_torque"), (4, "peak_torque"),
                     (6, "max_speed"), (6, "inertia"), (7, "id"), (8, "mass")]
    assert all(p.file == str(tmp_path / "vendor.csv") for p in problems)
    text_of = {(p.line, p.field.split()[0]): str(p) for p in problems}
    assert text_of[(3, "continuous_torque")] == (
        f"{tmp_path / 'vendor.csv'}:3: continuous_torque (column 'Rated torque (Nm)'): "
        f"expected a number (the unit N*m comes from --map), got 'x'")
    assert "required field is missing" in text_of[(4, "peak_torque")]
    assert "duplicate motor id 'A1' (first on line 2)" in text_of[(7, "id")]


def test_unreadable_csv_files(tmp_path):
    maps = [parse_column_map(m) for m in MAPS]
    cases = {
        "missing.csv": None,
        "empty.csv": b"\n\n",
        "latin.csv": VENDOR_CSV.replace("Remarks", "Bemerkung \xe4").encode("latin-1"),
        "header-only.csv": VENDOR_CSV.splitlines()[0].encode() + b"\n",
    }
    for name, content in cases.items():
        path = tmp_path / name
        if content is not None:
            path.write_bytes(content)
        with pytest.raises(UserError) as info:
            import_csv(path, maps, source=SOURCE)
        assert info.value.file == str(path), name
    latin = tmp_path / "latin.csv"
    maps_latin = [parse_column_map(m.replace("Remarks", "Bemerkung \xe4")) for m in MAPS]
    catalog = import_csv(latin, maps_latin, source=SOURCE, encoding="latin-1")
    assert len(catalog.motors) == 3
