"""IDTA 02021 "Sizing of Power Drive Trains" in and out (issue 37): hand-built examples of the
template (tests/data/idta, structure of IDTA 02021-1-0-1) read into the expected designs; the
written SizingResult validates against a schema derived from the template's structure, and
against the AAS V3.0 JSON schema when SIZER_AAS_SCHEMA names it (admin-shell-io/aas-specs,
schemas/json/aas.json)."""

from __future__ import annotations

import copy
import json
import math
import os
from pathlib import Path

import pytest

from sizer.errors import UserError
from sizer.idta import PairResult, read_motion_csv, read_submodel, sizing_result_submodel
from sizer.idta.read import read_csv_design
from tests.cli_run import assert_user_error, run_cli

DATA = Path(__file__).parent / "data" / "idta"
jsonschema = pytest.importorskip("jsonschema")


def _read(name: str, data: dict | None = None):
    data = data if data is not None else json.loads((DATA / name).read_text())
    return read_submodel(data, source=name, cam_file="cam.csv",
                         read_file=lambda p: (DATA / Path(p).name).read_text())


def _cam_rows(text: str) -> list[tuple[float, float]]:
    lines = [ln for ln in text.splitlines() if ln and not ln.startswith("#")]
    return [tuple(float(c) for c in ln.split(",")) for ln in lines[1:]]  # type: ignore[misc]


def test_the_rotary_table_example_reads_into_the_expected_design():
    result = _read("rotary-table.json")
    assert result.design == {
        "name": "Rotary indexing table",
        # the 0.4 s index, then the rest to the 1 s cycle (60/min): a dwell
        "task": {"duration": "0.4 s", "dwell": "0.6 s"},
        # LoadTorque -1.5 acts toward decreasing angles (template): it opposes the move
        "load": {"inertia": "0.5 kg*m^2", "friction": "2.0 N*m", "torque": "1.5 N*m"},
        "transmission": {"type": "gearbox", "ratio": 1, "name": "rotary table",
                         "efficiency": 0.9, "inertia": "0.0002 kg*m^2"},
        "laws": [{"kind": "cam_table", "file": "cam.csv"}],
    }
    rows = _cam_rows(result.cam_csv)
    assert result.cam_csv.splitlines()[1] == "t [s],q [rad]"
    # the 41 samples of the 0.4 s index alone (the rest is the task's dwell)
    assert len(rows) == 41
    assert rows[40] == (0.4, pytest.approx(math.pi / 2, abs=1e-12))
    notes = "\n".join(result.notes)
    for fragment in ("AngularVelocity not used", "AxialForce = 100: not used",
                     "gives no ratio", "rests (0.6 s) are the design's dwell"):
        assert fragment in notes


def test_the_spindle_example_joins_its_sections_and_maps_the_screw():
    result = _read("spindle.json")
    assert result.design["load"] == {"mass": "25.0 kg", "force": "-20.0 N",
                                     "friction_coefficient": 0.1}
    assert result.design["transmission"] == {
        "type": "ball_screw", "lead": "0.01 m", "preload_torque": "0.05 N*m",
        "efficiency": 0.9, "inertia": "3e-05 kg*m^2"}
    assert result.design["task"] == {"duration": "1.0 s", "dwell": "0 s"}
    rows = _cam_rows(result.cam_csv)
    assert result.cam_csv.splitlines()[1] == "t [s],q [mm]"
    assert len(rows) == 26 + 25  # the second section's first sample is the first's last
    assert rows[25] == (0.5, 100.0) and rows[-1] == (1.0, 0.0)
    times = [t for t, _ in rows]
    assert times == sorted(times)
    notes = "\n".join(result.notes)
    assert "Efficiency 90 read as a percentage" in notes
    assert "CounterMass = 5 kg: not used" in notes


def test_integer_typed_quantities_and_both_spellings_of_the_rotary_table():
    data = json.loads((DATA / "rotary-table.json").read_text())
    table = data["submodels"][0]["submodelElements"][2]["value"][0]
    for spelling in ("RotraryTable", "RotaryTable"):
        changed = copy.deepcopy(data)
        entity = changed["submodels"][0]["submodelElements"][2]["value"][0]
        entity["idShort"] = spelling
        entity["semanticId"]["keys"][0]["value"] = (
            f"https://admin-shell.io/idta/PowerDriveTrainSizing/{spelling}/1/0")
        entity["statements"][0]["value"] = "1"  # Efficiency as an xs:long integer
        result = _read("rotary-table.json", changed)
        assert result.design["transmission"]["efficiency"] == 1.0
    assert table["statements"][0]["valueType"] == "xs:long"  # the template's type, kept


