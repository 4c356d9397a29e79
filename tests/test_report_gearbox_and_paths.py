"""Reports show the gearbox chosen from a catalog (not a made-up one), no absolute paths of
the machine, and JSON documents carry their format version."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
import yaml
from cli_run import run_cli as run

from sizer.report.design_report import DesignReport
from sizer.units import to_si

ROOT = Path(__file__).resolve().parent.parent
GEARBOXES = ROOT / "examples" / "indexing-table-gearboxes.yaml"


def catalog_gearboxes() -> dict[str, dict[str, float]]:
    """'SERIES i=K' -> its efficiency and inertia, read from the catalog file here."""
    data = yaml.safe_load((ROOT / "examples/catalogs/example-gearboxes.yaml").read_text())
    out = {}
    for series in data["gearboxes"]:
        for item in series["ratios"]:
            efficiency = item.get("efficiency", series["efficiency"])
            out[f"{series['id']} i={item['ratio']:g}"] = {
                "ratio": float(item["ratio"]),
                "efficiency": to_si(efficiency, "fraction"),
                "inertia": to_si(item["inertia"], "inertia")}
    return out


@pytest.fixture(scope="module")
def gearbox_report() -> tuple[str, object]:
    from sizer.io import load_design
    from sizer.sizing import size_design

    design = load_design(GEARBOXES)
    sizing = size_design(design)
    return DesignReport(design, sizing, best=3, source=str(GEARBOXES)).markdown(), sizing


def test_the_transmission_section_invents_no_gearbox(gearbox_report) -> None:
    text, _ = gearbox_report
    section = text.split("## Transmission")[1].split("## Limits")[0]
    assert "| 1 | gearbox | from the gearbox catalog | per pair | per pair | per pair |" \
        in section
    assert "Total ratio" not in section  # no total of a ratio that is not chosen yet
    for name in catalog_gearboxes():
        assert name in section


def test_each_candidate_shows_its_catalog_gearbox(gearbox_report) -> None:
    text, sizing = gearbox_report
    catalog = catalog_gearboxes()
    best = [r for r in sizing.results if r.feasible][:3]
    lines = [x for x in text.splitlines() if x.startswith("- Transmission ratio K = ")]
    assert len(lines) == 3
    for result, line in zip(best, lines, strict=True):
        figures = catalog[result.gearbox]
        assert f"gearbox {result.gearbox} (from the catalog)" in line
        numbers = dict(re.findall(r"(ratio|efficiency|inertia) ([0-9.e+-]+)", line))
        assert float(numbers["ratio"]) == figures["ratio"] == result.ratio
        assert float(numbers["efficiency"]) == pytest.approx(figures["efficiency"], rel=1e-4)
        assert float(numbers["inertia"]) == pytest.approx(figures["inertia"], rel=1e-4)


def test_report_prints_no_absolute_path(tmp_path: Path) -> None:
    out = tmp_path / "report"
    result = run("report", str(GEARBOXES.resolve()), "-o", str(out), "--best", "0",
                 "--catalog", str((ROOT / "examples/catalogs/example-servo.yaml").resolve()))
    assert result.returncode == 0, result.stderr
    text = (out / "report.md").read_text()
    assert "Design file: `indexing-table-gearboxes.yaml`" in text
    assert str(ROOT) not in text and str(tmp_path) not in text
    assert not re.search(r"(^|[\s`(])/(work|home|tmp|root|Users)/", text)


def test_json_documents_carry_their_format_version() -> None:
    sized = json.loads(run("size", str(GEARBOXES), "--format", "json", "--top", "1").stdout)
    assert sized["format"] == "sizer.sizing/1"
    assert sized["ranked_by"] == "duration" and sized["ranking"].startswith("shortest")
    stage = sized["design"]["transmission"]["stages"][0]
    assert stage["chosen_per_pair"] is True and stage["ratio"] is None
    assert sized["design"]["transmission"]["choice"]["gearboxes"] == list(catalog_gearboxes())
    assert sized["results"][0]["gearbox"] in catalog_gearboxes()
    checked = json.loads(run("check", str(ROOT / "examples/indexing-table.yaml"),
                             "--format", "json").stdout)
    assert checked["format"] == "sizer.check/1"
