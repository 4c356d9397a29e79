"""``sizer size --front`` / ``--front-by`` and the ``front`` column of every CSV and JSON."""

from __future__ import annotations

import csv
import io
import json
from pathlib import Path

import pytest
from cli_run import assert_user_error
from cli_run import run_cli as run

ROOT = Path(__file__).resolve().parent.parent
GEARBOXES = str(ROOT / "examples" / "indexing-table-gearboxes.yaml")
INDEXING = str(ROOT / "examples" / "indexing-table.yaml")

PRICED = """\
name: priced axis
task: {displacement: 90 deg, duration: minimize, dwell: 0.3 s}
load: {inertia: 0.02 kg*m^2}
transmission: {type: gearbox, ratio: 5}
laws: [cycloidal, poly5]
limits: {braking_resistor_power: 1000 W}
motors:
"""
MOTORS = [  # id, rotor inertia kg*cm^2, tau_c, tau_p, price, mass, k_t, R
    ("small", 0.2, 0.32, 0.95, 300, 0.6, 0.3, 6.0),
    ("medium", 0.4, 0.64, 1.9, 350, 0.9, 0.3, 3.0),
    ("large", 1.5, 1.3, 3.8, 500, 1.5, 0.4, 1.5),
    ("huge", 6.0, 2.4, 7.2, 900, 3.0, 0.5, 0.8),
]


@pytest.fixture(scope="module")
def priced(tmp_path_factory: pytest.TempPathFactory) -> str:
    lines = [f"  - {{id: {m}, inertia: {j} kg*cm^2, continuous_torque: {tc}, peak_torque: "
             f"{tp}, rated_speed: 3000 rpm, max_speed: 6000 rpm, price: {p}, mass: {kg}, "
             f"torque_constant: {kt}, winding_resistance: {r}}}"
             for m, j, tc, tp, p, kg, kt, r in MOTORS]
    path = tmp_path_factory.mktemp("front") / "priced.yaml"
    path.write_text(PRICED + "\n".join(lines) + "\n")
    return str(path)


def ok(*args: str) -> str:
    result = run(*args)
    assert result.returncode == 0, result.stderr
    return result.stdout


def csv_rows(*args: str) -> list[dict[str, str]]:
    return list(csv.DictReader(io.StringIO(ok("size", *args, "--format", "csv"))))


def test_every_csv_and_json_has_the_front_column() -> None:
    rows = csv_rows(GEARBOXES, "--all")
    assert list(rows[0])[-1] == "front"
    marks = [r["front"] for r in rows]
    assert marks.count("knee") == 1 and set(marks) <= {"knee", "front", ""}
    data = json.loads(ok("size", GEARBOXES, "--format", "json"))
    assert [r["front"] for r in data["results"]] == marks
    assert "trade-off front" in data["units"]["front"]
    duration_mode = json.loads(ok("size", INDEXING, "--all", "--format", "json"))
    assert all("front" in r for r in duration_mode["results"])
    assert all(r["front"] == "" for r in duration_mode["results"] if not r["feasible"])


def test_front_shows_only_the_front_smallest_motor_first() -> None:
    everything = csv_rows(GEARBOXES)
    front = csv_rows(GEARBOXES, "--front")
    assert {r["rank"] for r in front} == {r["rank"] for r in everything if r["front"]}
    times = [float(r["duration [s]"]) for r in front]
    assert min(times) == min(float(r["duration [s]"]) for r in everything)  # the fastest
    assert front[0]["motor"] == "HG-KN13J"  # the smallest motor (100 W) first
    assert times == sorted(times, reverse=True)  # smaller motors are slower
    assert [r["front"] for r in front].count("knee") == 1


def test_front_json_states_the_rule_and_the_points() -> None:
    data = json.loads(ok("size", GEARBOXES, "--front", "--format", "json"))
    front = data["front"]
    assert front["by"] == "power" and front["time"] == "duration"
    assert "farthest from the straight line through the front's two ends" in front["rule"]
    assert "[0, 1]" in front["rule"]
    points = front["points"]
    assert [p["size"] for p in points] == sorted(p["size"] for p in points)
    assert front["knee"] in points and front["knee"]["status"] == "knee"
    assert [r["motor"] for r in data["results"]] == [p["motor"] for p in points]


def test_the_minimize_table_says_where_each_row_stands() -> None:
    text = ok("size", GEARBOXES, "--format", "md")
    header = next(line for line in text.splitlines() if line.startswith("| #"))
    assert header.rstrip(" |").endswith("front")
    from test_front import knee_by_hand

    from sizer import api

    sizing = api.size(GEARBOXES)
    knee = knee_by_hand(sizing)[0]
    assert f"knee: #{sizing.results.index(knee) + 1} {knee.motor}" in text
    given = ok("size", INDEXING, "--format", "md")  # a given duration: no column
    header = next(line for line in given.splitlines() if line.startswith("| #"))
    assert "front" not in header


@pytest.mark.parametrize(("by", "column", "first"), [
    ("price", "price", "300"), ("mass", "mass [kg]", "0.6"),
    ("energy", "energy per cycle [J]", None)])
def test_front_by(priced: str, by: str, column: str, first: str | None) -> None:
    text = ok("size", priced, "--front", "--front-by", by, "--format", "md")
    header = next(line for line in text.splitlines() if line.startswith("| #"))
    cells = [c.strip() for c in header.strip("|").split("|")]
    assert column in cells
    rows = [line for line in text.splitlines() if line.startswith("| ") and "---" not in line]
    values = [[c.strip() for c in row.strip("|").split("|")][cells.index(column)]
              for row in rows[1:]]
    assert [float(v) for v in values] == sorted(float(v) for v in values)
    if first is not None:
        assert values[0] == first
    data = json.loads(ok("size", priced, "--front", "--front-by", by, "--format", "json"))
    assert data["front"]["by"] == by
    assert data["front"]["size"] == {"price": "price", "mass": "mass",
                                     "energy": "cycle_energy"}[by]


def test_front_by_errors_name_the_option(priced: str) -> None:
    assert_user_error(run("size", priced, "--front-by", "volume"), "--front-by", "price")
    # the bundled example catalog gives no prices
    assert_user_error(run("size", GEARBOXES, "--front", "--front-by", "price"),
                      "--front-by", "price")
    machine = str(ROOT / "examples" / "machines" / "two-axis-packer.yaml")
    assert_user_error(run("size", machine, "--front"), "--front")


def test_a_given_duration_front_is_margin_against_size() -> None:
    text = ok("size", INDEXING, "--front", "--format", "md")
    assert "smallest margin against rated power" in text and "min margin [%]" in text