def test_a_motion_csv_alone_reads_with_a_load_to_fill_in():
    result = read_csv_design((DATA / "index-section.csv").read_text(encoding="utf-8"),
                             source="index-section.csv", cam_file="c.csv")
    assert result.design["load"] == {"inertia": "0 kg*m^2"}
    assert result.design["task"]["duration"] == "0.4 s"
    assert any("fill in the load" in n for n in result.notes)


@pytest.mark.parametrize(("text", "fragment", "line"), [
    ("Time [s];Position [m]\n0;0\n0,1;1\n", "'0,1' is not a number (the decimal point is '.')",
     3),
    ("Time [s];Position [m]\n0;0\n0;1\n", "times must increase", 3),
    ("Time [s];Speed [m/s]\n0;0\n1;1\n", "needs one position column", 1),
    ("Time [s];Position [m]\n0;0\n1\n", "1 fields where the header has 2", 3),
])
def test_bad_motion_files_are_located_errors(text, fragment, line):
    with pytest.raises(UserError) as caught:
        read_motion_csv(text, source="m.csv")
    assert fragment in caught.value.message and caught.value.line == line


def test_a_fan_is_refused_and_a_linear_section_needs_a_mechanism():
    data = json.loads((DATA / "spindle.json").read_text())
    fan = copy.deepcopy(data)
    entity = fan["submodels"][0]["submodelElements"][2]["value"][0]
    entity["idShort"] = "Fan"
    entity["semanticId"]["keys"][0]["value"] = (
        "https://admin-shell.io/idta/PowerDriveTrainSizing/Fan/1/0")
    with pytest.raises(UserError, match=r"a Fan .* is not supported"):
        _read("spindle.json", fan)
    data["submodels"][0]["submodelElements"].pop(2)
    with pytest.raises(UserError, match="needs a TransformationMechanism"):
        _read("spindle.json", data)


@pytest.mark.parametrize("name", ["rotary-table.json", "spindle.json"])
def test_the_examples_are_aas_environments(name):
    path = os.environ.get("SIZER_AAS_SCHEMA")
    if not path:
        pytest.skip("SIZER_AAS_SCHEMA (admin-shell-io/aas-specs schemas/json/aas.json) not set")
    schema = json.loads(Path(path).read_text())
    jsonschema.Draft201909Validator({**schema, "$ref": "#/definitions/Environment"}).validate(
        json.loads((DATA / name).read_text()))


def _derived_schema() -> dict:
    return json.loads((DATA / "sizing-result.schema.json").read_text())


def _validate_aas(submodel: dict) -> None:
    path = os.environ.get("SIZER_AAS_SCHEMA")
    if not path:
        return
    schema = json.loads(Path(path).read_text())
    jsonschema.Draft201909Validator(
        {**schema, "$ref": "#/definitions/Submodel"}).validate(submodel)


def test_the_sizing_result_maps_the_margins_and_validates():
    pair = PairResult(motor="M1", manufacturer="ACME", feasible=True, peak_torque=2.0,
                      rms_torque=1.0, max_speed=100 * math.pi, margin_peak=0.25,
                      margin_rms=0.5, margin_speed=0.75, limiting="peak",
                      law="cycloidal", ratio=5.0, gearbox="G5", notes=("a note",))
    submodel = sizing_result_submodel(pair, submodel_id="urn:x:1", project="p", tool="t",
                                      created="2026-12-06T16:00:00Z")
    jsonschema.Draft202012Validator(_derived_schema()).validate(submodel)
    _validate_aas(submodel)
    result = submodel["submodelElements"][1]
    motor = {e["idShort"]: e.get("value") for e in result["value"][0]["statements"]}
    assert motor["MaxTorqueUtilizationPercentage"] == "75.0"
    assert motor["MaxThermalUtilizationPercentage"] == "50.0"
    assert motor["MaxRotationSpeedUtilizationPercentage"] == "25.0"
    assert float(motor["MaxRotationSpeedUtilization"]) == pytest.approx(3000.0, rel=1e-15)
    gearbox = {e["idShort"]: e.get("value") for e in result["value"][1]["statements"]}
    assert gearbox["MainComponentType"] == "Gearbox"
    messages = result["value"][2]["value"]
    texts = [m["value"][1]["value"][0]["text"] for m in messages]
    assert texts[0].startswith("feasible; limiting check: peak (margin 25.0 %)")
    assert texts[1] == "a note"


