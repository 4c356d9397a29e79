"""The transmission examples end to end through the CLI (issue 4)."""

from __future__ import annotations

import json
import math
from pathlib import Path

from cli_run import run_cli

ROOT = Path(__file__).resolve().parents[1]


def run_json(*args: str) -> dict:
    result = run_cli(*args, "--format", "json")
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout)


def test_pick_and_place_vertical_axis_with_belt_and_ball_screw():
    data = run_json("size", str(ROOT / "examples" / "pick-and-place.yaml"),
                    "--motor", "SGM7J-04A", "--motor", "SGM7A-15A", "--all")
    results = data["results"]
    assert {r["motor"] for r in results} == {"SGM7J-04A", "SGM7A-15A"}
    screw_k = 2 * math.pi / 0.02
    for r in results:
        # the belt ratio was chosen in [1, 4]; the total ratio includes the screw's
        assert screw_k * (1 - 1e-9) <= r["ratio"] <= 4 * screw_k * (1 + 1e-9)
        assert r["load_speed"] > 0.15 / 0.3  # peak above the mean speed, in m/s
        assert math.isclose(r["max_speed"], r["load_speed"] * r["ratio"], rel_tol=1e-12)
        names = {c["name"] for c in r["checks"]}
        assert "ball_screw_speed" in names
    assert any(r["feasible"] for r in results)


def test_indexing_table_picks_a_catalog_gearbox():
    data = run_json("size", str(ROOT / "examples" / "indexing-table-gearboxes.yaml"),
                    "--motor", "HG-KN43J")
    best = data["results"][0]
    assert best["feasible"]
    assert best["gearbox"].startswith(("PG40-example", "PG60-example"))
    assert {"gearbox_speed", "gearbox_rms", "gearbox_peak"} <= {c["name"] for c in best["checks"]}
