"""The trade-off front (sizer.sizing.front): dominance, the knee's rule, a real sizing."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from sizer import api
from sizer.errors import UserError
from sizer.laws import make_law
from sizer.model.domain import Motor
from sizer.sizing import CandidateResult, Check, SizingResult
from sizer.sizing.front import (
    KNEE_RULE,
    FrontBy,
    front_by,
    knee_of,
    non_dominated,
    trade_off,
)

ROOT = Path(__file__).resolve().parents[1]
GEARBOXES = str(ROOT / "examples" / "indexing-table-gearboxes.yaml")
FASTEST = str(ROOT / "examples" / "indexing-table-fastest.yaml")


def brute_force(t: np.ndarray, s: np.ndarray) -> np.ndarray:
    """The front by definition: known points no other known point dominates."""
    known = np.isfinite(t) & np.isfinite(s)
    out = np.zeros(len(t), dtype=bool)
    for i in np.flatnonzero(known):
        out[i] = not any(t[j] <= t[i] and s[j] <= s[i] and (t[j] < t[i] or s[j] < s[i])
                         for j in np.flatnonzero(known))
    return out


@pytest.mark.parametrize("seed", range(12))
def test_non_dominated_is_the_definition(seed: int) -> None:
    rng = np.random.default_rng(seed)
    n = 60
    t = rng.integers(0, 8, n).astype(float)  # few values: many ties in one or both
    s = rng.integers(0, 8, n).astype(float)
    t[rng.random(n) < 0.1] = np.nan
    s[rng.random(n) < 0.1] = np.inf
    assert np.array_equal(non_dominated(t, s), brute_force(t, s))


def test_equal_points_are_both_on_the_front_and_nan_is_on_none() -> None:
    t = np.array([1.0, 1.0, 2.0, 1.0, np.nan])
    s = np.array([5.0, 5.0, 1.0, 6.0, 0.0])
    assert non_dominated(t, s).tolist() == [True, True, True, False, False]
    assert not non_dominated(np.array([]), np.array([])).any()


def test_knee_on_a_set_known_by_hand() -> None:
    # sorted by size: ends (10, 0) and (0, 10); scaled, t + s = 1 is the line through
    # them and 1 - t - s is 0, 0.5, 0.6, 0.5, 0: the knee is (2, 2)
    t = np.array([10.0, 4.0, 2.0, 1.0, 0.0])
    s = np.array([0.0, 1.0, 2.0, 4.0, 10.0])
    assert knee_of(t, s) == 2
    assert knee_of(t[::-1], s[::-1]) == 2  # any order of the points
    # the scale does not matter: seconds against watts
    assert knee_of(t * 1e-3, s * 1e4) == 2


def test_no_knee_for_a_straight_or_concave_front_or_two_points() -> None:
    assert knee_of(np.array([2.0, 1.0, 0.0]), np.array([0.0, 1.0, 2.0])) is None  # line
    # concave: the middle point lies on the far side of the line from the ideal point
    assert knee_of(np.array([2.0, 1.6, 0.0]), np.array([0.0, 1.6, 2.0])) is None
    assert knee_of(np.array([1.0, 0.0]), np.array([0.0, 1.0])) is None
    assert "farthest from the straight line through the front's two ends" in KNEE_RULE
    assert "[0, 1]" in KNEE_RULE


def test_a_knee_tie_goes_to_the_smaller_motor() -> None:
    # 1 - t - s is 0.25 at both inner points
    t = np.array([4.0, 1.0, 2.0, 0.0])
    s = np.array([0.0, 2.0, 1.0, 4.0])
    assert knee_of(t, s) == 2


def test_front_by_names_its_choices() -> None:
    assert front_by(None) is FrontBy.POWER and front_by("Price") is FrontBy.PRICE
    assert front_by("size") is FrontBy.POWER
    with pytest.raises(UserError) as raised:
        front_by("volume")
    assert raised.value.field == "front_by" and "power, price, mass, energy" in str(raised.value)


def check_front(sizing: SizingResult, by: str = "power") -> None:
    """The issue's properties of a front over a real sizing."""
    front = trade_off(sizing, by)
    feasible = [i for i, r in enumerate(sizing.results) if r.feasible]
    members = front.members.tolist()
    assert members and set(members) <= set(feasible)
    # both smaller better: a margin (given duration) is reported larger better
    t = -front.time if front.time_name == "margin" else front.time
    s = front.size
    for i in members:  # no front row dominated by any feasible row (nor by a front row)
        assert not any(t[j] <= t[i] and s[j] <= s[i] and (t[j] < t[i] or s[j] < s[i])
                       for j in feasible)
    fastest = min(t[j] for j in feasible)
    smallest = min(s[j] for j in feasible)
    assert any(t[i] == fastest for i in members)
    assert any(s[i] == smallest for i in members)
    assert [s[i] for i in members] == sorted(s[i] for i in members)  # by size
    if front.knee is not None:  # the rule, recomputed here
        tt, ss = t[members], s[members]
        bulge = 1 - (tt - tt.min()) / np.ptp(tt) - (ss - ss.min()) / np.ptp(ss)
        assert bulge[members.index(front.knee)] == pytest.approx(bulge.max(), abs=1e-15)
        assert front.statuses[front.knee] == "knee"
    assert {front.statuses[i] for i in members} <= {"front", "knee"}
    assert all(front.statuses[i] == "" for i in range(len(t)) if i not in members)