def test_a_wrong_value_type_fails_the_derived_schema():
    pair = PairResult(motor="M1", manufacturer=None, feasible=False, peak_torque=2.0,
                      rms_torque=1.0, max_speed=1.0, margin_peak=-0.1, margin_rms=0.5,
                      margin_speed=0.75, limiting="peak", law="cycloidal", reason="peak")
    submodel = sizing_result_submodel(pair, submodel_id="urn:x:1", project="p", tool="t",
                                      created="2026-12-06T16:00:00Z")
    statement = submodel["submodelElements"][1]["value"][0]["statements"][5]
    statement["valueType"] = "xs:long"
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.Draft202012Validator(_derived_schema()).validate(submodel)


def test_read_size_and_write_end_to_end(tmp_path):
    design = tmp_path / "axis.yaml"
    read = run_cli("idta", "read", str(DATA / "rotary-table.json"), "-o", str(design),
                   "--motors", "teco-jsma-p")
    assert read.returncode == 0, read.stderr
    assert (tmp_path / "axis-motion.csv").is_file()
    assert "note: TransformationMechanism.RotraryTable" in read.stderr
    sized = run_cli("size", str(design), "--format", "json")
    assert sized.returncode == 0, sized.stderr
    top = next(r for r in json.loads(sized.stdout)["results"] if r["feasible"])
    # the peak torque at the cycloid's peak acceleration 2 pi h / T^2 (power to the load)
    a = 2 * math.pi * (math.pi / 2) / 0.4**2
    motor_inertia = next(m for m in __import__("sizer").load(str(design)).motors
                         if m.id == top["motor"]).inertia
    expected = (motor_inertia + 0.0002) * a + (0.5 * a + 2.0 + 1.5) / 0.9
    assert top["peak_torque"] == pytest.approx(expected, rel=2e-3)
    out = tmp_path / "result.json"
    written = run_cli("idta", "write", str(design), "-o", str(out))
    assert written.returncode == 0, written.stderr
    submodel = json.loads(out.read_text())
    jsonschema.Draft202012Validator(_derived_schema()).validate(submodel)
    _validate_aas(submodel)
    motor = {e["idShort"]: e.get("value")
             for e in submodel["submodelElements"][1]["value"][0]["statements"]}
    assert motor["ManufacturerArticleNumber"] == top["motor"]
    assert float(motor["MaxTorqueUtilizationPercentage"]) == pytest.approx(
        100 * (1 - top["margin_peak"]), rel=1e-12)
    assert float(motor["RmsOfMotorTorque"]) == pytest.approx(top["rms_torque"], rel=1e-12)
    texts = [m["value"][1]["value"][0]["text"]
             for m in submodel["submodelElements"][1]["value"][1]["value"]]
    assert any("gives no ratio" in t for t in texts)  # the read notes carried on


def test_cli_errors_exit_2(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"submodels": []}')
    assert_user_error(run_cli("idta", "read", str(bad), "-o", str(tmp_path / "d.yaml")),
                      "bad.json", "no IDTA 02021")
    assert_user_error(run_cli("idta", "read", str(bad), "-o", str(bad)), "bad.json")


def test_the_written_result_is_the_same_bytes_for_the_same_input(tmp_path, monkeypatch):
    """No clock in the output: the dates are the design file's (or SOURCE_DATE_EPOCH)."""
    from cli_run import run_cli

    design = tmp_path / "axis.yaml"
    root = Path(__file__).resolve().parents[1]
    design.write_text((root / "examples" / "indexing-table.yaml").read_text(encoding="utf-8")
                      .replace("motors: catalogs/", f"motors: {root}/examples/catalogs/"))
    outputs = []
    for name in ("a.json", "b.json"):
        assert run_cli("idta", "write", str(design), "-o", str(tmp_path / name)).returncode \
            in (0, 1)
        outputs.append((tmp_path / name).read_bytes())
    assert outputs[0] == outputs[1]
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "0")
    run_cli("idta", "write", str(design), "-o", str(tmp_path / "c.json"))
    assert "1970-01-01T00:00:00Z" in (tmp_path / "c.json").read_text()
