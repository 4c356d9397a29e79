"""``sizer idta write ... -o FILE.aasx`` (issue 37): the SizingResult submodel in an AASX package
made by basyx-python-sdk (the ``aas`` extra). The package read back with basyx's own AASX reader
holds the JSON output's submodel, element by element and value by value (the JSON side parsed
here, by the XSD types it names, not by basyx); the same input gives the same bytes, whatever
the clock. Skipped where basyx is not installed (``pip install 'sizer-motion[aas]'``)."""

from __future__ import annotations

import io
import json
import math
import sys
import time
import zipfile
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import pytest

from sizer.idta import PairResult, sizing_result_submodel
from tests.cli_run import assert_user_error, run_cli

DATA = Path(__file__).parent / "data" / "idta"


def _json_value(element: dict[str, Any]) -> Any:
    """The value of a JSON Property by its valueType, parsed here (not by basyx)."""
    value, kind = element["value"], element["valueType"]
    if kind == "xs:double":
        return float(value)
    if kind == "xs:dateTime":
        return datetime.fromisoformat(value.replace("Z", "+00:00"))
    assert kind == "xs:string", kind
    return value


def _json_leaves(elements: list[dict[str, Any]], path: str = "") -> dict[str, tuple]:
    """path -> (modelType, semanticId, valueType, value) of every leaf of the JSON."""
    leaves: dict[str, tuple] = {}
    for element in elements:
        where = f"{path}/{element['idShort']}"
        semantic = element["semanticId"]["keys"][0]["value"]
        kind = element["modelType"]
        if kind == "Property":
            leaves[where] = (kind, semantic, element["valueType"], _json_value(element))
        elif kind == "MultiLanguageProperty":
            leaves[where] = (kind, semantic, None,
                             {s["language"]: s["text"] for s in element["value"]})
        else:
            leaves[where] = (kind, semantic, None, None)
            children = element["statements"] if kind == "Entity" else element["value"]
            leaves.update(_json_leaves(children, where))
    return leaves


def _basyx_leaves(elements, path: str = "") -> dict[str, tuple]:
    """The same mapping of the submodel basyx read from the package."""
    from basyx.aas import model

    names = {model.Property: "Property", model.MultiLanguageProperty: "MultiLanguageProperty",
             model.Entity: "Entity",
             model.SubmodelElementCollection: "SubmodelElementCollection"}
    leaves: dict[str, tuple] = {}
    for element in elements:
        where = f"{path}/{element.id_short}"
        kind = names[type(element)]
        semantic = element.semantic_id.key[0].value
        if kind == "Property":
            leaves[where] = (kind, semantic, model.datatypes.XSD_TYPE_NAMES[element.value_type],
                             element.value)
        elif kind == "MultiLanguageProperty":
            leaves[where] = (kind, semantic, None, dict(element.value))
        else:
            leaves[where] = (kind, semantic, None, None)
            children = element.statement if kind == "Entity" else element.value
            leaves.update(_basyx_leaves(children, where))
    return leaves


def _read_package(path: Path):
    from basyx.aas import model
    from basyx.aas.adapter import aasx

    objects: model.DictIdentifiableStore = model.DictIdentifiableStore()
    files = aasx.DictSupplementaryFileContainer()
    with aasx.AASXReader(str(path), failsafe=False) as reader:
        identifiers = reader.read_into(objects, files)
        created = reader.get_core_properties().created
    return objects, identifiers, created


