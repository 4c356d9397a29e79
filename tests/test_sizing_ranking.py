"""Ranking (sizer.sizing.ranking): the smallest motor that passes first, meaningful ties."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml

from sizer.errors import UserError
from sizer.laws import make_law
from sizer.model.domain import Motor
from sizer.sizing import CandidateResult, Check
from sizer.sizing.ranking import RANK_KEYS, RankKey, rank, rank_rule
from sizer.units import to_si

ROOT = Path(__file__).resolve().parent.parent


def result(motor: str, *, power: float, torque: float = 1.0, slack: float = 0.2,
           inertia: float = 1e-4, feasible: bool = True, duration: float = 0.25,
           rms: float = 1.0, price: float | None = None) -> CandidateResult:
    """A pair whose checks leave ``slack`` (and 0.5) beyond the required margins."""
    checks = (Check("peak", 0.5 - slack, 1.0, "", 0.5 + slack, 0.0),
              Check("rms", 0.5, 1.0, "N*m", 0.5, 0.0))
    return CandidateResult(motor_object=Motor(motor, inertia, torque, 3.0 * torque,
                                              power / torque, price=price),
                           law_object=make_law("cycloidal"),
                           feasible=feasible, duration=duration, peak_torque=1.0,
                           rms_torque=rms, max_speed=100.0, checks=checks, limiting="peak")


def motors(ranked: list[CandidateResult]) -> list[str]:
    return [r.motor for r in ranked]


def test_default_puts_the_smallest_feasible_motor_first_not_the_roomiest() -> None:
    big = result("big-3500W", power=3500.0, torque=11.0, slack=0.9)
    small = result("small-200W", power=200.0, torque=0.64, slack=0.05)
    middle = result("mid-400W", power=400.0, torque=1.3, slack=0.5)
    tiny = result("tiny-50W", power=50.0, torque=0.16, feasible=False, slack=-0.3)
    ranked = rank([big, tiny, middle, small], None, "duration")
    assert motors(ranked) == ["small-200W", "mid-400W", "big-3500W", "tiny-50W"]
    # the old default: the most room first, which is the most oversized motor
    assert motors(rank([big, middle, small], "margin", "duration"))[0] == "big-3500W"


def test_ties_go_to_torque_then_margin_then_inertia_then_the_id() -> None:
    a = result("a", power=400.0, torque=1.4, slack=0.5)
    b = result("b", power=400.0, torque=1.3, slack=0.1)  # same power, less torque
    assert motors(rank([a, b], "size", "duration")) == ["b", "a"]
    c = result("c", power=400.0, torque=1.3, slack=0.3)  # same size, more margin than b
    assert motors(rank([a, b, c], "size", "duration")) == ["c", "b", "a"]
    heavy = result("a-heavy", power=400.0, torque=1.3, slack=0.3, inertia=3e-4)
    assert motors(rank([heavy, c], "size", "duration")) == ["c", "a-heavy"]
    # all equal: the final total order (the motor id), whatever the input order
    z, y = result("z", power=400.0), result("y", power=400.0)
    assert motors(rank([z, y], "size", "duration")) == ["y", "z"]
    assert motors(rank([y, z], "size", "duration")) == ["y", "z"]


def test_minimize_ranks_by_duration_then_size() -> None:
    fast_big = result("fast-big", power=750.0, duration=0.08)
    fast_small = result("fast-small", power=400.0, duration=0.08)
    slow = result("slow", power=100.0, duration=0.2)
    assert motors(rank([slow, fast_big, fast_small], None, "minimize")) == [
        "fast-small", "fast-big", "slow"]


def test_other_keys_break_ties_by_size() -> None:
    cheap_big = result("cheap-big", power=750.0, price=100.0)
    cheap_small = result("cheap-small", power=200.0, price=100.0)
    unknown = result("unknown", power=50.0)
    assert motors(rank([unknown, cheap_big, cheap_small], "price", "duration")) == [
        "cheap-small", "cheap-big", "unknown"]
    low_rms = [result("x", power=750.0, rms=0.5), result("w", power=200.0, rms=0.5)]
    assert motors(rank(low_rms, "rms", "duration")) == ["w", "x"]


def test_keys_aliases_and_rules() -> None:
    assert set(RANK_KEYS) == {k.value for k in RankKey}
    assert rank_rule("power", "duration").key is RankKey.SIZE
    assert rank_rule(None, "duration").key is RankKey.SIZE
    assert rank_rule(None, "minimize").key is RankKey.DURATION
    assert all(rank_rule(k, "duration").text for k in RANK_KEYS)
    with pytest.raises(UserError, match=r"cannot rank by .speed.*size.*power"):
        rank_rule("speed", "duration")


def test_indexing_table_first_row_is_the_smallest_feasible_motor() -> None:
    """The example's ranking against the catalog's own ratings (tau_c*v_n, computed here)."""
    from sizer.io import load_design
    from sizer.sizing import size_design

    catalog = yaml.safe_load((ROOT / "examples/catalogs/example-servo.yaml").read_text())
    power = {m["id"]: to_si(m["continuous_torque"], "torque")
             * to_si(m["rated_speed"], "angular_speed") for m in catalog["motors"]}
    sizing = size_design(load_design(ROOT / "examples/indexing-table.yaml"))
    feasible = [r for r in sizing.results if r.feasible]
    assert feasible and all(not r.feasible for r in sizing.results[len(feasible):])
    powers = [power[r.motor] for r in feasible]
    assert powers == sorted(powers)
    assert power[feasible[0].motor] == min(power[r.motor] for r in feasible)
    assert feasible[0].motor == "HG-KN43J"  # 1.3 N*m x 3000 rpm = 408 W; HG-KN73J 754 W
    same_motor = [r for r in feasible if r.motor == feasible[0].motor]
    slacks = [r.slacks for r in same_motor]
    assert slacks == sorted(slacks, reverse=True)  # then by margin
    assert feasible[0].rated_power == pytest.approx(408.407, rel=1e-5)


CARRIAGE = """\
name: 5 kg carriage on a belt
task: {displacement: 300 mm, duration: 0.5 s, dwell: 0.2 s, return: true}
load: {mass: 5 kg, friction_coefficient: 0.05}
transmission: {type: belt, driver_diameter: 40 mm, efficiency: 0.95}
laws: [cycloidal, modified_sinusoidal]
limits: {torque_margin: 20 %}
"""


def test_a_light_carriage_gets_a_small_motor_from_the_bundled_catalogs(tmp_path: Path) -> None:
    """Against every bundled real motor: the first pair has the smallest rated power of
    all feasible motors; ranking by margin would put a motor of several kW first."""
    from sizer.io import load_design
    from sizer.sizing import size_design

    path = tmp_path / "carriage.yaml"
    path.write_text(CARRIAGE)
    design = load_design(path, default_motors=True)
    assert len(design.motors) > 50
    power = {m.id: m.continuous_torque * m.rated_speed for m in design.motors}
    sizing = size_design(design)
    feasible = [r for r in sizing.results if r.feasible]
    smallest = min(power[r.motor] for r in feasible)
    assert power[sizing.results[0].motor] == smallest < 250.0
    assert [power[r.motor] for r in feasible] == sorted(power[r.motor] for r in feasible)
    roomiest = rank(sizing.results, "margin", sizing.mode)[0]
    assert power[roomiest.motor] > 10 * smallest


def test_json_results_give_the_size_they_are_ranked_by() -> None:
    import json

    from cli_run import run_cli

    data = json.loads(run_cli("size", str(ROOT / "examples/indexing-table.yaml"), "-f", "json",
                              "--top", "1").stdout)
    assert data["results"][0]["motor"] == "HG-KN43J"
    assert data["results"][0]["rated_power"] == pytest.approx(1.3 * 3000 * 2 * 3.141592653589793
                                                              / 60, rel=1e-12)
    assert data["units"]["rated_power"].startswith("W")
