"""The continuous ratio search (sizer.sizing.choices._continuous): a lattice point a motor
evaluated in an earlier round is not evaluated again, and the search chooses what the
search that evaluates every round's four neighbours afresh chose (a test-only copy of it
below), on objectives with ties and several minima."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sizer.sizing import choices
from sizer.sizing.choices import COARSE, LOG_STEP, _continuous


class _Kept:
    """The best (smaller value, then smaller rank) per motor, as choices._Best keeps it."""

    def __init__(self, motors: int) -> None:
        self.value = np.full(motors, np.inf)
        self.rank = np.zeros(motors, dtype=np.intp)
        self.stage_ratio = np.full(motors, np.nan)
        self.seen = 0


def _search(objective, motors: int, bounds, search) -> tuple[np.ndarray, list]:
    """Run ``search`` with a consider that scores (motor, ratio) by ``objective`` and
    records every evaluation."""
    kept, calls = _Kept(motors), []

    def consider(points, names, motor, option, rank=None, candidates=None):
        ratios = np.array(points)[option]
        value = objective(motor, ratios)
        rank = kept.seen + np.arange(len(motor))
        kept.seen += len(motor)
        calls.extend(zip(motor.tolist(), ratios.tolist(), strict=True))
        for m, v, r, x in zip(motor, value, rank, ratios, strict=True):
            if v < kept.value[m] or (v == kept.value[m] and r < kept.rank[m]):
                kept.value[m], kept.rank[m], kept.stage_ratio[m] = v, r, x

    search(bounds, lambda ratio: ratio, consider, kept, motors)
    return kept.stage_ratio, calls


def _afresh(bounds, with_ratio, consider, best, motors) -> None:
    """The search before the points seen were skipped: each round's four neighbours."""
    lo, hi = math.log(bounds[0]), math.log(bounds[1])
    step = (hi - lo) / (COARSE - 1)
    consider([with_ratio(math.exp(x)) for x in np.linspace(lo, hi, COARSE)], None,
             np.repeat(np.arange(motors), COARSE), np.tile(np.arange(COARSE), motors))
    last, offsets = COARSE - 1, np.array([-2, -1, 1, 2])
    while step > LOG_STEP:
        step /= 2.0
        last *= 2
        centre = np.rint((np.log(best.stage_ratio) - lo) / step).astype(np.intp)
        keys = centre[:, None] + offsets[None, :]
        valid = (keys >= 0) & (keys <= last)
        motor = np.broadcast_to(np.arange(motors)[:, None], keys.shape)[valid]
        unique, option = np.unique(keys[valid], return_inverse=True)
        consider([with_ratio(math.exp(lo + int(k) * step)) for k in unique], None, motor,
                 option.reshape(-1))


def _objective(seed: int, motors: int):
    """Per motor a target in log ratio, a plateau (ties) or a second minimum."""
    rng = np.random.default_rng(seed)
    target = rng.uniform(-0.5, 2.0, motors)
    second = rng.uniform(-0.5, 2.0, motors)
    flat = rng.uniform(0.0, 0.3, motors) * (rng.random(motors) < 0.3)

    def objective(motor: np.ndarray, ratio: np.ndarray) -> np.ndarray:
        x = np.log(ratio)
        near = np.maximum(np.abs(x - target[motor]) - flat[motor], 0.0)
        other = 0.8 * np.abs(x - second[motor]) + 0.05
        return np.round(np.minimum(near, other), 6)  # rounded: ties between points

    return objective


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("bounds", [(1.0, 4.0), (0.5, 20.0), (3.0, 3.2)])
def test_each_point_once_and_the_same_choice(seed: int, bounds) -> None:
    motors = 40
    objective = _objective(seed, motors)
    chosen, calls = _search(objective, motors, bounds, _continuous)
    before, old_calls = _search(objective, motors, bounds, _afresh)
    assert np.array_equal(chosen, before)  # to the bit
    assert len(calls) == len(set(calls))  # no (motor, ratio) evaluated twice
    assert len(calls) < len(old_calls)
    # every point the search evaluated afresh had been evaluated by this one or was new
    # to the motor there: the same set of points
    assert set(calls) == set(old_calls)


def test_rounds_with_nothing_new_evaluate_nothing(monkeypatch) -> None:
    """A flat objective keeps the best at the lower bound: from the second halving on its
    neighbours two steps up were evaluated already, and one call never gets an empty
    set of points."""
    sizes: list[int] = []

    def objective(motor, ratio):
        return np.zeros(len(motor))

    def search(bounds, with_ratio, consider, best, motors):
        def counted(points, names, motor, option, rank=None, candidates=None):
            assert len(motor) > 0
            sizes.append(len(motor))
            consider(points, names, motor, option)

        choices._continuous(bounds, with_ratio, counted, best, motors)

    chosen, _ = _search(objective, 3, (1.0, 4.0), search)
    assert np.all(chosen == 1.0)
    assert sizes[0] == 3 * COARSE and all(size == 3 for size in sizes[1:])