@pytest.fixture(scope="module")
def design(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("idta") / "axis.yaml"
    read = run_cli("idta", "read", str(DATA / "rotary-table.json"), "-o", str(path),
                   "--motors", "teco-jsma-p")
    assert read.returncode == 0, read.stderr
    return path


@pytest.fixture(scope="module")
def outputs(design: Path) -> dict[str, Path]:
    """The design written as JSON and as AASX (dated 2026-12-06T16:00:00Z)."""
    pytest.importorskip("basyx.aas.adapter.aasx")
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("SOURCE_DATE_EPOCH", "1796572800")
        written = {}
        for name in ("result.json", "result.aasx"):
            path = design.with_name(name)
            result = run_cli("idta", "write", str(design), "-o", str(path))
            assert result.returncode == 0, result.stderr
            written[name] = path
    return written


def test_the_aasx_holds_the_json_submodel_value_by_value(outputs):
    submodel = json.loads(outputs["result.json"].read_text(encoding="utf-8"))
    objects, identifiers, created = _read_package(outputs["result.aasx"])
    assert identifiers == {submodel["id"]} == {o.id for o in objects}
    read = objects.get_item(submodel["id"])
    assert read.id_short == submodel["idShort"]
    assert read.semantic_id.key[0].value == submodel["semanticId"]["keys"][0]["value"]
    expected = _json_leaves(submodel["submodelElements"])
    found = _basyx_leaves(read.submodel_element)
    assert list(found) == list(expected)  # the same elements, in the same order
    for where, value in expected.items():
        assert found[where] == value, where
    # real quantities stay doubles (the template's xs:long is not restored), to the bit
    peak = expected["/SizingResult/MainComponent00/MaxTorqueUtilization"]
    assert peak[2] == "xs:double" and math.isfinite(peak[3])
    assert expected["/SizingProjectInformation/DateCreated"][3] == datetime(
        2026, 12, 6, 16, 0, tzinfo=UTC)
    assert created == datetime(2026, 12, 6, 16, 0, tzinfo=UTC)


def _pair() -> PairResult:
    return PairResult(motor="M1", manufacturer="ACME", feasible=True, peak_torque=2.0,
                      rms_torque=1.0, max_speed=100 * math.pi, margin_peak=0.25,
                      margin_rms=0.5, margin_speed=0.75, limiting="peak", law="cycloidal",
                      ratio=5.0, gearbox="G5", notes=("a note",))


def test_the_same_submodel_gives_the_same_bytes_whatever_the_clock(monkeypatch):
    pytest.importorskip("basyx.aas.adapter.aasx")
    from sizer.idta.aasx import ZIP_EPOCH, aasx_package

    submodel = sizing_result_submodel(_pair(), submodel_id="urn:x:1", project="p", tool="t",
                                      created="2026-12-06T16:00:00Z")
    date = datetime(2026, 12, 6, 16, 0, tzinfo=UTC)
    first = aasx_package(submodel, created=date, creator="sizer")
    real = time.time
    monkeypatch.setattr(time, "time", lambda: real() + 400 * 86400.0)  # a clock a year on
    second = aasx_package(submodel, created=date, creator="sizer")
    assert first == second
    with zipfile.ZipFile(io.BytesIO(first)) as package:
        assert {info.date_time for info in package.infolist()} == {ZIP_EPOCH}
        names = package.namelist()
        assert "aasx/data.json" in names and "[Content_Types].xml" in names
        environment = json.loads(package.read("aasx/data.json"))
    assert [s["id"] for s in environment["submodels"]] == ["urn:x:1"]


def test_the_cli_writes_the_same_aasx_bytes_again(outputs, design, monkeypatch):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1796572800")
    again = design.with_name("again.aasx")
    assert run_cli("idta", "write", str(design), "-o", str(again)).returncode == 0
    assert again.read_bytes() == outputs["result.aasx"].read_bytes()
    assert sorted(p.name for p in design.parent.glob("*.aasx*")) == [
        "again.aasx", "result.aasx"]  # written atomically: no temporary left


def test_without_basyx_an_aasx_output_is_a_user_error(design, tmp_path, monkeypatch):
    """basyx hidden (None in sys.modules: its import fails): exit 2 naming the extra, before
    sizing, and nothing written."""
    for name in [n for n in sys.modules if n.split(".")[0] in ("basyx", "pyecma376_2")]:
        monkeypatch.delitem(sys.modules, name)
    monkeypatch.setitem(sys.modules, "basyx", None)
    monkeypatch.setitem(sys.modules, "pyecma376_2", None)
    out = tmp_path / "r.aasx"
    result = run_cli("idta", "write", str(design), "-o", str(out))
    assert_user_error(result, "--output", "sizer-motion[aas]")
    assert not out.exists()
