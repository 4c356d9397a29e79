"""Catalog listings as plain data: summaries, motors as written and in SI, regions."""

from __future__ import annotations

import math

import pytest

from sizer.catalog_tools import catalog_entries, catalog_summaries, find_motor, summarize_catalog
from sizer.errors import UserError
from sizer.io import bundled_catalogs

RPM = 2 * math.pi / 60

MINE = """\
catalog: My motors
manufacturer: ACME
source: "ACME catalog, https://example.com"
motors:
  - id: M1
    inertia: 1 kg*cm^2
    continuous_torque: 1 N*m
    peak_torque: 3 N*m
    rated_speed: 3000 rpm
    notes: a note
"""


def test_summaries_of_the_bundled_catalogs():
    summaries = {s.name: s for s in catalog_summaries()}
    assert list(summaries) == list(bundled_catalogs())
    assert summaries["yaskawa-sgm7j"].motors == 7
    assert summaries["yaskawa-sgm7j"].manufacturers == ("Yaskawa",)
    assert summaries["yaskawa-sgm7j"].default is True
    assert summaries["book-examples"].default is False
    assert summaries["siemens-1ft7"].title == "Siemens SIMOTICS S-1FT7 servomotors"


def test_entries_keep_the_figures_as_written_with_catalog_defaults():
    entries = catalog_entries("yaskawa-sgm7j")
    first = entries[0]
    assert first.motor.id == "SGM7J-A5A" and first.catalog == "yaskawa-sgm7j"
    assert first.given["inertia"] == "0.0395e-4 kg*m^2"
    assert first.given["manufacturer"] == "Yaskawa"  # from the catalog level
    assert "https://" in first.given["source"]
    assert first.notes.startswith("grade B") and "notes" not in first.given
    assert first.line is not None and first.has_curves is False


def flat(curve):
    return [v for point in curve for v in point]


def test_regions_as_the_sizing_uses_them():
    hc52 = find_motor("HC52")
    assert flat(hc52.continuous_region) == pytest.approx([0.0, 2.94, 2000 * RPM, 2.39])
    assert flat(hc52.intermittent_region) == pytest.approx([0.0, 11.8, 2000 * RPM, 11.8])
    sgm = find_motor("SGM7J-02A")
    assert flat(sgm.continuous_region) == pytest.approx([0.0, 0.637, 3000 * RPM, 0.637])
    maxon = find_motor("EC45flat-30W-339281")
    assert flat(maxon.intermittent_region) == pytest.approx([0.0, 0.239, 4380 * RPM, 0.0])


def test_find_motor_in_given_catalogs_and_unknown_ids(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "mine.yaml").write_text(MINE)
    entry = find_motor("M1", ["mine.yaml"])
    assert entry.catalog == "mine" and entry.notes == "a note"
    assert summarize_catalog("mine.yaml").default is False
    with pytest.raises(UserError) as info:
        find_motor("SGM7J-02A", ["mine.yaml"])
    assert "no motor 'SGM7J-02A' in the given catalogs" in info.value.message
    with pytest.raises(UserError) as info:
        find_motor("SGM7J-2A")
    assert "did you mean 'SGM7J-C2A', 'SGM7J-02A'" in info.value.message
    with pytest.raises(UserError) as info:
        catalog_entries("no-such-catalog")
    assert "unknown catalog" in info.value.message
