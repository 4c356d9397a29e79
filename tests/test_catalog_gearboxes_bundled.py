"""The bundled gearbox catalogs (issue 35): real planetary series, graded and sourced,
named by a design like a file."""

from __future__ import annotations

from pathlib import Path

import yaml
from cli_run import run_cli

from sizer.catalog_tools import validate_catalogs
from sizer.io.transmission import bundled_gearbox_catalogs, load_gearbox_catalog
from sizer.model.domain import figure_provenance

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "indexing-table-gearboxes.yaml"
"""A design with a gearbox stage chosen from a catalog (its motors beside it)."""


def test_at_least_two_real_series_validate_clean_and_graded():
    bundled = bundled_gearbox_catalogs()
    assert len(bundled) >= 2
    report = validate_catalogs([str(p) for p in bundled.values()])
    assert report.findings == [] and report.unreadable == []
    for path in bundled.values():
        for option in load_gearbox_catalog(path):
            grades = {p.grade for p in figure_provenance(option).values() if p is not None}
            assert grades and grades <= {"A", "C"}, option.gearbox


def test_a_design_names_a_bundled_gearbox_catalog(tmp_path):
    data = yaml.safe_load(EXAMPLE.read_text(encoding="utf-8"))
    assert data["transmission"]["catalog"] == "catalogs/example-gearboxes.yaml"
    data["transmission"]["catalog"] = "beckhoff-ag2400-tp"  # a bundled name, not a file
    data["motors"] = str(EXAMPLE.parent / data["motors"])
    design = tmp_path / "design.yaml"
    design.write_text(yaml.safe_dump(data, sort_keys=False))
    result = run_cli("size", str(design), "--format", "json", "--top", "1")
    assert result.returncode == 0, result.stderr
    assert '"gearbox": "TP' in result.stdout
    data["transmission"]["catalog"] = "beckhoff-nope"
    design.write_text(yaml.safe_dump(data, sort_keys=False))
    missing = run_cli("size", str(design))
    assert missing.returncode == 2 and "beckhoff-ag2400-tp" in missing.stderr