def knee_by_hand(sizing: SizingResult) -> tuple[CandidateResult, int, int]:
    """The knee's pair (by the rule: front by brute force over the feasible pairs' T_min
    and rated power, both scaled to [0, 1] over it, the largest 1 - t - s, ties to the
    smaller motor), the front's size and the feasible count: from the results' figures."""
    feasible = [r for r in sizing.results if r.feasible]
    t = np.array([r.duration for r in feasible])
    s = np.array([r.rated_power for r in feasible])
    on = [i for i in range(len(t)) if not any(
        t[j] <= t[i] and s[j] <= s[i] and (t[j] < t[i] or s[j] < s[i]) for j in range(len(t)))]
    tt, ss = t[on], s[on]
    bulge = 1 - (tt - tt.min()) / np.ptp(tt) - (ss - ss.min()) / np.ptp(ss)
    best = max(range(len(on)), key=lambda k: (bulge[k], -ss[k]))
    return feasible[on[best]], len(on), len(feasible)


def test_the_front_of_a_minimize_sizing() -> None:
    sizing = api.size(GEARBOXES)
    check_front(sizing)
    front = trade_off(sizing)
    assert front.time_name == "duration"
    rows = [sizing.results[i] for i in front.members]
    # the smallest motor is the slowest end, the fastest pair the other end
    assert rows[0].rated_power == min(r.rated_power for r in sizing.feasible)
    assert rows[-1].duration == min(r.duration or math.inf for r in sizing.feasible)
    assert front.knee is not None
    knee = sizing.results[front.knee]
    assert knee is knee_by_hand(sizing)[0]  # 400 W, between 100 W and 750 W


def test_the_front_is_the_same_from_rows_and_from_the_table() -> None:
    sizing = api.size(FASTEST)
    hand_made = SizingResult(sizing.mode, tuple(sizing.results), sizing.design_name)
    one, two = trade_off(sizing), trade_off(hand_made)
    assert one.members.tolist() == two.members.tolist() and one.knee == two.knee
    check_front(sizing)


def test_with_a_given_duration_the_time_is_the_smallest_margin() -> None:
    sizing = api.size(str(ROOT / "examples" / "indexing-table.yaml"))
    front = trade_off(sizing)
    assert front.time_name == "margin"
    check_front(sizing)
    for i in front.members:  # the margin as reported, larger better
        assert front.time[i] == pytest.approx(sizing.results[i].worst_slack, abs=1e-15)
    assert "larger better" in front.rule and KNEE_RULE in front.rule


def motor(name: str, power: float, price: float | None) -> Motor:
    return Motor(name, 1e-4, power / 300.0, 3 * power / 300.0, 300.0, price=price)


def result(m: Motor, duration: float, feasible: bool = True) -> CandidateResult:
    check = Check("rms", 1.0, 2.0, "N*m", 0.5)
    return CandidateResult(m, make_law("cycloidal"), feasible, duration, 1.0, 1.0, 1.0,
                           (check,), "rms")


def test_price_front_leaves_out_the_pairs_without_a_price() -> None:
    rows = (result(motor("a", 100.0, 50.0), 0.3), result(motor("b", 200.0, None), 0.1),
            result(motor("c", 400.0, 80.0), 0.2), result(motor("d", 50.0, 10.0), 0.05, False))
    sizing = SizingResult("minimize", rows, "hand")
    front = trade_off(sizing, "price")
    assert front.members.tolist() == [0, 2] and front.left_out == 1
    assert trade_off(sizing).members.tolist() == [0, 1]  # by power: b dominates c
    no_price = SizingResult("minimize", rows[1:2], "hand")
    with pytest.raises(UserError) as raised:
        trade_off(no_price, "price")
    assert raised.value.field == "front_by"
    with pytest.raises(UserError):
        trade_off(sizing, "energy")  # no energy checks: no cycle energy


def test_no_feasible_pair_gives_an_empty_front() -> None:
    rows = (result(motor("a", 100.0, 50.0), 0.3, False),)
    front = trade_off(SizingResult("minimize", rows, "hand"))
    assert front.members.size == 0 and front.knee is None and front.statuses == ("",)
